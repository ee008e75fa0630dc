"""Static loads round a chain contour: speed, peripheral forces, span tensions, shaft loads.

Sign conventions (see :mod:`chaindrive.geometry.results`): span ``i`` runs from sprocket
``start`` to sprocket ``end`` in the direction of chain travel; the span that runs *into*
the driver is the tight one. On a sprocket the arriving span pulls back along
``−direction_in`` and the leaving span pulls forward along ``+direction_out``, so the torque
the chain puts on sprocket k is (T_out − T_in)·R_k. The driver therefore takes
T_tight − T_slack = F_t from the motor, and every driven sprocket k gives T_out − T_in = F_t,k
to its load: going *against* the chain travel from the tight span, each driven sprocket lowers
the tension by its peripheral force (idlers leave it unchanged), down to the slack span leaving
the driver, which carries F_0 + F_v [ChainDesignRU, §8]; F = P/v [Shigley2015, §17-5].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray, float_or_array
from chaindrive.errors import ChainDriveWarning, DesignError
from chaindrive.geometry.results import GeometryResult, SpanGeometry
from chaindrive.geometry.sag import DEFAULT_SAG_RATIO
from chaindrive.kinematics import mean_chain_speed
from chaindrive.model import Drive

__all__ = [
    "DEFAULT_SAG_RATIO",
    "G",
    "LoadsResult",
    "bearing_loads",
    "centrifugal_tension",
    "hinge_pressure",
    "installed_pretension",
    "installed_sag_ratio",
    "loads_of",
    "peripheral_force",
    "power_shares",
    "sag_factor",
    "sag_span",
    "sag_tension",
    "shaft_load_vectors",
    "small_sprocket",
    "span_tensions",
]

G = 9.80665  # standard gravity [m/s²]
SHARE_TOLERANCE = 1e-6


@shared_parameters
def power_shares(drive: Drive) -> NDArray[np.float64]:
    """Fraction of the drive power taken off at each sprocket.

    Driven sprockets without ``power_share`` split what the others leave equally.

    %(drive_returns)s
    numpy.ndarray
        (n,) share of each sprocket [-], 0 for the driver and idlers.

    Raises
    ------
    DesignError
        Naming ``sprockets[...].power_share`` when the shares do not add up to 1.
    """
    shares = np.zeros(len(drive.sprockets))
    driven = [i for i, s in enumerate(drive.sprockets) if s.role == "driven"]
    if not driven:
        raise DesignError("sprockets.role", "at least one sprocket must be driven to take the power")
    for s in drive.sprockets:
        if s.role != "driven" and s.power_share not in (None, 0.0):
            raise DesignError(f"sprockets[{s.name}].power_share",
                              f"only driven sprockets take power; a {s.role} takes none, "
                              f"got {s.power_share!r}")
    given: dict[int, float] = {i: share for i in driven
                               if (share := drive.sprockets[i].power_share) is not None}
    free = [i for i in driven if i not in given]
    rest = 1.0 - sum(given.values())
    names = ", ".join(drive.sprockets[i].name for i in given) or "none"
    where = f"sprockets[{drive.sprockets[next(iter(given), driven[0])].name}].power_share"
    if free and rest < -SHARE_TOLERANCE:
        raise DesignError(where,
                          f"the given shares ({names}) add up to {1 - rest:.4g} > 1")
    if not free and abs(rest) > SHARE_TOLERANCE:
        raise DesignError(where,
                          f"the shares of the driven sprockets ({names}) add up to "
                          f"{1 - rest:.4g}; they must add up to 1")
    for i, value in given.items():
        shares[i] = value
    for i in free:
        shares[i] = max(rest, 0.0) / len(free)
    return shares


def peripheral_force(power: float, speed: float) -> float:
    """Peripheral (useful) force F_t = P/v̄ [N], v̄ the mean chain speed z·p·n/60
    (:func:`chaindrive.kinematics.mean_chain_speed`).

    The one F_t of the package: the static span loads, the strength checks and the
    coefficient of dynamics K_D = 1 + F_D/F_t all divide by it. (The driver's pitch diameter
    gives v_max = Dω/2 ≥ v̄; P/v_max is not used.)

    Parameters
    ----------
    power : float
        Transmitted power P [W].
    speed : float
        Mean chain speed v̄ [m/s].

    Returns
    -------
    float
        F_t [N].

    References
    ----------
    [ISO10823] (F = P/v with v = z p n/60 000, p in mm); [Shigley2015, §17-5].
    """
    return power / speed


def centrifugal_tension(mass_per_length: float, speed: float) -> float:
    """Centrifugal tension F_v = q·v².

    Parameters
    ----------
    mass_per_length : float
        Chain mass per metre q [kg/m].
    speed : float
        Chain speed v [m/s].

    Returns
    -------
    float
        F_v [N].

    References
    ----------
    [ChainDesignRU, §8].
    """
    return mass_per_length * speed**2


def sag_factor(inclination: ArrayLike, sag_ratio: float = DEFAULT_SAG_RATIO) -> FloatOrArray:
    """Sag coefficient k_f of F_0 = k_f·q·g·a for a span inclined by ψ to the horizontal.

    Parabolic approximation of the catenary: a slack span of length a sagging by f = s·a
    (s = sag_ratio, 0.02 by default) carries the horizontal pull H = q·g·a²·cos ψ/(8 f), and
    at its upper end the weight of the hanging chain adds about q·g·a·|sin ψ|, so
    k_f = cos ψ/(8 s) + |sin ψ|. For s = 0.02: 6.25 horizontal, 1 vertical — the textbook
    range "k_f = 6 for a horizontal drive … 1 for a vertical one" (F0 = 9.81·kf·q·a with
    kf = 6 [ChainDesignRU, §8]; the intermediate textbook values 1.5 at ~45° are not
    confirmed, see docs/strength.md).

    Parameters
    ----------
    inclination : float or array_like
        ψ [rad].
    sag_ratio : float
        Sag of the slack span as a fraction s of its length [-].

    Returns
    -------
    float or numpy.ndarray
        k_f [-].

    References
    ----------
    [ChainDesignRU, §8]; [Irvine1981, ch. 1] (parabolic cable).
    """
    psi = np.abs(np.asarray(inclination, dtype=float))
    return float_or_array(np.cos(psi) / (8.0 * sag_ratio) + np.sin(psi))


def sag_tension(mass_per_length: float, length: float, inclination: float,
                sag_ratio: float = DEFAULT_SAG_RATIO, gravity: float = G) -> float:
    """Sag (gravity) tension F_0 = k_f·q·g·a of a span, k_f from :func:`sag_factor`.

    Parameters
    ----------
    mass_per_length : float
        Chain mass per metre q [kg/m].
    length : float
        Span length a [m].
    inclination : float
        Of the span to the horizontal ψ [rad].
    sag_ratio : float
        Sag as a fraction s of the span [-].
    gravity : float
        g [m/s²].

    Returns
    -------
    float
        F_0 [N].

    References
    ----------
    [ChainDesignRU, §8] (F0 = 9.81·kf·q·a).
    """
    return float(sag_factor(inclination, sag_ratio)) * mass_per_length * gravity * length


def span_tensions(slack_index: int, sprocket_forces: NDArray[np.float64],
                  spans: tuple[SpanGeometry, ...], base_tension: float) -> NDArray[np.float64]:
    """Static tension in every span.

    Going with the chain from the slack span, sprocket ``end`` of each span adds its force to
    the tension of the next span (torque balance (T_out − T_in)·R = F_t,k·R, module doc).

    Parameters
    ----------
    slack_index : int
        Index of the span leaving the driver.
    sprocket_forces : numpy.ndarray
        (n,) F_t,k given off at each sprocket k [N] (0 for idlers and the driver).
    spans : tuple of SpanGeometry
        The spans of the contour.
    base_tension : float
        Tension of the slack span F_0 + F_v [N].

    Returns
    -------
    numpy.ndarray
        (n,) tension of every span [N].
    """
    n = len(spans)
    by_start = {span.start: span.index for span in spans}
    tensions = np.empty(n)
    tensions[slack_index] = base_tension
    current = spans[slack_index]
    for _ in range(n - 1):
        k = current.end
        nxt = spans[by_start[k]]
        tensions[nxt.index] = tensions[current.index] + sprocket_forces[k]
        current = nxt
    return tensions


@shared_parameters
def shaft_load_vectors(geometry: GeometryResult, tensions: NDArray[np.float64],
                       centrifugal: float = 0.0, load_factor: float = 1.0) -> NDArray[np.float64]:
    """Shaft load vector on each sprocket.

    F_k = kв·[(T_out − F_v)·d_out − (T_in − F_v)·d_in]: the pull of the leaving span along its
    direction of travel plus the pull of the arriving span back along its own. The centrifugal
    tension F_v is balanced by the chain over the wrap and does not reach the shaft
    (Fв = kв·Ft + 2F0 [ChainDesignRU, §8]; pass ``centrifugal=0`` to keep it).

    Parameters
    ----------
    %(geometry_the_contour)s
    tensions : numpy.ndarray
        (n,) span tensions [N].
    centrifugal : float
        F_v [N].
    load_factor : float
        kв [-] (1.15 horizontal, 1.05 vertical [ChainDesignRU, §8]; default 1).

    Returns
    -------
    numpy.ndarray
        (n, 2) load on each shaft [N].

    References
    ----------
    [ChainDesignRU, §8].
    """
    n = len(geometry.sprockets)
    loads = np.zeros((n, 2))
    for span in geometry.spans:
        t = tensions[span.index] - centrifugal
        d = np.asarray(span.direction, dtype=float)
        loads[span.start] += t * d   # leaving span pulls forward
        loads[span.end] -= t * d     # arriving span pulls back
    out: NDArray[np.float64] = load_factor * loads
    return out


def hinge_pressure(force: float, operating_factor: float, bearing_area: float) -> float:
    """Mean bearing pressure in the chain joints p = F·Kэ/A.

    A of a multi-row chain already includes the row factor mр in the GOST tables.

    Parameters
    ----------
    force : float
        Peripheral force of the tight span F [N].
    operating_factor : float
        Kэ [-].
    bearing_area : float
        Projected bearing area of the whole chain A = d·B·mр [m²].

    Returns
    -------
    float
        p [Pa].

    References
    ----------
    [ChainDesignRU, Table 2A]; [TrinhChat2006].
    """
    return force * operating_factor / bearing_area


@dataclass(frozen=True, slots=True)
class LoadsResult:
    """Static loads of one contour.

    Parameters
    ----------
    speed : float
        Chain speed v [m/s].
    peripheral_force : float
        F_t of the driver [N].
    sprocket_forces : tuple of float
        Force given off at each sprocket [N] (0 for the driver and idlers).
    power_shares : tuple of float
        Share of the power of each sprocket [-].
    centrifugal_tension : float
        F_v [N].
    sag_tension : float
        F_0 of the slack span [N].
    sag_factor : float
        k_f [-].
    span_tensions : tuple of float
        Tension of each span [N].
    slack_span, tight_span : int
        Indices of the spans leaving and entering the driver.
    shaft_loads : tuple of tuple of float
        (n, 2) load vector on each shaft [N].
    warnings : tuple of ChainDriveWarning
        What the balance found.
    bearing_loads : tuple
        Per sprocket, the load vectors its two bearings carry ((x, y), (x, y)) [N], or None
        where the design gives no bearing positions (:func:`bearing_loads`).
    """

    speed: float
    peripheral_force: float
    sprocket_forces: tuple[float, ...]
    power_shares: tuple[float, ...]
    centrifugal_tension: float
    sag_tension: float
    sag_factor: float
    span_tensions: tuple[float, ...]
    slack_span: int
    tight_span: int
    shaft_loads: tuple[tuple[float, float], ...]
    warnings: tuple[ChainDriveWarning, ...] = field(default=())
    bearing_loads: tuple[tuple[tuple[float, float], tuple[float, float]] | None, ...] = ()

    @property
    def shaft_load_magnitudes(self) -> tuple[float, ...]:
        """|F_k| per sprocket [N]."""
        return tuple(math.hypot(x, y) for x, y in self.shaft_loads)

    @property
    def shaft_load_directions(self) -> tuple[float, ...]:
        """Direction of the load on each shaft [rad], from the +x axis of the drawing,
        counter-clockwise (atan2 of its components; 0 for a shaft without load)."""
        return tuple(math.atan2(y, x) if (x or y) else 0.0 for x, y in self.shaft_loads)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (forces in N, speed in m/s)."""
        return {
            "chain_speed_m_s": self.speed,
            "peripheral_force_n": self.peripheral_force,
            "sprocket_forces_n": list(self.sprocket_forces),
            "power_shares": list(self.power_shares),
            "centrifugal_tension_n": self.centrifugal_tension,
            "sag_tension_n": self.sag_tension,
            "sag_factor": self.sag_factor,
            "span_tensions_n": list(self.span_tensions),
            "slack_span": self.slack_span,
            "tight_span": self.tight_span,
            "shaft_loads_n": list(self.shaft_load_magnitudes),
            "shaft_load_vectors_n": [list(v) for v in self.shaft_loads],
            "shaft_load_directions_deg": [math.degrees(a) for a in self.shaft_load_directions],
            "bearing_load_vectors_n": [None if b is None else [list(b[0]), list(b[1])]
                                       for b in self.bearing_loads],
            "bearing_loads_n": [None if b is None else [math.hypot(*b[0]), math.hypot(*b[1])]
                                for b in self.bearing_loads],
        }


