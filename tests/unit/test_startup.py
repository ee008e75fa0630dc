"""Start-up transient (chaindrive.dynamics.transient.startup)."""

from __future__ import annotations

import itertools
import math
import shutil
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from chaindrive.checks import UNVERIFIED
from chaindrive.dynamics.checks import startup_safety_check
from chaindrive.dynamics.frequency.steady import span_incidence
from chaindrive.dynamics.model.assembly import LinearModel
from chaindrive.dynamics.motors import ConstantTorque, KlossMotor, RampTorque, ResistanceLaw
from chaindrive.dynamics.transient import startup as startup_module
from chaindrive.dynamics.transient.kernel import HAVE_NUMBA
from chaindrive.dynamics.transient.startup import (
    PolygonalLaw,
    StartupProblem,
    StartupResult,
    runup_time,
    settling_time,
    solve_startup,
    transient_times,
)
from chaindrive.dynamics.transient.zoh import expm, expm_input, zoh_matrices
from chaindrive.dynamics.warnings import startup_warnings
from chaindrive.errors import DesignError


def simulate_startup(masses: np.ndarray, stiffness: np.ndarray, radii: np.ndarray, beta: float,
                     motor, driver_index: int, resistance: ResistanceLaw | None, *,
                     duration: float, dt: float, pretension: float = 0.0,
                     polygonal: PolygonalLaw | None = None, backend: str = "auto"
                     ) -> SimpleNamespace:
    """A closed ring of reduced masses (span i joins mass i and i+1, span dampers βc_i, the
    motor on ``driver_index`` and the moments of resistance on the others), built as a
    :class:`StartupProblem` and integrated by the solver the analysis runs."""
    m, c, R = (np.asarray(a, dtype=float) for a in (masses, stiffness, radii))
    n = m.size
    others = np.flatnonzero(np.arange(n) != driver_index)
    law = resistance
    steps = max(1, math.ceil(duration / dt))
    p = StartupProblem(
        linear=LinearModel(np.diag(m), np.zeros((n, n)), np.zeros((n, n)), span_incidence(n),
                           c, beta * c, np.ones(n, dtype=bool)),
        pretension=np.full(n, float(pretension)),
        motor=(int(driver_index), 1.0 / float(R[driver_index]), 1.0, motor),
        load_coordinate=others if law is not None else np.zeros(0, np.intp),
        load_gain=1.0 / R[others] if law is not None else np.zeros(0),
        load_efficiency=np.ones(others.size if law is not None else 0),
        load_torque=np.asarray(law.torques, float)[others] if law is not None else np.zeros(0),
        load_speed=(np.asarray(law.nominal_speeds, float)[others] if law is not None
                    else np.zeros(0)),
        load_kind=(law.kind,) * others.size if law is not None else (),
        breakaway=law.breakaway if law is not None else 0.01, polygonal=polygonal,
        travel_coordinate=np.arange(n), travel_gain=np.ones(n), dt=float(dt), steps=steps)
    times, forces, states, fmax, _ = solve_startup(p, backend)  # type: ignore[arg-type]  # a str from parametrize
    return SimpleNamespace(times=times, span_forces=forces, speeds=states[:, n:] / R,
                           max_span_force=fmax,
                           slack_steps=int(np.count_nonzero((forces <= 0).any(axis=1))))


def test_zero_order_hold_of_one_oscillator_is_the_closed_form() -> None:
    # Van Loan (1978) block exponential with our Padé(13) exponential (Higham 2005) against
    # the closed form of a damped oscillator (Rao §2.6): x(t) = e^{−ζωt}(cos ω_d t +
    # ζω/ω_d sin ω_d t) from x = 1 at rest; the response to a held unit force is (1 − x)/k
    m, k, zeta, dt = 1.5, 6e5, 0.06, 3e-4
    w = math.sqrt(k / m)
    wd = w * math.sqrt(1 - zeta**2)
    P, G = zoh_matrices(np.array([[m]]), np.array([[k]]), np.array([[2 * zeta * w * m]]), dt)
    x = math.exp(-zeta * w * dt) * (math.cos(wd * dt) + zeta * w / wd * math.sin(wd * dt))
    assert_allclose(P[0, 0], x, rtol=1e-12)
    assert_allclose(G[0, 0], (1 - x) / k, rtol=1e-10)
    # a stiff, overdamped oscillator (a 1e-10 kg body on a tooth spring): x(t) = (r₂e^{r₁t}
    # − r₁e^{r₂t})/(r₂ − r₁), r the roots of m r² + c r + k (the balanced exponential)
    m, k, c, dt = 1e-10, 1.8e6, 18.0, 2e-5
    r1, r2 = np.roots([m, c, k])
    P, _ = zoh_matrices(np.array([[m]]), np.array([[k]]), np.array([[c]]), dt)
    assert_allclose(P[0, 0], (r2 * np.exp(r1 * dt) - r1 * np.exp(r2 * dt)) / (r2 - r1),
                    rtol=1e-8)


