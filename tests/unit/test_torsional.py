"""TorsionalModel: construction errors, matrices for the integrator, torques through reducers,
strain-energy shares (src/chaindrive/dynamics/torsional/model.py)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.dynamics import TorsionalModel, reducer_input_torque
from chaindrive.errors import DesignError


def _motor_pump() -> TorsionalModel:
    # the brief's example: motor, shaft, gear pair 3:1, ground spring on the wheel
    return (TorsionalModel().add_inertia("motor", 400.0).add_shaft("motor", "pinion", 1.88e5)
            .add_gear_mesh("pinion", "wheel", ratio=3.0).add_ground_spring("wheel", 5.0e4))


def test_springs_in_series_through_a_gear() -> None:
    # closed form: k_eq = 1 / (1/k_s + i²/k_g) at the motor, f = sqrt(k_eq/J)/2π; pinion and
    # wheel are massless and condensed out
    modes = _motor_pump().modal()
    k_eq = 1 / (1 / 1.88e5 + 3.0**2 / 5.0e4)
    assert_allclose(modes.frequencies_hz, [math.sqrt(k_eq / 400) / (2 * math.pi)], rtol=1e-12)
    # wheel turns 3× slower and the other way (external pair)
    shapes = modes.node_shapes
    assert_allclose(shapes["wheel"][0], -shapes["pinion"][0] / 3, rtol=1e-12)
    assert modes.governing_element(0) == "ground:wheel"
    json.dumps(modes.to_dict())


@pytest.mark.parametrize(("build", "field"), [
    (lambda t: t.add_inertia("a", -1.0), "a"),
    (lambda t: t.add_shaft("a", "b", -5.0), "shaft:a-b"),
    (lambda t: t.add_shaft("a", "b", 5.0, damping=float("nan")), "shaft:a-b"),
    (lambda t: t.add_shaft("a", "a", 5.0), "shaft:a-a"),
    (lambda t: t.add_ground_spring("nowhere", 1.0), "ground:nowhere"),
    (lambda t: t.add_gear_mesh("a", "b", ratio=0.0), "mesh:a-b"),
    (lambda t: t.add_gear_mesh("a", "b", ratio=2.0, efficiency=1.2), "mesh:a-b"),
    (lambda t: t.add_span("a", "b", 1e6, 0.0, 0.1), "span:a-b"),
    (lambda t: t.add_inertia("a", 1.0).add_inertia("a", 2.0), "a"),
    (lambda t: t.add_shaft("a", "b", 1.0, name="s").add_shaft("a", "c", 2.0, name="s"), "s"),
])
def test_bad_input_names_the_element(build, field: str) -> None:
    with pytest.raises(DesignError) as err:
        build(TorsionalModel())
    assert err.value.field == field


def test_default_element_names_are_unique() -> None:
    # two ground springs on one node without names: both kept (numbered names), and they act
    # in parallel: f = √((k₁ + k₂)/J)/2π (one rotor on two springs to ground, Rao §2.2)
    t = TorsionalModel().add_inertia("rotor", 2.0)
    t.add_ground_spring("rotor", 3e4).add_ground_spring("rotor", 5e4)
    t.add_shaft("rotor", "hub", 1e5).add_shaft("rotor", "hub", 2e5)
    t.add_inertia("hub", 1.0)
    assert {"ground:rotor", "ground:rotor#2", "shaft:rotor-hub", "shaft:rotor-hub#2"} <= set(
        t.system().element_names)
    single = TorsionalModel().add_inertia("rotor", 2.0).add_ground_spring("rotor", 8e4)
    assert_allclose(single.frequencies_hz(), [math.sqrt(8e4 / 2.0) / (2 * math.pi)], rtol=1e-12)
    both = TorsionalModel().add_inertia("rotor", 2.0)
    both.add_ground_spring("rotor", 3e4).add_ground_spring("rotor", 5e4)
    assert_allclose(both.frequencies_hz(), single.frequencies_hz(), rtol=1e-12)


def test_gear_loop_that_over_constrains() -> None:
    t = TorsionalModel().add_gear_mesh("a", "b", ratio=2.0).add_gear_mesh("b", "c", ratio=3.0)
    t.add_gear_mesh("a", "c", ratio=6.0, same_sense=True)  # consistent: (−1/2)(−1/3) = +1/6
    with pytest.raises(DesignError, match="over-constrains") as err:
        t.add_gear_mesh("c", "a", ratio=1 / 5.0, same_sense=True, name="bad mesh")
    assert err.value.field == "bad mesh"


def test_free_massless_node_and_all_massless() -> None:
    t = TorsionalModel().add_inertia("a", 1.0).add_inertia("b", 1.0).add_shaft("a", "b", 1e3)
    t.add_inertia("loose", 0.0)
    with pytest.raises(DesignError, match="not held"):
        t.modal()
    with pytest.raises(DesignError, match="massless"):
        TorsionalModel().add_shaft("a", "b", 1.0).add_ground_spring("a", 1.0).modal()


def test_condensed_refuses_a_damper_on_a_massless_node() -> None:
    t = (TorsionalModel().add_inertia("a", 1.0).add_inertia("c", 2.0)
         .add_shaft("a", "b", 1e4, damping=3.0).add_shaft("b", "c", 2e4))
    with pytest.raises(DesignError, match="first-order"):
        t.system().condensed()
    u = (TorsionalModel().add_inertia("a", 1.0).add_inertia("c", 2.0)
         .add_shaft("a", "b", 1e4).add_shaft("b", "c", 2e4))
    T, M, K, C = u.system().condensed()  # coordinates a, c (massed) and b (massless)
    k = 1 / (1 / 1e4 + 1 / 2e4)  # springs in series
    assert_allclose(K, [[k, -k], [-k, k]], rtol=1e-12)
    assert_allclose(M, np.diag([1.0, 2.0]))
    # the massless b sits where the springs balance: φ_b = (k1 φ_a + k2 φ_c) / (k1 + k2)
    assert_allclose(T[u.system().dof_of("b")[0]], [1 / 3, 2 / 3], rtol=1e-12)
    assert not C.any()


def test_span_matrices_for_the_integrator() -> None:
    # two sprockets, the second wrapped from the inside (negative radius), on a motor shaft
    t = (TorsionalModel().add_inertia("s1", 0.2).add_inertia("s2", 0.5).add_inertia("motor", 1.0)
         .add_span("s1", "s2", 2e6, 0.1, -0.15, damping=40.0, name="tight")
         .add_span("s2", "s1", 1e6, -0.15, 0.1, name="slack")
         .add_shaft("motor", "s1", 5e4, damping=2.0))
    s = t.system()
    q = np.array([0.01, -0.02, 0.03])
    e = s.span_incidence @ q
    phi = s.node_angles(q)
    assert_allclose(e[0], -0.15 * phi["s2"] - 0.1 * phi["s1"], rtol=1e-12)
    assert s.span_names == ("tight", "slack") and s.span_tension_only.all()
    K_all = s.stiffness_matrix()
    K_tight = s.stiffness_matrix([True, False])
    B = s.span_incidence
    assert_allclose(K_all - K_tight, 1e6 * np.outer(B[1], B[1]), rtol=1e-12)
    assert_allclose(s.damping_matrix() - s.damping_linear, 40.0 * np.outer(B[0], B[0]))
    # strain energy of q equals ½ Σ k e² over the elements
    energy = 0.5 * q @ K_all @ q
    strains = s.element_incidence @ q
    assert_allclose(energy, 0.5 * np.sum(s.element_stiffness * strains**2), rtol=1e-12)
    Q = s.generalized_force({"motor": 100.0})
    assert Q[s.dof_of("motor")[0]] == 100.0


def test_torques_through_a_two_stage_reducer() -> None:
    # T_in = T_out / (i η) in the driving direction, T_out η / i back-driven; a train of two
    # stages multiplies the ratios and the efficiencies
    assert reducer_input_torque(300.0, 3.0, 0.95) == pytest.approx(300 / (3 * 0.95))
    assert reducer_input_torque(300.0, 3.0, 0.95, driving=False) == pytest.approx(300 * 0.95 / 3)
    t = (TorsionalModel().add_inertia("motor", 0.1).add_shaft("motor", "p1", 1e5)
         .add_gear_mesh("p1", "w1", ratio=4.0, efficiency=0.97)
         .add_gear_mesh("w1", "w2", ratio=2.5, efficiency=0.96, same_sense=True))
    t.add_inertia("load", 3.0).add_shaft("w2", "load", 1e6)
    torque = t.referred_torque(1000.0, at="w2", to="p1")
    assert torque == pytest.approx(-1000.0 / (10.0 * 0.97 * 0.96))  # one external pair: sign flips
    assert t.referred_torque(1000.0, at="w2", to="p1", driving=False) == pytest.approx(
        -1000.0 * 0.97 * 0.96 / 10.0)
    with pytest.raises(DesignError, match="not joined"):
        t.referred_torque(1.0, at="load", to="motor")


def test_energy_shares_and_a_locked_gear_loop() -> None:
    # a shaft closing a gear loop with a ratio ≠ 1 holds the train: no rigid-body mode
    t = (TorsionalModel().add_inertia("a", 1.0).add_inertia("b", 1.0)
         .add_gear_mesh("a", "b", ratio=2.0, same_sense=True).add_shaft("a", "b", 1e4))
    modes = t.modal()
    assert not modes.rigid_body.any()
    # φ_b = φ_a/2: twist = −φ_a/2, k_eff = k/4, J_eff = 1 + 1/4
    assert_allclose(modes.frequencies_hz, [math.sqrt(1e4 / 4 / 1.25) / (2 * math.pi)], rtol=1e-12)
    assert_allclose(modes.strain_energy_shares.sum(axis=0), [1.0])


def test_from_contour_validates_its_data() -> None:
    with pytest.raises(DesignError, match="unknown sprocket"):
        TorsionalModel.from_contour(["a", "b"], [1, 1], [0.1, 0.1], [1e6, 1e6],
                                    trains={"c": [{"name": "m", "stiffness": 1.0}]})
    with pytest.raises(DesignError) as err:
        TorsionalModel.from_contour(["a", "b"], [1, 1], [0.1, 0.1], [1e6, 1e6],
                                    trains={"a": [{"name": "m", "stifness": 1.0}]})
    assert err.value.field == "trains.a[0]"
    with pytest.raises(DesignError) as err:
        TorsionalModel.from_contour(["a", "b"], [1, 1], [0.1, -0.1], [1e6, 1e6])
    assert err.value.field == "pitch_radii_m"
    with pytest.raises(DesignError) as err:
        TorsionalModel.from_contour(["a", "b"], [1, 1, 1], [0.1, 0.1], [1e6, 1e6])
    assert err.value.field == "inertias_kg_m2"


def test_frequencies_without_shapes_and_an_inside_sprocket() -> None:
    # frequencies_hz() (no eigenvectors) = modal(); an idler wrapped from the inside turns the
    # other way (sense −1): the frequencies are those of the ring model all the same
    from chaindrive.dynamics import RingModel

    J, R, c = [0.4, 0.02, 1.5, 0.3], [0.08, 0.05, 0.15, 0.1], [3e6, 2e6, 2.5e6, 4e6]
    t = TorsionalModel.from_contour(["a", "b", "c", "d"], J, R, c, senses=[1, -1, 1, 1],
                                    trains={"c": [{"name": "motor", "inertia": 0.5,
                                                   "stiffness": 4e4, "damping": 1.0}]})
    assert_allclose(t.frequencies_hz(), t.modal().frequencies_hz, rtol=1e-12)
    modes = t.modal()
    assert modes.rigid_body[0] and modes.node_shapes["b"][0] * modes.node_shapes["a"][0] < 0  # turns back
    rigid = (TorsionalModel.from_contour(["a", "b", "c", "d"], J, R, c, senses=[1, -1, 1, 1])
             .frequencies_hz())
    ring = RingModel(np.array(J) / np.array(R) ** 2, c).modal().frequencies_hz
    assert_allclose(rigid, ring, rtol=1e-10, atol=1e-9)


def test_several_rigid_groups_against_the_generalised_eigenproblem() -> None:
    # a grounded rotor and two free pairs: two rigid-body modes (exact zeros), the elastic
    # frequencies those of scipy.linalg.eigh(K, M), the shapes M-orthonormal
    import scipy.linalg

    t = (TorsionalModel().add_inertia("g", 2.0).add_ground_spring("g", 1e4)
         .add_inertia("a", 1.0).add_inertia("b", 3.0).add_shaft("a", "b", 5e3)
         .add_inertia("c", 1.5).add_inertia("d", 0.5).add_shaft("c", "d", 2e3))
    modes, s = t.modal(), t.system()
    assert modes.rigid_body.tolist() == [True, True, False, False, False]
    assert (modes.frequencies_hz[:2] == 0.0).all()
    lam = scipy.linalg.eigh(s.stiffness_matrix(), s.mass_matrix(), eigvals_only=True)
    assert_allclose(modes.frequencies_hz[2:], np.sqrt(np.sort(lam)[2:]) / (2 * math.pi),
                    rtol=1e-10)
    Q = modes.modal_coordinates
    assert_allclose(Q.T @ s.mass_matrix() @ Q, np.eye(5), atol=1e-12)
