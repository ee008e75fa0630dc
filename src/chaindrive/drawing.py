"""Drawings for the workshop, as DXF (ezdxf, model units mm, the object 1:1), SVG or PDF (the
same DXF document rendered by ezdxf's drawing add-on), each on a standard sheet.

* :func:`layout_document` — the contour at its coordinates: pitch and tip circles, the
  chain, the centre distance between consecutive sprockets and each wrap angle dimensioned,
  a table of the centres;
* :func:`sprocket_document` — the manufacturing drawing of one sprocket: the toothed outline
  as ONE closed polyline (layer ``OUTLINE``: what a laser cutter or a CNC takes), the bore
  (``BORE``) with its fit and the hub keyway (``KEYWAY``), the hub (``HUB``, dashed), the
  pitch circle, diameter dimensions with the limits of the tooth-form standard; the axial
  section A–A (``SECTION``, hatched on ``HATCH``) with the tooth width and chamfer, the hub
  and d + t2; the notes: tooth form, bore, keyway, hub, section, measurement over pins, tip
  diameter, material and hardening, general tolerances ISO 2768-m [ISO2768-1] (the values
  from :meth:`chaindrive.analysis.Analysis.workshop`);
* :func:`drawing_document` — the layout's sheet and, to its right, every sprocket's sheet
  (what ``chaindrive draw`` writes without ``--sprocket``).

Sheets: an ISO 5457 size (A4 upright, A3 … A0 landscape) drawn N times its size at the
largest ISO 5455 scale 1:N at which the drawing fits its frame above the ISO 7200 title
block (:func:`sheet_and_scale`); trimmed edge and frame on layer ``SHEET``, the title block
on ``FRAME`` [ISO5457], [ISO5455], [ISO7200].

Tooth outlines, forms and bodies come from the analysis
(:attr:`chaindrive.analysis.Analysis.profiles`, :mod:`chaindrive.geometry.profile`): the
ISO 606 outline lies between the two tooth-gap forms of the standard, its root within the
root-diameter tolerance d_f = d − d₁ (upper deviation 0) [ISO606]; the GOST 591 outline is
the profile of GOST 591-69 drawn without the offset e of the root-arc centres, which the
standard permits [GOST591]. The hub limit is ISO 606's absolute maximum shroud (hub)
diameter d_g = p·cot(180°/z) − 1.04·h₂ − 0.76 mm [ISO606]. Layers: ``OUTLINE``, ``BORE``,
``KEYWAY``, ``HUB``, ``PITCH``, ``TIP``, ``CHAIN``, ``CENTER``, ``BODY`` (polymeric
bodies), ``SECTION``, ``HATCH``, ``DIM``, ``TEXT``, ``FRAME``, ``SHEET``.

Placement: no text, table or title block is drawn over another, over a sprocket or across
a chain line. Every text's box is known before it is drawn (the width by ezdxf's measure of
the font, the height from the cap height down to the descender, as ``ezdxf.bbox`` reads it
back); a dimension's text is read from the block ezdxf renders. The layout places the wrap
angles, then the centre distances (beside their sprockets, outward first), then the
sprockets' names, each where it meets nothing drawn before (or, failing that, the least);
the centre table goes below the contour or beside it. A sprocket's drawing is the face view
with its diameters, the section to its right and the notes below both or beside them (a
polymeric body's section to the left); the title block sits in the frame's lower right
corner.

Signs: a TEXT writes the diameter, plus-minus and degree signs as the DXF control codes %%c,
%%p, %%d (:data:`DXF_CODES`), which every CAD program draws with the text style's font — the
style Standard's shape font "txt" has no glyph for the Unicode signs. The SVG draws them as
the glyphs (ezdxf's SVG backend, even-odd fill); the PDF fills every contour by its true
nesting (:func:`filled_path_orientation`), since the matplotlib backend of the add-on nests
contours by their bounding boxes and fills one of the two counters of Ø.
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
from chaindrive._docstrings import shared_parameters
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
    from chaindrive.geometry.workshop import SprocketWorkshop

__all__ = [
    "DXF_CODES",
    "FORMATS",
    "LAYERS",
    "drawing_document",
    "dxf_text",
    "filled_path_orientation",
    "layout_document",
    "outline_mm",
    "pdf_bytes",
    "sprocket_document",
    "svg_string",
    "tooth_form_lines",
    "write_drawing",
]

MM = 1e3  # metres → millimetres
LAYERS = {"OUTLINE": 7, "BORE": 7, "HUB": 8, "PITCH": 3, "TIP": 8, "CHAIN": 5, "CENTER": 1,
          "BODY": 30, "DIM": 6, "TEXT": 7, "FRAME": 7, "KEYWAY": 7, "SECTION": 7, "HATCH": 8,
          "SHEET": 7}
#: Text height on paper [mm] (ISO 3098: 3.5 for values, the notes at 0.75 of it); a
#: layout's dimensions and names at 2.5 (the smallest of ISO 3098's series on A4 … A0).
PAPER_TEXT = 3.5
LAYOUT_TEXT = 2.5
FORMATS = (".dxf", ".svg", ".pdf")
#: The signs a TEXT entity writes as DXF control codes (diameter %%c, plus-minus %%p, degree
#: %%d): every CAD program draws these with the font of the text style, also the shape font
#: "txt" of the style Standard, which has no glyph for the Unicode signs (a viewer shows "?").
DXF_CODES = {"Ø": "%%c", "±": "%%p", "°": "%%d"}
#: Largest deviation of a flattened curve from the curve [mm], for the nesting test of the
#: PDF's filled contours (a twentieth of the smallest text's stroke).
FLATTENING_MM = 0.005

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
    #: The three lists as (N, 4), (N, 3) and (N, 4) arrays with the lengths they were made
    #: at: the lists only grow, so equal lengths are equal contents.
    _arrays: tuple[tuple[int, int, int], tuple[NDArray[np.float64], NDArray[np.float64],
                   NDArray[np.float64]]] | None = field(default=None, repr=False, compare=False)

    def _as_arrays(self) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                  NDArray[np.float64]]:
        """The boxes, discs and lines as arrays, made again only after one was added (a
        layout asks the cost of a hundred places of each text against the same sheet)."""
        sizes = (len(self.boxes), len(self.discs), len(self.lines))
        if self._arrays is None or self._arrays[0] != sizes:
            self._arrays = sizes, (np.asarray(self.boxes, dtype=float).reshape(-1, 4),
                                   np.asarray(self.discs, dtype=float).reshape(-1, 3),
                                   np.asarray(self.lines, dtype=float).reshape(-1, 4))
        return self._arrays[1]

    def cost(self, boxes: Sequence[Box] = (), lines: Sequence[Segment] = ()) -> int:
        """How much new text ``boxes`` and ``lines`` meet: 100 for a text over a text, a
        table or a sprocket, 10 for a text across a line or a line across a text or a
        sprocket, 2 for a line across a line."""
        b, d, seg = self._as_arrays()
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


@dataclass(frozen=True)
class _Arrangements:
    """A drawing made on ``msp`` but for its last part (the notes of a sprocket, the centre
    table of a layout), which goes below it or to its right: ``last(msp, right)`` draws that
    part there (``msp`` None: draws nothing) and returns the box of the whole drawing [mm]."""

    msp: Modelspace
    last: Callable[[Modelspace | None, bool], Box]

    def box(self, right: bool) -> Box:
        """The box [mm] the drawing takes with its last part to the right (or below)."""
        return self.last(None, right)

    def finish(self, right: bool) -> Box:
        """Draw the last part to the right (or below); returns the drawing's box [mm]."""
        return self.last(self.msp, right)


