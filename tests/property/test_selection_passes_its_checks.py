"""Property: the chain a selection chooses passes every chain check, misses no layout check
by more than the small shortfall the selection leaves to the layout, and no lighter chain
that passes every chain check is passed over for a check whose margin lies inside its own
uncertainty band — for the bundled examples, for 30 random two-sprocket drives and, through
the one pipeline (``analyze``), for 30 random drives of 2 to 6 sprockets (hypothesis,
derandomised).

Closed form of the property: chosen ⇒ ∀ chain check: status = "pass", max layout
shortfall ≤ SMALL_LAYOUT_SHORTFALL; every selectable candidate is ranked before every other;
a lighter candidate that passes every chain check has a layout shortfall > SMALL, or a
resonance check whose highest detuning over its band (every natural frequency within
f·[√((1−u)/(1+u)), √((1+u)/(1−u))], [Horn2013, §4.2]) stays below the limit."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import chaindrive
from chaindrive.catalog import find_chain
from chaindrive.geometry.contour import contour_geometry
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength.drive_checks import checks_for, geometry_checks, settings_for
from chaindrive.strength.selection import (
    BEYOND_BAND,
    INSIDE_BAND,
    LAYOUT_REMEDY,
    NAMED_PASSED_OVER,
    PASSED_OVER,
    RESONANCE_POSSIBLE,
    SMALL_LAYOUT_SHORTFALL,
    SelectionResult,
    rank_chains,
)

EXAMPLES = sorted(p for p in (Path(__file__).parents[2] / "examples").glob("*.toml")
                  if "optimize" not in p.name)


def _assert_chosen_passes(drive: Drive, **options: object) -> bool:
    res = rank_chains(drive, **options)  # type: ignore[arg-type]
    selectable = [c.selectable for c in res.candidates]
    assert selectable == sorted(selectable, reverse=True)  # every selectable one first
    if res.chosen is None:
        assert res.closest is not None and res.closest.missed
        return False
    chosen = res.chosen
    assert chosen.chain_checks and all(c.passed for c in chosen.chain_checks), chosen.to_dict()
    assert chosen.layout_shortfall <= SMALL_LAYOUT_SHORTFALL
    on = drive.with_chain(res.chain)
    again = checks_for(on, contour_geometry(on), settings_for(on))
    chain_again = again[:len(chosen.chain_checks)]
    assert all(c.passed for c in chain_again), [c.to_dict() for c in chain_again if not c.passed]
    assert [c.status for c in again[len(chosen.chain_checks):]] == [
        c.status for c in chosen.layout_checks]
    if chosen.layout_shortfall > 0:  # the layout's to fix: said, with a remedy if one exists
        assert any(f.kind == LAYOUT_REMEDY and f.chain == chosen.designation
                   for f in res.findings)
    return True


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_bundled_examples(path: Path):
    drive = chaindrive.load(path)
    if drive.power is None:
        pytest.skip("no power: nothing to select")
    _assert_chosen_passes(drive, standard=drive.chain.spec.standard)


def _random_drive(rng: np.random.Generator, family: str) -> Drive:
    z1 = int(rng.integers(15, 26))
    z2 = int(min(120, round(z1 * rng.uniform(1.0, 4.0))))
    n1 = float(rng.uniform(50.0, 1500.0))
    power = float(10 ** rng.uniform(2.5, 4.5))  # 0.3 … 30 kW
    a = float(rng.uniform(0.4, 1.5))
    chain = {"A": "16A-1", "B": "16B-1"}.get(family, "16A-1")
    return Drive("random", Chain(find_chain(chain)),
                 (Sprocket("A", z1, 0.0, 0.0, "driver", speed=n1 * math.pi / 30),
                  Sprocket("B", z2, a, 0.0, "driven")),
                 power=power, service_factor=float(rng.choice([1.0, 1.3, 1.5])))


def test_thirty_random_drives():
    rng = np.random.default_rng(20261124)
    chosen = 0
    for i in range(30):
        family = ("A", "B", "GOST")[i % 3]
        drive = _random_drive(rng, family)
        if family == "GOST":
            chosen += _assert_chosen_passes(drive, standard="GOST 13568")
        else:
            chosen += _assert_chosen_passes(drive, standard="ISO 606", series=family)
    assert chosen >= 20  # the property is exercised, not vacuous


def _requested(drive: Drive, standard: str, series: str | None) -> dict[str, object]:
    """The design mapping of ``drive`` asking for a chain of ``standard``/``series`` instead
    of naming one."""
    from chaindrive.io.design import drive_to_mapping

    data = drive_to_mapping(drive)
    data["chain"] = {"standard": standard, **({"series": series} if series else {})}
    return data


def _assert_analysis_chooses_by_its_rule(data: dict[str, object]) -> SelectionResult | None:
    """Through the one pipeline: the chain the analysis selects passes every chain check of
    that analysis; its layout misses by at most the small shortfall; its resonance check (a
    response-free analysis: k₁, k₂ need the response) fails, if at all, inside its band
    only; and no lighter chain that passes every chain check was passed over for a margin
    inside its own band."""
    from chaindrive.errors import DesignError
    from chaindrive.io.design import drive_from_mapping

    try:
        a = chaindrive.analyze(drive_from_mapping(data), response=False)
    except DesignError as exc:  # no chain is selectable: the message names the closest
        message = str(exc)
    else:
        message = ""
    if message:
        assert "no chain passes" in message, message
        return None
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    chain_part = {c.key for c in sel.chosen.chain_checks}
    failed = [c for c in a.checks() if not c.passed]
    assert not [c.key for c in failed if c.key in chain_part]
    for c in failed:
        if c.part == "geometry":
            margin = c.margin_fraction
            assert margin is not None and -margin <= SMALL_LAYOUT_SHORTFALL + 1e-12, c.to_dict()
        elif c.key == "resonance_margin":
            assert sel.chosen.resonance == INSIDE_BAND
            assert any(f.kind == RESONANCE_POSSIBLE for f in sel.findings)
    _assert_no_lighter_passed_over_inside_its_band(a)
    _assert_remedies_make_their_checks_pass(a.design, sel)
    return sel


def _assert_remedies_make_their_checks_pass(design: Drive, sel: SelectionResult) -> None:
    """Each remedy of a layout finding, applied to the design with that chain and laid out
    again, makes its check pass."""
    for f in sel.findings:
        for r in f.remedies:
            spec = sel.specs[f.chain]
            changed = design.with_chain(spec).with_sprockets(tuple(
                replace(s, teeth=r.teeth, x=r.x, y=r.y) if s.name == r.sprocket else s
                for s in design.sprockets))
            changed = replace(changed, chain=replace(changed.chain, links=None))
            check = next(c for c in geometry_checks(changed, contour_geometry(changed))
                         if c.key == r.check)
            assert check.passed, (f.chain, r.text, check.to_dict())


def _assert_no_lighter_passed_over_inside_its_band(a: chaindrive.Analysis) -> None:
    """Every lighter candidate that passes every chain check was passed over for a layout
    shortfall beyond the small one, or for a resonance beyond its band: on the drive with
    that chain, some working frequency's highest detuning over the band, from the closed
    form max(|f_w/(f_n·lo) − 1|, |f_w/(f_n·hi) − 1|), stays below the limit."""
    sel = a.selection
    assert sel is not None
    chosen = sel.chosen
    assert chosen is not None
    lighter = sorted((c for c in sel.candidates if c.chain_passed and c is not chosen
                      and c.mass_per_length < chosen.mass_per_length),
                     key=lambda c: (c.mass_per_length, c.pitch, c.strands))
    named = {f.chain for f in sel.findings if f.kind == PASSED_OVER}
    assert {c.designation for c in lighter[:NAMED_PASSED_OVER]} <= named
    for c in lighter:
        if c.layout_shortfall > SMALL_LAYOUT_SHORTFALL:
            continue
        assert c.resonance == BEYOND_BAND, (c.designation, c.resonance)
        assert not c.dynamic_checks[0].passed
        probe = a._resonance_probe(sel.specs[c.designation])
        u = probe.uncertainty
        lo, hi = math.sqrt((1 - u) / (1 + u)), math.sqrt((1 + u) / (1 - u))
        assert any(100 * max(abs(fw / (fn * lo) - 1), abs(fw / (fn * hi) - 1))
                   < a.limits.resonance_band_percent for _, fw, fn, *_ in probe.rows)


def test_jindal_b_series_resonance_inside_its_band_keeps_the_lightest_chain():
    """[Jindal2010] example 30-3 (2.56 kW, z = 21/42 at 1000 rpm) asking for any ISO 606 B
    chain: the lightest chain that passes every chain check is 05B-3, whose drive has its
    first natural frequency 0.1 % from the third tooth harmonic (1050 Hz). With ±10 % on
    every stiffness and inertia the natural frequency lies anywhere in f·[0.905, 1.106]
    ([Horn2013, §4.2]) and the detuning over that band reaches 10.6 % > 10 %: the failed
    margin is inside its own band, so 05B-3 stays chosen with a "resonance possible"
    finding (before, a heavier chain was taken). Known to ±2 %, the detuning is at most
    2.1 % over the whole band: a resonance beyond its band, and 05B-3 is passed over."""
    drive = chaindrive.load(Path(__file__).parents[2] / "examples" / "two_sprocket_jindal.toml")
    from chaindrive.io.design import drive_from_mapping

    data = _requested(drive, "ISO 606", "B")
    a = chaindrive.analyze(drive_from_mapping(data), response=False)
    assert a.drive.chain.spec.designation == "ISO 606 05B-3"
    chosen = a.selection.chosen
    assert chosen.resonance == INSIDE_BAND
    lo = math.sqrt(0.9 / 1.1)
    _, fw, fn, _, _, high, _ = min(a.bands.detunings, key=lambda r: abs(r[3]))
    assert high == pytest.approx(100 * abs(fw / (fn * lo) - 1), rel=1e-9) and high > 10.0
    assert [f.kind for f in a.selection.findings] == [RESONANCE_POSSIBLE]
    assert "inside its own band" in a.check("resonance_margin").note

    data["dynamics"] = {**data.get("dynamics", {}), "uncertainty": 0.02}  # type: ignore[dict-item]
    narrow = chaindrive.analyze(drive_from_mapping(data), response=False)
    assert narrow.drive.chain.spec.designation != "ISO 606 05B-3"
    tried = next(c for c in narrow.selection.candidates if c.designation == "ISO 606 05B-3")
    assert tried.resonance == BEYOND_BAND and not tried.selectable
    assert any(f.kind == PASSED_OVER and f.chain == "ISO 606 05B-3"
               for f in narrow.selection.findings)
    assert all(c.passed for c in narrow.checks() if c.key == "resonance_margin")


def test_thirty_random_drives_choose_by_the_rule_in_the_one_pipeline():
    rng = np.random.default_rng(20261125)
    chosen = 0
    for i in range(30):
        family = ("A", "B", "GOST")[i % 3]
        drive = _random_drive(rng, family)
        standard = "GOST 13568" if family == "GOST" else "ISO 606"
        chosen += _assert_analysis_chooses_by_its_rule(
            _requested(drive, standard, None if family == "GOST" else family)) is not None
    assert chosen >= 20  # the property is exercised, not vacuous


@st.composite
def _drives(draw: st.DrawFn) -> tuple[Drive, str, str | None]:
    """A drive of 2 to 6 sprockets on the outside of a convex contour: the driver at the
    pointed end (so that its wrap can reach 120°), the others on a half circle at the far
    end, listed counter-clockwise, with more teeth the more of them share its wrap; at least
    one driven sprocket (no fewer teeth than the driver: the driver is then the small loaded
    sprocket), the rest idlers, one of them maybe the take-up; and the chain family."""
    n = draw(st.sampled_from([6, 5, 4, 3, 2]))
    length = draw(st.floats(0.6, 1.2))
    height = length * draw(st.floats(0.2, 0.4))
    phis = np.linspace(-math.pi / 2, math.pi / 2, n - 1) if n > 2 else np.zeros(1)
    z1 = draw(st.integers(15, 21))
    roles = ["driven", *(draw(st.sampled_from(["driven", "idler"])) for _ in range(n - 2))]
    draw_order = draw(st.permutations(list(range(n - 1))))
    roles = [roles[k] for k in draw_order]
    idlers = [i for i, r in enumerate(roles) if r == "idler"]
    take_up = draw(st.sampled_from(idlers)) if idlers and draw(st.booleans()) else None
    sprockets = [Sprocket("S1", z1, 0.0, 0.0, "driver",
                          speed=draw(st.floats(100.0, 1000.0)) * math.pi / 30)]
    for i, (role, phi) in enumerate(zip(roles, phis, strict=True)):
        teeth = draw(st.integers(max(z1, 6 * n), 3 * z1 + 6 * n) if role == "driven"
                     else st.integers(15, 10 * n))
        sprockets.append(Sprocket(f"S{i + 2}", teeth, length + height * math.cos(phi),
                                  height * math.sin(phi), role, adjustable=i == take_up))
    family = draw(st.sampled_from(["A", "B", "GOST"]))
    drive = Drive("random", Chain(find_chain("16A-1" if family == "A" else "16B-1")),
                  tuple(sprockets), power=draw(st.floats(500.0, 15e3)),
                  service_factor=draw(st.sampled_from([1.0, 1.3])))
    return drive, "GOST 13568" if family == "GOST" else "ISO 606", (
        None if family == "GOST" else family)


@settings(max_examples=30, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(_drives())
def test_random_drives_of_two_to_six_sprockets_choose_by_the_rule(
        case: tuple[Drive, str, str | None]) -> None:
    """30 random drives of 2–6 sprockets through ``analyze``: the chosen chain passes every
    chain check, and no lighter chain that passes them was passed over for a margin inside
    its own band (module docstring)."""
    drive, standard, series = case
    sel = _assert_analysis_chooses_by_its_rule(_requested(drive, standard, series))
    event(f"{len(drive.sprockets)} sprockets: " + ("chosen" if sel else "none selectable"))
    for f in () if sel is None else sel.findings:
        event(f"finding: {f.kind}")
