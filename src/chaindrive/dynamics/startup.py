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

:func:`linear_transient` is the closed-form modal solution for a linear ring under forces
known in advance (no slack, no speed-dependent law): mode j is a damped oscillator with
ζ_j = βω_j/2 (classical damping, Rao §6.13); a constant force (step) or a soft-start ramp
gives closed-form modal step / ramp responses (Rao §4.5) evaluated on the whole time grid at
once (modes × times, "don't integrate what has a closed form"); sampled forces held over
each step are propagated by the exact zero-order-hold recursion of each mode in its
eigen-coordinates (a first-order complex scan per mode).

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
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._numeric import exp_poly_at
from chaindrive.dynamics.steady import span_incidence
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = [
    "ConstantTorque",
    "KlossMotor",
    "LinearTransient",
    "RampTorque",
    "ResistanceLaw",
    "StartupResult",
    "linear_transient",
    "settling_time",
    "simulate_startup",
]

TWO_PI = 2.0 * math.pi
ResistanceKind = Literal["constant", "linear", "quadratic"]
#: Default steps per period of the first elastic mode (or tooth period): slack events and the
#: explicit forces need it (measured: 40 is unstable on the 24-sprocket example, 160 agrees
#: with a tight LSODA solution to 0.3 % in the peak force).
STEPS_PER_PERIOD = 160


# --- motor and resistance laws ------------------------------------------------------------

@dataclass(frozen=True, slots=True)
class ConstantTorque:
    """Motor torque M_D = const [N·m] from t = 0 (step)."""

    torque: float

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at time t [s] and speed ω [rad/s]."""
        return self.torque


@dataclass(frozen=True, slots=True)
class RampTorque:
    """Soft start: M_D = M·min(1, t/t_ramp) [N·m]; ramp_time t_ramp [s]."""

    torque: float
    ramp_time: float

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at time t [s] and speed ω [rad/s]."""
        return self.torque * min(1.0, t / self.ramp_time) if self.ramp_time > 0 else self.torque


@dataclass(frozen=True, slots=True)
class KlossMotor:
    """Induction motor by the Kloss formula M = 2 M_k / (s/s_k + s_k/s) (e.g. Fischer,
    Elektrische Maschinen; Чиликин, Общий курс электропривода).

    rated_power P_r [W]; rated_speed ω_r [rad/s] (of the driver shaft); breakdown_ratio
    λ = M_k/M_r; critical_slip s_k. The rated slip follows from M(s_r) = M_r:
    s_r = s_k (λ − sqrt(λ² − 1)); synchronous speed ω_s = ω_r/(1 − s_r).
    """

    rated_power: float
    rated_speed: float
    breakdown_ratio: float = 2.5
    critical_slip: float = 0.25

    def __post_init__(self) -> None:
        if not (self.rated_power > 0 and self.rated_speed > 0):
            raise DesignError("motor", "rated power and speed must be positive")
        if not (self.breakdown_ratio > 1 and 0 < self.critical_slip < 1):
            raise DesignError("motor", "need breakdown_ratio > 1 and 0 < critical_slip < 1")

    @property
    def rated_torque(self) -> float:
        """M_r = P_r/ω_r [N·m]."""
        return self.rated_power / self.rated_speed

    @property
    def rated_slip(self) -> float:
        """s_r [–]."""
        lam = self.breakdown_ratio
        return self.critical_slip * (lam - math.sqrt(lam * lam - 1.0))

    @property
    def synchronous_speed(self) -> float:
        """ω_s [rad/s]."""
        return self.rated_speed / (1.0 - self.rated_slip)

    def __call__(self, t: float, omega: float) -> float:
        """Torque [N·m] at speed ω [rad/s]: 2 M_k s s_k / (s² + s_k²), s = 1 − ω/ω_s."""
        s = 1.0 - omega / self.synchronous_speed
        sk = self.critical_slip
        return 2.0 * self.breakdown_ratio * self.rated_torque * s * sk / (s * s + sk * sk)


@dataclass(frozen=True, slots=True, eq=False)
class ResistanceLaw:
    """Moments of resistance of the sprockets: M_R,i = M_i · φ(ω_i/ω_n,i) [N·m].

    kind : "constant" (φ = 1 once moving; below ``breakaway``·ω_n the torque rises
    linearly from 0, a regularised dry friction), "linear" (φ = ω/ω_n) or "quadratic"
    (φ = (ω/ω_n)|ω/ω_n|); torques (n,) M_i [N·m] at the nominal speeds (n,) ω_n,i [rad/s].
    """

    kind: ResistanceKind
    torques: NDArray[np.float64]
    nominal_speeds: NDArray[np.float64]
    breakaway: float = 0.01

    def __call__(self, omega: NDArray[np.float64]) -> NDArray[np.float64]:
        """M_R [N·m] at the speeds ω (n,) [rad/s]."""
        r = omega / self.nominal_speeds
        if self.kind == "linear":
            return self.torques * r
        if self.kind == "quadratic":
            return self.torques * r * np.abs(r)
        if self.kind == "constant":
            return self.torques * np.clip(r / self.breakaway, -1.0, 1.0)
        raise DesignError("resistance", f"unknown law {self.kind!r}")


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
    s1, s2 = _mode_roots(ww, 0.5 * beta * ww)
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

@dataclass(frozen=True, eq=False)
class LinearTransient:
    """Response of a linear ring: times (N,) [s], velocities (N, n) [m/s], span_forces
    (N, n) [N] (elastic + damping, no slack rule) — what a start-up check reads, computed
    at once — and displacements (N, n) [m], evaluated on first access."""

    times: NDArray[np.float64]
    velocities: NDArray[np.float64]
    span_forces: NDArray[np.float64]
    displacements_source: Callable[[], NDArray[np.float64]] = field(repr=False)

    @cached_property
    def displacements(self) -> NDArray[np.float64]:
        """x (N, n) [m]."""
        return self.displacements_source()


def _mode_roots(omega: NDArray[np.float64], zeta: NDArray[np.float64]
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
    s1, s2 = _mode_roots(w, zeta)
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
    s1, s2 = _mode_roots(np.where(rigid, 1.0, omega), zeta)
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

    masses (n,) [kg]; stiffness (n,) [N/m]; beta [s]; times (N,) equally spaced from 0 [s];
    forces : (n,) constant — a step at t = 0 (or, with ``ramp_time`` t_r > 0 [s], a ramp
    f·min(t/t_r, 1), the soft start) in closed form: modal step/ramp responses on the whole
    grid at once — or (N, n) sampled, held constant over each step (exact zero-order-hold
    modal recursion, :func:`_zoh_modal`) [N].
    """
    from chaindrive.dynamics.ring import modal_analysis

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