# --- texts ------------------------------------------------------------------------------------

@functools.lru_cache(maxsize=8)
def _font(name: str) -> AbstractFont:
    from ezdxf.fonts import fonts

    return fonts.make_font(name, 1.0)


_FONT = "txt"  # the font of the style "Standard" of ezdxf.new(setup=True): what TEXT uses


@functools.lru_cache(maxsize=4096)
def _text_width(text: str) -> float:
    """Width of ``text`` in the drawings' font at cap height 1 (ezdxf's measure of the font;
    a sheet's texts are measured again at each scale tried)."""
    return _font(_FONT).text_width(text)


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
    width = _text_width(text) * height
    descent = font.measurements.descender_height * height
    vertical, _, horizontal = align.rpartition("_")  # "LEFT": on the baseline
    x0 = at[0] - {"LEFT": 0.0, "CENTER": 0.5, "RIGHT": 1.0}.get(horizontal, 0.0) * width
    base = at[1] - {"MIDDLE": 0.5 * height, "BOTTOM": -descent, "TOP": height}.get(vertical, 0.0)
    return x0, base - descent, x0 + width, base + height


def dxf_text(text: str) -> str:
    """The content of a TEXT entity: ``text`` with the signs of :data:`DXF_CODES` written as
    their control codes (a CAD program, and ezdxf's ``plain_text()``, shows the sign).

    Parameters
    ----------
    text : str
        The text as read (``"Bore Ø32.0 H7"``).

    Returns
    -------
    str
        The text as the DXF stores it (``"Bore %%c32.0 H7"``).
    """
    for sign, code in DXF_CODES.items():
        text = text.replace(sign, code)
    return text


def _text(msp: Modelspace | None, text: str, at: tuple[float, float], height: float,
          align: str = "MIDDLE_LEFT", layer: str = "TEXT") -> Box:
    """Draw a TEXT (its signs as DXF control codes, :func:`dxf_text`); returns its box [mm]
    (:func:`_text_box`). With ``msp`` None nothing is drawn: the box of the text it would
    draw."""
    if msp is not None:
        from ezdxf.enums import TextEntityAlignment

        entity: Text = msp.add_text(dxf_text(text), height=height, dxfattribs={"layer": layer})
        entity.set_placement(at, align=TextEntityAlignment[align])
    return _text_box(text, at, height, align)


def _text_lines(msp: Modelspace | None, lines: Sequence[str], top_left: Point, height: float,
                spacing: float) -> Box:
    """Lines of text, left-aligned, the first one's top at ``top_left``; returns the box
    (``msp`` None: draws nothing, the box they would take)."""
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
    discs, spans = _layout_outline(analysis)
    sheet.discs.extend(discs)
    for a, b in spans:
        msp.add_line(a, b, dxfattribs={"layer": "CHAIN"})
        sheet.lines.append((a, b))


def _layout_outline(analysis: Analysis) -> tuple[list[Disc], list[Segment]]:
    """The sprockets' tip circles and the chain's spans [mm]."""
    discs = [(s.x * MM, s.y * MM, s.tip_diameter / 2 * MM) for s in analysis.geometry.sprockets]
    spans = [((sp.start_point[0] * MM, sp.start_point[1] * MM),
              (sp.end_point[0] * MM, sp.end_point[1] * MM)) for sp in analysis.geometry.spans]
    return discs, spans


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


def _centre_table(msp: Modelspace | None, analysis: Analysis, top_left: Point, h: float) -> Box:
    """The sprockets' centres and pitch diameters as text lines below ``top_left`` [mm];
    returns their box (``msp`` None: draws nothing, the box they would take)."""
    lines = [f"{s.name}: z = {s.teeth}, x = {dimension(s.x * MM)}, y = {dimension(s.y * MM)}, "
             f"d = {dimension(s.pitch_diameter * MM)}" for s in analysis.geometry.sprockets]
    head = _text(msp, "Sprocket centres (mm): name, teeth, x, y, pitch diameter",
                 (top_left[0], top_left[1] - 0.5 * h), h)
    rest = _text_lines(msp, lines, (top_left[0], top_left[1] - 1.6 * h), 0.9 * h, 1.6 * h)
    return _union([head, rest]) if lines else head


def _layout_sheet(msp: Modelspace, analysis: Analysis, h: float) -> _Arrangements:
    """The layout with its dimensions; the centre table, drawn last, goes below it (or to
    its right) as the returned :class:`_Arrangements` is told, which gives both boxes [mm]
    first."""
    sheet = _Sheet(gap=0.3 * h)
    _layout_entities(msp, analysis, sheet)
    _wrap_dimensions(msp, analysis, h, sheet)
    _centre_distances(msp, analysis, h, sheet)
    _sprocket_names(msp, analysis, h, sheet)
    box = sheet.extents()
    return _Arrangements(msp, lambda m, right: _with_table(m, analysis, box, h, right))


def _with_table(msp: Modelspace | None, analysis: Analysis, box: Box, h: float,
                table_right: bool) -> Box:
    """Draw the centre table below the layout of box ``box`` [mm] (or to its right);
    returns the box of both (``msp`` None: draws nothing)."""
    x0, y0, x1, y1 = box
    corner = (x1 + 2 * h, y1) if table_right else (x0, y0 - 2 * h)
    return _union([box, _centre_table(msp, analysis, corner, h)])


def _layout_least(analysis: Analysis, h: float) -> tuple[Box, Box]:
    """Boxes [mm] the layout drawn with text ``h`` high takes at least, the table below it
    and to its right, known before it is drawn: the tip circles and the chain's spans (the
    dimensions and names only add to them) and the table beside them."""
    discs, spans = _layout_outline(analysis)
    box = _union([*map(_disc_box, discs), *map(_segment_box, spans)])
    return _with_table(None, analysis, box, h, False), _with_table(None, analysis, box, h, True)


def _layout_title(analysis: Analysis) -> dict[str, str]:
    """The title block fields of the layout."""
    g = analysis.geometry
    spec = analysis.drive.chain.spec
    return {"title": f"Chain drive layout {analysis.drive.name}",
            "supplementary": f"chain {spec.designation}, links {g.links} (length "
                             f"{dimension(g.chain_length * MM, 1)} mm), tooth form "
                             f"{analysis.drive.tooth_form}",
            "number": f"{_slug(analysis.drive.name)}-00", "material": "—"}


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
                f"Tip diameter da = De = {d(form.tip_diameter * MM, 1)} (to 0.1 mm)",
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


