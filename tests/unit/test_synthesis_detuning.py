"""The seed's detuning task (seed 000 §3.2, seed-notes §1): a drive built to start inside a
resonance band is detuned by added inertia so that every natural frequency ends at least 10 %
from every working frequency; checked with the drive's own modal analysis afterwards."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from chaindrive.analysis import Analysis
from chaindrive.dynamics.ring import ring_frequencies_batch
from chaindrive.errors import DesignError
from chaindrive.io.design import load_drive
from chaindrive.synthesis.detuning import band_shortfall, detune, detune_drive
from tests.conftest import EXAMPLES


def _relative_distance(a: Analysis) -> float:
    f = a.dynamics.modal.elastic_frequencies_hz
    w = a.working_frequencies_hz
    return float(np.min(np.abs(f[:, None] - w[None, :]) / w[None, :]))


@pytest.fixture(scope="module")
def resonant_drive():
    """The 8-sprocket example with the driver speed set so that the 2nd tooth harmonic falls
    exactly on the first elastic natural frequency."""
    drive = load_drive(EXAMPLES / "eight_sprocket.toml")
    f1 = Analysis(drive).dynamics.modal.elastic_frequencies_hz[0]
    omega = TWO_PI * f1 / 2 / drive.driver.teeth
    return drive.with_sprockets(tuple(replace(s, speed=omega) if s.role == "driver" else s
                                      for s in drive.sprockets))


TWO_PI = 2 * math.pi


def test_example_starts_inside_the_band(resonant_drive) -> None:
    assert _relative_distance(Analysis(resonant_drive)) < 0.01


def test_detuning_by_added_inertia_clears_every_band(resonant_drive) -> None:
    shafts = {s.name: (0.0, 0.2) for s in resonant_drive.sprockets if s.role != "idler"}
    detuned, result = detune_drive(resonant_drive, shafts, seed=1)
    assert result.cleared
    state = Analysis(detuned)  # re-analysed from the drive, not from the optimiser
    assert _relative_distance(state) >= 0.10
    assert detuned.driver.speed == resonant_drive.driver.speed
    for old, new in zip(resonant_drive.sprockets, detuned.sprockets, strict=True):
        if old.name in shafts:
            assert new.inertia is not None and new.inertia > 0


def test_detune_is_reproducible_and_respects_bounds() -> None:
    m = np.array([2.0, 1.0, 1.5, 1.0])
    c = np.full(4, 4e5)
    f0 = ring_frequencies_batch(m[None], c[None])[0][1]  # start exactly on mode 1
    bounds = np.column_stack([m * 0.5, m * 2.0])
    a = detune(m, c, [f0], mass_bounds=bounds, seed=5)
    b = detune(m, c, [f0], mass_bounds=bounds, seed=5)
    np.testing.assert_array_equal(a.masses_kg, b.masses_kg)
    assert a.cleared
    assert np.all(a.masses_kg >= bounds[:, 0] * (1 - 1e-12))
    assert np.all(a.masses_kg <= bounds[:, 1] * (1 + 1e-12))
    np.testing.assert_array_equal(a.stiffness_n_per_m, c)  # not varied


def test_band_shortfall_is_zero_only_outside_the_band() -> None:
    f = np.array([[100.0, 200.0]])
    assert band_shortfall(f, [150.0], 0.1)[0] == 0.0
    assert band_shortfall(f, [105.0], 0.1)[0] > 0.0


def test_detune_needs_something_to_vary() -> None:
    with pytest.raises(DesignError, match="no mass or stiffness may vary"):
        detune([1.0, 2.0], [1e5, 1e5], [50.0])
