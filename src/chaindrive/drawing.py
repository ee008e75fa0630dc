"""Drawings for CAD: the contour layout and each sprocket's tooth profile, as DXF (ezdxf) or
SVG (rendered from the same DXF document by ezdxf's drawing add-on). Model units: mm.

Layers: ``PITCH`` pitch circles (one CIRCLE per sprocket in the layout), ``TIP`` tip
circles, ``ROOT`` root circles, ``CHAIN`` spans and wrap arcs, ``CENTER`` centre marks,
``PROFILE`` toothed outlines, ``BODY`` polymeric sprocket bodies, ``DIM`` dimensions,
``TEXT`` labels and dimension lists.

Tooth profiles (built here from the dimensions of :mod:`chaindrive.geometry.sprocket`):

* GOST 591-69 (Anuriev т. 2 гл. 5; shared/data/gost591_sprocket_profile.md §1.3): seating
  arc r over the half space angle α, joining arc r1 centred at O1 = 0.8·d1·(sin α, cos α)
  over β, the straight part FC, and the head arc r2 centred at
  O2 = 1.24·d1·(cos 180°/z, sin 180°/z) up to the tip circle De (drawn without the offset
  e of the root-arc centres, which GOST 591 permits);
* ISO 606 (mean of the minimum and maximum tooth-gap forms): seating arc ri over the seating
  angle α, then the convex flank arc re tangent to it, up to the tip circle da (mean).

The profile of a tooth gap is drawn in a frame at the seat centre (x along the tangent, y
radial outward); teeth end on the tip circle or where the flanks of neighbouring gaps meet.
Polymeric sprockets (material of the polymer family): face view with bore, hub, web holes
and rim, and an axial half-section from seed 000 §3.4 (seed-notes §7) with mass and inertia
from :func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.geometry.results import SprocketGeometry
    from chaindrive.geometry.sprocket import Gost591ToothForm, ToothForm
    from chaindrive.model import Drive

MM = 1e3  # metres → millimetres
LAYERS = {"PITCH": 3, "TIP": 8, "ROOT": 8, "CHAIN": 5, "CENTER": 1, "PROFILE": 7,
          "BODY": 30, "DIM": 6, "TEXT": 7}
FORMATS = (".dxf", ".svg")


# --- tooth profile geometry (pure, metres) ---------------------------------------------------

def _arc(centre: NDArray[np.float64], radius: float, a0: float, a1: float,
         samples: int) -> NDArray[np.float64]:
    t = np.linspace(a0, a1, samples)
    return centre + radius * np.column_stack([np.cos(t), np.sin(t)])


def gost591_gap_wall(form: Gost591ToothForm, samples: int = 10) -> NDArray[np.float64]:
    """The left wall (x < 0) of a GOST 591-69 tooth gap in the seat frame [m], from the
    bottom of the seat up along the head arc (longer than needed; clipped later)."""
    d1, a, b = form.roller_diameter, form.half_space_angle, form.joining_angle
    r, r1, r2, fc = form.seating_radius, form.joining_radius, form.head_radius, form.straight_part
    t = np.linspace(0.0, a, samples)
    seat = r * np.column_stack([-np.sin(t), -np.cos(t)])
    o1 = 0.8 * d1 * np.array([math.sin(a), math.cos(a)])
    t = np.linspace(a, a + b, samples)
    joint = o1 + r1 * np.column_stack([-np.sin(t), -np.cos(t)])
    p3 = joint[-1] + fc * np.array([-math.cos(a + b), math.sin(a + b)])
    o2 = 1.24 * d1 * np.array([-math.cos(math.pi / form.teeth), -math.sin(math.pi / form.teeth)])
    a0 = math.atan2(p3[1] - o2[1], p3[0] - o2[0])
    head = _arc(o2, r2, a0, a0 + math.radians(150), 3 * samples)
    return np.vstack([seat, joint, head])


def iso606_gap_wall(form: ToothForm, samples: int = 10) -> NDArray[np.float64]:
    """The left wall of an ISO 606 tooth gap (mean form) in the seat frame [m]: seating arc
    ri over half the seating angle, then the convex flank re tangent to it."""
    ri, re = form.seating_radius_mean, form.flank_radius_mean
    half = 0.25 * (form.seating_angle_min + form.seating_angle_max)
    t = np.linspace(0.0, half, samples)
    seat = ri * np.column_stack([-np.sin(t), -np.cos(t)])
    d = np.array([-math.sin(half), -math.cos(half)])
    centre = (ri + re) * d
    a0 = math.atan2(-d[1], -d[0])
    sweep = math.radians(60)
    # the flank turns towards the tooth (away from the gap): pick the sense that rises
    sense = 1.0 if _arc(centre, re, a0, a0 + 1e-3, 2)[1, 1] > seat[-1, 1] else -1.0
    flank = _arc(centre, re, a0, a0 + sense * sweep, 4 * samples)
    return np.vstack([seat, flank])


def _clip_wall(wall: NDArray[np.float64], seat: NDArray[np.float64], u_r: NDArray[np.float64],
               tip_radius: float, half_pitch_angle: float) -> NDArray[np.float64]:
    """Wall points (global, centred on the sprocket) up to the tip circle or the tooth's
    bisector, with the crossing point interpolated."""
    u_t = np.array([-u_r[1], u_r[0]])
    pts = seat + wall[:, :1] * u_t + wall[:, 1:] * u_r
    rel = np.arctan2(pts @ u_t, pts @ u_r)
    f = np.maximum(np.hypot(pts[:, 0], pts[:, 1]) / tip_radius - 1.0,
                   (np.abs(rel) - half_pitch_angle) / half_pitch_angle)
    out = np.flatnonzero(f >= 0)
    if out.size == 0:
        return pts
    k = int(out[0])
    if k == 0:
        return pts[:1]
    s = f[k - 1] / (f[k - 1] - f[k])
    return np.vstack([pts[:k], pts[k - 1] + s * (pts[k] - pts[k - 1])])


def sprocket_outline(wall: NDArray[np.float64], teeth: int, pitch_radius: float,
                     tip_radius: float) -> NDArray[np.float64]:
    """Closed outline [m] of a toothed sprocket centred at the origin from the left wall of
    one tooth gap (seat frame); gap k is centred at the angle 2πk/z."""
    half = math.pi / teeth
    parts = []
    for k in range(teeth):
        th = 2 * math.pi * k / teeth
        u_r = np.array([math.cos(th), math.sin(th)])
        seat = pitch_radius * u_r
        left = _clip_wall(wall, seat, u_r, tip_radius, half)
        right = _clip_wall(wall * np.array([-1.0, 1.0]), seat, u_r, tip_radius, half)
        parts.append(np.vstack([left[::-1], right[1:]]))
        rel = math.remainder(math.atan2(right[-1, 1], right[-1, 0]) - th, 2 * math.pi)
        if np.hypot(*right[-1]) > 0.999 * tip_radius:
            # from this gap's right end to the next gap's left end (by symmetry)
            t = np.linspace(th + rel, th + 2 * half - rel, 5)[1:-1]
            parts.append(tip_radius * np.column_stack([np.cos(t), np.sin(t)]))
    return np.vstack(parts)


def tooth_form_of(drive: Drive, teeth: int) -> Gost591ToothForm | ToothForm:
    """The tooth form of a sprocket of ``drive`` by the drive's standard."""
    from chaindrive.geometry.sprocket import gost591_tooth_form, iso606_tooth_form

    spec = drive.chain.spec
    if drive.tooth_form == "GOST 591":
        return gost591_tooth_form(spec.pitch, teeth, spec.roller_diameter, spec.inner_width)
    return iso606_tooth_form(spec.pitch, teeth, spec.roller_diameter, spec.inner_width,
                             spec.strands)


