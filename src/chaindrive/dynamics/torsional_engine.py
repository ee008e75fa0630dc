"""The engine of the torsional model of a whole chain drive train (the public class with
its builders is :class:`chaindrive.dynamics.torsional.TorsionalModel`): the ring of
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

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.torsional_assembly import (
    RATIO_RTOL,
    WeightedUnion,
    gear_coordinates,
    grams,
    incidence,
    kinematic_groups,
    rigid_motions,
)
from chaindrive.dynamics.torsional_assembly import gram as _gram
from chaindrive.errors import DesignError

__all__ = ["RATIO_RTOL", "TorsionalEngine", "TorsionalModes", "TorsionalSystem",
           "reducer_input_torque"]

TWO_PI = 2.0 * math.pi
FloatArray = NDArray[np.float64]
#: One element of a train in :meth:`TorsionalEngine.from_contour` (plain data).
TrainElement = Mapping[str, "float | str | bool"]


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


def _nonneg(field: str, value: float, what: str) -> float:
    value = float(value)
    if not 0.0 <= value < _INF:  # also False for nan
        raise DesignError(field, f"{what} must be finite and ≥ 0, got {value!r}")
    return value


@dataclass(frozen=True, slots=True, eq=False)
class TorsionalSystem:
    """Assembled matrices of a :class:`TorsionalEngine` in reduced coordinates q.

    Node n turns by φ_n = node_factor[n]·q[node_dof[n]] (gear meshes eliminated). Equations of
    motion M q̈ + C q̇ + K q = Σ_n factor_n·T_n (:meth:`generalized_force`) with
    K = stiffness_linear + Bᵀ diag(c_span·active) B and C likewise, span elongations e = B q
    [Rao2011, ch. 6]. Units per coordinate: a rotating node's coordinate is an angle [rad],
    a chain node's (unit radius) a displacement [m]; below, [N·m/rad] and [kg·m²] read
    [N/m] and [kg] for the latter.

    Parameters
    ----------
    node_names : tuple of str
        The nodes, in the order they were created.
    node_dof : ndarray of int
        (nodes,) index [-] of the reduced coordinate each node turns with.
    node_factor : ndarray
        (nodes,) factor g_n [-]: φ_n = g_n·q[node_dof[n]] (signed product of gear ratios).
    node_inertia_kg_m2 : ndarray
        (nodes,) moment of inertia J of each node, chain inertia included [kg·m²].
    mass : ndarray
        (size,) diagonal of M [kg·m²]; 0 marks a massless coordinate (:meth:`condensed`).
    mass_coupling : ndarray
        (size, size) off-diagonal part of M [kg·m²]: a span's consistent chain mass couples
        its two ends (zero diagonal; all zeros when every chain mass is lumped).
    stiffness_linear : ndarray
        (size, size) stiffness of every element but the spans [N·m/rad].
    damping_linear : ndarray
        (size, size) damping of every element but the spans [N·m·s/rad].
    span_names : tuple of str
        The chain spans.
    span_incidence : ndarray
        (spans, size) B: span elongations e = B q [m per unit of coordinate].
    span_stiffness_n_per_m : ndarray
        (spans,) span stiffnesses c [N/m].
    span_damping_n_s_per_m : ndarray
        (spans,) span dampers d [N·s/m].
    span_tension_only : ndarray of bool
        (spans,) True for a span that drops out when slack.
    element_names : tuple of str
        Every element (shafts, ground springs, links, spans).
    element_kinds : tuple of str
        Kind of each element ("shaft", "ground", "span", "link", "wrap" …).
    element_incidence : ndarray
        (elements, size) strain of each element per unit of coordinate [rad or m].
    element_stiffness : ndarray
        (elements,) k of every element [N·m/rad for shafts and ground springs, N/m for
        spans and links].
    element_damping : ndarray
        (elements,) c of every element [N·m·s/rad or N·s/m].
    rigid_motions : ndarray
        (size, r) one exact strain-free motion per free group (no ground spring, no loop of
        mismatched ratios), from the graph [-].
    element_columns : ndarray of int
        (elements, 2) the columns [-] of the (at most two) nonzero entries of every row of
        ``element_incidence``, for assembling K and C by scatter.
    element_coefficients : ndarray
        (elements, 2) those entries [rad or m per unit of coordinate].
    span_mask : ndarray of bool
        (elements,) True for the spans among the elements.

    References
    ----------
    [Rao2011, ch. 6] (multi-degree-of-freedom equations of motion).
    """

    node_names: tuple[str, ...]
    node_dof: NDArray[np.intp]
    node_factor: FloatArray
    node_inertia_kg_m2: FloatArray
    mass: FloatArray
    mass_coupling: FloatArray
    stiffness_linear: FloatArray
    damping_linear: FloatArray
    span_names: tuple[str, ...]
    span_incidence: FloatArray
    span_stiffness_n_per_m: FloatArray
    span_damping_n_s_per_m: FloatArray
    span_tension_only: NDArray[np.bool_]
    element_names: tuple[str, ...]
    element_kinds: tuple[str, ...]
    element_incidence: FloatArray
    element_stiffness: FloatArray
    element_damping: FloatArray
    rigid_motions: FloatArray
    element_columns: NDArray[np.intp]
    element_coefficients: FloatArray
    span_mask: NDArray[np.bool_]

    @property
    def size(self) -> int:
        """Number of reduced coordinates (massless ones included)."""
        return int(self.mass.size)

    def updated(self, node_inertia_kg_m2: ArrayLike | None = None,
                element_stiffness: ArrayLike | None = None,
                element_damping: ArrayLike | None = None) -> TorsionalSystem:
        """The same topology with new values (what an optimiser varies), without a new
        assembly: the meshes, coordinates, incidence and rigid-body motions are reused.

        Parameters
        ----------
        node_inertia_kg_m2 : array_like | None
            (nodes,) J of every node, chain inertia included [kg·m²] (None: unchanged).
        element_stiffness : array_like | None
            (elements,) k of every element [N·m/rad or N/m] (None: unchanged); an element
            must keep k > 0 or k = 0 (its strain-free relation is part of the topology).
        element_damping : array_like | None
            (elements,) c of every element [N·m·s/rad or N·s/m] (None: unchanged).

        Returns
        -------
        TorsionalSystem
            The system with the new values.
        """
        J = self.node_inertia_kg_m2 if node_inertia_kg_m2 is None else \
            np.asarray(node_inertia_kg_m2, dtype=float)
        k = self.element_stiffness if element_stiffness is None else \
            np.asarray(element_stiffness, dtype=float)
        c = self.element_damping if element_damping is None else \
            np.asarray(element_damping, dtype=float)
        if J.shape != self.node_inertia_kg_m2.shape or k.shape != self.element_stiffness.shape \
                or c.shape != self.element_damping.shape:
            raise DesignError("updated", "need one value per node and per element")
        if ((k > 0) != (self.element_stiffness > 0)).any() or (J < 0).any() or (k < 0).any():
            raise DesignError("element_stiffness", "an element changed between k = 0 and k > 0 "
                              "(or a value is negative): that is another topology, rebuild it")
        f2 = self.node_factor * self.node_factor
        n = self.size
        mass = self.mass + np.asarray(np.bincount(
            self.node_dof, weights=(J - self.node_inertia_kg_m2) * f2, minlength=n), dtype=float)
        span = self.span_mask
        lin = ~span
        K_lin, C_lin = grams(self.element_columns[lin], self.element_coefficients[lin],
                             (k[lin], c[lin]), n)
        return TorsionalSystem(
            node_names=self.node_names, node_dof=self.node_dof, node_factor=self.node_factor,
            node_inertia_kg_m2=J, mass=mass, mass_coupling=self.mass_coupling,
            stiffness_linear=K_lin, damping_linear=C_lin, span_names=self.span_names,
            span_incidence=self.span_incidence,
            span_stiffness_n_per_m=k[span], span_damping_n_s_per_m=c[span],
            span_tension_only=self.span_tension_only, element_names=self.element_names,
            element_kinds=self.element_kinds, element_incidence=self.element_incidence,
            element_stiffness=k, element_damping=c, rigid_motions=self.rigid_motions,
            element_columns=self.element_columns,
            element_coefficients=self.element_coefficients, span_mask=span)

    def modal(self) -> TorsionalModes:
        """Undamped natural frequencies, shapes and strain-energy shares (as
        :meth:`TorsionalEngine.modal`).

        Returns
        -------
        TorsionalModes
            Frequencies [Hz], mass-normalised shapes and strain-energy shares [-].

        References
        ----------
        [Rao2011, ch. 6]; massless coordinates condensed [Guyan1965].
        """
        return _modal(self)

    def frequencies_hz(self) -> FloatArray:
        """The natural frequencies [Hz] without the shapes (as
        :meth:`TorsionalEngine.frequencies_hz`).

        Returns
        -------
        ndarray
            Natural frequencies [Hz], ascending, the rigid-body zeros first.
        """
        return _frequencies(self)

    def dof_of(self, node: str) -> tuple[int, float]:
        """(reduced coordinate, factor) of a node: φ_node = factor·q[coordinate].

        Parameters
        ----------
        node : str
            The node's name.

        Returns
        -------
        tuple of (int, float)
            The index of its coordinate [-] and the factor g [-].
        """
        try:
            i = self.node_names.index(node)
        except ValueError:
            raise DesignError("node", f"unknown node {node!r}; nodes: {list(self.node_names)}") \
                from None
        return int(self.node_dof[i]), float(self.node_factor[i])

    def mass_matrix(self) -> FloatArray:
        """M [kg·m²]: the diagonal ``mass`` plus the ``mass_coupling`` of consistent spans.

        Returns
        -------
        ndarray
            (size, size) M [kg·m²].
        """
        return np.diag(self.mass) + self.mass_coupling

    @property
    def has_mass_coupling(self) -> bool:
        """True when M is not diagonal (a span carries a consistent chain mass)."""
        return bool(self.mass_coupling.any())

    def stiffness_matrix(self, span_active: ArrayLike | None = None) -> FloatArray:
        """K with the spans flagged in ``span_active`` carrying [N·m/rad].

        Parameters
        ----------
        span_active : array_like | None
            (spans,) 1 for a span that carries, 0 for a slack one [-] (None: all carry).

        Returns
        -------
        ndarray
            (size, size) K = K_lin + Bᵀ diag(c·a) B [N·m/rad].
        """
        c = self.span_stiffness_n_per_m if span_active is None else \
            self.span_stiffness_n_per_m * np.asarray(span_active, dtype=float)
        return self.stiffness_linear + self._span_gram(c)

    def damping_matrix(self, span_active: ArrayLike | None = None) -> FloatArray:
        """C with the spans flagged in ``span_active`` carrying [N·m·s/rad].

        Parameters
        ----------
        span_active : array_like | None
            (spans,) 1 for a span that carries, 0 for a slack one [-] (None: all carry).

        Returns
        -------
        ndarray
            (size, size) C = C_lin + Bᵀ diag(d·a) B [N·m·s/rad].
        """
        d = self.span_damping_n_s_per_m if span_active is None else \
            self.span_damping_n_s_per_m * np.asarray(span_active, dtype=float)
        return self.damping_linear + self._span_gram(d)

    def _span_gram(self, weights: FloatArray) -> FloatArray:
        """Bᵀ diag(w) B of the spans, by scatter."""
        span = self.span_mask
        return _gram(self.element_columns[span], self.element_coefficients[span], weights,
                     self.size)

    def generalized_force(self, torques: Mapping[str, float]) -> FloatArray:
        """Q = Σ factor_n·T_n [N·m] of external torques T_n on named nodes (ideal meshes;
        mesh losses: :meth:`TorsionalEngine.referred_torque`).

        Parameters
        ----------
        torques : mapping of str to float
            Node name → torque T_n on it [N·m] (a force [N] on a chain node).

        Returns
        -------
        ndarray
            (size,) generalised force Q [N·m].
        """
        Q = np.zeros(self.size)
        for node, torque in torques.items():
            k, g = self.dof_of(node)
            Q[k] += g * float(torque)
        return Q

    def node_angles(self, q: ArrayLike) -> dict[str, float]:
        """Angles φ_n [rad] of all nodes for reduced coordinates q.

        Parameters
        ----------
        q : array_like
            (size,) reduced coordinates [rad].

        Returns
        -------
        dict of str to float
            Node name → φ_n = g_n·q[node_dof[n]] [rad] (a chain node's displacement [m]).
        """
        phi = self.node_factor * np.asarray(q, dtype=float)[self.node_dof]
        return dict(zip(self.node_names, phi.tolist(), strict=True))

    def condensed(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """(T, M_c, K_c, C_c): static condensation of the massless coordinates, q = T q_m.

        Exact for undamped motion: K_c = K_mm − K_m0 K_00⁻¹ K_0m. A damper on a massless
        coordinate makes it a first-order state, which no condensation reproduces:
        DesignError then (keep the node as a state C_00 q̇_0 = −K_00 q_0 − … instead).

        Returns
        -------
        tuple of ndarray
            T (size, m) [-]; the condensed M_c [kg·m²], K_c [N·m/rad] and C_c [N·m·s/rad],
            each (m, m).

        References
        ----------
        [Guyan1965].
        """
        massless = self.mass <= 0.0
        K, C = self.stiffness_matrix(), self.damping_matrix()
        if np.any(C[massless]):
            names = [n for n, k in zip(self.node_names, self.node_dof, strict=True) if massless[k]]
            raise DesignError("damping", f"a damper acts on the massless node(s) {names}: "
                              "give them an inertia or keep them as first-order states")
        X = _condensation(K, massless, self.node_names, self.node_dof)
        T = np.zeros((self.size, int((~massless).sum())))
        T[~massless] = np.eye(T.shape[1])
        T[massless] = -X
        return T, T.T @ self.mass_matrix() @ T, T.T @ K @ T, T.T @ C @ T


def _condensation(K: FloatArray, massless: NDArray[np.bool_], names: Sequence[str],
                  node_dof: NDArray[np.intp]) -> FloatArray:
    """X = K_00⁻¹ K_0m (massless rows 0, massed columns m); DesignError if K_00 is singular."""
    m = ~massless
    K00 = K[np.ix_(massless, massless)]
    try:
        L = np.linalg.cholesky(K00)
    except np.linalg.LinAlgError:
        free = [n for n, k in zip(names, node_dof, strict=True) if massless[k]]
        raise DesignError("inertia", f"massless node(s) among {free} are not held by any "
                          "spring (singular stiffness): give them an inertia or a spring") from None
    Y = np.linalg.solve(L, K[np.ix_(massless, m)])
    return np.linalg.solve(L.T, Y)


@dataclass(frozen=True, slots=True, eq=False)
class TorsionalModes:
    """Undamped natural frequencies and mode shapes of a :class:`TorsionalEngine`.

    Parameters
    ----------
    frequencies_hz : ndarray
        (n,) natural frequencies f_j [Hz], ascending; rigid-body modes exactly 0, first.
    rigid_body : ndarray of bool
        (n,) True for rigid-body modes.
    system : TorsionalSystem
        The assembled system.
    modal_coordinates : ndarray
        (size, n) reduced coordinates q of each mode, mass-normalised (qᵀ M q = 1 [kg·m²];
        massless coordinates recovered statically) [rad].

    Derived on access (so that a modal analysis costs little more than LAPACK):
    ``shape_matrix`` (nodes, n) angles φ [rad] of every node, ``shapes`` by node name,
    ``strain_energy_shares`` (elements, n) share of each element in the strain energy of each
    mode (columns sum to 1; 0 for rigid-body modes), ``participation`` by element name.

    References
    ----------
    [Rao2011, ch. 6] (modal analysis, mass-normalised modes).
    """

    frequencies_hz: FloatArray
    rigid_body: NDArray[np.bool_]
    system: TorsionalSystem
    modal_coordinates: FloatArray

    @property
    def node_names(self) -> tuple[str, ...]:
        """Node names, rows of ``shape_matrix``."""
        return self.system.node_names

    @property
    def element_names(self) -> tuple[str, ...]:
        """Element names, rows of ``strain_energy_shares``."""
        return self.system.element_names

    @property
    def shape_matrix(self) -> FloatArray:
        """(nodes, n) angle of every node in each mode [rad] (mass-normalised)."""
        s = self.system
        return s.node_factor[:, None] * self.modal_coordinates[s.node_dof]

    @property
    def strain_energy_shares(self) -> FloatArray:
        """(elements, n) share of each element in the strain energy ½ k e² of each mode."""
        s = self.system
        strain = s.element_incidence @ self.modal_coordinates
        energy = s.element_stiffness[:, None] * strain * strain
        total = energy.sum(axis=0)
        shares = np.divide(energy, total, out=np.zeros_like(energy), where=total > 0.0)
        shares[:, self.rigid_body] = 0.0
        return np.asarray(shares, dtype=np.float64)

    @property
    def angular_frequencies_rad_s(self) -> FloatArray:
        """ω_j = 2π f_j [rad/s]."""
        return self.frequencies_hz * TWO_PI

    @property
    def shapes(self) -> Mapping[str, FloatArray]:
        """Node name → its angle in every mode [rad] (a row of ``shape_matrix``)."""
        return MappingProxyType(dict(zip(self.system.node_names, self.shape_matrix,
                                         strict=True)))

    @property
    def participation(self) -> Mapping[str, FloatArray]:
        """Element name → its strain-energy share in every mode (which element governs)."""
        return MappingProxyType(dict(zip(self.system.element_names, self.strain_energy_shares,
                                         strict=True)))

    @property
    def elastic_frequencies_hz(self) -> FloatArray:
        """The elastic (non rigid-body) natural frequencies [Hz], ascending."""
        return self.frequencies_hz[~self.rigid_body]

    @property
    def first_elastic_frequency_hz(self) -> float:
        """The lowest elastic natural frequency [Hz] (nan if none)."""
        f = self.elastic_frequencies_hz
        return float(f[0]) if f.size else math.nan

    def governing_element(self, mode: int) -> str:
        """Name of the element with the largest strain-energy share in ``mode``.

        Parameters
        ----------
        mode : int
            Index of the mode (0 the lowest).

        Returns
        -------
        str
            The element's name ("" for a rigid-body mode or a model without elements).
        """
        if self.rigid_body[mode] or not self.system.element_names:
            return ""
        return self.system.element_names[int(np.argmax(self.strain_energy_shares[:, mode]))]

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict; ``mode_shapes[node][j]`` is the node's angle in mode j.

        Returns
        -------
        dict
            Frequencies (``natural_frequencies_hz``, ``natural_frequencies_rad_s``), the
            rigid-body flags, the shapes [rad], the strain-energy shares [-] and the
            governing element of each mode.
        """
        shares = self.strain_energy_shares
        governing = ["" if r or not self.system.element_names else
                     self.system.element_names[int(np.argmax(shares[:, j]))]
                     for j, r in enumerate(self.rigid_body.tolist())]
        return {
            "natural_frequencies_hz": self.frequencies_hz.tolist(),
            "natural_frequencies_rad_s": self.angular_frequencies_rad_s.tolist(),
            "rigid_body_modes": self.rigid_body.tolist(),
            "mode_shapes": {n: row.tolist() for n, row in self.shapes.items()},
            "strain_energy_shares": dict(zip(self.system.element_names, shares.tolist(),
                                             strict=True)),
            "governing_elements": governing,
        }


class TorsionalEngine:
    """Builder of the torsional model of a drive train (module docstring; docs/torsional.md).

    Nodes are named. ``add_inertia`` creates a node (or gives its inertia to a node that an
    element created massless); shafts, meshes and spans create the nodes they name when new
    (massless until given an inertia); ground springs, torques and queries need an existing
    node. Every error is a DesignError naming the element.
    """

    def __init__(self) -> None:
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
        # elements: name, kind, a, b (-1: ground), coef_a, coef_b, k, c, tension_only
        self._elements: list[tuple[str, str, int, int, float, float, float, float, bool]] = []
        self._names: set[str] = set()
        self._system: TorsionalSystem | None = None

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
        name = name or default
        if name in self._names:
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
        i = self._node(name, True, name)
        if self._given[i]:
            raise DesignError(name, "the node already has an inertia")
        self._inertia[i] = _nonneg(name, inertia, "inertia [kg·m²]")
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
        i = self._node(name, False, name)
        self._inertia[i] += _nonneg(name, inertia, "inertia [kg·m²]")
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
            :func:`chaindrive.dynamics.drive_model.shaft_stiffness`).
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
        name = self._element_name(name, f"shaft:{a}-{b}")
        ia, ib = self._index.get(a), self._index.get(b)  # the common case: both exist
        if ia is None or ib is None or a == b:
            ia, ib = self._pair(a, b, name)
        k = float(stiffness)
        if not 0.0 <= k < _INF:  # also True for nan (as _nonneg, without the call)
            _nonneg(name, k, "stiffness [N·m/rad]")
        c = float(damping)
        if not 0.0 <= c < _INF:
            _nonneg(name, c, "damping [N·m·s/rad]")
        self._elements.append((name, "shaft", ia, ib, -1.0, 1.0, k, c, False))
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
        name = self._element_name(name, f"ground:{node}")
        i = self._node(node, False, name)
        k = _nonneg(name, stiffness, "stiffness [N·m/rad]")
        self._elements.append((name, "ground", i, -1, 1.0, 0.0, k,
                               _nonneg(name, damping, "damping [N·m·s/rad]"), False))
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
        name = self._element_name(name, f"span:{a}-{b}")
        ra, rb = float(radius_a), float(radius_b)
        if not (math.isfinite(ra) and math.isfinite(rb) and ra != 0.0 and rb != 0.0):
            raise DesignError(name, f"pitch radii must be finite and ≠ 0, got {ra!r}, {rb!r}")
        m = float(mass)
        if not 0.0 <= m < _INF:  # also True for nan (as _nonneg, without the call)
            _nonneg(name, m, "span mass [kg]")
        ia, ib = self._index.get(a), self._index.get(b)  # the common case: both exist
        if ia is None or ib is None or a == b:
            ia, ib = self._pair(a, b, name)
        k = float(stiffness)
        if not 0.0 <= k < _INF:
            _nonneg(name, k, "stiffness [N/m]")
        c = float(damping)
        if not 0.0 <= c < _INF:
            _nonneg(name, c, "damping [N·s/m]")
        self._elements.append((name, "span", ia, ib, -ra, rb, k, c, bool(tension_only)))
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
        name = self._element_name(name, f"{kind}:{a}-{b}")
        ra, rb = float(radius_a), float(radius_b)
        if not (math.isfinite(ra) and math.isfinite(rb) and ra != 0.0 and rb != 0.0):
            raise DesignError(name, f"radii must be finite and ≠ 0, got {ra!r}, {rb!r}")
        ia, ib = self._pair(a, b, name)
        k = _nonneg(name, stiffness, "stiffness [N/m]")
        self._elements.append((name, kind, ia, ib, -ra, rb, k,
                               _nonneg(name, damping, "damping [N·s/m]"), False))
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
        for k, e in enumerate(self._elements):
            if e[0] == element:
                self._elements[k] = (*e[:7], _nonneg(element, damping, "damping"), e[8])
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
        i = self._node(node, False, f"wrap:{node}")
        m = _nonneg(f"wrap:{node}", mass, "wrapped chain mass [kg]")
        self._chain[i] += m * float(radius) ** 2
        self._system = None
        return self

    def _kinematics(self, a: int, b: int, w: float, stiffness: float) -> None:
        """Strain-free relation φ_b = w·φ_a of an element (ignored at stiffness 0); one that
        contradicts the others holds its group (no rigid-body motion; resolved at assembly:
        :func:`chaindrive.dynamics.torsional_assembly.kinematic_groups`)."""
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

    # -- results ------------------------------------------------------------------------
    def system(self) -> TorsionalSystem:
        """The assembled :class:`TorsionalSystem` (cached until the model changes).

        Returns
        -------
        TorsionalSystem
            The matrices in reduced coordinates (module docstring).
        """
        if self._system is None:
            self._system = _assemble(self)
        return self._system

    def modal(self) -> TorsionalModes:
        """Undamped natural frequencies, shapes and strain-energy shares.

        Returns
        -------
        TorsionalModes
            Frequencies [Hz], mass-normalised shapes and strain-energy shares [-].

        References
        ----------
        [Rao2011, ch. 6]; massless coordinates condensed [Guyan1965].
        """
        return _modal(self.system())

    def frequencies_hz(self) -> FloatArray:
        """The natural frequencies of :meth:`modal` [Hz] without the shapes (LAPACK computes
        no eigenvectors: 2–3× faster, see benchmarks/bench_torsional.py).

        Returns
        -------
        ndarray
            Natural frequencies [Hz], ascending, the rigid-body zeros first.
        """
        return _frequencies(self.system())

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
            "elements": [{"name": e[0], "kind": e[1], "a": names[e[2]],
                          "b": None if e[3] < 0 else names[e[3]], "coef_a": e[4], "coef_b": e[5],
                          "stiffness": e[6], "damping": e[7], "tension_only": e[8]}
                         for e in self._elements],
            "gear_meshes": [{"name": m[0], "driver": names[m[1]], "driven": names[m[2]],
                             "ratio": m[3], "efficiency": m[4], "same_sense": m[5] > 0}
                            for m in self._meshes],
        }


