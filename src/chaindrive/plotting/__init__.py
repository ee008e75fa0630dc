"""Figures of chaindrive results (matplotlib), kept apart from the compute modules.

Every function takes a result object and returns a :class:`matplotlib.figure.Figure`; pass
``ax=`` to draw into an axes of your own figure instead. matplotlib is imported only when a
figure is made, through :class:`matplotlib.figure.Figure` (not ``pyplot``): importing this
package changes no global state, selects no backend and never opens a window. Save with
``fig.savefig("name.png")`` (rendered by Agg) or ``.svg`` / ``.pdf``.

Families (one module each): :mod:`.layout` (contour to scale), :mod:`.kinematics` (speed and
ratio over a tooth period, [ChainNonUniformity]), :mod:`.strength` (static loads per span
and per shaft), :mod:`.dynamics` (mode shapes as the relative-amplitude bars of
[MultimassChainDrives], Campbell diagram), :mod:`.damping` (ψ against ȳ₀ for several
tensions, [ChainHingeDissipation]), :mod:`.multicontour` (K_m distribution, [Lyashuk]),
:mod:`.synthesis` (Pareto front), :mod:`.response` (start-up oscillograms, AFC, steady
dynamic loads, inertia loads and irregularity, material pairs —
[MultimassChainDrives, Fig. 2–3, Table 1]), :mod:`.linklevel` (frames of the link-level
model's chain, link tension along it, tooth loads), :mod:`.robust` (life curve,
probabilities of failure, sensitivity indices).
"""

from __future__ import annotations

from chaindrive.plotting.damping import absorption_vs_amplitude
from chaindrive.plotting.dynamics import campbell_diagram, mode_shapes
from chaindrive.plotting.kinematics import chain_speed, ratio_pair, transmission_ratio
from chaindrive.plotting.layout import contour_layout
from chaindrive.plotting.linklevel import (
    chain_frame,
    chain_frames,
    frame_times,
    tension_along_chain,
    tooth_loads,
)
from chaindrive.plotting.multicontour import km_distribution
from chaindrive.plotting.response import (
    afc_curves,
    inertia_and_irregularity,
    material_comparison_chart,
    startup_oscillogram,
    startup_speeds,
    steady_loads,
)
from chaindrive.plotting.robust import life_curve_figure, probability_figure, sensitivity_figure
from chaindrive.plotting.strength import shaft_loads, span_tensions
from chaindrive.plotting.synthesis import pareto_front

__all__ = [
    "absorption_vs_amplitude",
    "afc_curves",
    "campbell_diagram",
    "chain_frame",
    "chain_frames",
    "chain_speed",
    "contour_layout",
    "frame_times",
    "inertia_and_irregularity",
    "km_distribution",
    "life_curve_figure",
    "material_comparison_chart",
    "mode_shapes",
    "pareto_front",
    "probability_figure",
    "ratio_pair",
    "sensitivity_figure",
    "shaft_loads",
    "span_tensions",
    "startup_oscillogram",
    "startup_speeds",
    "steady_loads",
    "tension_along_chain",
    "tooth_loads",
    "transmission_ratio",
]
