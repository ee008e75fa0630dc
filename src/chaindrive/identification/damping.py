"""The chain's damping ratio calibrated to measured modal damping ratios, with its interval.

A mode's measured damping ratio ζ comes from a free decay (logarithmic decrement) or from
the width of its spectrum peak (half-power bandwidth) [Ewins2000, ch. 4]; [Inman2014,
ch. 1–2]:

* logarithmic decrement: successive maxima a_k one damped period apart fall as
  a_k = a_0 e^{−δk}, δ = 2πζ/sqrt(1 − ζ²), so ζ = δ/sqrt(4π² + δ²); δ is the slope of a
  straight line fitted to ln a_k (its standard error from the line's residuals);
* half-power bandwidth: the power |X(f)|² of a lightly damped peak at f_n falls to half at
  f_1 < f_n < f_2, and ζ ≈ (f_2 − f_1)/(2 f_n) (exact to first order in ζ).

The design's ``[dynamics] damping_ratio`` ζ_c sets the chain's dampers (every span and
wrap, :mod:`chaindrive.dynamics.model.damping`); the model's modal damping ratios follow
from it. ζ_c is fitted so the model's modal ratios of the measured modes match the
measured ones, by the one weighted least-squares fit of a positive parameter in its
logarithm (:func:`chaindrive.identification.fitting.fit_log_parameter`), ζ_c kept
below 1.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.signal import find_peaks
from scipy.stats import linregress

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.identification.fitting import fit_log_parameter, model_mode_indices

if TYPE_CHECKING:
    from chaindrive.model import Drive

__all__ = ["DampingCalibration", "MeasuredDamping", "calibrate_damping_ratio",
           "elastic_damping_ratios", "free_decay_damping_ratio", "half_power_damping_ratio",
           "log_decrement_damping_ratio", "with_damping_ratio"]

FloatArray = np.ndarray[Any, np.dtype[np.float64]]
#: Largest chain damping ratio the model accepts is below this [-].
ZETA_LIMIT = 0.999


@dataclass(frozen=True, slots=True)
class MeasuredDamping:
    """A measured damping ratio of an elastic mode.

    Parameters
    ----------
    mode : int
        Elastic mode m [-], counted from 1.
    ratio : float
        ζ [-].
    std : float
        Its standard uncertainty u [-], positive.
    """

    mode: int
    ratio: float
    std: float


def log_decrement_damping_ratio(maxima: Sequence[float]) -> tuple[float, float]:
    """ζ and its standard uncertainty from successive maxima of a free decay one damped
    period apart: ln a_k = c − δ k fitted by a straight line, ζ = δ/sqrt(4π² + δ²),
    u(ζ) = 4π²/(4π² + δ²)^{3/2} · u(δ) [Inman2014, ch. 1]; [JCGM100, §5.1].

    Parameters
    ----------
    maxima : sequence of float
        a_0, a_1, … [any unit], positive, at least 3.

    Returns
    -------
    ratio : float
        ζ [-].
    std : float
        u(ζ) [-] (from the scatter of ln a_k about the line).

    Raises
    ------
    DesignError
        Fewer than 3 maxima, a maximum not positive, or maxima that do not decay.
    """
    a = np.asarray(maxima, dtype=float)
    if a.size < 3:
        raise DesignError("decay", f"{a.size} maxima; allowed: 3 or more")
    if not np.all(np.isfinite(a) & (a > 0)):
        raise DesignError("decay", "a maximum that is not positive; allowed: above 0")
    line = linregress(np.arange(a.size, dtype=float), np.log(a))
    delta = -float(line.slope)
    if delta <= 0:
        raise DesignError("decay", f"logarithmic decrement {delta:.4g}; allowed: a decay "
                          "(above 0)")
    s = 4.0 * math.pi ** 2 + delta ** 2
    return delta / math.sqrt(s), 4.0 * math.pi ** 2 / s ** 1.5 * float(line.stderr)


def free_decay_damping_ratio(signal: FloatArray, sample_rate: float, frequency: float, *,
                             floor: float) -> tuple[float, float]:
    """ζ and u(ζ) of a free decay of one mode: its maxima (``scipy.signal.find_peaks``,
    [Virtanen2020]) at least 0.7 of a period apart, each refined as the vertex of a
    parabola fitted by least squares to the samples within ± 1/8 of a period of it (a fit
    linear in the samples, so zero-mean noise does not bias the maxima upwards as the
    largest noisy sample would), those above ``floor``, by
    :func:`log_decrement_damping_ratio`.

    Parameters
    ----------
    signal : ndarray
        The decaying record [any unit].
    sample_rate : float
        [Hz].
    frequency : float
        The mode's damped frequency f_d [Hz].
    floor : float
        Maxima below this (the noise) are not used [signal's unit].

    Returns
    -------
    ratio, std : float
        ζ and u(ζ) [-].
    """
    period = sample_rate / frequency
    idx, _ = find_peaks(signal, distance=max(1, int(0.7 * period)))
    w = max(1, int(period / 8))
    maxima = []
    for i in idx:
        if i - w < 0 or i + w >= signal.size:
            continue
        k = np.arange(-w, w + 1, dtype=float)
        c2, c1, c0 = np.polyfit(k, signal[i - w:i + w + 1], 2)
        top = float(c0 - c1 ** 2 / (4 * c2)) if c2 < 0 else float(signal[i])
        if top < floor:
            break
        maxima.append(top)
    return log_decrement_damping_ratio(maxima)


def half_power_damping_ratio(frequencies: FloatArray, power: FloatArray,
                             peak: float) -> float:
    """ζ ≈ (f_2 − f_1)/(2 f_n) of a spectrum peak from its half-power points [Ewins2000,
    ch. 4], f_1 and f_2 where the power falls to half the peak's (linear interpolation
    between samples), f_n the frequency of the largest power sample near ``peak``.

    Parameters
    ----------
    frequencies : ndarray
        f [Hz], increasing.
    power : ndarray
        |X(f)|² (a power spectrum, not dB) [any unit].
    peak : float
        The peak's frequency [Hz] (the nearest sample is taken as its top).

    Returns
    -------
    float
        ζ [-].

    Raises
    ------
    DesignError
        The power does not fall to half on both sides of the peak within the spectrum.
    """
    k = int(np.argmin(np.abs(frequencies - peak)))
    while 0 < k < power.size - 1 and (power[k - 1] > power[k] or power[k + 1] > power[k]):
        k += 1 if power[k + 1] > power[k] else -1
    half = 0.5 * power[k]
    lo = k
    while lo > 0 and power[lo] > half:
        lo -= 1
    hi = k
    while hi < power.size - 1 and power[hi] > half:
        hi += 1
    if power[lo] > half or power[hi] > half:
        raise DesignError("half-power", f"peak at {peak:.4g} Hz: the power does not fall to "
                          "half on both sides; allowed: a peak resolved by several bins")

    def cross(i: int, j: int) -> float:
        return float(frequencies[i] + (half - power[i]) * (frequencies[j] - frequencies[i])
                     / (power[j] - power[i]))

    return (cross(hi - 1, hi) - cross(lo, lo + 1)) / (2.0 * float(frequencies[k]))


def with_damping_ratio(drive: Drive, ratio: float) -> Drive:
    """The design with ``[dynamics] damping_ratio`` set to ζ [-].

    Parameters
    ----------
    drive : Drive
        The design.
    ratio : float
        ζ [-], from 0 to below 1.

    Returns
    -------
    Drive
    """
    return dataclasses.replace(drive, dynamics=dataclasses.replace(drive.dynamics,
                                                                   damping_ratio=ratio))


@shared_parameters
def elastic_damping_ratios(drive: Drive) -> FloatArray:
    """The modal damping ratios [-] of the elastic modes of a drive's whole-drive model,
    lowest frequency first.

    Only the stages the modal analysis rests on are computed (``analyze(..., lazy=True)``,
    as :func:`~chaindrive.identification.calibration.elastic_frequencies`).

    %(drive_returns)s
    ndarray
        ζ of the elastic modes [-].
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    modal = analyze(drive, response=False, lazy=True).dynamics.modal
    return np.asarray(modal.modal_damping_ratios, dtype=float)[~np.asarray(modal.rigid_body)]


