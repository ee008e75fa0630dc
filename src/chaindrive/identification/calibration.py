"""The model's link stiffness calibrated to measured natural frequencies, with its interval.

The uncertain input fitted is the axial stiffness of one link k_link (``[chain]
link_stiffness``), on which the chain-governed natural frequencies of the whole-drive model
rest. With θ = ln k_link and the measured natural frequencies f_i of elastic modes m_i with
standard uncertainties u_i, the weighted residuals r_i(θ) = (f_model,m_i(θ) − f_i)/u_i are
minimised by ``scipy.optimize.least_squares`` ([Virtanen2020]; trust-region reflective).
The covariance of θ is (JᵀJ)⁻¹ at the optimum, J = ∂r/∂θ (the residuals are weighted by
their stated uncertainties) [JCGM100, §5.1], multiplied by χ²/ν when that exceeds 1 (the
measurements scatter more than their stated uncertainties allow; never narrowed below
them); the 95 % interval is exp(θ ± 1.96 σ_θ) (normal approximation).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.identification.damping import (
    DampingCalibration,
    MeasuredDamping,
    calibrate_damping_ratio,
    with_damping_ratio,
)
from chaindrive.identification.fitting import (
    fit_log_parameter,
    fit_log_parameters,
    model_mode_indices,
)

if TYPE_CHECKING:
    from chaindrive.identification.spectrum import Identification
    from chaindrive.model import Drive

__all__ = ["CalibratedDesign", "Calibration", "MassCalibration", "MeasuredMode",
           "calibrate_link_stiffness", "calibrated_design", "check_measured_mode",
           "elastic_frequencies", "measured_natural_peaks", "verdict_changes", "with_chain",
           "with_reduced_mass"]

@dataclass(frozen=True, slots=True)
class MeasuredMode:
    """A measured natural frequency of an elastic mode.

    Parameters
    ----------
    mode : int
        Elastic mode m [-], counted from 1 (the rigid-body motion not counted).
    frequency : float
        f [Hz].
    std : float
        Its standard uncertainty u [Hz], positive.
    """

    mode: int
    frequency: float
    std: float


def check_measured_mode(m: MeasuredMode) -> None:
    """Refuse a measured natural frequency or uncertainty that is not positive (one line
    naming the ``--natural`` option, the mode and the value).

    Parameters
    ----------
    m : MeasuredMode
        One measurement.

    Raises
    ------
    DesignError
        The frequency or its uncertainty is not a positive number.
    """
    if not (math.isfinite(m.frequency) and m.frequency > 0):
        raise DesignError("--natural", f"mode {m.mode}: frequency {m.frequency!r} Hz; "
                          "allowed: above 0 Hz")
    if not (math.isfinite(m.std) and m.std > 0):
        raise DesignError("--natural", f"mode {m.mode}: uncertainty {m.std!r} Hz; allowed: "
                          "above 0 Hz")


@shared_parameters
def elastic_frequencies(drive: Drive) -> np.ndarray[Any, np.dtype[np.float64]]:
    """The elastic natural frequencies [Hz] of a drive's whole-drive model, lowest first.

    Only the stages the modal analysis rests on are computed (``analyze(..., lazy=True)``:
    the same frequencies, bit for bit, without the chain selection's ranking and the checks a
    fit run per parameter value does not read).

    %(drive_returns)s
    ndarray
        f [Hz] of the elastic modes.
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    modal = analyze(drive, response=False, lazy=True).dynamics.modal
    return np.asarray(modal.elastic_frequencies_hz, dtype=float)


def with_chain(drive: Drive, **values: float) -> Drive:
    """The design with fields of its ``[chain]`` table set: ``link_stiffness`` k_link [N/m],
    ``sag`` s, the installed sag of the slack span as a fraction of its length [-], …

    Parameters
    ----------
    drive : Drive
        The design.
    **values : float
        Field name of ``[chain]`` → its value [SI].

    Returns
    -------
    Drive
    """
    changes: dict[str, Any] = dict(values)  # Any: mypy checks ** against every field
    return dataclasses.replace(drive, chain=dataclasses.replace(drive.chain, **changes))


def with_reduced_mass(drive: Drive, sprocket: str, mass: float) -> Drive:
    """The design with one sprocket's ``reduced_mass`` set to m [kg] (its ``inertia``
    cleared: the two are alternatives).

    Parameters
    ----------
    drive : Drive
        The design.
    sprocket : str
        The sprocket's name.
    mass : float
        m = J/R² [kg].

    Returns
    -------
    Drive
    """
    return dataclasses.replace(drive, sprockets=tuple(
        dataclasses.replace(s, reduced_mass=mass, inertia=None) if s.name == sprocket else s
        for s in drive.sprockets))


