"""Wear geometry of a roller chain against the published relations.

* The chain makers' replacement rule [DiamondChainWear], [RegalChainWear]: 3 %, at most
  200/N % for a large sprocket of N teeth (3 % holds up to 67 teeth), 1.5 % for fixed centres
  or parallel chains.
* The pitch radius of a worn chain on a sprocket: the closed polygon of z worn pitches,
  R' = p(1 + ε)/(2 sin(π/z)) (ISO 606 / GOST 591 pitch diameter d = p/sin(180°/z) with the
  worn pitch), as the contour geometry builds it; at the 200/N rule the rollers rise by the
  height of the largest ISO 606 tooth tip above the pitch circle, (da,max − d)/2 = 0.625p −
  0.5d1, for rollers of d1 = 5p/8 (the rule is that tooth height).
* The sag of a span carrying extra chain length against the catenary
  ℓ + ΔL = 2a·sinh(ℓ/2a), f = a(cosh(ℓ/2a) − 1) [Irvine1981, ch. 1], and its shallow limit
  the parabola ΔL = 8f²/(3ℓ) of chaindrive.geometry.sag.
* A take-up allows the removal of two pitches of chain [DiamondChainTension]: a worn chain of
  N links is shortened by two links each time its take-up has absorbed its capacity c, so a
  state has N − 2k links with the least k for which (N − 2k)·p(1 + ε) − N·p ≤ c; on two
  sprockets its centre distance is then the exact two-sprocket closed form
  L_p = 2a·cos γ/p + (z₁ + z₂)/2 + (z₂ − z₁)·γ/π for N − 2k links of the worn pitch.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import chaindrive
from chaindrive.geometry.contour import two_sprocket_center_distance_exact
from chaindrive.geometry.sag import slack_for_sag
from chaindrive.robust import Perturbation, PerturbedAnalysis, nominal_analysis
from chaindrive.robust.wear import (
    allowable_elongation,
    catenary_excess_length,
    catenary_parameter,
    catenary_sag,
    elongated_pitch_radius,
    equivalent_sag_ratio,
    iso606_tip_height,
    links_removed,
    roller_lift,
)
from tests.conftest import EXAMPLES


def test_replacement_rule_of_the_chain_makers() -> None:
    # [DiamondChainWear]: 3 % up to 67 teeth, 200/N % above; [RegalChainWear]: over 66 teeth
    assert allowable_elongation(17) == 0.03
    assert allowable_elongation(66) == 0.03
    assert allowable_elongation(67) == pytest.approx(2.0 / 67)   # 2.985 % < 3 %
    assert allowable_elongation(100) == pytest.approx(0.02)
    assert allowable_elongation(120) == pytest.approx(2.0 / 120)
    # fixed centres, chains in parallel, smooth running: about 1.5 % [DiamondChainWear]
    assert allowable_elongation(40, fixed_centres=True) == 0.015
    assert allowable_elongation(40, parallel=True) == 0.015
    assert allowable_elongation(200, smooth=True) == pytest.approx(0.01)  # 200/N wins


@pytest.mark.parametrize("z", [67, 80, 100, 120, 150])
def test_200_over_n_rule_is_the_iso606_tooth_tip_height(z: int) -> None:
    p = 0.0254
    d1 = 5.0 * p / 8.0                       # ISO 606 16A: d1 = 15.88 mm = 0.625 p
    lift = float(roller_lift(p, z, allowable_elongation(z)))
    tip = float(iso606_tip_height(p, z, d1))
    assert tip == pytest.approx(0.625 * p - 0.5 * d1)
    # p/(z sin(π/z)) → p/π = 0.318 p against 0.3125 p: within 2 %
    assert lift == pytest.approx(p / (z * math.sin(math.pi / z)))
    assert lift == pytest.approx(tip, rel=0.02)


@pytest.mark.parametrize("z", [9, 17, 25, 40, 60, 66])
def test_three_percent_keeps_the_rollers_at_the_tip_up_to_66_teeth(z: int) -> None:
    # the rule's 3 % is the tip height at z = 66 (200/66 = 3.03 %): below it, the rollers
    # stay under the tip; at 66 teeth they reach it (0.3153 p against 0.3125 p)
    p, d1 = 0.0254, 0.625 * 0.0254
    lift, tip = float(roller_lift(p, z, 0.03)), float(iso606_tip_height(p, z, d1))
    assert lift < tip if z <= 60 else lift == pytest.approx(tip, rel=0.01)


@pytest.mark.parametrize("eps", [0.0, 0.01, 0.03])
def test_worn_chain_seats_on_the_closed_polygon_of_its_pitch(eps: float) -> None:
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "eight_sprocket.toml"))
    worn = PerturbedAnalysis(nominal, Perturbation(elongation=eps), response=False)
    p = nominal.drive.chain.pitch
    for s in worn.geometry.sprockets:
        expected = p * (1 + eps) / (2 * math.sin(math.pi / s.teeth))   # ISO 606 d = p/sin(π/z)
        assert s.pitch_radius == pytest.approx(expected, rel=1e-12)
        assert s.pitch_radius == pytest.approx(float(elongated_pitch_radius(p, s.teeth, eps)))
    # the chain keeps its links: its length grows by ε, the take-up takes it up
    assert worn.geometry.links == nominal.geometry.links
    assert worn.geometry.chain_length == pytest.approx(nominal.geometry.chain_length * (1 + eps))
    assert worn.geometry.slack == pytest.approx(0.0, abs=1e-9)
    assert (worn.take_up_travel() > 0) == (eps > 0)


@pytest.mark.parametrize("a_over_l", [0.5, 1.0, 3.0, 25.0])
def test_sag_against_the_catenary(a_over_l: float) -> None:
    span = 1.3
    a = a_over_l * span
    arc = 2 * a * math.sinh(span / (2 * a))             # ℓ + ΔL of the catenary
    sag = a * (math.cosh(span / (2 * a)) - 1.0)
    assert catenary_parameter(span, arc - span) == pytest.approx(a, rel=1e-10)
    assert catenary_sag(span, arc - span) == pytest.approx(sag, rel=1e-10)
    # the sag ratio handed to the static model gives the catenary's horizontal pull H = w·a
    s = equivalent_sag_ratio(span, arc - span)
    assert span / (8 * s) == pytest.approx(a, rel=1e-10)
    assert catenary_excess_length(span, s) == pytest.approx(arc - span, rel=1e-9)


@pytest.mark.parametrize("s", [0.001, 0.005, 0.02])
def test_shallow_catenary_is_the_parabola(s: float) -> None:
    span = 1.3
    extra = slack_for_sag(span, s)                        # ΔL = 8f²/(3ℓ) [Irvine1981]
    assert catenary_sag(span, extra) / span == pytest.approx(s, rel=4 * s * s + 1e-9)
    assert equivalent_sag_ratio(span, extra) == pytest.approx(s, rel=4 * s * s + 1e-9)


def test_fixed_centre_wear_grows_the_sag_and_drops_the_slack_tension() -> None:
    # the seed's contour has no take-up: the elongation collects in the slack span
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    states = [PerturbedAnalysis(nominal, Perturbation(elongation=e), response=False)
              for e in (0.0, 0.002, 0.005, 0.01)]
    sag = np.array([s.sag_ratio for s in states])
    slack = np.array([s.geometry.slack for s in states])
    f0 = np.array([s._static.loads.sag_tension for s in states])
    assert sag[0] == pytest.approx(0.02, rel=1e-9)        # the static model's sag when new
    assert np.all(np.diff(sag) > 0) and np.all(np.diff(slack) > 0) and np.all(np.diff(f0) < 0)
    # the extra slack is the chain's growth less the growth of the tight contour
    for s in states[1:]:
        grown = (s.geometry.chain_length - nominal.geometry.chain_length
                 - (s.geometry.tight_length - nominal.geometry.tight_length))
        assert s.geometry.slack - nominal.geometry.slack == pytest.approx(grown, rel=1e-9)
    # F0 = k_f·q·g·a with k_f from the catenary's pull: ∝ 1/s for a shallow horizontal span
    assert_allclose(f0[1:] / f0[0], (sag[0] / sag[1:]), rtol=0.05)


@pytest.mark.parametrize("eps", [0.0, 0.0076, 0.015, 0.02, 0.03, 0.045])
def test_take_up_state_shortens_the_chain_by_two_links_per_capacity(eps: float) -> None:
    """[DiamondChainTension]: the take-up absorbs two pitches, then two links come out; the
    state's centre distance is the exact two-sprocket closed form of its N − 2k worn links."""
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"))
    g0, p = nominal.geometry, nominal.drive.chain.pitch
    n, capacity = g0.links, 2.0 * p
    state = PerturbedAnalysis(nominal, Perturbation(elongation=eps), take_up_capacity=capacity,
                              response=False)
    removed = state.links_removed
    assert removed == links_removed(n, p, eps, capacity) and removed % 2 == 0
    absorbed = (n - removed) * p * (1 + eps) - n * p
    assert absorbed <= capacity + 1e-12                   # within the take-up's capacity
    assert removed == 0 or absorbed > capacity - 2 * p * (1 + eps)   # the least k
    assert removed == 2 * max(0, math.ceil((n * eps - 2.0) / (2 * (1 + eps)) - 1e-12))
    assert state.geometry.links == n - removed
    z1, z2 = (s.teeth for s in nominal.drive.sprockets)
    a = two_sprocket_center_distance_exact(n - removed, p * (1 + eps), z1, z2)
    assert state.geometry.center_distance == pytest.approx(a, rel=1e-9)
    a0 = two_sprocket_center_distance_exact(n, p, z1, z2)
    assert state.take_up_travel() == pytest.approx(a - a0, abs=1e-9)
    assert "take_up" not in {c.key for c in state.all_checks()}
