"""Assembly of the whole-drive model of :mod:`chaindrive.dynamics.model.build`: its parts
(the :class:`LinearModel` in the coordinates q, the motor's and the machines' places) and
how they are built from a :class:`~chaindrive.model.Drive` — sprockets with their chain
nodes, spans and wraps, the trains (shafts, couplings, gear stages, rotors, springs to the
frame), the motor's rotor and the driven machines — and condensed statically to the nodes
with an inertia [Rao2011, ch. 6], [Guyan1965].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import freeze_arrays, read_only, rebuilt
from chaindrive.dynamics.motor_inertia import estimated_rotor_inertia
from chaindrive.dynamics.motors import ConstantTorque, KlossMotor, RampTorque
from chaindrive.dynamics.torsional.engine import TorsionalEngine
from chaindrive.errors import DesignError, Quantities, Quantity
from chaindrive.kinematics import mean_chain_speed
from chaindrive.strength.loads import power_shares

if TYPE_CHECKING:
    from chaindrive.dynamics.parameters import RingParameters
    from chaindrive.dynamics.torsional.system import TorsionalSystem
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, Material, TrainElement

__all__ = [
    "CHAIN_NODE",
    "SHAFT_POISSON_RATIO",
    "DriveParts",
    "LinearModel",
    "LoadPlacement",
    "MotorPlacement",
    "assembled_parts",
    "kloss_parameters",
    "motor_rating",
    "shaft_stiffness",
]

FloatArray = NDArray[np.float64]
#: Name of the chain node at sprocket S: ``CHAIN_NODE.format("S")``.
CHAIN_NODE = "chain@{}"
#: Poisson's ratio of a shaft's material for its shear modulus G = E/(2(1 + ν)): 0.3, the
#: value of steels [Shigley2015, Table A-5].
SHAFT_POISSON_RATIO = 0.3


def shaft_stiffness(diameter: float, length: float, youngs_modulus: float,
                    poisson_ratio: float = SHAFT_POISSON_RATIO) -> float:
    """Torsional stiffness k = G π d⁴/(32 l) [N·m/rad] of a solid round shaft, G = E/(2(1+ν)).

    Parameters
    ----------
    diameter : float
        d [m].
    length : float
        l [m].
    youngs_modulus : float
        E [Pa].
    poisson_ratio : float
        ν [-].

    Returns
    -------
    float
        k [N·m/rad].

    References
    ----------
    [Shigley2015, ch. 3] (torsion of a round bar), [Roark2012, Table 10.1].
    """
    g = youngs_modulus / (2.0 * (1.0 + poisson_ratio))
    return g * math.pi * diameter**4 / (32.0 * length)


@dataclass(frozen=True, slots=True, eq=False)
class LinearModel:
    """M q̈ + C q̇ + K q = Q of a drive in its coordinates q (condensed); frozen, its arrays
    read-only (writeable inputs are copied).

    K = K_lin + Bᵀ diag(c·a) B and C = C_lin + Bᵀ diag(d·a) B, a the spans that carry (all,
    unless told) [Rao2011, ch. 6].

    Parameters
    ----------
    mass : ndarray
        (N, N) mass matrix M [kg·m²] (a chain coordinate of unit radius: [kg]).
    stiffness_linear : ndarray
        (N, N) stiffness K_lin of every element but the chain spans [N·m/rad].
    damping_linear : ndarray
        (N, N) damping C_lin of every element but the chain spans [N·m·s/rad].
    span_incidence : ndarray
        (S, N) B: span elongations e = B q [m per unit of coordinate].
    span_stiffness : ndarray
        (S,) span stiffnesses c [N/m].
    span_damping : ndarray
        (S,) span dampers d [N·s/m].
    span_tension_only : ndarray of bool
        (S,) True for a span that drops out when it goes slack.

    References
    ----------
    [Rao2011, ch. 6] (equations of motion of a multi-degree-of-freedom system).
    """

    mass: FloatArray
    stiffness_linear: FloatArray
    damping_linear: FloatArray
    span_incidence: FloatArray
    span_stiffness: FloatArray
    span_damping: FloatArray
    span_tension_only: NDArray[np.bool_]

    def __post_init__(self) -> None:
        # frozen once built: the model holds read-only arrays (copies of writeable inputs)
        for name in ("mass", "stiffness_linear", "damping_linear", "span_incidence",
                     "span_stiffness", "span_damping"):
            object.__setattr__(self, name, read_only(getattr(self, name)))
        object.__setattr__(self, "span_tension_only", read_only(self.span_tension_only, bool))

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        return rebuilt(self)  # unpickled: frozen again

    @property
    def size(self) -> int:
        """Number of coordinates N."""
        return int(self.mass.shape[0])

    @shared_parameters
    def stiffness(self, active: NDArray[np.bool_] | None = None) -> FloatArray:
        """K [N·m/rad] with the spans ``active`` carrying.

        %(active_matrix)s
            (N, N) K = K_lin + Bᵀ diag(c·a) B [N·m/rad].
        """
        return self.stiffness_linear + self._span_term(self.span_stiffness, active)

    @shared_parameters
    def damping(self, active: NDArray[np.bool_] | None = None) -> FloatArray:
        """C [N·m·s/rad] with the spans ``active`` carrying.

        %(active_matrix)s
            (N, N) C = C_lin + Bᵀ diag(d·a) B [N·m·s/rad].
        """
        return self.damping_linear + self._span_term(self.span_damping, active)

    def _span_term(self, values: FloatArray, active: NDArray[np.bool_] | None) -> FloatArray:
        """Bᵀ diag(w) B, w = ``values``·``active`` (all spans when ``active`` is None)."""
        w = values if active is None else values * active
        B = self.span_incidence
        return (B.T * w) @ B

    def scaled(self, stiffness: float = 1.0, inertia: float = 1.0) -> LinearModel:
        """The same model with every stiffness and every inertia scaled, the dampers by
        √(stiffness·inertia) so that the damping ratios ζ = d/(2√(k m)) are kept
        [Rao2011, ch. 2].

        Parameters
        ----------
        stiffness : float
            Factor on every stiffness [-].
        inertia : float
            Factor on every inertia [-].

        Returns
        -------
        LinearModel
            The scaled model.
        """
        d = math.sqrt(stiffness * inertia)
        return LinearModel(self.mass * inertia, self.stiffness_linear * stiffness,
                           self.damping_linear * d, self.span_incidence,
                           self.span_stiffness * stiffness, self.span_damping * d,
                           self.span_tension_only)


@dataclass(frozen=True, slots=True)
class MotorPlacement:
    """The motor of a drive model: the node its rotor is on and its law.

    Parameters
    ----------
    node : str
        The node of the rotor.
    coordinate : int
        Its coordinate k in q.
    gain : float
        g [-]: the forward speed of the node is ω = g q̇_k (g > 0 turning as in running).
    efficiency : float
        η [-] of the gear stages from the motor to the sprocket (the torque on q_k is
        g·η·T).
    law : callable
        Torque T(t, ω) [N·m] at time t [s] and speed ω [rad/s].
    nominal_speed : float
        Nominal speed of the node [rad/s].
    rotor_inertia : float
        Moment of inertia of the rotor [kg·m²] (0: not modelled).
    estimated : bool
        True when the rotor inertia is an estimate
        (:func:`chaindrive.dynamics.motor_inertia.estimated_rotor_inertia`).
    """

    node: str
    coordinate: int
    gain: float
    efficiency: float
    law: Callable[[float, float], float]
    nominal_speed: float
    rotor_inertia: float
    estimated: bool


@dataclass(frozen=True, slots=True)
class LoadPlacement:
    """A driven machine: its node, the law of its moment and the torque at the nominal speed.

    The moment on q_k is −g·M·φ(ω/ω_n)/η, φ the law (1, ω/ω_n or (ω/ω_n)²).

    Parameters
    ----------
    sprocket : str
        The driven sprocket whose train ends at the machine.
    node : str
        The machine's node (the outermost node of the train).
    coordinate : int
        Its coordinate k in q.
    gain : float
        g [-]: the forward speed of the node is ω = g q̇_k.
    efficiency : float
        η [-] of the gear stages from the sprocket to the machine.
    kind : str
        The law of the moment: "constant", "linear" or "quadratic" in the speed.
    torque : float
        M [N·m] at the nominal speed (its power share P_i = M ω_n).
    nominal_speed : float
        ω_n [rad/s] of the node.
    """

    sprocket: str
    node: str
    coordinate: int
    gain: float
    efficiency: float
    kind: str
    torque: float
    nominal_speed: float


# --------------------------------------------------------------------------- the builder
@dataclass(slots=True)
class _Train:
    """State of one train while it is built: its nodes and their kinematics."""

    sprocket: str
    node: str
    speed: float          # nominal angular speed of the current node [rad/s], signed
    efficiency: float     # product of the gear efficiencies from the sprocket
    nodes: list[str] = field(default_factory=list)
    description: list[dict[str, Any]] = field(default_factory=list)


def _add_element(t: TorsionalEngine, tr: _Train, k: int, e: TrainElement,
                 lookup: Callable[[str], Material], inward: bool) -> None:
    """Add one train element outward from the train's current node."""
    where = f"sprockets[{tr.sprocket}].train[{k}]"
    if e.kind == "rotor":
        if e.name and e.name != tr.node and tr.node != tr.sprocket:
            if e.name in t.node_names:
                raise DesignError(f"{where}.name", f"a node named {e.name!r} exists already")
            t.rename_node(tr.node, e.name)
            tr.nodes[-1] = tr.node = e.name
        t.add_inertia_to(tr.node, e.inertia)
        tr.description.append({"kind": "rotor", "node": tr.node, "inertia_kg_m2": e.inertia})
        return
    if e.kind == "ground":
        assert e.stiffness is not None
        t.add_ground_spring(tr.node, e.stiffness, e.damping, name=f"ground:{tr.node}:{k}")
        tr.description.append({"kind": "ground", "node": tr.node,
                                "stiffness_n_m_per_rad": e.stiffness,
                                "damping_n_m_s_per_rad": e.damping})
        return
    new = e.name or f"{tr.sprocket}.{k + 1}"
    if new in t.node_names:
        raise DesignError(f"{where}.name", f"a node named {new!r} exists already")
    t.add_inertia(new, e.inertia)
    if e.kind in ("shaft", "coupling"):
        if e.stiffness is not None:
            k_t = e.stiffness
        else:
            assert e.diameter is not None and e.length is not None
            k_t = shaft_stiffness(e.diameter, e.length, lookup(e.material).youngs_modulus)
        t.add_shaft(tr.node, new, k_t, e.damping, name=f"{e.kind}:{tr.node}-{new}")
        tr.description.append({"kind": e.kind, "from": tr.node, "to": new,
                               "stiffness_n_m_per_rad": k_t, "damping_n_m_s_per_rad": e.damping,
                               "inertia_kg_m2": e.inertia})
    else:
        assert e.ratio is not None
        # ratio = input/output speed along the power flow: inward on the driver's train
        mesh_ratio = 1.0 / e.ratio if inward else e.ratio  # ω_prev / ω_new
        t.add_gear_mesh(tr.node, new, mesh_ratio, e.efficiency, same_sense=True,
                        name=f"gear:{tr.node}-{new}")
        tr.speed /= mesh_ratio
        tr.efficiency *= e.efficiency
        tr.description.append({"kind": "gear", "from": tr.node, "to": new, "ratio": e.ratio,
                               "efficiency": e.efficiency, "inertia_kg_m2": e.inertia})
    tr.node = new
    tr.nodes.append(new)


