r"""Compiled step loop of the link-level model (numba, ``@njit(cache=True)``).

State: roller centres x (N, 2) [m] and velocities v (N, 2) [m/s]; rotational coordinates
θ (D,) [rad] and speeds ω (D,) [rad/s], the first n of which are the sprockets (the rest:
an optional linear torsional system attached to them, see :mod:`chaindrive.linklevel.model`).

Forces on roller r (module docstring of :mod:`chaindrive.linklevel` for the sources):

* gravity m g;
* links (pin–bush joints) i = (r, r+1): axial spring k·s on the elongation s = ℓ − ℓ₀
  outside the clearance band |ℓ − ℓ₀| ≤ Δ (s = 0 inside it) and an axial damper c·ℓ̇,
  the damper (and with θ = 1/4 the spring) taken implicitly (:func:`_velocity_update`) so
  that it sets no step limit;
* hinge friction at roller r between its two links: a moment
  M = −sat(ω_rel)·f·T̄·d₂/2 on the leading link and −M on the trailing one, T̄ the mean
  tension of the two links (≥ 0), ω_rel their relative angular speed; sat regularises the
  Coulomb law as a viscous moment −c_max ω_rel below the sliding limit (c_max:
  :func:`chaindrive.linklevel.simulate.hinge_regularisation`): explicit up to the step
  where it is stable (:func:`_hinge_moments`); above it linearised about the relative
  speed at the start of the step, the viscous hinges' moments taken implicitly
  (:func:`_hinge_solve`, so that they set no step limit), the sliding ones explicitly;
* roller–tooth contact with the nearest tooth gap of the sprocket the roller is near
  (contact search every ``search_every`` steps bounded to the rollers within reach of each
  sprocket): penetration δ into the tooth = tip disc minus the gap, the gap being the
  seating arc (radius r_i about the gap centre, half angle α) continued by its tangents
  (the flanks); force F = max(0, k_c δ + c_c δ̇) along the normal, reacted on the sprocket
  through the roller centre (exactly work-conjugate to δ).

Integrator: semi-implicit (symplectic) Euler, v ← v + Δt·a(x, v), x ← x + Δt·v
[Hairer2006, §I.1] — one force evaluation a step; the link dampers implicit
(:func:`_velocity_update`), and above the explicit hinge friction's stability limit the
viscous hinges too (:func:`_hinge_solve`, solved before the link dampers' step: a
first-order splitting of the two implicit parts, the order of the integrator itself).
With θ = 1/4 the link springs are implicit too, the
implicit–explicit partition of [HughesLiu1978]: in the central-difference form of the step,
x_{n+1} − 2x_n + x_{n−1} = Δt² M⁻¹ F, the springs act at the average
x̄ = (x_{n+1} + 2x_n + x_{n−1})/4 = x_n + (Δt/4)(v′ − v) (Newmark's β = 1/4, energy-
conserving and unconditionally stable for a linear spring), linearised along the links with
their directions frozen over the step: the tension T(x̄) ≈ T(x_n) + (Δt/4)k(ℓ̇′ − ℓ̇), whose
part in the new rates ℓ̇′ joins the damper's in the same cyclic tridiagonal solve
(c → c + Δt k/4). For a linear system the step is then stable below 2/ω of the explicit part
alone (the contacts) [HughesLiu1978]; the link modes come out at ω/√(1 + Δt²ω²/4) (below
2/Δt), the slow ones unchanged to O((Δt ω)²).

Model: [Pedersen2004], [Pedersen2005] (particles, spring–dampers, continuous contact on the
real tooth profile); hinge friction [ChainHingeDissipation]; tooth forms [ISO606],
[GOST591].
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

__all__ = ["compiled", "run_kernel"]

from chaindrive.dynamics.transient.kernel_codes import (  # the start-up kernel's codes
    MOTOR_CONSTANT,
    MOTOR_RAMP,
    RESISTANCE_CONSTANT,
    RESISTANCE_LINEAR,
    RESISTANCE_QUADRATIC,
)

#: The floating-point liberties the step loop is compiled with (LLVM's fast-math flags, as
#: numba passes them): fused multiply-add, a division by a reused divisor taken as a
#: multiplication by its reciprocal, sums reassociated (so that they vectorise), the sign of
#: zero ignored. NaN and infinity keep their IEEE meaning and the library functions (square
#: root, sine, cosine) stay exact to their last bit. Each changes a result by an ulp or so a
#: step; docs/linklevel.md §3 gives the speed and the convergence figures with them. The
#: static balance (:func:`static_forces`) and the link forces it shares are compiled
#: without them: its Hessian is taken by finite differences, which round-off reaches.
FAST = {"contract", "arcp", "reassoc", "nsz"}

#: Energy accumulators (indices of ``energy``): work of the motor, of the resistance
#: laws, dissipated in link dampers, contact dampers, hinge friction, torsional dampers.
E_MOTOR, E_LOAD, E_LINK, E_CONTACT, E_HINGE, E_TORSION = 0, 1, 2, 3, 4, 5


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _motor_torque(t: float, w: float, kind: int, mp: Any) -> float:
    """Motor torque [N·m] at time t [s] and forward speed w [rad/s] (laws of
    :mod:`chaindrive.dynamics.transient.startup`: constant, ramp, Kloss)."""
    if kind == MOTOR_CONSTANT:
        return float(mp[0])
    if kind == MOTOR_RAMP:
        return float(mp[0] * min(1.0, t / mp[1]) if mp[1] > 0 else mp[0])
    s = 1.0 - w / mp[2]
    return float(mp[0] * s * mp[1] / (s * s + mp[1] * mp[1]))


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _resistance_torque(w: float, kind: int, M: float, wn: float, brk: float) -> float:
    """Moment of resistance [N·m] at forward speed w [rad/s] (ResistanceLaw kinds)."""
    r = w / wn
    if kind == RESISTANCE_LINEAR:
        return M * r
    if kind == RESISTANCE_QUADRATIC:
        return M * r * abs(r)
    if kind == RESISTANCE_CONSTANT:
        return M * min(max(r / brk, -1.0), 1.0)
    return 0.0


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _search(x: Any, cx: Any, cy: Any, reach: Any, cand: Any, eng: Any, xs: Any,
            free: Any) -> None:
    """cand[r] = the first sprocket whose reach circle holds roller r, else −1. A roller that
    comes within reach of sprocket s from outside every reach is armed for an engagement
    (eng[r] = (s, −1, 0)); one that leaves every reach before touching is disarmed.

    A roller is tested against the reach circles only once it has moved away from where it
    was last tested (xs[r]) by the distance from there to the nearest circle that decides
    its answer (those of sprockets up to its own, or all when it was in none), less 1 nm:
    closer, no circle can have been crossed, so its answer stands. free[r] holds the square
    of that distance (−1: test it; the 1 nm dwarfs the round-off of the squared distances,
    ~10⁻¹⁷ m at these sizes, so the answer is the one a test would give)."""
    for r in range(x.shape[0]):
        old = cand[r]
        ex = x[r, 0] - xs[r, 0]
        ey = x[r, 1] - xs[r, 1]
        if not ex * ex + ey * ey < free[r]:  # (a NaN position is tested)
            new = -1
            margin = math.inf
            for s in range(cx.size):
                dx = x[r, 0] - cx[s]
                dy = x[r, 1] - cy[s]
                d2 = dx * dx + dy * dy
                margin = min(margin, abs(math.sqrt(d2) - reach[s]))
                if d2 < reach[s] * reach[s]:
                    new = s
                    break
            margin -= 1e-9
            free[r] = margin * margin if margin > 0.0 else -1.0
            xs[r, 0] = x[r, 0]
            xs[r, 1] = x[r, 1]
            cand[r] = new
        if old == -1 and cand[r] >= 0 and eng[r, 0] < 0:
            eng[r, 0] = cand[r]
            eng[r, 1] = -1.0
            eng[r, 2] = 0.0
        elif cand[r] < 0 and eng[r, 1] < 0:
            eng[r, 0] = -1.0


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _engagements(t: float, Fc: Any, eng: Any, win: Any, events: Any, count: Any) -> None:
    """Engagement impacts: an armed roller's first contact opens a window of win[s] steps
    (one tooth period at the nominal speed) over which its peak contact force is kept; a
    closed window is written as an event row (time of first contact [s], sprocket, roller,
    peak force [N])."""
    for r in range(Fc.size):
        s = int(eng[r, 0])
        if s < 0:
            continue
        if eng[r, 1] < 0.0:
            if Fc[r] > 0.0:
                eng[r, 1] = win[s]
                eng[r, 3] = t
            else:
                continue
        if Fc[r] > eng[r, 2]:
            eng[r, 2] = Fc[r]
        eng[r, 1] -= 1.0
        if eng[r, 1] <= 0.0:
            k = count[0]
            if k < events.shape[0]:
                events[k, 0] = eng[r, 3]
                events[k, 1] = s
                events[k, 2] = r
                events[k, 3] = eng[r, 2]
                count[0] = k + 1
            eng[r, 0] = -1.0


@numba.njit(cache=True, error_model="numpy")
def penetration(px: float, py: float, th: float, z: float, R: float, rr: float, ri: float,
                 ah: float, Ra: float) -> tuple[float, float, float, int]:
    """(δ [m], n_x, n_y, gap) of a roller centred at (px, py) relative to the sprocket
    centre, the sprocket at angle th: n the unit normal of the force on the roller."""
    rho_c = math.sqrt(px * px + py * py)
    step = 2.0 * math.pi / z
    a = math.atan2(py, px)
    j = math.floor((a - th) / step + 0.5)
    ga = th + j * step
    er_x, er_y = math.cos(ga), math.sin(ga)
    wx, wy = px - R * er_x, py - R * er_y
    wi = -(wx * er_x + wy * er_y)  # along the inward radial
    wt = -wx * er_y + wy * er_x  # along the tangent (+ counter-clockwise)
    theta = math.atan2(wt, wi)
    if abs(theta) <= ah:
        rho = math.sqrt(wx * wx + wy * wy)
        d_gap = rho + rr - ri
        if rho > 1e-15:
            nx, ny = -wx / rho, -wy / rho
        else:
            nx, ny = er_x, er_y
    else:
        d, nx, ny = _flank(px, py, wx, wy, er_x, er_y, 1.0 if theta > 0 else -1.0, R, rr, ri,
                           math.cos(ah), math.sin(ah), Ra)
        return d, nx, ny, j
    d_tip = Ra + rr - rho_c
    if d_tip < d_gap:
        return d_tip, px / rho_c, py / rho_c, j
    return d_gap, nx, ny, j


@numba.njit(cache=True, error_model="numpy", fastmath=FAST, inline="always")
def _flank(px: float, py: float, wx: float, wy: float, gx: float, gy: float, sg: float,
           R: float, rr: float, ri: float, ca: float, sa: float, Ra: float
           ) -> tuple[float, float, float]:
    """(δ [m], n_x, n_y) of a roller beyond the seating arc on side ``sg`` (±1) of the gap
    whose centre direction is (gx, gy): centre p (from the sprocket centre), w = p − R g.

    The tooth there is the tip disc |x| ≤ R_a on the tooth's side of the flank line (through
    the arc's end P_α = R g + r_i f, normal f into the tooth, running outwards along u to
    the corner C = P_α + L u on the tip circle). Inside the tooth δ = r − (its distance to
    the nearer face); outside, δ = r − the distance to the nearest point of the tooth: the
    foot on the flank while it lies below the corner, the tip circle's nearest point while
    it lies on the tooth's side of the flank, else the corner C itself — a roller clear of
    the corner is not pushed by the flank line extended beyond the tooth.
    """
    fx = -ca * gx - sg * sa * gy  # flank normal into the tooth: ca(−g) + sg sa t
    fy = -ca * gy + sg * sa * gx
    ux, uy = sg * fy, -sg * fx  # along the flank, outwards (u·g = sa > 0)
    ex, ey = wx - ri * fx, wy - ri * fy  # from P_α
    h = ex * fx + ey * fy  # into the tooth (> 0: p on the tooth's side)
    along = ex * ux + ey * uy
    rc = math.sqrt(px * px + py * py)
    d_flank = h + rr
    d_tip = Ra + rr - rc
    if h >= 0.0 and rc <= Ra:  # centre inside the tooth: the nearer face
        if d_tip < d_flank:
            return d_tip, px / rc, py / rc
        return d_flank, -fx, -fy
    # the corner's distance along the flank: |P_α + L u| = R_a, P_α·u = R sa
    pu = R * sa
    L = -pu + math.sqrt(max(pu * pu - (R * R - 2.0 * R * ri * ca + ri * ri - Ra * Ra), 0.0))
    flank_ok = h < 0.0 and along <= L
    tip_ok = False
    if rc > Ra:  # the tip circle's nearest point on the tooth's side of the flank?
        qx, qy = px * Ra / rc - R * gx - ri * fx, py * Ra / rc - R * gy - ri * fy
        tip_ok = qx * fx + qy * fy >= 0.0
    if flank_ok and (not tip_ok or d_flank <= d_tip):
        return d_flank, -fx, -fy
    if tip_ok:
        return d_tip, px / rc, py / rc
    cx = px - (R * gx + ri * fx + L * ux)  # from the corner C to the centre
    cy = py - (R * gy + ri * fy + L * uy)
    dc = math.sqrt(cx * cx + cy * cy)
    if dc <= 1e-15:
        return rr, -fx, -fy
    return rr - dc, cx / dc, cy / dc


@numba.njit(cache=True, error_model="numpy")
def _links(x: Any, v: Any, L0: Any, k: float, clear: float, T: Any, ux: Any, uy: Any,
           thd: Any, invl: Any, gd: Any) -> None:
    """Elastic tensions T, unit vectors (ux, uy), angular speeds thd, inverse lengths
    invl (1/ℓ) and axial rates gd (ℓ̇) of every link (no dependence between iterations: the
    loop vectorises)."""
    N = x.shape[0]
    last = N - 1
    for i in range(last):  # links 0 … N−2 (i → i+1): a loop without a branch vectorises
        _link(x, v, L0, k, clear, T, ux, uy, thd, invl, gd, i, i + 1)
    _link(x, v, L0, k, clear, T, ux, uy, thd, invl, gd, last, 0)  # the closing link


@numba.njit(cache=True, error_model="numpy", fastmath=FAST, inline="always")
def _link(x: Any, v: Any, L0: Any, k: float, clear: float, T: Any, ux: Any, uy: Any,
          thd: Any, invl: Any, gd: Any, i: int, b: int) -> None:
    """Link i from roller i to roller b: its entries of :func:`_links`."""
    dx, dy = x[b, 0] - x[i, 0], x[b, 1] - x[i, 1]
    dvx, dvy = v[b, 0] - v[i, 0], v[b, 1] - v[i, 1]
    l2 = dx * dx + dy * dy
    ell = math.sqrt(l2)
    inv = 1.0 / ell
    e = ell - L0[i]
    T[i] = k * (e - min(max(e, -clear), clear))  # zero inside the clearance band
    thd[i] = (dx * dvy - dy * dvx) * inv * inv
    gd[i] = (dx * dvx + dy * dvy) * inv
    invl[i] = inv
    ux[i] = dx * inv
    uy[i] = dy * inv


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _hinge_moments(T: Any, thd: Any, mu_r: float, cmax: float, M: Any) -> float:
    """Hinge friction moment M_r at every roller r on its leading link r (−M_r on the
    trailing link r−1), module docstring; returns the power dissipated [W]."""
    N = T.size
    diss = 0.0
    tprev, wprev = T[N - 1], thd[N - 1]
    for r in range(N):
        wrel = thd[r] - wprev
        tm = 0.5 * (T[r] + tprev)
        tprev, wprev = T[r], thd[r]
        limit = mu_r * tm if tm > 0.0 else 0.0
        visc = cmax * abs(wrel)
        mag = limit if visc > limit else visc
        moment = -mag if wrel > 0.0 else mag
        M[r] = moment
        diss -= moment * wrel
    return diss


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _hinge_linearised(T: Any, thd: Any, mu_r: float, cmax: float, M: Any, cv: Any) -> int:
    """The regularised Coulomb hinge friction at every roller r (module docstring),
    linearised about the relative angular speed ω_rel at the start of the step: a hinge
    below the sliding limit (c_max|ω_rel| < f·T̄·d₂/2) is viscous, its moment
    −c_max ω′_rel taken implicitly at the new rates (cv[r] = c_max, M[r] = 0,
    :func:`_hinge_solve`); one at the limit slides, its moment M[r] = −sign(ω_rel)·f·T̄·d₂/2
    explicit (cv[r] = 0) — on the leading link r, −M[r] on the trailing link r−1. Returns
    the number of viscous hinges."""
    N = T.size
    count = 0
    tprev, wprev = T[N - 1], thd[N - 1]
    for r in range(N):
        wrel = thd[r] - wprev
        tm = 0.5 * (T[r] + tprev)
        tprev, wprev = T[r], thd[r]
        limit = mu_r * tm if tm > 0.0 else 0.0
        if cmax * abs(wrel) < limit:
            M[r] = 0.0
            cv[r] = cmax
            count += 1
        else:
            M[r] = -limit if wrel > 0.0 else limit
            cv[r] = 0.0
    return count


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _hinge_solve(v: Any, f: Any, h: float, ux: Any, uy: Any, invl: Any, M: Any, cv: Any,
                 count: int, wk: Any) -> float:
    r"""The viscous hinges' moments taken implicitly (backward Euler at the new rates, the
    links' directions and lengths frozen over the step), their forces added to f; returns
    the power dissipated by all the hinges [W] at the rates after their moments.

    With q_i = 1/ℓ_i, n_i = u⊥_i, o_i = u_i·u_{i+1}, τ = h = Δt/m, the link angular rates
    ω_i = q_i n_i·(v_{i+1} − v_i) respond to the hinge moments M as
    ω′ = ω* + τ B Dᵀ M, (Dω)_r = ω_r − ω_{r−1} the relative rates, B = diag(q) A diag(q),
    A = tridiag(−o_{i−1}, 2, −o_i) (cyclic), ω* the rates of v* = v + h f. The viscous law
    M = −C Dω′, C = diag(cv), gives with M = C^{1/2} y the symmetric positive definite
    cyclic pentadiagonal system (I + τ C^{1/2} P C^{1/2}) y = −C^{1/2} D ω*,
    P = D B Dᵀ: P_rr = b_r + b_{r−1} − 2e_{r−1}, P_{r,r+1} = e_r − b_r + e_{r−1},
    P_{r,r+2} = −e_r with b_i = 2q_i², e_i = −o_i q_i q_{i+1}. Solved by the banded
    LDLᵀ factorisation [Golub2013, §4.3] of its first N − 2 rows and the 2 × 2 Schur
    complement of the last two (the cyclic corners). Backward Euler is unconditionally
    stable for the viscous law; taken explicitly it needs Δt·c_max·λ_max(P)/m < 2, and on
    a straight span λ_max(P) = 16/p² (the zigzag mode, P the fourth difference
    (1, −4, 6, −4, 1)/p²), so Δt < m p²/(8 c_max) (docs/linklevel.md §2). Needs N ≥ 5
    links.

    wk: work array (14, N).
    """
    N = v.shape[0]
    last = N - 1
    w = wk[0]  # ω*, then ω′
    for i in range(N):
        b = i + 1 if i < last else 0
        w[i] = invl[i] * (-uy[i] * (v[b, 0] - v[i, 0] + h * (f[b, 0] - f[i, 0]))
                          + ux[i] * (v[b, 1] - v[i, 1] + h * (f[b, 1] - f[i, 1])))
    mi = wk[1]  # the implicit moments
    mn = wk[2]  # net link moments over ℓ
    oo = wk[3]
    for i in range(N):
        b = i + 1 if i < last else 0
        oo[i] = ux[i] * ux[b] + uy[i] * uy[b]
        mi[i] = 0.0
    if count > 0:
        _hinge_system(h, invl, oo, cv, w, wk)
        s, y = wk[4], wk[5]
        for r in range(N):
            mi[r] = s[r] * y[r]
    for i in range(N):
        b = i + 1 if i < last else 0
        mn[i] = invl[i] * (mi[i] - mi[b])
    px, py = -uy[last] * mn[last], ux[last] * mn[last]  # mnet_{r−1} n_{r−1}
    for r in range(N):
        cx, cy = -uy[r] * mn[r], ux[r] * mn[r]
        f[r, 0] += px - cx
        f[r, 1] += py - cy
        px, py = cx, cy
    diss = 0.0
    for i in range(N):  # ω′ = ω* + τ q_i (2 mnet_i − o_i mnet_{i+1} − o_{i−1} mnet_{i−1})
        a = i - 1 if i > 0 else last
        b = i + 1 if i < last else 0
        wk[6, i] = w[i] + h * invl[i] * (2.0 * mn[i] - oo[i] * mn[b] - oo[a] * mn[a])
    wprev = wk[6, last]
    for r in range(N):
        wrel = wk[6, r] - wprev
        wprev = wk[6, r]
        diss -= (M[r] + mi[r]) * wrel
    return diss


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _hinge_system(h: float, q: Any, oo: Any, cv: Any, w: Any, wk: Any) -> None:
    """Assemble and solve the cyclic pentadiagonal system of :func:`_hinge_solve`: the
    scaling s = C^{1/2} into wk[4], the solution y into wk[5] (wk[6:14] work)."""
    N = q.size
    last = N - 1
    s, y = wk[4], wk[5]
    q0, q1, q2 = wk[6], wk[7], wk[8]  # diagonal, (r, r+1) and (r, r+2) entries
    for r in range(N):
        s[r] = math.sqrt(cv[r])
    for r in range(N):
        a = r - 1 if r > 0 else last
        b = r + 1 if r < last else 0
        c = b + 1 if b < last else 0
        br = 2.0 * q[r] * q[r]
        ba = 2.0 * q[a] * q[a]
        er = -oo[r] * q[r] * q[b]
        ea = -oo[a] * q[a] * q[r]
        q0[r] = 1.0 + h * s[r] * s[r] * (br + ba - 2.0 * ea)
        q1[r] = h * s[r] * s[b] * (er - br + ea)
        q2[r] = h * s[r] * s[c] * (-er)
        y[r] = -s[r] * (w[r] - w[a])  # right-hand side
    n = N - 2  # interior rows 0 … n−1, border rows n, n+1 (the cyclic corners)
    dg, l1, l2 = wk[9], wk[10], wk[11]
    # the border's columns in the interior rows: column n at rows 0, n−2, n−1 and
    # column n+1 at rows 0, 1, n−1; solved along with the right-hand side
    xa, xb = wk[12], wk[13]
    for i in range(n):
        xa[i] = 0.0
        xb[i] = 0.0
    xa[0] += q2[n]  # (n, 0) wraps: Q_{n, n+2} = Q_{n, 0}
    xa[n - 2] += q2[n - 2]
    xa[n - 1] += q1[n - 1]
    xb[0] += q1[last]  # (N−1, 0)
    xb[1] += q2[last]  # (N−1, 1)
    xb[n - 1] += q2[n - 1]
    ca0, ca1, ca2 = xa[0], xa[n - 2], xa[n - 1]
    cb0, cb1, cb2 = xb[0], xb[1], xb[n - 1]
    # banded LDLᵀ (dg: the reciprocal pivots) and the forward substitution, the previous
    # two rows carried in scalars
    p1 = p2 = 0.0  # reciprocal pivots of rows i−1, i−2
    c1 = 0.0  # l1 of row i−1
    y1 = y2 = a1v = a2v = b1v = b2v = 0.0
    for i in range(n):
        e2 = q2[i - 2] if i >= 2 else 0.0
        e1 = q1[i - 1] - e2 * c1 if i >= 1 else 0.0
        m2 = e2 * p2
        m1 = e1 * p1
        d = q0[i] - m2 * e2 - m1 * e1
        yi = y[i] - m2 * y2 - m1 * y1
        ai = xa[i] - m2 * a2v - m1 * a1v
        bi = xb[i] - m2 * b2v - m1 * b1v
        y[i], xa[i], xb[i] = yi, ai, bi
        inv = 1.0 / d
        dg[i] = inv
        l1[i] = m1
        l2[i] = m2
        p2, p1 = p1, inv
        c1 = m1
        y2, y1 = y1, yi
        a2v, a1v = a1v, ai
        b2v, b1v = b1v, bi
    y1 = y2 = a1v = a2v = b1v = b2v = 0.0  # back substitution, rows i+1, i+2
    k1 = k2 = h1 = 0.0  # l1 of row i+1, l2 of rows i+1 and i+2
    for i in range(n - 1, -1, -1):
        yi = y[i] * dg[i] - k1 * y1 - k2 * y2
        ai = xa[i] * dg[i] - k1 * a1v - k2 * a2v
        bi = xb[i] * dg[i] - k1 * b1v - k2 * b2v
        y[i], xa[i], xb[i] = yi, ai, bi
        y2, y1 = y1, yi
        a2v, a1v = a1v, ai
        b2v, b1v = b1v, bi
        k2 = h1
        k1 = l1[i]
        h1 = l2[i]
    # the 2 × 2 Schur complement of the border
    saa = q0[n] - (ca0 * xa[0] + ca1 * xa[n - 2] + ca2 * xa[n - 1])
    sab = q1[n] - (ca0 * xb[0] + ca1 * xb[n - 2] + ca2 * xb[n - 1])
    sbb = q0[last] - (cb0 * xb[0] + cb1 * xb[1] + cb2 * xb[n - 1])
    ra = y[n] - (ca0 * y[0] + ca1 * y[n - 2] + ca2 * y[n - 1])
    rb = y[last] - (cb0 * y[0] + cb1 * y[1] + cb2 * y[n - 1])
    det = saa * sbb - sab * sab
    ua = (ra * sbb - sab * rb) / det
    ub = (saa * rb - sab * ra) / det
    for i in range(n):
        y[i] -= xa[i] * ua + xb[i] * ub
    y[n] = ua
    y[last] = ub


@numba.njit(cache=True, error_model="numpy")
def _link_forces(f: Any, T: Any, ux: Any, uy: Any, invl: Any, M: Any) -> None:
    """Forces of the links on the rollers into f: link i pulls its ends together with T_i
    along u_i and turns with the net moment M_i − M_{i+1} of its two hinges, the force pair
    ±(M/ℓ)·u⊥ at its ends; roller r gets link r's start share s_r minus link r−1's, s_i =
    T_i u_i − (M_i − M_{i+1})/ℓ_i · u⊥_i."""
    N = T.size
    last = N - 1
    mnet = (M[last] - M[0]) * invl[last]
    px = T[last] * ux[last] + mnet * uy[last]
    py = T[last] * uy[last] - mnet * ux[last]
    for i in range(N):
        mnet = (M[i] - M[i + 1 if i < last else 0]) * invl[i]
        cx = T[i] * ux[i] + mnet * uy[i]
        cy = T[i] * uy[i] - mnet * ux[i]
        f[i, 0] += cx - px
        f[i, 1] += cy - py
        px, py = cx, cy


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _twisted_solve(hc: float, o: Any, b0: float, bl: float, diag: float, d: Any, z: Any,
                   cp: Any) -> None:
    """Solve the tridiagonal system with diagonal (b0, diag, …, diag, bl) and off-diagonals
    −h_c·o_i (entries (i, i+1) and (i+1, i)) for the right-hand sides d and z in place, by
    the twisted (two-sided) factorisation: eliminated from both ends towards the middle row
    and substituted back outwards ([Press2007, §2.4] applied from both ends), so that the
    two halves' dependency chains run side by side. cp: work array."""
    n = d.size
    last = n - 1
    k = n // 2
    cprev, dprev, zprev = 0.0, 0.0, 0.0  # top: c′_{j−1}, d′_{j−1}, z′_{j−1}
    anext, dnext, znext = 0.0, 0.0, 0.0  # bottom: a″_{j+1}, d″_{j+1}, z″_{j+1}
    for t in range(k):
        j = t  # top row j: sub-diagonal −h_c o_{j−1}, super-diagonal −h_c o_j
        a = -hc * o[j - 1] if j > 0 else 0.0
        inv = 1.0 / ((b0 if j == 0 else diag) - a * cprev)
        cprev = -hc * o[j] * inv
        dprev = (d[j] - a * dprev) * inv
        zprev = (z[j] - a * zprev) * inv
        cp[j] = cprev
        d[j] = dprev
        z[j] = zprev
        jb = last - t  # bottom row jb, above the middle row k
        if jb > k:
            c = -hc * o[jb] if jb < last else 0.0
            inv = 1.0 / ((bl if jb == last else diag) - c * anext)
            anext = -hc * o[jb - 1] * inv
            dnext = (d[jb] - c * dnext) * inv
            znext = (z[jb] - c * znext) * inv
            cp[jb] = anext
            d[jb] = dnext
            z[jb] = znext
    a = -hc * o[k - 1] if k > 0 else 0.0
    c = -hc * o[k] if k < last else 0.0
    bk = b0 if k == 0 else (bl if k == last else diag)
    aright = cp[k + 1] if k < last else 0.0
    dright = d[k + 1] if k < last else 0.0
    zright = z[k + 1] if k < last else 0.0
    inv = 1.0 / (bk - a * cprev - c * aright)
    xk = (d[k] - a * dprev - c * dright) * inv
    yk = (z[k] - a * zprev - c * zright) * inv
    d[k] = xk
    z[k] = yk
    up_x, up_y, dn_x, dn_y = xk, yk, xk, yk
    for t in range(1, max(k + 1, n - k)):
        j = k - t  # back-substitution upwards: x_j = d′_j − c′_j x_{j+1}
        if j >= 0:
            up_x = d[j] - cp[j] * up_x
            up_y = z[j] - cp[j] * up_y
            d[j] = up_x
            z[j] = up_y
        jb = k + t  # and downwards: x_j = d″_j − a″_j x_{j−1}
        if jb <= last:
            dn_x = d[jb] - cp[jb] * dn_x
            dn_y = z[jb] - cp[jb] * dn_y
            d[jb] = dn_x
            z[jb] = dn_y


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _velocity_update(v: Any, f: Any, h: float, hc: float, ux: Any, uy: Any, g: Any,
                     rhs: Any, zz: Any, cp: Any, oo: Any) -> None:
    """v ← v + h·f with the link dampers taken implicitly (backward Euler in the axial
    rates, directions frozen over the step): the rates g_i = u_i·(v′_{i+1} − v′_i) solve the
    cyclic tridiagonal system (1 + 2h_c) g_i − h_c (u_i·u_{i+1}) g_{i+1}
    − h_c (u_i·u_{i−1}) g_{i−1} = u_i·(v*_{i+1} − v*_i), h_c = Δt c/m, v* = v + h f
    (the corners by the Sherman–Morrison formula [Press2007, §2.7], the tridiagonal part by
    :func:`_twisted_solve`); then v′_r = v*_r + h_c (g_r u_r − g_{r−1} u_{r−1}).
    Unconditionally stable for any damping. Needs N ≥ 3 links."""
    N = v.shape[0]
    for r in range(N):
        v[r, 0] += h * f[r, 0]
        v[r, 1] += h * f[r, 1]
    if hc == 0.0:
        for i in range(N):
            g[i] = 0.0
        return
    last = N - 1
    for i in range(last):  # rhs and the off-diagonal dot products o_i = u_i·u_{i+1}
        rhs[i] = ux[i] * (v[i + 1, 0] - v[i, 0]) + uy[i] * (v[i + 1, 1] - v[i, 1])
        oo[i] = ux[i] * ux[i + 1] + uy[i] * uy[i + 1]
        zz[i] = 0.0
    rhs[last] = ux[last] * (v[0, 0] - v[last, 0]) + uy[last] * (v[0, 1] - v[last, 1])
    diag = 1.0 + 2.0 * hc
    corner = -hc * (ux[last] * ux[0] + uy[last] * uy[0])  # entries (0, N−1), (N−1, 0)
    gamma = -diag
    zz[0] = gamma
    zz[last] = corner
    _twisted_solve(hc, oo, diag - gamma, diag - corner * corner / gamma, diag, rhs, zz, cp)
    fac = (rhs[0] + corner * rhs[last] / gamma) / (1.0 + zz[0] + corner * zz[last] / gamma)
    ga = rhs[last] - fac * zz[last]
    g[last] = ga
    gx, gy = ga * ux[last], ga * uy[last]
    for r in range(N):
        gr = rhs[r] - fac * zz[r]
        g[r] = gr
        px, py = gr * ux[r], gr * uy[r]
        v[r, 0] += hc * (px - gx)
        v[r, 1] += hc * (py - gy)
        gx, gy = px, py


