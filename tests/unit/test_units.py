"""The quantity parser (chaindrive.units): common spellings read, angles and speeds checked,
nothing a design file writes is evaluated, every refusal is one DesignError line.

Expected values are unit definitions (closed forms): 1 rpm = 2π/60 rad/s; 1 hp = 745.7 W
(mechanical horsepower, 550 ft·lbf/s); 1 in = 25.4 mm; 1 lbf = 4.448 N; rotational frequency
n in min⁻¹ means revolutions per minute [ISO80000-3].
"""

from __future__ import annotations

import math

import pytest

from chaindrive.errors import DesignError
from chaindrive.units import MAX_TEXT, parse_quantity

RPM = 2 * math.pi / 60


@pytest.mark.parametrize(("text", "dimension", "si"), [
    ("300 kW", "power", 300e3), ("3 kw", "power", 3e3), ("3 KW", "power", 3e3),
    ("1 hp", "power", 745.6998715822701),
    ("300 rpm", "speed", 300 * RPM), ("300 RPM", "speed", 300 * RPM),
    ("300 Rpm", "speed", 300 * RPM), ("300 1/min", "speed", 300 * RPM),
    ("300 min⁻¹", "speed", 300 * RPM), ("300 min^-1", "speed", 300 * RPM),
    ("300 r/min", "speed", 300 * RPM), ("300 rev/min", "speed", 300 * RPM),
    ("5 1/s", "speed", 5 * 2 * math.pi), ("2 rad/s", "speed", 2.0),
    ("2 in", "length", 0.0508), ("25.4 mm", "length", 0.0254), (".5 mm", "length", 5e-4),
    ("5 lbf", "force", 22.241108076302503), ("5 KN", "force", 5e3),
    ("2 Nm", "torque", 2.0), ("2 N*m", "torque", 2.0),
    ("0.06 kg*m^2", "inertia", 0.06), ("0.06 kg*m²", "inertia", 0.06),
    ("30 deg", "angle", math.pi / 6), ("0.5 rad", "angle", 0.5),
])
def test_common_spellings(text: str, dimension: str, si: float) -> None:
    assert parse_quantity(text, dimension, "f") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(("text", "dimension", "message"), [
    ("300 m/s", "angle", "'300 m/s' is not an angle"),  # the dimension of an angle is checked
    ("30", "angle", "missing unit"),
    ("30 percent", "angle", "is not an angle"),
    ("1 Hz", "speed", "ambiguous speed unit"),
    ("300 kg", "speed", "is not a speed"),
    ("500", "length", "missing unit"),
    ("9**9**9 mm", "length", "cannot read the unit"),  # never evaluated
    ("2 mm**999", "length", "cannot read the unit"),
    ("1e400 mm", "length", "out of range"),
    ("inf mm", "length", "cannot read"),
    ("nan mm", "length", "cannot read"),
    ("1 furlongz", "length", "unknown unit"),
    ("12 mm\nx", "length", "unknown unit"),
    ("1 (mm", "length", "cannot read the unit"),
])
def test_refusals_are_one_line(text: str, dimension: str, message: str) -> None:
    with pytest.raises(DesignError) as info:
        parse_quantity(text, dimension, "sprockets[0].x")
    line = str(info.value)
    assert message in line
    assert "\n" not in line and line.startswith("sprockets[0].x: ")


def test_a_long_text_is_refused_and_cut_in_the_message() -> None:
    with pytest.raises(DesignError) as info:
        parse_quantity("1" * 5000 + " mm", "length", "x")
    assert "too long" in str(info.value)
    assert len(str(info.value)) < 3 * MAX_TEXT


@pytest.mark.parametrize("value", [12, 1.5, True, None, [1], {"a": 1}])
def test_non_strings_are_refused(value: object) -> None:
    with pytest.raises(DesignError, match="must be a string with a unit"):
        parse_quantity(value, "length", "x")


def test_forty_digits_read_as_a_number() -> None:
    """A 40-digit number is a number (the plausibility limits judge it, not the parser)."""
    assert parse_quantity("4" + "0" * 39 + " mm", "length", "x") == pytest.approx(4e36)
