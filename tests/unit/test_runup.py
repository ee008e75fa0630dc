"""The rigid-drive run-up (chaindrive.dynamics.transient.runup) against closed forms of the equation of
motion of an electric drive, J dω/dt = η M_M − M_L [Chilikin1981], its check, the durations an
automatic start-up tries, and the elastic start-up of the bundled seed drive."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from chaindrive.analysis import analyze
from chaindrive.dynamics.checks import motor_start_check
from chaindrive.dynamics.model.assembly import LinearModel, LoadPlacement, MotorPlacement
from chaindrive.dynamics.motors import ConstantTorque, KlossMotor
from chaindrive.dynamics.transient.runup import (
    LONGEST_STARTUP,
    SHORTEST_STARTUP,
    RunUp,
    rigid_runup,
    startup_durations,
)
from chaindrive.dynamics.transient.startup import runup_time
from chaindrive.io.design import load_drive

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _geared_pair(law: object, *, load: float = 0.0, kind: str = "constant",
                 ratio: float = 1.0 / 3.0) -> SimpleNamespace:
    """A motor rotor (0.5 kg·m², η = 0.95) on a shaft to a gear stage whose wheel turns a
    machine of 12 kg·m² at ``ratio`` of the motor's speed (η = 0.9): q₂ is the pinion's angle,
    the machine's speed ratio·q̇₂, its inertia 12·ratio² on q₂."""
    k = 1.0e5
    linear = LinearModel(
        mass=np.diag([0.5, 12.0 * ratio**2]),
        stiffness_linear=np.array([[k, -k], [-k, k]]), damping_linear=np.zeros((2, 2)),
        span_incidence=np.zeros((0, 2)), span_stiffness=np.zeros(0),
        span_damping=np.zeros(0), span_tension_only=np.zeros(0, dtype=bool))
    motor = MotorPlacement("motor", 0, 1.0, 0.95, law, 150.0, 0.5, False)  # type: ignore[arg-type]
    loads = () if load == 0.0 else (
        LoadPlacement("D", "machine", 1, ratio, 0.9, kind, load, 150.0 * ratio),)
    return SimpleNamespace(linear=linear, motor=motor, loads=loads)


def test_constant_torques_run_up_in_the_closed_form_time() -> None:
    """Constant η M_M and M_L: t₉₅ = J_red 0.95 ω_n / (η M_M − i M_L/η_L), J_red = J₁ + i² J₂
    (closed form of J dω/dt = const)."""
    i = 1.0 / 3.0
    r = rigid_runup(_geared_pair(ConstantTorque(100.0), load=150.0, ratio=i))  # type: ignore[arg-type]
    assert r is not None
    j_red = 0.5 + 12.0 * i**2
    net = 0.95 * 100.0 - i * 150.0 / 0.9
    assert r.inertia == pytest.approx(j_red, rel=1e-9)
    assert r.runup_time == pytest.approx(j_red * 0.95 * 150.0 / net, rel=1e-6)
    assert r.torque_ratio == pytest.approx(0.95 * 100.0 / (i * 150.0 / 0.9), rel=1e-9)
    assert math.isnan(r.working_speed) and r.starts


def test_kloss_motor_without_load_runs_up_in_the_closed_form_time() -> None:
    """An induction motor by Kloss, M = 2 M_k s s_k/(s² + s_k²), on an inertia alone:
    t = J ω_s/(2 η M_k s_k) [(1 − s₁²)/2 + s_k² ln(1/s₁)] from s = 1 to s₁ = 0.05 (95 % of the
    synchronous speed, its working speed without load) — the integral of dω = −ω_s ds
    [Chilikin1981]."""
    law = KlossMotor(3000.0, 149.75, 2.5, 0.25)
    r = rigid_runup(_geared_pair(law))  # type: ignore[arg-type]
    assert r is not None
    ws, sk = law.synchronous_speed, law.critical_slip
    mk = law.breakdown_ratio * law.rated_torque
    s1 = 0.05
    closed = r.inertia * ws / (2.0 * 0.95 * mk * sk) * ((1 - s1**2) / 2 + sk**2 * math.log(1 / s1))
    assert r.working_speed == pytest.approx(ws, rel=1e-6)
    assert r.runup_time == pytest.approx(closed, rel=1e-6)
    # final approach: τ = J/(η dM/ds / ω_s) at s = 0, dM/ds = 2 M_k/s_k there
    assert r.time_constant == pytest.approx(r.inertia * ws * sk / (0.95 * 2.0 * mk), rel=1e-3)
    assert motor_start_check(r) is None  # no machine: nothing to compare with


