"""Unit tests of chaindrive.strength.ke_method (Kэ, [p], pitch estimate, limits).

Table values: [ChainDesignRU] §1–§5, §10 (docs/references.md; sources named in the data file).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.model import ChainSpec
from chaindrive.strength import ke_method as ke
from chaindrive.strength.checks import chain_check
from chaindrive.strength.loads import hinge_pressure

RPM = math.pi / 30


def gost(pitch_mm: float, area_mm2: float | None, q_kn: float = 60.0) -> ChainSpec:
    p = pitch_mm * 1e-3
    return ChainSpec(f"ПР-{pitch_mm}", "GOST 13568", "ПР", p, 1, 0.625 * p, 0.31 * p, 0.62 * p,
                     0.95 * p, 0.0, q_kn * 1e3, 2.6, bearing_area=None if area_mm2 is None
                     else area_mm2 * 1e-6)


def test_operating_factor_from_tables():
    value = ke.operating_factor(ke.factor("dynamic", "shocks"),
                                ke.center_distance_factor(1.0, 0.025),
                                ke.inclination_factor(math.radians(70)),
                                ke.factor("adjustment", "none"), ke.factor("lubrication", "periodic"),
                                ke.factor("mode", 2))
    assert_allclose(value, 1.35 * 1.0 * 1.25 * 1.25 * 1.5 * 1.25, rtol=1e-12)
    assert ke.center_distance_factor(0.5, 0.025) == 1.25   # 20 t
    assert ke.center_distance_factor(1.75, 0.025) == 0.8   # 70 t
    assert ke.inclination_factor(math.radians(30)) == 1.0
    with pytest.raises(DesignError, match="did you mean 'periodic'"):
        ke.factor("lubrication", "periodik")


def test_allowable_pressure_table_and_interpolation():
    assert_allclose(ke.allowable_pressure(0.0254, 600 * RPM), 23.5e6, rtol=1e-12)
    assert_allclose(ke.allowable_pressure(0.0127, 1100 * RPM), 21.25e6, rtol=1e-12)
    assert_allclose(ke.allowable_pressure(0.0508, 20 * RPM), 35e6, rtol=1e-12)
    assert ke.allowable_pressure(0.0508, 900 * RPM) is None      # above the last column
    assert ke.allowable_pressure(0.008, 100 * RPM) is None       # pitch not tabulated
    assert_allclose(ke.teeth_corrected_pressure(20e6, 25), 21.6e6, rtol=1e-12)


def test_allowable_safety_and_limits():
    assert ke.allowable_safety_factor(0.0254, 1000 * RPM) == pytest.approx(12.9)
    assert ke.max_speed(0.0254) == pytest.approx(800 * RPM)
    assert ke.allowable_impacts(0.01905) == 35
    # i = z1·n1/(15·Lt): 25 teeth, 600 rpm, 100 links → 10 per second
    assert ke.impacts_per_second(25, 600 * RPM, 100) == pytest.approx(10.0)


def test_pitch_estimate_inverts_to_the_allowable_pressure():
    # t = 2.8·∛(T1·Kэ/(z1·[p]·m)) [mm, N·mm, MPa]: T1 = 100 N·m, Kэ = 1.5, z1 = 25, [p] = 25 MPa
    t = ke.pitch_estimate(100.0, 1.5, 25, 25e6)
    assert_allclose(t, 2.8e-3 * (100e3 * 1.5 / (25 * 25)) ** (1 / 3), rtol=1e-12)
    assert ke.pitch_estimate(100.0, 1.5, 25, 25e6, rows=2) < t


@pytest.mark.parametrize(("u", "z1"), [(1.0, 27), (2.0, 25), (3.0, 23), (2.5, 25), (2.8, 23), (8.0, 13)])
def test_recommended_teeth(u, z1):
    assert ke.recommended_teeth(u) == z1


def test_pressure_and_speed_checks_by_the_tables():
    # p = Kэ·Ft/A against [p] of Table 2A, n1 against n1 max of table 5.8 [ChainDesignRU]
    chain = gost(25.4, 180.0)
    area, estimated = ke.bearing_area(chain)
    assert not estimated and area == pytest.approx(180e-6)
    p = hinge_pressure(1000.0, 1.0, area)
    ok = chain_check("hinge pressure", chain.designation, p,
                     ke.allowable_pressure(chain.pitch, 300 * RPM))
    assert ok.passed and p == pytest.approx(1000.0 / 180e-6)
    heavy_p = hinge_pressure(5000.0, 1.0, area)
    allowed = ke.allowable_pressure(chain.pitch, 300 * RPM)
    heavy = chain_check("hinge pressure", chain.designation, heavy_p, allowed)
    assert heavy.margin_fraction < ok.margin_fraction
    assert_allclose(heavy.margin_fraction, allowed / heavy_p - 1, rtol=1e-12)
    fast = chain_check("speed limit", chain.designation, 900 * RPM, ke.max_speed(chain.pitch),
                       "x")
    fast_p = chain_check("hinge pressure", chain.designation, p,
                         ke.allowable_pressure(chain.pitch, 900 * RPM))
    assert not (fast.passed and fast_p.passed)


def test_bearing_area_estimate_when_missing():
    area, estimated = ke.bearing_area(gost(25.4, None))
    assert estimated and area == pytest.approx(1.42 * 0.31 * 0.62 * 0.0254**2)
    assert ke.bearing_area(gost(25.4, 180.0)) == (pytest.approx(180e-6), False)
