"""Dynamic response of a drive ([MultimassChainDrives, §3.2–3.6]): start-up oscillograms of the span forces
and of the sprocket speeds (its Fig. 2), amplitude–frequency curves per span with the
resonance marks (its Fig. 3), steady dynamic loads per span, inertia loads and irregularity
per mass, and the four material pairs side by side (its Fig. 2–3 and Table 1).

Spans are labelled ``span 1`` … and masses ``M1`` … unless ``names`` are given (the report
passes "S1→S2" and the sprocket names). With more than ``max_lines`` curves the most loaded
ones are drawn in colour with a legend and the others thin and grey, so a 24-sprocket drive
stays readable.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.display import RPM_PER_RAD_S, UnitSystem, fmt
from chaindrive.plotting._base import (
    CHAIN,
    CYCLE,
    GREY,
    TIGHT,
    figure_axes,
    finish,
    force_axes,
    new_figure,
    scale,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics.frequency.afc import AfcResult
    from chaindrive.dynamics.frequency.steady import SteadyStateResult
    from chaindrive.dynamics.materials import MaterialCase
    from chaindrive.dynamics.transient.startup import StartupResult

__all__ = ["afc_curves", "inertia_and_irregularity", "material_comparison_chart",
           "startup_oscillogram", "startup_speeds", "steady_loads"]



def _labels(n: int, names: Sequence[str] | None, prefix: str) -> list[str]:
    """``names`` (checked against n) or prefix + 1…n."""
    if names is None:
        return [f"{prefix}{i + 1}" for i in range(n)]
    if len(names) != n:
        raise ValueError(f"need {n} names, got {len(names)}")
    return [str(s) for s in names]


def _curves(ax: Axes, x: NDArray[np.float64], y: NDArray[np.float64], labels: list[str],
            max_lines: int) -> None:
    """One line per column of y (T, n); beyond max_lines only the columns of largest peak
    in colour, the rest thin grey under one legend entry."""
    n = y.shape[1]
    order = np.argsort(-np.abs(y).max(axis=0)) if n else np.zeros(0, int)
    shown = set(order[:max_lines].tolist())
    grey = False
    for i in range(n):
        if i in shown:
            continue
        ax.plot(x, y[:, i], color=GREY, lw=0.5, alpha=0.6,
                label=None if grey else f"other {n - len(shown)}")
        grey = True
    for k, i in enumerate(sorted(shown)):
        ax.plot(x, y[:, i], color=CYCLE[k % len(CYCLE)], lw=1.1, label=labels[i])


def _bar_ticks(ax: Axes, labels: list[str]) -> None:
    ax.set_xticks(range(len(labels)), labels, rotation=90 if len(labels) > 8 else 0,
                  fontsize="small")


def _zoom_end(t: NDArray[np.float64], transient: float) -> float:
    """End of the time axis [ms]: the whole record, or 4× the transient when it takes less
    than a fifth of the record (so the start-up itself is readable)."""
    if math.isfinite(transient) and transient > 0 and 4 * transient < t[-1]:
        return float(4 * transient)
    return float(t[-1])


@shared_parameters
def startup_oscillogram(startup: StartupResult, *, ax: Axes | None = None,
                        names: Sequence[str] | None = None, max_lines: int = 6,
                        units: UnitSystem = "SI") -> Figure:
    """Span forces F_i(t) [N, or lbf with ``units="US"``] during the start-up against time [ms]
    ([MultimassChainDrives, Fig. 2]), the largest one F₁max marked and labelled, the settling
    time as a dashed vertical line
    (:func:`chaindrive.dynamics.transient.startup.transient_times`; the title says when the
    record ends before the forces settle). names label the spans. When the start-up settles
    within a fifth of the record the time axis ends at 4× the settling time (the title says
    so).

    Parameters
    ----------
    startup : StartupResult
        The start-up.
    %(ax)s
    %(span_curves)s
    %(units_force_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.4, 3.6), units)
    t = np.asarray(startup.times) * 1e3
    F = np.asarray(startup.span_forces) * factor
    labels = _labels(F.shape[1], names, "span ")
    _curves(ax, t, F, labels, max_lines)
    # F₁max as the result holds it (the peak over every step, not only the recorded ones),
    # written by the rule of the tables, at the recorded peak of its span
    peaks = np.asarray(startup.max_span_force, dtype=float) * factor
    k = int(np.argmax(peaks))
    i = int(np.argmax(F[:, k]))
    top = float(peaks[k])
    ax.plot(t[i], top, "v", color="k", ms=7, zorder=5)
    ax.annotate(f"F₁max = {fmt(top)} {unit} ({labels[k]})", (t[i], top), xytext=(6, 2),
                textcoords="offset points", fontsize="small", va="bottom")
    ts = startup.settling_time * 1e3
    if math.isfinite(ts) and t[0] < ts <= t[-1]:
        ax.axvline(ts, color=GREY, ls="--", lw=1.0, label=f"settled at {ts:.0f} ms")
    ax.set_ylim(top=max(top, float(F.max())) * 1.15 if top > 0 else None)
    end = _zoom_end(t, max(ts, t[i]))
    ax.set_xlim(t[0], end)
    ax.set_xlabel("time, ms")
    ax.set_ylabel(f"span force, {unit}")
    _legend(ax, F.shape[1])
    title = "Start-up: span forces"
    if end < t[-1]:
        title += f" (first {end:.0f} of {t[-1]:.0f} ms)"
    if not math.isfinite(ts):
        title += f", not settled within {t[-1]:.0f} ms"
    finish(ax, title)
    return fig


