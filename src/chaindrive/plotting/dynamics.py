"""Vibration of the ring model: mode shapes (seed 000's relative-amplitude bars) and the
Campbell diagram (natural frequencies against the working-frequency lines)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from chaindrive.plotting._base import CYCLE, GREY, TIGHT, figure_axes, finish

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics import CampbellData, ModalResult


def mode_shapes(modal: ModalResult, *, ax: Axes | None = None,
                names: Sequence[str] | None = None, modes: int = 4) -> Figure:
    """Relative amplitudes μ_k^(j) = |X_k^(j)| / Σ_i|X_i^(j)| of each mass k in the first
    ``modes`` elastic modes j, as grouped bars (seed 000, its Fig. 5–7 and Table 1;
    rigid-body modes left out). names label the masses (default M1, M2, …)."""
    fig, ax = figure_axes(ax, (6.4, 3.6))
    elastic = np.flatnonzero(~np.asarray(modal.rigid_body))[:modes]
    mu = np.asarray(modal.normalized_amplitudes)
    n = mu.shape[0]
    labels = list(names) if names is not None else [f"M{i + 1}" for i in range(n)]
    width = 0.8 / max(len(elastic), 1)
    x = np.arange(n)
    for k, j in enumerate(elastic):
        ax.bar(x + (k - (len(elastic) - 1) / 2) * width, mu[:, j], width,
               color=CYCLE[k % len(CYCLE)],
               label=f"mode {j}: {modal.frequencies_hz[j]:.1f} Hz")
    ax.set_xticks(x, labels, rotation=90 if n > 8 else 0, fontsize="small")
    ax.set_ylabel("relative amplitude μ")
    ax.legend(fontsize="x-small")
    finish(ax, "Mode shapes (relative amplitudes of the masses)")
    return fig


def campbell_diagram(campbell: CampbellData, *, ax: Axes | None = None,
                     operating_rpm: float | None = None, max_lines: int = 8) -> Figure:
    """Campbell diagram: natural frequencies of the ring (horizontal, solid), the excitation
    lines (shaft frequencies and tooth-frequency harmonics, dashed, at most ``max_lines``),
    twice the spans' first transverse frequencies (parametric resonance, dotted) and the
    crossings (circles) against the driver speed [rpm]; the operating speed as a vertical
    line (seed 000 §3.3; seed-notes §1)."""
    fig, ax = figure_axes(ax, (6.4, 5.0))
    rpm = np.asarray(campbell.speeds_rpm)
    nat = np.asarray(campbell.natural_frequencies_hz)
    for j in range(nat.shape[1]):
        ax.plot(rpm, nat[:, j], color="k", lw=1.4, label="natural frequencies" if j == 0 else None)
    for k, (name, line) in enumerate(list(campbell.excitation_hz.items())[:max_lines]):
        ax.plot(rpm, line, ls="--", lw=1.0, color=CYCLE[k % len(CYCLE)], label=name)
    trans = np.asarray(campbell.span_transverse_hz)
    for i in range(trans.shape[1] if trans.ndim == 2 else 0):
        ax.plot(rpm, 2 * trans[:, i], ls=":", lw=1.0, color=GREY,
                label="2·f₁ of spans (parametric)" if i == 0 else None)
    cross = [(s, e) for e, _, s in campbell.crossings if rpm.min() <= s <= rpm.max()]
    if cross:
        ys = [np.interp(s, rpm, campbell.excitation_hz[e]) if e in campbell.excitation_hz
              else np.nan for s, e in cross]
        ax.plot([s for s, _ in cross], ys, "o", mfc="none", color=TIGHT, label="crossings")
    if operating_rpm is not None:
        ax.axvline(operating_rpm, color=TIGHT, lw=1.0, label=f"operating {operating_rpm:.0f} rpm")
    top = max(float(np.nanmax(nat)) if nat.size else 0.0, 1.0) * 1.3
    ax.set_ylim(0, top)
    ax.set_xlim(rpm.min(), rpm.max())
    ax.set_xlabel("driver speed, rpm")
    ax.set_ylabel("frequency, Hz")
    ax.legend(fontsize="x-small", ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    finish(ax, "Campbell diagram")
    return fig