def bearing_loads(shaft_load: tuple[float, float], z1: float, z2: float
                  ) -> tuple[tuple[float, float], tuple[float, float]]:
    """The loads two bearings at z1 and z2 carry from a shaft load F at z = 0 (the
    sprocket's mid-plane): the statics of a shaft on two simple supports, R1 = F·z2/(z2 − z1),
    R2 = −F·z1/(z2 − z1) (R1 + R2 = F, R1·z1 + R2·z2 = 0). Between the bearings both carry
    a part of F in its direction; an overhung sprocket loads the nearer bearing by more than
    F and the farther one the other way.

    Parameters
    ----------
    shaft_load : tuple of float
        F (x, y) [N].
    z1, z2 : float
        Axial positions of the bearings from the sprocket's mid-plane [m], z1 ≠ z2.

    Returns
    -------
    tuple
        ((R1x, R1y), (R2x, R2y)) [N], in the direction of the load the bearing carries.

    References
    ----------
    [Shigley2015] (statics of a simply supported shaft).
    """
    fx, fy = shaft_load
    k1, k2 = z2 / (z2 - z1), -z1 / (z2 - z1)
    return (k1 * fx, k1 * fy), (k2 * fx, k2 * fy)


def _tight_and_slack(drive: Drive, geometry: GeometryResult) -> tuple[int, int]:
    d = drive.driver_index
    tight = next((s.index for s in geometry.spans if s.end == d), None)
    slack = next((s.index for s in geometry.spans if s.start == d), None)
    if tight is None or slack is None:
        raise DesignError("geometry.spans", "no span arrives at / leaves the driver")
    return tight, slack


