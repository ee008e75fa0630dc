"""Order tracking of a run-up record: its order spectrum and its peaks over the speed range,
set against the model ([Brandt2011], the chapter on rotating machinery analysis).

Shaft angle. θ(t) of the driver shaft comes from a speed signal ω(t) (the trapezoidal rule,
θ = ∫ω dt) or from a tacho signal (rising crossings of its mid-level, each a known fraction
1/P of a revolution; θ between them by a monotone cubic, ``scipy.interpolate.PchipInterpolator``
[Virtanen2020]). Only the longest stretch of the record in which the shaft turns at
:data:`MIN_SPEED_FRACTION` of its top speed or faster is used.

Order spectrum (computed order tracking). Each signal is resampled at uniform steps of
angle: the times of θ_k = θ_0 + 2πk/R are read off θ(t) by linear interpolation and the
signal at those times by a cubic spline through its samples (``scipy.interpolate.CubicSpline``).
R = ⌈f_s/n_min⌉ samples per revolution (n_min the lowest speed used [rev/s]): every
frequency the record holds (below f_s/2) lies below the order R/2 at every speed used, so
the resampling folds nothing back. The resampled signal's Welch spectrum
(:func:`chaindrive.identification.spectrum.signal_spectrum`) is over orders (cycles per
revolution of the driver), kept up to f_s/(2 n_max), the highest order every speed used
resolves; a component locked to the shaft angle (the tooth order k·z₁,
a shaft's order z₁/z_i) is one sharp line, a component at a fixed frequency f is spread
over the orders f/n_max … f/n_min. Its peaks are found and labelled as in
:mod:`chaindrive.identification.spectrum`, against the shaft and tooth orders.

Run-up map. The record is cut into slices (:func:`slice_length` samples); each slice's
periodogram (Hann window) gives peaks (prominence ≥ ``prominence_db`` and at least
``prominence_db`` above the slice's median level — a periodogram bin of noise alone is
exponentially distributed [Welch1967], so it exceeds 15 dB above the median with
probability e^{−21.9}), each at the slice's mean speed n and labelled against the model's
lines at that speed: the fixed natural and span frequencies and the working frequencies at
n. A fixed-frequency resonance shows as points at one f over the speeds, at the orders
f·60/n (n in rpm); a tooth order as points on its ray f = k z₁ n/60.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import cumulative_trapezoid
from scipy.interpolate import CubicSpline, PchipInterpolator
from scipy.signal import find_peaks, periodogram

from chaindrive.dynamics.resonance import working_frequencies
from chaindrive.errors import DesignError
from chaindrive.identification.spectrum import (
    DEFAULT_PROMINENCE_DB,
    DEFAULT_TOLERANCE,
    MAX_HARMONICS,
    WORKING_KINDS,
    Identification,
    ModelLine,
    identify,
    label_peak,
    model_lines,
    signal_spectrum,
    spectral_peaks,
)
from chaindrive.units import RPM_PER_RAD_S, TWO_PI

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.io.record import Record

__all__ = ["MIN_SPEED_FRACTION", "OrderPeak", "OrderTracking", "RecordIdentification",
           "RunupPoint", "SignalOrders", "angle_from_speed", "angle_from_tacho",
           "identify_record", "order_lines", "resampled_by_angle", "slice_length",
           "swept_spectrum", "track_orders"]

#: Lowest speed used, as a fraction of the record's top speed [-]: below it a revolution
#: spans so many samples that the resampled record would grow by more than 1/fraction; a
#: choice, named in the output.
MIN_SPEED_FRACTION = 0.1
#: Most peaks kept per slice of the run-up map, the most prominent first [-].
MAX_SLICE_PEAKS = 10
#: Fewest slices of a run-up map [-].
MIN_SLICES = 16
#: Fewest revolutions of a record for an order spectrum [-].
MIN_REVOLUTIONS = 4.0


def angle_from_speed(speed: NDArray[np.float64], sample_rate: float) -> NDArray[np.float64]:
    """Shaft angle θ(t) = ∫₀ᵗ ω dt [rad] by the trapezoidal rule.

    Parameters
    ----------
    speed : ndarray
        ω at each sample [rad/s].
    sample_rate : float
        f_s [Hz].

    Returns
    -------
    ndarray
        θ at each sample [rad], from 0.
    """
    return np.asarray(cumulative_trapezoid(speed, dx=1.0 / sample_rate, initial=0),
                      dtype=np.float64)


def angle_from_tacho(pulses: NDArray[np.float64], sample_rate: float,
                     pulses_per_revolution: int) -> tuple[NDArray[np.float64],
                                                          NDArray[np.float64]]:
    """Shaft angle and speed from a tacho signal: its rising crossings of the level halfway
    between its least and greatest value (each located by linear interpolation between the
    two samples across it) are 2π/P apart; θ between them by a monotone cubic
    (``PchipInterpolator``, [Virtanen2020]), ω its derivative.

    Parameters
    ----------
    pulses : ndarray
        The tacho signal [any unit].
    sample_rate : float
        f_s [Hz].
    pulses_per_revolution : int
        P [-], at least 1.

    Returns
    -------
    angle : ndarray
        θ at each sample [rad]; NaN before the first and after the last pulse.
    speed : ndarray
        ω at each sample [rad/s]; NaN where θ is.

    Raises
    ------
    DesignError
        P below 1, or fewer than 3 pulses.
    """
    if pulses_per_revolution < 1:
        raise DesignError("--pulses-per-rev", f"{pulses_per_revolution!r}; allowed: 1 or more")
    level = 0.5 * (float(np.min(pulses)) + float(np.max(pulses)))
    k = np.flatnonzero((pulses[:-1] < level) & (pulses[1:] >= level))
    if k.size < 3:
        raise DesignError("--tacho", f"{k.size} pulses; allowed: 3 or more rising edges")
    times = (k + (level - pulses[k]) / (pulses[k + 1] - pulses[k])) / sample_rate
    theta = TWO_PI * np.arange(k.size) / pulses_per_revolution
    shape = PchipInterpolator(times, theta, extrapolate=False)
    t = np.arange(pulses.size) / sample_rate
    return (np.asarray(shape(t), dtype=float),
            np.asarray(shape.derivative()(t), dtype=float))


def _longest_run(mask: NDArray[np.bool_]) -> tuple[int, int]:
    """[start, stop) of the longest run of True."""
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    if starts.size == 0:
        return 0, 0
    i = int(np.argmax(stops - starts))
    return int(starts[i]), int(stops[i])


def resampled_by_angle(values: NDArray[np.float64], time: NDArray[np.float64],
                       angle: NDArray[np.float64], per_revolution: int) -> NDArray[np.float64]:
    """A signal resampled at uniform steps of shaft angle (module docstring).

    Parameters
    ----------
    values : ndarray
        The samples [signal unit] at ``time``.
    time : ndarray
        t [s], increasing.
    angle : ndarray
        θ at ``time`` [rad], strictly increasing.
    per_revolution : int
        R, samples per revolution [-].

    Returns
    -------
    ndarray
        The signal at θ_0 + 2πk/R, k = 0, 1, … while within the record [signal unit].

    References
    ----------
    [Brandt2011]; [Virtanen2020].
    """
    steps = math.floor((angle[-1] - angle[0]) * per_revolution / TWO_PI) + 1
    theta = angle[0] + TWO_PI * np.arange(steps) / per_revolution
    at = np.interp(theta, angle, time)
    return np.asarray(CubicSpline(time, values)(at), dtype=float)


def slice_length(samples: int) -> int:
    """Samples per slice of the run-up map [-]: the largest power of two not above
    1/:data:`MIN_SLICES` of the record, at least 64.

    Parameters
    ----------
    samples : int
        Samples of the stretch used [-].

    Returns
    -------
    int
    """
    return int(max(64, 2 ** math.floor(math.log2(max(samples // MIN_SLICES, 1)))))


def order_lines(analysis: Analysis, max_order: float) -> tuple[ModelLine, ...]:
    """The driver-shaft orders of the model: each shaft's z₁/z_i and the tooth orders k·z₁
    up to ``max_order`` (at most :data:`~chaindrive.identification.spectrum.MAX_HARMONICS`),
    as :class:`ModelLine` whose ``frequency`` is the order [-] (the working frequencies at
    one revolution per second).

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    max_order : float
        Highest order the spectrum shows [-].

    Returns
    -------
    tuple of ModelLine
    """
    drive = analysis.drive
    z1 = drive.driver.teeth
    harmonics = int(min(MAX_HARMONICS, max(1, math.floor(max_order / z1))))
    return tuple(ModelLine(w.kind, w.label, float(w.frequency)) for w in working_frequencies(
        TWO_PI, z1, [s.teeth for s in drive.sprockets], [s.name for s in drive.sprockets],
        harmonics))


def _lines_at(analysis: Analysis, fixed: tuple[ModelLine, ...], speed: float,
              max_frequency: float) -> tuple[ModelLine, ...]:
    """The model's lines [Hz] at driver speed ω [rad/s]: the fixed ones and the working
    frequencies at ω up to ``max_frequency``."""
    drive = analysis.drive
    z1 = drive.driver.teeth
    fz = z1 * speed / TWO_PI
    harmonics = int(min(MAX_HARMONICS, max(1, math.floor(max_frequency / fz))))
    working = working_frequencies(speed, z1, [s.teeth for s in drive.sprockets],
                                  [s.name for s in drive.sprockets], harmonics)
    return fixed + tuple(ModelLine(w.kind, w.label, float(w.frequency)) for w in working)


@dataclass(frozen=True, slots=True)
class OrderPeak:
    """One peak of an order spectrum and what it is.

    Parameters
    ----------
    order : float
        Cycles per driver revolution [-] (refined by a parabola in dB).
    level_db : float
        Its level [dB re 1 (signal unit)² per order].
    prominence_db : float
        Its prominence [dB].
    line : ModelLine | None
        The nearest shaft or tooth order within the tolerance (None: unexplained).
    deviation : float | None
        (o − o_line)/o_line [-].
    also : tuple of ModelLine
        Other orders within the tolerance.
    swept : tuple of str
        The model's fixed lines (natural, span) whose orders f/n over the speeds of the
        record include this order: a peak that is no shaft or tooth order may be one of them.
    """

    order: float
    level_db: float
    prominence_db: float
    line: ModelLine | None
    deviation: float | None
    also: tuple[ModelLine, ...] = ()
    swept: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"order": self.order, "level_db": self.level_db,
                "prominence_db": self.prominence_db,
                "label": "unexplained" if self.line is None else self.line.label,
                "kind": "unexplained" if self.line is None else self.line.kind,
                "model_order": None if self.line is None else self.line.frequency,
                "deviation_percent": None if self.deviation is None else 100 * self.deviation,
                "also_within_tolerance": [ln.label for ln in self.also],
                "fixed_lines_sweeping_this_order": list(self.swept)}


@dataclass(frozen=True, slots=True)
class SignalOrders:
    """One signal's order spectrum and its peaks.

    Parameters
    ----------
    name : str
        The signal.
    per_revolution : int
        R, samples per revolution of the resampled signal [-].
    revolutions : float
        Driver revolutions in the stretch used [-].
    segment : int
        Samples per Welch segment [-].
    orders : ndarray
        Orders of the spectrum [-], up to f_s/(2 n_max): the highest order every speed of the
        stretch holds (above it the record sees that order only at the lower speeds).
    psd : ndarray
        Its density [(signal unit)² per order].
    peaks : tuple of OrderPeak
        The peaks, by order.
    """

    name: str
    per_revolution: int
    revolutions: float
    segment: int
    orders: NDArray[np.float64]
    psd: NDArray[np.float64]
    peaks: tuple[OrderPeak, ...]

    @property
    def resolution(self) -> float:
        """One bin R/segment [orders]."""
        return self.per_revolution / self.segment

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the spectrum itself is left out; the figure shows it)."""
        return {"name": self.name, "samples_per_revolution": self.per_revolution,
                "revolutions": self.revolutions, "segment_samples": self.segment,
                "resolution_orders": self.resolution,
                "peaks": [p.to_dict() for p in self.peaks]}