def _modal_transition(m: np.ndarray, K: np.ndarray, beta: float, dt: float) -> np.ndarray:
    """Φ of M ẍ + βK ẋ + K x = 0 from the modes (classical damping, Rao §6.13): each mode a
    damped oscillator with 2ζω = βω², closed form per mode (ω = 0: free motion)."""
    d = 1 / np.sqrt(m)
    lam, V = np.linalg.eigh(K * d[:, None] * d[None, :])
    X = V * d[:, None]
    n = m.size
    p = np.empty((4, n))
    for j, w2 in enumerate(np.maximum(lam, 0.0)):
        A = np.array([[0.0, 1.0], [-w2, -beta * w2]])
        ev, W = np.linalg.eig(A)
        if w2 == 0.0 or abs(ev[0] - ev[1]) < 1e-9 * abs(ev).max():
            E = np.eye(2) + A * dt
        else:
            E = (W @ np.diag(np.exp(ev * dt)) @ np.linalg.inv(W)).real
        p[:, j] = E.ravel()
    XtM = X.T * m
    return np.block([[(X * p[0]) @ XtM, (X * p[1]) @ XtM], [(X * p[2]) @ XtM, (X * p[3]) @ XtM]])


def test_transition_matrix_against_the_modal_closed_form() -> None:
    # the balanced zero-order-hold exponential against the modes of a ring with
    # stiffness-proportional damping and slack spans (frequencies 30 Hz … 9 kHz)
    rng = np.random.default_rng(1)
    m = rng.uniform(0.05, 2.0, 12)
    c = rng.uniform(1e5, 1e8, 12)
    c[[3, 7]] = 0.0
    B = np.roll(np.eye(12), 1, axis=1) - np.eye(12)
    K = B.T @ (c[:, None] * B)
    beta, dt = 2 * 0.06 / 700, 2e-4
    P, _ = zoh_matrices(np.diag(m), K, beta * K, dt)
    ref = _modal_transition(m, K, beta, dt)
    assert_allclose(P, ref, rtol=0, atol=1e-9 * np.abs(ref).max())
    assert_allclose(expm(np.zeros((3, 3))), np.eye(3), rtol=0, atol=1e-15)



def test_block_exponential_is_the_closed_form() -> None:
    # expm([[a, e], [0, 0]]) = [[e^a, (e^a − 1)/a · e], [0, 1]] for a scalar a (the zero-order
    # hold of ẋ = a x + e u, Van Loan 1978); a = −40 takes the scaling-and-squaring branch
    for a in (-0.3, -40.0, 2.5):
        P, G = expm_input(np.array([[a]]), np.array([[1.7]]))
        assert_allclose(P[0, 0], math.exp(a), rtol=1e-13)
        assert_allclose(G[0, 0], math.expm1(a) / a * 1.7, rtol=1e-13)
    # a matrix: the blocks of the full block exponential (checked against closed forms above)
    rng = np.random.default_rng(3)
    A, E = rng.normal(size=(8, 8)) * 3.0, rng.normal(size=(8, 4))
    Z = np.zeros((12, 12))
    Z[:8, :8], Z[:8, 8:] = A, E
    full = expm(Z)
    P, G = expm_input(A, E)
    assert_allclose(P, full[:8, :8], rtol=0, atol=1e-12 * np.abs(full).max())
    assert_allclose(G, full[:8, 8:], rtol=0, atol=1e-12 * np.abs(full).max())


