"""What the page shows, computed without Streamlit: the contour drawn to scale as SVG, the
headline numbers, the pass/fail checks and the rows of the result tables.

The layout is drawn here as SVG rather than with :func:`chaindrive.plotting.contour_layout`
because the page redraws it on every edit: the SVG of a 24-sprocket contour takes about a
millisecond, a matplotlib PNG of it about a second (the report keeps the matplotlib figure).
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.app.state import Location, Outcome, locate
from chaindrive.display import (
    UnitSystem,
    candidate_verdict,
    check_line,
    check_row,
    clean,
    doc_value,
    fmt,
    header,
    margin_percent,
)
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.geometry.results import GeometryResult, SprocketGeometry

MM = 1e3
#: A table cell of a quantity that does not apply to its row (instead of "None").
NOT_APPLICABLE = "—"
#: The characters Streamlit's Markdown reads as markup (CommonMark's punctuation, the dollar
#: signs of its math, the tilde of strikethrough, the colon of its emoji shortcodes).
MARKDOWN_SPECIALS = frozenset("\\`*_{}[]()#+-.!|$~<>:&")


def plain(text: str) -> str:
    """``text`` as Markdown that shows it as written: every character Streamlit's Markdown
    reads as markup escaped with a backslash (CommonMark: a backslash before any ASCII
    punctuation stands for that character). A sprocket named ``$x$`` or ``**A**`` is shown
    so, not as a formula or in bold.

    Parameters
    ----------
    text : str
        Plain text (names, warnings, check lines).

    Returns
    -------
    str
        The Markdown.
    """
    return "".join("\\" + ch if ch in MARKDOWN_SPECIALS else ch for ch in text)
#: Height of the contour on the page [px]: it and the verdict fit above the fold at 900 px.
LAYOUT_HEIGHT_PX = 370
#: Colours of the figures of :mod:`chaindrive.plotting` (Okabe–Ito), reused for the SVG.
TIGHT, CHAIN, PITCH, GREY = "#D55E00", "#0072B2", "#009E73", "#7f7f7f"

@dataclass(frozen=True, slots=True)
class Check:
    """One check as the page shows it (:func:`chaindrive.display.check_row`).

    Parameters
    ----------
    name : str
        What is checked, with its subject.
    value : float | None
        The design's value in the unit it is read in [the check's display unit, e.g. MPa]
        (None: not computed).
    required : str
        The requirement as text (``≤ 35 MPa``).
    result : str
        ``pass``, ``FAIL`` or ``CANNOT BE VERIFIED``.
    source : str
        The rule's source, a key of docs/references.md.
    margin : float | None
        The margin [%] (≥ 0 passes; :attr:`chaindrive.checks.Check.margin_fraction`).
    line : str
        The line the page writes for it when it fails.
    """

    name: str
    value: float | None
    required: str
    result: str
    source: str
    margin: float | None = None
    line: str = ""

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
    (dash-dot), centre marks, the chain (blue; the tight span orange) with an arrow per span in
    the direction of travel, names with tooth counts; the sprocket named ``highlight`` is
    outlined in red.

    Parameters
    ----------
    geometry : GeometryResult
        The contour.
    highlight : str | None
        Name of the sprocket to outline (None: none).
    max_height_px : int
        Largest height of the drawing on the page [px].

    Returns
    -------
    str
        The SVG document (user units: mm, y down).
    """
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
                 f'orange: tight span · green dash-dot: pitch circles</text>')
    parts.append("</svg>")
    return "".join(parts)


# --- small charts -------------------------------------------------------------------------------

