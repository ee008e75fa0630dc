"""The dynamic checks of a drive: the working frequencies' distance from resonance, and the
two-stage safety factors k₁, k₂, k₂min against [k] [MultimassChainDrives, §3.6]."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from chaindrive.checks import Check, judged
from chaindrive.dynamics.resonance import Resonance
from chaindrive.dynamics.transient.runup import elastic_stall
from chaindrive.errors import Quantities
from chaindrive.units import RPM_PER_RAD_S

if TYPE_CHECKING:
    from chaindrive.dynamics.transient.runup import RunUp
    from chaindrive.dynamics.transient.startup import StartupResult

__all__ = ["disturbed_safety_check", "dynamic_safety_check", "motor_start_check",
           "resonance_check", "startup_safety_check"]


def dynamic_safety_check(name: str, value: float | None, allowable: float, note: str = ""
                         ) -> Check:
    """k₁ = Q/F₁max, k₂ = Q/(F_R + F₂) or k₂min = Q/(F_R + F₂max) ≥ [k]
    [MultimassChainDrives, §3.6].

    Parameters
    ----------
    name : str
        "k1", "k2" or "k2min".
    value : float | None
        The factor [-] (None when it could not be computed).
    allowable : float
        [k] [-].
    note : str
        What the factor rests on.

    Returns
    -------
    Check
    """
    return judged(name, {"k1": "start-up", "k2": "steady motion",
                         "k2min": "resonance in the run-up"}.get(name, name),
                  value, allowable, "min", "[MultimassChainDrives, §3.6]", note=note,
                  part="dynamics")


def startup_safety_check(startup: StartupResult | None, allowable: float, *,
                         missing: Sequence[str] = (), runup: RunUp | None = None) -> Check:
    """k₁ = Q/F₁max ≥ [k] of a start-up record [MultimassChainDrives, §3.6]. It cannot be
    verified on a model without its motor or machines (``missing``: the start-up of bare
    sprockets is not the drive's), when the motor does not start the drive (``runup``), or
    when the record ends before the driver is at speed or the forces settle (a larger F₁max
    may follow: the note gives the k₁ of the simulated time), unless that k₁ is already
    below [k] (F₁max over a longer record is at least as large: it fails). The note keeps the
    k₁ computed.

    Parameters
    ----------
    startup : StartupResult | None
        The start-up (None: none was simulated).
    allowable : float
        [k] [-].
    missing : sequence of str
        What makes the dynamic model incomplete (:attr:`DriveModel.missing`).
    runup : RunUp | None
        The rigid-drive run-up (:func:`chaindrive.dynamics.transient.runup.rigid_runup`).

    Returns
    -------
    Check
        Keyed ``k1``.
    """
    if startup is None:
        return dynamic_safety_check("k1", None, allowable)
    computed = "" if startup.k1 is None else f" (computed {startup.k1:.3g})"
    if missing:
        return dynamic_safety_check(
            "k1", None, allowable,
            note=f"the dynamic model is incomplete ({len(missing)} missing, see its warning): "
                 f"its start-up is not the drive's{computed}")
    if runup is not None and not runup.starts:
        return dynamic_safety_check(
            "k1", None, allowable,
            note=f"the motor does not start the drive (motor start check){computed}")
    if elastic_stall(runup, startup):
        return dynamic_safety_check(
            "k1", None, allowable,
            note="the elastic start-up does not run up where the rigid drive does: outside "
                 f"the model's range (see its warning){computed}")
    if not startup.settled:
        simulated = float(startup.times[-1]) if len(startup.times) else 0.0
        what = ("the driver is at its working speed" if math.isnan(startup.runup_time)
                else "the span forces settle")
        record = f"the start-up record ({simulated:.3g} s) ends before {what}"
        if startup.k1 is not None and startup.k1 < allowable:  # a longer record can only
            return dynamic_safety_check("k1", startup.k1, allowable,  # lower it
                                        note=f"already below the allowable although {record}")
        so_far = "" if startup.k1 is None else f" (so far {startup.k1:.3g})"
        return dynamic_safety_check(
            "k1", None, allowable,
            note=f"{record}{so_far}; lengthen [dynamics] startup_duration")
    return dynamic_safety_check("k1", startup.k1, allowable)


def motor_start_check(runup: RunUp | None) -> Check | None:
    """The motor runs the drive up: its torque, through the gear stages, above the machines'
    torques referred to the motor shaft at every speed from standstill to 95 % of its nominal
    speed, η M_M/M_L > 1 [Chilikin1981] (:mod:`chaindrive.dynamics.transient.runup`; the rigid drive).

    Parameters
    ----------
    runup : RunUp | None
        The rigid-drive run-up (None: no motor, or no rigid-body mode).

    Returns
    -------
    Check | None
        Keyed ``motor_start``; None without a run-up or without a machine load.
    """
    if runup is None or not math.isfinite(runup.torque_ratio):
        return None
    rpm = RPM_PER_RAD_S
    if runup.starts:
        note = (f"least at {runup.ratio_speed * rpm:.4g} rpm of the motor; rigid-drive run-up "
                f"{runup.runup_time:.3g} s")
    else:
        stall = runup.working_speed if math.isfinite(runup.working_speed) else 0.0
        note = (f"the motor's torque falls to the load's at {stall * rpm:.4g} rpm, "
                f"{100 * stall / runup.nominal_speed:.3g} % of its nominal speed: the drive "
                "stalls there")
    return judged("motor start", "motor torque / load torque", runup.torque_ratio, 1.0,
                  "min", "[Chilikin1981]", note=note, part="dynamics")


def resonance_check(rows: Sequence[Resonance], band_percent: float) -> Check | None:
    """The least detuning Δ = |f_w − f_n|/f_n [%] of a working frequency from its nearest
    natural frequency (ring modes, and the spans' principal parametric resonance) ≥ the band
    [MultimassChainDrives, §3.2], [API684]; None when there is no working frequency.

    The check's value is Δ; its margin is Δ/band − 1 (≥ 0 passes), a different number that
    the note keeps apart by naming the value the detuning (in words: the summary of the
    report shows the note before the symbol Δ is defined).

    Parameters
    ----------
    rows : sequence of Resonance
        The resonance table.
    band_percent : float
        The least distance required [%].

    Returns
    -------
    Check | None
    """
    if not rows:
        return None
    closest = min(rows, key=lambda r: r.detuning_percent)
    what = ("parametric resonance of a span" if closest.working.kind == "parametric"
            else "natural frequency")
    return judged("resonance margin", closest.working.label, closest.detuning_percent,
                  band_percent, "min", "[MultimassChainDrives, §3.2], [API684]", "%",
                  note=f"{closest.working.frequency:.4g} Hz {closest.side} the {what} "
                       f"{closest.natural_frequency:.4g} Hz; the value is their detuning"
                       + _also_inside(rows, closest, band_percent),
                  part="dynamics")


SHOWN = 3
"""Other resonances inside the band named in the check's note (the rest counted) [-]."""


def _also_inside(rows: Sequence[Resonance], closest: Resonance, band_percent: float) -> str:
    """"; also inside the band: …" naming every other working frequency closer than the band
    to a natural frequency ("" when there is none): the check judges the closest, the note
    counts the rest."""
    others = sorted((r for r in rows if r is not closest and r.detuning_percent < band_percent),
                    key=lambda r: r.detuning_percent)
    if not others:
        return ""
    named = ", ".join(f"{r.working.label} {r.detuning_percent:.3g} %" for r in others[:SHOWN])
    rest = len(others) - SHOWN
    return (f"; {len(others)} more inside the band: {named}"
            + (f" and {rest} more (the resonance table)" if rest > 0 else ""))


def disturbed_safety_check(breaking_load: float, operating: ArrayLike, polygonal: ArrayLike,
                           disturbances: Mapping[str, ArrayLike], allowable: float) -> Check:
    """k₂ with the internal disturbances: Q/max_i(F_R,i + F_2,i + Σ_d F_d,i) ≥ [k]
    [MultimassChainDrives, §3.6].

    The steady dynamic loads of the sprockets' eccentricity and of the chain's pitch
    scatter and accumulated error (``[dynamics]``) add to the polygonal load F₂ of each span;
    their peaks are summed — exact when the frequencies are incommensurate, an upper bound
    otherwise (the superposition of :mod:`chaindrive.dynamics.frequency.steady`).

    Parameters
    ----------
    breaking_load : float
        Q [N].
    operating : array_like
        F_R of each span [N].
    polygonal : array_like
        F₂, the polygonal steady dynamic load of each span [N].
    disturbances : Mapping[str, array_like]
        Each disturbance's steady dynamic load of each span [N].
    allowable : float
        [k] [-].

    Returns
    -------
    Check
    """
    total = np.asarray(operating, float) + np.asarray(polygonal, float)
    for loads in disturbances.values():
        total = total + np.asarray(loads, float)
    worst = float(np.max(total))
    value = breaking_load / worst if worst > 0 else None
    q = Quantities()
    note = f"largest span load {q(worst, 'force', '.4g')} with the disturbances' peaks added"
    return judged("k2 with disturbances", "steady motion with " + " and ".join(
        k.replace("_", " ") for k in disturbances), value, allowable, "min",
        "[MultimassChainDrives, §3.6]", part="dynamics", note=note, note_quantities=q.items)
