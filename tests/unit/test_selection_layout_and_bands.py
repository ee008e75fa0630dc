"""The selection chooses the chain on its chain checks and judges the layout and the dynamics
beside it (docs/selection.md, "The chain, the layout and the dynamics").

Fixtures (tests/fixtures/):

* ``selection_tensioner.toml`` — a four-sprocket ISO 606 B drive (driver, driven, an idler
  and a 15-tooth spring tensioner) whose tensioner has 2.95 teeth in mesh with the lightest
  chain that passes every chain check (20B-1): the layout, not the chain, is to change;
* ``selection_conveyor_ansi.toml`` — the five-sprocket conveyor at 7.5 kW asking for an ANSI
  chain, whose lightest chain that passes every chain check (ISO 606 20A-1 = ANSI 100) has a
  resonance detuning of 8.2 % against the 10 % required, inside its band.

Closed forms used: teeth in mesh z·θ/2π [Renold-DG]; the band of every natural frequency
f·[√((1−u)/(1+u)), √((1+u)/(1−u))] for stiffnesses and inertias within ±u [Horn2013, §4.2];
the detuning of f_w from f_n, |f_w − f_n|/f_n, is at least b over that band when
f_w ≤ (1−b)·f·√((1−u)/(1+u)) or f_w ≥ (1+b)·f·√((1+u)/(1−u)); the wrap of the small sprocket
of a two-sprocket drive π − 2·asin((R₂ − R₁)/a) ≥ 120° ⇔ a ≥ 2(R₂ − R₁) [Shigley2015, §17-2].
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest

import chaindrive
from chaindrive.analysis import Analysis
from chaindrive.catalog import chains, find_chain
from chaindrive.checks import Check, judged
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.sprocket import pitch_radius
from chaindrive.io.design import drive_from_mapping
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength.drive_checks import geometry_checks
from chaindrive.strength.remedies import layout_remedies
from chaindrive.strength.selection import (
    BEYOND_BAND,
    INSIDE_BAND,
    LAYOUT_REMEDY,
    PASSED_OVER,
    RESONANCE_PASS,
    RESONANCE_POSSIBLE,
    SMALL_LAYOUT_SHORTFALL,
    ResonanceProbe,
    banded_resonance_check,
    rank_chains,
    resonance_verdict,
)
from tests.conftest import rpm

FIXTURES = Path(__file__).parents[1] / "fixtures"


def _mapping(name: str) -> dict[str, Any]:
    """The fixture's design mapping as written (its chain request kept)."""
    return tomllib.loads((FIXTURES / name).read_text(encoding="utf-8"))


def _analysis(name: str, **changes: Any) -> Analysis:
    data = _mapping(name)
    for section, values in changes.items():
        data[section] = {**data.get(section, {}), **values}
    return chaindrive.analyze(drive_from_mapping(data), response=False)


def _lightest_doing_the_job(a: Analysis) -> str:
    """The lightest candidate that passes every chain check (the designer's choice)."""
    sel = a.selection
    assert sel is not None
    doing = [c for c in sel.candidates if c.chain_passed]
    return min(doing, key=lambda c: (c.mass_per_length, c.pitch, c.strands)).designation


# ------------------------------------------------------------------ the layout is to change