@pytest.mark.parametrize("backend", ["numpy", "auto"])
def test_linear_laws_taken_into_the_transition_are_the_law_step(
        backend: str, monkeypatch: pytest.MonkeyPatch) -> None:
    # a linear machine law f = −g M (g w/ω_n)/η on the mean speed w of its coordinate over the
    # step, solved once per slack pattern as a damper (Woodbury) or at every step in the laws'
    # linear system: the same linearly implicit step, so the same start-up to round-off
    n = 4
    m, c, R = np.array([0.5, 0.6, 0.4, 0.3]), np.array([1e6, 2e6, 1.5e6, 1.2e6]), np.full(4, .06)
    others = np.arange(1, n)
    p = StartupProblem(
        linear=LinearModel(np.diag(m), np.zeros((n, n)), np.zeros((n, n)), span_incidence(n),
                           c, 5e-5 * c, np.ones(n, dtype=bool)),
        pretension=np.full(n, 30.0), motor=(0, 1.0 / 0.06, 0.97, KlossMotor(3000.0, 26.0)),
        load_coordinate=others, load_gain=1.0 / R[others], load_efficiency=np.array([.9, .8, .95]),
        load_torque=np.array([20.0, 35.0, 10.0]), load_speed=np.array([20.0, 15.0, 25.0]),
        load_kind=("linear", "linear", "linear"), breakaway=0.01, polygonal=None,
        travel_coordinate=np.arange(n), travel_gain=np.ones(n), dt=2e-5, steps=4000)
    _, F, S, fmax, _ = solve_startup(p, backend)  # type: ignore[arg-type]  # a str from parametrize
    monkeypatch.setattr(startup_module, "_linear_laws",
                        lambda q: (q, (np.zeros(0, dtype=np.intp), np.zeros(0))))
    _, F0, S0, fmax0, _ = solve_startup(p, backend)  # type: ignore[arg-type]
    assert (F0 == 0).any()  # spans went slack: more than one pattern
    assert_allclose(fmax, fmax0, rtol=1e-9)
    assert_allclose(F, F0, rtol=0, atol=1e-9 * fmax0.max())
    assert_allclose(S[:, n:], S0[:, n:], rtol=0, atol=1e-9 * np.abs(S0[:, n:]).max())


def test_nonlinear_startup_matches_tight_reference() -> None:
    # slack spans + Kloss motor + linear resistance against LSODA (rtol 1e-8)
    m, c, R = np.array([0.5, 0.6, 0.4]), np.array([1e6, 2e6, 1.5e6]), np.array([.05, .08, .06])
    beta, T0 = 2 * 0.05 / 2000, 50.0
    mot = KlossMotor(3000.0, 26.0)
    res = ResistanceLaw("linear", np.array([0.0, 60.0, 0.0]), np.array([26.0, 16.25, 21.7]))
    r = simulate_startup(m, c, R, beta, mot, 0, res, duration=0.1, dt=2e-5, pretension=T0)
    nxt, prv = np.array([1, 2, 0]), np.array([2, 0, 1])

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        x, v = y[:3], y[3:]
        F = np.maximum(T0 + c * (x[nxt] - x) + beta * c * (v[nxt] - v), 0)
        f = F - F[prv] - np.array([0, 1, 1]) * res(v / R) / R
        f[0] += mot(t, v[0] / R[0]) / R[0]
        return np.concatenate([v, f / m])

    sol = solve_ivp(rhs, (0, 0.1), np.zeros(6), method="LSODA", t_eval=r.times,
                    rtol=1e-8, atol=1e-11)
    x, v = sol.y[:3].T, sol.y[3:].T
    F = np.maximum(T0 + c * (x[:, nxt] - x) + beta * c * (v[:, nxt] - v), 0)
    assert_allclose(r.max_span_force, F.max(axis=0), rtol=0.02)
    assert_allclose(r.speeds[-1], v[-1] / R, rtol=0.01)
    assert r.span_forces.min() >= 0.0  # tension only
    assert r.slack_steps > 0  # span 0 does go slack in this case


def test_kloss_motor_rated_and_breakdown_points() -> None:
    mot = KlossMotor(3000.0, 150.0, breakdown_ratio=2.5, critical_slip=0.2)
    assert_allclose(mot(0.0, 150.0), mot.rated_torque, rtol=1e-12)
    w_k = mot.synchronous_speed * (1 - 0.2)
    assert_allclose(mot(0.0, w_k), 2.5 * mot.rated_torque, rtol=1e-12)
    assert abs(mot(0.0, mot.synchronous_speed)) < 1e-9


