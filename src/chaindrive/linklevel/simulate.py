"""Entry point of the link-level model: :func:`simulate` (drive → :class:`LinkLevelResult`).

Time step (:mod:`chaindrive.linklevel.kernel`). Taken explicitly (the default), the
semi-implicit Euler step is stable for Δt < 2/ω_max ([Hairer2006], the Störmer–Verlet
stability interval of a linear oscillator), ω_max bounded by the stiffest local oscillator, a
roller between two links on one tooth, ω_max² ≤ (4k_link + k_c)/m (Gershgorin's theorem on
M⁻¹K): the link springs' 28–41 kHz set it; Δt = C·2/ω_max with C = :data:`COURANT` (below 1
for the contact nonlinearity and the dampers). With ``implicit_links`` the link springs are
taken implicitly (the kernel's θ = 1/4, the implicit–explicit partition of
[HughesLiu1978]): the step is then stable below 2/ω of the explicit part alone, a roller on
one tooth, ω² = k_c/m. The accuracy, not the stability, bounds it: :func:`default_step`
resolves the roller's oscillation on a tooth and the regularised hinge friction, which
leaves twice the explicit step on the seed's polymer sprockets and none on steel ones; there
K_D and the peaks move by 1–2 % when the step halves, the span dynamic loads by 4 %
(docs/linklevel.md §2), against 0.05–0.6 % for the explicit step. Above the explicit step
the hinge friction is taken implicitly (:func:`hinge_implicit`): taken explicitly its
regularised law is stable up to that step exactly. A joint clearance (a dead band, no
tangent stiffness inside it) keeps the explicit step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.motors import ResistanceLaw
from chaindrive.dynamics.response import motor_of
from chaindrive.dynamics.transient.kernel_codes import (
    MOTOR_CONSTANT,
    RESISTANCE_KINDS,
    RESISTANCE_NONE,
    motor_code,
)
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel.assembly import Assembly, assemble_chain
from chaindrive.linklevel.equilibrium import (
    Equilibrium,
    installed_geometry,
    kernel_tables,
    static_equilibrium,
)
from chaindrive.linklevel.kernel import run_kernel
from chaindrive.linklevel.model import (
    HINGE_FRICTION,
    LinkLevelModel,
    TorsionalAttachment,
    build_model,
)
from chaindrive.linklevel.result import LinkLevelResult, state_energy, step_convergence
from chaindrive.strength.loads import power_shares
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["COURANT", "InitialState", "StaticState", "default_step", "equilibrium_state",
           "hinge_implicit", "hinge_regularisation", "initial_state", "simulate",
           "static_state", "undamped"]

#: Fraction of the stability limit 2/ω_max taken as the step (module docstring).
COURANT = 0.8
#: Contact search at least every this many steps; the reach circle is widened by a quarter
#: pitch, which a roller at :data:`SEARCH_SPEED` crosses in 0.25·p/v: the search interval
#: stays below that (every step at the implicit step of a 12B chain).
SEARCH_EVERY = 8
#: Speed [m/s] a roller is assumed never to reach relative to the sprockets' reach circles
#: (several times the chain speeds of roller-chain drives).
SEARCH_SPEED = 60.0
#: The kernel's θ for the link springs: 1/4 (implicit, average of the central-difference
#: positions [HughesLiu1978]) or 0 (explicit).
IMPLICIT_THETA = 0.25
#: The implicit step's bound in explicit steps Δt_e (:func:`default_step`): two steps per
#: relaxation time 4Δt_e of the regularised hinge friction (:func:`hinge_regularisation`).
HINGE_STEPS = 2.0
#: ω_c·Δt of the implicit step (:func:`default_step`): the phase error of a roller's
#: oscillation on a tooth, (ω_c Δt)²/24, about 1 %.
CONTACT_RESOLUTION = 0.5
Start = Literal["rest", "steady"]
InitialSpeed = Literal["rest", "working"]


def _motor_code(motor: Callable[[float, float], float]) -> tuple[int, NDArray[np.float64]]:
    """Kernel code of a motor law of :mod:`chaindrive.dynamics.motors` (the start-up
    kernel's, :func:`chaindrive.dynamics.transient.kernel_codes.motor_code`)."""
    code = motor_code(motor)
    if code is None:
        raise DesignError("motor", "the link-level model takes a ConstantTorque, RampTorque "
                          f"or KlossMotor, got {type(motor).__name__}")
    return code


def _resistance(drive: Drive, kind: str | None, speeds: NDArray[np.float64]
                ) -> tuple[int, NDArray[np.float64], NDArray[np.float64], float]:
    """(code, M_i [N·m], ω_n,i [rad/s], breakaway) of the resistance on the driven sprockets:
    their power shares of P at the nominal speeds, as the ring model's start-up."""
    n = len(drive.sprockets)
    if kind is None or not drive.power:
        return RESISTANCE_NONE, np.zeros(n), np.ones(n), 1.0
    if kind not in RESISTANCE_KINDS:
        raise DesignError("resistance", f"must be one of {sorted(RESISTANCE_KINDS)}, got "
                          f"{kind!r}")

    torques = np.asarray(power_shares(drive), dtype=float) * drive.power / speeds
    torques[drive.driver_index] = 0.0
    law = ResistanceLaw(kind, torques, speeds)  # type: ignore[arg-type]
    return RESISTANCE_KINDS[kind], law.torques, law.nominal_speeds, law.breakaway


def _nominal_speeds(drive: Drive) -> NDArray[np.float64]:
    """Mean sprocket speeds [rad/s], ω_i = ω_driver z_driver / z_i."""
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    z = np.array([s.teeth for s in drive.sprockets], dtype=float)
    return driver.speed * driver.teeth / z


def _initial_velocities(model: LinkLevelModel, asm: Assembly, x: NDArray[np.float64],
                        geometry: GeometryResult, omega: NDArray[np.float64]
                        ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Roller velocities (N, 2) and sprocket speeds (n,) of steady running: the sprockets at
    their mean speeds, the rollers on a wrap turning with it, the rollers of a span moving
    along it at the speed its leaving hinge gives it (R ω cos β), so that no link starts
    stretching except where a span meets the next sprocket (the polygonal mismatch)."""
    w = model.turn * omega
    v = np.zeros_like(x)
    carried = np.zeros(2)
    for r in range(x.shape[0]):
        s = int(asm.sprocket_of[r])
        if s >= 0:
            d = x[r] - model.centres[s]
            v[r] = w[s] * np.array([-d[1], d[0]])
            carried = v[r]
        else:
            u = np.array(geometry.spans[int(asm.span_of[r])].direction)
            v[r] = float(carried @ u) * u
    return v, w


def simulate(drive: Drive, duration_s: float = 1.0, *, geometry: GeometryResult | None = None,
             model: LinkLevelModel | None = None, initial_speed: InitialSpeed | None = None,
             motor: Callable[[float, float], float] | bool | None = True,
             damping: bool = True, start: Start | None = None,
             resistance: str | None = "linear", dt_s: float | None = None,
             sample_rate_hz: float | None = None, hinge_friction: float | None = None,
             clearance_m: float = 0.0, torsional: TorsionalAttachment | None = None,
             steady_window: float = 0.5, kick_rad_s: Sequence[float] | None = None,
             span_kick_m_s: tuple[int, float] | None = None,
             dynamics: DriveModel | None = None,
             check_step: bool = False, implicit_links: bool = False,
             static: StaticState | None = None) -> LinkLevelResult:
    """Simulate ``drive`` at the level of its links for ``duration_s`` seconds.

    Parameters
    ----------
    drive : Drive
        The drive.
    duration_s : float
        Simulated time [s].
    geometry : GeometryResult or None
        Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).
    model : LinkLevelModel or None
        Link-level parameters (None: :func:`chaindrive.linklevel.model.build_model` with
        ``hinge_friction``, ``clearance_m`` and ``torsional``).
    initial_speed : {"rest", "working"} or None
        ``"rest"`` (a start-up from the static equilibrium) or ``"working"`` (every body at
        its nominal speed: coasting runs) (None: ``start``, else ``"rest"``).
    motor : callable, bool or None
        Motor torque motor(t, ω) [N·m] on the driver: a ConstantTorque, RampTorque or
        KlossMotor (True or None: the drive's ``[dynamics]`` motor rated at its power and
        driver speed; False: no motor torque and no machine loads).
    damping : bool
        False removes every damper and the hinge friction (the link, contact and torsional
        dampers): a conservative model, for the energy check.
    start : {"rest", "steady"} or None
        The former name of ``initial_speed`` (``"steady"`` is ``"working"``).
    resistance : str or None
        Law of the driven sprockets' moments (``"linear"``, ``"quadratic"``,
        ``"constant"``; None: none) with their power shares at the nominal speeds (none
        when ``motor`` is False).
    dt_s : float or None
        Time step [s] (None: :func:`default_step`); above the explicit step the hinge
        friction is taken implicitly (:func:`hinge_implicit`).
    sample_rate_hz : float or None
        Rate of the recorded history [Hz] (None: about 10× the whole-drive model's reference
        frequency, at least 1 kHz).
    hinge_friction : float or None
        Coefficient of friction in the hinges [-] (None: 0.1).
    clearance_m : float
        Clearance of the pin–bush joints [m].
    torsional : TorsionalAttachment or None
        An attached torsional system.
    steady_window : float
        Closing fraction of the run over which the steady span loads are taken [-].
    kick_rad_s : sequence of float or None
        (n,) speeds added to the sprockets at t = 0 [rad/s] (an impulse, for natural
        frequencies).
    span_kick_m_s : tuple of (int, float) or None
        (span k, u [m/s]): a transverse velocity u·sin(πξ) on the rollers of span k at
        t = 0 (ξ ∈ (0, 1) along it, to the left of the travel).
    dynamics : DriveModel or None
        The analysis's whole-drive model: the links' damping ratio and reference frequency
        (None: built from ``drive``; see :func:`chaindrive.linklevel.model.build_model`).
    check_step : bool
        True runs the same simulation again at half the step and reports how much K_D and
        the span loads moved (``result.convergence``,
        :func:`chaindrive.linklevel.result.step_convergence`); three times the cost.
    implicit_links : bool
        True takes the link springs implicitly (module docstring) at
        :func:`default_step`'s implicit step (at most twice the explicit one, less accurate:
        docs/linklevel.md §2); False (default) explicitly, at the step they allow. A
        clearance forces False.
    static : StaticState or None
        The assembled chain and its static state, solved once by :func:`static_state` for
        runs that differ only in their dampers or hinge friction, which the static state
        does not depend on (None: solved here). Refused unless it was solved for this
        drive's installed contour and this run's model.

    Returns
    -------
    LinkLevelResult
        Histories, summaries and the energy balance.

    Raises
    ------
    DesignError
        A duration or steady window out of range, no power and no motor, or a ``static``
        solved for another drive or model.

    References
    ----------
    [Pedersen2004], [Pedersen2005]; [Hairer2006, §I.1] (the integrator).
    """

    if not (duration_s > 0 and 0 < steady_window <= 1):
        raise DesignError("duration_s", f"need duration_s > 0 and 0 < steady_window ≤ 1, got "
                          f"{duration_s!r}, {steady_window!r}")
    speed = _initial_speed(initial_speed, start)
    given = geometry or contour_geometry(drive)
    geometry, take_up = installed_geometry(drive, given)
    if model is None:
        model = build_model(drive, geometry, clearance=clearance_m, torsional=torsional,
                            dynamics=dynamics,
                            hinge_friction=HINGE_FRICTION if hinge_friction is None
                            else hinge_friction)
    else:  # the caller's parameters on the installed contour (a take-up moves one centre)
        model = replace(model, centres=np.array([[g.x, g.y] for g in geometry.sprockets]))
    if not damping:
        model = undamped(model)
    omega = _nominal_speeds(drive)
    law = _motor_law(drive, motor, omega)
    if law is None:
        resistance = None
    theta = IMPLICIT_THETA if implicit_links and model.clearance == 0.0 else 0.0
    dt = float(dt_s) if dt_s is not None else default_step(model, theta > 0.0)
    steps = max(1, math.ceil(duration_s / dt))
    rate = sample_rate_hz or 10.0 * max(model.reference_frequency_hz, 100.0)
    every = max(1, round(1.0 / (rate * dt)))
    if static is None:
        asm, eq = equilibrium_state(drive, geometry, model, default_step(model, False), take_up)
    elif static.key != static_key(drive, geometry, model, take_up):
        raise DesignError("static", "a static state solved for another drive, contour or "
                          "model; allowed: static_state(...) of this run's drive and model")
    else:
        asm, eq = static.assembly, static.equilibrium
    state = _initial_state(model, asm, eq, geometry, omega, speed)
    _apply_kicks(state, model, geometry, kick_rad_s, span_kick_m_s)
    result = _run(drive, geometry, model, asm, eq, state, law, resistance, omega, dt, steps,
                  every, steady_window, theta)
    if not check_step:
        return result
    half = _run(drive, geometry, model, asm, eq, state, law, resistance, omega, 0.5 * dt,
                2 * steps, 2 * every, steady_window, theta)
    return replace(result, convergence=step_convergence(result, half))


def _initial_speed(initial_speed: str | None, start: str | None) -> InitialSpeed:
    """``initial_speed``, else the former ``start`` (``"steady"`` read as ``"working"``)."""
    if initial_speed is not None:
        if initial_speed not in ("rest", "working"):
            raise DesignError("initial_speed", "must be 'rest' or 'working', got "
                              f"{initial_speed!r}")
        return "rest" if initial_speed == "rest" else "working"
    if start is None or start == "rest":
        return "rest"
    if start == "steady":
        return "working"
    raise DesignError("start", f"must be 'rest' or 'steady', got {start!r}")


def _motor_law(drive: Drive, motor: Callable[[float, float], float] | bool | None,
               omega: NDArray[np.float64]) -> Callable[[float, float], float] | None:
    """The motor law of :func:`simulate`'s ``motor`` (None: no motor)."""
    if motor is False:
        return None
    if motor is None or motor is True:
        if not drive.power:
            raise DesignError("drive.power", "a link-level run needs the power (or a motor)")
        return motor_of(drive.dynamics, drive.power, float(omega[drive.driver_index]))
    return motor


