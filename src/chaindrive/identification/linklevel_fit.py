"""The link stiffness or the installed sag fitted to a measured natural frequency with the
link-level model as the forward model.

A tap test of a stationary drive rings at the link-level model's first mode along the chain
(:func:`chaindrive.linklevel.modes.linear_modes`: the undamped model linearised about its
static state at the pre-tension T₀ of the design's sag, every sprocket free, no motor). That
mode rests mostly on T₀ through the spans' sag and the sprockets' polygons, little on the
links' elasticity (docs/identification.md §4), so a record of it is fitted with this model,
not with the whole-drive model's modes at the running tensions.

One parameter x is fitted — ``[chain] link_stiffness`` k_link or ``[chain] sag`` s (which
sets T₀ = k_f q g a, k_f = cos ψ/(8s) + |sin ψ| [ChainDesignRU, §8]) — the other inputs held
at the design's. The least squares is that of the whole-drive calibration
(:func:`chaindrive.identification.fitting.fit_log_parameter`): θ = ln x, r_i = (f_model,i(θ) −
f_i)/u_i, ``scipy.optimize.least_squares`` [Virtanen2020], cov θ = (JᵀJ)⁻¹ × max(1, χ²/ν)
[JCGM100, §5.1], the 95 % interval exp(θ ± 1.96 σ_θ), J a secant over ±10 % of x
(:data:`LOG_STEP`; held between nearby iterates, taken at the fitted x for the covariance,
:data:`~chaindrive.identification.fitting.SECANT_REUSE`); for k_link the model's
frequency is interpolated through runs on a grid (:data:`GRID_POINTS`). With it the
sensitivity d ln f/d ln x
of each fitted frequency is reported (by Rayleigh's quotient, d ln f/d ln k = e/2, e the
share of the mode's strain energy in the links [FoxKapoor1968]); a parameter whose 95 %
interval spans more than a factor :data:`POORLY_IDENTIFIED_RATIO` is flagged as poorly
identified by the record: the interval is then a linearisation about a nearly flat model
and says no more than that the record does not fix the parameter.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from scipy.interpolate import PchipInterpolator

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ConvergenceError, DesignError
from chaindrive.identification.calibration import (
    MeasuredMode,
    check_measured_mode,
    verdict_changes,
    with_chain,
)
from chaindrive.identification.fitting import XTOL, fit_log_parameter

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.model import Drive

__all__ = ["GRID_POINTS", "LINK_STIFFNESS_RANGE", "LOG_STEP", "OTHER_STATE",
           "POORLY_IDENTIFIED_RATIO",
           "SAG_RANGE", "SAG_XTOL", "LinkLevelCalibration",
           "LinkLevelDesign", "calibrate_link_level", "calibrated_design_link_level",
           "link_level_modes_along_chain"]

#: A 95 % interval wider than this ratio (upper/lower) marks the parameter as poorly
#: identified by the record [-] (a choice: a factor 2 in k_link or s).
POORLY_IDENTIFIED_RATIO = 2.0
#: The fitted k_link is kept within these multiples of the design's [-] (the grid of
#: :data:`GRID_POINTS` spans them): where the link-level static state is found on the seed
#: drive (at 4 × the design's stiffness, 2.04e9 N/m, its pre-tension is not reached); a fit
#: ending on a bound says so.
LINK_STIFFNESS_RANGE = (0.1, 2.5)
#: The Jacobian's central-difference step in ln x [-]: a secant over ±10 % of x, a slope of
#: the model over the scale a record can resolve rather than over least_squares' own step
#: (1e-4 of ln x), which reads the model's finest irregularities (:data:`GRID_POINTS`).
LOG_STEP = math.log(1.1)
#: Runs of the link-level model on a log-spaced grid of k_link over its range, through which
#: ln f is interpolated by a monotone cubic in ln k [-]. The static state the link-level
#: model finds is not the same at every k_link: at some (on the seed drive at 4.498e8 but
#: not at 4.489e8 N/m; secants about 3.4e8 and 4.1e8 N/m reached others) it settles in
#: another, with no mode along the chain below 100 Hz (the first at 120 Hz); fitted run by
#: run, a step or a secant landing there read slopes of −3 to 290 where the model's is
#: 0.007, and intervals 1 % wide that missed the truth. f moves by about 1 % per doubling of
#: k_link, smoothly between the states, so the interpolation through the grid stands for the
#: model; a fit of the sag (slope −0.3) takes single runs.
GRID_POINTS = 9
#: A grid run whose ln f lies farther than this from the grid's median is another static
#: state and left out [-] (f moves by under 5 % over the whole range of k_link).
OTHER_STATE = 0.1
#: The sag fit stops once a step moves θ = ln s by less than this times |θ| (``least_squares``'
#: ``xtol``) [-]: the model resolves the sag only to about 2e-8 of itself (its frequency
#: scatters by 3e-9 of itself about its trend in s, the static state being solved to a
#: tolerance, docs/identification.md), and at the default 1e-10 the iterations go on
#: dithering in that scatter (on the seed drive, a record at 80 Hz: 6 of 17 runs).
SAG_XTOL = 1e-8
#: The fitted sag is kept within the design file's range of ``[chain] sag`` [-].
SAG_RANGE = (0.001, 0.1)

Parameter = Literal["link_stiffness", "sag"]


@shared_parameters
def link_level_modes_along_chain(drive: Drive) -> np.ndarray[Any, np.dtype[np.float64]]:
    """The link-level model's natural frequencies of its modes along the chain [Hz], lowest
    first: those of :func:`chaindrive.linklevel.modes.linear_modes` with more than half
    their kinetic energy along the chain and in the sprockets' turning.

    %(drive_returns)s
    ndarray
        f [Hz].

    Raises
    ------
    ChainDriveError
        The link-level model refuses the design or finds no static state.
    """
    from chaindrive.linklevel.modes import LONGITUDINAL, linear_modes  # lazy: heavy

    modes = linear_modes(drive)
    return np.asarray(modes.frequencies_hz[modes.longitudinal_fraction > LONGITUDINAL],
                      dtype=float)


@dataclass(frozen=True, slots=True)
class LinkLevelCalibration:
    """One parameter fitted with the link-level model (module docstring).

    Parameters
    ----------
    parameter : str
        ``"link_stiffness"`` [N/m] or ``"sag"`` [-].
    initial : float
        The design's value [N/m] or [-].
    value : float
        Fitted [N/m] or [-].
    std_log : float
        σ of its logarithm [-].
    interval : tuple of float
        95 % interval [N/m] or [-].
    bounds : tuple of float
        The range the fit was kept within [N/m] or [-].
    measured : tuple of MeasuredMode
        The measurements (mode m: the m-th mode along the chain).
    fitted_frequencies : tuple of float
        The link-level model's frequencies of those modes at the fitted value [Hz].
    sensitivities : tuple of float
        d ln f/d ln x of each at the fitted value [-].
    chi2_per_dof : float | None
        χ²/ν [-] (None with one measurement).
    evaluations : int
        Runs of the link-level model (its static state and modes) [-].
    pretension : float
        T₀ of the fitted design [N].
    held : tuple of str
        The input held that rests on a default or an estimate (the design gives none).
    """

    parameter: str
    initial: float
    value: float
    std_log: float
    interval: tuple[float, float]
    bounds: tuple[float, float]
    measured: tuple[MeasuredMode, ...]
    fitted_frequencies: tuple[float, ...]
    sensitivities: tuple[float, ...]
    chi2_per_dof: float | None
    evaluations: int
    pretension: float
    held: tuple[str, ...] = ()

    @property
    def interval_ratio(self) -> float:
        """Upper over lower end of the 95 % interval [-]."""
        return self.interval[1] / self.interval[0]

    @property
    def poorly_identified(self) -> bool:
        """The 95 % interval spans more than :data:`POORLY_IDENTIFIED_RATIO`."""
        return self.interval_ratio > POORLY_IDENTIFIED_RATIO

    @property
    def at_bound(self) -> bool:
        """The fit ended within 0.1 % of a bound of :attr:`bounds`."""
        return (self.value <= self.bounds[0] * 1.001 or self.value >= self.bounds[1] / 1.001)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        unit = "n_per_m" if self.parameter == "link_stiffness" else "fraction"
        return {
            "model": "link-level",
            "parameter": f"chain.{self.parameter}",
            f"initial_{unit}": self.initial,
            f"fitted_{unit}": self.value,
            "std_of_log": self.std_log,
            f"interval_95_{unit}": list(self.interval),
            "interval_95_ratio": self.interval_ratio,
            "poorly_identified": self.poorly_identified,
            f"bounds_{unit}": list(self.bounds),
            "at_bound": self.at_bound,
            "residuals": [{"mode": m.mode, "measured_hz": m.frequency, "std_hz": m.std,
                           "model_hz": f, "residual_hz": f - m.frequency,
                           "log_sensitivity": s}
                          for m, f, s in zip(self.measured, self.fitted_frequencies,
                                             self.sensitivities, strict=True)],
            "chi2_per_dof": self.chi2_per_dof,
            "model_evaluations": self.evaluations,
            "fitted_pretension_n": self.pretension,
            "held_from_default": list(self.held),
        }


def _run_or_nan(drive: Drive, modes: np.ndarray[Any, np.dtype[np.int64]]
                ) -> np.ndarray[Any, np.dtype[np.float64]]:
    """The link-level frequencies of ``modes`` [Hz], NaN where no static state is found."""
    try:
        return np.asarray(link_level_modes_along_chain(drive)[modes], dtype=float)
    except ConvergenceError:
        return np.full(modes.size, np.nan)


def _stiffness_surrogate(design: Callable[[float], Drive], bounds: tuple[float, float],
                         modes: np.ndarray[Any, np.dtype[np.int64]]
                         ) -> Callable[[float], np.ndarray[Any, np.dtype[np.float64]]]:
    """The link-level frequencies as a function of k_link (:data:`GRID_POINTS`): ln f of
    each mode a monotone cubic in ln k (``scipy.interpolate.PchipInterpolator``,
    [Virtanen2020]) through the runs on a log-spaced grid over ``bounds``, those whose ln f
    lies more than :data:`OTHER_STATE` from the grid's median left out (another static
    state)."""
    grid = np.linspace(math.log(bounds[0]), math.log(bounds[1]), GRID_POINTS)
    runs = np.log(np.vstack([_run_or_nan(design(math.exp(t)), modes) for t in grid]))
    curves = []
    for j in range(runs.shape[1]):
        found = np.isfinite(runs[:, j])
        keep = found & (np.abs(runs[:, j] - np.median(runs[found, j])) <= OTHER_STATE)
        if keep.sum() < 4:
            raise ConvergenceError(
                f"the link-level model finds no static state or another at {int((~keep).sum())} "
                f"of {GRID_POINTS} link stiffnesses between {bounds[0]:.4g} and {bounds[1]:.4g} "
                "N/m; its frequency cannot be fitted")
        curves.append(PchipInterpolator(grid[keep], runs[keep, j], extrapolate=True))

    def model(x: float) -> np.ndarray[Any, np.dtype[np.float64]]:
        return np.asarray(np.exp([float(c(math.log(x))) for c in curves]), dtype=float)

    return model


def _checked(measured: Sequence[MeasuredMode]) -> None:
    """Refuse what the link-level fit cannot take (one line per error)."""
    if not measured:
        raise DesignError("--natural", "no measured natural frequency; allowed: one or more")
    for m in measured:
        if m.mode != 1:
            raise DesignError("--natural", f"mode {m.mode} with --model links; allowed: 1 (the "
                              "link-level model's first mode along the chain; the higher ones "
                              "change order with the link stiffness)")
        check_measured_mode(m)


def calibrate_link_level(drive: Drive, measured: Sequence[MeasuredMode], *,
                         parameter: Parameter = "link_stiffness") -> LinkLevelCalibration:
    """Fit k_link or the sag s to measured frequencies of the link-level model's modes along
    the chain (module docstring), the other inputs held at the design's.

    Parameters
    ----------
    drive : Drive
        The design.
    measured : sequence of MeasuredMode
        Mode 1 (the first mode along the chain), one or more readings.
    parameter : {"link_stiffness", "sag"}
        What is fitted.

    Returns
    -------
    LinkLevelCalibration

    Raises
    ------
    DesignError
        No measurement, a mode other than 1, a frequency or uncertainty not positive, an
        unknown parameter.
    ChainDriveError
        The link-level model refuses the design or finds no static state.

    References
    ----------
    [Virtanen2020]; [JCGM100, §5.1]; [FoxKapoor1968].
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    _checked(measured)
    return _calibrated(drive, measured, parameter, analyze(drive, response=False))