def _ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round tick values between ``lo`` and ``hi``."""
    span = hi - lo or abs(hi) or 1.0
    raw = span / count
    step = 10 ** math.floor(math.log10(raw))
    step *= next(m for m in (1, 2, 2.5, 5, 10) if m * step >= raw)
    first = math.ceil(lo / step) * step
    return [first + i * step for i in range(int((hi - first) / step + 1e-9) + 1)]


def line_chart_svg(x: Any, series: dict[str, Any], *, x_label: str, y_label: str,
                   width: int = 460, height: int = 220) -> str:
    """A small line chart as an SVG document (drawn in a millisecond, where a plotting
    library takes a good part of a second): the ``series`` (label → y values) against
    ``x``, with ticks, axis labels and a legend.

    Parameters
    ----------
    x : array_like
        Abscissae [the unit ``x_label`` names].
    series : dict of str to array_like
        Label → ordinates, one per abscissa [the unit ``y_label`` names].
    x_label, y_label : str
        Axis labels, with their units.
    width, height : int
        Size of the chart [px].

    Returns
    -------
    str
        The SVG document.
    """
    xs = np.asarray(x, dtype=float)
    ys = [np.asarray(v, dtype=float) for v in series.values()]
    y_lo = min(float(v.min()) for v in ys)
    y_hi = max(float(v.max()) for v in ys)
    pad = 0.08 * ((y_hi - y_lo) or abs(y_hi) or 1.0)
    y_lo, y_hi = y_lo - pad, y_hi + pad
    left, right, top, bottom = 58, 10, 24, 40
    w, h = width - left - right, height - top - bottom

    def px(v: Any) -> Any:
        return left + (v - xs.min()) / ((xs.max() - xs.min()) or 1.0) * w

    def py(v: Any) -> Any:
        return top + (y_hi - v) / ((y_hi - y_lo) or 1.0) * h

    font = 'font-family="sans-serif" font-size="11"'
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" '
             f'style="width:100%;max-width:{width}px" role="img" '
             f'aria-label="{html.escape(y_label)} against {html.escape(x_label)}">',
             f'<rect x="{left}" y="{top}" width="{w}" height="{h}" fill="white" '
             f'stroke="{GREY}" stroke-width="0.6"/>']
    for t in _ticks(y_lo, y_hi):
        parts.append(f'<line x1="{left}" x2="{left + w}" y1="{py(t):.1f}" y2="{py(t):.1f}" '
                     f'stroke="#e5e5e5"/><text x="{left - 4}" y="{py(t) + 4:.1f}" '
                     f'text-anchor="end" {font}>{html.escape(fmt(t))}</text>')
    for t in _ticks(float(xs.min()), float(xs.max())):
        parts.append(f'<text x="{px(t):.1f}" y="{top + h + 14}" text-anchor="middle" {font}>'
                     f'{html.escape(fmt(t))}</text>')
    colours = (CHAIN, TIGHT, PITCH, GREY)
    for i, (label, v) in enumerate(zip(series, ys, strict=True)):
        pts = " ".join(f"{a:.1f},{b:.1f}" for a, b in zip(px(xs), py(v), strict=True))
        colour = colours[i % len(colours)]
        parts.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" '
                     f'stroke-width="1.8"/><text x="{left + 6 + 150 * i}" y="{top - 8}" '
                     f'fill="{colour}" {font}>{html.escape(label)}</text>')
    parts.append(f'<text x="{left + w / 2:.0f}" y="{height - 6}" text-anchor="middle" '
                 f'{font}>{html.escape(x_label)}</text>')
    parts.append(f'<text transform="translate(12,{top + h / 2:.0f}) rotate(-90)" '
                 f'text-anchor="middle" {font}>{html.escape(y_label)}</text></svg>')
    return "".join(parts)


# --- numbers ----------------------------------------------------------------------------------

def headline(analysis: Analysis) -> dict[str, Any]:
    """The numbers always on screen (SI, from the analysis): chain, links, chain length,
    slack, take-up, chain speed, tooth frequency.

    Parameters
    ----------
    analysis : Analysis
        The design's analysis.

    Returns
    -------
    dict
        ``chain``, ``links``, ``chain_length_m``, ``slack_m``, ``adjusted_sprocket``,
        ``adjustment_m``, ``chain_speed_m_s``, ``tooth_frequency_hz`` (units in the keys).
    """
    g, k = analysis.geometry, analysis.kinematics
    return {
        "chain": analysis.drive.chain.spec.designation,
        "links": g.links,
        "chain_length_m": g.chain_length,
        "slack_m": g.slack,
        "adjusted_sprocket": None if g.adjusted is None else g.sprockets[g.adjusted].name,
        "adjustment_m": g.adjustment,
        "chain_speed_m_s": k.chain_speed,
        "tooth_frequency_hz": k.tooth_frequency,
    }


@shared_parameters
def checks(analysis: Analysis, units: UnitSystem = "SI") -> list[Check]:
    """The checks of the analysis (:meth:`chaindrive.analysis.Analysis.checks`), as shown,
    with the margin of :mod:`chaindrive.checks` in per cent (≥ 0 passes).

    Parameters
    ----------
    analysis : Analysis
        The design's analysis.
    %(units)s

    Returns
    -------
    list of Check
        One per check, in the analysis's order; its ``line`` (the verdict's) without the
        check's note, which the check table shows.
    """
    return [Check(*check_row(c, units), margin_percent(c),
                  check_line(replace(c, note=""), units))
            for c in analysis.checks()]


@shared_parameters
def check_records(items: list[Check]) -> list[dict[str, Any]]:
    """Rows of the checks table (failed first), numbers by the presenters' one rule.

    Parameters
    ----------
    items : list of Check
        The checks as shown (:func:`checks`).

    Returns
    -------
    %(returns_rows)s
    """
    ordered = sorted(items, key=lambda c: c.passed)
    return [{"check": c.name, "value": None if c.value is None else clean(c.value),
             "required": c.required,
             "margin %": None if c.margin is None else clean(c.margin, 3),
             "result": c.result, "source": c.source} for c in ordered]


def _row(item: dict[str, Any], cols: tuple[tuple[str, str], ...], units: UnitSystem
         ) -> dict[str, Any]:
    """One row of a result table: each (label, key) of the document part, the header with
    the unit of ``units`` and the number cleaned of round-off."""
    out: dict[str, Any] = {}
    for label, key in cols:
        value = doc_value(key, item.get(key), units)[0]
        out[header(label, key, units)] = clean(value) if isinstance(value, float) else value
    return out


@shared_parameters
def sprocket_records(document: dict[str, Any], units: UnitSystem = "SI"
                     ) -> list[dict[str, Any]]:
    """Rows of the geometry-and-speed table of the sprockets.

    %(rows_document_units)s
    """
    speeds = {s["name"]: s for s in document["kinematics"]["sprockets"]}
    cols = (("name", "name"), ("teeth", "teeth"), ("x", "x_mm"), ("y", "y_mm"),
            ("pitch Ø", "pitch_diameter_mm"), ("tip Ø", "tip_diameter_mm"),
            ("wrap", "wrap_angle_deg"), ("teeth in mesh", "teeth_in_mesh"))
    kin = (("speed", "speed_rpm"), ("direction", "direction"),
           ("speed variation, %", "speed_variation_percent"))
    return [{**_row(s, cols, units), **_row(speeds.get(s["name"], {}), kin, units)}
            for s in document["geometry"]["sprockets"]]


@shared_parameters
def span_records(document: dict[str, Any], units: UnitSystem = "SI") -> list[dict[str, Any]]:
    """Rows of the span table (with the static tensions when the strength part exists).

    %(rows_document_units)s
    """
    st = document.get("strength") or {}
    tensions = st.get("span_tensions_n") or [None] * len(document["geometry"]["spans"])
    cols = (("length", "length_mm"), ("pitches", "length_pitches"),
            ("inclination", "inclination_deg"), ("tight", "tight"), ("tension", "tension_n"))
    return [{"span": f"{s['from']} → {s['to']}", **_row({**s, "tension_n": t}, cols, units)}
            for s, t in zip(document["geometry"]["spans"], tensions, strict=True)]


@shared_parameters
def resonance_records(document: dict[str, Any], spans: list[str] | None = None
                      ) -> list[dict[str, Any]]:
    """Rows of the resonance table: working frequency, the nearest natural one (a ring mode,
    or for a parametric row twice the transverse frequency of a span, named by the span),
    the detuning |f_w − f_n|/f_n ≥ 0 and whether the working frequency lies below or
    above.

    Parameters
    ----------
    %(document)s
    spans : list of str | None
        Span names in the geometry's order (None: spans named by number).

    Returns
    -------
    %(returns_rows)s
    """
    out = []
    for r in document["dynamics"].get("resonances") or []:
        span = r["kind"] == "parametric"
        where = (spans[r["mode"]] if span and spans and r["mode"] < len(spans)
                 else f"span {r['mode'] + 1}" if span else f"mode {r['mode']}")
        out.append({"working": r["label"], "f working, Hz": clean(r["frequency_hz"]),
                    "nearest": where, "f natural, Hz": clean(r["natural_frequency_hz"]),
                    "detuning, %": clean(r["detuning_percent"], 3),
                    "f working is": r["working_frequency_is"]})
    return out


@shared_parameters
def modal_records(document: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of the natural-frequency table (elastic modes; ``rigid_body_modes`` is one flag
    per mode).

    Parameters
    ----------
    %(document)s

    Returns
    -------
    list of dict
        One dict per elastic mode: ``mode``, ``natural, Hz``, ``damped, Hz`` (None for an
        overdamped mode, which does not oscillate).
    """
    dyn = document["dynamics"]
    rigid = dyn["rigid_body_modes"]
    return [{"mode": j, "natural, Hz": clean(f), "damped, Hz": clean(fd) if fd > 0 else None}
            for j, (f, fd) in enumerate(zip(dyn["natural_frequencies_hz"],
                                            dyn["damped_frequencies_hz"], strict=True))
            if not rigid[j]]


