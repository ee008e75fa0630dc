"""Positive model parameters fitted to measurements by weighted least squares in their
logarithms, with their covariance and 95 % intervals.

With θ = ln x and measurements y_i of standard uncertainty u_i, the weighted residuals
r_i(θ) = (y_model,i(e^θ) − y_i)/u_i are minimised by ``scipy.optimize.least_squares``
([Virtanen2020]; trust-region reflective). The covariance of θ is (JᵀJ)⁻¹ at the optimum,
J = ∂r/∂θ [JCGM100, §5.1], multiplied by χ²/ν when that exceeds 1 (the measurements scatter
more than their stated uncertainties allow; never narrowed below them); each 95 % interval
is exp(θ_j ± 1.96 σ_j) (normal approximation, marginal).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from chaindrive.errors import DesignError

__all__ = ["SECANT_REUSE", "XTOL", "Z95", "LogFit", "fit_log_parameter", "fit_log_parameters",
           "model_mode_indices"]

#: Two-sided 95 % point of the normal distribution [-].
Z95 = 1.959963984540054
#: With a secant Jacobian (``log_step`` h), the secant is held while θ stays within this
#: fraction of h of where it was taken [-] (the chord method, [Kelley1995, §5.4]): moving
#: its centre by 0.1 h moves the secant by about as much as the secant itself differs from
#: the derivative, so the iterations converge as fast, to the same optimum; the covariance
#: and the slopes read the secant taken at the optimum. On the link-level sag fit of the
#: seed drive this halves the model's runs (a record at 78.3 Hz: 28 to 12).
SECANT_REUSE = 0.1
#: ``least_squares``' ``xtol`` by default [-]: it stops once a step moves θ by less than
#: xtol·(xtol + ‖θ‖).
XTOL = 1e-10


@dataclass(frozen=True, slots=True)
class LogFit:
    """One positive parameter x fitted by weighted least squares in θ = ln x.

    Parameters
    ----------
    value : float
        Fitted x [the parameter's unit].
    std_log : float
        σ of ln x [-].
    interval : tuple of float
        95 % interval exp(θ ± 1.96 σ_θ) [the parameter's unit].
    fitted : tuple of float
        The model's values at the fitted x [the measurements' unit].
    chi2_per_dof : float | None
        χ²/ν of the weighted residuals [-] (None with as many measurements as parameters).
    evaluations : int
        Model evaluations [-].
    correlation : tuple of float
        Correlation of ln x with each fitted parameter's logarithm [-] (itself: 1).
    log_slopes : tuple of float
        d ln y_model,i / d ln x of each model value at the fit [-] (J_i u_i / y_model,i, from
        the fit's own finite-difference Jacobian): how strongly each measurement depends on
        x.
    """

    value: float
    std_log: float
    interval: tuple[float, float]
    fitted: tuple[float, ...]
    chi2_per_dof: float | None
    evaluations: int
    correlation: tuple[float, ...] = (1.0,)
    log_slopes: tuple[float, ...] = ()


def fit_log_parameters(model: Callable[[np.ndarray[Any, np.dtype[np.float64]]],
                                      np.ndarray[Any, np.dtype[np.float64]]],
                       measured: np.ndarray[Any, np.dtype[np.float64]],
                       std: np.ndarray[Any, np.dtype[np.float64]], initial: Sequence[float], *,
                       upper: Sequence[float] | None = None,
                       lower: Sequence[float] | None = None,
                       log_step: float | None = None, xtol: float = XTOL
                       ) -> tuple[LogFit, ...]:
    """Fit positive parameters x so a model's values match measured ones (module
    docstring): θ = ln x, r_i(θ) = (y_model,i(e^θ) − y_i)/u_i minimised by
    ``scipy.optimize.least_squares`` ([Virtanen2020]), cov θ = (JᵀJ)⁻¹ × max(1, χ²/ν)
    [JCGM100, §5.1], each 95 % interval exp(θ_j ± 1.96 σ_j) (marginal).

    Parameters
    ----------
    model : callable
        x (ndarray) → the model's values y_model (same order as ``measured``).
    measured : ndarray
        y_i [the measurements' unit].
    std : ndarray
        u_i, positive [the measurements' unit].
    initial : sequence of float
        x at the start, positive [the parameter's unit].
    upper : sequence of float | None
        Each x is kept below its bound (None: unbounded) [the parameter's unit].
    lower : sequence of float | None
        Each x is kept above its bound (None: unbounded), positive [the parameter's unit].
    log_step : float | None
        The Jacobian by central differences θ ± h with this h [-] (a secant over x·e^±h,
        for a model whose values are not smooth on the scale of ``least_squares``' own
        steps), held between iterates closer than :data:`SECANT_REUSE`·h and taken afresh
        at the optimum for the covariance; None: ``least_squares``' forward differences
        (relative step 1e-4).
    xtol : float
        ``least_squares``' ``xtol`` [-] (:data:`XTOL`; larger for a model that resolves θ
        no finer).

    Returns
    -------
    tuple of LogFit
        One per parameter (the same ``fitted``, ``chi2_per_dof`` and ``evaluations``), with
        the correlation of the estimates in :attr:`LogFit.correlation`.

    References
    ----------
    [Virtanen2020]; [JCGM100, §5.1].
    """
    count = [0]
    n = len(initial)
    # the model's values at each θ it was run at: least_squares may ask again for a θ it has
    # (and the values at the θ it ends on are read after), the model is run once per θ
    runs: dict[bytes, np.ndarray[Any, np.dtype[np.float64]]] = {}

    def model_at(theta: np.ndarray[Any, np.dtype[np.float64]]
                 ) -> np.ndarray[Any, np.dtype[np.float64]]:
        key = np.asarray(theta, dtype=float).tobytes()
        if key not in runs:
            runs[key] = np.array(model(np.exp(theta)), dtype=float)
        return runs[key].copy()

    def residuals(theta: np.ndarray[Any, np.dtype[np.float64]]
                  ) -> np.ndarray[Any, np.dtype[np.float64]]:
        count[0] += 1
        return np.asarray((model_at(theta) - measured) / std, dtype=float)

    hi = np.full(n, np.inf) if upper is None else np.log(np.asarray(upper, dtype=float))
    lo = np.full(n, -np.inf) if lower is None else np.log(np.asarray(lower, dtype=float))
    x0 = np.maximum(np.minimum(np.log(np.asarray(initial, dtype=float)), hi - 1e-3), lo + 1e-3)
    h = float(log_step or 0.0)

    def secant_at(theta: np.ndarray[Any, np.dtype[np.float64]]
                  ) -> np.ndarray[Any, np.dtype[np.float64]]:
        return np.column_stack([(residuals(theta + h * e) - residuals(theta - h * e)) / (2 * h)
                                for e in np.eye(n)])

    # the secant held while θ stays within SECANT_REUSE·h of where it was taken (the chord
    # method [Kelley1995, §5.4]); the covariance reads the one taken at the optimum (below)
    held: list[tuple[np.ndarray[Any, np.dtype[np.float64]],
                     np.ndarray[Any, np.dtype[np.float64]]]] = []

    def secant(theta: np.ndarray[Any, np.dtype[np.float64]]
               ) -> np.ndarray[Any, np.dtype[np.float64]]:
        theta = np.array(theta, dtype=float)
        if not held or float(np.max(np.abs(theta - held[-1][0]))) > SECANT_REUSE * h:
            held.append((theta, secant_at(theta)))
        return held[-1][1].copy()

    fit = least_squares(residuals, x0=x0, bounds=(lo, hi), method="trf",
                        jac="2-point" if log_step is None else secant,
                        diff_step=np.full(n, 1e-4), x_scale=np.ones(n), xtol=xtol,
                        ftol=1e-10)
    theta = np.asarray(fit.x, dtype=float)
    if log_step is None:
        J = np.asarray(fit.jac, dtype=float)
    else:  # the secant at the optimum (not one held from an earlier iterate)
        J = held[-1][1] if np.array_equal(held[-1][0], theta) else secant_at(theta)
    dof = measured.size - n
    chi2 = float(np.sum(fit.fun ** 2))
    # the measurements scatter more than their stated uncertainties: widen by sqrt(χ²/ν)
    cov = np.linalg.pinv(J.T @ J) * (max(1.0, chi2 / dof) if dof > 0 else 1.0)
    sigma = np.sqrt(np.maximum(np.diag(cov), 0.0))
    corr = cov / np.where(np.outer(sigma, sigma) > 0, np.outer(sigma, sigma), 1.0)
    y = model_at(theta)
    fitted = tuple(float(x) for x in y)
    slopes = J * std[:, None] / np.where(y != 0, y, 1.0)[:, None]  # d ln y_i / dθ_k
    return tuple(LogFit(math.exp(t), float(s), (math.exp(t - Z95 * s), math.exp(t + Z95 * s)),
                        fitted, chi2 / dof if dof > 0 else None, count[0],
                        tuple(float(c) for c in corr[k]),
                        tuple(float(v) for v in slopes[:, k]))
                 for k, (t, s) in enumerate(zip(theta, sigma, strict=True)))


def fit_log_parameter(model: Callable[[float], np.ndarray[Any, np.dtype[np.float64]]],
                      measured: np.ndarray[Any, np.dtype[np.float64]],
                      std: np.ndarray[Any, np.dtype[np.float64]], initial: float, *,
                      upper: float = math.inf, lower: float = 0.0,
                      log_step: float | None = None, xtol: float = XTOL) -> LogFit:
    """One positive parameter fitted by :func:`fit_log_parameters`.

    Parameters
    ----------
    model : callable
        x → the model's values y_model (same order as ``measured``).
    measured : ndarray
        y_i [the measurements' unit].
    std : ndarray
        u_i, positive [the measurements' unit].
    initial : float
        x at the start, positive [the parameter's unit].
    upper : float
        x is kept below this bound (e.g. a damping ratio below 1) [the parameter's unit].
    lower : float
        x is kept above this bound (0: unbounded) [the parameter's unit].
    log_step : float | None
        Central-difference step in ln x of the Jacobian [-] (None: ``least_squares``' own).
    xtol : float
        ``least_squares``' ``xtol`` [-] (:func:`fit_log_parameters`).

    Returns
    -------
    LogFit
    """
    return fit_log_parameters(lambda x: model(float(x[0])), measured, std, [initial],
                              upper=None if math.isinf(upper) else [upper],
                              lower=None if lower <= 0.0 else [lower], log_step=log_step,
                              xtol=xtol)[0]


def model_mode_indices(modes: Sequence[int], n_model: int, option: str
                       ) -> np.ndarray[Any, np.dtype[np.int64]]:
    """The model's indices of measured elastic modes m, counted from 1 (index m − 1).

    Parameters
    ----------
    modes : sequence of int
        The measured modes m [-].
    n_model : int
        Elastic modes the model has [-].
    option : str
        The command-line option the measurements came from (named in the error).

    Returns
    -------
    ndarray
        m − 1 of each [-].

    Raises
    ------
    DesignError
        A mode the model does not have (the first such one is named).
    """
    index = np.array(modes) - 1
    bad = [int(k) + 1 for k in index if not 0 <= k < n_model]
    if bad:
        raise DesignError(option, f"mode {bad[0]}; allowed: 1 to {n_model} (the model's "
                          "elastic modes)")
    return index
