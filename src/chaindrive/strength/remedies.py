"""Layout remedies: the change of one sprocket that brings a failed layout check over its
limit, found by laying the drive out again.

A layout check (:func:`chaindrive.strength.drive_checks.geometry_checks`: teeth in mesh,
wrap, longest span) depends on the chain only through its pitch and roller; when it fails,
what is to change is the layout. For a failed check of a drive laid out with a chain this
module looks for

* **teeth** — on an idler the check is about, the fewest teeth z' > z (up to 2z) that make
  it pass (an idler's teeth do not change the speed ratio; a loaded sprocket's would, so
  none is proposed for one);
* **a move** — of the sprocket the check is about, or of an idler next to it (when the drive
  has no idler: a sprocket other than the driver, e.g. the driven one of a two-sprocket
  drive), along the bisector of its wrap, u = (d_in − d_out)/|d_in − d_out| with d_in, d_out
  the directions of travel of the spans arriving and leaving (the line of the take-up: u
  points into the chain, and moving that way lengthens the contour at 2·sin(θ/2) per unit
  of travel, :func:`chaindrive.geometry.contour.adjustment_direction`), into the chain or
  out of it, by the least distance that makes it pass;
* **for the longest span** — in addition the closed form of its limit: ℓ ≤ 80·p.

Every change is laid out again with :func:`chaindrive.geometry.contour.contour_geometry`
(the design's take-up and link rounding) and accepted only when the failed check then
passes and no layout check that passed fails. The distance is scanned in 32 steps up to the
shorter of the sprocket's two spans (the layout's link count, and with it the take-up, jumps
as the sprocket moves, so the checks are not monotone in the distance), the first passing
step is bisected between it and the step before to 0.5 mm, and the centre that is reported
— the design's centre moved by that distance, written to 0.1 mm as a design file would take
it — is the one laid out and verified.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, replace
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.checks import Check
from chaindrive.errors import DesignError, Quantities, Quantity
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.results import GeometryResult
from chaindrive.model import MAX_TEETH, Drive, Sprocket
from chaindrive.strength.drive_checks import geometry_checks

__all__ = ["MOVE_STEPS", "Layouts", "Remedy", "layout_remedies", "move_direction", "span_limit_text"]

#: Steps of the scan of a move, up to the shorter span of the sprocket moved [-].
MOVE_STEPS = 32
#: Resolution of the bisection of a move [m].
_MOVE_RESOLUTION = 5e-4
#: Resolution of a reported centre, as a design file would take it [m] (0.1 mm).
_CENTRE_RESOLUTION = 1e-4


@dataclass(frozen=True, slots=True)
class Remedy:
    """One change of the layout that makes a failed layout check pass, verified by laying
    the changed drive out again.

    Parameters
    ----------
    check : str
        The key of the check it makes pass (``teeth_in_mesh[T]``, ``wrap[S1]`` …).
    sprocket : str
        The sprocket to change.
    action : str
        ``"teeth"`` (another number of teeth) or ``"move"`` (another centre).
    teeth : int
        Its number of teeth after the change [-].
    x, y : float
        Its centre in the design after the change [m].
    distance : float
        How far the centre moves [m] (0 for a change of teeth); positive into the chain.
    value : float
        The check's value after the change [SI].
    unit : str
        The unit the check is read in.
    scale : float
        Factor from SI to ``unit`` [-].
    links : int
        The chain's links in the changed layout [-].
    text : str
        The remedy in words (SI).
    quantities : tuple of Quantity
        The numbers with units ``text`` writes.
    """

    check: str
    sprocket: str
    action: str
    teeth: int
    x: float
    y: float
    distance: float
    value: float
    unit: str
    scale: float
    links: int
    text: str
    quantities: tuple[Quantity, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm, the check's value in its unit)."""
        return {"check": self.check, "sprocket": self.sprocket, "action": self.action,
                "teeth": self.teeth, "x_mm": self.x * 1e3, "y_mm": self.y * 1e3,
                "move_mm": self.distance * 1e3, "value_after": self.value * self.scale,
                "unit": self.unit, "links": self.links, "text": self.text,
                "quantities": [q.to_dict() for q in self.quantities]}


def move_direction(geometry: GeometryResult, index: int) -> tuple[float, float] | None:
    """The bisector of a sprocket's wrap, pointing into the chain: u = (d_in − d_out)/|…|
    (module docstring).

    Parameters
    ----------
    geometry : GeometryResult
        The laid-out contour.
    index : int
        The sprocket.

    Returns
    -------
    tuple of float or None
        (2,) unit vector [-]; None when the chain runs straight past it (no wrap).
    """
    spans = geometry.spans
    d_in, d_out = spans[index - 1].direction, spans[index].direction
    ux, uy = d_in[0] - d_out[0], d_in[1] - d_out[1]
    norm = math.hypot(ux, uy)
    if norm < 1e-9:
        return None
    return ux / norm, uy / norm


