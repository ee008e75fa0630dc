r"""Compiled time-stepping kernel of the nonlinear start-up (:mod:`chaindrive.dynamics.transient.startup`).

The same step as the NumPy loop of :func:`chaindrive.dynamics.transient.startup.run_startup`, for a
model M q̈ + C q̇ + K q = Q of any coordinates q (the whole drive, or the ring as a special
case): exact zero-order-hold transition Φ_s, Γ_s per slack pattern s [VanLoan1978];
explicit pre-tension and polygonal span forces −Bᵀ(...) extrapolated to mid-step; the motor
and load laws acting on the mean speed of their own coordinate over the step, linearly
implicit and coupled through the step's response (one small linear solve over the law
coordinates; the stability argument is in :mod:`chaindrive.dynamics.transient.startup`); a
step that changes the slack pattern redone once with the new pattern. Written on plain arrays so that numba
compiles it (``@njit(cache=True)``), the step in one loop (:func:`run_kernel_flat` says why).

Laws are codes and parameter arrays (:mod:`chaindrive.dynamics.transient.kernel_codes`): the motor acts
on coordinate ``mk`` with gain g and efficiency η (torque g·η·T(t, g q̇)); every load l on
coordinate lk[l] (moment −g_l M_l φ(g_l q̇/ω_n,l)/η_l, φ by its kind). The span forces are
F = T₀ + c (B q + d) + d_s (B q̇ + ḋ) with the polygonal elongations d at the span ends
(tooth phase from the chain travel x = g_p q of the sprocket at each end).

The Φ_s, Γ_s of the slack patterns met so far are stacked in arrays. When a step meets a
pattern not yet in the stack the kernel returns the step index and the pattern; the caller
adds Φ_s, Γ_s and calls the kernel again from that step (the state is left untouched, so the
result does not depend on the interruption). The state (q, q̇) and the span forces are kept
every ``rec`` steps; the largest force of every span is tracked at every step.

numba is optional: :data:`HAVE_NUMBA` is False when it is not importable and the caller
falls back to the NumPy loop. :func:`run_kernel_flat` is the entry point, with plain arguments,
that :mod:`chaindrive.dynamics.transient.kernel_build` compiles ahead of time.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, TypeVar, cast

import numpy as np

from chaindrive.dynamics.transient.kernel_codes import (  # the kernel's integer codes
    MOTOR_CONSTANT,
    MOTOR_KLOSS,
    MOTOR_RAMP,
    RESISTANCE_CONSTANT,
    RESISTANCE_LINEAR,
    RESISTANCE_QUADRATIC,
    kloss_end_speed,
)

try:  # numba is optional (project rule: compiled hot loop with a NumPy fallback)
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    numba = None  # type: ignore[assignment]
    HAVE_NUMBA = False

__all__ = ["FLAT_SIGNATURE", "HAVE_NUMBA", "run_kernel_flat"]


_Kernel = TypeVar("_Kernel", bound=Callable[..., Any])


def _njit(fn: _Kernel) -> _Kernel:
    # numba's decorator is untyped; the compiled function keeps the Python signature
    return cast(_Kernel, numba.njit(cache=True, fastmath=False)(fn)) if HAVE_NUMBA else fn


@_njit
def _polygonal(y: Any, d: Any, dd: Any, pz: Any, pR: Any, ps: Any, psign: Any, pidx: Any,
               pgain: Any, pk: float, plin: float, pd0: Any) -> None:
    """Polygonal elongation d and its rate ḋ of every span (exact hinge law, d(0) removed)."""
    ns = d.size
    n = y.size // 2
    for i in range(ns):
        d[i] = 0.0
        dd[i] = 0.0
    for j in range(2 * ns):
        x = pgain[j] * y[pidx[j]]
        v = pgain[j] * y[n + pidx[j]]
        psi = pk * x - 2.0 * math.pi * ps[j]
        psi = np.mod(psi + math.pi, 2.0 * math.pi) - math.pi
        sa = math.sin(psi / pz[j])
        # |ψ/z| ≤ π/3 (|ψ| ≤ π, z ≥ 3): cos(ψ/z) = √(1 − sin²) ≥ 1/2
        ca = math.sqrt(1.0 - sa * sa)
        dl = psign[j] * (pR[j] * sa - plin * psi)
        dv = psign[j] * (pR[j] / pz[j] * ca * pk - 1.0) * v
        d[j % ns] += dl
        dd[j % ns] += dv
    for i in range(ns):
        d[i] -= pd0[i]


@(numba.njit(cache=True, fastmath={"reassoc"}) if HAVE_NUMBA else (lambda f: f))
def _matvec_add(A: Any, y: Any, out: Any) -> None:
    """out += A @ y (sums reassociated so that they run in SIMD lanes; four rows at a time,
    each y[j] loaded once for the four)."""
    m, n = A.shape[0], A.shape[1]
    i = 0
    while i + 4 <= m:
        a0 = 0.0
        a1 = 0.0
        a2 = 0.0
        a3 = 0.0
        for j in range(n):
            yj = y[j]
            a0 += A[i, j] * yj
            a1 += A[i + 1, j] * yj
            a2 += A[i + 2, j] * yj
            a3 += A[i + 3, j] * yj
        out[i] += a0
        out[i + 1] += a1
        out[i + 2] += a2
        out[i + 3] += a3
        i += 4
    while i < m:
        acc = 0.0
        for j in range(n):
            acc += A[i, j] * y[j]
        out[i] += acc
        i += 1


@_njit
def _find(masks: Any, npat: int, mask: Any) -> int:
    """Index of ``mask`` among the first ``npat`` stacked patterns, −1 if absent."""
    for p in range(npat):
        same = True
        for i in range(mask.size):
            if masks[p, i] != mask[i]:
                same = False
                break
        if same:
            return p
    return -1


@_njit
def _sparse_rows(B: Any) -> tuple:
    """(row pointers, columns, values) of the nonzeros of B, row by row (an incidence has a
    few a row)."""
    nnz = 0
    for i in range(B.shape[0]):
        for k in range(B.shape[1]):
            if B[i, k] != 0.0:
                nnz += 1
    ptr = np.zeros(B.shape[0] + 1, dtype=np.int64)
    idx = np.empty(nnz, dtype=np.int64)
    val = np.empty(nnz)
    j = 0
    for i in range(B.shape[0]):
        for k in range(B.shape[1]):
            if B[i, k] != 0.0:
                idx[j] = k
                val[j] = B[i, k]
                j += 1
        ptr[i + 1] = j
    return ptr, idx, val


#: the plain-Python helper compiled for the kernel
_kloss_end_speed = _njit(kloss_end_speed)


@_njit
def _solve_small(A: Any, b: Any) -> None:
    """b ← A⁻¹ b by Gaussian elimination with partial pivoting (A overwritten; a few unknowns)."""
    m = b.size
    for k in range(m):
        piv = k
        big = abs(A[k, k])
        for i in range(k + 1, m):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                piv = i
        if piv != k:
            for j in range(m):
                A[k, j], A[piv, j] = A[piv, j], A[k, j]
            b[k], b[piv] = b[piv], b[k]
        for i in range(k + 1, m):
            r = A[i, k] / A[k, k]
            if r != 0.0:
                for j in range(k + 1, m):
                    A[i, j] -= r * A[k, j]
                b[i] -= r * b[k]
    for k in range(m - 1, -1, -1):
        acc = b[k]
        for j in range(k + 1, m):
            acc -= A[k, j] * b[j]
        b[k] = acc / A[k, k]


@_njit
def run_kernel_flat(y: Any, w: Any, span_prev: Any, state: Any, steps: int, dt: float,
                    rec: int, masks: Any, Phis: Any, G0s: Any, GBs: Any, GLs: Any, npat: int,
                    B: Any, c: Any, ds: Any, tonly: Any, T0: Any, mk: int,
                    mgain: float, meff: float, mkind: int, mp: Any, lk: Any, lgain: Any,
                    leff: Any, lkind: Any, lM: Any, lwn: Any, brk: float, poly: bool, pz: Any,
                    pR: Any, ps: Any, psign: Any, pidx: Any, pgain: Any, pk: float, plin: float,
                    pd0: Any, forces: Any, states: Any, fmax: Any, need: Any, lcols: Any) -> int:
    """Advance from step state[0] to ``steps``; returns the step reached.

    y (2N,) state, w (N,) the mean speeds over the previous step (of the law coordinates
    L = ``lcols``; the others are not read), span_prev (S,) the held
    span forces of the previous step, state = [step, slack count, pattern index, pattern of
    the previous step] (all updated in place); Φ_s, Γ_s(−Bᵀ)T₀ (the pre-tension's part, T₀
    of the spans s holds), Γ_s(−Bᵀ) and Γ_s[:, L] of the patterns stacked in Phis, G0s, GBs,
    GLs (L = ``lcols``, the coordinates of the laws); the spans (incidence B, stiffnesses c,
    dampers ds, which carry tension only, pre-tensions T₀); the motor (mk: its coordinate,
    −1 for none; gain, efficiency, kind and parameters) and the loads (their coordinates lk,
    gains, efficiencies, kinds, moments, nominal speeds, the breakaway); the polygonal law
    (poly … pd0) as in :func:`_polygonal`; forces (R, S) and states (R, 2N) filled at every
    ``rec``-th step, fmax (S,) the largest span forces. Returns < steps when a step needs a
    slack pattern not among the first ``npat``: it is written into ``need`` and nothing of
    that step is kept. One fixed signature (:data:`FLAT_SIGNATURE`) for the ahead-of-time
    build.

    One step, as its parts were once written in helper functions: (a) the held span forces
    s, (3 s_k − s_{k−1})/2 less the pre-tension's part; (b) the laws' forces f(w) at the
    previous mean speeds and their slopes J by a forward difference; (c) y* = Φ y + g₀ +
    Γ(−Bᵀ) s + Γ[:, L] f; (d) the laws' linearly implicit increment (I − diag(J) G) Δf =
    J (w* − w), G = Γ[L, L]/Δt, J clipped to 1/(2 G_ii) where it rises, a Kloss motor
    beyond that by backward Euler (:func:`kloss_end_speed`); (e) the span forces at the new
    state (polygonal law included) and the slack test, the step redone once with a new
    pattern. They are written out in this one loop, and the pattern's arrays taken out of
    their stacks only when the pattern changes: every array a function receives, and every
    view, counts a reference up and down (an atomic operation each), which on a model of 4
    coordinates cost twice the step's arithmetic (measured: 65 % of the run in the counting
    with the parts as inlined helpers).
    """
    ns = c.size
    n = w.size
    m = lcols.size
    nl = lk.size
    bptr, bidx, bval = _sparse_rows(B)
    d, dd = np.zeros(ns), np.zeros(ns)
    d_new, dd_new = np.zeros(ns), np.zeros(ns)
    if poly:
        _polygonal(y, d, dd, pz, pR, ps, psign, pidx, pgain, pk, plin, pd0)
    se = np.empty(ns)
    span = np.empty(ns)
    fl, f2, vh = np.zeros(n), np.zeros(n), np.zeros(n)
    lA = np.empty((m, m))
    lb = np.empty(m)
    y_new = np.empty(2 * n)
    F = np.empty(ns)
    p, pp = state[2], state[3]
    mask, prev = masks[p], masks[pp]
    g0, Phi, GB, GL = G0s[p], Phis[p], GBs[p], GLs[p]
    for k in range(state[0], steps):
        t = k * dt
        th = t + 0.5 * dt
        redo = False
        while True:
            # (a) the held span forces
            for i in range(ns):
                sp = T0[i]
                if poly:
                    sp += c[i] * d[i] + ds[i] * dd[i]
                span[i] = sp if mask[i] else 0.0
            if redo:
                for i in range(ns):
                    se[i] = span[i] - (T0[i] if mask[i] else 0.0)
            else:
                for i in range(ns):
                    # (3 s_k − s_{k−1})/2 less its pre-tension part T₀ (in g₀), the parts of
                    # T₀ in s_k and s_{k−1} taken out first: exactly 0 without polygonal
                    # excitation
                    now = T0[i] if mask[i] else 0.0
                    was = T0[i] if prev[i] else 0.0
                    se[i] = 1.5 * (span[i] - now) - 0.5 * (span_prev[i] - was) \
                        + 0.5 * (now - was)
            # (b) the laws at w (fl) and at w + h (f2)
            for a in range(m):
                i = lcols[a]
                vh[i] = w[i] + 1e-6 * (1.0 + abs(w[i]))
            for j in range(nl):
                fl[lk[j]] = 0.0
                f2[lk[j]] = 0.0
            if mk >= 0:
                fl[mk] = 0.0
                f2[mk] = 0.0
            for j in range(nl):
                r1 = lgain[j] * w[lk[j]] / lwn[j]
                r2 = lgain[j] * vh[lk[j]] / lwn[j]
                if lkind[j] == RESISTANCE_LINEAR:
                    phi1, phi2 = r1, r2
                elif lkind[j] == RESISTANCE_QUADRATIC:
                    phi1, phi2 = r1 * abs(r1), r2 * abs(r2)
                elif lkind[j] == RESISTANCE_CONSTANT:
                    phi1 = min(max(r1 / brk, -1.0), 1.0)
                    phi2 = min(max(r2 / brk, -1.0), 1.0)
                else:
                    phi1, phi2 = 0.0, 0.0
                fl[lk[j]] -= lgain[j] * lM[j] * phi1 / leff[j]
                f2[lk[j]] -= lgain[j] * lM[j] * phi2 / leff[j]
            if mk >= 0:
                if mkind == MOTOR_CONSTANT:
                    tq1 = mp[0]
                    tq2 = mp[0]
                elif mkind == MOTOR_RAMP:
                    tq1 = mp[0] * min(1.0, th / mp[1]) if mp[1] > 0 else mp[0]
                    tq2 = tq1
                else:
                    s1 = 1.0 - mgain * w[mk] / mp[2]
                    tq1 = mp[0] * s1 * mp[1] / (s1 * s1 + mp[1] * mp[1])
                    s2 = 1.0 - mgain * vh[mk] / mp[2]
                    tq2 = mp[0] * s2 * mp[1] / (s2 * s2 + mp[1] * mp[1])
                fl[mk] += mgain * meff * tq1
                f2[mk] += mgain * meff * tq2
            # (c) the explicit step
            for a in range(m):
                lb[a] = fl[lcols[a]]
            for i in range(2 * n):
                y_new[i] = g0[i]
            _matvec_add(Phi, y, y_new)
            for i in range(ns):
                if se[i] != 0.0:
                    _matvec_add(GB, se, y_new)
                    break
            _matvec_add(GL, lb, y_new)
            # (d) the laws' linearly implicit increment
            if m > 0:
                am = -1
                for a in range(m):
                    i = lcols[a]
                    J = (f2[i] - fl[i]) / (1e-6 * (1.0 + abs(w[i])))
                    gii = GL[i, a] / dt
                    if gii > 0.0 and 0.5 / gii < J:
                        J = 0.5 / gii
                        if i == mk and mkind == MOTOR_KLOSS:
                            am = a
                    for b in range(m):
                        lA[a, b] = -J * GL[i, b] / dt
                    lA[a, a] += 1.0
                    lb[a] = J * ((y_new[i] - y[i]) / dt - w[i])
                _solve_small(lA, lb)
                if am >= 0:  # a Kloss motor rising faster than the step: backward Euler
                    wa = (y_new[mk] - y[mk]) / dt
                    for b in range(m):
                        if b != am:
                            wa += GL[mk, b] / dt * lb[b]
                    s1 = 1.0 - mgain * w[mk] / mp[2]
                    fw = mgain * meff * mp[0] * s1 * mp[1] / (s1 * s1 + mp[1] * mp[1])
                    u = _kloss_end_speed(w[mk], wa, fw, GL[mk, am] / dt, mgain, mgain * meff,
                                         mp[0], mp[1], mp[2])
                    s1 = 1.0 - mgain * u / mp[2]
                    lb[am] = mgain * meff * mp[0] * s1 * mp[1] / (s1 * s1 + mp[1] * mp[1]) - fw
                _matvec_add(GL, lb, y_new)
            # (e) the span forces at the new state, before the slack rule
            if poly:
                # _polygonal written out (it gives the initial state): calling it at every
                # step made the two-sprocket analysis's start-up 29.5 → 44 ms
                for i in range(ns):
                    d_new[i] = 0.0
                    dd_new[i] = 0.0
                for j in range(2 * ns):
                    x = pgain[j] * y_new[pidx[j]]
                    v = pgain[j] * y_new[n + pidx[j]]
                    psi = pk * x - 2.0 * math.pi * ps[j]
                    psi = np.mod(psi + math.pi, 2.0 * math.pi) - math.pi
                    sa = math.sin(psi / pz[j])
                    ca = math.sqrt(1.0 - sa * sa)
                    d_new[j % ns] += psign[j] * (pR[j] * sa - plin * psi)
                    dd_new[j % ns] += psign[j] * (pR[j] / pz[j] * ca * pk - 1.0) * v
                for i in range(ns):
                    d_new[i] -= pd0[i]
            for i in range(ns):
                e = 0.0
                ed = 0.0
                for j in range(bptr[i], bptr[i + 1]):
                    e += bval[j] * y_new[bidx[j]]
                    ed += bval[j] * y_new[n + bidx[j]]
                if poly:
                    e += d_new[i]
                    ed += dd_new[i]
                F[i] = T0[i] + c[i] * e + ds[i] * ed
            if redo:
                state[1] += 1
                break
            changed = False
            for i in range(ns):
                need[i] = (F[i] > 0 or not tonly[i]) and c[i] > 0
                changed = changed or need[i] != mask[i]
            if not changed:
                break
            q = _find(masks, npat, need)
            if q < 0:
                state[0], state[2], state[3] = k, p, pp
                return k
            p = q
            mask = masks[p]
            g0, Phi, GB, GL = G0s[p], Phis[p], GBs[p], GLs[p]
            redo = True
        if pp != p:
            pp = p
            prev = masks[pp]
        for i in range(ns):
            span_prev[i] = span[i]
            d[i] = d_new[i]
            dd[i] = dd_new[i]
        for a in range(m):
            i = lcols[a]
            w[i] = (y_new[i] - y[i]) / dt
        for i in range(2 * n):
            y[i] = y_new[i]
        for i in range(ns):
            f = F[i] if mask[i] else 0.0
            f = max(f, 0.0) if tonly[i] else f
            F[i] = f
            if f > fmax[i]:
                fmax[i] = f
        if (k + 1) % rec == 0:
            r = (k + 1) // rec
            for i in range(ns):
                forces[r, i] = F[i]
            for i in range(2 * n):
                states[r, i] = y[i]
    state[0], state[2], state[3] = steps, p, pp
    return steps


#: numba signature of :func:`run_kernel_flat` (C-contiguous float64/int64/bool arrays).
FLAT_SIGNATURE = (
    "i8(f8[::1], f8[::1], f8[::1], i8[::1], i8, f8, i8, b1[:, ::1], f8[:, :, ::1],"
    " f8[:, ::1], f8[:, :, ::1], f8[:, :, ::1], i8, f8[:, ::1], f8[::1], f8[::1], b1[::1], f8[::1], i8,"
    " f8, f8, i8, f8[::1], i8[::1], f8[::1], f8[::1], i8[::1], f8[::1], f8[::1], f8, b1,"
    " f8[::1], f8[::1], f8[::1], f8[::1], i8[::1], f8[::1], f8, f8, f8[::1], f8[:, ::1],"
    " f8[:, ::1], f8[::1], b1[::1], i8[::1])"
)