@shared_parameters
def kloss_parameters(drive: Drive) -> tuple[float, float]:
    """(λ = M_k/M_r, s_k) of the motor's Kloss law: ``[motor]`` over ``[dynamics]``.

    %(drive_returns)s
    tuple of float
        Breakdown ratio [-] and critical slip [-].
    """
    m, s = drive.motor, drive.dynamics
    lam = m.breakdown_ratio if m is not None and m.breakdown_ratio is not None else \
        s.breakdown_ratio
    sk = m.critical_slip if m is not None and m.critical_slip is not None else s.critical_slip
    return lam, sk


@shared_parameters
def motor_rating(drive: Drive) -> tuple[float | None, float | None]:
    """(rated power [W], rated speed [rad/s]) of the motor as the model places it:
    ``[motor] rated_power`` else the drive's power; ``[motor] rated_speed`` else the driver's
    speed times the ratios of the gear stages on its train (the motor's own speed). None where
    neither is given.

    %(drive_returns)s
    tuple of float or None
    """
    m, driver = drive.motor, drive.driver
    power = m.rated_power if m is not None and m.rated_power else drive.power
    if m is not None and m.rated_speed:
        return power, m.rated_speed
    if driver.speed is None:
        return power, None
    ratios = [e.ratio for e in driver.train if e.kind == "gear" and e.ratio is not None]
    return power, abs(driver.speed * math.prod(ratios))


