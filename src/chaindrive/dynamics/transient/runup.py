"""The run-up of the drive as one rigid body: the motor's torque against the machines' torques
referred to the motor shaft, the time to reach the working speed, and whether the motor
starts the drive at all (docs/dynamics.md §5).

Rigid, the whole drive turns in its rigid-body mode φ (K φ = 0, the chain taut), scaled so
the motor turns at ω. Projected on it, the equation of motion of the drive is the one of an
electric drive [Chilikin1981]:

    J_red dω/dt = η M_M(t, ω) − M_L(ω),    J_red = φᵀ M φ,
    M_L(ω) = Σ_j i_j M_R,j(i_j ω) / η_j,

i_j = ω_j/ω the speed ratio of machine j to the motor, η the efficiencies of the gear stages
(the same places, gains and efficiencies as the start-up of :mod:`.drive_startup`). The
motor accelerates the drive only while η M_M > M_L; the **working speed** ω_w is the first
speed where the two meet, and the time to 95 % of it is the quadrature

    t₉₅ = ∫₀^{0.95 ω_w} J_red dω / (η M_M(ω) − M_L(ω))   (Gauss–Legendre),

after which the speed approaches ω_w with the time constant τ = J_red / (−d(η M_M − M_L)/dω)
at ω_w. A torque law that ramps in time (a soft start) is taken at its full torque: the
run-up then takes at most the ramp time longer. The elastic model's start-up (:mod:`.startup`)
is the reference; this estimate gives it a duration to simulate and says when a motor cannot
start its machines (its torque falls to the load's below the working speed: the drive
stalls there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

from chaindrive.dynamics.motors import (
    ConstantTorque,
    KlossMotor,
    RampTorque,
    ResistanceKind,
    ResistanceLaw,
)

if TYPE_CHECKING:
    from chaindrive.dynamics.model.assembly import LinearModel
    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.dynamics.transient.startup import StartupResult

__all__ = ["LONGEST_STARTUP", "RUNUP_FRACTION", "SHORTEST_STARTUP", "RunUp", "elastic_stall",
           "rigid_body_shape", "rigid_runup", "startup_durations"]

FloatArray = NDArray[np.float64]

RUNUP_FRACTION = 0.95
"""Share of the working speed that ends the run-up (as :func:`.startup.runup_time`) [-]."""

GRID = 801
"""Speeds at which the torques are compared, from standstill to the top speed [-]."""

SETTLE_SHARE = 0.01
"""The speed has settled within this share of the working speed [-]."""

SHORTEST_STARTUP = 1.0
"""The shortest automatic start-up [s] (the duration a design had before it was automatic)."""

LONGEST_STARTUP = 60.0
"""The longest start-up simulated [s] (the bound of ``[dynamics] startup_duration``)."""


@dataclass(frozen=True, slots=True)
class RunUp:
    """The rigid-drive run-up (module docstring).

    Parameters
    ----------
    inertia : float
        J_red, the drive's inertia referred to the motor shaft [kg·m²].
    nominal_speed : float
        The motor's nominal speed [rad/s].
    working_speed : float
        ω_w, the first speed where η M_M = M_L [rad/s] (nan: none up to the top speed).
    runup_time : float
        t₉₅ [s] (inf when the drive stalls below 95 % of the nominal speed).
    time_constant : float
        τ of the final approach to ω_w [s] (nan without a working speed).
    torque_ratio : float
        Least η M_M / M_L from standstill to 95 % of the nominal speed [-] (inf without a
        load).
    ratio_speed : float
        The speed of that least ratio [rad/s].
    ramp_time : float
        Time of the motor's torque ramp [s] (0 for a law without one).
    """

    inertia: float
    nominal_speed: float
    working_speed: float
    runup_time: float
    time_constant: float
    torque_ratio: float
    ratio_speed: float
    ramp_time: float = 0.0

    @property
    def starts(self) -> bool:
        """True when the motor's torque exceeds the load's up to 95 % of the nominal speed."""
        return self.torque_ratio > 1.0

    @property
    def speed_settled_time(self) -> float:
        """t₉₅ + τ ln(5 %/1 %) + the ramp: the speed within 1 % of ω_w [s] (an upper
        estimate with a ramp; inf when the drive stalls)."""
        if not self.starts or not math.isfinite(self.runup_time):
            return math.inf
        tail = self.time_constant * math.log((1.0 - RUNUP_FRACTION) / SETTLE_SHARE) \
            if math.isfinite(self.time_constant) else 0.0
        return self.runup_time + tail + self.ramp_time

    def to_dict(self) -> dict[str, Any]:
        """JSON fields, units in the names (null for what is not finite)."""
        def num(x: float) -> float | None:
            return x if math.isfinite(x) else None
        return {"method": "rigid drive: the motor's torque against the machines' referred "
                          "to the motor shaft",
                "inertia_referred_kg_m2": self.inertia,
                "nominal_speed_rad_s": self.nominal_speed,
                "working_speed_rad_s": num(self.working_speed),
                "runup_time_s": num(self.runup_time),
                "time_constant_s": num(self.time_constant),
                "torque_ratio_min": num(self.torque_ratio),
                "torque_ratio_speed_rad_s": self.ratio_speed,
                "ramp_time_s": self.ramp_time,
                "starts": self.starts}


def rigid_body_shape(linear: LinearModel) -> FloatArray | None:
    """The rigid-body mode φ of M q̈ + K q = 0 with every span taut (K φ = 0), or None when
    the model has none (a spring to the frame holds it).

    Parameters
    ----------
    linear : LinearModel
        The model's matrices.

    Returns
    -------
    ndarray or None
        (N,) φ of unit length: the eigenvector of K whose eigenvalue is zero to round-off
        (below 10⁻¹⁰ of the largest and 10⁻⁶ of the next).
    """
    b = linear.span_incidence
    k = linear.stiffness_linear + b.T @ (linear.span_stiffness[:, None] * b)
    if linear.size < 2:
        return None
    w, v = np.linalg.eigh(0.5 * (k + k.T))
    order = np.argsort(np.abs(w))
    zero, next_ = abs(w[order[0]]), abs(w[order[1]])
    if not (zero <= 1e-10 * float(np.abs(w).max()) and zero <= 1e-6 * next_):
        return None
    return np.asarray(v[:, order[0]], dtype=float)


def _root(f: Any, lo: float, hi: float, tol: float) -> float:
    """The root of a scalar function with f(lo) > 0 ≥ f(hi), by bisection to ``tol`` [its
    argument's unit]."""
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _integral(f: Any, a: float, b: float, panels: int = 64, order: int = 8) -> float:
    """∫ₐᵇ f by composite Gauss–Legendre quadrature (``panels`` × ``order`` nodes; ``f``
    vectorised), exact for polynomials of degree 2·order − 1 on each panel."""
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(a, b, panels + 1)
    half = 0.5 * np.diff(edges)
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * x[None, :]
    return float(np.sum(half[:, None] * w[None, :] * f(nodes.ravel()).reshape(nodes.shape)))


def _motor_torque(law: Any, speeds: FloatArray) -> FloatArray:
    """M_M at the speeds [N·m], a ramp at its full torque. The package's motor laws are
    arithmetic on ω, so they take the whole grid at once (the same operations element by
    element: the same numbers); any other callable is called speed by speed."""
    t = math.inf if isinstance(law, RampTorque) else 0.0
    if type(law) in (ConstantTorque, RampTorque, KlossMotor):
        return np.broadcast_to(np.asarray(law(t, speeds), dtype=float), speeds.shape).copy()
    return np.array([float(law(t, float(w))) for w in speeds])


def rigid_runup(model: DriveModel) -> RunUp | None:
    """The run-up of the drive as one rigid body (module docstring) [Chilikin1981].

    Parameters
    ----------
    model : DriveModel
        The drive's model with its motor and machines.

    Returns
    -------
    RunUp or None
        None without a motor or a rigid-body mode.
    """
    motor = model.motor
    phi = None if motor is None else rigid_body_shape(model.linear)
    if motor is None or phi is None or phi[motor.coordinate] == 0.0:
        return None
    phi = phi / (motor.gain * phi[motor.coordinate])   # the motor turns at ω: φ per rad/s
    inertia = float(phi @ model.linear.mass @ phi)
    ratios = np.array([ld.gain * phi[ld.coordinate] for ld in model.loads])
    top = motor.law.synchronous_speed if isinstance(motor.law, KlossMotor) \
        else 1.5 * motor.nominal_speed
    speeds = np.linspace(0.0, top, GRID)
    speeds[0] = 1e-9 * top  # standstill, a load's breakaway torque already acting

    laws = [ResistanceLaw(cast(ResistanceKind, ld.kind), np.array([ld.torque]),
                          np.array([ld.nominal_speed]),
                          breakaway=1e-12)  # the full breakaway torque once moving
            for ld in model.loads]

    def load(w: FloatArray) -> FloatArray:
        out = np.zeros_like(w)
        for ld, law, i in zip(model.loads, laws, ratios, strict=True):
            out += i * law(i * w) / ld.efficiency
        return out

    def net(w: FloatArray) -> FloatArray:
        return motor.efficiency * _motor_torque(motor.law, w) - load(w)

    loads = load(speeds)
    driving = motor.efficiency * _motor_torque(motor.law, speeds)
    below = np.flatnonzero(driving - loads <= 0.0)
    working = math.nan
    if below.size:
        j = int(below[0])
        lo = speeds[j - 1] if j > 0 else 0.0
        working = lo if j == 0 else _root(lambda w: float(net(np.array([w]))[0]), lo,
                                          float(speeds[j]), 1e-9 * top)
    target = RUNUP_FRACTION * (working if math.isfinite(working) else motor.nominal_speed)
    upto = speeds <= RUNUP_FRACTION * motor.nominal_speed
    span = speeds[upto]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(loads[upto] > 0.0, driving[upto] / loads[upto], np.inf)
    worst = int(np.argmin(ratio)) if ratio.size else 0
    torque_ratio = float(ratio[worst]) if ratio.size else math.inf
    runup, tau = math.inf, math.nan
    if torque_ratio > 1.0 and target > 0.0:
        runup = _integral(lambda w: inertia / net(w), 0.0, target)
        if math.isfinite(working):
            h = 1e-4 * working
            slope = float(np.diff(net(np.array([working - h, working + h])))[0]) / (2 * h)
            tau = inertia / -slope if slope < 0.0 else math.nan
    ramp = motor.law.ramp_time if isinstance(motor.law, RampTorque) else 0.0
    return RunUp(inertia, motor.nominal_speed, working, runup, tau, torque_ratio,
                 float(span[worst]) if span.size else 0.0, ramp)


def startup_durations(runup: RunUp | None, longest: float = LONGEST_STARTUP
                      ) -> tuple[float, ...]:
    """The durations an automatic start-up tries in turn until its record settles [s]: twice
    the rigid-drive time for the speed to settle within 1 % (at least
    :data:`SHORTEST_STARTUP`), then twice and four times that, none beyond ``longest``; only
    the first when the motor does not start the drive (a longer record of a stall shows
    nothing new).

    Parameters
    ----------
    runup : RunUp | None
        The rigid-drive run-up (None: the shortest duration).
    longest : float
        The longest duration allowed [s] (the bound of the field, or what the step budget
        affords).

    Returns
    -------
    tuple of float
        Increasing durations [s], at least one.
    """
    settle = math.inf if runup is None else runup.speed_settled_time
    first = SHORTEST_STARTUP if not math.isfinite(settle) else max(SHORTEST_STARTUP,
                                                                    2.0 * settle)
    first = min(first, longest)
    if runup is None or not runup.starts:
        return (first,)
    return tuple(dict.fromkeys(min(f * first, longest) for f in (1.0, 2.0, 4.0)))


def elastic_stall(runup: RunUp | None, record: StartupResult) -> bool:
    """True when the elastic start-up has not run up in a time in which the drive as one rigid
    body does (its motor starts it): the record is outside the model's range (docs/dynamics.md
    §8), and a longer one shows nothing new.

    Parameters
    ----------
    runup : RunUp | None
        The rigid-drive run-up.
    record : StartupResult
        The elastic start-up.

    Returns
    -------
    bool
    """
    simulated = float(record.times[-1]) if len(record.times) else 0.0
    return (runup is not None and runup.starts and math.isnan(record.runup_time)
            and runup.runup_time < simulated)
