"""Which tolerance matters: Sobol global sensitivity indices of the drive's metrics over the
groups of its uncertainty model, on a sample grown until the indices can be ranked.

The Saltelli design of N·(G + 2) points (rows A, AB_1 … AB_G, B per base point; first-order
and total indices, no second order) [Saltelli2010] is drawn by SALib [Herman2017] in the unit
cube of the d variables with the groups of
:class:`~chaindrive.robust.uncertainty.UncertaintyModel` (eccentricity, shaft positions,
inertias, … each one group), mapped through the variables' inverse CDFs and evaluated
through the full path (:class:`~chaindrive.robust.analysis.PerturbedAnalysis`). For every
metric (resonance margin, K_D, k₂, k₂ with the eccentricity loads, f₁, and the margin of the
checks asked for) S1 (the share of the variance a group explains alone) and S_T (with all its
interactions) are estimated by Janon et al.'s estimator of a closed index on the design's
pick-freeze pairs [Janon2014] (:func:`janon_closed_index`: S1_j from f(B), f(AB_j), S_T,j =
1 − S_{~j} from f(A), f(AB_j)). These are the variance-based indices SALib's estimators
(Saltelli 2010's S1, Jansen's S_T [Jansen1999]) estimate too; Janon's normalises each pair by
its own variance, so when a few states hold most of a metric's variance (a resonance crossed
by a few states) they enter numerator and denominator alike. On the seed three-sprocket
drive, whose K_D has 87 % of its variance in 1 % of the states, the spread of nine
independently scrambled estimates of K_D's leading S_T at N = 256 is ±0.16 against Jansen's
±1.1 (docs/robust.md).

**Intervals from independent replicates.** The design is drawn R = :data:`REPLICATES` times,
each with its own scrambling of the Sobol sequence (independent seeds spawned from the
model's seed): randomised quasi-Monte Carlo replicates [Owen1997], [Owen2013, §17],
[LEcuyerLemieux2002]. An index is Janon's estimate on the pairs of all replicates pooled; its
half-width is the Student-t one across the replicates, with the jackknife over them for the
standard error of this ratio of means [Efron1982], widened to the bootstrap half-width of the
pooled base points where that is wider (:func:`replicate_indices`). The independent
replicates see what the scrambling draws — whether a few resonant states are in the sample —
which a bootstrap of one sample cannot: on the seed drive at N = 512 one scrambling's
bootstrap said ±0.06–0.09 for K_D's leading S_T while eight scramblings spread by ±0.128
(docs/robust.md). The pooled estimate rather than the mean of the replicates' own
estimates: when a few states hold the variance, most small replicates hold none of them and
the mean of their ratios is biased — on an additive output with a spike on 0.5 % of one
group's range, 8 replicates of N = 64, the Student-t intervals about the replicates' mean
held the closed forms in 18 of 80 cases, those about the pooled estimate in 70 (docs).

**Adaptive sample.** Each replicate's base points are a scrambled Sobol sequence, so its
design of 2N begins with its design of N: N (per replicate) is doubled from
``sensitivity_samples``, every state is evaluated once, until the leading total index of every
metric (the group with the largest S_T) has an interval no wider than ± ``target`` (0.1), or
the next doubling would exceed the budget of evaluations; the result says which
(``converged``, ``budget_hit``) and keeps the widths at every N. N grows rather than R: the
t quantile stays that of R − 1 degrees of freedom, the ratio estimator's bias (of order 1/N)
falls only with N, and a scrambled net of more points integrates a smooth output better than
more nets of fewer points would [Owen2013, §17] (on the seed drive one scrambling's estimates
of f₁'s leading S_T spread by σ = 0.145 at N = 128, 0.021 at N = 256). The stopping test
applies from :data:`MIN_STOP_BASE` base points over all replicates.

**Reading the indices.** An index is a share of the variance, in [0, 1]; the estimators can
leave that range on a finite sample. A value outside by no more than its interval half-width
is reported clipped to [0, 1]; one outside by more is clipped too and flagged (``outside``),
since the estimate contradicts its own interval. Groups are ranked by S_T; a group's rank is
1 + the number of groups whose interval lies entirely above its own, so groups whose
intervals cannot be told apart share a rank (tied).

A state that cannot be built takes the mean of the others (said in the result).

References
----------
[Saltelli2010], [Janon2014], [Jansen1999], [Herman2017], [Owen1997], [Owen2013],
[LEcuyerLemieux2002], [Efron1982]
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from SALib.sample import sobol as sobol_sample
from scipy.stats import norm, t

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.robust.sampling import (
    StateEvaluator,
    StepProgress,
    full_path_held,
    serial_states,
)
from chaindrive.robust.uncertainty import UncertaintyModel

__all__ = ["BOOTSTRAP_RESAMPLES", "ESTIMATOR", "FEW_STATES_SHARE", "INTERVAL", "MIN_STOP_BASE",
           "RANK_TOLERANCE", "REPLICATES", "SENSITIVITY_BUDGET", "SENSITIVITY_METRICS", "TARGET_HALF_WIDTH",
           "GroupIndex", "SensitivityResult", "Step", "grouped_indices", "janon_closed_index",
           "pick_freeze_indices", "ranks", "replicate_indices", "replicate_seeds", "sensitivity",
           "tail_variance_share"]

#: Share of a metric's variance held by its farthest 1 % of states above which the variance
#: is said to sit in a few states [–]: more than twice a normal output's 0.085
#: (:func:`tail_variance_share`) — a choice, not a published figure.
FEW_STATES_SHARE = 0.2
#: Metrics whose variance is apportioned, with their units.
SENSITIVITY_METRICS: dict[str, str] = {"resonance_margin_percent": "%",
                                       "coefficient_of_dynamics": "-", "k2": "-",
                                       "k2_with_errors": "-", "f1_hz": "Hz"}
#: Half-width of the interval of every metric's leading S_T the sample grows to [–] (the
#: default of ``[uncertainty] sensitivity_target``).
TARGET_HALF_WIDTH = 0.1
#: Evaluations the adaptive sample may spend [–] (the default of ``[uncertainty]
#: sensitivity_budget``): R = 8 replicates of N = 256 base points on six groups, what the
#: seed three-sprocket drive needs (docs/robust.md).
SENSITIVITY_BUDGET = 16384
#: Base points over all replicates from which the stopping test is applied [–] (module
#: docstring).
MIN_STOP_BASE = 256
#: Independently scrambled Saltelli designs whose spread gives the intervals [–] (as the
#: probabilities' default ``replicates``; module docstring).
REPLICATES = 8
#: How the indices are estimated (the JSON's ``estimator``).
ESTIMATOR = ("Janon et al. 2014 on the Saltelli design's pick-freeze pairs (S1; S_T = 1 − "
             "closed index of the other groups), pooled over independently scrambled "
             "replicates")
#: How their intervals are found (the JSON's ``interval``).
INTERVAL = ("Student-t across independently scrambled replicates (jackknife standard "
            "error), widened to the bootstrap of the pooled base points where wider")

#: Evaluates (S, d) variable rows [SI] to metric name → (S,) values (nan: not available).
RowEvaluator = Callable[[NDArray[np.float64]], Mapping[str, NDArray[np.float64]]]


@dataclass(frozen=True, slots=True)
class GroupIndex:
    """The Sobol indices of one group for one metric, as reported.

    Parameters
    ----------
    group : str
        The group.
    first, first_conf : float
        S1 clipped to [0, 1] and its interval half-width [–].
    total, total_conf : float
        S_T clipped to [0, 1] and its interval half-width [–].
    first_raw, total_raw : float
        The estimators' values before clipping [–].
    first_outside, total_outside : bool
        The raw value leaves [0, 1] by more than its half-width.
    rank : int
        1 + the groups whose S_T interval lies entirely above this one's (equal ranks: tied).
    """

    group: str
    first: float
    first_conf: float
    total: float
    total_conf: float
    first_raw: float
    total_raw: float
    first_outside: bool
    total_outside: bool
    rank: int


@dataclass(frozen=True, slots=True)
class Step:
    """One size of the adaptive sample.

    Parameters
    ----------
    base_samples, evaluations : int
        N over all replicates and N·(G + 2) [–].
    widest_half_width : float
        The widest interval half-width of a leading S_T over the metrics [–].
    metric : str
        The metric it belongs to.
    per_replicate : int
        N of each replicate [–] (0: one design).
    """

    base_samples: int
    evaluations: int
    widest_half_width: float
    metric: str
    per_replicate: int = 0


@dataclass(frozen=True, slots=True)
class SensitivityResult:
    """Sobol indices per metric and group, with the sample that gave them.

    Parameters
    ----------
    groups : tuple of str
        The groups of variables.
    first_order, total : dict
        Metric → (G,) S1 and ST as estimated on the replicates pooled [–] (nan for a
        metric without variance).
    first_order_conf, total_conf : dict
        Metric → (G,) half-widths of their intervals [–] (the wider of the two below).
    base_samples : int
        N of the Saltelli designs over all replicates; ``evaluations`` = N·(G + 2).
    evaluations : int
        States evaluated.
    unbuilt : int
        States that could not be built (their metrics took the mean).
    target : float
        Half-width aimed at for every metric's leading S_T [–].
    budget : int
        Evaluations allowed [–].
    converged : bool
        Every leading S_T's half-width ≤ ``target``.
    budget_hit : bool
        The sample stopped because the next doubling would pass ``budget``.
    history : tuple of Step
        The widest leading half-width at each N.
    confidence : float
        Level of the intervals [–].
    held_at_nominal : tuple of str
        What the states hold at nominal (the full path's).
    tail_share : dict
        Metric → share of its variance held by the 1 % of the states farthest from its mean
        [–] (:func:`tail_variance_share`): below 0.1 for a smooth metric; a large share
        (a resonance or a threshold crossed by a few states) is why its indices converge
        slowly.
    replicates : int
        R, the independently scrambled designs [–].
    first_order_conf_replicates, total_conf_replicates : dict
        Metric → (G,) Student-t half-widths across the replicates (jackknife) [–] (nan:
        R < 2).
    first_order_conf_bootstrap, total_conf_bootstrap : dict
        Metric → (G,) bootstrap half-widths of the pooled base points [–].
    """

    groups: tuple[str, ...]
    first_order: dict[str, tuple[float, ...]]
    total: dict[str, tuple[float, ...]]
    first_order_conf: dict[str, tuple[float, ...]]
    total_conf: dict[str, tuple[float, ...]]
    base_samples: int
    evaluations: int
    unbuilt: int
    target: float = TARGET_HALF_WIDTH
    budget: int = SENSITIVITY_BUDGET
    converged: bool = False
    budget_hit: bool = False
    history: tuple[Step, ...] = ()
    confidence: float = 0.95
    held_at_nominal: tuple[str, ...] = field(default=())
    tail_share: dict[str, float] = field(default_factory=dict)
    replicates: int = 1
    first_order_conf_replicates: dict[str, tuple[float, ...]] = field(default_factory=dict)
    total_conf_replicates: dict[str, tuple[float, ...]] = field(default_factory=dict)
    first_order_conf_bootstrap: dict[str, tuple[float, ...]] = field(default_factory=dict)
    total_conf_bootstrap: dict[str, tuple[float, ...]] = field(default_factory=dict)

    @shared_parameters
    def indices(self, metric: str) -> list[GroupIndex]:
        """The indices of ``metric`` as reported, in the order of :attr:`groups`.

        %(params_metric_returns)s
        list of GroupIndex
            Clipped values, intervals, flags and ranks (empty for a metric without
            variance).
        """
        s1, st = self.first_order[metric], self.total[metric]
        c1, ct = self.first_order_conf[metric], self.total_conf[metric]
        if not all(math.isfinite(v) for v in st):
            return []
        rank = ranks(st, ct)
        return [GroupIndex(g, _clip(s1[k]), c1[k], _clip(st[k]), ct[k], s1[k], st[k],
                           _outside(s1[k], c1[k]), _outside(st[k], ct[k]), rank[k])
                for k, g in enumerate(self.groups)]

    @shared_parameters
    def ranking(self, metric: str) -> list[tuple[str, float]]:
        """Groups by decreasing total index of ``metric``.

        %(params_metric_returns)s
        list of (str, float)
            (group, total Sobol index S_T [-] clipped to [0, 1]), the largest first; groups
            without a finite index are left out.
        """
        return [(i.group, i.total) for i in sorted(self.indices(metric),
                                                   key=lambda i: -i.total_raw)]

    @shared_parameters
    def leading_half_width(self, metric: str) -> float:
        """The interval half-width of the leading S_T of ``metric`` [–] (nan: no variance).

        %(params_metric_returns)s
        float
        """
        return _leading_half_width(self.total[metric], self.total_conf[metric])

    @shared_parameters
    def tied(self, metric: str) -> list[list[str]]:
        """Sets of two or more groups whose S_T cannot be told apart (one rank).

        %(params_metric_returns)s
        list of list of str
            Each set's groups, by decreasing S_T; the sets by rank.
        """
        by_rank: dict[int, list[GroupIndex]] = {}
        for i in self.indices(metric):
            by_rank.setdefault(i.rank, []).append(i)
        return [[i.group for i in sorted(v, key=lambda i: -i.total_raw)]
                for _, v in sorted(by_rank.items()) if len(v) > 1]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (nan as None); ``estimator`` names the estimator
        (:data:`ESTIMATOR`) and ``interval`` how the half-widths ``*_conf`` are found
        (:data:`INTERVAL`; their two parts under ``*_conf_replicates`` and
        ``*_conf_bootstrap``), ``first_order``/``total`` are the clipped values, ``*_raw`` the
        estimators', ``*_outside`` the flags, ``rank`` and ``tied`` the ranking by S_T."""
        def clean(values: Sequence[float]) -> list[float | None]:
            return [v if math.isfinite(v) else None for v in values]

        metrics: dict[str, Any] = {}
        for m in self.first_order:
            idx = self.indices(m)
            half = self.leading_half_width(m)
            tail = self.tail_share.get(m, math.nan)
            entry: dict[str, Any] = {"unit": SENSITIVITY_METRICS.get(m, "-"),
                                     "leading_half_width": half if math.isfinite(half) else None,
                                     "variance_share_of_farthest_1pct": (
                                         tail if math.isfinite(tail) else None),
                                     "variance_in_few_states": bool(
                                         math.isfinite(tail) and tail > FEW_STATES_SHARE),
                                     "converged": bool(math.isfinite(half)
                                                       and half <= self.target),
                                     "first_order_conf": clean(self.first_order_conf[m]),
                                     "total_conf": clean(self.total_conf[m])}
            for key in ("first_order_conf_replicates", "total_conf_replicates",
                        "first_order_conf_bootstrap", "total_conf_bootstrap"):
                part = getattr(self, key).get(m)
                entry[key] = None if part is None else clean(part)
            if idx:
                entry |= {"first_order": [i.first for i in idx],
                          "total": [i.total for i in idx],
                          "first_order_raw": [i.first_raw for i in idx],
                          "total_raw": [i.total_raw for i in idx],
                          "first_order_outside": [i.first_outside for i in idx],
                          "total_outside": [i.total_outside for i in idx],
                          "rank": [i.rank for i in idx], "tied": self.tied(m)}
            else:
                entry |= {"first_order": clean(self.first_order[m]),
                          "total": clean(self.total[m]), "rank": None, "tied": []}
            metrics[m] = entry
        return {"groups": list(self.groups), "path": "full", "estimator": ESTIMATOR,
                "interval": INTERVAL, "replicates": self.replicates,
                "base_samples_per_replicate": self.base_samples // max(1, self.replicates),
                "base_samples": self.base_samples,
                "evaluations": self.evaluations, "unbuilt": self.unbuilt,
                "confidence": self.confidence, "target_half_width": self.target,
                "budget_evaluations": self.budget, "converged": self.converged,
                "budget_hit": self.budget_hit,
                "history": [{"base_samples": h.base_samples, "evaluations": h.evaluations,
                             "widest_leading_half_width": (h.widest_half_width if math.isfinite(
                                 h.widest_half_width) else None), "metric": h.metric,
                             "base_samples_per_replicate": h.per_replicate or h.base_samples}
                            for h in self.history],
                "held_at_nominal": list(self.held_at_nominal), "metrics": metrics}


def _clip(v: float) -> float:
    return min(1.0, max(0.0, v)) if math.isfinite(v) else v


def _outside(v: float, half: float) -> bool:
    """Whether ``v`` leaves [0, 1] by more than ``half``."""
    return math.isfinite(v) and (v < -half or v > 1.0 + half)


#: Gap between two intervals below which they are taken to touch [–]: round-off of an index
#: (a group that does not act has an estimate of ±1e-16 with a half-width of 0).
RANK_TOLERANCE = 1e-9


def ranks(values: Sequence[float], half_widths: Sequence[float]) -> list[int]:
    """Rank of each value: 1 + the number of values whose interval [v − h, v + h] lies
    entirely above its own by more than :data:`RANK_TOLERANCE` (values that cannot be told
    apart share a rank).

    Parameters
    ----------
    values, half_widths : sequence of float
        Estimates and their interval half-widths [–].

    Returns
    -------
    list of int
        Ranks ≥ 1, in the order given.
    """
    lo = [v - h for v, h in zip(values, half_widths, strict=True)]
    hi = [v + h for v, h in zip(values, half_widths, strict=True)]
    return [1 + sum(lo[j] > hi[k] + RANK_TOLERANCE for j in range(len(values)))
            for k in range(len(values))]


def _saltelli_problem(model: UncertaintyModel) -> dict[str, Any]:
    return {"num_vars": model.dimension, "names": [v.name for v in model.variables],
            "bounds": [[0.0, 1.0]] * model.dimension,
            "groups": [v.group for v in model.variables]}


def _leading_half_width(total: tuple[float, ...], conf: tuple[float, ...]) -> float:
    if not all(math.isfinite(v) for v in total):
        return math.nan
    return conf[int(np.argmax(total))]


#: Bootstrap resamples of the base rows behind every interval [–] (SALib's default
#: [Herman2017]).
BOOTSTRAP_RESAMPLES = 100


def janon_closed_index(y: NDArray[np.float64], y_shared: NDArray[np.float64]
                       ) -> NDArray[np.float64]:
    """Janon et al.'s estimator of the closed Sobol index of the variables two outputs share.

    With y and y' the outputs at N pairs of points that share the variables u and draw the
    others independently (pick-freeze), and m = mean((y + y')/2),

    ``S_u = (mean(y·y') − m²) / (mean((y² + y'²)/2) − m²)``,

    the numerator estimating Cov(Y, Y') = Var(E[Y | X_u]) and the denominator Var(Y) from the
    same pairs. It is asymptotically normal and the most efficient of the estimators built on
    these pairs [Janon2014]. On the rows of the Saltelli design [Saltelli2010] the first-order
    index of group j is S_j from (f(B), f(AB_j)) (they share group j), the total index
    ``1 − S_{~j}`` from (f(A), f(AB_j)) (they share every other group), i.e.
    ``mean((f(A) − f(AB_j))²)/2`` over the pair's own variance: Jansen's numerator [Jansen1999]
    over a denominator that holds the same states. When a few states hold most of the variance
    (a resonance), those states then enter numerator and denominator alike.

    Parameters
    ----------
    y, y_shared : ndarray
        (..., N) outputs of the pairs [any unit, the same for both]; the last axis is the
        sample.

    Returns
    -------
    ndarray
        (...) the estimate [–] (nan where the pairs have no variance).

    References
    ----------
    [Janon2014], [Saltelli2010]
    """
    m = np.mean((y + y_shared) / 2.0, axis=-1)
    den = np.mean((y * y + y_shared * y_shared) / 2.0, axis=-1) - m * m
    num = np.mean(y * y_shared, axis=-1) - m * m
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0.0, num / np.where(den > 0.0, den, 1.0), np.nan)