def _quantity_rows(rows: tuple[tuple[str, str], ...], part: dict[str, Any], units: UnitSystem,
                   *, present_only: bool = False) -> list[dict[str, Any]]:
    """Rows (quantity, value, unit) of the (label, key) ``rows`` of a document part, each
    value formatted in the unit of ``units`` (``present_only``: a key that is None left
    out)."""
    return [{"quantity": label, "value": fmt(value), "unit": unit}
            for label, key in rows if not (present_only and part.get(key) is None)
            for value, unit in (doc_value(key, part.get(key), units),)]


@shared_parameters
def strength_records(strength: dict[str, Any], units: UnitSystem = "SI"
                     ) -> list[dict[str, Any]]:
    """Rows (quantity, value, unit) of the loads and static strength.

    Parameters
    ----------
    strength : dict
        The ``strength`` part of the analysis's JSON document.
    %(units)s

    Returns
    -------
    list of dict
        One dict per quantity: ``quantity``, ``value`` (formatted), ``unit``.
    """
    rows = (("chain speed v", "chain_speed_m_s"), ("peripheral force F_t", "peripheral_force_n"),
            ("sag tension F₀", "sag_tension_n"), ("centrifugal tension F_v",
                                                  "centrifugal_tension_n"),
            ("operating factor Kэ", "operating_factor_ke"),
            ("joint pressure p_h", "hinge_pressure_mpa"),
            ("allowable joint pressure [p_h]", "allowable_pressure_mpa"),
            ("static safety factor s", "safety_factor_static"),
            ("allowable static safety factor [s]", "allowable_safety_factor"),
            ("rated power P_r", "rated_power_w"), ("wear life L_h", "wear_life_h"))
    return _quantity_rows(rows, strength, units)