def _motor_law(drive: Drive, rated_power: float, rated_speed: float
               ) -> Callable[[float, float], float]:
    """The torque law of the motor (``[motor]`` over ``[dynamics]``)."""
    m, s = drive.motor, drive.dynamics
    law = (m.law if m is not None and m.law is not None else s.motor)
    lam, sk = kloss_parameters(drive)
    torque = m.torque if m is not None and m.torque is not None else rated_power / rated_speed
    if law == "kloss":
        return KlossMotor(rated_power, rated_speed, lam, sk)
    if law == "ramp":
        ramp = m.ramp_time if m is not None and m.ramp_time is not None else s.ramp_time
        return RampTorque(torque, ramp)
    return ConstantTorque(torque)


def _rotor_inertia(drive: Drive, rated_power: float, rated_speed: float
                   ) -> tuple[float, bool]:
    """(J [kg·m²], estimated) of the motor's rotor (0 without a ``[motor]`` table)."""
    m = drive.motor
    if m is None:
        return 0.0, False
    if m.rotor_inertia is not None:
        return m.rotor_inertia, False
    lam, sk = kloss_parameters(drive)
    synchronous = KlossMotor(rated_power, rated_speed, lam, sk).synchronous_speed
    try:
        return estimated_rotor_inertia(rated_power, synchronous).inertia_kg_m2, True
    except DesignError as exc:
        raise DesignError("motor.rotor_inertia", f"cannot be estimated ({exc}); give the "
                          "motor's rotor inertia, or a reducer on the driver's train") from None