@dataclass(frozen=True, slots=True)
class RunupPoint:
    """A peak of one slice of the run-up map: a measured point of the Campbell diagram.

    Parameters
    ----------
    signal : str
        The signal.
    speed_rpm : float
        The slice's mean driver speed [rpm].
    frequency : float
        f [Hz] (refined by a parabola in dB).
    level_db : float
        Its level [dB re 1 (signal unit)²/Hz].
    line : ModelLine | None
        The nearest model line at that speed within the tolerance (None: unexplained).
    deviation : float | None
        (f − f_line)/f_line [-].
    also : tuple of ModelLine
        Other lines within the tolerance.
    """

    signal: str
    speed_rpm: float
    frequency: float
    level_db: float
    line: ModelLine | None
    deviation: float | None
    also: tuple[ModelLine, ...] = ()

    @property
    def order(self) -> float:
        """f·60/n: cycles per driver revolution [-]."""
        return self.frequency * TWO_PI * RPM_PER_RAD_S / self.speed_rpm

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"signal": self.signal, "speed_rpm": self.speed_rpm,
                "frequency_hz": self.frequency, "order": self.order,
                "level_db": self.level_db,
                "label": "unexplained" if self.line is None else self.line.label,
                "kind": "unexplained" if self.line is None else self.line.kind,
                "model_frequency_hz": None if self.line is None else self.line.frequency,
                "deviation_percent": None if self.deviation is None else 100 * self.deviation,
                "also_within_tolerance": [ln.label for ln in self.also]}