@shared_parameters
def selection_records(selection: dict[str, Any], units: UnitSystem = "SI", top: int = 12
                      ) -> list[dict[str, Any]]:
    """Rows of the ranked candidates of the chain selection.

    Parameters
    ----------
    selection : dict
        The ``selection`` part of the analysis's JSON document.
    %(units)s
    top : int
        How many candidates to show, the best first.

    Returns
    -------
    %(returns_rows)s
    """
    mass = header("mass", "mass_kg_m", units)
    return [{"chain": c["chain"], "method": c["method"], "strands": c["strands"],
             mass: clean(doc_value("mass_kg_m", c["mass_kg_m"], units)[0]),
             "verdict": candidate_verdict(c),
             "margin, %": None if c["margin_fraction"] is None
             else clean(100 * c["margin_fraction"], 3),
             "governing check": c["governing"], "lubrication": c["lubrication"]}
            for c in selection["candidates"][:top]]


@shared_parameters
def length_option_records(document: dict[str, Any], units: UnitSystem = "SI"
                          ) -> list[dict[str, Any]]:
    """Rows of the chain length options: each whole link count around the tight length as
    designed, laid out (:func:`chaindrive.geometry.length_options.length_options`).

    %(params_document_units)s

    Returns
    -------
    list of dict
        One dict per link count: column header (with its unit) → cell; the design's pick
        marked "(chosen)", a count that cannot be laid out with the reason.
    """
    lc = document["geometry"]["length_options"]
    cols: tuple[tuple[str, str], ...] = (("centre distance", "centre_distance_mm"), ("take-up", "take_up_mm"),
            ("slack-span sag", "slack_sag_mm"))
    errors = any(o["error"] for o in lc["options"])
    # a quantity no option has (the centre distance of a contour of more than two sprockets,
    # whose take-up is its adjustable sprocket's travel) is no column; one an option lacks
    # (a count that cannot be laid out) is a dash, with the reason in the note
    cols = tuple(c for c in cols if any(o.get(c[1]) is not None for o in lc["options"]))
    rows = [{"links": o["links"],
             "rounding": o["rounding"] + (" (chosen)" if o["rounding"] == lc["chosen"] else ""),
             **_row(o, cols, units), **({"note": o["error"] or ""} if errors else {})}
            for o in lc["options"]]
    return [{k: NOT_APPLICABLE if v is None else v for k, v in r.items()} for r in rows]


