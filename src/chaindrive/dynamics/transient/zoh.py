"""Exact zero-order-hold discretisation of a linear second-order system, with a NumPy matrix
exponential (no SciPy on the command line's path: importing ``scipy.linalg`` costs about
0.3 s, docs/performance.md).

For M q̈ + C q̇ + K q = f held constant over a step Δt, with y = (q, q̇), ẏ = A y + E f::

    expm([[A, E], [0, 0]] Δt) = [[Φ, Γ], [0, I]],     y_{k+1} = Φ y_k + Γ f_k

[VanLoan1978]. The exponential is Padé(13) with scaling and squaring [Higham2005], carried
out on the blocks of [[A, E], [0, 0]] (:func:`expm_input`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["expm", "expm_input", "zoh_matrices"]

FloatArray = NDArray[np.float64]

# Padé(13) coefficients b_0 … b_13 [Higham2005, Alg. 2.3]
_B13 = (64764752532480000.0, 32382376266240000.0, 7771770303897600.0, 1187353796428800.0,
        129060195264000.0, 10559470521600.0, 670442572800.0, 33522128640.0, 1323241920.0,
        40840800.0, 960960.0, 16380.0, 182.0, 1.0)
#: θ₁₃: the largest 1-norm for which Padé(13) is accurate to double precision
#: [Higham2005, Table 2.3].
_THETA13 = 5.371920351148152


def expm(A: FloatArray) -> FloatArray:
    """Matrix exponential e^A of a square real matrix.

    Parameters
    ----------
    A : ndarray
        (n, n) matrix [-] (a state matrix times a time step).

    Returns
    -------
    ndarray
        (n, n) e^A.

    References
    ----------
    [Higham2005]: Padé(13) approximant with scaling and squaring (the degree-13 branch of
    its Algorithm 2.3, used at every norm: a little more work for small norms, the same
    accuracy).
    """
    A = np.asarray(A, dtype=float)
    n = A.shape[0]
    norm = float(np.abs(A).sum(axis=0).max()) if n else 0.0
    s = max(0, math.ceil(math.log2(norm / _THETA13))) if norm > _THETA13 else 0
    U, V = _padé13_parts(A / 2.0**s)
    R = np.linalg.solve(V - U, V + U)
    for _ in range(s):
        R = R @ R
    return np.asarray(R, dtype=np.float64)


def _padé13_parts(Z: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(U, V) of the Padé(13) approximant of e^Z: e^Z ≈ (V − U)⁻¹(V + U) [Higham2005,
    Alg. 2.3]."""
    b = _B13
    eye = np.eye(Z.shape[0])
    Z2 = Z @ Z
    Z4 = Z2 @ Z2
    Z6 = Z4 @ Z2
    U = Z @ (Z6 @ (b[13] * Z6 + b[11] * Z4 + b[9] * Z2)
             + b[7] * Z6 + b[5] * Z4 + b[3] * Z2 + b[1] * eye)
    V = Z6 @ (b[12] * Z6 + b[10] * Z4 + b[8] * Z2) + b[6] * Z6 + b[4] * Z4 + b[2] * Z2 \
        + b[0] * eye
    return U, V


