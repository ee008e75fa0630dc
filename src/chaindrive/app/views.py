"""What the page shows, computed without Streamlit: the contour drawn to scale as SVG, the
headline numbers, the pass/fail checks and the rows of the result tables.

The layout is drawn here as SVG rather than with :func:`chaindrive.plotting.contour_layout`
because the page redraws it on every edit: the SVG of a 24-sprocket contour takes about a
millisecond, a matplotlib PNG of it about a second (the report keeps the matplotlib figure).
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.display import check_row

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.geometry.results import GeometryResult, SprocketGeometry

MM = 1e3
#: Colours of the figures of :mod:`chaindrive.plotting` (Okabe–Ito), reused for the SVG.
TIGHT, CHAIN, PITCH, GREY = "#D55E00", "#0072B2", "#009E73", "#7f7f7f"

@dataclass(frozen=True, slots=True)
class Check:
    """One check as the page shows it: what, its value (in the unit it is read in), the
    requirement, the result (``pass``, ``FAIL``, ``CANNOT BE VERIFIED``) and its source."""

    name: str
    value: float | None
    required: str
    result: str
    source: str

    @property
    def passed(self) -> bool:
        """True when the check passes."""
        return self.result == "pass"


# --- layout -----------------------------------------------------------------------------------

def _wrap_points(s: SprocketGeometry, samples: int = 48) -> np.ndarray:
    """Points [m] of the chain's wrap on the pitch circle, arrive → leave in the direction the
    sprocket turns (the same construction as :func:`chaindrive.plotting.layout`)."""
    a0 = math.atan2(s.arrive[1] - s.y, s.arrive[0] - s.x)
    angles = a0 + s.turn * np.linspace(0.0, s.wrap_angle, samples)
    return np.column_stack([s.x + s.pitch_radius * np.cos(angles),
                            s.y + s.pitch_radius * np.sin(angles)])


def _pts(points: np.ndarray) -> str:
    """SVG points (mm, y down) of points [m] (y up)."""
    return " ".join(f"{x * MM:.2f},{-y * MM:.2f}" for x, y in points)


def _arrow(mid: tuple[float, float], direction: tuple[float, float], size: float,
           colour: str) -> str:
    """A filled triangle [mm] at ``mid`` [mm, y up] pointing along ``direction``."""
    dx, dy = direction
    nx, ny = -dy, dx
    tip = (mid[0] + dx * size, mid[1] + dy * size)
    left = (mid[0] - dx * size + nx * 0.6 * size, mid[1] - dy * size + ny * 0.6 * size)
    right = (mid[0] - dx * size - nx * 0.6 * size, mid[1] - dy * size - ny * 0.6 * size)
    pts = " ".join(f"{x:.2f},{-y:.2f}" for x, y in (tip, left, right))
    return f'<polygon points="{pts}" fill="{colour}"/>'


def layout_svg(geometry: GeometryResult, *, highlight: str | None = None,
               max_height_px: int = 520) -> str:
    """The contour to scale as an SVG document [mm]: tip circles (grey discs), pitch circles
    (dash-dot), centre marks, the chain (blue; the tight span red) with an arrow per span in
    the direction of travel, names with tooth counts; the sprocket named ``highlight`` is
    outlined in red."""
    tips = np.array([s.tip_diameter / 2 for s in geometry.sprockets]) * MM
    xs = np.array([s.x for s in geometry.sprockets]) * MM
    ys = np.array([s.y for s in geometry.sprockets]) * MM
    x0, x1 = float((xs - tips).min()), float((xs + tips).max())
    y0, y1 = float((ys - tips).min()), float((ys + tips).max())
    size = max(x1 - x0, y1 - y0, 1.0)
    pad = 0.06 * size
    font = 0.022 * size
    box = (x0 - pad, -(y1 + pad + 1.6 * font), x1 - x0 + 2 * pad, y1 - y0 + 2 * pad + 1.6 * font)
    stroke = 'vector-effect="non-scaling-stroke"'
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{box[0]:.1f} {box[1]:.1f} '
             f'{box[2]:.1f} {box[3]:.1f}" style="width:100%;max-height:{max_height_px}px" '
             f'role="img" aria-label="contour layout to scale">',
             f'<rect x="{box[0]:.1f}" y="{box[1]:.1f}" width="{box[2]:.1f}" '
             f'height="{box[3]:.1f}" fill="white"/>']
    for s, r in zip(geometry.sprockets, tips, strict=True):
        cx, cy = s.x * MM, -s.y * MM
        edge = TIGHT if s.name == highlight else GREY
        width = 2.5 if s.name == highlight else 0.8
        parts.append(f'<circle cx="{cx:.2f}" cy="{cy:.2f}" r="{r:.2f}" fill="#f2f2f2" '
                     f'stroke="{edge}" stroke-width="{width}" {stroke}/>')
        parts.append(f'<circle cx="{cx:.2f}" cy="{cy:.2f}" r="{s.pitch_radius * MM:.2f}" '
                     f'fill="none" stroke="{PITCH}" stroke-width="0.8" '
                     f'stroke-dasharray="8 3 2 3" {stroke}/>')
        m = 0.15 * s.pitch_radius * MM
        parts.append(f'<path d="M{cx - m:.2f},{cy:.2f}H{cx + m:.2f}M{cx:.2f},{cy - m:.2f}'
                     f'V{cy + m:.2f}" stroke="{GREY}" stroke-width="0.8" {stroke}/>')
        parts.append(f'<polyline points="{_pts(_wrap_points(s))}" fill="none" '
                     f'stroke="{CHAIN}" stroke-width="2" {stroke}/>')
        parts.append(f'<text x="{cx:.2f}" y="{cy - r - 0.4 * font:.2f}" font-size="{font:.1f}" '
                     f'text-anchor="middle" font-family="sans-serif">'
                     f'{html.escape(s.name)} (z = {s.teeth})</text>')
    for span in geometry.spans:
        colour = TIGHT if span.tight else CHAIN
        (ax, ay), (bx, by) = span.start_point, span.end_point
        parts.append(f'<line x1="{ax * MM:.2f}" y1="{-ay * MM:.2f}" x2="{bx * MM:.2f}" '
                     f'y2="{-by * MM:.2f}" stroke="{colour}" stroke-width="2" {stroke}/>')
        parts.append(_arrow((0.5 * (ax + bx) * MM, 0.5 * (ay + by) * MM), span.direction,
                            0.9 * font, colour))
    parts.append(f'<text x="{box[0] + 0.3 * pad:.1f}" y="{box[1] + 1.3 * font:.1f}" '
                 f'font-size="{font:.1f}" font-family="sans-serif" fill="{GREY}">'
                 f'{geometry.links} links · {geometry.chain_length * MM:.1f} mm of chain · '
                 f'red: tight span · green dash-dot: pitch circles</text>')
    parts.append("</svg>")
    return "".join(parts)


# --- numbers ----------------------------------------------------------------------------------

def headline(document: dict[str, Any]) -> dict[str, Any]:
    """The numbers always on screen, from the JSON document of the analysis."""
    g, k, d = document["geometry"], document["kinematics"], document["drive"]
    return {
        "chain": d["chain"],
        "links": g["links"],
        "chain_length_mm": g["chain_length_mm"],
        "slack_mm": g["slack_mm"],
        "adjusted_sprocket": g["adjusted_sprocket"],
        "adjustment_mm": g["adjustment_mm"],
        "chain_speed_m_s": k["chain_speed_m_s"],
        "tooth_frequency_hz": k["tooth_frequency_hz"],
    }


def checks(analysis: Analysis) -> list[Check]:
    """The checks of the analysis (:meth:`chaindrive.analysis.Analysis.checks`), as shown."""
    return [Check(*check_row(c)) for c in analysis.checks()]


def _r(value: Any, digits: int = 2) -> Any:
    """A float rounded for a table cell (other values as they are)."""
    return round(value, digits) if isinstance(value, float) else value


def check_records(items: list[Check]) -> list[dict[str, Any]]:
    """Rows of the checks table (failed first)."""
    ordered = sorted(items, key=lambda c: c.passed)
    return [{"check": c.name, "value": None if c.value is None else float(f"{c.value:.4g}"),
             "required": c.required, "result": c.result, "source": c.source} for c in ordered]


def sprocket_records(document: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of the geometry-and-speed table of the sprockets."""
    speeds = {s["name"]: s for s in document["kinematics"]["sprockets"]}
    rows = []
    for s in document["geometry"]["sprockets"]:
        k = speeds.get(s["name"], {})
        rows.append({"name": s["name"], "teeth": s["teeth"], "x mm": _r(s["x_mm"]),
                     "y mm": _r(s["y_mm"]), "pitch Ø mm": _r(s["pitch_diameter_mm"]),
                     "tip Ø mm": _r(s["tip_diameter_mm"]), "wrap °": _r(s["wrap_angle_deg"], 1),
                     "teeth in mesh": _r(s["teeth_in_mesh"], 1),
                     "speed rpm": _r(k.get("speed_rpm"), 1), "direction": k.get("direction"),
                     "speed variation %": _r(k.get("speed_variation_percent"), 3)})
    return rows


