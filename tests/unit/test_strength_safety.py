"""Unit tests of chaindrive.strength.safety, .wear and the strength_of entry point."""

from __future__ import annotations

import dataclasses

import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import strength_of
from chaindrive.strength.safety import (
    ALLOWABLE_DYNAMIC_SAFETY,
    startup_safety_factor,
    static_safety_factor,
    steady_safety_factor,
)
from chaindrive.strength.wear import wear_life_hours
from tests.conftest import make_spec, rpm
from tests.unit.test_strength_loads import hand_geometry


def test_static_safety_factor_formula():
    # s = Q/(kд·Ft + F0 + Fv)
    assert static_safety_factor(60_000, 1000, 50, 30, 1.2) == pytest.approx(60_000 / 1280)


def test_two_stage_factors():
    # [MultimassChainDrives, §3.6]: k1 = Q/F1max, k2 = Q/(F_R + F2), k2min with F2max; [k] = 2.5
    assert ALLOWABLE_DYNAMIC_SAFETY == 2.5
    assert startup_safety_factor(10_000, 2_000) == 5.0
    assert steady_safety_factor(10_000, 1_500, 500) == 5.0
    assert steady_safety_factor(10_000, 1_500, 2_000) == pytest.approx(10_000 / 3_500)
    assert steady_safety_factor(10_000, 1_500, 3_000) == pytest.approx(2.2222, 1e-4)


def test_wear_life_scaling():
    assert wear_life_hours(1000.0, 1000.0) == pytest.approx(15000.0)
    # H^2.5·h/Lp = const; elongation scales linearly
    assert_allclose(wear_life_hours(2000.0, 1000.0, links=120, elongation=0.02),
                    15000 * 2**2.5 * 1.2 * 2 / 3, rtol=1e-12)


def drive_two(material: str = "steel", standard: str = "ISO 606") -> Drive:
    spec = dataclasses.replace(make_spec(0.0254), material=material, bearing_area=180e-6,
                               standard=standard)
    return Drive("two", Chain(spec), (Sprocket("A", 19, 0.0, 0.0, "driver", speed=rpm(400)),
                                      Sprocket("B", 38, 1.0, 0.0, "driven")),
                 power=5000.0, service_factor=1.3)


def test_strength_of_keys_and_values():
    drive = drive_two()
    res = strength_of(drive, hand_geometry(drive), dynamic_factor=1.2)
    d = res.to_dict()
    for key in ("span_tensions_n", "shaft_loads_n", "hinge_pressure_mpa", "allowable_pressure_mpa",
                "safety_factor_static", "allowable_safety_factor", "wear_life_h"):
        assert key in d
    ft = res.loads.peripheral_force
    assert_allclose(d["hinge_pressure_mpa"], ft * 1.3 / 180e-6 / 1e6, rtol=1e-12)
    assert_allclose(d["safety_factor_static"], 60_000 / (1.2 * ft + res.loads.sag_tension
                                                         + res.loads.centrifugal_tension))
    # a rated (ISO 606 B) chain: no joint-pressure limit in its method, s >= 6 [DiamondChain]
    assert d["allowable_pressure_mpa"] is None
    assert d["allowable_safety_factor"] == 6.0
    assert d["wear_life_h"] > 0


def test_strength_of_gost_chain_takes_the_russian_tables():
    drive = drive_two(standard="GOST 13568")
    d = strength_of(drive, hand_geometry(drive)).to_dict()
    assert d["allowable_pressure_mpa"] == pytest.approx(26.0)   # Table 2A: 25.4 mm, 400 rpm
    assert d["allowable_safety_factor"] == pytest.approx(9.3)   # Table 9A: 25.4 mm, 400 rpm


@pytest.mark.parametrize("sag", [None, 0.005])
@pytest.mark.parametrize("standard", ["ISO 606", "GOST 13568"])
def test_strength_allowables_are_those_of_the_checks(standard: str, sag: float | None) -> None:
    """The strength block states the values and limits the analysis's checks hold the chain
    to: one chain, one s, one [s] and one [p] (chaindrive.strength.drive_checks), the
    installed sag included (it sets F0 in s = Q/(kд·Ft + F0 + Fv))."""
    from chaindrive.strength.drive_checks import checks_for
    drive = drive_two(standard=standard)
    drive = dataclasses.replace(drive, chain=dataclasses.replace(drive.chain, sag=sag))
    geometry = hand_geometry(drive)
    d = strength_of(drive, geometry).to_dict()
    checks = {c.name: c for c in checks_for(drive, geometry)}
    assert checks["static safety"].value == pytest.approx(d["safety_factor_static"], rel=1e-12)
    assert checks["static safety"].limit == pytest.approx(d["allowable_safety_factor"])
    if d["allowable_pressure_mpa"] is None:
        assert "hinge pressure" not in checks
    else:
        assert checks["hinge pressure"].limit == pytest.approx(d["allowable_pressure_mpa"] * 1e6)


def test_strength_of_polymer_chain_drops_steel_limits():
    drive = drive_two("PA6")
    d = strength_of(drive, hand_geometry(drive)).to_dict()
    assert d["allowable_pressure_mpa"] is None and d["wear_life_h"] is None
    assert any(w.code == "strength.non-steel-chain" for w in
               strength_of(drive, hand_geometry(drive)).warnings)


def test_strength_of_bad_elongation():
    drive = drive_two()
    with pytest.raises(DesignError, match="elongation"):
        strength_of(drive, hand_geometry(drive), elongation=0.5)


def test_wear_life_beyond_ten_times_the_basis_is_flagged():
    # h = 15 000·(H_r/H_d)^2.5 (Shigley Eq. 17-40): at H_d = 40 % of the rating h = 148 ≈
    # 10× the basis; below that the relation is extrapolated and the result says so
    from chaindrive.strength.wear import EXTRAPOLATION_LIMIT_H, is_extrapolated

    assert not is_extrapolated(float(wear_life_hours(1000.0, 410.0)))
    assert is_extrapolated(float(wear_life_hours(1000.0, 390.0)))
    drive = dataclasses.replace(drive_two(), power=50.0)  # far below the rating
    d = strength_of(drive, hand_geometry(drive)).to_dict()
    assert d["wear_life_h"] > EXTRAPOLATION_LIMIT_H and d["wear_life_extrapolated"] is True
    assert any(w.code == "strength.wear-life-extrapolated" for w in
               strength_of(drive, hand_geometry(drive)).warnings)
    d = strength_of(drive_two(), hand_geometry(drive_two())).to_dict()
    assert d["wear_life_extrapolated"] is (d["wear_life_h"] > EXTRAPOLATION_LIMIT_H)