@dataclass(frozen=True, slots=True)
class OrderTracking:
    """A run-up record's order spectra and run-up map set against the model.

    Parameters
    ----------
    record : str
        The record's name.
    reference : str
        What gave the angle (the speed or tacho column).
    speed_range_rpm : tuple of float
        Lowest and highest driver speed of the stretch used [rpm].
    duration : float
        Length of the stretch used [s].
    lines : tuple of ModelLine
        The shaft and tooth orders (``frequency`` is the order [-]).
    natural : tuple of ModelLine
        The model's fixed lines [Hz] (natural and span frequencies).
    signals : tuple of SignalOrders
        Each signal's order spectrum.
    points : tuple of RunupPoint
        The run-up map's peaks.
    slice_seconds : float
        Length of a slice of the run-up map [s].
    slice_resolution : float
        Its frequency bin [Hz].
    tolerance : float
        Relative tolerance of a model frequency [-].
    prominence_db : float
        Least prominence [dB].
    notes : tuple of str
        What the result rests on.
    """

    record: str
    reference: str
    speed_range_rpm: tuple[float, float]
    duration: float
    lines: tuple[ModelLine, ...]
    natural: tuple[ModelLine, ...]
    signals: tuple[SignalOrders, ...]
    points: tuple[RunupPoint, ...]
    slice_seconds: float
    slice_resolution: float
    tolerance: float
    prominence_db: float
    notes: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {"record": self.record, "angle_from": self.reference,
                "speed_range_rpm": list(self.speed_range_rpm), "duration_s": self.duration,
                "min_speed_fraction": MIN_SPEED_FRACTION,
                "tolerance_percent": 100 * self.tolerance, "prominence_db": self.prominence_db,
                "signals": [s.to_dict() for s in self.signals],
                "runup_slice_s": self.slice_seconds,
                "runup_resolution_hz": self.slice_resolution,
                "runup_points": [p.to_dict() for p in self.points],
                "model_orders": [{"kind": ln.kind, "label": ln.label, "order": ln.frequency}
                                 for ln in self.lines],
                "notes": list(self.notes)}


