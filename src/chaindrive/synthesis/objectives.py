"""Objectives of the synthesis: what a design is judged by, read from its
:class:`~chaindrive.analysis.Analysis` (the evaluation is :mod:`.evaluation`).

[MultimassChainDrives], §3.6 and conclusion: minimum cost, material (mass), occupied volume
and weight, maximum dynamic quality. Every objective is a :class:`Metric` of an
:class:`~chaindrive.analysis.Analysis` in :data:`OBJECTIVES` (a module adds its own with
:func:`register_objective`). The constraints are the analysis's own checks
(:meth:`~chaindrive.analysis.Analysis.checks`, their ``violation`` ≤ 0 when satisfied) that
the problem's ``[optimize.constraints]`` select and set the limits of, plus two wishes of the
designer that are not engineering rules: the driven speeds' ratio tolerance and a highest
mean chain speed. The analysis is lazy: a design costs only the stages its objectives and
constraints read.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from chaindrive.analysis import Analysis
from chaindrive.robust.synthesis import ROBUST_OBJECTIVES, robust_statistic
from chaindrive.synthesis.detuning import BAND, detuning_metric_value, normalised_amplitude_at

__all__ = ["OBJECTIVES", "Metric", "available_objectives", "register_objective"]


@dataclass(frozen=True, slots=True)
class Metric:
    """An objective of the synthesis.

    Parameters
    ----------
    name : str
        Its name in ``[optimize] objectives``.
    unit : str
        The unit of its value.
    sense : int
        +1 minimise, −1 maximise.
    value : callable
        Analysis → value [``unit``].
    description : str
        What it measures.
    """

    name: str
    unit: str
    sense: int
    value: Callable[[Analysis], float]
    description: str


OBJECTIVES: dict[str, Metric] = {}


def register_objective(metric: Metric) -> Metric:
    """Add (or replace) an objective by name.

    Parameters
    ----------
    metric : Metric
        The objective.

    Returns
    -------
    Metric
        The same objective.
    """
    OBJECTIVES[metric.name] = metric
    return metric


def objective_unit(name: str, currency: str) -> str:
    """The unit of an objective's value, the currency of the cost model for a price.

    Parameters
    ----------
    name : str
        A registered objective.
    currency : str
        The cost model's currency (e.g. "EUR").

    Returns
    -------
    str
        E.g. "kg", "m^3", "EUR", "-".
    """
    unit = OBJECTIVES[name].unit
    return currency if unit == "currency" else unit


def available_objectives() -> tuple[str, ...]:
    """Names of the registered objectives.

    Returns
    -------
    tuple of str
        In the order of registration.
    """
    return tuple(OBJECTIVES)


def _resonance_margin(a: Analysis) -> float:
    c = a.check("resonance_margin")
    return math.inf if c is None or c.value is None else float(c.value)


def _kd(a: Analysis) -> float:
    s = a.steady
    return 1.0 if s is None or s.coefficient_of_dynamics is None else float(
        s.coefficient_of_dynamics)


for _m in (
    Metric("cost", "currency", 1, lambda a: a.metrics.cost,
           "sprockets + chain + flywheels (chaindrive.cost)"),
    Metric("mass", "kg", 1, lambda a: a.metrics.mass_kg, "sprocket bodies + chain + flywheels"),
    Metric("volume", "m^3", 1, lambda a: a.metrics.volume_m3,
           "bounding box of the tip circles × chain width"),
    Metric("chain_length", "m", 1, lambda a: float(a.geometry.chain_length), "chain length"),
    Metric("resonance_margin", "%", -1, _resonance_margin,
           "least distance of a working frequency from resonance (maximised)"),
    Metric("normalised_amplitude", "-", 1,
           lambda a: normalised_amplitude_at(a.dynamics.modal,
                                             a.working_frequencies_hz,
                                             a.dynamics.modal.damping_ratio),
           "largest normalised amplitude at the working frequencies"),
    Metric("coefficient_of_dynamics", "-", 1, _kd,
           "K_D = 1 + F_D/F_t in steady motion [MultimassChainDrives]"),
    Metric("detuning", "-", 1,
           lambda a: detuning_metric_value(a.dynamics.modal.elastic_frequencies_hz,
                                           a.working_frequencies_hz, BAND),
           "Σ squared shortfall of the natural frequencies inside ±10 % of the working "
           "frequencies (0 = clear)"),
):
    register_objective(_m)

# robust objectives: statistics of the design's states over its [uncertainty] model
# (they need [optimize.robust]; chaindrive.robust.synthesis)
for _name, (_metric, _q, _sense, _unit, _text) in ROBUST_OBJECTIVES.items():
    register_objective(Metric(_name, _unit, _sense, partial(robust_statistic, name=_name), _text))
