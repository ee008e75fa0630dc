"""The bibliography of the report: every entry of ``docs/references.md`` (the project's
one list of sources), keyed as the code and the report cite them (``[MultimassChainDrives,
§3.6]``). the list is read from the package's copy of that file; *text between
asterisks* is a title (set in italics).
"""

from __future__ import annotations

import re
from importlib import resources

__all__ = ["REFERENCES", "cited_keys", "parse_references"]

#: An entry of the list: ``- **[Key]** text`` up to the next entry or heading.
_ENTRY = re.compile(r"^- \*\*\[([^\]]+)\]\*\*\s+(.*?)(?=^- \*\*\[|^## |\Z)", re.S | re.M)


def parse_references(text: str) -> dict[str, tuple[str, str]]:
    """The entries of a list of sources written as ``docs/references.md`` is.

    Parameters
    ----------
    text : str
        Markdown: ``## Heading`` lines and ``- **[Key]** entry`` items.

    Returns
    -------
    dict of str to (str, str)
        Key → (the heading it stands under, the entry's text on one line).
    """
    out: dict[str, tuple[str, str]] = {}
    heading = ""
    for block in re.split(r"(?m)^(?=## )", text):
        if block.startswith("## "):
            heading = block[3:block.index("\n")].strip() if "\n" in block else block[3:]
        for m in _ENTRY.finditer(block):
            out[m.group(1)] = (heading, " ".join(m.group(2).split()))
    return out


#: Key → (heading of docs/references.md, entry text): the package's copy of the list
#: (``chaindrive/report/references.md``, which docs/references.md links to).
REFERENCES: dict[str, tuple[str, str]] = parse_references(
    resources.files("chaindrive.report").joinpath("references.md").read_text(encoding="utf-8"))


_CITATION = re.compile(r"\[([A-Za-z][\w.-]*)(?:,[^\]]*)?\]")


def cited_keys(text: str) -> list[str]:
    """The keys of :data:`REFERENCES` cited in ``text`` (``[Key]`` or ``[Key, §3.6]``), in
    order of first citation.

    Parameters
    ----------
    text : str
        Any text (a section of the report, a check's source).

    Returns
    -------
    list of str
        The keys, each once.
    """
    seen: dict[str, None] = {}
    for m in _CITATION.finditer(text):
        if m.group(1) in REFERENCES:
            seen.setdefault(m.group(1))
    return list(seen)
