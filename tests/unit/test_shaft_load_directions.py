"""Shaft loads with their direction: the JSON gives each load's components and its angle from
+x (counter-clockwise, atan2 of the components), the command line prints all three."""

from __future__ import annotations

import io
import math
from contextlib import redirect_stdout

import chaindrive
from chaindrive.cli import run
from tests.conftest import EXAMPLES


def test_directions_are_the_angles_of_the_load_vectors() -> None:
    doc = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                             response=False).strength.loads.to_dict()
    for (x, y), deg, f in zip(doc["shaft_load_vectors_n"], doc["shaft_load_directions_deg"],
                              doc["shaft_loads_n"], strict=True):
        assert math.isclose(f * math.cos(math.radians(deg)), x, rel_tol=1e-12, abs_tol=1e-9)
        assert math.isclose(f * math.sin(math.radians(deg)), y, rel_tol=1e-12, abs_tol=1e-9)


def test_the_command_line_prints_components_and_direction() -> None:
    out = io.StringIO()
    with redirect_stdout(out):
        assert run(["analyze", str(EXAMPLES / "seed_three_sprocket.toml"), "--quick"]) == 0
    text = out.getvalue()
    assert "Shaft loads (direction from +x, counter-clockwise)" in text
    assert "direction, °" in text
