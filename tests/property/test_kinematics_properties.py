"""Property tests of the polygonal kinematics laws (hypothesis)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from chaindrive import kinematics as kin

teeth = st.integers(min_value=6, max_value=150)
pitch = st.floats(min_value=4e-3, max_value=0.1)
speed = st.floats(min_value=0.1, max_value=500.0)
PSI = np.linspace(-np.pi, np.pi, 721)


@settings(max_examples=40, deadline=None)
@given(pitch, teeth, speed)
def test_instantaneous_speed_bounded(p: float, z: int, omega: float) -> None:
    v = kin.instantaneous_chain_speed(p, z, omega, PSI)
    lo, hi = kin.min_chain_speed(p, z, omega), kin.max_chain_speed(p, z, omega)
    assert np.all(v >= lo * (1 - 1e-12))
    assert np.all(v <= hi * (1 + 1e-12))
    assert lo < kin.mean_chain_speed(p, z, omega) < hi


@settings(max_examples=40, deadline=None)
@given(pitch, teeth)
def test_peak_matches_sampled_exact_law(p: float, z: int) -> None:
    sampled = np.max(kin.hinge_displacement_exact(p, z, np.linspace(0, np.pi, 20001)))
    peak = kin.hinge_displacement_peak(p, z)
    assert sampled <= peak * (1 + 1e-9)
    assert sampled >= peak * (1 - 1e-6)


@settings(max_examples=30, deadline=None)
@given(pitch, teeth, st.integers(min_value=1, max_value=29))
def test_series_error_decreases(p: float, z: int, n: int) -> None:
    exact = kin.hinge_displacement_exact(p, z, PSI)
    e_n = np.max(np.abs(kin.hinge_displacement_fourier(p, z, PSI, n) - exact))
    e_more = np.max(np.abs(kin.hinge_displacement_fourier(p, z, PSI, n + 1) - exact))
    assert e_more <= e_n * (1 + 1e-9)


@settings(max_examples=30, deadline=None)
@given(teeth, teeth, speed)
def test_tooth_frequency_common_to_the_contour(z1: int, z2: int, omega1: float) -> None:
    omega2 = kin.mean_driven_speed(z1, omega1, z2)
    assert np.isclose(kin.tooth_frequency(z1, omega1), kin.tooth_frequency(z2, omega2))
    assert np.isclose(kin.mean_chain_speed(0.0254, z1, omega1),
                      kin.mean_chain_speed(0.0254, z2, omega2))