@dataclass(frozen=True, slots=True)
class DampingCalibration:
    """The fitted chain damping ratio and how well it fits.

    Parameters
    ----------
    initial : float | None
        The design's ``[dynamics] damping_ratio`` (None: from the materials or hinge
        friction).
    ratio : float
        Fitted ζ_c [-].
    std_log : float
        σ of ln ζ_c [-].
    interval : tuple of float
        95 % interval of ζ_c [-].
    measured : tuple of MeasuredDamping
        The measurements fitted.
    fitted_ratios : tuple of float
        The model's modal ratios of those modes at the fitted ζ_c [-].
    chi2_per_dof : float | None
        χ²/ν [-] (None with one measurement).
    evaluations : int
        Model evaluations [-].
    """

    initial: float | None
    ratio: float
    std_log: float
    interval: tuple[float, float]
    measured: tuple[MeasuredDamping, ...]
    fitted_ratios: tuple[float, ...]
    chi2_per_dof: float | None
    evaluations: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {
            "parameter": "dynamics.damping_ratio",
            "initial": self.initial,
            "fitted": self.ratio,
            "std_of_log": self.std_log,
            "interval_95": list(self.interval),
            "residuals": [{"mode": m.mode, "measured": m.ratio, "std": m.std, "model": z,
                           "residual": z - m.ratio}
                          for m, z in zip(self.measured, self.fitted_ratios, strict=True)],
            "chi2_per_dof": self.chi2_per_dof,
            "model_evaluations": self.evaluations,
        }