def _assemble(model: TorsionalEngine) -> TorsionalSystem:
    """Reduced coordinates (one per gear tree), element incidence, rigid-body motions, on
    whole arrays (:mod:`chaindrive.dynamics.torsional_assembly`)."""
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
    names, kinds, a, b, ca, cb, k, c, tension = (zip(*el, strict=True) if el else
                                                 ((),) * 9)
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


def _deflated_eigh(A: FloatArray, W: FloatArray,
                   vectors: bool = True) -> tuple[FloatArray, FloatArray]:
    """Eigenpairs of the symmetric A on the orthogonal complement of the orthonormal columns
    W (exact null vectors of A): (λ, V) with V orthonormal and Wᵀ V = 0.

    One null vector: a Householder reflector H (H w = −e₁) makes H A H block-diagonal, O(n²);
    more: a complete QR basis of the complement.
    """
    n, r = W.shape
    if r == 1:
        w = W[:, 0]
        v = w.copy()
        v[0] += math.copysign(1.0, w[0])  # H = I − 2 v vᵀ / vᵀv maps w to ∓e₁
        v /= math.sqrt(v @ v)
        Av = A @ v
        u = Av - (v @ Av) * v            # H A H = A − 2 (v uᵀ + u vᵀ)
        v1, u1 = v[1:, None], u[1:, None]
        B = A[1:, 1:] - 2.0 * (v1 * u1.T + u1 * v1.T)
        if not vectors:
            return np.asarray(np.linalg.eigvalsh(B), dtype=np.float64), np.empty((n, 0))
        lam, Ve = np.linalg.eigh(B)
        V = np.zeros((n, n - 1))
        V[1:] = Ve
        V -= 2.0 * (v[:, None] * (v @ V)[None, :])
        return np.asarray(lam, dtype=np.float64), V
    basis = np.linalg.qr(W, mode="complete")[0][:, r:]
    if not vectors:
        return np.linalg.eigvalsh(basis.T @ A @ basis), np.empty((n, 0))
    lam, Ve = np.linalg.eigh(basis.T @ A @ basis)
    return lam, basis @ Ve


