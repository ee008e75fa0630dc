"""Vibration of the ring model: mode shapes (signed, along the contour) and the Campbell
diagram (natural frequencies against the working-frequency lines, zoomed to the crossings
near the working speed) [MultimassChainDrives, eq. 2, §3.3]."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import fmt
from chaindrive.plotting._base import CYCLE, GREY, TIGHT, figure_axes, finish

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics import CampbellData, Modes


@shared_parameters
def mode_shapes(modal: Modes, *, ax: Axes | None = None,
                names: Sequence[str] | None = None, modes: int = 4) -> Figure:
    """Mode shapes X^(j) of the first ``modes`` elastic modes as signed lines along the
    contour: one point per mass in contour order, the first mass repeated at the end to
    close the ring; each shape scaled to a largest |X| of 1 with its largest component
    positive ([MultimassChainDrives, eq. 2]). A line that crosses zero between two masses
    has a node there; masses on opposite sides of zero move in opposite directions.
    names label the masses (default M1, M2, …).

    Parameters
    ----------
    modal : Modes
        The ring's modes.
    %(ax)s
    names : sequence of str or None
        Labels of the masses (None: M1, M2, …).
    modes : int
        Elastic modes drawn [-].

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (6.4, 3.6))
    elastic = np.flatnonzero(~np.asarray(modal.rigid_body))[:modes]
    shapes = np.asarray(modal.shapes, dtype=float)
    n = shapes.shape[0]
    labels = list(names) if names is not None else [f"M{i + 1}" for i in range(n)]
    x = np.arange(n + 1)
    for k, j in enumerate(elastic):
        col = shapes[:, j]
        big = int(np.argmax(np.abs(col)))
        scaled = col / col[big] if col[big] != 0 else col
        closed = np.append(scaled, scaled[0])
        ax.plot(x, closed, marker="o", ms=3.5, lw=1.4, color=CYCLE[k % len(CYCLE)],
                label=f"mode {j}: {modal.frequencies_hz[j]:.1f} Hz")
    ax.axhline(0.0, color=GREY, lw=0.8)
    ax.set_xticks(x, [*labels, labels[0]], rotation=90 if n > 8 else 0, fontsize="small")
    ax.set_xlim(0, n)
    ax.set_ylim(-1.1, 1.1)
    ax.set_xlabel("masses in contour order (the ring closes on the first)")
    ax.set_ylabel("mode shape X (largest = 1)")
    ax.legend(fontsize="x-small", loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=4,
              frameon=False)
    finish(ax)
    return fig


def campbell_window(campbell: CampbellData, operating_rpm: float | None,
                    window: float = 0.3) -> tuple[list[tuple[str, int, float, float]], float]:
    """The crossings that matter and the top of the frequency axis [Hz].

    A crossing (excitation line meets a natural frequency) matters when it lies within
    ±``window`` (a fraction) of the operating speed: the working point sits near it. The
    frequency axis reaches 1.3 × the highest such crossing, or 1.3 × the lowest natural
    frequency when there is none (so the first mode and the lines below it show). Returns
    ([(excitation, mode, speed [rpm], frequency [Hz])], top [Hz]).

    Parameters
    ----------
    campbell : CampbellData
        The Campbell data.
    operating_rpm : float or None
        Operating driver speed [rpm] (None: no crossing matters).
    window : float
        Half-width of the window round the operating speed, as a fraction of it [-].

    Returns
    -------
    crossings : list of tuple
        (excitation, mode, speed [rpm], frequency [Hz]) of the crossings that matter.
    top : float
        Top of the frequency axis [Hz].
    """
    rpm = np.asarray(campbell.speeds_rpm)
    nat = np.asarray(campbell.natural_frequencies_hz)
    out = []
    for e, _mode, s in campbell.crossings:
        if not rpm.min() <= s <= rpm.max():
            continue
        if operating_rpm is not None and abs(s / operating_rpm - 1.0) > window:
            continue
        # a parametric zone sits on the tooth line
        line = campbell.excitation_hz.get(e, campbell.excitation_hz.get("tooth x1", rpm * 0))
        f = float(np.interp(s, rpm, line))
        out.append((e, _mode, float(s), f))
    first = float(nat[0, 0]) if nat.size else 1.0
    top = 1.3 * max([f for *_, f in out] or [first])
    return out, max(top, 1.0)


