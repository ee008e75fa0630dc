"""Unit tests of chaindrive.strength.iso10823 (factors, ACA rating envelopes, lubrication).

Check values: shared/data/iso10823_method.md §3.1 (computed table of the tooth factors) and
§5 (ACA check values: chain 40 and 60, N1 = 17, from Shigley Eq. 17-32/17-33, [AK] test case).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.model import ChainSpec
from chaindrive.strength import iso10823 as iso
from chaindrive.strength.checks import chain_check

RPM = math.pi / 30


def ansi(number: str, pitch_in: float, strands: int = 1) -> ChainSpec:
    p = pitch_in * 0.0254
    return ChainSpec(f"ANSI {number}", "ANSI", "A", p, strands, 0.625 * p, 0.31 * p, 0.62 * p,
                     0.95 * p, 1.15 * p * (strands > 1), 12500 * pitch_in**2 * 4.448 * strands,
                     2.8 * pitch_in**2 * strands, ansi=number if strands == 1 else f"{number}-{strands}")


def test_tooth_factors_match_the_tabulated_values():
    z = [11, 13, 15, 17, 19, 21, 23, 25]
    assert_allclose(iso.tooth_correction_aca(z), [0.625, 0.748, 0.874, 1.0, 1.128, 1.256, 1.386,
                                                1.517], atol=6e-4)
    assert_allclose(iso.tooth_correction_aca(z, "impact"), [0.520, 0.669, 0.829, 1.0, 1.182,
                                                          1.373, 1.574, 1.783], atol=6e-4)
    assert_allclose(iso.tooth_factor_iso(z), [1.804, 1.507, 1.291, 1.128, 1.0, 0.898, 0.814,
                                            0.743], atol=6e-4)
    with pytest.raises(DesignError):
        iso.tooth_correction_aca(17, "other")


def test_strand_and_service_factors():
    assert [iso.strand_factor(n) for n in (1, 2, 3, 4, 5, 6, 8)] == [1, 1.7, 2.5, 3.3, 3.9, 4.6, 6.0]
    with pytest.raises(DesignError, match="chain.strands"):
        iso.strand_factor(7)
    assert iso.service_factor("moderate_shock", "ic_engine_mechanical") == 1.4
    assert iso.service_factor("smooth") == 1.0
    with pytest.raises(DesignError, match="did you mean 'smooth'"):
        iso.service_factor("smoth")


@pytest.mark.parametrize(("number", "p_in", "n1", "h1", "h2"), [
    ("40", 0.5, 1000, 5.48, 21.6),
    ("40", 0.5, 2000, 10.2, 7.65),
    ("60", 0.75, 500, 9.81, 84.7),
    ("60", 0.75, 1500, 26.4, 16.3),
])
def test_aca_envelopes_reproduce_check_values(number, p_in, n1, h1, h2):
    assert_allclose(iso.link_plate_rating_hp(17, n1, p_in), h1, rtol=5e-3)
    assert_allclose(iso.roller_bush_rating_hp(17, n1, p_in, 17.0), h2, rtol=5e-3)
    rating, governing = iso.aca_rating(ansi(number, p_in), 17, n1 * RPM)
    assert_allclose(rating / iso.HP, min(h1, h2), rtol=5e-3)
    assert governing == ("link-plate fatigue" if h1 < h2 else "roller-bush impact")


def test_aca_low_speed_check_value_and_kr():
    # [AK] test case: chain 40, N1 = 17, n1 = 100 rpm → H1 = 0.689 hp
    assert_allclose(iso.aca_rating(ansi("40", 0.5), 17, 100 * RPM)[0] / iso.HP, 0.689, rtol=2e-3)
    assert iso.roller_constant(ansi("35", 0.375)) == 29
    assert iso.roller_constant(ansi("41", 0.5)) == 3.4
    assert iso.roller_constant(ansi("80", 1.0, 2)) == 17


def test_life_and_length_correction_of_h2():
    base = iso.roller_bush_rating_hp(17, 2000, 0.5, 17.0)
    # H2^2.5·h/Lp = const (Shigley Eq. 17-40)
    h2 = iso.roller_bush_rating_hp(17, 2000, 0.5, 17.0, links=200, life_h=30000)
    assert_allclose(h2**2.5 * 30000 / 200, base**2.5 * 15000 / 100, rtol=1e-12)


def test_lubrication_type_by_speed():
    c = ansi("40", 0.5)
    assert iso.lubrication_type(c, 1.0) == "A"
    assert iso.lubrication_type(c, 5.0) == "B"
    assert iso.lubrication_type(c, 12.0) == "C"
    assert iso.lubrication_type(ansi("25", 0.25), 1.0) is None


def test_galling_limit_falls_with_tension():
    low = iso.galling_speed_limit(0.0508, 17, 10_000.0)
    high = iso.galling_speed_limit(0.0508, 17, 30_000.0)
    assert high < low
    # the formula at F = 0, p = 1 in, N1 = 0: 1000·(82.5/7.95)^(1/1.873) rev/min
    assert_allclose(iso.galling_speed_limit(0.0254, 0, 0.0) / RPM,
                    1000 * (82.5 / 7.95) ** (1 / 1.873), rtol=1e-12)


def test_rating_margin_and_multi_strand():
    # three strands carry 2.5 single-strand ratings [Shigley2015, Table 17-23]: at the
    # single-strand rating × K_s = 1.25 the power-rating check has a margin 2.5/1.25 − 1
    c1 = ansi("80", 1.0)
    single = iso.aca_rating(c1, 17, 300 * RPM)[0]
    check = chain_check("power rating", "80-3", single * iso.strand_factor(3), single * 1.25,
                        "[Shigley2015]")
    assert_allclose(check.margin_fraction, 2.5 / 1.25 - 1, rtol=1e-12)
    assert check.passed and iso.lubrication_type(c1, 3.0) in {"A", "B", "C"}
    assert iso.required_rating(10.0, 1.3, 1.5, 1.0, 2.5) == pytest.approx(7.8)


def test_textbook_rating_lookup():
    assert iso.textbook_rating("Bhandari table 14.2", "16A", 300) == pytest.approx(11630.0)
    assert iso.textbook_rating("Bhandari table 14.2", "12A", 300) is None
    assert iso.tooth_factor_bhandari(19) == 1.11
    with pytest.raises(DesignError):
        iso.tooth_factor_bhandari(18)
