"""A measured record's spectrum, its peaks, and what each peak is in the model.

Spectrum: Welch's averaged periodogram ([Welch1967]; ``scipy.signal.welch``
[Virtanen2020]), Hann window, segments of :func:`segment_length` samples overlapping by half,
the mean removed. Peaks: ``scipy.signal.find_peaks`` on the spectrum in decibels with a
prominence of at least ``prominence_db`` (the peak stands that far above the higher of the
two lowest points that separate it from a higher peak on either side — SciPy's definition);
the two lowest bins (the mean's leakage) are not peaks.

Labelling: each peak is set against the model's lines — the natural frequencies of the
whole-drive model (elastic modes), the working frequencies (tooth-order excitations and
shaft speeds) and the spans' transverse frequencies (running, from the design's span
tensions) — and takes the nearest line within its tolerance: max(``tolerance`` · f_line, one
frequency bin) for the model's natural and span frequencies, max(1 % · f_line, one bin) for
the working frequencies, which follow from the speed alone; other lines within their
tolerance are listed beside it (the peak cannot tell them apart); no line within it:
"unexplained".

Damping: each peak's half-power damping ratio ζ ≈ (f₂ − f₁)/(2 f_n) ([Ewins2000, ch. 4];
:func:`chaindrive.identification.damping.half_power_damping_ratio`) read from a Welch
spectrum of the signal whose segment is fitted to the peak (:func:`peak_damping_ratio`):
the half-power band must span at least :data:`HALF_POWER_BINS` bins, with at least
:data:`HALF_POWER_AVERAGES` segments averaged; otherwise the ratio is not given and the
reason is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.signal import find_peaks, welch

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.resonance import working_frequencies
from chaindrive.errors import DesignError
from chaindrive.identification.damping import half_power_damping_ratio

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.io.record import Record

__all__ = ["DEFAULT_PROMINENCE_DB", "DEFAULT_TOLERANCE", "Identification", "ModelLine", "Peak",
           "SignalSpectrum", "identify", "label_peak", "line_tolerance", "model_lines",
           "peak_damping_ratio", "segment_length", "signal_spectrum", "spectral_peaks"]

#: Prominence a peak needs [dB]. A Welch estimate of K averaged segments scatters as χ² with
#: 2K degrees of freedom [Welch1967]: for K ≈ 8 the 0.1 % and 99.9 % points lie −5.7 dB and
#: +3.9 dB about the true density, so noise alone makes peak-to-valley steps near 10 dB;
#: 15 dB clears them (a choice, ``--prominence``).
DEFAULT_PROMINENCE_DB = 15.0
#: Relative tolerance of a match [-]: the model's natural frequencies rest on the link
#: stiffness and the span tensions, uncertain by more than this; 5 % is a starting choice,
#: not a measured one (``--tolerance``).
DEFAULT_TOLERANCE = 0.05
#: Most peaks kept per signal, the most prominent first [-].
MAX_PEAKS = 20
#: Most tooth-frequency harmonics listed as model lines [-].
MAX_HARMONICS = 100
#: Relative tolerance of a working frequency (tooth orders, shaft speeds) [-]: they follow
#: from the driver speed alone, which a motor holds to about its slip, ±1 % (an assumption).
WORKING_TOLERANCE = 0.01
#: Kinds of model line that are working frequencies.
WORKING_KINDS = frozenset({"tooth", "shaft", "parametric"})
#: Fewest frequency bins the half-power band 2ζf_n must span for its ζ to be given [-]. A
#: Hann window widens any line to 1.44 bins at half power [Harris1978], so a band of a few
#: bins is mostly the window's; from 8 bins on, the test's single-mode records (ζ = 0.05,
#: 0.1) read ζ within a few per cent on average (docs/identification.md §2). A choice.
HALF_POWER_BINS = 8
#: Fewest Welch segments averaged for a half-power reading [-]: each bin of an average of K
#: segments scatters by about 1/√K [Welch1967], and the half-power points are read from single
#: bins; 16 keep that scatter near 25 % of the power (≈ 1 dB). A choice.
HALF_POWER_AVERAGES = 16
#: Most refinements of the segment length for a half-power reading [-].
_HALF_POWER_STEPS = 8


@dataclass(frozen=True, slots=True)
class ModelLine:
    """One frequency of the model a peak may be.

    Parameters
    ----------
    kind : str
        ``"natural"``, ``"tooth"``, ``"shaft"``, ``"parametric"`` or ``"span transverse"``.
    label : str
        Which one (mode 2, tooth x1, span S1-S2 n=1 …).
    frequency : float
        f [Hz].
    """

    kind: str
    label: str
    frequency: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"kind": self.kind, "label": self.label, "frequency_hz": self.frequency}


def model_lines(analysis: Analysis, max_frequency: float | None = None) -> tuple[ModelLine, ...]:
    """The model's frequencies a measured peak is set against.

    Parameters
    ----------
    analysis : Analysis
        The analysed design (its modal stage).
    max_frequency : float | None
        Highest frequency the record shows [Hz] (its Nyquist frequency): the tooth-frequency
        harmonics are listed up to it (at most :data:`MAX_HARMONICS`); None: the analysis's
        own harmonics.

    Returns
    -------
    tuple of ModelLine
        Elastic natural frequencies (``"natural"``, mode k counted from 1 over the elastic
        modes), the working frequencies (:func:`chaindrive.dynamics.resonance.working_frequencies`)
        and the spans' transverse frequencies (running; none without span tensions).
    """
    dyn = analysis.dynamics
    lines: list[ModelLine] = []
    elastic = [float(f) for f, rigid in zip(dyn.modal.frequencies_hz, dyn.modal.rigid_body,
                                            strict=True) if not rigid]
    lines += [ModelLine("natural", f"mode {k}", f) for k, f in enumerate(elastic, start=1)]
    working = dyn.working
    drive = analysis.drive
    fz = analysis.kinematics.tooth_frequency
    if max_frequency is not None and drive.driver.speed is not None and fz > 0:
        harmonics = int(min(MAX_HARMONICS, max(1, math.floor(max_frequency / fz))))
        working = working_frequencies(drive.driver.speed, drive.driver.teeth,
                                      [s.teeth for s in drive.sprockets],
                                      [s.name for s in drive.sprockets], harmonics)
    lines += [ModelLine(w.kind, w.label, float(w.frequency)) for w in working]
    names = [f"{s.start_name}-{s.end_name}" for s in analysis.geometry.spans]
    st = dyn.span_transverse_hz
    for i in range(st.shape[0]):
        lines += [ModelLine("span transverse", f"span {names[i]} n={n + 1}", float(st[i, n]))
                  for n in range(st.shape[1]) if st[i, n] > 0]
    return tuple(lines)


def segment_length(samples: int) -> int:
    """Samples per Welch segment [-]: the largest power of two not above a quarter of the
    record (about seven averaged segments at half overlap), at least 64 and at most the
    record.

    Parameters
    ----------
    samples : int
        Length of the record [-].

    Returns
    -------
    int
    """
    return int(min(samples, max(64, 2 ** math.floor(math.log2(max(samples // 4, 1))))))


@dataclass(frozen=True, slots=True)
class Peak:
    """One peak of a spectrum and what it is.

    Parameters
    ----------
    frequency : float
        f [Hz] (refined by a parabola through the bin and its neighbours in dB).
    level_db : float
        Power spectral density at the peak [dB re 1 (signal unit)²/Hz].
    prominence_db : float
        Its prominence [dB].
    line : ModelLine | None
        The nearest model line within the tolerance (None: unexplained).
    deviation : float | None
        (f − f_line)/f_line [-].
    also : tuple of ModelLine
        Other lines within the tolerance.
    damping_ratio : float | None
        Half-power damping ratio ζ [-] (:func:`peak_damping_ratio`); None: not resolvable.
    damping_reason : str | None
        Why ζ is not given (None when it is).
    damping_bins : float | None
        Bins the half-power band spans in the spectrum ζ was read from [-].
    """

    frequency: float
    level_db: float
    prominence_db: float
    line: ModelLine | None
    deviation: float | None
    also: tuple[ModelLine, ...] = ()
    damping_ratio: float | None = None
    damping_reason: str | None = None
    damping_bins: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {
            "frequency_hz": self.frequency, "level_db": self.level_db,
            "prominence_db": self.prominence_db,
            "label": "unexplained" if self.line is None else self.line.label,
            "kind": "unexplained" if self.line is None else self.line.kind,
            "model_frequency_hz": None if self.line is None else self.line.frequency,
            "deviation_percent": None if self.deviation is None else 100.0 * self.deviation,
            "also_within_tolerance": [line.label for line in self.also],
            "damping_ratio_half_power": self.damping_ratio,
            "damping_ratio_half_power_bins": self.damping_bins,
            "damping_ratio_half_power_not_given": self.damping_reason,
        }


@shared_parameters
def line_tolerance(line: ModelLine, tolerance: float, resolution: float) -> float:
    """Half-width [Hz] of the match round a model line: max(``tolerance``·f, one bin) for a
    natural or span transverse frequency (the model's, uncertain), max(
    :data:`WORKING_TOLERANCE`·f, one bin) for a working frequency (known from the speed).

    Parameters
    ----------
    line : ModelLine
        The line.
    %(tolerance_resolution_returns)s
    float
        [Hz].
    """
    rel = WORKING_TOLERANCE if line.kind in WORKING_KINDS else tolerance
    return max(rel * line.frequency, resolution)


@shared_parameters
def label_peak(frequency: float, lines: tuple[ModelLine, ...], tolerance: float,
               resolution: float) -> tuple[ModelLine | None, float | None,
                                           tuple[ModelLine, ...]]:
    """The model line a peak at f is, by the rule of the module docstring
    (:func:`line_tolerance`).

    Parameters
    ----------
    frequency : float
        The peak's f [Hz].
    lines : tuple of ModelLine
        The model's lines.
    %(tolerance_resolution_returns)s
    line : ModelLine | None
        The nearest line within the tolerance, or None.
    deviation : float | None
        (f − f_line)/f_line [-].
    also : tuple of ModelLine
        The other lines within the tolerance, nearest first.
    """
    near = sorted(((abs(frequency - ln.frequency), ln) for ln in lines
                   if abs(frequency - ln.frequency) <= line_tolerance(ln, tolerance, resolution)),
                  key=lambda pair: pair[0])
    if not near:
        return None, None, ()
    best = near[0][1]
    return best, (frequency - best.frequency) / best.frequency, tuple(ln for _, ln in near[1:])


@dataclass(frozen=True, slots=True)
class SignalSpectrum:
    """One signal's spectrum and its labelled peaks.

    Parameters
    ----------
    name : str
        The signal (column).
    samples : int
        Its length [-].
    sample_rate : float
        f_s [Hz].
    segment : int
        Samples per Welch segment [-].
    frequencies : ndarray
        Frequencies of the spectrum [Hz].
    psd : ndarray
        Power spectral density [(signal unit)²/Hz].
    peaks : tuple of Peak
        The peaks, by frequency.
    """

    name: str
    samples: int
    sample_rate: float
    segment: int
    frequencies: NDArray[np.float64]
    psd: NDArray[np.float64]
    peaks: tuple[Peak, ...]

    @property
    def resolution(self) -> float:
        """One frequency bin f_s / segment [Hz]."""
        return self.sample_rate / self.segment

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the spectrum itself is left out; the figure shows it)."""
        return {"name": self.name, "samples": self.samples, "sample_rate_hz": self.sample_rate,
                "duration_s": self.samples / self.sample_rate, "segment_samples": self.segment,
                "resolution_hz": self.resolution, "peaks": [p.to_dict() for p in self.peaks]}