#: The layouts already made of changes of one drive, by the sprocket changed: its index and
#: the changed sprocket (with the signs of its centre, so that −0 and 0 stay apart) → the
#: changed drive laid out and its layout checks by key, or None when it cannot be laid out.
Layouts = dict[tuple[int, Sprocket, float, float],
               tuple[GeometryResult, dict[str, Check]] | None]


def _laid_out(drive: Drive, index: int, sprocket: Sprocket, memo: Layouts
              ) -> tuple[GeometryResult, dict[str, Check]] | None:
    """``drive`` with sprocket ``index`` changed to ``sprocket``, laid out and its layout
    checks by key (None when it cannot be laid out), from ``memo`` when that change was laid
    out before."""
    key = (index, sprocket, math.copysign(1.0, sprocket.x), math.copysign(1.0, sprocket.y))
    if key not in memo:
        changed = _with(drive, index, sprocket)
        try:
            geometry = contour_geometry(changed)
        except DesignError:
            memo[key] = None
        else:
            memo[key] = geometry, {c.key: c for c in geometry_checks(changed, geometry)}
    return memo[key]


def _outcome(drive: Drive, index: int, sprocket: Sprocket, key: str,
             passing: frozenset[str], memo: Layouts) -> tuple[Check, GeometryResult] | None:
    """The check ``key`` of ``drive`` with sprocket ``index`` changed to ``sprocket``, laid
    out again, when it passes and no check of ``passing`` fails; None otherwise (or when the
    changed drive cannot be laid out)."""
    laid = _laid_out(drive, index, sprocket, memo)
    if laid is None:
        return None
    geometry, checks = laid
    target = checks.get(key)
    if target is None or not target.passed:
        return None
    if any(not checks[k].passed for k in passing if k in checks):
        return None
    return target, geometry


def _with(drive: Drive, index: int, sprocket: Sprocket) -> Drive:
    return drive.with_sprockets(tuple(sprocket if i == index else s
                                      for i, s in enumerate(drive.sprockets)))


def _teeth_remedy(drive: Drive, index: int, failed: Check,
                  passing: frozenset[str], memo: Layouts) -> Remedy | None:
    """The fewest teeth on idler ``index`` that make ``failed`` pass."""
    s = drive.sprockets[index]
    for z in range(s.teeth + 1, min(MAX_TEETH, 2 * s.teeth) + 1):
        found = _outcome(drive, index, replace(s, teeth=z), failed.key, passing, memo)
        if found is not None:
            check, geometry = found
            value = check.shown(check.value) or 0.0
            text = (f"give {s.name} {z} teeth instead of {s.teeth} ({failed.name} "
                    f"{value:.3g} {check.unit}, {geometry.links} links)")
            return Remedy(failed.key, s.name, "teeth", z, s.x, s.y, 0.0,
                          check.value or 0.0, check.unit, check.scale, geometry.links, text)
    return None


def _moved(s: Sprocket, u: tuple[float, float], t: float) -> Sprocket:
    """``s`` moved by t along u, its centre written to :data:`_CENTRE_RESOLUTION`."""
    def snap(v: float) -> float:
        return round(v / _CENTRE_RESOLUTION) * _CENTRE_RESOLUTION

    return s.moved_to(snap(s.x + t * u[0]), snap(s.y + t * u[1]))


