"""Probabilities of failure over the uncertainty model: randomised quasi-Monte Carlo through the
analysis, and a batched modal path.

* **Points.** R independent Owen-scrambled Sobol sequences (``scipy.stats.qmc.Sobol``) of 2^m
  points each in the d variables of the :class:`~chaindrive.robust.uncertainty.UncertaintyModel`
  [Owen1997]; each point u ∈ (0, 1)^d becomes a state by the variables' inverse CDFs.
* **Full path.** Every state is a :class:`~chaindrive.robust.analysis.PerturbedAnalysis`: its
  checks (layout, chain, resonance, k₂, k₂min) and :meth:`~PerturbedAnalysis.state_checks`
  pass or fail, and its K_D, k₂, f₁ and resonance margin are kept.
* **Modal path** (where it suffices: the resonance margin and the natural frequencies). The
  geometric variables are held at nominal tolerances and at the wear states the setting
  names (new, worn to the allowable elongation, or K midpoints of the life); at each the
  analysis builds its whole-drive model and working frequencies once, and the modal
  variables (inertias, chain stiffness, polymer temperature) change its values for every
  sample at once: the wrap (ladder) and sag stiffnesses in closed form, the frequencies of
  the stacked eigenvalue problems (:mod:`chaindrive.robust.modal`). Over the
  life the probability is the mean over the K states (the midpoint rule in the life
  fraction, which is uniform).
* **What is held, what is averaged.** Each result lists what its states hold at nominal
  (:func:`full_path_held`, :func:`modal_path_held`: the modal path holds every geometric
  tolerance; both hold the individual link pitches and judge the catalogue checks at the
  nominal chain speed) and over what its probability is averaged (:func:`averaged_over`:
  the life, the temperature, the tolerances sampled), and counts sampled points, wear
  states and the states evaluated (points × wear states on the modal path).
* **Estimate and interval.** p̂ is the mean of the R replicate means; the interval is the
  Student-t interval of the replicates [Owen1997], widened to contain the Clopper–Pearson
  interval of the pooled count [ClopperPearson1934] (which bounds an estimate of 0 or 1). A
  model with no random variable is evaluated once: p is exactly 0 or 1.

References
----------
[Owen1997], [ClopperPearson1934], [MultimassChainDrives]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.stats import beta as beta_dist
from scipy.stats import qmc
from scipy.stats import t as t_dist

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.catalog import find_material
from chaindrive.checks import Check
from chaindrive.errors import ChainDriveError
from chaindrive.robust.analysis import PerturbedAnalysis, first_elastic_hz
from chaindrive.robust.modal import StackedState, stacked_margins, stacked_state
from chaindrive.robust.perturbation import (
    REFERENCE_TEMPERATURE_C,
    Perturbation,
    modulus_factors,
)
from chaindrive.robust.uncertainty import (
    MODAL_GROUPS,
    UncertaintyModel,
    UncertaintySettings,
)

__all__ = ["BUILD_FAILURE", "CheckProbability", "MetricSummary", "ModalBasis",
           "ReliabilityResult", "StateOutcome", "StepProgress", "averaged_over",
           "basis_reliability", "estimate_probability", "full_path_held", "modal_basis",
           "modal_path_held", "reliability", "sample_count", "sobol_points", "state_outcome"]

#: The pseudo-check of a state that cannot be built (e.g. the chain does not fit).
BUILD_FAILURE = "buildable"
#: Metrics kept per state, with their units.
METRICS: dict[str, str] = {"f1_hz": "Hz", "resonance_margin_percent": "%",
                           "coefficient_of_dynamics": "-", "k2": "-", "k2min": "-",
                           "k2_with_errors": "-",
                           "take_up_travel_mm": "mm", "sag_ratio": "-", "elongation": "-"}
#: ``progress(done, total)``: states evaluated so far and states planned (a presenter's bar).
StepProgress = Callable[[int, int], None]


def full_path_held(model: UncertaintyModel) -> tuple[str, ...]:
    """What every state of the full path holds at nominal (not sampled).

    Parameters
    ----------
    model : UncertaintyModel
        The uncertainty model.

    Returns
    -------
    tuple of str
        One line per quantity held, with its nominal value where it has one.
    """
    groups = set(model.groups)
    held = ["individual link pitches (only the chain's length is toleranced)",
            "the chain's catalogue checks: judged at the nominal chain speed and pitch"]
    if "temperature" not in groups:
        held.append(f"temperature: {REFERENCE_TEMPERATURE_C:g} °C (it enters only polymer "
                    "moduli)")
    for name, group in (("inertias", "inertias"), ("chain stiffness", "chain stiffness")):
        if group not in groups:
            held.append(f"{name}: no scatter asked for")
    return tuple(held)


def modal_path_held(model: UncertaintyModel) -> tuple[str, ...]:
    """What every state of the batched modal path holds at nominal: the geometric
    tolerances of the model (they are listed as its variables but not sampled), then what
    the full path holds too.

    Parameters
    ----------
    model : UncertaintyModel
        The whole uncertainty model (geometric and modal groups).

    Returns
    -------
    tuple of str
        One line per quantity held.
    """
    counts: dict[str, int] = {}
    for v in model.variables:
        if v.group not in MODAL_GROUPS and v.group != "wear":
            counts[v.group] = counts.get(v.group, 0) + 1
    held = [f"{group}{'' if k == 1 else f' ({k} variables)'}: at nominal (in the model, "
            "not sampled on the modal path)" for group, k in counts.items()]
    if "temperature" in model.groups:
        held.append(f"train shafts' stiffness: at {REFERENCE_TEMPERATURE_C:g} °C (the full "
                    "path softens polymer shafts)")
    return (*held, *full_path_held(model))


def averaged_over(model: UncertaintyModel, path: str) -> tuple[str, ...]:
    """Over what a probability of the path is averaged: the life, the temperature, the
    groups sampled.

    Parameters
    ----------
    model : UncertaintyModel
        The uncertainty model.
    path : str
        "full" or "modal".

    Returns
    -------
    tuple of str
        One line each for the life, the temperature and the tolerances.
    """
    s = model.settings
    eps = f"{model.allowable_elongation:.3g}"
    if s.wear == "life":
        life = (f"the life: {s.wear_states} wear states at the midpoints of the life "
                f"fraction, uniform from new to the replacement elongation {eps}"
                if path == "modal" else "the life: wear elongation uniform from new to the "
                f"replacement elongation {eps} (sampled with the tolerances)")
    elif s.wear == "new":
        life = "a new chain only (no wear)"
    else:
        life = f"a chain worn to the replacement elongation {eps} only"
    if "temperature" in model.groups:
        temperature = (f"temperature uniform over {s.temperature_min:g} … "
                       f"{s.temperature_max:g} °C")
    else:
        temperature = f"temperature fixed at {REFERENCE_TEMPERATURE_C:g} °C"
    sampled = [g for g in model.groups if g != "wear" and (path == "full"
                                                            or g in MODAL_GROUPS)]
    return (life, temperature, "tolerances sampled: " + (", ".join(sampled) or "none"))


def sobol_points(dimension: int, samples: int, replicates: int, seed: int) -> NDArray[np.float64]:
    """R independent scrambled Sobol point sets, shape (R, n, d), n = 2^⌈log₂(samples/R)⌉.

    Parameters
    ----------
    dimension : int
        d ≥ 1 [–].
    samples : int
        Total samples wanted (rounded up to R·2^m) [–].
    replicates : int
        R [–].
    seed : int
        Seed of the scramblings.

    Returns
    -------
    ndarray
        Points in (0, 1).

    References
    ----------
    [Owen1997]
    """
    m = round(math.log2(sample_count(samples, replicates) // replicates))
    return _sobol(dimension, m, replicates, seed).copy()


def sample_count(samples: int, replicates: int) -> int:
    """The states :func:`sobol_points` gives for ``samples`` asked: R·2^m, m = ⌈log₂(S/R)⌉ ≥ 1
    (a scrambled Sobol set keeps its balance in powers of two) [Owen1997] [–].

    Parameters
    ----------
    samples, replicates : int
        S asked and R [–].

    Returns
    -------
    int
    """
    return replicates << max(1, math.ceil(math.log2(max(samples, replicates) / replicates)))


@lru_cache(maxsize=32)
def _sobol(dimension: int, m: int, replicates: int, seed: int) -> NDArray[np.float64]:
    """The point sets of :func:`sobol_points`, made once per arguments (an optimiser asks
    for the same ones for every design: common random numbers)."""
    streams = np.random.SeedSequence(seed).spawn(replicates)
    return np.stack([qmc.Sobol(dimension, scramble=True, seed=np.random.default_rng(s))
                     .random_base2(m) for s in streams])


@dataclass(frozen=True, slots=True)
class StateOutcome:
    """What one state gives: every check's status and margin fraction, the metrics, or the
    reason it could not be built.

    Parameters
    ----------
    status : dict
        Check key → "pass", "fail" or "cannot be verified".
    margin : dict
        Check key → margin fraction (≥ 0 passes; None when it cannot be verified).
    metrics : dict
        Name of :data:`METRICS` → value (nan when absent).
    error : str | None
        Why the state could not be built.
    """

    status: dict[str, str]
    margin: dict[str, float | None]
    metrics: dict[str, float]
    error: str | None = None

    @shared_parameters
    def failed(self, key: str) -> bool:
        """Whether check ``key`` failed (a state that cannot be built fails every check).

        %(params_check_key_returns)s
        bool
            True when it failed or could not be verified in this state.
        """
        return self.error is not None or self.status.get(key, "pass") != "pass"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (nan as None)."""
        return {"status": self.status, "margin": self.margin,
                "metrics": {k: None if not math.isfinite(v) else v
                            for k, v in self.metrics.items()}, "error": self.error}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> StateOutcome:
        """The outcome :meth:`to_dict` wrote.

        Parameters
        ----------
        data : dict
            ``{"status", "margin", "metrics", "error"}`` as :meth:`to_dict` writes them.

        Returns
        -------
        StateOutcome
            The outcome (a metric written as None reads as nan).
        """
        return cls(dict(data["status"]), dict(data["margin"]),
                   {k: math.nan if v is None else float(v) for k, v in data["metrics"].items()},
                   data.get("error"))


