"""Checks that cannot be made say so: a design without its power has its chain's strength
'cannot be verified' (never an analysis that passes because the checks needing the power were
left out), and k₁ of a model without its motor cannot be verified."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import chaindrive
from chaindrive.checks import UNVERIFIED

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_without_power_the_strength_cannot_be_verified() -> None:
    drive = chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml")
    a = chaindrive.analyze(replace(drive, power=None))
    row = a.check("chain_strength")
    assert row is not None and row.status == UNVERIFIED and "no power given" in row.note
    assert not all(c.passed for c in a.checks())
    names = {c.name for c in a.checks()}
    assert {"teeth in mesh", "wrap", "span length"} <= names  # the layout is still checked


def test_k1_of_an_incomplete_model_cannot_be_verified() -> None:
    """The Jindal example has no motor and nothing on the driven shaft: its start-up is that
    of bare sprockets, and the model warns that it is not the drive's."""
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"))
    assert not a.drive_model.complete
    k1 = a.check("k1")
    assert k1 is not None and k1.status == UNVERIFIED and "incomplete" in k1.note
    assert any(w.code == "dynamics.model-incomplete" for w in a.warnings)


def test_estimated_catalogue_data_are_named_in_the_json() -> None:
    """The polymer catalogue row marks its breaking load, mass, allowable load and speed limit
    as estimates (formulas of the catalogue's header): the JSON's drive summary names them
    beside the numbers; a published steel row names none."""
    polymer = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket_polymer.toml"),
                                 response=False).to_dict()["drive"]
    assert polymer["estimated_data"] == ["breaking_load_kN", "mass_kg_m", "allowable_load_kN",
                                         "max_speed_m_s"]
    steel = chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"),
                               response=False).to_dict()["drive"]
    assert steel["estimated_data"] == []