@shared_parameters
def pick_freeze_indices(y: NDArray[np.float64], groups: int, confidence: float, seed: int,
                        resamples: int = BOOTSTRAP_RESAMPLES
                        ) -> tuple[tuple[float, ...], ...]:
    """S1 and S_T of every group with bootstrap half-widths, from the outputs of a Saltelli
    design without second order (rows A, AB_1 … AB_G, B per base point, SALib's order).

    The estimates are Janon et al.'s (:func:`janon_closed_index`): S1_j from (f(B), f(AB_j)),
    S_T,j = 1 − S_{~j} from (f(A), f(AB_j)) [Janon2014]. The half-width is z·σ of the
    estimates over ``resamples`` bootstrap resamples of the N base points (each resample
    keeps a point's A, AB and B together), z the normal quantile of ``confidence``
    [Herman2017].

    Parameters
    ----------
    y : ndarray
        (N·(G + 2),) outputs in the design's order [any unit].
    %(sobol_bootstrap_returns)s
        (S1, S_T, S1 half-width, S_T half-width), each a (G,) tuple [–].

    References
    ----------
    [Janon2014], [Saltelli2010], [Herman2017]
    """
    step = groups + 2
    n = y.size // step
    a, b = y[0:n * step:step], y[step - 1:n * step:step]
    ab = np.stack([y[j + 1:n * step:step] for j in range(groups)])
    r = np.random.default_rng(seed).integers(n, size=(resamples, n))
    z = float(norm.ppf(0.5 + confidence / 2.0))
    first = janon_closed_index(b, ab)
    total = 1.0 - janon_closed_index(a, ab)
    first_boot = janon_closed_index(b[r], ab[:, r])
    total_boot = 1.0 - janon_closed_index(a[r], ab[:, r])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a resample without variance: nan
        first_half = z * np.nanstd(first_boot, axis=-1, ddof=1)
        total_half = z * np.nanstd(total_boot, axis=-1, ddof=1)
    return tuple(tuple(float(v) for v in x) for x in (first, total, first_half, total_half))


