"""The chain damping ratio calibrated to measured modal damping ratios, and the two
estimators of a mode's damping ratio against their closed forms.

Closed forms of a single-degree-of-freedom system [Inman2014, ch. 1–2]; [Ewins2000, ch. 4]:
a free decay e^{−ζωt} cos(ω_d t) has maxima one damped period apart in the ratio e^{−δ},
δ = 2πζ/sqrt(1 − ζ²); the power |H(r)|² = 1/((1 − r²)² + (2ζr)²), r = f/f_n, peaks at
r_p² = 1 − 2ζ² and falls to half at r² = 1 − 2ζ² ∓ 2ζ sqrt(1 − ζ²)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import DesignError
from chaindrive.identification.calibration import elastic_frequencies
from chaindrive.identification.damping import (
    MeasuredDamping,
    calibrate_damping_ratio,
    elastic_damping_ratios,
    free_decay_damping_ratio,
    half_power_damping_ratio,
    log_decrement_damping_ratio,
    with_damping_ratio,
)
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def drive() -> chaindrive.Drive:
    return chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")


@pytest.mark.parametrize("zeta", [0.005, 0.02, 0.08])
def test_half_power_bandwidth_against_the_single_degree_of_freedom_closed_form(
        zeta: float) -> None:
    fn = 50.0
    f = np.linspace(0.5 * fn, 1.5 * fn, 400_001)
    r = f / fn
    power = 1.0 / ((1 - r ** 2) ** 2 + (2 * zeta * r) ** 2)
    lo = math.sqrt(1 - 2 * zeta ** 2 - 2 * zeta * math.sqrt(1 - zeta ** 2))
    hi = math.sqrt(1 - 2 * zeta ** 2 + 2 * zeta * math.sqrt(1 - zeta ** 2))
    exact = (hi - lo) / (2 * math.sqrt(1 - 2 * zeta ** 2))
    estimate = half_power_damping_ratio(f, power, fn)
    assert estimate == pytest.approx(exact, rel=1e-4)
    # and the estimator is ζ to first order: its error is below ζ² (below ζ relative)
    assert estimate == pytest.approx(zeta, rel=zeta)


def test_half_power_refuses_an_unresolved_peak() -> None:
    f = np.linspace(0.0, 10.0, 11)
    with pytest.raises(DesignError, match="does not fall to half on both sides"):
        half_power_damping_ratio(f, np.linspace(1.0, 2.0, 11), 10.0)


@pytest.mark.parametrize("zeta", [0.01, 0.05, 0.3])
def test_log_decrement_against_its_closed_form(zeta: float) -> None:
    delta = 2 * math.pi * zeta / math.sqrt(1 - zeta ** 2)
    ratio, std = log_decrement_damping_ratio(np.exp(-delta * np.arange(8)))
    assert ratio == pytest.approx(zeta, rel=1e-12)
    assert std < 1e-12


def test_free_decay_of_a_sampled_single_degree_of_freedom_system() -> None:
    zeta, fn, fs = 0.02, 40.0, 20_000.0
    wd = 2 * math.pi * fn * math.sqrt(1 - zeta ** 2)
    t = np.arange(0.0, 1.0, 1.0 / fs)
    x = np.exp(-zeta * 2 * math.pi * fn * t) * np.cos(wd * t)
    ratio, _std = free_decay_damping_ratio(x, fs, wd / (2 * math.pi), floor=0.05)
    assert ratio == pytest.approx(zeta, rel=1e-3)


def test_bad_decays_are_refused() -> None:
    with pytest.raises(DesignError, match="2 maxima; allowed: 3 or more"):
        log_decrement_damping_ratio([1.0, 0.5])
    with pytest.raises(DesignError, match="allowed: a decay"):
        log_decrement_damping_ratio([1.0, 1.1, 1.2])


def _free_decay(f_d: float, zeta: float, fs: float, noise: float,
                rng: np.random.Generator) -> np.ndarray:
    t = np.arange(0.0, 0.5, 1.0 / fs)
    wn = 2 * math.pi * f_d / math.sqrt(1 - zeta ** 2)
    return (np.exp(-zeta * wn * t) * np.cos(2 * math.pi * f_d * t)
            + noise * rng.standard_normal(t.size))


def test_a_known_damping_ratio_is_recovered_within_its_interval(
        drive: chaindrive.Drive) -> None:
    # free decays of the first two elastic modes of the seed drive's model at a known chain
    # damping ratio (each mode's frequency and modal ratio from the package), 0.2 % noise
    true = 0.03
    designed = with_damping_ratio(drive, true)
    f = elastic_frequencies(designed)[:2]
    z = elastic_damping_ratios(designed)[:2]
    fs, noise = 20_000.0, 0.002
    rng = np.random.default_rng(5)
    measured = []
    for k in range(2):
        f_d = f[k] * math.sqrt(1 - z[k] ** 2)
        ratio, std = free_decay_damping_ratio(_free_decay(f_d, z[k], fs, noise, rng), fs,
                                              f_d, floor=20 * noise)
        measured.append(MeasuredDamping(k + 1, ratio, std))
    cal = calibrate_damping_ratio(drive, measured)
    lo, hi = cal.interval
    assert lo < true < hi
    assert cal.ratio == pytest.approx(true, rel=0.03)
    assert cal.initial is None  # the seed drive's damping comes from its materials
    for m, zm in zip(measured, cal.fitted_ratios, strict=True):
        assert abs(zm - m.ratio) < 3 * m.std * max(1.0, cal.chi2_per_dof or 1.0) ** 0.5


@dataclass(frozen=True)
class _Dynamics:
    damping_ratio: float | None


@dataclass(frozen=True)
class _Drive:
    dynamics: _Dynamics


def test_a_fit_of_a_closed_form_model() -> None:
    # modal ζ_m = c_m ζ_c: one measurement gives ζ_c = ζ_1/c_1 and σ(ln ζ_c) = u/ζ_1
    c = np.array([0.8, 2.5])
    cal = calibrate_damping_ratio(
        _Drive(_Dynamics(0.05)),  # type: ignore[arg-type]
        [MeasuredDamping(2, 0.06, 0.003)],
        ratios=lambda d: c * d.dynamics.damping_ratio)
    assert cal.ratio == pytest.approx(0.06 / 2.5, rel=1e-6)
    assert cal.std_log == pytest.approx(0.003 / 0.06, rel=1e-3)
    assert cal.initial == 0.05


def test_bad_measurements_are_refused(drive: chaindrive.Drive) -> None:
    with pytest.raises(DesignError, match="no measured damping ratio"):
        calibrate_damping_ratio(drive, [])
    with pytest.raises(DesignError, match="damping ratio 1.5; allowed: above 0 and below 1"):
        calibrate_damping_ratio(drive, [MeasuredDamping(1, 1.5, 0.1)])
    with pytest.raises(DesignError, match=r"mode 9; allowed: 1 to 2"):
        calibrate_damping_ratio(drive, [MeasuredDamping(9, 0.02, 0.001)],
                                ratios=lambda d: np.array([0.02, 0.05]))
