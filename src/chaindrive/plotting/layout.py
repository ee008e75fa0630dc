"""The contour to scale: sprockets (pitch and tip circles, centre marks), spans, wrap arcs,
direction of travel and labels (millimetres, or inches in the US customary system)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem
from chaindrive.plotting._base import CHAIN, GREY, PITCH, TIGHT, figure_axes, finish, scale

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.transforms import Transform

    from chaindrive.geometry.results import GeometryResult, SprocketGeometry

MM = 1e3  # metres → millimetres (the SI drawing; other systems: display's length factor)


def wrap_arc_points(s: SprocketGeometry, samples: int = 60) -> np.ndarray:
    """Points [m] of the chain's wrap on the pitch circle, from the arrive point to the leave
    point in the sprocket's direction of turning (``turn``), shape (samples, 2).

    Parameters
    ----------
    s : SprocketGeometry
        The sprocket (centre, pitch radius, arrive and leave points, turn).
    samples : int
        Points on the arc [-].

    Returns
    -------
    ndarray
        (samples, 2) points [m].
    """
    a0 = math.atan2(s.arrive[1] - s.y, s.arrive[0] - s.x)
    angles = a0 + s.turn * np.linspace(0.0, s.wrap_angle, samples)
    return np.column_stack([s.x + s.pitch_radius * np.cos(angles),
                            s.y + s.pitch_radius * np.sin(angles)])


def _sprocket(ax: Axes, s: SprocketGeometry, label: bool, MM: float = MM) -> None:
    """One sprocket, drawn with MM the factor from metres to the drawing's length unit."""
    from matplotlib.patches import Circle

    c = (s.x * MM, s.y * MM)
    ax.add_patch(Circle(c, s.pitch_radius * MM, fill=False, color=PITCH, lw=0.8, ls="-."))
    ax.add_patch(Circle(c, s.tip_diameter / 2 * MM, fill=True, fc="#f2f2f2", ec=GREY, lw=0.6))
    mark = 0.15 * s.pitch_radius * MM
    ax.plot([c[0] - mark, c[0] + mark], [c[1], c[1]], color=GREY, lw=0.6)
    ax.plot([c[0], c[0]], [c[1] - mark, c[1] + mark], color=GREY, lw=0.6)
    arc = wrap_arc_points(s) * MM
    ax.plot(arc[:, 0], arc[:, 1], color=CHAIN, lw=1.6)
    if label:
        ax.annotate(f"{s.name} (z = {s.teeth})", (c[0], c[1] + s.tip_diameter / 2 * MM),
                    xytext=(0, 3), textcoords="offset points", fontsize="small",
                    ha="center", va="bottom")


def _figsize(geometry: GeometryResult) -> tuple[float, float]:
    """Figure size [in] following the aspect of the contour (7 in wide, 2.8…7 in high)."""
    r = np.array([s.tip_diameter / 2 for s in geometry.sprockets])
    x = np.array([s.x for s in geometry.sprockets])
    y = np.array([s.y for s in geometry.sprockets])
    width = np.ptp(np.r_[x - r, x + r])
    height = np.ptp(np.r_[y - r, y + r])
    return 7.0, float(np.clip(7.0 * height / max(width, 1e-9) + 1.3, 2.8, 7.0))


def _below_xlabel(ax: Axes) -> Transform:
    """Axes coordinates shifted 0.5 in down: the top of a legend anchored there clears the
    tick labels and the x label whatever the height of the axes."""
    from matplotlib.transforms import ScaledTranslation

    return ax.transAxes + ScaledTranslation(0.0, -0.5, ax.figure.dpi_scale_trans)


@shared_parameters
def contour_layout(geometry: GeometryResult, *, ax: Axes | None = None,
                   labels: bool = True, units: UnitSystem = "SI") -> Figure:
    """The contour of a drive to scale [mm, or in with ``units="US"``]: tip circles (grey discs), pitch
    circles (dash-dot), centre marks, the chain (blue, the tight span orange) with an arrow per span in the
    direction of travel, and sprocket names with tooth counts.

    Parameters
    ----------
    geometry : GeometryResult
        The contour.
    %(ax)s
    labels : bool
        True writes the sprocket names and tooth counts.
    units : {"SI", "US"}
        Unit system of the axes and of the chain length in the title: mm (SI) or in (US)
        (:data:`chaindrive.display.QUANTITIES`, kind ``"length"``).

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, _figsize(geometry))
    MM, unit = scale("length", units)  # metres → the drawing's unit
    arrow = MM / 1e3  # the arrows' 1 mm half-length in the drawing's unit
    for s in geometry.sprockets:
        _sprocket(ax, s, labels, MM)
    for span in geometry.spans:
        (x0, y0), (x1, y1) = span.start_point, span.end_point
        colour = TIGHT if span.tight else CHAIN
        ax.plot([x0 * MM, x1 * MM], [y0 * MM, y1 * MM], color=colour, lw=1.6)
        xm, ym = 0.5 * (x0 + x1) * MM, 0.5 * (y0 + y1) * MM
        dx, dy = span.direction
        dx, dy = dx * arrow, dy * arrow
        ax.annotate("", xy=(xm + dx, ym + dy), xytext=(xm - dx, ym - dy),
                    arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.2,
                                "mutation_scale": 14})
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.06)  # room for the labels of the outermost sprockets
    ax.autoscale_view()
    ax.set_xlabel(f"x, {unit}")
    ax.set_ylabel(f"y, {unit}")
    ax.plot([], [], color=TIGHT, lw=1.6, label="tight span")
    ax.plot([], [], color=CHAIN, lw=1.6, label="chain (wrap arcs, spans)")
    ax.plot([], [], color=PITCH, lw=0.8, ls="-.", label="pitch circles")
    # a fixed place below the axes: loc="best" costs ~40 % of the figure's time (it tries
    # every position against every line) and may still cover a sprocket
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3, fontsize="x-small",
              frameon=False, bbox_transform=_below_xlabel(ax))
    finish(ax, f"Contour layout ({geometry.links} links, "
           f"{geometry.chain_length * MM:.1f} {unit} of chain)")
    return fig