@dataclass(frozen=True, slots=True)
class MassCalibration:
    """A sprocket's reduced mass fitted jointly with the link stiffness.

    Parameters
    ----------
    sprocket : str
        The sprocket's name.
    initial : float
        Its reduced mass in the design [kg].
    mass : float
        Fitted [kg].
    std_log : float
        σ of ln m [-].
    interval : tuple of float
        95 % interval [kg] (marginal).
    correlation : float
        Correlation of ln m with ln k_link [-].
    """

    sprocket: str
    initial: float
    mass: float
    std_log: float
    interval: tuple[float, float]
    correlation: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {"parameter": f"sprockets[{self.sprocket}].reduced_mass",
                "initial_kg": self.initial, "fitted_kg": self.mass,
                "std_of_log": self.std_log, "interval_95_kg": list(self.interval),
                "correlation_with_link_stiffness": self.correlation}


@dataclass(frozen=True, slots=True)
class Calibration:
    """The fitted link stiffness and how well it fits.

    Parameters
    ----------
    initial : float
        k_link of the design before the fit [N/m].
    stiffness : float
        Fitted k_link [N/m].
    std_log : float
        σ of ln k_link [-].
    interval : tuple of float
        95 % interval of k_link [N/m].
    measured : tuple of MeasuredMode
        The measurements fitted.
    fitted_frequencies : tuple of float
        The model's frequencies of those modes at the fitted k_link [Hz].
    chi2_per_dof : float | None
        χ²/ν of the weighted residuals [-] (None with as many measurements as parameters).
    evaluations : int
        Model evaluations of the fit [-].
    mass : MassCalibration | None
        The reduced mass fitted jointly (None: not fitted).
    """

    initial: float
    stiffness: float
    std_log: float
    interval: tuple[float, float]
    measured: tuple[MeasuredMode, ...]
    fitted_frequencies: tuple[float, ...]
    chi2_per_dof: float | None
    evaluations: int
    mass: MassCalibration | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {
            "parameter": "chain.link_stiffness",
            "initial_n_per_m": self.initial,
            "fitted_n_per_m": self.stiffness,
            "std_of_log": self.std_log,
            "interval_95_n_per_m": list(self.interval),
            "residuals": [{"mode": m.mode, "measured_hz": m.frequency, "std_hz": m.std,
                           "model_hz": f, "residual_hz": f - m.frequency}
                          for m, f in zip(self.measured, self.fitted_frequencies, strict=True)],
            "chi2_per_dof": self.chi2_per_dof,
            "model_evaluations": self.evaluations,
            "reduced_mass": self.mass.to_dict() if self.mass is not None else None,
        }


def calibrate_link_stiffness(drive: Drive, measured: Sequence[MeasuredMode], *,
                             initial: float,
                             frequencies: Callable[[Drive], np.ndarray[Any, np.dtype[np.float64]]]
                             = elastic_frequencies,
                             uncertain_mass: tuple[str, float] | None = None) -> Calibration:
    """Fit k_link to measured natural frequencies (module docstring), and with it, when
    asked, one sprocket's reduced mass (θ = (ln k_link, ln m), :func:`fit_log_parameters`).

    Parameters
    ----------
    drive : Drive
        The design.
    measured : sequence of MeasuredMode
        At least one; modes among the model's elastic modes.
    initial : float
        The design's k_link [N/m], the fit's start.
    frequencies : callable
        The model's elastic frequencies of a design [Hz] (:func:`elastic_frequencies`).
    uncertain_mass : tuple of (str, float) | None
        The sprocket whose reduced mass is fitted too and its design value [kg] (needs two
        or more measured frequencies).

    Returns
    -------
    Calibration

    Raises
    ------
    DesignError
        No measurement, a mode the model does not have, a frequency or uncertainty that is
        not positive; a reduced mass to fit with fewer than two frequencies.

    References
    ----------
    [Virtanen2020]; [JCGM100, §5.1].
    """
    if not measured:
        raise DesignError("--natural", "no measured natural frequency; allowed: one or more")
    for m in measured:
        check_measured_mode(m)
    modes = model_mode_indices([m.mode for m in measured], frequencies(drive).size,
                               "--natural")
    f = np.array([m.frequency for m in measured])
    u = np.array([m.std for m in measured])
    if uncertain_mass is None:
        fit = fit_log_parameter(
            lambda k: frequencies(with_chain(drive, link_stiffness=k))[modes], f, u, initial)
        return Calibration(initial, fit.value, fit.std_log, fit.interval, tuple(measured),
                           fit.fitted, fit.chi2_per_dof, fit.evaluations)
    name, m0 = uncertain_mass
    if f.size < 2:
        raise DesignError("--uncertain-mass", f"{name}: {f.size} measured frequency; allowed: "
                          "two or more to fit the link stiffness and a reduced mass")
    k_fit, m_fit = fit_log_parameters(
        lambda x: frequencies(with_reduced_mass(with_chain(drive, link_stiffness=float(x[0])),
                                                name, float(x[1])))[modes], f, u, [initial, m0])
    mass = MassCalibration(name, m0, m_fit.value, m_fit.std_log, m_fit.interval,
                           m_fit.correlation[0])
    return Calibration(initial, k_fit.value, k_fit.std_log, k_fit.interval, tuple(measured),
                       k_fit.fitted, k_fit.chi2_per_dof, k_fit.evaluations, mass)


