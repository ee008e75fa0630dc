"""Integral indices of dynamic quality of a drive ([MultimassChainDrives, §3.2])."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from chaindrive.errors import DesignError

__all__ = ["coefficient_of_dynamics", "nominal_peripheral_force"]


def nominal_peripheral_force(power: float, pitch_diameter: float, speed: float) -> float:
    """Nominal peripheral force F_t = P / v = 2P / (D ω) [N].

    power P [W]; pitch_diameter D of the driver [m]; speed ω of the driver [rad/s]
    (F_t = 60 P / (π D n) with n in rpm).
    """
    if not (power > 0 and pitch_diameter > 0 and speed > 0):
        raise DesignError("power", "power, pitch diameter and speed must be positive")
    return 2.0 * power / (pitch_diameter * speed)


def coefficient_of_dynamics(dynamic_loads: ArrayLike, nominal_force: float) -> float:
    """Coefficient of dynamics K_D = 1 + F_D / F_t [–].

    dynamic_loads : the largest dynamic load [N] of every branch (sign ignored);
    nominal_force F_t [N]. F_D is the root mean square of the branch loads. Reading of
    [MultimassChainDrives]'s lost formula used by the project (its 3-sprocket example:
    44.75 N at F_t ≈ 262 N gives 1.17 against the printed 1.18).
    """
    loads = np.abs(np.asarray(dynamic_loads, dtype=float)).ravel()
    if loads.size == 0 or not np.all(np.isfinite(loads)):
        raise DesignError("dynamic_loads", "need at least one finite branch load")
    if not (math.isfinite(nominal_force) and nominal_force > 0):
        raise DesignError("nominal_force", f"must be positive, got {nominal_force!r}")
    return 1.0 + float(np.sqrt(np.mean(loads**2))) / nominal_force
