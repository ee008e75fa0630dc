"""Unit tests of chaindrive.strength.selection (ranking, choice, errors)."""

from __future__ import annotations

import pytest

from chaindrive.catalog import chains
from chaindrive.errors import DesignError
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import iso10823, select_chain
from chaindrive.strength.selection import estimated_links, method_for
from tests.conftest import make_spec, rpm


def drive(power: float, n1: float = 500.0, standard: str = "ISO 606") -> Drive:
    spec = make_spec(0.0254)
    if standard != "ISO 606":
        spec = next(c for c in chains() if c.standard == standard and c.strands == 1)
    return Drive("sel", Chain(spec), (Sprocket("A", 19, 0.0, 0.0, "driver", speed=rpm(n1)),
                                      Sprocket("B", 38, 1.0, 0.0, "driven")), power=power)


def test_method_by_family():
    assert method_for("ISO 606") == "ISO 10823"
    assert method_for("ANSI") == "ISO 10823"
    assert method_for("GOST 13568") == "Kэ"


def test_iso_selection_is_lightest_feasible_simplex():
    res = select_chain(drive(5000.0), series="A")
    assert res.method == "ISO 10823" and res.chain.strands == 1
    iso = [c for c in res.candidates if c.method == "ISO 10823"]
    feasible = [c for c in iso if c.feasible and c.strands == 1]
    assert res.chain.designation == min(feasible, key=lambda c: c.mass_per_length).designation
    # every lighter simplex chain of the family falls short
    for c in iso:
        if c.strands == 1 and c.mass_per_length < res.chain.mass_per_length:
            assert not c.feasible
    assert {c.method for c in res.candidates} == {"ISO 10823", "Kэ"}
    d = res.to_dict()
    assert d["chain"] == res.chain.designation and d["candidates"][0]["feasible"]


def test_candidates_ranked_feasible_then_pitch_strands_margin():
    res = select_chain(drive(5000.0), series="B")
    keys = [(not c.feasible, c.pitch, c.strands, -c.margin) for c in res.candidates]
    assert keys == sorted(keys)


def test_strands_given_and_margin_positive():
    res = select_chain(drive(5000.0), series="A", strands=2)
    assert res.chain.strands == 2
    chosen = next(c for c in res.candidates
                  if c.designation == res.chain.designation and c.method == res.method)
    assert chosen.margin >= 0
    single, _ = iso10823.aca_rating(res.chain, 19, rpm(500))
    assert chosen.details["rated_power_w"] == pytest.approx(single * 1.7)


def test_gost_selection_uses_ke_method():
    res = select_chain(drive(3000.0, 300.0, "GOST 13568"), operating_factor=1.5)
    assert res.method == "Kэ"
    chosen = next(c for c in res.candidates
                  if c.designation == res.chain.designation and c.method == "Kэ")
    assert chosen.feasible and chosen.details["pressure_mpa"] <= chosen.details[
        "allowable_pressure_mpa"]


def test_no_chain_can_carry_it_names_best_candidate():
    with pytest.raises(DesignError, match=r"no chain can carry .* best candidate .* falls short"):
        select_chain(drive(5e6), series="A")


def test_bad_inputs():
    d = Drive("x", Chain(make_spec()), (Sprocket("A", 19, 0, 0, "driver"),
                                        Sprocket("B", 19, 1, 0, "driven")))
    with pytest.raises(DesignError, match="drive.power"):
        select_chain(d)
    with pytest.raises(DesignError, match="chain.strands"):
        select_chain(drive(1000.0), strands=9)
    with pytest.raises(DesignError, match="method"):
        select_chain(drive(1000.0), method="AGMA")


def test_estimated_links_two_sprocket():
    # 2a/p + (z1 + z2)/2
    assert estimated_links(drive(1.0), 0.0254) == pytest.approx(2 / 0.0254 + 28.5)
