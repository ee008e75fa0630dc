"""The layers of chaindrive, checked on the source: no import cycle, presenters on top.

Every module of ``src/chaindrive`` is parsed (:mod:`ast`, nothing is imported) and its
run-time imports of chaindrive modules are collected: the imports at module level and inside
functions, but not those under ``if TYPE_CHECKING:`` (they never run). Importing
``chaindrive.a.b`` also runs the package ``chaindrive.a`` (its ``__init__``), so a module
outside ``chaindrive.a`` that imports ``chaindrive.a.b`` depends on ``chaindrive.a`` too.

The tests fail on

(a) an import cycle between chaindrive modules (a strongly connected component of the import
    graph with more than one module);
(b) a module outside the presenters importing a presenter (``cli``, ``report``,
    ``plotting``, ``app``, ``drawing``, ``display``): computing never depends on showing;
(c) a presenter (``cli``, ``report``, ``plotting``, ``app``, ``drawing``) importing, at run
    time, anything but the entry points of the pipeline (:data:`PRESENTER_MAY_IMPORT`):
    presenters read an ``Analysis``; the analysis functions (geometry, kinematics, strength,
    dynamics, multicontour, metrics) reach them only under ``TYPE_CHECKING``.

Imports that break (c) today are listed in :data:`KNOWN_PRESENTER_IMPORTS`, each with the
branch that removes it; the list may only shrink.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = SRC / "chaindrive"

PRESENTERS = ("chaindrive.cli", "chaindrive.report", "chaindrive.plotting", "chaindrive.app",
              "chaindrive.drawing", "chaindrive.display", "chaindrive.__main__")
#: presenters held to rule (c) (``display`` is the formatting helper they share)
RULE_C_PRESENTERS = ("chaindrive.cli", "chaindrive.report", "chaindrive.plotting",
                     "chaindrive.app", "chaindrive.drawing")
#: what a presenter may import at run time (a module or any module inside it when it ends
#: in ``.*``)
PRESENTER_MAY_IMPORT = (
    "chaindrive",                       # load, analyze
    "chaindrive.analysis",
    "chaindrive.io.*",
    "chaindrive.errors",
    "chaindrive.units",
    "chaindrive._docstrings",           # the shared docstring entries (no computation)
    "chaindrive.display",
    "chaindrive.model",                 # the data
    "chaindrive.catalog",               # listing the catalogue
    "chaindrive.examples",
    "chaindrive.checks",                # the Check type
    "chaindrive.synthesis",             # entry points: load_problem, solve, studies, workflow
    "chaindrive.synthesis.problem",
    "chaindrive.synthesis.solve",
    "chaindrive.synthesis.studies",
    "chaindrive.synthesis.workflow",
    "chaindrive.robust",                # entry points of the robust study: study, uncertainty
    "chaindrive.robust.study",
    "chaindrive.robust.uncertainty",
    "chaindrive.cost",                  # loading a price file
    "chaindrive.linklevel",             # its entry point simulate
    "chaindrive.linklevel.simulate",
    "chaindrive.identification",        # its entry points (tension, identify, calibrate)
    *(f"{p}.*" for p in PRESENTERS), *PRESENTERS,
)
#: run-time imports of analysis functions by presenters that exist today: (presenter module,
#: imported module) → who removes it. May only shrink.
KNOWN_PRESENTER_IMPORTS: dict[tuple[str, str], str] = {}
#: import cycles that exist today → who removes them. May only shrink.
KNOWN_CYCLES: dict[frozenset[str], str] = {
}


def module_name(path: Path) -> str:
    """``src/chaindrive/a/b.py`` → ``chaindrive.a.b``; a package's ``__init__`` → the package."""
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES: dict[str, Path] = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _runtime_import_nodes(node: ast.AST) -> Iterator[ast.Import | ast.ImportFrom]:
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.If) and _is_type_checking(child.test):
            for sub in child.orelse:
                yield from _runtime_import_nodes(sub)
                if isinstance(sub, ast.Import | ast.ImportFrom):
                    yield sub
            continue
        if isinstance(child, ast.Import | ast.ImportFrom):
            yield child
        yield from _runtime_import_nodes(child)


