"""Seed 001 hinge-friction damping (seed-notes §4) and the plain damping ratio."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.dynamics.damping import (
    DEFAULT_DAMPING_RATIO,
    PR_12_7_1820_1,
    absorption_coefficient,
    damped_frequencies,
    dissipated_energy_per_cycle,
    dynamic_load_factor,
    equivalent_damping_ratio,
    hinge_friction_damping,
    max_potential_energy,
)
from chaindrive.errors import DesignError

# Seed 001's worked data: ПР-12,7-1820-1, t = 12.7 mm, z = 49 hinges → a = t (z − 1)
A = 12.7e-3 * 48
F0 = np.array([250.0, 500.0, 750.0, 1000.0])
Y = np.linspace(0.015, 0.030, 7)


def _psi(f0: float | np.ndarray, y: float | np.ndarray, friction: float = 0.1,
         d2: float = 4.45e-3) -> np.ndarray:
    return absorption_coefficient(friction, d2, A, y, f0, PR_12_7_1820_1)


def test_psi_end_values_of_seed_notes() -> None:
    # seed-notes §4: ψ ≈ 0.07 at (F0 = 250 N, ȳ0 = 0.03) and ≈ 1.35 at (1000 N, 0.015).
    # Hand check: F_max(250, 0.03) = 32.55 + 248.28 + 226 + 1236.6 + 76.5 + 9.81 = 1829.7 N,
    # K_aF = 6.319, ψ = 6π·0.1·4.45e-3 / (0.03·0.6096·6.319) = 0.0726;
    # F_max(1000, 0.015) = 1679.8 N, K_aF = 0.6798, ψ = 1.349.
    assert _psi(250.0, 0.03) == pytest.approx(0.0726, abs=5e-4)
    assert _psi(1000.0, 0.015) == pytest.approx(1.349, abs=2e-3)
    assert 0.065 <= _psi(250.0, 0.03) <= 0.075
    assert 1.30 <= _psi(1000.0, 0.015) <= 1.40


def test_psi_equals_w_over_e_and_18_9_form() -> None:
    for f0 in F0:
        for y in Y:
            W = dissipated_energy_per_cycle(0.1, f0, 4.45e-3, y * A, A)
            E = max_potential_energy(A, y, f0)
            assert_allclose(_psi(f0, y), W / E, rtol=1e-12)
            # eq. (14): 18.9 f d2 / (ȳ0 t (z − 1) K_aF), 18.9 ≈ 6π
            k = dynamic_load_factor(f0, y)
            assert_allclose(_psi(f0, y), 18.9 * 0.1 * 4.45e-3 / (y * A * k), rtol=3e-3)


def test_seed_001_conclusions_on_a_grid() -> None:
    # Conclusions 4 and 5 of seed 001: W grows with F0, f, d2 and y0 and falls with a;
    # ψ grows with F0, f and d2 and falls with ȳ0.
    f0, y = np.meshgrid(F0, Y, indexing="ij")
    W = dissipated_energy_per_cycle(0.1, f0, 4.45e-3, y * A, A)
    assert np.all(np.diff(W, axis=0) > 0) and np.all(np.diff(W, axis=1) > 0)
    assert np.all(dissipated_energy_per_cycle(0.15, f0, 4.45e-3, y * A, A) > W)
    assert np.all(dissipated_energy_per_cycle(0.1, f0, 5.0e-3, y * A, A) > W)
    assert np.all(dissipated_energy_per_cycle(0.1, f0, 4.45e-3, y * A, 1.2 * A) < W)
    psi = _psi(f0, y)
    assert np.all(np.diff(psi, axis=0) > 0)   # grows with F0
    assert np.all(np.diff(psi, axis=1) < 0)   # falls with ȳ0
    assert np.all(_psi(f0, y, friction=0.15) > psi)
    assert np.all(_psi(f0, y, d2=5.0e-3) > psi)


def test_fmax_at_zero_amplitude_near_tension() -> None:
    # seed-notes §4: with all k positive, F_max at ȳ0 → 0 stays within 10 % of F0
    k = dynamic_load_factor(F0, 1e-12)
    assert np.all((k > 0) & (k < 0.10))


def test_damping_ratio_and_result() -> None:
    r = hinge_friction_damping(1000.0, 0.015, A)
    assert r.absorption_coefficient == pytest.approx(float(_psi(1000.0, 0.015)))
    assert r.damping_ratio == pytest.approx(r.absorption_coefficient / (4 * math.pi))
    assert r.dissipated_energy / r.potential_energy == pytest.approx(r.absorption_coefficient)
    assert set(r.to_dict()) >= {"absorption_coefficient", "damping_ratio", "tension_n"}
    assert_allclose(equivalent_damping_ratio([4 * math.pi]), [1.0])
    assert PR_12_7_1820_1.to_dict()["k4"] == 1.374e6
    custom = replace(PR_12_7_1820_1, friction=0.2)
    assert hinge_friction_damping(1000.0, 0.015, A, custom).absorption_coefficient == \
        pytest.approx(2 * r.absorption_coefficient)


def test_plain_damping_ratio_seed_000_table1() -> None:
    # Seed 000 §3.2: D = 0.06; Table 1 metal/metal 612.4 → 611.3 rad/s (0.18 %).
    assert DEFAULT_DAMPING_RATIO == 0.06
    wd = damped_frequencies(612.4, DEFAULT_DAMPING_RATIO)
    assert 100 * (1 - wd / 612.4) == pytest.approx(0.18, abs=0.01)
    with pytest.raises(DesignError):
        damped_frequencies(1.0, 1.0)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan])
def test_invalid_inputs(bad: float) -> None:
    with pytest.raises(DesignError):
        absorption_coefficient(0.1, 4.45e-3, A, bad, 500.0)


def test_material_loss_factors_combine_by_strain_energy() -> None:
    """Springs in series share one force, so their energies are ∝ compliance
    (η = Σ η_k/c_k / Σ 1/c_k); a mode whose branches all have η has η (modal strain
    energy method, Johnson & Kienholz 1982)."""
    from chaindrive.dynamics.damping import modal_loss_factor, series_loss_factor

    assert series_loss_factor([[0.01], [0.03]], [[1.0], [1.0]])[0] == pytest.approx(0.02)
    assert series_loss_factor([[0.01], [0.03]], [[3.0], [1.0]])[0] == pytest.approx(0.015)
    shape = np.array([1.0, -0.5, 0.2, -0.7])
    assert modal_loss_factor([0.02] * 4, [1e6, 2e6, 3e6, 4e6], shape) == pytest.approx(0.02)
    # a branch that is not strained in the mode adds nothing
    assert modal_loss_factor([0.02, 0.5], [1e6, 1e6], [1.0, 1.0]) == 0.0