def calibrate_damping_ratio(drive: Drive, measured: Sequence[MeasuredDamping], *,
                            ratios: Callable[[Drive], FloatArray] = elastic_damping_ratios
                            ) -> DampingCalibration:
    """Fit ``[dynamics] damping_ratio`` to measured modal damping ratios (module docstring).

    Parameters
    ----------
    drive : Drive
        The design.
    measured : sequence of MeasuredDamping
        At least one; modes among the model's elastic modes.
    ratios : callable
        The model's elastic modal damping ratios of a design (:func:`elastic_damping_ratios`).

    Returns
    -------
    DampingCalibration

    Raises
    ------
    DesignError
        No measurement, a mode the model does not have, a ratio not in (0, 1) or an
        uncertainty that is not positive.

    References
    ----------
    [Virtanen2020]; [JCGM100, §5.1].
    """
    if not measured:
        raise DesignError("--damping", "no measured damping ratio; allowed: one or more")
    for m in measured:
        if not (math.isfinite(m.ratio) and 0 < m.ratio < 1):
            raise DesignError("--damping", f"mode {m.mode}: damping ratio {m.ratio!r}; "
                              "allowed: above 0 and below 1")
        if not (math.isfinite(m.std) and m.std > 0):
            raise DesignError("--damping", f"mode {m.mode}: uncertainty {m.std!r}; allowed: "
                              "above 0")
    z = np.array([m.ratio for m in measured])
    u = np.array([m.std for m in measured])
    initial = drive.dynamics.damping_ratio
    start = initial if initial else float(z[0])
    modes = model_mode_indices([m.mode for m in measured],
                               ratios(with_damping_ratio(drive, start)).size, "--damping")
    fit = fit_log_parameter(lambda c: ratios(with_damping_ratio(drive, c))[modes], z, u,
                            start, upper=ZETA_LIMIT)
    return DampingCalibration(initial, fit.value, fit.std_log,
                              (fit.interval[0], min(fit.interval[1], ZETA_LIMIT)),
                              tuple(measured), fit.fitted, fit.chi2_per_dof, fit.evaluations)
