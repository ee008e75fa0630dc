"""A measured spectrum with the model's frequencies overlaid ([Welch1967] spectrum; the
lines of :func:`chaindrive.identification.model_lines`), and the model's Campbell diagram with
the measured peaks at the record's speed; for a run-up record, its order spectrum with the
shaft and tooth orders and the bands of orders the model's fixed lines sweep, and the
Campbell diagram with the run-up map's points over the record's speeds ([Brandt2011])."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.plotting._base import CYCLE, figure_axes, finish
from chaindrive.units import RAD_S_PER_RPM, TWO_PI

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics.resonance import CampbellData
    from chaindrive.identification import Identification, OrderTracking

__all__ = ["measured_campbell", "measured_spectrum", "order_spectrum", "runup_campbell"]

#: Line style of each kind of model line.
_STYLE = {"natural": ("-", 0), "tooth": ("--", 1), "shaft": (":", 2), "parametric": ("-.", 3),
          "span transverse": ((0, (1, 3)), 4)}


def _traces(ax: Axes, signals: list[tuple[str, Any, Any, list[tuple[float, float, Any]]]]
            ) -> float:
    """Draw each signal's spectral density [dB] (name, x, psd, peaks as (x, level [dB],
    matched line or None)), its peaks marked and labelled; returns the largest x drawn."""
    top = 0.0
    for k, (name, x, psd, peaks) in enumerate(signals):
        colour = CYCLE[k % len(CYCLE)]
        ax.plot(x, 10.0 * np.log10(np.maximum(psd, 1e-300)), lw=0.8, color=colour, label=name)
        top = max(top, float(x[-1]))
        for px, level, line in peaks:
            ax.plot([px], [level], "v", ms=4, color=colour)
            ax.annotate("?" if line is None else line.label, (px, level),
                        textcoords="offset points", xytext=(2, 4), fontsize="xx-small",
                        rotation=60)
    return top


def _model_lines(ax: Axes, lines: Sequence[Any], top: float, suffix: str) -> list[Any]:
    """Draw the model's lines up to ``top`` as vertical lines styled by kind (one legend
    entry a kind, "model: <kind><suffix>"); returns the lines drawn."""
    seen: set[str] = set()
    drawn = []
    for line in lines:
        if line.frequency > top:
            continue
        style, c = _STYLE.get(line.kind, ("-", 5))
        ax.axvline(line.frequency, ls=style, lw=0.7, color=CYCLE[c % len(CYCLE)], alpha=0.8,
                   label=None if line.kind in seen else f"model: {line.kind}{suffix}")
        seen.add(line.kind)
        drawn.append(line)
    return drawn


def _room_for_labels(ax: Axes) -> None:
    """Raise the top of ``ax``'s y axis by 15 % of its span: room for the peaks' labels."""
    low, high = ax.get_ylim()
    ax.set_ylim(low, high + 0.15 * (high - low))


def _campbell_axes(campbell: CampbellData, operating_rpm: float,
                   ax: Axes | None) -> tuple[Figure, Axes]:
    """The model's Campbell diagram drawn at ``operating_rpm`` [rpm] into ``ax`` (None: a new
    figure), and the axes it is drawn in."""
    from chaindrive.plotting.dynamics import campbell_diagram  # lazy: as the package does

    fig = campbell_diagram(campbell, ax=ax, operating_rpm=operating_rpm)
    return fig, fig.axes[0] if ax is None else ax


@shared_parameters
def measured_spectrum(result: Identification, *, ax: Axes | None = None) -> Figure:
    """Each signal's power spectral density [dB] against frequency [Hz], its peaks marked and
    labelled, the model's lines within the plotted range drawn as vertical lines by kind,
    with the matching tolerance shaded around the natural frequencies.

    Parameters
    ----------
    result : Identification
        :func:`chaindrive.identification.identify`.
    %(ax_returns_figure)s
    """
    fig, ax = figure_axes(ax, (7.5, 4.2))
    top = _traces(ax, [(s.name, s.frequencies, s.psd, [(p.frequency, p.level_db, p.line)
                                                        for p in s.peaks])
                       for s in result.signals])
    for line in _model_lines(ax, result.lines, top, ""):
        if line.kind == "natural":
            c = _STYLE.get(line.kind, ("-", 5))[1]
            ax.axvspan(line.frequency * (1 - result.tolerance),
                       line.frequency * (1 + result.tolerance), color=CYCLE[c % len(CYCLE)],
                       alpha=0.08, lw=0)
    _room_for_labels(ax)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("power spectral density [dB]")
    ax.legend(fontsize="x-small")
    finish(ax, f"Measured spectrum of {result.record} and the model's frequencies")
    return fig


@shared_parameters
def measured_campbell(result: Identification, campbell: CampbellData, operating_rpm: float, *,
                      ax: Axes | None = None) -> Figure:
    """The model's Campbell diagram (:func:`chaindrive.plotting.dynamics.campbell_diagram`)
    with the measured peaks drawn at the speed the record was taken at: filled where a peak
    matched a model line, open where it is unexplained; the frequency axis extended to show
    every peak.

    Parameters
    ----------
    result : Identification
        :func:`chaindrive.identification.identify`.
    %(campbell)s
    operating_rpm : float
        Driver speed of the record [rpm].
    %(ax_returns_figure)s
    """
    fig, axes = _campbell_axes(campbell, operating_rpm, ax)
    peaks = [p for sig in result.signals for p in sig.peaks]
    matched = [p.frequency for p in peaks if p.line is not None]
    alone = [p.frequency for p in peaks if p.line is None]
    if matched:
        axes.plot([operating_rpm] * len(matched), matched, "D", ms=5, color=CYCLE[3],
                  label="measured peak (matched)")
    if alone:
        axes.plot([operating_rpm] * len(alone), alone, "D", ms=5, mfc="none", color=CYCLE[3],
                  label="measured peak (unexplained)")
    if peaks:
        low, high = axes.get_ylim()
        axes.set_ylim(low, max(high, 1.1 * max(p.frequency for p in peaks)))
        axes.legend(fontsize="xx-small")
    return fig


@shared_parameters
def order_spectrum(tracking: OrderTracking, *, ax: Axes | None = None) -> Figure:
    """Each signal's order spectrum [dB] against the driver order, its peaks marked and
    labelled, the shaft and tooth orders as vertical lines, and shaded the band of orders
    f/n_max … f/n_min each natural frequency of the model sweeps over the record's speeds.

    Parameters
    ----------
    tracking : OrderTracking
        :func:`chaindrive.identification.track_orders`.
    %(ax_returns_figure)s
    """
    fig, ax = figure_axes(ax, (7.5, 4.2))
    top = _traces(ax, [(s.name, s.orders, s.psd, [(p.order, p.level_db, p.line)
                                                    for p in s.peaks])
                       for s in tracking.signals])
    _model_lines(ax, tracking.lines, top, " order")
    lo, hi = (r * RAD_S_PER_RPM / TWO_PI for r in tracking.speed_range_rpm)  # rev/s
    first = True
    for line in tracking.natural:
        if line.kind != "natural" or line.frequency / hi > top:
            continue
        ax.axvspan(line.frequency / hi, min(line.frequency / lo, top), color=CYCLE[0],
                   alpha=0.06, lw=0,
                   label="natural frequency swept over the run-up" if first else None)
        first = False
    _room_for_labels(ax)
    ax.set_xlim(0.0, top)
    ax.set_xlabel("order [cycles per driver revolution]")
    ax.set_ylabel("spectral density [dB per order]")
    ax.legend(fontsize="x-small")
    finish(ax, f"Order spectrum of {tracking.record}, "
               f"{tracking.speed_range_rpm[0]:.0f}–{tracking.speed_range_rpm[1]:.0f} rpm")
    return fig


@shared_parameters
def runup_campbell(tracking: OrderTracking, campbell: CampbellData, operating_rpm: float, *,
                   ax: Axes | None = None) -> Figure:
    """The model's Campbell diagram (:func:`chaindrive.plotting.dynamics.campbell_diagram`)
    with the run-up map's points at their slices' speeds: filled where a point matched a
    model line, open where it is unexplained; the axes extended to show every point.

    Parameters
    ----------
    tracking : OrderTracking
        :func:`chaindrive.identification.track_orders`.
    %(campbell)s
    operating_rpm : float
        The design's driver speed [rpm].
    %(ax_returns_figure)s
    """
    fig, axes = _campbell_axes(campbell, operating_rpm, ax)
    pts = tracking.points
    for matched, face, label in ((True, None, "measured (matched)"),
                                 (False, "none", "measured (unexplained)")):
        chosen = [p for p in pts if (p.line is not None) == matched]
        if chosen:
            axes.plot([p.speed_rpm for p in chosen], [p.frequency for p in chosen], "D", ms=3,
                      mfc=face, color=CYCLE[3], label=label)
    if pts:
        low, high = axes.get_ylim()
        axes.set_ylim(low, max(high, 1.05 * max(p.frequency for p in pts)))
        left, right = axes.get_xlim()
        axes.set_xlim(min(left, 0.95 * tracking.speed_range_rpm[0]),
                      max(right, 1.05 * tracking.speed_range_rpm[1]))
        axes.legend(fontsize="xx-small")
    return fig