def _slice_peaks(values: NDArray[np.float64], sample_rate: float, prominence_db: float
                 ) -> tuple[list[tuple[float, float]], float]:
    """Peaks (f [Hz], level [dB]) of one slice's periodogram (module docstring) and its bin."""
    f, p = periodogram(values, fs=sample_rate, window="hann", detrend="constant",
                       scaling="density")
    p = np.asarray(p, dtype=float)
    db = 10.0 * np.log10(np.maximum(p, np.max(p) * 1e-30 + 1e-300))
    floor = float(np.median(db))
    idx, props = find_peaks(db, prominence=prominence_db, height=floor + prominence_db)
    keep = sorted(((int(i), float(pr)) for i, pr in zip(idx, props["prominences"], strict=True)
                   if 2 <= i < db.size - 1), key=lambda t: -t[1])[:MAX_SLICE_PEAKS]
    df = float(f[1] - f[0])
    out = []
    for i, _ in sorted(keep):
        a, b, c = db[i - 1], db[i], db[i + 1]
        denom = a - 2 * b + c
        shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
        out.append((float(f[i] + shift * df), float(b - 0.25 * (a - c) * shift)))
    return out, df


def track_orders(record: Record, analysis: Analysis, reference: str, *,
                 speed: NDArray[np.float64] | None = None,
                 angle: NDArray[np.float64] | None = None,
                 tolerance: float = DEFAULT_TOLERANCE,
                 prominence_db: float = DEFAULT_PROMINENCE_DB) -> OrderTracking:
    """Order spectra and run-up map of a record (module docstring).

    Parameters
    ----------
    record : Record
        The signals (the speed or tacho column taken out).
    analysis : Analysis
        The analysed design.
    reference : str
        What gives the angle, for the output (the column's name).
    speed : ndarray | None
        Driver speed ω at each sample [rad/s].
    angle : ndarray | None
        Driver angle θ at each sample [rad] (NaN where unknown; from
        :func:`angle_from_tacho`, with ``speed``); None: from ``speed``
        (:func:`angle_from_speed`).
    tolerance : float
        Relative tolerance of the model's natural and span frequencies [-], in (0, 1).
    prominence_db : float
        Least prominence of a peak [dB], positive.

    Returns
    -------
    OrderTracking

    Raises
    ------
    DesignError
        No speed, a speed that is not positive somewhere in the record, fewer than
        :data:`MIN_REVOLUTIONS` revolutions or too few samples in the stretch used, or a
        tolerance or prominence out of range.

    References
    ----------
    [Brandt2011]; [Welch1967]; [Virtanen2020].
    """
    if speed is None:
        raise DesignError("--speed", "no speed signal; allowed: a speed or tacho column")
    if not (0 < tolerance < 1):
        raise DesignError("--tolerance", f"must lie between 0 and 100 %, got "
                          f"{100 * tolerance!r} %")
    if not (math.isfinite(prominence_db) and prominence_db > 0):
        raise DesignError("--prominence", f"must be above 0 dB, got {prominence_db!r}")
    fs = record.sample_rate
    theta = angle_from_speed(speed, fs) if angle is None else angle
    known = np.isfinite(theta) & np.isfinite(speed)
    top = float(np.max(np.where(known, speed, -np.inf))) if known.any() else 0.0
    if not top > 0:
        raise DesignError(f"--record.{reference}", "the shaft does not turn (speed never "
                          "above 0); allowed: a run-up or a running record")
    start, stop = _longest_run(known & (speed >= MIN_SPEED_FRACTION * top))
    theta_used, speed_used = theta[start:stop], speed[start:stop]
    revolutions = float(theta_used[-1] - theta_used[0]) / TWO_PI if stop - start > 1 else 0.0
    if stop - start < 64 or revolutions < MIN_REVOLUTIONS:
        raise DesignError(f"--record.{reference}", f"{revolutions:.3g} revolutions in "
                          f"{stop - start} samples at {MIN_SPEED_FRACTION:.0%} of the top "
                          f"speed or above; allowed: at least {MIN_REVOLUTIONS:g} and 64")
    n_min = float(np.min(speed_used)) / TWO_PI
    per_rev = math.ceil(fs / n_min)
    t = np.arange(start, stop) / fs
    n_max = float(np.max(speed_used)) / TWO_PI
    max_order = fs / (2.0 * n_max)
    lines = order_lines(analysis, max_order)
    fixed = tuple(ln for ln in model_lines(analysis) if ln.kind not in WORKING_KINDS)
    spectra = []
    for name, values in record.signals.items():
        x = resampled_by_angle(values[start:stop], t, theta_used, per_rev)
        o, p, nper = signal_spectrum(x, float(per_rev))
        seen = o <= max_order
        o, p = o[seen], p[seen]
        peaks = [OrderPeak(op, level, pr, *label_peak(op, lines, tolerance, per_rev / nper),
                           swept=tuple(ln.label for ln in fixed
                                       if ln.frequency / n_max <= op <= ln.frequency / n_min))
                 for op, level, pr in spectral_peaks(o, p, prominence_db)]
        spectra.append(SignalOrders(name, per_rev, revolutions, nper, o, p, tuple(peaks)))
    width = slice_length(stop - start)
    points: list[RunupPoint] = []
    df = fs / width
    for k in range(0, stop - start - width + 1, width):
        w = float(np.mean(speed_used[k:k + width]))
        at = _lines_at(analysis, fixed, w, fs / 2.0)
        for name, values in record.signals.items():
            found, df = _slice_peaks(values[start + k:start + k + width], fs, prominence_db)
            points += [RunupPoint(name, w * RPM_PER_RAD_S, f, level,
                                  *label_peak(f, at, tolerance, df)) for f, level in found]
    rpm = (float(np.min(speed_used)) * RPM_PER_RAD_S,
           float(np.max(speed_used)) * RPM_PER_RAD_S)
    notes = (f"the stretch at {MIN_SPEED_FRACTION:.0%} of the top speed or above is used "
             f"({(stop - start) / fs:.4g} s of {next(iter(record.signals.values())).size / fs:.4g}"
             " s)",
             "the spans' transverse frequencies are the design's, at its own speed and "
             "tension")
    return OrderTracking(record.name, reference, rpm, (stop - start) / fs, lines, fixed,
                         tuple(spectra), tuple(points), width / fs, df, tolerance,
                         prominence_db, notes)