def _finite(x: float | None) -> float:
    return math.nan if x is None else float(x)


def _margin(c: Check) -> float | None:
    m = c.margin_fraction
    return None if m is None else (1e6 if math.isinf(m) else float(m))


def state_outcome(state: PerturbedAnalysis) -> StateOutcome:
    """The checks and metrics of one state (a build error becomes the outcome's error).

    Parameters
    ----------
    state : PerturbedAnalysis
        The analysis of the state.

    Returns
    -------
    StateOutcome
    """
    try:
        checks = state.all_checks()
        steady = state.steady if state.with_response else None
        res = state.check("resonance_margin")
        metrics = {"f1_hz": first_elastic_hz(state),
                   "resonance_margin_percent": _finite(None if res is None else res.value),
                   "coefficient_of_dynamics": _finite(None if steady is None
                                                      else steady.coefficient_of_dynamics),
                   "k2": _finite(None if steady is None else steady.k2),
                   "k2min": _finite(None if steady is None else steady.k2_min),
                   "k2_with_errors": _finite(state.k2_with_errors() if state.with_response
                                             else None),
                   "take_up_travel_mm": state.take_up_travel() * 1e3,
                   "sag_ratio": state.sag_ratio,
                   "elongation": state.perturbation.elongation}
    except ChainDriveError as exc:
        return StateOutcome({}, {}, dict.fromkeys(METRICS, math.nan), str(exc))
    return StateOutcome({c.key: c.status for c in checks}, {c.key: _margin(c) for c in checks},
                        metrics)


