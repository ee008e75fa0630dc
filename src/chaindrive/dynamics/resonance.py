"""Working frequencies, the resonance table and Campbell-diagram data.

[MultimassChainDrives, §3.2–3.3]: the disturbing frequencies of a contour are the shaft
rotation frequencies ω_i and the tooth (mesh) frequency ω_z = z_1 ω_1 = … = z_n ω_n with
its harmonics k ω_z; the natural frequencies must be kept away from them. The parametric
resonance of a span (tension pulsating at the tooth frequency, principal zone
f_z ≈ 2 f_transverse, :mod:`chaindrive.dynamics.transverse`) is checked too.

The offset of a working frequency from its nearest natural frequency is
(f_working − f_natural)/f_natural · 100 % (signed: negative when the working frequency lies
below the natural one); its absolute value is the detuning Δ ≥ 0, and every presenter (the
resonance tables, the warnings, the JSON document) shows Δ with the side, "below" or
"above". Δ is the value of the resonance check, not its margin: the check's margin
m = Δ/Δ_required − 1 (:attr:`chaindrive.checks.Check.margin_fraction`) is ≥ 0 when it
passes, like every margin of the package.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.transverse import span_transverse_frequencies
from chaindrive.errors import ChainDriveWarning, DesignError
from chaindrive.kinematics import mean_chain_speed, tooth_frequency
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.dynamics.modes import Modes


__all__ = ["CampbellData", "Resonance", "WorkingFrequency", "campbell_data",
           "resonance_table", "shaft_frequencies", "working_frequencies"]



@shared_parameters
def shaft_frequencies(driver_speed: ArrayLike, driver_teeth: int,
                      teeth: Sequence[int]) -> NDArray[np.float64]:
    """Rotation frequencies f_i = ω_1 z_1 / (2π z_i) [Hz] of every shaft (the same chain speed
    on every sprocket: ω_i = z_1 ω_1 / z_i).

    Parameters
    ----------
    driver_speed : array_like
        Driver speed ω_1 [rad/s] (a scalar or an array of S speeds).
    %(driver_teeth)s
    teeth : sequence of int
        Teeth z_i of every sprocket [-].

    Returns
    -------
    ndarray
        (..., n) f_i [Hz].
    """
    w = np.asarray(driver_speed, dtype=float)
    z = np.asarray(teeth, dtype=float)
    return np.asarray((w[..., None] * driver_teeth / z) / TWO_PI, dtype=np.float64)


@dataclass(frozen=True, slots=True)
class WorkingFrequency:
    """One disturbing frequency of the drive.

    Parameters
    ----------
    kind : str
        ``"shaft"``, ``"tooth"`` or ``"parametric"``.
    label : str
        What it is (sprocket, harmonic, span).
    frequency : float
        The frequency [Hz].
    harmonic : int
        Harmonic k of the tooth frequency [-] (1 for shafts).
    """

    kind: str
    label: str
    frequency: float
    harmonic: int = 1

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"kind": self.kind, "label": self.label, "frequency_hz": self.frequency,
                "harmonic": self.harmonic}


@shared_parameters
def working_frequencies(driver_speed: float, driver_teeth: int, teeth: Sequence[int],
                        names: Sequence[str] | None = None,
                        harmonics: int = 3) -> tuple[WorkingFrequency, ...]:
    """The shaft frequencies and the tooth frequency with harmonics k = 1…``harmonics``.

    Parameters
    ----------
    driver_speed : float
        Driver speed ω_1 [rad/s].
    %(driver_teeth)s
    teeth : sequence of int
        Teeth z_i of all sprockets [-].
    %(sprocket_names)s
    harmonics : int
        Harmonics of the tooth frequency [-], at least 1.

    Returns
    -------
    tuple of WorkingFrequency
        The shaft frequencies, then the tooth harmonics.

    Raises
    ------
    DesignError
        ``harmonics`` below 1.

    References
    ----------
    [MultimassChainDrives, §3.3].
    """
    if harmonics < 1:
        raise DesignError("harmonics", f"must be at least 1, got {harmonics!r}")
    names = list(names) if names is not None else [f"S{i + 1}" for i in range(len(teeth))]
    shafts = shaft_frequencies(driver_speed, driver_teeth, teeth)
    out = [WorkingFrequency("shaft", f"shaft {name}", float(f))
           for name, f in zip(names, shafts, strict=True)]
    fz = float(tooth_frequency(driver_teeth, driver_speed))
    out += [WorkingFrequency("tooth", f"tooth x{k}", k * fz, k) for k in range(1, harmonics + 1)]
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Resonance:
    """A row of the resonance table.

    Parameters
    ----------
    working : WorkingFrequency
        The working frequency.
    natural_frequency : float
        The nearest elastic natural frequency [Hz] (for a ``parametric`` row: 2 f_1 of the
        span).
    mode : int
        Its index in the modal result, or the span index for ``parametric`` [-].
    offset_percent : float
        (f_working − f_natural)/f_natural·100 [%], signed (negative below).
    """

    working: WorkingFrequency
    natural_frequency: float
    mode: int
    offset_percent: float

    @property
    def detuning_percent(self) -> float:
        """Δ = |f_working − f_natural|/f_natural·100 [%] ≥ 0."""
        return abs(self.offset_percent)

    @property
    def side(self) -> str:
        """Where the working frequency lies: "below" or "above" the natural one."""
        return "below" if self.offset_percent < 0 else "above"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: the detuning Δ ≥ 0 [%] and the side of the working frequency."""
        return {**self.working.to_dict(), "natural_frequency_hz": self.natural_frequency,
                "mode": self.mode, "detuning_percent": self.detuning_percent,
                "working_frequency_is": self.side}