def _calibrated(drive: Drive, measured: Sequence[MeasuredMode], parameter: Parameter,
                analysis: Analysis) -> LinkLevelCalibration:
    """:func:`calibrate_link_level` with the design's analysis (``response=False``) given:
    k_link read from it."""
    # lazy: the link-level model loads numba's kernels
    from chaindrive.geometry.contour import contour_geometry
    from chaindrive.linklevel.equilibrium import installed_geometry
    from chaindrive.linklevel.model import build_model
    from chaindrive.strength.loads import installed_sag_ratio

    f = np.array([m.frequency for m in measured])
    u = np.array([m.std for m in measured])
    modes = np.array([m.mode for m in measured]) - 1
    k0 = analysis.ring_parameters.link_stiffness_n_per_m
    if parameter == "link_stiffness":
        x0 = k0
        held = (() if drive.chain.sag is not None else
                (f"the installed sag {100 * installed_sag_ratio(drive):g} % (the default; "
                 "the design gives none)",))
        bounds = (LINK_STIFFNESS_RANGE[0] * x0, LINK_STIFFNESS_RANGE[1] * x0)
    elif parameter == "sag":
        x0 = installed_sag_ratio(drive)
        bounds = SAG_RANGE
        held = (() if drive.chain.link_stiffness is not None else
                (f"the link stiffness {k0:.4g} N/m (computed from its plates and pins; the design "
                 "gives none)",))
    else:
        raise DesignError("--parameter", f"{parameter!r}; allowed: link_stiffness, sag")

    def design(x: float) -> Drive:
        return with_chain(drive, **{parameter: x})

    # the design as given: refused here, not mid-fit; for the sag, with its sag (the one it
    # states or the default it takes) written out, the run the fit starts from
    start = link_level_modes_along_chain(design(x0) if parameter == "sag" else drive)

    def runs(x: float) -> np.ndarray[Any, np.dtype[np.float64]]:
        found = start if x == x0 else link_level_modes_along_chain(design(x))
        return np.asarray(found[modes], dtype=float)

    model = runs if parameter == "sag" else _stiffness_surrogate(design, bounds, modes)

    fit = fit_log_parameter(model, f, u, x0, lower=bounds[0], upper=bounds[1],
                            log_step=LOG_STEP,
                            xtol=SAG_XTOL if parameter == "sag" else XTOL)
    fitted = design(fit.value)
    geometry, _ = installed_geometry(fitted, contour_geometry(fitted))
    pretension = float(build_model(fitted, geometry).pretension)
    return LinkLevelCalibration(parameter, float(x0), fit.value, fit.std_log, fit.interval,
                                (float(bounds[0]), float(bounds[1])), tuple(measured),
                                fit.fitted, fit.log_slopes, fit.chi2_per_dof,
                                fit.evaluations if parameter == "sag" else GRID_POINTS,
                                pretension, held)