@numba.njit(cache=True, error_model="numpy", fastmath=FAST, inline="always")
def _gap_local(px: float, py: float, gx: float, gy: float, R: float, rr: float, ri: float,
               ca: float, sa: float, ta: float, Ra: float) -> tuple[float, float, float]:
    """(δ [m], n_x, n_y) of a roller centred at (px, py) (relative to the sprocket centre) in
    the gap whose centre direction is the unit vector (gx, gy): the trigonometry-free form of
    :func:`penetration` (α given by its cosine, sine and tangent)."""
    wx, wy = px - R * gx, py - R * gy
    wi = -(wx * gx + wy * gy)
    wt = -wx * gy + wy * gx
    if wi > 0.0 and abs(wt) <= ta * wi:
        rho = math.sqrt(wx * wx + wy * wy)
        d = rho + rr - ri
        if rho > 1e-15:
            nx, ny = -wx / rho, -wy / rho
        else:
            nx, ny = gx, gy
    else:
        return _flank(px, py, wx, wy, gx, gy, 1.0 if wt > 0.0 else -1.0, R, rr, ri, ca, sa,
                      Ra)
    lim = Ra + rr - d  # the tip disc governs when |p| > R_a + r − δ_gap
    rc2 = px * px + py * py
    if lim < 0.0 or rc2 > lim * lim:
        rc = math.sqrt(rc2)
        return Ra + rr - rc, px / rc, py / rc
    return d, nx, ny


