"""Inputs of the dynamic response of a drive and the result the analysis assembles.

:class:`DynamicResponse` (built by :mod:`chaindrive.analysis`) holds the fragments
``dynamics.startup``, ``dynamics.steady``, ``dynamics.afc``,
``dynamics.coefficient_of_dynamics`` and ``strength.k1/k2/k2min/allowable_k``
([MultimassChainDrives, §3.6]).

Defaults (docs/dynamic_response.md §5): induction motor by Kloss with the drive's power and the
driver's speed as rated values, λ = 2.5, s_k = 0.25; resistance ∝ speed on the driven
sprockets with their power shares at the nominal speed; pre-tension T_0 the sag tension of
the span leaving the driver; polygonal excitation with 10 harmonics; damping ζ of the model.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.excitation import (
    SpanExcitation,
    chain_error_excitation,
    eccentricity_excitation,
    path_positions,
)
from chaindrive.dynamics.frequency.afc import AfcResult
from chaindrive.dynamics.frequency.steady import SteadyStateResult
from chaindrive.dynamics.motors import (
    ConstantTorque,
    KlossMotor,
    RampTorque,
)
from chaindrive.dynamics.transient.startup import (
    PolygonalLaw,
    StartupResult,
)
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, DynamicsSettings

__all__ = ["DynamicResponse", "disturbance_excitations", "motor_of", "polygonal_law"]




def _speeds(drive: Drive) -> tuple[float, NDArray[np.float64]]:
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    z = np.array([s.teeth for s in drive.sprockets], float)
    return driver.speed, driver.speed * driver.teeth / z


@shared_parameters
def disturbance_excitations(drive: Drive, geometry: GeometryResult, *,
                            eccentricity: Sequence[float] | None = None,
                            pitch_scatter: float = 0.0, accumulated_error: float = 0.0
                            ) -> dict[str, SpanExcitation]:
    """The optional internal disturbances as span excitations at the nominal speed: sprocket
    eccentricity (n,) [m] (once per revolution), link pitch scatter σ [m] and an accumulated
    chain error Δ [m] (once per chain revolution; :mod:`chaindrive.dynamics.excitation`).

    Parameters
    ----------
    drive : Drive
        The drive (the driver's speed).
    %(geometry)s
    eccentricity : sequence of float | None
        ε of every sprocket [m].
    pitch_scatter : float
        σ [m].
    accumulated_error : float
        Δ [m].

    Returns
    -------
    dict
        "eccentricity" and/or "chain_error" → SpanExcitation.
    """
    w_d, _ = _speeds(drive)
    wz = drive.driver.teeth * w_d
    extra: dict[str, SpanExcitation] = {}
    if eccentricity is not None and np.any(np.asarray(eccentricity) > 0):
        extra["eccentricity"] = eccentricity_excitation(geometry, wz, eccentricity)
    if pitch_scatter > 0 or accumulated_error != 0:
        extra["chain_error"] = chain_error_excitation(geometry, wz, pitch_scatter=pitch_scatter,
                                                      accumulated_error=accumulated_error)
    return extra



def polygonal_law(geometry: GeometryResult) -> PolygonalLaw:
    """Exact polygonal hinge law of every span of a contour (for the start-up).

    Parameters
    ----------
    geometry : GeometryResult
        The contour (teeth, tangent-point path positions).

    Returns
    -------
    PolygonalLaw
        The pitch, and the teeth and path positions of both ends of every span.

    References
    ----------
    [ChainNonUniformity].
    """
    s0, s1 = path_positions(geometry)
    z = np.array([g.teeth for g in geometry.sprockets], float)
    starts = np.array([sp.start for sp in geometry.spans])
    ends = np.array([sp.end for sp in geometry.spans])
    return PolygonalLaw(geometry.pitch, z[starts], z[ends], s0, s1)



@dataclass(frozen=True, slots=True, eq=False)
class DynamicResponse:
    """Start-up, steady state (polygonal), AFC, disturbance loads and the two-stage check.

    Parameters
    ----------
    startup : StartupResult or None
        The start-up (None: not run).
    steady : SteadyStateResult
        Steady response to the polygonal excitation at the nominal speed.
    afc : AfcResult
        The speed sweep.
    disturbances : dict of str to SteadyStateResult
        Steady loads of the optional internal disturbances, by name.
    span_tensions : ndarray
        (n,) operating span tensions F_R [N].
    breaking_load : float
        Breaking load Q of the chain [N].
    allowable_k : float
        Allowable dynamic safety factor [k] [-].
    """

    startup: StartupResult | None
    steady: SteadyStateResult
    afc: AfcResult
    disturbances: dict[str, SteadyStateResult]
    span_tensions: NDArray[np.float64]
    breaking_load: float
    allowable_k: float

    def strength_dict(self) -> dict[str, Any]:
        """``strength.k1/k2/k2min/allowable_k`` ([MultimassChainDrives, §3.6])."""
        k1 = self.startup.k1 if self.startup is not None else None
        factors = [k for k in (k1, self.steady.k2, self.steady.k2_min) if k is not None]
        return {"k1": k1, "k2": self.steady.k2, "k2min": self.steady.k2_min,
                "allowable_k": self.allowable_k,
                "dynamic_check_passed": bool(factors) and min(factors) >= self.allowable_k}

    def to_dict(self) -> dict[str, Any]:
        """JSON fragment: {"dynamics": {...}, "strength": {...}}."""
        steady = self.steady.to_dict()
        steady.pop("time_s")
        steady.pop("span_load_trace_n")
        dyn: dict[str, Any] = {
            "startup": None if self.startup is None else self.startup.to_dict(),
            "steady": steady,
            "coefficient_of_dynamics": self.steady.coefficient_of_dynamics,
            "afc": {"max_span_dynamic_load_n": self.afc.max_span_load.tolist(),
                    "peak_tooth_frequencies_hz": self.afc.peak_tooth_frequencies_hz.tolist()},
            "disturbances": {k: {"span_dynamic_load_n": v.span_dynamic_load.tolist()}
                             for k, v in self.disturbances.items()},
        }
        return {"dynamics": dyn, "strength": self.strength_dict()}


def motor_of(settings: DynamicsSettings, power: float, speed: float
             ) -> Callable[[float, float], float]:
    """The motor law a design's ``[dynamics]`` table names: Kloss induction motor rated at the
    drive's power and driver speed, constant rated torque P/ω, or a soft-start ramp to it.

    Parameters
    ----------
    settings : DynamicsSettings
        The ``[dynamics]`` table (law, λ, s_k, ramp time).
    power : float
        Rated power P [W].
    speed : float
        Rated speed ω of the driver [rad/s].

    Returns
    -------
    callable
        Torque [N·m] of time [s] and speed [rad/s]
        (:mod:`chaindrive.dynamics.motors`).
    """
    if settings.motor == "kloss":
        return KlossMotor(power, speed, settings.breakdown_ratio, settings.critical_slip)
    if settings.motor == "ramp":
        return RampTorque(power / speed, settings.ramp_time)
    return ConstantTorque(power / speed)



