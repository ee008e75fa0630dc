"""Contour geometry of a closed chain round 2 to 24 sprockets anywhere in a plane.

The chain is modelled on the pitch circles (radius R = p / (2 sin(π/z)), the pitch diameter
of [ISO606] and [GOST591]) joined by straight tangent spans, in the order in which the
sprockets are listed (the order the chain runs round the contour,
[MultimassChainDrives, §3.6]).

Signed radii
------------
Let the chain run counter-clockwise round the contour (a clockwise listing is handled by
mirroring the layout, y → −y, solving, and mirroring back). A sprocket on the *outside*
of the contour (the chain wraps round it, the usual case) has signed radius r = +R; one
on the *inside* (an idler pressing on the chain from outside the loop: the chain wraps it
with its other face and it turns the other way) has r = −R. With n the unit normal of a
span pointing to the right of the direction of travel, the span leaves circle i at
c_i + r_i·n and arrives on circle j at c_j + r_j·n, so that

    (c_j − c_i) · n = r_i − r_j                                            (1)

which, with D = c_j − c_i, L = |D|, u = D/L and u⊥ = u rotated +90°, gives

    n = a·u − √(1 − a²)·u⊥,   a = (r_i − r_j) / L                          (2)

(the outer common tangent for equal signs of r, the crossed tangent when the side changes;
the belt-drive construction of [Shigley2015, §17-2]). Span length ℓ = √(L² − (r_i − r_j)²).

Wrap angle on sprocket i: θ_i = (sgn r_i · (φ_out − φ_in)) mod 2π, φ the polar angles of
the normals of the arriving and leaving spans. A contour that closes once has
Σ sgn(r_i)·θ_i = 2π (the tangent turns once round the loop); anything else (a figure of
eight, an outside sprocket in a concave corner) is refused as a contour that cannot close.

Chain length
------------
On a sprocket the chain lies on the pitch polygon, θ·z/(2π) pitches for a wrap θ; in the
spans it is straight. The tight chain length in pitches is therefore

    L_p = Σ ℓ_k / p + Σ z_i θ_i / (2π)                                    (3)

For two sprockets on the outside this is exactly (sin γ = (R₂ − R₁)/a)

    L_p = 2a·cos γ / p + (z₁ + z₂)/2 + (z₂ − z₁)·γ/π                       (4)

and [ISO10823] (and the textbooks: [Shigley2015, Eq. 17-34], [Bhandari2010, Eq. 14.7])
uses its small-angle form L_p ≈ 2a/p + (z₁ + z₂)/2 + ((z₂ − z₁)/2π)²·p/a.
The number of links is L_p rounded up (or, when the design asks, down) to an even number
(odd only when allowed: it needs an offset link). The *take-up* moves the adjustable
sprocket along its line of adjustment until L_p equals the number of links exactly (less
the slack of a sag allowance, :mod:`chaindrive.geometry.sag`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import (
    ChainDriveWarning,
    ConvergenceError,
    DesignError,
    GeometryError,
    Quantities,
)
from chaindrive.geometry.results import GeometryResult, SpanGeometry, SprocketGeometry
from chaindrive.geometry.sag import DEFAULT_SAG_RATIO, sag_of_slack, slack_for_sag
from chaindrive.geometry.sprocket import pitch_radius, root_diameter, tip_diameter
from chaindrive.model import Drive, ToothFormName
from chaindrive.units import TWO_PI

__all__ = ["Layout", "adjustment_direction", "bracketed_root", "contour_geometry",
           "driver_rotation", "in_travel_order", "round_links", "solve_layout",
           "span_lengths", "span_normals", "tight_pitches_of", "travel_orientation",
           "two_sprocket_center_distance_exact", "two_sprocket_center_distance_iso10823",
           "two_sprocket_links_exact", "two_sprocket_links_iso10823", "wrap_angles"]

_CLOSE_TOL = 1e-6


@dataclass(frozen=True, slots=True)
class Layout:
    """The contour solved in the counter-clockwise frame.

    Parameters
    ----------
    normals : numpy.ndarray
        (n, 2) span normals [-], span k from sprocket k to k+1.
    span_lengths : numpy.ndarray
        (n,) span lengths [m].
    wraps : numpy.ndarray
        (n,) wrap angle of each sprocket [rad].
    tight_pitches : float
        Tight chain length L_p [pitches].
    """

    normals: NDArray[np.float64]  # (n, 2) span normals, span k from k to k+1
    span_lengths: NDArray[np.float64]  # (n,)
    wraps: NDArray[np.float64]  # (n,) wrap angle per sprocket [rad]
    tight_pitches: float


def _following(a: NDArray[Any]) -> NDArray[Any]:
    """``a`` shifted one place back along its first axis, entry k the old entry k+1 (the
    last the first), as ``numpy.roll`` by −1 gives it, by one concatenation (a fifth of
    its time on the short arrays of a contour)."""
    return np.concatenate((a[1:], a[:1]))


def _preceding(a: NDArray[Any]) -> NDArray[Any]:
    """``a`` shifted one place on along its first axis, entry k the old entry k−1 (the first
    the last), as ``numpy.roll`` by +1 gives it, by one concatenation."""
    return np.concatenate((a[-1:], a[:-1]))


def _radii(pitch: float, teeth: NDArray[np.int_] | list[int]) -> NDArray[np.float64]:
    """Pitch radii as an array (:func:`chaindrive.geometry.sprocket.pitch_radius`) [m]."""
    return np.atleast_1d(np.asarray(pitch_radius(pitch, teeth), dtype=float))


@functools.lru_cache(maxsize=256, typed=True)
def _diameters(kind: str, pitch: float, teeth: tuple[int, ...], roller: float,
               form: ToothFormName) -> NDArray[np.float64]:
    """Pitch radii (``kind`` "radii", :func:`_radii`), tip or root diameters ("tip", "root":
    :func:`~chaindrive.geometry.sprocket.tip_diameter`, :func:`~.root_diameter`) of the
    sprockets of ``teeth`` [m], read-only: a search that lays out a drive again and again
    with a sprocket moved (the remedies of a layout check lay out ~200) asks for the same
    ones each time. The same call as without the cache (``teeth`` as the same int array),
    so the same numbers; an error is raised again on each call (not cached)."""
    z = np.array(teeth)
    if kind == "radii":
        out = _radii(pitch, z)
    else:
        diameter = tip_diameter if kind == "tip" else root_diameter
        out = np.asarray(diameter(pitch, z, roller, form=form), float)
    out.flags.writeable = False
    return out


@shared_parameters
def span_normals(centres: NDArray[np.float64], radii: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit normals of the tangent spans k → k+1 (eq. 2 of the module docstring).

    %(centres_signed_radii)s

    Returns
    -------
    numpy.ndarray
        (n, 2) unit normals [-], span k from sprocket k to k+1.

    Raises
    ------
    GeometryError
        When two consecutive circles admit no such tangent (one inside the other).
    """
    d = _following(centres) - centres
    length = np.hypot(d[:, 0], d[:, 1])
    if np.any(length == 0.0):
        k = int(np.argmin(length))
        raise GeometryError("sprockets", f"sprockets {k} and {(k + 1) % len(radii)} have the same centre")
    u = d / length[:, None]
    u_perp = np.column_stack((-u[:, 1], u[:, 0]))
    a = (radii - _following(radii)) / length
    if np.any(np.abs(a) >= 1.0):
        k = int(np.argmax(np.abs(a)))
        raise GeometryError(
            "sprockets", f"no chain span can join sprocket {k} to sprocket {(k + 1) % len(radii)}: "
            "one lies inside the other"
        )
    normals: NDArray[np.float64] = a[:, None] * u - np.sqrt(1.0 - a * a)[:, None] * u_perp
    return normals