# ---------------------------------------------------------------------- estimates
@dataclass(frozen=True, slots=True)
class CheckProbability:
    """The probability that a check fails, with its interval.

    Parameters
    ----------
    key, name : str
        The check's key and name (``buildable`` / ``any check`` for the pseudo-checks).
    source : str
        The check's rule.
    probability : float
        p̂ [–].
    low, high : float
        Confidence interval [–].
    failures, samples : int
        Failed states and states evaluated.
    """

    key: str
    name: str
    source: str
    probability: float
    low: float
    high: float
    failures: int
    samples: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"key": self.key, "check": self.name, "source": self.source,
                "probability": self.probability, "ci_low": self.low, "ci_high": self.high,
                "failures": self.failures, "samples": self.samples}


def estimate_probability(failed: NDArray[np.bool_], confidence: float = 0.95
                         ) -> tuple[float, float, float]:
    """p̂ and its interval from failure indicators of shape (R, n) (module docstring).

    Parameters
    ----------
    failed : ndarray of bool
        (R, n) indicators; R = 1, n = 1 for a deterministic model.
    confidence : float
        Confidence level [–].

    Returns
    -------
    tuple of float
        (p̂, low, high) [–].

    References
    ----------
    [Owen1997], [ClopperPearson1934]
    """
    f = np.atleast_2d(np.asarray(failed, dtype=float))
    r, n = f.shape
    p = float(f.mean())
    if r * n == 1:
        return p, p, p
    means = f.mean(axis=1)
    half = (_student_t(0.5 * (1.0 + confidence), r - 1) * float(means.std(ddof=1))
            / math.sqrt(r)) if r > 1 else 1.0
    cp_low, cp_high = _clopper_pearson(round(float(f.sum())), r * n, 1.0 - confidence)
    return p, max(0.0, min(p - half, cp_low)), min(1.0, max(p + half, cp_high))


