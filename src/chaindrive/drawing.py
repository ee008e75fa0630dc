"""Drawings for the workshop, as DXF (ezdxf, model units mm, 1:1) or SVG (the same DXF
document rendered by ezdxf's drawing add-on).

* :func:`layout_document` — the contour at its coordinates: pitch and tip circles, the
  chain, the centre distance between consecutive sprockets and each wrap angle dimensioned,
  a table of the centres and a title block (drive, chain, links, date, chaindrive version);
* :func:`sprocket_document` — the manufacturing drawing of one sprocket: the toothed outline
  as ONE closed polyline (layer ``OUTLINE``: what a laser cutter or a CNC takes), the bore
  (``BORE``), the largest hub that clears the chain (``HUB``, dashed), the pitch circle,
  diameter dimensions with the limits of the tooth-form standard, a table of the tooth form
  and a title block;
* :func:`drawing_document` — the layout and, below it, every sprocket's drawing in rows on
  one sheet (what ``chaindrive draw`` writes without ``--sprocket``).

Tooth outlines, forms and bodies come from the analysis
(:attr:`chaindrive.analysis.Analysis.profiles`, :mod:`chaindrive.geometry.profile`): the
ISO 606 outline lies between the two tooth-gap forms of the standard, its root within the
root-diameter tolerance d_f = d − d₁ (upper deviation 0) [ISO606]; the GOST 591 outline is
the profile of GOST 591-69 drawn without the offset e of the root-arc centres, which the
standard permits [GOST591]. The bore is the 0.19·z·p/π of the body proportions the mass
model uses [MultimassChainDrives, §3.4]; the hub limit is ISO 606's absolute maximum shroud
(hub) diameter d_g = p·cot(180°/z) − 1.04·h₂ − 0.76 mm [ISO606]. Layers: ``OUTLINE``,
``BORE``, ``HUB``, ``PITCH``, ``TIP``, ``CHAIN``, ``CENTER``, ``BODY`` (polymeric bodies),
``DIM``, ``TEXT``, ``FRAME``.

Placement: no text, table or title block is drawn over another, over a sprocket or across
a chain line. Every text's box is known before it is drawn (the width by ezdxf's measure of
the font, the height from the cap height down to the descender, as ``ezdxf.bbox`` reads it
back); a dimension's text is read from the block ezdxf renders. The layout places the wrap
angles, then the centre distances (beside their sprockets, outward first), then the
sprockets' names, each where it meets nothing drawn before (or, failing that, the least);
the centre table and the title block go below the contour. A sprocket's drawing is the
face view with its diameters, the notes to the right of it and the title block below the
notes (a polymeric body's section to the left); the sheets are set in rows below the layout.
"""

from __future__ import annotations

import datetime as _dt
import functools
import itertools
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

import chaindrive
from chaindrive.display import dimension
from chaindrive.errors import DesignError
from chaindrive.io.atomic import write_bytes
from chaindrive.units import TWO_PI

if TYPE_CHECKING:  # ezdxf is imported where a drawing is made
    from ezdxf.document import Drawing
    from ezdxf.entities import Dimension, DXFGraphic, Text
    from ezdxf.fonts.fonts import AbstractFont
    from ezdxf.layouts import Modelspace

    from chaindrive.analysis import Analysis
    from chaindrive.geometry.profile import SprocketProfile
    from chaindrive.geometry.results import SprocketGeometry
    from chaindrive.geometry.sprocket import Gost591ToothForm, PolymericProportions, ToothForm

__all__ = ["FORMATS", "LAYERS", "drawing_document", "layout_document",
           "outline_mm", "sprocket_document", "svg_string", "tooth_form_lines",
           "write_drawing"]

MM = 1e3  # metres → millimetres
LAYERS = {"OUTLINE": 7, "BORE": 7, "HUB": 8, "PITCH": 3, "TIP": 8, "CHAIN": 5, "CENTER": 1,
          "BODY": 30, "DIM": 6, "TEXT": 7, "FRAME": 7}
FORMATS = (".dxf", ".svg")

Box = tuple[float, float, float, float]  # x0, y0, x1, y1 [mm]
Point = tuple[float, float]
Segment = tuple[Point, Point]
Disc = tuple[float, float, float]  # centre x, y and radius [mm]


def outline_mm(profile: SprocketProfile) -> NDArray[np.float64]:
    """The toothed outline [mm] of a profile as one closed polyline, centred at 0, without
    repeated points (consecutive points closer than 1 µm are merged, and the last point is
    not the first again: the polyline is closed by its flag).

    Parameters
    ----------
    profile : SprocketProfile
        The sprocket's tooth profile (tip, root, seating and flank arcs).

    Returns
    -------
    ndarray
        (K, 2) points of the outline [mm].

    References
    ----------
    [ISO606], [GOST591] (the tooth forms).
    """
    pts = np.asarray(profile.outline, dtype=float) * MM
    step = np.hypot(*np.diff(pts, axis=0, append=pts[:1]).T)
    out: NDArray[np.float64] = pts[step > 1e-3]
    return out


# --- boxes, discs and lines ------------------------------------------------------------------

def _union(boxes: Iterable[Box]) -> Box:
    b = list(boxes)
    return (min(x[0] for x in b), min(x[1] for x in b), max(x[2] for x in b),
            max(x[3] for x in b))


def _grow(b: Box, margin: float) -> Box:
    return b[0] - margin, b[1] - margin, b[2] + margin, b[3] + margin


def _disc_box(d: Disc) -> Box:
    return d[0] - d[2], d[1] - d[2], d[0] + d[2], d[1] + d[2]


def _segment_box(s: Segment) -> Box:
    (x0, y0), (x1, y1) = s
    return min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)