@shared_parameters
def span_lengths(centres: NDArray[np.float64], radii: NDArray[np.float64]) -> NDArray[np.float64]:
    """Tangent span lengths ℓ = √(L² − (r_i − r_j)²) for spans k → k+1.

    %(centres_signed_radii)s

    Returns
    -------
    numpy.ndarray
        (n,) span lengths ℓ [m].
    """
    d = _following(centres) - centres
    dist2 = np.einsum("ij,ij->i", d, d)
    lengths: NDArray[np.float64] = np.sqrt(dist2 - (radii - _following(radii)) ** 2)
    return lengths


def wrap_angles(normals: NDArray[np.float64], signs: NDArray[np.float64]) -> NDArray[np.float64]:
    """Wrap angles θ_i = (sgn_i·(φ_out − φ_in)) mod 2π (module docstring).

    Parameters
    ----------
    normals : numpy.ndarray
        (n, 2) span normals [-] (:func:`span_normals`).
    signs : numpy.ndarray
        (n,) sign of each signed radius [-] (+1 outside, −1 inside).

    Returns
    -------
    numpy.ndarray
        (n,) wrap angle θ of each sprocket [rad].
    """
    phi = np.arctan2(normals[:, 1], normals[:, 0])
    phi_in = _preceding(phi)  # span i-1 → i arrives on sprocket i
    wraps: NDArray[np.float64] = np.mod(signs * (phi - phi_in), TWO_PI)
    return wraps


