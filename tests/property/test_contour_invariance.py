"""Invariants of the contour geometry (hypothesis): rigid motions, listing order, and
the two-sprocket closed form (module docstring of chaindrive.geometry.contour, eq. 4)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from chaindrive.geometry.contour import (
    contour_geometry,
    tight_pitches_of,
    two_sprocket_links_exact,
)
from chaindrive.geometry.sprocket import pitch_radius
from chaindrive.model import Chain, Drive, Sprocket
from tests.conftest import make_spec, rpm

P = 0.0127

# A four-sprocket contour (driver, two driven, an inside idler) that closes.
BASE = [("M", 17, 0.0, 0.0, "outside"), ("A", 25, 0.6, 0.05, "outside"),
        ("I", 13, 0.45, 0.27, "inside"), ("B", 19, 0.15, 0.45, "outside")]


def drive_of(rows: list[tuple[str, int, float, float, str]]) -> Drive:
    return Drive(
        name="p", chain=Chain(make_spec(P)),
        sprockets=tuple(Sprocket(n, z, x, y, "driver" if n == "M" else
                                 ("idler" if side == "inside" else "driven"),
                                 speed=rpm(200) if n == "M" else None, side=side)
                        for n, z, x, y, side in rows),
    )


@settings(max_examples=60, deadline=None)
@given(dx=st.floats(-50, 50), dy=st.floats(-50, 50), angle=st.floats(-math.pi, math.pi),
       mirror=st.booleans())
def test_length_is_invariant_under_rigid_motion(dx: float, dy: float, angle: float,
                                                mirror: bool) -> None:
    ref = contour_geometry(drive_of(BASE)).tight_pitches
    c, s = math.cos(angle), math.sin(angle)
    moved = []
    for n, z, x, y, side in BASE:
        y = -y if mirror else y
        moved.append((n, z, c * x - s * y + dx, s * x + c * y + dy, side))
    assert_allclose(contour_geometry(drive_of(moved)).tight_pitches, ref, rtol=1e-10)


@settings(max_examples=30, deadline=None)
@given(shift=st.integers(0, 3))
def test_reversed_and_rotated_listing_gives_the_same_length(shift: int) -> None:
    ref = contour_geometry(drive_of(BASE))
    order = (BASE[shift:] + BASE[:shift])[::-1]
    other = contour_geometry(drive_of(order))
    assert_allclose(other.tight_pitches, ref.tight_pitches, rtol=1e-12)
    assert other.orientation == -ref.orientation
    wraps = {s.name: s.wrap_angle for s in ref.sprockets}
    for s in other.sprockets:
        assert_allclose(s.wrap_angle, wraps[s.name], rtol=1e-10, atol=1e-12)


@settings(max_examples=80, deadline=None)
@given(z1=st.integers(9, 60), z2=st.integers(9, 120), spare=st.floats(1.05, 40.0),
       angle=st.floats(-math.pi, math.pi))
def test_two_sprockets_match_the_closed_form(z1: int, z2: int, spare: float,
                                              angle: float) -> None:
    """General solver = exact closed form (eq. 4) for any centre distance, tooth counts and
    direction of the line of centres; the take-up rounds up to an even count."""
    r1 = P / (2 * math.sin(math.pi / z1))
    r2 = P / (2 * math.sin(math.pi / z2))
    tip = 0.5 * (2 * r1 + 2 * r2) + 1.3 * P
    a = tip * spare
    drive = Drive(
        name="two", chain=Chain(make_spec(P), links=None),
        sprockets=(Sprocket("A", z1, 0.0, 0.0, "driver", speed=rpm(100)),
                   Sprocket("B", z2, a * math.cos(angle), a * math.sin(angle), "driven",
                            adjustable=False)),
    )
    # Compare before the take-up: the layout as given.
    centres = np.array([[0.0, 0.0], [a * math.cos(angle), a * math.sin(angle)]])
    lp = tight_pitches_of(centres, np.asarray(pitch_radius(P, [z1, z2])), np.array([False, False]),
                          np.array([z1, z2]), P)
    assert_allclose(lp, two_sprocket_links_exact(a, P, z1, z2), rtol=1e-12)
    g = contour_geometry(drive)
    assert g.links >= lp - 1e-9 and g.links % 2 == 0
