"""Citations a reader can follow: every source the code names is an entry of
``docs/references.md``, cited by its key in square brackets (``[Rao2011, §5.2]``).

For the modules and package data that are done (those not in
:data:`tests.unit.test_docstrings.TO_BE_DOCUMENTED`) the tests fail on

* a reference key in square brackets that ``docs/references.md`` does not define,
* a citation a reader cannot follow: a working note ("seed 000", "seed-notes"), a tracker
  issue ("issue 4") or a path outside the repository ("shared/data/…", "/work/…").
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.unit.test_docstrings import TO_BE_DOCUMENTED

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "src" / "chaindrive"
REFERENCES = ROOT / "docs" / "references.md"

#: a key: starts with a capital, then letters, digits, hyphens (ISO606, Rao2011, ANSI-B29.1)
_CITED = re.compile(r"(?<![\w\]\[)])\[([A-Z][A-Za-z]+[A-Za-z0-9.-]*)(?:, [^\]\n]+)?\]")
_DEFINED = re.compile(r"^- \*\*\[([^\]]+)\]\*\*", re.MULTILINE)
#: bracketed words that are units or symbols (or Python constants in a list: ``[None] * n``),
#: not references
_NOT_KEYS = {"Pa", "MPa", "GPa", "Hz", "SI", "Nm", "N", "W", "kW", "Kind", "Status", "None",
             "True", "False"}
_UNFOLLOWABLE = re.compile(r"seed 0\d{2}|seed-notes|\bissue \d+|shared/(data|spec|seeds)|/work/",
                           re.IGNORECASE)


def _module_of(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _done(path: Path) -> bool:
    """A source or data file of a module that is not on the to-be-documented list."""
    module = _module_of(path if path.suffix == ".py" else path.parent / "__init__.py")
    return not any(module == m or module.startswith(m + ".") for m in TO_BE_DOCUMENTED)


#: package data another branch still cites informally → its owner (may only shrink)
TO_BE_CITED: dict[str, str] = {}

FILES = sorted(p for p in PACKAGE.rglob("*")
               if p.suffix in {".py", ".toml", ".csv"} and "__pycache__" not in p.parts
               and _done(p) and not (p.suffix != ".py"
                                     and p.parent.name in TO_BE_CITED))


def defined_keys() -> set[str]:
    """The keys of docs/references.md."""
    return set(_DEFINED.findall(REFERENCES.read_text(encoding="utf-8")))


def test_the_bibliography_defines_the_source_papers() -> None:
    keys = defined_keys()
    assert {"MultimassChainDrives", "ChainHingeDissipation", "ChainNonUniformity",
            "Lyashuk", "ISO606"} <= keys


@pytest.mark.parametrize("path", [p for p in FILES if p.suffix == ".py"],
                         ids=lambda p: str(p.relative_to(PACKAGE)))
def test_every_cited_key_is_in_the_bibliography(path: Path) -> None:
    keys = defined_keys()
    text = path.read_text(encoding="utf-8")
    unknown = sorted({k for k in _CITED.findall(text) if k not in keys and k not in _NOT_KEYS
                      and len(k) > 3})
    assert not unknown, f"{path.name} cites keys docs/references.md does not define: {unknown}"


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_citation_a_reader_cannot_follow(path: Path) -> None:
    bad = [f"line {n}: {line.strip()[:100]}"
           for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
           if _UNFOLLOWABLE.search(line)]
    assert not bad, "\n".join(bad)


def test_the_key_pattern_reads_citations_not_types() -> None:
    text = "x : list[ChainSpec] — see [Rao2011, §5.2] and [ISO606]; p [Pa]"
    assert _CITED.findall(text) == ["Rao2011", "ISO606", "Pa"]
