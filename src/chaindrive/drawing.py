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
* :func:`drawing_document` — the layout and every sprocket's drawing on one sheet (what
  ``chaindrive draw`` writes without ``--sprocket``).

Tooth outlines, forms and bodies come from the analysis
(:attr:`chaindrive.analysis.Analysis.profiles`, :mod:`chaindrive.geometry.profile`): the
ISO 606 outline is the mean of the two tooth-gap forms of the standard [ISO606], the GOST
591 outline the profile of GOST 591-69 drawn without the offset e of the root-arc centres,
which the standard permits [GOST591]. The bore is the 0.19·z·p/π of the body proportions
the mass model uses [MultimassChainDrives, §3.4]; the hub limit is ISO 606's absolute
maximum shroud (hub) diameter d_g = p·cot(180°/z) − 1.04·h₂ − 0.76 mm [ISO606]. Layers:
``OUTLINE``, ``BORE``, ``HUB``, ``PITCH``, ``TIP``, ``CHAIN``, ``CENTER``, ``BODY``
(polymeric bodies), ``DIM``, ``TEXT``, ``FRAME``.
"""

from __future__ import annotations

import datetime as _dt
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

import chaindrive
from chaindrive.display import dimension
from chaindrive.errors import DesignError
from chaindrive.io.atomic import write_bytes

if TYPE_CHECKING:  # ezdxf is imported where a drawing is made
    from ezdxf.document import Drawing
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


def _text(msp: Modelspace, text: str, at: tuple[float, float], height: float,
          align: str = "MIDDLE_LEFT", layer: str = "TEXT") -> None:
    from ezdxf.enums import TextEntityAlignment

    msp.add_text(text, height=height, dxfattribs={"layer": layer}).set_placement(
        at, align=TextEntityAlignment[align])


def _centre_mark(msp: Modelspace, c: tuple[float, float], size: float) -> None:
    msp.add_line((c[0] - size, c[1]), (c[0] + size, c[1]), dxfattribs={"layer": "CENTER"})
    msp.add_line((c[0], c[1] - size), (c[0], c[1] + size), dxfattribs={"layer": "CENTER"})


def _dim_override(h: float, decimals: int = 2) -> dict[str, Any]:
    return {"dimtxt": h, "dimasz": 0.8 * h, "dimdec": decimals, "dimlfac": 1.0,
            "dimtad": 1, "dimgap": 0.3 * h}


def _title_block(msp: Modelspace, corner: tuple[float, float], h: float,
                 rows: list[tuple[str, str]]) -> tuple[float, float]:
    """A title block whose lower right corner is ``corner`` [mm]: a framed table of
    (label, value) rows; returns its (width, height) [mm]."""
    width = h * (4 + 0.62 * max(len(a) + len(b) for a, b in rows))
    row = 1.8 * h
    height = row * len(rows)
    x1, y0 = corner
    x0, y1 = x1 - width, y0 + height
    msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                       dxfattribs={"layer": "FRAME"})
    label_w = h * (1 + 0.62 * max(len(a) for a, _ in rows))
    msp.add_line((x0 + label_w, y0), (x0 + label_w, y1), dxfattribs={"layer": "FRAME"})
    for i, (label, value) in enumerate(rows):
        y = y1 - (i + 0.5) * row
        if i:
            msp.add_line((x0, y1 - i * row), (x1, y1 - i * row), dxfattribs={"layer": "FRAME"})
        _text(msp, label, (x0 + 0.5 * h, y), 0.8 * h)
        _text(msp, value, (x0 + label_w + 0.5 * h, y), 0.8 * h if i else h)
    return width, height


def _stamp(analysis: Analysis) -> list[tuple[str, str]]:
    """The rows every title block starts with."""

    return [("drive", analysis.drive.name),
            ("date", _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d")),
            ("drawn by", f"chaindrive {chaindrive.__version__}"),
            ("units", "mm, scale 1:1")]


# --- the layout ------------------------------------------------------------------------------

def _layout_entities(msp: Modelspace, analysis: Analysis, h: float) -> None:
    """Pitch and tip circles, centre marks, the chain, names at the sprockets [mm]."""
    for s in analysis.geometry.sprockets:
        c = (s.x * MM, s.y * MM)
        msp.add_circle(c, s.pitch_radius * MM, dxfattribs={"layer": "PITCH"})
        msp.add_circle(c, s.tip_diameter / 2 * MM, dxfattribs={"layer": "TIP"})
        _centre_mark(msp, c, 0.25 * s.pitch_radius * MM)
        a0, a1 = _tangent_angles(s)
        start, end = (a0, a1) if s.turn > 0 else (a1, a0)  # DXF arcs run counter-clockwise
        if s.wrap_angle > 1e-9:
            msp.add_arc(c, s.pitch_radius * MM, start, end, dxfattribs={"layer": "CHAIN"})
        _text(msp, f"{s.name}  z = {s.teeth}", (c[0], c[1] + s.tip_diameter / 2 * MM + 0.6 * h),
              h, "BOTTOM_CENTER")
    for sp in analysis.geometry.spans:
        msp.add_line(tuple(v * MM for v in sp.start_point), tuple(v * MM for v in sp.end_point),
                     dxfattribs={"layer": "CHAIN"})


def _tangent_angles(s: SprocketGeometry) -> tuple[float, float]:
    """Angles [°] of the arriving and leaving tangent points seen from the centre."""
    a0 = math.degrees(math.atan2(s.arrive[1] - s.y, s.arrive[0] - s.x))
    a1 = math.degrees(math.atan2(s.leave[1] - s.y, s.leave[0] - s.x))
    return a0, a1


def _layout_dimensions(msp: Modelspace, analysis: Analysis, h: float) -> None:
    """The centre distance between consecutive sprockets (aligned, offset outwards) and the
    wrap angle of each sprocket (angular, on a circle outside its tip)."""
    g = analysis.geometry
    pts = [(s.x * MM, s.y * MM) for s in g.sprockets]
    cx, cy = np.mean(pts, axis=0)
    n = len(pts)
    for i in range(n if n > 2 else 1):
        p1, p2 = sorted((pts[i], pts[(i + 1) % n]))  # left to right: the text stands upright
        mid = ((p1[0] + p2[0]) / 2 - cx, (p1[1] + p2[1]) / 2 - cy)
        normal = (p2[1] - p1[1], p1[0] - p2[0])
        outward = 1.0 if normal[0] * mid[0] + normal[1] * mid[1] >= 0 else -1.0
        msp.add_aligned_dim(p1=p1, p2=p2, distance=outward * 4 * h, dimstyle="EZDXF",
                            override=_dim_override(h), dxfattribs={"layer": "DIM"}).render()
    for s in g.sprockets:
        if s.wrap_angle < math.radians(1.0):
            continue
        a0, a1 = _tangent_angles(s)
        start, end = (a0, a1) if s.turn > 0 else (a1, a0)
        msp.add_angular_dim_cra(center=(s.x * MM, s.y * MM),
                                radius=s.tip_diameter / 2 * MM + 1.5 * h, start_angle=start,
                                end_angle=end, distance=0.5 * h, dimstyle="EZDXF",
                                override={**_dim_override(h, 1), "dimaunit": 0},
                                dxfattribs={"layer": "DIM"}).render()


def _centre_table(msp: Modelspace, analysis: Analysis, origin: tuple[float, float],
                  h: float) -> None:
    """The sprockets' centres and pitch diameters as text lines below ``origin`` [mm]."""
    lines = ["Sprocket centres (mm): name, teeth, x, y, pitch diameter"]
    lines += [f"{s.name}: z = {s.teeth}, x = {dimension(s.x * MM)}, y = {dimension(s.y * MM)}, "
              f"d = {dimension(s.pitch_diameter * MM)}" for s in analysis.geometry.sprockets]
    for i, line in enumerate(lines):
        _text(msp, line, (origin[0], origin[1] - 1.6 * h * i), h * (0.9 if i else 1.0))