def test_tensioner_drive_keeps_the_lightest_chain_and_names_the_layout_remedy():
    a = _analysis("selection_tensioner.toml")
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    chosen = sel.chosen
    assert chosen.designation == _lightest_doing_the_job(a) == "ISO 606 20B-1"
    # the old rule took a heavier chain whose layout passes: it is still in the ranking
    assert any(c.passed for c in sel.candidates if c.mass_per_length > chosen.mass_per_length)
    # teeth in mesh on T = z·θ/2π from the contour, short of 3 by less than the small amount
    g = next(s for s in a.geometry.sprockets if s.name == "T")
    assert g.teeth_in_mesh == pytest.approx(15 * g.wrap_angle / (2 * math.pi), rel=1e-12)
    check = a.check("teeth_in_mesh[T]")
    assert check is not None and not check.passed
    assert 0 < -(check.margin_fraction or 0.0) <= SMALL_LAYOUT_SHORTFALL
    finding = next(f for f in sel.findings if f.kind == LAYOUT_REMEDY)
    assert finding.chain == chosen.designation and finding.check == "teeth_in_mesh[T]"
    assert finding.shortfall_fraction == pytest.approx(-(check.margin_fraction or 0.0))
    actions = {r.action for r in finding.remedies}
    assert actions == {"teeth", "move"}
    assert "the layout misses teeth in mesh on T" in finding.text


@pytest.mark.parametrize("action", ["teeth", "move"])
def test_tensioner_remedy_applied_passes_the_layout_check(action: str) -> None:
    """Re-analyse the design with the remedy applied (the tensioner retoothed, or moved to
    the centre the finding gives): the check passes, and the same chain is chosen with no
    layout finding left."""
    a = _analysis("selection_tensioner.toml")
    assert a.selection is not None
    finding = next(f for f in a.selection.findings if f.kind == LAYOUT_REMEDY)
    remedy = next(r for r in finding.remedies if r.action == action)
    data = _mapping("selection_tensioner.toml")
    t = next(s for s in data["sprockets"] if s["name"] == "T")
    t["teeth"] = remedy.teeth
    t["x"], t["y"] = f"{remedy.x * 1e3:.1f} mm", f"{remedy.y * 1e3:.1f} mm"
    again = chaindrive.analyze(drive_from_mapping(data), response=False)
    check = again.check("teeth_in_mesh[T]")
    assert check is not None and check.passed
    assert check.value == pytest.approx(remedy.value, rel=1e-9)
    assert again.geometry.links == remedy.links
    assert again.drive.chain.spec.designation == "ISO 606 20B-1"
    assert again.selection is not None
    assert not [f for f in again.selection.findings if f.kind == LAYOUT_REMEDY]


def test_remedy_of_a_two_sprocket_wrap_matches_the_closed_form():
    """Driver 17 teeth, driven 60 teeth, 12B chain rounded down (the take-up shortens the
    centre distance), centre distance too short for 120° of wrap on the driver: the remedy
    moves the driven sprocket away (the line of centres, its wrap bisector), and the
    remedied layout's centre distance is at least 2(R₂ − R₁)."""
    spec = find_chain("12B-1")
    r1, r2 = pitch_radius(spec.pitch, 17), pitch_radius(spec.pitch, 60)
    a0 = 1.9 * (r2 - r1)  # wrap π − 2 asin(1/1.9) = 116.5° < 120°
    drive = Drive("wrap", Chain(spec, rounding="round down"), (
        Sprocket("A", 17, 0.0, 0.0, "driver", speed=rpm(300.0)),
        Sprocket("B", 60, a0, 0.0, "driven")), power=2000.0)
    geometry = contour_geometry(drive)
    failed = next(c for c in geometry_checks(drive, geometry) if c.key == "wrap[A]")
    assert not failed.passed
    remedies = layout_remedies(drive, geometry, failed)
    move = next(r for r in remedies if r.sprocket == "B")
    assert move.action == "move" and move.distance > 0 and move.y == pytest.approx(0.0, abs=1e-9)
    laid = contour_geometry(drive.with_sprockets((drive.sprockets[0],
                                                  drive.sprockets[1].moved_to(move.x, move.y))))
    assert laid.center_distance is not None and laid.center_distance >= 2 * (r2 - r1) - 1e-9
    assert math.degrees(laid.sprockets[0].wrap_angle) >= 120.0 - 1e-9
    # the least such move: half a millimetre less (the bisection's resolution) does not do
    short = drive.with_sprockets((drive.sprockets[0], drive.sprockets[1].moved_to(
        move.x - 1e-3, 0.0)))
    assert not next(c for c in geometry_checks(short, contour_geometry(short))
                    if c.key == "wrap[A]").passed


