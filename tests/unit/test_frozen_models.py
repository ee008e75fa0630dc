"""Built models cannot change: the torsional model once its system is assembled, the linear
model, the whole-drive model and the ring (attributes and arrays), also after a round trip
through pickle (the web page's worker processes)."""

from __future__ import annotations

import pickle
from dataclasses import FrozenInstanceError

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import chaindrive
from chaindrive import examples
from chaindrive.dynamics import RingModel, TorsionalModel
from chaindrive.dynamics.model.build import DriveModel, LinearModel


@pytest.fixture(scope="module")
def seed_model() -> DriveModel:
    return chaindrive.analyze(examples.load("seed_three_sprocket"), response=False).dynamics.model


def _two_rotors() -> TorsionalModel:
    t = TorsionalModel().add_inertia("a", 1.0).add_inertia("b", 2.0)
    t.add_shaft("a", "b", 1e4, name="s")
    return t


def test_torsional_model_is_frozen_once_its_system_is_assembled() -> None:
    t = _two_rotors()
    t.add_ground_spring("a", 5.0)  # still a builder: nothing assembled yet
    system = t.system()
    for change in (lambda: t.add_inertia("c", 1.0), lambda: t.add_shaft("a", "b", 1.0),
                   lambda: t.add_ground_spring("b", 1.0), lambda: t.set_damping("s", 2.0),
                   lambda: t.add_gear_mesh("b", "c", 2.0), lambda: t.rename_node("a", "z"),
                   lambda: t.add_span("a", "b", 1e6, 0.1, 0.1), lambda: t.add_inertia_to("a", 1)):
        with pytest.raises(FrozenInstanceError):
            change()
    with pytest.raises(FrozenInstanceError):
        t._elements = []
    assert t.system() is system  # nothing changed: the same system
    with pytest.raises(ValueError, match="read-only"):
        system.stiffness_linear[0, 0] = 0.0
    assert TorsionalModel.from_contour(["a", "b"], [1, 1], [0.1, 0.1], [1e6, 1e6])._built


def test_with_damping_gives_a_built_copy_and_leaves_the_model() -> None:
    t = _two_rotors()
    t.build()
    u = t.with_damping({"s": 3.0})
    assert_array_equal(u.system().damping_linear, [[3.0, -3.0], [-3.0, 3.0]])  # c·(−1, 1)ᵀ(−1, 1)
    assert not t.system().damping_linear.any()
    with pytest.raises(FrozenInstanceError):
        u.add_inertia("c", 1.0)


def test_linear_model_arrays_are_read_only_and_inputs_stay_writeable() -> None:
    mass = np.eye(2)
    lin = LinearModel(mass, np.zeros((2, 2)), np.zeros((2, 2)), np.array([[-1.0, 1.0]]),
                      np.array([1e5]), np.array([2.0]), np.array([True]))
    with pytest.raises(FrozenInstanceError):
        lin.mass = np.eye(2)  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        lin.mass[0, 0] = 2.0
    mass[0, 0] = 5.0  # the caller's array is copied, not frozen
    assert lin.mass[0, 0] == 1.0
    assert lin.scaled(2.0, 3.0).span_stiffness[0] == 2e5
    assert not lin.scaled(2.0).span_incidence.flags.writeable


def test_drive_model_is_frozen_also_after_pickling(seed_model: DriveModel) -> None:
    for model in (seed_model, pickle.loads(pickle.dumps(seed_model))):
        assert isinstance(model, DriveModel)
        for array in (model.linear.mass, model.linear.span_damping, model.sprocket_gain,
                      model.condensation, model.system.element_incidence):
            assert not array.flags.writeable
        with pytest.raises(FrozenInstanceError):
            model.linear = model.linear  # type: ignore[misc]
        with pytest.raises(FrozenInstanceError):
            model.torsional.add_inertia("extra", 1.0)
    # the chain's dampers reach the torsional model's copy, not the pre-damper assembly
    assert seed_model.torsional.system().span_damping_n_s_per_m.tolist() == \
        seed_model.linear.span_damping.tolist()
    assert not seed_model.system.span_damping_n_s_per_m.any()


def test_ring_model_is_frozen() -> None:
    ring = RingModel([1.0, 2.0], [1e5, 1e5], names=["a", "b"])  # type: ignore[arg-type]
    with pytest.raises(FrozenInstanceError):
        ring.closed = False  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        ring.masses_kg[0] = 3.0
    assert ring.names == ("a", "b")


def test_ring_torsional_and_whole_drive_return_the_one_modal_result(
        seed_model: DriveModel) -> None:
    from chaindrive.dynamics.modes import Modes, drive_modes

    ring = RingModel([1.0, 2.0, 3.0], [1e5, 2e5, 3e5], damping_ratio=0.06).modal()
    drive = drive_modes(seed_model)
    torsional = seed_model.modal()
    for modes in (ring, drive, torsional):
        assert isinstance(modes, Modes)
        assert not modes.shapes.flags.writeable
        with pytest.raises(FrozenInstanceError):
            modes.damping_ratio = 0.0  # type: ignore[misc]
    # the ring's modal damping: ζ on every elastic mode, f_d = f·sqrt(1 − ζ²) [Rao2011, ch. 2]
    assert ring.modal_damping_ratios.tolist() == [0.0, 0.06, 0.06]
    assert ring.damped_frequencies_hz[1] == pytest.approx(ring.frequencies_hz[1] *
                                                          (1 - 0.06**2) ** 0.5, rel=1e-15)
    assert drive.system is not None and ring.system is None
    assert drive.modal_coordinates is not None and drive.right is not None
    assert not drive.modal_coordinates.flags.writeable
    assert not drive.right.flags.writeable  # the complex modes of the damped model
    # the undamped torsional analysis gives no damped fields; the drive's adds them to the
    # same frequencies and shapes of every node
    assert torsional.damped_frequencies_hz.size == 0 and torsional.eigenvalues is None
    assert_array_equal(drive.frequencies_hz, torsional.frequencies_hz)
    assert_array_equal(drive.shape_matrix, torsional.shapes)
    assert drive.governing == tuple(torsional.governing_element(j)
                                    for j in range(torsional.frequencies_hz.size))
    assert drive.partial_frequencies_hz.size == 0 and ring.partial_frequencies_hz.size == 3