@shared_parameters
def startup_speeds(startup: StartupResult, *, ax: Axes | None = None,
                   names: Sequence[str] | None = None, max_lines: int = 6) -> Figure:
    """Sprocket speeds [rpm] during the start-up against time [ms] ([MultimassChainDrives, Fig. 2]), over
    the same time axis as :func:`startup_oscillogram`. names label the sprockets (masses).

    Parameters
    ----------
    startup : StartupResult
        The start-up.
    %(ax)s
    names : sequence of str or None
        Labels of the sprockets (None: M1, M2, …).
    max_lines : int
        Sprockets drawn at most [-].

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (6.4, 3.6))
    t = np.asarray(startup.times) * 1e3
    w = np.asarray(startup.speeds) * RPM_PER_RAD_S
    _curves(ax, t, w, _labels(w.shape[1], names, "M"), max_lines)
    end = _zoom_end(t, startup.settling_time * 1e3)
    ax.set_xlim(t[0], end)
    ax.set_xlabel("time, ms")
    ax.set_ylabel("speed, rpm")
    _legend(ax, w.shape[1], inside="lower right")
    title = "Start-up: sprocket speeds"
    finish(ax, title if end >= t[-1] else f"{title} (first {end:.0f} of {t[-1]:.0f} ms)")
    return fig


def _chosen_markers(afc: AfcResult, max_markers: int) -> list[tuple[int, int, float, float]]:
    """The resonance markers inside the sweep to draw, at most max_markers: highest span
    load first, skipping any closer than 3 % of the sweep to one already chosen (their
    labels would print over each other)."""
    fz = np.asarray(afc.tooth_frequencies_hz)
    top = np.asarray(afc.span_load).max(axis=1)
    inside = [m for m in afc.markers if fz.min() <= m[3] <= fz.max()]
    inside.sort(key=lambda m: -float(np.interp(m[3], fz, top)))
    gap = 0.03 * float(np.ptp(fz)) if fz.size else 0.0
    chosen: list[tuple[int, int, float, float]] = []
    for m in inside:
        if len(chosen) < max_markers and all(abs(m[3] - c[3]) >= gap for c in chosen):
            chosen.append(m)
    return sorted(chosen, key=lambda m: m[3])


def _mode_number(marker: int, mode_numbers: Sequence[int] | None) -> int:
    """The table's number of the mode an AFC marker names (its own numbers count the
    elastic modes from 1)."""
    if mode_numbers is None or not 1 <= marker <= len(mode_numbers):
        return marker
    return int(mode_numbers[marker - 1])


def _legend(ax: Axes, curves: int,
            inside: Literal["upper right", "lower right", "upper left"] = "upper right") -> None:
    """Legend inside (at ``inside``) for a few curves, outside on the right for many."""
    if curves > 4:
        ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  frameon=False)
    else:
        ax.legend(fontsize="x-small", loc=inside)


@shared_parameters
def afc_curves(afc: AfcResult, *, ax: Axes | None = None, names: Sequence[str] | None = None,
               max_lines: int = 6, max_markers: int = 8,
               operating_hz: float | None = None,
               mode_numbers: Sequence[int] | None = None, units: UnitSystem = "SI") -> Figure:
    """Amplitude–frequency characteristics: peak dynamic load of each span [N, or lbf with
    ``units="US"``] against the
    tooth frequency [Hz] ([MultimassChainDrives, Fig. 3]), every resonance (harmonic k of the tooth
    frequency on natural frequency f_j, at f_z = f_j/k) as a dotted vertical line labelled
    "mode j × k" above the plot, clear of the curves (the ``max_markers`` with the highest
    load; modes numbered as in the tables with ``mode_numbers``),
    and the operating tooth frequency ``operating_hz`` as a solid line. Logarithmic load
    axis: the resonance peaks stand orders of magnitude above the rest of the curves.

    Parameters
    ----------
    afc : AfcResult
        The speed sweep.
    %(ax)s
    %(span_curves)s
    max_markers : int
        Resonance lines labelled at most [-].
    operating_hz : float or None
        Operating tooth frequency [Hz] (None: not drawn).
    mode_numbers : sequence of int or None
        The number each elastic mode carries in the tables, in the order of
        ``afc.natural_frequencies_hz`` (None: the markers' own 1, 2, …).
    %(units_force_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.4, 4.0), units)
    fz = np.asarray(afc.tooth_frequencies_hz)
    F = np.asarray(afc.span_load) * factor
    _curves(ax, fz, F, _labels(F.shape[1], names, "span "), max_lines)
    trans = ax.get_xaxis_transform()
    longest = 0
    for j, k, _, f in _chosen_markers(afc, max_markers):
        ax.axvline(f, color=GREY, ls=":", lw=0.9)
        label = f"mode {_mode_number(j, mode_numbers)} × {k}"
        longest = max(longest, len(label))
        # above the plotting area: clear of the curves (the markers are 3 % apart)
        ax.text(f, 1.01, label, transform=trans, rotation=90, va="bottom", ha="center",
                fontsize="xx-small", color="#444444", clip_on=False)
    if operating_hz is not None:
        ax.axvline(operating_hz, color="k", lw=1.0,
                   label=f"operating {operating_hz:.1f} Hz")
    ax.set_xlim(fz[0], fz[-1])
    ax.set_yscale("log")  # the resonance peaks are orders of magnitude above the rest
    positive = F[F > 0]
    if positive.size:
        ax.set_ylim(max(float(positive.min()), float(positive.max()) * 1e-4) * 0.8,
                    float(positive.max()) * 3.0)
    ax.set_xlabel("tooth frequency f_z, Hz")
    ax.set_ylabel(f"dynamic load, {unit}")
    _legend(ax, F.shape[1], inside="upper left")
    finish(ax)
    # the title clears the resonance labels above the plot (≈ 3 pt a character)
    ax.set_title("Amplitude–frequency characteristics per span", fontsize="medium",
                 pad=6.0 + 3.0 * longest)
    return fig


