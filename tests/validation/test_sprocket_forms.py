"""Validation of the sprocket tooth forms against published and compiled values."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.geometry import sprocket as sp

MM = 1e-3


# Case BHANDARI-DME-EX14.5-SPROCKET (shared/validation/cases.yaml): Bhandari, Design of
# Machine Elements, 3rd ed., Ex. 14.5 via the FOSSEE companion — 12B, z = 17.
# Tolerance stated by the case: ±0.01 mm on each quantity.
@pytest.fixture(scope="module")
def bhandari_form() -> sp.ToothForm:
    return sp.iso606_tooth_form(19.05 * MM, 17, 12.07 * MM, 11.68 * MM, strands=1)


@pytest.mark.parametrize(("attribute", "expected_mm"), [
    # expected (published)
    ("pitch_diameter", 103.67),
    ("tip_diameter_mean", 112.14),
    ("root_diameter_mean", 91.32),
    ("flank_radius_mean", 36.40),
    ("side_radius", 19.05),
    ("tooth_width", 11.10),
    ("side_relief_mean", 2.38),
    # derived (the source's own equations)
    ("tip_diameter_max", 115.42),
    ("tip_diameter_min", 108.86),
    ("root_diameter_max", 91.48),
    ("root_diameter_min", 91.17),
    ("flank_radius_max", 45.29),
    ("flank_radius_min", 27.52),
])
def test_bhandari_ex14_5(bhandari_form: sp.ToothForm, attribute: str, expected_mm: float) -> None:
    assert_allclose(getattr(bhandari_form, attribute) / MM, expected_mm, atol=0.01 + 1e-9)


def test_bhandari_ex14_5_dict_keys(bhandari_form: sp.ToothForm) -> None:
    data = bhandari_form.to_dict()
    assert_allclose(data["tip_diameter_mean_mm"], 112.14, atol=0.01)
    assert data["standard"] == "ISO 606"


def test_bhandari_tip_diameter_convenience_is_the_mean() -> None:
    # BHANDARI-DME-EX14.5-SPROCKET: Da (mean of the limits) = 112.14 mm
    assert_allclose(sp.tip_diameter(19.05 * MM, 17, 12.07 * MM) / MM, 112.14, atol=0.01)


# shared/data/gost591_sprocket_profile.md §2, ISO 606 check values (08B z=20, 16A z=25).
@pytest.mark.parametrize(("pitch", "d1", "z", "d", "df", "da_max", "da_min", "ri", "re", "alpha"), [
    (12.7, 8.51, 20, 81.184, 72.674, 88.549, 84.358, (4.298, 4.438), (22.466, 39.486),
     (115.5, 135.5)),
    (25.4, 15.88, 25, 202.660, 186.780, 218.530, 210.554, (8.019, 8.193), (51.451, 102.267),
     (116.4, 136.4)),
])
def test_iso606_check_values(pitch: float, d1: float, z: int, d: float, df: float,
                             da_max: float, da_min: float, ri: tuple[float, float],
                             re: tuple[float, float], alpha: tuple[float, float]) -> None:
    form = sp.iso606_tooth_form(pitch * MM, z, d1 * MM, 10 * MM)
    assert_allclose(form.pitch_diameter / MM, d, atol=0.001)
    assert_allclose(form.root_diameter / MM, df, atol=0.001)
    assert_allclose(sp.root_diameter(pitch * MM, z, d1 * MM) / MM, df, atol=0.001)
    assert_allclose([form.tip_diameter_min / MM, form.tip_diameter_max / MM], [da_min, da_max],
                    atol=0.001)
    assert_allclose([form.seating_radius_min / MM, form.seating_radius_max / MM], ri, atol=0.001)
    assert_allclose([form.flank_radius_min / MM, form.flank_radius_max / MM], re, atol=0.001)
    assert_allclose(np.degrees([form.seating_angle_min, form.seating_angle_max]), alpha,
                    atol=0.05)


# shared/data/gost591_sprocket_profile.md §1.6: GOST 591-69 check values computed from the
# Anuriev formulas (3 decimals; De is stated to 0.1 mm by the standard).
GOST_CASES = {
    "ПР-12,7-18,2 z=20": dict(
        t=12.7, d1=8.51, z=20, lam=1.4924, K=0.480, d=81.184, De=86.3, r=4.326, Di=72.532,
        r1=11.134, alpha=52.0, beta=15.2, phi=13.8, r2=5.683, FC=0.732, OO2=10.552, Lx=None),
    "ПР-25,4-60 z=25": dict(
        t=25.4, d1=15.88, z=25, lam=1.5995, K=0.532, d=202.660, De=214.6, r=8.030, Di=186.600,
        r1=20.734, alpha=52.6, beta=15.76, phi=14.44, r2=10.562, FC=1.460, OO2=19.691,
        Lx=186.200),
}


@pytest.mark.parametrize("name", list(GOST_CASES))
def test_gost591_check_values(name: str) -> None:
    c = GOST_CASES[name]
    f = sp.gost591_tooth_form(c["t"] * MM, c["z"], c["d1"] * MM, 10 * MM)
    assert_allclose(f.lam, c["lam"], atol=5e-5)
    assert_allclose(f.K, c["K"], rtol=0)
    assert_allclose(f.tip_diameter / MM, c["De"], atol=0.05)  # De to 0.1 mm
    for attribute, key in [("pitch_diameter", "d"), ("seating_radius", "r"),
                           ("root_diameter", "Di"), ("joining_radius", "r1"),
                           ("head_radius", "r2"), ("straight_part", "FC"),
                           ("head_centre_distance", "OO2")]:
        assert_allclose(getattr(f, attribute) / MM, c[key], atol=0.0011, err_msg=attribute)
    assert_allclose(np.degrees([f.half_space_angle, f.joining_angle, f.half_tooth_angle]),
                    [c["alpha"], c["beta"], c["phi"]], atol=1e-9)
    if c["Lx"] is not None:
        assert_allclose(f.measuring_chord / MM, c["Lx"], atol=0.001)
    assert_allclose(sp.tip_diameter(c["t"] * MM, c["z"], c["d1"] * MM, form="GOST 591") / MM,
                    c["De"], atol=0.05)
    assert_allclose(sp.root_diameter(c["t"] * MM, c["z"], c["d1"] * MM, form="GOST 591") / MM,
                    c["Di"], atol=0.001)


def test_gost591_rim_width_single_row() -> None:
    # gost591_sprocket_profile.md §1.4 [WB]: b = 0.93·Bвн − 0.15 mm; ПР-25,4-60 Bвн = 15.88 mm
    f = sp.gost591_tooth_form(25.4 * MM, 25, 15.88 * MM, 15.88 * MM)
    assert_allclose(f.rim_width / MM, 0.93 * 15.88 - 0.15, rtol=1e-12)


def test_gost591_refuses_lambda_over_two() -> None:
    # GOST 591-69 scope: λ = t/d1 ≤ 2
    with pytest.raises(DesignError, match="roller_diameter") as info:
        sp.gost591_tooth_form(25.4 * MM, 20, 12.0 * MM, 15 * MM)
    assert info.value.field == "roller_diameter"


# seed-notes §3 (seed 000 worked example, t = 25.4 mm, z = 15, 25, 14): the printed
# diameters equal t·z/π = 121.3/202.1/113.2 mm, not p/sin(π/z). The notes give the pitch
# diameters as 122.2/202.7/114.2 mm; for z = 14 the correct value is 25.4/sin(π/14) =
# 114.147 mm, i.e. 114.1 (the notes' last figure is a rounding slip, reported).
def test_seed_example_diameters() -> None:
    z = np.array([15, 25, 14])
    assert_allclose(sp.approximate_pitch_diameter(25.4 * MM, z) / MM, [121.3, 202.1, 113.2],
                    atol=0.05)
    assert_allclose(sp.pitch_diameter(25.4 * MM, z) / MM, [122.2, 202.7, 114.1], atol=0.05)
    # the seed's printed (truncated) diameters 121 / 202 / 113 mm are the t·z/π values
    assert_allclose(np.floor(sp.approximate_pitch_diameter(25.4 * MM, z) / MM), [121, 202, 113])
