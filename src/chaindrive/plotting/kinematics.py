"""Chain speed and transmission ratio over one tooth period ([ChainNonUniformity])."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem, fmt
from chaindrive.plotting._base import CHAIN, CYCLE, GREY, figure_axes, finish, scale

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from chaindrive.analysis import Analysis
    from chaindrive.kinematics import KinematicsResult


@shared_parameters
def chain_speed(kinematics: KinematicsResult, *, ax: Axes | None = None,
                units: UnitSystem = "SI") -> Figure:
    """Instantaneous chain speed v = R₁ω₁cos β [m/s, or ft/min with ``units="US"``] over one tooth period of
    the driver ([ChainNonUniformity, eq. 6]), with the mean speed v̄ = z₁pω₁/2π dashed. x: driver rotation β
    [°].

    Parameters
    ----------
    kinematics : KinematicsResult
        The drive's kinematics (speed traces of the tight span).
    %(ax)s
    units : {"SI", "US"}
        Unit system of the speed axis: m/s (SI) or ft/min (US)
        (:data:`chaindrive.display.QUANTITIES`, kind ``"velocity"``).

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (6.0, 3.4))
    factor, unit = scale("velocity", units)
    beta = np.degrees(kinematics.phase)
    mean = kinematics.chain_speed * factor
    ax.plot(beta, np.asarray(kinematics.chain_speed_trace) * factor, color=CHAIN, lw=1.6,
            label="v(β)")
    ax.axhline(mean, color=GREY, ls="--", lw=1.0,
               label=f"mean {mean:.3f} {unit}" if units == "SI" else f"mean {fmt(mean)} {unit}")
    ax.set_xlabel("driver rotation within one tooth β, °")
    ax.set_ylabel(f"chain speed, {unit}")
    ax.legend(fontsize="x-small")
    finish(ax, "Chain speed over a tooth period")
    return fig


def ratio_pair(analysis: Analysis) -> tuple[int, int]:
    """The sprockets whose ratio :func:`transmission_ratio` draws: (driver, the sprocket at
    the far end of the tight span), indices into ``analysis.drive.sprockets``.

    Parameters
    ----------
    analysis : Analysis
        The analysis (its drive and geometry).

    Returns
    -------
    tuple of int
        (driver index, index of the other sprocket).
    """
    tight = next((s for s in analysis.geometry.spans if s.tight), analysis.geometry.spans[0])
    return analysis.drive.driver_index, tight.start


@shared_parameters
def transmission_ratio(analysis: Analysis, *, ax: Axes | None = None) -> Figure:
    """Instantaneous ratio i = ω₁/ω₂ over one tooth period for the sprocket at the far end
    of the tight span ([ChainNonUniformity]: i = R₂cos γ / (R₁cos β)), as computed by
    :func:`chaindrive.kinematics.drive_kinematics` (``ratio_traces``); the labels name the
    pair (:func:`ratio_pair`), e.g. ω(S1) / ω(S3) and z(S3) / z(S1) = 14/15.

    Parameters
    ----------
    analysis : Analysis
        The analysis (its kinematics and geometry).
    %(ax)s

    Returns
    -------
    %(returns_figure)s
    """
    fig, ax = figure_axes(ax, (6.0, 3.4))
    drive = analysis.drive
    i, j = ratio_pair(analysis)
    driver, other = drive.sprockets[i], drive.sprockets[j]
    ratio = analysis.kinematics.ratio_traces[j]
    beta = np.degrees(analysis.kinematics.phase)
    a, b = driver.name, other.name
    ax.plot(beta, ratio, color=CYCLE[1], lw=1.6, label=f"ω({a}) / ω({b})")
    ax.axhline(other.teeth / driver.teeth, color=GREY, ls="--", lw=1.0,
               label=f"z({b}) / z({a}) = {other.teeth}/{driver.teeth} = "
                     f"{fmt(other.teeth / driver.teeth)}")
    ax.set_xlabel(f"driver rotation within one tooth β ({a}), °")
    ax.set_ylabel(f"ratio ω({a}) / ω({b})")
    ax.legend(fontsize="x-small")
    finish(ax, f"Instantaneous transmission ratio {a} → {b}")
    return fig
