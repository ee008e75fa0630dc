"""Contour geometry: tangent spans, wraps, closure, take-up and checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.errors import DesignError, GeometryError
from chaindrive.geometry.contour import (
    contour_geometry,
    round_links,
    two_sprocket_center_distance_exact,
    two_sprocket_links_exact,
)
from chaindrive.model import Chain, Drive, Sprocket
from tests.conftest import make_spec, rpm, two_sprocket


def test_two_equal_sprockets_is_two_half_wraps_and_two_centre_distances() -> None:
    """Equal sprockets: wraps are exactly 180°, spans equal the centre distance, so
    L_p = 2a/p + z (closed form)."""
    a = 20 * 0.0254  # 2a/p + z = 60 links, even: the take-up does not move it
    g = contour_geometry(two_sprocket(20, 20, a))
    assert_allclose([s.wrap_angle for s in g.sprockets], [math.pi, math.pi], rtol=1e-12)
    assert_allclose([s.length for s in g.spans], [a, a], rtol=1e-12)
    assert_allclose(g.tight_pitches, 2 * a / 0.0254 + 20, rtol=1e-12)
    assert g.links == 60
    assert g.adjustment == pytest.approx(0.0, abs=1e-12)


def test_take_up_fits_links_exactly_and_matches_inverse_closed_form() -> None:
    g = contour_geometry(two_sprocket(17, 34, 0.5))
    assert g.links % 2 == 0
    assert_allclose(g.tight_pitches, g.links, atol=1e-9)
    assert_allclose(g.center_distance, two_sprocket_center_distance_exact(g.links, 0.0254, 17, 34),
                    atol=1e-9)
    assert g.slack == pytest.approx(0.0, abs=1e-9)
    assert g.adjusted == 1


def test_imposed_links_move_the_driven_sprocket() -> None:
    g = contour_geometry(two_sprocket(17, 34, 0.5, links=90))
    assert g.links == 90
    assert_allclose(two_sprocket_links_exact(g.center_distance, 0.0254, 17, 34), 90, atol=1e-9)


def test_odd_links_need_allow_odd() -> None:
    with pytest.raises(DesignError, match="chain.links"):
        Chain(make_spec(), links=91)
    assert round_links(90.2) == 92
    assert round_links(90.2, allow_odd=True) == 91


def test_wraps_turn_once_round_the_contour_with_an_inside_idler() -> None:
    """An inside idler turns the chain back: Σ(outside wraps) − Σ(inside wraps) = 2π, and
    it turns against the other sprockets."""
    drive = Drive(
        name="idler", chain=Chain(make_spec(0.0127)),
        sprockets=(Sprocket("A", 17, 0.0, 0.0, "driver", speed=rpm(500)),
                   Sprocket("B", 17, 0.6, 0.0, "driven"),
                   Sprocket("I", 13, 0.3, 0.09, "idler", side="inside")),
    )
    g = contour_geometry(drive)
    signs = np.array([-1.0 if s.side == "inside" else 1.0 for s in g.sprockets])
    assert_allclose(np.sum(signs * [s.wrap_angle for s in g.sprockets]), 2 * math.pi, atol=1e-9)
    assert g.sprockets[2].turn == -g.sprockets[0].turn
    assert g.sprockets[0].turn == g.sprockets[1].turn
    # the idler pushes the upper span in: both sprockets wrap more than half a turn
    assert all(s.wrap_angle > math.pi for s in g.sprockets[:2])


def test_tight_span_runs_into_the_driver() -> None:
    g = contour_geometry(two_sprocket(17, 34, 0.5))
    tight = [s for s in g.spans if s.tight]
    assert len(tight) == 1 and tight[0].end_name == "A"


def test_overlapping_sprockets_are_refused() -> None:
    with pytest.raises(GeometryError, match="overlap"):
        contour_geometry(two_sprocket(40, 40, 0.2))


def test_span_through_a_sprocket_is_refused() -> None:
    """A square contour with an inside sprocket E pulled down into a V between C and D:
    the bottom span A → B passes 2.5 mm from E's centre, through its teeth."""
    drive = Drive(
        name="cut", chain=Chain(make_spec(0.0127)),
        sprockets=(Sprocket("A", 17, 0.0, 0.0, "driver", speed=rpm(500)),
                   Sprocket("B", 17, 1.0, 0.0, "driven"),
                   Sprocket("C", 17, 1.0, 1.0, "driven"),
                   Sprocket("E", 17, 0.5, -0.01, "idler", side="inside"),
                   Sprocket("D", 17, 0.0, 1.0, "driven")),
    )
    with pytest.raises(GeometryError, match="cuts through sprocket E"):
        contour_geometry(drive)


def test_outside_sprocket_in_a_concave_corner_cannot_close() -> None:
    drive = Drive(
        name="concave", chain=Chain(make_spec(0.0127)),
        sprockets=(Sprocket("A", 17, 0.0, 0.0, "driver", speed=rpm(500)),
                   Sprocket("B", 17, 1.0, 0.0, "driven"),
                   Sprocket("C", 17, 1.0, 0.5, "driven"),
                   Sprocket("D", 17, 0.5, 0.15, "driven")),
    )
    with pytest.raises(GeometryError, match="cannot close"):
        contour_geometry(drive)


def test_contour_that_cannot_close_is_refused() -> None:
    """Listing a square's corners in a crossed order makes a figure of eight."""
    corners = [(0, 0), (1, 1), (1, 0), (0, 1)]
    drive = Drive(
        name="eight", chain=Chain(make_spec(0.0127)),
        sprockets=tuple(Sprocket(f"S{i}", 17, x, y, "driver" if i == 0 else "driven",
                                 speed=rpm(100) if i == 0 else None)
                        for i, (x, y) in enumerate(corners)),
    )
    with pytest.raises(GeometryError, match="cannot close"):
        contour_geometry(drive)


def test_warnings_small_wrap_on_driver() -> None:
    """A driver that the chain barely touches (an idler-like position) is warned about."""
    drive = Drive(
        name="wrap", chain=Chain(make_spec(0.0127)),
        sprockets=(Sprocket("A", 17, 0.0, 0.0, "driven"),
                   Sprocket("B", 17, 1.0, 0.0, "driven"),
                   Sprocket("M", 17, 0.5, 0.06, "driver", speed=rpm(100))),
    )
    g = contour_geometry(drive)
    assert {w.code for w in g.warnings} >= {"geometry.driver-wrap", "geometry.teeth-in-mesh"}
    assert any("under 120°" in str(w) for w in g.warnings)