def _resolve(base: str) -> str | None:
    """The longest chaindrive module that ``base`` names (or lies in)."""
    parts = base.split(".")
    while parts:
        name = ".".join(parts)
        if name in MODULES:
            return name
        parts.pop()
    return None


def imported_modules(name: str) -> set[str]:
    """chaindrive modules that module ``name`` imports at run time."""
    path = MODULES[name]
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in _runtime_import_nodes(tree):
        if isinstance(node, ast.Import):
            bases = [alias.name for alias in node.names]
        else:
            if node.level:
                up = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                prefix = ".".join(up + ([node.module] if node.module else []))
            else:
                prefix = node.module or ""
            bases = [f"{prefix}.{alias.name}" for alias in node.names]
        for base in bases:
            if base.split(".")[0] != "chaindrive":
                continue
            target = _resolve(base)
            if target is not None and target != name:
                found.add(target)
    return found


def import_graph() -> dict[str, set[str]]:
    """Run-time import edges, with the packages that an import of a submodule runs."""
    graph: dict[str, set[str]] = {}
    for name in MODULES:
        edges = set()
        for target in imported_modules(name):
            edges.add(target)
            parts = target.split(".")
            for k in range(2, len(parts)):  # packages above the target, below chaindrive
                package = ".".join(parts[:k])
                if not (name == package or name.startswith(package + ".")):
                    edges.add(package)
        graph[name] = edges - {name}
    return graph


def strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's strongly connected components (iterative), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                out.append(sorted(component))
    return out


def _inside(name: str, prefixes: tuple[str, ...]) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def _allowed_for_presenter(target: str) -> bool:
    for rule in PRESENTER_MAY_IMPORT:
        if rule.endswith(".*"):
            if target.startswith(rule[:-1]) or target == rule[:-2]:
                return True
        elif target == rule:
            return True
    return False


def test_the_graph_sees_the_known_edges() -> None:
    graph = import_graph()
    assert "chaindrive.errors" in graph["chaindrive.geometry.contour"]
    assert "chaindrive.geometry.sprocket" in graph["chaindrive.geometry.contour"]
    assert "chaindrive.geometry" in graph["chaindrive.kinematics"]  # the package runs too


def test_type_checking_imports_are_not_run_time_imports() -> None:
    # kinematics names GeometryResult and Drive only under TYPE_CHECKING
    assert "chaindrive.model" not in imported_modules("chaindrive.kinematics")


def test_the_cycle_finder_finds_a_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert [c for c in strongly_connected(graph) if len(c) > 1] == [["a", "b", "c"]]


def test_no_import_cycle() -> None:
    cycles = [c for c in strongly_connected(import_graph())
              if len(c) > 1 and frozenset(c) not in KNOWN_CYCLES]
    assert not cycles, "import cycles (run-time imports):\n" + "\n".join(
        " ↔ ".join(c) for c in cycles)