@dataclass(frozen=True, slots=True)
class RecordIdentification:
    """A record matched to the model: its spectra, and its order tracking when a speed or
    tacho column gives the driver's angle.

    Parameters
    ----------
    spectrum : Identification
        The frequency spectra and their labelled peaks.
    orders : OrderTracking | None
        The order spectra and run-up map (None: no speed or tacho column named).
    """

    spectrum: Identification
    orders: OrderTracking | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: the spectrum's document with ``orders`` (null without a speed)."""
        return {**self.spectrum.to_dict(),
                "orders": None if self.orders is None else self.orders.to_dict()}


def identify_record(record: Record, analysis: Analysis, *, speed: str | None = None,
                    tacho: str | None = None, pulses_per_revolution: int = 1,
                    tolerance: float = DEFAULT_TOLERANCE,
                    prominence_db: float = DEFAULT_PROMINENCE_DB) -> RecordIdentification:
    """The entry point of ``chaindrive identify`` and the page: the record's spectra matched
    to the model's lines up to its Nyquist frequency
    (:func:`chaindrive.identification.spectrum.identify`), and, with a speed column (its
    unit ending its name, :func:`chaindrive.io.record.speed_unit`) or a tacho column
    (``pulses_per_revolution`` rising edges per driver revolution), its order tracking
    (:func:`track_orders`). The speed or tacho column is not itself a signal.

    Parameters
    ----------
    record : Record
        The measured record.
    analysis : Analysis
        The analysed design.
    speed : str | None
        The driver speed column.
    tacho : str | None
        The driver tacho column.
    pulses_per_revolution : int
        Tacho pulses per driver revolution [-].
    tolerance : float
        Relative tolerance of the model's natural and span frequencies [-].
    prominence_db : float
        Least prominence of a peak [dB].

    Returns
    -------
    RecordIdentification

    Raises
    ------
    DesignError
        Both a speed and a tacho column, an unknown column, a speed column without its unit,
        or what :func:`track_orders` and :func:`identify` refuse.
    """
    from chaindrive.io.record import speed_unit, take_column  # the column names' units

    if speed is not None and tacho is not None:
        raise DesignError("--tacho", "give a speed column or a tacho column, not both")
    column = speed if speed is not None else tacho
    if column is None:
        spectrum = identify(record, model_lines(analysis, record.sample_rate / 2.0),
                            tolerance=tolerance, prominence_db=prominence_db)
        return RecordIdentification(spectrum, None)
    option = "--speed" if speed is not None else "--tacho"
    rest, values = take_column(record, column, option)
    if speed is not None:
        omega, theta = values * speed_unit(column), None
    else:
        theta, omega = angle_from_tacho(values, record.sample_rate, pulses_per_revolution)
    spectrum = identify(rest, model_lines(analysis, rest.sample_rate / 2.0),
                        tolerance=tolerance, prominence_db=prominence_db)
    tracking = track_orders(rest, analysis, column, speed=omega, angle=theta,
                            tolerance=tolerance, prominence_db=prominence_db)
    return RecordIdentification(swept_spectrum(spectrum, tracking), tracking)


