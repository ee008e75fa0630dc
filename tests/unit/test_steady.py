"""Frequency-domain steady state (chaindrive.dynamics.frequency.steady, excitation)."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from chaindrive.dynamics.excitation import polygonal_span_elongation
from chaindrive.kinematics import hinge_displacement_fourier


def test_polygonal_elongation_matches_hinge_series() -> None:
    # d = δ_end − δ_start with δ from chaindrive.kinematics (seed-notes §1), ψ = ω_z t − 2π s
    p, zs, ze, s0, s1 = 0.0254, np.array([15.0]), np.array([25.0]), np.array([0.0]), np.array([53.68])
    D = polygonal_span_elongation(p, zs, ze, s0, s1, 10)
    psi = np.linspace(0, 2 * math.pi, 50)
    d = (np.exp(1j * np.outer(psi, np.arange(1, 11))) @ D).real[:, 0]
    ref = (hinge_displacement_fourier(p, 25, psi - 2 * math.pi * s1[0])
           - hinge_displacement_fourier(p, 15, psi))
    assert_allclose(d, ref, atol=1e-12)


