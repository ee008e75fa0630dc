"""Every public function, method and class of chaindrive documents its parameters.

Walks the public API of the package — each module's ``__all__`` (or, without one, the names
it defines that do not start with ``_``), the public methods of its classes and the
constructors of its classes — and parses the numpydoc ``Parameters`` section of each
docstring. A test fails when

* a parameter of the signature is not documented (``name : type`` line in ``Parameters``),
* a documented parameter does not exist in the signature,
* a public module-level function that returns something has no ``Returns`` section,
* a number (a parameter whose type says ``float`` or ``array``, not a boolean mask) carries
  no unit in brackets (``[m]``, ``[-]`` for a pure number, ``[rad/s]`` …) in its
  description.

The style follows python-control's test of its docstrings; the parser is written here (a few
regular expressions, no documentation tool at test time). The closed form it checks against
is the signature itself (:func:`inspect.signature`).

Every module of the package is checked. Two rules leave something out, each for a reason:

* **A ``__main__`` module is not imported**: it is what ``python -m chaindrive`` runs, and
  importing it runs the command line (which reads pytest's arguments and exits the
  process). It may define no function or class — :func:`test_main_modules_define_no_api`
  reads its source to hold it to that — so skipping it leaves no API unchecked.
  (``chaindrive.app.main``, the Streamlit page, draws the page only under
  ``if __name__ == "__main__"``: it imports without side effects and is checked.)
* **Command callbacks of the typer CLI are checked by their options, not by a numpydoc
  Parameters section.** A command's docstring is the ``--help`` text users read and each
  of its options already carries its own ``help=``; a Parameters section would repeat
  every option in a second place that drifts (or, cut off by typer's ``\f``, in a place
  no user sees). So :func:`test_cli_commands_and_options_have_help` requires every
  command to have a help text and every option and argument a non-empty ``help``, and the
  numpydoc check skips the callbacks registered on a :class:`typer.Typer` of the module.
  The CLI's other public functions (``run``, ``main``, ``user_errors`` …) are checked as
  any function.

:data:`TO_BE_DOCUMENTED` is the allowlist of modules still being documented; it is empty,
and a module put in it is skipped (not even imported) until it is taken out again.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import importlib.util
import inspect
import pkgutil
import re
from collections.abc import Callable, Iterator
from types import ModuleType

import click
import pytest
import typer

import chaindrive

# to be documented: modules whose documentation is still under way (empty: every module is
# checked; a module listed here is skipped, not even imported)
TO_BE_DOCUMENTED: frozenset[str] = frozenset()

_SECTION = re.compile(r"^(?P<title>[A-Z][A-Za-z ]+)\n-{3,}\s*$", re.MULTILINE)
_PARAM = re.compile(r"^(?P<names>\*{0,2}\w+(?:\s*,\s*\*{0,2}\w+)*)\s*:(?P<type>.*)$")
_NUMBER_TYPE = re.compile(r"\b(float|array|ndarray|ArrayLike)\b", re.IGNORECASE)


def _runs_when_imported(module_name: str) -> bool:
    """A ``__main__`` module: importing it runs the program (module docstring)."""
    return module_name.rsplit(".", 1)[-1] == "__main__"


def _skipped(module_name: str) -> bool:
    return _runs_when_imported(module_name) or any(
        module_name == m or module_name.startswith(m + ".") for m in TO_BE_DOCUMENTED)


def _modules() -> list[str]:
    names = ["chaindrive"]
    for info in pkgutil.walk_packages(chaindrive.__path__, "chaindrive."):
        if not _skipped(info.name):
            names.append(info.name)
    return sorted(names)


def _sections(doc: str) -> dict[str, str]:
    """Numpydoc sections of a docstring: title → body."""
    heads = list(_SECTION.finditer(doc))
    out = {}
    for k, head in enumerate(heads):
        end = heads[k + 1].start() if k + 1 < len(heads) else len(doc)
        out[head.group("title").strip()] = doc[head.end():end]
    return out


def documented_parameters(doc: str) -> dict[str, tuple[str, str]]:
    """``name → (type, description)`` of the ``Parameters`` section (numpydoc form
    ``name : type`` at the left margin, the description indented below it)."""
    body = _sections(doc).get("Parameters", "")
    out: dict[str, tuple[str, str]] = {}
    current: list[str] = []
    for line in body.splitlines():
        if not line.strip():
            continue
        match = _PARAM.match(line) if not line.startswith((" ", "\t")) else None
        if match:
            current = [n.strip() for n in match.group("names").split(",")]
            for name in current:
                out[name] = (match.group("type").strip(), "")
        elif current:
            for name in current:
                kind, text = out[name]
                out[name] = (kind, f"{text} {line.strip()}".strip())
    return out


def _signature_names(func: Callable[..., object]) -> tuple[list[str], bool]:
    """Parameter names to document (``*args`` as ``*args``) and whether there is ``**kw``."""
    names, var_kw = [], False
    for name, par in inspect.signature(func).parameters.items():
        if name in ("self", "cls"):
            continue
        if par.kind is inspect.Parameter.VAR_KEYWORD:
            var_kw = True
            names.append(f"**{name}")
        elif par.kind is inspect.Parameter.VAR_POSITIONAL:
            names.append(f"*{name}")
        else:
            names.append(name)
    return names, var_kw


def _problems(qualname: str, func: Callable[..., object], doc: str | None, *,
              needs_returns: bool, inherited: dict[str, tuple[str, str]] | None = None
              ) -> Iterator[str]:
    if not doc:
        yield f"{qualname}: no docstring"
        return
    names, var_kw = _signature_names(func)
    # a dataclass's fields documented by the dataclass it extends count as documented
    documented = (inherited or {}) | documented_parameters(doc)
    plain = {n.lstrip("*") for n in documented}
    for name in names:
        if name.lstrip("*") not in plain:
            yield f"{qualname}: parameter {name!r} is not documented"
    for name in documented:
        if name not in names and name.lstrip("*") not in {n.lstrip("*") for n in names} \
                and not var_kw:
            yield f"{qualname}: documents {name!r}, which is not a parameter"
    for name, (kind, text) in documented.items():
        boolean = "bool" in kind or re.match(r"(\(.*?\)\s*)?(True|False)\b", text)
        if _NUMBER_TYPE.search(kind) and not boolean and "[" not in text:
            yield f"{qualname}: the number {name!r} has no unit in brackets ([m], [-] …)"
    if needs_returns and "Returns" not in _sections(doc) and "Yields" not in _sections(doc):
        ret = inspect.signature(func).return_annotation
        if ret not in (None, "None", inspect.Signature.empty):
            yield f"{qualname}: no Returns section"


def _public_names(module: ModuleType) -> list[str]:
    if hasattr(module, "__all__"):
        return list(module.__all__)
    return [n for n, obj in vars(module).items() if not n.startswith("_")
            and (inspect.isfunction(obj) or inspect.isclass(obj))
            and getattr(obj, "__module__", None) == module.__name__]


def _class_problems(qualname: str, cls: type) -> Iterator[str]:
    if dataclasses.is_dataclass(cls) or "__init__" in vars(cls):
        inherited: dict[str, tuple[str, str]] = {}
        for base in reversed(cls.__mro__[1:]):
            if dataclasses.is_dataclass(base) and base.__doc__:
                inherited |= documented_parameters(inspect.cleandoc(base.__doc__))
        yield from _problems(qualname, cls, inspect.getdoc(cls), needs_returns=False,
                             inherited=inherited)
    for name, attr in vars(cls).items():
        if name.startswith("_"):
            continue
        func = attr.__func__ if isinstance(attr, classmethod | staticmethod) else attr
        # a method a base class generates for each subclass (matplotlib's Artist.set) is the
        # library's, written in its file: not ours to document
        if inspect.isfunction(func) and func.__code__.co_filename == inspect.getfile(cls):
            yield from _problems(f"{qualname}.{name}", func, inspect.getdoc(func),
                                 needs_returns=False)


def _command_callbacks(module: ModuleType) -> set[object]:
    """The callbacks of the commands registered on the module's typer apps (checked by
    :func:`test_cli_commands_and_options_have_help` instead)."""
    return {command.callback for app in vars(module).values() if isinstance(app, typer.Typer)
            for command in app.registered_commands}


def module_problems(module_name: str) -> list[str]:
    """Every documentation problem of the public API of one module."""
    module = importlib.import_module(module_name)
    commands = _command_callbacks(module)
    out: list[str] = []
    for name in _public_names(module):
        obj = getattr(module, name)
        home = getattr(obj, "__module__", None)
        if home != module_name:
            continue  # re-exported: checked where it is defined
        if obj in commands:
            continue  # a CLI command: its options' help texts are checked instead
        qualname = f"{module_name}.{name}"
        if inspect.isclass(obj):
            out += _class_problems(qualname, obj)
        elif inspect.isfunction(obj):
            out += _problems(qualname, obj, inspect.getdoc(obj), needs_returns=True)
    return out


@pytest.mark.parametrize("module_name", _modules())
def test_public_api_documents_its_parameters(module_name: str) -> None:
    problems = module_problems(module_name)
    assert not problems, "\n".join(problems)


def test_parser_reads_numpydoc_parameters() -> None:
    doc = inspect.cleandoc("""Summary.

    Parameters
    ----------
    pitch, teeth : float
        Chain pitch p [m] and tooth count z [-].
    speed : float
        Angular speed.

    Returns
    -------
    float
        Chain speed [m/s].
    """)
    found = documented_parameters(doc)
    assert set(found) == {"pitch", "teeth", "speed"}
    assert found["speed"] == ("float", "Angular speed.")

    def f(pitch: float, teeth: float, speed: float, extra: int) -> float:
        return pitch

    problems = list(_problems("f", f, doc, needs_returns=True))
    assert problems == ["f: parameter 'extra' is not documented",
                        "f: the number 'speed' has no unit in brackets ([m], [-] …)"]


def test_allowlist_names_only_existing_modules() -> None:
    every = {i.name for i in pkgutil.walk_packages(chaindrive.__path__, "chaindrive.")}
    stale = {m for m in TO_BE_DOCUMENTED if m not in every}
    assert not stale, f"remove from TO_BE_DOCUMENTED: {sorted(stale)}"


def _main_modules() -> list[str]:
    return sorted(i.name for i in pkgutil.walk_packages(chaindrive.__path__, "chaindrive.")
                  if _runs_when_imported(i.name))


def test_main_rule_finds_the_entry_point() -> None:
    assert _main_modules() == ["chaindrive.__main__"]


@pytest.mark.parametrize("module_name", _main_modules())
def test_main_modules_define_no_api(module_name: str) -> None:
    """What the ``__main__`` rule skips holds no function or class (read from its source,
    since importing it would run the program)."""
    spec = importlib.util.find_spec(module_name)
    assert spec is not None and spec.origin is not None
    with open(spec.origin, encoding="utf-8") as f:
        tree = ast.parse(f.read())
    defined = [node.name for node in tree.body
               if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)]
    assert not defined, f"{module_name} defines {defined}: move them to a module that imports"


def test_cli_commands_and_options_have_help() -> None:
    """Every ``chaindrive`` command has a help text (its docstring) and every option and
    argument a ``help=``: what ``chaindrive <command> --help`` shows."""
    from chaindrive.cli import app

    group = typer.main.get_command(app)
    assert isinstance(group, click.Group)
    missing = []
    for name, command in group.commands.items():
        if not (command.help or "").strip():
            missing.append(f"{name}: no help text (docstring)")
        missing += [f"{name} {param.name}: no help"
                    for param in command.params if not (getattr(param, "help", "") or "").strip()]
    assert len(group.commands) == len(app.registered_commands)
    assert not missing, "\n".join(missing)


def test_command_rule_skips_only_commands() -> None:
    """The typer rule of :func:`module_problems` leaves out the command callbacks and
    nothing else of ``chaindrive.cli`` (``run``, ``main`` … are still checked)."""
    import chaindrive.cli as cli

    skipped = _command_callbacks(cli)
    assert skipped == {c.callback for c in cli.app.registered_commands}
    assert cli.run not in skipped and cli.main not in skipped
    assert cli.analyze in skipped


def test_shared_parameter_entries_are_written_out_at_import() -> None:
    # a line ``%(name)s`` becomes the entry of chaindrive._docstrings.PARAMETERS, indented as
    # the line; a ``%`` elsewhere stays; an unknown name fails at once
    from chaindrive._docstrings import expand
    from chaindrive.kinematics import max_chain_speed

    doc = "x.\n\n    Parameters\n    ----------\n        %(pitch)s\n    5 %(pitch)s stays\n"
    assert expand(doc) == ("x.\n\n    Parameters\n    ----------\n"
                           "        pitch : float\n            Chain pitch p [m].\n"
                           "    5 %(pitch)s stays\n")
    with pytest.raises(KeyError):
        expand("    %(no_such_entry)s")
    assert "%(" not in (max_chain_speed.__doc__ or "")
    assert "    pitch : float or array_like\n        Chain pitch p [m]." in (
        max_chain_speed.__doc__ or "")