def _nearest(f: float, natural: NDArray[np.float64]) -> tuple[int, float, float]:
    k = int(np.argmin(np.abs(natural - f)))
    fn = float(natural[k])
    return k, fn, (f - fn) / fn * 100.0  # offset [%], signed


def resonance_table(modal: Modes, working: Sequence[WorkingFrequency],
                    span_transverse_hz: ArrayLike | None = None,
                    tooth_hz: float | None = None,
                    span_names: Sequence[str] = ()) -> tuple[Resonance, ...]:
    """Nearest elastic natural frequency and the detuning from it of each working frequency,
    sorted by the detuning (most critical first).

    Parameters
    ----------
    modal : Modes
        The modes (rigid-body modes are skipped).
    working : sequence of WorkingFrequency
        The disturbing frequencies.
    span_transverse_hz : array_like or None
        (spans,) first transverse frequency of every span [Hz]; with ``tooth_hz``, each span
        with f_1 > 0 adds one ``parametric`` row comparing the tooth frequency with the
        principal parametric resonance 2 f_1.
    tooth_hz : float or None
        The tooth frequency [Hz].
    span_names : sequence of str
        Labels of the spans for the parametric rows.

    Returns
    -------
    tuple of Resonance
        The rows.

    References
    ----------
    [MultimassChainDrives, §3.2–3.3]; [Bolotin1964, ch. 1] (the parametric zone).
    """
    elastic_idx = np.flatnonzero(~modal.rigid_body)
    natural = modal.frequencies_hz[elastic_idx]
    rows: list[Resonance] = []
    if natural.size:
        for w in working:
            k, fn, offset = _nearest(w.frequency, natural)
            rows.append(Resonance(w, fn, int(elastic_idx[k]), offset))
    if span_transverse_hz is not None and tooth_hz is not None:
        for i, f1 in enumerate(np.asarray(span_transverse_hz, dtype=float).ravel()):
            if f1 > 0:
                span = span_names[i] if i < len(span_names) else str(i)
                w = WorkingFrequency("parametric", f"tooth vs 2·f1 of span {span}",
                                     float(tooth_hz))
                rows.append(Resonance(w, 2.0 * f1, i, (tooth_hz - 2.0 * f1) / (2.0 * f1) * 100))
    return tuple(sorted(rows, key=lambda r: r.detuning_percent))


