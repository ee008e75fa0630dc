"""Shared helpers of the plotting modules (matplotlib imported lazily)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from chaindrive.display import QUANTITIES, UnitSystem

if TYPE_CHECKING:
    from collections.abc import Iterable

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: Colours used across the figures (colour-blind safe, Okabe–Ito).
TIGHT = "#D55E00"
CHAIN = "#0072B2"
PITCH = "#009E73"
GREY = "#7f7f7f"
CYCLE = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000")


def new_figure(figsize: tuple[float, float]) -> Figure:
    """A new figure (no pyplot, so nothing global changes) with a constrained layout, whose
    texts are drawn as written.

    Matplotlib reads a text between two dollar signs as a formula: a drive or sprocket named
    ``"$\\frac{a}{$"`` would stop the drawing with a parse error, and ``"$x$"`` would come out
    as an italic x. No label of these figures is a formula, so every text of the figure is
    drawn without the math parser, whatever was added to it and whenever (the setting is
    applied to each text as the figure is drawn).

    Parameters
    ----------
    figsize : tuple of float
        Width and height [in].

    Returns
    -------
    Figure
        The figure.
    """
    # lazy: _figure imports matplotlib.figure (≈0.26 s, -X importtime), paid when a figure is made
    from chaindrive.plotting._figure import PlainTextFigure

    return PlainTextFigure(figsize=figsize, layout="constrained")


def figure_axes(ax: Axes | None, figsize: tuple[float, float] = (6.4, 4.0)
                ) -> tuple[Figure, Axes]:
    """The figure and axes to draw into: ``ax`` and its figure, or a new Figure (no pyplot,
    so nothing global changes) with one axes. figsize [in].

    Parameters
    ----------
    ax : Axes or None
        The axes to draw into, or None for a new figure.
    figsize : tuple of float
        Size of a new figure (width, height) [in].

    Returns
    -------
    fig : Figure
        The figure.
    ax : Axes
        The axes.
    """
    if ax is not None:
        return ax.figure, ax  # type: ignore[return-value]
    fig = new_figure(figsize)
    return fig, fig.add_subplot()


def force_axes(ax: Axes | None, figsize: tuple[float, float], units: UnitSystem
               ) -> tuple[Figure, Axes, float, str]:
    """The figure and axes to draw forces into (:func:`figure_axes`), with the factor and
    unit the forces are shown in (:func:`scale`, kind ``"force"``).

    Parameters
    ----------
    ax, figsize : Axes or None, tuple of float
        As for :func:`figure_axes`: the axes to draw into (None: a new figure), the size of
        a new figure (width, height) [in].
    units : {"SI", "US"}
        Unit system of the forces: N (SI) or lbf (US).

    Returns
    -------
    tuple of (Figure, Axes, float, str)
        The figure and axes of :func:`figure_axes`, the factor from N to the unit shown
        [unit / N] and the unit's symbol (``"N"`` or ``"lbf"``).
    """
    fig, ax = figure_axes(ax, figsize)
    factor, unit = scale("force", units)
    return fig, ax, factor, unit


def finish(ax: Axes, title: str | None = None, *, grid: bool = True) -> None:
    """Common finishing: title, light grid.

    Parameters
    ----------
    ax : Axes
        The axes.
    title : str or None
        Its title (None: none).
    grid : bool
        True draws the light grid.
    """
    if title:
        ax.set_title(title, fontsize="medium")
    if grid:
        ax.grid(True, alpha=0.3, linewidth=0.6)


def labels_of(items: Iterable[object]) -> list[str]:
    """Names of result items (objects with a ``name``).

    Parameters
    ----------
    items : iterable
        Objects with a ``name``.

    Returns
    -------
    list of str
        Their names.
    """
    return [str(getattr(i, "name", i)) for i in items]


def scale(kind: str, units: UnitSystem = "SI") -> tuple[float, str]:
    """Factor from SI and unit symbol of a kind of quantity in a unit system, as
    :mod:`chaindrive.display` defines them: plotted value = SI value × factor.

    Parameters
    ----------
    kind : str
        A kind of quantity of :data:`chaindrive.display.QUANTITIES` (``"length"``,
        ``"force"``, ``"velocity"`` …).
    units : {"SI", "US"}
        The output unit system.

    Returns
    -------
    factor : float
        From the SI unit of ``kind`` (m, N, m/s …) to the unit shown [unit / SI unit].
    unit : str
        The unit's symbol (``"mm"``, ``"in"``, ``"lbf"`` …).
    """
    shown = QUANTITIES[kind][units]
    return shown.factor, shown.unit
