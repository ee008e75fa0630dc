"""Unit tests of chaindrive.strength.loads: speed, power shares, span tensions, shaft loads."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError
from chaindrive.geometry.results import GeometryResult, SpanGeometry, SprocketGeometry
from chaindrive.kinematics import mean_chain_speed
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import loads as ld
from tests.conftest import make_spec, rpm


def hand_geometry(drive: Drive) -> GeometryResult:
    """Geometry of a convex contour of equal sprockets, all outside, run counter-clockwise:
    the tangent spans are parallel to the centre lines (built by hand, no solver)."""
    p = drive.chain.pitch
    centres = np.array([(s.x, s.y) for s in drive.sprockets])
    n = len(centres)
    sprockets, spans = [], []
    for s in drive.sprockets:
        r = p / (2 * math.sin(math.pi / s.teeth))
        sprockets.append(SprocketGeometry(s.name, s.teeth, s.side, s.x, s.y, r, 2 * r, 2 * r,
                                          2 * r, 2 * math.pi / n, s.teeth / n, 1, (0, 0), (0, 0)))
    for i in range(n):
        j = (i + 1) % n
        d = centres[j] - centres[i]
        length = float(np.hypot(*d))
        u = d / length
        incl = math.atan(u[1] / u[0]) if abs(u[0]) > 1e-12 else math.copysign(math.pi / 2, u[1])
        spans.append(SpanGeometry(i, i, j, drive.sprockets[i].name, drive.sprockets[j].name,
                                  length, length / p, (float(u[0]), float(u[1])),
                                  tuple(centres[i]), tuple(centres[j]), incl,
                                  j == drive.driver_index))
    return GeometryResult(p, tuple(sprockets), tuple(spans), 100.0, 100, 100 * p, 100 * p, 0.0,
                          None, None, 0.0, 1)


def eight_sprockets(shares: dict[str, float] | None = None) -> Drive:
    """8 sprockets on an octagon of radius 0.6 m: S1 driver, S3 and S6 idlers, five driven."""
    shares = shares or {}
    roles = ["driver", "driven", "idler", "driven", "driven", "idler", "driven", "driven"]
    sprockets = []
    for k, role in enumerate(roles):
        a = 2 * math.pi * k / 8
        name = f"S{k + 1}"
        sprockets.append(Sprocket(name, 19, 0.6 * math.cos(a), 0.6 * math.sin(a), role,
                                  speed=rpm(400) if role == "driver" else None,
                                  power_share=shares.get(name)))
    return Drive("eight", Chain(make_spec(0.01905)), tuple(sprockets), power=4000.0)


def test_chain_speed_is_z_p_n_over_60():
    # v = z·p·n/60 (Shigley Eq. 17-30 in SI) for z = 17, p = 19.05 mm, n = 1000 rpm
    assert_allclose(mean_chain_speed(0.01905, 17, rpm(1000)), 17 * 0.01905 * 1000 / 60, rtol=1e-12)


def test_power_shares_default_equal_split_idlers_none():
    shares = ld.power_shares(eight_sprockets())
    assert_allclose(shares, [0, 0.2, 0, 0.2, 0.2, 0, 0.2, 0.2])


def test_power_shares_given_and_rest_split():
    shares = ld.power_shares(eight_sprockets({"S2": 0.4, "S4": 0.3}))
    assert_allclose(shares, [0, 0.4, 0, 0.3, 0.1, 0, 0.1, 0.1])


def test_power_shares_not_adding_to_one_names_the_field():
    full = {"S2": 0.4, "S4": 0.3, "S5": 0.1, "S7": 0.1, "S8": 0.05}
    with pytest.raises(DesignError, match=r"sprockets\[S2\]\.power_share.*0\.95"):
        ld.power_shares(eight_sprockets(full))
    with pytest.raises(DesignError, match=r"power_share.*> 1"):
        ld.power_shares(eight_sprockets({"S2": 0.8, "S4": 0.7}))


@pytest.mark.parametrize("shares", [None, {"S2": 0.4, "S4": 0.3}])
def test_eight_sprocket_contour_balance(shares):
    """At every sprocket T_out − T_in equals the power it takes off / v (issue 3 'done when')."""
    drive = eight_sprockets(shares)
    geometry = hand_geometry(drive)
    res = ld.loads_of(drive, geometry)
    t = np.array(res.span_tensions)
    v = mean_chain_speed(0.01905, 19, rpm(400))
    ft = 4000.0 / v
    expected = ld.power_shares(drive) * ft
    expected[drive.driver_index] = -ft   # the driver puts F_t in
    for k in range(8):
        t_in = t[next(s.index for s in geometry.spans if s.end == k)]
        t_out = t[next(s.index for s in geometry.spans if s.start == k)]
        assert_allclose(t_out - t_in, expected[k], rtol=1e-12, atol=1e-9)
    base = res.sag_tension + res.centrifugal_tension
    assert_allclose(t[res.slack_span], base, rtol=1e-12)
    assert_allclose(t[res.tight_span], ft + base, rtol=1e-12)
    assert t.min() == pytest.approx(base)
    # the shaft loads of a closed contour balance (every span pulls its two ends equally)
    assert_allclose(np.sum(res.shaft_loads, axis=0), [0.0, 0.0], atol=1e-9)


def test_centrifugal_and_sag():
    assert ld.centrifugal_tension(2.6, 5.0) == pytest.approx(65.0)
    assert float(ld.sag_factor(0.0)) == pytest.approx(6.25)       # cos 0 /(8·0.02)
    assert float(ld.sag_factor(math.pi / 2)) == pytest.approx(1.0)  # own weight only
    assert ld.sag_tension(2.0, 1.0, 0.0) == pytest.approx(6.25 * 2.0 * ld.G)


def test_two_sprocket_shaft_load_is_ft_plus_two_f0():
    """Parallel spans: |F_shaft| = F_t + 2·F_0 (Russian Fв = Ft + 2F0, kв = 1)."""
    drive = Drive("two", Chain(make_spec(0.0254)),
                  (Sprocket("A", 19, 0.0, 0.0, "driver", speed=rpm(300)),
                   Sprocket("B", 19, 0.8, 0.0, "driven")), power=3000.0)
    res = ld.loads_of(drive, hand_geometry(drive), shaft_load_factor=1.0)
    assert_allclose(res.shaft_load_magnitudes, [res.peripheral_force + 2 * res.sag_tension] * 2,
                    rtol=1e-12)
    d = res.to_dict()
    assert len(d["span_tensions_n"]) == 2 and len(d["shaft_loads_n"]) == 2
    assert ld.loads_of(drive, hand_geometry(drive), shaft_load_factor=1.15).shaft_load_magnitudes[
        0] == pytest.approx(1.15 * res.shaft_load_magnitudes[0])


def test_hinge_pressure_and_missing_power():
    assert ld.hinge_pressure(1000.0, 1.5, 1.5e-4) == pytest.approx(1e7)
    drive = Drive("two", Chain(make_spec()), (Sprocket("A", 19, 0, 0, "driver"),
                                               Sprocket("B", 19, 0.5, 0, "driven")))
    with pytest.raises(DesignError, match="drive.power"):
        ld.loads_of(drive, hand_geometry(drive))


def test_idler_cannot_take_power():
    drive = eight_sprockets({"S3": 0.2})
    with pytest.raises(DesignError, match=r"sprockets\[S3\]\.power_share"):
        ld.power_shares(drive)


def test_balance_on_the_solved_seed_contour(seed_drive):
    """Seed 000 three-sprocket contour laid out by the geometry solver: the tight span is the
    one into the driver and carries F_t + F_0 + F_v; the idler changes nothing."""
    from chaindrive.geometry.contour import contour_geometry

    geometry = contour_geometry(seed_drive)
    res = ld.loads_of(seed_drive, geometry)
    assert geometry.spans[res.tight_span].tight
    t = res.span_tensions
    base = res.sag_tension + res.centrifugal_tension
    assert_allclose(t[res.tight_span], res.peripheral_force + base, rtol=1e-12)
    assert_allclose(t[res.slack_span], base, rtol=1e-12)
    idler_in = next(s.index for s in geometry.spans if s.end == 2)
    idler_out = next(s.index for s in geometry.spans if s.start == 2)
    assert t[idler_in] == t[idler_out]