def undamped(model: LinkLevelModel) -> LinkLevelModel:
    """``model`` without its dampers and hinge friction (link, contact, torsional).

    Parameters
    ----------
    model : LinkLevelModel
        The parameters.

    Returns
    -------
    LinkLevelModel
        The conservative model.
    """
    att = model.torsional
    if att is not None:
        att = replace(att, damping=np.zeros_like(np.asarray(att.damping, dtype=float)))
    return replace(model, link_damping=0.0, hinge_friction=0.0,
                   contact_damping=np.zeros_like(model.contact_damping), torsional=att)


@shared_parameters
def equilibrium_state(drive: Drive, geometry: GeometryResult, model: LinkLevelModel,
                      dt: float, take_up: str | None) -> tuple[Assembly, Equilibrium]:
    """The chain assembled on the installed contour and its static state at T₀
    (:func:`chaindrive.linklevel.equilibrium.static_equilibrium`; with gravity the slack
    hangs in the spans).

    Parameters
    ----------
    %(installed_link_level)s
    dt : float
        Time step of the run [s]; the static state, solved rather than stepped, does not
        depend on it (kept for the callers that pass it).

    Returns
    -------
    tuple of (Assembly, Equilibrium)
        The assembled chain and its static state.
    """
    asm = assemble_chain(geometry, drive.driver_index, hang=bool(model.gravity[1] != 0.0))
    reference = next((k for k, sp in enumerate(geometry.spans)
                      if sp.start == drive.driver_index), 0)
    return asm, static_equilibrium(model, geometry, asm, reference, take_up)


