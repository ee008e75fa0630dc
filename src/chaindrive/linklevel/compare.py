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

    from chaindrive.linklevel.result import LinkLevelResult

__all__ = ["DURATION", "LINK_LEVEL", "MODEL_NAMES", "SETTLED_SPEED", "WHOLE_DRIVE",
           "GoverningLoads", "ModelComparison", "checked_duration", "governing_loads",
           "model_comparison"]

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
    """

    rows: tuple[Row, ...]
    settled: bool
    steady_from_s: float
    duration_s: float

    @property
    def governing(self) -> tuple[str | None, ...]:
        """Per row, the model whose value governs (:func:`governing_model`)."""
        return tuple(governing_model(row) for row in self.rows)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the rows as records (with the governing model, ``"whole_drive"``,
        ``"link_level"`` or null) and the run's window (SI, unit in the keys)."""
        return {"rows": [{"quantity": q, "whole_drive": w, "link_level": k, "unit": u,
                          "governing": g}
                         for (q, w, k, u), g in zip(self.rows, self.governing, strict=True)],
                "settled": self.settled, "steady_from_s": self.steady_from_s,
                "duration_s": self.duration_s}


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
                     link_first_frequency_hz: float | None = None) -> ModelComparison:
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
    late = result.times >= result.steady_from
    speed = float(np.mean(np.abs(result.sprocket_speeds[late, result.model.driver])))
    settled = math.isfinite(speed) and abs(speed / nominal_speed - 1.0) <= SETTLED_SPEED
    return ModelComparison(tuple(rows), settled, float(result.steady_from),
                           float(result.times[-1]))


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