def test_constant_torque_rigid_acceleration() -> None:
    # no resistance: the free ring accelerates as one body, a = F/Σm
    m, c, R = np.array([1.0, 2.0, 1.0]), np.array([1e6, 1e6, 1e6]), np.full(3, 0.1)
    r = simulate_startup(m, c, R, 1e-5, ConstantTorque(4.0), 0, None, duration=0.2,
                         dt=1e-4, pretension=1e4)
    assert_allclose(r.speeds[-1].mean() * 0.1, 40.0 / 4.0 * 0.2, rtol=1e-3)


def _small_ring(polygonal: bool) -> dict:
    m, c, R = np.array([0.5, 0.6, 0.4, 0.7]), np.array([1e6, 2e6, 1.5e6, 1.2e6]), \
        np.array([.05, .08, .06, .07])
    law = PolygonalLaw(0.0127, np.array([25.0, 40, 30, 35]), np.array([40.0, 30, 35, 25]),
                       np.array([0.0, 21.3, 40.9, 66.2]), np.array([9.6, 33.1, 55.4, 74.8]))
    return {"masses": m, "stiffness": c, "radii": R, "beta": 2 * 0.05 / 2000,
            "driver_index": 0, "duration": 0.05, "dt": 2e-5, "pretension": 50.0,
            "polygonal": law if polygonal else None}


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("backend", ["numba", "jit"])  # numba: the ahead-of-time build
@pytest.mark.parametrize(("motor", "kind", "polygonal"), [
    (KlossMotor(3000.0, 26.0), "linear", True),
    (ConstantTorque(40.0), "constant", False),
    (RampTorque(120.0, 0.02), "quadratic", True),
])
def test_numba_kernel_equals_numpy_loop(motor, kind: str, polygonal: bool, backend: str) -> None:
    # the compiled kernel (ahead of time and just in time) and the NumPy loop take the same
    # steps: equal to round-off
    res = ResistanceLaw(kind, np.array([0.0, 60.0, 10.0, 5.0]), np.array([26.0, 16., 21., 19.]))
    args = _small_ring(polygonal)
    a = simulate_startup(motor=motor, resistance=res, backend=backend, **args)
    b = simulate_startup(motor=motor, resistance=res, backend="numpy", **args)
    assert b.slack_steps > 0  # the slack rule is exercised
    assert_allclose(a.span_forces, b.span_forces, rtol=0, atol=1e-9 * b.span_forces.max())
    assert_allclose(a.speeds, b.speeds, rtol=0, atol=1e-9 * np.abs(b.speeds).max())


def test_unknown_motor_falls_back_to_numpy_loop() -> None:
    args = _small_ring(False) | {"duration": 0.005}
    a = simulate_startup(motor=lambda t, w: 40.0, resistance=None, **args)
    b = simulate_startup(motor=ConstantTorque(40.0), resistance=None, backend="numpy", **args)
    assert_allclose(a.speeds, b.speeds, rtol=1e-12, atol=1e-12)
    with pytest.raises(DesignError):
        simulate_startup(motor=lambda t, w: 40.0, resistance=None, backend="numba", **args)
    with pytest.raises(DesignError):
        simulate_startup(motor=ConstantTorque(1.0), resistance=None, backend="fortran", **args)


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler: no ahead-of-time build")
def test_ahead_of_time_kernel_is_built_and_current(monkeypatch: pytest.MonkeyPatch) -> None:
    # make builds chaindrive.dynamics.transient._startup_aot from the current kernel source; a module
    # whose source digest differs (a stale build) is not used
    from chaindrive.dynamics.transient import _startup_aot, kernel_build  # type: ignore[attr-defined]

    assert _startup_aot.source_digest() == kernel_build.source_digest()
    assert kernel_build.compiled_kernel() is _startup_aot.run_kernel_flat
    monkeypatch.setattr(kernel_build, "source_digest", lambda: -1)
    kernel_build.compiled_kernel.cache_clear()
    try:
        assert kernel_build.compiled_kernel() is None
    finally:
        kernel_build.compiled_kernel.cache_clear()
    # built for this processor: on another one (another model or instruction set) the digest
    # differs and the module is not used
    monkeypatch.undo()
    digest = kernel_build.source_digest()
    monkeypatch.setattr(kernel_build, "processor", lambda: "x86_64|another processor|sse2")
    assert kernel_build.source_digest() != digest
    kernel_build.compiled_kernel.cache_clear()
    try:
        assert kernel_build.compiled_kernel() is None
    finally:
        kernel_build.compiled_kernel.cache_clear()