def crossing_label(excitation: str, mode: int, *, mode_numbers: Sequence[int] | None = None,
                   span_names: Sequence[str] | None = None) -> str:
    """What a crossing of a Campbell diagram is, numbered as the tables number the modes:
    "tooth x1 × mode 1" (a line on a natural frequency) or "tooth x1 = 2·f₁ of span T→D5"
    (a parametric zone).

    Parameters
    ----------
    excitation : str
        The crossing's excitation (``"tooth x1"``, ``"shaft S2"``, ``"parametric span 6"``).
    mode : int
        Its column of the diagram's natural frequencies (the elastic modes from 0), −1 for a
        parametric zone.
    mode_numbers : sequence of int or None
        The number of each column in the tables (None: 1, 2, … — one rigid mode numbered 0).
    span_names : sequence of str or None
        Names of the spans in order (None: span 1, span 2, …).

    Returns
    -------
    str
        The label.
    """
    if mode >= 0:
        number = (mode_numbers[mode] if mode_numbers is not None and mode < len(mode_numbers)
                  else mode + 1)
        return f"{excitation} × mode {number}"
    tail = excitation.rsplit(" ", 1)[-1]
    if tail.isdigit():
        i = int(tail)
        tail = (span_names[i] if span_names is not None and i < len(span_names)
                else f"{i + 1}")
    return f"tooth x1 = 2·f₁ of span {tail}"


#: Where a crossing's number may go, offsets from the point [pt], in the order tried.
TAG_OFFSETS = ((0.0, 12.0), (0.0, -12.0), (11.0, 0.0), (-11.0, 0.0), (10.0, 11.0),
               (-10.0, 11.0), (10.0, -11.0), (-10.0, -11.0), (0.0, 22.0), (0.0, -22.0))
#: Size of the plotting area of a Campbell diagram the tags are placed for [pt] (its axes
#: in the report's 6.4 × 5 in figure), and the half-size of a tag and of a marker [pt].
_AXES_PT, _TAG_PT, _MARKER_PT = (400.0, 190.0), (5.0, 6.0), 4.0


def _tag_offsets(points: Sequence[tuple[float, float]],
                 markers: Sequence[tuple[float, float]] = ()) -> list[tuple[float, float]]:
    """An offset [pt] for the number of each point (axes fractions): the first of
    :data:`TAG_OFFSETS` whose tag covers neither an earlier tag nor any of the points and
    ``markers`` (axes fractions)."""
    w, h = _AXES_PT
    pts = [(x * w, y * h) for x, y in points]
    obstacles = pts + [(x * w, y * h) for x, y in markers]
    placed: list[tuple[float, float]] = []
    out = []
    for px, py in pts:
        def free(dx: float, dy: float, px: float = px, py: float = py) -> bool:
            cx, cy = px + dx, py + dy
            clear_tags = all(abs(cx - tx) > 2 * _TAG_PT[0] or abs(cy - ty) > 2 * _TAG_PT[1]
                             for tx, ty in placed)
            clear_points = all(abs(cx - qx) > _TAG_PT[0] + _MARKER_PT
                               or abs(cy - qy) > _TAG_PT[1] + _MARKER_PT
                               for qx, qy in obstacles)
            return clear_tags and clear_points
        dx, dy = next((o for o in TAG_OFFSETS if free(*o)), TAG_OFFSETS[0])
        placed.append((px + dx, py + dy))
        out.append((dx, dy))
    return out