def test_a_large_layout_shortfall_passes_the_chain_over_and_says_why():
    """The tensioner fixture with the idler pushed up into the contour: with 16B-2 the
    tensioner's teeth in mesh miss 3 by more than the small amount — it passes every chain
    check, is passed over, and is named with its shortfall and remedies."""
    drive = chaindrive.load(FIXTURES / "selection_tensioner.toml")
    res = rank_chains(drive, standard="ISO 606", series="B")
    big = [c for c in res.candidates
           if c.chain_passed and c.layout_shortfall > SMALL_LAYOUT_SHORTFALL]
    assert big, "the fixture has a chain whose layout misses by more than the small amount"
    for c in big:
        assert not c.selectable
    lighter = [c for c in big if res.chosen and c.mass_per_length < res.chosen.mass_per_length]
    named = {f.chain for f in res.findings if f.kind == PASSED_OVER}
    assert {c.designation for c in lighter[:3]} <= named


def test_small_shortfall_is_below_the_smallest_pitch_step_of_the_catalogue():
    """The rationale of SMALL_LAYOUT_SHORTFALL (docs/selection.md): smaller than the least
    relative step between neighbouring pitches of any family of the catalogue, so the next
    size clears such a shortfall by its scale alone."""
    families: dict[tuple[str, str], set[float]] = {}
    for c in chains():
        families.setdefault((c.standard, c.series), set()).add(round(c.pitch, 6))
    steps = [b / a - 1 for pitches in families.values()
             for a, b in zip(sorted(pitches), sorted(pitches)[1:], strict=False)]
    assert min(steps) > SMALL_LAYOUT_SHORTFALL


# ------------------------------------------------------------------ dynamics: beyond the band

def test_conveyor_resonance_inside_its_band_keeps_the_lighter_chain():
    a = _analysis("selection_conveyor_ansi.toml")
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    chosen = sel.chosen
    assert chosen.designation == _lightest_doing_the_job(a) == "ISO 606 20A-1"
    assert sel.to_dict()["ansi_number"] == "100"
    assert chosen.resonance == INSIDE_BAND and chosen.layout_shortfall == 0
    check = a.check("resonance_margin")
    assert check is not None and not check.passed and check.value < 10.0
    # the band: closed form of the detuning over f_n·[lo, hi]
    u = a.drive.dynamics.uncertainty
    lo, hi = math.sqrt((1 - u) / (1 + u)), math.sqrt((1 + u) / (1 - u))
    label, fw, fn, _, low, high, _ = min(a.bands.detunings, key=lambda r: abs(r[3]))
    assert label == check.subject
    assert high == pytest.approx(100 * max(abs(fw / (fn * lo) - 1), abs(fw / (fn * hi) - 1)))
    assert low < 10.0 <= high  # the margin lies inside its own band
    assert "inside its own band" in check.note
    finding = next(f for f in sel.findings if f.kind == RESONANCE_POSSIBLE)
    assert finding.chain == chosen.designation
    for settle in ("[chain] sag", "[chain] link_stiffness", "[dynamics] uncertainty",
                   "tooth counts", "inertias"):
        assert settle in finding.text
    # the working frequencies it names are where the band's detuning is exactly 10 %
    b = 0.10
    below, above = (1 - b) * fn * lo, (1 + b) * fn * hi
    assert f"below {below:.4g} Hz" in finding.text and f"above {above:.4g} Hz" in finding.text
    assert 1 - below / (fn * lo) == pytest.approx(b) and above / (fn * hi) - 1 == pytest.approx(b)


