"""Integer codes and parameter arrays of the motor and resistance laws, as the compiled
start-up kernel takes them (:mod:`chaindrive.dynamics.transient.kernel`, its ahead-of-time
build, and the caller in :mod:`chaindrive.dynamics.transient.startup`). Plain Python: importing it
does not import numba.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from chaindrive.dynamics.motors import ConstantTorque, KlossMotor, RampTorque, ResistanceLaw

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import NDArray

__all__ = ["RESISTANCE_KINDS", "motor_code", "resistance_code"]

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
