"""Drawings for CAD: the contour layout and each sprocket's tooth profile, as DXF (ezdxf) or
SVG (rendered from the same DXF document by ezdxf's drawing add-on). Model units: mm.

Layers: ``PITCH`` pitch circles (one CIRCLE per sprocket in the layout), ``TIP`` tip
circles, ``ROOT`` root circles, ``CHAIN`` spans and wrap arcs, ``CENTER`` centre marks,
``PROFILE`` toothed outlines, ``BODY`` polymeric sprocket bodies, ``DIM`` dimensions,
``TEXT`` labels and dimension lists.

Tooth profiles, outlines and polymeric bodies come from the analysis
(:attr:`chaindrive.analysis.Analysis.profiles`, :mod:`chaindrive.geometry.profile`).
Polymeric sprockets (material of the polymer family): face view with bore, hub, web holes
and rim, and an axial half-section from seed 000 §3.4 (seed-notes §7) with mass and inertia
from :func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.errors import DesignError
from chaindrive.io.atomic import atomic_path

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.geometry.profile import SprocketProfile
    from chaindrive.geometry.results import SprocketGeometry
    from chaindrive.geometry.sprocket import Gost591ToothForm, PolymericProportions, ToothForm

MM = 1e3  # metres → millimetres
LAYERS = {"PITCH": 3, "TIP": 8, "ROOT": 8, "CHAIN": 5, "CENTER": 1, "PROFILE": 7,
          "BODY": 30, "DIM": 6, "TEXT": 7}
FORMATS = (".dxf", ".svg")


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


def _detail(msp: Any, s: SprocketGeometry, profile: SprocketProfile,
            centre: tuple[float, float], h: float) -> float:
    """One sprocket drawn at ``centre`` [mm]: outline, circles, dimensions, text; returns
    the width used [mm]."""
    form = profile.form
    pts = profile.outline * MM + np.asarray(centre)
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
    if profile.body is not None:
        lines += _polymer_body(msp, profile, profile.body, centre, ra, h)
        width += 6 * h + profile.body.hub_length * MM
    for i, line in enumerate(lines):
        _text(msp, line, (x_text, centre[1] + ra - 1.6 * h * i), h * (1.2 if i == 0 else 0.8))
    return width


def _polymer_body(msp: Any, profile: SprocketProfile, p: PolymericProportions,
                  centre: tuple[float, float], ra: float, h: float) -> list[str]:
    """Face-view circles and the axial half-section of a polymeric body
    ([MultimassChainDrives, §3.4]); returns the text lines (mass, inertia, proportions)."""
    cx, cy = centre
    for d in (p.bore_diameter, p.hub_outer_diameter, p.rim_inner_diameter):
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
    x0 = cx + ra + 34 * h + p.hub_length / 2 * MM
    for sign in (1.0, -1.0):
        msp.add_lwpolyline([(x0 + a * MM, cy + sign * r * MM) for a, r in half], close=True,
                           dxfattribs={"layer": "BODY"})
    msp.add_line((x0 - p.hub_length * MM, cy), (x0 + p.hub_length * MM, cy),
                 dxfattribs={"layer": "CENTER"})
    _text(msp, "section (polymeric proportions)", (x0, cy + d / 2 * MM + h), 0.8 * h,
          "BOTTOM_CENTER")
    return [f"material {profile.material}: {profile.density:.0f} kg/m3",
            f"mass = {profile.mass.mass:.4f} kg",
            f"inertia = {profile.mass.moment_of_inertia:.4e} kg m2"] + [
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
    for s, profile in zip(g.sprockets, analysis.profiles, strict=True):
        r = s.tip_diameter / 2 * MM
        x += _detail(msp, s, profile, (x + r, y - h), h) + 2 * h
    return doc


def write_drawing(analysis: Analysis, path: str | Path) -> Path:
    """Write the drawing as DXF or SVG (by the suffix of ``path``)."""
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in FORMATS:
        raise DesignError("output", f"must end in .dxf or .svg, got {out.name!r}")
    doc = drawing_document(analysis)
    with atomic_path(out) as tmp:  # complete or absent, never half-written
        if suffix == ".dxf":
            doc.saveas(tmp)
        else:
            tmp.write_text(svg_string(doc), encoding="utf-8")
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
