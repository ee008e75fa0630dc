r"""Closed-form start-up of a linear ring (no slack, forces known in advance).

:func:`linear_transient` is the closed-form modal solution for a linear ring under forces
known in advance (no slack, no speed-dependent law): mode j is a damped oscillator with
ζ_j = βω_j/2 (classical damping, [Rao2011, §6.13]); a constant force (step) or a soft-start ramp
gives closed-form modal step / ramp responses ([Rao2011, §4.5]) evaluated on the whole time grid at
once (modes × times, "don't integrate what has a closed form"); sampled forces held over
each step are propagated by the exact zero-order-hold recursion of each mode in its
eigen-coordinates (a first-order complex scan per mode).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.ring import modal_analysis

__all__ = ["LinearTransient", "exp_poly_at", "exp_poly_on_grid", "linear_transient"]


def _exp_steps(s: NDArray[np.complex128], dt: float, count: int) -> NDArray[np.complex128]:
    """e^{s_j kΔt} for k < count, (count, J): with k = uC + v (C ≈ √count) as the product
    e^{s uCΔt}·e^{s vΔt} of two sets of about √count direct exponentials each."""
    C = math.isqrt(max(count - 1, 0)) + 1
    U = -(-count // C)
    coarse = np.exp(np.multiply.outer((C * dt) * np.arange(U), s))[:, None, :]
    fine = np.exp(np.multiply.outer(dt * np.arange(C), s))[None, :, :]
    return np.asarray((coarse * fine).reshape(U * C, s.size)[:count], dtype=np.complex128)


def exp_poly_on_grid(t0: float, dt: float, count: int, exponents: ArrayLike,
                     coef: ArrayLike, poly: ArrayLike, block: int = 512
                     ) -> NDArray[np.float64]:
    """y_r(t_k) = Re Σ_j coef[r, j]·e^{s_j t_k} + Σ_p poly[r, p]·t_k^p on t_k = t₀ + kΔt.

    Linear responses from rest are sums of this form (modal step and ramp responses), and on
    an equally spaced grid they separate: with t = t_a + τ_b, t_a = t₀ + aBΔt, τ_b = bΔt
    (b < B),

        e^{s t} = e^{s t_a}·e^{s τ_b},   t^p = Σ_q C(p, q) t_a^{p−q} τ_b^q,

    so block a of the result is one real matrix product W·M_a, W = [Re e^{sτ}, Im e^{sτ},
    τ^q] (B × (2J + P), the same for every block) and M_a the block's coefficients
    [Re(coef·e^{s t_a}), −Im(coef·e^{s t_a}), poly shifted to t_a]ᵀ. The blocks go to BLAS
    as one stacked product: no (J, count) temporaries, J·count/B exponentials instead of
    J·count. Each factor is exact to round-off (e^{s t_a} and e^{s τ} are evaluated
    directly, never as powers), so is the result.

    Parameters
    ----------
    t0 : float
        First time t₀ [s].
    dt : float
        Step Δt [s].
    count : int
        Number of samples [-].
    exponents : array_like
        (J,) complex exponents s_j [1/s].
    coef : array_like
        (R, J) complex coefficients [unit of y].
    poly : array_like
        (R, P) real polynomial coefficients [unit of y / s^p] (P may be 0).
    block : int
        Samples per block B at most [-].

    Returns
    -------
    ndarray
        (count, R) y [unit of y].

    References
    ----------
    [Rao2011, §4.5] (modal step and ramp responses).
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
    return np.asarray(out.reshape(nb * B, R)[:count], dtype=np.float64)


def exp_poly_at(times: ArrayLike, exponents: ArrayLike, coef: ArrayLike, poly: ArrayLike
                ) -> NDArray[np.float64]:
    """:func:`exp_poly_on_grid` at any times: the block products on an equally spaced grid,
    else the direct sum (T exponentials per exponent).

    Parameters
    ----------
    times : array_like
        (T,) times t [s].
    exponents : array_like
        (J,) complex exponents s_j [1/s].
    coef : array_like
        (R, J) complex coefficients [unit of y].
    poly : array_like
        (R, P) real polynomial coefficients [unit of y / s^p].

    Returns
    -------
    ndarray
        (T, R) y [unit of y].
    """
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
    return np.asarray(out, dtype=np.float64)


