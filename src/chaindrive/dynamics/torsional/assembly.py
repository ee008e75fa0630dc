"""Assembly of the torsional model on plain arrays (the engine is
:class:`chaindrive.dynamics.torsional.engine.TorsionalEngine`; docs/torsional.md): the gear
trees' reduced coordinates, the groups of strain-free motion, the element incidence in the
(at most two) columns of each row and the scatter of K and C from it.

Every step but the union–find (one pass over the relations recorded while building) works
on whole arrays built once per assembly — index arrays and a single scatter per matrix — so
that assembling a
model of a few dozen nodes costs a few tens of microseconds (benchmarks/bench_torsional.py).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters

__all__ = ["RATIO_RTOL", "WeightedUnion", "gear_coordinates", "gram", "grams", "incidence",
           "kinematic_groups", "rigid_motions"]

FloatArray = NDArray[np.float64]
IndexArray = NDArray[np.intp]
#: Relative tolerance of kinematic ratios (gear loops, strain-free rigid motions).
RATIO_RTOL = 1e-9


class WeightedUnion:
    """Union–find of coordinates tied by linear relations x_child = w·x_parent."""

    __slots__ = ("joined", "parent", "weight")

    def __init__(self) -> None:
        self.parent: list[int] = []
        self.weight: list[float] = []
        self.joined = False  # True once a relation joined two elements

    def find(self, i: int) -> tuple[int, float]:
        """The root of a coordinate's tree and its factor (path halving).

        Parameters
        ----------
        i : int
            The coordinate's index.

        Returns
        -------
        tuple of int and float
            (root, w) with x_i = w·x_root [-].
        """
        return _find(self.parent, self.weight, i)

    def relate(self, a: int, b: int, w_ab: float) -> bool:
        """Impose x_b = w_ab·x_a.

        Parameters
        ----------
        a, b : int
            The two coordinates' indices.
        w_ab : float
            The factor [-] (a gear ratio with its sense).

        Returns
        -------
        bool
            False if it contradicts the relations already there.
        """
        joined = _relate(self.parent, self.weight, a, b, w_ab)
        self.joined = self.joined or joined is True
        return joined is not False


def _find(parent: list[int], weight: list[float], i: int) -> tuple[int, float]:
    """(root, w) of coordinate ``i`` with x_i = w·x_root, halving the path on the way."""
    w = 1.0
    while parent[i] != i:
        p = parent[i]
        if parent[p] != p:  # compress: point i at its grandparent
            weight[i] *= weight[p]
            parent[i] = parent[p]
        w *= weight[i]
        i = parent[i]
    return i, w


def _relate(parent: list[int], weight: list[float], a: int, b: int,
            w_ab: float) -> bool | None:
    """Impose x_b = w_ab·x_a: True when it joined two trees, None when it agrees with the
    relations already there, False when it contradicts them."""
    ra, fa = _find(parent, weight, a)
    rb, fb = _find(parent, weight, b)
    if ra == rb:
        return None if abs(fb - w_ab * fa) <= RATIO_RTOL * max(abs(fb), abs(w_ab * fa)) else False
    parent[rb] = ra
    weight[rb] = w_ab * fa / fb
    return True


def gear_coordinates(gears: WeightedUnion, n_nodes: int) -> tuple[IndexArray, FloatArray, int]:
    """The reduced coordinate of every node: one per gear tree, in order of first appearance,
    φ_node = factor·q (gear meshes eliminated).

    Parameters
    ----------
    gears : WeightedUnion
        The union–find of the gear meshes (x_driven = w·x_driver).
    n_nodes : int
        Number of nodes [-].

    Returns
    -------
    tuple of ndarray, ndarray and int
        node_dof (nodes,) coordinate of each node [-], factor (nodes,) φ_node / q [-], and the
        number n of coordinates [-].
    """
    if not gears.joined:
        return np.arange(n_nodes, dtype=np.intp), np.ones(n_nodes), n_nodes
    dof_of_root: dict[int, int] = {}
    node_dof = np.empty(n_nodes, dtype=np.intp)
    factor = np.empty(n_nodes)
    for i in range(n_nodes):
        root, factor[i] = gears.find(i)
        node_dof[i] = dof_of_root.setdefault(root, len(dof_of_root))
    return node_dof, factor, len(dof_of_root)


def kinematic_groups(n_nodes: int, relations: Sequence[tuple[int, int, float]],
                     held: Sequence[bool]) -> tuple[IndexArray, FloatArray, NDArray[np.bool_]]:
    """The groups of strain-free motion of the stiff elements and meshes.

    The union–find of :class:`WeightedUnion` (path halving) over the relations in the order
    recorded.

    Parameters
    ----------
    n_nodes : int
        Number of nodes [-].
    relations : sequence of (int, int, float)
        (a, b, w_ab): φ_b = w_ab·φ_a in a strain-free motion [-], in the order recorded.
    held : sequence of bool
        Nodes held by a ground spring.

    Returns
    -------
    tuple of ndarray
        root (nodes,) the group's root node [-]; w (nodes,) φ_node = w·φ_root [-]; held_root
        (nodes,) True at the roots of groups without a strain-free motion (a ground spring, or
        a loop whose ratios disagree).
    """
    parent, weight = list(range(n_nodes)), [1.0] * n_nodes
    held_nodes = list(held)
    for a, b, w_ab in relations:
        if _relate(parent, weight, a, b, w_ab) is False:
            held_nodes[a] = True
    found = [_find(parent, weight, j) for j in range(n_nodes)]
    root = np.array([r for r, _ in found], dtype=np.intp)
    held_root = np.zeros(n_nodes, dtype=bool)
    held_root[root[np.array(held_nodes, dtype=bool)]] = True
    return root, np.array([w for _, w in found], dtype=np.float64), held_root


@shared_parameters
def rigid_motions(node_dof: IndexArray, factor: FloatArray, kin_root: IndexArray,
                  kin_w: FloatArray, held_root: NDArray[np.bool_], n: int) -> FloatArray:
    """One exact strain-free motion per free group (no ground spring, no mismatched loop), in
    reduced coordinates: q_k = φ_n / factor_n of any node n of coordinate k.

    Parameters
    ----------
    %(node_dof_factor)s
    kin_root : ndarray
        (nodes,) root of each node's group [-] (:func:`kinematic_groups`).
    kin_w : ndarray
        (nodes,) φ_node / φ_root in the group's strain-free motion [-].
    held_root : ndarray
        (nodes,) True at held roots.
    n : int
        Number of coordinates [-].

    Returns
    -------
    ndarray
        (n, r) the motions [-], one column per free group.
    """
    free = [r for r in dict.fromkeys(kin_root.tolist()) if not held_root[r]]
    rigid = np.zeros((n, len(free)))
    if free:
        column = np.full(kin_root.size, -1, dtype=np.intp)
        column[free] = np.arange(len(free))
        col = column[kin_root]
        nodes = col >= 0
        rigid[node_dof[nodes], col[nodes]] = kin_w[nodes] / factor[nodes]
    return rigid


@shared_parameters
def incidence(node_dof: IndexArray, factor: FloatArray, a: IndexArray, b: IndexArray,
              coef_a: FloatArray, coef_b: FloatArray,
              n: int) -> tuple[FloatArray, IndexArray, FloatArray]:
    """The element incidence B, strain e = B q, and the (at most two) entries of each row:
    nonzero ones first in ascending column, then the first zero column.

    Parameters
    ----------
    %(node_dof_factor)s
    a, b : ndarray
        (elements,) the two end nodes [-] (b < 0: an element to the ground).
    coef_a, coef_b : ndarray
        (elements,) e = coef_a·φ_a + coef_b·φ_b [m/rad for a span, - for a shaft].
    n : int
        Number of coordinates [-].

    Returns
    -------
    tuple of ndarray
        B (elements, n), cols (elements, 2) [-] and coef (elements, 2), in the unit of
        ``coef_a``.
    """
    ne = a.size
    plain = n == node_dof.size  # no gear mesh: every node its own coordinate, factor 1
    ka, va = (a, coef_a) if plain else (node_dof[a], coef_a * factor[a])
    if ne and b.min() >= 0:
        kb, vb = (b, coef_b) if plain else (node_dof[b], coef_b * factor[b])
    else:
        two = b >= 0
        b_safe = np.where(two, b, a)
        kb = np.where(two, node_dof[b_safe], ka)
        vb = np.where(two, coef_b * factor[b_safe], 0.0)
    swap = kb < ka
    c0, c1 = np.where(swap, kb, ka), np.where(swap, ka, kb)
    v0, v1 = np.where(swap, vb, va), np.where(swap, va, vb)
    same = np.flatnonzero(ka == kb)  # to the ground, or both ends on one coordinate (meshed)
    if same.size:
        v0[same] = va[same] + vb[same]
        v1[same] = 0.0
        c1[same] = np.where(ka[same] == 0, 1, 0)
        cancelled = same[v0[same] == 0.0]
        c0[cancelled], c1[cancelled] = 0, 1
    if n == 1:
        c1[:] = 0
    B = np.zeros((ne, n))
    rows = np.arange(ne)
    B[rows, c0] = v0
    B[rows, c1] += v1
    return B, np.column_stack([c0, c1]).astype(np.intp, copy=False), np.column_stack([v0, v1])


def gram(cols: IndexArray, coef: FloatArray, weights: FloatArray, n: int) -> FloatArray:
    """Σ_e w_e b_e b_eᵀ of elements whose incidence rows b_e have at most two nonzero entries:
    a scatter of four products per element instead of a dense Bᵀ diag(w) B.

    Parameters
    ----------
    cols : ndarray
        (elements, 2) columns of the entries [-] (:func:`incidence`).
    coef : ndarray
        (elements, 2) the entries [m/rad for a span, - for a shaft].
    weights : ndarray
        (elements,) w_e: stiffnesses [N/m or N·m/rad] or dampers [N·s/m or N·m·s/rad].
    n : int
        Number of coordinates [-].

    Returns
    -------
    ndarray
        (n, n) the matrix [N·m/rad or N·m·s/rad].
    """
    return grams(cols, coef, (weights,), n)[0]


def grams(cols: IndexArray, coef: FloatArray, weights: Sequence[FloatArray],
          n: int) -> list[FloatArray]:
    """:func:`gram` of several weightings of the same elements (e.g. their stiffnesses and
    their dampers), the scatter indices built once.

    Parameters
    ----------
    cols : ndarray
        (elements, 2) columns of the entries [-].
    coef : ndarray
        (elements, 2) the entries [m/rad for a span, - for a shaft].
    weights : sequence of ndarray
        Each (elements,) [N/m or N·m/rad, or N·s/m or N·m·s/rad].
    n : int
        Number of coordinates [-].

    Returns
    -------
    list of ndarray
        One (n, n) matrix per weighting.
    """
    if cols.shape[0] == 0:
        return [np.zeros((n, n)) for _ in weights]
    a, b = cols[:, 0], cols[:, 1]
    ca, vb = coef[:, 0], coef[:, 1]
    idx = np.concatenate([a * n + a, b * n + b, a * n + b, b * n + a])
    vbb = vb * vb
    out = []
    for w_e in weights:
        va = ca * w_e
        vab = va * vb
        w = np.concatenate([va * ca, vbb * w_e, vab, vab])
        out.append(np.asarray(np.bincount(idx, weights=w, minlength=n * n),
                              dtype=np.float64).reshape(n, n))
    return out
