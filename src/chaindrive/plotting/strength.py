"""Static loads: tension per span and load per shaft (bar charts)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem
from chaindrive.errors import DesignError
from chaindrive.plotting._base import CHAIN, TIGHT, figure_axes, finish, scale

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.analysis import Analysis
    from chaindrive.strength import StrengthResult


def _strength(analysis: Analysis) -> StrengthResult:
    if analysis.strength is None:
        raise DesignError("drive.power", "no loads: the design gives no power")
    return analysis.strength


@shared_parameters
def span_tensions(analysis: Analysis, *, ax: Axes | None = None,
                  units: UnitSystem = "SI") -> Figure:
    """Static tension of each span [N, or lbf with ``units="US"``] (tight span red): F_t + F_0 + F_v on the
    tight span, F_0 + F_v on the slack one, stepping at each driven sprocket
    (:mod:`chaindrive.strength.loads`).

    %(loads_figure)s
    """
    loads = _strength(analysis).loads
    names = [f"{s.start_name}→{s.end_name}" for s in analysis.geometry.spans]
    colours = [TIGHT if s.tight else CHAIN for s in analysis.geometry.spans]
    factor, unit = scale("force", units)
    return _bars(ax, names, np.asarray(loads.span_tensions) * factor, colours, f"tension, {unit}",
                 "Static tension per span")


def _bars(ax: Axes | None, names: list[str], values: Any, colours: Any, ylabel: str,
          title: str) -> Figure:
    """One bar per named item (labels turned upright past 8 bars)."""
    fig, ax = figure_axes(ax, (6.0, 3.4))
    ax.bar(range(len(names)), values, color=colours)
    ax.set_xticks(range(len(names)), names, rotation=90 if len(names) > 8 else 0,
                  fontsize="small")
    ax.set_ylabel(ylabel)
    finish(ax, title)
    return fig


@shared_parameters
def shaft_loads(analysis: Analysis, *, ax: Axes | None = None,
                units: UnitSystem = "SI") -> Figure:
    """Magnitude of the load on each shaft [N, or lbf with ``units="US"``] (vector sum of the two span
    tensions meeting at the sprocket, :func:`chaindrive.strength.loads.shaft_load_vectors`).

    %(loads_figure)s
    """
    loads = _strength(analysis).loads
    names = [s.name for s in analysis.drive.sprockets]
    factor, unit = scale("force", units)
    return _bars(ax, names, np.asarray(loads.shaft_load_magnitudes) * factor, CHAIN,
                 f"shaft load, {unit}", "Load per shaft")
