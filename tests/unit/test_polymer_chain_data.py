"""Unit tests of the packaged polymer chain rows (``catalog/data/chains_polymer.csv``).

What each test compares against:

* the dimensions: the published ISO 606:1994 values of the chain number [ISO606] (Table 1:
  pitch, roller diameter, pin diameter, inner width, plate depth, transverse pitch);
* the glass-filled material: 27 kpsi, the tensile strength of PA66 + 30 % glass fibre in
  Harper, *Handbook of Plastics Technologies*, Table 5.21 [HPT];
* the estimated columns: the closed forms stated in the file's header (net plate section ×
  tensile strength, steel mass × density ratio, breaking load / 6 [DiamondChain]);
* the speed limit: 50 m/min, the maximum chain speed of standard polyacetal engineered-plastic
  chain in Tsubakimoto Chain, *The Complete Guide to Chain*, Table 4.1 [TsubakiGuide]
  (transferred to these rows, so listed as an estimate); the allowable loads against the same
  guide's Table 4.14 (RS40P 0.44 kN);
* the sources: every number is either covered by a cited source or listed as ESTIMATED.
"""

from __future__ import annotations

import csv
import math
from dataclasses import replace
from importlib import resources

import pytest

import chaindrive
from chaindrive.catalog import find_chain, find_material
from chaindrive.io.design import drive_from_mapping, parse_toml
from chaindrive.model import Drive
from chaindrive.strength.selection import rank_chains

KPSI = 6.894757e6  # Pa per kpsi (exact to the 7 figures of the definition 1 lbf/in² = 6894.757 Pa)
DIMENSIONS = ("pitch_mm", "roller_diameter_mm", "pin_diameter_mm", "inner_width_mm",
              "plate_depth_mm", "transverse_pitch_mm")
NUMBERS = (*DIMENSIONS, "breaking_load_kN", "mass_kg_m", "allowable_load_kN", "max_speed_m_s")


def _rows(name: str) -> list[dict[str, str]]:
    text = resources.files("chaindrive").joinpath(f"catalog/data/{name}").read_text("utf-8")
    return list(csv.DictReader(line for line in text.splitlines()
                               if line.strip() and not line.startswith("#")))


POLYMER = _rows("chains_polymer.csv")
STEEL = {row["designation"]: row for row in _rows("chains_iso606.csv")}


def _number(row: dict[str, str]) -> str:
    """The ISO 606 chain number of a polymer row ('polymer POM 08B-1' → '08B')."""
    return row["designation"].split()[-1].split("-")[0]


def _estimated(row: dict[str, str]) -> set[str]:
    """The columns a row lists after 'ESTIMATED:' in its source cell."""
    tail = row["source"].split("ESTIMATED:", 1)
    return set() if len(tail) == 1 else set(tail[1].split("(")[0].strip().split("|"))


# ISO 606:1994 Table 1, B series: p, d1 max, d2 max, b1 min, h2 max, pt [mm] [ISO606]
ISO606_B = {"06B": (9.525, 6.35, 3.28, 5.72, 8.26, 10.24),
            "08B": (12.70, 8.51, 4.45, 7.75, 11.81, 13.92),
            "10B": (15.875, 10.16, 5.08, 9.65, 14.73, 16.59),
            "16B": (25.40, 15.88, 8.28, 17.02, 21.08, 31.88)}


def test_there_are_acetal_polyamide_and_glass_filled_polyamide_chains():
    assert {row["material"] for row in POLYMER} == {"POM", "PA66", "PA66-GF30"}
    assert {_number(r) for r in POLYMER if r["material"] == "PA66-GF30"} == set(ISO606_B)


@pytest.mark.parametrize("row", POLYMER, ids=lambda r: r["designation"])
def test_dimensions_are_the_published_iso606_values(row: dict[str, str]):
    """[ISO606] Table 1 (B series) for the chain number of the row."""
    published = ISO606_B[_number(row)]
    assert tuple(float(row[c]) for c in DIMENSIONS) == pytest.approx(published, abs=1e-9)