def test_settling_time_of_a_decay_into_a_clipped_ripple() -> None:
    """A decaying transient e^{-t/τ} that ends in a steady ripple clipped at zero (a span that
    goes slack: F = max(0, F₀ + A sin ωt)) settles where the decay has fallen into the band
    of the ripple, not at the end of the record: the final band is centred on the ripple's
    mid-range, which holds every sample of a ripple of any shape (closed form below)."""
    t = np.linspace(0.0, 2.0, 20001)
    omega, f0, amp, tol = 2 * math.pi * 50.0, 100.0, 150.0, 0.05
    ripple = np.maximum(0.0, f0 + amp * np.sin(omega * t))
    peak, tau = 400.0, 0.05
    force = ripple + peak * np.exp(-t / tau)
    got = settling_time(t, force[:, None], tolerance=tol)
    tail = ripple[t >= 1.8]
    margin = tol * tail.mean()  # the band's width beyond the ripple's own half-range
    # the decay leaves the band where peak·e^{-t/τ} ≤ margin (± one ripple period)
    expected = tau * math.log(peak / margin)
    assert abs(got - expected) <= 2 * math.pi / omega
    assert got < 0.5  # the old, mean-centred band put it at the end of the record


def test_settling_time_waits_for_a_growing_ripple() -> None:
    """A ripple that grows toward its final amplitude, A(t) = A∞(1 − e^{−t/τ}) (a resonance
    approached as the speed creeps up), has settled once A∞e^{−t/τ} ≤ δ = 5 % of the mean
    force: closed form t = τ ln(A∞/δ), to within one window (a tenth of the record). A ripple
    still growing by more than δ per window at the end (A = 150 N/s · t: 30 N per 0.2 s
    window against δ = 25 N) has not settled (nan)."""
    t = np.linspace(0.0, 2.0, 40001)
    omega, f0, a_inf, tau = 2 * math.pi * 40.0, 500.0, 300.0, 0.1
    delta = 0.05 * f0
    force = f0 + a_inf * (1 - np.exp(-t / tau)) * np.sin(omega * t)
    got = settling_time(t, force[:, None], period=1 / 40.0)
    expected = tau * math.log(a_inf / delta)
    assert expected - 0.01 <= got <= expected + 0.2 + 0.01
    growing = f0 + 150.0 * t * np.sin(omega * t)
    assert math.isnan(settling_time(t, growing[:, None], period=1 / 40.0))


def test_settling_needs_a_record_of_two_ripple_periods() -> None:
    """A final state must hold two periods of the ripple: a record shorter than four
    periods cannot show one (nan), a longer one can (0: a steady ripple from the start)."""
    omega = 2 * math.pi * 5.0
    for end, settled in ((0.7, False), (1.0, True)):
        t = np.linspace(0.0, end, 7001)
        force = (300.0 + 100.0 * np.sin(omega * t))[:, None]
        got = settling_time(t, force, period=0.2)
        assert (got == 0.0) if settled else math.isnan(got)


def test_transient_times_run_up_then_decay() -> None:
    """Settling is the later of the run-up and the force settling; decay is the rest."""
    t = np.linspace(0.0, 1.0, 10001)
    speed = np.minimum(t / 0.3, 1.0) * 100.0               # at 95 % at t = 0.285 s
    force = (400.0 + 300.0 * np.exp(-t / 0.02))[:, None]   # settled long before
    settle, runup, decay = transient_times(t, force, speed, 0.0)
    assert runup == pytest.approx(0.285, abs=1e-4)
    assert settle == runup and decay == 0.0
    late = (400.0 + 300.0 * np.exp(-t / 0.1))[:, None]     # 300 e^{-t/0.1} = 20 N at 0.27 s
    settle, runup, decay = transient_times(t, late, speed, 0.0)
    assert settle == pytest.approx(max(runup, 0.1 * math.log(300.0 / 20.0)), abs=1e-3)
    assert decay == pytest.approx(settle - runup)