def expm_input(A: FloatArray, E: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(Φ, Γ) of expm([[A, E], [0, 0]]) = [[Φ, Γ], [0, I]] without forming the block matrix.

    The powers of Z = [[A, E], [0, 0]] keep its shape, Z^k = [[A^k, A^{k−1}E], [0, 0]], and
    so does every polynomial in Z, [[X, Y], [0, x I]]; the Padé(13) approximant with scaling
    and squaring of :func:`expm` (the same degree, the same scaling s from the 1-norm of Z)
    is carried out on the blocks (X, Y, x): a product costs n²(n + m) instead of (n + m)³
    (2.2× less for m = n/2, the zero-order hold of a second-order model), the solve
    (V − U)⁻¹(V + U) is one n × n solve with n + m right-hand sides.

    Parameters
    ----------
    A : ndarray
        (n, n) state matrix times the step [-].
    E : ndarray
        (n, m) input matrix times the step [-].

    Returns
    -------
    tuple of ndarray
        Φ = e^A (n, n) and Γ = ∫₀¹ e^{A(1−τ)} dτ E (n, m).

    References
    ----------
    [VanLoan1978] (the block exponential); [Higham2005] (Padé(13), scaling and squaring).
    """
    A, E = np.asarray(A, dtype=float), np.asarray(E, dtype=float)
    n = A.shape[0]
    norm = float(max(np.abs(A).sum(axis=0).max(), np.abs(E).sum(axis=0).max())) if n else 0.0
    s = max(0, math.ceil(math.log2(norm / _THETA13))) if norm > _THETA13 else 0
    A, E = A / 2.0**s, E / 2.0**s
    b = _B13
    eye = np.eye(n)
    # the powers Z², Z⁴, Z⁶ as (A^k, A^{k−1}E)
    A2, E2 = A @ A, A @ E
    A4, E4 = A2 @ A2, A2 @ E2
    A6, E6 = A4 @ A2, A4 @ E2
    # inner polynomials (lower-right blocks 0: no identity term)
    P1 = b[13] * A6 + b[11] * A4 + b[9] * A2
    Q1 = b[13] * E6 + b[11] * E4 + b[9] * E2
    P2 = b[12] * A6 + b[10] * A4 + b[8] * A2
    # U = Z (Z⁶ P1 + b7 Z⁶ + b5 Z⁴ + b3 Z² + b1 I): the bracket is (X, Y, b1)
    X = A6 @ P1 + b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * eye
    Y = A6 @ Q1 + b[7] * E6 + b[5] * E4 + b[3] * E2
    UA, UE = A @ X, A @ Y + b[1] * E  # Z (X, Y, b1) = (A X, A Y + b1 E, 0)
    VA = A6 @ P2 + b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * eye
    # R = (V − U)⁻¹(V + U) with V − U = (VA − UA, VE − UE, b0), V + U = (VA + UA, VE + UE,
    # b0): R = (X⁻¹(VA + UA), X⁻¹((VE + UE) − (VE − UE)), 1), X = VA − UA; V's upper-right
    # block VE cancels and is not formed
    sol = np.linalg.solve(VA - UA, np.hstack([VA + UA, 2.0 * UE]))
    Phi, Gam = sol[:, :n], sol[:, n:]
    for _ in range(s):  # (Φ, Γ, 1)² = (Φ², ΦΓ + Γ, 1)
        Phi, Gam = Phi @ Phi, Phi @ Gam + Gam
    return np.asarray(Phi, dtype=np.float64), np.asarray(Gam, dtype=np.float64)


def zoh_matrices(mass: FloatArray, stiffness: FloatArray, damping: FloatArray,
                 dt: float) -> tuple[FloatArray, FloatArray]:
    """(Φ, Γ) of M q̈ + C q̇ + K q = f over a step Δt with f held (module docstring).

    Parameters
    ----------
    mass : ndarray
        (N, N) M, symmetric positive definite [kg·m² or kg].
    stiffness : ndarray
        (N, N) K [N·m/rad or N/m].
    damping : ndarray
        (N, N) C [N·m·s/rad or N·s/m].
    dt : float
        Δt [s].

    Returns
    -------
    tuple of ndarray
        Φ (2N, 2N) [-] and Γ (2N, N) [s²/kg-like units]: y_{k+1} = Φ y_k + Γ f.

    References
    ----------
    [VanLoan1978]; [Higham2005].
    """
    n = mass.shape[0]
    Minv = np.linalg.inv(mass)
    # balanced state (q, q̇/s), s_i the partial frequency √(K_ii/M_ii) (1/Δt where there is
    # none): the state matrix of a stiff oscillator is far from normal, and scaling and
    # squaring loses accuracy on it without this similarity transform (balancing)
    kd, md = np.abs(np.diag(stiffness)), np.abs(np.diag(mass))
    s = np.sqrt(np.divide(kd, md, out=np.full(n, 0.0), where=md > 0))
    s = np.where(s * dt > 1.0, s, 1.0 / dt)
    g = s * np.abs(np.diag(Minv))  # input scale: the held force gives about unit rates
    S = np.zeros((2 * n, 3 * n))
    S[:n, n:2 * n] = np.diag(s)
    S[n:2 * n, :n] = -(Minv @ stiffness) / s[:, None]
    S[n:2 * n, n:2 * n] = -(Minv @ damping) * (s[None, :] / s[:, None])
    S[n:2 * n, 2 * n:] = Minv / s[:, None] / g[None, :]
    S *= dt
    Phi, Gam = expm_input(S[:, :2 * n], S[:, 2 * n:])
    d = np.concatenate([np.ones(n), s])
    return Phi * d[:, None] / d[None, :], Gam * d[:, None] * g[None, :]
