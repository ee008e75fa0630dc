"""The span tension read from a measured transverse frequency, against closed forms.

Sources: the axially moving string f_n = n/(2L)·(T − q v²)/sqrt(T q) ([Mote1965],
[WickertMote1990]); Irvine's symmetric in-plane frequency equation
tan(ω̄/2) = ω̄/2 − (4/λ²)(ω̄/2)³ ([IrvineCaughey1974]); first-order propagation of
independent uncertainties ([JCGM100, §5.1]).
"""

from __future__ import annotations

import math

import pytest

from chaindrive.errors import DesignError
from chaindrive.identification import (
    expected_frequency,
    span_tension_from_frequency,
    string_tension,
)
from chaindrive.identification.tension import irvine_parameter, symmetric_inplane_ratio


@pytest.mark.parametrize(("speed", "mode"), [(0.0, 1), (0.0, 3), (2.0, 1), (8.0, 2), (25.0, 1)])
def test_the_inverse_returns_the_frequency_it_was_read_from(speed: float, mode: int) -> None:
    # round trip through the forward law of chaindrive.dynamics.transverse
    T = string_tension(17.3, 0.68, 2.6, mode, speed)
    assert expected_frequency(T, 0.68, 2.6, mode, speed) == pytest.approx(17.3, rel=1e-12)


def test_a_hand_computed_case_stationary_and_running() -> None:
    # L = 0.5 m, q = 1 kg/m, f = 20 Hz, n = 1: T = 4 L² f² q = 400 N (taut string);
    # running at v = 10 m/s: a = 2 L f sqrt(q) = 20, s = (20 + sqrt(400 + 400))/2 = 10(1+√2),
    # T = 100 (3 + 2√2) = 582.84 N; check: (T − q v²)/sqrt(T q) = 482.84/24.142 = 20 = 2 L f.
    assert string_tension(20.0, 0.5, 1.0) == pytest.approx(400.0, rel=1e-14)
    assert string_tension(20.0, 0.5, 1.0, 1, 10.0) == pytest.approx(100 * (3 + 2 * math.sqrt(2)),
                                                                   rel=1e-14)
    # mode n: T = 4 L² f² q / n²
    assert string_tension(40.0, 0.5, 1.0, 2) == pytest.approx(400.0, rel=1e-14)


def test_the_moving_string_tends_to_the_taut_string_as_the_speed_vanishes() -> None:
    taut = 4 * 0.9 ** 2 * 11.0 ** 2 * 3.1
    previous = math.inf
    for v in (1.0, 0.1, 0.01, 0.001):
        gap = string_tension(11.0, 0.9, 3.1, 1, v) - taut
        assert 0 < gap < previous  # above the taut string's, shrinking towards it
        previous = gap
    # first order: s = sqrt(T) ≈ a + q v²/a, so T − T₀ ≈ 2 q v² for q v² ≪ T (one q v² is
    # the centrifugal part, the other the (1 − v²/c²) of the travelling wave)
    assert previous == pytest.approx(2 * 3.1 * 1e-6, rel=1e-3)


def test_the_uncertainty_of_a_stationary_span_is_the_closed_form_of_t_proportional_l2_f2_q() -> None:
    f, L, q = 23.4, 0.75, 2.6
    uf, uL, uq = 0.1, 0.002, 0.05 * 2.6
    est = span_tension_from_frequency(f, L, q, frequency_std=uf, length_std=uL, mass_std=uq)
    rel = math.sqrt((2 * uf / f) ** 2 + (2 * uL / L) ** 2 + (uq / q) ** 2)
    assert est.tension == pytest.approx(4 * L ** 2 * f ** 2 * q, rel=1e-14)
    assert est.std == pytest.approx(rel * est.tension, rel=1e-6)
    assert est.contributions["length"] == pytest.approx(2 * uL / L * est.tension, rel=1e-6)


def test_irvine_ratio_meets_its_closed_forms() -> None:
    # λ² = 4π²: ω̄ = 2π exactly (tan π = 0 = π − π³/π²); λ² → ∞: tan x = x, x = 4.493409457909
    assert symmetric_inplane_ratio(4 * math.pi ** 2) == pytest.approx(2.0, rel=1e-12)
    assert symmetric_inplane_ratio(1e15) == pytest.approx(2 * 4.493409457909064 / math.pi,
                                                          rel=1e-9)
    assert symmetric_inplane_ratio(0.0) == 1.0
    assert 1.0 < symmetric_inplane_ratio(0.1) < 1.01


