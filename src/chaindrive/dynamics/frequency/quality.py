"""Integral indices of dynamic quality of a drive ([MultimassChainDrives, §3.2])."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from chaindrive.errors import DesignError

__all__ = ["coefficient_of_dynamics"]


def coefficient_of_dynamics(dynamic_loads: ArrayLike, nominal_force: float) -> float:
    """Coefficient of dynamics K_D = 1 + F_D / F_t [-], F_D the root mean square of the
    largest dynamic loads of the branches.

    Reading of [MultimassChainDrives]'s lost formula used by the project (its 3-sprocket
    example: 44.75 N at F_t ≈ 262 N gives 1.17 against the printed 1.18).

    Parameters
    ----------
    dynamic_loads : array_like
        The largest dynamic load of every branch [N] (sign ignored).
    nominal_force : float
        Nominal peripheral force F_t = P/v̄ [N]
        (:func:`chaindrive.strength.loads.peripheral_force`).

    Returns
    -------
    float
        K_D [-].

    Raises
    ------
    DesignError
        No finite branch load, or a nominal force that is not positive.

    References
    ----------
    [MultimassChainDrives, §3.3].
    """
    loads = np.abs(np.asarray(dynamic_loads, dtype=float)).ravel()
    if loads.size == 0 or not np.all(np.isfinite(loads)):
        raise DesignError("dynamic_loads", "need at least one finite branch load")
    if not (math.isfinite(nominal_force) and nominal_force > 0):
        raise DesignError("nominal_force", f"must be positive, got {nominal_force!r}")
    return 1.0 + float(np.sqrt(np.mean(loads**2))) / nominal_force