@shared_parameters
def static_key(drive: Drive, geometry: GeometryResult, model: LinkLevelModel,
               take_up: str | None) -> tuple[object, ...]:
    """What the static state of :func:`equilibrium_state` is solved from: the installed
    contour, the driver, the take-up and every parameter of ``model`` the static balance
    reads (:func:`chaindrive.linklevel.equilibrium.static_equilibrium`) — not the dampers
    (link, contact, torsional) nor the hinge friction, which act only on motion (the static
    balance, :func:`chaindrive.linklevel.kernel.static_forces`, is taken at zero speeds).

    Parameters
    ----------
    %(installed_link_level)s

    Returns
    -------
    tuple
        Equal for two runs exactly when their static states are the same solve.
    """
    arrays = (model.gravity, model.centres, model.teeth, model.pitch_radii,
              model.seating_radii, model.seating_half_angles, model.tip_radii,
              model.contact_stiffness)
    return (geometry.pitch, geometry.links, geometry.sprockets, geometry.spans,
            drive.driver_index, take_up, model.driver, model.torsional is None,
            model.links, model.pitch, model.roller_mass, model.roller_radius,
            model.link_stiffness, model.clearance, model.pretension,
            *((a.dtype.str, a.shape, a.tobytes()) for a in arrays))


@dataclass(frozen=True, slots=True, eq=False)
class StaticState:
    """The chain assembled on a drive's installed contour and its static state, solved once
    (:func:`static_state`) for :func:`simulate` runs that differ only in their dampers or
    hinge friction.

    Parameters
    ----------
    key : tuple
        What it was solved from (:func:`static_key`).
    assembly : Assembly
        The assembled chain.
    equilibrium : Equilibrium
        Its static state.
    """

    key: tuple[object, ...]
    assembly: Assembly
    equilibrium: Equilibrium


