"""Unit tests of sprocket proportions, tooth widths, mass and inertia."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.geometry import sprocket as sp

MM = 1e-3


@pytest.mark.parametrize(("pitch_mm", "b1_mm", "strands", "expected_mm"), [
    # DIN 8187 sprocket tables (yavuzlardisli.com, "DIN 8187 standart zincir dişli"):
    # 12B b1 = 11.68: simplex 11.1, duplex 10.8 (≈ 0.93·11.68 = 10.86); 08B b1 = 7.75:
    # simplex 7.2, duplex 7.0; 16B b1 = 17.02: simplex 16.2, duplex 15.8.
    (19.05, 11.68, 1, 11.1), (19.05, 11.68, 2, 10.86), (12.7, 7.75, 1, 7.2),
    (12.7, 7.75, 2, 7.05), (25.4, 17.02, 1, 16.17), (25.4, 17.02, 3, 15.83),
])
def test_iso606_tooth_width(pitch_mm: float, b1_mm: float, strands: int,
                            expected_mm: float) -> None:
    assert_allclose(sp.iso606_tooth_width(pitch_mm * MM, b1_mm * MM, strands) / MM, expected_mm,
                    atol=0.06)


def test_multi_strand_width() -> None:
    # Autodesk Inventor: bs = pt (k − 1) + bf; 16B-2 pt = 31.88 mm → 15.83 + 31.88 = 47.71 mm
    # (DIN 8187 table: B2 = 47.7 mm)
    bf = sp.iso606_tooth_width(25.4 * MM, 17.02 * MM, 2)
    assert_allclose(sp.multi_strand_width(bf, 31.88 * MM, 2) / MM, 47.7, atol=0.05)


def test_convenience_vectorised_and_form_checked() -> None:
    z = np.array([9, 17, 60])
    assert sp.tip_diameter(25.4 * MM, z, 15.88 * MM).shape == (3,)
    assert np.all(sp.tip_diameter(25.4 * MM, z, 15.88 * MM) > sp.pitch_diameter(25.4 * MM, z))
    assert np.all(sp.root_diameter(25.4 * MM, z, 15.88 * MM, "GOST 591")
                  < sp.pitch_diameter(25.4 * MM, z))
    with pytest.raises(DesignError, match="tooth_form"):
        sp.tip_diameter(25.4 * MM, 17, 15.88 * MM, form="DIN")  # type: ignore[arg-type]
    with pytest.raises(DesignError, match="teeth"):
        sp.pitch_diameter(25.4 * MM, 2)
    with pytest.raises(DesignError, match="pitch"):
        sp.pitch_diameter(-1.0, 17)


def test_polymeric_proportions() -> None:
    prop = sp.polymeric_sprocket_proportions(25.4 * MM, 15, 15.88 * MM)
    D = 25.4 * 15 / math.pi
    assert_allclose(prop.d_pitch / MM, D)
    assert_allclose([prop.rim_inner_diameter, prop.hub_outer_diameter, prop.bore_diameter],
                    np.array([0.8, 0.33, 0.19]) * D * MM)
    assert_allclose([prop.rim_width, prop.web_thickness, prop.hub_length],
                    np.array([0.85, 0.425, 2.55]) * 15.88 * MM)
    assert prop.to_dict()["hole_circle_diameter_mm"] == pytest.approx(0.56 * D)


def test_annulus_against_numerical_integration() -> None:
    do, di, w, rho = 0.2, 0.05, 0.01, 7850.0
    r = np.linspace(di / 2, do / 2, 20001)
    ring = rho * w * 2 * np.pi * r
    m, inertia = sp.annulus_mass_and_inertia(do, di, w, rho)
    assert_allclose(m, np.trapezoid(ring, r), rtol=1e-8)
    assert_allclose(inertia, np.trapezoid(ring * r**2, r), rtol=1e-8)


def test_steel_plate_sprocket_mass() -> None:
    # disc of d = p/sin(π/z), thickness bf1, minus the bore 0.19·tz/π
    p, z, b1 = 25.4 * MM, 25, 17.02 * MM
    d = sp.pitch_diameter(p, z)
    bore = 0.19 * p * z / math.pi
    width = 0.95 * b1
    props = sp.sprocket_mass_and_inertia(p, z, b1, 7850.0, polymeric=False)
    assert_allclose(props.mass, 7850 * width * math.pi * (d**2 - bore**2) / 4, rtol=1e-12)
    mass, inertia = props
    assert mass * d**2 / 8 < inertia < mass * d**2 / 4  # between solid disc and thin ring
    assert props.to_dict()["mass_kg"] == mass


def test_polymeric_lighter_than_solid_and_holes_reduce() -> None:
    p, z, b1, rho = 25.4 * MM, 25, 15.88 * MM, 1140.0
    full = sp.sprocket_mass_and_inertia(p, z, b1, rho, polymeric=True, hole_count=0)
    holed = sp.sprocket_mass_and_inertia(p, z, b1, rho, polymeric=True)
    assert holed.mass < full.mass
    assert holed.moment_of_inertia < full.moment_of_inertia
    assert holed.mass > 0


def test_mass_scales_geometrically() -> None:
    # every dimension ∝ pitch and inner width: m ∝ s³, I ∝ s⁵
    for polymeric in (True, False):
        a = sp.sprocket_mass_and_inertia(15.875 * MM, 21, 9.65 * MM, 1000.0, polymeric)
        b = sp.sprocket_mass_and_inertia(2 * 15.875 * MM, 21, 2 * 9.65 * MM, 1000.0, polymeric)
        assert_allclose(b.mass / a.mass, 8.0, rtol=1e-12)
        assert_allclose(b.moment_of_inertia / a.moment_of_inertia, 32.0, rtol=1e-12)


def test_a_body_density_that_is_not_positive_is_refused_as_a_density() -> None:
    # the density is checked as a positive value, not as "a positive length" (the message
    # names the field and what is allowed)
    with pytest.raises(DesignError, match=r"density: must be positive, got -7800") as err:
        sp.sprocket_mass_and_inertia(0.0254, 17, 0.0156, -7800.0, polymeric=False)
    assert "length" not in str(err.value)