@pytest.mark.parametrize("row", POLYMER, ids=lambda r: r["designation"])
def test_every_number_is_sourced_or_flagged_as_an_estimate(row: dict[str, str]):
    estimated = _estimated(row)
    assert estimated <= set(NUMBERS), "ESTIMATED names a column the file does not have"
    assert "[ISO606]" in row["source"]  # the dimensions' source
    material = find_material(row["material"])
    assert material.source and material.tensile_strength is not None
    for column in NUMBERS:
        if row[column].strip() and column not in DIMENSIONS:
            assert column in estimated, f"{column} has neither a source nor the estimate flag"
    # the speed limit is a transferred maker's value: flagged, and its source named
    assert "max_speed_m_s" in estimated and "[TsubakiGuide]" in row["source"]


@pytest.mark.parametrize("row", POLYMER, ids=lambda r: r["designation"])
def test_estimates_follow_the_header_formulas(row: dict[str, str]):
    """Q = σ_t·2·(h2 − d2)·t with t = (pt − b1)/4; q = q_steel·ρ/7850; allowable = Q/6."""
    steel = STEEL[f"ISO 606 {_number(row)}-1"]
    material = find_material(row["material"])
    pt, b1, h2, d2 = (float(row[c]) * 1e-3 for c in ("transverse_pitch_mm", "inner_width_mm",
                                                      "plate_depth_mm", "pin_diameter_mm"))
    breaking = material.tensile_strength * 2 * (h2 - d2) * (pt - b1) / 4
    # three significant figures in the file: within 0.5 %
    assert float(row["breaking_load_kN"]) * 1e3 == pytest.approx(breaking, rel=5e-3)
    assert float(row["mass_kg_m"]) == pytest.approx(
        float(steel["mass_kg_m"]) * material.density / 7850.0, rel=5e-3)
    assert float(row["allowable_load_kN"]) * 1e3 == pytest.approx(breaking / 6, rel=5e-3)


# [TsubakiGuide] Table 4.1: standard polyacetal engineered-plastic chain, 50 m/min
POLYACETAL_MAX_SPEED = 50.0 / 60.0  # m/s
# [TsubakiGuide] Table 4.14: RS40P (12.70 mm pitch, polyacetal) maximum allowable load
RS40P_ALLOWABLE = 0.44e3  # N


@pytest.mark.parametrize("row", POLYMER, ids=lambda r: r["designation"])
def test_speed_limit_is_the_published_polyacetal_chain_limit(row: dict[str, str]):
    """[TsubakiGuide] Table 4.1: 50 m/min = 0.8333 m/s (the file prints 3 decimals)."""
    assert float(row["max_speed_m_s"]) == pytest.approx(POLYACETAL_MAX_SPEED, abs=5e-4)
    assert find_chain(row["designation"]).max_speed == pytest.approx(POLYACETAL_MAX_SPEED,
                                                                     abs=5e-4)


def test_estimated_allowable_load_is_below_the_published_polyacetal_chain_of_that_pitch():
    """Cross-check, not a calibration: the POM 08B-1 estimate (Q/6 = 0.246 kN) stays below the
    0.44 kN a maker allows its polyacetal RS40P chain of the same 12.70 mm pitch
    ([TsubakiGuide] Table 4.14; that chain runs on stainless-steel pins, which the all-polymer
    estimate leaves out, so the estimate is expected lower, not equal)."""
    pom = find_chain("POM 08B")
    assert pom.pitch == pytest.approx(0.0127)
    assert pom.allowable_load is not None and pom.allowable_load < RS40P_ALLOWABLE
    assert pom.allowable_load == pytest.approx(246.0, rel=5e-3)


