"""Dynamic response of a drive: start-up, steady state, AFC and the two-stage check.

Entry point for :mod:`chaindrive.analysis`: :func:`dynamics_response` returns a
:class:`DynamicResponse` whose ``to_dict()`` holds the fragments ``dynamics.startup``,
``dynamics.steady``, ``dynamics.afc``, ``dynamics.coefficient_of_dynamics`` and
``strength.k1/k2/k2min/allowable_k`` ([MultimassChainDrives, §3.6]).

Defaults (docs/dynamic_response.md §5): induction motor by Kloss with the drive's power and the
driver's speed as rated values, λ = 2.5, s_k = 0.25; resistance ∝ speed on the driven
sprockets with their power shares at the nominal speed; pre-tension T_0 the sag tension of
the span leaving the driver; polygonal excitation with 10 harmonics; damping ζ of the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.afc import AfcResult, afc_sweep
from chaindrive.dynamics.excitation import (
    SpanExcitation,
    chain_error_excitation,
    eccentricity_excitation,
    path_positions,
    polygonal_excitation,
)
from chaindrive.dynamics.motors import (
    ConstantTorque,
    KlossMotor,
    RampTorque,
    ResistanceKind,
    ResistanceLaw,
)
from chaindrive.dynamics.quality import nominal_peripheral_force
from chaindrive.dynamics.startup import (
    STEPS_PER_PERIOD,
    PolygonalLaw,
    StartupResult,
    simulate_startup,
)
from chaindrive.dynamics.steady import SteadyStateResult, damping_beta, steady_state
from chaindrive.errors import DesignError
from chaindrive.strength.loads import installed_sag_ratio, loads_of, power_shares, sag_tension
from chaindrive.strength.safety import ALLOWABLE_DYNAMIC_SAFETY

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from chaindrive.dynamics.ring import RingModel
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, DynamicsSettings

__all__ = ["DynamicResponse", "disturbance_excitations", "disturbance_responses",
           "drive_startup", "dynamics_response", "mean_radii", "motor_of", "polygonal_law",
           "polygonal_steady", "speed_sweep", "startup_pretension"]

TWO_PI = 2.0 * math.pi


def mean_radii(drive: Drive) -> NDArray[np.float64]:
    """R̄_i = z_i p/2π [m]: chain travel per radian of sprocket i.

    Parameters
    ----------
    drive : Drive
        The drive (teeth and pitch).

    Returns
    -------
    ndarray
        (n,) R̄_i [m].

    References
    ----------
    [ChainNonUniformity] (the mean chain speed z p ω/2π).
    """
    return np.array([s.teeth for s in drive.sprockets], float) * drive.chain.pitch / TWO_PI


def _speeds(drive: Drive) -> tuple[float, NDArray[np.float64]]:
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    z = np.array([s.teeth for s in drive.sprockets], float)
    return driver.speed, driver.speed * driver.teeth / z


def startup_pretension(drive: Drive, geometry: GeometryResult) -> float:
    """Pre-tension T₀ [N] of the spans at rest: the sag tension of the span leaving the driver
    at the installed sag (:func:`chaindrive.strength.loads.sag_tension`,
    :func:`chaindrive.strength.loads.installed_sag_ratio`), the F₀ of the static loads.

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult
        Its contour.

    Returns
    -------
    float
        T₀ [N].
    """
    slack = next((s for s in geometry.spans if s.start == drive.driver_index), geometry.spans[0])
    return float(sag_tension(drive.chain.spec.mass_per_length, slack.length, slack.inclination,
                             installed_sag_ratio(drive)))


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
    geometry : GeometryResult
        Its contour.
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


def _shares(drive: Drive) -> NDArray[np.float64]:
    return np.asarray(power_shares(drive), dtype=float)


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


def drive_startup(drive: Drive, geometry: GeometryResult, model: RingModel, *,
                  motor: Callable[[float, float], float] | None = None,
                  resistance: ResistanceKind = "linear", duration: float = 1.0,
                  dt: float | None = None, pretension: float | None = None,
                  polygonal: bool = True) -> StartupResult:
    """Start-up transient of ``drive`` (see :func:`chaindrive.dynamics.startup.simulate_startup`).

    Parameters
    ----------
    drive : Drive
        The drive (one contour's share of the power).
    geometry : GeometryResult
        Its contour.
    model : RingModel
        Its ring model (:func:`chaindrive.dynamics.drive.ring_model`).
    motor : callable or None
        Motor torque law motor(t, ω) [N·m] of time [s] and driver speed [rad/s] (None: Kloss
        from ``drive.power`` and the driver speed).
    resistance : {"constant", "linear", "quadratic"}
        Law of the moments of resistance of the driven sprockets.
    duration : float
        Simulated time [s].
    dt : float or None
        Time step [s] (None: the solver's own from the highest natural frequency).
    pretension : float or None
        Pre-tension T_0 of the spans at rest [N] (None: the sag tension,
        :func:`startup_pretension`).
    polygonal : bool
        True includes the polygonal excitation.

    Returns
    -------
    StartupResult
        Span forces and speeds over time, the peaks and k₁.

    References
    ----------
    [MultimassChainDrives, §3.2–3.3, Fig. 2].
    """
    w_d, w = _speeds(drive)
    if drive.power is None and motor is None:
        raise DesignError("drive.power", "a start-up needs the power (or an explicit motor)")
    P = drive.power or 0.0
    if motor is None:
        motor = KlossMotor(P, w_d)
    law = ResistanceLaw(resistance, _shares(drive) * P / w, w) if P > 0 else None
    T0 = startup_pretension(drive, geometry) if pretension is None else pretension
    if dt is None:
        f1 = model.modal().first_elastic_frequency_hz
        fz = drive.driver.teeth * w_d / TWO_PI
        dt = 1.0 / (STEPS_PER_PERIOD * max(f1 if f1 > 0 else 0.0, fz))
    return simulate_startup(
        model.masses_kg, model.stiffness_n_per_m, mean_radii(drive), damping_beta(model),
        motor, drive.driver_index, law, duration=duration, dt=dt, pretension=T0,
        polygonal=polygonal_law(geometry) if polygonal else None,
        breaking_load=drive.chain.spec.breaking_load)


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


def polygonal_steady(drive: Drive, geometry: GeometryResult, model: RingModel, *,
                     span_tensions: ArrayLike, harmonics: int = 10,
                     resonance_loads: ArrayLike | None = None) -> SteadyStateResult:
    """Steady response to the polygonal excitation at the nominal speed, with K_D and the
    dynamic safety factors k₂ and (given the resonance loads F₂max of the run-up) k₂min.
    K_D = 1 + F_D/F_t with F_t the nominal peripheral force P/v.

    Parameters
    ----------
    drive : Drive
        The drive (one contour's share of the power).
    geometry : GeometryResult
        Its contour.
    model : RingModel
        Its ring model (:func:`chaindrive.dynamics.drive.ring_model`).
    span_tensions : array_like
        (n,) operating span tensions F_R [N].
    harmonics : int
        Harmonics of the tooth frequency [-].
    resonance_loads : array_like or None
        (n,) resonance loads F₂max per span [N] (None: no k₂min).

    Returns
    -------
    SteadyStateResult
        The steady response with K_D, k₂ and k₂min.

    References
    ----------
    [MultimassChainDrives, §3.3, §3.6].
    """
    w_d, _ = _speeds(drive)
    ex = polygonal_excitation(geometry, drive.driver.teeth * w_d, harmonics)
    Ft = (nominal_peripheral_force(drive.power, geometry.sprockets[drive.driver_index]
                                   .pitch_diameter, w_d) if drive.power else None)
    radii = np.array([g.pitch_radius for g in geometry.sprockets])
    return steady_state(model, ex, radii=radii, nominal_force=Ft,
                        teeth=[s.teeth for s in drive.sprockets],
                        breaking_load=drive.chain.spec.breaking_load,
                        operating_forces=np.asarray(span_tensions, float),
                        resonance_loads=resonance_loads)


def speed_sweep(drive: Drive, geometry: GeometryResult, model: RingModel, *,
                harmonics: int = 10, speed_range: tuple[float, float] = (0.1, 1.5),
                points: int = 2000) -> AfcResult:
    """Amplitude–frequency characteristic: the steady polygonal response over driver speeds
    from speed_range[0] to speed_range[1] times the nominal one; its per-span maxima are the
    resonance loads F₂max of a run-up through that range.

    Parameters
    ----------
    drive : Drive
        The drive (one contour's share of the power).
    geometry : GeometryResult
        Its contour.
    model : RingModel
        Its ring model (:func:`chaindrive.dynamics.drive.ring_model`).
    harmonics : int
        Harmonics of the tooth frequency [-].
    speed_range : tuple of float
        Lowest and highest driver speed as fractions of the nominal one [-].
    points : int
        Number of speeds [-].

    Returns
    -------
    AfcResult
        The sweep.

    References
    ----------
    [MultimassChainDrives, §3.3, Fig. 3].
    """
    w_d, _ = _speeds(drive)
    ex = polygonal_excitation(geometry, drive.driver.teeth * w_d, harmonics)
    return afc_sweep(model, ex, np.linspace(*speed_range, points) * w_d, drive.driver.teeth)


def disturbance_responses(drive: Drive, geometry: GeometryResult, model: RingModel, *,
                          eccentricity: Sequence[float] | None = None,
                          pitch_scatter: float = 0.0, accumulated_error: float = 0.0
                          ) -> dict[str, SteadyStateResult]:
    """Steady loads of the optional internal disturbances, each on its own (see
    :mod:`chaindrive.dynamics.excitation`).

    Parameters
    ----------
    drive : Drive
        The drive (one contour's share of the power).
    geometry : GeometryResult
        Its contour.
    model : RingModel
        Its ring model (:func:`chaindrive.dynamics.drive.ring_model`).
    eccentricity : sequence of float or None
        Eccentricity ε of every sprocket [m] (once per revolution; None: none).
    pitch_scatter : float
        Standard deviation σ of the link pitches [m].
    accumulated_error : float
        Accumulated chain length error Δ [m] (once per chain revolution).

    Returns
    -------
    dict of str to SteadyStateResult
        ``"eccentricity"`` and/or ``"chain_error"`` → its steady response.

    References
    ----------
    [MultimassChainDrives, §2].
    """
    extra = disturbance_excitations(drive, geometry, eccentricity=eccentricity,
                                    pitch_scatter=pitch_scatter,
                                    accumulated_error=accumulated_error)
    radii = np.array([g.pitch_radius for g in geometry.sprockets])
    return {k: steady_state(model, v, radii=radii, teeth=[s.teeth for s in drive.sprockets])
            for k, v in extra.items()}


def dynamics_response(drive: Drive, geometry: GeometryResult, model: RingModel, *,
                      span_tensions: Sequence[float] | None = None, harmonics: int = 10,
                      startup: bool = True, startup_duration: float = 1.0,
                      motor: Callable[[float, float], float] | None = None,
                      resistance: ResistanceKind = "linear",
                      speed_range: tuple[float, float] = (0.1, 1.5), afc_points: int = 2000,
                      eccentricity: Sequence[float] | None = None,
                      pitch_scatter: float = 0.0, accumulated_error: float = 0.0,
                      allowable: float = ALLOWABLE_DYNAMIC_SAFETY) -> DynamicResponse:
    """Every response stage of ``drive`` at once (what :class:`chaindrive.analysis.Analysis`
    computes stage by stage): the speed sweep (F₂max), the polygonal steady state with K_D,
    k₂, k₂min, the disturbances and the start-up.

    Parameters
    ----------
    drive : Drive
        The drive (one contour's share of the power).
    geometry : GeometryResult
        Its contour.
    model : RingModel
        Its ring model (:func:`chaindrive.dynamics.drive.ring_model`).
    span_tensions : sequence of float or None
        (n,) operating span tensions F_R [N] (None: :func:`chaindrive.strength.loads.loads_of`).
    harmonics : int
        Harmonics of the tooth frequency [-].
    startup : bool
        True runs the start-up.
    startup_duration : float
        Simulated start-up time [s].
    motor : callable or None
        Motor torque law [N·m] of time [s] and speed [rad/s] (None: :func:`motor_of`).
    resistance : {"constant", "linear", "quadratic"}
        Law of the moments of resistance.
    speed_range : tuple of float
        Speed sweep range as fractions of the nominal driver speed [-].
    afc_points : int
        Speeds of the sweep [-].
    eccentricity : sequence of float or None
        Eccentricity ε of every sprocket [m] (once per revolution; None: none).
    pitch_scatter : float
        Standard deviation σ of the link pitches [m].
    accumulated_error : float
        Accumulated chain length error Δ [m] (once per chain revolution).
    allowable : float
        Allowable dynamic safety factor [k] [-] (default 2.5, [MultimassChainDrives, §3.6]).

    Returns
    -------
    DynamicResponse
        All stages and the two-stage check.

    References
    ----------
    [MultimassChainDrives, §3.2–3.6].
    """
    if span_tensions is not None:
        T = np.asarray(span_tensions, float)
    elif drive.power is not None:
        T = np.asarray(loads_of(drive, geometry).span_tensions, float)
    else:
        T = np.zeros(len(drive.sprockets))
    afc = speed_sweep(drive, geometry, model, harmonics=harmonics, speed_range=speed_range,
                      points=afc_points)
    steady = polygonal_steady(drive, geometry, model, span_tensions=T, harmonics=harmonics,
                              resonance_loads=afc.max_span_load)
    dist = disturbance_responses(drive, geometry, model, eccentricity=eccentricity,
                                 pitch_scatter=pitch_scatter, accumulated_error=accumulated_error)
    st = (drive_startup(drive, geometry, model, motor=motor, resistance=resistance,
                        duration=startup_duration)
          if startup and (drive.power or motor is not None) else None)
    return DynamicResponse(st, steady, afc, dist, T, drive.chain.spec.breaking_load, allowable)