@shared_parameters
def installed_sag_ratio(drive: Drive) -> float:
    """Sag of the slack span of the new chain as installed, as a fraction of its length [-]:
    the design's ``[chain] sag``, else :data:`DEFAULT_SAG_RATIO`.

    %(drive_returns)s
    float
        s = f/ℓ [-].
    """
    return DEFAULT_SAG_RATIO if drive.chain.sag is None else drive.chain.sag


@shared_parameters
def sag_span(drive: Drive, geometry: GeometryResult) -> SpanGeometry:
    """The span whose sag the design's ``[chain] sag`` gives: the span leaving the driver,
    the slack span in operation (the first span where none leaves it).

    Parameters
    ----------
    %(drive_geometry)s

    Returns
    -------
    SpanGeometry
        That span.
    """
    return next((s for s in geometry.spans if s.start == drive.driver_index), geometry.spans[0])


@shared_parameters
def installed_pretension(drive: Drive, geometry: GeometryResult) -> float:
    """Pre-tension F₀ = k_f·q·g·a [N] of the chain as installed: the sag tension
    (:func:`sag_tension`) of :func:`sag_span` at the installed sag
    (:func:`installed_sag_ratio`). At rest every span carries it (the tension's change
    with height along the chain, q·g·Δy, left out as in the static loads).

    Parameters
    ----------
    %(drive_geometry)s

    Returns
    -------
    float
        F₀ [N].

    References
    ----------
    [ChainDesignRU, §8].
    """
    span = sag_span(drive, geometry)
    return sag_tension(drive.chain.spec.mass_per_length, span.length, span.inclination,
                       installed_sag_ratio(drive))