def _move_remedy(drive: Drive, geometry: GeometryResult, index: int, sign: float,
                 failed: Check, passing: frozenset[str], memo: Layouts) -> Remedy | None:
    """The least move of sprocket ``index`` along ±u that makes ``failed`` pass."""
    u0 = move_direction(geometry, index)
    if u0 is None:
        return None
    u = (sign * u0[0], sign * u0[1])
    s = drive.sprockets[index]
    spans = geometry.spans
    reach = min(spans[index - 1].length, spans[index].length)
    if reach <= 0:
        return None
    step = reach / MOVE_STEPS

    def trial(t: float) -> tuple[Check, GeometryResult] | None:
        return _outcome(drive, index, _moved(s, u, t), failed.key, passing, memo)

    before = 0.0
    for k in range(1, MOVE_STEPS + 1):
        t = k * step
        found = trial(t)
        if found is None:
            before = t
            continue
        lo, hi, best = before, t, (t, found)
        while hi - lo > _MOVE_RESOLUTION:
            mid = 0.5 * (lo + hi)
            at = trial(mid)
            if at is None:
                lo = mid
            else:
                hi, best = mid, (mid, at)
        distance, (check, laid) = best
        moved = _moved(s, u, distance)
        distance = math.hypot(moved.x - s.x, moved.y - s.y)
        q = Quantities()
        way = "into the chain" if sign > 0 else "out of the chain"
        if len(drive.sprockets) == 2:  # the bisector is the line of centres
            other = drive.sprockets[1 - index].name
            way = f"away from {other}" if sign > 0 else f"towards {other}"
        value = check.shown(check.value) or 0.0
        take_up = (f"; the take-up then needs {laid.links} links"
                   if drive.adjustable_index is not None else f"; {laid.links} links")
        text = (f"move {s.name} {q(distance, 'length', '.0f')} {way}, to x = "
                f"{q(moved.x, 'length', '.1f')}, y = {q(moved.y, 'length', '.1f')} "
                f"({failed.name} {value:.3g} {check.unit}{take_up})")
        return Remedy(failed.key, s.name, "move", s.teeth, moved.x, moved.y,
                      sign * distance, check.value or 0.0,
                      check.unit, check.scale, laid.links, text, q.items)
    return None


def _subject_index(drive: Drive, failed: Check) -> int | None:
    """The sprocket a failed check is about (None for the span length)."""
    names = [s.name for s in drive.sprockets]
    return names.index(failed.item) if failed.item in names else None


def _movable(drive: Drive, near: int | None) -> Iterator[int]:
    """The sprockets a move may change: the check's sprocket and its neighbours that are
    idlers (every idler for a span check); without an idler in the drive, any sprocket but
    the driver."""
    n = len(drive.sprockets)
    idlers = [i for i, s in enumerate(drive.sprockets) if s.role == "idler"]
    pool = idlers or [i for i in range(n) if i != drive.driver_index]
    if near is None:
        yield from pool
        return
    for i in dict.fromkeys((near, (near - 1) % n, (near + 1) % n)):
        if i in pool:
            yield i


@shared_parameters
def span_limit_text(failed: Check, pitch: float) -> tuple[str, tuple[Quantity, ...]]:
    """The closed form of the span-length limit: ℓ ≤ 80·p, how much shorter the span must
    be, or that it needs support.

    Parameters
    ----------
    failed : Check
        The failed span-length check (value and limit in pitches).
    %(pitch)s

    Returns
    -------
    text : str
        The remedy in words (SI).
    quantities : tuple of Quantity
        The numbers with units it writes.
    """
    q = Quantities()
    value, limit = (failed.value or 0.0) * pitch, (failed.limit or 0.0) * pitch
    text = (f"support the {failed.subject} with a guide or an idler, or shorten it to at most "
            f"{q(limit, 'length', '.0f')} ({q(value - limit, 'length', '.0f')} shorter)")
    return text, q.items


@shared_parameters
def layout_remedies(drive: Drive, geometry: GeometryResult, failed: Check,
                    memo: Layouts | None = None) -> tuple[Remedy, ...]:
    """The remedies of one failed layout check (module docstring): a change of teeth first
    (when the check is about an idler), then the least move of each sprocket that may move,
    the smallest first.

    Parameters
    ----------
    drive : Drive
        The drive with the chain, laid out as the selection lays it out (its link rounding).
    %(geometry)s
    failed : Check
        The failed layout check.
    memo : dict or None
        The layouts already made of changes of this same ``drive`` (:data:`Layouts`), filled
        as changes are laid out: the remedies of several failed checks of one drive try many
        of the same changes (None: a memo of this call only).

    Returns
    -------
    tuple of Remedy
        Each one verified by laying the changed drive out again; empty when none is found.
    """
    memo = {} if memo is None else memo
    passing = frozenset(c.key for c in geometry_checks(drive, geometry) if c.passed)
    index = _subject_index(drive, failed)
    out: list[Remedy] = []
    if index is not None and drive.sprockets[index].role == "idler":
        teeth = _teeth_remedy(drive, index, failed, passing, memo)
        if teeth is not None:
            out.append(teeth)
    moves: list[Remedy] = []
    for i in _movable(drive, index):
        found = [m for sign in (1.0, -1.0)
                 if (m := _move_remedy(drive, geometry, i, sign, failed, passing, memo)) is not None]
        if found:
            moves.append(min(found, key=lambda m: abs(m.distance)))
    out += sorted(moves, key=lambda m: abs(m.distance))
    return tuple(out)
