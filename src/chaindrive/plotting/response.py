"""The dynamic response (Dynamics II): start-up oscillograms (seed 000 Fig. 2), the
amplitude–frequency characteristic (seed 000 Fig. 3), and the steady dynamic loads, inertia
loads and irregularity of rotation per span and per mass (seed 000 §3.3)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from chaindrive.plotting._base import CYCLE, GREY, TIGHT, figure_axes, finish

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics.afc import AfcResult
    from chaindrive.dynamics.startup import StartupResult
    from chaindrive.dynamics.steady import SteadyStateResult

RPM = 30.0 / np.pi


def _names(count: int, names: Sequence[str] | None, prefix: str) -> list[str]:
    return list(names) if names is not None else [f"{prefix}{i + 1}" for i in range(count)]


def startup_oscillogram(startup: StartupResult, *, ax: Axes | None = None,
                        names: Sequence[str] | None = None) -> Figure:
    """Span forces against time during the start-up (seed 000 Fig. 2), the largest force
    F₁max marked and the settling time as a vertical line. names label the spans."""
    fig, ax = figure_axes(ax, (6.4, 3.6))
    t = np.asarray(startup.times) * 1e3
    forces = np.asarray(startup.span_forces)
    labels = _names(forces.shape[1], names, "span ")
    shown = np.argsort(startup.max_span_force)[::-1][:6]  # the six most loaded spans
    for k, i in enumerate(shown):
        ax.plot(t, forces[:, i], lw=0.9, color=CYCLE[k % len(CYCLE)], label=labels[i])
    i_max = int(np.argmax(startup.max_span_force))
    k_max = int(np.argmax(forces[:, i_max]))
    ax.plot([t[k_max]], [forces[k_max, i_max]], "o", color=TIGHT, ms=5,
            label=f"F₁max = {forces[k_max, i_max]:.0f} N")
    ax.axvline(startup.settling_time * 1e3, color=GREY, ls="--", lw=0.9,
               label=f"settled at {startup.settling_time * 1e3:.0f} ms")
    ax.set_xlabel("time, ms")
    ax.set_ylabel("span force, N")
    ax.legend(fontsize="x-small", loc="upper right")
    finish(ax, "Start-up: span forces")
    return fig


def startup_speeds(startup: StartupResult, *, ax: Axes | None = None,
                   names: Sequence[str] | None = None) -> Figure:
    """Sprocket speeds [rpm] against time during the start-up."""
    fig, ax = figure_axes(ax, (6.4, 3.2))
    t = np.asarray(startup.times) * 1e3
    speeds = np.asarray(startup.speeds) * RPM
    labels = _names(speeds.shape[1], names, "S")
    for i in range(min(speeds.shape[1], 8)):
        ax.plot(t, speeds[:, i], lw=0.9, color=CYCLE[i % len(CYCLE)], label=labels[i])
    ax.set_xlabel("time, ms")
    ax.set_ylabel("speed, rpm")
    ax.legend(fontsize="x-small", loc="lower right")
    finish(ax, "Start-up: sprocket speeds")
    return fig


def afc_curves(afc: AfcResult, *, ax: Axes | None = None,
               names: Sequence[str] | None = None, max_markers: int = 6) -> Figure:
    """Dynamic load amplitude of every span against the tooth frequency (seed 000 Fig. 3),
    with the resonances inside the sweep (natural frequency j over harmonic k) as dotted
    lines."""
    fig, ax = figure_axes(ax, (6.4, 3.8))
    fz = np.asarray(afc.tooth_frequencies_hz)
    load = np.asarray(afc.span_load)
    labels = _names(load.shape[1], names, "span ")
    shown = np.argsort(load.max(axis=0))[::-1][:6]
    for k, i in enumerate(shown):
        ax.plot(fz, load[:, i], lw=1.0, color=CYCLE[k % len(CYCLE)], label=labels[i])
    for j, k, _f, f_line in list(afc.markers)[:max_markers]:
        ax.axvline(f_line, color=GREY, ls=":", lw=0.8)
        ax.annotate(f"mode {j} × {k}", (f_line, 0.97), xycoords=("data", "axes fraction"),
                    rotation=90, fontsize="xx-small", va="top", ha="right", color=GREY)
    ax.set_yscale("log")
    ax.set_xlabel("tooth frequency, Hz")
    ax.set_ylabel("dynamic load amplitude, N")
    ax.legend(fontsize="x-small", loc="lower right")
    finish(ax, "Amplitude–frequency characteristic")
    return fig


def steady_loads(steady: SteadyStateResult, *, ax: Axes | None = None,
                 names: Sequence[str] | None = None) -> Figure:
    """Largest steady dynamic load of every span under the polygonal excitation (bars)."""
    fig, ax = figure_axes(ax, (6.4, 3.2))
    load = np.asarray(steady.span_dynamic_load)
    labels = _names(load.size, names, "span ")
    x = np.arange(load.size)
    ax.bar(x, load, color=TIGHT, width=0.7)
    ax.set_xticks(x, labels, rotation=90 if load.size > 8 else 0, fontsize="small")
    ax.set_ylabel("dynamic load, N")
    finish(ax, "Steady motion: dynamic load per span")
    return fig


def inertia_and_irregularity(steady: SteadyStateResult, *,
                             names: Sequence[str] | None = None) -> Figure:
    """Two bar charts per mass: the inertia load m·ẍ [N] and the irregularity of rotation
    Δ = 2x/R·100 [%] in steady motion (seed 000 §3.3)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.6), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    inertia = np.asarray(steady.inertia_load)
    irregular = np.asarray(steady.irregularity_percent)
    labels = _names(inertia.size, names, "S")
    x = np.arange(inertia.size)
    top.bar(x, inertia, color=CYCLE[0], width=0.7)
    top.set_ylabel("inertia load, N")
    finish(top, "Steady motion: inertia load and irregularity per mass")
    bottom.bar(x, irregular, color=CYCLE[2], width=0.7)
    bottom.set_ylabel("irregularity Δ, %")
    bottom.set_xticks(x, labels, rotation=90 if inertia.size > 8 else 0, fontsize="small")
    finish(bottom)
    return fig
