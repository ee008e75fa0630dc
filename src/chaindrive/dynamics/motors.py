"""Motor and load laws of a drive: the torque a motor gives and the moments of resistance
of the driven machines, as functions of time and speed.

Used by the start-up solvers (:mod:`chaindrive.dynamics.transient.startup`) and the compiled kernel
(:mod:`chaindrive.dynamics.transient.kernel_codes` maps each law to the kernel's integer codes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from chaindrive.errors import DesignError

__all__ = ["ConstantTorque", "KlossMotor", "RampTorque", "ResistanceKind", "ResistanceLaw"]

ResistanceKind = Literal["constant", "linear", "quadratic"]


@dataclass(frozen=True, slots=True)
class ConstantTorque:
    """Motor torque M_D = const [N·m] from t = 0 (step).

    Parameters
    ----------
    torque : float
        The torque M_D [N·m].
    """

    torque: float

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at time t [s] and speed ω [rad/s]."""
        return self.torque


@dataclass(frozen=True, slots=True)
class RampTorque:
    """Soft start: M_D = M·min(1, t/t_ramp) [N·m].

    Parameters
    ----------
    torque : float
        The torque M reached at the end of the ramp [N·m].
    ramp_time : float
        Duration t_ramp of the ramp [s] (0: a step).
    """

    torque: float
    ramp_time: float

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at time t [s] and speed ω [rad/s]."""
        return self.torque * min(1.0, t / self.ramp_time) if self.ramp_time > 0 else self.torque


@dataclass(frozen=True, slots=True)
class KlossMotor:
    """Induction motor by the Kloss formula M = 2 M_k / (s/s_k + s_k/s).

    The rated slip follows from M(s_r) = M_r: s_r = s_k (λ − sqrt(λ² − 1)); the synchronous
    speed ω_s = ω_r/(1 − s_r).

    Parameters
    ----------
    rated_power : float
        Rated power P_r [W].
    rated_speed : float
        Rated speed ω_r [rad/s] (of the driver shaft).
    breakdown_ratio : float
        λ = M_k/M_r, breakdown over rated torque [-], above 1.
    critical_slip : float
        Critical (breakdown) slip s_k [-], in (0, 1).

    Raises
    ------
    DesignError
        ``motor``: a rated value that is not positive, or λ, s_k out of range.

    References
    ----------
    [Chilikin1981] (the Kloss formula); [IEC60034-12] (breakdown torques of cage motors).
    """

    rated_power: float
    rated_speed: float
    breakdown_ratio: float = 2.5
    critical_slip: float = 0.25

    def __post_init__(self) -> None:
        if not (self.rated_power > 0 and self.rated_speed > 0):
            raise DesignError("motor", "rated power and speed must be positive")
        if not (self.breakdown_ratio > 1 and 0 < self.critical_slip < 1):
            raise DesignError("motor", "need breakdown_ratio > 1 and 0 < critical_slip < 1")

    @property
    def rated_torque(self) -> float:
        """M_r = P_r/ω_r [N·m]."""
        return self.rated_power / self.rated_speed

    @property
    def rated_slip(self) -> float:
        """s_r [–]."""
        lam = self.breakdown_ratio
        return self.critical_slip * (lam - math.sqrt(lam * lam - 1.0))

    @property
    def synchronous_speed(self) -> float:
        """ω_s [rad/s]."""
        return self.rated_speed / (1.0 - self.rated_slip)

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at speed ω [rad/s]: 2 M_k s s_k / (s² + s_k²), s = 1 − ω/ω_s."""
        s = 1.0 - omega / self.synchronous_speed
        sk = self.critical_slip
        return 2.0 * self.breakdown_ratio * self.rated_torque * s * sk / (s * s + sk * sk)


@dataclass(frozen=True, slots=True, eq=False)
class ResistanceLaw:
    """Moments of resistance of the sprockets: M_R,i = M_i · φ(ω_i/ω_n,i) [N·m].

    Parameters
    ----------
    kind : {"constant", "linear", "quadratic"}
        φ = 1 once moving for "constant" (below ``breakaway``·ω_n the torque rises linearly
        from 0, a regularised dry friction), φ = ω/ω_n for "linear", φ = (ω/ω_n)|ω/ω_n| for
        "quadratic".
    torques : ndarray
        (n,) moments M_i at the nominal speeds [N·m].
    nominal_speeds : ndarray
        (n,) nominal speeds ω_n,i [rad/s].
    breakaway : float
        Fraction of the nominal speed below which a constant moment is regularised [-].
    """

    kind: ResistanceKind
    torques: NDArray[np.float64]
    nominal_speeds: NDArray[np.float64]
    breakaway: float = 0.01

    def __call__(self, omega: NDArray[np.float64]) -> NDArray[np.float64]:
        """M_R [N·m] at the speeds ω (n,) [rad/s]."""
        r = omega / self.nominal_speeds
        if self.kind == "linear":
            return self.torques * r
        if self.kind == "quadratic":
            return self.torques * r * np.abs(r)
        if self.kind == "constant":
            return self.torques * np.clip(r / self.breakaway, -1.0, 1.0)
        raise DesignError("resistance", f"unknown law {self.kind!r}")