def _layout_sheet(msp: Modelspace, analysis: Analysis, h: float) -> tuple[float, float, float]:
    """The layout with its dimensions, centre table and title block; returns the left edge,
    the bottom and the right edge used [mm]."""
    g = analysis.geometry
    _layout_entities(msp, analysis, h)
    _layout_dimensions(msp, analysis, h)
    left = min((s.x - s.tip_diameter / 2) * MM for s in g.sprockets) - 6 * h
    right = max((s.x + s.tip_diameter / 2) * MM for s in g.sprockets) + 6 * h
    bottom = min((s.y - s.tip_diameter / 2) * MM for s in g.sprockets) - 7 * h
    _centre_table(msp, analysis, (left, bottom), h)
    spec = analysis.drive.chain.spec
    rows = [("chain drive layout", analysis.drive.name),
            ("chain", spec.designation),
            ("links", f"{g.links} (length {dimension(g.chain_length * MM, 1)} mm)"),
            ("tooth form", analysis.drive.tooth_form), *_stamp(analysis)[1:]]
    table_bottom = bottom - 1.6 * h * (len(g.sprockets) + 1)
    _title_block(msp, (right, table_bottom), h, rows)
    return left, table_bottom - 2 * h, right


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
    """Text height [mm] of a layout: 1/40 of the largest tip diameter, at least 2.5 mm."""
    biggest = max(s.tip_diameter for s in analysis.geometry.sprockets) * MM
    span = max(np.ptp([s.x for s in analysis.geometry.sprockets]),
               np.ptp([s.y for s in analysis.geometry.sprockets])) * MM
    return float(max(2.5, round(max(biggest / 40, float(span) / 150), 1)))


