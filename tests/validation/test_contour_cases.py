"""Published chain-length / centre-distance cases (../shared/validation/cases.yaml) and the
seed's worked example, reproduced by the closed forms and by the general contour solver."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

import chaindrive
from chaindrive.geometry.contour import (
    contour_geometry,
    round_links,
    two_sprocket_center_distance_exact,
    two_sprocket_center_distance_iso10823,
    two_sprocket_links_exact,
    two_sprocket_links_iso10823,
)
from tests.conftest import EXAMPLES, two_sprocket


def test_seed_three_sprocket_contour_128_links(seed_drive: chaindrive.Drive) -> None:
    """Seed 000, worked example (seed-notes §3): 'chain length 3251 mm = 128 links'
    (128 × 25.4 = 3251.2 mm); the tight wrap measures about 127.5 pitches."""
    g = contour_geometry(seed_drive)
    assert g.links == 128
    assert_allclose(g.chain_length * 1e3, 3251.2, atol=1e-9)
    assert 127.0 < g.tight_pitches < 128.0


def test_seed_example_file_gives_the_same() -> None:
    result = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    doc = result.to_dict()
    assert doc["geometry"]["links"] == 128
    assert_allclose(doc["geometry"]["chain_length_mm"], 3251.2, atol=1e-9)
    # seed-notes §3: the printed diameters are t·z/π, the pitch diameters t/sin(π/z)
    # (122.2, 202.7 and — the notes say 114.2 — 114.147 mm for z = 14)
    assert_allclose([s["pitch_diameter_mm"] for s in doc["geometry"]["sprockets"]],
                    [122.2, 202.7, 114.15], atol=0.05)
    # seed: speeds 300, 180, 321.43 rpm (z·n the same on every sprocket)
    assert_allclose([s["speed_rpm"] for s in doc["kinematics"]["sprockets"]],
                    [300.0, 180.0, 321.43], atol=0.005)


def test_jindal_30_2_links_from_minimum_centre_distance() -> None:
    """JINDAL-MD-EX30.2: p = 12.7 mm, z = 17/68, Da = p/tan(180/z) + 0.6p,
    Cmin = 1.2 (Da1 + Da2)/2 = 214.73 mm, Lp = 80.21 → 80 links (published)."""
    p, z1, z2 = 0.0127, 17, 68
    da1 = p / math.tan(math.pi / z1) + 0.6 * p
    da2 = p / math.tan(math.pi / z2) + 0.6 * p
    c_min = 1.2 * (da1 + da2) / 2
    assert_allclose(c_min * 1e3, 214.73, atol=0.01)
    lp = two_sprocket_links_iso10823(c_min, p, z1, z2)
    assert_allclose(lp, 80.21, atol=0.005)
    assert round(lp) == 80  # published: 80 links (book rounds to nearest even)
    # Derived (cases.yaml): centre distance for 80 links by the standard formula 213.20 mm.
    assert_allclose(two_sprocket_center_distance_iso10823(80, p, z1, z2) * 1e3, 213.20, atol=0.5)
    # The exact pitch-polygon solution is 0.6 mm shorter: at a/p = 17 and z2 − z1 = 51 the
    # angle γ = asin((R2 − R1)/a) ≈ 29° is far from the small angle the ISO form assumes.
    exact = two_sprocket_center_distance_exact(80, p, z1, z2)
    assert 0.3e-3 < two_sprocket_center_distance_iso10823(80, p, z1, z2) - exact < 1.0e-3


def test_jindal_30_3_chain_length() -> None:
    """JINDAL-MD-EX30.3: 06B (Jindal p = 9.52 mm), z = 21/42, a = 50p: Lp = 131.72,
    L = 1254.01 mm (flag: a real chain has 132 links = 1256.64 mm)."""
    p = 0.00952
    lp = two_sprocket_links_iso10823(50 * p, p, 21, 42)
    assert_allclose(lp * p * 1e3, 1254.01, atol=3.0)
    assert_allclose(two_sprocket_links_exact(50 * p, p, 21, 42), lp, atol=1e-3)
    assert round_links(lp) == 132
    assert_allclose(132 * p * 1e3, 1256.64, atol=0.01)


def test_jindal_example_file_takes_up_to_132_links() -> None:
    """The bundled two-sprocket example (Jindal 30-3 with the ISO pitch 9.525 mm)."""
    doc = chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml")).to_dict()
    g = doc["geometry"]
    assert g["links"] == 132
    assert_allclose(g["chain_length_mm"], 132 * 9.525, atol=1e-9)
    a = two_sprocket_center_distance_exact(132, 0.009525, 21, 42) * 1e3
    assert_allclose(g["center_distance_mm"], a, atol=1e-6)
    # Within 0.5 mm of the ISO 10823 closed form.
    iso = two_sprocket_center_distance_iso10823(132, 0.009525, 21, 42) * 1e3
    assert abs(g["center_distance_mm"] - iso) < 0.5


def test_khurmi_11_23_pitch_and_length() -> None:
    """KHURMI-TOM-EX11.23: p = d2 sin(180/T2) = 47.1 mm (±0.05), L = 3.0402 m (±1 mm)."""
    p = 0.600 * math.sin(math.pi / 40)
    assert_allclose(p * 1e3, 47.1, atol=0.05)
    assert_allclose(two_sprocket_links_iso10823(0.8, p, 20, 40) * p, 3.0402, atol=1e-3)
    assert_allclose(two_sprocket_links_exact(0.8, p, 20, 40) * p, 3.0402, atol=1e-3)


def test_cadpaper_centre_distance_114_links() -> None:
    """CADPAPER-CENTRE-DISTANCE-114 (gate: approximate value only): N = 20/63, L = 114:
    C = 35.6 pitches (± 0.05)."""
    assert_allclose(two_sprocket_center_distance_iso10823(114, 1.0, 20, 63), 35.6, atol=0.05)
    assert_allclose(two_sprocket_center_distance_exact(114, 1.0, 20, 63), 35.6, atol=0.05)


@pytest.mark.parametrize(("z1", "z2", "a_pitches"), [(17, 34, 40), (21, 42, 50), (19, 57, 30)])
def test_general_solver_agrees_with_iso10823_within_half_a_millimetre(
        z1: int, z2: int, a_pitches: float) -> None:
    """Issue 2: the two-sprocket closed forms must agree with the general solver."""
    p = 0.01905
    g = contour_geometry(two_sprocket(z1, z2, a_pitches * p, pitch=p))
    iso = two_sprocket_center_distance_iso10823(g.links, p, z1, z2)
    assert abs(g.center_distance - iso) < 0.5e-3


def test_equal_sprockets_at_whole_pitches_transmit_uniformly() -> None:
    """Seed 003 (and every textbook on the chordal effect): with z1 = z2 and a centre
    distance of a whole number of pitches both sprockets are in the same phase, γ = β, so
    the instantaneous ratio ω1/ω2 = R2 cos γ / (R1 cos β) is exactly 1 throughout."""
    result = chaindrive.analyze(two_sprocket(20, 20, 20 * 0.0254))
    driven = result.kinematics.sprockets[1]
    assert_allclose([driven.ratio_min, driven.ratio_max], [1.0, 1.0], atol=1e-9)


def test_ratio_stays_within_the_polygon_bounds() -> None:
    """ω1/ω2 = (R2/R1)·cos γ/cos β with |β| ≤ π/z1, |γ| ≤ π/z2 (seed 003)."""
    z1, z2 = 17, 34
    result = chaindrive.analyze(two_sprocket(z1, z2, 0.5))
    driven = result.kinematics.sprockets[1]
    r_ratio = math.sin(math.pi / z1) / math.sin(math.pi / z2)
    assert r_ratio * math.cos(math.pi / z2) - 1e-12 <= driven.ratio_min
    assert driven.ratio_max <= r_ratio / math.cos(math.pi / z1) + 1e-12
    assert driven.ratio_min < z2 / z1 < driven.ratio_max