def test_conveyor_with_a_given_sag_is_still_inside_its_band():
    """With [chain] sag = 0.01 the detuning moves (the span frequencies follow the sag), and
    stays inside its band: the chain is kept, the finding no longer lists the sag as
    assumed."""
    a = _analysis("selection_conveyor_ansi.toml", chain={"sag": 0.01})
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    assert sel.chosen.designation == "ISO 606 20A-1" and sel.chosen.resonance == INSIDE_BAND
    finding = next(f for f in sel.findings if f.kind == RESONANCE_POSSIBLE)
    assert "[chain] sag" not in finding.text and "[chain] link_stiffness" in finding.text


def test_conveyor_resonance_beyond_its_band_moves_the_selection_and_says_so():
    """Known to ±1 %, the detuning of 20A-1 stays below 10 % over its whole band: it is
    passed over for the next chain, and the finding says it failed beyond its band."""
    a = _analysis("selection_conveyor_ansi.toml", dynamics={"uncertainty": 0.01})
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    tried = next(c for c in sel.candidates if c.designation == "ISO 606 20A-1")
    assert tried.resonance == BEYOND_BAND and not tried.selectable
    assert sel.chosen.mass_per_length > tried.mass_per_length
    assert sel.chosen.resonance != BEYOND_BAND
    finding = next(f for f in sel.findings if f.kind == PASSED_OVER)
    assert finding.chain == "ISO 606 20A-1" and "beyond its band" in finding.text


def _probe(nominal: float, u: float, band: float = 10.0) -> ResonanceProbe:
    """One resonance row with the working frequency ``nominal`` % below f_n = 100 Hz, its
    band by the closed form (module docstring)."""
    lo, hi = math.sqrt((1 - u) / (1 + u)), math.sqrt((1 + u) / (1 - u))
    fn, fw = 100.0, 100.0 * (1 - nominal / 100)
    inside = fn * lo <= fw <= fn * hi
    edges = (abs(fw / (fn * lo) - 1), abs(fw / (fn * hi) - 1))
    row = ("tooth", fw, fn, -nominal, 0.0 if inside else 100 * min(edges), 100 * max(edges),
           inside)
    check: Check = judged("resonance margin", "tooth", nominal, band, "min", "[API684]", "%",
                          part="dynamics")
    return ResonanceProbe(check, (row,), u, (lo, hi))


@pytest.mark.parametrize(("nominal", "u", "verdict"), [
    (12.0, 0.1, RESONANCE_PASS),
    (8.97, 0.1, INSIDE_BAND),   # 8.97 % against 10 %: inside ±10 %
    (0.1, 0.1, INSIDE_BAND),    # ±10 %: the band reaches 10.6 % even on the resonance
    (8.97, 0.01, BEYOND_BAND),  # ±1 %: at most 9.9 % over the band
    (0.1, 0.02, BEYOND_BAND),
])
def test_resonance_verdict_by_the_band(nominal: float, u: float, verdict: str) -> None:
    probe = _probe(nominal, u)
    assert resonance_verdict(probe, 10.0) == verdict
    banded = banded_resonance_check(probe, 10.0)
    assert banded is not None
    if verdict == INSIDE_BAND:
        assert "inside its own band" in banded.note
    elif verdict == BEYOND_BAND:
        assert "fails over its whole band" in banded.note
    else:
        assert banded == probe.check


def test_no_working_frequency_is_no_verdict():
    probe = replace(_probe(5.0, 0.1), check=None)
    assert resonance_verdict(probe, 10.0) == RESONANCE_PASS
    assert banded_resonance_check(probe, 10.0) is None