def verdict_changes(before: Sequence[Any], after: Sequence[Any]) -> list[dict[str, Any]]:
    """The checks whose verdict differs between two runs of the same design's checks.

    Parameters
    ----------
    before, after : sequence of Check
        :meth:`chaindrive.analysis.Analysis.checks` of the design and of the calibrated one
        (the same checks in the same order).

    Returns
    -------
    list of dict
        ``{"check", "subject", "before", "after", "value_before", "value_after"}`` per
        changed verdict.
    """
    return [{"check": a.name, "subject": a.subject, "before": a.status, "after": b.status,
             "value_before": a.value, "value_after": b.value}
            for a, b in zip(before, after, strict=False) if a.status != b.status]


def measured_natural_peaks(result: Identification) -> list[MeasuredMode]:
    """The peaks of a matched record labelled as natural frequencies, as measurements.

    Each peak lies within ± half a frequency bin of its true frequency, taken as a
    rectangular distribution: u = Δf / (2√3) [JCGM100, §4.3.7]. Where several signals show
    the same mode, the most prominent peak is kept.

    Parameters
    ----------
    result : Identification
        :func:`chaindrive.identification.identify`.

    Returns
    -------
    list of MeasuredMode
        By mode.
    """
    best: dict[int, tuple[float, MeasuredMode]] = {}
    for sig in result.signals:
        for p in sig.peaks:
            if p.line is None or p.line.kind != "natural":
                continue
            mode = int(p.line.label.split()[-1])
            m = MeasuredMode(mode, p.frequency, sig.resolution / (2.0 * math.sqrt(3.0)))
            if mode not in best or p.prominence_db > best[mode][0]:
                best[mode] = (p.prominence_db, m)
    return [best[k][1] for k in sorted(best)]


@dataclass(frozen=True, slots=True)
class CalibratedDesign:
    """A design calibrated to measurements and what its checks say after.

    Parameters
    ----------
    calibration : Calibration | None
        The link stiffness fit (None: no natural frequency measured).
    drive : Drive
        The design with the fitted ``[chain] link_stiffness`` and ``[dynamics]
        damping_ratio``.
    changes : list of dict
        Checks whose verdict changed (:func:`verdict_changes`).
    damping : DampingCalibration | None
        The damping ratio fit (None: no damping ratio measured).
    """

    calibration: Calibration | None
    drive: Drive
    changes: list[dict[str, Any]]
    damping: DampingCalibration | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: the stiffness fit's keys (when fitted), ``damping`` and
        ``verdicts_changed``."""
        return {**(self.calibration.to_dict() if self.calibration is not None else {}),
                "damping": self.damping.to_dict() if self.damping is not None else None,
                "verdicts_changed": self.changes}


def calibrated_design(drive: Drive, measured: Sequence[MeasuredMode],
                      damping: Sequence[MeasuredDamping] = (),
                      uncertain_mass: str | None = None) -> CalibratedDesign:
    """Fit k_link to measured natural frequencies (:func:`calibrate_link_stiffness`), then
    the chain's damping ratio to measured modal damping ratios
    (:func:`chaindrive.identification.damping.calibrate_damping_ratio`, on the design with
    the fitted stiffness), and re-run the design's checks with them.

    Parameters
    ----------
    drive : Drive
        The design.
    measured : sequence of MeasuredMode
        The measured natural frequencies (may be empty when ``damping`` is given).
    damping : sequence of MeasuredDamping
        The measured modal damping ratios (may be empty).
    uncertain_mass : str | None
        A sprocket whose reduced mass is fitted jointly with the link stiffness.

    Returns
    -------
    CalibratedDesign

    Raises
    ------
    DesignError
        Neither a natural frequency nor a damping ratio measured; an unknown sprocket, or
        a reduced mass to fit without natural frequencies.
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    if not measured and not damping:
        raise DesignError("--natural", "nothing measured; allowed: one or more natural "
                          "frequencies or damping ratios")
    before = analyze(drive, response=False)
    names = [s.name for s in drive.sprockets]
    if uncertain_mass is not None and uncertain_mass not in names:
        raise DesignError("--uncertain-mass", f"{uncertain_mass!r}; allowed: "
                          + ", ".join(names))
    if uncertain_mass is not None and not measured:
        raise DesignError("--uncertain-mass", f"{uncertain_mass}: no natural frequency "
                          "measured; allowed: with two or more --natural or a --record")
    mass = (None if uncertain_mass is None else
            (uncertain_mass, float(before.ring_parameters.masses_kg[names.index(uncertain_mass)])))
    cal = None
    calibrated = drive
    if measured:
        cal = calibrate_link_stiffness(drive, measured,
                                       initial=before.ring_parameters.link_stiffness_n_per_m,
                                       uncertain_mass=mass)
        calibrated = with_chain(drive, link_stiffness=cal.stiffness)
        if cal.mass is not None:
            calibrated = with_reduced_mass(calibrated, cal.mass.sprocket, cal.mass.mass)
    zeta = None
    if damping:
        zeta = calibrate_damping_ratio(calibrated, damping)
        calibrated = with_damping_ratio(calibrated, zeta.ratio)
    after = analyze(calibrated, response=False)
    return CalibratedDesign(cal, calibrated, verdict_changes(before.checks(), after.checks()),
                            zeta)
