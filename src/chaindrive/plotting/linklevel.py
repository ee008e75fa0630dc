"""Frames of the link-level model (:mod:`chaindrive.linklevel`): the chain's rollers and
links over the sprockets at recorded instants, coloured by link tension; and the tooth-load
distribution of every sprocket. Plotting only reads the result: it computes nothing."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem
from chaindrive.plotting._base import CYCLE, GREY, figure_axes, finish, force_axes, new_figure, scale
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle

    from chaindrive.linklevel import LinkLevelResult

__all__ = ["chain_frame", "chain_frames", "frame_times", "tension_along_chain",
           "tooth_loads"]


def _sample(result: LinkLevelResult, time_s: float | None) -> int:
    """Index of the recorded sample nearest ``time_s`` (None: the last)."""
    if time_s is None:
        return len(result.times) - 1
    return int(np.argmin(np.abs(result.times - time_s)))


def _draw(result: LinkLevelResult, k: int, ax: Axes, vmax: float, magnify: float,
          units: UnitSystem = "SI") -> None:
    """One frame on ``ax``: pitch and tip circles with the gap centres, links coloured by
    tension, rollers (filled where in contact); transverse deviations from the nominal
    spans multiplied by ``magnify``. Positions in display's ``"distance"`` unit, tensions
    (and vmax, already converted) in its ``"force"`` unit of ``units``."""
    from matplotlib.collections import LineCollection

    model, geometry = result.model, result.geometry
    pos = result.positions[k]
    if magnify != 1.0:
        pos = pos.copy()
        for span in geometry.spans:
            a, u = np.array(span.start_point), np.array(span.direction)
            rel = pos - a
            along = rel @ u
            normal = np.array([-u[1], u[0]])
            across = rel @ normal
            on = ((along > 0) & (along < span.length) & (np.abs(across) < 2.0 * model.pitch)
                  & (result.contact_sprocket[k] < 0))
            pos[on] = a + np.outer(along[on], u) + np.outer(magnify * across[on], normal)
    m, _ = scale("distance", units)
    f, _ = scale("force", units)
    pos = pos * m
    for i, g in enumerate(geometry.sprockets):
        x, y, r = g.x * m, g.y * m, g.pitch_radius * m
        ax.add_patch(_circle((x, y), model.tip_radii[i] * m, GREY, 0.6))
        ax.add_patch(_circle((x, y), r, GREY, 0.3, dashed=True))
        angle = result.angles[k, i] + TWO_PI * np.arange(g.teeth) / g.teeth
        ax.plot(x + r * np.cos(angle), y + r * np.sin(angle), ".", color=GREY, markersize=2)
        ax.annotate(g.name, (x, y), ha="center", va="center", fontsize="small")
    segments = np.stack([pos, np.roll(pos, -1, axis=0)], axis=1)
    lines = LineCollection(list(segments), cmap="viridis", linewidths=1.5)
    lines.set_array(result.link_tensions[k] * f)
    lines.set_clim(0.0, vmax)
    ax.add_collection(lines)
    touching = result.contact_sprocket[k] >= 0
    ax.plot(pos[~touching, 0], pos[~touching, 1], "o", mfc="none", color=CYCLE[0],
            markersize=2.5)
    ax.plot(pos[touching, 0], pos[touching, 1], "o", color=CYCLE[1], markersize=2.5)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(f"t = {result.times[k] * 1e3:.1f} ms", fontsize="small")


def _circle(centre: tuple[float, float], radius: float, color: str, alpha: float,
            dashed: bool = False) -> Circle:
    from matplotlib.patches import Circle

    return Circle(centre, radius, fill=False, color=color, alpha=alpha,
                  linestyle="--" if dashed else "-", linewidth=0.8)


@shared_parameters
def chain_frame(result: LinkLevelResult, time_s: float | None = None, *, ax: Axes | None = None,
                magnify: float = 1.0, units: UnitSystem = "SI") -> Figure:
    """The chain at the recorded instant nearest ``time_s`` [s] (None: the last): sprockets
    (tip and pitch circles, gap centres), links coloured by tension [N], rollers in contact
    filled; ``magnify`` scales the transverse deviations of the free rollers within two
    pitches of a span's line (taut spans) to make them visible.

    Parameters
    ----------
    result : LinkLevelResult
        A link-level run.
    time_s : float or None
        The instant [s] (None: the last recorded one).
    %(ax)s
    %(magnify_units)s

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (7.0, 4.0))
    k = _sample(result, time_s)
    vmax = float(max(result.link_tensions[k].max(), 1.0)) * scale("force", units)[0]
    _draw(result, k, ax, vmax, magnify, units)
    _colorbar(fig, ax, vmax, units=units)
    finish(ax, None, grid=False)
    ax.set_title(f"Link-level model, t = {result.times[k] * 1e3:.1f} ms")
    return fig


