"""The workshop data of a sprocket against the standards' tables and closed forms (values
written out here, not read from the package):

* ISO 286-1 Table 1 [ISO286-1]: IT7 is 18 µm over 10 up to 18 mm, 25 µm over 30 up to 50 mm,
  46 µm over 180 up to 250 mm; IT9 36 µm over 6 up to 10 mm; IT11 190 µm over 50 up to 80 mm.
* DIN 6885-1 [DIN6885-1]: bore 30 mm (in "over 22 up to 30") takes the key 8 × 7, t2 = 3.3;
  bore 30.5 mm takes 10 × 8, t2 = 3.3; bore 150 mm: 36 × 20, t2 = 8.4, depth tolerance
  +0.3 mm (over 130 mm); bore 20 mm: +0.1 mm.
* ISO 606 [ISO606]: side relief 0.10 … 0.15 p, side radius p; GOST 591 [GOST591]: r3 = 1.7 d1,
  h3 = 0.8 d1, so 0.2 d1 off at the tip.
"""

from __future__ import annotations

import math

import pytest

from chaindrive.errors import DesignError
from chaindrive.geometry.workshop import (
    bore_deviations,
    chosen_tip_diameter,
    gost591_chamfer,
    hub_keyway,
    iso286_tolerance,
    iso606_chamfer,
    measurement_over_pins,
)

UM = 1e-6
MM = 1e-3


@pytest.mark.parametrize(("size_mm", "grade", "it_um"), [(12, 7, 18), (32, 7, 25), (200, 7, 46),
                                                         (8, 9, 36), (60, 11, 190), (30, 7, 21)])
def test_iso286_standard_tolerances(size_mm: float, grade: int, it_um: float) -> None:
    assert iso286_tolerance(size_mm * MM, grade) == pytest.approx(it_um * UM)


def test_bore_fit() -> None:
    assert bore_deviations(0.032, "H7") == pytest.approx((25 * UM, 0.0))
    assert bore_deviations(0.032, "H8") == pytest.approx((39 * UM, 0.0))
    with pytest.raises(DesignError, match="bore_fit"):
        bore_deviations(0.032, "K7")
    with pytest.raises(DesignError):
        iso286_tolerance(0.6, 7)  # beyond the table


@pytest.mark.parametrize(("bore_mm", "b", "h", "t2", "upper"),
                         [(30.0, 8, 7, 3.3, 0.2), (30.5, 10, 8, 3.3, 0.2),
                          (150.0, 36, 20, 8.4, 0.3), (20.0, 6, 6, 2.8, 0.1)])
def test_din6885_hub_keyway(bore_mm: float, b: float, h: float, t2: float, upper: float) -> None:
    k = hub_keyway(bore_mm * MM)
    assert (k.key_width, k.key_height, k.hub_depth) == pytest.approx((b * MM, h * MM, t2 * MM))
    assert k.depth_upper == pytest.approx(upper * MM)
    assert k.over_bore == pytest.approx((bore_mm + t2) * MM)
    it9 = iso286_tolerance(b * MM, 9)
    assert (k.width_upper, k.width_lower) == pytest.approx((it9 / 2, -it9 / 2))  # JS9


def test_keyway_outside_the_table() -> None:
    with pytest.raises(DesignError, match="keyway = false"):
        hub_keyway(0.25)
    with pytest.raises(DesignError):
        hub_keyway(0.005)


def test_measurement_over_pins() -> None:
    p, d1 = 25.4 * MM, 15.88 * MM
    for z in (24, 25):
        d = p / math.sin(math.pi / z)
        expected = d + d1 if z % 2 == 0 else d * math.cos(math.pi / (2 * z)) + d1
        assert measurement_over_pins(d, z, d1) == pytest.approx(expected, rel=1e-12)


def test_tip_diameter_inside_the_range() -> None:
    # 16B-1 (p = 25.4, d1 = 15.88), z = 25: range 210.554 … 218.530 mm
    p, d1, z = 25.4, 15.88, 25
    d = p / math.sin(math.pi / z)
    lo, hi = d + p * (1 - 1.6 / z) - d1, d + 1.25 * p - d1
    da, upper, lower = chosen_tip_diameter(lo * MM, hi * MM)
    assert da == pytest.approx(math.floor((lo + hi) / 2 * 10) / 10 * MM)
    assert upper == 0.0 and lower == pytest.approx(-290 * UM)  # h11 over 180 up to 250 mm
    assert lo * MM <= da + lower and da <= hi * MM
    with pytest.raises(DesignError):
        chosen_tip_diameter(0.1000, 0.1001)  # narrower than IT11
    da, _, lower = chosen_tip_diameter(5.40, 5.45)  # a large sprocket: IT11 by its formula
    assert da == pytest.approx(5.425) and lower == pytest.approx(
        -100 * (0.004 * 5425 + 2.1) * UM)
    _, _, lower = chosen_tip_diameter(0.70, 0.72)  # IT11 over 630 up to 800 mm: 500 µm
    assert lower == pytest.approx(-500 * UM)


def test_chamfers() -> None:
    p = 25.4 * MM
    ba, rx, depth = iso606_chamfer(p)
    assert 0.10 * p <= ba <= 0.15 * p and rx == p
    assert (rx - math.sqrt(rx * rx - depth * depth)) == pytest.approx(ba)  # tangent arc
    d1 = 15.88 * MM
    f, r3, h3 = gost591_chamfer(d1)
    assert (r3, h3) == pytest.approx((1.7 * d1, 0.8 * d1))
    assert f == pytest.approx(0.2 * d1)
