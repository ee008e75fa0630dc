"""The assembled torsional system of a drive train and its undamped modes: the matrices of a
:class:`chaindrive.dynamics.torsional.engine.TorsionalEngine` in reduced coordinates
(:class:`TorsionalSystem`) and the natural frequencies and mode shapes solved from them
(:class:`chaindrive.dynamics.modes.Modes`), docs/torsional.md.

The reduced mass matrix is diagonal up to the chain's consistent-mass coupling; the modes
come from the symmetric eigenproblem of M^{-1/2} K M^{-1/2} [Rao2011, ch. 6] after the
massless coordinates are condensed out statically [Guyan1965]. Rigid-body modes are counted
from the graph, set to exactly 0 Hz with their exact shapes and projected out before the
eigensolver (deflation), so that no eigenvalue is zeroed by a round-off threshold.

References
----------
[Rao2011] ch. 6; [Guyan1965].
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import freeze_arrays, rebuilt
from chaindrive.dynamics.modes import Modes
from chaindrive.dynamics.precision import check_spread
from chaindrive.dynamics.torsional.assembly import gram as _gram
from chaindrive.dynamics.torsional.assembly import grams
from chaindrive.dynamics.torsional.blas_threads import small_problem_threads
from chaindrive.errors import DesignError
from chaindrive.units import TWO_PI

__all__ = ["TorsionalSystem"]

FloatArray = NDArray[np.float64]


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

    def __post_init__(self) -> None:
        freeze_arrays(self)  # read-only arrays (writeable inputs copied)

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        return rebuilt(self)  # unpickled: frozen again

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

    def modal(self) -> Modes:
        """Undamped natural frequencies, shapes and strain-energy shares (as
        :meth:`TorsionalEngine.modal`).

        Returns
        -------
        Modes
            Frequencies [Hz], mass-normalised shapes and strain-energy shares [-].

        References
        ----------
        [Rao2011, ch. 6]; massless coordinates condensed [Guyan1965]; on one BLAS thread
        when small (:func:`chaindrive.dynamics.torsional.blas_threads.small_problem_threads`).
        """
        with small_problem_threads(self.size):
            return _modal(self)

    def frequencies_hz(self) -> FloatArray:
        """The natural frequencies [Hz] without the shapes (as
        :meth:`TorsionalEngine.frequencies_hz`).

        Returns
        -------
        ndarray
            Natural frequencies [Hz], ascending, the rigid-body zeros first.
        """
        with small_problem_threads(self.size):
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

    @shared_parameters
    def stiffness_matrix(self, span_active: ArrayLike | None = None) -> FloatArray:
        """K with the spans flagged in ``span_active`` carrying [N·m/rad].

        %(span_active_matrix)s
            (size, size) K = K_lin + Bᵀ diag(c·a) B [N·m/rad].
        """
        return self.stiffness_linear + self._span_gram(self.span_stiffness_n_per_m, span_active)

    @shared_parameters
    def damping_matrix(self, span_active: ArrayLike | None = None) -> FloatArray:
        """C with the spans flagged in ``span_active`` carrying [N·m·s/rad].

        %(span_active_matrix)s
            (size, size) C = C_lin + Bᵀ diag(d·a) B [N·m·s/rad].
        """
        return self.damping_linear + self._span_gram(self.span_damping_n_s_per_m, span_active)

    def _span_gram(self, values: FloatArray, span_active: ArrayLike | None) -> FloatArray:
        """Bᵀ diag(w) B of the spans, by scatter, w = ``values``·``span_active``."""
        weights = values if span_active is None else values * np.asarray(span_active,
                                                                          dtype=float)
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
        T = self.condensation_basis(K)
        return T, T.T @ self.mass_matrix() @ T, T.T @ K @ T, T.T @ C @ T

    def condensation_basis(self, stiffness: FloatArray, field: str = "inertia") -> FloatArray:
        """T of the static condensation q = T q_m of the massless coordinates (mass 0) under
        ``stiffness``: the massed rows the identity, the massless rows −K_00⁻¹ K_0m (0 the
        massless, m the massed coordinates; exact for undamped motion).

        Parameters
        ----------
        stiffness : ndarray
            (size, size) the stiffness K that holds the massless coordinates [N·m/rad].
        field : str
            The field a DesignError names when K_00 is singular.

        Returns
        -------
        ndarray
            T (size, m) [-] (the identity when no coordinate is massless).

        Raises
        ------
        DesignError
            On ``field``: a massless node is held by no spring of ``stiffness``.

        References
        ----------
        [Guyan1965].
        """
        massless = self.mass <= 0.0
        if not massless.any():
            return np.eye(self.size)
        X = _condensation(stiffness, massless, self.node_names, self.node_dof, field)
        T = np.zeros((self.size, int((~massless).sum())))
        T[~massless] = np.eye(T.shape[1])
        T[massless] = -X
        return T


def _condensation(K: FloatArray, massless: NDArray[np.bool_], names: Sequence[str],
                  node_dof: NDArray[np.intp], field: str = "inertia") -> FloatArray:
    """X = K_00⁻¹ K_0m (massless rows 0, massed columns m); DesignError on ``field`` if K_00
    is singular."""
    m = ~massless
    K00 = K[np.ix_(massless, massless)]
    try:
        L = np.linalg.cholesky(K00)
    except np.linalg.LinAlgError:
        free = [n for n, k in zip(names, node_dof, strict=True) if massless[k]]
        raise DesignError(field, f"massless node(s) among {free} are not held by any "
                          "spring (singular stiffness): give them an inertia or a spring") from None
    Y = np.linalg.solve(L, K[np.ix_(massless, m)])
    return np.linalg.solve(L.T, Y)


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
    check_spread(lam)  # as _modal: both answer, or both refuse
    f[nr:] = np.sqrt(np.maximum(lam, 0.0)) / TWO_PI
    return f


def _modal(system: TorsionalSystem) -> Modes:
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
    check_spread(lam)  # modes lost in round-off are refused, never answered
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
    shapes = system.node_factor[:, None] * Q[system.node_dof]  # as Modes.shape_matrix
    for a in (f, rigid, Q, shapes):  # the solver's own arrays: frozen in place, not copied
        a.flags.writeable = False
    return Modes(frequencies_hz=f, rigid_body=rigid, shapes=shapes, system=system,
                 modal_coordinates=Q)
