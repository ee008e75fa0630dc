"""Unit tests of the polygonal kinematics laws (chaindrive.kinematics)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive import kinematics as kin
from chaindrive.errors import DesignError

MM = 1e-3
PSI = np.linspace(-np.pi, np.pi, 4001)


def test_fourier_coefficients_match_numerical_transform() -> None:
    # independent check of the derivation: FFT of the exact law vs the closed-form b_k
    p, z, n = 25.4 * MM, 11, 8
    m = 4096
    psi = -np.pi + 2 * np.pi * np.arange(m) / m
    spectrum = np.fft.rfft(kin.hinge_displacement_exact(p, z, psi)) / (m / 2)
    k = np.arange(1, n + 1)
    numeric_sine = -(spectrum[k] * np.exp(-1j * np.pi * k)).imag  # shift origin to ψ = 0
    A, B = kin.hinge_displacement_coefficients(p, z, n)
    assert_allclose(numeric_sine, A, atol=1e-10)
    assert_allclose(B, 0.0, atol=0.0)
    assert abs(spectrum[0]) < 1e-12  # zero mean


def test_series_converges_to_exact_law() -> None:
    p, z = 12.7 * MM, 17
    exact = kin.hinge_displacement_exact(p, z, PSI)
    peak = np.max(np.abs(exact))
    errors = [np.max(np.abs(kin.hinge_displacement_fourier(p, z, PSI, n) - exact))
              for n in (1, 2, 3, 5, 10, 20, 30)]
    assert np.all(np.diff(errors) < 0)
    assert errors[-1] < 1e-3 * peak


def test_exact_law_is_continuous_periodic_and_zero_mean() -> None:
    p, z = 25.4 * MM, 15
    assert_allclose(kin.hinge_displacement_exact(p, z, [-np.pi, np.pi, 0.0]), 0.0, atol=1e-15)
    # periodic at the tooth period
    assert_allclose(kin.hinge_displacement_exact(p, z, PSI + 2 * np.pi),
                    kin.hinge_displacement_exact(p, z, PSI), atol=1e-15)
    assert abs(np.trapezoid(kin.hinge_displacement_exact(p, z, PSI), PSI)) < 1e-14


def test_displacement_derivative_is_speed_deviation() -> None:
    # dδ/dτ = v − v̄ with ψ = z ω τ
    p, z, omega = 19.05 * MM, 13, 50.0
    tau = np.linspace(0.0, 2 * np.pi / (z * omega), 2001)[1:-1]
    h = 1e-7
    delta = [kin.hinge_displacement_exact(p, z, kin.tooth_phase(z, omega, tau + s, 0.3))
             for s in (h, -h)]
    numeric = (delta[0] - delta[1]) / (2 * h)
    analytic = kin.hinge_velocity_deviation(p, z, omega, kin.tooth_phase(z, omega, tau, 0.3))
    assert_allclose(numeric, analytic, atol=1e-6 * kin.max_chain_speed(p, z, omega))


def test_phase_shift_is_a_time_shift() -> None:
    p, z, shift = 25.4 * MM, 21, 0.7
    A, B = kin.hinge_displacement_coefficients(p, z, 40, phase=shift)
    k = np.arange(1, 41)
    series = np.sum(A * np.sin(k * PSI[:, None]) + B * np.cos(k * PSI[:, None]), axis=-1)
    assert_allclose(series, kin.hinge_displacement_fourier(p, z, PSI + shift, 40), atol=1e-15)
    assert_allclose(series, kin.hinge_displacement_exact(p, z, PSI + shift), atol=1e-8)


def test_vectorised_over_teeth_and_phase() -> None:
    z = np.array([[9], [15], [30]])
    out = kin.hinge_displacement_fourier(25.4 * MM, z, PSI, harmonics=5)
    assert out.shape == (3, PSI.size)
    A, B = kin.hinge_displacement_coefficients(25.4 * MM, np.array([9, 15]), 4)
    assert A.shape == B.shape == (2, 4)
    assert isinstance(kin.speed_variation_percent(15), float)
    assert kin.speed_variation_percent(np.array([10, 20])).shape == (2,)


def test_speed_variation_falls_with_teeth() -> None:
    z = np.arange(6, 151)
    assert np.all(np.diff(kin.speed_variation_percent(z)) < 0)
    assert np.all(kin.speed_variation_about_mean_percent(z) > kin.speed_variation_percent(z))


def test_instantaneous_ratio_two_sprockets() -> None:
    z1, z2 = 15, 45
    # at ψ = 0 with no offset, both hinges at β = γ = 0: i = R2/R1
    r_ratio = np.sin(np.pi / z1) / np.sin(np.pi / z2)
    assert_allclose(kin.instantaneous_ratio(z1, z2, 0.0), r_ratio, rtol=1e-12)
    ratio = kin.instantaneous_ratio(z1, z2, PSI, phase_offset=0.4)
    assert_allclose(np.mean(ratio), z2 / z1, rtol=0.01)
    omega1 = 30.0
    omega2 = kin.instantaneous_driven_speed(12.7 * MM, z1, z2, omega1, PSI, 0.4)
    assert_allclose(omega1 / omega2, ratio, rtol=1e-12)
    assert_allclose(np.mean(omega2), z1 * omega1 / z2, rtol=0.01)


def test_bad_input_is_refused() -> None:
    with pytest.raises(DesignError, match="teeth"):
        kin.speed_variation_percent(2)
    with pytest.raises(DesignError, match="harmonics"):
        kin.hinge_displacement_coefficients(25.4 * MM, 15, 0)
