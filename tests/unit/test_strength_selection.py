"""Unit tests of chaindrive.strength.selection: one rule ranks and chooses, top N, margins as
fractions, the closest chain when nothing passes, user catalogue entries, bad input.

Numbers come from closed forms (the ranking rule, margin = rated/design − 1) or from the
check functions themselves; the published cases are in tests/validation/."""

from __future__ import annotations

import math

import pytest

from chaindrive.catalog import chains, find_chain
from chaindrive.errors import DesignError
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import ratings, select_chain
from chaindrive.strength.selection import estimated_links, family_method, rank_chains, rank_key
from tests.conftest import make_spec, rpm


def drive(power: float, n1: float = 500.0, standard: str = "ISO 606", a: float = 1.0,
          service_factor: float | None = None) -> Drive:
    spec = make_spec(0.0254)
    if standard != "ISO 606":
        spec = next(c for c in chains() if c.standard == standard and c.strands == 1)
    return Drive("sel", Chain(spec), (Sprocket("A", 19, 0.0, 0.0, "driver", speed=rpm(n1)),
                                      Sprocket("B", 38, a, 0.0, "driven")), power=power,
                 service_factor=service_factor)


def test_method_by_family_and_by_chain():
    assert family_method("ISO 606") == "rating" and family_method("GOST 13568") == "Kэ"
    assert ratings.method_for(find_chain("16A-1")) == ratings.ACA
    assert ratings.method_for(find_chain("ANSI 80H")) == ratings.ACA
    assert ratings.method_for(find_chain("16B-1")) == ratings.B_TABLE
    assert ratings.method_for(find_chain("POM 08B")) == ratings.POLYMER
    gost = next(c for c in chains() if c.standard == "GOST 13568")
    assert ratings.method_for(gost) == ratings.KE


def test_one_rule_ranks_and_chooses():
    res = rank_chains(drive(5000.0), series="A")
    keys = [rank_key(c) for c in res.candidates]
    assert keys == sorted(keys)
    chosen = res.chosen
    assert chosen is not None and chosen is res.candidates[0]
    assert res.chain.designation == chosen.designation
    # the rule: every lighter candidate misses a check
    for c in res.candidates:
        if c.mass_per_length < chosen.mass_per_length:
            assert not c.passed and c.missed
    assert all(c.passed for c in chosen.checks)


def test_top_n_and_one_margin_unit():
    res = rank_chains(drive(5000.0), series="A")
    assert [c.designation for c in res.top(3)] == [c.designation for c in res.candidates[:3]]
    d = res.to_dict(top=3)
    assert len(d["candidates"]) == 3 and d["candidate_count"] == len(res.candidates)
    assert d["candidates"][0]["chain"] == d["chain"]
    assert "margin" not in d["candidates"][0] and "margin_fraction" in d["candidates"][0]
    with pytest.raises(DesignError, match="top"):
        res.top(0)
    # margin of the power-rating check = rated / design − 1 (a fraction, not per cent)
    c = res.chosen
    assert c is not None
    check = next(k for k in c.checks if k.name == "power rating")
    assert check.margin_fraction == pytest.approx(check.value / check.limit - 1.0)
    assert c.margin_fraction <= check.margin_fraction + 1e-12


def test_nothing_passes_names_the_closest_and_what_it_misses():
    res = rank_chains(drive(5e6), series="A")
    assert res.chosen is None and res.closest is not None
    assert res.closest.missed
    d = res.to_dict(top=5)
    assert d["chain"] is None and d["closest"]["missed"]
    assert res.closest.designation in d["shortfall"]
    # one rule ranks and names: the closest heads the table, the rest follow by closeness
    assert d["candidates"][0]["chain"] == res.closest.designation
    fewest = [len(c.missed) for c in res.candidates if c.governing != "geometry"]
    assert fewest == sorted(fewest)
    with pytest.raises(DesignError, match=r"no chain passes every check: the closest is"):
        select_chain(drive(5e6), series="A")
    with pytest.raises(DesignError, match="no chain passes"):
        _ = res.chain


def test_gost_candidates_are_checked_by_the_ke_method():
    res = rank_chains(drive(3000.0, 300.0, "GOST 13568"), operating_factor=1.5)
    chosen = res.chosen
    assert chosen is not None and chosen.method == "Kэ"
    names = {c.name for c in chosen.checks}
    assert {"hinge pressure", "speed limit", "impacts per second", "static safety"} <= names
    p = next(c for c in chosen.checks if c.name == "hinge pressure")
    assert p.value <= p.limit


def test_outside_the_tables_is_cannot_be_verified_and_fails():
    """At 30 000 rpm no [p], [s] or n1 max table has a value: the GOST chains cannot be
    verified (a failure, said as such) instead of passing."""
    res = rank_chains(drive(100.0, 30000.0, "GOST 13568"))
    assert res.chosen is None
    statuses = {c.status for cand in res.candidates for c in cand.checks
                if c.name in ("hinge pressure", "static safety")}
    assert "cannot be verified" in statuses


def test_user_catalogue_entries_take_part(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text('[[chains]]\ndesignation = "MY 16B-1"\nstandard = "ISO 606"\n'
                    'series = "B"\npitch = "25.4 mm"\nroller_diameter = "15.88 mm"\n'
                    'pin_diameter = "8.28 mm"\ninner_width = "17.02 mm"\n'
                    'plate_depth = "21.08 mm"\ntransverse_pitch = "31.88 mm"\n'
                    'breaking_load = "60 kN"\nmass_per_length = "0.5 kg/m"\n',
                    encoding="utf-8")
    res = rank_chains(drive(5000.0), series="B", extra_files=[str(path)])
    assert "MY 16B-1" in {c.designation for c in res.candidates}


def test_bad_inputs():
    d = Drive("x", Chain(make_spec()), (Sprocket("A", 19, 0, 0, "driver"),
                                        Sprocket("B", 19, 1, 0, "driven")))
    with pytest.raises(DesignError, match="drive.power"):
        select_chain(d)
    with pytest.raises(DesignError, match="chain.strands"):
        select_chain(drive(1000.0), strands=9)
    with pytest.raises(DesignError, match="method"):
        select_chain(drive(1000.0), method="AGMA")
    with pytest.raises(DesignError, match="no ISO 606 series Q"):
        select_chain(drive(1000.0), series="Q")


def test_legacy_method_name_means_rating():
    a = rank_chains(drive(5000.0), series="A", method="ISO 10823")
    b = rank_chains(drive(5000.0), series="A")
    assert a.chosen is not None and a.chosen.designation == b.chosen.designation


def test_estimated_links_two_sprocket():
    # 2a/p + (z1 + z2)/2
    assert estimated_links(drive(1.0), 0.0254) == pytest.approx(2 / 0.0254 + 28.5)


def test_every_candidate_has_lubrication_and_rating():
    res = rank_chains(drive(5000.0), series="B")
    for c in res.candidates:
        assert c.lubrication is not None and c.rating is not None
        assert math.isfinite(c.lubrication.speed)
