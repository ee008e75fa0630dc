"""Warnings of the whole-drive dynamics: an incomplete model, estimated inputs, a resonance
inside the band of uncertain stiffness and inertia, hinge friction outside its data."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from chaindrive.dynamics.transient.runup import RunUp, elastic_stall
from chaindrive.errors import ChainDriveWarning, Quantities
from chaindrive.strength.loads import DEFAULT_SAG_RATIO

if TYPE_CHECKING:
    from collections.abc import Sequence

    from chaindrive.dynamics.frequency.response import Bands
    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.dynamics.transient.startup import StartupResult

__all__ = ["ELASTIC_DOMINATED", "SAG_DOMINATED", "SLACK_SHARE", "dynamics_warnings",
           "startup_warnings"]

#: A span keeping less than this share of its taut stiffness is set by its sag (its tension).
SAG_DOMINATED = 0.9
#: A span keeping at least this share of its taut stiffness is set mostly by its links and
#: teeth (its elastic compliance is at least this share of the whole).
ELASTIC_DOMINATED = 0.5
#: A span slack in more than this share of the start-up's samples is named in a warning.
SLACK_SHARE = 0.01


def dynamics_warnings(model: DriveModel, bands: Bands, *, assumed_sag: bool = False,
                      computed_link_stiffness: bool = False) -> list[ChainDriveWarning]:
    """The warnings of a drive model and its bands.

    Parameters
    ----------
    model : DriveModel
        The whole-drive model (completeness, estimates, damping source).
    bands : Bands
        The bands for the design's uncertainty.
    assumed_sag : bool
        True when the design gives no installed sag (``[chain] sag``) and the static
        tensions rest on the default one.
    computed_link_stiffness : bool
        True when the design gives no measured link stiffness (``[chain] link_stiffness``)
        and the model computed it from the plates and the pin.

    Returns
    -------
    list of ChainDriveWarning
        ``dynamics.model-incomplete`` (its frequencies are upper bounds, the start-up not
        meaningful), ``dynamics.estimate`` (an input the model estimated),
        ``dynamics.resonance-in-band`` (a working frequency inside the band of a natural
        frequency), ``dynamics.hinge-friction-extrapolated``.
    """
    out = list(model.warnings())
    out += [ChainDriveWarning("dynamics.estimate", "motor.rotor_inertia", note,
                              [q for q in model.note_quantities if q.text in note])
            for note in model.notes if "estimated" in note]
    sag = model.ring.sag_factors
    if assumed_sag and sag is not None and float(min(sag)) < SAG_DOMINATED:
        out.append(ChainDriveWarning(
            "dynamics.estimate", "chain.sag",
            f"the span tensions rest on an installed sag of {100 * DEFAULT_SAG_RATIO:g} % of "
            "the slack span (assumed: [chain] sag is not given), and the sagging spans keep "
            f"down to {100 * float(min(sag)):.2g} % of their taut stiffness (∝ T³): the natural "
            "frequencies follow the sag; give the installed sag ([chain] sag)"))
    if computed_link_stiffness and sag is not None and float(max(sag)) >= ELASTIC_DOMINATED:
        q = Quantities()
        out.append(ChainDriveWarning(
            "dynamics.estimate", "chain.link_stiffness",
            f"the link stiffness is computed from the plates and the pin "
            f"({q(model.ring.link_stiffness_n_per_m, 'stiffness', '.3g')}; the contact of pin, "
            "bush and roller left out, so an upper bound), and spans keeping up to "
            f"{100 * float(max(sag)):.3g} % of their taut stiffness follow it: the natural "
            "frequencies are upper bounds too; give the maker's measured value ([chain] "
            "link_stiffness)", q.items))
    inside = bands.resonances_inside
    if inside:
        pct = f"{100 * bands.uncertainty:g}"
        out.append(ChainDriveWarning(
            "dynamics.resonance-in-band", "dynamics",
            f"{', '.join(inside)} lie(s) within the band of a natural frequency for ±{pct} % "
            "on every stiffness and inertia: a resonance cannot be ruled out; detune the "
            "drive (masses, span lengths, teeth) or know its parameters better"))
    if model.damping_source.startswith("hinge friction"):
        out.append(ChainDriveWarning(
            "dynamics.hinge-friction-extrapolated", "dynamics.hinge_friction",
            "the hinge-friction damping rests on the friction fit of one chain "
            "(ПР-12,7-1820-1) [ChainHingeDissipation]; for this chain it is an extrapolation"))
    return out


def startup_warnings(startup: StartupResult, span_names: Sequence[str],
                     runup: RunUp | None = None) -> list[ChainDriveWarning]:
    """The warnings of a start-up record.

    Parameters
    ----------
    startup : StartupResult
        The start-up.
    span_names : sequence of str
        Names of the spans of one contour ("S1→S2", …), in the order of the span forces.
    runup : RunUp | None
        The drive's run-up as a rigid body (:func:`chaindrive.dynamics.transient.runup.rigid_runup`).

    Returns
    -------
    list of ChainDriveWarning
        ``dynamics.startup-not-settled`` (the record ends before the driver is at speed or
        before the forces settle: F₁max and k₁ cover only the simulated time),
        ``dynamics.startup-stall`` (the elastic start-up has not run up in a time in which
        the rigid drive does: out of the model's range) and ``dynamics.startup-slack`` (spans
        slack in more than :data:`SLACK_SHARE` of the samples).
    """
    out = []
    simulated = float(startup.times[-1]) if len(startup.times) else 0.0
    stall = elastic_stall(runup, startup)
    if stall:
        assert runup is not None
        out.append(ChainDriveWarning(
            "dynamics.startup-stall", "dynamics",
            f"the elastic start-up has not run up in {simulated:.3g} s, while the drive as "
            f"one rigid body runs up in {runup.runup_time:.3g} s: the motor side bounces "
            "against the slack spans, fed by the motor's static torque curve, which rises with "
            "the speed below the breakdown torque (the model has no electromagnetic "
            "transient of the motor); the start-up is outside the model's range — read the "
            "rigid run-up and the motor-start check, and give the motor more starting torque "
            "or a softer start"))
    if not startup.settled:
        what = ("the driver is not at its working speed" if math.isnan(startup.runup_time)
                else f"the span forces have not settled (run-up {startup.runup_time:.3g} s)")
        out.append(ChainDriveWarning(
            "dynamics.startup-not-settled", "dynamics.startup_duration",
            f"{what} within the simulated {simulated:.3g} s of the start-up: its largest span "
            "force and safety factor cover only that time"
            + ("" if stall else "; lengthen [dynamics] startup_duration")))
    share = (startup.span_forces <= 0.0).mean(axis=0) if len(startup.times) else []
    names = (list(span_names) if len(span_names) == len(share)
             else [f"span {i + 1}" for i in range(len(share))])
    slack = [f"{name} {100 * float(f):.3g} %" for name, f in zip(names, share, strict=True)
             if f > SLACK_SHARE]
    if slack:
        out.append(ChainDriveWarning(
            "dynamics.startup-slack", "chain.sag",
            f"in the start-up spans go slack ({', '.join(slack)} of the samples): the ring "
            "holds their force at zero (a chain cannot push) and re-engages them as springs, "
            "without the roller–tooth impacts of a span snatching taut (the link-level model "
            "has them), so the largest start-up force may be low there; a tauter installation "
            "([chain] sag) or a softer start lowers the slack"))
    return out