@dataclass(frozen=True, slots=True)
class LinkLevelDesign:
    """A design calibrated with the link-level model and what its checks say after.

    Parameters
    ----------
    calibration : LinkLevelCalibration
        The fit.
    drive : Drive
        The design with the fitted parameter.
    changes : list of dict
        Checks whose verdict changed (:func:`~chaindrive.identification.calibration.verdict_changes`).
    """

    calibration: LinkLevelCalibration
    drive: Drive
    changes: list[dict[str, Any]]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: the fit's keys and ``verdicts_changed``."""
        return {**self.calibration.to_dict(), "verdicts_changed": self.changes}


def calibrated_design_link_level(drive: Drive, measured: Sequence[MeasuredMode], *,
                                 parameter: Parameter = "link_stiffness") -> LinkLevelDesign:
    """Fit k_link or the sag with the link-level model (:func:`calibrate_link_level`) and
    re-run the design's checks with the fitted value.

    Parameters
    ----------
    drive : Drive
        The design.
    measured : sequence of MeasuredMode
        Mode 1 (the first mode along the chain).
    parameter : {"link_stiffness", "sag"}
        What is fitted.

    Returns
    -------
    LinkLevelDesign
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    _checked(measured)
    analysis = analyze(drive, response=False)  # the design's: its k_link and its checks
    cal = _calibrated(drive, measured, parameter, analysis)
    fitted = with_chain(drive, **{parameter: cal.value})
    before = analysis.checks()
    after = analyze(fitted, response=False).checks()
    return LinkLevelDesign(cal, fitted, verdict_changes(before, after))