@dataclass(frozen=True, slots=True, eq=False)
class CampbellData:
    """Data of a Campbell diagram over the driver speed.

    Parameters
    ----------
    speeds_rpm : ndarray
        (S,) driver speeds [rpm].
    natural_frequencies_hz : ndarray
        (S, modes) elastic frequencies [Hz] (independent of speed in the linear model).
    span_transverse_hz : ndarray
        (S, spans) first transverse frequency of every span [Hz] (depends on the chain speed);
        the parametric zones lie at twice these.
    excitation_hz : dict of str to ndarray
        Name → (S,) excitation line [Hz] (shafts, tooth harmonics).
    crossings : tuple of tuple
        (excitation, natural mode index, speed [rpm]) where a line crosses a natural
        frequency (linear interpolation between grid speeds); the mode index is the column of
        ``natural_frequencies_hz`` (elastic modes from 0), −1 for a parametric zone, whose
        excitation is ``"parametric span <i>"`` (spans from 0).
    rigid_modes : int
        Rigid-body modes before the elastic ones (the JSON numbers the modes as the
        resonance table does: the first elastic mode is ``rigid_modes``).
    span_names : tuple of str
        Names of the spans ("S1→S2", …; the JSON names a parametric zone's span by it).
    """

    speeds_rpm: NDArray[np.float64]
    natural_frequencies_hz: NDArray[np.float64]
    span_transverse_hz: NDArray[np.float64]
    excitation_hz: dict[str, NDArray[np.float64]]
    crossings: tuple[tuple[str, int, float], ...]
    rigid_modes: int = 1
    span_names: tuple[str, ...] = ()

    def _excitation(self, e: str, m: int) -> str:
        i = e.rsplit(" ", 1)[-1]
        if m >= 0 or not i.isdigit() or int(i) >= len(self.span_names):
            return e
        return f"parametric span {self.span_names[int(i)]}"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: modes numbered as the resonance table (rigid-body modes first,
        from 0), a parametric zone with mode null and its span by name."""
        return {
            "speeds_rpm": self.speeds_rpm.tolist(),
            "natural_frequencies_hz": self.natural_frequencies_hz.tolist(),
            "span_transverse_frequencies_hz": self.span_transverse_hz.tolist(),
            "excitation_hz": {k: v.tolist() for k, v in self.excitation_hz.items()},
            "crossings": [{"excitation": self._excitation(e, m),
                           "mode": m + self.rigid_modes if m >= 0 else None, "speed_rpm": s}
                          for e, m, s in self.crossings],
        }


def _crossings(speeds: NDArray[np.float64], line: NDArray[np.float64],
               natural: NDArray[np.float64]) -> list[tuple[int, float]]:
    """(column j, speed) where ``line`` crosses column j of ``natural`` (S, E), by linear
    interpolation between the speeds; by column, then by speed."""
    g = (np.reshape(line, (-1, 1)) - natural).T                         # (E, S)
    j, i = np.nonzero(np.sign(g[:, :-1]) * np.sign(g[:, 1:]) <= 0)
    a, b = g[j, i], g[j, i + 1]
    keep = a != b
    j, i, a, b = j[keep], i[keep], a[keep], b[keep]
    s = speeds[i] - a * (speeds[i + 1] - speeds[i]) / (b - a)
    return list(zip(j.tolist(), s.tolist(), strict=True))


@shared_parameters
def campbell_data(modal: Modes, driver_speeds: ArrayLike, driver_teeth: int,
                  teeth: Sequence[int], names: Sequence[str] | None = None, harmonics: int = 3,
                  span_lengths: ArrayLike | None = None, span_tensions: ArrayLike | None = None,
                  mass_per_length: float | None = None, pitch: float | None = None,
                  ) -> CampbellData:
    """Natural frequencies and excitation lines over a range of driver speeds.

    With the span data the spans' first transverse frequencies at the chain speed
    v = z_1 p ω_1 / 2π are added and compared with the tooth frequency for parametric
    crossings (f_z = 2 f_1).

    Parameters
    ----------
    modal : Modes
        The modes.
    driver_speeds : array_like
        (S,) driver speeds ω_1 [rad/s].
    %(driver_teeth)s
    teeth : sequence of int
        Teeth z_i of every sprocket [-].
    %(sprocket_names)s
    %(harmonics)s
    span_lengths : array_like or None
        (spans,) span lengths [m].
    span_tensions : array_like or None
        (spans,) span tensions [N].
    mass_per_length : float or None
        Chain mass per unit length q [kg/m].
    pitch : float or None
        Chain pitch p [m].

    Returns
    -------
    CampbellData
        The lines and their crossings.

    References
    ----------
    [Mote1965] (the travelling span); [Bolotin1964, ch. 1] (the parametric zone).
    """

    w = np.atleast_1d(np.asarray(driver_speeds, dtype=float))
    names = list(names) if names is not None else [f"S{i + 1}" for i in range(len(teeth))]
    natural = np.broadcast_to(modal.elastic_frequencies_hz, (w.size, modal.elastic_frequencies_hz.size))
    lines = {f"shaft {n}": col for n, col in zip(names, shaft_frequencies(w, driver_teeth, teeth).T,
                                                 strict=True)}
    fz = np.asarray(tooth_frequency(driver_teeth, w))
    lines.update({f"tooth x{k}": k * fz for k in range(1, harmonics + 1)})
    crossings = [(name, j, s) for name, line in lines.items()
                 for j, s in _crossings(w, line, natural)]
    transverse = np.zeros((w.size, 0))
    if span_lengths is not None and span_tensions is not None and mass_per_length and pitch:
        v = np.asarray(mean_chain_speed(pitch, driver_teeth, w))
        transverse = span_transverse_frequencies(np.asarray(span_lengths)[None, :],
                                                 np.asarray(span_tensions)[None, :],
                                                 mass_per_length, v[:, None], modes=1)[..., 0]
        crossings += [(f"parametric span {i}", -1, s)
                      for i in range(transverse.shape[1])
                      for _, s in _crossings(w, fz, 2.0 * transverse[:, i:i + 1])]
    rpm = w * 60.0 / TWO_PI
    crossings = [(e, m, float(s * 60.0 / TWO_PI)) for e, m, s in crossings]
    spans = tuple(f"{a}→{names[(i + 1) % len(names)]}" for i, a in enumerate(names))
    rigid = int(np.asarray(modal.frequencies_hz).size - modal.elastic_frequencies_hz.size)
    return CampbellData(rpm, np.array(natural), transverse, lines, tuple(crossings), rigid, spans)


#: Half-width of the band round a natural frequency that a working frequency should stay
#: out of ([MultimassChainDrives, §3.2] "detune the spectrum from the working frequencies"; the ±10 %
#: band is the usual rotordynamics separation margin, e.g. API 684 §2.8 asks 10–26 %).
RESONANCE_BAND_PERCENT = 10.0


def resonance_warnings(rows: Sequence[Resonance],
                       band_percent: float = RESONANCE_BAND_PERCENT) -> list[ChainDriveWarning]:
    """One warning per working frequency within ±band of its nearest natural frequency,
    worded as the resonance table: the detuning Δ ≥ 0 and the side (module docstring)."""
    out = []
    for r in rows:
        parametric = r.working.kind == "parametric"
        if r.detuning_percent < band_percent:
            natural = "twice the span's transverse frequency" if parametric else \
                "the natural frequency"
            out.append(ChainDriveWarning(
                "dynamics.parametric-resonance" if parametric else "dynamics.resonance",
                "dynamics",
                f"{'parametric resonance' if parametric else 'resonance'}: {r.working.label} at "
                f"{r.working.frequency:.1f} Hz is {r.detuning_percent:.1f} % {r.side} "
                f"{natural} {r.natural_frequency:.1f} Hz (required detuning ≥ {band_percent:g} %)"))
    return out