@dataclass(frozen=True, slots=True, eq=False)
class _Scaling:
    """y = S q of the massed coordinates with Sᵀ S = M: S = diag(√m) for a diagonal M, else
    S = Lᵀ of the Cholesky factor M = L Lᵀ (a consistent chain mass couples two ends)."""

    sqrt_m: FloatArray | None
    L: FloatArray | None

    def y_of(self, q: FloatArray) -> FloatArray:
        """S q."""
        return q * self.sqrt_m[:, None] if self.sqrt_m is not None else self.L.T @ q  # type: ignore[union-attr]

    def q_of(self, y: FloatArray) -> FloatArray:
        """S⁻¹ y."""
        if self.sqrt_m is not None:
            return y / self.sqrt_m[:, None]
        return np.linalg.solve(self.L.T, y)  # type: ignore[union-attr]

    def scaled(self, K: FloatArray) -> FloatArray:
        """S⁻ᵀ K S⁻¹ (symmetric)."""
        if self.sqrt_m is not None:
            d = 1.0 / self.sqrt_m
            return K * d[:, None] * d[None, :]
        Y = np.linalg.solve(self.L, K)  # type: ignore[arg-type]
        A = np.linalg.solve(self.L, Y.T)  # type: ignore[arg-type]
        return 0.5 * (A + A.T)


