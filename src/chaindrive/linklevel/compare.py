"""The link-level run of an analysis beside the whole-drive (ring) model: the bounded
simulated time of a run asked for by a user, and the table of the summary quantities both
models give (span dynamic loads, K_D, start-up peaks, first natural frequency), in SI.

The definitions are the ring model's [MultimassChainDrives, §3.3, §3.6]: F₂,i the peak
dynamic load of span i in steady motion, F_D their root mean square, K_D = 1 + F_D/F_t,
F₁max the largest span force of the start-up from rest. The link-level run of an analysis
is one start-up from rest (:func:`chaindrive.linklevel.simulate`): its start-up peaks are
over the whole run, its steady quantities over the closing half of it
(:class:`~chaindrive.linklevel.result.LinkLevelResult`), which is steady motion only once
the drive has settled by then (the ``settled`` flag of :func:`model_comparison`).

**Like with like** (:func:`mode_agreement`, :func:`span_load_agreement`; docs/linklevel.md
§6). The two models share the chain's link stiffness, the teeth's contact compliance, the
sprockets' inertias and the spans' sag (the whole-drive model through the Dischinger–Ernst
factor of each span's tension [Ernst1965], the link-level through the tension's geometric
stiffness of its links [Irvine1981, ch. 2]); the whole-drive model adds the motor's rotor
and the trains, the link-level model the spans' transverse motion and the engagement
impacts. The natural frequencies are compared at one tension state: the link-level model's
static state (at rest at T₀, or loaded), whose span tensions the whole-drive model takes for
its sag factors — its only dependence on the tensions, so it is evaluated at the other's
state exactly — and on the same masses (the drive without motor and trains, as the
link-level model turns its sprockets alone). The link-level modes are split by where their
kinetic energy is (:mod:`chaindrive.linklevel.modes`): the first of the longitudinal–torsional
family is set against the whole-drive model's first, by frequency and by the modal assurance
criterion MAC = |aᵀb|²/(aᵀa·bᵀb) of the sprockets' turns [Allemang2003]; the transverse modes
against the string frequency of their span at its tension [Mote1965], which sag leaves
alone for the antisymmetric (even) ones [Irvine1981, ch. 2].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.checks import LINK_LEVEL, WHOLE_DRIVE
from chaindrive.errors import DesignError, Quantities
from chaindrive.io.limits import Range

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.modes import LinearModes
    from chaindrive.linklevel.result import LinkLevelResult
    from chaindrive.model import Drive

__all__ = ["DURATION", "FREQUENCY_TOLERANCE", "LINK_LEVEL", "LOAD_TOLERANCE", "MODEL_NAMES",
           "SETTLED_SPEED", "WHOLE_DRIVE", "GoverningLoads", "ModeAgreement", "ModePair",
           "ModelComparison", "SpanLoadAgreement", "TransverseMode", "checked_duration",
           "governing_loads", "mac", "mode_agreement", "model_comparison",
           "span_load_agreement"]

#: Simulated time of a link-level run asked for from the command line, the report or the
#: page [s]. Below 1 ms no tooth period of a practical drive fits (f_z ≤ 1 kHz); the
#: histories are kept in memory, 0.04 GB per simulated second on the 24-sprocket example
#: (744 rollers recorded at 1.1 kHz, five arrays of 8 bytes per roller and sample; measured),
#: and the run takes 3.5 s of wall time per simulated second there (docs/linklevel.md §3):
#: 10 s bounds both, and a start-up settles within one or two seconds.
DURATION = Range(1e-3, 10.0, "at least a tooth period; at most 10 s, as the histories are "
                 "kept in memory (0.04 GB per simulated second on 24 sprockets)")
#: The closing half of a run counts as steady motion when the driver's mean speed over it is
#: within this fraction of the nominal speed.
SETTLED_SPEED = 0.02
#: Where the two models share their physics their first natural frequencies along the chain
#: agree within this fraction (the project's requirement; docs/linklevel.md §6).
FREQUENCY_TOLERANCE = 0.05
#: ... and their steady span loads within this fraction.
LOAD_TOLERANCE = 0.15
#: Whole-drive modes paired with link-level ones (the lowest elastic ones).
PAIRED_MODES = 3
#: Transverse link-level modes set against the string (the lowest ones).
STRING_MODES = 6
#: The row of :class:`ModelComparison` with both models' first frequency along the chain at
#: one tension state (:func:`mode_agreement`).
SAME_STATE_F1 = ("first natural frequency along the chain, both models at the link-level's "
                 "static state (its counterpart by MAC)")
#: Two modes have the same shape on the sprockets' turns when their MAC is at least this.
SAME_SHAPE = 0.8
#: The spans' transverse motion takes part in a mode along the chain when its link-level
#: form holds this much more of its strain energy in the tension than the whole-drive
#: model's in its sag factor [-] (an explanation's threshold; it decides no check).
SPAN_COUPLING = 0.1


def checked_duration(value: float, field: str = "link_duration_s") -> float:
    """The simulated time ``value`` [s] of a link-level run when it lies in
    :data:`DURATION`, else a :class:`~chaindrive.errors.DesignError` naming ``field``.

    Parameters
    ----------
    value : float
        Simulated time [s].
    field : str
        The name of the input, for the message (``"--duration"`` on the command line).

    Returns
    -------
    float
        ``value`` [s].
    """
    if not DURATION.contains(value):
        raise DesignError(field, f"{value:g} s is outside {DURATION.low:g} s to "
                          f"{DURATION.high:g} s ({DURATION.reason})")
    return float(value)


Row = tuple[str, float | None, float | None, str]


@dataclass(frozen=True, slots=True)
class ModelComparison:
    """The summary quantities of the whole-drive (ring) model and of the link-level run.

    Parameters
    ----------
    rows : tuple of Row
        (quantity, whole drive, link level, unit) in SI, None where a model does not give
        the quantity.
    settled : bool
        True when the driver's mean speed over the link-level run's closing half is within
        :data:`SETTLED_SPEED` of the nominal (its steady quantities are then those of steady
        motion).
    steady_from_s : float
        Where that closing half starts [s].
    duration_s : float
        The run's duration [s].
    modes : ModeAgreement or None
        Both models' first frequencies along the chain at one tension state
        (:func:`mode_agreement`; None: not computed).
    """

    rows: tuple[Row, ...]
    settled: bool
    steady_from_s: float
    duration_s: float
    modes: ModeAgreement | None = None

    @property
    def governing(self) -> tuple[str | None, ...]:
        """Per row, the model whose value governs (:func:`governing_model`; the row of the
        two models' first frequencies at one state: the verdict of :attr:`modes`)."""
        return tuple(self.modes.verdict[0] if self.modes is not None and row[0] == SAME_STATE_F1
                     else governing_model(row) for row in self.rows)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the rows as records (with the governing model, ``"whole_drive"``,
        ``"link_level"`` or null) and the run's window (SI, unit in the keys)."""
        return {"rows": [{"quantity": q, "whole_drive": w, "link_level": k, "unit": u,
                          "governing": g}
                         for (q, w, k, u), g in zip(self.rows, self.governing, strict=True)],
                "settled": self.settled, "steady_from_s": self.steady_from_s,
                "duration_s": self.duration_s,
                "mode_agreement": None if self.modes is None else self.modes.to_dict()}


def governing_model(row: Row) -> str | None:
    """The model whose value governs a row: for a load or K_D (unit N or 1) the larger of
    the two ("whole_drive" or "link_level"; the one given when the other is absent); None
    for a natural frequency (not a load: docs/linklevel.md §6 says which model is right
    there) or a row neither model gives.

    Parameters
    ----------
    row : Row
        (quantity, whole drive, link level, unit).

    Returns
    -------
    str or None
        ``"whole_drive"``, ``"link_level"`` or None.
    """
    _, ring, link, unit = row
    if unit not in ("N", "1") or (ring is None and link is None):
        return None
    if link is None or (ring is not None and ring >= link):
        return "whole_drive"
    return "link_level"


def _values(values: NDArray[np.float64] | None, n: int) -> list[float | None]:
    """Per-span values as floats (None for every span when absent)."""
    return [None] * n if values is None else [float(v) for v in values]


def model_comparison(result: LinkLevelResult, *, nominal_speed: float,
                     ring_span_dynamic_load: NDArray[np.float64] | None,
                     ring_dynamic_load_rms: float | None, ring_kd: float | None,
                     ring_startup_peak: NDArray[np.float64] | None,
                     first_frequency_hz: float | None,
                     link_first_frequency_hz: float | None = None,
                     modes: ModeAgreement | None = None) -> ModelComparison:
    """Rows of the quantities both models give, the ring model's beside the link-level's.

    Parameters
    ----------
    result : LinkLevelResult
        The link-level start-up from rest.
    nominal_speed : float
        The driver's nominal speed ω₁ [rad/s] (for the ``settled`` flag).
    ring_span_dynamic_load : ndarray | None
        F₂,i of the ring's steady response [N] per span (None without it).
    ring_dynamic_load_rms : float | None
        F_D = √(Σ F₂,i²/n) of the ring [N].
    ring_kd : float | None
        K_D = 1 + F_D/F_t of the ring [–].
    ring_startup_peak : ndarray | None
        F₁max,i of the ring's start-up [N] per span (None without a start-up).
    first_frequency_hz : float | None
        The first elastic natural frequency of the analysis's whole-drive model [Hz].
    link_first_frequency_hz : float | None
        The link-level model's first mode along the chain from its linearisation about the
        static state [Hz] (:func:`chaindrive.linklevel.modes.linear_modes`,
        docs/linklevel.md §6; None: not computed).
    modes : ModeAgreement or None
        The two models' first frequencies along the chain at one tension state, with the
        link-level modes' classification (:func:`mode_agreement`; None: not computed).

    Returns
    -------
    ModelComparison
        The rows; :attr:`ModelComparison.governing` names the governing model of each.

    References
    ----------
    [MultimassChainDrives, §3.3, §3.6] (F₂, F_D, K_D, F₁max).
    """
    spans = result.span_names
    n = len(spans)
    link_fd = result.span_dynamic_load
    link_peak = result.peak_span_force
    impacts = result.impacts[:, 3]
    rows: list[Row] = [
        ("coefficient of dynamics K_D", ring_kd,
         None if (kd := result.coefficient_of_dynamics) is None else float(kd), "1"),
        ("dynamic load F_D (RMS over the spans)", ring_dynamic_load_rms,
         float(np.sqrt(np.mean(link_fd**2))), "N")]
    rows += [(f"steady dynamic load F₂ of span {s}", w, float(k), "N")
             for s, w, k in zip(spans, _values(ring_span_dynamic_load, n), link_fd,
                                strict=True)]
    rows += [(f"start-up peak F₁max of span {s}", w, float(k), "N")
             for s, w, k in zip(spans, _values(ring_startup_peak, n), link_peak, strict=True)]
    rows += [("largest start-up span force F₁max",
              None if ring_startup_peak is None else float(np.max(ring_startup_peak)),
              float(link_peak.max()), "N"),
             ("first natural frequency", first_frequency_hz, link_first_frequency_hz, "Hz"),
             ("largest roller–tooth impact force", None,
              float(impacts.max()) if impacts.size else None, "N")]
    if modes is not None:
        c = modes.counterpart
        rows.append((SAME_STATE_F1, _num(modes.whole_drive_hz),
                     None if c is None else c.link_level_hz, "Hz"))
    late = result.times >= result.steady_from
    speed = float(np.mean(np.abs(result.sprocket_speeds[late, result.model.driver])))
    settled = math.isfinite(speed) and abs(speed / nominal_speed - 1.0) <= SETTLED_SPEED
    return ModelComparison(tuple(rows), settled, float(result.steady_from),
                           float(result.times[-1]), modes)


#: How a note names each model.
MODEL_NAMES = {WHOLE_DRIVE: "whole-drive model", LINK_LEVEL: "link-level model"}


@dataclass(frozen=True, slots=True)
class GoverningLoads:
    """The span loads the dynamic checks take when the link-level model was run beside the
    whole-drive model: of each span's load the larger (docs/linklevel.md §6), unless the
    link-level's is not comparable (then the whole-drive model's, and the reason).

    Parameters
    ----------
    startup_peak : ndarray | None
        (n,) F₁max,i of the start-up from rest [N] the checks take (None: the whole-drive
        model ran no start-up).
    startup_models : tuple of str
        (n,) per span the model it comes from (:data:`WHOLE_DRIVE` or :data:`LINK_LEVEL`).
    startup_link : ndarray
        (n,) the link-level run's F₁max,i [N] (for the notes).
    startup_ring : ndarray | None
        (n,) the whole-drive model's F₁max,i [N].
    startup_reason : str
        Why the link-level start-up peaks are not taken ("" when they are comparable).
    steady_dynamic : ndarray | None
        (n,) F₂,i of steady motion [N] the checks take (None: no steady response).
    steady_models : tuple of str
        (n,) per span the model it comes from.
    steady_link : ndarray
        (n,) the link-level run's F₂,i over its closing half [N].
    steady_ring : ndarray | None
        (n,) the whole-drive model's F₂,i [N].
    steady_reason : str
        Why the link-level steady loads are not taken ("" when they are comparable).
    span_names : tuple of str
        (n,) the spans ("S1-S2").
    """

    startup_peak: NDArray[np.float64] | None
    startup_models: tuple[str, ...]
    startup_link: NDArray[np.float64]
    startup_ring: NDArray[np.float64] | None
    startup_reason: str
    steady_dynamic: NDArray[np.float64] | None
    steady_models: tuple[str, ...]
    steady_link: NDArray[np.float64]
    steady_ring: NDArray[np.float64] | None
    steady_reason: str
    span_names: tuple[str, ...]

    def largest_startup(self) -> tuple[float, str] | None:
        """(the largest F₁max [N] the checks take, the model it comes from); None without a
        whole-drive start-up."""
        if self.startup_peak is None:
            return None
        i = int(np.argmax(self.startup_peak))
        return float(self.startup_peak[i]), self.startup_models[i]

    def startup_note(self, q: Quantities) -> tuple[str, str]:
        """(governing model, the note's sentence) of a check on the start-up's largest span
        force (k₁, fatigue in start-up); ``q`` records the note's forces.

        Parameters
        ----------
        q : Quantities
            The note's numbers with units (:class:`chaindrive.errors.Quantities`).

        Returns
        -------
        tuple of str
            The governing model and the sentence saying which and why.
        """
        assert self.startup_ring is not None  # a check on the start-up has one
        ring, link = float(np.max(self.startup_ring)), float(np.max(self.startup_link))
        return _said(WHOLE_DRIVE if self.startup_reason or ring >= link else LINK_LEVEL,
                     "largest start-up span force", ring, link, self.startup_reason, q)

    def steady_note(self, span: int, q: Quantities) -> tuple[str, str]:
        """(governing model, the note's sentence) of a check on the steady dynamic load of
        span ``span`` (k₂, k₂ with disturbances, fatigue in steady running).

        Parameters
        ----------
        span : int
            The span whose load decides the check [-].
        q : Quantities
            The note's numbers with units.

        Returns
        -------
        tuple of str
            The governing model and the sentence saying which and why.
        """
        assert self.steady_ring is not None
        return _said(self.steady_models[span], f"steady dynamic load of span {self.span_names[span]}",
                     float(self.steady_ring[span]), float(self.steady_link[span]),
                     self.steady_reason, q)


def _said(model: str, what: str, ring: float, link: float, reason: str,
          q: Quantities) -> tuple[str, str]:
    """(model, sentence): which model's ``what`` the check takes, both values, and
    ``reason`` when the link-level's is not comparable."""
    if reason:
        return WHOLE_DRIVE, (f"the whole-drive model's {what} {q(ring, 'force')} governs: the "
                             f"link-level model's ({q(link, 'force')}) is not comparable, "
                             f"{reason}")
    other = LINK_LEVEL if model == WHOLE_DRIVE else WHOLE_DRIVE
    mine, theirs = (ring, link) if model == WHOLE_DRIVE else (link, ring)
    return model, (f"the {MODEL_NAMES[model]}'s {what} {q(mine, 'force')} governs, the "
                   f"larger of the two models' ({MODEL_NAMES[other]} {q(theirs, 'force')})")


def governing_loads(result: LinkLevelResult, *, settled: bool,
                    ring_span_dynamic_load: NDArray[np.float64] | None,
                    ring_startup_peak: NDArray[np.float64] | None,
                    trains: Sequence[str]) -> GoverningLoads:
    """The span loads the dynamic checks take with both models run: per span the larger of
    the whole-drive model's and the link-level run's, where the link-level's is comparable
    (docs/linklevel.md §6, "Which model governs a check").

    The link-level loads are not comparable, and the whole-drive model's are kept, when the
    whole-drive model carries torsional trains (motor, gear stages, couplings, machines) the
    link-level model leaves out (its sprockets turn alone: a drive without its machines);
    its steady loads besides when the run had not settled by its closing half (they still
    hold the start-up).

    Parameters
    ----------
    result : LinkLevelResult
        The link-level start-up from rest, its spans in the order of the whole-drive model's.
    settled : bool
        The run's closing half is steady motion (:attr:`ModelComparison.settled`).
    ring_span_dynamic_load : ndarray | None
        F₂,i of the whole-drive model's steady response [N] (None: none).
    ring_startup_peak : ndarray | None
        F₁max,i of the whole-drive model's start-up [N] (None: none).
    trains : sequence of str
        The sprockets that carry a train in the whole-drive model.

    Returns
    -------
    GoverningLoads
        The loads the checks take, the model of each and the reasons.
    """
    why_trains = (f"as its sprockets {', '.join(trains)} turn without the trains (motor, "
                  "gear stages, couplings, machines) the whole-drive model gives them"
                  if trains else "")
    startup_reason = why_trains
    steady_reason = why_trains or ("" if settled else
                                   "as the driver was not at its nominal speed over the "
                                   "closing half of the run (its loads still hold the "
                                   "start-up)")
    link_peak = np.asarray(result.peak_span_force, dtype=float)
    link_fd = np.asarray(result.span_dynamic_load, dtype=float)
    peak, peak_models = _larger(ring_startup_peak, link_peak, startup_reason)
    fd, fd_models = _larger(ring_span_dynamic_load, link_fd, steady_reason)
    return GoverningLoads(
        peak, peak_models, link_peak,
        None if ring_startup_peak is None else np.asarray(ring_startup_peak, dtype=float),
        startup_reason, fd, fd_models, link_fd,
        None if ring_span_dynamic_load is None else np.asarray(ring_span_dynamic_load,
                                                                dtype=float),
        steady_reason, tuple(result.span_names))


def _larger(ring: NDArray[np.float64] | None, link: NDArray[np.float64], reason: str
            ) -> tuple[NDArray[np.float64] | None, tuple[str, ...]]:
    """Per span the larger load and its model; the whole-drive model's when ``reason``
    says the link-level's is not comparable; (None, ()) without the whole-drive's."""
    if ring is None:
        return None, ()
    ring = np.asarray(ring, dtype=float)
    if ring.shape != link.shape:
        raise ValueError(f"{ring.size} spans of the whole-drive model against {link.size} of "
                         "the link-level run")
    if reason:
        return ring.copy(), (WHOLE_DRIVE,) * ring.size
    return np.maximum(ring, link), tuple(WHOLE_DRIVE if r >= k else LINK_LEVEL
                                         for r, k in zip(ring, link, strict=True))


# --------------------------------------------------------------------------- like with like
def mac(a: NDArray[np.float64], b: NDArray[np.float64]) -> float:
    """Modal assurance criterion MAC = |aᵀb|²/(aᵀa · bᵀb) of two mode shapes [-]
    (1: the same shape up to scale; 0: orthogonal; nan when either is zero).

    Parameters
    ----------
    a, b : ndarray
        (n,) the two shapes on the same coordinates [any unit, the same for both].

    Returns
    -------
    float
        MAC in [0, 1].

    References
    ----------
    [Allemang2003] (the modal assurance criterion).
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    den = float(a @ a) * float(b @ b)
    return float(a @ b) ** 2 / den if den > 0.0 else math.nan


@dataclass(frozen=True, slots=True)
class ModePair:
    """A whole-drive mode and the link-level mode of the longitudinal–torsional family that
    resembles it most on the sprockets' turns.

    Parameters
    ----------
    whole_drive_hz : float
        The whole-drive mode's frequency [Hz].
    link_level_hz : float or None
        The link-level mode's [Hz] (None: none in the band).
    mac : float or None
        Their MAC on the sprockets' turns [-].
    """

    whole_drive_hz: float
    link_level_hz: float | None
    mac: float | None


@dataclass(frozen=True, slots=True)
class TransverseMode:
    """A transverse link-level mode beside the string frequency of its span.

    Parameters
    ----------
    frequency_hz : float
        The link-level mode [Hz].
    span : str
        The span holding most of its motion ("S1-S2").
    half_waves : int
        Its half-waves n along the span [-].
    string_hz : float
        n/(2L)·√(T/q) of the span at its static tension [Hz] [Mote1965].
    """

    frequency_hz: float
    span: str
    half_waves: int
    string_hz: float

    @property
    def ratio(self) -> float:
        """frequency / string frequency [-] (sag raises the odd n; nan without a string)."""
        return self.frequency_hz / self.string_hz if self.string_hz > 0 else math.nan


@dataclass(frozen=True, slots=True)
class ModeAgreement:
    """The first natural frequency along the chain of both models at one tension state
    (module docstring).

    Parameters
    ----------
    loaded : bool
        The state: loaded (True) or at rest at T₀ (False).
    span_tensions_n : tuple of float
        The link-level static state's span tensions [N], the whole-drive model's too.
    whole_drive_hz : float
        The first elastic frequency of the whole-drive model at those tensions, on the
        link-level model's masses (no motor, no trains) [Hz].
    link_level_hz : float or None
        The link-level's first mode along the chain (the first of its longitudinal–torsional
        family by kinetic energy, seat modes included) [Hz].
    first_mac : float or None
        The MAC of those two on the sprockets' turns [-].
    below : int
        Link-level modes below ``link_level_hz`` (all transverse) [-].
    link_strain : tuple of float
        The link-level's first mode along the chain: its strain energy in (links, tension,
        contacts) [-].
    whole_strain : tuple of float
        The whole-drive model's first mode: its strain energy in (links, sag, wraps), each
        span's share split by its sag factor s (the links s, the sag 1 − s of the span's
        compliance) [-].
    pairs : tuple of ModePair
        The lowest :data:`PAIRED_MODES` whole-drive modes, each with the link-level mode
        along the chain of largest MAC within half to twice its frequency; the first is the
        whole-drive f₁'s counterpart.
    transverse : tuple of TransverseMode
        The lowest :data:`STRING_MODES` transverse link-level modes against their spans'
        strings.
    counterpart_strain : tuple of float
        The counterpart's strain energy in (links, tension, contacts) [-].
    first_seat_hz : float or None
        The link-level's first seat mode (along the chain, held by the contacts) [Hz].
    lowest_string_hz : float
        The lowest first string frequency of the spans at their tensions [Hz].
    chain_mass_ratio : float
        The chain's mass over the sum of the sprockets' reduced masses J/R² [-].
    """

    loaded: bool
    span_tensions_n: tuple[float, ...]
    whole_drive_hz: float
    link_level_hz: float | None
    first_mac: float | None
    below: int
    link_strain: tuple[float, ...]
    whole_strain: tuple[float, ...]
    pairs: tuple[ModePair, ...]
    transverse: tuple[TransverseMode, ...]
    counterpart_strain: tuple[float, ...]
    first_seat_hz: float | None
    lowest_string_hz: float
    chain_mass_ratio: float

    @property
    def counterpart(self) -> ModePair | None:
        """The whole-drive f₁ and its link-level counterpart (largest MAC), or None."""
        return self.pairs[0] if self.pairs else None

    @property
    def deviation(self) -> float | None:
        """counterpart / whole-drive f₁ − 1 [-] (None: no counterpart)."""
        c = self.counterpart
        if c is None or c.link_level_hz is None or not c.whole_drive_hz > 0:
            return None
        return c.link_level_hz / c.whole_drive_hz - 1.0

    @property
    def agrees(self) -> bool:
        """The whole-drive f₁ has a counterpart of its shape (MAC ≥ :data:`SAME_SHAPE`)
        within :data:`FREQUENCY_TOLERANCE` of it."""
        d, c = self.deviation, self.counterpart
        return (d is not None and c is not None and c.mac is not None
                and c.mac >= SAME_SHAPE and abs(d) <= FREQUENCY_TOLERANCE)

    @property
    def verdict(self) -> tuple[str, str]:
        """(the model whose first frequency along the chain is right, why), the why one of
        ``"shared"`` (they agree: the whole-drive model's f₁, which its checks take,
        stands), ``"sag"`` (the whole-drive f₁ lies above the spans' first transverse
        frequency and holds most of its strain energy in its spans' static sag factor, or
        its link-level counterpart holds :data:`SPAN_COUPLING` more of its own in the
        tension: there the spans' transverse motion, with its mass, takes part
        [Starossek1991], which the static factor cannot carry: the link-level is right),
        ``"seats"`` (its counterpart lies above the link-level's first seat mode: the
        wrapped chain rides on the seats the whole-drive model's wrap spring stiffens) or
        ``"unexplained"`` (docs/linklevel.md §6)."""
        if self.agrees:
            return WHOLE_DRIVE, "shared"
        if self.whole_drive_hz > self.lowest_string_hz and (
                self.whole_strain[1] > 0.5
                or self.counterpart_strain[1] - self.whole_strain[1] > SPAN_COUPLING):
            return LINK_LEVEL, "sag"
        c = self.counterpart
        if (c is not None and c.link_level_hz is not None and self.first_seat_hz is not None
                and c.link_level_hz > self.first_seat_hz):
            return LINK_LEVEL, "seats"
        return LINK_LEVEL, "unexplained"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI, unit in the keys)."""
        c = self.counterpart
        governing, reason = self.verdict
        return {"state": "loaded" if self.loaded else "rest",
                "span_tension_n": list(self.span_tensions_n),
                "whole_drive_first_hz": _num(self.whole_drive_hz),
                "link_level_counterpart_hz": None if c is None else c.link_level_hz,
                "counterpart_mac": None if c is None else c.mac,
                "deviation": self.deviation, "within_tolerance": self.agrees,
                "tolerance": FREQUENCY_TOLERANCE, "governing": governing, "reason": reason,
                "link_level_first_along_chain_hz": self.link_level_hz,
                "first_mac": _num(self.first_mac), "transverse_modes_below": self.below,
                "link_level_first_seat_hz": self.first_seat_hz,
                "link_level_strain_share": _shares(("links", "tension", "contacts"),
                                                   self.link_strain),
                "whole_drive_strain_share": _shares(("links", "sag", "wraps"),
                                                    self.whole_strain),
                "counterpart_strain_share": _shares(("links", "tension", "contacts"),
                                                    self.counterpart_strain),
                "pairs": [{"whole_drive_hz": p.whole_drive_hz, "link_level_hz": p.link_level_hz,
                           "mac": _num(p.mac)} for p in self.pairs],
                "transverse": [{"frequency_hz": t.frequency_hz, "span": t.span,
                                "half_waves": t.half_waves, "string_hz": t.string_hz,
                                "ratio": _num(t.ratio)} for t in self.transverse],
                "lowest_string_hz": _num(self.lowest_string_hz),
                "chain_mass_ratio": self.chain_mass_ratio}


def _num(value: float | None) -> float | None:
    """``value`` for JSON: None for a value not computed (None or nan)."""
    return value if value is not None and math.isfinite(value) else None


def _shares(names: tuple[str, ...], values: tuple[float, ...]) -> dict[str, float | None]:
    """Strain-energy shares by part, JSON-ready (None for a share not computed)."""
    return {k: _num(v) for k, v in zip(names, values, strict=True)}


def _bare(drive: Drive) -> Drive:
    """The drive without its motor and trains: the masses the link-level model turns."""
    from dataclasses import replace

    return replace(drive, motor=None,
                   sprockets=tuple(replace(s, train=()) for s in drive.sprockets),
                   dynamics=replace(drive.dynamics, require_complete_model=False))


def mode_agreement(drive: Drive, *, geometry: GeometryResult | None = None,
                   loaded: bool = False, modes: LinearModes | None = None) -> ModeAgreement:
    """The first natural frequency along the chain of the link-level model and of the
    whole-drive model, at one tension state and on the same masses (module docstring).

    Parameters
    ----------
    drive : Drive
        The drive (one contour).
    geometry : GeometryResult or None
        Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`); the take-up
        installs it as the link-level model does.
    loaded : bool
        At the loaded static state (True) or at rest at T₀ (False).
    modes : LinearModes or None
        The link-level modes at that state (None:
        :func:`~chaindrive.linklevel.modes.linear_modes`).

    Returns
    -------
    ModeAgreement
        Frequencies, MAC, strain shares and the transverse modes against their strings.

    References
    ----------
    [Allemang2003] (MAC); [Ernst1965] (sag factor); [Mote1965] (string).
    """
    # lazy: the link-level modes import numba and the kernel
    from chaindrive.dynamics.model.build import drive_model
    from chaindrive.dynamics.modes import drive_modes
    from chaindrive.dynamics.transverse import span_transverse_frequencies
    from chaindrive.geometry.contour import contour_geometry
    from chaindrive.linklevel.equilibrium import installed_geometry
    from chaindrive.linklevel.modes import linear_modes

    geometry, _ = installed_geometry(drive, geometry or contour_geometry(drive))
    if modes is None:
        modes = linear_modes(drive, geometry=geometry, loaded=loaded)
    tensions = np.asarray(modes.span_tensions_n, dtype=float)
    model = drive_model(_bare(drive), geometry, span_tensions=tensions.tolist())
    whole = drive_modes(model)
    elastic = np.flatnonzero(~whole.rigid_body)
    turns = whole.shapes / model.mean_radii[:, None]  # forward angles of the sprockets
    f_whole = whole.frequencies_hz
    links = np.flatnonzero(modes.longitudinal)
    first = modes.first_longitudinal
    seat = modes.first_of("seat")
    f1_link = None if first is None else float(modes.frequencies_hz[first])
    first_mac = (None if first is None or not elastic.size
                 else mac(turns[:, elastic[0]], modes.sprocket_turns[:, first]))
    pairs = []
    counterpart_strain: tuple[float, ...] = (math.nan,) * 3
    for j in elastic[:PAIRED_MODES]:
        band = links[(modes.frequencies_hz[links] >= 0.5 * f_whole[j])
                     & (modes.frequencies_hz[links] <= 2.0 * f_whole[j])]
        macs = [mac(turns[:, j], modes.sprocket_turns[:, m]) for m in band]
        best = int(band[int(np.nanargmax(macs))]) if band.size and np.any(
            np.isfinite(macs)) else None
        if j == elastic[0] and best is not None:
            counterpart_strain = tuple(float(v) for v in modes.strain_shares[best])
        pairs.append(ModePair(float(f_whole[j]),
                              None if best is None else float(modes.frequencies_hz[best]),
                              None if best is None else float(np.nanmax(macs))))
    kinds = np.array(whole.system.element_kinds) if whole.system is not None else np.array([])
    names = whole.system.element_names if whole.system is not None else ()
    if elastic.size:
        shares = whole.strain_energy_shares[:, elastic[0]]
        span_share = np.array([shares[names.index(f"span:{sp.start_name}-{sp.end_name}")]
                               for sp in geometry.spans])
        sag = model.ring.sag_factors
        whole_strain = (float(span_share @ sag), float(span_share @ (1.0 - sag)),
                        float(shares[kinds == "wrap"].sum()))
    else:
        whole_strain = (math.nan, math.nan, math.nan)
    link_strain = ((math.nan,) * 3 if first is None
                   else tuple(float(v) for v in modes.strain_shares[first]))
    q = drive.chain.spec.mass_per_length
    transverse = []
    for m in np.flatnonzero(~modes.longitudinal)[:STRING_MODES]:
        k, n = int(modes.span[m]), int(modes.half_waves[m])
        sp = geometry.spans[k]
        string = float(span_transverse_frequencies(sp.length, tensions[k], q, 0.0,
                                                   modes=n)[-1])
        transverse.append(TransverseMode(float(modes.frequencies_hz[m]),
                                         f"{sp.start_name}-{sp.end_name}", n, string))
    chain_mass = q * sum(sp.length for sp in geometry.spans) + q * sum(
        g.pitch_radius * g.wrap_angle for g in geometry.sprockets)
    strings = [float(span_transverse_frequencies(sp.length, t, q, 0.0, modes=1)[0])
               for sp, t in zip(geometry.spans, tensions, strict=True)]
    return ModeAgreement(
        loaded=modes.loaded, span_tensions_n=tuple(float(t) for t in tensions),
        whole_drive_hz=float(f_whole[elastic[0]]) if elastic.size else math.nan,
        link_level_hz=f1_link, first_mac=first_mac,
        below=0 if first is None else first, link_strain=link_strain,
        whole_strain=whole_strain, pairs=tuple(pairs), transverse=tuple(transverse),
        counterpart_strain=counterpart_strain,
        first_seat_hz=None if seat is None else float(modes.frequencies_hz[seat]),
        lowest_string_hz=min(f for f in strings if f > 0) if any(strings) else math.nan,
        chain_mass_ratio=float(chain_mass / np.sum(model.ring.masses_kg)))


@dataclass(frozen=True, slots=True)
class SpanLoadAgreement:
    """The steady span loads of the two models at one operating point: the link-level run's
    mean span forces over its steady window beside the whole-drive model's static span
    tensions (:func:`chaindrive.dynamics.parameters.static_span_tensions`).

    Parameters
    ----------
    span_names : tuple of str
        The spans ("S1-S2").
    whole_drive_n : tuple of float
        The whole-drive model's static tension of each span [N].
    link_level_n : tuple of float
        The link-level run's mean force of each span [N].
    tight : tuple of bool
        Per span, whether it carries more than the mean of the two models' lowest spans
        (a loaded span) rather than the pre-tension alone (a slack span).
    """

    span_names: tuple[str, ...]
    whole_drive_n: tuple[float, ...]
    link_level_n: tuple[float, ...]
    tight: tuple[bool, ...]

    @property
    def deviations(self) -> tuple[float, ...]:
        """Per span link level / whole drive − 1 [-]."""
        return tuple(k / w - 1.0 if w > 0 else math.nan
                     for w, k in zip(self.whole_drive_n, self.link_level_n, strict=True))

    @property
    def within(self) -> tuple[bool, ...]:
        """Per span |deviation| ≤ :data:`LOAD_TOLERANCE`."""
        return tuple(bool(abs(d) <= LOAD_TOLERANCE) for d in self.deviations)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready records per span (SI, unit in the keys)."""
        return {"tolerance": LOAD_TOLERANCE,
                "spans": [{"span": s, "whole_drive_n": w, "link_level_n": k,
                           "deviation": d, "within_tolerance": ok, "loaded_span": t}
                          for s, w, k, d, ok, t in zip(
                              self.span_names, self.whole_drive_n, self.link_level_n,
                              self.deviations, self.within, self.tight, strict=True)]}


def span_load_agreement(span_names: Sequence[str], whole_drive: NDArray[np.float64],
                        link_level: NDArray[np.float64]) -> SpanLoadAgreement:
    """The steady span loads of both models side by side (:class:`SpanLoadAgreement`).

    A span counts as loaded when the whole-drive model's tension exceeds its lowest span's
    by more than :data:`LOAD_TOLERANCE` of it (the spans between the driver and a driven
    sprocket on the tight side carry T₀ + their part of F_t; the others T₀).

    Parameters
    ----------
    span_names : sequence of str
        The spans.
    whole_drive : ndarray
        (n,) the whole-drive model's static span tensions [N].
    link_level : ndarray
        (n,) the link-level run's mean span forces over its steady window [N].

    Returns
    -------
    SpanLoadAgreement
        Both, with the deviations.
    """
    w = np.asarray(whole_drive, dtype=float)
    k = np.asarray(link_level, dtype=float)
    if w.shape != k.shape or w.shape != (len(span_names),):
        raise ValueError(f"{w.size} whole-drive spans, {k.size} link-level, "
                         f"{len(span_names)} names")
    low = float(w.min())
    return SpanLoadAgreement(tuple(span_names), tuple(float(v) for v in w),
                             tuple(float(v) for v in k),
                             tuple(bool(v > (1.0 + LOAD_TOLERANCE) * low) for v in w))