def _sprocket_sheet(msp: Modelspace, analysis: Analysis, index: int, h: float,
                    outline: bool = True) -> _Arrangements:
    """The drawing of sprocket ``index`` with its centre at the origin: the face view with
    its diameters and the keyway (and a polymeric body's circles), the axial section A–A to
    its right (the metal or polymeric body, :func:`_axial_section`); the notes, drawn last,
    go below both (or to their right) as the returned :class:`_Arrangements` is told, which
    gives both boxes [mm] first. ``outline`` False leaves out the toothed outline, which no
    box depends on (a scale tried only for its boxes; the outline is most of a sheet's
    points)."""
    from ezdxf import bbox

    g = analysis.geometry.sprockets[index]
    profile = analysis.profiles[index]
    w = analysis.workshop(index)
    origin = (0.0, 0.0)
    if outline:
        pts = outline_mm(profile)
        msp.add_lwpolyline(pts.tolist(), close=True, dxfattribs={"layer": "OUTLINE"})
    ra, root = _tip_and_root(profile)
    bore = w.bore * MM
    hub = w.hub_diameter * MM
    msp.add_circle(origin, bore / 2, dxfattribs={"layer": "BORE"})
    if w.keyway is not None:
        b, top = w.keyway.key_width * MM / 2, w.keyway.over_bore * MM - bore / 2
        foot = math.sqrt(max((bore / 2) ** 2 - b * b, 0.0))
        msp.add_lwpolyline([(-b, foot), (-b, top), (b, top), (b, foot)],
                           dxfattribs={"layer": "KEYWAY"})
    if hub > bore:
        msp.add_circle(origin, hub / 2, dxfattribs={"layer": "HUB"})
    msp.add_circle(origin, g.pitch_diameter / 2 * MM, dxfattribs={"layer": "PITCH"})
    _centre_mark(msp, origin, 1.1 * ra)
    tip_text, root_text = _limits_text(profile, w)
    dims = []
    for radius, angle, text in ((g.pitch_diameter / 2 * MM, 30.0, "<>"), (ra, 70.0, tip_text),
                                (bore / 2, -35.0, f"<> {w.bore_fit}"),
                                (root, -70.0, root_text)):
        dim = msp.add_diameter_dim(origin, radius=radius, angle=angle, dimstyle="EZ_RADIUS",
                                   override=_dim_override(0.8 * h), text=text,
                                   dxfattribs={"layer": "DIM"})
        # every text outside the teeth, on the line's extension
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
    section = _axial_section(msp, w, ra, root, face[2] + 3 * h, h, profile.body)
    if profile.body is not None:
        _polymer_body(msp, profile.body)
    lines = _notes(profile, w)
    views = _union([face, section])
    return _Arrangements(msp, lambda m, right: _with_notes(m, views, lines, h, right))


def _tip_and_root(profile: SprocketProfile) -> tuple[float, float]:
    """Tip and root radius [mm] of the drawn outline."""
    pts = outline_mm(profile)
    r = np.hypot(pts[:, 0], pts[:, 1])
    return float(np.max(r)), float(np.min(r))


def _notes(profile: SprocketProfile, w: SprocketWorkshop) -> list[str]:
    """The notes of a sprocket's drawing: tooth form, workshop data, a polymeric body."""
    lines = [*tooth_form_lines(profile), *workshop_lines(w, profile.body is not None)]
    if profile.body is not None:
        lines += _polymer_body_lines(profile, profile.body)
    return lines


def _with_notes(msp: Modelspace | None, views: Box, lines: Sequence[str], h: float,
                notes_right: bool) -> Box:
    """Draw the notes below the views of box ``views`` [mm] (or to their right); returns
    the box of both (``msp`` None: draws nothing)."""
    corner = (views[2] + 3 * h, views[3]) if notes_right else (views[0], views[1] - 1.5 * h)
    return _union([views, _text_lines(msp, lines, corner, 0.75 * h, 1.5 * h)])


def _sprocket_least(analysis: Analysis, index: int, h: float) -> tuple[Box, Box]:
    """Boxes [mm] the drawing of sprocket ``index`` with text ``h`` high takes at least,
    the notes below and to the right, known before it is drawn: the face view's square of
    ±1.1 tip radii (its dimensions only add to it), the section's body and its label with
    the section as far left as it can be, and the notes beside them."""
    profile = analysis.profiles[index]
    w = analysis.workshop(index)
    ra, root = _tip_and_root(profile)
    reach = _section_reach(w, root, profile.body)
    cx = 1.1 * ra + 3 * h + reach
    views = _union([(-1.1 * ra, -1.1 * ra, 1.1 * ra, 1.1 * ra), (cx - reach, -ra, cx + reach, ra),
                    _text_box("A–A", _section_label_at(w, ra, cx, h), 0.8 * h, "BOTTOM_CENTER")])
    lines = _notes(profile, w)
    return _with_notes(None, views, lines, h, False), _with_notes(None, views, lines, h, True)


def _teeth(w: SprocketWorkshop, ra: float, root: float, x_left: float) -> list[Point]:
    """The teeth of the axial section from (``x_left``, root) to the last strand's right side
    at the root [mm]: a tooth per strand of the face width, its tip chamfered by an arc of
    the chamfer radius tangent to the tooth's side, the chamfer depth below the tip ([ISO606]
    bf1, ba, rx; [GOST591] b, r3, f)."""
    face, pt = w.face_width * MM, w.transverse_pitch * MM
    rad, depth = w.chamfer_radius * MM, min(w.chamfer_depth * MM, ra - root)

    def tooth(x0: float) -> list[Point]:
        """Up the left side at x0, over the chamfered tip, down the right side."""
        up: list[Point] = [(x0, root), (x0, ra - depth)]
        for t in np.linspace(0.0, 1.0, 9)[1:]:  # the arc tangent to the side at ra − depth
            dy = t * depth
            up.append((x0 + rad - math.sqrt(max(rad * rad - dy * dy, 0.0)), ra - depth + dy))
        down = [(2 * x0 + face - x, y) for x, y in reversed(up)]
        return up + down

    return [p for k in range(w.strands) for p in tooth(x_left + k * pt)]