def _solve_ccw(centres: NDArray[np.float64], radii: NDArray[np.float64], teeth: NDArray[np.int_],
               pitch: float) -> Layout | None:
    """Solve the contour assuming counter-clockwise travel; None if it does not close."""
    normals = span_normals(centres, radii)
    signs = np.sign(radii)
    wraps = wrap_angles(normals, signs)
    turning = float(np.sum(signs * wraps))
    if abs(turning - TWO_PI) > _CLOSE_TOL:
        return None
    lengths = span_lengths(centres, radii)
    tight = float(np.sum(lengths) / pitch + np.sum(teeth * wraps) / TWO_PI)
    return Layout(normals, lengths, wraps, tight)


@shared_parameters
def solve_layout(centres: NDArray[np.float64], radii_abs: NDArray[np.float64],
                 inside: NDArray[np.bool_], teeth: NDArray[np.int_], pitch: float,
                 prefer: int = 1) -> tuple[Layout, int]:
    """Solve the contour in whichever travel direction closes it (``prefer`` first).

    Parameters
    ----------
    %(layout_inputs)s
    prefer : int
        The orientation tried first: +1 counter-clockwise, −1 clockwise (it decides only a
        contour that closes both ways, e.g. two sprockets on the outside).

    Returns
    -------
    tuple
        The layout (in the frame where travel is counter-clockwise: span normals, span
        lengths [m], wraps [rad], tight length [pitches]) and the orientation: +1 if the
        listing runs counter-clockwise in the user's frame, −1 if it runs clockwise (then
        the layout is in the mirrored frame y → −y).

    Raises
    ------
    GeometryError
        When the contour closes in neither direction.
    """
    radii = np.where(inside, -radii_abs, radii_abs)
    for orientation in ((1, -1) if prefer >= 0 else (-1, 1)):
        layout = _solve_ccw(centres * np.array([1.0, float(orientation)]), radii, teeth, pitch)
        if layout is not None:
            return layout, orientation
    raise GeometryError(
        "sprockets",
        "the contour cannot close: list the sprockets in the order the chain runs round them, "
        "and mark with side = \"inside\" every sprocket that the chain wraps from outside the loop",
    )


@shared_parameters
def tight_pitches_of(centres: NDArray[np.float64], radii_abs: NDArray[np.float64],
                     inside: NDArray[np.bool_], teeth: NDArray[np.int_], pitch: float) -> float:
    """Tight chain length L_p = Σ ℓ_k/p + Σ z_i θ_i/(2π), eq. (3), of a layout.

    Parameters
    ----------
    %(layout_inputs)s

    Returns
    -------
    float
        L_p [pitches].

    Raises
    ------
    GeometryError
        When the contour cannot close.
    """
    return solve_layout(centres, radii_abs, inside, teeth, pitch)[0].tight_pitches


# --- two-sprocket closed forms -------------------------------------------------------------


def _too_few_links(links: float, z1: int, z2: int) -> GeometryError:
    """The error of a chain of ``links`` too short to go round sprockets of z1 and z2 teeth."""
    return GeometryError("chain.links", f"{links} links are too few for z1 = {z1}, z2 = {z2}")


@shared_parameters
def two_sprocket_links_exact(center_distance: float, pitch: float, z1: int, z2: int) -> float:
    """Tight length of a two-sprocket drive, exact on the pitch polygons, eq. (4).

    L_p = 2a·cos γ/p + (z₁+z₂)/2 + (z₂−z₁)·γ/π, sin γ = (R₂ − R₁)/a, R = p/(2 sin(π/z)).

    Parameters
    ----------
    %(two_sprocket_links)s
    """
    r1, r2 = _radii(pitch, [z1, z2])
    gamma = math.asin((r2 - r1) / center_distance)
    return 2.0 * center_distance * math.cos(gamma) / pitch + (z1 + z2) / 2 + (z2 - z1) * gamma / math.pi


@shared_parameters
def two_sprocket_links_iso10823(center_distance: float, pitch: float, z1: int, z2: int) -> float:
    """Chain length by the ISO 10823 / textbook approximation
    L_p = 2a/p + (z₁ + z₂)/2 + ((z₂ − z₁)/(2π))²·p/a.

    Parameters
    ----------
    %(two_sprocket_links)s

    References
    ----------
    [ISO10823]; [Shigley2015, Eq. 17-34]; [Bhandari2010, Eq. 14.7];
    [ChainDesignRU, §6].
    """
    return (2.0 * center_distance / pitch + (z1 + z2) / 2
            + ((z2 - z1) / TWO_PI) ** 2 * pitch / center_distance)