def static_state(drive: Drive, model: LinkLevelModel,
                 geometry: GeometryResult | None = None) -> StaticState:
    """The static state :func:`simulate` solves for ``drive`` with ``model``, to be passed
    to runs of the same drive that differ only in their dampers or hinge friction.

    Parameters
    ----------
    drive : Drive
        The drive.
    model : LinkLevelModel
        Its link-level parameters (:func:`chaindrive.linklevel.model.build_model` on the
        installed contour, as :func:`simulate` builds them: T₀ rests on it).
    geometry : GeometryResult or None
        Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).

    Returns
    -------
    StaticState
        The assembled chain, its static state and what they were solved from.
    """
    installed, take_up = installed_geometry(drive, geometry or contour_geometry(drive))
    model = replace(model, centres=np.array([[g.x, g.y] for g in installed.sprockets]))
    asm, eq = equilibrium_state(drive, installed, model, default_step(model, False), take_up)
    return StaticState(static_key(drive, installed, model, take_up), asm, eq)


State = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
              NDArray[np.float64]]


def _initial_state(model: LinkLevelModel, asm: Assembly, eq: Equilibrium,
                   geometry: GeometryResult, omega: NDArray[np.float64],
                   speed: InitialSpeed) -> State:
    """(x, v, θ, ω) at t = 0: the static equilibrium at rest or at the nominal speeds."""
    n_extra = 0 if model.torsional is None else model.torsional.extra_inertias.size
    th = np.concatenate([eq.angles, np.zeros(n_extra)])
    w = np.zeros(th.size)
    x = eq.positions.copy()
    v = np.zeros_like(x)
    if speed == "working":
        if model.torsional is not None and n_extra:
            raise DesignError("initial_speed", "a start at working speed with an attached "
                              "torsional system needs its initial speeds: start from rest")
        v, w[:model.centres.shape[0]] = _initial_velocities(model, asm, x, geometry, omega)
    return x, v, th, w