@numba.njit(cache=True, error_model="numpy", fastmath=FAST, inline="always")
def _contacts(x: Any, v: Any, f: Any, th: Any, w: Any, tq: Any, cand: Any, spr: Any,
              trig: Any, gtab: Any, Fc: Any, Sc: Any, Gc: Any, cth: Any, sth: Any) -> float:
    """Roller–tooth contact forces into f and the sprocket torques tq; the contact force
    Fc [N], sprocket Sc and gap Gc of every roller (Gc ≥ 0 also serves as the guess of the
    next step: the nearest of gaps Gc−1, Gc, Gc+1 by distance, which on one pitch circle is
    the nearest by angle); returns the damper power [W].

    spr rows: cx, cy, z, R, r_roller, r_i, α, R_a, k_c, c_c, 2π/z, R sin(π/z); trig rows:
    cos α, sin α, tan α;
    gtab[s, j] = (cos, sin) of 2πj/z_s, the gap directions in the sprocket's frame; cth,
    sth: work arrays (n,) for the cosine and sine of the sprockets' angles.
    """
    diss = 0.0
    ns = th.size if th.size < spr.shape[1] else spr.shape[1]
    for s in range(ns):
        cth[s] = math.cos(th[s])
        sth[s] = math.sin(th[s])
    for r in range(x.shape[0]):
        s = cand[r]
        Fc[r] = 0.0
        Sc[r] = -1
        if s < 0:
            Gc[r] = -1
            continue
        px, py = x[r, 0] - spr[0, s], x[r, 1] - spr[1, s]
        z = spr[2, s]
        R = spr[3, s]
        step = spr[10, s]
        zi = int(z + 0.5)
        j = Gc[r]
        if j < 0:
            a = math.atan2(py * cth[s] - px * sth[s], px * cth[s] + py * sth[s])
            j = math.floor(a / step + 0.5)
            gx = math.cos(th[s] + j * step)
            gy = math.sin(th[s] + j * step)
        else:
            # the current gap, unless the roller has moved past the bisector towards a
            # neighbour (|tangential offset| > R sin(π/z)): then the nearest of the three
            gx = gtab[s, j, 0] * cth[s] - gtab[s, j, 1] * sth[s]
            gy = gtab[s, j, 0] * sth[s] + gtab[s, j, 1] * cth[s]
            if abs(-px * gy + py * gx) > spr[11, s]:
                best = 1e300
                jb = j
                for jj in range(j - 1, j + 2):
                    k = jj if jj >= 0 else jj + zi
                    k = k if k < zi else k - zi
                    ux = gtab[s, k, 0]  # gap direction in the sprocket frame
                    uy = gtab[s, k, 1]
                    ex = ux * cth[s] - uy * sth[s]
                    ey = ux * sth[s] + uy * cth[s]
                    dx, dy = px - R * ex, py - R * ey
                    d2 = dx * dx + dy * dy
                    if d2 < best:
                        best, gx, gy, jb = d2, ex, ey, jj
                j = jb
        j = j % zi if (j < 0 or j >= zi) else j
        Gc[r] = j
        d, nx, ny = _gap_local(px, py, gx, gy, R, spr[4, s], spr[5, s], trig[0, s], trig[1, s],
                               trig[2, s], spr[7, s])
        if d <= 0.0:
            continue
        vrx = v[r, 0] + w[s] * py  # roller velocity relative to the sprocket point under it
        vry = v[r, 1] - w[s] * px
        dd = -(vrx * nx + vry * ny)
        F = spr[8, s] * d + spr[9, s] * dd
        if F < 0.0:
            F = 0.0
        diss += (F - spr[8, s] * d) * dd
        f[r, 0] += F * nx
        f[r, 1] += F * ny
        tq[s] -= F * (px * ny - py * nx)
        Fc[r] = F
        Sc[r] = s
    return diss


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def _rotational(t: float, th: Any, th0: Any, w: Any, tq: Any, J: Any, Kt: Any, Ct: Any,
                mkind: int,
                mp: Any, mdof: int, msign: float, rkind: int, rM: Any, rwn: Any, rbrk: float,
                rsign: Any, energy: Any, dt: float) -> None:
    """Torques of the torsional system (on the turns θ − θ₀ since the start), motor and
    resistances into tq; work into energy."""
    D = J.size
    diss = 0.0
    for i in range(D if Kt.shape[0] > 0 else 0):
        acc = 0.0
        dmp = 0.0
        for k in range(D):
            acc -= Kt[i, k] * (th[k] - th0[k])
            dmp -= Ct[i, k] * w[k]
        tq[i] += acc + dmp
        diss -= dmp * w[i]
    energy[E_TORSION] += diss * dt
    m = msign * _motor_torque(t, msign * w[mdof], mkind, mp)
    tq[mdof] += m
    energy[E_MOTOR] += m * w[mdof] * dt
    for i in range(rM.size):
        if rM[i] != 0.0:
            mr = -rsign[i] * _resistance_torque(rsign[i] * w[i], rkind, rM[i], rwn[i], rbrk)
            tq[i] += mr
            energy[E_LOAD] += mr * w[i] * dt