def test_a_motor_weaker_than_its_load_stalls_and_fails_its_check() -> None:
    """A constant load referred to the motor above the Kloss starting torque 2 λ M_r s_k/(1 +
    s_k²): the drive does not start (ratio below 1 at standstill), the run-up is infinite and
    the check fails naming where the torques meet."""
    law = KlossMotor(3000.0, 149.75, 2.5, 0.25)
    start = 2.0 * 2.5 * law.rated_torque * 0.25 / (1.0 + 0.25**2)
    load = 1.2 * 0.95 * start / (1.0 / 3.0) * 0.9  # referred: 1.2 × η M_start
    r = rigid_runup(_geared_pair(law, load=load))  # type: ignore[arg-type]
    assert r is not None and not r.starts and math.isinf(r.runup_time)
    assert r.torque_ratio == pytest.approx(1.0 / 1.2, rel=1e-3)
    check = motor_start_check(r)
    assert check is not None and check.status == "fail" and "stalls" in check.note
    assert startup_durations(r) == (SHORTEST_STARTUP,)


def test_automatic_durations_double_from_twice_the_rigid_settling() -> None:
    """Twice the rigid time to settle within 1 % (t₉₅ + τ ln 5), at least 1 s, then twice and
    four times that, bounded by the longest duration."""
    r = RunUp(1.0, 100.0, 99.0, 2.0, 0.5, 1.5, 10.0)
    first = 2.0 * (2.0 + 0.5 * math.log(5.0))
    assert startup_durations(r) == pytest.approx((first, 2 * first, 4 * first))
    assert startup_durations(r, longest=10.0) == pytest.approx((first, 10.0))
    quick = RunUp(1.0, 100.0, 99.0, 0.1, 0.01, 1.5, 10.0)
    assert startup_durations(quick) == (1.0, 2.0, 4.0)
    assert startup_durations(None) == (SHORTEST_STARTUP,)
    assert max(startup_durations(r)) <= LONGEST_STARTUP


def test_runup_is_when_the_speed_stays_up() -> None:
    """A driver that reaches 95 % at 0.1 s, falls back to 50 % (bouncing against a slack
    chain) and runs up again on a ramp reaching 95 % at 0.6 s: its run-up ends at 0.6 s, one
    sample's step at most (the closed form of the ramp)."""
    t = np.linspace(0.0, 2.0, 20001)
    speed = np.where(t < 0.2, np.minimum(t / 0.1, 1.0), np.minimum(0.5 + (t - 0.2) / 0.8, 1.0))
    speed = 100.0 * np.where((t >= 0.1) & (t < 0.2), 0.96, speed)
    assert runup_time(t, speed) == pytest.approx(0.2 + 0.45 * 0.8, abs=2e-4)


@pytest.mark.parametrize("name", ["seed_three_sprocket.toml",
                                  "seed_three_sprocket_polymer.toml"])
def test_elastic_runup_agrees_with_the_rigid_drive(name: str) -> None:
    """With the motor's torque well above the load's (ratio ≈ 1.8), the elastic start-up's
    run-up is the rigid drive's within 1 % (the chain's stretch shifts it by a fraction of the
    first mode's period, 1/73 Hz = 14 ms, against 0.29 s); the automatic duration of a drive
    that settles within 1 s is 1 s."""
    a = analyze(load_drive(EXAMPLES / name))
    assert a.runup is not None and a.startup is not None
    assert a.runup.torque_ratio > 1.5
    assert a.startup.runup_time == pytest.approx(a.runup.runup_time, rel=0.01)
    assert a.startup.times[-1] == pytest.approx(1.0, abs=1e-3) and a.startup.settled


def test_automatic_startup_lengthens_until_it_settles() -> None:
    """The conveyor with ten times heavier drums (12 kg·m²) and fan-like (quadratic) loads runs
    up in about 0.7 s rigid; one second of start-up ends before its transient has decayed, and
    the automatic duration lengthens the record until it has (k₁ then verified)."""
    drive = load_drive(EXAMPLES / "conveyor_five_sprocket.toml")
    heavy = [replace(s, load="quadratic", train=tuple(
        replace(e, inertia=12.0) if e.name.startswith("drum") else e for e in s.train))
        if s.role == "driven" else s for s in drive.sprockets]
    drive = replace(drive, sprockets=tuple(heavy))
    a = analyze(drive)
    assert a.runup is not None and 0.5 < a.runup.runup_time < 1.0
    assert a.startup is not None and a.startup.settled and a.startup.times[-1] > 1.0
    fixed = analyze(replace(drive, dynamics=replace(drive.dynamics, startup_duration=1.0)))
    assert fixed.startup is not None and not fixed.startup.settled
    assert a.check("k1") is not None and a.check("k1").status in ("pass", "fail")