def _sprocket_senses(geometry: GeometryResult) -> FloatArray:
    return np.array([-1.0 if g.side == "inside" else 1.0 for g in geometry.sprockets])


@dataclass(frozen=True, slots=True, eq=False)
class DriveParts:
    """The assembled model of a drive before its chain dampers, completeness and modes: what
    :func:`assembled_parts` returns and what
    :class:`~chaindrive.dynamics.model.build.DriveModel` extends. Frozen, its arrays
    read-only, its torsional model built (frozen too).

    Parameters
    ----------
    torsional : TorsionalEngine
        The torsional model (nodes, elements; the modal analysis).
    system : TorsionalSystem
        Its assembled matrices in reduced coordinates.
    linear : LinearModel
        Its matrices in q (massless nodes condensed [Guyan1965]).
    condensation : ndarray
        (size, N) T: the reduced coordinates of ``system`` are T q [-].
    sprocket_names : tuple of str
        The sprockets, in the order of the design.
    sprocket_coordinate : ndarray of int
        (n,) index k_i [-] of each sprocket's coordinate in q.
    sprocket_gain : ndarray
        (n,) g_i [-]: the forward angular speed of sprocket i is g_i q̇[k_i].
    pitch_radii : ndarray
        (n,) pitch radii R [m].
    mean_radii : ndarray
        (n,) mean radii R̄ = z p/2π [m] (chain travel per radian).
    nominal_speeds : ndarray
        (n,) nominal angular speeds of the sprockets [rad/s].
    rotor_names : tuple of str
        Every node of the trains with an inertia (motor and machines among them).
    rotor_coordinate : ndarray of int
        Index [-] of each rotor's coordinate in q.
    rotor_gain : ndarray
        Gain g [-] of each rotor (forward speed g q̇).
    rotor_nominal_speed : ndarray
        Nominal angular speed of each rotor [rad/s].
    motor : MotorPlacement | None
        The motor (None: the design gives none).
    loads : tuple of LoadPlacement
        The driven machines.
    span_damping_ratios : ndarray
        (S,) damping ratios ζ of the chain spans [-].
    damping_source : str
        Where ζ comes from: the design's ``[dynamics] damping_ratio``, hinge friction
        [ChainHingeDissipation] or the material pair [MultimassChainDrives, Table 1].
    reference_frequency_hz : float
        f_ref = ω_ref/2π of the chain's dampers d = 2ζk/ω_ref [Hz].
    contours : int
        m: the spans carry m parallel contours (forces per contour are F/m).
    ring : RingParameters
        The ring reduction (reduced masses, series branch stiffnesses) for the ring-model
        tools.
    driver_index : int
        Index of the driving sprocket.
    notes : tuple of str
        What the model rests on (estimates, approximations).
    trains : dict
        Sprocket name → its train as plain data (for the JSON document).
    note_quantities : tuple of Quantity
        The numbers with units the notes write (SI; :class:`chaindrive.errors.Quantities`),
        for a presenter to write in another unit system.
    """

    torsional: TorsionalEngine
    system: TorsionalSystem
    linear: LinearModel
    condensation: FloatArray
    sprocket_names: tuple[str, ...]
    sprocket_coordinate: NDArray[np.intp]
    sprocket_gain: FloatArray
    pitch_radii: FloatArray
    mean_radii: FloatArray
    nominal_speeds: FloatArray
    rotor_names: tuple[str, ...]
    rotor_coordinate: NDArray[np.intp]
    rotor_gain: FloatArray
    rotor_nominal_speed: FloatArray
    motor: MotorPlacement | None
    loads: tuple[LoadPlacement, ...]
    span_damping_ratios: FloatArray
    damping_source: str
    reference_frequency_hz: float
    contours: int
    ring: RingParameters
    driver_index: int
    notes: tuple[str, ...] = ()
    trains: dict[str, list[dict[str, Any]]] = field(default_factory=dict)
    note_quantities: tuple[Quantity, ...] = ()

    def __post_init__(self) -> None:
        freeze_arrays(self)  # frozen once built: read-only arrays

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        return rebuilt(self)  # unpickled: frozen again