def replicate_seeds(seed: int, replicates: int) -> list[int]:
    """Scrambling seeds of ``replicates`` independent Saltelli designs, spawned from ``seed``
    (NumPy's ``SeedSequence``: independent streams, the same for the same seed).

    Parameters
    ----------
    seed : int
        The model's seed.
    replicates : int
        R [–].

    Returns
    -------
    list of int
        R seeds.
    """
    return [int(c.generate_state(1)[0]) for c in np.random.SeedSequence(seed).spawn(replicates)]


@shared_parameters
def replicate_indices(ys: Sequence[NDArray[np.float64]], groups: int, confidence: float,
                      seed: int, resamples: int = BOOTSTRAP_RESAMPLES
                      ) -> tuple[tuple[float, ...], ...]:
    """S1 and S_T of every group with their half-widths, from R independently scrambled
    Saltelli designs.

    The index Ŝ is Janon et al.'s estimate on the pairs of all R designs pooled
    (:func:`pick_freeze_indices`), a smooth function of the R replicates' means of the pairs'
    moments. Its half-width is the Student-t one of independent randomised quasi-Monte Carlo
    replicates [Owen2013, §17], [LEcuyerLemieux2002] with the jackknife over the replicates
    for the standard error of that function of means [Efron1982]: with Ŝ_(−r) the estimate
    without replicate r and s their standard deviation,

    ``h = max(t_{R−1, (1+c)/2} · (R − 1) s/√R, h_boot)``,

    ``(R − 1)s/√R`` being the jackknife standard error (for a plain mean it is the familiar
    s_r/√R of the replicates' own estimates), widened to the bootstrap half-width of the
    pooled base points (z·σ over ``resamples`` resamples keeping a point's rows together,
    [Herman2017]) where that is wider — a guard for an interval whose R replicates agree by
    chance. The pooled estimate, not the mean of the R replicates' ratios: when a few
    states hold the variance most small replicates hold none of them, and the mean of
    their ratios is biased (module docstring, docs/robust.md). A jackknife estimate without
    variance is left out of s; with fewer than two the half-width is the bootstrap's.

    Parameters
    ----------
    ys : sequence of ndarray
        Per replicate, (N·(G + 2),) outputs in the design's order [any unit, the same for
        all].
    %(sobol_bootstrap_returns)s
        (S1, S_T, S1 half-width, S_T half-width, S1 and S_T Student-t parts, S1 and S_T
        bootstrap parts), each a (G,) tuple [–].

    References
    ----------
    [Janon2014], [Owen2013], [LEcuyerLemieux2002], [Efron1982], [Herman2017]
    """
    pooled = pick_freeze_indices(np.concatenate(list(ys)), groups, confidence, seed,
                                 resamples=resamples)
    left_out = [pick_freeze_indices(np.concatenate([y for k, y in enumerate(ys) if k != r]),
                                    groups, confidence, seed, resamples=0)
                for r in range(len(ys))] if len(ys) > 1 else []
    out: list[tuple[float, ...]] = []
    for kind in (0, 1):
        est = np.array([p[kind] for p in left_out]).reshape(len(left_out), groups)
        finite = np.isfinite(est)
        k = finite.sum(axis=0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # fewer than two: nan
            sd = np.nanstd(np.where(finite, est, np.nan), axis=0, ddof=1)
            q = t.ppf(0.5 + confidence / 2.0, k - 1)
            t_half = np.where(k >= 2, q * sd * (k - 1) / np.sqrt(k), np.nan)
        boot = np.asarray(pooled[2 + kind])
        half = np.where(np.isfinite(t_half), np.fmax(t_half, boot), boot)
        out += [tuple(float(v) for v in x) for x in (pooled[kind], half, t_half, boot)]
    s1, s1_half, s1_t, s1_boot, st, st_half, st_t, st_boot = out
    return s1, st, s1_half, st_half, s1_t, st_t, s1_boot, st_boot


def _analyse(problem: dict[str, Any], outputs: Mapping[str, Sequence[NDArray[np.float64]]],
             confidence: float, seed: int
             ) -> dict[str, tuple[tuple[float, ...], ...]]:
    """Metric → (S1, ST, S1 half-width, ST half-width, their Student-t and bootstrap parts)
    of the replicates' outputs on their Saltelli designs (:func:`replicate_indices`; a state
    without a value takes the mean of the others, over all replicates)."""
    g = len(dict.fromkeys(problem["groups"]))
    nan = (math.nan,) * g
    out: dict[str, tuple[tuple[float, ...], ...]] = {}
    for metric, ys in outputs.items():
        y = np.concatenate([np.asarray(v, float) for v in ys])
        finite = np.isfinite(y)
        if finite.sum() < 2 or float(np.var(y[finite])) <= 1e-24 * max(1.0, float(
                np.mean(y[finite]) ** 2)):
            out[metric] = (nan,) * 8
            continue
        mean, std = float(np.mean(y[finite])), float(np.std(y[finite]))
        out[metric] = replicate_indices(
            [(np.where(np.isfinite(v), v, mean) - mean) / std for v in ys], g, confidence,
            seed + 1)
    return out


def grouped_indices(model: UncertaintyModel, evaluate: RowEvaluator, *, start: int,
                    budget: int = SENSITIVITY_BUDGET, target: float = TARGET_HALF_WIDTH,
                    replicates: int = REPLICATES,
                    progress: StepProgress | None = None) -> SensitivityResult:
    """Sobol indices over the groups of ``model`` of the outputs of ``evaluate``, on R
    independently scrambled Saltelli designs of N base points each, N doubled from ``start``
    until every output's leading S_T has a half-width ≤ ``target`` or the budget is spent
    (module docstring).

    Parameters
    ----------
    model : UncertaintyModel
        The variables (their inverse CDFs map the design) and their groups (≥ 2); its
        settings give the seed and the confidence.
    evaluate : callable
        (S, d) variable rows [SI] → output name → (S,) values (called once per N with the
        new rows of every replicate).
    start : int
        First N per replicate (rounded up to a power of two ≥ 4) [–].
    budget : int
        Evaluations allowed; the first N is evaluated whatever it costs [–].
    target : float
        Half-width aimed at [–].
    replicates : int
        R [–] (1: one design, bootstrap intervals only).
    progress : callable | None
        ``progress(done, total)`` in evaluations, the total growing with N.

    Returns
    -------
    SensitivityResult
        With ``unbuilt`` = 0 (see :func:`sensitivity`).

    References
    ----------
    [Saltelli2010], [Janon2014], [Owen2013], [Herman2017]
    """
    s = model.settings
    problem = _saltelli_problem(model)
    per_base = len(model.groups) + 2
    seeds = replicate_seeds(s.seed, replicates)
    n = 1 << max(2, math.ceil(math.log2(max(1, start))))
    outputs: dict[str, list[NDArray[np.float64]]] = {}
    done = 0
    history: list[Step] = []
    while True:
        designs = [sobol_sample.sample(problem, n, calc_second_order=False, seed=sd)
                   for sd in seeds]
        have = len(next(iter(outputs.values()))[0]) if outputs else 0
        total = sum(len(u) for u in designs)
        if progress is not None:
            progress(done, total)
        fresh = evaluate(model.values(np.concatenate([u[have:] for u in designs])))
        step = len(designs[0]) - have
        outputs = {k: [np.concatenate([outputs[k][r] if k in outputs else np.empty(0),
                                       np.asarray(v, float)[r * step:(r + 1) * step]])
                       for r in range(replicates)] for k, v in fresh.items()}
        done = total
        if progress is not None:
            progress(done, done)
        result = _analyse(problem, outputs, s.confidence, s.seed)
        widths = {m: _leading_half_width(r[1], r[3]) for m, r in result.items()}
        finite = {m: w for m, w in widths.items() if math.isfinite(w)}
        worst = max(finite, key=lambda m: finite[m]) if finite else ""
        history.append(Step(n * replicates, done, finite.get(worst, math.nan), worst, n))
        converged = all(w <= target for w in finite.values())
        stop_test = n * replicates >= MIN_STOP_BASE
        over = 2 * n * replicates * per_base > budget
        if (converged and stop_test) or over:
            break
        n *= 2
    pick = {name: {m: r[k] for m, r in result.items()} for k, name in enumerate(
        ("first_order", "total", "first_order_conf", "total_conf", "first_order_conf_replicates",
         "total_conf_replicates", "first_order_conf_bootstrap", "total_conf_bootstrap"))}
    return SensitivityResult(
        model.groups, pick["first_order"], pick["total"], pick["first_order_conf"],
        pick["total_conf"], n * replicates, done, 0, target, budget, converged,
        over and not converged, tuple(history), s.confidence,
        tail_share={m: tail_variance_share(np.concatenate(v)) for m, v in outputs.items()},
        replicates=replicates,
        first_order_conf_replicates=pick["first_order_conf_replicates"],
        total_conf_replicates=pick["total_conf_replicates"],
        first_order_conf_bootstrap=pick["first_order_conf_bootstrap"],
        total_conf_bootstrap=pick["total_conf_bootstrap"])


def tail_variance_share(values: NDArray[np.float64], fraction: float = 0.01) -> float:
    """Share of the variance of ``values`` held by the ``fraction`` of them farthest from
    their mean.

    With ``d = (y - ȳ)²`` sorted in decreasing order, the share is
    ``Σ_{k < ⌈fraction·n⌉} d_k / Σ d_k``. For a smooth output it stays small (at 1 %: 0.030
    for a uniform output, 0.085 for a normal one, ``2(zφ(z) + 1 − Φ(z))`` with
    z = Φ⁻¹(0.995)); when a few states hold most of
    the variance (a resonance crossed by a few of them, a threshold), the variance-based
    indices of that output rest on those states, which the sample holds few of: the indices
    of the groups that move it converge slowly — why an S_T can stay wide however the sample
    grows [Saltelli2010], [Janon2014].

    Parameters
    ----------
    values : ndarray
        The output over the states [its unit] (non-finite values are left out).
    fraction : float
        The share of the states counted [–], 0 < fraction ≤ 1.

    Returns
    -------
    float
        The share [–] (nan: fewer than two finite values, or no variance).

    References
    ----------
    [Saltelli2010], [Janon2014]
    """
    y = np.asarray(values, float)
    y = y[np.isfinite(y)]
    if y.size < 2:
        return math.nan
    d = np.sort((y - y.mean()) ** 2)[::-1]
    total = float(d.sum())
    if total <= 0.0:
        return math.nan
    return float(d[:math.ceil(fraction * y.size)].sum() / total)


def sensitivity(nominal: Analysis, model: UncertaintyModel, *,
                evaluator: StateEvaluator | None = None,
                checks: Sequence[str] = (), budget: int | None = None,
                target: float | None = None,
                progress: StepProgress | None = None) -> SensitivityResult | None:
    """Sobol indices of the drive's metrics over the groups of ``model`` (module docstring).

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    model : UncertaintyModel
        Its model (``sensitivity_samples``: the first N; ``seed`` from its settings).
    evaluator : StateEvaluator | None
        Evaluates the states (default :func:`chaindrive.robust.sampling.serial_states`).
    checks : sequence of str
        Check keys whose margin fraction is apportioned too (as ``margin[<key>]``).
    budget : int | None
        Evaluations the adaptive sample may spend [–] (None: ``sensitivity_budget``).
    target : float | None
        Half-width aimed at for every metric's leading S_T [–] (None:
        ``sensitivity_target``).
    progress : callable | None
        ``progress(done, total)`` in states.

    Returns
    -------
    SensitivityResult | None
        None for a model with fewer than two groups (nothing to apportion).

    References
    ----------
    [Saltelli2010], [Janon2014], [Herman2017]
    """
    if len(model.groups) < 2:
        return None
    counts = {"done": 0, "unbuilt": 0}

    def evaluate(x: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
        base = counts["done"]

        def step(k: int, total: int) -> None:
            if progress is not None:
                progress(base + k, base + total)

        outcomes = (evaluator(nominal, model, x, True) if evaluator is not None
                    else serial_states(nominal, model, x, True, progress=step))
        counts["done"] += len(x)
        counts["unbuilt"] += sum(o.error is not None for o in outcomes)
        out = {m: np.array([o.metrics.get(m, math.nan) for o in outcomes])
               for m in SENSITIVITY_METRICS}
        out |= {f"margin[{k}]": np.array([math.nan if o.margin.get(k) is None
                                          else float(o.margin[k] or 0.0) for o in outcomes])
                for k in checks}
        return out

    r = grouped_indices(model, evaluate, start=model.settings.sensitivity_samples,
                        budget=model.settings.sensitivity_budget if budget is None else budget,
                        target=model.settings.sensitivity_target if target is None else target,
                        progress=progress)
    return replace(r, unbuilt=counts["unbuilt"], held_at_nominal=full_path_held(model))