@lru_cache(maxsize=64)
def _student_t(q: float, dof: int) -> float:
    """The q quantile of Student's t with ``dof`` degrees of freedom [–] (kept: a study
    asks for the same one for every design)."""
    return float(t_dist.ppf(q, dof))


@lru_cache(maxsize=4096)
def _clopper_pearson(k: int, total: int, alpha: float) -> tuple[float, float]:
    """The Clopper–Pearson interval of k failures in ``total`` trials at level 1 − α [–]
    [ClopperPearson1934] (kept: k takes few values over a study's designs)."""
    low = 0.0 if k == 0 else float(beta_dist.ppf(alpha / 2, k, total - k + 1))
    high = 1.0 if k == total else float(beta_dist.ppf(1 - alpha / 2, k + 1, total - k))
    return low, high


@dataclass(frozen=True, slots=True)
class MetricSummary:
    """Mean, standard deviation and the 5, 50 and 95 % quantiles of a metric over the states
    (nan states left out).

    Parameters
    ----------
    name : str
        The metric (a name of :data:`METRICS`).
    unit : str
        Its unit ("" for a pure number).
    mean, std : float
        Mean and standard deviation over the states [``unit``].
    p05, p50, p95 : float
        The 5, 50 and 95 % quantiles [``unit``].
    """

    name: str
    unit: str
    mean: float
    std: float
    p05: float
    p50: float
    p95: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (nan as None)."""
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in (("name", self.name), ("unit", self.unit), ("mean", self.mean),
                             ("std", self.std), ("p05", self.p05), ("p50", self.p50),
                             ("p95", self.p95))}


def _summary(name: str, values: NDArray[np.float64]) -> MetricSummary:
    v = values[np.isfinite(values)]
    if not v.size:
        return MetricSummary(name, METRICS.get(name, ""), *([math.nan] * 5))
    q = np.quantile(v, [0.05, 0.5, 0.95])
    return MetricSummary(name, METRICS.get(name, ""), float(v.mean()), float(v.std()),
                         float(q[0]), float(q[1]), float(q[2]))


@dataclass(frozen=True, slots=True, eq=False)
class ReliabilityResult:
    """Probabilities of failure of a drive over its uncertainty model.

    Parameters
    ----------
    path : str
        "full" or "modal".
    samples, replicates : int
        States evaluated per wear state and independent scramblings.
    confidence : float
        Level of the intervals [-] (0.95: 95 %).
    checks : tuple of CheckProbability
        One per check (most probable failure first), then ``any check``.
    metrics : tuple of MetricSummary
        Statistics of the metrics.
    values : dict
        Metric name → (states,) values, for quantiles and plots.
    margins : dict
        Check key → (states,) margin fractions (nan where it cannot be verified).
    states : tuple of str
        The wear states of the modal path (empty for the full path).
    held_at_nominal : tuple of str
        What every state holds at nominal (:func:`full_path_held`, :func:`modal_path_held`).
    averaged_over : tuple of str
        Over what the probabilities are averaged (:func:`averaged_over`).
    """

    path: str
    samples: int
    replicates: int
    confidence: float
    checks: tuple[CheckProbability, ...]
    metrics: tuple[MetricSummary, ...]
    values: dict[str, NDArray[np.float64]]
    margins: dict[str, NDArray[np.float64]]
    states: tuple[str, ...] = ()
    held_at_nominal: tuple[str, ...] = ()
    averaged_over: tuple[str, ...] = ()

    @property
    def evaluated_states(self) -> int:
        """States evaluated: the sampled points × the wear states of the modal path [–]."""
        return self.samples * max(1, len(self.states))

    @shared_parameters
    def probability(self, key: str) -> CheckProbability | None:
        """The entry of check ``key``.

        %(params_check_key_returns)s
        CheckProbability | None
            Its probability of failure with the interval (None when no state had it).
        """
        return next((c for c in self.checks if c.key == key), None)

    def quantile(self, metric: str, q: float) -> float:
        """The q-quantile of a metric over the states [its unit] (nan when absent).

        Parameters
        ----------
        metric : str
            A name of :data:`METRICS`.
        q : float
            Probability [–].
        """
        v = self.values.get(metric, np.array([]))
        v = v[np.isfinite(v)]
        return float(np.quantile(v, q)) if v.size else math.nan

    def margin_quantile(self, key: str, q: float) -> float:
        """The q-quantile of a check's margin fraction (a state that cannot be verified or
        built counts as −1) [–].

        Parameters
        ----------
        key : str
            The check's key.
        q : float
            Probability [–].
        """
        v = self.margins.get(key)
        if v is None or not v.size:
            return math.nan
        return float(np.quantile(np.where(np.isfinite(v), v, -1.0), q))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"path": self.path, "samples": self.samples, "sampled_points": self.samples,
                "wear_states": len(self.states), "evaluated_states": self.evaluated_states,
                "replicates": self.replicates, "confidence": self.confidence,
                "states": list(self.states), "held_at_nominal": list(self.held_at_nominal),
                "averaged_over": list(self.averaged_over),
                "checks": [c.to_dict() for c in self.checks],
                "metrics": [m.to_dict() for m in self.metrics]}


def _aggregate(outcomes: Sequence[Sequence[StateOutcome]], info: dict[str, tuple[str, str]],
               confidence: float) -> list[CheckProbability]:
    """CheckProbability per key from outcomes shaped (R, n)."""
    keys = list(info)
    out = []
    for key in [*keys, BUILD_FAILURE]:
        failed = np.array([[o.error is not None if key == BUILD_FAILURE else o.failed(key)
                            for o in row] for row in outcomes])
        p, lo, hi = estimate_probability(failed, confidence)
        name, source = info.get(key, ("buildable", "the chain fits the layout"))
        out.append(CheckProbability(key, name, source, p, lo, hi, int(failed.sum()),
                                    failed.size))
    anyf = np.array([[o.error is not None or any(s != "pass" for s in o.status.values())
                      for o in row] for row in outcomes])
    p, lo, hi = estimate_probability(anyf, confidence)
    ranked = sorted(out, key=lambda c: -c.probability)
    return [*ranked, CheckProbability("any", "any check", "", p, lo, hi, int(anyf.sum()),
                                      anyf.size)]


def _check_info(states: Sequence[PerturbedAnalysis | None]) -> dict[str, tuple[str, str]]:
    info: dict[str, tuple[str, str]] = {}
    for s in states:
        if s is None:
            continue
        try:
            for c in s.all_checks():
                info.setdefault(c.key, (c.name, c.source))
        except ChainDriveError:
            continue
        break
    return info


#: Evaluates variable rows (S, d) to outcomes, in order (in process, or on Dask).
StateEvaluator = Callable[[Analysis, UncertaintyModel, NDArray[np.float64], bool],
                          list[StateOutcome]]


def serial_states(nominal: Analysis, model: UncertaintyModel, x: NDArray[np.float64],
                  response: bool, *, progress: StepProgress | None = None
                  ) -> list[StateOutcome]:
    """Evaluate the states of the variable rows in this process.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    model : UncertaintyModel
        Its uncertainty model.
    x : ndarray
        (S, d) variable values [SI].
    response : bool
        Compute the states' dynamic response.
    progress : callable | None
        ``progress(done, total)`` after every state.

    Returns
    -------
    list of StateOutcome
        In the order of the rows.
    """
    out = []
    for row in x:
        out.append(state_outcome(PerturbedAnalysis(
            nominal, model.perturbation(row), allowable_elongation=model.allowable_elongation,
            take_up_capacity=model.take_up_capacity, response=response)))
        if progress is not None:
            progress(len(out), len(x))
    return out


def reliability(nominal: Analysis, model: UncertaintyModel, *, path: str = "full",
                evaluator: StateEvaluator | None = None,
                response: bool = True, progress: StepProgress | None = None
                ) -> ReliabilityResult:
    """Probabilities of failure of every check of the drive over ``model``.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    model : UncertaintyModel
        Its uncertainty model (samples, replicates, seed, confidence from its settings).
    path : str
        "full" (every check through :class:`PerturbedAnalysis`) or "modal" (the resonance
        margin and f₁ by the batched modal path).
    evaluator : StateEvaluator | None
        Evaluates the full path's states (default :func:`serial_states`; see
        :func:`chaindrive.robust.study.dask_states` for Dask).
    response : bool
        Compute the states' dynamic response (K_D, k₂, k₂min); False stops after the modes
        (the layout, chain and resonance checks only).
    progress : callable | None
        ``progress(done, total)`` after every state of the full path in this process.

    Returns
    -------
    ReliabilityResult
    """
    s = model.settings
    if path == "modal":
        return modal_reliability(nominal, model)
    if model.dimension == 0:
        x = model.values(np.zeros((1, 0)))
        shaped = x.reshape(1, 1, 0)
    else:
        u = sobol_points(model.dimension, s.samples, s.replicates, s.seed)
        shaped = model.values(u.reshape(-1, model.dimension)).reshape(*u.shape)
    r, n = shaped.shape[:2]
    flat = (evaluator(nominal, model, shaped.reshape(r * n, -1), response)
            if evaluator is not None else serial_states(
                nominal, model, shaped.reshape(r * n, -1), response, progress=progress))
    rows = [flat[i * n:(i + 1) * n] for i in range(r)]
    info = _check_info([PerturbedAnalysis(nominal, model.perturbation(shaped[0, 0]),
                                          allowable_elongation=model.allowable_elongation,
                                          take_up_capacity=model.take_up_capacity,
                                          response=response)])
    for o in flat:
        for key in o.status:
            info.setdefault(key, (key, ""))
    values = {k: np.array([o.metrics.get(k, math.nan) for o in flat]) for k in METRICS}
    margins = {k: np.array([_finite(o.margin.get(k)) for o in flat]) for k in info}
    return ReliabilityResult("full", r * n, r, s.confidence,
                             tuple(_aggregate(rows, info, s.confidence)),
                             tuple(_summary(k, v) for k, v in values.items()), values, margins,
                             held_at_nominal=full_path_held(model),
                             averaged_over=averaged_over(model, "full"))


# ---------------------------------------------------------------------- the modal path
def _modal_factors(model: UncertaintyModel, values: NDArray[np.float64], n: int
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """(inertia (S, n), link (S,), temperature (S,)) factors of modal variable rows."""
    s = values.shape[0]
    inertia = np.ones((s, n))
    link = np.ones(s)
    temperature = np.full(s, REFERENCE_TEMPERATURE_C)
    cols = [v.group for v in model.variables]
    k_inertia = [k for k, g in enumerate(cols) if g == "inertias"]
    if k_inertia:
        inertia = values[:, k_inertia]
    if "chain stiffness" in cols:
        link = values[:, cols.index("chain stiffness")].copy()
    if "temperature" in cols:
        temperature = values[:, cols.index("temperature")]
    return inertia, link, temperature


def modal_states(nominal: Analysis, model: UncertaintyModel) -> dict[str, Analysis]:
    """The geometric states of the modal path, nominal tolerances, factors 1: new, worn to
    the allowable elongation, or over the life the K midpoints λ_k = (k + ½)/K of the life
    fraction (``wear_states`` = K; ε = λ·ε_allow). The new state is the nominal analysis
    itself (the same numbers, :class:`PerturbedAnalysis` at ε = 0).

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    model : UncertaintyModel
        Its model (wear setting, allowable elongation).

    Returns
    -------
    dict
        Name → the analysis of that state.
    """
    s = model.settings
    if s.wear == "life":
        life = [(k + 0.5) / s.wear_states for k in range(s.wear_states)]
    else:
        life = [0.0 if s.wear == "new" else 1.0]
    return {f"life {lam:.3g}": nominal if lam == 0.0 else PerturbedAnalysis(
        nominal, Perturbation(elongation=lam * model.allowable_elongation),
        take_up_capacity=model.take_up_capacity, response=False) for lam in life}


@dataclass(frozen=True, slots=True, eq=False)
class ModalBasis:
    """The batched modal path of a drive built up to its frequencies: every geometric state
    (:func:`modal_states`) stacked under the samples (:class:`~chaindrive.robust.modal.
    StackedState`), ready for inertias added on the sprockets' shafts
    (:func:`basis_reliability`).

    Parameters
    ----------
    settings : UncertaintySettings
        Samples, replicates and confidence.
    replicates : int
        R scrambled sequences.
    points : int
        Points per sequence.
    band_percent : float
        The resonance margin required [%].
    names : tuple of str
        The geometric states.
    states : tuple of StackedState
        Each state stacked.
    held_at_nominal, averaged_over : tuple of str
        What its states hold at nominal and over what its probability is averaged
        (:func:`modal_path_held`, :func:`averaged_over`).
    """

    settings: UncertaintySettings
    replicates: int
    points: int
    band_percent: float
    names: tuple[str, ...]
    states: tuple[StackedState, ...]
    held_at_nominal: tuple[str, ...] = ()
    averaged_over: tuple[str, ...] = ()


@shared_parameters
def modal_basis(nominal: Analysis, model: UncertaintyModel) -> ModalBasis:
    """Everything of the batched modal path that the sprockets' added inertias leave
    unchanged: the geometric states, their models and stiffness matrices under the samples.

    %(nominal_modal_returns)s
    ModalBasis
    """
    s = model.settings
    modal = model.modal_only()
    states = modal_states(nominal, modal)
    if modal.dimension:
        u = sobol_points(modal.dimension, s.samples, s.replicates, s.seed)
        shaped = modal.values(u.reshape(-1, modal.dimension)).reshape(*u.shape)
    else:
        shaped = np.zeros((1, 1, 0))
    r, n = shaped.shape[:2]
    stacked = []
    for state in states.values():
        inertia, link, temperature = _modal_factors(modal, shaped.reshape(r * n, -1),
                                                    len(state.drive.sprockets))
        link = link * modulus_factors(find_material(state.drive.chain.spec.material),
                                      temperature)
        stacked.append(stacked_state(state, inertia, link, temperature))
    return ModalBasis(s, r, n, nominal.limits.resonance_band_percent, tuple(states),
                      tuple(stacked), modal_path_held(model), averaged_over(model, "modal"))


def basis_reliability(basis: ModalBasis, added_inertia: NDArray[np.float64] | None = None
                      ) -> ReliabilityResult:
    """The resonance check and f₁ by the batched modal path of a basis, with inertias added
    on the sprockets' shafts (:func:`chaindrive.robust.modal.stacked_margins`).

    Parameters
    ----------
    basis : ModalBasis
        The drive without the added inertias (:func:`modal_basis`).
    added_inertia : ndarray | None
        (n,) inertia added on every sprocket's shaft [kg·m²] (None: none).

    Returns
    -------
    ReliabilityResult
        With the one check ``resonance_margin``.
    """
    s, r, n, band = basis.settings, basis.replicates, basis.points, basis.band_percent
    per_state, f1_all, margin_all = [], [], []
    for stacked in basis.states:
        f1, margin = stacked_margins(stacked, added_inertia)
        per_state.append((margin < band * (1 - 1e-12)).reshape(r, n))
        f1_all.append(f1)
        margin_all.append(margin)
    failed = np.mean(np.stack(per_state), axis=0)  # the midpoint rule over the life
    p, lo, hi = estimate_probability(failed, s.confidence)
    entry = CheckProbability("resonance_margin", "resonance margin",
                             "[MultimassChainDrives, §3.2], [API684]", p, lo, hi,
                             int(np.stack(per_state).sum()), failed.size * len(per_state))
    margins = np.concatenate(margin_all)
    values = {"f1_hz": np.concatenate(f1_all), "resonance_margin_percent": margins}
    return ReliabilityResult("modal", r * n, r, s.confidence, (entry,),
                             tuple(_summary(k, v) for k, v in values.items()), values,
                             {"resonance_margin": np.where(np.isfinite(margins),
                                                           margins / band - 1.0, 1e6)},
                             basis.names, basis.held_at_nominal, basis.averaged_over)


@shared_parameters
def modal_reliability(nominal: Analysis, model: UncertaintyModel) -> ReliabilityResult:
    """The resonance check and f₁ by the batched modal path (module docstring).

    %(nominal_modal_returns)s
    ReliabilityResult
        With the one check ``resonance_margin``.
    """
    return basis_reliability(modal_basis(nominal, model))
