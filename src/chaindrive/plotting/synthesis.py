"""The Pareto front of an optimal synthesis (chaindrive.synthesis, [MultimassChainDrives, §3.6])."""

from __future__ import annotations

from typing import TYPE_CHECKING

from chaindrive._docstrings import shared_parameters
from chaindrive.plotting._base import CHAIN, TIGHT, figure_axes, finish

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.synthesis.solve import SynthesisResult


@shared_parameters
def pareto_front(result: SynthesisResult, *, ax: Axes | None = None) -> Figure:
    """Scatter of the Pareto set of a :class:`chaindrive.synthesis.solve.SynthesisResult`:
    the first two objectives on the axes, the third (if any) as colour, the start design
    as a star.

    Parameters
    ----------
    result : SynthesisResult
        An optimisation run.
    %(ax)s

    Returns
    -------
    %(returns_figure)s

    References
    ----------
    [MultimassChainDrives, §3.6] (the multi-criteria synthesis).
    """
    fig, ax = figure_axes(ax)
    names = list(result.objectives)
    if result.pareto and len(names) >= 2:
        x = [p.objectives[names[0]] for p in result.pareto]
        y = [p.objectives[names[1]] for p in result.pareto]
        c = [p.objectives[names[2]] for p in result.pareto] if len(names) > 2 else None
        sc = ax.scatter(x, y, c=c if c is not None else CHAIN, s=28, label="Pareto set")
        if c is not None:
            fig.colorbar(sc, ax=ax, label=names[2])
        if result.start.error is None:
            start = result.start.objectives
            ax.scatter([start[names[0]]], [start[names[1]]], marker="*", s=140, color=TIGHT,
                       label="start design")
        ax.set_xlabel(names[0])
        ax.set_ylabel(names[1])
        ax.legend(fontsize="small")
    finish(ax, f"Pareto front ({len(result.pareto)} designs, {result.method}, seed {result.seed})")
    return fig
