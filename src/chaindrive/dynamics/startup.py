r"""Start-up transient of a chain contour from rest (seed 000 §3.1, Fig. 2; seed-notes §1–2).

Equations (x_i along the chain travel, span i joins mass i and i+1, e = B x)::

    M ẍ = −Bᵀ F + f_ext(t, ẋ),    F_i = s_i · [T_0 + c_i (e_i + d_i) + β c_i (ė_i + ḋ_i)],

s_i = 1 while the bracket is positive and 0 when the span goes slack (tension only: a
chain cannot push; it takes up again when the bracket turns positive); T_0 the
pre-tension from sag (equal in every span, so the contour is in equilibrium at rest);
d_i the polygonal elongation (:mod:`chaindrive.dynamics.excitation`, exact hinge law
δ(ψ) = R sin(ψ_w/z) − pψ_w/2π with the tooth phase ψ = 2π(x/p − s) following each
sprocket's own motion, offset so that d(0) = 0: the chain is assembled at rest);
β = 2ζ/ω_1 as in :mod:`chaindrive.dynamics.steady`. f_ext: the motor torque M_D(t, ω_1)/R̄_1
on the driver, −M_R,i(ω_i)/R̄_i on driven sprockets, R̄ = z p/2π (the chain moves z p per
revolution; x_i is the chain coordinate, so rigid rotation keeps every e_i = 0).

**Integrator** (exponential / zero-order-hold, Van Loan 1978, "Computing integrals
involving the matrix exponential", IEEE TAC 23): for each slack pattern s the linear part
ẏ = A_s y + E f (y = (x, ẋ)) is discretised exactly,

    expm([[A_s, E], [0, 0]] Δt) = [[Φ_s, Γ_s], [0, I]],   y_{k+1} = Φ_s y_k + Γ_s f_{k+½},

with f_{k+½} = (3 f_k − f_{k−1})/2 (second-order extrapolation of the explicit forces:
motor, resistance, pre-tension, polygonal). Φ_s, Γ_s are cached per pattern. The linear
stiff part is exact at any step (no stability limit from the kHz modes); a step whose end
state changes the slack pattern is redone once with the new pattern. Δt defaults to
1/(160 f_1) and 1/(160 f_z) at most (f_1 first elastic frequency, f_z tooth frequency).

**Compiled kernel.** The step loop of :func:`simulate_startup` runs in numba
(:mod:`chaindrive.dynamics.startup_kernel`) when the motor is a ConstantTorque, RampTorque
or KlossMotor — compiled ahead of time when that build is present and current
(:mod:`chaindrive.dynamics.kernel_build`), else just in time when numba is importable;
otherwise in NumPy. Both take the same steps and
agree to round-off (tests); note that with slack spans and polygonal excitation the
trajectory itself amplifies round-off (a 1e-13 change of T_0 moves the 24-sprocket speed
history by ~3 % pointwise; the two backends there differ as much pointwise, while their
peak forces agree to 1e-14), so equivalence is tested on small cases.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.linear import mode_roots
from chaindrive.dynamics.motors import ResistanceLaw
from chaindrive.dynamics.steady import span_incidence
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = ["PolygonalLaw", "StartupResult", "settling_time", "simulate_startup"]

TWO_PI = 2.0 * math.pi
#: Default steps per period of the first elastic mode (or tooth period): slack events and the
#: explicit forces need it (measured: 40 is unstable on the 24-sprocket example, 160 agrees
#: with a tight LSODA solution to 0.3 % in the peak force).
STEPS_PER_PERIOD = 160


# --- results -------------------------------------------------------------------------------

@dataclass(frozen=True, slots=True, eq=False)
class StartupResult:
    """Time histories of a start-up (seed 000 Fig. 2).

    times (N,) [s]; span_forces (N, n) [N]; speeds (N, n) sprocket speeds [rad/s];
    max_span_force (n,) F₁max per span [N]; settling_time [s] (:func:`settling_time`);
    k1 = Q/max F₁max (None without Q; seed 000 §3.6); steps taken; slack_steps: number of
    recorded samples with at least one slack span.
    """

    times: NDArray[np.float64]
    span_forces: NDArray[np.float64]
    speeds: NDArray[np.float64]
    max_span_force: NDArray[np.float64]
    settling_time: float
    k1: float | None
    steps: int
    slack_steps: int

    def to_dict(self, include_history: bool = False) -> dict[str, Any]:
        """JSON-ready dict; histories only with ``include_history``."""
        out: dict[str, Any] = {
            "max_span_force_n": self.max_span_force.tolist(),
            "max_force_n": float(self.max_span_force.max()),
            "settling_time_s": self.settling_time,
            "k1": self.k1,
            "final_speed_rad_s": self.speeds[-1].tolist(),
            "steps": self.steps,
            "slack_samples": self.slack_steps,
        }
        if include_history:
            out["time_s"] = self.times.tolist()
            out["span_force_n"] = self.span_forces.T.tolist()
            out["speed_rad_s"] = self.speeds.T.tolist()
        return out


def settling_time(times: NDArray[np.float64], forces: NDArray[np.float64],
                  tolerance: float = 0.05, tail: float = 0.1) -> float:
    """Time [s] after which every span force stays in its final band.

    The final state is the last ``tail`` fraction of the record: its mean F̄_i and
    half-range r_i (a steady ripple, e.g. polygonal). Band: |F_i − F̄_i| ≤ r_i +
    tolerance·max_j |F̄_j|. Returns the first time after the last excursion (0 if none).
    """
    k0 = int(len(times) * (1.0 - tail))
    end = forces[k0:]
    mean = end.mean(axis=0)
    band = 0.5 * (end.max(axis=0) - end.min(axis=0)) + tolerance * np.abs(mean).max()
    out = np.any(np.abs(forces - mean) > band, axis=1)
    idx = np.flatnonzero(out)
    return float(times[min(idx[-1] + 1, len(times) - 1)]) if idx.size else 0.0


# --- the nonlinear integrator ---------------------------------------------------------------

def _discretise(m: NDArray[np.float64], c_eff: NDArray[np.float64], beta: float,
                dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact zero-order-hold Φ, Γ of ẏ = A y + E f, K = Bᵀ diag(c_eff) B, C = βK.

    Built from the modes (classical damping): mode j moves over dt by
    [[1 − ω²S, h], [−ω²h, h']] on (q, q̇) and by (S, h)·u under a held modal force u, S the
    unit-step response and h = Ṡ (Rao §4.5); rigid modes [[1, dt], [0, 1]], (dt²/2, dt).
    Equal to Van Loan's block exponential expm([[A, E], [0, 0]] dt) (checked in the tests),
    ~50× cheaper for a 24-mass ring.
    """
    from chaindrive.dynamics.ring import modal_analysis

    modal = modal_analysis(m, c_eff)
    X, w = modal.shapes, modal.angular_frequencies_rad_s
    rigid = w <= 0
    ww = np.where(rigid, 1.0, w)
    s1, s2 = mode_roots(ww, 0.5 * beta * ww)
    e1, e2 = np.exp(s1 * dt), np.exp(s2 * dt)
    S = ((1.0 - (s2 * e1 - s1 * e2) / (s2 - s1)) / ww**2).real
    h = ((e1 - e2) / (s1 - s2)).real
    hd = ((s1 * e1 - s2 * e2) / (s1 - s2)).real
    p11, p12, p21, p22 = 1.0 - ww**2 * S, h, -(ww**2) * h, hd
    p11[rigid], p12[rigid], p21[rigid], p22[rigid] = 1.0, dt, 0.0, 1.0
    S[rigid], h[rigid] = 0.5 * dt * dt, dt
    XtM = X.T * m
    n = m.size
    Phi = np.empty((2 * n, 2 * n))
    Phi[:n, :n] = (X * p11) @ XtM
    Phi[:n, n:] = (X * p12) @ XtM
    Phi[n:, :n] = (X * p21) @ XtM
    Phi[n:, n:] = (X * p22) @ XtM
    Gam = np.vstack([(X * S) @ X.T, (X * h) @ X.T])
    return Phi, Gam