def _body_side(w: SprocketWorkshop, root: float,
               body: PolymericProportions | None) -> list[Point]:
    """The left side of the section's body from the bore up to the rim's root, as (distance
    left of the mid-plane, radius) [mm], radius −1 marking the bore: a metal sprocket's hub
    and its rim of the overall width; a polymeric body's hub, web and rim
    [MultimassChainDrives, §3.4]."""
    if body is None:
        hub_len, hub_r = w.hub_length * MM / 2, w.hub_diameter * MM / 2
        return [(hub_len, -1.0), (hub_len, hub_r), (w.overall_width * MM / 2, hub_r)]
    hub_len, hub_r = body.hub_length * MM / 2, body.hub_outer_diameter * MM / 2
    web, rim = body.web_thickness * MM / 2, body.rim_width * MM / 2
    rim_r = body.rim_inner_diameter * MM / 2
    return [(hub_len, -1.0), (hub_len, hub_r), (web, hub_r), (web, rim_r), (rim, rim_r),
            (rim, root)]


def _axial_section(msp: Modelspace, w: SprocketWorkshop, ra: float, root: float, left: float,
                   h: float, body: PolymericProportions | None = None) -> Box:
    """The axial section A–A of a sprocket, its left edge at ``left`` and its axis on y = 0:
    the body (a metal hub and rim, or a polymeric ``body``'s hub, web and rim) to the root
    circle, the teeth with their chamfer (:func:`_teeth`) and the bore (through the keyway
    above the axis), two closed halves hatched; dimensioned with the tooth width, the hub
    length and diameter, the overall width of several strands and d + t2; returns its box
    [mm]."""
    from ezdxf import bbox

    overall = w.overall_width * MM
    side = _body_side(w, root, body)
    hub_len, hub_r = 2 * side[0][0], side[1][1]
    reach = _section_reach(w, root, body)
    cx = left + reach
    bore_r = w.bore * MM / 2
    top_bore = (w.keyway.over_bore * MM - bore_r) if w.keyway is not None else bore_r
    depth = min(w.chamfer_depth * MM, ra - root)
    inner = -1.0  # marks the bore's radius, set per half below
    outline = ([(cx - a, r) for a, r in side] + _teeth(w, ra, root, cx - overall / 2)
               + [(cx + a, r) for a, r in reversed(side)])
    for sign, radius in ((1.0, top_bore), (-1.0, bore_r)):
        poly = _ordered([(x, sign * (radius if y == inner else y)) for x, y in outline])
        msp.add_lwpolyline(poly, close=True, dxfattribs={"layer": "SECTION"})
        hatch = msp.add_hatch(color=8, dxfattribs={"layer": "HATCH"})
        hatch.set_pattern_fill("ANSI31", scale=max(0.5, h / 3))
        hatch.paths.add_polyline_path(poly, is_closed=True)
    msp.add_line((cx - reach - h, 0.0), (cx + reach + h, 0.0), dxfattribs={"layer": "CENTER"})
    override = _dim_override(0.8 * h)
    x_tooth = cx - overall / 2
    wanted: list[tuple[Point, Point, float, int, str]] = [
        ((x_tooth, ra - depth), (x_tooth + w.face_width * MM, ra - depth), ra + 1.5 * h, 0,
         "<>"),
        ((cx - hub_len / 2, -hub_r), (cx + hub_len / 2, -hub_r), -ra - 1.5 * h, 0, "<>"),
        ((cx + hub_len / 2, -hub_r), (cx + hub_len / 2, hub_r), cx + reach + 1.5 * h, 90,
         "%%c<>")]
    if w.strands > 1:
        wanted.append(((cx - overall / 2, root), (cx + overall / 2, root), ra + 4.0 * h, 0,
                       "<>"))
    if w.keyway is not None:  # d + t2, from the bore's far side to the keyway's bottom
        t2_tol = _pm(w.keyway.depth_upper, 0.0, 1).replace(" / ", "/")
        wanted.append(((cx - hub_len / 2, -bore_r), (cx - hub_len / 2, top_bore),
                       cx - reach - 1.5 * h, 90, f"<> {t2_tol}"))
    dims = []
    for p1, p2, base, angle, text in wanted:
        dim = msp.add_linear_dim(base=(base, 0.0) if angle else (0.0, base), p1=p1, p2=p2,
                                 angle=angle, dimstyle="EZDXF", override=override, text=text,
                                 dxfattribs={"layer": "DIM"})
        dim.render()
        dims.append(dim.dimension)
    label = _text(msp, "A–A", _section_label_at(w, ra, cx, h), 0.8 * h, "BOTTOM_CENTER")
    ext = bbox.extents(dims)
    return _union([(cx - reach, -ra, cx + reach, ra), label,
                   (ext.extmin.x, ext.extmin.y, ext.extmax.x, ext.extmax.y)])


def _section_reach(w: SprocketWorkshop, root: float, body: PolymericProportions | None
                   ) -> float:
    """Half the width [mm] of the axial section's body and teeth."""
    side = _body_side(w, root, body)
    return max(a for a, _ in [*side, (w.overall_width * MM / 2, 0.0)])


def _section_label_at(w: SprocketWorkshop, ra: float, cx: float, h: float) -> Point:
    """Where the label A–A of a section centred at ``cx`` stands [mm] (its bottom centre),
    above the dimensions over the teeth."""
    return cx, ra + (6.5 if w.strands > 1 else 4.0) * h


def _ordered(points: list[Point]) -> list[Point]:
    """The points without consecutive repeats (closer than 1 µm)."""
    out: list[Point] = []
    for p in points:
        if not out or math.dist(out[-1], p) > 1e-3:
            out.append(p)
    return out


def _pm(upper: float, lower: float, places: int = 3) -> str:
    """Deviations [m] as written: "+0.025 / 0", "±0.018"."""
    u, lo = upper * MM, lower * MM

    def signed(x: float) -> str:
        return "0" if abs(x) < 5e-7 else f"{'+' if x > 0 else '−'}{dimension(abs(x), places)}"

    if abs(u + lo) < 5e-7 and u > 0:
        return f"±{dimension(u, places)}"
    return f"{signed(u)} / {signed(lo)}"