@shared_parameters
def lubrication_records(document: dict[str, Any], units: UnitSystem = "SI"
                        ) -> list[dict[str, Any]]:
    """Rows (quantity, value, unit) of the lubrication advice at the chain speed
    (:func:`chaindrive.strength.lubrication.lubrication_advice`).

    %(params_document_units)s

    Returns
    -------
    list of dict
        One dict per quantity: ``quantity``, ``value`` (formatted), ``unit``; the note and
        the source are the document's ``lubrication.note`` and ``.source`` (shown below the
        table, they are long).
    """
    lube = document["lubrication"]
    regime = lube["regime"] + ("" if lube["ansi_type"] is None
                               else f" (ANSI type {lube['ansi_type']})")
    rows = (("chain speed", "chain_speed_m_s"), ("manual up to", "manual_max_m_s"),
            ("drip up to", "drip_max_m_s"), ("oil bath or slinger disc up to", "bath_max_m_s"))
    return [{"quantity": "regime", "value": regime, "unit": ""},
            *_quantity_rows(rows, lube, units, present_only=True)]


@shared_parameters
def tension_reading_records(reading: dict[str, Any], units: UnitSystem = "SI"
                            ) -> list[dict[str, Any]]:
    """Rows (quantity, value, unit) of a span's tension read from its measured frequency
    (:meth:`chaindrive.identification.SpanTensionReading.to_dict`).

    Parameters
    ----------
    reading : dict
        The reading's JSON document.
    %(units)s

    Returns
    -------
    list of dict
        One dict per quantity: ``quantity``, ``value`` (formatted), ``unit``; a quantity the
        reading does not have (a design without power has no running tension) is left out.
    """
    rows = (("tension read", "tension_n"), ("± standard uncertainty", "tension_std_n"),
            ("design pretension F₀ (standing)", "design_pretension_n"),
            ("frequency expected at F₀ (standing)", "expected_frequency_standing_hz"),
            ("design tension in operation", "design_running_tension_n"),
            ("frequency expected in operation", "expected_frequency_running_hz"))
    return _quantity_rows(rows, reading, units, present_only=True)


def identification_records(doc: dict[str, Any]) -> list[dict[str, str]]:
    """Rows of the peaks of a measured record and what each is, as ``chaindrive identify``
    prints them (:meth:`chaindrive.identification.RecordIdentification.to_dict`).

    Parameters
    ----------
    doc : dict
        The identification's JSON document.

    Returns
    -------
    list of dict
        One per peak: ``signal``, ``f [Hz]``, ``prominence [dB]``, ``is``, ``model f [Hz]``,
        ``Δ [%]``, ``also within tolerance``, ``ζ half-power`` ("not resolved" with no ratio).
    """
    def text(value: Any, digits: int = 4) -> str:
        return "—" if value is None else fmt(value, digits)

    return [{"signal": sig["name"], "f [Hz]": text(p["frequency_hz"]),
             "prominence [dB]": text(p["prominence_db"], 3), "is": p["label"],
             "model f [Hz]": text(p["model_frequency_hz"]),
             "Δ [%]": text(p["deviation_percent"], 2),
             "also within tolerance": ", ".join(p["also_within_tolerance"]) or "—",
             "ζ half-power": ("not resolved" if p["damping_ratio_half_power"] is None
                              else text(p["damping_ratio_half_power"], 3))}
            for sig in doc["signals"] for p in sig["peaks"]]