def span_records(document: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of the span table (with the static tensions when the strength part exists)."""
    st = document.get("strength") or {}
    tensions = st.get("span_tensions_n") or [None] * len(document["geometry"]["spans"])
    return [{"span": f"{s['from']} → {s['to']}", "length mm": _r(s["length_mm"]),
             "pitches": _r(s["length_pitches"], 3), "inclination °": _r(s["inclination_deg"]),
             "tight": s["tight"], "tension N": _r(t, 1)}
            for s, t in zip(document["geometry"]["spans"], tensions, strict=True)]


def resonance_records(document: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of the resonance table: working frequency, nearest natural one, margin."""
    return [{"working": r["label"], "f working Hz": _r(r["frequency_hz"]),
             "mode": r["mode"], "f natural Hz": _r(r["natural_frequency_hz"]),
             "margin %": _r(r["margin_percent"], 1)}
            for r in document["dynamics"].get("resonances") or []]


def modal_records(document: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of the natural-frequency table (elastic modes; ``rigid_body_modes`` is one flag
    per mode)."""
    dyn = document["dynamics"]
    rigid = dyn["rigid_body_modes"]
    return [{"mode": j, "natural Hz": _r(f), "damped Hz": _r(fd)}
            for j, (f, fd) in enumerate(zip(dyn["natural_frequencies_hz"],
                                            dyn["damped_frequencies_hz"], strict=True))
            if not rigid[j]]


@dataclass(frozen=True, slots=True, eq=False)
class Screen:
    """Everything the page redraws after an edit: the outcome of the evaluation and, when
    the design was analysed, its JSON document, headline numbers, checks and layout SVG."""

    outcome: Any
    document: dict[str, Any] | None = None
    numbers: dict[str, Any] | None = None
    checks: tuple[Check, ...] = ()
    svg: str | None = None


def recompute(design: dict[str, Any], catalogs: dict[str, Path] | None = None) -> Screen:
    """Evaluate the design mapping and derive what is always on screen (the work the page
    does after every edit; timed by ``benchmarks/bench_app_recompute.py``); ``catalogs``:
    the session's uploaded catalogues (:func:`chaindrive.app.state.evaluate`)."""
    from chaindrive.app.state import evaluate

    outcome = evaluate(design, catalogs=catalogs)
    if outcome.analysis is None:
        return Screen(outcome)
    analysis = outcome.analysis
    document = analysis.to_dict()
    return Screen(outcome, document, headline(document), tuple(checks(analysis)),
                  layout_svg(analysis.geometry))