def outline_of(form: Gost591ToothForm | ToothForm) -> NDArray[np.float64]:
    """Closed toothed outline [m] of a sprocket with this tooth form (centred at 0)."""
    from chaindrive.geometry.sprocket import Gost591ToothForm

    if isinstance(form, Gost591ToothForm):
        return sprocket_outline(gost591_gap_wall(form), form.teeth, form.pitch_diameter / 2,
                                form.tip_diameter / 2)
    return sprocket_outline(iso606_gap_wall(form), form.teeth, form.pitch_diameter / 2,
                            form.tip_diameter_mean / 2)


def dimension_lines(form: Gost591ToothForm | ToothForm) -> list[str]:
    """The form's dimensions as text lines (mm, degrees)."""
    lines = [f"{form.standard}, z = {form.teeth}"]
    for key, value in form.to_dict().items():
        if key in ("teeth", "standard", "pitch_mm"):
            continue
        lines.append(f"{key} = {value:.3f}" if isinstance(value, float) else f"{key} = {value}")
    return lines


# --- DXF document ---------------------------------------------------------------------------

def _text(msp: Any, text: str, at: tuple[float, float], height: float,
          align: str = "MIDDLE_LEFT", layer: str = "TEXT") -> None:
    from ezdxf.enums import TextEntityAlignment

    msp.add_text(text, height=height, dxfattribs={"layer": layer}).set_placement(
        at, align=TextEntityAlignment[align])