def workshop_lines(w: SprocketWorkshop, polymeric: bool = False) -> list[str]:
    """What the drawing states of the bore, keyway, hub, section, measurement over pins,
    tip diameter, material and general tolerances [mm], each with its rule.

    Parameters
    ----------
    w : SprocketWorkshop
        The data of the drawing (:func:`chaindrive.geometry.workshop.sprocket_workshop`).
    polymeric : bool
        A polymeric body (its own notes give the hub and its section).

    Returns
    -------
    list of str
        One line per item.

    References
    ----------
    [ISO606], [GOST591], [DIN6885-1], [ISO286-1], [ISO2768-1], [MultimassChainDrives, §3.4].
    """
    d = dimension
    source = ("given by the design" if w.bore_given
              else "default 0.19·z·p/π of the body model, an estimate: give sprockets.bore")
    lines = [f"Bore Ø{d(w.bore * MM, 1)} {w.bore_fit} ({_pm(w.bore_upper, w.bore_lower)}), "
             f"{source}"]
    if w.keyway is None:
        lines.append("No keyway (keyway = false in the design)")
    else:
        k = w.keyway
        lines.append(f"Keyway DIN 6885-1 / ISO 773 for key {d(k.key_width * MM, 0)} × "
                     f"{d(k.key_height * MM, 0)}: width {d(k.key_width * MM, 0)} JS9 "
                     f"({_pm(k.width_upper, k.width_lower)}), depth t2 = "
                     f"{d(k.hub_depth * MM, 1)}, d + t2 = {d(k.over_bore * MM, 1)} "
                     f"({_pm(k.depth_upper, 0.0, 1)})")
    if not polymeric:
        lines.append(f"Hub Ø{d(w.hub_diameter * MM, 1)} × {d(w.hub_length * MM, 1)} long "
                     f"(body model: 0.33/0.19 of the bore, 3 face widths), at most dg = "
                     f"{d(w.hub_limit * MM, 1)}")
    if w.standard == "GOST 591":
        lines.append(f"Section A–A: face width bf1 = b = {d(w.face_width * MM, 2)}, tooth chamfer "
                     f"r3 = {d(w.chamfer_radius * MM, 2)} (1.7 d1) about centres h3 = 0.8 d1 "
                     f"below the tip, f = {d(w.chamfer_width * MM, 2)} at the tip (GOST 591)")
    else:
        lines.append(f"Section A–A: face width bf1 = {d(w.face_width * MM, 2)}, tooth chamfer "
                     f"ba = {d(w.chamfer_width * MM, 2)} (0.125 p, inside 0.10 … 0.15 p), "
                     f"rx = {d(w.chamfer_radius * MM, 2)} (= p), "
                     f"{d(w.chamfer_depth * MM, 2)} deep (ISO 606)")
    if w.strands > 1:
        lines.append(f"{w.strands} strands at pt = {d(w.transverse_pitch * MM, 2)}, overall "
                     f"{d(w.overall_width * MM, 2)}")
    rule = "even z: d + dR" if w.teeth % 2 == 0 else "odd z: d·cos(90°/z) + dR"
    tol = (f"({_pm(w.pins_upper, w.pins_lower, 2)}, as the root diameter)"
           if w.standard == "ISO 606" else "(GOST 591 tolerance not compiled)")
    lines.append(f"Measurement over pins MR = {d(w.pins_measurement * MM, 3)} {tol}, "
                 f"pins Ø dR = d1 = {d(w.pin_diameter * MM, 2)} ({rule})")
    if w.standard == "ISO 606":
        lines.append(f"Tip diameter da = {d(w.tip_diameter * MM, 1)} h11 "
                     f"({_pm(w.tip_upper, w.tip_lower)}): the mean of the ISO 606 range "
                     f"{d(w.tip_min * MM, 2)} … {d(w.tip_max * MM, 2)} rounded down to 0.1 mm")
    hardening = w.hardening or "not given by the design (sprockets.hardening)"
    lines.append(f"Material: {w.material}; hardening: {hardening}")
    lines.append("General tolerances ISO 2768-m")
    return lines


def _limits_text(profile: SprocketProfile, w: SprocketWorkshop) -> tuple[str, str]:
    """Text of the tip and root diameter dimensions with the standard's limits (the tip as
    chosen inside the ISO 606 range, h11)."""
    if profile.standard == "GOST 591":
        form = cast("Gost591ToothForm", profile.form)
        return (f"%%c{dimension(form.tip_diameter * MM, 1)}",
                f"%%c{dimension(form.root_diameter * MM, 3)}")
    iso = cast("ToothForm", profile.form)
    return (f"%%c{dimension(w.tip_diameter * MM, 1)} h11",
            f"%%c{dimension(iso.root_diameter * MM, 2)} {_root_tolerance(profile)}")


def _polymer_body(msp: Modelspace, p: PolymericProportions) -> None:
    """Face-view circles of a polymeric body (hub, rim and six lightening holes)
    [MultimassChainDrives, §3.4]; its notes are :func:`_polymer_body_lines`, its section
    :func:`_axial_section`'s."""
    centre = (0.0, 0.0)
    for d in (p.hub_outer_diameter, p.rim_inner_diameter):
        msp.add_circle(centre, d / 2 * MM, dxfattribs={"layer": "BODY"})
    hole = _lightening_hole(p)
    for k in range(6):
        a = TWO_PI * k / 6
        msp.add_circle((p.hole_circle_diameter / 2 * MM * math.cos(a),
                        p.hole_circle_diameter / 2 * MM * math.sin(a)), hole / 2,
                       dxfattribs={"layer": "BODY"})


def _lightening_hole(p: PolymericProportions) -> float:
    """Diameter [mm] of the lightening holes: half the web between hub and rim."""
    return 0.5 * (p.rim_inner_diameter - p.hub_outer_diameter) / 2 * MM


def _polymer_body_lines(profile: SprocketProfile, p: PolymericProportions) -> list[str]:
    """The notes of a polymeric body: mass, inertia, proportions [MultimassChainDrives,
    §3.4]."""
    hole = _lightening_hole(p)
    lines = [f"Polymeric body: mass = {profile.mass.mass:.4g} kg, inertia = "
             f"{profile.mass.moment_of_inertia:.4g} kg·m²",
             f"Hub Ø {dimension(p.hub_outer_diameter * MM, 1)} × "
             f"{dimension(p.hub_length * MM, 1)}, web {dimension(p.web_thickness * MM, 1)} "
             f"thick, rim from Ø {dimension(p.rim_inner_diameter * MM, 1)}, "
             f"{dimension(p.rim_width * MM, 1)} wide",
             f"Six lightening holes Ø {dimension(hole, 1)} on Ø "
             f"{dimension(p.hole_circle_diameter * MM, 1)}"]
    return lines


def _index_of(analysis: Analysis, name: str) -> int:
    names = [s.name for s in analysis.drive.sprockets]
    if name not in names:
        raise DesignError("--sprocket", f"no sprocket named {name!r}; the sprockets are "
                          f"{', '.join(names)}")
    return names.index(name)


# --- standard sheets (ISO 5457 sizes and borders, ISO 5455 scales, ISO 7200 title block) ------

#: ISO 5457 trimmed sheet sizes [mm] (width, height) as drawn: A4 upright, the others
#: landscape.
ISO5457_SHEETS: dict[str, tuple[float, float]] = {
    "A4": (210.0, 297.0), "A3": (420.0, 297.0), "A2": (594.0, 420.0), "A1": (841.0, 594.0),
    "A0": (1189.0, 841.0)}
#: ISO 5455 reduction scales 1:N (the 1, 2, 5 series).
ISO5455_SCALES: tuple[int, ...] = (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000)
#: ISO 5457 borders [mm]: 20 at the left (filing margin), 10 at the other edges.
BORDER_LEFT, BORDER = 20.0, 10.0