def swept_spectrum(spectrum: Identification, tracking: OrderTracking) -> Identification:
    """The frequency spectra of a run-up with no half-power ratio for a peak that lies
    where a shaft or tooth order sweeps (o·n_min … o·n_max): its width is the sweep's, not
    a damping; and a note that the working frequencies are the design speed's.

    Parameters
    ----------
    spectrum : Identification
        The record's frequency spectra.
    tracking : OrderTracking
        Its order tracking.

    Returns
    -------
    Identification
    """
    lo, hi = (r / (TWO_PI * RPM_PER_RAD_S) for r in tracking.speed_range_rpm)
    signals = []
    for sig in spectrum.signals:
        peaks = []
        for p in sig.peaks:
            sweep = next((ln.label for ln in tracking.lines
                          if ln.frequency * lo <= p.frequency <= ln.frequency * hi), None)
            if sweep is not None and p.damping_ratio is not None:
                p = dataclasses.replace(p, damping_ratio=None, damping_reason=(
                    f"{sweep} sweeps this frequency over the run-up: the peak's width is "
                    "the sweep's, not a damping"))
            peaks.append(p)
        signals.append(dataclasses.replace(sig, peaks=tuple(peaks)))
    note = (f"a run-up from {tracking.speed_range_rpm[0]:.4g} to "
            f"{tracking.speed_range_rpm[1]:.4g} rpm: the working frequencies listed are the "
            "design speed's; the orders and the run-up map follow the speed")
    return dataclasses.replace(spectrum, signals=tuple(signals),
                               notes=(*spectrum.notes, note))