def assembled_parts(drive: Drive, geometry: GeometryResult, ring: RingParameters,
                    lookup: Callable[[str], Material]) -> DriveParts:
    """The model of ``drive`` without the chain's dampers (they follow from its modes).

    Parameters
    ----------
    drive : Drive
        The validated drive.
    geometry : GeometryResult
        Its geometry.
    ring : RingParameters
        Its ring reduction (inertias, span and wrap stiffnesses, sag factors).
    lookup : callable
        Material name → :class:`~chaindrive.model.Material`.

    Returns
    -------
    DriveParts
        The torsional model, its matrices and where sprockets, rotors, motor and machines
        are in them (docs/dynamics.md §1).
    """
    spec = drive.chain.spec
    m = drive.chain.contours
    q = spec.mass_per_length * m
    names = [s.name for s in drive.sprockets]
    n = len(names)
    sense = _sprocket_senses(geometry)
    R = ring.pitch_radii_m
    # R̄_i = z_i p/2π: the mean chain speed per rad/s of sprocket i
    Rbar = np.asarray(mean_chain_speed(spec.pitch, [s.teeth for s in drive.sprockets], 1.0))
    w_d = drive.driver.speed or 1.0
    speeds = sense * w_d * drive.driver.teeth / np.array([s.teeth for s in drive.sprockets])
    t = TorsionalEngine()
    chain = [CHAIN_NODE.format(x) for x in names]
    for i, g in enumerate(geometry.sprockets):
        t.add_inertia(names[i], float(ring.inertias_kg_m2[i]))
        t.add_inertia(chain[i], q * g.pitch_radius * g.wrap_angle)
    k_span = ring.chain_stiffness_n_per_m * ring.sag_factors * m
    k_wrap = ring.wrap_stiffness_n_per_m * m
    for i, sp in enumerate(geometry.spans):
        b = (i + 1) % n
        t.add_span(chain[i], chain[b], float(k_span[i]), 1.0, 1.0, mass=q * sp.length,
                   consistent_mass=True, name=f"span:{names[i]}-{names[b]}")
    for i in range(n):
        t.add_link(names[i], chain[i], float(k_wrap[i]), float(sense[i] * R[i]), 1.0,
                   name=f"wrap:{names[i]}", kind="wrap")
    trains: dict[str, _Train] = {}
    for i, s in enumerate(drive.sprockets):
        tr = _Train(s.name, s.name, float(speeds[i]), 1.0)
        for k, e in enumerate(s.train):
            _add_element(t, tr, k, e, lookup, inward=s.role == "driver")
        trains[s.name] = tr
    notes: list[str] = []
    motor_node = trains[drive.driver.name].node
    rated_power, rated = motor_rating(drive)
    rated_speed = rated if rated is not None else abs(trains[drive.driver.name].speed)
    j_rotor, estimated = (0.0, False) if rated_power is None else \
        _rotor_inertia(drive, rated_power, rated_speed)
    if j_rotor > 0:
        t.add_inertia_to(motor_node, j_rotor)
    said = Quantities()
    if estimated:
        notes.append(f"the motor's rotor inertia {said(j_rotor, 'inertia', '.4g')} is estimated "
                     "from its rated power and speed [MotiveDelphi] (a factor 2 either way)")
    system = t.system()
    T, lin, massed_index = _condensed(system, notes)
    parts = _placements(drive, t, system, T, lin, massed_index, trains, speeds, R, Rbar, ring,
                        rated_power, rated_speed, j_rotor, estimated, notes)
    return replace(parts, note_quantities=said.items)


