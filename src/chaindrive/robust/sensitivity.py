"""Which tolerance matters: Sobol global sensitivity indices of the drive's metrics over the
groups of its uncertainty model (SALib).

The Saltelli design of N·(G + 2) points (first-order and total indices, no second order)
[Saltelli2010] is drawn in the unit cube of the d variables with the groups of
:class:`~chaindrive.robust.uncertainty.UncertaintyModel` (eccentricity, shaft positions,
inertias, … each one group), mapped through the variables' inverse CDFs and evaluated
through the full path (:class:`~chaindrive.robust.analysis.PerturbedAnalysis`). For every
metric (resonance margin, K_D, k₂, k₂ with the eccentricity loads, f₁, and the margin of the
checks asked for) SALib estimates S1
(the share of the variance a group explains alone) and ST (with all its interactions) with
bootstrap intervals [Herman2017].
A state that cannot be built takes the mean of the others (said in the result).

References
----------
[Saltelli2010], [Herman2017]
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from SALib.analyze import sobol as sobol_analyze
from SALib.sample import sobol as sobol_sample

from chaindrive.analysis import Analysis
from chaindrive.robust.sampling import StateEvaluator, serial_states
from chaindrive.robust.uncertainty import UncertaintyModel

__all__ = ["SENSITIVITY_METRICS", "SensitivityResult", "sensitivity"]

#: Metrics whose variance is apportioned, with their units.
SENSITIVITY_METRICS: dict[str, str] = {"resonance_margin_percent": "%",
                                       "coefficient_of_dynamics": "-", "k2": "-",
                                       "k2_with_errors": "-", "f1_hz": "Hz"}


@dataclass(frozen=True, slots=True)
class SensitivityResult:
    """Sobol indices per metric and group.

    Parameters
    ----------
    groups : tuple of str
        The groups of variables.
    first_order, total : dict
        Metric → (G,) S1 and ST [–] (nan for a metric without variance).
    first_order_conf, total_conf : dict
        Metric → (G,) half-widths of their bootstrap intervals [–].
    base_samples : int
        N of the Saltelli design; ``evaluations`` = N·(G + 2).
    evaluations : int
        States evaluated.
    unbuilt : int
        States that could not be built (their metrics took the mean).
    """

    groups: tuple[str, ...]
    first_order: dict[str, tuple[float, ...]]
    total: dict[str, tuple[float, ...]]
    first_order_conf: dict[str, tuple[float, ...]]
    total_conf: dict[str, tuple[float, ...]]
    base_samples: int
    evaluations: int
    unbuilt: int

    def ranking(self, metric: str) -> list[tuple[str, float]]:
        """Groups by decreasing total index of ``metric``.

        Parameters
        ----------
        metric : str
            A name of :data:`SENSITIVITY_METRICS`.

        Returns
        -------
        list of (str, float)
            (group, total Sobol index S_T [-]), the largest first; groups without a finite
            index are left out.
        """
        st = self.total.get(metric, ())
        pairs = [(g, v) for g, v in zip(self.groups, st, strict=True) if math.isfinite(v)]
        return sorted(pairs, key=lambda p: -p[1])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (nan as None)."""
        def clean(values: tuple[float, ...]) -> list[float | None]:
            return [v if math.isfinite(v) else None for v in values]

        return {"groups": list(self.groups), "base_samples": self.base_samples,
                "evaluations": self.evaluations, "unbuilt": self.unbuilt,
                "metrics": {m: {"unit": SENSITIVITY_METRICS.get(m, "-"),
                                "first_order": clean(self.first_order[m]),
                                "first_order_conf": clean(self.first_order_conf[m]),
                                "total": clean(self.total[m]),
                                "total_conf": clean(self.total_conf[m])}
                            for m in self.first_order}}


def sensitivity(nominal: Analysis, model: UncertaintyModel, *,
                evaluator: StateEvaluator | None = None,
                checks: Sequence[str] = ()) -> SensitivityResult | None:
    """Sobol indices of the drive's metrics over the groups of ``model``.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    model : UncertaintyModel
        Its model (``sensitivity_samples`` and ``seed`` from its settings).
    evaluator : StateEvaluator | None
        Evaluates the states (default :func:`chaindrive.robust.sampling.serial_states`).
    checks : sequence of str
        Check keys whose margin fraction is apportioned too (as ``margin[<key>]``).

    Returns
    -------
    SensitivityResult | None
        None for a model with fewer than two groups (nothing to apportion).

    References
    ----------
    [Saltelli2010], [Herman2017]
    """
    groups = model.groups
    if len(groups) < 2:
        return None
    s = model.settings
    problem = {"num_vars": model.dimension, "names": [v.name for v in model.variables],
               "bounds": [[0.0, 1.0]] * model.dimension,
               "groups": [v.group for v in model.variables]}
    n = 1 << max(2, math.ceil(math.log2(s.sensitivity_samples)))
    u = sobol_sample.sample(problem, n, calc_second_order=False, seed=s.seed)
    outcomes = (evaluator or serial_states)(nominal, model, model.values(u), True)
    unbuilt = sum(o.error is not None for o in outcomes)
    first: dict[str, tuple[float, ...]] = {}
    total: dict[str, tuple[float, ...]] = {}
    first_conf: dict[str, tuple[float, ...]] = {}
    total_conf: dict[str, tuple[float, ...]] = {}
    nan = (math.nan,) * len(groups)
    outputs = {m: np.array([o.metrics.get(m, math.nan) for o in outcomes])
               for m in SENSITIVITY_METRICS}
    outputs.update({f"margin[{k}]": np.array([math.nan if o.margin.get(k) is None
                                              else float(o.margin[k] or 0.0)
                                              for o in outcomes]) for k in checks})
    for metric, y in outputs.items():
        finite = np.isfinite(y)
        if finite.sum() < 2 or float(np.var(y[finite])) <= 1e-24 * max(1.0, float(
                np.mean(y[finite]) ** 2)):
            first[metric] = total[metric] = first_conf[metric] = total_conf[metric] = nan
            continue
        y = np.where(finite, y, float(np.mean(y[finite])))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # SALib's bootstrap on few points
            r = sobol_analyze.analyze(problem, y, calc_second_order=False, seed=s.seed)
        first[metric] = tuple(float(v) for v in r["S1"])
        total[metric] = tuple(float(v) for v in r["ST"])
        first_conf[metric] = tuple(float(v) for v in r["S1_conf"])
        total_conf[metric] = tuple(float(v) for v in r["ST_conf"])
    return SensitivityResult(tuple(groups), first, total, first_conf, total_conf, n,
                             len(outcomes), unbuilt)
