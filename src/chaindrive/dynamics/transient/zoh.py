"""Exact zero-order-hold discretisation of a linear second-order system, with a NumPy matrix
exponential (no SciPy on the command line's path: importing ``scipy.linalg`` costs about
0.3 s, docs/performance.md).

For M q̈ + C q̇ + K q = f held constant over a step Δt, with y = (q, q̇), ẏ = A y + E f::

    expm([[A, E], [0, 0]] Δt) = [[Φ, Γ], [0, I]],     y_{k+1} = Φ y_k + Γ f_k

[VanLoan1978]. The exponential is Padé(13) with scaling and squaring [Higham2005].
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["expm", "zoh_matrices"]

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
    A = A / 2.0**s
    b = _B13
    eye = np.eye(n)
    A2 = A @ A
    A4 = A2 @ A2
    A6 = A4 @ A2
    U = A @ (A6 @ (b[13] * A6 + b[11] * A4 + b[9] * A2)
             + b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * eye)
    V = A6 @ (b[12] * A6 + b[10] * A4 + b[8] * A2) + b[6] * A6 + b[4] * A4 + b[2] * A2 \
        + b[0] * eye
    R = np.linalg.solve(V - U, V + U)
    for _ in range(s):
        R = R @ R
    return np.asarray(R, dtype=np.float64)


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
    S = np.zeros((3 * n, 3 * n))
    S[:n, n:2 * n] = np.diag(s)
    S[n:2 * n, :n] = -(Minv @ stiffness) / s[:, None]
    S[n:2 * n, n:2 * n] = -(Minv @ damping) * (s[None, :] / s[:, None])
    S[n:2 * n, 2 * n:] = Minv / s[:, None] / g[None, :]
    E = expm(S * dt)
    d = np.concatenate([np.ones(n), s])
    Phi = E[:2 * n, :2 * n] * d[:, None] / d[None, :]
    Gam = E[:2 * n, 2 * n:] * d[:, None] * g[None, :]
    return Phi, Gam