@shared_parameters
def two_sprocket_center_distance_iso10823(links: float, pitch: float, z1: int, z2: int) -> float:
    """Centre distance for a number of links, the inverse of the ISO 10823 approximation
    a = p/4·[ (L_p − (z₁+z₂)/2) + √((L_p − (z₁+z₂)/2)² − 8((z₂−z₁)/(2π))²) ].

    Parameters
    ----------
    %(two_sprocket_center_distance)s

    References
    ----------
    [ISO10823]; [Shigley2015, Eq. 17-35] (C = p/4·(−A + √(A² − 8((N₂−N₁)/2π)²))).
    """
    b = links - (z1 + z2) / 2
    disc = b * b - 8.0 * ((z2 - z1) / TWO_PI) ** 2
    if disc < 0:
        raise _too_few_links(links, z1, z2)
    return pitch / 4.0 * (b + math.sqrt(disc))


@shared_parameters
def two_sprocket_center_distance_exact(links: float, pitch: float, z1: int, z2: int) -> float:
    """Centre distance at which ``links`` fit exactly: eq. (4) solved for a.

    Parameters
    ----------
    %(two_sprocket_center_distance)s
    """
    r1, r2 = _radii(pitch, [z1, z2])
    a_min = abs(r2 - r1) * (1 + 1e-12) + 1e-12
    a_max = links * pitch

    def excess(a: float) -> float:
        return two_sprocket_links_exact(a, pitch, z1, z2) - links

    f_min, f_max = excess(a_min), excess(a_max)
    if f_min > 0:
        raise _too_few_links(links, z1, z2)
    return bracketed_root(excess, a_min, a_max, f_min, f_max, xtol=1e-14)


# --- the drive -----------------------------------------------------------------------------


def round_links(tight_pitches: float, allow_odd: bool = False, down: bool = False,
                nearest: bool = False) -> int:
    """Whole number of links for a tight length.

    Parameters
    ----------
    tight_pitches : float
        Tight chain length L_p [pitches].
    allow_odd : bool
        Allow an odd count (it needs an offset link).
    down : bool
        Round down (the take-up then shortens the layout) instead of up.
    nearest : bool
        The nearer of the counts below and above (the one above on a tie).

    Returns
    -------
    int
        The smallest whole (even unless ``allow_odd``) count ≥ L_p, or with ``down`` the
        largest one ≤ it, or with ``nearest`` the nearer of the two [links].

    References
    ----------
    [ChainDesignRU, §6] (round to a whole, preferably even, count).
    """
    if nearest:
        below = round_links(tight_pitches, allow_odd, down=True)
        above = round_links(tight_pitches, allow_odd)
        return below if tight_pitches - below < above - tight_pitches else above
    if down:
        links = math.floor(tight_pitches + 1e-9)
        return links if allow_odd or links % 2 == 0 else links - 1
    links = math.ceil(tight_pitches - 1e-9)
    if links % 2 and not allow_odd:
        links += 1
    return links


def adjustment_direction(layout: Layout, orientation: int, index: int, inside: bool,
                         angle: float | None) -> NDArray[np.float64]:
    """Unit vector of the line of adjustment of sprocket ``index``.

    Given ``angle``: (cos, sin). Default: from the centre towards the middle of the arc the
    chain wraps, i.e. into the chain. Moving a sprocket that way lengthens the
    contour at the rate 2·sin(θ/2) per unit of travel (the two spans' directions), for an
    outside and an inside sprocket alike; in a two-sprocket drive it is the line of
    centres, away from the other sprocket.

    Parameters
    ----------
    layout : Layout
        The contour solved in the counter-clockwise frame.
    orientation : int
        +1 or −1 (:func:`solve_layout`).
    index : int
        The sprocket.
    inside : bool
        True for a sprocket on the inside of the contour.
    angle : float or None
        Direction of the line of adjustment from the x axis [rad] (None: into the chain).

    Returns
    -------
    numpy.ndarray
        (2,) unit vector [-] in the user's frame.
    """
    if angle is not None:
        return np.array([math.cos(angle), math.sin(angle)])
    sgn = -1.0 if inside else 1.0
    n_in = layout.normals[index - 1]
    radial_in = sgn * n_in  # centre → arrival point, in the counter-clockwise frame
    half = sgn * 0.5 * float(layout.wraps[index])
    c, s = math.cos(half), math.sin(half)
    mid = np.array([c * radial_in[0] - s * radial_in[1], s * radial_in[0] + c * radial_in[1]])
    direction: NDArray[np.float64] = mid * np.array([1.0, float(orientation)])
    return direction