@numba.njit(cache=True, error_model="numpy", fastmath=FAST)
def run_kernel(x: Any, v: Any, th: Any, w: Any, t0: float, steps: int, dt: float,
               record_every: int, m: float, gx: float, gy: float, L0: Any, k: float, c: float,
               clear: float, mu_r: float, cmax: float, spr: Any, trig: Any, gtab: Any,
               reach: Any,
               search_every: int, win: Any, J: Any, Kt: Any, Ct: Any, mkind: int, mp: Any, mdof: int,
               msign: float, rkind: int, rM: Any, rwn: Any, rbrk: float, rsign: Any,
               rec_x: Any, rec_th: Any, rec_w: Any, rec_T: Any, rec_F: Any, rec_S: Any,
               rec_G: Any, energy: Any, cand: Any, eng: Any, events: Any,
               count: Any, eta: float = 0.0, theta: float = 0.0,
               implicit_hinge: bool = False) -> None:
    """Advance the state ``steps`` steps of Δt from time t0, recording every
    ``record_every`` steps into the rec_* arrays (row 0: the initial state); x, v, th, w are
    updated in place, energy accumulates the work and dissipation (E_* indices); cand, eng
    carry the contact candidates and engagement windows from call to call, events (E, 4)
    collects the engagement impacts (count[0] of them); event times are those of the window
    ends. eta [1/s]: a mass-proportional damping v ← v/(1 + Δt·η) on every body, taken
    implicitly (0 in a run; the settling of :mod:`chaindrive.linklevel.equilibrium` only).
    theta: 0 takes the link springs explicitly; 1/4 takes them implicitly, their force at
    the average x̄ = x + (Δt/4)(v′ − v) of the three positions of the central-difference
    form, linearised along the links (module docstring; needs no clearance).
    implicit_hinge: False takes the regularised hinge friction explicitly
    (:func:`_hinge_moments`, stable for Δt·c_max·16/(m ℓ²) ≤ 2); True linearises it and
    takes the viscous hinges implicitly (:func:`_hinge_linearised`, :func:`_hinge_solve`,
    stable for any step, about 2.9 µs more a step at 128 links)."""
    N = x.shape[0]
    D = J.size
    th0 = th.copy()
    f = np.empty((N, 2))
    T = np.empty(N)
    thd = np.empty(N)
    invl = np.empty(N)
    gd = np.empty(N)
    Tf = np.empty(N)
    M = np.zeros(N)
    cv = np.zeros(N)
    wk = np.zeros((14, N))
    ux = np.empty(N)
    uy = np.empty(N)
    g = np.zeros(N)
    rhs = np.empty(N)
    zz = np.empty(N)
    cp = np.empty(N)
    oo = np.empty(N)
    tq = np.empty(D)
    Fc = np.zeros(N)
    Sc = np.full(N, -1, dtype=np.int64)
    Gc = np.full(N, -1, dtype=np.int64)
    cth = np.empty(spr.shape[1])  # cos and sin of the sprockets' angles (_contacts)
    sth = np.empty(spr.shape[1])
    xs = np.zeros((N, 2))  # where each roller was last tested against the reach circles
    free = np.full(N, -1.0)  # and the square of how far it may go untested (_search)
    row = 0
    for step in range(steps + 1):
        t = t0 + step * dt
        if step % search_every == 0:
            _search(x, spr[0], spr[1], reach, cand, eng, xs, free)
        for r in range(N):
            f[r, 0] = m * gx
            f[r, 1] = m * gy
        for i in range(D):
            tq[i] = 0.0
        _links(x, v, L0, k, clear, T, ux, uy, thd, invl, gd)
        p_hinge = 0.0
        viscous = 0
        if mu_r > 0.0:
            if implicit_hinge:
                viscous = _hinge_linearised(T, thd, mu_r, cmax, M, cv)
            else:
                p_hinge = _hinge_moments(T, thd, mu_r, cmax, M)
        kt = theta * dt * k  # the implicit spring's share of the axial rate, T − kt·ℓ̇
        for i in range(N):
            Tf[i] = T[i] - kt * gd[i]
        _link_forces(f, Tf, ux, uy, invl, M)
        p_contact = _contacts(x, v, f, th, w, tq, cand, spr, trig, gtab, Fc, Sc, Gc, cth,
                              sth)
        if step < steps:
            _engagements(t, Fc, eng, win, events, count)
            _rotational(t, th, th0, w, tq, J, Kt, Ct, mkind, mp, mdof, msign, rkind, rM, rwn,
                        rbrk, rsign, energy, dt)
            if mu_r > 0.0 and implicit_hinge:
                p_hinge = _hinge_solve(v, f, dt / m, ux, uy, invl, M, cv, viscous, wk)
            _velocity_update(v, f, dt / m, dt * (c + kt) / m, ux, uy, g, rhs, zz, cp, oo)
            p_link = 0.0
            for i in range(N):
                p_link += c * g[i] * g[i]
                T[i] += c * g[i]
            energy[E_LINK] += p_link * dt
            energy[E_HINGE] += p_hinge * dt
            energy[E_CONTACT] += p_contact * dt
        if step % record_every == 0:
            # copied element by element, not by slice (rec_x[row] = x): numba compiles a
            # slice assignment's shape-mismatch error message, string formatting and all,
            # a quarter of the kernel's cold compile (first run 11.0 → 8.3 s, idle core)
            for r in range(N):
                rec_x[row, r, 0] = x[r, 0]
                rec_x[row, r, 1] = x[r, 1]
                rec_T[row, r] = T[r]
                rec_F[row, r] = Fc[r]
                rec_S[row, r] = Sc[r]
                rec_G[row, r] = Gc[r]
            for i in range(D):
                rec_th[row, i] = th[i]
                rec_w[row, i] = w[i]
            row += 1
        if step == steps:
            break
        relax = 1.0 / (1.0 + dt * eta)
        if eta > 0.0:
            for r in range(N):
                v[r, 0] *= relax
                v[r, 1] *= relax
        for r in range(N):  # (without a branch inside, the loop vectorises)
            x[r, 0] += dt * v[r, 0]
            x[r, 1] += dt * v[r, 1]
        for i in range(D):
            w[i] = (w[i] + dt * tq[i] / J[i]) * relax
            th[i] += dt * w[i]


