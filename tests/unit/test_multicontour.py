"""Unit tests of chaindrive.multicontour (seed 004: keyed joints, ΔL₃, K_m, load sharing)."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad
from scipy.stats import truncnorm

from chaindrive.errors import DesignError
from chaindrive.multicontour import (
    KeyedJoint,
    clearance_coefficient_c4,
    clearance_pdf,
    clearance_placements,
    contour_factor_at_risk,
    contour_factor_compatibility,
    contour_factor_km,
    contour_factor_linear_at_risk,
    effect_map,
    key_corner_angle,
    keyway_max_clearance,
    length_difference_stats,
    length_error_exact,
    length_error_simplified,
    load_sharing,
    parallel_key,
    placement_probabilities,
    simulate_length_difference,
    simulate_load_sharing,
    span_deformation,
)

JOINT = KeyedJoint(pitch_radius=0.0813, shaft_radius=0.020, key_width=0.012, key_height=0.008,
                   max_clearance=54e-6)


# --- keyed joint, eq. 2–6 -------------------------------------------------------------

def test_exact_length_error_is_zero_without_clearance_and_grows() -> None:
    z = np.linspace(0.0, 200e-6, 21)
    dl = length_error_exact(JOINT, z)
    assert dl[0] == pytest.approx(0.0, abs=1e-15)
    assert np.all(np.diff(dl) > 0)


def test_exact_tends_to_linearised_simplified_form() -> None:
    # eq. 5 → C4·z as z → 0; the relative error of the first-order form is O(z)
    errors = []
    for z in (1e-4, 1e-5, 1e-6):
        exact = float(length_error_exact(JOINT, z))
        errors.append(abs(exact / float(length_error_simplified(JOINT, z, "linearised")) - 1))
    assert errors[2] < 1e-4
    assert errors[0] / errors[1] == pytest.approx(10.0, rel=0.05)


def test_seed_c4_differs_from_the_limit_by_cos_beta() -> None:
    beta = key_corner_angle(JOINT.key_width, JOINT.shaft_radius, JOINT.key_height)
    ratio = clearance_coefficient_c4(JOINT, "printed") / clearance_coefficient_c4(JOINT, "linearised")
    assert_allclose(ratio, math.cos(beta), rtol=1e-12)
    exact = float(length_error_exact(JOINT, 1e-7))
    assert_allclose(float(length_error_simplified(JOINT, 1e-7)), exact * math.cos(beta),
                    rtol=1e-5)


def test_standard_key_and_fit_clearances() -> None:
    # DIN 6885-1: d 38…44 mm → 12 × 8; ISO 286: b = 12 mm (10…18): IT9 = 43 µm, IT10 = 70,
    # D: EI = +50, P: ES = −18; key h9
    assert_allclose(parallel_key(0.040), (0.012, 0.008))
    assert_allclose(keyway_max_clearance(0.012, "normal"), 1.5 * 43e-6)
    assert_allclose(keyway_max_clearance(0.012, "free"), (50 + 70 + 43) * 1e-6)
    assert_allclose(keyway_max_clearance(0.012, "tight"), (43 - 18) * 1e-6)
    joint = KeyedJoint.from_standard(0.1, 0.040)
    assert joint.key_width == pytest.approx(0.012)
    assert joint.max_clearance == pytest.approx(64.5e-6)


def test_bad_joint_inputs_raise_design_errors() -> None:
    with pytest.raises(DesignError, match="did you mean 'normal'"):
        keyway_max_clearance(0.012, "normall")
    with pytest.raises(DesignError, match="shaft_diameter"):
        parallel_key(0.9)
    with pytest.raises(DesignError, match="joint.pitch_radius"):
        KeyedJoint(0.01, 0.02, 0.006, 0.006, 1e-5)
    with pytest.raises(DesignError, match="clearance"):
        length_error_exact(JOINT, -1e-6)


# --- clearance distribution and placements, eq. 7–10 ----------------------------------------

def test_truncated_pdf_integrates_to_one_and_vanishes_outside() -> None:
    z_max = 80e-6
    area, _ = quad(lambda z: float(clearance_pdf(z, z_max)), 0.0, z_max)
    assert_allclose(area, 1.0, rtol=1e-9)
    assert float(clearance_pdf(1.01 * z_max, z_max)) == 0.0
    assert_allclose(float(clearance_pdf(z_max / 2, z_max)) * z_max,
                    6 / math.sqrt(2 * math.pi) / 0.9973002, rtol=1e-6)


def test_all_sixteen_placements_and_their_probabilities() -> None:
    rows = clearance_placements("all")
    assert len(rows) == 16
    assert placement_probabilities("all") == {0: Fraction(6, 16), 1: Fraction(8, 16),
                                              2: Fraction(2, 16)}
    for row in rows:
        assert row.total == abs((row.joints[2] + row.joints[3]) - (row.joints[0] + row.joints[1]))
    seed = {r.joints for r in clearance_placements("table")}
    missing = {r.joints for r in rows} - seed
    assert missing == {(True, True, False, True), (True, False, True, True)}


def test_placement_model_monte_carlo_matches_its_mixture() -> None:
    # "placements" model: only the joints of a drawn row have a clearance; placement 0000
    # (1 of 14) gives ΔL3 = 0 exactly
    samples = simulate_length_difference(140_000, 7, c4=2.0, max_clearance=60e-6,
                                         model="placements")
    assert_allclose(np.mean(samples == 0.0), 1 / 14, rtol=0.05)
    # the mixture's second moment: Σ over rows of (n_clear·σ_z² + (n_II − n_I)²·z̄²)·C4² / 14
    sz, zbar = 10e-6, 30e-6
    rows = clearance_placements("table")
    m2 = sum(sum(r.joints) * sz**2 + (r.contour_ii - r.contour_i) ** 2 * zbar**2
             for r in rows) * 4.0 / len(rows)
    assert_allclose(np.mean(samples**2), m2, rtol=0.02)


def test_truncated_clearances_shrink_the_spread() -> None:
    # truncating Normal(z_max/2, z_max/6) to [0, z_max] lowers σ by the factor of the
    # truncated normal (scipy.stats.truncnorm), ≈ 0.9866: |ΔL3| is 1.3 % smaller
    samples = simulate_length_difference(400_000, 11, c4=1.0, max_clearance=6.0,
                                         truncated=True)
    factor = truncnorm.std(-3, 3)
    assert_allclose(samples.std(), 2.0 * factor, rtol=0.005)
    assert factor < 0.99


def test_length_difference_quantile_is_half_normal() -> None:
    stats = length_difference_stats(2.0, 60e-6)
    assert_allclose(stats.quantile_95_abs, 1.959964 * stats.sigma, rtol=1e-6)
    assert_allclose(stats.quantile_abs(0.5), 0.6744898 * stats.sigma, rtol=1e-6)
    json.dumps(stats.to_dict())


def test_monte_carlo_is_seedable() -> None:
    a = simulate_length_difference(1000, 3, c4=1.0, max_clearance=1e-4)
    b = simulate_length_difference(1000, np.random.default_rng(3), c4=1.0, max_clearance=1e-4)
    assert_allclose(a, b)
    with pytest.raises(DesignError, match="did you mean"):
        simulate_length_difference(10, 0, c4=1.0, max_clearance=1e-4, model="placement")


# --- K_m, eq. 15–18 ----------------------------------------------------------------------

def test_contour_factor_at_risk_uses_the_95_percent_quantile() -> None:
    c4, z_max, dy = 3.0, 64.5e-6, 0.25e-3
    q = 1.959964 * 2 * c4 * z_max / 6
    assert_allclose(contour_factor_at_risk(c4, z_max, dy), 1 + 2 * dy / (q + 2 * dy), rtol=1e-6)
    assert contour_factor_at_risk(c4, z_max, dy, risk=0.01) < contour_factor_at_risk(c4, z_max, dy)


def test_span_deformation_power_law() -> None:
    assert_allclose(span_deformation(2000.0, 40, 1e-6, 1.0, 1.0), 0.08)
    assert_allclose(span_deformation(8000.0, 40, 1e-6, 0.5, 1.0), 1e-6 * 40 * math.sqrt(8000))


# --- load sharing, m contours ------------------------------------------------------------

def test_load_sharing_balances_and_respects_slack() -> None:
    result = load_sharing([0.0, 0.1e-3, 0.5e-3, 2e-3], 10_000.0, 1e7)
    assert_allclose(sum(result.forces), 10_000.0, rtol=1e-12)
    assert result.forces[3] == 0.0
    delta = result.deformation
    assert_allclose(result.forces[:3], 1e7 * np.maximum(0.0, delta - np.array([0, 1e-4, 5e-4])))
    assert result.effective_contours == pytest.approx(1.0 / result.max_share)
    equal = load_sharing([1e-4] * 3, 900.0, [1e6, 2e6, 3e6])
    assert_allclose(equal.shares, [1 / 6, 2 / 6, 3 / 6])
    json.dumps(result.to_dict())


def test_compatibility_two_contours_is_linear_and_contains_eq16() -> None:
    s = np.linspace(0.0, 3e-4, 31)
    pairs = np.stack([np.zeros_like(s), s], axis=-1)
    dy = 0.2e-3
    assert_allclose(contour_factor_compatibility(pairs, dy), np.maximum(1.0, 2.0 - s / dy))
    # eq. 16 is the compatibility factor with the slacker contour stretched by 2Δy
    assert_allclose(contour_factor_compatibility(pairs, s + 2 * dy), contour_factor_km(s, dy),
                    rtol=1e-12)
    # and agrees with Δa = 2Δy to first order in |ΔL3|
    small = 1e-8
    slope_seed = (2.0 - float(contour_factor_km(small, dy))) / small
    assert_allclose(slope_seed, 1.0 / (2 * dy), rtol=1e-4)


def test_load_sharing_capacity_matches_compatibility_factor() -> None:
    # at the load where the tightest contour reaches Δa, F/F_a equals K
    s, k, da = np.array([0.0, 0.05e-3, 0.12e-3]), 2e7, 0.1e-3
    total = k * np.sum(np.maximum(0.0, da - s))
    result = load_sharing(s, total, k)
    assert_allclose(result.deformation, da, rtol=1e-12)
    assert_allclose(total / (k * da), contour_factor_compatibility(s, da), rtol=1e-12)


def test_simulated_two_contours_reduce_to_the_analytic_result() -> None:
    c4, z_max, da = 3.0, 64.5e-6, 0.2e-3
    sim = simulate_load_sharing(2, 400_000, 5, c4=c4, max_clearance=z_max,
                                allowable_deformation=da)
    assert_allclose(sim.km_at_risk, contour_factor_linear_at_risk(c4, z_max, da), rtol=0.003)
    assert_allclose(sim.max_share_at_risk, 1.0 / sim.km_at_risk, rtol=1e-3)
    json.dumps(sim.to_dict())


def test_more_contours_lose_more_but_keep_order() -> None:
    kw = {"c4": 3.0, "max_clearance": 64.5e-6, "allowable_deformation": 0.2e-3}
    k4 = simulate_load_sharing(4, 50_000, 1, **kw)
    k4_stiff = simulate_load_sharing(4, 50_000, 1, **{**kw, "allowable_deformation": 2e-3})
    assert 1.0 <= k4.km_at_risk < k4.km_mean < 4.0
    assert k4.km_at_risk < k4_stiff.km_at_risk < 4.0
    nonlinear = simulate_load_sharing(4, 50_000, 1, deformation_exponent=0.7, **kw)
    assert nonlinear.km_at_risk != pytest.approx(k4.km_at_risk)
    with pytest.raises(DesignError, match="contours"):
        simulate_load_sharing(1, 10, 0, **kw)


# --- effect map ---------------------------------------------------------------------------

def test_effect_map_is_frozen_json_ready_and_sensitive_to_the_fit() -> None:
    normal = effect_map(pitches=(0.0254, 0.0508), teeth=(15, 45))
    free = effect_map(pitches=(0.0254, 0.0508), teeth=(15, 45), fit="free")
    assert np.all(free.km_printed < normal.km_printed)
    assert np.all(normal.km_linear <= normal.km_printed)
    json.dumps(normal.to_dict())
    with pytest.raises(AttributeError):
        normal.risk = 0.1  # type: ignore[misc]