def test_nothing_below_the_presenters_imports_a_presenter() -> None:
    bad = [f"{name} imports {target}" for name, targets in import_graph().items()
           if not _inside(name, PRESENTERS)
           for target in imported_modules(name) if _inside(target, PRESENTERS)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("presenter", sorted(n for n in MODULES
                                             if _inside(n, RULE_C_PRESENTERS)))
def test_presenters_import_only_the_entry_points(presenter: str) -> None:
    bad = [t for t in sorted(imported_modules(presenter))
           if not _allowed_for_presenter(t) and (presenter, t) not in KNOWN_PRESENTER_IMPORTS]
    assert not bad, f"{presenter} imports analysis functions at run time: {bad}"


def test_known_cycles_still_exist() -> None:
    cycles = {frozenset(c) for c in strongly_connected(import_graph()) if len(c) > 1}
    stale = [sorted(c) for c in KNOWN_CYCLES if c not in cycles]
    assert not stale, f"remove from KNOWN_CYCLES: {stale}"


def test_known_presenter_imports_still_exist() -> None:
    stale = [pair for pair in KNOWN_PRESENTER_IMPORTS
             if pair[0] not in MODULES or pair[1] not in imported_modules(pair[0])]
    assert not stale, f"remove from KNOWN_PRESENTER_IMPORTS: {stale}"


def _local_package_imports(path: Path) -> Iterator[tuple[int, str]]:
    """(line, function) of every import of a chaindrive module inside a function body (not
    under ``if TYPE_CHECKING``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in _runtime_import_nodes(fn):
                mod = node.module if isinstance(node, ast.ImportFrom) else node.names[0].name
                if mod and mod.split(".")[0] == "chaindrive":
                    yield node.lineno, fn.name


def _has_reason(lines: list[str], lineno: int) -> bool:
    """A comment on the import's line, or above the run of import lines it belongs to (a
    blank line or an ``if``/``else`` line may sit between the comment and the run)."""
    if "#" in lines[lineno - 1]:
        return True
    j = lineno - 2
    while j >= 0:
        text = lines[j].strip()
        if text.startswith("#"):
            return True
        if (text.startswith(("from ", "import ", ")", "if ", "else")) or text.endswith(",")
                or text == ""):
            j -= 1
            continue
        return False
    return False


def test_a_function_level_import_says_why() -> None:
    """Package imports sit at the top of the file; one inside a function carries its reason
    beside it (the import time it saves, measured, or the process it runs in)."""
    missing = []
    for path in sorted(SRC.rglob("*.py")):
        lines = path.read_text(encoding="utf-8").split("\n")
        missing += [f"{module_name(path)}:{n} ({fn})"
                    for n, fn in _local_package_imports(path) if not _has_reason(lines, n)]
    assert not missing, "function-level imports without a reason: " + ", ".join(missing)


#: at most this many modules (files and subpackages) directly in ``chaindrive/dynamics``: a
#: subject that outgrows a module becomes a subpackage (docs/architecture.md).
MAX_DYNAMICS_MODULES = 20


def dynamics_entries() -> list[str]:
    """The modules and subpackages directly in ``chaindrive/dynamics`` (not ``__init__``)."""
    root = PACKAGE / "dynamics"
    files = [p.stem for p in root.glob("*.py") if p.stem != "__init__"]
    packages = [p.name for p in root.iterdir() if (p / "__init__.py").is_file()]
    return sorted(files + packages)


def test_dynamics_is_arranged_by_subject() -> None:
    entries = dynamics_entries()
    assert len(entries) <= MAX_DYNAMICS_MODULES, (
        f"{len(entries)} modules directly in dynamics/ (at most {MAX_DYNAMICS_MODULES}): "
        "put a subject that outgrows one module into a subpackage")
    # each subpackage says what it holds
    for p in (PACKAGE / "dynamics").iterdir():
        init = p / "__init__.py"
        if init.is_file():
            assert ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))), init


def private_imports(tree: ast.AST) -> list[tuple[int, str]]:
    """(line, name) of every ``from chaindrive… import _name`` in ``tree``: a module's
    private names (a leading underscore, not a dunder) are not imported by another module."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("chaindrive"):
            out.extend((node.lineno, a.name) for a in node.names
                       if a.name.startswith("_") and not a.name.startswith("__"))
    return out


def test_the_private_import_rule_sees_one() -> None:
    tree = ast.parse("from chaindrive.x import a, _b\nfrom chaindrive.y import c as _c\n")
    assert private_imports(tree) == [(1, "_b")]


def test_no_private_name_is_imported_across_modules() -> None:
    found = [f"{p.relative_to(SRC)}:{line}: {name}" for p in sorted(PACKAGE.rglob("*.py"))
             for line, name in private_imports(ast.parse(p.read_text(encoding="utf-8")))]
    assert not found, "private names imported from another module (make them public):\n" \
        + "\n".join(found)
