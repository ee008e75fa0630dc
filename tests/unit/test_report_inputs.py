"""The report's Inputs hold what the dynamic model is built from: every sprocket's reduced mass,
power share and load law, the motor as the model uses it and every element of the trains, in
the report's units (the conveyor example: motor, reducer, couplings and drums)."""

from __future__ import annotations

from pathlib import Path

import pytest

import chaindrive
from chaindrive.report import Table, build_report

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _tables(name: str, units: str = "SI") -> dict[str, Table]:
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / f"{name}.toml"), response=False)
    r = build_report(a, units=units, dpi=40)  # type: ignore[arg-type]
    blocks = next(s for s in r.sections if s.key == "inputs").blocks
    return {b.caption.split(" (")[0]: b for b in blocks if isinstance(b, Table)}


def test_conveyor_inputs_show_motor_and_trains() -> None:
    t = _tables("conveyor_five_sprocket")
    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    motor = {r[0]: r[1] for r in t["Motor"].rows}
    assert motor["rotor inertia"] == pytest.approx(drive.motor.rotor_inertia)
    assert motor["rated speed"] == pytest.approx(1430.0)
    trains = t["Trains of the sprockets"].rows
    elements = [(s.name, e.name) for s in drive.sprockets for e in s.train]
    assert [(r[0], r[2]) for r in trains] == elements
    drums = [r for r in trains if str(r[2]).startswith("drum")]
    assert drums and all(r[3] == pytest.approx(1.2) for r in drums)  # kg·m², as given
    sprockets = t["Sprockets as given"]
    assert "power share" in sprockets.columns and "load law" in sprockets.columns


def test_seed_inputs_show_the_entered_reduced_masses() -> None:
    """The seed enters reduced masses (17.26 / 28.44 / 2.0 kg); they are what the model uses."""
    rows = _tables("seed_three_sprocket")["Sprockets as given"]
    col = next(i for i, c in enumerate(rows.columns) if c.startswith("reduced mass"))
    assert [r[col] for r in rows.rows] == pytest.approx([17.26, 28.44, 2.0])


def test_trains_in_us_units() -> None:
    t = _tables("conveyor_five_sprocket", "US")
    cols = t["Trains of the sprockets"].columns
    assert any("lb·ft²" in c for c in cols) and any("lbf·ft/rad" in c for c in cols)