def _apply_kicks(state: State, model: LinkLevelModel, geometry: GeometryResult,
                 kick: Sequence[float] | None, span_kick: tuple[int, float] | None) -> None:
    """Add the impulses of :func:`simulate` to the initial velocities (in place)."""
    x, v, _, w = state
    n = model.centres.shape[0]
    if kick is not None:
        k = np.asarray(kick, dtype=float)
        if k.shape != (n,):
            raise DesignError("kick_rad_s", f"need {n} sprocket speeds, got shape {k.shape}")
        w[:n] += k * model.turn
    if span_kick is not None:
        index, speed = span_kick
        if not 0 <= index < len(geometry.spans):
            raise DesignError("span_kick_m_s", f"no span {index}")
        sp = geometry.spans[index]
        a, u = np.array(sp.start_point), np.array(sp.direction)
        xi = (x - a) @ u / sp.length
        off = np.abs((x - a) @ np.array([-u[1], u[0]]))
        on = (xi > 0) & (xi < 1) & (off < model.pitch)
        v[on] += speed * np.sin(np.pi * xi[on])[:, None] * np.array([-u[1], u[0]])


@dataclass(frozen=True, slots=True, eq=False)
class InitialState:
    """The state a run starts from (what a peer engine needs to start from the same one).

    Parameters
    ----------
    positions : ndarray
        (N, 2) roller positions x [m].
    velocities : ndarray
        (N, 2) roller velocities v [m/s].
    angles : ndarray
        (D,) rotational coordinates θ [rad].
    speeds : ndarray
        (D,) their speeds ω [rad/s].
    rest_lengths : ndarray
        (N,) link rest lengths ℓ₀ [m].
    """

    positions: NDArray[np.float64]
    velocities: NDArray[np.float64]
    angles: NDArray[np.float64]
    speeds: NDArray[np.float64]
    rest_lengths: NDArray[np.float64]


