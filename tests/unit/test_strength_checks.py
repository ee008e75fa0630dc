"""Unit tests of chaindrive.strength.checks and drive_checks: verdicts, margins as fractions,
"cannot be verified" as a failure, and the limits users found missing (idler and driver teeth
in mesh, a 380-pitch span, speeds outside every table). Limits are the cited rules of the
module (≥ 3 teeth in mesh [Renold-DG], wrap ≥ 120° [Mott2014], span ≤ 80 p)."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from chaindrive.catalog import find_chain
from chaindrive.geometry.contour import contour_geometry
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import checks as ck
from chaindrive.strength.drive_checks import checks_for, geometry_checks

RPM = math.pi / 30


def test_verdicts_and_margins():
    c = ck.chain_check("hinge pressure", "x", 20e6, 25e6)
    assert c.status == "pass" and c.margin_fraction == pytest.approx(0.25)
    assert c.to_dict()["value"] == pytest.approx(20.0) and c.to_dict()["unit"] == "MPa"
    c = ck.chain_check("static safety", "x", 5.0, 6.0, "[DiamondChain]")
    assert c.status == "fail" and c.margin_fraction == pytest.approx(5 / 6 - 1)
    c = ck.chain_check("hinge pressure", "x", 20e6, None)
    assert c.status == "cannot be verified" and not c.passed and c.margin_fraction is None
    assert "no [p]" in c.note


def test_worst_orders_failures_then_unverified_then_smallest_margin():
    a = ck.chain_check("wear life", "x", 20000.0, 15000.0)
    b = ck.chain_check("speed limit", "x", 10.0, None, "s")
    f = ck.chain_check("power rating", "x", 900.0, 1000.0, "s")
    assert ck.worst([a, b, f]) is f and ck.worst([a, b]) is b and ck.worst([a]) is a


def _drive(idler_y: float | None = None, driven_x: float = 1.0, teeth: int = 19) -> Drive:
    sps = [Sprocket("A", teeth, 0.0, 0.0, "driver", speed=300 * RPM),
           Sprocket("B", 38, driven_x, 0.0, "driven", adjustable=True)]
    if idler_y is not None:
        sps.append(Sprocket("I", 14, driven_x / 2, idler_y, "idler"))
    return Drive("t", Chain(find_chain("16A-1")), tuple(sps), power=1000.0)


def test_idler_with_a_fraction_of_a_tooth_in_mesh_fails():
    """An idler barely touching the slack span (the seed layout: 0.28 teeth) fails the
    3-teeth rule; its wrap has no limit of its own, so no wrap check is listed for it (one
    that cannot fail would count as a pass)."""
    d = _drive(idler_y=0.1315)
    g = contour_geometry(d)
    checks = {(c.name, c.subject): c for c in geometry_checks(d, g)}
    idler = checks[("teeth in mesh", "I")]
    assert idler.value < 1.0 and idler.status == "fail"
    assert ("wrap", "I") not in checks and ("wrap", "A") in checks


def test_driver_with_few_teeth_in_mesh_fails():
    """A 6-tooth driver wraps about half its teeth: 2.x teeth in mesh < 3."""
    d = _drive(teeth=6)
    g = contour_geometry(d)
    c = next(c for c in geometry_checks(d, g) if c.name == "teeth in mesh" and c.subject == "A")
    assert 2.0 < c.value < 3.0 and c.status == "fail"


def test_span_of_380_pitches_fails():
    d = _drive(driven_x=380 * 0.0254)
    c = next(c for c in geometry_checks(d, contour_geometry(d)) if c.name == "span length")
    assert c.value == pytest.approx(380, rel=0.01) and c.status == "fail"


def test_rated_chain_at_30000_rpm_fails_instead_of_passing():
    """At 30 000 rpm the galling limit [Shigley2015] is far below: the chain fails."""
    d = Drive("fast", Chain(find_chain("08A-1")),
              (Sprocket("A", 19, 0, 0, "driver", speed=30000 * RPM),
               Sprocket("B", 19, 0.5, 0, "driven")), power=100.0)
    checks = checks_for(d, contour_geometry(d))
    assert not all(c.passed for c in checks)
    assert next(c for c in checks if c.name == "speed limit").status == "fail"


def test_polymer_chain_checks_allowable_load_and_says_what_it_cannot_verify():
    """The packaged polymer rows carry a speed limit (50 m/min, [TsubakiGuide] Table 4.1, an
    estimate): checked against v = z·p·n/60. A catalogue row without one (a user's file) is
    reported as "cannot be verified"."""
    spec = find_chain("POM 08B")
    d = Drive("poly", Chain(spec),
              (Sprocket("A", 19, 0, 0, "driver", speed=100 * RPM),
               Sprocket("B", 38, 0.5, 0, "driven")), power=20.0)
    checks = {c.name: c for c in checks_for(d, contour_geometry(d))}
    assert checks["allowable load"].limit == pytest.approx(spec.allowable_load)
    assert checks["speed limit"].status == "pass"
    assert checks["speed limit"].limit == pytest.approx(50.0 / 60.0, abs=5e-4)
    assert "power rating" not in checks and "hinge pressure" not in checks
    bare = replace(d, chain=Chain(replace(spec, max_speed=None)))
    unlimited = {c.name: c for c in checks_for(bare, contour_geometry(bare))}
    assert unlimited["speed limit"].status == "cannot be verified"


@pytest.mark.parametrize("chain", ["08A-1", "POM 08B"])
def test_chain_checks_read_the_strength_stage_loads_to_the_same_figures(chain: str) -> None:
    """The analysis hands the chain's checks the strength stage's loads (v, F_t, F_0, F_v of
    loads_of); computed again here from the same formulas they give the same checks, value
    for value (the rated path and the polymer path)."""
    from chaindrive.strength.loads import loads_of

    d = Drive("two", Chain(find_chain(chain)),
              (Sprocket("A", 19, 0, 0, "driver", speed=300 * RPM),
               Sprocket("B", 38, 0.5, 0, "driven")), power=200.0)
    g = contour_geometry(d)
    assert checks_for(d, g, loads=loads_of(d, g)) == checks_for(d, g)