def _centre_mark(msp: Any, c: tuple[float, float], size: float) -> None:
    msp.add_line((c[0] - size, c[1]), (c[0] + size, c[1]), dxfattribs={"layer": "CENTER"})
    msp.add_line((c[0], c[1] - size), (c[0], c[1] + size), dxfattribs={"layer": "CENTER"})


def _layout(msp: Any, analysis: Analysis, h: float) -> None:
    """Contour layout at its real coordinates [mm]."""
    for s in analysis.geometry.sprockets:
        c = (s.x * MM, s.y * MM)
        msp.add_circle(c, s.pitch_radius * MM, dxfattribs={"layer": "PITCH"})
        msp.add_circle(c, s.tip_diameter / 2 * MM, dxfattribs={"layer": "TIP"})
        _centre_mark(msp, c, 0.2 * s.pitch_radius * MM)
        a0 = math.degrees(math.atan2(s.arrive[1] - s.y, s.arrive[0] - s.x))
        a1 = math.degrees(math.atan2(s.leave[1] - s.y, s.leave[0] - s.x))
        start, end = (a0, a1) if s.turn > 0 else (a1, a0)  # DXF arcs run counter-clockwise
        if s.wrap_angle > 1e-9:
            msp.add_arc(c, s.pitch_radius * MM, start, end, dxfattribs={"layer": "CHAIN"})
        _text(msp, f"{s.name} z={s.teeth} d={s.pitch_diameter * MM:.2f}",
              (c[0], c[1] + s.tip_diameter / 2 * MM + h), h, "BOTTOM_CENTER")
    for sp in analysis.geometry.spans:
        msp.add_line(tuple(v * MM for v in sp.start_point), tuple(v * MM for v in sp.end_point),
                     dxfattribs={"layer": "CHAIN"})


def _detail(msp: Any, drive: Drive, s: SprocketGeometry, centre: tuple[float, float],
            h: float) -> float:
    """One sprocket drawn at ``centre`` [mm]: outline, circles, dimensions, text; returns
    the width used [mm]."""
    form = tooth_form_of(drive, s.teeth)
    pts = outline_of(form) * MM + np.asarray(centre)
    msp.add_lwpolyline(pts.tolist(), close=True, dxfattribs={"layer": "PROFILE"})
    ra = float(np.max(np.hypot(*(pts - centre).T)))
    for layer, d, angle in (("PITCH", s.pitch_diameter, 30.0), ("ROOT", s.root_diameter, -30.0),
                            ("TIP", 2 * ra / MM, 75.0)):
        msp.add_circle(centre, d / 2 * MM, dxfattribs={"layer": layer})
        msp.add_diameter_dim(centre, radius=d / 2 * MM, angle=angle, dimstyle="EZ_RADIUS",
                             override={"dimtxt": h, "dimasz": h, "dimdec": 2, "dimlfac": 1.0},
                             dxfattribs={"layer": "DIM"}).render()
    _centre_mark(msp, centre, 0.15 * ra)
    x_text = centre[0] + ra + 2 * h
    lines = [f"{s.name}", *dimension_lines(form)]
    width = 2 * ra + 2 * h + 32 * h
    sprocket = drive.sprockets[[p.name for p in drive.sprockets].index(s.name)]
    material = _material(sprocket.material)
    if material is not None and material.is_polymer:
        lines += _polymer_body(msp, drive, s.teeth, material, centre, ra, h)
        width += 6 * h + _body_width(drive, s.teeth)
    for i, line in enumerate(lines):
        _text(msp, line, (x_text, centre[1] + ra - 1.6 * h * i), h * (1.2 if i == 0 else 0.8))
    return width


def _material(name: str) -> Any:
    from chaindrive.catalog import find_material
    from chaindrive.errors import ChainDriveError

    try:
        return find_material(name)
    except ChainDriveError:
        return None


def _body_width(drive: Drive, teeth: int) -> float:
    from chaindrive.geometry.sprocket import polymeric_sprocket_proportions

    spec = drive.chain.spec
    return polymeric_sprocket_proportions(spec.pitch, teeth, spec.inner_width).hub_length * MM