def _boxes_meet(a: Box, b: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Does box ``a`` overlap each of the (N, 4) boxes ``b`` (touching is not)?"""
    out: NDArray[np.bool_] = ((a[0] < b[:, 2]) & (b[:, 0] < a[2]) & (a[1] < b[:, 3])
                              & (b[:, 1] < a[3]))
    return out


def _box_meets_discs(b: Box, d: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Does box ``b`` reach into each of the (N, 3) discs ``d``?"""
    dx = np.maximum(np.maximum(b[0] - d[:, 0], 0.0), d[:, 0] - b[2])
    dy = np.maximum(np.maximum(b[1] - d[:, 1], 0.0), d[:, 1] - b[3])
    out: NDArray[np.bool_] = dx * dx + dy * dy < d[:, 2] ** 2
    return out


def _segments_meet_boxes(p: NDArray[np.float64], q: NDArray[np.float64],
                         b: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Does segment p–q pass through the inside of box b (arrays (…, 2), (…, 2), (…, 4),
    broadcast)? Their extents overlap and the box's corners lie on both sides of the line."""
    lo, hi = np.minimum(p, q), np.maximum(p, q)
    overlap = ((lo[..., 0] < b[..., 2]) & (b[..., 0] < hi[..., 0])
               & (lo[..., 1] < b[..., 3]) & (b[..., 1] < hi[..., 1]))
    d = q - p
    sides = np.stack([d[..., 0] * (b[..., j] - p[..., 1]) - d[..., 1] * (b[..., i] - p[..., 0])
                      for i, j in ((0, 1), (2, 1), (2, 3), (0, 3))])
    out: NDArray[np.bool_] = overlap & ~((sides >= 0).all(axis=0) | (sides <= 0).all(axis=0))
    return out


def _segments_cross(p1: NDArray[np.float64], q1: NDArray[np.float64],
                    p2: NDArray[np.float64], q2: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Do segments p1–q1 and p2–q2 cross (arrays (…, 2), broadcast; touching is not)?"""
    def side(a: NDArray[np.float64], b: NDArray[np.float64],
             c: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.sign((b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1])
                       - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0]))

    out: NDArray[np.bool_] = ((side(p1, q1, p2) * side(p1, q1, q2) < 0)
                              & (side(p2, q2, p1) * side(p2, q2, q1) < 0))
    return out


def _segments_meet_discs(p: NDArray[np.float64], q: NDArray[np.float64],
                         d: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Does segment p–q come into each of the (N, 3) discs ``d``?"""
    v = q - p
    t = np.clip(((d[:, :2] - p) @ v) / max(float(v @ v), 1e-300), 0.0, 1.0)
    near = p + t[:, None] * v
    out: NDArray[np.bool_] = np.hypot(*(near - d[:, :2]).T) < d[:, 2]
    return out


@dataclass
class _Sheet:
    """What is drawn on a sheet so far [mm] — text and table boxes, sprockets (discs) and
    lines — for placing what comes next where it meets none of them (or the fewest)."""

    gap: float
    boxes: list[Box] = field(default_factory=list)
    discs: list[Disc] = field(default_factory=list)
    lines: list[Segment] = field(default_factory=list)

    def cost(self, boxes: Sequence[Box] = (), lines: Sequence[Segment] = ()) -> int:
        """How much new text ``boxes`` and ``lines`` meet: 100 for a text over a text, a
        table or a sprocket, 10 for a text across a line or a line across a text or a
        sprocket, 2 for a line across a line."""
        b = np.asarray(self.boxes, dtype=float).reshape(-1, 4)
        d = np.asarray(self.discs, dtype=float).reshape(-1, 3)
        seg = np.asarray(self.lines, dtype=float).reshape(-1, 4)
        cost = 0
        for box in boxes:
            g = _grow(box, self.gap)
            cost += 100 * int(_boxes_meet(g, b).sum() + _box_meets_discs(g, d).sum())
            cost += 10 * int(_segments_meet_boxes(seg[:, :2], seg[:, 2:], np.asarray(g)).sum())
        for (x0, y0), (x1, y1) in lines:
            p, q = np.array([x0, y0]), np.array([x1, y1])
            cost += 10 * int(_segments_meet_boxes(p, q, b).sum()
                             + _segments_meet_discs(p, q, d).sum())
            cost += 2 * int(_segments_cross(p, q, seg[:, :2], seg[:, 2:]).sum())
        return cost

    def extents(self) -> Box:
        """The box of everything on the sheet."""
        return _union([*self.boxes, *map(_disc_box, self.discs), *map(_segment_box, self.lines)])


# --- texts ------------------------------------------------------------------------------------

@functools.lru_cache(maxsize=8)
def _font(name: str) -> AbstractFont:
    from ezdxf.fonts import fonts

    return fonts.make_font(name, 1.0)


_FONT = "txt"  # the font of the style "Standard" of ezdxf.new(setup=True): what TEXT uses


def _text_box(text: str, at: tuple[float, float], height: float,
             align: str = "MIDDLE_LEFT") -> Box:
    """The box [mm] a TEXT entity of the drawings takes (style Standard): its width as ezdxf
    measures the font, its height from the descender to the cap height — the box
    ``ezdxf.bbox`` reads back.

    Parameters
    ----------
    text : str
        The text.
    at : tuple of float
        Its placement point (x, y) [mm].
    height : float
        Cap height [mm].
    align : str
        The ezdxf ``TextEntityAlignment`` name of the placement: "LEFT", "CENTER", "RIGHT"
        (on the baseline) or "BOTTOM_…", "MIDDLE_…", "TOP_…" ("ALIGNED", "FIT" and
        "MIDDLE" are not used by the drawings).

    Returns
    -------
    tuple of float
        (x0, y0, x1, y1) [mm].
    """
    font = _font(_FONT)
    width = font.text_width(text) * height
    descent = font.measurements.descender_height * height
    vertical, _, horizontal = align.rpartition("_")  # "LEFT": on the baseline
    x0 = at[0] - {"LEFT": 0.0, "CENTER": 0.5, "RIGHT": 1.0}.get(horizontal, 0.0) * width
    base = at[1] - {"MIDDLE": 0.5 * height, "BOTTOM": -descent, "TOP": height}.get(vertical, 0.0)
    return x0, base - descent, x0 + width, base + height


def _text(msp: Modelspace, text: str, at: tuple[float, float], height: float,
          align: str = "MIDDLE_LEFT", layer: str = "TEXT") -> Box:
    """Draw a TEXT; returns its box [mm] (:func:`_text_box`)."""
    from ezdxf.enums import TextEntityAlignment

    entity: Text = msp.add_text(text, height=height, dxfattribs={"layer": layer})
    entity.set_placement(at, align=TextEntityAlignment[align])
    return _text_box(text, at, height, align)


def _text_lines(msp: Modelspace, lines: Sequence[str], top_left: Point, height: float,
                spacing: float) -> Box:
    """Lines of text, left-aligned, the first one's top at ``top_left``; returns the box."""
    x, y = top_left
    return _union(_text(msp, line, (x, y - 0.5 * height - spacing * i), height)
                  for i, line in enumerate(lines))


def _dimension_text_boxes(dim: Dimension) -> list[Box]:
    """Boxes [mm] of the texts of a rendered dimension (its block is drawn in WCS)."""
    from ezdxf import bbox

    out = []
    for e in dim.get_geometry_block() or ():
        if e.dxftype() in ("MTEXT", "TEXT"):
            ext = bbox.extents([e])
            out.append((ext.extmin.x, ext.extmin.y, ext.extmax.x, ext.extmax.y))
    return out


def _discard(msp: Modelspace, entities: Iterable[DXFGraphic]) -> None:
    """Remove entities drawn for a placement that was not taken (a dimension with its
    block)."""
    for e in entities:
        name = e.dxf.get("geometry") if e.dxftype() == "DIMENSION" else None
        msp.delete_entity(e)
        if name and msp.doc is not None and name in msp.doc.blocks:
            msp.doc.blocks.delete_block(name, safe=False)


# --- DXF helpers ---------------------------------------------------------------------------

def _new_document() -> Drawing:
    import ezdxf

    doc = ezdxf.new("R2010", setup=True, units=4)
    for name, colour in LAYERS.items():
        doc.layers.add(name, color=colour)
    doc.layers.get("PITCH").dxf.linetype = "CENTER"
    doc.layers.get("CENTER").dxf.linetype = "CENTER"
    doc.layers.get("HUB").dxf.linetype = "DASHED"
    return doc


def _centre_mark(msp: Modelspace, c: tuple[float, float], size: float) -> None:
    msp.add_line((c[0] - size, c[1]), (c[0] + size, c[1]), dxfattribs={"layer": "CENTER"})
    msp.add_line((c[0], c[1] - size), (c[0], c[1] + size), dxfattribs={"layer": "CENTER"})


def _dim_override(h: float, decimals: int = 2) -> dict[str, Any]:
    return {"dimtxt": h, "dimasz": 0.8 * h, "dimdec": decimals, "dimlfac": 1.0,
            "dimtad": 1, "dimgap": 0.3 * h}


def _title_block(msp: Modelspace, top_left: Point, h: float,
                 rows: list[tuple[str, str]]) -> Box:
    """A title block with its upper left corner at ``top_left`` [mm]: a framed table of
    (label, value) rows, the columns as wide as their longest text; returns its box."""
    width = _title_size(h, rows)[0]
    font = _font(_FONT)
    label_w = h + 0.8 * h * max(font.text_width(a) for a, _ in rows)
    row = 1.8 * h
    x0, y1 = top_left
    x1, y0 = x0 + width, y1 - row * len(rows)
    msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                       dxfattribs={"layer": "FRAME"})
    msp.add_line((x0 + label_w, y0), (x0 + label_w, y1), dxfattribs={"layer": "FRAME"})
    for i, (label, value) in enumerate(rows):
        y = y1 - (i + 0.5) * row
        if i:
            msp.add_line((x0, y1 - i * row), (x1, y1 - i * row), dxfattribs={"layer": "FRAME"})
        _text(msp, label, (x0 + 0.5 * h, y), 0.8 * h)
        _text(msp, value, (x0 + label_w + 0.5 * h, y), 0.8 * h if i else h)
    return x0, y0, x1, y1


def _title_size(h: float, rows: list[tuple[str, str]]) -> tuple[float, float]:
    """(width, height) [mm] of a title block (:func:`_title_block`)."""
    font = _font(_FONT)
    label_w = h + 0.8 * h * max(font.text_width(a) for a, _ in rows)
    value_w = h + h * max(font.text_width(b) * (0.8 if i else 1.0)
                          for i, (_, b) in enumerate(rows))
    return label_w + value_w, 1.8 * h * len(rows)


def _stamp(analysis: Analysis) -> list[tuple[str, str]]:
    """The rows every title block starts with."""

    return [("drive", analysis.drive.name),
            ("date", _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d")),
            ("drawn by", f"chaindrive {chaindrive.__version__}"),
            ("units", "mm, scale 1:1")]


# --- the layout ------------------------------------------------------------------------------

def _layout_entities(msp: Modelspace, analysis: Analysis, sheet: _Sheet) -> None:
    """Pitch and tip circles, centre marks and the chain [mm]; the tip circles and the
    chain's spans go on ``sheet``."""
    for s in analysis.geometry.sprockets:
        c = (s.x * MM, s.y * MM)
        msp.add_circle(c, s.pitch_radius * MM, dxfattribs={"layer": "PITCH"})
        msp.add_circle(c, s.tip_diameter / 2 * MM, dxfattribs={"layer": "TIP"})
        _centre_mark(msp, c, 0.25 * s.pitch_radius * MM)
        a0, a1 = _tangent_angles(s)
        start, end = (a0, a1) if s.turn > 0 else (a1, a0)  # DXF arcs run counter-clockwise
        if s.wrap_angle > 1e-9:
            msp.add_arc(c, s.pitch_radius * MM, start, end, dxfattribs={"layer": "CHAIN"})
        sheet.discs.append((c[0], c[1], s.tip_diameter / 2 * MM))
    for sp in analysis.geometry.spans:
        a = (sp.start_point[0] * MM, sp.start_point[1] * MM)
        b = (sp.end_point[0] * MM, sp.end_point[1] * MM)
        msp.add_line(a, b, dxfattribs={"layer": "CHAIN"})
        sheet.lines.append((a, b))


def _tangent_angles(s: SprocketGeometry) -> tuple[float, float]:
    """Angles [°] of the arriving and leaving tangent points seen from the centre."""
    a0 = math.degrees(math.atan2(s.arrive[1] - s.y, s.arrive[0] - s.x))
    a1 = math.degrees(math.atan2(s.leave[1] - s.y, s.leave[0] - s.x))
    return a0, a1


def _arc_segments(c: Point, r: float, start: float, end: float) -> list[Segment]:
    """The arc [mm] from ``start`` counter-clockwise to ``end`` [°] as a few chords."""
    sweep = (end - start) % 360.0
    t = np.radians(start + np.linspace(0.0, sweep, max(2, int(sweep / 10) + 2)))
    pts = [(c[0] + r * math.cos(a), c[1] + r * math.sin(a)) for a in t]
    return list(itertools.pairwise(pts))


def _wrap_dimensions(msp: Modelspace, analysis: Analysis, h: float, sheet: _Sheet) -> None:
    """The wrap angle of each sprocket: an angular dimension on an arc outside its tip,
    moved outwards while that clears what is drawn (:func:`_place`). On an arc too short for the text
    and both arrows, the text stands higher above the arc (clear of the arrows)."""
    for s in analysis.geometry.sprockets:
        if s.wrap_angle < math.radians(1.0):
            continue
        a0, a1 = _tangent_angles(s)
        start, end = (a0, a1) if s.turn > 0 else (a1, a0)
        c = (s.x * MM, s.y * MM)
        width = _box_size(_text_box(f"{math.degrees(s.wrap_angle):.2f}°", c, h))[0]

        def draw(step: int, c: Point = c, s: SprocketGeometry = s, start: float = start,
                 end: float = end, width: float = width
                 ) -> tuple[list[DXFGraphic], list[Box], list[Segment]]:
            radius = s.tip_diameter / 2 * MM + (1.5 + 1.5 * step) * h
            short = (radius + 0.5 * h) * s.wrap_angle < width + 2.6 * h
            override = {**_dim_override(h, 1), "dimaunit": 0}
            if short:
                override["dimgap"] = 0.9 * h
            dim = msp.add_angular_dim_cra(
                center=c, radius=radius, start_angle=start, end_angle=end, distance=0.5 * h,
                dimstyle="EZDXF", override=override, dxfattribs={"layer": "DIM"})
            dim.render()
            ends = [((c[0] + radius * math.cos(math.radians(a)),
                      c[1] + radius * math.sin(math.radians(a))),
                     (c[0] + (radius + h) * math.cos(math.radians(a)),
                      c[1] + (radius + h) * math.sin(math.radians(a)))) for a in (start, end)]
            return ([dim.dimension], _dimension_text_boxes(dim.dimension),
                    [*_arc_segments(c, radius + 0.5 * h, start, end), *ends])

        _place(msp, sheet, draw, [(0.5 * step, step) for step in range(6)])


_Draw = Callable[[Any], tuple[list["DXFGraphic"], list[Box], list[Segment]]]


def _place(msp: Modelspace, sheet: _Sheet, draw: _Draw,
           options: Iterable[tuple[float, Any]]) -> None:
    """Draw a dimension at the option of the least cost on the sheet plus the option's
    penalty (how far it is from where it belongs); ``options`` are (penalty, option) and
    ``draw(option)`` draws it and returns (the entities drawn, the text boxes, the lines).
    Options are tried by penalty until none left can do better; the kept one goes on the
    sheet, the others are removed."""
    best: tuple[float, list[DXFGraphic], list[Box], list[Segment]] | None = None
    for penalty, option in sorted(options, key=lambda o: o[0]):
        if best is not None and best[0] <= penalty:
            break
        entities, boxes, lines = draw(option)
        total = sheet.cost(boxes, lines) + penalty
        if best is None or total < best[0]:
            if best is not None:
                _discard(msp, best[1])
            best = (total, entities, boxes, lines)
        else:
            _discard(msp, entities)
    assert best is not None  # options is never empty
    sheet.boxes.extend(best[2])
    sheet.lines.extend(best[3])


def _centre_distances(msp: Modelspace, analysis: Analysis, h: float, sheet: _Sheet) -> None:
    """The centre distance between consecutive sprockets: an aligned dimension beside the
    two sprockets, its line clear of both and its extension lines drawn from each tip
    circle (the dimension's own are suppressed); outwards of the contour unless inwards
    meets much less, as close as what is drawn lets it (:func:`_place`)."""
    g = analysis.geometry
    pts = [(s.x * MM, s.y * MM) for s in g.sprockets]
    radii = [s.tip_diameter / 2 * MM for s in g.sprockets]
    cx, cy = np.mean(pts, axis=0)
    n = len(pts)
    for i in range(n if n > 2 else 1):
        j = (i + 1) % n
        (p1, r1), (p2, r2) = sorted(((pts[i], radii[i]), (pts[j], radii[j])))  # text upright
        length = math.dist(p1, p2)
        if length < 1e-9:
            continue
        left = (-(p2[1] - p1[1]) / length, (p2[0] - p1[0]) / length)  # ezdxf's + side
        mid = ((p1[0] + p2[0]) / 2 - cx, (p1[1] + p2[1]) / 2 - cy)
        outward = 1.0 if left[0] * mid[0] + left[1] * mid[1] >= 0 else -1.0

        def draw(option: tuple[float, int], p1: Point = p1, p2: Point = p2, r1: float = r1,
                 r2: float = r2, left: Point = left
                 ) -> tuple[list[DXFGraphic], list[Box], list[Segment]]:
            side, step = option
            offset = side * (max(r1, r2) + (1.5 + 1.5 * step) * h)
            dim = msp.add_aligned_dim(p1=p1, p2=p2, distance=offset, dimstyle="EZDXF",
                                      override={**_dim_override(h), "dimse1": 1, "dimse2": 1},
                                      dxfattribs={"layer": "DIM"})
            dim.render()

            def at(p: Point, d: float) -> Point:
                return p[0] + left[0] * d, p[1] + left[1] * d

            ext = [(at(p, side * (r + 0.5 * h)), at(p, offset + side * 0.6 * h))
                   for p, r in ((p1, r1), (p2, r2))]
            drawn = [msp.add_line(a, b, dxfattribs={"layer": "DIM"}) for a, b in ext]
            return ([dim.dimension, *drawn], _dimension_text_boxes(dim.dimension),
                    [(at(p1, offset), at(p2, offset)), *ext])

        _place(msp, sheet, draw, [(0.5 * step + (3.0 if side != outward else 0.0), (side, step))
                                  for side in (outward, -outward) for step in range(8)])


def _sprocket_names(msp: Modelspace, analysis: Analysis, h: float, sheet: _Sheet) -> None:
    """Each sprocket's name and teeth beside its tip circle: above it if that is free,
    else below, else the first free place around it."""
    angles = (90, 270, 45, 135, 315, 225, 0, 180, 67.5, 112.5, 292.5, 247.5, 22.5, 157.5,
              337.5, 202.5)
    for s in analysis.geometry.sprockets:
        text = f"{s.name}  z = {s.teeth}"
        lift = _text_box(text, (0.0, 0.0), h, "MIDDLE_CENTER")
        w, hb = _box_size(lift)
        best: tuple[int, Point, Box] | None = None
        for step in range(6):
            for angle in angles:
                u = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
                reach = (s.tip_diameter / 2 * MM + (0.5 + 1.5 * step) * h
                         + abs(u[0]) * w / 2 + abs(u[1]) * hb / 2)
                # the box centred at c + u·reach: the placement point is off the box centre
                bx, by = s.x * MM + u[0] * reach, s.y * MM + u[1] * reach
                at = (bx - (lift[0] + lift[2]) / 2, by - (lift[1] + lift[3]) / 2)
                box = _text_box(text, at, h, "MIDDLE_CENTER")
                cost = sheet.cost([box])
                if best is None or cost < best[0]:
                    best = (cost, at, box)
                if cost == 0:
                    break
            if best is not None and best[0] == 0:
                break
        assert best is not None
        sheet.boxes.append(_text(msp, text, best[1], h, "MIDDLE_CENTER"))


def _box_size(b: Box) -> tuple[float, float]:
    return b[2] - b[0], b[3] - b[1]


def _centre_table(msp: Modelspace, analysis: Analysis, top_left: Point, h: float) -> Box:
    """The sprockets' centres and pitch diameters as text lines below ``top_left`` [mm];
    returns their box."""
    lines = [f"{s.name}: z = {s.teeth}, x = {dimension(s.x * MM)}, y = {dimension(s.y * MM)}, "
             f"d = {dimension(s.pitch_diameter * MM)}" for s in analysis.geometry.sprockets]
    head = _text(msp, "Sprocket centres (mm): name, teeth, x, y, pitch diameter",
                 (top_left[0], top_left[1] - 0.5 * h), h)
    rest = _text_lines(msp, lines, (top_left[0], top_left[1] - 1.6 * h), 0.9 * h, 1.6 * h)
    return _union([head, rest]) if lines else head


def _layout_sheet(msp: Modelspace, analysis: Analysis, h: float) -> Box:
    """The layout with its dimensions, centre table and title block; returns its box [mm]."""
    g = analysis.geometry
    sheet = _Sheet(gap=0.3 * h)
    _layout_entities(msp, analysis, sheet)
    _wrap_dimensions(msp, analysis, h, sheet)
    _centre_distances(msp, analysis, h, sheet)
    _sprocket_names(msp, analysis, h, sheet)
    x0, y0, x1, _ = box = sheet.extents()
    table = _centre_table(msp, analysis, (x0, y0 - 2 * h), h)
    spec = analysis.drive.chain.spec
    rows = [("chain drive layout", analysis.drive.name),
            ("chain", spec.designation),
            ("links", f"{g.links} (length {dimension(g.chain_length * MM, 1)} mm)"),
            ("tooth form", analysis.drive.tooth_form), *_stamp(analysis)[1:]]
    width, _ = _title_size(h, rows)
    if x1 - width >= table[2] + 3 * h:  # beside the table, right-aligned with the contour
        title = _title_block(msp, (x1 - width, y0 - 2 * h), h, rows)
    else:  # below it
        title = _title_block(msp, (max(x1, table[0] + width) - width, table[1] - 2 * h), h,
                             rows)
    return _union([box, table, title])


def layout_document(analysis: Analysis) -> Drawing:
    """The layout drawing alone (ezdxf document, mm).

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design (geometry, sprocket profiles).

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm.
    """
    doc = _new_document()
    _layout_sheet(doc.modelspace(), analysis, _text_height(analysis))
    return doc


def _text_height(analysis: Analysis) -> float:
    """Text height [mm] of a layout: 1/40 of the largest tip diameter or 1/150 of the
    contour's extent, at least 2.5 mm."""
    biggest = max(s.tip_diameter for s in analysis.geometry.sprockets) * MM
    span = max(np.ptp([s.x for s in analysis.geometry.sprockets]),
               np.ptp([s.y for s in analysis.geometry.sprockets])) * MM
    return float(max(2.5, round(max(biggest / 40, float(span) / 150), 1)))


def _sheet_text_height(tip_diameter: float) -> float:
    """Text height [mm] of a sprocket's drawing: 1/40 of the tip diameter [mm], at least
    2.5 mm."""
    return float(max(2.5, round(tip_diameter / 40, 1)))


# --- one sprocket ------------------------------------------------------------------------------

def _root_tolerance(profile: SprocketProfile) -> str:
    """The ISO 606 deviations of the root diameter as written: "0 / −0.25" or, for a class
    of ISO 286, "h11 (0 / −0.320)"."""
    grade = profile.root_tolerance_class
    upper, lower = (x * MM for x in profile.root_deviations)
    places = 3 if grade else 2

    def signed(x: float) -> str:
        return "0" if x == 0 else f"{'+' if x > 0 else '−'}{dimension(abs(x), places)}"

    text = f"{signed(upper)} / {signed(lower)}"
    return f"{grade} ({text})" if grade else text


def _drawn_root(profile: SprocketProfile) -> float:
    """The root diameter [mm] of the drawn outline (its smallest diameter)."""
    return 2 * float(np.min(np.hypot(*outline_mm(profile).T)))


def tooth_form_lines(profile: SprocketProfile) -> list[str]:
    """The tooth form as a drawing states it: each dimension by its name, symbol and value
    [mm, °], toleranced as the standard limits it.

    Parameters
    ----------
    profile : SprocketProfile
        The sprocket's tooth profile.

    Returns
    -------
    list of str
        One line per dimension.

    References
    ----------
    [ISO606], [GOST591] (the dimensions and their limits).
    """
    d = dimension
    if profile.standard == "GOST 591":
        form = cast("Gost591ToothForm", profile.form)
        deg = math.degrees
        return [f"Tooth form GOST 591-69, z = {form.teeth}, λ = p/d1 = {form.lam:.3f}, "
                f"K = {form.K:g}",
                f"Pitch diameter d = {d(form.pitch_diameter * MM, 3)}",
                f"Tip diameter De = {d(form.tip_diameter * MM, 1)} (to 0.1 mm)",
                f"Root diameter Di = {d(form.root_diameter * MM, 3)} (d − 2 r)",
                f"Seating radius r = {d(form.seating_radius * MM, 3)}",
                f"Joining radius r1 = {d(form.joining_radius * MM, 3)}",
                f"Head radius r2 = {d(form.head_radius * MM, 3)}",
                f"Half space angle α = {deg(form.half_space_angle):.2f}°, joining angle "
                f"β = {deg(form.joining_angle):.2f}°, half tooth angle "
                f"φ = {deg(form.half_tooth_angle):.2f}°",
                f"Straight part FC = {d(form.straight_part * MM, 3)}, OO2 = "
                f"{d(form.head_centre_distance * MM, 3)}",
                f"Measuring chord Lx = {d(form.measuring_chord * MM, 3)}"
                f"{' (odd z)' if form.teeth % 2 else ' (across the roots)'}",
                f"Rim width b = {d(form.rim_width * MM, 2)}",
                "Drawn without the root-arc offset e = 0.03 p (GOST 591-69 permits it).",
                "GOST 591-69 §2 tolerances: not compiled here, agree with the workshop."]
    f = cast("ToothForm", profile.form)
    df = f.root_diameter * MM
    upper, lower = (x * MM for x in profile.root_deviations)
    root = _drawn_root(profile)
    return [f"Tooth form ISO 606, z = {f.teeth} (drawn: re and α the means of the two "
            f"tooth-gap forms, ri = {d((f.pitch_diameter * MM - root) / 2, 3)})",
            f"Pitch diameter d = {d(f.pitch_diameter * MM, 3)}",
            f"Tip diameter da = {d(f.tip_diameter_min * MM, 3)} … {d(f.tip_diameter_max * MM, 3)}",
            f"Root diameter df = {d(df, 3)} (d − d1), deviations {_root_tolerance(profile)}: "
            f"{d(df + lower, 3)} … {d(df + upper, 3)} (drawn {d(root, 3)})",
            f"Roller seating d − 2 ri = {d(f.root_diameter_min * MM, 3)} … "
            f"{d(f.root_diameter_max * MM, 3)} (ri max … ri min; the bottom of the two "
            "tooth-gap forms)",
            f"Seating radius ri = {d(f.seating_radius_min * MM, 3)} … "
            f"{d(f.seating_radius_max * MM, 3)}",
            f"Seating angle α = {math.degrees(f.seating_angle_min):.2f}° … "
            f"{math.degrees(f.seating_angle_max):.2f}°",
            f"Flank radius re = {d(f.flank_radius_min * MM, 2)} … {d(f.flank_radius_max * MM, 2)}",
            f"Tooth width bf1 = {d(f.tooth_width * MM, 2)}, side relief ba = "
            f"{d(f.side_relief_min * MM, 2)} … {d(f.side_relief_max * MM, 2)}, "
            f"side radius rx = {d(f.side_radius * MM, 2)}",
            "The gap must lie between the minimum form (ri min, re max, α max) and the "
            "maximum form (ri max, re min, α min)."]


def _sprocket_sheet(msp: Modelspace, analysis: Analysis, index: int, h: float) -> Box:
    """The drawing of sprocket ``index`` with its centre at the origin: the face view with
    its diameters, the notes to the right of it, the title block below the notes and, for
    a polymeric body, its section to the left; returns the box it takes [mm]."""
    from ezdxf import bbox

    g = analysis.geometry.sprockets[index]
    profile = analysis.profiles[index]
    spec = analysis.drive.chain.spec
    origin = (0.0, 0.0)
    pts = outline_mm(profile)
    msp.add_lwpolyline(pts.tolist(), close=True, dxfattribs={"layer": "OUTLINE"})
    ra = float(np.max(np.hypot(pts[:, 0], pts[:, 1])))
    root = float(np.min(np.hypot(pts[:, 0], pts[:, 1])))
    bore = profile.bore_diameter * MM
    hub = profile.hub_limit_diameter * MM
    msp.add_circle(origin, bore / 2, dxfattribs={"layer": "BORE"})
    if hub > bore:
        msp.add_circle(origin, hub / 2, dxfattribs={"layer": "HUB"})
    msp.add_circle(origin, g.pitch_diameter / 2 * MM, dxfattribs={"layer": "PITCH"})
    _centre_mark(msp, origin, 1.1 * ra)
    tip_text, root_text = _limits_text(profile)
    dims = []
    for radius, angle, text in ((g.pitch_diameter / 2 * MM, 30.0, "<>"), (ra, 70.0, tip_text),
                                (bore / 2, -35.0, "<>"), (root, -70.0, root_text)):
        dim = msp.add_diameter_dim(origin, radius=radius, angle=angle, dimstyle="EZ_RADIUS",
                                   override=_dim_override(0.8 * h), text=text,
                                   dxfattribs={"layer": "DIM"})
        if radius > bore / 2:  # the text outside the teeth, on the line's extension
            shown = text.replace("<>", f"%%c{dimension(2 * radius)}").replace("%%c", "Ø")
            width = _box_size(_text_box(shown, origin, 0.8 * h))[0]
            t = math.radians(angle + 180.0)  # the side ezdxf writes the text on
            dim.set_location(((ra + h + width / 2) * math.cos(t),
                              (ra + h + width / 2) * math.sin(t)), leader=False, relative=False)
        dim.render()
        dims.append(dim.dimension)
    ext = bbox.extents(dims)
    face = _union([(-1.1 * ra, -1.1 * ra, 1.1 * ra, 1.1 * ra),
                   (ext.extmin.x, ext.extmin.y, ext.extmax.x, ext.extmax.y)])
    boxes = [face]
    lines = [
        *tooth_form_lines(profile),
        f"Bore d0 = {dimension(bore, 1)} (0.19·z·p/π; fit to the shaft to be chosen)",
        f"Hub diameter at most dg = {dimension(hub, 1)} (ISO 606: p·cot(180°/z) − 1.04 h2 "
        "− 0.76 mm)", "Outline: one closed polyline on layer OUTLINE; bore on layer BORE."]
    if profile.body is not None:
        body_lines, section = _polymer_body(msp, profile, profile.body, face, h)
        lines += body_lines
        boxes.append(section)
    notes = _text_lines(msp, lines, (face[2] + 2 * h, ra), 0.75 * h, 1.5 * h)
    rows = [(f"sprocket {g.name}", f"{g.teeth} teeth"), ("chain", spec.designation),
            ("material", f"{profile.material} ({profile.density:.0f} kg/m³), mass "
                         f"{profile.mass.mass:.3g} kg"),
            ("tooth form", analysis.drive.tooth_form), *_stamp(analysis)]
    title = _title_block(msp, (notes[0], notes[1] - 1.5 * h), 0.8 * h, rows)
    return _union([*boxes, notes, title])


def _limits_text(profile: SprocketProfile) -> tuple[str, str]:
    """Text of the tip and root diameter dimensions with the standard's limits."""
    if profile.standard == "GOST 591":
        form = cast("Gost591ToothForm", profile.form)
        return (f"%%c{dimension(form.tip_diameter * MM, 1)}",
                f"%%c{dimension(form.root_diameter * MM, 3)}")
    iso = cast("ToothForm", profile.form)
    return (f"%%c{dimension(iso.tip_diameter_min * MM, 2)} … "
            f"{dimension(iso.tip_diameter_max * MM, 2)}",
            f"%%c{dimension(iso.root_diameter * MM, 2)} {_root_tolerance(profile)}")


def _polymer_body(msp: Modelspace, profile: SprocketProfile, p: PolymericProportions,
                  face: Box, h: float) -> tuple[list[str], Box]:
    """Face-view circles and, left of the face view's box ``face``, the axial half-section
    of a polymeric body [MultimassChainDrives, §3.4]; returns the text lines (mass, inertia,
    proportions) and the section's box."""
    centre = (0.0, 0.0)
    for d in (p.hub_outer_diameter, p.rim_inner_diameter):
        msp.add_circle(centre, d / 2 * MM, dxfattribs={"layer": "BODY"})
    hole = 0.5 * (p.rim_inner_diameter - p.hub_outer_diameter) / 2 * MM
    for k in range(6):
        a = TWO_PI * k / 6
        msp.add_circle((p.hole_circle_diameter / 2 * MM * math.cos(a),
                        p.hole_circle_diameter / 2 * MM * math.sin(a)), hole / 2,
                       dxfattribs={"layer": "BODY"})
    d = profile.form.pitch_diameter
    half = [(-p.hub_length / 2, p.bore_diameter / 2), (p.hub_length / 2, p.bore_diameter / 2),
            (p.hub_length / 2, p.hub_outer_diameter / 2),
            (p.web_thickness / 2, p.hub_outer_diameter / 2),
            (p.web_thickness / 2, p.rim_inner_diameter / 2),
            (p.rim_width / 2, p.rim_inner_diameter / 2), (p.rim_width / 2, d / 2),
            (-p.rim_width / 2, d / 2), (-p.rim_width / 2, p.rim_inner_diameter / 2),
            (-p.web_thickness / 2, p.rim_inner_diameter / 2),
            (-p.web_thickness / 2, p.hub_outer_diameter / 2),
            (-p.hub_length / 2, p.hub_outer_diameter / 2)]
    label = "Section A–A"
    at_top = d / 2 * MM + h
    label_w = _box_size(_text_box(label, (0.0, 0.0), 0.8 * h, "BOTTOM_CENTER"))[0]
    reach = max(p.hub_length * MM, max(abs(a) for a, _ in half) * MM)  # the centre line
    x0 = min(face[0] - 2 * h - reach, face[0] - 2 * h - label_w / 2)
    for sign in (1.0, -1.0):
        msp.add_lwpolyline([(x0 + a * MM, sign * r * MM) for a, r in half], close=True,
                           dxfattribs={"layer": "BODY"})
    msp.add_line((x0 - p.hub_length * MM, 0.0), (x0 + p.hub_length * MM, 0.0),
                 dxfattribs={"layer": "CENTER"})
    text = _text(msp, label, (x0, at_top), 0.8 * h, "BOTTOM_CENTER")
    section = _union([(x0 - reach, -d / 2 * MM, x0 + reach, d / 2 * MM), text])
    lines = [f"Polymeric body: mass = {profile.mass.mass:.4g} kg, inertia = "
             f"{profile.mass.moment_of_inertia:.4g} kg·m²",
             f"Hub Ø {dimension(p.hub_outer_diameter * MM, 1)} × "
             f"{dimension(p.hub_length * MM, 1)}, web {dimension(p.web_thickness * MM, 1)} "
             f"thick, rim from Ø {dimension(p.rim_inner_diameter * MM, 1)}, "
             f"{dimension(p.rim_width * MM, 1)} wide",
             f"Six lightening holes Ø {dimension(hole, 1)} on Ø "
             f"{dimension(p.hole_circle_diameter * MM, 1)}"]
    return lines, section


def _index_of(analysis: Analysis, name: str) -> int:
    names = [s.name for s in analysis.drive.sprockets]
    if name not in names:
        raise DesignError("--sprocket", f"no sprocket named {name!r}; the sprockets are "
                          f"{', '.join(names)}")
    return names.index(name)


def sprocket_document(analysis: Analysis, name: str) -> Drawing:
    """The manufacturing drawing of the sprocket ``name`` alone (ezdxf document, mm).

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design (geometry, sprocket profiles).
    name : str
        The sprocket's name.

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm.
    """
    i = _index_of(analysis, name)
    doc = _new_document()
    tip = analysis.geometry.sprockets[i].tip_diameter * MM
    _sprocket_sheet(doc.modelspace(), analysis, i, _sheet_text_height(tip))
    return doc


def drawing_document(analysis: Analysis) -> Drawing:
    """The layout and, below it, every sprocket's manufacturing drawing in rows no wider
    than the layout (or the widest drawing) (ezdxf document, mm).

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design (geometry, sprocket profiles).

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm.
    """
    doc = _new_document()
    msp = doc.modelspace()
    h = _text_height(analysis)
    layout = _layout_sheet(msp, analysis, h)
    hs = _sheet_text_height(max(s.tip_diameter for s in analysis.geometry.sprockets) * MM)
    sheets: list[tuple[list[DXFGraphic], Box]] = []
    for i in range(len(analysis.geometry.sprockets)):
        start = len(msp)
        box = _sprocket_sheet(msp, analysis, i, hs)
        sheets.append((list(msp)[start:], box))
    gap = 4 * hs
    width = max(layout[2] - layout[0], *(b[2] - b[0] for _, b in sheets))
    x, top = layout[0], layout[1] - 4 * h
    bottom = top
    for entities, box in sheets:
        if x > layout[0] and x + box[2] - box[0] > layout[0] + width:  # a new row
            x, top = layout[0], bottom - gap
        dx, dy = x - box[0], top - box[3]
        for e in entities:
            e.translate(dx, dy, 0.0)
        bottom = min(bottom, box[1] + dy)
        x += box[2] - box[0] + gap
    return doc


def write_drawing(analysis: Analysis, path: str | Path, *, sprocket: str | None = None
                  ) -> Path:
    """Write the drawing as DXF or SVG (by the suffix of ``path``): the layout with every
    sprocket, or with ``sprocket`` the manufacturing drawing of that sprocket alone. The
    file is written at once, after the whole drawing is made.

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design (geometry, sprocket profiles).
    path : str or Path
        The file to write; its suffix ``.dxf`` or ``.svg`` chooses the format.
    sprocket : str or None
        The name of one sprocket (None: the layout with every sprocket).

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    DesignError
        ``output`` with another suffix; ``--sprocket`` naming no sprocket of the drive.
    """
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in FORMATS:
        raise DesignError("output", f"must end in .dxf or .svg, got {out.name!r}")
    doc = (sprocket_document(analysis, sprocket) if sprocket is not None
           else drawing_document(analysis))
    if suffix == ".dxf":
        import io

        stream = io.StringIO()
        doc.write(stream)
        data = stream.getvalue().encode(doc.output_encoding or "utf-8")
    else:
        data = svg_string(doc).encode("utf-8")
    write_bytes(out, data)  # complete or absent, never half-written
    return out


def svg_string(doc: Drawing, page_width_mm: float = 420.0) -> str:
    """The modelspace of ``doc`` as SVG (ezdxf drawing add-on) on a white page
    ``page_width_mm`` wide (A3 by default), scaled to fit; the DXF stays 1:1.

    Parameters
    ----------
    doc : ezdxf.document.Drawing
        A DXF document.
    page_width_mm : float
        Width of the page [mm].

    Returns
    -------
    str
        The SVG text.
    """
    from ezdxf import bbox
    from ezdxf.addons.drawing import Frontend, RenderContext, config, layout, svg

    box = bbox.extents(doc.modelspace(), fast=True)
    w, h = (box.size.x, box.size.y) if box.has_data else (100.0, 100.0)
    backend = svg.SVGBackend()
    cfg = config.Configuration(background_policy=config.BackgroundPolicy.WHITE,
                               color_policy=config.ColorPolicy.COLOR)
    Frontend(RenderContext(doc), backend, config=cfg).draw_layout(doc.modelspace())
    page = layout.Page(page_width_mm, page_width_mm * h / max(w, 1e-9) + 20, layout.Units.mm,
                       margins=layout.Margins.all(10))
    return backend.get_string(page)