def _scaled_problem(system: TorsionalSystem) -> tuple[FloatArray, _Scaling, FloatArray,
                                                      FloatArray | None, NDArray[np.bool_]]:
    """(A = S⁻ᵀ K_c S⁻¹, S, U, X, massed): the condensed, mass-scaled stiffness, the scaling
    Sᵀ S = M of the massed coordinates, their rigid-body motions U made M-orthonormal, the
    condensation X."""
    mass = system.mass
    massed = mass > 0.0
    if not massed.any():
        raise DesignError("inertia", "every node is massless: no mode to compute")
    K = system.stiffness_matrix()
    massless = ~massed
    X = None
    if massless.any():
        X = _condensation(K, massless, system.node_names, system.node_dof)
        K = K[np.ix_(massed, massed)] - K[np.ix_(massed, massless)] @ X
        U = system.rigid_motions[massed]
    else:
        U = system.rigid_motions
    if system.has_mass_coupling:
        Mm = system.mass_matrix()[np.ix_(massed, massed)]
        scaling = _Scaling(None, np.asarray(np.linalg.cholesky(Mm), dtype=np.float64))
        if U.shape[1]:  # M-orthonormal rigid motions (groups may touch through a span's mass)
            G = U.T @ Mm @ U
            U = U @ np.linalg.inv(np.linalg.cholesky(G)).T
        return scaling.scaled(K), scaling, U, X, massed
    m = mass if X is None else mass[massed]
    sqrt_m = np.sqrt(m)
    scaling = _Scaling(sqrt_m, None)
    if U.shape[1]:  # disjoint groups are M-orthogonal already
        U = U / np.sqrt((m[:, None] * U * U).sum(axis=0))
    d = 1.0 / sqrt_m
    K *= d[:, None]  # K is this call's own array: S⁻ᵀ K S⁻¹ in place (as _Scaling.scaled)
    K *= d[None, :]
    return K, scaling, U, X, massed