def bracketed_root(f: Callable[[float], float], lo: float, hi: float, f_lo: float, f_hi: float,
                   xtol: float = 1e-12, maxiter: int = 100) -> float:
    """Root of ``f`` in a bracket: the Illinois variant of regula falsi, superlinear and
    never leaving the bracket.

    Written here rather than calling scipy.optimize.brentq because importing
    scipy.optimize takes 0.5–0.7 s on the project machine, more than half of the 1 s that
    ``chaindrive analyze`` of a 24-sprocket contour may take (benchmarks/bench_analyze.py).

    Parameters
    ----------
    f : callable
        f(x) [any unit], continuous on [lo, hi].
    lo, hi : float
        The bracket [unit of x].
    f_lo, f_hi : float
        f(lo) and f(hi), of opposite signs (or one of them 0) [unit of f].
    xtol : float
        Width of the bracket at which to stop [unit of x].
    maxiter : int
        Most evaluations of ``f`` [-].

    Returns
    -------
    float
        The root [unit of x].

    Raises
    ------
    ConvergenceError
        After ``maxiter`` evaluations.

    References
    ----------
    [DowellJarratt1971].
    """
    if f_lo == 0.0:
        return lo
    if f_hi == 0.0:
        return hi
    side = 0
    for _ in range(maxiter):
        x = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        fx = f(x)
        if fx == 0.0 or abs(hi - lo) < xtol:
            return x
        if (fx > 0) == (f_hi > 0):
            hi, f_hi = x, fx
            if side == -1:
                f_lo *= 0.5
            side = -1
        else:
            lo, f_lo = x, fx
            if side == 1:
                f_hi *= 0.5
            side = 1
        if abs(hi - lo) < xtol:
            return x
    raise ConvergenceError(f"take-up did not converge in {maxiter} steps")


def _take_up(centres: NDArray[np.float64], radii: NDArray[np.float64], inside: NDArray[np.bool_],
             teeth: NDArray[np.int_], pitch: float, index: int, direction: NDArray[np.float64],
             links: float, name: str) -> float:
    """Displacement s [m] along ``direction`` at which the tight length equals ``links``."""

    def excess(s: float) -> float:
        moved = centres.copy()
        moved[index] = centres[index] + s * direction
        return tight_pitches_of(moved, radii, inside, teeth, pitch) - links

    f0 = excess(0.0)
    if f0 == 0.0:
        return 0.0
    step = pitch * max(1.0, abs(f0) / 2.0) * (1.0 if f0 < 0 else -1.0)
    lo, f_lo = 0.0, f0
    for _ in range(200):
        hi = lo + step
        try:
            f_hi = excess(hi)
        except GeometryError:
            break
        if f_hi == 0.0 or (f_hi > 0) != (f_lo > 0):
            return bracketed_root(excess, lo, hi, f_lo, f_hi)
        lo, f_lo = hi, f_hi
        step *= 1.5
    raise GeometryError(
        "chain.links",
        f"{links:g} links cannot be fitted by moving {name} along its line of adjustment "
        f"(the tight contour needs {f0 + links:.2f} pitches there)",
    )


def _check_clearances(centres: NDArray[np.float64], tips: NDArray[np.float64], names: list[str],
                      starts: NDArray[np.float64], ends: NDArray[np.float64]) -> None:
    """Refuse overlapping sprockets and spans that cut through a third sprocket.

    Vectorised over all pairs (sprocket–sprocket) and all span–sprocket pairs; the first
    offender in the order of the former double loops is reported.
    """
    n = len(centres)
    diff = centres[None, :, :] - centres[:, None, :]
    dist = np.hypot(diff[..., 0], diff[..., 1])
    need = 0.5 * (tips[:, None] + tips[None, :])
    bad = np.triu(dist < need, k=1)
    if bad.any():
        i, j = (int(x) for x in np.argwhere(bad)[0])
        raise GeometryError(
            f"sprockets[{j}]",
            f"{names[i]} and {names[j]} overlap: centres {dist[i, j] * 1e3:.1f} mm apart, "
            f"their tip circles need at least {need[i, j] * 1e3:.1f} mm",
        )
    ab = ends - starts                                        # (n, 2) spans k
    seg2 = np.einsum("ij,ij->i", ab, ab)                      # (n,)
    rel = centres[None, :, :] - starts[:, None, :]            # (k, m, 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.clip(np.einsum("kmj,kj->km", rel, ab) / seg2[:, None], 0.0, 1.0)
    closest = starts[:, None, :] + t[..., None] * ab[:, None, :] - centres[None, :, :]
    span_dist = np.hypot(closest[..., 0], closest[..., 1])
    k_idx = np.arange(n)
    own = (k_idx[None, :] == k_idx[:, None]) | (k_idx[None, :] == ((k_idx + 1) % n)[:, None])
    cuts = (span_dist < 0.5 * tips[None, :] - 1e-9) & ~own & (seg2[:, None] != 0.0)
    if cuts.any():
        k, m = (int(x) for x in np.argwhere(cuts)[0])
        raise GeometryError(
            "sprockets",
            f"the span {names[k]} → {names[(k + 1) % n]} cuts through sprocket {names[m]} "
            f"({span_dist[k, m] * 1e3:.1f} mm from its centre, tip radius {tips[m] * 500:.1f} mm)",
        )