def sheet_and_scale(width: float, height: float, sheets: tuple[str, ...] = ("A4", "A3"),
                    title_height: float = 0.0, margin: float = 0.0,
                    scales: tuple[int, ...] = ISO5455_SCALES) -> tuple[str, int]:
    """The first ISO 5457 sheet of ``sheets`` at the largest ISO 5455 scale 1:N (scales
    first, then sheets) whose drawing area holds a drawing of ``width`` × ``height`` above a
    title block ``title_height`` high.

    The drawing area is the sheet inside its borders (20 mm left, 10 mm elsewhere).

    Parameters
    ----------
    width, height : float
        Size of the drawing [mm of the object, 1:1].
    sheets : tuple of str
        Candidate sheets of :data:`ISO5457_SHEETS`, smallest first.
    title_height : float
        Height of the title block strip at the bottom of the area [mm on paper].
    margin : float
        Clearance kept inside the frame on every side [mm on paper].
    scales : tuple of int
        The N of the candidate scales 1:N, largest scale first.

    Returns
    -------
    tuple of (str, int)
        (sheet, N).

    Raises
    ------
    DesignError
        Nothing fits (beyond 1:1000 on the largest sheet).

    References
    ----------
    [ISO5457] (sizes, borders); [ISO5455] (scales).
    """
    for n in scales:
        for name in sheets:
            w, h = ISO5457_SHEETS[name]
            if (width / n + 2 * margin <= w - BORDER_LEFT - BORDER
                    and height / n + 2 * margin <= h - 2 * BORDER - title_height):
                return name, n
    raise DesignError("drawing", f"{width:.0f} × {height:.0f} mm does not fit "
                                 f"{sheets[-1]} at 1:{scales[-1]}")



#: ISO 7200 title block [mm on paper]: 180 wide, rows 9 high; each row's cells as
#: (field, label, width).
TITLE_ROWS: tuple[tuple[tuple[str, str, float], ...], ...] = (
    (("title", "Title", 135.0), ("number", "Drawing number", 45.0)),
    (("supplementary", "Supplementary title", 180.0),),
    (("material", "Material", 100.0), ("scale", "Scale", 35.0), ("sheet", "Sheet size", 45.0)),
    (("created", "Created by", 50.0), ("checked", "Checked by", 50.0),
     ("approved", "Approved by", 35.0), ("date", "Date of issue", 45.0)),
    (("owner", "Legal owner", 100.0), ("type", "Document type", 35.0),
     ("revision", "Rev. / sheet", 45.0)),
)
TITLE_ROW = 10.0
TITLE_HEIGHT = TITLE_ROW * len(TITLE_ROWS)
SHEET_MARGIN = 5.0  # mm on paper between the frame and the drawing


def _slug(name: str) -> str:
    """A drawing number's stem from a drive's name (letters, digits and dashes)."""
    out = "".join(c if c.isalnum() else "-" for c in name.upper()).strip("-")
    return "-".join(filter(None, out.split("-")))[:24] or "DRIVE"


def _iso7200_block(msp: Modelspace, right_bottom: Point, n: float,
                   values: dict[str, str]) -> Box:
    """The ISO 7200 title block with its lower right corner at ``right_bottom``, drawn at
    1:``n`` (every size × n): one closed polyline on FRAME, the cell lines, each cell's
    label (small, top left) and value (3.5 mm, smaller when it would not fit); returns its
    box [mm]."""
    font = _font(_FONT)
    x1, y0 = right_bottom
    x0, y1 = x1 - 180.0 * n, y0 + TITLE_HEIGHT * n
    msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                       dxfattribs={"layer": "FRAME"})
    for r, row in enumerate(TITLE_ROWS):
        top = y1 - r * TITLE_ROW * n
        if r:
            msp.add_line((x0, top), (x1, top), dxfattribs={"layer": "FRAME"})
        x = x0
        for c, (key, label, width) in enumerate(row):
            if c:
                msp.add_line((x, top), (x, top - TITLE_ROW * n), dxfattribs={"layer": "FRAME"})
            _text(msp, label, (x + 1.0 * n, top - 0.6 * n), 1.8 * n, "TOP_LEFT")
            value = values.get(key, "")
            if value:
                room = (width - 2.0) * n
                height = min(PAPER_TEXT * n, room / max(font.text_width(value), 1e-9))
                _text(msp, value, (x + 1.0 * n, top - TITLE_ROW * n + 0.8 * n), height,
                      "BOTTOM_LEFT")
            x += width * n
    return x0, y0, x1, y1


def _frame(msp: Modelspace, content: Box, sheet: str, n: int,
           values: dict[str, str]) -> Box:
    """Put a drawing on a standard sheet drawn at 1:``n``: the trimmed sheet edge and the
    ISO 5457 frame (layer SHEET), the drawing's top left corner ``SHEET_MARGIN`` inside the
    frame's, the ISO 7200 title block in the frame's lower right corner; returns the sheet's
    box [mm]."""
    w, h = ISO5457_SHEETS[sheet]
    x = content[0] - (BORDER_LEFT + SHEET_MARGIN) * n
    y = content[3] + (BORDER + SHEET_MARGIN) * n - h * n
    edge = [(x, y), (x + w * n, y), (x + w * n, y + h * n), (x, y + h * n)]
    msp.add_lwpolyline(edge, close=True, dxfattribs={"layer": "SHEET"})
    fx0, fy0, fx1, fy1 = x + BORDER_LEFT * n, y + BORDER * n, x + (w - BORDER) * n, y + (h - BORDER) * n
    msp.add_lwpolyline([(fx0, fy0), (fx1, fy0), (fx1, fy1), (fx0, fy1)], close=True,
                       dxfattribs={"layer": "SHEET", "lineweight": 70})
    _iso7200_block(msp, (fx1, fy0), n, {**values, "scale": f"1:{n}", "sheet": sheet})
    return x, y, x + w * n, y + h * n


def _fits(content: Box, sheet: str, n: int) -> bool:
    """Does a drawing of box ``content`` [mm] fit the sheet at 1:``n`` above its title
    block?"""
    try:
        sheet_and_scale(content[2] - content[0], content[3] - content[1], (sheet,),
                        TITLE_HEIGHT, SHEET_MARGIN, (n,))
    except DesignError:
        return False
    return True


_Build = Callable[["Modelspace", float], _Arrangements]


