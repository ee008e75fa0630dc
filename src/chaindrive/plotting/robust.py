"""Figures of the robust study (:mod:`chaindrive.robust`): the life curve, the probabilities of
failure with their intervals, and the sensitivity indices. Each takes a result and returns a
Figure (no pyplot, nothing global changes)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from chaindrive.display import UnitSystem
from chaindrive.plotting._base import CHAIN, CYCLE, GREY, TIGHT, figure_axes, finish, new_figure, scale

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.robust.life import LifeCurve
    from chaindrive.robust.sampling import ReliabilityResult
    from chaindrive.robust.sensitivity import SensitivityResult

__all__ = ["life_curve_figure", "probability_figure", "sensitivity_figure"]


def _limits(ax: Axes, life: LifeCurve) -> None:
    ax.axvline(life.allowable_elongation * 100, color=GREY, linestyle="--", linewidth=1,
               label="replacement elongation")
    if life.first_failure_elongation is not None:
        ax.axvline(life.first_failure_elongation * 100, color=TIGHT, linestyle=":",
                   linewidth=1.2, label=f"first failure ({life.first_failure})")


def life_curve_figure(life: LifeCurve, *, units: UnitSystem = "SI") -> Figure:
    """f₁ and the detuning Δ, K_D and k₂, and the take-up travel or the sag against the
    chain's elongation, with the replacement elongation and the first failure marked.

    Parameters
    ----------
    life : LifeCurve
        The life curve (:func:`chaindrive.robust.life.life_curve`).
    units : {"SI", "US"}
        Unit system of the take-up travel: mm (SI) or in (US)
        (:data:`chaindrive.display.QUANTITIES`, kind ``"length"``).

    Returns
    -------
    Figure
    """

    eps = np.array([s.elongation for s in life.states]) * 100
    fig = new_figure(figsize=(7.2, 7.0))
    axes = fig.subplots(3, 1, sharex=True)
    ax = axes[0]
    ax.plot(eps, [s.f1_hz for s in life.states], color=CHAIN, marker="o", ms=3, label="f₁")
    ax.set_ylabel("f₁ [Hz]")
    twin = ax.twinx()
    twin.plot(eps, [s.resonance_margin_percent for s in life.states], color=TIGHT, marker="s",
              ms=3, label="detuning Δ")
    twin.set_ylabel("detuning Δ [%]", color=TIGHT)
    _limits(ax, life)
    ax.legend(loc="upper right", fontsize="small")
    finish(ax, "The drive as its chain wears")
    ax = axes[1]
    ax.plot(eps, [s.coefficient_of_dynamics for s in life.states], color=CHAIN, marker="o",
            ms=3, label="K_D")
    ax.set_ylabel("K_D [–]")
    twin = ax.twinx()
    twin.plot(eps, [s.k2 for s in life.states], color=CYCLE[2], marker="s", ms=3, label="k₂")
    twin.set_ylabel("k₂ [–]", color=CYCLE[2])
    _limits(ax, life)
    finish(ax)
    ax = axes[2]
    if any(s.take_up_travel_mm for s in life.states):
        factor, unit = scale("length", units)
        factor /= 1e3  # the travel is held in mm
        ax.plot(eps, [s.take_up_travel_mm * factor for s in life.states], color=CHAIN,
                marker="o", ms=3)
        ax.set_ylabel(f"take-up travel [{unit}]")
        if life.take_up_runs_out is not None:
            ax.axvline(life.take_up_runs_out * 100, color=CYCLE[3], linestyle="-.",
                       linewidth=1, label="take-up capacity used")
            ax.legend(loc="upper left", fontsize="small")
    else:
        ax.plot(eps, [s.sag_ratio * 100 for s in life.states], color=CHAIN, marker="o", ms=3)
        ax.set_ylabel("slack-span sag [% of span]")
    _limits(ax, life)
    ax.set_xlabel("chain elongation [%]")
    finish(ax)
    return fig


def probability_figure(result: ReliabilityResult, *, ax: Axes | None = None,
                       top: int = 12) -> Figure:
    """Probability of failing each check (the ``top`` most probable, and ``any check``) with
    its confidence interval, on a log scale.

    Parameters
    ----------
    result : ReliabilityResult
        Probabilities (:func:`chaindrive.robust.sampling.reliability`).
    ax : Axes | None
        Axes to draw into.
    top : int
        How many checks to show.

    Returns
    -------
    Figure
    """
    rows = [c for c in result.checks if c.key != "any"][:top]
    rows += [c for c in result.checks if c.key == "any"]
    fig, ax = figure_axes(ax, (6.4, 0.35 * len(rows) + 1.4))
    y = np.arange(len(rows))
    floor = 0.5 / max(result.samples, 1)
    p = np.array([max(c.probability, floor) for c in rows])
    lo = np.array([max(c.low, floor) for c in rows])
    hi = np.array([max(c.high, floor) for c in rows])
    ax.barh(y, p, color=[TIGHT if c.probability > 0 else CHAIN for c in rows], alpha=0.8)
    ax.errorbar(p, y, xerr=[p - lo, hi - p], fmt="none", ecolor="black", capsize=3,
                linewidth=1)
    ax.set_yticks(y, [c.name if c.key in ("any", "buildable") else c.key for c in rows],
                  fontsize="small")
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlim(floor / 2, 1.5)
    ax.set_xlabel(f"probability of failure ({result.samples} states, "
                  f"{result.confidence:.0%} interval)")
    finish(ax, "Probability of failing each check")
    return fig


def sensitivity_figure(result: SensitivityResult, *, ax: Axes | None = None) -> Figure:
    """Total Sobol indices ST of every group for each metric (grouped bars, with their
    intervals).

    Parameters
    ----------
    result : SensitivityResult
        The indices (:func:`chaindrive.robust.sensitivity.sensitivity`).
    ax : Axes | None
        Axes to draw into.

    Returns
    -------
    Figure
    """
    fig, ax = figure_axes(ax, (7.2, 4.0))
    metrics = [m for m, v in result.total.items() if np.all(np.isfinite(v))]
    groups = result.groups
    width = 0.8 / max(len(metrics), 1)
    x = np.arange(len(groups))
    for k, m in enumerate(metrics):
        st = np.clip(np.array(result.total[m]), 0.0, None)
        ax.bar(x + (k - (len(metrics) - 1) / 2) * width, st, width,
               yerr=np.array(result.total_conf[m]), capsize=2, color=CYCLE[k % len(CYCLE)],
               label=m, error_kw={"linewidth": 0.8})
    ax.set_xticks(x, groups, rotation=25, ha="right", fontsize="small")
    ax.set_ylabel("total Sobol index S_T [–]")
    ax.legend(fontsize="small")
    finish(ax, f"Which tolerance matters ({result.evaluations} states)")
    return fig
