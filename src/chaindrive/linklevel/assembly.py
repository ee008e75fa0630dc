"""Initial state of the link-level model: the chain assembled on the contour.

The contour path of :func:`chaindrive.geometry.contour.contour_geometry` — the pitch arc of
every sprocket from the arrival to the leaving point, turning with the sprocket, then the
straight tangent span to the next one — is walked from the arrival point of the first
sprocket, placing each roller at a chord of one pitch p from the previous one (the chord
on a pitch circle of radius R = p/(2 sin(π/z)) spans exactly one tooth, so the rollers on a
wrap sit at the gap centres of the pitch polygon). Each sprocket is turned so that one gap
centre lies under the first roller that reaches its arc. The N-th chord does not close
exactly (the spans meet the polygons, not the pitch circles): the rollers of the last span
are spaced evenly between its two ends instead (or hung in a sag when the contour has
slack that no take-up removes), and the misfit is returned.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from chaindrive.errors import GeometryError
from chaindrive.geometry.results import GeometryResult

__all__ = ["Assembly", "assemble_chain", "contour_path"]

_BISECTIONS = 52


@dataclass(frozen=True, slots=True)
class _Path:
    """Pieces of the contour path: kind 0 arc (centre, radius, start angle, sense) or
    1 segment (start, direction), each with its length and start parameter s [m]."""

    kinds: tuple[int, ...]
    owners: tuple[int, ...]  # sprocket of an arc, span of a segment
    starts: NDArray[np.float64]  # (P,) start parameter
    lengths: NDArray[np.float64]
    data: NDArray[np.float64]  # (P, 5): arc cx, cy, R, a0, sense | seg x0, y0, ux, uy, 0
    # the same numbers as Python floats, for the scalar walk of :meth:`point` (which runs
    # some 50 times per roller): the same arithmetic without NumPy's per-call overhead
    _starts: tuple[float, ...] = field(init=False, repr=False, compare=False)
    _rows: tuple[tuple[float, ...], ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_starts", tuple(float(v) for v in self.starts))
        object.__setattr__(self, "_rows", tuple(tuple(float(v) for v in row)
                                                for row in self.data))

    @property
    def total(self) -> float:
        """Path length [m]."""
        return float(self.starts[-1] + self.lengths[-1])

    def point(self, s: float) -> tuple[float, float]:
        """Point at parameter s [m]."""
        k = min(max(bisect_right(self._starts, s) - 1, 0), len(self.kinds) - 1)
        d = self._rows[k]
        u = s - self._starts[k]
        if self.kinds[k] == 0:
            a = d[3] + d[4] * u / d[2]
            return d[0] + d[2] * math.cos(a), d[1] + d[2] * math.sin(a)
        return d[0] + d[2] * u, d[1] + d[3] * u

    def piece(self, s: float) -> int:
        """Index of the piece holding parameter s."""
        k = int(np.searchsorted(self.starts, s, side="right")) - 1
        return min(max(k, 0), len(self.kinds) - 1)


def contour_path(geometry: GeometryResult, first: int = 0) -> _Path:
    """The closed path of the chain's pitch line: arc on sprocket ``first``, the span leaving
    it, the arc on the next sprocket, …, the span arriving at ``first``.

    Parameters
    ----------
    geometry : GeometryResult
        The contour.
    first : int
        Index of the sprocket the path starts on [-].

    Returns
    -------
    _Path
        The segments of the path with their lengths [m].
    """
    kinds, owners, lengths, data = [], [], [], []
    n = len(geometry.sprockets)
    for i in [(first + k) % n for k in range(n)]:
        g = geometry.sprockets[i]
        a0 = math.atan2(g.arrive[1] - g.y, g.arrive[0] - g.x)
        kinds.append(0)
        owners.append(i)
        lengths.append(g.pitch_radius * g.wrap_angle)
        data.append((g.x, g.y, g.pitch_radius, a0, float(g.turn)))
        sp = geometry.spans[i]
        kinds.append(1)
        owners.append(i)
        lengths.append(sp.length)
        data.append((sp.start_point[0], sp.start_point[1], sp.direction[0], sp.direction[1], 0.0))
    lens = np.array(lengths)
    starts = np.concatenate([[0.0], np.cumsum(lens)[:-1]])
    return _Path(tuple(kinds), tuple(owners), starts, lens, np.array(data))


@dataclass(frozen=True, slots=True, eq=False)
class Assembly:
    """The assembled chain.

    Parameters
    ----------
    positions : ndarray
        (N, 2) roller centres [m].
    parameters : ndarray
        (N,) path parameters s [m].
    angles : ndarray
        (n,) sprocket angles [rad] (a gap centre at angle θ_i + 2πj/z_i).
    closing_misfit : float
        The last span's length minus its links' pitches [m].
    last_span : int
        Index of the span evened out [-].
    path_length : float
        Length of the pitch-line path [m].
    sprocket_of : ndarray
        (N,) the sprocket whose arc holds each roller (−1 on a span) [-].
    span_of : ndarray
        (N,) the span of each roller (−1 on an arc) [-].
    """

    positions: NDArray[np.float64]
    parameters: NDArray[np.float64]
    angles: NDArray[np.float64]
    closing_misfit: float
    last_span: int
    path_length: float
    sprocket_of: NDArray[np.int64]
    span_of: NDArray[np.int64]


def _next_parameter(path: _Path, s0: float, pitch: float) -> float:
    """Smallest s > s0 with |P(s) − P(s0)| = p (bisection on the monotone chord)."""
    x0, y0 = path.point(s0)
    lo, hi = s0, s0 + 1.6 * pitch
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        x, y = path.point(mid)
        if math.hypot(x - x0, y - y0) < pitch:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def assemble_chain(geometry: GeometryResult, slack_span: int = -1, *,
                   hang: bool = False) -> Assembly:
    """Place the N rollers on the contour and turn the sprockets under them (module
    docstring).

    The walk ends in span ``slack_span``, whose rollers are spaced evenly on its line when
    the contour is taut (a take-up sprocket, or no slack: the links of that span then differ
    from p by misfit/count, a few µm, which their rest lengths absorb) or else hung on a
    circular arc of equal chords p sagging along −y (the slack the contour leaves).

    Parameters
    ----------
    geometry : GeometryResult
        The contour.
    slack_span : int
        Index of the span the walk ends in [-] (−1: the last).
    hang : bool
        True hangs any slack (a negative misfit) in the sag even on a taken-up contour (the
        chain installed with sag, :mod:`chaindrive.linklevel.equilibrium`).

    Returns
    -------
    Assembly
        Roller positions, sprocket angles and the misfit.

    Raises
    ------
    GeometryError
        A misfit beyond one pitch.
    """
    n = len(geometry.spans)
    last = slack_span % n
    path = contour_path(geometry, (last + 1) % n)
    p, n_links = geometry.pitch, geometry.links
    s = np.empty(n_links)
    s[0] = 0.0
    for r in range(1, n_links):
        s[r] = _next_parameter(path, float(s[r - 1]), p)
    total = path.total
    span_start = float(path.starts[-1])
    tail = np.flatnonzero(s > span_start)
    x_end = np.array(path.point(total))
    pos = np.array([path.point(float(v)) for v in s])
    # the first roller on the last span stays where the walk put it (a chord p from the
    # arc); the ones after it are re-placed between it and the closing point
    first = int(tail[0]) if tail.size else n_links - 1
    anchor = pos[first].copy()
    gap = float(np.hypot(*(x_end - anchor)))
    count = n_links - first  # links from the anchor round to roller 0
    misfit = gap - count * p
    if abs(misfit) > p:
        raise GeometryError("chain.links", f"the {n_links} links do not close on the contour "
                            f"(misfit {misfit * 1e3:.2f} mm)")
    taut = not hang and (geometry.adjusted is not None or geometry.slack <= 0.0)
    if count > 1 and (misfit >= 0 or taut):
        frac = np.arange(1, count)[:, None] / count
        pos[first + 1:] = anchor + frac * (x_end - anchor)
    elif count > 1:
        pos[first + 1:] = sagging_polygon(anchor, x_end, count, p)[1:-1]
    angles = _sprocket_angles(geometry, path, s, pos)
    piece = np.array([path.piece(float(v)) for v in s])
    if tail.size:
        piece[first:] = len(path.kinds) - 1
    kinds = np.array(path.kinds)[piece]
    owners = np.array(path.owners)[piece]
    return Assembly(pos, s, angles, misfit, last, total,
                    np.where(kinds == 0, owners, -1), np.where(kinds == 1, owners, -1))


def sagging_polygon(a: NDArray[np.float64], b: NDArray[np.float64], count: int,
                    pitch: float) -> NDArray[np.float64]:
    """Vertices (count+1, 2) [m] of ``count`` equal chords of length p from a to b on a
    circular arc bowing towards −y (|b − a| < count·p): the chord angle β solves
    sin(count·β/2)/sin(β/2) = |b − a|/p (bisection, the ratio falls monotonically in β)."""
    d = b - a
    gap = float(np.hypot(*d))
    ratio = gap / pitch
    lo, hi = 1e-12, 2.0 * math.pi / count
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if math.sin(count * mid / 2) / math.sin(mid / 2) > ratio:
            lo = mid
        else:
            hi = mid
    beta = 0.5 * (lo + hi)
    u = d / gap
    normal = np.array([-u[1], u[0]])
    if normal[1] > 0 or (normal[1] == 0 and normal[0] > 0):
        normal = -normal
    # chord k turns by β from the previous; the first leaves at +(count−1)β/2 to the chord
    ang = (0.5 * (count - 1) - np.arange(count)) * beta
    steps = pitch * (np.cos(ang)[:, None] * u + np.sin(ang)[:, None] * normal)
    out = np.zeros((count + 1, 2))
    out[1:] = np.cumsum(steps, axis=0)
    return a + out


def _sprocket_angles(geometry: GeometryResult, path: _Path, s: NDArray[np.float64],
                     pos: NDArray[np.float64]) -> NDArray[np.float64]:
    """Angle of each sprocket that puts a gap centre under the first roller on its arc."""
    angles = np.zeros(len(geometry.sprockets))
    for k, (kind, owner) in enumerate(zip(path.kinds, path.owners, strict=True)):
        if kind != 0:
            continue
        lo, hi = float(path.starts[k]), float(path.starts[k] + path.lengths[k])
        on = np.flatnonzero((s >= lo - 1e-12) & (s <= hi + 1e-12))
        g = geometry.sprockets[owner]
        if on.size == 0:
            continue
        r = int(on[0])
        angles[owner] = math.atan2(pos[r, 1] - g.y, pos[r, 0] - g.x)
    return angles