def test_glass_filled_polyamide_strength_is_the_handbook_value():
    """[HPT] Table 5.21: PA66 + 30 % glass fibre, tensile strength 27 kpsi."""
    gf = find_material("PA66-GF30")
    assert gf.tensile_strength == pytest.approx(27 * KPSI, rel=1e-3)
    assert gf.family == "glass-filled polyamide" and gf.is_polymer
    # about 2.9 × the breaking load of the unfilled PA66 chain of the same number
    ratio = find_chain("PA66-GF30 08B").breaking_load / find_chain("PA66 08B").breaking_load
    assert ratio == pytest.approx(27 * KPSI / find_material("PA66").tensile_strength, rel=1e-2)


def _drive(designation: str, power_w: float) -> Drive:
    """A two-sprocket design file naming its chain by designation (one line)."""
    text = (f'[drive]\nname = "poly"\npower = "{power_w} W"\n[chain]\n'
            f'designation = "{designation}"\n[[sprockets]]\nname = "A"\nteeth = 19\n'
            'x = "0 mm"\ny = "0 mm"\nrole = "driver"\nspeed = "100 rpm"\n'
            '[[sprockets]]\nname = "B"\nteeth = 38\nx = "500 mm"\ny = "0 mm"\n'
            'role = "driven"\n')
    return drive_from_mapping(parse_toml(text, "poly.toml"))


def test_glass_filled_chain_is_analysed_and_ranked():
    """A 20 W drive at 100 rpm on 19 teeth: chain speed v = 19·0.0127·100/60 = 0.402 m/s, pull
    F_t = P/v = 49.7 N (closed form) plus the sag and centrifugal pulls — far below the
    estimated allowable load of the PA66-GF30 08B-1 row (704 N)."""
    drive = _drive("PA66-GF30 08B", 20.0)
    result = chaindrive.analyze(drive, response=False)
    (allowable,) = [c for c in result.checks() if c.name == "allowable load"]
    f_t = 20.0 / (19 * 0.0127 * 100 / 60)
    assert allowable.limit == pytest.approx(704.0, rel=1e-2) and allowable.status == "pass"
    assert f_t <= allowable.value <= 1.2 * f_t
    # the speed check is verified against the packaged limit: v = z·p·n/60 (closed form)
    (speed,) = [c for c in result.checks() if c.name == "speed limit"]
    assert speed.status == "pass"
    assert speed.value == pytest.approx(19 * 0.0127 * 100 / 60, rel=1e-9)
    assert speed.limit == pytest.approx(POLYACETAL_MAX_SPEED, abs=5e-4)
    # so the selection can choose a polymer chain, and the one it chooses passes every check
    ranked = rank_chains(drive, standard="polymer")
    by_name = {c.designation: c for c in ranked.candidates}
    assert {"polymer PA66-GF30 08B-1", "polymer POM 08B-1"} <= set(by_name)
    assert ranked.chosen is not None and ranked.chosen.designation.startswith("polymer ")
    assert all(c.status == "pass" for c in ranked.chosen.checks)


def test_polymer_chain_above_the_speed_limit_fails_and_none_is_chosen():
    """300 rpm on 19 teeth: v = 19·p·300/60 ≥ 0.905 m/s for every packaged pitch (06B:
    p = 9.525 mm), above the 0.833 m/s limit [TsubakiGuide, Table 4.1]: the speed check fails
    (it no longer reports "cannot be verified") and no polymer chain is chosen."""
    drive = _drive("POM 08B", 20.0)
    drive = replace(drive, sprockets=(replace(drive.sprockets[0], speed=300 * math.pi / 30),
                                      drive.sprockets[1]))
    result = chaindrive.analyze(drive, response=False)
    (speed,) = [c for c in result.checks() if c.name == "speed limit"]
    assert speed.status == "fail"
    assert speed.value == pytest.approx(19 * 0.0127 * 300 / 60, rel=1e-9)
    ranked = rank_chains(drive, standard="polymer")
    assert ranked.chosen is None
    assert all(c.governing == "speed limit" for c in ranked.candidates)