def test_json_and_select_table_carry_the_findings():
    a = _analysis("selection_tensioner.toml")
    assert a.selection is not None
    doc = a.to_dict()["selection"]
    assert doc["small_layout_shortfall_fraction"] == SMALL_LAYOUT_SHORTFALL
    kinds = [f["kind"] for f in doc["findings"]]
    assert LAYOUT_REMEDY in kinds
    remedy = next(f for f in doc["findings"] if f["kind"] == LAYOUT_REMEDY)["remedies"][0]
    assert {"check", "sprocket", "action", "teeth", "x_mm", "y_mm", "move_mm", "value_after",
            "unit", "links", "text"} <= set(remedy)
    first = doc["candidates"][0]
    assert first["chain_checks_passed"] and first["selectable"] and not first["passed"]
    assert first["layout_shortfall_fraction"] == pytest.approx(
        -a.check("teeth_in_mesh[T]").margin_fraction)


def test_presenters_show_the_findings_in_the_unit_system():
    """The page's candidate rows carry the verdict; the findings are written in the output
    unit system (the move of the remedy in inches: 1 in = 25.4 mm exactly)."""
    from chaindrive.app.views import selection_records
    from chaindrive.display import candidate_verdict, finding_lines

    a = _analysis("selection_tensioner.toml")
    assert a.selection is not None
    doc = a.selection.to_dict()
    rows = selection_records(doc)
    assert rows[0]["verdict"] == candidate_verdict(doc["candidates"][0])
    assert rows[0]["verdict"].startswith("layout ") and "short" in rows[0]["verdict"]
    si = dict(finding_lines(doc))
    us = dict(finding_lines(doc, "US"))
    move = next(r for f in a.selection.findings for r in f.remedies if r.action == "move")
    assert f"move T {move.distance * 1e3:.0f} mm" in si[LAYOUT_REMEDY]
    assert f"{abs(move.distance) / 0.0254:.3g} in" in us[LAYOUT_REMEDY]


def test_two_sprocket_remedy_reads_as_a_centre_distance():
    spec = find_chain("12B-1")
    r1, r2 = pitch_radius(spec.pitch, 17), pitch_radius(spec.pitch, 60)
    drive = Drive("wrap", Chain(spec, rounding="round down"), (
        Sprocket("A", 17, 0.0, 0.0, "driver", speed=rpm(300.0)),
        Sprocket("B", 60, 1.9 * (r2 - r1), 0.0, "driven")), power=2000.0)
    geometry = contour_geometry(drive)
    failed = next(c for c in geometry_checks(drive, geometry) if c.key == "wrap[A]")
    (move,) = layout_remedies(drive, geometry, failed)
    assert move.text.startswith("move B ") and "away from A" in move.text


def test_remedies_sharing_a_memo_are_those_found_alone_with_fewer_layouts(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The selection lays each change of a chain's drive out once for all its missed layout
    checks (the memo of :func:`layout_remedies`): the remedies are those each check finds
    alone, and the shared changes are not laid out again."""
    from chaindrive.examples import __file__ as examples
    from chaindrive.io.design import load_drive
    from chaindrive.strength import remedies as rem

    a = chaindrive.analyze(load_drive(Path(examples).parent / "seed_three_sprocket.toml"),
                           response=False)
    assert a.selection is not None
    c = next(c for c in a.selection.candidates if c.chain_passed and c.geometry is not None
             and len([k for k in c.layout_checks if not k.passed]) > 1)
    missed = [k for k in c.layout_checks if not k.passed]
    on = replace(a.design, chain=replace(a.design.chain, links=None, request=None)
                 ).with_chain(a.selection.specs[c.designation])  # as the selection lays out
    solves = 0
    solve = rem.contour_geometry

    def counted(drive: Drive) -> Any:
        nonlocal solves
        solves += 1
        return solve(drive)

    monkeypatch.setattr(rem, "contour_geometry", counted)
    assert c.geometry is not None
    alone = [layout_remedies(on, c.geometry, k) for k in missed]
    solves_alone, solves = solves, 0
    memo: rem.Layouts = {}
    shared = [layout_remedies(on, c.geometry, k, memo) for k in missed]
    assert shared == alone
    assert any(alone)
    assert 0 < solves == len(memo) < solves_alone
