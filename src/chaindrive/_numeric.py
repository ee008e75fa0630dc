"""Small array helpers shared by the vectorised formula modules (internal)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError

FloatOrArray = float | NDArray[np.float64]


def float_or_array(value: ArrayLike) -> FloatOrArray:
    """A Python float for a 0-d result, else a float64 array."""
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def teeth_array(teeth: ArrayLike) -> NDArray[np.float64]:
    """Tooth counts as floats, refusing anything below 3 or not finite."""
    z = np.asarray(teeth, dtype=float)
    if np.any(~np.isfinite(z)) or np.any(z < 3):
        raise DesignError("teeth", f"must be a whole number of at least 3, got {teeth!r}")
    return z


def _exp_steps(s: NDArray[np.complex128], dt: float, count: int) -> NDArray[np.complex128]:
    """e^{s_j kΔt} for k < count, (count, J): with k = uC + v (C ≈ √count) as the product
    e^{s uCΔt}·e^{s vΔt} of two sets of about √count direct exponentials each."""
    C = math.isqrt(max(count - 1, 0)) + 1
    U = -(-count // C)
    coarse = np.exp(np.multiply.outer((C * dt) * np.arange(U), s))[:, None, :]
    fine = np.exp(np.multiply.outer(dt * np.arange(C), s))[None, :, :]
    return (coarse * fine).reshape(U * C, s.size)[:count]


def exp_poly_on_grid(t0: float, dt: float, count: int, exponents: ArrayLike,
                     coef: ArrayLike, poly: ArrayLike, block: int = 512
                     ) -> NDArray[np.float64]:
    """y_r(t_k) = Re Σ_j coef[r, j]·e^{s_j t_k} + Σ_p poly[r, p]·t_k^p on t_k = t₀ + kΔt.

    exponents s (J,) complex; coef (R, J) complex; poly (R, P) real (P may be 0); returns
    (count, R). Linear responses from rest are sums of this form (modal step and ramp
    responses, Rao §4.5), and on an equally spaced grid they separate: with t = t_a + τ_b,
    t_a = t₀ + aBΔt, τ_b = bΔt (b < B),

        e^{s t} = e^{s t_a}·e^{s τ_b},   t^p = Σ_q C(p, q) t_a^{p−q} τ_b^q,

    so block a of the result is one real matrix product W·M_a, W = [Re e^{sτ}, Im e^{sτ},
    τ^q] (B × (2J + P), the same for every block) and M_a the block's coefficients
    [Re(coef·e^{s t_a}), −Im(coef·e^{s t_a}), poly shifted to t_a]ᵀ. The blocks go to BLAS
    as one stacked product: no (J, count) temporaries, J·count/B exponentials instead of
    J·count. Each factor is exact to round-off (e^{s t_a} and e^{s τ} are evaluated
    directly, never as powers), so is the result.
    """
    s = np.asarray(exponents, dtype=complex)
    a_coef = np.asarray(coef, dtype=complex)
    p_coef = np.asarray(poly, dtype=float)
    R, P = p_coef.shape
    nb = max(1, -(-count // block))
    B = -(-count // nb)  # blocks of equal length, at most nb − 1 samples spare
    tau = dt * np.arange(B)
    e_fine = _exp_steps(s, dt, B)
    W = np.concatenate([e_fine.real, e_fine.imag, tau[:, None] ** np.arange(P)], axis=1)
    ta = t0 + (B * dt) * np.arange(nb)
    Q = np.exp(np.multiply.outer(ta, s))[:, None, :] * a_coef  # (nb, R, J)
    M = np.empty((nb, W.shape[1], R))
    J = s.size
    M[:, :J, :] = Q.real.transpose(0, 2, 1)
    M[:, J:2 * J, :] = -Q.imag.transpose(0, 2, 1)
    if P:
        # shifted polynomial: coefficient of τ^q is Σ_{p≥q} poly_p C(p, q) t_a^{p−q}
        p_idx = np.arange(P)
        binom = np.array([[math.comb(p, q) for q in range(P)] for p in range(P)], float)
        powers = np.where(p_idx[:, None] >= p_idx[None, :],
                          ta[:, None, None] ** np.maximum(p_idx[:, None] - p_idx[None, :], 0),
                          0.0) * binom  # (nb, p, q)
        M[:, 2 * J:, :] = np.matmul(powers.transpose(0, 2, 1), p_coef.T)
    out = np.matmul(W, M)  # (nb, B, R)
    return out.reshape(nb * B, R)[:count]


def exp_poly_at(times: ArrayLike, exponents: ArrayLike, coef: ArrayLike, poly: ArrayLike
                ) -> NDArray[np.float64]:
    """:func:`exp_poly_on_grid` at any times (T,): the block products on an equally spaced
    grid, else the direct sum (T exponentials per exponent)."""
    t = np.asarray(times, dtype=float)
    T = t.size
    if T >= 16:
        dt = (t[-1] - t[0]) / (T - 1)
        if dt > 0 and np.allclose(np.diff(t), dt, rtol=1e-9, atol=0.0):
            return exp_poly_on_grid(float(t[0]), dt, T, exponents, coef, poly)
    s = np.asarray(exponents, dtype=complex)
    p_coef = np.asarray(poly, dtype=float)
    out = (np.exp(np.multiply.outer(t, s)) @ np.asarray(coef, dtype=complex).T).real
    if p_coef.shape[1]:
        out += (t[:, None] ** np.arange(p_coef.shape[1])) @ p_coef.T
    return out