@numba.njit(cache=True, error_model="numpy")
def static_forces(x: Any, th: Any, L0: Any, k: float, clear: float, m: float, gx: float,
                  gy: float, spr: Any, trig: Any, gtab: Any, reach: Any, f: Any, tq: Any,
                  T: Any, tr: Any) -> None:
    """Forces on the rollers at rest: f (N, 2) [N] of gravity, the link springs and the
    roller–tooth contacts (no dampers, no hinge friction: nothing moves), the contact torques
    tq (n,) [N·m] on the sprockets, each roller's share tr (N,) [N·m] of them and the link
    tensions T (N,) [N] — the residual of the static balance
    (:mod:`chaindrive.linklevel.equilibrium`)."""
    N = x.shape[0]
    n = spr.shape[1]
    v = np.zeros((N, 2))
    w = np.zeros(n)
    ux = np.empty(N)
    uy = np.empty(N)
    thd = np.empty(N)
    invl = np.empty(N)
    gd = np.empty(N)
    M = np.zeros(N)
    cand = np.full(N, -1, dtype=np.int64)
    Fc = np.zeros(N)
    Sc = np.full(N, -1, dtype=np.int64)
    Gc = np.full(N, -1, dtype=np.int64)
    for r in range(N):
        f[r, 0] = m * gx
        f[r, 1] = m * gy
        for s in range(n):
            dx = x[r, 0] - spr[0, s]
            dy = x[r, 1] - spr[1, s]
            if dx * dx + dy * dy < reach[s] * reach[s]:
                cand[r] = s
                break
    for s in range(n):
        tq[s] = 0.0
    _links(x, v, L0, k, clear, T, ux, uy, thd, invl, gd)
    _link_forces(f, T, ux, uy, invl, M)
    before = f.copy()
    _contacts(x, v, f, th, w, tq, cand, spr, trig, gtab, Fc, Sc, Gc, np.empty(n), np.empty(n))
    for r in range(N):
        s = Sc[r]
        tr[r] = 0.0
        if s >= 0:
            px, py = x[r, 0] - spr[0, s], x[r, 1] - spr[1, s]
            tr[r] = -(px * (f[r, 1] - before[r, 1]) - py * (f[r, 0] - before[r, 0]))


