"""The fit of a damping input to a tap test's decay on the link-level model's readings
(:func:`chaindrive.identification.linklevel_damping.fit_decay_curve`), against closed forms:
on a reading linear in ln x the test-inverted 95 % interval is x̂ exp(± 1.96 u/b), b the
slope dζ/d ln x — the first-order propagation of u through the slope [JCGM100, §5.1]."""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np
import pytest

from chaindrive.errors import DesignError
from chaindrive.identification import MeasuredDamping
from chaindrive.identification.linklevel_damping import DecayCurve, fit_decay_curve

GRID = np.geomspace(0.02, 0.4, 13)


def _curve(ratios: np.ndarray, initial: float = 0.1) -> DecayCurve:
    return DecayCurve("hinge_friction", initial, GRID, ratios, np.full(GRID.size, 1e-3), ())


@pytest.mark.parametrize(("truth", "u"), [(0.06, 4e-4), (0.15, 1e-3), (0.03, 2e-4)])
def test_a_reading_linear_in_ln_x_gives_the_propagated_interval(truth: float, u: float
                                                                 ) -> None:
    a, b = 0.03, 0.006  # ζ_m = a + b ln x, exactly linear between the grid's points
    fit = fit_decay_curve(_curve(a + b * np.log(GRID)),
                          MeasuredDamping(1, a + b * math.log(truth), u))
    assert fit.value == pytest.approx(truth, rel=1e-9)
    half = NormalDist().inv_cdf(0.975) * u / b  # the two-sided 95 % normal quantile
    assert fit.interval[0] == pytest.approx(truth * math.exp(-half), rel=1e-9)
    assert fit.interval[1] == pytest.approx(truth * math.exp(half), rel=1e-9)
    assert fit.identified
    # d ln ζ/d ln x at x̂: b/ζ_m, the secant of the grid interval holding x̂ (ζ_m is linear
    # in ln x, so ln ζ_m is not: within the interval's ends)
    lo = (a + b * np.log(GRID))
    assert min(b / lo) <= fit.log_slope <= max(b / lo)


def test_a_flat_reading_leaves_the_interval_open_on_both_sides() -> None:
    fit = fit_decay_curve(_curve(np.full(GRID.size, 0.021)), MeasuredDamping(1, 0.0205, 0.0014))
    assert fit.interval == pytest.approx((GRID[0], GRID[-1]))
    assert fit.open_below and fit.open_above and not fit.identified
    assert fit.value == pytest.approx(GRID[0])  # no crossing: the grid's best point (the first)


def test_a_reading_that_levels_off_bounds_one_side_only() -> None:
    # ζ_m rises to 0.021 at a grid point x_k and stays there (the hinge friction's knee,
    # docs/identification.md §4)
    knee = float(GRID[7])
    z = np.minimum(0.021, 0.021 + 0.01 * np.log(GRID / knee))
    fit = fit_decay_curve(_curve(z), MeasuredDamping(1, 0.0205, 0.001))
    assert fit.open_above and not fit.open_below
    low = 0.0205 - NormalDist().inv_cdf(0.975) * 1e-3  # the reading less its 95 % half-width
    assert fit.interval[0] == pytest.approx(knee * math.exp((low - 0.021) / 0.01), rel=1e-9)
    assert fit.value == pytest.approx(knee * math.exp(-0.05), rel=1e-9)


def test_unread_runs_are_left_out_and_counted() -> None:
    a, b = 0.03, 0.006
    z = a + b * np.log(GRID)
    z[4] = np.nan
    fit = fit_decay_curve(_curve(z), MeasuredDamping(1, a + b * math.log(0.15), 1e-3))
    assert fit.curve.unread == 1
    assert fit.value == pytest.approx(0.15, rel=1e-9)
    assert fit.to_dict()["grid_decay_ratios"][4] is None


def test_a_decay_the_model_cannot_give_is_refused() -> None:
    with pytest.raises(DesignError, match="allowed: a decay the model can give"):
        fit_decay_curve(_curve(np.full(GRID.size, 0.01)), MeasuredDamping(1, 0.05, 0.001))
    with pytest.raises(DesignError, match="uncertainty 0.0; allowed: above 0"):
        fit_decay_curve(_curve(np.full(GRID.size, 0.01)), MeasuredDamping(1, 0.01, 0.0))