def _on_sheet(build: _Build, least: Callable[[float], tuple[Box, Box]], size: float,
              sheets: tuple[str, ...], text: float = PAPER_TEXT, *,
              canvas: Modelspace | None = None) -> tuple[str, int, bool, _Arrangements]:
    """The sheet, scale and arrangement of a drawing made by ``build(msp, text height)``:
    from the largest ISO 5455 scale at which an object of ``size`` [mm] could fit the
    largest sheet, the first scale, then the first sheet, then the first arrangement (notes
    below, notes to the right) at which the drawing made with text 3.5 mm high on paper
    fits (:func:`chaindrive.geometry.workshop.sheet_and_scale`); with the drawing at that
    scale, made on a new document, its last part not yet drawn. One drawing per scale tried
    gives the boxes of both arrangements; a scale at which ``least(text height)``, boxes
    the drawing takes at least each way, fits no sheet is passed over without drawing.
    With ``canvas`` every scale tried is drawn on it instead of on a new document (for a
    caller that only reads the boxes and draws the chosen scale itself)."""
    room = max(ISO5457_SHEETS[sheets[-1]]) - 2 * SHEET_MARGIN - BORDER_LEFT - BORDER
    for n in ISO5455_SCALES:
        if size / n > room or not any(_fits(_grow(b, -1e-6), sheet, n)
                                      for b in least(text * n) for sheet in sheets):
            continue
        made = build(_new_document().modelspace() if canvas is None else canvas, text * n)
        boxes = (made.box(False), made.box(True))
        for sheet in sheets:
            for right in (False, True):
                if _fits(boxes[right], sheet, n):
                    return sheet, n, right, made
    if sheets[-1] != "A0":
        return _on_sheet(build, least, size, ("A2", "A1", "A0"), text, canvas=canvas)
    raise DesignError("drawing", "does not fit A0 at 1:1000")


def _sheet_record(doc: Drawing, sheet: str, n: int) -> None:
    """Record the sheet and scale of a one-sheet document (read by :func:`svg_string`)."""
    doc.header.custom_vars.append("chaindrive_sheet", f"{sheet} 1:{n}")


def _sprocket_values(analysis: Analysis, index: int) -> dict[str, str]:
    s = analysis.drive.sprockets[index]
    spec = analysis.drive.chain.spec
    return {"title": f"Sprocket {s.name}, z = {s.teeth}",
            "supplementary": f"for chain {spec.designation}, tooth form "
                             f"{analysis.drive.tooth_form}, drive {analysis.drive.name}",
            "number": f"{_slug(analysis.drive.name)}-{index + 1:02d}",
            "material": f"{s.material}; {s.hardening or 'hardening not given'}",
            "type": "Detail drawing"}