def _frequencies(system: TorsionalSystem) -> FloatArray:
    """Natural frequencies only [Hz] (rigid-body zeros first), no eigenvectors."""
    A, scaling, U, _, _ = _scaled_problem(system)
    nm, nr = int(A.shape[0]), int(U.shape[1])
    f = np.zeros(nm)
    if nr == 0:
        lam = np.linalg.eigvalsh(A)
    elif nr < nm:
        lam = _deflated_eigh(A, scaling.y_of(U), vectors=False)[0]
    else:
        return f
    f[nr:] = np.sqrt(np.maximum(lam, 0.0)) / TWO_PI
    return f


def _modal(system: TorsionalSystem) -> TorsionalModes:
    """Modes of the assembled system (module docstring: condensation, rigid-body modes)."""
    A, scaling, U, X, massed = _scaled_problem(system)
    nm, nr = int(A.shape[0]), int(U.shape[1])
    if nr:
        lam, V = _deflated_eigh(A, scaling.y_of(U)) if nr < nm else \
            (np.empty(0), np.empty((nm, 0)))
        Qm = np.concatenate([U, scaling.q_of(V)], axis=1)
    else:
        lam, V = np.linalg.eigh(A)
        Qm = scaling.q_of(V)
    if X is None:
        Q = Qm
    else:
        Q = np.empty((system.size, nm))
        Q[massed] = Qm
        Q[~massed] = -X @ Qm
    f = np.zeros(nm)
    f[nr:] = np.sqrt(np.maximum(lam, 0.0)) / TWO_PI
    rigid = np.zeros(nm, dtype=bool)
    rigid[:nr] = True
    return TorsionalModes(frequencies_hz=f, rigid_body=rigid, system=system, modal_coordinates=Q)