@shared_parameters
def signal_spectrum(values: NDArray[np.float64], sample_rate: float
                    ) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Welch spectrum of one signal (module docstring).

    %(params_samples_rate)s

    Returns
    -------
    frequencies : ndarray
        [Hz].
    psd : ndarray
        [(signal unit)²/Hz].
    segment : int
        Samples per segment [-].

    References
    ----------
    [Welch1967]; [Virtanen2020].
    """
    nper = segment_length(values.size)
    f, p = welch(values, fs=sample_rate, window="hann", nperseg=nper, noverlap=nper // 2,
                 detrend="constant", scaling="density")
    return np.asarray(f, dtype=float), np.asarray(p, dtype=float), nper


def spectral_peaks(frequencies: NDArray[np.float64], psd: NDArray[np.float64],
                   prominence_db: float) -> list[tuple[float, float, float]]:
    """Peaks of a spectrum with at least ``prominence_db`` of prominence (module docstring).

    Parameters
    ----------
    frequencies : ndarray
        [Hz], evenly spaced.
    psd : ndarray
        Power spectral density [(signal unit)²/Hz].
    prominence_db : float
        Least prominence [dB].

    Returns
    -------
    list of (frequency [Hz], level [dB], prominence [dB])
        At most :data:`MAX_PEAKS`, the most prominent, by frequency.
    """
    db = 10.0 * np.log10(np.maximum(psd, np.max(psd) * 1e-30 + 1e-300))
    idx, props = find_peaks(db, prominence=prominence_db)
    keep = [(int(i), float(pr)) for i, pr in zip(idx, props["prominences"], strict=True)
            if 2 <= i < db.size - 1]
    keep = sorted(keep, key=lambda t: -t[1])[:MAX_PEAKS]
    df = float(frequencies[1] - frequencies[0])
    out = []
    for i, pr in sorted(keep):
        a, b, c = db[i - 1], db[i], db[i + 1]
        denom = a - 2 * b + c
        shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
        out.append((float(frequencies[i] + shift * df), float(b - 0.25 * (a - c) * shift), pr))
    return out


@shared_parameters
def peak_damping_ratio(values: NDArray[np.float64], sample_rate: float, frequency: float
                       ) -> tuple[float | None, float | None, str | None]:
    """Half-power damping ratio of the peak of a signal at f_n, read from a Welch spectrum
    whose segment is fitted to the peak (module docstring).

    The first reading is taken from 64-sample segments (coarse: the window widens the peak,
    so ζ comes out high); while the band spans fewer than :data:`HALF_POWER_BINS` bins
    (at most :data:`_HALF_POWER_STEPS` times) the segment becomes the shortest power of two
    whose bin f_s/N is at most 2ζf_n/:data:`HALF_POWER_BINS` at the last reading (at least
    twice the last) and ζ is read again. The segment may not exceed the record divided by
    :data:`HALF_POWER_AVERAGES`. A Hann-windowed Welch spectrum suits a mode driven by
    broadband excitation; a single free decay is read with
    :func:`chaindrive.identification.damping.free_decay_damping_ratio` instead.

    %(params_samples_rate)s
    frequency : float
        The peak's f_n [Hz].

    Returns
    -------
    ratio : float | None
        ζ ≈ (f₂ − f₁)/(2 f_n) [-] ([Ewins2000, ch. 4]); None when not resolvable.
    bins : float | None
        Bins the half-power band spans in the last spectrum [-] (None: no band found).
    reason : str | None
        Why ζ is not given (None when it is).

    References
    ----------
    [Ewins2000, ch. 4]; [Welch1967]; [Harris1978].
    """
    longest = values.size // HALF_POWER_AVERAGES
    nper = min(64, longest)
    if nper < 16:
        return None, None, "record too short for a half-power reading"
    zeta: float | None = None
    bins: float | None = None
    for _ in range(_HALF_POWER_STEPS + 1):
        f, p = welch(values, fs=sample_rate, window="hann", nperseg=nper,
                     noverlap=nper // 2, detrend="constant", scaling="density")
        try:
            zeta = half_power_damping_ratio(np.asarray(f, dtype=float),
                                            np.asarray(p, dtype=float), frequency)
        except DesignError:
            return None, None, "the power does not fall to half on both sides of the peak"
        bins = 2.0 * zeta * frequency * nper / sample_rate
        if bins >= HALF_POWER_BINS:
            break
        need = max(2 * nper, 2 ** math.ceil(math.log2(HALF_POWER_BINS * sample_rate
                                                      / (2.0 * zeta * frequency))))
        if need > longest:
            seconds = need * HALF_POWER_AVERAGES / sample_rate
            return None, bins, (f"the half-power band spans {bins:.3g} bins of "
                                f"{sample_rate / nper:.3g} Hz; {HALF_POWER_BINS} are needed, "
                                f"in a record {HALF_POWER_AVERAGES} segments long ({seconds:.3g}"
                                " s at this ζ): a forced line, or a record too short")
        nper = need
    else:
        return None, bins, "the half-power band did not settle"
    return zeta, bins, None


@dataclass(frozen=True, slots=True)
class Identification:
    """A measured record matched to the model.

    Parameters
    ----------
    record : str
        The record's name.
    signals : tuple of SignalSpectrum
        Each signal's spectrum and peaks.
    lines : tuple of ModelLine
        The model's lines.
    tolerance : float
        Relative tolerance of a match [-].
    prominence_db : float
        Least prominence of a peak [dB].
    notes : tuple of str
        What the record cannot show (model lines above its Nyquist frequency).
    """

    record: str
    signals: tuple[SignalSpectrum, ...]
    lines: tuple[ModelLine, ...]
    tolerance: float
    prominence_db: float
    notes: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {"record": self.record, "tolerance_percent": 100.0 * self.tolerance,
                "prominence_db": self.prominence_db,
                "signals": [s.to_dict() for s in self.signals],
                "model_lines": [ln.to_dict() for ln in self.lines], "notes": list(self.notes)}


def identify(record: Record, lines: tuple[ModelLine, ...], *,
             tolerance: float = DEFAULT_TOLERANCE,
             prominence_db: float = DEFAULT_PROMINENCE_DB) -> Identification:
    """Spectrum, peaks and their labels for every signal of a record.

    Parameters
    ----------
    record : Record
        The measured record (:func:`chaindrive.io.record.read_record`).
    lines : tuple of ModelLine
        The model's lines (:func:`model_lines`).
    tolerance : float
        Relative tolerance of a match [-], in (0, 1).
    prominence_db : float
        Least prominence of a peak [dB], positive.

    Returns
    -------
    Identification

    Raises
    ------
    DesignError
        A tolerance or prominence out of range.

    References
    ----------
    [Welch1967]; [Virtanen2020]; [Ewins2000, ch. 4].
    """
    if not (0 < tolerance < 1):
        raise DesignError("--tolerance", f"must lie between 0 and 100 %, got "
                          f"{100 * tolerance!r} %")
    if not (math.isfinite(prominence_db) and prominence_db > 0):
        raise DesignError("--prominence", f"must be above 0 dB, got {prominence_db!r}")
    out = []
    nyquist = record.sample_rate / 2.0
    for name, values in record.signals.items():
        f, p, nper = signal_spectrum(values, record.sample_rate)
        df = record.sample_rate / nper
        peaks = []
        for fp, level, pr in spectral_peaks(f, p, prominence_db):
            line, dev, also = label_peak(fp, lines, tolerance, df)
            zeta, bins, why = peak_damping_ratio(values, record.sample_rate, fp)
            peaks.append(Peak(fp, level, pr, line, dev, also, zeta, why, bins))
        out.append(SignalSpectrum(name, int(values.size), record.sample_rate, nper, f, p,
                                  tuple(peaks)))
    above = [ln.label for ln in lines if ln.frequency >= nyquist]
    notes = ((f"above the Nyquist frequency {nyquist:g} Hz, not seen by this record: "
              + ", ".join(above)),) if above else ()
    return Identification(record.name, tuple(out), lines, tolerance, prominence_db, notes)