def _polymer_body(msp: Any, drive: Drive, teeth: int, material: Any,
                  centre: tuple[float, float], ra: float, h: float) -> list[str]:
    """Face-view circles and the axial half-section of a polymeric body (seed 000 §3.4);
    returns the text lines (mass, inertia, proportions)."""
    from chaindrive.geometry.sprocket import (
        polymeric_sprocket_proportions,
        sprocket_mass_and_inertia,
    )

    spec = drive.chain.spec
    p = polymeric_sprocket_proportions(spec.pitch, teeth, spec.inner_width)
    mass = sprocket_mass_and_inertia(spec.pitch, teeth, spec.inner_width, material.density,
                                     polymeric=True)
    cx, cy = centre
    for d in (p.bore_diameter, p.hub_outer_diameter, p.rim_inner_diameter):
        msp.add_circle(centre, d / 2 * MM, dxfattribs={"layer": "BODY"})
    hole = 0.5 * (p.rim_inner_diameter - p.hub_outer_diameter) / 2 * MM
    for k in range(6):
        a = 2 * math.pi * k / 6
        msp.add_circle((cx + p.hole_circle_diameter / 2 * MM * math.cos(a),
                        cy + p.hole_circle_diameter / 2 * MM * math.sin(a)), hole / 2,
                       dxfattribs={"layer": "BODY"})
    d = spec.pitch / math.sin(math.pi / teeth)
    half = [(-p.hub_length / 2, p.bore_diameter / 2), (p.hub_length / 2, p.bore_diameter / 2),
            (p.hub_length / 2, p.hub_outer_diameter / 2),
            (p.web_thickness / 2, p.hub_outer_diameter / 2),
            (p.web_thickness / 2, p.rim_inner_diameter / 2),
            (p.rim_width / 2, p.rim_inner_diameter / 2), (p.rim_width / 2, d / 2),
            (-p.rim_width / 2, d / 2), (-p.rim_width / 2, p.rim_inner_diameter / 2),
            (-p.web_thickness / 2, p.rim_inner_diameter / 2),
            (-p.web_thickness / 2, p.hub_outer_diameter / 2),
            (-p.hub_length / 2, p.hub_outer_diameter / 2)]
    x0 = cx + ra + 34 * h + p.hub_length / 2 * MM
    for sign in (1.0, -1.0):
        msp.add_lwpolyline([(x0 + a * MM, cy + sign * r * MM) for a, r in half], close=True,
                           dxfattribs={"layer": "BODY"})
    msp.add_line((x0 - p.hub_length * MM, cy), (x0 + p.hub_length * MM, cy),
                 dxfattribs={"layer": "CENTER"})
    _text(msp, "section (seed 000 proportions)", (x0, cy + d / 2 * MM + h), 0.8 * h,
          "BOTTOM_CENTER")
    return [f"material {material.name}: {material.density:.0f} kg/m3",
            f"mass = {mass.mass:.4f} kg", f"inertia = {mass.moment_of_inertia:.4e} kg m2"] + [
        f"{k} = {v:.2f}" for k, v in p.to_dict().items()]


def drawing_document(analysis: Analysis) -> Any:
    """The ezdxf document (units mm): the contour layout at its coordinates, and below it
    every sprocket's profile with its dimensions, side by side."""
    import ezdxf

    doc = ezdxf.new("R2010", setup=True, units=4)
    for name, colour in LAYERS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    g = analysis.geometry
    biggest = max(s.tip_diameter for s in g.sprockets) * MM
    h = max(2.5, round(biggest / 40, 1))
    _layout(msp, analysis, h)
    bottom = min((s.y - s.tip_diameter / 2) * MM for s in g.sprockets)
    x = min((s.x - s.tip_diameter / 2) * MM for s in g.sprockets)
    y = bottom - 4 * h - biggest / 2
    _text(msp, f"{analysis.drive.name}: {analysis.drive.chain.spec.designation}, "
               f"{g.links} links, tooth form {analysis.drive.tooth_form}",
          (x, bottom - 2 * h), h)
    for s in g.sprockets:
        r = s.tip_diameter / 2 * MM
        x += _detail(msp, analysis.drive, s, (x + r, y - h), h) + 2 * h
    return doc


def write_drawing(analysis: Analysis, path: str | Path) -> Path:
    """Write the drawing as DXF or SVG (by the suffix of ``path``)."""
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in FORMATS:
        raise DesignError("output", f"must end in .dxf or .svg, got {out.name!r}")
    doc = drawing_document(analysis)
    out.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".dxf":
        doc.saveas(out)
    else:
        out.write_text(svg_string(doc), encoding="utf-8")
    return out


def svg_string(doc: Any, page_width_mm: float = 420.0) -> str:
    """The modelspace of ``doc`` as SVG (ezdxf drawing add-on) on a white page
    ``page_width_mm`` wide (A3 by default), scaled to fit; the DXF stays 1:1."""
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