@shared_parameters
def campbell_diagram(campbell: CampbellData, *, ax: Axes | None = None,
                     operating_rpm: float | None = None, max_lines: int = 8,
                     band_percent: float | None = None, window: float = 0.3,
                     max_labels: int = 4, mode_numbers: Sequence[int] | None = None,
                     span_names: Sequence[str] | None = None) -> Figure:
    """Campbell diagram zoomed to where it matters: natural frequencies of the ring
    (horizontal, solid), the excitation lines (shaft frequencies and tooth-frequency
    harmonics, dashed, at most ``max_lines``), twice the spans' first transverse frequencies
    (parametric resonance, dotted) and every crossing (circles) against the driver speed
    [rpm]; the operating speed as a vertical line with the band ±``band_percent`` round it
    shaded; the crossings within ±``window`` of the operating speed filled, the
    ``max_labels`` nearest to it numbered on the plot and named in the legend
    (:func:`crossing_label`, modes numbered as in the tables) ([MultimassChainDrives,
    §3.3]). Tooth-frequency
    harmonics are drawn before the shaft lines. The frequency axis is cut at 1.3 × the highest of
    those crossings (:func:`campbell_window`): a low crossing near the working speed is
    never lost under a scale set by the highest mode.

    Parameters
    ----------
    campbell : CampbellData
        The Campbell data.
    %(ax)s
    operating_rpm : float or None
        Operating driver speed [rpm] (None: not drawn).
    max_lines : int
        Excitation lines drawn at most [-].
    band_percent : float or None
        Half-width of the shaded band round the operating speed [%] (None: none).
    window : float
        Half-width of the window of crossings that matter, a fraction of the operating
        speed [-].
    max_labels : int
        Crossings labelled at most [-].
    mode_numbers : sequence of int or None
        The number of each elastic mode in the tables (None: 1, 2, …).
    span_names : sequence of str or None
        Names of the spans (None: span 1, span 2, …).

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (6.4, 5.0))
    rpm = np.asarray(campbell.speeds_rpm)
    nat = np.asarray(campbell.natural_frequencies_hz)
    near, top = campbell_window(campbell, operating_rpm, window)
    for j in range(nat.shape[1]):
        ax.plot(rpm, nat[:, j], color="k", lw=1.4, label="natural frequencies" if j == 0 else None)
    lines = sorted(campbell.excitation_hz.items(), key=lambda kv: not kv[0].startswith("tooth"))
    for k, (name, line) in enumerate(lines[:max_lines]):
        ax.plot(rpm, line, ls="--", lw=1.0, color=CYCLE[k % len(CYCLE)], label=name)
    trans = np.asarray(campbell.span_transverse_hz)
    for i in range(trans.shape[1] if trans.ndim == 2 else 0):
        ax.plot(rpm, 2 * trans[:, i], ls=":", lw=1.0, color=GREY,
                label="2·f₁ of spans (parametric)" if i == 0 else None)
    tooth = campbell.excitation_hz.get("tooth x1", np.zeros_like(rpm))
    cross = [(s, e) for e, _, s in campbell.crossings if rpm.min() <= s <= rpm.max()]
    if cross:
        ys = [np.interp(s, rpm, campbell.excitation_hz.get(e, tooth)) for s, e in cross]
        ax.plot([s for s, _ in cross], ys, "o", mfc="none", color=TIGHT, label="crossings")
    labelled: list[tuple[str, float, float]] = []
    x0, width = float(rpm.min()), float(np.ptp(rpm)) or 1.0
    w, h = _AXES_PT
    for e, mode, s, f in sorted(near, key=lambda c: abs(c[2] - (operating_rpm or c[2]))):
        ax.plot([s], [f], "o", color=TIGHT, ms=7)
        covered = any(abs(s - x) / width * w < _MARKER_PT and abs(f - y) / top * h < _MARKER_PT
                      for _, x, y in labelled)  # on a labelled one: its number would hide it
        if len(labelled) < max_labels and not covered:
            labelled.append((crossing_label(e, mode, mode_numbers=mode_numbers,
                                            span_names=span_names), s, f))
    # numbers on the plot (above and below the point by turns, so that neighbours do not
    # print over each other), their names in the legend
    labelled.sort(key=lambda c: c[1])
    offsets = _tag_offsets([((s - x0) / width, f / top) for _, s, f in labelled],
                           [((s - x0) / width, f / top) for *_, s, f in near])
    for n, ((_, s, f), offset) in enumerate(zip(labelled, offsets, strict=True), start=1):
        far = max(abs(offset[0]), abs(offset[1])) > 12  # a leader line to its point
        ax.annotate(str(n), (s, f), textcoords="offset points", xytext=offset,
                    fontsize="x-small", color=TIGHT, fontweight="bold", ha="center",
                    va="center", bbox={"boxstyle": "round,pad=0.12", "fc": "white",
                                       "ec": "none", "alpha": 0.85},
                    arrowprops={"arrowstyle": "-", "color": TIGHT, "lw": 0.6,
                                "shrinkA": 0, "shrinkB": 3} if far else None)
    if operating_rpm is not None:
        if band_percent:
            b = band_percent / 100.0
            ax.axvspan(operating_rpm / (1 + b), operating_rpm / (1 - b) if b < 1 else rpm.max(),
                       color=TIGHT, alpha=0.1, lw=0,
                       label=f"±{band_percent:g} % of the working frequencies")
        ax.axvline(operating_rpm, color=TIGHT, lw=1.0, label=f"operating {operating_rpm:.0f} rpm")
    ax.set_ylim(0, top)
    ax.set_xlim(rpm.min(), rpm.max())
    ax.set_xlabel("driver speed, rpm")
    ax.set_ylabel("frequency, Hz")
    hidden = int(np.sum(nat[0] > top)) if nat.size else 0
    if hidden:
        ax.text(0.99, 0.98, f"{hidden} higher mode(s) above {top:.0f} Hz not shown",
                transform=ax.transAxes, ha="right", va="top", fontsize="x-small", color=GREY)
    for n, (what, s, f) in enumerate(labelled, start=1):
        ax.plot([], [], ls="none", marker=f"${n}$", color=TIGHT,
                label=f"{what}: {fmt(s)} rpm, {fmt(f)} Hz")
    ax.legend(fontsize="x-small", ncol=2 if labelled else 3, loc="upper center",
              bbox_to_anchor=(0.5, -0.16))
    finish(ax, "Campbell diagram")
    return fig