def _discretise_expm(m: NDArray[np.float64], c_eff: NDArray[np.float64], beta: float,
                     dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Reference Φ, Γ by Van Loan's block exponential (used by the tests)."""
    n = m.size
    B = span_incidence(n)
    K = B.T @ (c_eff[:, None] * B)
    Minv = 1.0 / m
    S = np.zeros((3 * n, 3 * n))
    S[:n, n:2 * n] = np.eye(n)
    S[n:2 * n, :n] = -Minv[:, None] * K
    S[n:2 * n, n:2 * n] = -beta * Minv[:, None] * K
    S[n:2 * n, 2 * n:] = np.diag(Minv)
    import scipy.linalg  # the reference form only (tests): not on the command line's path

    E = scipy.linalg.expm(S * dt)
    return E[:2 * n, :2 * n], E[:2 * n, 2 * n:]


@dataclass(frozen=True, slots=True)
class PolygonalLaw:
    """Data of the exact polygonal hinge law at both ends of every span (module docstring).

    pitch p [m]; teeth_start, teeth_end (n,); s_start, s_end (n,) path positions [pitches].
    """

    pitch: float
    teeth_start: NDArray[np.float64]
    teeth_end: NDArray[np.float64]
    s_start: NDArray[np.float64]
    s_end: NDArray[np.float64]


PolyData = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                 NDArray[np.float64], NDArray[np.intp], float, float]


