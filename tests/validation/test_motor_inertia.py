"""Rotor inertia estimate against the catalogue it was fitted to ([MotiveDelphi], technical
data tables for 2, 4 and 6 poles; src/chaindrive/dynamics/motor_inertia.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.dynamics import estimated_rotor_inertia
from chaindrive.dynamics.motor_inertia import (
    CATALOGUE,
    EXCLUDED,
    FIT_COEFFICIENTS,
    MAX_SCATTER_FACTOR,
    RMS_SCATTER_FACTOR,
    fit_coefficients,
)
from chaindrive.errors import DesignError


def test_coefficients_are_the_least_squares_fit_of_the_catalogue() -> None:
    assert_allclose(fit_coefficients(), FIT_COEFFICIENTS, rtol=1e-9)


def test_reproduces_the_catalogue_within_the_stated_scatter() -> None:
    # every catalogue motor within the stated largest factor, the rms factor as stated
    ratios = []
    for motor, power_kw, _speed, inertia in CATALOGUE:
        if motor in EXCLUDED:
            continue
        poles = int(motor.rsplit("-", 1)[1])
        est = estimated_rotor_inertia(power_kw * 1e3, 2 * math.pi * 50 / (poles / 2))
        assert est.is_estimate and est.low_kg_m2 <= inertia <= est.high_kg_m2, motor
        ratios.append(math.log(inertia / est.inertia_kg_m2))
    r = np.array(ratios)
    assert len(r) == 107
    assert math.exp(np.sqrt(np.mean(r**2))) == pytest.approx(RMS_SCATTER_FACTOR, abs=1e-3)
    assert math.exp(np.abs(r).max()) == pytest.approx(MAX_SCATTER_FACTOR, abs=1e-3)
    assert abs(r.mean()) < 1e-9  # least squares with a constant term: no bias


def test_catalogue_rows_are_consistent() -> None:
    # rated speed below synchronous speed (slip), J increasing with power on each frame line
    for motor, power_kw, speed, inertia in CATALOGUE:
        poles = int(motor.rsplit("-", 1)[1])
        assert 0.85 * 6000 / poles < speed < 6000 / poles, motor
        assert power_kw > 0 and inertia > 0


def test_outside_the_catalogue_range_is_refused() -> None:
    with pytest.raises(DesignError) as err:
        estimated_rotor_inertia(2e6, 157.08)
    assert err.value.field == "motor.rated_power" and "N·m" in str(err.value)
    with pytest.raises(DesignError) as err:
        estimated_rotor_inertia(5e3, 30.0)
    assert err.value.field == "motor.rated_speed" and "286.5 rpm" in str(err.value)
