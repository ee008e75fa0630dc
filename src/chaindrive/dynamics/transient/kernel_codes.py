"""Integer codes and parameter arrays of the motor and resistance laws, as the compiled
start-up kernel takes them (:mod:`chaindrive.dynamics.transient.kernel`, its ahead-of-time
build, and the caller in :mod:`chaindrive.dynamics.transient.startup`). Plain Python: importing it
does not import numba.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from chaindrive.dynamics.motors import ConstantTorque, KlossMotor, RampTorque, ResistanceLaw

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import NDArray

__all__ = ["RESISTANCE_KINDS", "kloss_end_speed", "motor_code", "resistance_code"]

MOTOR_CONSTANT, MOTOR_RAMP, MOTOR_KLOSS = 0, 1, 2
RESISTANCE_NONE, RESISTANCE_CONSTANT, RESISTANCE_LINEAR, RESISTANCE_QUADRATIC = 0, 1, 2, 3
#: Kernel code of every load law (:class:`~chaindrive.dynamics.motors.ResistanceLaw` kinds).
RESISTANCE_KINDS = {"constant": RESISTANCE_CONSTANT, "linear": RESISTANCE_LINEAR,
                    "quadratic": RESISTANCE_QUADRATIC}


def motor_code(motor: Callable[[float, float], float]) -> tuple[int, NDArray[np.float64]] | None:
    """(kind, parameters) of a motor law the kernel knows, None for any other callable.

    ConstantTorque → (0, [M]); RampTorque → (1, [M, t_ramp]); KlossMotor →
    (2, [2λM_r, s_k, ω_s]) (the Kloss formula 2λM_r·s·s_k/(s² + s_k²), s = 1 − ω/ω_s,
    evaluated in the same order as ``KlossMotor.__call__``).

    Parameters
    ----------
    motor : callable
        A motor law of :mod:`chaindrive.dynamics.motors` (torque [N·m] of time [s] and speed
        [rad/s]) or any other callable.

    Returns
    -------
    tuple of (int, ndarray) or None
        The kernel's code of the law and its three parameters (torques [N·m], ramp time [s],
        slip [-], synchronous speed [rad/s] as listed above); None for a law the kernel does
        not know.
    """
    if type(motor) is ConstantTorque:
        return MOTOR_CONSTANT, np.array([motor.torque, 0.0, 0.0])
    if type(motor) is RampTorque:
        return MOTOR_RAMP, np.array([motor.torque, motor.ramp_time, 0.0])
    if type(motor) is KlossMotor:
        return MOTOR_KLOSS, np.array([2.0 * motor.breakdown_ratio * motor.rated_torque,
                                      motor.critical_slip, motor.synchronous_speed])
    return None


def resistance_code(law: ResistanceLaw | None, n: int) -> tuple[int, NDArray[np.float64], NDArray[np.float64],
                                                 float] | None:
    """(kind, torques M_i [N·m], nominal speeds ω_n,i [rad/s], breakaway) of a
    :class:`~chaindrive.dynamics.motors.ResistanceLaw` (None law: kind 0); None if the kind
    is unknown.

    Parameters
    ----------
    law : ResistanceLaw or None
        The moments of resistance of the sprockets.
    n : int
        Number of sprockets [-] (the torques and speeds are broadcast to it).

    Returns
    -------
    tuple or None
        The kernel's code of the law, the torques (n,) [N·m], the nominal speeds (n,)
        [rad/s] and the breakaway fraction of the nominal speed [-]; None for an unknown kind.
    """
    if law is None:
        return RESISTANCE_NONE, np.zeros(n), np.ones(n), 1.0
    kind = RESISTANCE_KINDS.get(law.kind)
    if kind is None:
        return None
    return (kind, np.broadcast_to(np.asarray(law.torques, float), (n,)).copy(),
            np.broadcast_to(np.asarray(law.nominal_speeds, float), (n,)).copy(),
            float(law.breakaway))


def kloss_end_speed(w: float, a: float, fw: float, g: float, gain: float, kappa: float,
                    peak: float, sk: float, ws: float) -> float:
    """Mean speed over a step of the coordinate that carries a Kloss motor, by backward
    Euler on the motor law (the caller's fallback where the linearised step does not hold:
    the rising branch of the curve steeper than the step resolves).

    The motor force f(u) = κ T(g_m u), T = A s s_k/(s² + s_k²), s = 1 − g_m u/ω_s. With the
    force f(w) held the step reaches the mean speed a; a force increment Δf changes it by
    g Δf. The end speed u solves u − a = g (f(u) − f(w)), a cubic in s:
    β s³ − α s² + (β s_k² + γ) s − α s_k² = 0 with β = ω_s/g_m, α = β − (a − g f(w)),
    γ = g κ A s_k. Of its real roots the one first met going from w toward a is taken: the
    speed the motor reaches within the step, not an equilibrium beyond another one.

    Parameters
    ----------
    w : float
        Mean speed over the previous step [rad/s or m/s of the coordinate].
    a : float
        Mean speed of the step with f(w) held [same unit].
    fw : float
        f(w) [N·m or N].
    g : float
        Mean-speed response of the coordinate to a held force [speed unit per force unit].
    gain : float
        g_m: motor shaft speed per coordinate speed [-].
    kappa : float
        κ: gain × efficiency from the motor torque to the coordinate's force [-].
    peak : float
        A = 2 λ M_r [N·m].
    sk : float
        Critical slip s_k [-].
    ws : float
        Synchronous speed ω_s [rad/s].

    Returns
    -------
    float
        u [speed unit]; a when no root lies toward a (cannot happen for a bounded curve).

    References
    ----------
    [HairerWanner1996, §IV.1] (backward Euler); the Kloss formula as in
    :class:`~chaindrive.dynamics.motors.KlossMotor`.
    """
    if a == w or gain == 0.0:
        return a
    beta = ws / gain
    alpha = beta - (a - g * fw)
    gamma = g * kappa * peak * sk
    # s³ + c2 s² + c1 s + c0 = 0: Cardano's or the trigonometric form, each real root
    # polished by two Newton steps (one real root: taken three times)
    c2, c1, c0 = -alpha / beta, sk * sk + gamma / beta, -alpha * sk * sk / beta
    shift = c2 / 3.0
    p = c1 - c2 * shift
    q = 2.0 * shift ** 3 - shift * c1 + c0
    disc = 0.25 * q * q + p * p * p / 27.0
    best, dist = a, math.inf
    for k in range(3):
        if disc >= 0.0 or p >= 0.0:
            r = math.sqrt(max(disc, 0.0))
            x, y = -0.5 * q + r, -0.5 * q - r
            s = math.copysign(abs(x) ** (1.0 / 3.0), x) + math.copysign(abs(y) ** (1.0 / 3.0),
                                                                       y) - shift
        else:
            m = 2.0 * math.sqrt(-p / 3.0)
            phi = math.acos(min(1.0, max(-1.0, 3.0 * q / (p * m)))) / 3.0
            s = m * math.cos(phi - 2.0 * math.pi * k / 3.0) - shift
        for _ in range(2):
            dp = (3.0 * s + 2.0 * c2) * s + c1
            if dp != 0.0:
                s -= (((s + c2) * s + c1) * s + c0) / dp
        u = ws * (1.0 - s) / gain
        if (u - w) * (a - w) >= 0.0 and abs(u - w) < dist:
            best, dist = u, abs(u - w)
    return best