@dataclass(frozen=True, slots=True, eq=False)
class Screen:
    """Everything the page redraws after an edit.

    Parameters
    ----------
    outcome : Outcome
        The outcome of the evaluation (:class:`chaindrive.app.state.Outcome`).
    document : dict | None
        The analysis's JSON document, with the chain selection (None until
        :func:`complete`).
    numbers : dict | None
        The headline numbers (:func:`headline`; None for a bad design).
    checks : tuple of Check
        The checks as shown.
    svg : str | None
        The contour layout (:func:`layout_svg`; None for a bad design).
    """

    outcome: Any
    document: dict[str, Any] | None = None
    numbers: dict[str, Any] | None = None
    checks: tuple[Check, ...] = ()
    svg: str | None = None


def _failure(drive: Any, exc: Exception, names: list[str]) -> Screen:
    """The screen of a design that could not be analysed (the command line's message)."""

    if isinstance(exc, ChainDriveError):
        where = getattr(exc, "field", "")
        return Screen(Outcome(drive=drive, message=str(exc), location=locate(where, names)))
    return Screen(Outcome(drive=drive, unexpected=True, location=Location("design"),
                          message=f"the analysis failed unexpectedly ({type(exc).__name__}); "
                                  "please report it with the design file"))


@shared_parameters
def quick_screen(design: dict[str, Any], catalogs: dict[str, Path] | None = None) -> Screen:
    """Validate the design mapping and compute what is on screen at once: the contour,
    the headline numbers and every check (geometry, kinematics, strength, modes) — the
    stages of one lazy :class:`~chaindrive.analysis.Analysis`, without the chain selection
    that :func:`complete` adds. ``catalogs``: the catalogues uploaded in the session, the
    only files ``chain.catalog`` may name (:func:`chaindrive.io.design.drive_from_mapping`).
    Never raises for a bad design.

    %(params_design_catalogs)s

    Returns
    -------
    Screen
        The quick part, or the screen of a bad design (the command line's message).
    """

    names = [str(r.get("name")) for r in design.get("sprockets") or []
             if isinstance(r, dict)]
    drive = None
    try:
        drive = drive_from_mapping(design, catalogs=dict(catalogs or {}))
        analysis = Analysis(drive, response=False)
        shown = tuple(checks(analysis))
        return Screen(Outcome(analysis=analysis, drive=drive), None, headline(analysis), shown,
                      layout_svg(analysis.geometry, max_height_px=LAYOUT_HEIGHT_PX))
    except Exception as exc:  # the page must never show a traceback
        return _failure(drive, exc, names)


def complete(screen: Screen) -> Screen:
    """The screen with the JSON document of its analysis (chain selection, warnings,
    dynamics tables); a failure there becomes the screen of a bad design.

    Parameters
    ----------
    screen : Screen
        A screen of :func:`quick_screen`.

    Returns
    -------
    Screen
        The same screen with its document (unchanged when it has one or holds no analysis).
    """
    analysis = screen.outcome.analysis
    if analysis is None or screen.document is not None:
        return screen
    try:
        document = analysis.to_dict()
    except Exception as exc:
        names = [s.name for s in analysis.design.sprockets]
        return _failure(screen.outcome.drive, exc, names)
    return replace(screen, document=document)


@shared_parameters
def recompute(design: dict[str, Any], catalogs: dict[str, Path] | None = None) -> Screen:
    """Everything the page shows after an edit (:func:`quick_screen` then :func:`complete`;
    timed by ``benchmarks/bench_app_recompute.py``); ``catalogs`` as for
    :func:`quick_screen`.

    %(params_design_catalogs)s

    Returns
    -------
    Screen
        The complete screen.
    """
    return complete(quick_screen(design, catalogs))


@shared_parameters
def screens(design: dict[str, Any], catalogs: dict[str, Path] | None = None
            ) -> Iterator[Screen]:
    """The screens of :func:`recompute` one after the other, each as soon as it is ready:
    :func:`quick_screen` (what the page draws first), then, when the design was analysed,
    that analysis with its document (:func:`complete`: the quick part is not computed
    twice).

    %(params_design_catalogs)s

    Yields
    ------
    Screen
        The quick screen, then the complete one.
    """
    quick = quick_screen(design, catalogs)
    yield quick
    if quick.outcome.ok:
        yield complete(quick)