@numba.njit(cache=True, error_model="numpy")
def potential_energy(x: Any, u: Any, th: Any, rest: float, k: float, clear: float, m: float,
                     gx: float, gy: float, spr: Any, reach: Any) -> float:
    """Potential energy [J] of the chain at rest whose gradient is minus the forces of
    :func:`static_forces`: the links ½k·s² (s the elongation
    outside the clearance band), gravity −m g·u (u the rollers' displacements from a fixed
    placement, so that the sum stays small against its round-off) and the roller–tooth
    contacts ½k_c·δ² for δ > 0 (δ of the gap nearest by angle, as the static forces take
    it; the contact force is work-conjugate to δ, module docstring). It stands here, beside
    the static forces, so that numba's cache, kept per source file, recompiles it with them.

    Parameters
    ----------
    x : ndarray
        (N, 2) roller centres [m].
    u : ndarray
        (N, 2) their displacements from the placement [m].
    th : ndarray
        (n,) sprocket angles [rad].
    rest : float
        Rest length ℓ₀ of the links [m].
    k, clear, m, gx, gy : float
        Link stiffness [N/m], clearance [m], roller mass [kg], gravity [m/s²].
    spr, reach : ndarray
        The kernel's sprocket tables
        (:class:`chaindrive.linklevel.equilibrium.KernelTables`).

    Returns
    -------
    float
        The energy [J].
    """
    N = x.shape[0]
    n = spr.shape[1]
    e = 0.0
    for i in range(N):
        b = i + 1 if i < N - 1 else 0
        dx, dy = x[b, 0] - x[i, 0], x[b, 1] - x[i, 1]
        s = math.sqrt(dx * dx + dy * dy) - rest
        s -= min(max(s, -clear), clear)
        e += 0.5 * k * s * s - m * (gx * u[i, 0] + gy * u[i, 1])
        for q in range(n):
            px, py = x[i, 0] - spr[0, q], x[i, 1] - spr[1, q]
            if px * px + py * py < reach[q] * reach[q]:
                d = penetration(px, py, th[q], spr[2, q], spr[3, q], spr[4, q], spr[5, q],
                                spr[6, q], spr[7, q])[0]
                if d > 0.0:
                    e += 0.5 * spr[8, q] * d * d
                break
    return e


def compiled() -> bool:
    """Whether the kernel's compiled code is in numba's cache, so that a run starts at once;
    False when the first run will compile it (about 8 s on an idle core of the project
    machine — 8.3 s for a 0.01 s seed run against 0.33 s with the cache — and minutes on a
    busy one). Read from the cache index numba keeps beside this module (or under
    ``NUMBA_CACHE_DIR``); where numba's cache cannot be inspected, False (a message too many
    rather than a silent wait).

    Returns
    -------
    bool
        True when the cache of the step loop and of the static balance (its forces and
        its energy) is present.
    """
    import os

    try:
        dispatchers: tuple[Any, ...] = (run_kernel, static_forces, potential_energy)
        return all(os.path.exists(f._cache._cache_file._index_path)  # numba's cache index
                   for f in dispatchers)
    except AttributeError:
        return False
