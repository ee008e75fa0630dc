"""The engine of the torsional model of a whole chain drive train (the public class with
its builders is :class:`chaindrive.dynamics.torsional.model.TorsionalModel`): the ring of
sprockets with an open train of shafts, couplings, gear pairs and machines on every
sprocket (docs/torsional.md).

Nodes are rotating bodies with a moment of inertia J [kg·m²] (0: a massless node, condensed
out) and an angle φ [rad]. Elements:

- shaft or coupling between two nodes: twist e = φ_b − φ_a, torque k·e + c·ė;
- ground spring at a node: e = φ, torque k·e + c·ė to a fixed frame;
- rigid gear mesh, a constraint: φ_driven = s·φ_driver / i with the ratio i = ω_driver /
  ω_driven and s = −1 for a pair of external gears (the sense reverses), s = +1 for a
  same-sense stage (internal gear, idler, a reducer taken as a whole); frequencies do not
  depend on s, torques and shapes do;
- chain span between two sprockets: elongation e = r_b·φ_b − r_a·φ_a with signed pitch radii
  r (negative for a sprocket wrapped from the inside, which turns the other way), force
  c·e + d·ė along the span, tension-only (a start-up integrator may switch a slack span off).
  This is the ring model of :mod:`chaindrive.dynamics.ring` ([MultimassChainDrives, §3.1])
  written in sprocket angles: x_i = R_i φ_i, m_i = J_i / R_i².

Rigid gear meshes are eliminated: every node's angle is ``factor × q_k`` of one reduced
coordinate q_k per gear tree (gear trains are trees; a mesh that closes a loop must agree with
the ratios already there, else it over-constrains: DesignError). The reduced mass matrix
M_kk = Σ J_n·factor_n² is diagonal, so the modes come from the symmetric eigenproblem of
M^{-1/2} K M^{-1/2} [Rao2011, ch. 6]. Massless coordinates are condensed out exactly by static
(Guyan) condensation K_c = K_mm − K_m0 K_00⁻¹ K_0m [Guyan1965] for the undamped modes; the
massless nodes' angles follow as q_0 = −K_00⁻¹ K_0m q_m. Damping on a massless node is not
condensable in the time domain (the node is then a first-order state, C_00 q̇_0 + K_00 q_0 =
…): :meth:`TorsionalSystem.condensed` refuses it, and an integrator must keep such a node.

Rigid-body modes are counted from the graph (each connected group of coordinates whose
elements all admit a common strain-free motion — no ground spring, no loop of mismatched
ratios), set to exactly 0 Hz with their exact shapes, and projected out before the
eigensolver; no eigenvalue is ever zeroed by a round-off threshold.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import FrozenInstanceError, dataclass, replace

import numpy as np
from numpy.typing import NDArray

from chaindrive.dynamics.modes import Modes
from chaindrive.dynamics.torsional.assembly import (
    RATIO_RTOL,
    WeightedUnion,
    gear_coordinates,
    grams,
    incidence,
    kinematic_groups,
    rigid_motions,
)
from chaindrive.dynamics.torsional.system import TorsionalSystem
from chaindrive.errors import DesignError

__all__ = ["RATIO_RTOL", "Element", "TorsionalEngine", "reducer_input_torque"]

FloatArray = NDArray[np.float64]
#: One element of a train in :meth:`TorsionalEngine.from_contour` (plain data).
TrainElement = Mapping[str, "float | str | bool"]


@dataclass(frozen=True, slots=True)
class Element:
    """One spring–damper element of the model: its strain is coef_a·φ_a + coef_b·φ_b.

    Parameters
    ----------
    name : str
        Unique name.
    kind : str
        What added it: ``shaft``, ``ground``, ``span``, ``wrap``, ``link``, …
    a, b : int
        Node indices [-] (b = −1: the ground).
    coef_a, coef_b : float
        Strain per rotation of node a and of node b [m/rad or rad/rad].
    stiffness : float
        k [N/m or N·m/rad].
    damping : float
        c [N·s/m or N·m·s/rad].
    tension_only : bool
        True for a chain span that goes slack instead of pushing.
    """

    name: str
    kind: str
    a: int
    b: int
    coef_a: float
    coef_b: float
    stiffness: float
    damping: float
    tension_only: bool


def reducer_input_torque(output_torque: float, ratio: float, efficiency: float = 1.0,
                         driving: bool = True) -> float:
    """Torque [N·m] at the input of a reducer of ratio i = ω_in / ω_out and efficiency η.

    Driving direction (power flows input → output): T_in = T_out / (i·η); back-driven (power
    flows output → input): T_in = T_out·η / i. Closed form: the power balance
    T_in ω_in η = T_out ω_out, η being by definition the ratio of output to input power.

    Parameters
    ----------
    output_torque : float
        T_out [N·m].
    ratio : float
        i = ω_in / ω_out [-] (> 0).
    efficiency : float
        η ∈ (0, 1] [-].
    driving : bool
        True when power flows from the input to the output.

    Returns
    -------
    float
        T_in [N·m].

    References
    ----------
    [Shigley2015, ch. 13] (power and torque through a gear train).
    """
    _check_ratio("ratio", ratio)
    _check_efficiency("efficiency", efficiency)
    return output_torque / (ratio * efficiency) if driving else output_torque * efficiency / ratio


def _check_ratio(field: str, ratio: float) -> None:
    if not (math.isfinite(ratio) and ratio > 0.0):
        raise DesignError(field, f"gear ratio must be finite and > 0, got {ratio!r}")


def _check_efficiency(field: str, efficiency: float) -> None:
    if not (math.isfinite(efficiency) and 0.0 < efficiency <= 1.0):
        raise DesignError(field, f"efficiency must be in (0, 1], got {efficiency!r}")


_INF = math.inf


def nonneg(field: str, value: float, what: str) -> float:
    value = float(value)
    if not 0.0 <= value < _INF:  # also False for nan
        raise DesignError(field, f"{what} must be finite and ≥ 0, got {value!r}")
    return value


class TorsionalEngine:
    """Builder of the torsional model of a drive train (module docstring; docs/torsional.md).

    Nodes are named. ``add_inertia`` creates a node (or gives its inertia to a node that an
    element created massless); shafts, meshes and spans create the nodes they name when new
    (massless until given an inertia); ground springs, torques and queries need an existing
    node. Every error is a DesignError naming the element.

    The model is built (frozen) when its system is first assembled (:meth:`build`,
    :meth:`system`, :meth:`modal`, :meth:`frequencies_hz`): from then on every ``add_*``,
    :meth:`rename_node`, :meth:`set_damping` and every attribute assignment raises
    :class:`dataclasses.FrozenInstanceError`, so that the system and modes computed from it
    stay its own; :meth:`with_damping` gives a built copy with other dampers.
    """

    def __init__(self) -> None:
        self._built = False
        self._index: dict[str, int] = {}
        self._inertia: list[float] = []
        self._given: list[bool] = []
        self._chain: list[float] = []
        # consistent chain mass of the spans: (node a, node b, m/6·r_a·r_b) [kg·m²]
        self._mass_pairs: list[tuple[int, int, float]] = []
        self._gears = WeightedUnion()
        # strain-free relations φ_b = w·φ_a of all elements of stiffness > 0 and meshes, in
        # order (their groups are the rigid-body modes; resolved at assembly)
        self._relations: list[tuple[int, int, float]] = []
        self._held: list[bool] = []
        self._meshes: list[tuple[str, int, int, float, float, float]] = []
        self._elements: list[Element] = []
        self._names: set[str] = set()
        self._system: TorsionalSystem | None = None

    def __setattr__(self, name: str, value: object) -> None:
        if getattr(self, "_built", False):
            raise FrozenInstanceError(f"cannot assign to {name!r}: the torsional model is built")
        object.__setattr__(self, name, value)

    def _unbuilt(self, what: str) -> None:
        """Refuse a change to a built model."""
        if self._built:
            raise FrozenInstanceError(f"cannot {what}: the torsional model is built (frozen "
                                      "since its system was assembled); build a new one")

    # -- construction -------------------------------------------------------------------
    def _node(self, name: str, create: bool, field: str) -> int:
        i = self._index.get(name)
        if i is not None:
            return i
        if not create:
            raise DesignError(field, f"unknown node {name!r}; nodes: {list(self._index)}")
        if not isinstance(name, str) or not name:
            raise DesignError(field, f"a node needs a non-empty name, got {name!r}")
        self._index[name] = i = len(self._inertia)
        self._inertia.append(0.0)
        self._given.append(False)
        self._chain.append(0.0)
        self._gears.parent.append(i)  # a new root of its own
        self._gears.weight.append(1.0)
        self._held.append(False)
        return i

    def _element_name(self, name: str | None, default: str) -> str:
        """The element's name: the one given (refused when taken) or the default, numbered
        ``default#2``, ``default#3``, … when another element already has it."""
        if not name:
            name, k = default, 1
            while name in self._names:
                k += 1
                name = f"{default}#{k}"
        elif name in self._names:
            raise DesignError(name, "an element of that name already exists")
        self._names.add(name)
        self._system = None
        return name

    def add_inertia(self, name: str, inertia: float) -> TorsionalEngine:
        """Node ``name`` with moment of inertia J ≥ 0 (0: massless), or the inertia of a node
        an element created massless.

        Parameters
        ----------
        name : str
            The node's name.
        inertia : float
            J [kg·m²] (a chain node of unit radius: its mass [kg]).

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add a node")
        i = self._node(name, True, name)
        if self._given[i]:
            raise DesignError(name, "the node already has an inertia")
        self._inertia[i] = nonneg(name, inertia, "inertia [kg·m²]")
        self._given[i] = True
        self._system = None
        return self

    def add_inertia_to(self, name: str, inertia: float) -> TorsionalEngine:
        """Add J ≥ 0 to the inertia of an existing node (a body on the same shaft).

        Parameters
        ----------
        name : str
            The node's name.
        inertia : float
            J added [kg·m²].

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add an inertia")
        i = self._node(name, False, name)
        self._inertia[i] += nonneg(name, inertia, "inertia [kg·m²]")
        self._given[i] = True
        self._system = None
        return self

    def rename_node(self, old: str, new: str) -> TorsionalEngine:
        """Give node ``old`` the name ``new`` (not yet used).

        Parameters
        ----------
        old : str
            The node's present name.
        new : str
            Its new name.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("rename a node")
        if new in self._index:
            raise DesignError(new, "a node of that name exists already")
        i = self._node(old, False, old)
        self._index = {(new if k == old else k): v for k, v in self._index.items()}
        self._system = None
        del i
        return self

    def add_shaft(self, a: str, b: str, stiffness: float, damping: float = 0.0,
                  name: str | None = None) -> TorsionalEngine:
        """Shaft or coupling between nodes a and b: twist e = φ_b − φ_a, torque k·e + c·ė.

        Parameters
        ----------
        a, b : str
            The nodes it joins (created massless when new).
        stiffness : float
            Torsional stiffness k [N·m/rad] (of a round shaft:
            :func:`chaindrive.dynamics.model.build.shaft_stiffness`).
        damping : float
            Torsional damping c [N·m·s/rad].
        name : str | None
            The element's name (None: "shaft:<a>-<b>"); names are unique.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).

        References
        ----------
        [Rao2011, ch. 6] (torsional spring and damper elements).
        """
        self._unbuilt("add a shaft")
        name = self._element_name(name, f"shaft:{a}-{b}")
        ia, ib = self._index.get(a), self._index.get(b)  # the common case: both exist
        if ia is None or ib is None or a == b:
            ia, ib = self._pair(a, b, name)
        k = float(stiffness)
        if not 0.0 <= k < _INF:  # also True for nan (as nonneg, without the call)
            nonneg(name, k, "stiffness [N·m/rad]")
        c = float(damping)
        if not 0.0 <= c < _INF:
            nonneg(name, c, "damping [N·m·s/rad]")
        self._elements.append(Element(name, "shaft", ia, ib, -1.0, 1.0, k, c, False))
        if k > 0.0:  # its strain-free relation (as _kinematics, without the call)
            self._relations.append((ia, ib, 1.0))
        return self

    def add_ground_spring(self, node: str, stiffness: float, damping: float = 0.0,
                          name: str | None = None) -> TorsionalEngine:
        """Spring (and damper) from an existing node to the fixed frame: torque k·φ + c·φ̇.

        Parameters
        ----------
        node : str
            The node.
        stiffness : float
            k [N·m/rad].
        damping : float
            c [N·m·s/rad].
        name : str | None
            The element's name (None: "ground:<node>"); names are unique.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add a ground spring")
        name = self._element_name(name, f"ground:{node}")
        i = self._node(node, False, name)
        k = nonneg(name, stiffness, "stiffness [N·m/rad]")
        self._elements.append(Element(name, "ground", i, -1, 1.0, 0.0, k,
                                      nonneg(name, damping, "damping [N·m·s/rad]"), False))
        self._held[i] = self._held[i] or k > 0.0
        return self

    def add_gear_mesh(self, driver: str, driven: str, ratio: float, efficiency: float = 1.0,
                      same_sense: bool = False, name: str | None = None) -> TorsionalEngine:
        """Rigid mesh: φ_driven = s·φ_driver / i (the driven node turns i× slower), s = −1 for
        an external pair, +1 for a same-sense stage [Shigley2015, ch. 13].

        Parameters
        ----------
        driver, driven : str
            The nodes it joins (created massless when new).
        ratio : float
            i = ω_driver/ω_driven [-] (> 0).
        efficiency : float
            η ∈ (0, 1] [-], kept for torques (:meth:`referred_torque`); the modes do not use
            it.
        same_sense : bool
            True for a stage that keeps the sense of rotation (internal gear, idler, a
            reducer taken as a whole).
        name : str | None
            The element's name (None: "mesh:<a>-<b>"); names are unique.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add a gear mesh")
        name = self._element_name(name, f"mesh:{driver}-{driven}")
        _check_ratio(name, ratio)
        _check_efficiency(name, efficiency)
        ia, ib = self._pair(driver, driven, name)
        w = (1.0 if same_sense else -1.0) / ratio
        if not self._gears.relate(ia, ib, w):
            raise DesignError(name, f"gear loop over-constrains: the ratio {ratio!r} between "
                              f"{driver!r} and {driven!r} contradicts the meshes already "
                              "joining them")
        self._meshes.append((name, ia, ib, float(ratio), float(efficiency), w))
        self._kinematics(ia, ib, w, 1.0)
        return self

    def add_span(self, a: str, b: str, stiffness: float, radius_a: float, radius_b: float,
                 damping: float = 0.0, tension_only: bool = True, mass: float = 0.0,
                 name: str | None = None, consistent_mass: bool = False) -> TorsionalEngine:
        """Chain span from sprocket a to b: elongation e = r_b φ_b − r_a φ_a, force c·e + d·ė
        along the span [MultimassChainDrives, §3.1].

        The span's mass m = q·L is split to its ends, m/2·r² on each sprocket, or with
        ``consistent_mass`` distributed as the consistent mass of a linear velocity profile
        along the span: m/3·r² on each end and m/6·r_a·r_b between them (kinetic energy
        m/6·(v_a² + v_a v_b + v_b²) [Rao2011, ch. 2]; docs/torsional.md §5 measures both).

        Parameters
        ----------
        a, b : str
            The sprockets (nodes) it joins (created massless when new).
        stiffness : float
            Span stiffness c [N/m].
        radius_a, radius_b : float
            Signed pitch radii r [m] (negative for a sprocket wrapped from the inside).
        damping : float
            Span damper d [N·s/m].
        tension_only : bool
            True: the span carries no compression (an integrator may switch it off when
            slack).
        mass : float
            Mass of the span's chain q·L [kg].
        name : str | None
            The element's name (None: "span:<a>-<b>"); names are unique.
        consistent_mass : bool
            True: consistent mass of a linear velocity profile; False: lumped in halves.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add a span")
        name = self._element_name(name, f"span:{a}-{b}")
        ra, rb = float(radius_a), float(radius_b)
        if not (math.isfinite(ra) and math.isfinite(rb) and ra != 0.0 and rb != 0.0):
            raise DesignError(name, f"pitch radii must be finite and ≠ 0, got {ra!r}, {rb!r}")
        m = float(mass)
        if not 0.0 <= m < _INF:  # also True for nan (as nonneg, without the call)
            nonneg(name, m, "span mass [kg]")
        ia, ib = self._index.get(a), self._index.get(b)  # the common case: both exist
        if ia is None or ib is None or a == b:
            ia, ib = self._pair(a, b, name)
        k = float(stiffness)
        if not 0.0 <= k < _INF:
            nonneg(name, k, "stiffness [N/m]")
        c = float(damping)
        if not 0.0 <= c < _INF:
            nonneg(name, c, "damping [N·s/m]")
        self._elements.append(Element(name, "span", ia, ib, -ra, rb, k, c, bool(tension_only)))
        if k > 0.0:  # its strain-free relation (as _kinematics, without the call)
            self._relations.append((ia, ib, ra / rb))
        if m == 0.0:
            return self
        if consistent_mass:
            self._chain[ia] += m / 3.0 * ra * ra
            self._chain[ib] += m / 3.0 * rb * rb
            if m > 0.0:
                self._mass_pairs.append((ia, ib, m / 6.0 * ra * rb))
        else:
            self._chain[ia] += 0.5 * m * ra * ra
            self._chain[ib] += 0.5 * m * rb * rb
        return self

    def add_link(self, a: str, b: str, stiffness: float, radius_a: float, radius_b: float,
                 damping: float = 0.0, name: str | None = None,
                 kind: str = "link") -> TorsionalEngine:
        """Linear spring between two nodes at radii r_a, r_b: strain e = r_b φ_b − r_a φ_a [m],
        force k·e + c·ė [N]; pushes and pulls (e.g. the tooth contact of a sprocket with the
        chain wrapped on it, kind "wrap"). A node of radius 1 m is a translational body whose
        "angle" is its displacement [m] and "inertia" its mass [kg].

        Parameters
        ----------
        a, b : str
            The nodes it joins (created massless when new).
        stiffness : float
            k [N/m].
        radius_a, radius_b : float
            Signed radii r_a, r_b [m] (≠ 0).
        damping : float
            c [N·s/m].
        name : str | None
            The element's name (None: "<kind>:<a>-<b>"); names are unique.
        kind : str
            The element's kind, as :attr:`TorsionalSystem.element_kinds` reports it.

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).

        References
        ----------
        [Rao2011, ch. 6] (spring and damper elements).
        """
        self._unbuilt("add a link")
        name = self._element_name(name, f"{kind}:{a}-{b}")
        ra, rb = float(radius_a), float(radius_b)
        if not (math.isfinite(ra) and math.isfinite(rb) and ra != 0.0 and rb != 0.0):
            raise DesignError(name, f"radii must be finite and ≠ 0, got {ra!r}, {rb!r}")
        ia, ib = self._pair(a, b, name)
        k = nonneg(name, stiffness, "stiffness [N/m]")
        self._elements.append(Element(name, kind, ia, ib, -ra, rb, k,
                                      nonneg(name, damping, "damping [N·s/m]"), False))
        self._kinematics(ia, ib, ra / rb, k)
        return self

    def set_damping(self, element: str, damping: float) -> TorsionalEngine:
        """Replace the damping coefficient of an existing element.

        Parameters
        ----------
        element : str
            The element's name.
        damping : float
            The new coefficient [N·s/m for spans and links, N·m·s/rad for shafts and ground
            springs].

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("set a damping")
        for k, e in enumerate(self._elements):
            if e.name == element:
                self._elements[k] = replace(e, damping=nonneg(element, damping, "damping"))
                self._system = None
                return self
        raise DesignError(element, "no element of that name")

    def add_chain_wrap(self, node: str, mass: float, radius: float) -> TorsionalEngine:
        """Links wrapped on a sprocket turn with it: adds m_wrap·r² [kg·m²] to its inertia.

        Parameters
        ----------
        node : str
            The sprocket's node.
        mass : float
            m_wrap, the mass of the wrapped links [kg].
        radius : float
            r, the pitch radius [m].

        Returns
        -------
        TorsionalEngine
            The model itself (calls chain).
        """
        self._unbuilt("add a chain wrap")
        i = self._node(node, False, f"wrap:{node}")
        m = nonneg(f"wrap:{node}", mass, "wrapped chain mass [kg]")
        self._chain[i] += m * float(radius) ** 2
        self._system = None
        return self

    def _kinematics(self, a: int, b: int, w: float, stiffness: float) -> None:
        """Strain-free relation φ_b = w·φ_a of an element (ignored at stiffness 0); one that
        contradicts the others holds its group (no rigid-body motion; resolved at assembly:
        :func:`chaindrive.dynamics.torsional.assembly.kinematic_groups`)."""
        if stiffness > 0.0:
            self._relations.append((a, b, w))

    def _pair(self, a: str, b: str, name: str) -> tuple[int, int]:
        if a == b:
            raise DesignError(name, f"an element must join two different nodes, got {a!r} twice")
        return self._node(a, True, name), self._node(b, True, name)

    @property
    def node_names(self) -> tuple[str, ...]:
        """Names of the nodes, in the order they were created."""
        return tuple(self._index)

    def with_damping(self, damping: Mapping[str, float]) -> TorsionalEngine:
        """A built copy of this model with the dampers of the named elements replaced (this
        model is left as it is).

        Parameters
        ----------
        damping : mapping
            Element name → its damping coefficient [N·s/m for spans and links, N·m·s/rad for
            shafts and ground springs].

        Returns
        -------
        TorsionalEngine
            The copy, built (its system assembled when first asked for).
        """
        where = {e.name: k for k, e in enumerate(self._elements)}
        elements = list(self._elements)
        for name, d in damping.items():
            k = where.get(name)
            if k is None:
                raise DesignError(name, "no element of that name")
            elements[k] = replace(elements[k], damping=nonneg(name, d, "damping"))
        new = copy.copy(self)  # shares the rest: neither model changes it once built
        object.__setattr__(new, "_elements", tuple(elements))
        object.__setattr__(new, "_system", None)
        object.__setattr__(new, "_built", True)
        return new

    # -- results ------------------------------------------------------------------------
    def build(self) -> TorsionalEngine:
        """Assemble the system and freeze the model (class docstring).

        Returns
        -------
        TorsionalEngine
            The model itself, built.
        """
        if self._system is None:
            system = _assemble(self)
            for name in ("_inertia", "_given", "_chain", "_mass_pairs", "_relations", "_held",
                         "_meshes", "_elements"):
                object.__setattr__(self, name, tuple(getattr(self, name)))
            object.__setattr__(self, "_names", frozenset(self._names))
            object.__setattr__(self, "_system", system)
            object.__setattr__(self, "_built", True)
        return self

    def system(self) -> TorsionalSystem:
        """The assembled :class:`TorsionalSystem`; builds (freezes) the model.

        Returns
        -------
        TorsionalSystem
            The matrices in reduced coordinates (module docstring).
        """
        system = self.build()._system
        assert system is not None
        return system

    def modal(self) -> Modes:
        """Undamped natural frequencies, shapes and strain-energy shares.

        Returns
        -------
        Modes
            Frequencies [Hz], mass-normalised shapes of every node [rad] and strain-energy
            shares [-] (no damped fields: an undamped analysis).

        References
        ----------
        [Rao2011, ch. 6]; massless coordinates condensed [Guyan1965].
        """
        return self.system().modal()

    def frequencies_hz(self) -> FloatArray:
        """The natural frequencies of :meth:`modal` [Hz] without the shapes (LAPACK computes
        no eigenvectors: 2–3× faster, see benchmarks/bench_torsional.py).

        Returns
        -------
        ndarray
            Natural frequencies [Hz], ascending, the rigid-body zeros first.
        """
        return self.system().frequencies_hz()

    def referred_torque(self, torque: float, at: str, to: str, driving: bool = True) -> float:
        """Torque T_at [N·m] acting at node ``at`` referred to node ``to`` through the gear
        meshes between them, with their efficiencies.

        Power flowing from ``to`` to ``at`` (``driving``): T_to = T_at·(g_at/g_to) / Πη; the
        other way: T_to = T_at·(g_at/g_to)·Πη, g the nodes' factors (signed ratios; for one
        reducer |g_at/g_to| = 1/i, see :func:`reducer_input_torque`).

        Parameters
        ----------
        torque : float
            T_at [N·m].
        at : str
            The node the torque acts on.
        to : str
            The node it is referred to (joined to ``at`` by gear meshes).
        driving : bool
            True when power flows from ``to`` to ``at``.

        Returns
        -------
        float
            T_to [N·m].

        References
        ----------
        [Shigley2015, ch. 13] (power and torque through a gear train).
        """
        ia, it = self._node(at, False, "at"), self._node(to, False, "to")
        (ra, ga), (rt, gt) = self._gears.find(ia), self._gears.find(it)
        if ra != rt:
            raise DesignError("to", f"{at!r} and {to!r} are not joined by gear meshes")
        eta = math.prod(self._meshes[k][4] for k in self._mesh_path(ia, it))
        return float(torque) * (ga / gt) * (1.0 / eta if driving else eta)

    def _mesh_path(self, a: int, b: int) -> list[int]:
        """Indices of the meshes on a path from node a to node b (breadth-first)."""
        adjacency: dict[int, list[tuple[int, int]]] = {}
        for k, (_, i, j, *_rest) in enumerate(self._meshes):
            adjacency.setdefault(i, []).append((j, k))
            adjacency.setdefault(j, []).append((i, k))
        previous: dict[int, tuple[int, int]] = {a: (a, -1)}
        frontier = [a]
        while frontier and b not in previous:
            nxt = []
            for i in frontier:
                for j, k in adjacency.get(i, []):
                    if j not in previous:
                        previous[j] = (i, k)
                        nxt.append(j)
            frontier = nxt
        path, i = [], b
        while i != a:
            i, k = previous[i]
            path.append(k)
        return path

    def to_dict(self) -> dict[str, object]:
        """JSON-ready description of the model.

        Returns
        -------
        dict
            ``nodes`` (inertias [kg·m²]), ``elements`` (stiffness, damping, incidence
            coefficients) and ``gear_meshes`` (ratio, efficiency, sense).
        """
        names = list(self._index)
        return {
            "nodes": {n: {"inertia_kg_m2": self._inertia[i], "chain_inertia_kg_m2": self._chain[i]}
                      for n, i in self._index.items()},
            "elements": [{"name": e.name, "kind": e.kind, "a": names[e.a],
                          "b": None if e.b < 0 else names[e.b], "coef_a": e.coef_a,
                          "coef_b": e.coef_b, "stiffness": e.stiffness, "damping": e.damping,
                          "tension_only": e.tension_only}
                         for e in self._elements],
            "gear_meshes": [{"name": m[0], "driver": names[m[1]], "driven": names[m[2]],
                             "ratio": m[3], "efficiency": m[4], "same_sense": m[5] > 0}
                            for m in self._meshes],
        }


def _assemble(model: TorsionalEngine) -> TorsionalSystem:
    """Reduced coordinates (one per gear tree), element incidence, rigid-body motions, on
    whole arrays (:mod:`chaindrive.dynamics.torsional.assembly`)."""
    n_nodes = len(model._inertia)
    if n_nodes == 0:
        raise DesignError("nodes", "the model has no node")
    node_dof, factor, n = gear_coordinates(model._gears, n_nodes)
    kin_root, kin_w, held_root = kinematic_groups(n_nodes, model._relations, model._held)
    inertia = np.array(model._inertia) + np.array(model._chain)
    mass = np.asarray(np.bincount(node_dof, weights=inertia * factor * factor, minlength=n),
                      dtype=np.float64)
    coupling = np.zeros((n, n))
    for ia_, ib_, m_ab in model._mass_pairs:
        ka, kb = node_dof[ia_], node_dof[ib_]
        w_ab = m_ab * factor[ia_] * factor[ib_]
        if ka == kb:  # both ends on one coordinate (meshed): it is diagonal mass
            mass[ka] += 2.0 * w_ab
        else:
            coupling[ka, kb] += w_ab
            coupling[kb, ka] += w_ab
    el = model._elements
    names = [e.name for e in el]
    kinds = [e.kind for e in el]
    a, b = [e.a for e in el], [e.b for e in el]
    ca, cb = [e.coef_a for e in el], [e.coef_b for e in el]
    k, c = [e.stiffness for e in el], [e.damping for e in el]
    tension = [e.tension_only for e in el]
    B, cols, coef = incidence(node_dof, factor, np.array(a, dtype=np.intp),
                              np.array(b, dtype=np.intp), np.array(ca, dtype=float),
                              np.array(cb, dtype=float), n)
    k_all, c_all = np.array(k, dtype=float), np.array(c, dtype=float)
    span = np.array([kd == "span" for kd in kinds], dtype=bool)
    lin = ~span
    K_lin, C_lin = grams(cols[lin], coef[lin], (k_all[lin], c_all[lin]), n)
    return TorsionalSystem(
        node_names=tuple(model._index), node_dof=node_dof, node_factor=factor,
        node_inertia_kg_m2=inertia, mass=mass, mass_coupling=coupling,
        stiffness_linear=K_lin, damping_linear=C_lin,
        span_names=tuple(x for x, sp in zip(names, span.tolist(), strict=True) if sp),
        span_incidence=B[span], span_stiffness_n_per_m=k_all[span],
        span_damping_n_s_per_m=c_all[span],
        span_tension_only=np.array(tension, dtype=bool)[span],
        element_names=tuple(names), element_kinds=tuple(kinds), element_incidence=B,
        element_stiffness=k_all, element_damping=c_all,
        rigid_motions=rigid_motions(node_dof, factor, kin_root, kin_w, held_root, n),
        element_columns=cols, element_coefficients=coef, span_mask=span)