def _condensed(system: TorsionalSystem, notes: list[str]
               ) -> tuple[FloatArray, LinearModel, NDArray[np.intp]]:
    """(T, linear model in q, index of each reduced coordinate in q or −1): static condensation
    of the massless coordinates [Guyan1965]."""
    massless = system.mass <= 0.0
    n = system.size
    K = system.stiffness_linear
    C = system.damping_linear
    T = system.condensation_basis(K, "train")
    if np.any(C[massless]):
        notes.append("dampers on massless nodes are condensed with their static shape "
                     "(approximate)")
    index = np.full(n, -1, dtype=np.intp)
    index[~massless] = np.arange(int((~massless).sum()))
    M = T.T @ system.mass_matrix() @ T
    lin = LinearModel(M, T.T @ K @ T, T.T @ C @ T, system.span_incidence @ T,
                      system.span_stiffness_n_per_m.copy(), system.span_damping_n_s_per_m.copy(),
                      system.span_tension_only.copy())
    return T, lin, index


def _node_coordinate(system: TorsionalSystem, T: FloatArray, node: str) -> tuple[int, float]:
    """(coordinate k of q, factor f): the node turns by f·q_k (a node condensed rigidly onto
    one massed coordinate, e.g. a massless end, maps to that coordinate)."""
    k, f = system.dof_of(node)
    row = T[k]
    nz = np.flatnonzero(np.abs(row) > 1e-12 * max(1.0, np.abs(row).max()))
    if nz.size != 1:
        raise DesignError(node, "a motor or a machine must sit on a node with an inertia")
    return int(nz[0]), float(f * row[nz[0]])