def contour_geometry(drive: Drive) -> GeometryResult:
    """Build the contour of a drive: spans, wraps, length, links and take-up.

    Steps: pitch radii → solve the layout in the direction that closes (module docstring
    eqs. 1–3) → links (imposed, or L_p rounded up to even) → take-up of the adjustable
    sprocket until L_p equals the links exactly → checks (overlap, spans through
    sprockets) and warnings (driver wrap < 120°, < 3 teeth in mesh on loaded sprockets).

    Parameters
    ----------
    drive : Drive
        The design: chain, sprockets in the order the chain runs, take-up.

    Returns
    -------
    GeometryResult
        The contour in the user's frame.

    Raises
    ------
    GeometryError
        When sprockets overlap, a span cuts a sprocket or the contour cannot close.
    DesignError
        When an imposed number of links cannot be fitted.

    References
    ----------
    [Mott2014, ch. 7] (wrap ≥ 120°); [Renold-DG] (three teeth in mesh).
    """
    spec = drive.chain.spec
    p = spec.pitch
    sps = drive.sprockets
    names = [s.name for s in sps]
    teeth = np.array([s.teeth for s in sps])
    inside = np.array([s.side == "inside" for s in sps])
    centres = np.array([[s.x, s.y] for s in sps], dtype=float)
    counts = tuple(s.teeth for s in sps)
    radii = _diameters("radii", p, counts, spec.roller_diameter, drive.tooth_form)
    tips = _diameters("tip", p, counts, spec.roller_diameter, drive.tooth_form)
    _check_clearances(centres, tips, names, centres, centres)  # overlap only (zero-length spans)

    prefer = travel_orientation(drive)
    layout, orientation = solve_layout(centres, radii, inside, teeth, p, prefer)
    links = drive.chain.links or round_links(layout.tight_pitches, drive.chain.allow_odd,
                                             down=drive.chain.rounding == "round down",
                                             nearest=drive.chain.rounding == "nearest")
    adjusted = drive.adjustable_index
    adjustment = shortening = 0.0
    if adjusted is not None:
        s = sps[adjusted]
        direction = adjustment_direction(layout, orientation, adjusted, s.side == "inside",
                                         s.adjust_angle)
        adjustment = _take_up(centres, radii, inside, teeth, p, adjusted, direction, links,
                              s.name)
        if drive.chain.sag is not None:  # installed with sag: the slack span keeps ΔL
            moved = centres.copy()
            moved[adjusted] = centres[adjusted] + adjustment * direction
            tight_layout, _ = solve_layout(moved, radii, inside, teeth, p, prefer)
            slack_span = float(tight_layout.span_lengths[drive.driver_index])
            target = links - slack_for_sag(slack_span, drive.chain.sag) / p
            adjustment = _take_up(centres, radii, inside, teeth, p, adjusted, direction, target,
                                  s.name)
        if drive.chain.sag_allowance is not None:  # installed short of the tight position
            other = (drive.driver_index if adjusted != drive.driver_index
                     else (adjusted + 1) % len(sps))
            shortening = drive.chain.sag_allowance * float(np.linalg.norm(
                centres[adjusted] + adjustment * direction - centres[other]))
            adjustment += sag_allowance_travel(centres[adjusted] + adjustment * direction,
                                               centres[other], direction, shortening, s.name)
        centres[adjusted] = centres[adjusted] + adjustment * direction
    elif drive.chain.sag_allowance is not None:
        raise DesignError("chain.sag_allowance", "shortens the installed centre distance by "
                          "moving the adjustable sprocket; no sprocket is adjustable "
                          "(give one adjustable = true)")
    elif drive.chain.links is not None and links < layout.tight_pitches - 1e-9:
        raise DesignError(
            "chain.links",
            f"{links} links are shorter than the tight contour ({layout.tight_pitches:.2f} pitches) "
            "and no sprocket is adjustable",
        )
    layout, orientation = solve_layout(centres, radii, inside, teeth, p, prefer)
    result = _assemble(drive, centres, radii, tips, inside, layout, orientation, links, adjusted,
                       adjustment)
    return replace(result, sag_allowance=shortening) if shortening else result