def test_startup_warnings_name_an_unsettled_record_and_slack_spans() -> None:
    """A record that ends before the forces settle, and the spans slack in more than 1 % of
    the samples, each give one warning naming them; a settled taut record gives none."""
    t = np.linspace(0.0, 1.0, 1001)
    forces = np.column_stack([np.full(t.size, 300.0),
                              np.where(np.arange(t.size) % 10 == 0, 0.0, 200.0)])
    speeds = np.ones((t.size, 2))
    record = StartupResult(t, forces, speeds, forces.max(axis=0), math.nan, None, 1000,
                           101, 0.2, math.nan)
    warnings = startup_warnings(record, ["A→B", "B→A"])
    assert [w.code for w in warnings] == ["dynamics.startup-not-settled",
                                          "dynamics.startup-slack"]
    assert "run-up 0.2 s" in warnings[0].message and "within the simulated 1 s" in \
        warnings[0].message
    assert "B→A 10.1 %" in warnings[1].message and "A→B" not in warnings[1].message
    taut = StartupResult(t, forces + 1.0, speeds, forces.max(axis=0), 0.3, None, 1000, 0,
                         0.2, 0.1)
    assert startup_warnings(taut, ["A→B", "B→A"]) == []


def test_k1_cannot_be_verified_on_an_unsettled_record() -> None:
    """k₁ = Q/F₁max [MultimassChainDrives, §3.6] of a record that ends before the forces
    settle cannot be verified (a larger F₁max may follow); the note keeps k₁ so far."""
    t = np.linspace(0.0, 1.0, 101)
    forces = np.full((t.size, 1), 100.0)
    speeds = np.ones((t.size, 1))
    open_end = StartupResult(t, forces, speeds, forces.max(axis=0), math.nan, 50.0, 100, 0,
                             0.2, math.nan)
    check = startup_safety_check(open_end, 2.5)
    assert check.status == UNVERIFIED and check.value is None
    assert "(so far 50)" in check.note and "startup_duration" in check.note
    # already below [k] on the partial record: a longer one can only lower k₁, so it fails
    low = startup_safety_check(replace(open_end, k1=2.0), 2.5)
    assert low.status == "fail" and low.value == 2.0 and "already below" in low.note
    settled = StartupResult(t, forces, speeds, forces.max(axis=0), 0.3, 50.0, 100, 0, 0.2,
                            0.1)
    assert startup_safety_check(settled, 2.5).status == "pass"
    assert startup_safety_check(replace(settled, k1=2.0), 2.5).status == "fail"


def test_runup_needs_the_speed_levelled_off() -> None:
    """A ramp to 100 rad/s in 0.3 s, then 100 rad/s with a ±2 % polygonal ripple at 50 Hz:
    the run-up (95 %) lies between 0.3·0.95/1.02 s (on a ripple crest) and 0.285 s (on the
    mean; one sample later, the first sample at or above) — closed form. The same ramp cut at
    0.2 s is still accelerating at the end of its record: no run-up time (nan), although its
    speed passes 95 % of its own final mean."""
    t = np.linspace(0.0, 1.0, 20001)
    speed = np.minimum(t / 0.3, 1.0) * 100.0 * (1.0 + 0.02 * np.sin(2 * math.pi * 50.0 * t))
    assert 0.3 * 0.95 / 1.02 <= runup_time(t, speed, period=0.02) <= 0.285 + 1.001 * t[1]
    cut = t <= 0.2
    assert math.isnan(runup_time(t[cut], speed[cut], period=0.02))


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_progress_reports_leave_the_result_bit_identical(backend: str) -> None:
    # with a progress callback the compiled kernel runs in pieces, resuming from its state:
    # the same numbers to the bit; the reports climb to the last step
    from chaindrive.dynamics.transient.startup import PROGRESS_REPORTS, startup_progress

    if backend == "numba" and not HAVE_NUMBA:
        pytest.skip("numba not installed")
    args = _small_ring(True)
    res = ResistanceLaw("linear", np.array([0.0, 60.0, 10.0, 5.0]),
                        np.array([26.0, 16., 21., 19.]))
    plain = simulate_startup(motor=KlossMotor(3000.0, 26.0), resistance=res, backend=backend,
                             **args)
    seen: list[tuple[int, int]] = []
    with startup_progress(lambda done, total: seen.append((done, total))):
        shown = simulate_startup(motor=KlossMotor(3000.0, 26.0), resistance=res,
                                 backend=backend, **args)
    assert np.array_equal(plain.span_forces, shown.span_forces)
    assert np.array_equal(plain.speeds, shown.speeds)
    assert np.array_equal(plain.max_span_force, shown.max_span_force)
    steps = seen[-1][1]
    assert seen[-1] == (steps, steps)
    assert len(seen) == math.ceil(steps / math.ceil(steps / PROGRESS_REPORTS))
    assert all(a[0] < b[0] for a, b in itertools.pairwise(seen))
