"""The start-up at the edges of the allowed inputs: the lowest driver speed and stiff, light
trains (chaindrive.dynamics.transient.startup, the laws' step)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose

from chaindrive.analysis import analyze
from chaindrive.dynamics.motors import KlossMotor
from chaindrive.dynamics.transient.kernel_codes import kloss_end_speed
from chaindrive.dynamics.transient.startup import _law_increment
from chaindrive.io.design import drive_from_mapping, read_toml

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _eight_sprocket(**changes: object) -> dict:
    data = read_toml(EXAMPLES / "eight_sprocket.toml")
    data["sprockets"][0].update(changes)
    return data


def test_law_increment_of_one_damper_is_backward_euler() -> None:
    # one coordinate, a damper f = J w (J < 0) with mean-speed response g: the implicit step
    # gives w' − w = (w* − w)/(1 − J g) (closed form of the backward-Euler damper), at any g,
    # so Δf = J (w' − w)
    for J, g in ((-3.0, 0.1), (-1e6, 10.0)):
        dw = 2.0
        df = _law_increment(np.array([J]), np.array([[g]]), np.array([dw]))
        assert_allclose(df[0], J * dw / (1.0 - J * g), rtol=1e-12)


def test_law_increment_couples_the_law_coordinates() -> None:
    # two dampers on coordinates that move together (G = g·11ᵀ, a stiff shaft between them):
    # the implicit step solves them as one damper of slope J1 + J2 on the common speed
    g, J = 0.5, np.array([-40.0, -60.0])
    G = np.full((2, 2), g)
    dw = np.array([1.0, 1.0])
    df = _law_increment(J, G, dw)
    assert_allclose(df, J * dw / (1.0 - J.sum() * g), rtol=1e-12)


def test_law_increment_clips_a_rising_slope() -> None:
    # a rising motor curve (J > 0) is taken implicit up to J g = 1/2 only: beyond, the
    # increment is that of J = 1/(2g), amplification 1/(1 − 1/2) = 2
    g = 0.01
    df = _law_increment(np.array([1e6]), np.array([[g]]), np.array([1.0]))
    assert_allclose(df[0], (0.5 / g) / (1.0 - 0.5), rtol=1e-12)


def test_startup_at_the_lowest_driver_speed_is_finite_and_physical() -> None:
    # 1 rpm is the schema's lower limit; the default Kloss motor then drives a sprocket of
    # 1e-3 kg·m² with 38 kN·m (the rigid run-up takes 6e-8 s). The start-up stays finite,
    # the driver runs on the stable branch of its torque curve (between the breakdown and
    # the synchronous speed), and no span carries more than twice the breakdown torque on
    # the driver's pitch radius (a passive train under a suddenly applied torque)
    a = analyze(drive_from_mapping(_eight_sprocket(speed="1 rpm")))
    s = a.startup
    assert s is not None
    assert np.isfinite(s.max_span_force).all() and np.isfinite(s.speeds).all()
    assert np.isfinite(s.span_forces).all()
    law = a.drive_model.motor.law
    assert isinstance(law, KlossMotor)
    w_s = law.synchronous_speed
    w = s.speeds[-1, a.drive_model.driver_index]
    assert (1.0 - law.critical_slip) * w_s <= w <= w_s
    radius = a.drive.chain.spec.pitch / (2.0 * math.sin(math.pi / a.drive.driver.teeth))
    assert 0.0 < s.max_span_force.max() <= 2.0 * law.breakdown_ratio * law.rated_torque / radius
    assert s.k1 is not None and s.k1 > 0


def _with_stiff_light_trains(data: dict) -> dict:
    for i, sp in enumerate(data["sprockets"]):
        if sp.get("role") in ("driver", "driven"):
            sp["train"] = [{"kind": "shaft", "name": f"n{i}", "stiffness": "1e10 N*m/rad",
                            "inertia": "1e-8 kg*m^2"}]
    return data


def test_stiff_light_trains_start_up_finite_and_as_without_them() -> None:
    # the stiffest allowed shafts (1e10 N·m/rad) to the lightest allowed nodes (1e-8 kg·m²) on
    # the driver and every driven sprocket, the motor on the driver's node: a mode of 1e9 rad/s
    # that the step (3e-5 s) cannot resolve. Such a train adds no inertia and no compliance,
    # so the start-up is the drive's without the trains: the same peak span forces and final
    # speeds, and every node turning with its sprocket
    plain = analyze(drive_from_mapping(_eight_sprocket())).startup
    a = analyze(drive_from_mapping(_with_stiff_light_trains(_eight_sprocket())))
    s = a.startup
    assert s is not None and plain is not None
    assert np.isfinite(s.max_span_force).all() and np.isfinite(s.rotor_speeds).all()
    assert s.settled
    assert_allclose(s.max_span_force, plain.max_span_force, rtol=0.01)
    assert_allclose(s.speeds[-1], plain.speeds[-1], rtol=0.01)
    names = list(a.drive_model.sprocket_names)
    for j, rotor in enumerate(s.rotor_names):
        owner = next(k for k, t in a.drive_model.trains.items()
                     if any(rotor in (e.get("to"), e.get("node")) for e in t))
        assert_allclose(s.rotor_speeds[-1, j], s.speeds[-1, names.index(owner)], rtol=0.01)


def test_kloss_end_speed_solves_backward_euler_on_the_curve() -> None:
    # the motor from rest with a step far beyond its time constant: the end speed solves
    # u − a = g (f(u) − f(w)) and lies on the stable branch (between breakdown and
    # synchronous speed), the first root toward a
    m = KlossMotor(4000.0, 0.10471975511965977)
    peak, ws = 2.0 * m.breakdown_ratio * m.rated_torque, m.synchronous_speed
    for g in (1e-6, 0.015, 10.0):
        fw = m(0.0, 0.0)
        a = g * fw
        u = kloss_end_speed(0.0, a, fw, g, 1.0, 1.0, peak, m.critical_slip, ws)
        assert abs(u - a - g * (m(0.0, u) - fw)) <= 1e-12 * (abs(a) + abs(u))
        assert 0.0 < u <= ws
        if g >= 0.015:
            assert u >= (1.0 - m.critical_slip) * ws
