"""The PDF report a checker signs, typeset with Typst, looked at page by page: the verdict on
page 1, no internal reference, every symbol defined where it first appears (with a formula
that Typst can set), the references of docs/references.md, and the list of sections pinned
for the seed example ([MultimassChainDrives] worked example) and the 24-sprocket example.

The page images are Typst's own PNG output of the same document as the PDF (one per page).
With ``CHAINDRIVE_UPDATE_SCREENSHOTS=1`` page 1 of the seed report is written to
docs/report_seed.png.
"""

from __future__ import annotations

import io
import os
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.report import Definitions, Plot, Table, Text, Verdict, build_report, render_pdf
from chaindrive.report.bibliography import REFERENCES
from chaindrive.report.pdf import page_map, render_png_pages, typst_source
from chaindrive.report.symbols import SYMBOLS

ROOT = Path(__file__).parents[2]
EXAMPLES = ROOT / "examples"
SCREENSHOT = ROOT / "docs" / "report_seed.png"
#: The golden section lists: what a report of each example contains, in order.
GOLDEN = {
    "seed_three_sprocket": ["summary", "inputs", "geometry", "kinematics", "selection",
                            "strength", "dynamics", "response", "checks", "design_file",
                            "references"],
    "twenty_four_sprocket": ["summary", "inputs", "geometry", "kinematics", "selection",
                             "strength", "dynamics", "response", "checks", "design_file",
                             "references"],
}
#: What must never reach a reader: the project's internal names of its sources and tasks.
INTERNAL = re.compile(r"seed[ _-]?0\d\d|seed-notes|\bissue \d|shared/", re.IGNORECASE)


def _report(name: str) -> chaindrive.report.Report:
    path = EXAMPLES / f"{name}.toml"
    drive = chaindrive.load(path)
    short = replace(drive.dynamics, startup_duration=0.1)  # a short start-up keeps it fast
    return build_report(chaindrive.analyze(replace(drive, dynamics=short)), source=path,
                        dpi=40)


@pytest.fixture(scope="module", params=sorted(GOLDEN))
def report(request: pytest.FixtureRequest) -> tuple[str, chaindrive.report.Report]:
    return request.param, _report(request.param)


def _words(b: object) -> list[str]:
    """The pieces of text a block shows (a table's caption, headers and text cells)."""
    if isinstance(b, Text):
        return [b.text] if b.kind != "code" else []
    if isinstance(b, Table):
        return [b.caption, *b.columns, *(v for r in b.rows for v in r if isinstance(v, str))]
    if isinstance(b, Plot):
        return [b.caption]
    if isinstance(b, Verdict):
        return [b.headline, b.detail]
    return []


def _occurs(sym: str, text: str) -> bool:
    """``sym`` stands in ``text`` as a symbol (not inside a longer word or symbol)."""
    return re.search(rf"(?<![\w\[]){re.escape(sym)}(?![\w₀-₉\]])", text) is not None


def test_sections_are_the_golden_list(report) -> None:
    name, r = report
    assert [s.key for s in r.sections] == GOLDEN[name]


def test_pages_verdict_first_and_furniture(report, tmp_path: Path) -> None:
    """The PDF and its page images have the same pages, none blank; the verdict and the
    governing checks are on page 1, the inputs start on page 2; every page carries the
    drive's name (header) and "page x of y" (footer) in the Typst source."""
    name, r = report
    pdf = render_pdf(r)
    n_pdf = len(re.findall(rb"/Type\s*/Page(?![s\w])", pdf))
    pages = render_png_pages(r, ppi=40)
    assert len(pages) == n_pdf >= 5
    import matplotlib.image as mpimg

    for png in pages:
        image = mpimg.imread(io.BytesIO(png), format="png")
        assert float(np.std(image)) > 0.01  # not blank
    where = page_map(r)
    assert where["verdict"] == 1 and where["summary"] == 1
    assert 2 <= where["inputs"] <= 3  # the verdict and its summary stand alone, on two pages at most
    assert list(where) == ["summary", "verdict", *GOLDEN[name][1:]]
    assert where["references"] == len(pages) or where["references"] == len(pages) - 1
    source, _ = typst_source(r)
    assert 'counter(page).display("1 of 1", both: true)' in source
    assert r.drive in source and r.version in source and r.date[:10] in source
    if name == "seed_three_sprocket" and os.environ.get("CHAINDRIVE_UPDATE_SCREENSHOTS") == "1":
        SCREENSHOT.write_bytes(render_png_pages(r, ppi=80)[0])


def test_no_internal_reference(report) -> None:
    _, r = report
    source, _ = typst_source(r)
    assert INTERNAL.search(source) is None, INTERNAL.search(source)


def test_every_symbol_defined_where_it_first_appears(report) -> None:
    """Walking the report in order, a symbol of the glossary (a distinctive one: Greek, a
    subscript or more than one letter) is never shown before a Symbols table defined it."""
    _, r = report
    _symbols_defined_first(r)


@pytest.mark.parametrize("name", ["two_sprocket_jindal", "seed_three_sprocket_polymer",
                                  "conveyor_five_sprocket", "eight_sprocket"])
def test_every_symbol_defined_first_in_the_other_examples(name: str) -> None:
    """The same walk for the other examples, whose warnings and check notes (texts of the
    analysis) reach the summary before the Symbols tables."""
    _symbols_defined_first(_report(name))


def _symbols_defined_first(r: chaindrive.report.Report) -> None:
    distinctive = {k: s.text for k, s in SYMBOLS.items()
                   if len(s.text) > 1 or not s.text.isascii()}
    defined: set[str] = set()
    for section in r.sections:
        if section.key in ("references", "design_file"):
            continue
        for b in section.blocks:
            if isinstance(b, Definitions):
                defined.update(b.keys)
                continue
            for text in _words(b):
                for key, sym in distinctive.items():
                    if key not in defined and _occurs(sym, text):
                        raise AssertionError(f"{sym} ({key}) in {section.key} before its "
                                             f"definition: {text!r}")


def test_formulas_set_in_typst() -> None:
    """Every symbol and formula of the glossary is valid Typst math."""
    import typst

    body = "\n".join(f"${s.math}$ : ${s.formula_math or s.math}$\n" for s in SYMBOLS.values())
    assert typst.compile(body.encode("utf-8"), format="pdf")[:4] == b"%PDF"


def test_every_citation_is_in_the_references(report) -> None:
    """Each source the report cites is listed at the end, with the text of
    docs/references.md."""
    _, r = report
    refs = next(s for s in r.sections if s.key == "references")
    listed = {b.text.split("]")[0][1:] for b in refs.blocks}
    assert {"MultimassChainDrives", "Renold-DG"} <= listed
    for b in refs.blocks:
        key = b.text.split("]")[0][1:]
        assert b.text == f"[{key}] {REFERENCES[key][1]}"


def test_bibliography_is_docs_references() -> None:
    """chaindrive.report.bibliography holds every entry of docs/references.md, word for word."""
    text = (ROOT / "docs" / "references.md").read_text(encoding="utf-8")
    entries = {m.group(1): " ".join(m.group(2).split())
               for m in re.finditer(r"^- \*\*\[([^\]]+)\]\*\*\s+(.*?)(?=^- \*\*\[|^## |\Z)",
                                    text, re.S | re.M)}
    assert {k: v[1] for k, v in REFERENCES.items()} == entries
