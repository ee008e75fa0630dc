"""Hinge-friction damping: absorption coefficient ψ against the relative amplitude ȳ₀ for
several initial tensions F₀ ([ChainHingeDissipation, Fig. 2])."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem, fmt
from chaindrive.plotting._base import CYCLE, finish, force_axes
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.dynamics.damping import HingeFrictionResult


@shared_parameters
def absorption_vs_amplitude(results: Sequence[HingeFrictionResult], *,
                            ax: Axes | None = None, units: UnitSystem = "SI") -> Figure:
    """ψ = 6πfd₂/(ȳ₀aK_aF) ([ChainHingeDissipation, eq. 14]) against ȳ₀, one curve per tension F₀ [N].

    results : :class:`chaindrive.dynamics.damping.HingeFrictionResult` over a grid of (F₀, ȳ₀),
    e.g. from :func:`chaindrive.dynamics.damping.hinge_friction_damping`; grouped by tension.
    The right axis reads the equivalent viscous ratio ζ = ψ/4π.

    Parameters
    ----------
    results : sequence of HingeFrictionResult
        Results over a grid of (F₀, ȳ₀).
    %(ax)s
    units : {"SI", "US"}
        Unit system of the tensions F₀ in the legend: N (SI) or lbf (US)
        (:data:`chaindrive.display.QUANTITIES`, kind ``"force"``).

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax, factor, unit = force_axes(ax, (6.0, 3.8), units)
    tensions = sorted({r.tension for r in results})
    for k, f0 in enumerate(tensions):
        rows = sorted((r for r in results if r.tension == f0), key=lambda r: r.relative_amplitude)
        y = np.array([r.relative_amplitude for r in rows])
        psi = np.array([r.absorption_coefficient for r in rows])
        ax.plot(y, psi, "o-", ms=3, color=CYCLE[k % len(CYCLE)], label=f"F₀ = {f0:g} N" if units == "SI"
                else f"F₀ = {fmt(f0 * factor)} {unit}")
    ax.set_xlabel("relative amplitude ȳ₀ = y₀/a")
    ax.set_ylabel("absorption coefficient ψ")
    right = ax.secondary_yaxis("right", functions=(lambda p: np.asarray(p) / (2 * TWO_PI),
                                                   lambda z: np.asarray(z) * (2 * TWO_PI)))
    right.set_ylabel("ζ = ψ/4π")
    ax.legend(fontsize="x-small")
    finish(ax, "Hinge-friction damping [ChainHingeDissipation]")
    return fig
