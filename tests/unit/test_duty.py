"""Duty of a drive: service factor from the duty classes, required life, direction of rotation
and the tight span, an idler on the tight span, the fatigue check.

Sources:
* the service-factor grid of [Mott2014, Table 7-17] ([Tsubaki, Table 4.2] prints the same
  numbers), as compiled in /work/shared/data/iso10823_method.md §2.1–2.2;
* kд of the Kэ method: 1.0 calm, 1.35 with shocks (programs' value in the textbooks'
  1.2…1.5), 1.8 heavy shocks [ChainDesignRU, §1] (/work/shared/data/chain_design_method_ru.md);
* Bhandari, Design of Machine Elements, 3rd ed., example 14.3: 5 kW, 1400 rpm, z1 = 21,
  z2 = 63, a = 500 mm, Ks = 1.3 for moderate shock with an electric motor (iso10823_method.md
  §2.3): the book chooses 08A;
* the tight span of a two-sprocket drive: the driver pulls in the span on the side towards
  which its top or bottom moves — closed form of the rotation.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from chaindrive.catalog import find_chain
from chaindrive.checks import FAIL, PASS, UNVERIFIED
from chaindrive.geometry.contour import contour_geometry, driver_rotation, in_travel_order
from chaindrive.io.design import drive_from_mapping, drive_to_mapping, parse_toml
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength.drive_checks import checks_for, settings_for
from chaindrive.strength.duty import (
    DRIVEN_EXAMPLES,
    DRIVER_EXAMPLES,
    duty_warnings,
    service_factor_for,
)
from chaindrive.strength.loads import loads_of
from chaindrive.strength.selection import rank_chains
from chaindrive.strength.span_checks import fatigue_check, idler_checks, idler_warnings

RPM = math.pi / 30

# [Mott2014, Table 7-17] rows smooth / moderate shock / heavy shock; columns electric motor,
# hydraulic drive (IC engine), IC engine with mechanical drive (iso10823_method.md §2.2)
MOTT = {("smooth", "smooth"): 1.0, ("smooth", "moderate shock"): 1.3,
        ("smooth", "heavy shock"): 1.5,
        ("slight shock", "smooth"): 1.0, ("slight shock", "moderate shock"): 1.2,
        ("slight shock", "heavy shock"): 1.4,
        ("moderate shock", "smooth"): 1.2, ("moderate shock", "moderate shock"): 1.4,
        ("moderate shock", "heavy shock"): 1.7}
KD = {"smooth": 1.0, "moderate shock": 1.35, "heavy shock": 1.8}


def two(chain: str = "ISO 606 08A-1", z1: int = 21, z2: int = 63, a: float = 0.5,
        **kw: object) -> Drive:
    return Drive("t", Chain(find_chain(chain)),
                 (Sprocket("A", z1, 0.0, 0.0, "driver", speed=1400 * RPM),
                  Sprocket("B", z2, a, 0.0, "driven")), power=5e3, **kw)  # type: ignore[arg-type]


@pytest.mark.parametrize(("driver", "driven"), list(MOTT))
def test_grid_reproduces_mott_table_7_17(driver, driven):
    sf = service_factor_for(two(driver_duty=driver, driven_duty=driven))
    assert sf.value == MOTT[driver, driven]
    assert sf.origin == "duty classes" and "Mott2014, Table 7-17" in sf.table
    assert "ISO 10823" not in sf.table  # the ISO f1 table was not available


@pytest.mark.parametrize("driven", list(KD))
def test_gost_chains_take_kd_of_the_ke_method(driven):
    d = two("GOST 13568 ПР-12,7-18,2", driver_duty="moderate shock", driven_duty=driven)
    sf = service_factor_for(d)
    assert sf.value == KD[driven] and "kд" in sf.table


def test_given_factor_overrides_and_default_is_said():
    assert service_factor_for(two(service_factor=1.7, driven_duty="smooth")).origin == "given"
    default = two()
    sf = service_factor_for(default)
    assert (sf.value, sf.origin) == (1.0, "default")
    assert [w.code for w in duty_warnings(default)] == ["duty.service-factor-default"]
    assert duty_warnings(two(driver_duty="smooth", driven_duty="smooth")) == []
    half = two(driven_duty="heavy shock")  # driver left out: smooth assumed, and said
    assert service_factor_for(half).value == 1.5
    assert [w.code for w in duty_warnings(half)] == ["duty.class-assumed"]


def test_every_class_has_examples():
    assert set(DRIVER_EXAMPLES) == {"smooth", "slight shock", "moderate shock"}
    assert set(DRIVEN_EXAMPLES) == {"smooth", "moderate shock", "heavy shock"}
    assert all(DRIVER_EXAMPLES.values()) and all(DRIVEN_EXAMPLES.values())


BHANDARI_14_3 = '''
[drive]
name = "Bhandari 14.3"
power = "5 kW"
driver = "smooth"
driven = "moderate shock"
required_life = "20000 h"

[chain]
standard = "ISO 606"
series = "A"

[[sprockets]]
name = "A"
teeth = 21
x = "0 mm"
y = "0 mm"
role = "driver"
speed = "1400 rpm"

[[sprockets]]
name = "B"
teeth = 63
x = "500 mm"
y = "0 mm"
'''


def test_bhandari_ex14_3_through_the_design_file_fields():
    """Moderate shock with an electric motor gives Bhandari's Ks = 1.3; with it the selection
    chooses the book's 08A (the book: 5.28 kW ≥ 5.16 kW required)."""
    drive = drive_from_mapping(parse_toml(BHANDARI_14_3, "t"))
    assert service_factor_for(drive).value == 1.3
    settings = settings_for(drive)
    assert settings.service_factor == 1.3 and settings.required_life_h == pytest.approx(20000.0)
    res = rank_chains(drive, standard="ISO 606", series="A")
    assert res.chosen is not None and res.chosen.designation == "ISO 606 08A-1"
    # the wear-life check reads the design's required life
    chosen = drive.with_chain(res.chain)
    wear = next(c for c in checks_for(chosen, contour_geometry(chosen)) if c.name == "wear life")
    assert wear.limit == pytest.approx(20000.0)
    # round trip keeps the duty fields
    again = drive_from_mapping(drive_to_mapping(chosen))
    assert (again.driver_duty, again.driven_duty, again.required_life) == (
        "smooth", "moderate shock", pytest.approx(20000.0 * 3600.0))


