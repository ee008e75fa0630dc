"""The whole-drive model from a design file: trains, motor, machines, completeness, damping
sources, the design schema and the bounded start-up (chaindrive.dynamics.model.build)."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

import chaindrive
from chaindrive import examples
from chaindrive.dynamics.damping import span_hinge_damping_ratios
from chaindrive.dynamics.model.build import shaft_stiffness
from chaindrive.dynamics.motor_inertia import estimated_rotor_inertia
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping, drive_to_toml, parse_toml, schema
from chaindrive.model import TrainElement


@pytest.fixture(scope="module")
def conveyor() -> chaindrive.analysis.Analysis:
    return chaindrive.analyze(examples.load("conveyor_five_sprocket"))


def test_schema_lists_trains_motor_and_dynamics_fields() -> None:
    doc = schema()
    train = {f["field"]: f for f in doc["sprockets.train"]}
    assert {"kind", "inertia", "stiffness", "damping", "ratio", "efficiency", "diameter",
            "length"} <= set(train)
    assert train["stiffness"]["si_unit"] == "N*m/rad"
    assert {f["field"] for f in doc["motor"]} >= {"rated_power", "rated_speed",
                                                  "rotor_inertia", "breakdown_ratio"}
    dyn = {f["field"] for f in doc["dynamics"]}
    assert {"hinge_friction", "uncertainty", "require_complete_model"} <= dyn
    assert "reduced_mass" in {f["field"] for f in doc["sprockets"]}


def test_design_file_round_trip_keeps_trains_and_motor() -> None:
    drive = examples.load("conveyor_five_sprocket")
    again = drive_from_mapping(parse_toml(drive_to_toml(drive), "again.toml"))
    assert again.motor == drive.motor
    for a, b in zip(again.sprockets, drive.sprockets, strict=True):
        assert len(a.train) == len(b.train)
        for ea, eb in zip(a.train, b.train, strict=True):
            assert ea.kind == eb.kind and ea.name == eb.name
            for key in ("inertia", "stiffness", "damping", "ratio", "efficiency", "diameter"):
                va, vb = getattr(ea, key), getattr(eb, key)
                assert (va is None and vb is None) or va == pytest.approx(vb, rel=1e-11)
        assert a.load == b.load


@pytest.mark.parametrize(("element", "field"), [
    ('{kind = "gear", ratio = 0}', "sprockets[0].train[0].ratio"),
    ('{kind = "shaft", stiffness = "1e4 N*m/rad", diameter = "40 mm", length = "1 m"}',
     "sprockets[0].train[0].stiffness"),
    ('{kind = "rotor"}', "sprockets[0].train[0].inertia"),
    ('{kind = "belt"}', "sprockets[0].train[0].kind"),
    ('{kind = "coupling", stiffness = "1e4 N/m"}', None),
])
def test_bad_train_element_names_its_field(element: str, field: str | None) -> None:
    text = examples.text("two_sprocket_jindal").replace(
        'role = "driver"', f'role = "driver"\ntrain = [{element}]', 1)
    with pytest.raises(DesignError) as err:
        drive_from_mapping(parse_toml(text, "x.toml"))
    assert str(err.value).startswith(field or "sprockets[0].train[0].stiffness")


def test_a_ground_spring_holds_the_drive() -> None:
    # a spring to the frame on a driven machine (a torque arm): no rigid-body mode is left,
    # and as its stiffness vanishes the first frequency tends to 0 (the free drive)
    drive = examples.load("conveyor_five_sprocket")

    def f1(k: float) -> float:
        s = drive.sprockets[1]
        ground = TrainElement("ground", stiffness=k)
        d = replace(drive, sprockets=(drive.sprockets[0], replace(s, train=(*s.train, ground)),
                                      *drive.sprockets[2:]))
        modes = chaindrive.analyze(d, response=False).dynamics.modal
        assert not modes.rigid_body.any()
        return float(modes.frequencies_hz[0])

    assert f1(1e-3) < 0.01 < 1.0 < f1(1e5)


def test_shaft_stiffness_closed_form() -> None:
    # k = G J_p / l, G = E/(2(1 + ν)), J_p = π d⁴/32 (Shigley §4-12): a 50 × 300 mm steel shaft
    k = shaft_stiffness(0.05, 0.3, 210e9)
    assert k == pytest.approx(210e9 / 2.6 * math.pi * 0.05**4 / 32 / 0.3, rel=1e-12)
    e = TrainElement("shaft", "x", diameter=0.05, length=0.3)
    drive = examples.load("conveyor_five_sprocket")
    d = replace(drive, sprockets=(replace(drive.sprockets[0], train=(e,)),
                                  *drive.sprockets[1:]))
    a = chaindrive.analyze(d, response=False)
    assert a.drive_model.trains["S1"][0]["stiffness_n_m_per_rad"] == pytest.approx(k)


def test_conveyor_trains_motor_and_machines(conveyor) -> None:
    m = conveyor.drive_model
    assert m.complete and m.motor is not None
    assert m.motor.node == "motor" and m.motor.efficiency == pytest.approx(0.94)
    assert m.motor.nominal_speed == pytest.approx(110 * 13.0 * math.pi / 30, rel=1e-12)
    assert {ld.node for ld in m.loads} == {"drum 1", "drum 2", "drum 3"}
    # each machine takes its power share at its nominal speed: P_i = M_i ω_i
    p = sum(ld.torque * ld.nominal_speed for ld in m.loads)
    assert p == pytest.approx(3000.0, rel=1e-12)
    # after the run-up every rotor turns at its nominal speed (through the reducer) within
    # the motor's slip and the steady ripple
    st = conveyor.startup
    assert st is not None
    final = dict(zip(st.rotor_names, st.rotor_speeds[-200:].mean(axis=0), strict=True))
    assert final["reducer in"] == pytest.approx(110 * 13.0 * math.pi / 30, rel=0.03)
    assert final["drum 2"] == pytest.approx(110 * 19 / 25 * math.pi / 30, rel=0.03)
    # the drums' couplings govern the first modes
    assert conveyor.dynamics.modal.governing[1].startswith("coupling:")


def test_motor_power_in_steady_running_covers_the_losses(conveyor) -> None:
    """After the run-up the motor delivers the machines' power over the reducer's efficiency:
    T_m ω_m η = Σ P_i (power balance of the gear stage, [Shigley2015, ch. 13])."""
    m = conveyor.drive_model
    st = conveyor.startup
    w = float(st.rotor_speeds[-500:, st.rotor_names.index("motor")].mean())
    torque = m.motor.law(1.0, w)
    loads = sum(ld.torque * ld.nominal_speed for ld in m.loads)
    assert torque * w * m.motor.efficiency == pytest.approx(loads, rel=0.03)


def test_incomplete_model_warns_and_can_be_an_error() -> None:
    drive = examples.load("eight_sprocket")
    a = chaindrive.analyze(drive, response=False)
    codes = [w.code for w in a.warnings]
    assert codes.count("dynamics.model-incomplete") == 1
    doc = a.to_dict()
    assert doc["dynamics"]["model"]["complete"] is False
    assert "the driver M has no motor" in doc["dynamics"]["model"]["missing"]
    strict = replace(drive, dynamics=replace(drive.dynamics, require_complete_model=True))
    with pytest.raises(DesignError, match="require_complete_model"):
        chaindrive.analyze(strict, response=False)


def test_estimated_rotor_inertia_is_said() -> None:
    drive = examples.load("conveyor_five_sprocket")
    d = replace(drive, motor=replace(drive.motor, rotor_inertia=None))
    a = chaindrive.analyze(d, response=False)
    m = a.drive_model.motor
    assert m is not None and m.estimated
    # the catalogue fit at the Kloss motor's synchronous speed [MotiveDelphi]
    kloss = m.law
    ref = estimated_rotor_inertia(3000.0, kloss.synchronous_speed).inertia_kg_m2
    assert m.rotor_inertia == pytest.approx(ref)
    assert 0.5 < m.rotor_inertia / 0.0067 < 2.0  # the catalogue's 100LB-4: 0.0067 kg·m²
    assert "dynamics.estimate" in {w.code for w in a.warnings}


def test_hinge_friction_damps_each_span_at_its_own_tension() -> None:
    drive = examples.load("seed_three_sprocket")
    d = replace(drive, dynamics=replace(drive.dynamics, hinge_friction=True))
    a = chaindrive.analyze(d)
    m = a.drive_model
    lengths = [s.length for s in a.geometry.spans]
    expected = span_hinge_damping_ratios(a.strength.loads.span_tensions, lengths,
                                         d.chain.spec.pin_diameter, 0.02)
    np.testing.assert_allclose(m.span_damping_ratios, expected)
    assert m.damping_source.startswith("hinge friction")
    # it enters the responses: the resonant seed example responds differently
    pair = chaindrive.analyze(drive)
    assert a.steady.coefficient_of_dynamics != pytest.approx(
        pair.steady.coefficient_of_dynamics, rel=0.01)
    assert "dynamics.hinge-friction-extrapolated" in {w.code for w in a.warnings}


def test_json_has_the_model_trains_and_bands(conveyor) -> None:
    doc = json.loads(json.dumps(conveyor.to_dict()))
    dyn = doc["dynamics"]
    assert dyn["model"]["complete"] is True
    assert dyn["model"]["trains"]["S1"][1]["kind"] == "gear"
    assert dyn["bands"]["uncertainty"] == 0.1
    assert len(dyn["bands"]["natural_frequencies_hz"]) == len(
        conveyor.dynamics.modal.elastic_frequencies_hz)
    kd = dyn["bands"]["coefficient_of_dynamics"]
    assert kd["low"] <= kd["nominal"] <= kd["high"]
    assert dyn["startup"]["runup_time_s"] > 0 and dyn["startup"]["decay_time_s"] >= 0
    assert set(dyn["steady"]["rotor_irregularity_percent"]) == set(
        conveyor.drive_model.rotor_names)


def test_a_start_up_beyond_the_work_budget_is_refused_in_one_line() -> None:
    drive = examples.load("twenty_four_sprocket")
    d = replace(drive, dynamics=replace(drive.dynamics, startup_duration=60.0))
    with pytest.raises(DesignError) as err:
        chaindrive.analyze(d)
    text = str(err.value)
    assert "\n" not in text and "start-up step" in text and "startup_duration" in text


def test_a_vanishing_sprocket_inertia_ends_with_a_result_or_one_line() -> None:
    """A two-sprocket drive with a sprocket of 1e-10 kg·m²: the chain's own mass and the
    tooth contact keep the chain's modes where they were, so the start-up's step does not
    follow the vanishing body (the exact zero-order hold takes its stiff mode); the run gives
    finite results (or, should a model put the step on it, one line naming it)."""
    drive = examples.load("two_sprocket_jindal")
    tiny = replace(drive, sprockets=(replace(drive.sprockets[0], inertia=1e-10),
                                     *drive.sprockets[1:]))
    try:
        a = chaindrive.analyze(tiny)
    except DesignError as exc:
        message = str(exc)
        a = None
    if a is None:
        assert "inertia" in message and "\n" not in message
    else:
        assert a.startup is not None and np.all(np.isfinite(a.startup.max_span_force))
        assert a.startup.steps < 1e6
