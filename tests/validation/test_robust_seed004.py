"""The robust sampler against [Lyashuk]'s analytic distribution of the contour length
difference and its contour factor K_m (seed 004, eq. 7, 11–18: closed forms).

Each keyed joint's clearance z ~ Normal(z_max/2, z_max/6) (eq. 7); the length difference of
two contours ΔL₃ = C₄·[(z₁,II + z₂,II) − (z₁,I + z₂,I)] is Normal(0, (2C₄σ_z)²) (eq. 13) and
|ΔL₃| half-normal (eq. 14); K_m at the 5 % risk is eq. 16 at the 95 % quantile of |ΔL₃|
(eq. 17–18). The sampler — scrambled Sobol points through the uncertainty model's inverse
CDFs — must reproduce them.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.special import ndtr

import chaindrive
from chaindrive.multicontour import (
    contour_factor_at_risk,
    contour_factor_km,
    length_difference_stats,
)
from chaindrive.multicontour.drive import most_loaded_share
from chaindrive.robust import (
    PerturbedAnalysis,
    UncertaintySettings,
    nominal_analysis,
    uncertainty_model,
)
from chaindrive.robust.sampling import sobol_points
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def two_contours() -> tuple[object, object]:
    drive = chaindrive.load(EXAMPLES / "eight_sprocket.toml")
    nominal = nominal_analysis(replace(drive, chain=replace(drive.chain, contours=2)))
    model = uncertainty_model(nominal, UncertaintySettings(samples=4096, replicates=4, seed=4))
    return nominal, model


def _length_differences(nominal, model) -> tuple[np.ndarray, np.ndarray]:
    u = sobol_points(model.dimension, model.settings.samples, model.settings.replicates,
                     model.settings.seed).reshape(-1, model.dimension)
    x = model.values(u)
    cols = [k for k, v in enumerate(model.variables) if v.group == "key clearances"]
    z = x[:, cols]                       # (contour I driving, driven, contour II driving, driven)
    c4 = nominal.contours.c4
    return c4 * ((z[:, 2] + z[:, 3]) - (z[:, 0] + z[:, 1])), z


def test_clearances_are_the_seeds_normal(two_contours) -> None:
    nominal, model = two_contours
    _, z = _length_differences(nominal, model)
    z_max = nominal.contours.joint.max_clearance
    assert z.mean() == pytest.approx(z_max / 2, rel=2e-3)          # z̄ = z_max/2
    assert z.std() == pytest.approx(z_max / 6, rel=1e-2)           # σ_z = z_max/6


def test_sampler_reproduces_the_half_normal_of_eq14(two_contours) -> None:
    nominal, model = two_contours
    d, _ = _length_differences(nominal, model)
    stats = length_difference_stats(nominal.contours.c4, nominal.contours.joint.max_clearance)
    assert d.std() == pytest.approx(stats.sigma, rel=1e-2)           # eq. 13
    assert np.abs(d).mean() == pytest.approx(stats.mean_abs, rel=1e-2)   # eq. 14
    assert np.abs(d).var() == pytest.approx(stats.variance_abs, rel=3e-2)
    # the whole distribution: Kolmogorov distance to the half-normal CDF 2Φ(x/σ) − 1
    x = np.sort(np.abs(d))
    cdf = 2 * ndtr(x / stats.sigma) - 1
    ecdf = np.arange(1, x.size + 1) / x.size
    assert np.max(np.abs(ecdf - cdf)) < 0.01
    assert np.quantile(np.abs(d), 0.95) == pytest.approx(stats.quantile_95_abs, rel=1e-2)


def test_sampler_reproduces_km_at_the_5_percent_risk(two_contours) -> None:
    nominal, model = two_contours
    d, _ = _length_differences(nominal, model)
    c = nominal.contours
    km_samples = contour_factor_km(d, c.span_deformation)            # eq. 16 per state
    km_analytic = contour_factor_at_risk(c.c4, c.joint.max_clearance, c.span_deformation, 0.05)
    # risk 5 %: K_m is lower with probability 5 % (eq. 17–18)
    assert np.quantile(km_samples, 0.05) == pytest.approx(km_analytic, rel=2e-3)
    assert np.mean(km_samples < km_analytic) == pytest.approx(0.05, abs=0.005)


def test_a_state_takes_its_clearances_into_the_load_sharing(two_contours) -> None:
    nominal, model = two_contours
    x = model.values(np.full((1, model.dimension), 0.5))[0]
    cols = [k for k, v in enumerate(model.variables) if v.group == "key clearances"]
    x[cols] = np.array([0.0, 0.0, 1.0, 1.0]) * nominal.contours.joint.max_clearance
    state = PerturbedAnalysis(nominal, model.perturbation(x), response=False)
    c = nominal.contours
    slacks = c.c4 * np.array([0.0, 2.0 * c.joint.max_clearance])
    assert state.contours.km == pytest.approx(
        1.0 / float(most_loaded_share(slacks, 2 * c.span_deformation)))
    assert state.contours.km < c.km_mean
