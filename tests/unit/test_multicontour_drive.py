"""The multi-contour check of a drive (seed 004 applied through analyze): K_m, the most
loaded contour's share and the strength made for it."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

import chaindrive
from chaindrive.catalog import find_chain
from chaindrive.errors import DesignError
from chaindrive.model import Chain
from chaindrive.multicontour import contour_check, contour_factor_at_risk
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def eight() -> chaindrive.Drive:
    return chaindrive.load(EXAMPLES / "eight_sprocket.toml")


def with_contours(drive: chaindrive.Drive, m: int) -> chaindrive.Drive:
    return replace(drive, chain=replace(drive.chain, contours=m))


def test_two_contours_share_and_strength(eight: chaindrive.Drive) -> None:
    one = chaindrive.analyze(eight)
    two = chaindrive.analyze(with_contours(eight, 2))
    check = two.contours
    assert check is not None
    assert 1.0 <= check.km <= check.km_mean <= 2.0
    assert_allclose(check.max_share, 1.0 / check.km)
    # the seed's eq. 16–17 value for the same joint and stretch
    assert check.km_printed == pytest.approx(contour_factor_at_risk(
        check.c4, check.joint.max_clearance, check.span_deformation, 0.05))
    # the strength is made for the most loaded contour: P / K_m
    assert one.strength is not None and two.strength is not None
    assert_allclose(two.strength.hinge_pressure, one.strength.hinge_pressure / check.km,
                    rtol=1e-12)
    # two contours in parallel stiffen every branch twice (same per-contour tensions → same sag)
    doc = two.to_dict()
    assert doc["strength"]["contour_factor_km"] == check.km
    assert doc["strength"]["multicontour"]["contours"] == 2


def test_more_contours_carry_more_but_share_worse(eight: chaindrive.Drive) -> None:
    """More contours carry more in all (K_m grows) but further from the ideal m: each is
    stretched less by its share, so the same clearances unload the others more."""
    k2 = chaindrive.analyze(with_contours(eight, 2)).contours
    k4 = chaindrive.analyze(with_contours(eight, 4)).contours
    assert k2 is not None and k4 is not None
    assert k2.km < k4.km <= 4.0
    assert k4.km / 4 < k2.km / 2


def test_a_stiffer_span_loses_more_capacity() -> None:
    """Compatibility of deformations: the stiffer the chain, the smaller its stretch Δ_y
    against the same clearances, the lower K_m (seed 004 eq. 16)."""
    soft = contour_check(2, 100.0, 0.08, 1000.0, 1e5)
    stiff = contour_check(2, 100.0, 0.08, 1000.0, 1e7)
    assert stiff.km < soft.km


def test_contours_out_of_range() -> None:
    spec = find_chain("ISO 606 08B-1")
    with pytest.raises(DesignError, match="chain.contours"):
        Chain(spec, contours=9)
    with pytest.raises(DesignError, match="chain.contours"):
        contour_check(1, 100.0, 0.08, 1000.0, 1e6)


def test_most_loaded_share_closed_forms() -> None:
    """m = 2: with slack difference d < F/c the shares are (F ± c d)/2, so
    F_max/F = (1 + d/(F/c))/2; with d ≥ F/c one contour carries all. Equal slacks: 1/m."""
    from chaindrive.multicontour.drive import most_loaded_share

    stretch = 1.0
    d = np.array([[0.0, 0.2], [0.5, 0.0], [0.0, 1.5]])
    assert_allclose(most_loaded_share(d, stretch), [0.6, 0.75, 1.0])
    assert_allclose(most_loaded_share(np.zeros((1, 5)), stretch), [0.2])
    # three contours, slacks 0, 0.1, 5: the third never engages; two share F + c·0.1
    assert_allclose(most_loaded_share(np.array([[0.0, 0.1, 5.0]]), stretch), [(1 + 0.1) / 2])