def _polygonal_data(law: PolygonalLaw) -> PolyData:
    """Hinge-law data of the 2n span ends (start ends, then end ends): teeth z, radii
    R = p/(2 sin(π/z)) [m], path positions s [pitches], signs (−1 start, +1 end), the mass
    each end follows, k = 2π/p [1/m], p/2π [m]."""
    n = law.teeth_start.size
    nxt = (np.arange(n) + 1) % n
    z = np.concatenate([law.teeth_start, law.teeth_end]).astype(float)
    R = law.pitch / (2.0 * np.sin(np.pi / z))
    s = np.concatenate([law.s_start, law.s_end]).astype(float)
    sign = np.concatenate([-np.ones(n), np.ones(n)])
    idx = np.concatenate([np.arange(n), nxt])
    return z, R, s, sign, idx, TWO_PI / law.pitch, law.pitch / TWO_PI


def _polygonal_raw(data: PolyData, x: NDArray[np.float64], v: NDArray[np.float64]
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(d, ḋ) [m, m/s] of every span by the exact hinge law (seed-notes §1), d(0) kept."""
    z, R, s, sign, idx, k, lin = data
    n = x.size
    psi = k * x[idx] - TWO_PI * s
    psi = np.mod(psi + np.pi, TWO_PI) - np.pi
    dl = sign * (R * np.sin(psi / z) - lin * psi)
    dv = sign * (R / z * np.cos(psi / z) * k - 1.0) * v[idx]
    return dl[:n] + dl[n:], dv[:n] + dv[n:]


def _polygonal_offset(data: PolyData) -> NDArray[np.float64]:
    """d(0) [m]: the elongation at rest, removed (the chain is assembled at rest)."""
    n = data[0].size // 2
    return _polygonal_raw(data, np.zeros(n), np.zeros(n))[0]


def _polygonal_terms(law: PolygonalLaw) -> Callable[[NDArray[np.float64], NDArray[np.float64]],
                                                    tuple[NDArray[np.float64],
                                                          NDArray[np.float64]]]:
    """(x, v) → (d, ḋ) [m, m/s] of every span, exact hinge law, d(0) removed."""
    data = _polygonal_data(law)
    d0 = _polygonal_offset(data)

    def terms(x: NDArray[np.float64], v: NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        d, dd = _polygonal_raw(data, x, v)
        return d - d0, dd

    return terms


@dataclass(frozen=True, slots=True, eq=False)
class _Problem:
    """Checked inputs of :func:`simulate_startup` (SI units, see there)."""

    m: NDArray[np.float64]
    c: NDArray[np.float64]
    R: NDArray[np.float64]
    beta: float
    motor: Callable[[float, float], float]
    driver: int
    resistance: ResistanceLaw | None
    dt: float
    steps: int
    pretension: float
    polygonal: PolygonalLaw | None


class _Patterns:
    """Φ_s, Γ_s and diag Γ_vv of the slack patterns met so far, cached by pattern."""

    def __init__(self, p: _Problem) -> None:
        self.p = p
        self.cache: dict[bytes, tuple[NDArray[np.float64], NDArray[np.float64],
                                      NDArray[np.float64]]] = {}

    def __call__(self, mask: NDArray[np.bool_]) -> tuple[NDArray[np.float64],
                                                          NDArray[np.float64],
                                                          NDArray[np.float64]]:
        key = mask.tobytes()
        if key not in self.cache:
            n = self.p.m.size
            P, G = _discretise(self.p.m, self.p.c * mask, self.p.beta, self.p.dt)
            self.cache[key] = (P, G, G[n:].diagonal().copy())
        return self.cache[key]


def _run_numpy(p: _Problem) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The step loop in NumPy (fallback without numba): forces, speeds (steps+1, n), slack
    re-steps."""
    c, R, n, dt, T0 = p.c, p.R, p.m.size, p.dt, p.pretension
    nxt, prv = (np.arange(n) + 1) % n, (np.arange(n) - 1) % n
    bc = p.beta * c
    poly = _polygonal_terms(p.polygonal) if p.polygonal is not None else None
    driven = (np.arange(n) != p.driver).astype(float)
    Rd = R[p.driver]
    mats = _Patterns(p)

    def span_part(x: NDArray[np.float64], v: NDArray[np.float64],
                  mask: NDArray[np.bool_]) -> NDArray[np.float64]:
        """−Bᵀ of the pre-tension and polygonal span forces [N] (explicit part)."""
        span = np.where(mask, T0, 0.0)
        if poly is not None:
            d, dd = poly(x, v)
            span = span + mask * (c * d + bc * dd)
        return span - span[prv]

    def laws(t: float, v: NDArray[np.float64]) -> NDArray[np.float64]:
        """Motor and resistance forces [N] at the chain speeds v (each on its own mass)."""
        f = -driven * p.resistance(v / R) / R if p.resistance is not None else np.zeros(n)
        f[p.driver] += p.motor(t, v[p.driver] / Rd) / Rd
        return f

    def span_force(y: NDArray[np.float64]) -> NDArray[np.float64]:
        x, v = y[:n], y[n:]
        e, ed = x[nxt] - x, v[nxt] - v
        if poly is not None:
            d, dd = poly(x, v)
            e, ed = e + d, ed + dd
        return T0 + c * e + bc * ed

    def advance(y: NDArray[np.float64], t: float, fr: NDArray[np.float64],
                mask: NDArray[np.bool_]) -> NDArray[np.float64]:
        """One step; the speed laws linearly implicit on each mass's own speed."""
        Phi, Gam, gvv = mats(mask)
        v = y[n:]
        fl = laws(t + 0.5 * dt, v)
        hv = 1e-6 * (1.0 + np.abs(v))
        J = (laws(t + 0.5 * dt, v + hv) - fl) / hv                 # ∂f_i/∂v_i
        y_star = Phi @ y + Gam @ (fr + fl)
        df = J * (y_star[n:] - v) / np.maximum(1.0 - gvv * J, 0.1)
        return y_star + Gam @ df

    y, mask = np.zeros(2 * n), c > 0
    forces, speeds = np.empty((p.steps + 1, n)), np.empty((p.steps + 1, n))
    forces[0], speeds[0] = np.where(mask, T0, 0.0), 0.0
    fr_prev = span_part(y[:n], y[n:], mask)
    slack = 0
    for k in range(p.steps):
        t = k * dt
        fr = span_part(y[:n], y[n:], mask)
        y_new = advance(y, t, 1.5 * fr - 0.5 * fr_prev, mask)
        F = span_force(y_new)
        new_mask = (F > 0) & (c > 0)
        if not np.array_equal(new_mask, mask):
            mask = new_mask
            fr = span_part(y[:n], y[n:], mask)
            y_new = advance(y, t, fr, mask)
            F = span_force(y_new)
            slack += 1
        fr_prev, y = fr, y_new
        forces[k + 1] = np.maximum(F, 0.0) * mask
        speeds[k + 1] = y[n:] / R
    return forces, speeds, slack


def _kernel_laws(p: _Problem) -> tuple[Any, ...] | None:
    """Motor and resistance laws as the kernel's codes and arrays (None: not supported)."""
    from chaindrive.dynamics.kernel_codes import motor_code, resistance_code

    n = p.m.size
    mot, res = motor_code(p.motor), resistance_code(p.resistance, n)
    if mot is None or res is None:
        return None
    driven = (np.arange(n) != p.driver).astype(float)
    return (p.R, driven, p.driver, mot[0], mot[1], res[0], res[1], res[2], res[3])


def _compiled_runner(backend: Backend) -> Any:
    """The compiled step loop: the ahead-of-time module when built from the current source
    (:mod:`chaindrive.dynamics.kernel_build`; loads without numba), else numba's
    just-in-time ``run_kernel_flat`` (backend "jit" forces it), else None."""
    if backend != "jit":
        from chaindrive.dynamics.kernel_build import compiled_kernel

        runner = compiled_kernel()
        if runner is not None:
            return runner
    from chaindrive.dynamics.startup_kernel import HAVE_NUMBA, run_kernel_flat

    return run_kernel_flat if HAVE_NUMBA else None


def _run_compiled(p: _Problem, lw: tuple[Any, ...], runner: Any
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The step loop compiled (:mod:`chaindrive.dynamics.startup_kernel`); same output as
    :func:`_run_numpy`. Slack patterns new to the kernel are discretised here, then the
    kernel resumes from the step that met them."""
    c, n = p.c, p.m.size
    mats = _Patterns(p)
    masks = np.zeros((4, n), dtype=np.bool_)
    Phis, Gams, gvvs = np.empty((4, 2 * n, 2 * n)), np.empty((4, 2 * n, n)), np.empty((4, n))
    npat = 0

    def add(mask: NDArray[np.bool_]) -> None:
        nonlocal masks, Phis, Gams, gvvs, npat
        if npat == masks.shape[0]:
            masks, Phis, Gams, gvvs = (np.concatenate([a, np.empty_like(a)])
                                       for a in (masks, Phis, Gams, gvvs))
        masks[npat] = mask
        Phis[npat], Gams[npat], gvvs[npat] = mats(mask)
        npat += 1

    add(c > 0)
    f8 = np.ascontiguousarray
    if p.polygonal is not None:
        data = _polygonal_data(p.polygonal)
        pg = (*(f8(a, dtype=float) for a in data[:4]), f8(data[4], dtype=np.int64),
              float(data[5]), float(data[6]), f8(_polygonal_offset(data), dtype=float))
    else:
        e = np.zeros(2 * n)
        pg = (e, e, e, e, np.zeros(2 * n, dtype=np.int64), 0.0, 0.0, np.zeros(n))
    R, driven, driver, mkind, mp, rkind, rM, rwn, rbrk = lw
    laws = (f8(R, dtype=float), f8(driven, dtype=float), int(driver), int(mkind),
            f8(mp, dtype=float), int(rkind), f8(rM, dtype=float), f8(rwn, dtype=float),
            float(rbrk))
    forces, speeds = np.empty((p.steps + 1, n)), np.empty((p.steps + 1, n))
    forces[0], speeds[0] = np.where(c > 0, p.pretension, 0.0), 0.0
    y, need = np.zeros(2 * n), np.zeros(n, dtype=np.bool_)
    fr_prev = _kernel_span_part(p, masks[0])
    state = np.zeros(3, dtype=np.int64)
    cc, bc = f8(c, dtype=float), f8(p.beta * c, dtype=float)
    while runner(y, fr_prev, state, p.steps, p.dt, masks, Phis, Gams, gvvs, npat, cc, bc,
                 float(p.pretension), *laws, p.polygonal is not None, *pg, forces, speeds,
                 need) < p.steps:
        add(need.copy())
    return forces, speeds, int(state[1])


def _kernel_span_part(p: _Problem, mask: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Explicit span part at rest (d(0) = 0): −Bᵀ of the pre-tension [N]."""
    span = np.where(mask, p.pretension, 0.0)
    return span - np.roll(span, 1)


Backend = Literal["auto", "numba", "jit", "numpy"]


def simulate_startup(masses: ArrayLike, stiffness: ArrayLike, radii: ArrayLike, beta: float,
                     motor: Callable[[float, float], float], driver_index: int,
                     resistance: ResistanceLaw | None, *, duration: float = 1.0,
                     dt: float | None = None, pretension: float = 0.0,
                     polygonal: PolygonalLaw | None = None,
                     breaking_load: float | None = None,
                     backend: Backend = "auto") -> StartupResult:
    """Nonlinear start-up from rest (module docstring).

    masses (n,) [kg]; stiffness (n,) c_i [N/m] (span i joins mass i and i+1, closed ring;
    0: slack for good); radii (n,) R̄_i = z_i p/2π [m] converting torques and speeds;
    beta [s]; motor(t, ω) → torque [N·m] on mass ``driver_index``; resistance laws (None:
    none); duration [s]; dt [s] (None: 1/(160 f_1)); pretension T_0 [N]; polygonal hinge
    law (None: no polygonal excitation); breaking_load Q [N] → k1. backend: "numba" the
    compiled kernel (:mod:`chaindrive.dynamics.startup_kernel`: its ahead-of-time build
    when current, else numba's just-in-time compilation; needs a
    ConstantTorque/RampTorque/KlossMotor motor), "jit" the just-in-time one only, "numpy"
    the NumPy loop, "auto" the compiled kernel when it can, else NumPy. All give the same
    result to round-off.
    """
    m = np.asarray(masses, dtype=float)
    c = np.asarray(stiffness, dtype=float)
    R = np.asarray(radii, dtype=float)
    n = m.size
    if c.shape != (n,) or R.shape != (n,) or not 0 <= driver_index < n:
        raise DesignError("startup", "masses, stiffness and radii must have one entry per mass")
    if dt is None:
        dt = _default_step(m, c)
    p = _Problem(m, c, R, float(beta), motor, int(driver_index), resistance, float(dt),
                 max(1, math.ceil(duration / dt)), float(pretension), polygonal)
    forces, speeds, _ = _run(p, backend)
    times = np.arange(p.steps + 1) * p.dt
    fmax = forces.max(axis=0)
    k1 = breaking_load / float(fmax.max()) if breaking_load is not None and fmax.max() > 0 else None
    return StartupResult(times, forces, speeds, fmax, settling_time(times, forces), k1, p.steps,
                         int(np.count_nonzero((forces <= 0).any(axis=1))))


def _run(p: _Problem, backend: Backend) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Dispatch to the compiled kernel or the NumPy loop (see ``simulate_startup``)."""
    if backend not in ("auto", "numba", "jit", "numpy"):
        raise DesignError("backend", f"unknown start-up backend {backend!r}")
    lw = _kernel_laws(p) if backend != "numpy" else None
    runner = _compiled_runner(backend) if lw is not None else None
    if runner is not None:
        return _run_compiled(p, lw, runner)
    if backend in ("numba", "jit"):
        raise DesignError("backend", "numba is not installed or the motor/resistance law is "
                          "not one the compiled kernel knows (use backend='numpy')")
    return _run_numpy(p)


def _default_step(m: NDArray[np.float64], c: NDArray[np.float64]) -> float:
    """1/(160 f_1) [s], f_1 the first elastic natural frequency of the taut ring."""
    from chaindrive.dynamics.ring import modal_analysis

    modal = modal_analysis(m, np.maximum(c, 0.0))
    f1 = modal.first_elastic_frequency_hz
    return 1.0 / (STEPS_PER_PERIOD * f1) if f1 > 0 else 1e-3


# --- linear closed form -------------------------------------------------------------------
