"""A span's tension read from its measured frequency, set beside the design's (the drive
level of :mod:`chaindrive.identification.tension`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.dynamics.stiffness import GRAVITY
from chaindrive.errors import DesignError
from chaindrive.identification.calibration import verdict_changes, with_chain
from chaindrive.identification.fitting import Z95
from chaindrive.identification.spectrum import signal_spectrum, spectral_peaks
from chaindrive.identification.tension import (
    TensionEstimate,
    expected_frequency,
    span_tension_from_frequency,
)
from chaindrive.strength.loads import installed_pretension, installed_sag_ratio, sag_span

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.io.record import Record
    from chaindrive.model import Drive

__all__ = [
    "RecordPeak",
    "SagCalibration",
    "SpanTensionReading",
    "calibrated_sag",
    "record_peak",
    "rectangular_std",
    "sag_for_pretension",
    "span_index",
    "span_tension_reading",
]

#: Least prominence [dB] of the peak a pluck's record is read at (the spectrum's, section 2 of
#: docs/identification.md: noise alone makes steps of about 10 dB in an 8-segment Welch
#: estimate).
PLUCK_PROMINENCE_DB = 15.0


@dataclass(frozen=True, slots=True)
class RecordPeak:
    """The peak a record of a pluck rings at.

    Parameters
    ----------
    signal : str
        The signal it was read from.
    frequency : float
        f [Hz] (the spectrum's peak, refined by a parabola through three bins).
    resolution : float
        The spectrum's bin Δf [Hz]; the peak lies within ± Δf/2 of the true frequency.
    prominence_db : float
        Its prominence [dB].
    """

    signal: str
    frequency: float
    resolution: float
    prominence_db: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {"signal": self.signal, "frequency_hz": self.frequency,
                "resolution_hz": self.resolution, "prominence_db": self.prominence_db}


def record_peak(record: Record, *, prominence_db: float = PLUCK_PROMINENCE_DB) -> RecordPeak:
    """The most prominent peak of a record of a pluck, over all its signals: each signal's
    Welch spectrum and peaks as ``chaindrive identify`` finds them
    (:func:`chaindrive.identification.spectrum.signal_spectrum`,
    :func:`~chaindrive.identification.spectrum.spectral_peaks`; [Welch1967],
    [Virtanen2020]).

    Parameters
    ----------
    record : Record
        The record (:func:`chaindrive.io.record.read_record`).
    prominence_db : float
        Least prominence of a peak [dB].

    Returns
    -------
    RecordPeak

    Raises
    ------
    DesignError
        No signal has a peak of that prominence.
    """
    best: RecordPeak | None = None
    for name, values in record.signals.items():
        f, psd, segment = signal_spectrum(np.asarray(values, dtype=float), record.sample_rate)
        for freq, _level, prominence in spectral_peaks(f, psd, prominence_db):
            if best is None or prominence > best.prominence_db:
                best = RecordPeak(name, freq, record.sample_rate / segment, prominence)
    if best is None:
        raise DesignError("--record", f"{record.name}: no peak {prominence_db:g} dB above its "
                          "surroundings; allowed: a record of a pluck that rings")
    return best


def rectangular_std(half_width: float) -> float:
    """Standard uncertainty a/√3 [same unit] of a quantity known to lie within ±a
    (rectangular distribution, [JCGM100, §4.3.7]).

    Parameters
    ----------
    half_width : float
        a [any unit], ≥ 0.

    Returns
    -------
    float
        u = a / √3.
    """
    return half_width / math.sqrt(3.0)


def span_index(analysis: Analysis, span: str) -> int:
    """Index of the span named ``FROM-TO`` (sprocket names) in the analysed contour.

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    span : str
        ``"S1-S2"``.

    Returns
    -------
    int

    Raises
    ------
    DesignError
        No span of that name (the message lists the spans).
    """
    names = [f"{s.start_name}-{s.end_name}" for s in analysis.geometry.spans]
    if span not in names:
        raise DesignError("--span", f"unknown span {span!r}; allowed: {', '.join(names)}")
    return names.index(span)


@dataclass(frozen=True, slots=True)
class SpanTensionReading:
    """A span's tension from its measured frequency, with what the design expects.

    Parameters
    ----------
    span : str
        ``FROM-TO``.
    estimate : TensionEstimate
        The tension read from the frequency.
    pretension : float
        The design's pretension F_0 [N]: the sag tension of its slack span at the installed
        sag, which every span carries at rest
        (:func:`chaindrive.strength.loads.installed_pretension`).
    expected_standing : float
        The frequency [Hz] of mode n of the stationary span at F_0.
    running_tension : float | None
        The design's span tension in operation [N] (None: the design gives no power).
    expected_running : float | None
        The frequency [Hz] of mode n of the running span at that tension.
    assumed : tuple of str
        The inputs that rest on an assumed value (named, with the value).
    """

    span: str
    estimate: TensionEstimate
    pretension: float
    expected_standing: float
    running_tension: float | None
    expected_running: float | None
    assumed: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {
            "span": self.span,
            **self.estimate.to_dict(),
            "design_pretension_n": self.pretension,
            "expected_frequency_standing_hz": self.expected_standing,
            "design_running_tension_n": self.running_tension,
            "expected_frequency_running_hz": self.expected_running,
            "assumed": list(self.assumed),
        }


def span_tension_reading(analysis: Analysis, span: str, frequency: float, *, mode: int = 1,
                         running: bool = False, frequency_tolerance: float = 0.0,
                         length_tolerance: float = 0.002, mass_tolerance: float = 0.05,
                         assumed: tuple[str, ...] = ()) -> SpanTensionReading:
    """The tension of one span of a design from its measured transverse frequency.

    The span's length, inclination and the chain's q and EA = k_link·p come from the
    analysis; a running chain moves at the mean chain speed v̄. Tolerances are half-widths
    of rectangular distributions (:func:`rectangular_std`). The expected frequencies are the
    string law at the design's pretension F_0 — the sag tension of the span whose sag the
    design gives, which the chain carries in every span at rest ([ChainDesignRU, §8],
    :func:`chaindrive.strength.loads.installed_pretension`; stationary) — and at the span's
    tension in operation (running).

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    span : str
        ``FROM-TO``.
    frequency : float
        Measured f [Hz].
    mode : int
        n [-].
    running : bool
        The chain was running at the design speed when measured.
    frequency_tolerance : float
        ±[Hz] of the measured frequency.
    length_tolerance : float
        ±[m] of the span length.
    mass_tolerance : float
        ± relative [-] of the mass per metre.
    assumed : tuple of str
        Which of the tolerances were not given (named in the result).

    Returns
    -------
    SpanTensionReading

    Raises
    ------
    DesignError
        Unknown span, an input out of range, or ``running`` for a design without speed.

    References
    ----------
    [Mote1965], [WickertMote1990], [JCGM100, §4.3.7, §5.1], [ChainDesignRU, §8].
    """
    i = span_index(analysis, span)
    for name, value in (("--frequency-tolerance", frequency_tolerance),
                        ("--length-tolerance", length_tolerance),
                        ("--mass-tolerance", mass_tolerance)):
        if not (math.isfinite(value) and value >= 0):
            raise DesignError(name, f"must be ≥ 0, got {value!r}")
    drive = analysis.drive
    spec = drive.chain.spec
    sp = analysis.geometry.spans[i]
    ring = analysis.ring_parameters
    speed = 0.0
    if running:
        if drive.driver.speed is None:
            raise DesignError("--running", "the design gives no driver speed")
        speed = float(analysis.kinematics.chain_speed)
    q = spec.mass_per_length
    estimate = span_tension_from_frequency(
        frequency, sp.length, q, mode=mode, speed=speed,
        frequency_std=rectangular_std(frequency_tolerance),
        length_std=rectangular_std(length_tolerance),
        mass_std=rectangular_std(mass_tolerance * q),
        axial_stiffness=ring.link_stiffness_n_per_m * spec.pitch,
        inclination=sp.inclination)
    f0 = installed_pretension(drive, analysis.geometry)
    tensions = ring.span_tensions_n
    running_t = None if tensions is None else float(tensions[i])
    running_f = None
    if running_t is not None and drive.driver.speed is not None:
        running_f = expected_frequency(running_t, sp.length, q, mode,
                                       float(analysis.kinematics.chain_speed))
    return SpanTensionReading(span, estimate, f0, expected_frequency(f0, sp.length, q, mode),
                              running_t, running_f, assumed)


def sag_for_pretension(tension: float, length: float, mass_per_length: float,
                       inclination: float) -> float:
    """Installed sag s [-] (fraction of the span) whose pretension F₀ = k_f·q·g·a is T: the
    inverse of k_f = cos ψ/(8s) + |sin ψ| (:func:`chaindrive.strength.loads.sag_factor`),
    s = cos ψ / (8 (T/(q g a) − |sin ψ|)).

    Parameters
    ----------
    tension : float
        T [N] read from the stationary span.
    length : float
        Span length a [m].
    mass_per_length : float
        q [kg/m].
    inclination : float
        ψ [rad].

    Returns
    -------
    float
        s [-].

    Raises
    ------
    DesignError
        T at or below the weight component of the span q g a |sin ψ| (no sag gives it).

    References
    ----------
    [ChainDesignRU, §8]; [Irvine1981, ch. 1].
    """
    weight = mass_per_length * GRAVITY * length
    excess = tension / weight - abs(math.sin(inclination))
    if excess <= 0:
        raise DesignError("--frequency", f"the tension read, {tension:.4g} N, is not above the "
                          f"span's weight component {weight * abs(math.sin(inclination)):.4g} N; "
                          "no sag gives it")
    return math.cos(inclination) / (8.0 * excess)


@dataclass(frozen=True, slots=True)
class SagCalibration:
    """The design's installed sag calibrated to a tension read from a stationary span.

    Parameters
    ----------
    initial : float
        The design's installed sag s [-] before.
    sag : float
        The sag s [-] of the slack span whose pretension is the tension read.
    interval : tuple of float
        s at T ± z₉₅ u(T) [-] (95 %, normal approximation, :data:`chaindrive.identification.fitting.Z95`).
    drive : Drive
        The design with ``[chain] sag`` = s.
    changes : list of dict
        Checks whose verdict changed (:func:`chaindrive.identification.calibration.verdict_changes`).
    span : str
        ``FROM-TO`` of the span whose sag s is (:func:`chaindrive.strength.loads.sag_span`).
    """

    initial: float
    sag: float
    interval: tuple[float, float]
    drive: Drive
    changes: list[dict[str, Any]]
    span: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"parameter": "chain.sag", "sag_span": self.span,
                "initial_fraction": self.initial,
                "fitted_fraction": self.sag, "interval_95_fraction": list(self.interval),
                "verdicts_changed": self.changes}


def calibrated_sag(drive: Drive, reading: SpanTensionReading) -> SagCalibration:
    """Set the design's installed sag to the one whose pretension is the tension read from a
    stationary span, and re-run the checks.

    At rest every span carries the pretension F₀, and the design's ``[chain] sag`` is that of
    its slack span (:func:`chaindrive.strength.loads.sag_span`), whose sag tension F₀ is
    (:func:`chaindrive.strength.loads.installed_pretension`): the sag is the one that gives
    the slack span the tension read (:func:`sag_for_pretension` on that span's length and
    inclination), whichever span was measured. The tension read is the measured span's mean
    along its length; the change of the tension with height along the chain, q g Δy, is
    left out, as in the design's static loads.

    Parameters
    ----------
    drive : Drive
        The design as loaded.
    reading : SpanTensionReading
        A stationary reading (:func:`span_tension_reading`) of the analysed design.

    Returns
    -------
    SagCalibration

    Raises
    ------
    DesignError
        A running reading, or a sag outside the design file's range 0.001–0.1.
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline

    est = reading.estimate
    if est.speed > 0:
        raise DesignError("--running", "the sag is calibrated from a stationary span; measure "
                          "with the chain at rest")
    before = analyze(drive, response=False)
    span_index(before, reading.span)  # the span read is one of this design's
    sp = sag_span(drive, before.geometry)

    def sag(t: float) -> float:
        return sag_for_pretension(t, sp.length, est.mass_per_length, sp.inclination)

    s = sag(est.tension)
    if not 0.001 <= s <= 0.1:
        raise DesignError("chain.sag", f"the tension read gives a sag of {s:.4g} of the slack "
                          "span; allowed: 0.001 to 0.1")
    lo = sag(est.tension + Z95 * est.std)
    hi = sag(max(est.tension - Z95 * est.std, 1e-9))
    calibrated = with_chain(drive, sag=s)
    after = analyze(calibrated, response=False)
    return SagCalibration(installed_sag_ratio(drive), s, (lo, hi), calibrated,
                          verdict_changes(before.checks(), after.checks()),
                          f"{sp.start_name}-{sp.end_name}")
