"""The uncertainty model and the states of a drive (chaindrive.robust.uncertainty,
.perturbation, .analysis, .life).

Numbers: the commercial sprocket eccentricity table [RyleTolerances] (ASME B29.1), the
installation tolerance of shaft distances [TsubakiGuide, §7.1.2.2], the acetal modulus
points [Delrin500P], the take-up's two pitches [DiamondChainTension] and the ACA wear-life
relation h ∝ ε [Shigley2015, Eq. 17-40].
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.catalog import find_material
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping
from chaindrive.robust import (
    Perturbation,
    PerturbedAnalysis,
    UncertaintySettings,
    life_curve,
    nominal_analysis,
    uncertainty_model,
    uncertainty_settings,
)
from chaindrive.robust.life import wear_state
from chaindrive.robust.perturbation import modulus_factor
from chaindrive.robust.uncertainty import eccentricity_limit, position_tolerance
from chaindrive.robust.wear import links_removed
from chaindrive.strength.wear import wear_life_hours
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def eight() -> chaindrive.analysis.Analysis:
    return nominal_analysis(chaindrive.load(EXAMPLES / "eight_sprocket.toml"))


def test_settings_defaults_and_mistakes() -> None:
    s = uncertainty_settings(None)
    assert (s.samples, s.wear, s.chain_length_tolerance) == (256, "life", 0.0015)
    assert uncertainty_settings({"eccentricity": "0.05 mm"}).eccentricity == pytest.approx(5e-5)
    with pytest.raises(DesignError, match=r"uncertainty\.wear"):
        uncertainty_settings({"wear": "old"})
    with pytest.raises(DesignError, match=r"uncertainty\.temperature_max"):
        uncertainty_settings({"temperature_min": 40.0, "temperature_max": 20.0})
    with pytest.raises(DesignError, match=r"uncertainty\.sample.*samples"):
        uncertainty_settings({"sample": 10})
    data = tomllib.loads((EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8"))
    data["uncertainty"] = {"inertia_scatter": 2.0}
    with pytest.raises(DesignError, match=r"uncertainty\.inertia_scatter"):
        drive_from_mapping(data)          # the design file is checked when it loads


def test_tolerances_from_the_tables() -> None:
    # ASME B29.1 commercial sprockets: TIR 0.006 in up to 4 in, 0.020 in for 15–20 in
    assert eccentricity_limit(3.9 * 0.0254) == pytest.approx(0.003 * 0.0254)
    assert eccentricity_limit(16 * 0.0254) == pytest.approx(0.010 * 0.0254)
    assert eccentricity_limit(150 * 0.0254) == pytest.approx(0.024 * 0.0254)  # last row
    # shafts: ±1 mm up to 1 m, ±a/1000 to 10 m, ±10 mm beyond
    assert position_tolerance(0.6) == 1e-3
    assert position_tolerance(4.0) == pytest.approx(4e-3)
    assert position_tolerance(25.0) == 10e-3
    pom = find_material("POM")
    assert modulus_factor(pom, 100.0) == pytest.approx(700 / 3250)
    assert modulus_factor(pom, -40.0) == pytest.approx(3450 / 3250)
    assert modulus_factor(find_material("steel"), 100.0) == 1.0


def test_model_of_a_drive_with_a_take_up(eight) -> None:
    model = uncertainty_model(eight)
    assert model.allowable_elongation == 0.03 and not model.fixed_centres
    assert model.take_up_capacity == pytest.approx(2 * eight.drive.chain.pitch)
    assert set(model.groups) == {"chain length", "wear", "eccentricity", "shaft positions",
                                 "inertias", "chain stiffness"}
    # no position variable for the driver or for the take-up that moves anyway
    moved = {v.name for v in model.variables if v.group == "shaft positions"}
    assert "x[0]" not in moved and f"x[{eight.geometry.adjusted}]" not in moved
    # a state's elongation: length tolerance + the life fraction of the rest
    x = model.values(np.full((1, model.dimension), 0.5))[0]
    eps0 = 0.5 * 0.0015
    assert model.perturbation(x).elongation == pytest.approx(eps0 + 0.5 * (0.03 - eps0))


def test_nominal_state_is_the_analysis(eight) -> None:
    state = PerturbedAnalysis(eight, Perturbation())
    assert [(c.key, c.status) for c in state.checks()] == [
        (c.key, c.status) for c in eight.checks()]
    for a, b in zip(state.checks(), eight.checks(), strict=True):
        assert a.value == pytest.approx(b.value, rel=1e-9)


def test_life_curve_of_a_fixed_centre_drive() -> None:
    """The seed contour as drawn fails the checks its analysis fails (teeth in mesh on the
    idler S3 and S3 on the tight span, the resonance margin: the whole-drive model's
    f₁ = 73.06 Hz lies 2.7 % below the 75 Hz tooth frequency, docs/dynamics.md §7); those
    are left out of the
    first failure, so the chain's life ends at the replacement rule of a fixed-centre drive,
    1.5 % [DiamondChainWear]."""
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    model = uncertainty_model(nominal, UncertaintySettings())
    life = life_curve(nominal, model, points=7)
    assert model.fixed_centres and life.allowable_elongation == 0.015
    assert life.failing_when_new == tuple(c.key for c in nominal.checks() if not c.passed)
    # and its polymer sprockets' teeth (no confirmed allowable stress) cannot be verified; its
    # chain's fatigue passes against the estimate 15 % of the breaking load [IwisFatigue]
    teeth = {f"{n}[{s}]" for s in ("S1", "S2", "S3")
             for n in ("tooth_root_stress", "tooth_contact_pressure")}
    assert set(life.failing_when_new) == {"teeth_in_mesh[S3]", "resonance_margin", *teeth}
    assert life.first_failure == "chain_elongation"
    assert life.first_failure_elongation == life.life_elongation == 0.015
    sag = [s.sag_ratio for s in life.states]
    assert sag == sorted(sag)
    assert life.hours_per_elongation is None       # a GOST chain has no ACA rating


def test_seed_kd_tail_is_the_tooth_frequency_resonance_of_a_new_chain() -> None:
    """The long upper tail of K_D over the seed's states (docs/robust.md) is a resonance,
    not a numerical jump: with S2 0.4 mm farther from S1 (within one standard deviation of
    its position tolerance, [TsubakiGuide, §7.1.2.2]) the new chain hangs tighter than the
    drawing's 2 % sag and f₁ lies above the tooth frequency f_z = z₁n₁ = 15 · 5 Hz = 75 Hz;
    as the chain wears (ε from 0 to 0.06 %) the slack grows, f₁ falls through f_z
    monotonically, and K_D traces one resonance peak whose top is the state with f₁
    nearest f_z ([Rao2011, ch. 3]: the steady amplitude of a lightly damped mode is largest at
    resonance, within a step here, and falls monotonically on both sides; the next mode,
    f₂ ≈ 250 Hz, is far away)."""
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    assert nominal.steady is not None
    f_z = nominal.steady.tooth_angular_frequency / (2 * np.pi)
    assert f_z == pytest.approx(15 * 300 / 60)
    f1, kd = [], []
    for eps in np.linspace(0.0, 6e-4, 25):
        state = PerturbedAnalysis(nominal, Perturbation(
            elongation=float(eps), offsets=((0.0, 0.0), (-4e-4, 0.0), (0.0, 0.0))))
        assert state.steady is not None and state.steady.coefficient_of_dynamics is not None
        f1.append(float(state.dynamics.modal.elastic_frequencies_hz[0]))
        kd.append(state.steady.coefficient_of_dynamics)
    assert np.all(np.diff(f1) < 0) and f1[0] > f_z > f1[-1]
    peak = int(np.argmax(kd))
    assert abs(peak - int(np.argmin(np.abs(np.asarray(f1) - f_z)))) <= 1
    assert 0 < peak < len(kd) - 1
    assert np.all(np.diff(kd[:peak + 1]) > 0) and np.all(np.diff(kd[peak:]) < 0)


def test_life_curve_bisects_the_first_failure(tmp_path: Path) -> None:
    """The conveyor example turning the other way (counter-clockwise: its tensioner T then
    sits on the span into the driver) passes every check when new but that tensioner (its
    fatigue passes: the study runs no start-up, and the steady span forces stay below the
    estimated fatigue strength); the
    wear lowers its first natural frequency into the resonance band (the analysis's rule
    [MultimassChainDrives, §3.2]) before the replacement rule: the bisection brackets the
    flip of the check."""
    text = (EXAMPLES / "conveyor_five_sprocket.toml").read_text(encoding="utf-8")
    assert 'rotation = "cw"' in text
    (tmp_path / "ccw.toml").write_text(text.replace('rotation = "cw"', 'rotation = "ccw"'),
                                       encoding="utf-8")
    nominal = nominal_analysis(chaindrive.load(tmp_path / "ccw.toml"))
    model = uncertainty_model(nominal, UncertaintySettings())
    life = life_curve(nominal, model, points=5)
    assert set(life.failing_when_new) == {"idler_on_slack_span[T]"}
    eps = life.first_failure_elongation
    assert eps is not None and life.first_failure == "resonance_margin"
    assert 0 < eps < life.allowable_elongation and life.life_elongation == eps
    assert "resonance_margin" in wear_state(nominal, model, eps).failed
    assert "resonance_margin" not in wear_state(nominal, model, eps * 0.98).failed


def test_life_curve_with_a_take_up(eight) -> None:
    model = uncertainty_model(eight)
    life = life_curve(eight, model, points=5)
    travel = [s.take_up_travel_mm for s in life.states]
    runs_out = life.take_up_runs_out
    assert runs_out == pytest.approx(2 * eight.drive.chain.pitch / eight.geometry.chain_length)
    # the take-up follows the chain until it has absorbed two pitches, then two links come out
    # [DiamondChainTension]: it never travels further than it did up to that point
    before = [t for t, s in zip(travel, life.states, strict=True) if s.elongation <= runs_out]
    after = [t for t, s in zip(travel, life.states, strict=True) if s.elongation > runs_out]
    assert travel[0] == 0 and before == sorted(before) and after
    at_capacity = wear_state(eight, model, runs_out).take_up_travel_mm
    assert max(travel) <= at_capacity + 1e-6
    assert [s.links_removed for s in life.states] == [
        links_removed(eight.geometry.links, eight.drive.chain.pitch, s.elongation,
                      model.take_up_capacity) for s in life.states]
    assert all(s.links_removed >= 2 for s in life.states if s.elongation > runs_out)
    rated = eight.strength.rated_power
    hours = wear_life_hours(rated, eight.drive.power * (eight.drive.service_factor or 1.0),
                            eight.geometry.links, 0.03)
    assert life.hours(0.03) == pytest.approx(hours)        # ACA: h ∝ ε
    assert life.life_elongation <= 0.03
