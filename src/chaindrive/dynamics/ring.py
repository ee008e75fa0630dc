"""The n-mass ring model of a chain contour and its modal analysis.

[MultimassChainDrives] (§3.1–3.2): the rotating masses of sprocket i are reduced to the
radius of the hinge centres, m_i = I_i / R_i², the displacement is x_i = R_i φ_i, and branch
(span) i joins mass i to mass i+1 (the last joins mass n to mass 1 and closes the ring)::

    M ẍ + K x = f(t),     K = Σ_i c_i (e_i − e_{i+1})(e_i − e_{i+1})ᵀ

— K is the weighted Laplacian of the ring graph. Sign convention: the elongation of branch
i is e_i = x_{i+1} − x_i, a branch in tension has e > 0 and pulls mass i forward.
The natural frequencies are the roots of det(K − ω² M) = 0 ([MultimassChainDrives, eq. 2]), solved here as
the symmetric eigenproblem of M^{-1/2} K M^{-1/2} (M is diagonal) with LAPACK ``syevd``.
A branch of stiffness 0 (a slack span) drops out: the ring becomes an open chain. Each
connected group of masses has one rigid-body mode; its frequency is set to exactly 0 and its
shape to the uniform vector of the group (not the 0.08 Hz of [MultimassChainDrives], Table 2).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.modes import Modes
from chaindrive.dynamics.precision import check_spread
from chaindrive.errors import DesignError
from chaindrive.units import TWO_PI

if TYPE_CHECKING:

    pass

__all__ = ["RingModel", "modal_analysis", "ring_frequencies_batch",
           "ring_stiffness_matrix"]

_ALL = np.arange(64)
_ALL.flags.writeable = False


def ring_stiffness_matrix(stiffness: ArrayLike, closed: bool = True) -> NDArray[np.float64]:
    """Stiffness matrix K [N/m] of masses on a ring joined by branches ``stiffness`` [N/m].

    K is the weighted graph Laplacian: symmetric, positive semi-definite, rows summing to 0.

    Parameters
    ----------
    stiffness : array_like
        (n,) branch stiffnesses c_i [N/m]; branch i joins mass i and i+1.
    closed : bool
        True: the last branch joins mass n and 1; False: it is ignored (an open chain of n
        masses and n−1 branches).

    Returns
    -------
    ndarray
        (n, n) K [N/m].

    References
    ----------
    [MultimassChainDrives, eq. 2].
    """
    c = np.asarray(stiffness, dtype=float).copy()
    n = c.size
    if not closed:
        c[-1] = 0.0
    i = np.arange(n)
    j = (i + 1) % n
    K = np.zeros((n, n))
    if n == 2:  # both branches join the same two masses: they act in parallel
        s = c.sum()
        K[:] = [[s, -s], [-s, s]]
        return K
    K[i, i] = c + np.roll(c, 1)
    K[i, j] = -c
    K[j, i] = -c
    return K


def _components(cuts: list[int], n: int) -> list[NDArray[np.intp]] | list[slice]:
    """Groups of masses joined by branches of non-zero stiffness (ring order kept);
    ``cuts``: sorted indices of the slack branches (cut k separates mass k and k+1)."""
    if len(cuts) <= 1:  # a closed ring, or one opened by a single slack branch
        return [slice(None)]
    groups = []
    for a, b in zip(cuts, cuts[1:] + cuts[:1], strict=True):
        stop = b + 1 if b > a else b + 1 + n  # b == a: a single cut, one open chain
        groups.append(np.arange(a + 1, stop) % n)
    return groups


def _check_damping(damping_ratio: float) -> float:
    if not (math.isfinite(damping_ratio) and 0.0 <= damping_ratio < 1.0):
        raise DesignError("damping_ratio", f"must be from 0 to below 1, got {damping_ratio!r}")
    return float(damping_ratio)


def modal_analysis(masses: ArrayLike, stiffness: ArrayLike, closed: bool = True,
                   damping_ratio: float = 0.0) -> Modes:
    """Undamped modal analysis of masses on a ring ([MultimassChainDrives, eq. 2]).

    Solves K X = ω² M X through the symmetric standard form A = M^{-1/2} K M^{-1/2}
    (one LAPACK call: ``dsyevd``, or ``dstevd`` for a ring opened by a slack branch, which
    is tridiagonal when numbered from the cut, when SciPy is loaded; measured faster than the
    generalised ``scipy.linalg.eigh``, see ``benchmarks/bench_modal.py``). Rigid-body
    eigenvalues (one per connected group of masses) are set to exactly 0 with uniform shapes
    over their group; every other eigenvalue is a genuine mode, however small (only a
    negative round-off value is clamped to 0).

    Parameters
    ----------
    masses : array_like
        (n,) reduced masses m_i [kg], all > 0.
    stiffness : array_like
        (n,) branch stiffnesses c_i [N/m] ≥ 0; branch i joins mass i and i+1.
    closed : bool
        False for an open chain (the last branch is ignored).
    damping_ratio : float
        ζ for the damped frequencies f·sqrt(1 − ζ²) [-] (modal, light damping).

    Returns
    -------
    Modes
        Frequencies, mass-normalised shapes, the damped frequencies and the partial ones.

    References
    ----------
    [MultimassChainDrives, eq. 2]; [Rao2011, ch. 6] (mass-normalised modes).
    """
    m = np.array(masses, dtype=float)
    c = np.array(stiffness, dtype=float)
    _validate(m, c)
    if not closed:
        c[-1] = 0.0
    return _modal(m, c, _check_damping(damping_ratio))


def _scaled_stiffness(m: NDArray[np.float64], c: NDArray[np.float64],
                      d: NDArray[np.float64]) -> NDArray[np.float64]:
    """A = M^{-1/2} K M^{-1/2} of a ring (branch i joins mass i and i+1), built directly."""
    n = m.size
    A = np.zeros((n, n))
    if n == 2:
        s = c[0] + c[1]
        A[0, 0], A[1, 1] = s / m[0], s / m[1]
        A[0, 1] = A[1, 0] = -s * d[0] * d[1]
        return A
    c_prev = np.empty(n)
    c_prev[0] = c[-1]
    c_prev[1:] = c[:-1]
    off = -c * d * np.append(d[1:], d[0])
    flat = A.reshape(-1)
    flat[:: n + 1] = (c + c_prev) / m
    flat[1:: n + 1] = off[:-1]
    flat[n:: n + 1] = off[:-1]
    A[0, n - 1] = A[n - 1, 0] = off[-1]
    return A


def _scipy_lapack() -> Any:
    """SciPy's LAPACK wrappers when ``scipy.linalg`` is already imported in this process,
    else None.

    Importing ``scipy.linalg`` costs about 0.3 s (SciPy 1.17 on the project machine,
    ``python -X importtime``), more than one command-line analysis spends in all its modal
    analyses together (about a dozen, 60 µs each). A process that has it anyway — the
    optimiser, the web page, a notebook, the benchmarks — gets the tridiagonal solver
    ``dstevd`` (10–25 % faster than NumPy's dense ``eigh`` at n = 24, measured in
    ``benchmarks/bench_modal.py``); the command line gets NumPy's ``eigh``. Both are LAPACK
    and agree to round-off.
    """
    linalg = sys.modules.get("scipy.linalg")
    return getattr(linalg, "lapack", None)


def _eigen(m: NDArray[np.float64], c: NDArray[np.float64], d: NDArray[np.float64],
           cut: int | None) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                     NDArray[np.float64]]:
    """Eigenvalues, eigenvectors of A = M^{-1/2} K M^{-1/2} and its diagonal.

    A ring cut at branch ``cut`` (slack) is, numbered from mass cut+1, a tridiagonal
    matrix: solved with LAPACK ``dstevd`` when SciPy's linalg is loaded
    (:func:`_scipy_lapack`), else as a dense symmetric matrix; a closed ring with the dense
    ``dsyevd`` (through :func:`numpy.linalg.eigh`).
    """
    n = m.size
    lapack = _scipy_lapack() if cut is not None and n > 2 else None
    if lapack is not None and cut is not None:
        last = cut == n - 1
        order = None if last else np.roll(_ALL[:n] if n <= _ALL.size else np.arange(n),
                                           -(cut + 1))
        mr, cr, dr = (m, c, d) if last else (m[order], c[order], d[order])
        # numbered from the cut, branch n-1 is the slack one (cr[-1] == 0)
        diag = np.empty(n)
        diag[0] = cr[0]
        np.add(cr[1:], cr[:-1], out=diag[1:])
        diag /= mr
        off = cr[:-1] * dr[:-1]
        off *= dr[1:]
        np.negative(off, out=off)
        lam, V, info = lapack.dstevd(diag, off, compute_v=1)
        if info == 0:
            if last:
                return lam, V, diag
            Vf = np.empty_like(V)
            Vf[order] = V
            full = np.empty(n)
            full[order] = diag
            return lam, Vf, full
    A = _scaled_stiffness(m, c, d)
    lam, V = np.linalg.eigh(A)
    return lam, V, A.diagonal().copy()


def _modal(m: NDArray[np.float64], c: NDArray[np.float64], zeta: float) -> Modes:
    """Core of :func:`modal_analysis` on validated arrays (c with slack branches at 0)."""
    n = m.size
    cuts = [i for i, ci in enumerate(c.tolist()) if ci <= 0.0]
    d = 1.0 / np.sqrt(m)
    lam, V, diag = _eigen(m, c, d, cuts[0] if cuts else None)
    V *= d[:, None]  # mass-normalised shapes (V is LAPACK's fresh array: scaled in place)
    shapes = V
    groups = _components(cuts, n)
    n_rigid = len(groups)
    # exactly one rigid-body mode per group; a small elastic eigenvalue is a genuine mode
    # (e.g. masses [1, 1e-11, 1]: 0.159 Hz), never zeroed by a relative round-off threshold
    lam[:n_rigid] = 0.0
    check_spread(lam[n_rigid:])  # modes lost in round-off are refused, never answered
    np.maximum(lam, 0.0, out=lam)
    if n_rigid == 1 and isinstance(groups[0], slice):  # one connected ring: uniform shape
        shapes[:, 0] = 1.0 / math.sqrt(math.fsum(m.tolist()))
    else:
        for k, g in enumerate(groups):  # exact rigid-body shapes, M-orthonormal
            shapes[:, k] = 0.0
            shapes[g, k] = 1.0 / math.sqrt(m[g].sum())  # type: ignore[index,call-overload]
    rigid = np.zeros(n, dtype=bool)
    rigid[:n_rigid] = True
    np.sqrt(lam, out=lam)
    lam *= 1.0 / TWO_PI
    ratios = np.where(rigid, 0.0, zeta)
    for a in (lam, shapes, rigid, m, c, diag, ratios):  # fresh arrays: frozen, not copied
        a.flags.writeable = False
    return Modes(lam, rigid, shapes, lam * math.sqrt(1.0 - zeta**2), ratios, m, c, zeta,
                 scaled_diagonal=diag)


def _validate(m: NDArray[np.float64], c: NDArray[np.float64]) -> None:
    if m.ndim != 1 or m.size < 2:
        raise DesignError("masses_kg", f"need a list of at least 2 masses, got shape {m.shape}")
    if c.shape != m.shape:
        raise DesignError("stiffness_n_per_m",
                          f"need one stiffness per mass ({m.size}), got shape {c.shape}")
    # on Python lists: a NumPy reduction costs more than the whole check for n ≤ 24
    ml, cl = m.tolist(), c.tolist()
    if not (min(ml) > 0 and min(cl) >= 0 and math.isfinite(sum(ml) + sum(cl))):
        if not (min(ml) > 0 and math.isfinite(sum(ml))):
            raise DesignError("masses_kg", f"must all be positive and finite, got {ml}")
        raise DesignError("stiffness_n_per_m", f"must all be finite and ≥ 0, got {cl}")


def ring_frequencies_batch(masses: ArrayLike, stiffness: ArrayLike,
                           closed: bool = True) -> NDArray[np.float64]:
    """Natural frequencies [Hz] of many ring models at once (frequencies only).

    Builds the stacked symmetric matrices M^{-1/2} K M^{-1/2} with vectorised indexing and
    calls :func:`numpy.linalg.eigvalsh` once (same eigenproblem as :func:`modal_analysis`).

    Parameters
    ----------
    masses : array_like
        (B, n) reduced masses [kg] of B designs.
    stiffness : array_like
        (B, n) branch stiffnesses [N/m]; branch i joins mass i and i+1.
    closed : bool
        False for open chains (the last branch of every design is ignored).

    Returns
    -------
    ndarray
        (B, n) ascending frequencies [Hz]; the rigid-body modes (one per connected group of
        masses) come out as exactly 0.

    References
    ----------
    [MultimassChainDrives, eq. 2].
    """
    m = np.atleast_2d(np.asarray(masses, dtype=float))
    c = np.array(np.atleast_2d(np.asarray(stiffness, dtype=float)))
    if m.shape != c.shape or m.shape[1] < 2:
        raise DesignError("stiffness_n_per_m",
                          f"masses and stiffness must both be (B, n ≥ 2), got {m.shape}, {c.shape}")
    if not (np.all(m > 0) and np.all(c >= 0)):
        raise DesignError("masses_kg", "masses must be > 0 and stiffnesses ≥ 0")
    if not closed:
        c[:, -1] = 0.0
    B, n = m.shape
    inv_m = 1.0 / m
    d = np.sqrt(inv_m)
    A = np.zeros((B, n, n))
    i = np.arange(n)
    j = (i + 1) % n
    if n == 2:
        s = c.sum(axis=1)
        A[:, 0, 0] = s * inv_m[:, 0]
        A[:, 1, 1] = s * inv_m[:, 1]
        A[:, 0, 1] = A[:, 1, 0] = -s * d[:, 0] * d[:, 1]
    else:
        A[:, i, i] = (c + np.roll(c, 1, axis=1)) * inv_m
        off = -c * d * d[:, j]
        A[:, i, j] = off
        A[:, j, i] = off
    lam = np.linalg.eigvalsh(A)
    # one rigid-body mode per connected group of masses (max(1, slack branches)); only
    # those are set to 0, a small genuine eigenvalue is kept
    n_rigid = np.maximum((c <= 0.0).sum(axis=1), 1)
    lam[np.arange(n)[None, :] < n_rigid[:, None]] = 0.0
    return np.asarray(np.sqrt(np.maximum(lam, 0.0)) / TWO_PI, dtype=np.float64)


@dataclass(frozen=True, slots=True, eq=False)
class RingModel:
    """Reduced masses on a closed chain contour ([MultimassChainDrives, §3.1]).

    A stiffness of 0 (a slack span) opens the ring.

    Parameters
    ----------
    masses_kg : ndarray
        (n,) reduced masses m_i = J_i / R_i² [kg], all > 0.
    stiffness_n_per_m : ndarray
        (n,) branch stiffnesses c_i [N/m] ≥ 0; branch i joins mass i and i+1.
    closed : bool
        True: the last branch joins mass n and mass 1; False: an open chain.
    damping_ratio : float
        ζ for the damped frequencies [-] ([MultimassChainDrives]: D = 0.06).
    names : tuple of str
        Labels of the masses (empty, or one per mass).

    Raises
    ------
    DesignError
        A mass that is not positive, a negative stiffness, ζ out of range or a wrong number of
        names.
    """

    masses_kg: NDArray[np.float64]
    stiffness_n_per_m: NDArray[np.float64]
    closed: bool = True
    damping_ratio: float = 0.0
    names: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        m = np.array(self.masses_kg, dtype=float)
        c = np.array(self.stiffness_n_per_m, dtype=float)
        _validate(m, c)
        _check_damping(self.damping_ratio)
        m.flags.writeable = False
        c.flags.writeable = False
        object.__setattr__(self, "masses_kg", m)
        object.__setattr__(self, "stiffness_n_per_m", c)
        object.__setattr__(self, "names", tuple(self.names))
        if self.names and len(self.names) != m.size:
            raise DesignError("names", f"need {m.size} names, got {len(self.names)}")

    @property
    def size(self) -> int:
        """Number of masses n."""
        return int(self.masses_kg.size)

    def stiffness_matrix(self) -> NDArray[np.float64]:
        """K [N/m], the ring Laplacian (see :func:`ring_stiffness_matrix`)."""
        return ring_stiffness_matrix(self.stiffness_n_per_m, self.closed)

    def mass_matrix(self) -> NDArray[np.float64]:
        """M [kg], diagonal."""
        return np.diag(self.masses_kg)

    def modal(self) -> Modes:
        """Natural frequencies and forms; see :func:`modal_analysis`."""
        c = self.stiffness_n_per_m
        if not self.closed:
            c = c.copy()
            c[-1] = 0.0
        return _modal(self.masses_kg, c, self.damping_ratio)  # read-only arrays: shared

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the model."""
        return {"names": list(self.names),
                "reduced_masses_kg": self.masses_kg.tolist(),
                "branch_stiffness_n_per_m": self.stiffness_n_per_m.tolist(),
                "closed": self.closed, "damping_ratio": self.damping_ratio}
