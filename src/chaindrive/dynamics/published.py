"""Published figures of the worked examples the package reproduces, set beside the
analysis' own (the report and docs/dynamics.md §7 read them).

[MultimassChainDrives], its three-sprocket worked example (printout) and Fig. 2: the first
natural frequency F1 = 67.68 Hz, the largest dynamic loads of the branches 55.39, 51.95 and
15.32 N, their RMS ("dynamic loading") 44.75 N, the dynamic factor 1.18, the start-up peaks
542 N (metal chain) and 470 N (polymer chain), transients over after about 0.15 s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis

__all__ = ["PUBLISHED", "PublishedFigure", "published_comparison"]


@dataclass(frozen=True, slots=True)
class PublishedFigure:
    """One printed figure: what it is, its value in SI units and its unit for display.

    Parameters
    ----------
    quantity : str
        What the figure is (``"first natural frequency"`` …).
    value : float
        The printed value converted to SI [SI unit of the quantity: Hz, N, …].
    unit : str
        The unit it is shown in beside ours.
    """

    quantity: str
    value: float
    unit: str


#: Drive name (as the example files name it) → (source, printed figures).
PUBLISHED: dict[str, tuple[str, tuple[PublishedFigure, ...]]] = {
    "Seed three-sprocket contour": ("[MultimassChainDrives], worked example and Fig. 2", (
        PublishedFigure("first natural frequency", 67.68, "Hz"),
        PublishedFigure("dynamic load, branch 1", 55.392, "N"),
        PublishedFigure("dynamic load, branch 2", 51.945, "N"),
        PublishedFigure("dynamic load, branch 3", 15.317, "N"),
        PublishedFigure("RMS of the branch loads F_D", 44.75, "N"),
        PublishedFigure("coefficient of dynamics K_D", 1.18, ""),
        PublishedFigure("start-up peak force", 542.0, "N"),
        PublishedFigure("transient over after", 0.15, "s"),
    )),
    "Seed three-sprocket contour, polymer chain": ("[MultimassChainDrives], Fig. 2", (
        PublishedFigure("start-up peak force", 470.0, "N"),
        PublishedFigure("transient over after", 0.15, "s"),
    )),
}


def _ours(a: Analysis, quantity: str) -> float | None:
    """The analysis' value of a published quantity (None when it has none)."""
    steady, startup = a.steady, a.startup
    if quantity == "first natural frequency":
        return a.dynamics.modal.first_elastic_frequency_hz
    if quantity.startswith("dynamic load, branch") and steady is not None:
        return float(steady.span_dynamic_load[int(quantity[-1]) - 1])
    if quantity.startswith("RMS") and steady is not None:
        return steady.dynamic_load_rms
    if quantity.startswith("coefficient") and steady is not None:
        return steady.coefficient_of_dynamics
    if quantity == "start-up peak force" and startup is not None:
        return float(startup.max_span_force.max())
    if quantity == "transient over after" and startup is not None:
        return startup.settling_time
    return None


def published_comparison(analysis: Analysis
                         ) -> tuple[str, tuple[tuple[str, float, float | None, str], ...]] | None:
    """The printed figures of the drive beside the analysis' own.

    Parameters
    ----------
    analysis : Analysis
        An analysis of a drive named as a published example (:data:`PUBLISHED`).

    Returns
    -------
    tuple | None
        (source, rows of (quantity, printed value, ours, unit)), or None for another drive.
    """
    entry = PUBLISHED.get(analysis.drive.name)
    if entry is None:
        return None
    source, figures = entry
    return source, tuple((f.quantity, f.value, _ours(analysis, f.quantity), f.unit)
                         for f in figures)
