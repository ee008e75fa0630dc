"""The one formatting rule and the output unit systems of chaindrive.display.

The US customary factors are the exact definitions of NIST SP 811, App. B [NIST-SP811]:
1 in = 25.4 mm, 1 lb = 0.45359237 kg, 1 lbf = 4.4482216152605 N, 1 hp = 745.69987158227022 W,
1 psi = 6894.757293168 Pa, 1 ft/min = 0.00508 m/s.
"""

from __future__ import annotations

import math

import pytest

from chaindrive.checks import judged
from chaindrive.display import (
    check_line,
    check_row,
    clean,
    convert,
    dimension,
    doc_value,
    fmt,
    header,
    margin_percent,
    unit_header,
    unit_system,
)
from chaindrive.errors import DesignError


@pytest.mark.parametrize(("value", "text"), [
    (None, "—"), (math.nan, "—"), (True, "yes"), (False, "no"), (128, "128"),
    (-6.424e-16, "0"), (-0.0, "0"), (700.0000000000001, "700"), (60.67, "60.67"),
    (1364.0, "1364"), (12345.6, "12,346"), (9999.6, "10,000"), (2.154e8, "2.154e8"),
    (4.2e-5, "4.2e-5"), (0.06025, "0.06025"), (math.inf, "∞"), (122.16699, "122.2")])
def test_fmt(value: object, text: str) -> None:
    assert fmt(value) == text


def test_clean_and_dimension() -> None:
    assert clean(700.0000000000001) == 700.0 and clean(-6.4e-16) == 0.0
    assert dimension(122.1669, 2) == "122.17" and dimension(-1e-9, 2) == "0.00"


@pytest.mark.parametrize(("kind", "si", "us"), [
    ("length", 0.0254, 1.0), ("force", 4.4482216152605, 1.0),
    ("power", 745.69987158227022, 1.0), ("pressure", 6894.757293168, 1.0),
    ("velocity", 0.00508, 1.0), ("mass", 0.45359237, 1.0),
    ("linear_density", 0.45359237 / 0.3048, 1.0),
    ("inertia", 0.45359237 * 0.3048**2, 1.0)])
def test_us_customary_factors(kind: str, si: float, us: float) -> None:
    assert convert(si, kind, "US")[0] == pytest.approx(us, rel=1e-12)


def test_document_keys_and_headers() -> None:
    assert doc_value("x_mm", 1364.0, "SI") == (1364.0, "mm")
    assert doc_value("x_mm", 1364.0, "US")[0] == pytest.approx(1364 / 25.4, rel=1e-12)
    assert doc_value("tension_n", 4.4482216152605, "US")[0] == pytest.approx(1.0)
    assert doc_value("mass_per_length_kg_m", 1.0, "SI") == (1.0, "kg/m")
    assert doc_value("links", 128, "US") == (128, "")
    assert header("pitch Ø", "pitch_diameter_mm", "US") == "pitch Ø, in"
    assert unit_system("us") == "US" and unit_system(None) == "SI"
    with pytest.raises(DesignError, match="units"):
        unit_system("imperial")


def test_checks_read_in_either_system_with_one_margin_sign() -> None:
    """A pressure check 31 MPa ≤ 28 MPa: margin 28/31 − 1 < 0 (fails) in both systems."""
    c = judged("hinge pressure", "chain", 31e6, 28e6, "max", "[ChainDesignRU]", "MPa", 1e-6)
    assert check_row(c)[1:4] == (pytest.approx(31.0), "≤ 28 MPa", "FAIL")
    us = check_row(c, "US")
    assert us[1] == pytest.approx(31e6 / 6894.757293168) and us[2].endswith(" psi")
    assert margin_percent(c) == pytest.approx(100 * (28 / 31 - 1))
    assert check_line(c) == "FAIL: hinge pressure: chain = 31 MPa (required ≤ 28 MPa)"


@pytest.mark.parametrize(("label", "unit", "text"), [
    ("chain_length", "m", "chain length, m"), ("volume", "m^3", "volume, m³"),
    ("cost", "EUR", "cost, EUR"), ("coefficient_of_dynamics", "-", "coefficient of dynamics")])
def test_unit_header_names_the_unit(label: str, unit: str, text: str) -> None:
    assert unit_header(label, unit) == text


def test_a_length_below_a_micrometre_is_shown_as_zero() -> None:
    """A taut span's sag of 1.376e-8 m (round-off) was printed as 1.376e-5 mm; lengths
    resolve to 1 µm (display.RESOLUTION), in either unit system."""
    from chaindrive.display import RESOLUTION, convert

    assert RESOLUTION["length"] == 1e-6
    assert convert(1.376e-8, "length") == (0.0, "mm")
    assert convert(-3.9e-7 * 0.0254, "length", "US") == (0.0, "in")
    assert convert(2e-6, "length")[0] == pytest.approx(2e-3)
    assert convert(1.376e-8, "force") == (pytest.approx(1.376e-8), "N")  # other kinds as they are
