"""The sign-off sheet (``report --summary``): two A4 pages, read back from what Typst typesets
(its own page count of the PDF and the pages each part lands on), with the verdict and the
governing checks of the analysis on page 1, the chain and sprockets to buy on page 2, and the
symbols said in words where the sheet first uses them.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pytest
from typer.testing import CliRunner

import chaindrive
from chaindrive.cli import app
from chaindrive.display import warning_text
from chaindrive.report import Report, Table, Verdict, build_report, render_pdf, report_text
from chaindrive.report.pdf import page_map, render_png_pages
from chaindrive.report.sections import governing_checks
from tests.conftest import EXAMPLES

#: Every bundled example of two to 24 sprockets.
NAMES = ["seed_three_sprocket", "two_sprocket_jindal", "eight_sprocket",
         "twenty_four_sprocket"]


def _analysis(name: str) -> chaindrive.Analysis:
    drive = chaindrive.load(EXAMPLES / f"{name}.toml")
    short = replace(drive.dynamics, startup_duration=0.1)  # a short start-up keeps it fast
    return chaindrive.analyze(replace(drive, dynamics=short))


@pytest.fixture(scope="module", params=NAMES)
def sheet(request: pytest.FixtureRequest) -> tuple[chaindrive.Analysis, Report]:
    a = _analysis(request.param)
    return a, build_report(a, source=EXAMPLES / f"{request.param}.toml", dpi=60,
                           summary=True)


def _pdf_pages(data: bytes) -> int:
    """The page count a PDF declares in its page tree (``/Type /Pages … /Count n``)."""
    counts = [int(m) for m in re.findall(rb"/Type\s*/Pages\b[^>]*?/Count\s+(\d+)", data)]
    counts += [int(m) for m in re.findall(rb"/Count\s+(\d+)[^>]*?/Type\s*/Pages\b", data)]
    assert counts, "no page tree found"
    return max(counts)


def test_two_pages_verdict_on_one_purchase_on_two(sheet) -> None:
    _, report = sheet
    pages = render_png_pages(report, ppi=20)
    assert len(pages) == 2
    assert _pdf_pages(render_pdf(report)) == 2
    where = page_map(report)
    assert where["verdict"] == 1 and where["summary"] == 1 and where["purchase"] == 2


def test_verdict_and_governing_checks_are_the_analysis(sheet) -> None:
    a, report = sheet
    page1 = report.sections[0]
    checks = a.checks()
    failed = [c for c in checks if not c.passed]
    verdict = next(b for b in page1.blocks if isinstance(b, Verdict))
    assert verdict.passed is (not failed)
    assert (f"FAILS {len(failed)} of {len(checks)}" if failed
            else f"passes all {len(checks)}") in verdict.headline
    table = next(b for b in page1.blocks if isinstance(b, Table))
    shown = {(r[0], s.strip()) for r in table.rows for s in str(r[1]).split("; ")}
    for c in governing_checks(checks):
        assert (c.name, c.subject) in shown, (c.name, c.subject)
    # the rows that do not pass are marked, and their result says FAIL or CANNOT BE VERIFIED
    for i, r in enumerate(table.rows):
        assert (i in table.highlight) is (r[5] != "pass")


def test_defaults_and_estimates_and_the_drive_on_page_one(sheet) -> None:
    a, report = sheet
    page1 = report_text(report.sections[:1])
    assert "The results rest on these defaults and estimates" in page1
    assert "The drive to scale" in page1
    for w in a.warnings:
        if w.code in ("dynamics.estimate", "strength.bearing-area-estimated"):
            # said in full (its first letter capitalised), whatever the full report shortens
            assert warning_text(w, "SI")[1:60] in page1


def test_chain_and_sprockets_to_buy(sheet) -> None:
    a, report = sheet
    page2 = report.sections[1]
    chain, sprockets = [b for b in page2.blocks if isinstance(b, Table)][:2]
    items = dict((r[0], r[1]) for r in chain.rows)
    assert items["designation"].startswith(a.drive.chain.spec.designation)
    assert items["number of links L_p (pitches of the closed chain)"] == a.geometry.links
    assert "lubrication" in items
    assert [r[0] for r in sprockets.rows] == [s.name for s in a.geometry.sprockets]
    assert [r[2] for r in sprockets.rows] == [s.teeth for s in a.geometry.sprockets]


#: Symbols of the sheet's own words and the words that must come just before their first use.
IN_WORDS = {"K_D": "coefficient of dynamics", "k₁": "dynamic safety factors",
            "L_p": "number of links", "f_z": "tooth frequency", "θ": "wrap angle",
            "d_a": "tip diameter"}


def test_every_symbol_in_words_at_first_use(sheet) -> None:
    a, report = sheet
    text = report_text(report.sections)
    for symbol, words in IN_WORDS.items():
        if a.response is None and symbol in ("K_D", "k₁"):
            continue
        first = text.index(symbol)
        assert words in text[max(0, first - 60):first + 60], symbol


def test_cli_summary_writes_two_pages(tmp_path: Path) -> None:
    out = tmp_path / "sheet.pdf"
    run = CliRunner().invoke(app, ["report", str(EXAMPLES / "two_sprocket_jindal.toml"),
                                   "--summary", "-o", str(out)])
    assert run.exit_code == 0, run.output
    assert _pdf_pages(out.read_bytes()) == 2