def sag_allowance_travel(centre: NDArray[np.float64], other: NDArray[np.float64],
                         direction: NDArray[np.float64], shortening: float, name: str) -> float:
    """How far [m] to move a sprocket along its line of adjustment (negative: back) so that
    its centre distance a to ``other`` becomes a − Δa: the root of |v + t·u|² = (a − Δa)²
    (v = centre − other, u = direction) nearest to 0. Textbooks install the chain with the
    centre distance shortened by Δa = (0.002 … 0.004)·a so that the slack span sags.

    Parameters
    ----------
    centre, other : ndarray
        The adjustable sprocket's centre at the tight position and the other centre [m].
    direction : ndarray
        Unit vector of the line of adjustment.
    shortening : float
        Δa [m].
    name : str
        The adjustable sprocket, for the message.

    Returns
    -------
    float
        t [m].

    Raises
    ------
    DesignError
        The line of adjustment cannot shorten that distance by Δa.

    References
    ----------
    [ChainDesignRU, §7]; [Bhandari2010, ex. 14.4] (Δa = 0.002·a).
    """
    v = centre - other
    a = float(np.linalg.norm(v))
    vu = float(v @ direction)
    disc = vu * vu - (2.0 * a * shortening - shortening * shortening)
    if disc < 0.0 or a <= shortening:
        raise DesignError("chain.sag_allowance", f"the line of adjustment of {name} cannot "
                          f"shorten its centre distance {a * 1e3:.1f} mm by "
                          f"{shortening * 1e3:.2f} mm; allowed: a line of adjustment with a "
                          "component along the centre line (adjust_angle)")
    root = math.sqrt(disc)
    return min((-vu + root, -vu - root), key=abs)


def travel_orientation(drive: Drive) -> int:
    """The orientation of chain travel round the contour that the driver's rotation asks
    for: +1 counter-clockwise, −1 clockwise (+1, the orientation tried first, when the
    design gives no rotation).

    A driver on the outside of the contour turns the way the chain travels round it; one on
    the inside turns the other way (module docstring).

    Parameters
    ----------
    drive : Drive
        The design (``drive.rotation``: "cw", "ccw" or None).

    Returns
    -------
    int
        +1 or −1.
    """
    if drive.rotation is None:
        return 1
    turn = 1 if drive.rotation == "ccw" else -1
    return -turn if drive.driver.side == "inside" else turn


@shared_parameters
def driver_rotation(geometry: GeometryResult, driver_index: int) -> str:
    """The driver's direction of rotation in a laid-out contour.

    Parameters
    ----------
    %(geometry_the_contour)s
    driver_index : int
        Index of the driver.

    Returns
    -------
    str
        "ccw" or "cw" on the drawing plane (x right, y up).
    """
    return "ccw" if geometry.sprockets[driver_index].turn > 0 else "cw"


@shared_parameters
def in_travel_order(drive: Drive) -> Drive:
    """The drive with its sprockets listed in the order the chain runs round them when the
    driver turns as ``drive.rotation`` says.

    The chain leaves the driver on the slack span and the driver pulls in the tight span, so
    the direction of travel, and with it which spans are tight, follows from the rotation.
    When the listing runs against it, the order is reversed (the first sprocket kept first:
    S0, S(n−1), …, S1); a contour of two sprockets closes both ways and keeps its order (the
    layout takes the orientation of the rotation, :func:`travel_orientation`). Without a
    rotation the drive is returned as it is.

    %(drive_returns)s
    Drive
        The same drive, its sprockets in the order of travel.

    Raises
    ------
    GeometryError
        When the contour closes in neither direction.
    """
    if drive.rotation is None or len(drive.sprockets) < 3:
        return drive
    sps = drive.sprockets
    p = drive.chain.spec.pitch
    teeth = np.array([s.teeth for s in sps])
    centres = np.array([[s.x, s.y] for s in sps], dtype=float)
    inside = np.array([s.side == "inside" for s in sps])
    want = travel_orientation(drive)
    _, orientation = solve_layout(centres, _radii(p, teeth), inside, teeth, p, want)
    if orientation == want:
        return drive
    return drive.with_sprockets((sps[0], *sps[:0:-1]))


