"""The chain length options and the lubrication advice reach every output: the JSON
document, the command line, the report and the web page's tables. The numbers are the
analysis's own: the option the design picks is the layout the analysis made (same links,
centre distance and take-up, closed check), and the advice is
:func:`chaindrive.strength.lubrication.lubrication_advice` at the analysed chain speed
(its limits tested against [McGuireLube] and [KettenfabrikUnna] in
test_lubrication_length_cost.py)."""

from __future__ import annotations

from dataclasses import replace

import pytest

import chaindrive
from chaindrive.app.views import length_option_records, lubrication_records, selection_records
from chaindrive.cli.tables import print_analysis, print_selection
from chaindrive.report import build_report, render_html
from chaindrive.strength.lubrication import lubrication_advice
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def jindal() -> chaindrive.Analysis:
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"),
                              response=False)


def _option(doc: dict, rounding: str) -> dict:
    return next(o for o in doc["geometry"]["length_options"]["options"]
                if o["rounding"] == rounding)


@pytest.mark.parametrize("rounding", ["round up", "round down"])
def test_the_chosen_length_option_is_the_layout_analysed(jindal, rounding):
    """Jindal 30-3: 131.72 pitches → 130 or 132 links; the design's pick is what the
    analysis lays out, the other count is laid out beside it."""
    design = jindal.design
    a = chaindrive.analyze(replace(design, chain=replace(design.chain, rounding=rounding)),
                           response=False)
    doc = a.to_dict()
    lc = doc["geometry"]["length_options"]
    assert lc["chosen"] == rounding
    assert lc["tight_length_pitches"] == pytest.approx(131.7235, abs=1e-4)
    assert [o["links"] for o in lc["options"]] == [130, 132]
    picked = _option(doc, rounding)
    assert picked["links"] == a.geometry.links
    assert picked["centre_distance_mm"] == pytest.approx(a.geometry.center_distance * 1e3,
                                                         rel=1e-12)
    assert picked["take_up_mm"] == pytest.approx(a.geometry.adjustment * 1e3, rel=1e-12)
    # round down pulls the driven sprocket in, round up pushes it out
    assert _option(doc, "round down")["take_up_mm"] < 0 < _option(doc, "round up")["take_up_mm"]


def test_lubrication_in_the_document_is_the_advice_at_the_chain_speed(jindal):
    doc = jindal.to_dict()
    expected = lubrication_advice(jindal.drive.chain.spec, jindal.kinematics.chain_speed)
    assert doc["lubrication"] == expected.to_dict()
    # 06B at 1000 rpm, z1 = 21: v = 21·9.525 mm·1000/60 = 3.334 m/s, between the drip and
    # the bath limits of the pitch → bath or disc (ANSI type B)
    assert doc["lubrication"]["chain_speed_m_s"] == pytest.approx(21 * 9.525e-3 * 1000 / 60)
    assert doc["lubrication"]["regime"] == "bath/disc"


def test_a_polymer_chain_is_advised_to_run_dry():
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket_polymer.toml"),
                           response=False)
    lube = a.to_dict()["lubrication"]
    assert lube["regime"].startswith("none: dry-running polymer") and lube["ansi_type"] is None


def test_the_command_line_prints_both(jindal, capsys):
    print_analysis(jindal.to_dict(), jindal.checks())
    out = " ".join(capsys.readouterr().out.split())
    assert "length options (tight length as designed 131.7 pitches): 130 links (round down):" \
        in out
    assert "132 links (round up, chosen): centre distance 477.6 mm, take-up 1.32 mm" in out
    assert "lubrication: bath/disc (ANSI type B) at 3.334 m/s" in out
    assert "[McGuireLube]" in out


def test_select_lists_the_lubrication_of_each_candidate(capsys):
    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    sel = chaindrive.analyze(drive, response=False).selection
    assert sel is not None
    print_selection(sel.to_dict())
    out = capsys.readouterr().out
    assert "lubrication" in out
    first = sel.candidates[0]
    assert first.lubrication is not None and first.lubrication.regime in out


def test_the_report_has_both_tables(jindal):
    text = render_html(build_report(jindal, dpi=30))
    assert "Chain length options (tight length as designed 131.7 pitches)" in text
    assert "round up (chosen)" in text
    assert "Lubrication at the chain speed 3.334 m/s" in text
    assert "McGuire Bearing" in text  # the reference list carries the cited table


def test_the_page_tables_in_both_unit_systems(jindal):
    doc = jindal.to_dict()
    rows = length_option_records(doc)
    assert [r["links"] for r in rows] == [130, 132] and rows[1]["rounding"] == "round up (chosen)"
    a_mm = jindal.geometry.center_distance * 1e3  # shown to 4 significant digits
    assert rows[1]["centre distance, mm"] == pytest.approx(a_mm, rel=5e-4)
    us = length_option_records(doc, "US")
    assert us[1]["centre distance, in"] == pytest.approx(a_mm / 25.4, rel=5e-4)
    lube = {r["quantity"]: r for r in lubrication_records(doc)}
    assert lube["regime"]["value"] == "bath/disc (ANSI type B)"
    assert lube["chain speed"]["unit"] == "m/s"
    assert {r["quantity"]: r for r in lubrication_records(doc, "US")}["chain speed"]["unit"] \
        == "ft/min"
    sel = chaindrive.analyze(chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml"),
                             response=False).to_dict()["selection"]
    assert all(r["lubrication"] for r in selection_records(sel))


def test_the_page_length_table_has_no_none_cells() -> None:
    """A quantity that does not apply is no column (a contour of more than two sprockets has
    no centre distance) or a dash with its reason (a count that cannot be laid out), never
    "None"."""
    for name in ("seed_three_sprocket.toml", "eight_sprocket.toml"):
        doc = chaindrive.analyze(chaindrive.load(EXAMPLES / name), response=False).to_dict()
        rows = length_option_records(doc)
        assert rows and all(v is not None and v != "None" for r in rows for v in r.values())
        assert not any("centre distance" in k for r in rows for k in r)
    seed = length_option_records(chaindrive.analyze(
        chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"), response=False).to_dict())
    short = next(r for r in seed if r["rounding"] == "round down")
    assert short["slack-span sag, mm"] == "—" and "shorter than the tight contour" in short["note"]


def test_reusing_the_design_layout_changes_no_option(jindal):
    """The analysis hands its own layout to length_options for the count it made; laying
    every count out afresh gives the same options to round-off."""
    from chaindrive.geometry.length_options import length_options

    fresh = length_options(jindal.design).to_dict()  # names its chain: no selection
    reused = jindal.length_choice.to_dict()
    assert fresh["chosen"] == reused["chosen"]
    for a, b in zip(fresh["options"], reused["options"], strict=True):
        assert a["links"] == b["links"] and a["error"] == b["error"]
        for key in ("centre_distance_mm", "take_up_mm", "slack_sag_mm"):
            assert a[key] == pytest.approx(b[key], rel=1e-12, abs=1e-12)