def test_k1_cannot_be_verified_without_the_drive_or_when_the_motor_stalls() -> None:
    """k₁ = Q/F₁max [MultimassChainDrives, §3.6] of a settled record is judged; on a model
    without its motor or machines (a start-up of bare sprockets), or with a motor that does
    not start the drive, it cannot be verified, and the note keeps the k₁ computed."""
    from chaindrive.checks import UNVERIFIED
    from chaindrive.dynamics.checks import startup_safety_check
    from chaindrive.dynamics.transient.startup import StartupResult

    t = np.linspace(0.0, 1.0, 101)
    forces = np.full((t.size, 1), 100.0)
    record = StartupResult(t, forces, np.ones((t.size, 1)), forces.max(axis=0), 0.3, 50.0,
                           100, 0, 0.2, 0.1)
    assert startup_safety_check(record, 2.5).status == "pass"
    bare = startup_safety_check(record, 2.5, missing=("the driver S1 has no motor",))
    assert bare.status == UNVERIFIED and "incomplete (1 missing" in bare.note
    assert "computed 50" in bare.note
    stalled = RunUp(1.0, 100.0, 20.0, math.inf, math.nan, 0.8, 20.0)
    stall = startup_safety_check(record, 2.5, runup=stalled)
    assert stall.status == UNVERIFIED and "does not start" in stall.note


def test_every_resonance_inside_the_band_is_named() -> None:
    """The resonance check judges the closest working frequency; the others inside the band
    are counted in its note, the three closest named (the 24-sprocket example: the tooth
    frequency 0.2 % from a ring mode, two spans' parametric resonances at 2.5 %, …)."""
    a = analyze(load_drive(EXAMPLES / "twenty_four_sprocket.toml"), response=False)
    check = a.check("resonance_margin")
    inside = [r for r in a.dynamics.resonances if r.detuning_percent < 10.0]
    assert check is not None and check.status == "fail" and len(inside) > 2
    assert f"{len(inside) - 1} more inside the band" in check.note
    closest, *others = sorted(inside, key=lambda r: r.detuning_percent)
    assert check.subject == closest.working.label
    assert all(f"{r.working.label} {r.detuning_percent:.3g} %" in check.note
               for r in others[:3])
    assert f"and {len(others) - 3} more (the resonance table)" in check.note


def test_an_elastic_stall_is_said_and_not_lengthened() -> None:
    """The conveyor with ten times heavier drums (12 kg·m²) and its constant loads: the motor
    starts the rigid drive (torque ratio 1.10, rigid run-up about 2 s), but the elastic model's
    motor side bounces against the slack spans (the static Kloss curve's rising branch feeds
    it; docs/dynamics.md §8). The start-up stops at its first duration, a warning says it is
    out of the model's range, and k₁ cannot be verified."""
    from chaindrive.checks import UNVERIFIED
    from chaindrive.dynamics.transient.runup import elastic_stall

    drive = load_drive(EXAMPLES / "conveyor_five_sprocket.toml")
    heavy = [replace(s, train=tuple(replace(e, inertia=12.0) if e.name.startswith("drum")
                                    else e for e in s.train)) if s.role == "driven" else s
             for s in drive.sprockets]
    a = analyze(replace(drive, sprockets=tuple(heavy)))
    assert a.runup is not None and a.runup.starts and 1.0 < a.runup.runup_time < 3.0
    assert a.startup is not None and elastic_stall(a.runup, a.startup)
    assert a.startup.times[-1] == pytest.approx(startup_durations(a.runup)[0], rel=1e-3)
    assert any(w.code == "dynamics.startup-stall" for w in a.warnings)
    k1 = a.check("k1")
    assert k1 is not None and k1.status == UNVERIFIED and "outside the model's range" in k1.note


def test_motor_torque_on_the_grid_is_the_law_speed_by_speed() -> None:
    # the package's motor laws take the whole speed grid at once: the same numbers, bit for
    # bit, as calling the law at every speed (what any other callable gets)
    from chaindrive.dynamics.motors import ConstantTorque, KlossMotor, RampTorque
    from chaindrive.dynamics.transient.runup import _motor_torque

    w = np.linspace(1e-9, 160.0, 4001)
    for law in (KlossMotor(3000.0, 150.0), RampTorque(10.0, 0.2), ConstantTorque(4.0)):
        t = math.inf if isinstance(law, RampTorque) else 0.0
        expected = np.array([float(law(t, float(x))) for x in w])
        assert np.array_equal(_motor_torque(law, w), expected)
        if not isinstance(law, RampTorque):  # a wrapped ramp is not known to be at full torque
            assert np.array_equal(_motor_torque(lambda t, x, law=law: law(t, x), w), expected)