@shared_parameters
def loads_of(drive: Drive, geometry: GeometryResult, *, sag_ratio: float | None = None,
             shaft_load_factor: float = 1.0) -> LoadsResult:
    """Static loads round the contour of a drive.

    F_0 is the sag tension of the slack span (the one leaving the driver), F_v = q·v²;
    tight span F_t + F_0 + F_v, slack span F_0 + F_v; see the module docstring for the
    balance at each sprocket.

    Parameters
    ----------
    drive : Drive
        The design (power [W] and the driver's speed [rad/s] needed).
    %(geometry)s
    sag_ratio : float | None
        Sag of the slack span as a fraction of its length [-]; None: the design's installed
        sag (``[chain] sag``), else :data:`DEFAULT_SAG_RATIO` (the textbook k_f = 6).
    shaft_load_factor : float
        kв of the shaft loads [-].

    Returns
    -------
    LoadsResult
        Speed, forces, tensions and shaft loads.

    References
    ----------
    [ChainDesignRU, §8]; [Shigley2015, §17-5].
    """
    if drive.power is None:
        raise DesignError("drive.power", "power is needed to compute the loads")
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    if len(geometry.spans) != len(drive.sprockets):
        raise DesignError("geometry.spans",
                          f"expected {len(drive.sprockets)} spans, got {len(geometry.spans)}")
    spec = drive.chain.spec
    if sag_ratio is None:
        sag_ratio = installed_sag_ratio(drive)
    v = float(mean_chain_speed(spec.pitch, driver.teeth, driver.speed))
    shares = power_shares(drive)
    ft = peripheral_force(drive.power, v)
    forces = shares * ft
    tight, slack = _tight_and_slack(drive, geometry)
    slack_span = geometry.spans[slack]
    fv = centrifugal_tension(spec.mass_per_length, v)
    kf = float(sag_factor(slack_span.inclination, sag_ratio))
    f0 = sag_tension(spec.mass_per_length, slack_span.length, slack_span.inclination, sag_ratio)
    tensions = span_tensions(slack, forces, geometry.spans, f0 + fv)
    shafts = shaft_load_vectors(geometry, tensions, fv, shaft_load_factor)
    warnings: list[ChainDriveWarning] = []
    if not math.isclose(tensions[tight], ft + f0 + fv, rel_tol=1e-9):
        warnings.append(ChainDriveWarning("strength.tension-balance", "strength",
                                          "tension round the contour does not close on the "
                                          "tight span"))
    return LoadsResult(
        speed=v, peripheral_force=ft, sprocket_forces=tuple(float(f) for f in forces),
        power_shares=tuple(float(s) for s in shares), centrifugal_tension=fv, sag_tension=f0,
        sag_factor=kf, span_tensions=tuple(float(t) for t in tensions), slack_span=slack,
        tight_span=tight, shaft_loads=tuple((float(x), float(y)) for x, y in shafts),
        warnings=tuple(warnings),
        bearing_loads=tuple(None if s.bearings is None
                            else bearing_loads((float(f[0]), float(f[1])), *s.bearings)
                            for s, f in zip(drive.sprockets, shafts, strict=True)),
    )


def small_sprocket(drive: Drive) -> tuple[int, float]:
    """Teeth and angular speed of the smallest loaded sprocket (driver or driven).

    Ratings and the [p] / [s] tables refer to the small sprocket of the drive; its speed
    follows from the driver's, ω_k = ω_d·z_d/z_k (one chain speed). Idlers transmit no
    torque and are left out.

    Parameters
    ----------
    drive : Drive
        The design (the driver's speed is needed).

    Returns
    -------
    tuple of (int, float)
        Teeth z [-] and angular speed ω [rad/s].

    References
    ----------
    [Shigley2015, §17-5]; n1 of [ChainDesignRU].
    """
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    loaded = [s for s in drive.sprockets if s.role in ("driver", "driven")]
    small = min(loaded, key=lambda s: s.teeth)
    return small.teeth, driver.speed * driver.teeth / small.teeth