# --- one sprocket ------------------------------------------------------------------------------

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
                f"Root diameter Di = {d(form.root_diameter * MM, 3)}",
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
    return [f"Tooth form ISO 606, z = {f.teeth} (drawn: the mean of the two tooth-gap forms)",
            f"Pitch diameter d = {d(f.pitch_diameter * MM, 3)}",
            f"Tip diameter da = {d(f.tip_diameter_min * MM, 3)} … {d(f.tip_diameter_max * MM, 3)}",
            f"Root diameter df = {d(f.root_diameter_min * MM, 3)} … "
            f"{d(f.root_diameter_max * MM, 3)} (d − 2 ri)",
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


def _sprocket_sheet(msp: Modelspace, analysis: Analysis, index: int,
                    origin: tuple[float, float], h: float) -> float:
    """The drawing of sprocket ``index`` with its centre at ``origin`` [mm]; returns the
    width it takes [mm]."""
    g = analysis.geometry.sprockets[index]
    profile = analysis.profiles[index]
    spec = analysis.drive.chain.spec
    cx, cy = origin
    pts = outline_mm(profile) + np.asarray(origin)
    msp.add_lwpolyline(pts.tolist(), close=True, dxfattribs={"layer": "OUTLINE"})
    ra = float(np.max(np.hypot(pts[:, 0] - cx, pts[:, 1] - cy)))
    bore = profile.bore_diameter * MM
    hub = profile.hub_limit_diameter * MM
    msp.add_circle(origin, bore / 2, dxfattribs={"layer": "BORE"})
    if hub > bore:
        msp.add_circle(origin, hub / 2, dxfattribs={"layer": "HUB"})
    msp.add_circle(origin, g.pitch_diameter / 2 * MM, dxfattribs={"layer": "PITCH"})
    _centre_mark(msp, origin, 1.1 * ra)
    tip_text, root_text = _limits_text(profile)
    for d, angle, text in ((g.pitch_diameter * MM, 30.0, "<>"),
                           (2 * ra, 70.0, tip_text), (bore, -35.0, "<>")):
        msp.add_diameter_dim(origin, radius=d / 2, angle=angle, dimstyle="EZ_RADIUS",
                             override=_dim_override(0.8 * h), text=text,
                             dxfattribs={"layer": "DIM"}).render()
    root = float(np.min(np.hypot(pts[:, 0] - cx, pts[:, 1] - cy)))
    msp.add_diameter_dim(origin, radius=root, angle=-70.0, dimstyle="EZ_RADIUS",
                         override=_dim_override(0.8 * h), text=root_text,
                         dxfattribs={"layer": "DIM"}).render()
    x_text = cx + ra + 3 * h
    lines = [
        *tooth_form_lines(profile),
        f"Bore d0 = {dimension(bore, 1)} (0.19·z·p/π; fit to the shaft to be chosen)",
        f"Hub diameter at most dg = {dimension(hub, 1)} (ISO 606: p·cot(180°/z) − 1.04 h2 "
        "− 0.76 mm)", "Outline: one closed polyline on layer OUTLINE; bore on layer BORE."]
    if profile.body is not None:
        lines += _polymer_body(msp, profile, profile.body, origin, ra, h)
    for i, line in enumerate(lines):
        _text(msp, line, (x_text, cy + ra - 1.5 * h * i), 0.75 * h)
    rows = [(f"sprocket {g.name}", f"{g.teeth} teeth"), ("chain", spec.designation),
            ("material", f"{profile.material} ({profile.density:.0f} kg/m³), mass "
                         f"{profile.mass.mass:.3g} kg"),
            ("tooth form", analysis.drive.tooth_form), *_stamp(analysis)]
    width = ra + 3 * h + 0.5 * h * max(len(x) for x in lines)
    _title_block(msp, (cx + width, cy - ra - 3 * h), 0.8 * h, rows)
    return width + ra


def _limits_text(profile: SprocketProfile) -> tuple[str, str]:
    """Text of the tip and root diameter dimensions with the standard's limits."""
    if profile.standard == "GOST 591":
        form = cast("Gost591ToothForm", profile.form)
        return (f"%%c{dimension(form.tip_diameter * MM, 1)}",
                f"%%c{dimension(form.root_diameter * MM, 3)}")
    iso = cast("ToothForm", profile.form)
    return (f"%%c{dimension(iso.tip_diameter_min * MM, 2)} … "
            f"{dimension(iso.tip_diameter_max * MM, 2)}",
            f"%%c{dimension(iso.root_diameter_min * MM, 2)} … "
            f"{dimension(iso.root_diameter_max * MM, 2)}")


def _polymer_body(msp: Modelspace, profile: SprocketProfile, p: PolymericProportions,
                  centre: tuple[float, float], ra: float, h: float) -> list[str]:
    """Face-view circles and the axial half-section of a polymeric body
    [MultimassChainDrives, §3.4]; returns the text lines (mass, inertia, proportions)."""
    cx, cy = centre
    for d in (p.hub_outer_diameter, p.rim_inner_diameter):
        msp.add_circle(centre, d / 2 * MM, dxfattribs={"layer": "BODY"})
    hole = 0.5 * (p.rim_inner_diameter - p.hub_outer_diameter) / 2 * MM
    for k in range(6):
        a = 2 * math.pi * k / 6
        msp.add_circle((cx + p.hole_circle_diameter / 2 * MM * math.cos(a),
                        cy + p.hole_circle_diameter / 2 * MM * math.sin(a)), hole / 2,
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
    x0 = cx - ra - 3 * h - p.hub_length * MM
    for sign in (1.0, -1.0):
        msp.add_lwpolyline([(x0 + a * MM, cy + sign * r * MM) for a, r in half], close=True,
                           dxfattribs={"layer": "BODY"})
    msp.add_line((x0 - p.hub_length * MM, cy), (x0 + p.hub_length * MM, cy),
                 dxfattribs={"layer": "CENTER"})
    _text(msp, "Section A–A", (x0, cy + d / 2 * MM + h), 0.8 * h, "BOTTOM_CENTER")
    return [f"Polymeric body: mass = {profile.mass.mass:.4g} kg, inertia = "
            f"{profile.mass.moment_of_inertia:.4g} kg·m²",
            f"Hub Ø {dimension(p.hub_outer_diameter * MM, 1)} × {dimension(p.hub_length * MM, 1)}"
            f", web {dimension(p.web_thickness * MM, 1)} thick, rim from Ø "
            f"{dimension(p.rim_inner_diameter * MM, 1)}, {dimension(p.rim_width * MM, 1)} wide",
            f"Six lightening holes Ø {dimension(hole, 1)} on Ø "
            f"{dimension(p.hole_circle_diameter * MM, 1)}"]


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
    _sprocket_sheet(doc.modelspace(), analysis, i, (0.0, 0.0), max(2.5, round(tip / 40, 1)))
    return doc


def drawing_document(analysis: Analysis) -> Drawing:
    """The layout and, below it, every sprocket's manufacturing drawing side by side
    (ezdxf document, mm).

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
    x, bottom, _ = _layout_sheet(msp, analysis, h)
    biggest = max(s.tip_diameter for s in analysis.geometry.sprockets) * MM
    y = bottom - biggest / 2 - 6 * h
    for i, s in enumerate(analysis.geometry.sprockets):
        r = s.tip_diameter / 2 * MM
        x += _sprocket_sheet(msp, analysis, i, (x + r, y), h) + 4 * h
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