def _assemble(drive: Drive, centres: NDArray[np.float64], radii: NDArray[np.float64],
              tips: NDArray[np.float64], inside: NDArray[np.bool_], layout: Layout,
              orientation: int, links: int, adjusted: int | None,
              adjustment: float) -> GeometryResult:
    """Turn a solved layout into the user-frame GeometryResult, with its checks."""
    spec = drive.chain.spec
    p = spec.pitch
    sps = drive.sprockets
    n = len(sps)
    mirror = np.array([1.0, float(orientation)])
    signed = np.where(inside, -radii, radii)
    frame = centres * mirror  # the counter-clockwise frame
    starts = (frame + signed[:, None] * layout.normals) * mirror
    ends = (_following(frame) + _following(signed)[:, None] * layout.normals) * mirror
    _check_clearances(centres, tips, [s.name for s in sps], starts, ends)

    driver = drive.driver_index
    roots = _diameters("root", p, tuple(s.teeth for s in sps), spec.roller_diameter,
                       drive.tooth_form)
    spans = []
    for k in range(n):
        d = ends[k] - starts[k]
        length = float(layout.span_lengths[k])
        direction = d / length if length > 0 else np.zeros(2)
        incl = math.atan2(direction[1], direction[0])
        if incl > math.pi / 2:
            incl -= math.pi
        elif incl < -math.pi / 2:
            incl += math.pi
        spans.append(SpanGeometry(
            index=k, start=k, end=(k + 1) % n, start_name=sps[k].name,
            end_name=sps[(k + 1) % n].name, length=length, pitches=length / p,
            direction=(float(direction[0]), float(direction[1])),
            start_point=(float(starts[k][0]), float(starts[k][1])),
            end_point=(float(ends[k][0]), float(ends[k][1])),
            inclination=incl, tight=(k + 1) % n == driver,
        ))
    sprockets = []
    for i, s in enumerate(sps):
        turn = orientation * (-1 if inside[i] else 1)
        sprockets.append(SprocketGeometry(
            name=s.name, teeth=s.teeth, side=s.side, x=float(centres[i][0]), y=float(centres[i][1]),
            pitch_radius=float(radii[i]), pitch_diameter=float(2 * radii[i]),
            tip_diameter=float(tips[i]), root_diameter=float(roots[i]),
            wrap_angle=float(layout.wraps[i]),
            teeth_in_mesh=float(s.teeth * layout.wraps[i] / TWO_PI), turn=turn,
            arrive=spans[i - 1].end_point, leave=spans[i].start_point,
        ))
    chain_length = links * p
    tight_length = layout.tight_pitches * p
    return GeometryResult(
        pitch=p, sprockets=tuple(sprockets), spans=tuple(spans),
        tight_pitches=layout.tight_pitches, links=links, chain_length=chain_length,
        tight_length=tight_length, slack=max(0.0, chain_length - tight_length),
        center_distance=float(np.hypot(*(centres[1] - centres[0]))) if n == 2 else None,
        adjusted=adjusted, adjustment=adjustment, orientation=orientation,
        warnings=tuple(_geometry_warnings(drive, sprockets, chain_length - tight_length, adjusted,
                                          spans[driver].length)),
    )


def _geometry_warnings(drive: Drive, sprockets: list[SprocketGeometry], slack: float,
                       adjusted: int | None, slack_span: float) -> list[ChainDriveWarning]:
    """Engineering warnings: small driver wrap, few teeth in mesh, untaken slack (with the sag
    it hangs in, the slack span's length ``slack_span`` [m])."""
    out = []
    driver = sprockets[drive.driver_index]
    if math.degrees(driver.wrap_angle) < 120.0:
        out.append(ChainDriveWarning(
            "geometry.driver-wrap", f"sprockets[{driver.name}]",
            f"driver {driver.name}: wrap angle {math.degrees(driver.wrap_angle):.1f}° is "
            "under 120° (chain may jump teeth; add an idler or increase the wrap)"))
    for s, g in zip(drive.sprockets, sprockets, strict=True):
        if s.role != "idler" and g.teeth_in_mesh < 3.0:
            out.append(ChainDriveWarning(
                "geometry.teeth-in-mesh", f"sprockets[{s.name}]",
                f"{s.name}: only {g.teeth_in_mesh:.2f} teeth in mesh on a loaded sprocket "
                "(at least 3 are needed)"))
    if adjusted is None and slack > 1e-6:
        sag = sag_of_slack(slack_span, slack)
        given = drive.chain.sag
        tension = (f"the span tensions and the dynamics assume a sag of "
                   f"{100 * DEFAULT_SAG_RATIO:g} % ([chain] sag not given)" if given is None
                   else f"[chain] sag gives {100 * given:.3g} %")
        q = Quantities()
        out.append(ChainDriveWarning(
            "geometry.slack", "chain",
            f"chain slack {q(slack, 'length', '.1f')} ({slack / drive.chain.pitch:.2f} "
            f"pitches) is not taken up: in the slack span ({q(slack_span, 'length', '.0f')}) "
            f"it hangs in a sag of {q(sag, 'length', '.1f')} ({100 * sag / slack_span:.3g} "
            f"%), while {tension}; mark a sprocket adjustable, add a tensioner or give the "
            "installed sag", q.items))
    return out