# ----------------------------------------------------------------------------- rotation
def tight_side(drive: Drive) -> float:
    """y of the middle of the tight span (above or below the line of centres)."""
    g = contour_geometry(drive)
    span = next(s for s in g.spans if s.tight)
    return 0.5 * (span.start_point[1] + span.end_point[1])


def test_two_sprockets_reversing_the_rotation_moves_the_tight_span():
    """Driver at the origin, driven at +x: a driver turning ccw moves its top towards −x,
    pulling in the top span (tight above, y > 0); cw pulls in the bottom one."""
    assert tight_side(two(rotation="ccw")) > 0
    assert tight_side(two(rotation="cw")) < 0
    assert driver_rotation(contour_geometry(two(rotation="cw")), 0) == "cw"
    assert driver_rotation(contour_geometry(two()), 0) == "ccw"  # the default of the order


def three(rotation: str | None, idler_adjustable: bool = False) -> Drive:
    """Driver A at the origin, driven B at +x, idler C above between them (outside): listed
    A → B → C the chain runs counter-clockwise."""
    return Drive("t", Chain(find_chain("ISO 606 08B-1")),
                 (Sprocket("A", 17, 0.0, 0.0, "driver", speed=300 * RPM),
                  Sprocket("B", 34, 0.6, 0.0, "driven"),
                  Sprocket("C", 17, 0.3, 0.15, "idler", adjustable=idler_adjustable)),
                 power=2e3, rotation=rotation)


def test_three_sprockets_rotation_against_the_order_reverses_the_travel():
    listed = three(None)
    g = contour_geometry(listed)
    assert driver_rotation(g, 0) == "ccw"
    assert next(s for s in g.spans if s.tight).start_name == "C"  # C → A into the driver
    assert in_travel_order(three("ccw")).sprockets == listed.sprockets
    flipped = in_travel_order(three("cw"))
    assert [s.name for s in flipped.sprockets] == ["A", "C", "B"]
    gf = contour_geometry(flipped)
    assert driver_rotation(gf, 0) == "cw"
    assert next(s for s in gf.spans if s.tight).start_name == "B"  # B → A, below


def test_idler_on_the_tight_span_fails_with_its_shaft_load():
    """Counter-clockwise, C sits on the span into the driver: it carries F_t + F_0 + F_v,
    all of F_t beyond the slack span (share 1); clockwise it is on the slack span (0)."""
    on_tight = three("ccw", idler_adjustable=True)
    loads = loads_of(on_tight, contour_geometry(on_tight))
    (check,) = idler_checks(on_tight, loads)
    assert check.status == FAIL and check.value == pytest.approx(1.0, rel=1e-9)
    assert check.key == "idler_on_slack_span[C]" and "tensioner" in check.note
    shaft = loads.shaft_load_magnitudes[2]
    assert any(q.value == pytest.approx(shaft) for q in check.note_quantities)
    on_slack = in_travel_order(three("cw", idler_adjustable=True))
    (ok,) = idler_checks(on_slack, loads_of(on_slack, contour_geometry(on_slack)))
    assert ok.status == PASS and ok.value == 0.0


# ----------------------------------------------------------------------------- fatigue
def test_fatigue_check_against_the_catalogue_strength():
    spec = find_chain("ISO 606 08B-1")
    assert spec.fatigue_strength is None  # the packaged catalogue has none
    given = replace(spec, fatigue_strength=1500.0)
    ok = fatigue_check(given, 900.0, 1200.0)
    assert ok.status == PASS and not ok.limit_estimated and ok.value == 1200.0
    assert ok.part == "chain" and "IwisFatigue" not in ok.source
    worse = fatigue_check(given, 1600.0, 1200.0)
    assert worse.status == FAIL and worse.value == 1600.0 and "steady running" in worse.note
    assert worse.margin_fraction == pytest.approx(1500.0 / 1600.0 - 1.0)