def initial_state(drive: Drive, geometry: GeometryResult, model: LinkLevelModel,
                  start: Start = "rest", dt_s: float | None = None) -> InitialState:
    """The assembled chain and its start state, as :func:`simulate` builds them.

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult
        Its contour.
    model : LinkLevelModel
        The parameters.
    start : {"rest", "steady"}
        ``"rest"`` (a start-up) or ``"steady"`` (every body moving at its mean speed).
    dt_s : float or None
        Time step of the run [s] (None: :func:`simulate`'s default); the static state does
        not depend on it.

    Returns
    -------
    InitialState
        Positions, velocities and rest lengths, on the installed contour
        (:func:`chaindrive.linklevel.equilibrium.installed_geometry`).
    """
    installed, take_up = installed_geometry(drive, geometry)
    model = replace(model, centres=np.array([[g.x, g.y] for g in installed.sprockets]))
    dt = float(dt_s) if dt_s is not None else default_step(model, False)
    asm, eq = equilibrium_state(drive, installed, model, dt, take_up)
    x, v, th, w = _initial_state(model, asm, eq, installed, _nominal_speeds(drive),
                                 _initial_speed(None, start))
    return InitialState(x, v, th, w, np.full(x.shape[0], eq.rest_length))


def _rotational_system(model: LinkLevelModel) -> tuple[NDArray[np.float64], ...]:
    """J (D,), K (D, D), C (D, D) of the sprockets and an attached torsional system."""
    n = model.inertias.size
    att = model.torsional
    if att is None:  # no torsional system: empty matrices (the kernel skips them)
        return model.inertias.copy(), np.zeros((0, 0)), np.zeros((0, 0))
    D = n + att.extra_inertias.size
    K, C = np.asarray(att.stiffness, float), np.asarray(att.damping, float)
    if K.shape != (D, D) or C.shape != (D, D):
        raise DesignError("torsional", f"stiffness and damping must be {D}×{D}")
    return np.concatenate([model.inertias, att.extra_inertias]), K, C


