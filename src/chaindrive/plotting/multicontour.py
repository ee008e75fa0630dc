"""Multi-contour drives: the distribution of the contour factor K_m ([Lyashuk])."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._docstrings import shared_parameters
from chaindrive.plotting._base import CHAIN, GREY, TIGHT, figure_axes, finish

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


@shared_parameters
def km_distribution(km: ArrayLike, *, ax: Axes | None = None, risk: float = 0.05,
                    bins: int = 40) -> Figure:
    """Histogram (density) of Monte-Carlo samples of the contour factor K_m ([Lyashuk]
    eq. 16: K_m = 1 + 2Δ_y/(|ΔL₃| + 2Δ_y), e.g. from
    :func:`chaindrive.multicontour.simulate_length_difference` and
    :func:`chaindrive.multicontour.contour_factor_km`), with its mean and the value not
    reached with probability ``risk`` (K_m at risk, eq. 17–18).

    Parameters
    ----------
    km : array_like
        Samples of K_m [-].
    %(ax)s
    risk : float
        Probability that K_m at risk is exceeded [-].
    bins : int
        Histogram bins [-].

    Returns
    -------
    %(returns_figure)s
    """
    values = np.asarray(km, dtype=float).ravel()
    fig, ax = figure_axes(ax, (6.0, 3.4))
    ax.hist(values, bins=bins, density=True, color=CHAIN, alpha=0.75)
    mean, low = float(values.mean()), float(np.quantile(values, risk))
    ax.axvline(mean, color=GREY, ls="--", label=f"mean {mean:.3f}")
    ax.axvline(low, color=TIGHT, label=f"K_m at {risk:.0%} risk {low:.3f}")
    ax.set_xlabel("contour factor K_m")
    ax.set_ylabel("probability density")
    ax.legend(fontsize="x-small")
    finish(ax, f"K_m distribution ({values.size} samples)")
    return fig
