r"""Start-up transient from rest: the nonlinear time integration of a drive model with
tension-only chain spans [MultimassChainDrives, §3.1, Fig. 2].

Equations, for coordinates q of any drive model (the whole drive of
:mod:`chaindrive.dynamics.model.build`, or any :class:`StartupProblem` built by hand)::

    M q̈ + C_lin q̇ + K_lin q = −Bᵀ F + Q_laws(t, q̇),
    F_i = s_i · [T₀,i + c_i (e_i + d_i) + d_s,i (ė_i + ḋ_i)],   e = B q,

s_i = 1 while the bracket is positive and 0 when the span goes slack (a chain cannot push; it
takes up again when the bracket turns positive); T₀ the pre-tension from sag; d_i the
polygonal elongation (:mod:`chaindrive.dynamics.excitation`, exact hinge law δ(ψ) = R sin(ψ/z)
− pψ/2π with the tooth phase ψ = 2π(x/p − s) following each sprocket's own chain travel x,
offset so that d(0) = 0: the chain is assembled at rest). Q_laws: the motor torque g·η·T(t, ω)
on the motor's coordinate, the machines' moments −g·M·φ(ω/ω_n)/η on theirs (g the gain of a
coordinate to the node's forward speed, η the efficiencies of the gear stages between it and
its sprocket; :mod:`chaindrive.dynamics.motors`).

**Integrator** (exponential / zero-order-hold [VanLoan1978]): for each slack pattern s the
linear part ẏ = A_s y + E f (y = (q, q̇)) is discretised exactly,
expm([[A_s, E], [0, 0]] Δt) = [[Φ_s, Γ_s], [0, I]] (:mod:`chaindrive.dynamics.transient.zoh`), and
y_{k+1} = Φ_s y_k + Γ_s f_{k+½}, f_{k+½} = (3 f_k − f_{k−1})/2 for the explicit span forces
(pre-tension, polygonal). Φ_s, Γ_s are cached per pattern. The linear part is exact at any
step (no stability limit from stiff modes); a step whose end state changes the slack pattern
is redone once with the new pattern.

**Laws** (motor and machines, on the coordinates L). They act on the *mean* speed of their
coordinate over the step, w = (q_{k+1} − q_k)/Δt, not on the speed sampled at the step's
end: a mode far above the step (a light rotor on a stiff shaft, 10⁹ rad/s against a step of
10⁻⁵ s) is sampled by the step as an aliased, undamped oscillation that a law fed with the
sampled speed pumps without bound (a torque rising with the speed is a negative damper),
while its mean over the step is smaller by ωΔt. The held law force is linearly implicit on w: with
f(w_k) held the step gives mean speeds w*, a force increment Δf on L changes them by
G Δf (G = Γ_s[q_L, L]/Δt, fixed per pattern), and the linearised law asks
Δf = J (w_{k+1} − w_k), J_i = ∂f_i/∂w_i, so (I − diag(J) G) Δf = J (w* − w_k): the linearly
implicit Euler step on the laws [HairerWanner1996, §IV.7] over the exact transition of the
linear part. Solved as one system over L, not coordinate by coordinate: the law coordinates
of a stiff train respond together (G has off-diagonal terms as large as its diagonal), and
a per-coordinate correction then adds up to an amplification — a whole-drive start-up at the
lowest allowed driver speed (1 rpm) reached 2.5·10³⁰³ N that way. Stability: a dissipative
law (J ≤ 0: every machine's moment, the stable branch of a motor curve) is a damper taken
implicitly, w' − w = (w* − w)/(1 + |J| g) for one coordinate of response g > 0, bounded at
any step. The rising branch of a motor curve (J > 0, below the breakdown speed) is a negative
damper: taken linearly implicit while J g ≤ 1/2 (the step's own increment amplified by
1/(1 − J g) ≤ 2). Steeper, the linearisation does not hold over the step (a motor of little
inertia runs through its whole curve within one step): a Kloss motor is then taken by
backward Euler on its own curve, w' − a = g (f(w') − f(w)) — a cubic in the slip — at the
root first met from w toward the step's speed a, the speed the motor reaches before any
other equilibrium (:func:`chaindrive.dynamics.transient.kernel_codes.kloss_end_speed`); any
other law with J clipped to 1/(2g), the rest of its slope explicit.

A "linear" machine law is linear in w, f = −c w: its row of that system is the same at every
step, so it is solved once per slack pattern — taken into the pattern's transition
(:func:`implicit_dampers`) — and the system of a step holds the motor and the nonlinear
laws only (one coordinate instead of twelve on the 24-sprocket example). The same equations;
the response G the motor's clipping and backward-Euler step see is then the transition's
with the machines' dampers in it (before, the response without them, the machines'
increments from the linearised solve beside it): the bundled examples' peak span forces
agree to 10⁻⁹ either way.

**Compiled kernel.** The step loop runs in numba (:mod:`chaindrive.dynamics.transient.kernel`)
when the motor is a ConstantTorque, RampTorque or KlossMotor — compiled ahead of time when
that build is present and current (:mod:`chaindrive.dynamics.transient.kernel_build`), else just in
time; otherwise in NumPy. Both take the same steps and agree to round-off on small cases
(with slack spans and polygonal excitation the trajectory itself amplifies round-off: peak
forces are the robust output).

**Bounded work.** The state is kept every ``record_every`` steps (at most
:data:`MAX_RECORDS` samples) and the largest span forces at every step, so memory does not
grow with the steps; :func:`work_estimate` counts the floating-point operations a run takes
and the callers refuse a run beyond :data:`WORK_BUDGET`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from chaindrive.dynamics.model.assembly import LinearModel
from chaindrive.dynamics.motors import KlossMotor, ResistanceLaw
from chaindrive.dynamics.transient.kernel_codes import (
    RESISTANCE_KINDS,
    kloss_end_speed,
    motor_code,
)
from chaindrive.dynamics.transient.zoh import zoh_matrices
from chaindrive.errors import DesignError
from chaindrive.units import TWO_PI

__all__ = ["MAX_RECORDS", "STEPS_PER_PERIOD", "WORK_BUDGET", "PolygonalLaw", "StartupProblem",
           "StartupResult", "runup_time", "settling_time", "solve_startup", "startup_progress",
           "transient_times", "work_estimate"]

FloatArray = NDArray[np.float64]
#: Default steps per period of the reference mode (or tooth period): slack events and the
#: explicit forces need it (measured: 40 is unstable on the 24-sprocket example, 160 agrees
#: with a tight LSODA solution to 0.3 % in the peak force).
STEPS_PER_PERIOD = 160
#: Most samples of a history kept (the largest span forces are tracked at every step).
MAX_RECORDS = 20_000
#: Most floating-point operations a start-up may take (:func:`work_estimate`, a step's own
#: cost included): about 4 s on the project machine (a step ran at about 1.5e9 of them a
#: second, small model or large); a 30 s start-up of the eight-sprocket example (4.3e9, 2.6 s)
#: stays within it, a 60 s one does not.
WORK_BUDGET = 6.0e9
#: What a step costs besides its matrix products, in the same operations [-]: the polygonal law
#: at every span end, the slack test and the records. Measured on the project machine: the
#: 4-coordinate model of the two-sprocket example at 30 000 rpm ran 20.8 million steps in
#: 19 s (0.9 µs a step, where its products count 192 operations), so the budget, counted in
#: products alone, let a small model run past a minute on a loaded machine; a 16-coordinate
#: model's step (3 072 operations of products) took about 2 µs.
STEP_OVERHEAD = 1200.0
Backend = Literal["auto", "numba", "jit", "numpy"]
#: Progress reports per start-up when a callback listens (:func:`startup_progress`).
PROGRESS_REPORTS = 200
_PROGRESS: ContextVar[Callable[[int, int], None] | None] = ContextVar(
    "chaindrive_startup_progress", default=None)


@contextmanager
def startup_progress(callback: Callable[[int, int], None]) -> Iterator[None]:
    """Within the context, every start-up integrated in this thread calls
    ``callback(steps done, steps in all)`` about :data:`PROGRESS_REPORTS` times (the
    compiled kernel then runs in as many pieces; the result is the same to the bit: the
    kernel resumes from its state).

    Parameters
    ----------
    callback : callable
        Called with (steps done, steps in all) [-].

    Yields
    ------
    None
    """
    token = _PROGRESS.set(callback)
    try:
        yield
    finally:
        _PROGRESS.reset(token)


# --- results -------------------------------------------------------------------------------

@dataclass(frozen=True, slots=True, eq=False)
class StartupResult:
    """Time histories of a start-up [MultimassChainDrives, Fig. 2].

    Parameters
    ----------
    times : ndarray
        (R,) recorded times [s].
    span_forces : ndarray
        (R, S) span forces of one contour [N].
    speeds : ndarray
        (R, n) sprocket speeds [rad/s].
    max_span_force : ndarray
        (S,) F₁max per span over every step [N].
    settling_time : float
        Run-up and decay together [s]: the later of the run-up time and the time after
        which every span force stays in its final band (:func:`transient_times`); nan when
        the record ends before (not settled within the simulated time).
    k1 : float or None
        k₁ = Q / max F₁max [-] ([MultimassChainDrives, §3.6]; None without Q).
    steps : int
        Steps taken [-].
    slack_steps : int
        Recorded samples with a slack span [-].
    runup_time : float
        Time to reach the working speed [s] (:func:`runup_time`).
    decay_time : float
        Settling after the run-up [s] (settling_time − runup_time; 0 when the forces are
        in their final band by the time the driver is at speed).
    rotor_names : tuple of str
        The rotors of the trains.
    rotor_speeds : ndarray
        (R, r) their speeds [rad/s].
    states : ndarray or None
        (R, 2N) the coordinates and their rates [m, rad; m/s, rad/s], or None.
    time_step : float
        The integration step [s].

    Attributes
    ----------
    settled : bool
        The driver reached its speed and the forces settled within the record.
    slack_fraction : float
        Share of the recorded samples in which at least one span is slack [-].
    """

    times: FloatArray
    span_forces: FloatArray
    speeds: FloatArray
    max_span_force: FloatArray
    settling_time: float
    k1: float | None
    steps: int
    slack_steps: int
    runup_time: float = math.nan
    decay_time: float = math.nan
    rotor_names: tuple[str, ...] = ()
    rotor_speeds: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))
    states: FloatArray | None = None
    time_step: float = math.nan

    @property
    def settled(self) -> bool:
        """The driver reached its speed and the forces settled within the record."""
        return not (math.isnan(self.runup_time) or math.isnan(self.settling_time))

    @property
    def slack_fraction(self) -> float:
        """Share of the recorded samples with a slack span [-] (0 for an empty record)."""
        return self.slack_steps / len(self.times) if len(self.times) else 0.0

    def to_dict(self, include_history: bool = False) -> dict[str, Any]:
        """JSON-ready dict.

        Parameters
        ----------
        include_history : bool
            True adds the time histories (times, span forces, speeds).

        Returns
        -------
        dict
            Peaks, k₁ and times in SI (with the unit in the key).
        """
        out: dict[str, Any] = {
            "max_span_force_n": self.max_span_force.tolist(),
            "max_force_n": float(self.max_span_force.max()),
            "settled": self.settled,
            "settling_time_s": None if math.isnan(self.settling_time) else self.settling_time,
            "simulated_time_s": float(self.times[-1]) if len(self.times) else 0.0,
            "runup_time_s": None if math.isnan(self.runup_time) else self.runup_time,
            "decay_time_s": None if math.isnan(self.decay_time) else self.decay_time,
            "k1": self.k1,
            "final_speed_rad_s": self.speeds[-1].tolist(),
            "final_rotor_speed_rad_s": dict(zip(
                self.rotor_names, self.rotor_speeds[-1].tolist() if self.rotor_names else [],
                strict=True)),
            "steps": self.steps,
            "time_step_s": None if math.isnan(self.time_step) else self.time_step,
            "slack_samples": self.slack_steps,
            "slack_fraction": self.slack_fraction,
        }
        if include_history:
            out["time_s"] = self.times.tolist()
            out["span_force_n"] = self.span_forces.T.tolist()
            out["speed_rad_s"] = self.speeds.T.tolist()
        return out


def settling_time(times: FloatArray, forces: FloatArray, tolerance: float = 0.05,
                  tail: float = 0.1, period: float = 0.0) -> float:
    """Time [s] after which every span force stays in its final band and its envelope is
    the final one; nan when the record ends before that.

    The final state is the last ``tail`` fraction of the record, or two periods of the
    steady ripple if they are longer (``period``, the tooth period); its mid-range
    F̃_i = (max + min)/2 and half-range r_i (a steady ripple, e.g. polygonal), so that every
    sample of the final state lies in the band, whatever the shape of the ripple (a span that
    goes slack clips it at zero). With δ = tolerance·max_j |F̄_j| (F̄_j the mean of span j
    over the final state) the record has settled after

    * the last excursion from the band |F_i − F̃_i| ≤ r_i + δ (a transient that decays into
      the ripple), and
    * the end of the last window, as long as the final state and sliding by a quarter of it,
      whose largest or smallest force of some span stays more than δ inside the final
      band (a ripple still growing toward its final amplitude: a resonance approached as
      the speed creeps up, a beat that has not died out).

    When that time reaches the final state, or the final state would take more than half of
    the record, the record has not settled: nan.

    Parameters
    ----------
    times : ndarray
        (R,) times [s].
    forces : ndarray
        (R, S) span forces [N].
    tolerance : float
        Band beyond the ripple as a fraction of the largest mean force [-].
    tail : float
        Fraction of the record taken as the final state [-].
    period : float
        Period of the steady ripple [s] (the tooth period; 0: none).

    Returns
    -------
    float
        The settling time [s] (0 if the record starts settled), nan if it has not settled
        before its final state.
    """
    k0 = min(int(len(times) * (1.0 - tail)),
             int(np.searchsorted(times, times[-1] - 2.0 * period, side="right")))
    if k0 < len(times) // 2 or times[-1] <= times[0]:
        return math.nan
    end = forces[k0:]
    top, bottom = end.max(axis=0), end.min(axis=0)
    middle = 0.5 * (top + bottom)
    delta = tolerance * np.abs(end.mean(axis=0)).max()
    out = np.any(np.abs(forces - middle) > 0.5 * (top - bottom) + delta, axis=1)
    idx = np.flatnonzero(out)
    settle = float(times[min(idx[-1] + 1, len(times) - 1)]) if idx.size else 0.0
    width = len(times) - k0  # k0 ≥ width: every window lies before the final state
    for start in {*range(0, k0 - width + 1, max(1, width // 4)), k0 - width}:
        window = forces[start:start + width]
        if np.any(window.max(axis=0) < top - delta) or np.any(
                window.min(axis=0) > bottom + delta):
            settle = max(settle, float(times[start + width]))
    return settle if settle < times[k0] else math.nan


def transient_times(times: FloatArray, forces: FloatArray, driver_speed: FloatArray,
                    period: float) -> tuple[float, float, float]:
    """Settling, run-up and decay times of a start-up record [s].

    The transient is over when the driver is at speed (:func:`runup_time`) and the span
    forces have settled (:func:`settling_time`): settling = max of the two, decay = settling
    − run-up. nan where the record ends first.

    Parameters
    ----------
    times : ndarray
        (R,) [s].
    forces : ndarray
        (R, S) span forces [N].
    driver_speed : ndarray
        (R,) forward speed of the driver [rad/s].
    period : float
        Period of the steady ripple [s] (the tooth period; 0: none).

    Returns
    -------
    tuple of float
        (settling, run-up, decay) [s].
    """
    settle = settling_time(times, forces, period=period)
    runup = runup_time(times, driver_speed, period=period)
    if math.isnan(runup) or math.isnan(settle):
        return math.nan, runup, math.nan
    settle = max(settle, runup)
    return settle, runup, settle - runup


def runup_time(times: FloatArray, speed: FloatArray, fraction: float = 0.95,
               tail: float = 0.1, period: float = 0.0, level: float = 0.01) -> float:
    """Time [s] from which a speed history stays at or above ``fraction`` of its final speed
    (averaged over one ripple period, centred, so the ripple does not count; a driver that
    bounces against a slack chain has not run up while it falls back below); nan when the
    record ends before the speed has levelled off.

    The final speed is the mean over the last ``tail`` of the record, or two ripple periods
    if they are longer. It has levelled off when the means of the two halves of that final
    state differ by at most ``level`` of it (each half holds at least one ripple period, so
    the polygonal ripple averages out); a record that ends while the driver still
    accelerates — or whose final state would take more than half of it — has no run-up time.

    Parameters
    ----------
    times : ndarray
        (R,) [s].
    speed : ndarray
        (R,) forward speed [rad/s].
    fraction : float
        [-].
    tail : float
        [-].
    period : float
        Period of the steady ripple [s] (the tooth period; 0: none).
    level : float
        Largest change of the mean speed across the final state, as a fraction of it [-].

    Returns
    -------
    float
        [s].
    """
    k0 = min(int(len(times) * (1.0 - tail)),
             int(np.searchsorted(times, times[-1] - 2.0 * period, side="right")))
    if k0 < len(times) // 2 or len(times) - k0 < 2:
        return math.nan
    end = speed[k0:]
    final = float(end.mean())
    half = end.size // 2
    if final <= 0 or abs(float(end[half:].mean()) - float(end[:half].mean())) > level * final:
        return math.nan
    smooth = speed
    if period > 0 and len(times) > 1:
        width = round(period / float(np.mean(np.diff(times))))
        if width > 1:
            smooth = np.convolve(speed, np.ones(width) / width, mode="same")
            smooth[-(width // 2 + 1):] = speed[-(width // 2 + 1):]  # no zeros past the end
    below = np.flatnonzero(smooth < fraction * final)
    if not below.size:
        return float(times[0])
    return float(times[below[-1] + 1]) if below[-1] + 1 < len(times) else math.nan


# --- the problem ---------------------------------------------------------------------------

@dataclass(frozen=True, slots=True)
class PolygonalLaw:
    """Data of the exact polygonal hinge law at both ends of every span (module docstring).

    Parameters
    ----------
    pitch : float
        Chain pitch p [m].
    teeth_start, teeth_end : ndarray
        (S,) teeth of the sprocket at the start and at the end of each span [-].
    s_start, s_end : ndarray
        (S,) path positions of the span's tangent points [pitches].

    References
    ----------
    [ChainNonUniformity].
    """

    pitch: float
    teeth_start: FloatArray
    teeth_end: FloatArray
    s_start: FloatArray
    s_end: FloatArray


@dataclass(frozen=True, slots=True, eq=False)
class StartupProblem:
    """Checked inputs of :func:`solve_startup` (SI units; module docstring). The coordinates q
    are chain travels [m] or rotations [rad]; matrices are in the matching units.

    Parameters
    ----------
    linear : LinearModel
        M, C, K of the elements that never go slack, the spans' incidence, stiffnesses,
        dampers and which spans carry tension only
        (:class:`~chaindrive.dynamics.model.assembly.LinearModel`); read through the
        problem's properties of the same names (``mass``, ``span_stiffness``, …).
    pretension : ndarray
        (S,) pre-tension T₀ at rest [N].
    motor : tuple or None
        (coordinate, gain, efficiency, law(t, ω) [N·m]) of the motor, or None.
    load_coordinate : ndarray of int
        (L,) indices of the coordinates the moments of resistance act on [-].
    load_gain : ndarray
        (L,) factor from a coordinate's rate to its machine's speed [rad/s per coordinate
        rate] (1/R for a chain travel).
    load_efficiency : ndarray
        (L,) efficiency of the path to each machine [-].
    load_torque : ndarray
        (L,) moments of resistance at the nominal speeds [N·m].
    load_speed : ndarray
        (L,) nominal speeds ω_n [rad/s].
    load_kind : tuple of str
        (L,) ``"constant"``, ``"linear"`` or ``"quadratic"``.
    breakaway : float
        Fraction of ω_n below which a constant moment is ramped from 0 [-].
    polygonal : PolygonalLaw or None
        The polygonal excitation (None: none).
    travel_coordinate : ndarray of int
        (n,) index of the coordinate of each sprocket's chain travel [-].
    travel_gain : ndarray
        (n,) x_i = travel_gain_i · q[travel_coordinate_i] [m per coordinate unit] (span i
        leaves sprocket i and runs onto i+1).
    dt : float
        Time step [s].
    steps : int
        Number of steps [-].
    record_every : int
        Steps between recorded samples [-].
    scale : float
        The span forces reported are F/scale [-] (m contours: scale m).
    """

    linear: LinearModel
    pretension: FloatArray
    motor: tuple[int, float, float, Callable[[float, float], float]] | None
    load_coordinate: NDArray[np.intp]
    load_gain: FloatArray
    load_efficiency: FloatArray
    load_torque: FloatArray
    load_speed: FloatArray
    load_kind: tuple[str, ...]
    breakaway: float
    polygonal: PolygonalLaw | None
    travel_coordinate: NDArray[np.intp]
    travel_gain: FloatArray
    dt: float
    steps: int
    record_every: int = 1
    scale: float = 1.0

    @property
    def size(self) -> int:
        """N coordinates."""
        return self.linear.size

    @property
    def mass(self) -> FloatArray:
        """(N, N) mass matrix [kg or kg·m²] (the linear model's)."""
        return self.linear.mass

    @property
    def stiffness_linear(self) -> FloatArray:
        """(N, N) stiffness of the elements that never go slack [N/m or N·m/rad]."""
        return self.linear.stiffness_linear

    @property
    def damping_linear(self) -> FloatArray:
        """(N, N) their damping [N·s/m or N·m·s/rad]."""
        return self.linear.damping_linear

    @property
    def span_incidence(self) -> FloatArray:
        """(S, N) span elongation per coordinate [-]."""
        return self.linear.span_incidence

    @property
    def span_stiffness(self) -> FloatArray:
        """(S,) span stiffnesses [N/m]."""
        return self.linear.span_stiffness

    @property
    def span_damping(self) -> FloatArray:
        """(S,) span dampers [N·s/m]."""
        return self.linear.span_damping

    @property
    def span_tension_only(self) -> NDArray[np.bool_]:
        """(S,) True for a span that carries tension only (goes slack)."""
        return self.linear.span_tension_only


def work_estimate(size: int, steps: int, patterns: int = 4) -> float:
    """Floating-point operations of a start-up [-]: two (2N)×(2N)/(2N)×N products and
    :data:`STEP_OVERHEAD` per step, and a (3N)³ matrix exponential (about 20 products) per
    slack pattern.

    Parameters
    ----------
    size : int
        Number of coordinates N [-].
    steps : int
        Number of time steps [-].
    patterns : int
        Slack patterns expected [-].

    Returns
    -------
    float
        The operation count [-].

    References
    ----------
    [Higham2005] (cost of the scaling-and-squaring exponential).
    """
    return (steps * (2.0 * (2 * size) ** 2 * 1.5 + STEP_OVERHEAD)
            + patterns * 20.0 * (3 * size) ** 3)


PolyData = tuple[FloatArray, FloatArray, FloatArray, FloatArray, NDArray[np.intp], FloatArray,
                 float, float]


def _polygonal_data(p: StartupProblem) -> PolyData:
    """Hinge-law data of the 2S span ends (start ends, then end ends): teeth z, radii
    R = p/(2 sin(π/z)) [m], path positions s [pitches], signs (−1 start, +1 end), the
    coordinate and travel gain each end follows, k = 2π/p [1/m], p/2π [m]."""
    law = p.polygonal
    assert law is not None
    n = law.teeth_start.size
    nxt = (np.arange(n) + 1) % n
    z = np.concatenate([law.teeth_start, law.teeth_end]).astype(float)
    R = law.pitch / (2.0 * np.sin(np.pi / z))
    s = np.concatenate([law.s_start, law.s_end]).astype(float)
    sign = np.concatenate([-np.ones(n), np.ones(n)])
    sprocket = np.concatenate([np.arange(n), nxt])
    return (z, R, s, sign, p.travel_coordinate[sprocket], p.travel_gain[sprocket],
            TWO_PI / law.pitch, law.pitch / TWO_PI)


def _polygonal_raw(data: PolyData, y: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(d, ḋ) [m, m/s] of every span at the state y by the exact hinge law, d(0) kept."""
    z, R, s, sign, idx, gain, k, lin = data
    n2 = z.size
    N = y.size // 2
    x, v = gain * y[idx], gain * y[N + idx]
    psi = k * x - TWO_PI * s
    psi = np.mod(psi + np.pi, TWO_PI) - np.pi
    dl = sign * (R * np.sin(psi / z) - lin * psi)
    dv = sign * (R / z * np.cos(psi / z) * k - 1.0) * v
    return dl[:n2 // 2] + dl[n2 // 2:], dv[:n2 // 2] + dv[n2 // 2:]


#: The linear machine laws taken into the transition: their coordinates (distinct) and the
#: summed slopes c = g² M/(η ω_n) of the laws on each [N·m·s/rad or N·s/m].
Dampers = tuple[NDArray[np.intp], FloatArray]


def _linear_laws(p: StartupProblem) -> tuple[StartupProblem, Dampers]:
    """The problem without its "linear" machine laws, and those laws as dampers for
    :class:`_Patterns` to take into each pattern's transition.

    A linear law's force on its coordinate is −g M φ/η, φ = g w/ω_n
    (:class:`~chaindrive.dynamics.motors.ResistanceLaw`), w the mean speed over the step:
    linear in w, so the linearly implicit step on it (module docstring, *Laws*) is exact
    in it, f = −c w_{k+1}, c = g² M/(η ω_n), and needs no law evaluation or linear solve at
    each step.

    Parameters
    ----------
    p : StartupProblem
        The problem.

    Returns
    -------
    tuple
        The problem with the other laws only (``p`` itself when it has no linear one), and
        the dampers (coordinates, c) [-, N·m·s/rad or N·s/m].
    """
    linear = [j for j, kind in enumerate(p.load_kind) if kind == "linear"]
    if not linear:
        return p, (np.zeros(0, dtype=np.intp), np.zeros(0))
    slope: dict[int, float] = {}
    for j in linear:
        k = int(p.load_coordinate[j])
        slope[k] = slope.get(k, 0.0) + float(p.load_gain[j] ** 2 * p.load_torque[j]
                                             / (p.load_efficiency[j] * p.load_speed[j]))
    keep = [j for j, kind in enumerate(p.load_kind) if kind != "linear"]
    rest = replace(p, load_coordinate=p.load_coordinate[keep], load_gain=p.load_gain[keep],
                   load_efficiency=p.load_efficiency[keep], load_torque=p.load_torque[keep],
                   load_speed=p.load_speed[keep], load_kind=tuple(p.load_kind[j] for j in keep))
    return rest, (np.array(sorted(slope), dtype=np.intp),
                  np.array([slope[k] for k in sorted(slope)]))


def implicit_dampers(Phi: FloatArray, Gam: FloatArray, coordinates: NDArray[np.intp],
                     slope: FloatArray, dt: float) -> tuple[FloatArray, FloatArray]:
    """The step's transition with dampers acting on the mean speeds of their coordinates
    over the step taken in: the (Φ', Γ') of y_{k+1} = Φ' y_k + Γ' f for the other forces f.

    With f_d = −c (q_{k+1} − q_k)/Δt on the coordinates d (P y = q_d),
    y_{k+1} = Φ y_k + Γ_d f_d + Γ f, so H y_{k+1} = (Φ + U P) y_k + Γ f with
    U = Γ_d diag(c)/Δt, H = I + U P: Φ' = H⁻¹ (Φ + U P), Γ' = H⁻¹ Γ. The same equations the
    law system of every step solved for these laws (module docstring, *Laws*), solved once
    per slack pattern instead, and in the same small system: by the Woodbury identity
    H⁻¹ X = X − U (I + P U)⁻¹ P X [Golub2013, §2.1], I + P U = I + Γ[q_d, d] diag(c)/Δt
    (D × D, the law system's own matrix). An LU factorisation of the (2N)² H itself is not
    used: its rows of a light node on a stiff shaft are 10⁵ times the others, and the
    rounding it left made such nodes ring by 1 % of their speed (10⁻⁴ % with this form).

    Parameters
    ----------
    Phi : ndarray
        (2N, 2N) transition [-].
    Gam : ndarray
        (2N, N) response to held forces [s²/kg-like units].
    coordinates : ndarray of int
        (D,) the damped coordinates, distinct [-].
    slope : ndarray
        (D,) their dampers c [N·m·s/rad or N·s/m].
    dt : float
        Δt [s].

    Returns
    -------
    tuple of ndarray
        Φ' (2N, 2N), Γ' (2N, N).

    References
    ----------
    [HairerWanner1996, §IV.7] (linearly implicit methods); [VanLoan1978]; [Golub2013].
    """
    if not coordinates.size:
        return Phi, Gam
    U = Gam[:, coordinates] * (slope / dt)[None, :]
    small = np.eye(coordinates.size) + U[coordinates]
    X = Phi.copy()
    X[:, coordinates] += U
    return (np.asarray(X - U @ np.linalg.solve(small, X[coordinates]), dtype=np.float64),
            np.asarray(Gam - U @ np.linalg.solve(small, Gam[coordinates]), dtype=np.float64))


class _Patterns:
    """Φ_s, Γ_s of the slack patterns met so far (the linear laws' dampers taken in,
    :func:`implicit_dampers`), cached by pattern."""

    def __init__(self, p: StartupProblem, dampers: Dampers) -> None:
        self.p = p
        self.dampers = dampers
        self.cache: dict[bytes, tuple[FloatArray, FloatArray]] = {}

    def __call__(self, mask: NDArray[np.bool_]) -> tuple[FloatArray, FloatArray]:
        key = mask.tobytes()
        if key not in self.cache:
            p = self.p
            lin = p.linear
            P, G = zoh_matrices(lin.mass, lin.stiffness(mask), lin.damping(mask), p.dt)
            self.cache[key] = implicit_dampers(P, G, *self.dampers, p.dt)
        return self.cache[key]


def _law_arrays(p: StartupProblem) -> tuple[Any, ...] | None:
    """The laws as the kernel's codes and arrays (None: a motor law it does not know)."""
    if p.motor is None:
        mk, mgain, meff, mkind, mp = -1, 0.0, 1.0, 0, np.zeros(3)
    else:
        code = motor_code(p.motor[3])
        if code is None:
            return None
        mk, mgain, meff = int(p.motor[0]), float(p.motor[1]), float(p.motor[2])
        mkind, mp = code
    kinds = np.array([RESISTANCE_KINDS[k] for k in p.load_kind], dtype=np.int64)
    f8 = np.ascontiguousarray
    return (mk, mgain, meff, int(mkind), f8(mp, dtype=float),
            f8(p.load_coordinate, dtype=np.int64), f8(p.load_gain, dtype=float),
            f8(p.load_efficiency, dtype=float), kinds, f8(p.load_torque, dtype=float),
            f8(p.load_speed, dtype=float), float(p.breakaway))


def _laws_numpy(p: StartupProblem, t: float, v: FloatArray) -> FloatArray:
    """Generalised forces of the motor and the loads at the coordinate speeds v."""
    out = np.zeros(p.size)
    r = p.load_gain * v[p.load_coordinate] / p.load_speed
    for j, kind in enumerate(p.load_kind):
        law = ResistanceLaw(kind, p.load_torque[j:j + 1], np.ones(1), p.breakaway)  # type: ignore[arg-type]
        out[p.load_coordinate[j]] -= p.load_gain[j] * float(law(r[j:j + 1])[0]) / \
            p.load_efficiency[j]
    if p.motor is not None:
        k, g, eta, law_m = p.motor
        out[k] += g * eta * law_m(t, g * v[k])
    return out


def _law_columns(p: StartupProblem) -> NDArray[np.int64]:
    """Sorted indices of the coordinates the motor and load laws act on."""
    law = {int(k) for k in p.load_coordinate} | ({int(p.motor[0])} if p.motor else set())
    return np.array(sorted(law), dtype=np.int64)


def _law_increment(J: FloatArray, G: FloatArray, dw: FloatArray) -> FloatArray:
    """Increment Δf of the law forces over a step that makes them linearly implicit on the
    mean speeds of their coordinates (module docstring, *Laws*).

    (I − diag(J̃) G) Δf = J̃ Δw, J̃_i = min(J_i, 1/(2 G_ii)).

    Parameters
    ----------
    J : ndarray
        (L,) slopes ∂f_i/∂w_i of the laws at the previous mean speeds [N·s/m or N·m·s/rad].
    G : ndarray
        (L, L) mean-speed response of the step to forces held on the law coordinates,
        Γ_s[q_L, L]/Δt [m/(N·s) or rad/(N·m·s)].
    dw : ndarray
        (L,) w* − w: the mean speeds of the step with the forces f(w) held, less w [m/s or
        rad/s].

    Returns
    -------
    ndarray
        (L,) Δf [N or N·m].

    References
    ----------
    [HairerWanner1996, §IV.7] (linearly implicit methods).
    """
    g = G.diagonal()
    Jc = np.where((J > 0) & (g > 0), np.minimum(J, 0.5 / np.where(g > 0, g, 1.0)), J)
    return np.asarray(np.linalg.solve(np.eye(J.size) - Jc[:, None] * G, Jc * dw), dtype=float)


def _run_numpy(p: StartupProblem, dampers: Dampers
               ) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """The step loop in NumPy (fallback without numba): forces (R, S), states (R, 2N), the
    largest span forces (S,), slack re-steps."""
    n, dt = p.size, p.dt
    B, c, ds, T0 = p.span_incidence, p.span_stiffness, p.span_damping, p.pretension
    poly = _polygonal_data(p) if p.polygonal is not None else None
    d0 = _polygonal_raw(poly, np.zeros(2 * n))[0] if poly is not None else None
    mats = _Patterns(p, dampers)
    lcols = _law_columns(p)
    # a Kloss motor: its coordinate, its place in lcols, gain, efficiency, law
    kloss: tuple[int, int, float, float, KlossMotor] | None = None
    if p.motor is not None and type(p.motor[3]) is KlossMotor:  # as the kernel's motor_code
        kloss = (int(p.motor[0]), int(np.searchsorted(lcols, p.motor[0])), float(p.motor[1]),
                 float(p.motor[2]), p.motor[3])

    def pdd(y: FloatArray) -> tuple[FloatArray, FloatArray]:
        assert poly is not None and d0 is not None
        d, dd = _polygonal_raw(poly, y)
        return d - d0, dd

    def span_part(y: FloatArray, mask: NDArray[np.bool_]) -> FloatArray:
        span = T0.copy()
        if poly is not None:
            d, dd = pdd(y)
            span = span + c * d + ds * dd
        return -(np.where(mask, span, 0.0) @ B)

    def span_force(y: FloatArray) -> FloatArray:
        e, ed = B @ y[:n], B @ y[n:]
        if poly is not None:
            d, dd = pdd(y)
            e, ed = e + d, ed + dd
        return T0 + c * e + ds * ed

    def advance(y: FloatArray, w: FloatArray, t: float, fr: FloatArray,
                mask: NDArray[np.bool_]) -> FloatArray:
        Phi, Gam = mats(mask)
        fl = _laws_numpy(p, t + 0.5 * dt, w)
        hv = 1e-6 * (1.0 + np.abs(w))
        J = (_laws_numpy(p, t + 0.5 * dt, w + hv) - fl) / hv
        y_star = Phi @ y + Gam @ (fr + fl)
        G = Gam[lcols][:, lcols] / dt
        w_star = (y_star[lcols] - y[lcols]) / dt
        df = _law_increment(J[lcols], G, w_star - w[lcols])
        if kloss is not None and J[kloss[0]] > 0.5 / G[kloss[1], kloss[1]] > 0:
            # a Kloss motor on its rising branch faster than the step: backward Euler
            k, am, g_m, eta, law_m = kloss
            wa = w_star[am] + G[am] @ df - G[am, am] * df[am]
            fw = g_m * eta * law_m(t + 0.5 * dt, g_m * w[k])
            u = kloss_end_speed(w[k], wa, fw, G[am, am], g_m, g_m * eta,
                                2.0 * law_m.breakdown_ratio * law_m.rated_torque,
                                law_m.critical_slip, law_m.synchronous_speed)
            df[am] = g_m * eta * law_m(t + 0.5 * dt, g_m * u) - fw
        return y_star + Gam[:, lcols] @ df

    rec = p.record_every
    rows = p.steps // rec + 1
    forces, states, fmax = np.zeros((rows, c.size)), np.zeros((rows, 2 * n)), np.zeros(c.size)
    y, mask = np.zeros(2 * n), c > 0
    forces[0] = np.where(mask, T0, 0.0)
    fmax[:] = np.maximum(forces[0], 0.0)
    fr_prev = span_part(y, mask)
    w = np.zeros(n)  # mean speed over the last step
    slack = 0
    report = _PROGRESS.get()
    chunk = max(1, math.ceil(p.steps / PROGRESS_REPORTS))
    for k in range(p.steps):
        t = k * dt
        fr = span_part(y, mask)
        y_new = advance(y, w, t, 1.5 * fr - 0.5 * fr_prev, mask)
        F = span_force(y_new)
        new_mask = ((F > 0) | ~p.span_tension_only) & (c > 0)
        if not np.array_equal(new_mask, mask):
            mask = new_mask
            fr = span_part(y, mask)
            y_new = advance(y, w, t, fr, mask)
            F = span_force(y_new)
            slack += 1
        w = (y_new[:n] - y[:n]) / dt
        fr_prev, y = fr, y_new
        F = np.where(mask, F, 0.0)
        F = np.where(p.span_tension_only, np.maximum(F, 0.0), F)
        np.maximum(fmax, F, out=fmax)
        if (k + 1) % rec == 0:
            forces[(k + 1) // rec] = F
            states[(k + 1) // rec] = y
        if report is not None and ((k + 1) % chunk == 0 or k + 1 == p.steps):
            report(k + 1, p.steps)
    return forces, states, fmax, slack


def _compiled_runner(backend: Backend) -> Any:  # a numba Dispatcher or an AOT function
    """The compiled step loop: the ahead-of-time module when built from the current source
    (:mod:`chaindrive.dynamics.transient.kernel_build`; loads without numba), else numba's
    just-in-time ``run_kernel_flat`` (backend "jit" forces it), else None."""
    # imported here: the kernel module imports numba (0.25 s), the ahead-of-time module not
    if backend != "jit":
        from chaindrive.dynamics.transient.kernel_build import compiled_kernel

        runner = compiled_kernel()
        if runner is not None:
            return runner
    # lazy: the just-in-time kernel imports numba (0.25 s), only when no compiled one exists
    from chaindrive.dynamics.transient.kernel import HAVE_NUMBA, run_kernel_flat

    return run_kernel_flat if HAVE_NUMBA else None


def _run_compiled(p: StartupProblem, dampers: Dampers, laws: tuple[Any, ...], runner: Any
                  ) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """The step loop compiled (:mod:`chaindrive.dynamics.transient.kernel`); same output as
    :func:`_run_numpy`. Slack patterns new to the kernel are discretised here, then the
    kernel resumes from the step that met them."""
    n, ns = p.size, p.span_stiffness.size
    mats = _Patterns(p, dampers)
    lcols = _law_columns(p)
    masks = np.zeros((4, ns), dtype=np.bool_)
    Phis, G0s, GBs, GLs = (np.empty((4, 2 * n, 2 * n)), np.empty((4, 2 * n)),
                           np.empty((4, 2 * n, ns)), np.empty((4, 2 * n, lcols.size)))
    npat = 0
    minus_Bt = -p.span_incidence.T

    def add(mask: NDArray[np.bool_]) -> None:
        # per pattern: Φ, Γ(−Bᵀ)T₀ (the pre-tension of the spans that hold), Γ(−Bᵀ) (the span
        # forces' columns) and Γ[:, L] (the laws')
        nonlocal masks, Phis, G0s, GBs, GLs, npat
        if npat == masks.shape[0]:
            masks, Phis, G0s, GBs, GLs = (np.concatenate([a, np.empty_like(a)])
                                          for a in (masks, Phis, G0s, GBs, GLs))
        masks[npat] = mask
        Phi, Gam = mats(mask)
        Phis[npat], GBs[npat], GLs[npat] = Phi, Gam @ minus_Bt, Gam[:, lcols]
        G0s[npat] = GBs[npat] @ np.where(mask, p.pretension, 0.0)
        npat += 1

    c = np.ascontiguousarray(p.span_stiffness, dtype=float)
    add(c > 0)
    f8 = np.ascontiguousarray
    if p.polygonal is not None:
        data = _polygonal_data(p)
        d0 = _polygonal_raw(data, np.zeros(2 * n))[0]
        pg = (*(f8(a, dtype=float) for a in data[:4]), f8(data[4], dtype=np.int64),
              f8(data[5], dtype=float), float(data[6]), float(data[7]), f8(d0, dtype=float))
    else:
        e, i0 = np.zeros(2 * ns), np.zeros(2 * ns, dtype=np.int64)
        pg = (e, e, e, e, i0, e, 0.0, 0.0, np.zeros(ns))
    rec = p.record_every
    rows = p.steps // rec + 1
    forces, states = np.zeros((rows, ns)), np.zeros((rows, 2 * n))
    forces[0] = np.where(c > 0, p.pretension, 0.0)
    fmax = np.maximum(forces[0], 0.0)
    y, w, need = np.zeros(2 * n), np.zeros(n), np.zeros(ns, dtype=np.bool_)
    span_prev = np.where(masks[0], p.pretension, 0.0)
    state = np.zeros(4, dtype=np.int64)  # step, slack re-steps, pattern, previous pattern
    B = f8(p.span_incidence, dtype=float)
    ds, T0 = f8(p.span_damping, dtype=float), f8(p.pretension, dtype=float)
    tonly = f8(p.span_tension_only, dtype=np.bool_)
    # the coordinates the forces act on (a Python set: np.unique imports numpy.ma, 12 ms)
    report = _PROGRESS.get()
    chunk = p.steps if report is None else max(1, math.ceil(p.steps / PROGRESS_REPORTS))
    end = min(chunk, p.steps)
    while True:
        if runner(y, w, span_prev, state, end, p.dt, rec, masks, Phis, G0s, GBs, GLs, npat, B, c,
                  ds, tonly, T0, *laws, p.polygonal is not None, *pg, forces, states, fmax,
                  need, lcols) < end:
            add(need.copy())
            continue
        if report is not None:
            report(end, p.steps)
        if end == p.steps:
            return forces, states, fmax, int(state[1])
        end = min(end + chunk, p.steps)


def solve_startup(p: StartupProblem, backend: Backend = "auto"
                  ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, int]:
    """Integrate a start-up problem from rest (module docstring).

    Parameters
    ----------
    p : StartupProblem
        The model, laws, step and records.
    backend : str
        "numba" the compiled kernel (its ahead-of-time build when current, else numba's
        just-in-time compilation; needs a ConstantTorque/RampTorque/KlossMotor motor), "jit"
        the just-in-time one only, "numpy" the NumPy loop, "auto" the compiled kernel when it
        can, else NumPy.

    Returns
    -------
    tuple
        times (R,) [s], span forces (R, S) [N] divided by ``p.scale``, states (R, 2N)
        (coordinates and rates), the largest span forces (S,) [N] / scale, slack re-steps.
    """
    if backend not in ("auto", "numba", "jit", "numpy"):
        raise DesignError("backend", f"unknown start-up backend {backend!r}")
    p, dampers = _linear_laws(p)
    laws = _law_arrays(p) if backend != "numpy" else None
    runner = _compiled_runner(backend) if laws is not None else None
    if runner is not None and laws is not None:
        forces, states, fmax, slack = _run_compiled(p, dampers, laws, runner)
    elif backend in ("numba", "jit"):
        raise DesignError("backend", "numba is not installed or the motor law is not one the "
                          "compiled kernel knows (use backend='numpy')")
    else:
        forces, states, fmax, slack = _run_numpy(p, dampers)
    times = np.arange(forces.shape[0], dtype=np.float64) * (p.dt * p.record_every)
    return times, forces / p.scale, states, fmax / p.scale, slack


# --- the ring of reduced masses ------------------------------------------------------------