@shared_parameters
def chain_frames(result: LinkLevelResult, times_s: Sequence[float], *,
                 columns: int | None = None, magnify: float = 1.0,
                 units: UnitSystem = "SI") -> Figure:
    """A sequence of frames (one axes per instant, :func:`chain_frame`), on one tension
    scale. Each frame is sized to the contour's aspect.

    Parameters
    ----------
    result : LinkLevelResult
        A link-level run.
    times_s : sequence of float
        The instants [s].
    columns : int or None
        Axes per row [-] (None: one column for a contour more than twice as wide as high,
        else two).
    %(magnify_units)s

    Returns
    -------
    Figure
        A new figure with one axes per instant.
    """

    idx = [_sample(result, t) for t in times_s]
    extent = np.ptp(result.positions[idx[-1]], axis=0) + 2.0 * float(result.model.tip_radii.max())
    aspect = float(extent[0] / max(extent[1], 1e-9))
    if columns is None:
        columns = 1 if aspect > 2.0 else 2
    rows = math.ceil(len(idx) / columns)
    width = 5.0 / columns  # of one drawing, beside the colour bar [in]
    height = min(max(width / aspect, 0.8), 4.0) + 0.45  # the drawing, its title and ticks
    fig = new_figure(figsize=(8.0, height * rows))
    axes = fig.subplots(rows, columns, squeeze=False)
    vmax = float(max(result.link_tensions[idx].max(), 1.0)) * scale("force", units)[0]
    for ax, k in zip(axes.ravel(), idx, strict=False):
        _draw(result, k, ax, vmax, magnify, units)
        ax.tick_params(labelsize="x-small")
    for ax in axes.ravel()[len(idx):]:
        ax.set_visible(False)
    _colorbar(fig, axes.ravel()[0], vmax, axes=list(axes.ravel()), units=units)
    return fig


def _colorbar(fig: Figure, ax: Axes, vmax: float, axes: list[Axes] | None = None,
              units: UnitSystem = "SI") -> None:
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    mappable = ScalarMappable(Normalize(0.0, vmax), cmap="viridis")
    fig.colorbar(mappable, ax=axes or ax, label=f"link tension [{scale('force', units)[1]}]",
                 shrink=0.8)


@shared_parameters
def tooth_loads(result: LinkLevelResult, *, ax: Axes | None = None,
                units: UnitSystem = "SI") -> Figure:
    """Mean contact force [N, or lbf with ``units="US"``] on the rollers at each place of every sprocket's
    wrap (place 0 where the chain arrives) over the steady window, one line per sprocket.

    Parameters
    ----------
    result : LinkLevelResult
        A link-level run.
    %(ax)s
    %(units_force_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.4, 3.6), units)
    for i, (name, loads) in enumerate(zip(result.names, result.tooth_loads, strict=True)):
        ax.plot(np.arange(loads.size), loads * factor, "o-", color=CYCLE[i % len(CYCLE)], label=name,
                markersize=3)
    ax.set_xlabel("place on the wrap (from the chain's arrival)")
    ax.set_ylabel(f"mean tooth load [{unit}]")
    ax.legend(fontsize="x-small", ncol=2)
    finish(ax, "Tooth load distribution")
    return fig


def frame_times(result: LinkLevelResult, count: int = 4) -> list[float]:
    """``count`` recorded instants spread evenly over the run, the last one included [s].

    Parameters
    ----------
    result : LinkLevelResult
        A link-level run.
    count : int
        Number of instants [-].

    Returns
    -------
    list of float
        The instants [s].
    """
    end = float(result.times[-1])
    return [end * (k + 1) / count for k in range(count)]


@shared_parameters
def tension_along_chain(result: LinkLevelResult, times_s: Sequence[float] | None = None, *,
                        ax: Axes | None = None, units: UnitSystem = "SI") -> Figure:
    """The tension of every link along the chain [N, or lbf with ``units="US"``] at recorded instants (None:
    :func:`frame_times`), links numbered as assembled (link i joins rollers i and i + 1).

    Parameters
    ----------
    result : LinkLevelResult
        A link-level run.
    times_s : sequence of float or None
        The instants [s] (None: :func:`frame_times`).
    %(ax)s
    %(units_force_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.4, 3.4), units)
    times = frame_times(result) if times_s is None else list(times_s)
    links = np.arange(result.link_tensions.shape[1])
    for j, t in enumerate(times):
        k = _sample(result, t)
        ax.plot(links, result.link_tensions[k] * factor, color=CYCLE[j % len(CYCLE)], linewidth=1.0,
                label=f"t = {result.times[k] * 1e3:.1f} ms")
    ax.set_xlabel("link along the chain")
    ax.set_ylabel(f"link tension [{unit}]")
    ax.legend(fontsize="x-small")
    finish(ax, "Link tension along the chain")
    return fig