@dataclass(frozen=True, eq=False)
class LinearTransient:
    """Response of a linear ring: what a start-up check reads, computed at once, and the
    displacements, evaluated on first access.

    Parameters
    ----------
    times : ndarray
        (N,) times [s].
    velocities : ndarray
        (N, n) velocities of the masses [m/s].
    span_forces : ndarray
        (N, n) span forces [N] (elastic + damping, no slack rule).
    displacements_source : callable
        Returns the (N, n) displacements [m] when :attr:`displacements` is first read.
    """

    times: NDArray[np.float64]
    velocities: NDArray[np.float64]
    span_forces: NDArray[np.float64]
    displacements_source: Callable[[], NDArray[np.float64]] = field(repr=False)

    @cached_property
    def displacements(self) -> NDArray[np.float64]:
        """x (N, n) [m]."""
        return self.displacements_source()


def mode_roots(omega: NDArray[np.float64], zeta: NDArray[np.float64]
                ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Roots s₁,₂ = ω(−ζ ± sqrt(ζ² − 1)) of s² + 2ζωs + ω² (ζ = 1 nudged)."""
    z = np.where(np.abs(zeta - 1.0) < 1e-6, 1.0 + 1e-6, zeta)
    r = np.sqrt((z * z - 1.0).astype(complex))
    return omega * (-z + r), omega * (-z - r)


@dataclass(frozen=True, slots=True)
class _ModalSeries:
    """Modal responses S_j(t), V_j(t) written as exponential-polynomial sums:

        S_j(t) = Re Σ_k [mode_k = j]·κS_k e^{s_k t} + Σ_p PS[j, p] t^p   (V likewise),

    the form :func:`chaindrive._numeric.exp_poly_on_grid` evaluates."""

    exponents: NDArray[np.complex128]  # s_k (K,)
    mode: NDArray[np.intp]  # mode index j of term k (K,)
    kS: NDArray[np.complex128]  # (K,)
    kV: NDArray[np.complex128]  # (K,)
    pS: NDArray[np.float64]  # (modes, P)
    pV: NDArray[np.float64]  # (modes, P)


def _step_series(omega: NDArray[np.float64], zeta: NDArray[np.float64]) -> _ModalSeries:
    """Unit-step response S(t) of q̈ + 2ζωq̇ + ω²q = 1 and Ṡ, from rest (Rao §4.5).

    S = (1 − (s₂e^{s₁t} − s₁e^{s₂t})/(s₂ − s₁))/ω², Ṡ = (e^{s₁t} − e^{s₂t})/(s₁ − s₂),
    s₁,₂ = ω(−ζ ± sqrt(ζ² − 1)). For ζ < 1 (s₂ = s̄₁ = −ζω − iω_d) one complex term:
    S = 1/ω² + Re(e^{s₁t}(−1 + iζω/ω_d))/ω², Ṡ = Re(e^{s₁t}(−i/ω_d)); for ζ ≥ 1 two real
    ones; a rigid mode (ω = 0): S = t²/2, Ṡ = t.
    """
    m = omega.size
    rigid = omega <= 0
    w = np.where(rigid, 1.0, omega)
    s1, s2 = mode_roots(w, zeta)
    under = (zeta < 1.0) & ~rigid
    over = ~under & ~rigid
    ju, jo = np.flatnonzero(under), np.flatnonzero(over)
    wu, wo = w[ju], w[jo]
    wd = s1[ju].imag
    a, b = s1[jo].real, s2[jo].real
    exps = np.concatenate([s1[ju], a, b]).astype(complex)
    mode = np.concatenate([ju, jo, jo])
    kS = np.concatenate([(-1.0 + 1j * zeta[ju] * wu / wd) / wu**2,
                         -b / ((b - a) * wo**2), a / ((b - a) * wo**2)]).astype(complex)
    kV = np.concatenate([-1j / wd, 1.0 / (a - b), -1.0 / (a - b)]).astype(complex)
    pS, pV = np.zeros((m, 4)), np.zeros((m, 4))
    pS[~rigid, 0] = 1.0 / w[~rigid] ** 2
    pS[rigid, 2] = 0.5
    pV[rigid, 1] = 1.0
    return _ModalSeries(exps, mode, kS, kV, pS, pV)


def _ramp_series(step: _ModalSeries) -> _ModalSeries:
    """Unit-ramp response (input u = t): ∫₀ᵗS and S. Term by term, ∫₀ᵗ Re(κe^{sτ})dτ =
    Re((κ/s)e^{st}) − Re(κ/s) and ∫₀ᵗ τ^p dτ = t^{p+1}/(p + 1)."""
    k = step.kS / step.exponents
    pS = np.zeros_like(step.pS)
    pS[:, 1:] = step.pS[:, :-1] / np.arange(1, step.pS.shape[1])
    np.subtract.at(pS[:, 0], step.mode, k.real)
    return _ModalSeries(step.exponents, step.mode, k, step.kS, pS, step.pS)


def _physical_series(series: _ModalSeries, Xp: NDArray[np.float64], c: NDArray[np.float64],
                     beta: float) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """Coefficients (3n, K) and polynomial (3n, P) of v = Xp·V, the span forces
    F_i = c_i (y_{i+1} − y_i), y = x + βv (branch i joins mass i and i+1, the last mass n−1
    and mass 0; a slack branch has c_i = 0) and x = Xp·S, in this order of rows."""
    G = c[:, None] * (np.roll(Xp, -1, axis=0) - Xp)
    cols = series.mode
    coef = np.concatenate([Xp[:, cols] * series.kV, G[:, cols] * (series.kS + beta * series.kV),
                           Xp[:, cols] * series.kS])
    poly = np.concatenate([Xp @ series.pV, G @ (series.pS + beta * series.pV), Xp @ series.pS])
    return coef, poly


def _zoh_modal(P: NDArray[np.float64], omega: NDArray[np.float64], zeta: NDArray[np.float64],
               dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact zero-order-hold response from rest of the modal oscillators to the sampled
    modal forces P (modes, N) held over each step: q, q̇ (modes, N) at the samples.

    With the eigenvalues s₁,₂ of mode j the state is (q, q̇) = w₁(1, s₁) + w₂(1, s₂),
    ẇ₁ = s₁w₁ + u/(s₁ − s₂), ẇ₂ = s₂w₂ − u/(s₁ − s₂), so each w is a scalar first-order
    recursion w_{k+1} = e^{sΔt}w_k + (e^{sΔt} − 1)/s·(±u_k/(s₁ − s₂)) — exact for a held
    force (Van Loan 1978), run by ``scipy.signal.lfilter`` (a C scan, O(N) per mode); for
    ζ < 1, w₂ = w̄₁. Rigid modes: q̇_k = Δt Σ_{j<k} u_j, q_{k+1} = q_k + Δt q̇_k + Δt²u_k/2.
    """
    q = np.zeros_like(P)
    qd = np.zeros_like(P)
    rigid = omega <= 0
    s1, s2 = mode_roots(np.where(rigid, 1.0, omega), zeta)
    for j in np.flatnonzero(~rigid):
        roots = (s1[j],) if zeta[j] < 1.0 else (s1[j], s2[j])
        for s, sign in zip(roots, (1.0, -1.0), strict=False):
            lam = np.exp(s * dt)
            g = (lam - 1.0) / s * sign / (s1[j] - s2[j])
            wj = _lfilter([0.0, g], [1.0, -lam], P[j].astype(complex))
            k = 2.0 if zeta[j] < 1.0 else 1.0
            q[j] += k * wj.real
            qd[j] += k * (s * wj).real
    for j in np.flatnonzero(rigid):
        qd[j, 1:] = dt * np.cumsum(P[j, :-1])
        q[j, 1:] = np.cumsum(dt * qd[j, :-1] + 0.5 * dt * dt * P[j, :-1])
    return q, qd


def linear_transient(masses: ArrayLike, stiffness: ArrayLike, beta: float, times: ArrayLike,
                     forces: ArrayLike, closed: bool = True,
                     ramp_time: float = 0.0) -> LinearTransient:
    """Response from rest of the linear ring to nodal forces (module docstring).

    A constant force vector is a step at t = 0 (or, with ``ramp_time`` t_r > 0, a ramp
    f·min(t/t_r, 1), the soft start) solved in closed form: modal step/ramp responses on the
    whole grid at once. Sampled forces (N, n) are held constant over each step (exact
    zero-order-hold modal recursion).

    Parameters
    ----------
    masses : array_like
        (n,) reduced masses [kg].
    stiffness : array_like
        (n,) branch stiffnesses [N/m].
    beta : float
        β of the stiffness-proportional damping C = βK [s].
    times : array_like
        (N,) equally spaced times from 0 [s].
    forces : array_like
        (n,) constant or (N, n) sampled nodal forces [N].
    closed : bool
        False for an open chain (the last branch is ignored).
    ramp_time : float
        Duration t_r of the ramp of constant forces [s] (0: a step).

    Returns
    -------
    LinearTransient
        Times, velocities, span forces and (lazily) displacements.

    References
    ----------
    [Rao2011, §6.13] (classical damping, decoupled modes), [Rao2011, §4.5] (step and ramp
    responses); [VanLoan1978] (the exact zero-order hold).
    """

    m = np.asarray(masses, dtype=float)
    c = np.array(stiffness, dtype=float)
    if not closed:
        c[-1] = 0.0
    t = np.asarray(times, dtype=float)
    f = np.asarray(forces, dtype=float)
    modal = modal_analysis(m, c)
    X, w = modal.shapes, modal.angular_frequencies_rad_s
    zeta = 0.5 * beta * w
    n = m.size
    if f.ndim == 1:
        Xp = X * (X.T @ f)
        series = _step_series(w, zeta)
        if ramp_time > 0:
            series = _ramp_series(series)
        coef, poly = _physical_series(series, Xp, c, beta)  # rows: v, F, x

        def response(rows: slice) -> NDArray[np.float64]:
            out = exp_poly_at(t, series.exponents, coef[rows], poly[rows])
            if ramp_time > 0:  # f·min(t/t_r, 1) = f(R(t) − R(t − t_r)·H(t − t_r))/t_r
                late = t > ramp_time
                out[late] -= exp_poly_at(t[late] - ramp_time, series.exponents, coef[rows],
                                         poly[rows])
                out /= ramp_time
            return out

        vF = response(slice(0, 2 * n))
        return LinearTransient(t, vF[:, :n], vF[:, n:], lambda: response(slice(2 * n, 3 * n)))
    S, V = _zoh_modal((f @ X).T, w, zeta, t[1] - t[0])
    x, v, F = _physical(X, c, beta, S, V)
    return LinearTransient(t, v, F, lambda: x)


def _physical(Xp: NDArray[np.float64], c: NDArray[np.float64], beta: float,
              S: NDArray[np.float64], V: NDArray[np.float64], block: int = 512
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """x = Xp S, v = Xp V and the span forces F_i = c_i (e_i + β ė_i), e_i = x_{i+1} − x_i
    (a slack branch has c_i = 0), returned (T, n). The products are taken in blocks of
    ``block`` times: OpenBLAS runs a 24×24×10⁴ product multi-threaded, which was measured
    30× slower on a loaded 2-core machine; blocks stay single-threaded and in cache. The
    forces come from x and v by differences (O(nT)), not by a third product (O(n²T))."""
    n, T = Xp.shape[0], S.shape[1]
    xs, vs = np.empty((n, T)), np.empty((n, T))
    for k in range(0, T, block):
        np.matmul(Xp, S[:, k:k + block], out=xs[:, k:k + block])
        np.matmul(Xp, V[:, k:k + block], out=vs[:, k:k + block])
    y = np.multiply(vs, beta)
    y += xs
    F = np.empty_like(y)  # F_i = c_i (y_{i+1} − y_i), the last joins mass n−1 to mass 0
    np.subtract(y[1:], y[:-1], out=F[:-1])
    np.subtract(y[:1], y[-1:], out=F[-1:])
    F *= c[:, None]
    return xs.T, vs.T, F.T


def _lfilter(b: list[float], a: list[float], x: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """scipy.signal.lfilter, imported on first use (scipy.signal takes about 1 s to import,
    which the command line should not pay when it does not need it)."""
    from scipy.signal import lfilter

    return lfilter(b, a, x)