@shared_parameters
def steady_loads(steady: SteadyStateResult, *, ax: Axes | None = None,
                 names: Sequence[str] | None = None, units: UnitSystem = "SI") -> Figure:
    """Steady dynamic load of each span under the polygonal effect ([MultimassChainDrives, §3.3]): peak
    |F_i(t)| and amplitude (max − min)/2 over a tooth period [N, or lbf with ``units="US"``],
    grouped bars.

    Parameters
    ----------
    steady : SteadyStateResult
        The steady state.
    %(ax)s
    %(span_names)s
    %(units_force_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.0, 3.4), units)
    peak = np.asarray(steady.span_dynamic_load) * factor
    amp = np.asarray(steady.span_load_amplitude) * factor
    labels = _labels(peak.size, names, "span ")
    x = np.arange(peak.size)
    ax.bar(x - 0.2, peak, 0.4, color=TIGHT, label="peak |F(t)|")
    ax.bar(x + 0.2, amp, 0.4, color=CHAIN, label="amplitude (max − min)/2")
    _bar_ticks(ax, labels)
    ax.set_ylabel(f"dynamic load, {unit}")
    ax.legend(fontsize="x-small")
    finish(ax, "Steady dynamic load per span (polygonal effect)")
    return fig


@shared_parameters
def inertia_and_irregularity(steady: SteadyStateResult, *,
                             names: Sequence[str] | None = None,
                             units: UnitSystem = "SI") -> Figure:
    """Two bar charts per mass ([MultimassChainDrives, §3.3]): the inertia load max |m_i ẍ_i| [N, or lbf with
    ``units="US"``] and the irregularity of rotation Δ_i = 2 x_A/R_i · 100 [%] (nan bars when the radii were
    not given to the steady state).

    Parameters
    ----------
    steady : SteadyStateResult
        The steady state.
    names : sequence of str or None
        Labels of the masses (None: M1, M2, …).
    %(units_force)s

    Returns
    -------
    Figure
        A new figure with the two charts.
    """

    factor, unit = scale("force", units)
    inertia = np.asarray(steady.inertia_load) * factor
    irr = np.asarray(steady.irregularity_percent)
    labels = _labels(inertia.size, names, "M")
    wide = inertia.size > 8
    fig = new_figure(figsize=(6.4, 5.6) if wide else (7.6, 3.2))
    rows, columns = (2, 1) if wide else (1, 2)
    ax1, ax2 = fig.add_subplot(rows, columns, 1), fig.add_subplot(rows, columns, 2)
    ax1.bar(range(inertia.size), inertia, color=CHAIN)
    ax1.set_ylabel(f"inertia load m·ẍ, {unit}")
    _bar_ticks(ax1, labels)
    finish(ax1, "Inertia load per mass")
    ax2.bar(range(irr.size), np.nan_to_num(irr), color=TIGHT)
    ax2.set_ylabel("irregularity Δ, %")
    _bar_ticks(ax2, labels)
    finish(ax2, "Irregularity of rotation per mass")
    return fig


def _pair_label(case: MaterialCase) -> str:
    return f"{case.chain_material}\non {case.sprocket_material}"


@shared_parameters
def material_comparison_chart(cases: Sequence[MaterialCase], *,
                              units: UnitSystem = "SI") -> Figure:
    """The material pairs side by side ([MultimassChainDrives, Fig. 2–3, Table 1]): start-up peak span force
    [N] and the amplitude of the first resonance [N] (lbf for both with ``units="US"``; its tooth frequency
    [Hz] printed on the bar) per pair of chain and sprocket materials
    (:func:`chaindrive.dynamics.materials.material_comparison`).

    Parameters
    ----------
    cases : sequence of MaterialCase
        One per material pair.
    %(units_force)s

    Returns
    -------
    Figure
        A new figure.
    """

    labels = [_pair_label(c) for c in cases]
    colours = [CYCLE[i % len(CYCLE)] for i in range(len(cases))]
    fig = new_figure(figsize=(7.6, 3.4))
    ax1, ax2 = fig.subplots(1, 2)
    factor, unit = scale("force", units)
    x = np.arange(len(cases))
    bars = ax1.bar(x, [c.startup_peak_n * factor for c in cases], color=colours)
    ax1.bar_label(bars, fmt="%.0f", fontsize="x-small")
    ax1.set_ylabel(f"start-up peak F₁max, {unit}")
    finish(ax1, "Start-up peak")
    amplitude = [c.resonance_amplitude_n * factor for c in cases]
    bars = ax2.bar(x, amplitude, color=colours)
    ax2.bar_label(bars, [f"{a:.0f} {unit}\n@ {c.resonance_tooth_frequency_hz:.0f} Hz"
                         for a, c in zip(amplitude, cases, strict=True)], fontsize="x-small")
    ax2.set_ylabel(f"first resonance amplitude, {unit}")
    finish(ax2, "First resonance (AFC)")
    for ax in (ax1, ax2):
        ax.set_xticks(x, labels, fontsize="x-small")
        ax.set_xlabel("chain material on sprocket material", fontsize="small")
        ax.margins(y=0.22)
    return fig