def _common_values() -> dict[str, str]:
    return {"created": f"chaindrive {chaindrive.__version__}",
            "date": _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d"), "revision": "A  1/1"}


def _place_sprocket(analysis: Analysis, index: int, msp: Modelspace | None = None,
                    scratch: Modelspace | None = None) -> tuple[Modelspace, Box, str, int]:
    """The framed drawing of sprocket ``index`` on its sheet, drawn on ``msp`` or (None) on
    the new document its sheet and scale were chosen with; returns the modelspace drawn on,
    the sheet's box, the sheet and 1:N. With ``msp`` given, the scales are tried on
    ``scratch`` (a modelspace whose drawing is thrown away; None: a new document per scale
    tried), only their boxes read."""
    tip = analysis.geometry.sprockets[index].tip_diameter * MM
    canvas = scratch if msp is not None else None  # the tries on it give only boxes
    sheet, n, right, made = _on_sheet(
        lambda m, h: _sprocket_sheet(m, analysis, index, h, outline=canvas is None),
        lambda h: _sprocket_least(analysis, index, h), 1.6 * tip, ("A4", "A3"), canvas=canvas)
    if msp is not None:
        made = _sprocket_sheet(msp, analysis, index, PAPER_TEXT * n)
    box = made.finish(right)
    values = {**_common_values(), **_sprocket_values(analysis, index)}
    return made.msp, _frame(made.msp, box, sheet, n, values), sheet, n


def _place_layout(analysis: Analysis) -> tuple[Modelspace, Box, str, int]:
    """The framed layout on its sheet, drawn on the new document its sheet and scale were
    chosen with; returns its modelspace, the sheet's box, the sheet and 1:N."""
    g = analysis.geometry.sprockets
    r = max(s.tip_diameter for s in g) / 2 * MM
    size = max(np.ptp([s.x for s in g]), np.ptp([s.y for s in g])) * MM + 2 * r
    sheet, n, right, made = _on_sheet(lambda m, h: _layout_sheet(m, analysis, h),
                                      lambda h: _layout_least(analysis, h), float(size),
                                      ("A4", "A3"), LAYOUT_TEXT)
    box = made.finish(right)
    values = {**_common_values(), **_layout_title(analysis), "type": "Layout"}
    return made.msp, _frame(made.msp, box, sheet, n, values), sheet, n


def _document(msp: Modelspace) -> Drawing:
    """The document of a modelspace."""
    assert msp.doc is not None  # a modelspace of _new_document
    return msp.doc


@shared_parameters
def sprocket_document(analysis: Analysis, name: str) -> Drawing:
    """The manufacturing drawing of the sprocket ``name`` alone on a standard sheet (ezdxf
    document, mm): ISO 5457 A4 or A3, the largest ISO 5455 scale 1:N at which it fits, the
    ISO 7200 title block.

    %(params_drawing_analysis)s
    name : str
        The sprocket's name.

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm, the sheet drawn N times its size.
    """
    i = _index_of(analysis, name)
    msp, _, sheet, n = _place_sprocket(analysis, i)
    doc = _document(msp)
    _sheet_record(doc, sheet, n)
    return doc


@shared_parameters
def layout_document(analysis: Analysis) -> Drawing:
    """The layout drawing alone on a standard sheet (ezdxf document, mm): ISO 5457 A4 or A3
    (A2 … A0 when nothing smaller holds it at 1:1000), the largest ISO 5455 scale at which
    it fits, the ISO 7200 title block.

    %(params_drawing_analysis)s

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm, the sheet drawn N times its size.
    """
    msp, _, sheet, n = _place_layout(analysis)
    doc = _document(msp)
    _sheet_record(doc, sheet, n)
    return doc


@shared_parameters
def drawing_document(analysis: Analysis) -> Drawing:
    """The layout on its sheet and, to its right, every sprocket's manufacturing drawing on
    its own sheet (ezdxf document, mm; each sheet at its own scale).

    %(params_drawing_analysis)s

    Returns
    -------
    ezdxf.document.Drawing
        The DXF document, drawn 1:1 in mm.
    """
    msp, layout, _, _ = _place_layout(analysis)
    x = layout[2] + 20.0
    # each sprocket's scales are tried on one scratch document, not a new one per scale
    # tried (the tries are read for their boxes only; the sheet is then drawn on msp)
    scratch = _new_document().modelspace()
    for i in range(len(analysis.geometry.sprockets)):
        start = len(msp)
        _, box, _, _ = _place_sprocket(analysis, i, msp, scratch)
        dx, dy = x - box[0], layout[3] - box[3]
        for e in list(msp)[start:]:
            e.translate(dx, dy, 0.0)
        x += box[2] - box[0] + 20.0
    return _document(msp)


@shared_parameters
def write_drawing(analysis: Analysis, path: str | Path, *, sprocket: str | None = None
                  ) -> Path:
    """Write the drawing as DXF or SVG (by the suffix of ``path``): the layout with every
    sprocket, or with ``sprocket`` the manufacturing drawing of that sprocket alone. The
    file is written at once, after the whole drawing is made.

    %(params_drawing_analysis)s
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
        raise DesignError("output", f"must end in .dxf, .svg or .pdf, got {out.name!r}")
    doc = (sprocket_document(analysis, sprocket) if sprocket is not None
           else drawing_document(analysis))
    if suffix == ".dxf":
        import io

        stream = io.StringIO()
        doc.write(stream)
        data = stream.getvalue().encode(doc.output_encoding or "utf-8")
    elif suffix == ".pdf":
        data = pdf_bytes(doc)
    else:
        data = svg_string(doc).encode("utf-8")
    write_bytes(out, data)  # complete or absent, never half-written
    return out


@shared_parameters
def svg_string(doc: Drawing, page_width_mm: float = 420.0) -> str:
    """The modelspace of ``doc`` as SVG (ezdxf drawing add-on) on a white page: a document
    on one standard sheet on a page of that sheet's size (the drawing at its scale, true
    to size when printed 1:1); otherwise a page ``page_width_mm`` wide (A3 by default),
    scaled to fit. The DXF stays 1:1.

    %(params_dxf_page)s

    Returns
    -------
    str
        The SVG text.
    """
    from ezdxf.addons.drawing import Frontend, RenderContext, config, layout, svg

    backend = svg.SVGBackend()
    cfg = config.Configuration(background_policy=config.BackgroundPolicy.WHITE,
                               color_policy=config.ColorPolicy.COLOR)
    Frontend(RenderContext(doc), backend, config=cfg).draw_layout(doc.modelspace())
    pw, ph, edge = _page(doc, page_width_mm)
    if edge is not None:
        page = layout.Page(pw, ph, layout.Units.mm, margins=layout.Margins.all(0))
    else:
        page = layout.Page(pw, ph + 20, layout.Units.mm, margins=layout.Margins.all(10))
    return backend.get_string(page)


def _page(doc: Drawing, page_width_mm: float) -> tuple[float, float, tuple[float, ...] | None]:
    """Page size [mm] of a document: its sheet's for a one-sheet document (and the sheet's
    edge in model units), else ``page_width_mm`` wide in the proportion of its extents."""
    from ezdxf import bbox

    record = dict(doc.header.custom_vars).get("chaindrive_sheet")
    if record:
        pw, ph = ISO5457_SHEETS[record.split()[0]]
        edge = max((bbox.extents([p]) for p in doc.modelspace().query(
            "LWPOLYLINE[layer=='SHEET']")), key=lambda e: e.size.x)
        return pw, ph, (edge.extmin.x, edge.extmin.y, edge.extmax.x, edge.extmax.y)
    box = bbox.extents(doc.modelspace(), fast=True)
    w, h = (box.size.x, box.size.y) if box.has_data else (100.0, 100.0)
    return page_width_mm, page_width_mm * h / max(w, 1e-9), None


def filled_path_orientation(contours: Sequence[NDArray[np.float64]]) -> list[bool]:
    """The orientation each contour of a filled shape takes so that a non-zero fill shows the
    even-odd rule: counter-clockwise (True) for a contour inside an even number of the
    others, clockwise (False) for one inside an odd number (a hole, an island in a hole …).

    A contour's depth counts the others that contain its first vertex (a point-in-polygon
    test, after a bounding-box test), not the others whose bounding box holds its box: the
    two counters of Ø lie side by side with overlapping boxes.

    Parameters
    ----------
    contours : sequence of ndarray
        Closed polygons (N, 2) [drawing units, one for all], not crossing one another (the
        contours of glyphs and hatch boundaries).

    Returns
    -------
    list of bool
        True (counter-clockwise) or False (clockwise), one per contour.
    """
    from matplotlib.path import Path as MplPath

    boxes = np.array([(*c.min(axis=0), *c.max(axis=0)) for c in contours])
    shapes = [MplPath(c) for c in contours]
    out = []
    for i, c in enumerate(contours):
        x, y = c[0]
        around = np.flatnonzero((boxes[:, 0] <= x) & (x <= boxes[:, 2])
                                & (boxes[:, 1] <= y) & (y <= boxes[:, 3]))
        depth = sum(1 for j in around if j != i and shapes[j].contains_point((x, y)))
        out.append(depth % 2 == 0)
    return out


def _pdf_backend(ax: Any) -> Any:
    """ezdxf's matplotlib backend on ``ax``, filling each contour by its true nesting
    (:func:`filled_path_orientation`): the add-on nests contours by their bounding boxes,
    which fills a counter of a glyph such as Ø (its two counters' boxes overlap)."""
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
    from ezdxf.npshapes import to_matplotlib_path
    from matplotlib.patches import PathPatch

    class _Backend(MatplotlibBackend):
        def draw_filled_paths(self, paths: Iterable[Any], properties: Any) -> None:
            contours = [p for path in paths for p in path.sub_paths() if len(p) > 0]
            polygons = [np.array([(v.x, v.y) for v in p.flattening(FLATTENING_MM)])
                        for p in contours]
            kept = [(c, g) for c, g in zip(contours, polygons, strict=True) if len(g) >= 3]
            if not kept:
                return
            for (c, _), ccw in zip(kept, filled_path_orientation([g for _, g in kept]),
                                   strict=True):
                if ccw:
                    c.counter_clockwise()
                else:
                    c.clockwise()
            self.ax.add_patch(PathPatch(to_matplotlib_path([c for c, _ in kept]),
                                        color=properties.color, linewidth=0, fill=True,
                                        zorder=self._get_z()))

    return _Backend(ax)


@shared_parameters
def pdf_bytes(doc: Drawing, page_width_mm: float = 420.0) -> bytes:
    """The modelspace of ``doc`` as a one-page PDF (ezdxf drawing add-on, matplotlib): a
    document on one standard sheet on a page of that sheet's size, the sheet filling it (so
    the drawing prints at its scale); otherwise a page ``page_width_mm`` wide.

    %(params_dxf_page)s

    Returns
    -------
    bytes
        The PDF.
    """
    import io

    # matplotlib and the add-on load only when a PDF is asked for (import time of `draw`)
    import matplotlib.figure
    from ezdxf.addons.drawing import Frontend, RenderContext, config

    pw, ph, edge = _page(doc, page_width_mm)
    fig = matplotlib.figure.Figure(figsize=(pw / 25.4, ph / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    cfg = config.Configuration(background_policy=config.BackgroundPolicy.WHITE,
                               color_policy=config.ColorPolicy.COLOR)
    Frontend(RenderContext(doc), _pdf_backend(ax), config=cfg).draw_layout(
        doc.modelspace(), finalize=True)
    if edge is not None:
        ax.set_xlim(edge[0], edge[2])
        ax.set_ylim(edge[1], edge[3])
    ax.set_axis_off()
    fig.set_size_inches(pw / 25.4, ph / 25.4)  # the backend's finalize resizes the figure
    ax.set_position((0.0, 0.0, 1.0, 1.0))
    stream = io.BytesIO()
    fig.savefig(stream, format="pdf")
    return stream.getvalue()
