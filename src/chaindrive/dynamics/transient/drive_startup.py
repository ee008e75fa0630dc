"""The start-up of the whole-drive model from rest: the motor law on the motor's rotor, the
machines' moments on theirs, tension-only spans with their pre-tension and the polygonal
hinge law [MultimassChainDrives, §3.1, Fig. 2] (docs/dynamics.md §5).

The integrator is :func:`chaindrive.dynamics.transient.startup.solve_startup`. Its step follows the
model: Δt = 1/(160 max(f_ref, f_z)), f_ref the chain's reference mode (the first elastic mode
in which the spans and wraps hold most of the strain energy, :mod:`.drive_model`) and f_z the
tooth frequency — stiff modes above it cost nothing (the zero-order hold is exact for the
linear part). A run whose work would exceed :data:`chaindrive.dynamics.transient.startup.WORK_BUDGET`
is refused with one line naming the body that sets the step.

Reported separately: the **run-up time** (the driver first at 95 % of its final speed) and the
**decay** of the transient after it (until every span force stays within its final band,
:func:`chaindrive.dynamics.transient.startup.settling_time`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.transient.startup import (
    MAX_RECORDS,
    STEPS_PER_PERIOD,
    WORK_BUDGET,
    Backend,
    PolygonalLaw,
    StartupProblem,
    StartupResult,
    solve_startup,
    transient_times,
    work_estimate,
)
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.dynamics.modes import Modes

__all__ = ["affordable_duration", "model_startup", "startup_step"]



def _step_body(model: DriveModel, modes: Modes, f_ref: float) -> tuple[str, str]:
    """(design field, description) of the body that moves most in the mode at ``f_ref``."""
    j = int(np.argmin(np.abs(modes.frequencies_hz - f_ref)))
    sys = model.system
    kinetic = sys.node_inertia_kg_m2 * modes.shape_matrix[:, j] ** 2
    node = sys.node_names[int(np.argmax(kinetic))]
    element = modes.governing_element(j)
    names = model.sprocket_names
    if node in names:
        field = f"sprockets[{names.index(node)}].inertia"
    elif node.startswith("chain@"):
        field = "chain"
    else:
        owner = next((s for s, t in model.trains.items()
                      if any(node in (e.get("to"), e.get("node")) for e in t)), names[0])
        field = f"sprockets[{names.index(owner)}].train"
    return field, f"{node} (mode at {f_ref:.4g} Hz, governed by {element})"


@shared_parameters
def startup_step(model: DriveModel, tooth_frequency_hz: float, duration: float,
                 modes: Modes | None = None) -> tuple[float, int]:
    """(Δt [s], steps) of a start-up of ``duration`` [s] (module docstring); DesignError when
    the work would exceed the budget.

    %(params_model_tooth_frequency)s
    duration : float
        [s].
    modes : Modes | None
        Its modes (None: computed when a refusal needs them).

    Returns
    -------
    tuple of float and int
    """
    f_ref = max(model.reference_frequency_hz, tooth_frequency_hz)
    if not f_ref > 0:
        raise DesignError("dynamics", "the model has no elastic mode and no tooth frequency")
    dt = _time_step(f_ref)
    steps = max(1, math.ceil(duration / dt))
    work = work_estimate(model.linear.size, steps)
    if work > WORK_BUDGET:
        field, body = _step_body(model, modes or model.modal(), f_ref)
        raise DesignError(field, f"{body} sets the start-up step to {dt:.3g} s: {steps} steps "
                          f"for {duration:g} s, {work:.3g} operations (limit "
                          f"{WORK_BUDGET:.3g}); give this body a realistic inertia, shorten "
                          "[dynamics] startup_duration or set transient = false")
    return dt, steps


@shared_parameters
def affordable_duration(model: DriveModel, tooth_frequency_hz: float) -> float:
    """The longest start-up [s] whose work stays within
    :data:`~chaindrive.dynamics.transient.startup.WORK_BUDGET` at the step of :func:`startup_step`
    (0 when not even one step does).

    %(params_model_tooth_frequency)s

    Returns
    -------
    float
        [s].
    """
    f_ref = max(model.reference_frequency_hz, tooth_frequency_hz)
    if not f_ref > 0:
        return 0.0
    n = model.linear.size
    fixed, per_step = work_estimate(n, 0), work_estimate(n, 1) - work_estimate(n, 0)
    steps = math.floor((WORK_BUDGET - fixed) / per_step) - 1  # ceil of the step count: one less
    return max(0, steps) * _time_step(f_ref)


def _time_step(f_ref: float) -> float:
    """Δt = 1/(160 f_ref) [s] of a start-up at the reference frequency f_ref [Hz] (module
    docstring)."""
    return 1.0 / (STEPS_PER_PERIOD * f_ref)


def model_startup(model: DriveModel, polygonal: PolygonalLaw | None, *, duration: float,
                  pretension: float, tooth_frequency_hz: float,
                  breaking_load: float | None = None, keep_states: bool = False,
                  backend: Backend = "auto") -> StartupResult:
    """Start-up of the whole-drive model from rest (module docstring).

    Parameters
    ----------
    model : DriveModel
        The model with its motor and machines.
    polygonal : PolygonalLaw | None
        The polygonal hinge law of the contour (None: no polygonal excitation).
    duration : float
        Simulated time [s].
    pretension : float
        T₀ of every span of one contour [N] (the sag tension).
    tooth_frequency_hz : float
        f_z at the nominal speed [Hz] (the step).
    breaking_load : float | None
        Q of one contour [N] → k₁ = Q/F₁max.
    keep_states : bool
        Keep the state (q, q̇) of every step (``StartupResult.states``; the memory grows with
        the steps: for checks such as the energy balance).
    backend : str
        See :func:`chaindrive.dynamics.transient.startup.solve_startup`.

    Returns
    -------
    StartupResult
        Span forces of one contour, the sprockets' and rotors' forward speeds.
    """
    if model.motor is None:
        raise DesignError("drive.power", "a start-up needs the motor (the drive's power)")
    dt, steps = startup_step(model, tooth_frequency_hz, duration)
    lin, mot, loads = model.linear, model.motor, model.loads
    m = float(model.contours)
    p = StartupProblem(
        linear=lin, pretension=np.full(lin.span_stiffness.size, pretension * m),
        motor=(mot.coordinate, mot.gain, mot.efficiency, mot.law),
        load_coordinate=np.array([ld.coordinate for ld in loads], dtype=np.intp),
        load_gain=np.array([ld.gain for ld in loads]),
        load_efficiency=np.array([ld.efficiency for ld in loads]),
        load_torque=np.array([ld.torque for ld in loads]),
        load_speed=np.array([ld.nominal_speed for ld in loads]),
        load_kind=tuple(ld.kind for ld in loads), breakaway=0.01, polygonal=polygonal,
        travel_coordinate=model.sprocket_coordinate,
        travel_gain=model.sprocket_gain * model.mean_radii, dt=dt, steps=steps,
        record_every=1 if keep_states else max(1, math.ceil(steps / MAX_RECORDS)), scale=m)
    times, forces, states, fmax, _ = solve_startup(p, backend)
    n = lin.size
    speeds = states[:, n + model.sprocket_coordinate] * model.sprocket_gain
    rotors = states[:, n + model.rotor_coordinate] * model.rotor_gain
    k1 = breaking_load / float(fmax.max()) if breaking_load and fmax.max() > 0 else None
    period = 1.0 / tooth_frequency_hz if polygonal is not None and tooth_frequency_hz > 0 \
        else 0.0
    settle, runup, decay = transient_times(times, forces, speeds[:, model.driver_index], period)
    return StartupResult(times, forces, speeds, fmax, settle, k1, steps,
                         int(np.count_nonzero((forces <= 0).any(axis=1))), runup, decay,
                         model.rotor_names, rotors, states if keep_states else None, dt)