def test_fatigue_check_without_a_catalogue_strength_holds_to_the_estimate_and_says_so():
    # no fatigue strength in the catalogue: the limit is the low end of the maker's range,
    # fatigue strength 15-20 % of the breaking force [IwisFatigue], on the catalogue's minimum
    # breaking load Q (08B-1: 17.8 kN, [ISO606])
    spec = find_chain("ISO 606 08B-1")
    q = spec.breaking_load
    assert q == pytest.approx(17.8e3)
    below = fatigue_check(spec, 0.10 * q, 0.12 * q)
    assert below.status == PASS and below.limit == pytest.approx(0.15 * q)
    assert below.limit_estimated and below.to_dict()["limit_estimated"] is True
    assert "estimate" in below.note and "[IwisFatigue]" in below.source
    assert "inside the band" not in below.note
    band = fatigue_check(spec, 0.10 * q, 0.18 * q)  # between 15 and 20 %: not decided
    assert band.status == FAIL and "inside the band of the estimate" in band.note
    beyond = fatigue_check(spec, 0.21 * q, 0.10 * q)  # above 20 %: fails over the whole band
    assert beyond.status == FAIL and "inside the band" not in beyond.note
    assert beyond.margin_fraction == pytest.approx(0.15 / 0.21 - 1.0)


def test_fatigue_check_of_a_polymer_chain_cannot_be_verified():
    # the maker's 15-20 % rule is for steel chains: a polymer chain has no estimate
    spec = find_chain("polymer PA66-GF30 16B-1")
    unknown = fatigue_check(spec, 300.0, 400.0)
    assert unknown.status == UNVERIFIED and unknown.limit is None
    assert "no fatigue strength in the catalogue" in unknown.note and not unknown.limit_estimated


def test_schema_shows_the_duty_fields_with_allowed_values_and_example_machines():
    from chaindrive.io.design import schema

    drive = {f["field"]: f for f in schema()["drive"]}
    assert drive["driver"]["allowed"] == 'one of "smooth", "slight shock", "moderate shock"'
    assert drive["driven"]["allowed"] == 'one of "smooth", "moderate shock", "heavy shock"'
    assert drive["rotation"]["allowed"] == 'one of "cw", "ccw"'
    assert drive["required_life"]["kind"] == "time"
    assert "electric motor" in drive["driver"]["description"]
    assert "hammer mills" in drive["driven"]["description"]


def square(adjustable: bool) -> Drive:
    """A → B → C → D counter-clockwise round a square: driven B and D take half the power
    each, so the span B → C → D carries F_0 + F_v + F_t/2 (share 1/2, closed form)."""
    return Drive("t", Chain(find_chain("ISO 606 08B-1")),
                 (Sprocket("A", 17, 0.0, 0.0, "driver", speed=300 * RPM),
                  Sprocket("B", 25, 0.6, 0.0, "driven"),
                  Sprocket("C", 17, 0.6, 0.4, "idler", adjustable=adjustable),
                  Sprocket("D", 25, 0.0, 0.4, "driven")), power=2e3)


def test_guide_idler_between_driven_sprockets_is_a_warning_a_tensioner_there_fails():
    guide = square(False)
    loads = loads_of(guide, contour_geometry(guide))
    assert idler_checks(guide, loads) == []
    (w,) = idler_warnings(guide, loads)
    assert w.code == "strength.idler-on-loaded-span" and "50% of the peripheral force" in w.message
    tensioner = square(True)
    loads = loads_of(tensioner, contour_geometry(tensioner))
    (check,) = idler_checks(tensioner, loads)
    assert check.status == FAIL and check.value == pytest.approx(0.5, rel=1e-9)
    assert idler_warnings(tensioner, loads) == []


def test_json_carries_the_duty_with_its_origins_and_the_defaults_are_warned():
    from chaindrive.analysis import Analysis

    bare = Analysis(two(), response=False)
    doc = bare.to_dict()["drive"]
    assert (doc["service_factor"], doc["service_factor_origin"]) == (1.0, "default")
    assert doc["required_life_h"] is None and doc["required_life_origin"].startswith("default")
    assert (doc["rotation"], doc["rotation_origin"]) == (
        "ccw", "default: from the order of the sprockets")
    codes = {w.code for w in bare.warnings}
    assert {"duty.service-factor-default", "duty.rotation-default"} <= codes
    given = Analysis(two(driver_duty="smooth", driven_duty="moderate shock",
                         required_life=3600.0 * 20000, rotation="cw"), response=False)
    doc = given.to_dict()["drive"]
    assert (doc["service_factor"], doc["service_factor_origin"]) == (1.3, "duty classes")
    assert doc["required_life_h"] == pytest.approx(20000.0)
    assert (doc["rotation"], doc["rotation_origin"]) == ("cw", "given")
    assert not {"duty.service-factor-default", "duty.rotation-default"} & {
        w.code for w in given.warnings}
    wear = next(c for c in given.checks() if c.name == "wear life")
    assert wear.limit == pytest.approx(20000.0)