def test_irvine_parameter_by_hand() -> None:
    # q g L / T = 2.6·9.80665·0.5/100 = 0.12749, d/L = that/8, L_e = L(1 + 8 (d/L)²),
    # λ² = 0.12749² · L · EA / (T L_e)
    r = 2.6 * 9.80665 * 0.5 / 100.0
    expected = r ** 2 * 0.5 * 1e6 / (100.0 * 0.5 * (1 + 8 * (r / 8) ** 2))
    assert irvine_parameter(100.0, 0.5, 2.6, 1e6) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"frequency": 0.0}, "frequency"), ({"frequency": -3.0}, "frequency"),
    ({"length": 0.0}, "length"), ({"mass_per_length": math.nan}, "mass_per_length"),
    ({"mode": 0}, "mode"), ({"speed": -1.0}, "speed")])
def test_bad_inputs_are_refused_by_name(kwargs: dict[str, float], field: str) -> None:
    args: dict[str, float] = {"frequency": 10.0, "length": 0.5, "mass_per_length": 1.0,
                              "mode": 1, "speed": 0.0}
    args.update(kwargs)
    with pytest.raises(DesignError) as err:
        string_tension(args["frequency"], args["length"], args["mass_per_length"],
                       int(args["mode"]), args["speed"])
    assert err.value.field == field


@pytest.mark.parametrize("psi", [0.0, 0.3, -0.7])
def test_the_sag_for_a_pretension_inverts_the_design_law(psi: float) -> None:
    # F₀ = k_f q g a with k_f = cos ψ/(8s) + |sin ψ| (chaindrive.strength.loads.sag_tension)
    from chaindrive.identification.reading import sag_for_pretension
    from chaindrive.strength.loads import sag_tension

    f0 = sag_tension(2.6, 0.68, psi, 0.017)
    assert sag_for_pretension(f0, 0.68, 2.6, psi) == pytest.approx(0.017, rel=1e-12)
    with pytest.raises(DesignError, match="no sag gives it"):
        sag_for_pretension(0.5 * 2.6 * 9.80665 * 0.68 * abs(math.sin(psi)), 0.68, 2.6, psi)


def test_a_stationary_reading_calibrates_the_installed_sag() -> None:
    # the frequency the design expects at its own pretension gives back its sag (2 %); a
    # calibrated design expects exactly the frequency read
    import chaindrive
    from chaindrive.identification import calibrated_sag, span_tension_reading
    from tests.conftest import EXAMPLES

    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    analysis = chaindrive.analyze(drive, response=False)
    f_design = span_tension_reading(analysis, "S2-S3", 5.0).expected_standing
    same = calibrated_sag(drive, span_tension_reading(analysis, "S2-S3", f_design))
    assert same.sag == pytest.approx(0.02, rel=1e-9) and same.changes == []
    cal = calibrated_sag(drive, span_tension_reading(analysis, "S2-S3", 5.1))
    lo, hi = cal.interval
    assert 0.02 < lo < cal.sag < hi  # 5.1 Hz is below the design's 6.70 Hz: a lower tension
    again = span_tension_reading(chaindrive.analyze(cal.drive, response=False), "S2-S3", 5.1)
    assert again.expected_standing == pytest.approx(5.1, rel=1e-9)
    with pytest.raises(DesignError, match="stationary span"):
        calibrated_sag(drive, span_tension_reading(analysis, "S2-S3", 9.0, running=True))
    with pytest.raises(DesignError, match=r"chain.sag: .* allowed: 0.001 to 0.1"):
        calibrated_sag(drive, span_tension_reading(analysis, "S2-S3", 1.0))


@pytest.mark.parametrize("span", ["S1-S2", "S2-S3", "S3-S1"])
def test_the_calibrated_design_carries_the_tension_read_whichever_span_is_measured(
        span: str) -> None:
    # At rest every span carries the pretension F₀, the sag tension of the slack span
    # (S1-S2, the span leaving the driver) at the design's sag [ChainDesignRU, §8]: the
    # reading's design pretension is the analysis's F₀ for every span, and the design
    # calibrated to a tension read on any span has that tension as its own F₀ (the static
    # loads' sag tension and the tension the dynamics start from).
    import chaindrive
    from chaindrive.identification import calibrated_sag, span_tension_reading
    from chaindrive.strength.loads import installed_pretension
    from tests.conftest import EXAMPLES

    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    analysis = chaindrive.analyze(drive, response=False)
    assert analysis.strength is not None
    f0 = analysis.strength.loads.sag_tension
    reading = span_tension_reading(analysis, span, 6.0)
    assert reading.pretension == pytest.approx(f0, rel=1e-12)
    cal = calibrated_sag(drive, reading)
    assert cal.span == "S1-S2"
    after = chaindrive.analyze(cal.drive, response=False)
    assert after.strength is not None
    assert after.strength.loads.sag_tension == pytest.approx(reading.estimate.tension, rel=1e-9)
    assert installed_pretension(cal.drive, after.geometry) == pytest.approx(
        reading.estimate.tension, rel=1e-9)