def _loads_on_dofs(model: LinkLevelModel, dofs: int, torques: NDArray[np.float64],
                   speeds: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Moments of resistance M [N·m], nominal speeds [rad/s] and running senses (D,) on
    the rotational coordinates: sprocket i's on its own, or on ``load_dofs[i]`` of an
    attached torsional system."""
    n = model.centres.shape[0]
    target = list(range(n))
    att = model.torsional
    if att is not None and att.load_dofs is not None:
        if len(att.load_dofs) != n or not all(0 <= k < dofs for k in att.load_dofs):
            raise DesignError("torsional.load_dofs", f"need {n} coordinates in 0…{dofs - 1}, "
                              f"got {att.load_dofs!r}")
        target = [int(k) for k in att.load_dofs]
    M, wn, sign = np.zeros(dofs), np.ones(dofs), np.ones(dofs)
    for i, k in enumerate(target):
        if torques[i] != 0.0:
            M[k] += torques[i]
            wn[k] = speeds[i]
            sign[k] = model.turn[i]
    return M, wn, sign


def _run(drive: Drive, geometry: GeometryResult, model: LinkLevelModel, asm: Assembly,
         eq: Equilibrium, state: State, motor: Callable[[float, float], float] | None,
         resistance: str | None, omega: NDArray[np.float64], dt: float, steps: int,
         every: int, steady_window: float, theta: float = 0.0) -> LinkLevelResult:
    """Set up the kernel's arrays, run it, wrap the result (theta: the kernel's)."""
    x, v, th, w = (np.array(a, dtype=float, order="C") for a in state)  # copies: state stays
    x0, v0, th0, w0 = x.copy(), v.copy(), th.copy(), w.copy()
    L0 = np.full(x.shape[0], eq.rest_length)
    J, K, C = _rotational_system(model)
    mkind, mp = (MOTOR_CONSTANT, np.zeros(3)) if motor is None else _motor_code(motor)
    rkind, rM, rwn, rbrk = _resistance(drive, resistance, omega)
    rM, rwn, rsign = _loads_on_dofs(model, J.size, rM, rwn)
    N = x.shape[0]
    mdof = model.driver if model.torsional is None or model.torsional.motor_dof is None \
        else int(model.torsional.motor_dof)
    msign = float(model.turn[model.driver])
    tables = kernel_tables(model)
    spr, trig, gtab, reach = tables.spr, tables.trig, tables.gtab, tables.reach
    win = np.maximum(1.0, np.round(TWO_PI / (model.teeth * np.abs(omega)) / dt))
    cmax = hinge_regularisation(model)
    search = max(1, min(SEARCH_EVERY, int(0.25 * model.pitch / (SEARCH_SPEED * dt))))
    rows = steps // every + 1
    rec = (np.empty((rows, N, 2)), np.empty((rows, J.size)), np.empty((rows, J.size)),
           np.empty((rows, N)), np.empty((rows, N)), np.empty((rows, N), dtype=np.int64),
           np.empty((rows, N), dtype=np.int64))
    energy = np.zeros(6)
    d = x[:, None, :] - model.centres[None, :, :]
    inside = np.hypot(d[..., 0], d[..., 1]) < reach[None, :]
    cand = np.where(inside.any(axis=1), inside.argmax(axis=1), -1).astype(np.int64)
    eng = np.full((N, 4), -1.0)
    capacity = int(4 * N + 2 * duration_events(model, omega, steps * dt)) + 16
    events, count = np.zeros((capacity, 4)), np.zeros(1, dtype=np.int64)
    run_kernel(x, v, th, w, 0.0, steps, dt, every, model.roller_mass, float(model.gravity[0]),
               float(model.gravity[1]), L0, model.link_stiffness, model.link_damping,
               model.clearance, model.hinge_friction * model.pin_radius, cmax, spr, trig, gtab, reach,
               search, win, J, K, C, mkind, mp, mdof, msign, rkind, rM, rwn, rbrk,
               rsign, *rec, energy, cand, eng, events, count, 0.0, theta,
               hinge_implicit(model, dt))
    times = np.arange(rows, dtype=np.float64) * every * dt
    kernel_args = (L0, spr, J, K, th0)
    e_start = state_energy(model, x0, v0, th0, w0, *kernel_args)
    e_end = state_energy(model, x, v, th, w, *kernel_args)
    return LinkLevelResult.build(
        drive=drive, geometry=geometry, model=model, times=times, records=rec, dt=dt,
        steps=steps, energy_terms=energy, energy_start=e_start, energy_end=e_end,
        events=events[:int(count[0])], closing_misfit=asm.closing_misfit,
        steady_window=steady_window, equilibrium=eq.to_dict())


def default_step(model: LinkLevelModel, implicit: bool = False) -> float:
    """Default time step [s].

    Explicit link springs: Δt_e = :data:`COURANT`·2/ω_max, ω_max² = (4k_link + k_c)/m (the
    roller between two links on one tooth). Implicit link springs: stable below
    :data:`COURANT`·2/ω_c, ω_c² = k_c/m, the explicit part alone [HughesLiu1978]; the step
    is the smaller of :data:`CONTACT_RESOLUTION`/ω_c (a roller's oscillation on a tooth
    resolved to a phase error (ω_c Δt)²/24 ≈ 1 % [Hairer2006]) and :data:`HINGE_STEPS`·Δt_e
    (the regularised hinge friction's relaxation time I/c_max = 4Δt_e in two steps,
    :func:`hinge_regularisation`), and never below Δt_e.

    The explicit Δt_e stays the default although, with the hinge friction implicit above
    it, K_D and the peak span forces hold the 2 % step-halving rule up to 1.5Δt_e on the
    seed, the 12B 15/25 drive and the eight-sprocket example: the implicit hinge solve
    costs more a step than the 1.5× step saves (docs/linklevel.md §3).

    Parameters
    ----------
    model : LinkLevelModel
        The parameters.
    implicit : bool
        Whether the link springs are taken implicitly.

    Returns
    -------
    float
        Δt [s].
    """
    explicit = COURANT * 2.0 / (TWO_PI * model.highest_frequency_hz)
    if not implicit:
        return explicit
    contact = CONTACT_RESOLUTION / (TWO_PI * model.contact_frequency_hz)
    return max(explicit, min(contact, HINGE_STEPS * explicit))


def hinge_regularisation(model: LinkLevelModel) -> float:
    """Viscous coefficient [N·m·s/rad] of the regularised Coulomb hinge friction below its
    sliding limit: a link's inertia I = m p²/2 over 4Δt_e, Δt_e the explicit step
    (:func:`default_step` with explicit link springs), c_max = m p²/(8Δt_e), whatever the
    step of the run — so that the friction law does not change with the step or the
    integrator. Taken explicitly it is stable up to Δt_e exactly (:func:`hinge_implicit`);
    above, the kernel takes it implicitly.

    Parameters
    ----------
    model : LinkLevelModel
        The parameters.

    Returns
    -------
    float
        c_max [N·m·s/rad].
    """
    return model.roller_mass * model.pitch**2 / 2.0 / (4.0 * default_step(model, False))


def hinge_implicit(model: LinkLevelModel, dt: float) -> bool:
    """Whether a run at step ``dt`` [s] takes the viscous hinges implicitly: when the
    explicit hinge friction would be unstable, Δt·c_max·λ_max/m > 2 with λ_max = 16/p² the
    zigzag mode of a straight span (the fourth difference (1, −4, 6, −4, 1)/p² of the
    hinges' relative rates, forward Euler on a viscous law [Hairer2006]), i.e. Δt >
    m p²/(8 c_max) = Δt_e (:func:`hinge_regularisation`). At and below Δt_e the explicit
    law (cheaper by about 2.4 µs a step at 128 links, docs/linklevel.md §3).

    Parameters
    ----------
    model : LinkLevelModel
        The parameters.
    dt : float
        The run's time step [s].

    Returns
    -------
    bool
        True above the explicit hinge friction's stability limit.
    """
    limit = model.roller_mass * model.pitch**2 / (8.0 * hinge_regularisation(model))
    return dt > limit * (1.0 + 1e-9)  # Δt_e itself (rounding of the two expressions) explicit


def duration_events(model: LinkLevelModel, omega: NDArray[np.float64], duration: float) -> float:
    """Expected number of roller engagements in ``duration`` [s]: Σ z_i |ω_i| t / 2π."""
    return float(np.sum(model.teeth * np.abs(omega)) * duration / TWO_PI)
