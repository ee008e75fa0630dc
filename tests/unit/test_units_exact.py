"""The units read without pint (chaindrive.units.EXACT_UNITS) give pint's value to the last
bit, and a design in those units loads without importing pint.

Reference: pint's own conversion (the parser's path for every other unit,
``chaindrive.units._with_pint``) on the same text; the factors themselves are unit
definitions (closed forms: 1 mm = 10⁻³ m, 1 rpm = 2π/60 rad/s, 1 deg = π/180 rad, …).
"""

from __future__ import annotations

import math
import random
import subprocess
import sys

import pytest

from chaindrive.units import DIMENSIONS, EXACT_UNITS, _with_pint, parse_quantity

CLOSED_FORMS = {"mm": 1e-3, "cm": 1e-2, "rpm": 2 * math.pi / 60, "deg": math.pi / 180,
                "kW": 1e3, "min": 60.0, "h": 3600.0, "MPa": 1e6, "mm^2": 1e-6}


def _values() -> list[float]:
    rng = random.Random(14)
    return [0.0, 1.0, 25.4, 0.3, 1450.0, 7.5, -3.25] + \
        [rng.uniform(-1.0, 1.0) * 10.0 ** rng.randint(-9, 9) for _ in range(200)]


@pytest.mark.parametrize(("dimension", "unit"), sorted(EXACT_UNITS))
def test_exact_unit_is_pints_value_to_the_last_bit(dimension: str, unit: str) -> None:
    assert dimension in DIMENSIONS
    for v in _values():
        text = f"{v!r} {unit}"
        assert parse_quantity(text, dimension, "x") == _with_pint(text, dimension, "x"), text
    factor = EXACT_UNITS[(dimension, unit)]
    if unit in CLOSED_FORMS:
        assert factor == pytest.approx(CLOSED_FORMS[unit], rel=1e-15)


def test_other_spellings_still_go_through_pint() -> None:
    # a unit outside the table (inch: 25.4 mm by definition) and a refusal keep pint's path
    assert parse_quantity("1 inch", "length", "x") == pytest.approx(0.0254, rel=1e-15)
    with pytest.raises(Exception, match="is not a length"):
        parse_quantity("3 kg", "length", "x")


@pytest.mark.concurrency
def test_a_design_in_those_units_loads_without_pint() -> None:
    code = ("import sys, chaindrive; from chaindrive.examples import load; "
            "load('twenty_four_sprocket'); print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.strip() == "False"