def _placements(drive: Drive, t: TorsionalEngine, system: TorsionalSystem, T: FloatArray,
                lin: LinearModel, index: NDArray[np.intp], trains: dict[str, _Train],
                speeds: FloatArray, R: FloatArray, Rbar: FloatArray, ring: RingParameters,
                rated_power: float | None, rated_speed: float, j_rotor: float,
                estimated: bool, notes: list[str]) -> DriveParts:
    """Coordinates of the sprockets, rotors, motor and machines."""
    names = tuple(s.name for s in drive.sprockets)
    sc, sg = zip(*(_node_coordinate(system, T, x) for x in names), strict=True)
    s_coord = np.array(sc, dtype=np.intp)
    s_gain = np.array(sg) * np.sign(speeds)
    rotors = [x for tr in trains.values() for x in tr.nodes
              if system.node_inertia_kg_m2[system.node_names.index(x)] > 0]
    rot = [_node_coordinate(system, T, x) for x in rotors]
    nominal = {x: tr.speed for tr in trains.values() for x in tr.nodes}
    nominal.update({tr.node: tr.speed for tr in trains.values()})
    r_gain = np.array([f * math.copysign(1.0, nominal[x]) for x, (_, f) in
                       zip(rotors, rot, strict=True)])
    motor = None
    if rated_power is not None and drive.driver.speed is not None:
        tr = trains[drive.driver.name]
        k, f = _node_coordinate(system, T, tr.node)
        motor = MotorPlacement(tr.node, k, f * math.copysign(1.0, tr.speed), tr.efficiency,
                               _motor_law(drive, rated_power, rated_speed), abs(tr.speed),
                               j_rotor, estimated)
    loads = []
    if drive.power is not None and drive.driver.speed is not None:
        shares = power_shares(drive)
        for i, s in enumerate(drive.sprockets):
            if shares[i] <= 0:
                continue
            tr = trains[s.name]
            k, f = _node_coordinate(system, T, tr.node)
            w_n = abs(tr.speed)
            loads.append(LoadPlacement(s.name, tr.node, k, f * math.copysign(1.0, tr.speed),
                                       tr.efficiency, s.load or drive.dynamics.resistance,
                                       shares[i] * drive.power / w_n, w_n))
    return DriveParts(
        torsional=t, system=system, linear=lin, condensation=T, sprocket_names=names,
        sprocket_coordinate=s_coord, sprocket_gain=s_gain, pitch_radii=R, mean_radii=Rbar,
        nominal_speeds=np.abs(speeds), rotor_names=tuple(rotors),
        rotor_coordinate=np.array([k for k, _ in rot], dtype=np.intp), rotor_gain=r_gain,
        rotor_nominal_speed=np.array([abs(nominal[x]) for x in rotors]), motor=motor,
        loads=tuple(loads), span_damping_ratios=np.zeros(len(names)), damping_source="",
        reference_frequency_hz=0.0, contours=drive.chain.contours, ring=ring,
        driver_index=drive.driver_index, notes=tuple(notes),
        trains={k: v.description for k, v in trains.items() if v.description})
