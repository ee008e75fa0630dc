r"""Compiled time-stepping kernel of the nonlinear start-up (:mod:`chaindrive.dynamics.startup`).

The same step as the NumPy loop of :func:`chaindrive.dynamics.startup.simulate_startup`
(exact zero-order-hold transition Φ_s, Γ_s per slack pattern s, Van Loan 1978; explicit
pre-tension and polygonal span forces extrapolated to mid-step; motor and resistance laws
linearly implicit on each mass's own speed; a step that changes the slack pattern redone
once with the new pattern), written on plain arrays so that numba compiles it
(``@njit(cache=True)``: the machine code is cached on disk, later runs skip compilation).

The motor and resistance laws are passed as codes and parameter arrays
(:mod:`chaindrive.dynamics.kernel_codes`); the Φ_s, Γ_s of the slack patterns met so far
are stacked in arrays. When a step meets a pattern not yet in the stack the kernel returns
the step index and the pattern; the caller adds Φ_s, Γ_s and calls the kernel again from
that step (the state is left untouched, so the result does not depend on the interruption).

numba is optional: :data:`HAVE_NUMBA` is False when it is not importable and the caller
falls back to the NumPy loop. :func:`run_kernel_flat` is the entry point with plain arguments
(arrays, numbers), the one :mod:`chaindrive.dynamics.kernel_build` compiles ahead of time into
an extension module that loads without numba.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from chaindrive.dynamics.kernel_codes import (  # the kernel's integer codes
    MOTOR_CONSTANT,
    MOTOR_RAMP,
    RESISTANCE_CONSTANT,
    RESISTANCE_LINEAR,
    RESISTANCE_QUADRATIC,
)

try:  # numba is optional (project rule: compiled hot loop with a NumPy fallback)
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    numba = None
    HAVE_NUMBA = False

__all__ = ["FLAT_SIGNATURE", "HAVE_NUMBA", "run_kernel", "run_kernel_flat"]

def _njit(fn: Any) -> Any:
    return numba.njit(cache=True, fastmath=False)(fn) if HAVE_NUMBA else fn


@_njit
def _laws(t: float, v: Any, out: Any, R: Any, driven: Any, driver: int, mkind: int, mp: Any,
          rkind: int, rM: Any, rwn: Any, rbrk: float) -> None:
    """Motor and resistance forces [N] at the chain speeds v (as ``simulate_startup.laws``)."""
    n = v.size
    for i in range(n):
        r = (v[i] / R[i]) / rwn[i]
        if rkind == RESISTANCE_LINEAR:
            mr = rM[i] * r
        elif rkind == RESISTANCE_QUADRATIC:
            mr = rM[i] * r * abs(r)
        elif rkind == RESISTANCE_CONSTANT:
            mr = rM[i] * min(max(r / rbrk, -1.0), 1.0)
        else:
            mr = 0.0
        out[i] = -driven[i] * mr / R[i]
    w = v[driver] / R[driver]
    if mkind == MOTOR_CONSTANT:
        torque = mp[0]
    elif mkind == MOTOR_RAMP:
        torque = mp[0] * min(1.0, t / mp[1]) if mp[1] > 0 else mp[0]
    else:
        s = 1.0 - w / mp[2]
        torque = mp[0] * s * mp[1] / (s * s + mp[1] * mp[1])
    out[driver] += torque / R[driver]


@_njit
def _polygonal(x: Any, v: Any, d: Any, dd: Any, pz: Any, pR: Any, ps: Any, psign: Any,
               pidx: Any, pk: float, plin: float, pd0: Any) -> None:
    """Polygonal elongation d and its rate ḋ of every span (exact hinge law, d(0) removed)."""
    n = d.size
    for i in range(n):
        d[i] = 0.0
        dd[i] = 0.0
    for j in range(2 * n):
        psi = pk * x[pidx[j]] - 2.0 * math.pi * ps[j]
        psi = np.mod(psi + math.pi, 2.0 * math.pi) - math.pi
        sa = math.sin(psi / pz[j])
        # |ψ/z| ≤ π/3 (|ψ| ≤ π, z ≥ 3): cos(ψ/z) ≥ 1/2 is sqrt(1 − sin²), a square root
        # instead of a second transcendental per span end and step
        ca = math.sqrt(1.0 - sa * sa)
        dl = psign[j] * (pR[j] * sa - plin * psi)
        dv = psign[j] * (pR[j] / pz[j] * ca * pk - 1.0) * v[pidx[j]]
        d[j % n] += dl
        dd[j % n] += dv
    for i in range(n):
        d[i] -= pd0[i]


@(numba.njit(cache=True, fastmath={"reassoc"}) if HAVE_NUMBA else (lambda f: f))
def _matvec_add(A: Any, y: Any, out: Any) -> None:
    """out += A @ y (the dot products reassociated so that they run in SIMD lanes: round-off
    order as in a BLAS matrix-vector product, not left to right)."""
    for i in range(A.shape[0]):
        acc = 0.0
        for j in range(A.shape[1]):
            acc += A[i, j] * y[j]
        out[i] += acc


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
def _span_part(mask: Any, fr: Any, c: Any, bc: Any, T0: float, poly: bool, d: Any, dd: Any,
               span: Any) -> None:
    """−Bᵀ of the pre-tension and polygonal span forces [N] (explicit part), from the
    polygonal elongations d, ḋ at the current state (``span``: work array)."""
    n = fr.size
    for i in range(n):
        s = T0 if mask[i] else 0.0
        if poly:
            s = s + (1.0 if mask[i] else 0.0) * (c[i] * d[i] + bc[i] * dd[i])
        span[i] = s
    for i in range(n):
        fr[i] = span[i] - span[i - 1]


@_njit
def _advance(y: Any, t: float, dt: float, fr: Any, Phi: Any, Gam: Any, gvv: Any, y_new: Any,
             lw: tuple, work: Any) -> None:
    """One step; the speed laws linearly implicit on each mass's own speed (``work``:
    (6, n) work array)."""
    R, driven, driver, mkind, mp, rkind, rM, rwn, rbrk = lw
    n = fr.size
    v = y[n:]
    fl, f2, hv, vh, f, df = work[0], work[1], work[2], work[3], work[4], work[5]
    th = t + 0.5 * dt
    _laws(th, v, fl, R, driven, driver, mkind, mp, rkind, rM, rwn, rbrk)
    for i in range(n):
        hv[i] = 1e-6 * (1.0 + abs(v[i]))
        vh[i] = v[i] + hv[i]
    _laws(th, vh, f2, R, driven, driver, mkind, mp, rkind, rM, rwn, rbrk)
    for i in range(n):
        f[i] = fr[i] + fl[i]
    y_new[:] = 0.0
    _matvec_add(Phi, y, y_new)
    _matvec_add(Gam, f, y_new)
    for i in range(n):
        J = (f2[i] - fl[i]) / hv[i]
        df[i] = J * (y_new[n + i] - v[i]) / max(1.0 - gvv[i] * J, 0.1)
    _matvec_add(Gam, df, y_new)


@_njit
def _span_force(y: Any, F: Any, c: Any, bc: Any, T0: float, poly: bool, d: Any, dd: Any,
                pz: Any, pR: Any, ps: Any, psign: Any, pidx: Any, pk: float, plin: float,
                pd0: Any) -> None:
    """Span forces [N] before the slack rule at the state y = (x, ẋ); the polygonal
    elongations d, ḋ at y are left in ``d``, ``dd`` (the next step's explicit part uses
    them: the same state, not evaluated twice)."""
    n = F.size
    x = y[:n]
    v = y[n:]
    if poly:
        _polygonal(x, v, d, dd, pz, pR, ps, psign, pidx, pk, plin, pd0)
    for i in range(n):
        j = (i + 1) % n
        e = x[j] - x[i]
        ed = v[j] - v[i]
        if poly:
            e, ed = e + d[i], ed + dd[i]
        F[i] = T0 + c[i] * e + bc[i] * ed


@_njit
def run_kernel(y: Any, fr_prev: Any, state: Any, steps: int, dt: float, masks: Any, Phis: Any,
               Gams: Any, gvvs: Any, npat: int, c: Any, bc: Any, T0: float, lw: tuple,
               poly: bool, pg: tuple, forces: Any, speeds: Any, need: Any) -> int:
    """Advance from step state[0] to ``steps``; returns the step reached.

    y (2n,) state, fr_prev (n,) explicit forces of the previous step, state = [step, slack
    count, pattern index] (all updated in place); forces, speeds (steps+1, n) filled in.
    Returns < steps when a step needs a slack pattern not among the first ``npat``: it is
    written into ``need`` and nothing of that step is kept.
    """
    pz, pR, ps, psign, pidx, pk, plin, pd0 = pg
    R = lw[0]
    n = c.size
    d, dd = np.zeros(n), np.zeros(n)  # polygonal elongation and rate at the state y
    d_new, dd_new = np.zeros(n), np.zeros(n)  # … at the candidate state y_new
    if poly:
        _polygonal(y[:n], y[n:], d, dd, pz, pR, ps, psign, pidx, pk, plin, pd0)
    fr = np.empty(n)
    fe = np.empty(n)
    span = np.empty(n)
    work = np.empty((6, n))
    y_new = np.empty(2 * n)
    F = np.empty(n)
    p = state[2]
    for k in range(state[0], steps):
        t = k * dt
        mask = masks[p]
        _span_part(mask, fr, c, bc, T0, poly, d, dd, span)
        for i in range(n):
            fe[i] = 1.5 * fr[i] - 0.5 * fr_prev[i]
        _advance(y, t, dt, fe, Phis[p], Gams[p], gvvs[p], y_new, lw, work)
        _span_force(y_new, F, c, bc, T0, poly, d_new, dd_new, pz, pR, ps, psign, pidx, pk,
                    plin, pd0)
        changed = False
        for i in range(n):
            need[i] = F[i] > 0 and c[i] > 0
            changed = changed or need[i] != mask[i]
        if changed:
            q = _find(masks, npat, need)
            if q < 0:
                state[0], state[2] = k, p
                return k
            p = q
            _span_part(masks[p], fr, c, bc, T0, poly, d, dd, span)
            _advance(y, t, dt, fr, Phis[p], Gams[p], gvvs[p], y_new, lw, work)
            _span_force(y_new, F, c, bc, T0, poly, d_new, dd_new, pz, pR, ps, psign, pidx,
                        pk, plin, pd0)
            state[1] += 1
        mask = masks[p]
        fr_prev[:] = fr
        y[:] = y_new
        d, d_new = d_new, d
        dd, dd_new = dd_new, dd
        for i in range(n):
            forces[k + 1, i] = max(F[i], 0.0) * (1.0 if mask[i] else 0.0)
            speeds[k + 1, i] = y[n + i] / R[i]
    state[0], state[2] = steps, p
    return steps


@_njit
def run_kernel_flat(y: Any, fr_prev: Any, state: Any, steps: int, dt: float, masks: Any,
                    Phis: Any, Gams: Any, gvvs: Any, npat: int, c: Any, bc: Any, T0: float,
                    R: Any, driven: Any, driver: int, mkind: int, mp: Any, rkind: int, rM: Any,
                    rwn: Any, rbrk: float, poly: bool, pz: Any, pR: Any, ps: Any, psign: Any,
                    pidx: Any, pk: float, plin: float, pd0: Any, forces: Any, speeds: Any,
                    need: Any) -> int:
    """:func:`run_kernel` with the law and polygonal tuples spread out (lw = R … rbrk,
    pg = pz … pd0): one fixed signature (:data:`FLAT_SIGNATURE`) for the ahead-of-time build."""
    return run_kernel(y, fr_prev, state, steps, dt, masks, Phis, Gams, gvvs, npat, c, bc, T0,
                      (R, driven, driver, mkind, mp, rkind, rM, rwn, rbrk), poly,
                      (pz, pR, ps, psign, pidx, pk, plin, pd0), forces, speeds, need)


#: numba signature of :func:`run_kernel_flat` (C-contiguous float64/int64/bool arrays).
FLAT_SIGNATURE = (
    "i8(f8[::1], f8[::1], i8[::1], i8, f8, b1[:, ::1], f8[:, :, ::1], f8[:, :, ::1], f8[:, ::1],"
    " i8, f8[::1], f8[::1], f8, f8[::1], f8[::1], i8, i8, f8[::1], i8, f8[::1], f8[::1], f8,"
    " b1, f8[::1], f8[::1], f8[::1], f8[::1], i8[::1], f8, f8, f8[::1], f8[:, ::1], f8[:, ::1],"
    " b1[::1])"
)
