"""Robust synthesis: chance constraints and robust objectives for the optimiser
(:mod:`chaindrive.synthesis`), read from ``[optimize.robust]``::

    [optimize.robust]
    samples = 320                # states per design (Sobol points; left out: the least
                                 # that certifies every chance constraint)
    path = "auto"                # auto | modal | full
    verification = 0             # states of the independent check (0: 4 × samples)
    [optimize.robust.chance]     # check key → largest probability of failing it
    resonance_margin = 0.01      # P(a working frequency within the band) ≤ 1 %
    k2 = 0.001                   # P(k₂ < [k]) ≤ 0.1 %

and objectives such as ``"kd_p95"`` (the 95th percentile of K_D) in ``[optimize]
objectives``. The uncertainty model is the design file's ``[uncertainty]`` table.

A chance constraint P(check fails) ≤ α holds only as a confidence statement: with k of S
states failing, the design passes when the one-sided Clopper–Pearson upper bound at the
``[uncertainty]`` confidence c is ≤ α (:mod:`chaindrive.robust.chance`), i.e. when at most
k* = max{k : p_up(k, S, c) ≤ α} states fail. The search gets this as a continuous value: the
(k* + 1)-th smallest margin fraction m of the states (m ≥ 0 passes), g = −m₍ₖ*₊₁₎ ≤ 0 —
the value-at-risk form of a chance constraint [Rockafellar2000] at the certified level
instead of the point estimate. S below S_min = ⌈ln(1 − c)/ln(1 − α)⌉ (299 for 1 % at 95 %)
cannot certify α at all and is refused; left out, ``samples`` is the least Sobol count that
certifies every chance constraint. Every design of a search sees the same points (common
random numbers), so the Pareto designs found are verified with an independent sample
(another seed, ``verification`` states, by default four times the search's) **on the full
path** (every tolerance sampled, whatever path the search took: the modal path holds the
geometric tolerances at nominal), and that verification (:class:`ChanceVerification`: the
search's probability and the full path's, ``certified`` only when the full path's bound
holds) is what the result reports. The path "auto"
takes the batched modal path when the constraints and objectives need only the resonance
margin and f₁, and the full path otherwise; the modal path evaluates each sampled point at
its wear states, so there a point counts as the fraction of its wear states that fail.

References
----------
[Rockafellar2000], [ClopperPearson1934], [MultimassChainDrives]
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.analysis import Analysis
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.io.design import Field, parse_section
from chaindrive.model import Drive

if TYPE_CHECKING:  # the sampling, chance and uncertainty modules import scipy.stats (0.35 s):
    # imported where a robust problem uses them, not by every optimisation that imports this
    from chaindrive.robust.sampling import ReliabilityResult
    from chaindrive.robust.uncertainty import UncertaintySettings

__all__ = ["MODAL_KEYS", "RESPONSE_KEYS", "ROBUST_FIELDS", "ROBUST_OBJECTIVES", "ChanceVerification",
           "RobustAnalysis", "RobustSettings", "chance_statement", "robust_constraints",
           "robust_settings", "robust_statistic", "verify_design"]

ROBUST_FIELDS: tuple[Field, ...] = (
    Field("samples", "int", "states of the uncertainty model per design (Sobol points); left "
          "out: the least that certifies every chance constraint (32 without one)",
          default=None, minimum=4, maximum=1 << 16,
          reason="a chance constraint P <= a needs at least ln(1 - c)/ln(1 - a) states "
          "(Clopper-Pearson with no failure)", example="320"),
    Field("verification", "int", "states of the independent sample each Pareto design is "
          "verified with (0: four times the search's)", default=0, minimum=0,
          maximum=1 << 18, reason="a larger sample than the search's, another seed",
          example="2048"),
    Field("path", "choice", "auto: the batched modal path when only the resonance margin and "
          "f1 are needed; modal; full", default="auto", choices=("auto", "modal", "full")),
)
#: Robust objectives: name → (metric of the states, quantile, sense, unit, description).
ROBUST_OBJECTIVES: dict[str, tuple[str, float, int, str, str]] = {
    "kd_p95": ("coefficient_of_dynamics", 0.95, 1, "-",
               "95th percentile of K_D over the uncertainty model (minimised)"),
    "k2_p05": ("k2", 0.05, -1, "-", "5th percentile of k2 over the uncertainty model "
               "(maximised)"),
    "resonance_margin_p05": ("resonance_margin_percent", 0.05, -1, "%",
                             "5th percentile of the resonance margin over the uncertainty "
                             "model (maximised)"),
}
#: Check keys and metrics the batched modal path gives.
MODAL_KEYS = frozenset({"resonance_margin", "resonance_margin_percent", "f1_hz"})
#: Check keys and metrics that need the states' dynamic response.
RESPONSE_KEYS = frozenset({"k2", "k2min", "k2_with_errors", "coefficient_of_dynamics"})


@dataclass(frozen=True, slots=True)
class RobustSettings:
    """``[optimize.robust]`` with the ``[uncertainty]`` table.

    Parameters
    ----------
    uncertainty : UncertaintySettings
        The uncertainty model's settings (``samples`` replaced by the table's).
    chance : tuple of (str, float)
        (check key, largest probability of failing it [-]).
    path : str
        "modal" or "full" (resolved from "auto").
    objectives : tuple of str
        The robust objectives the problem asks for.
    response : bool
        The states need the dynamic response (K_D, k₂, k₂min are asked for).
    verification : int
        States of the independent verification of the designs found [–].
    """

    uncertainty: UncertaintySettings
    chance: tuple[tuple[str, float], ...]
    path: str
    objectives: tuple[str, ...] = ()
    response: bool = True
    verification: int = 0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"uncertainty": self.uncertainty.to_dict(), "chance": dict(self.chance),
                "path": self.path, "objectives": list(self.objectives),
                "verification": self.verification}


def _chance(table: Any) -> tuple[tuple[str, float], ...]:
    if not isinstance(table, Mapping):
        raise DesignError("optimize.robust.chance", f"must be a table of check keys and "
                          f"probabilities, got {type(table).__name__}")
    out = []
    for key, value in table.items():
        path = f"optimize.robust.chance.{key}"
        if isinstance(value, bool) or not isinstance(value, int | float) or not (
                0.0 < float(value) < 0.5):
            raise DesignError(path, f"must be a probability in (0, 0.5), got {value!r}")
        out.append((str(key), float(value)))
    return tuple(out)


def robust_settings(table: Mapping[str, Any], uncertainty: Mapping[str, Any] | None,
                    objectives: Sequence[str] = ()) -> RobustSettings:
    """Read ``[optimize.robust]`` (and ``[uncertainty]``); a mistake is one
    :class:`~chaindrive.errors.DesignError` naming the field.

    Parameters
    ----------
    table : Mapping
        The ``[optimize.robust]`` table.
    uncertainty : Mapping | None
        The design file's ``[uncertainty]`` table.
    objectives : sequence of str
        The problem's objectives (the robust ones decide the path).

    Returns
    -------
    RobustSettings
    """
    known = {f.name for f in ROBUST_FIELDS} | {"chance"}
    for key in table:
        if key not in known:
            raise DesignError(f"optimize.robust.{key}", "unknown field" + did_you_mean(key, known)
                              + f" (known: {', '.join(sorted(known))})")
    values = parse_section({k: v for k, v in table.items() if k != "chance"}, ROBUST_FIELDS,
                           "optimize.robust")
    chance = _chance(table.get("chance", {}))
    robust = tuple(o for o in objectives if o in ROBUST_OBJECTIVES)
    if not chance and not robust:
        raise DesignError("optimize.robust", "asks for nothing: add [optimize.robust.chance] "
                          f"or a robust objective ({', '.join(ROBUST_OBJECTIVES)})")
    needs = {k for k, _ in chance} | {ROBUST_OBJECTIVES[o][0] for o in robust}
    path = values["path"]
    if path == "auto":
        path = "modal" if needs <= MODAL_KEYS else "full"
    elif path == "modal" and not needs <= MODAL_KEYS:
        raise DesignError("optimize.robust.path", "the modal path gives only the resonance "
                          f"margin and f1; {', '.join(sorted(needs - MODAL_KEYS))} need "
                          'path = "full"')
    # lazy: the robust study's statistics (scipy.stats, SALib) load only for a problem that
    # has a robust part, not for every `optimize`
    from chaindrive.robust.chance import minimum_samples
    from chaindrive.robust.sampling import sample_count
    from chaindrive.robust.uncertainty import uncertainty_settings

    base = uncertainty_settings(uncertainty)
    samples = values["samples"]
    if samples is None:
        samples = max([32, *(minimum_samples(a, base.confidence) for _, a in chance)])
    settings = replace(base, samples=samples)
    _check_certifiable(settings, chance)
    states = sample_count(settings.samples, settings.replicates)
    return RobustSettings(settings, chance, path, robust, bool(needs & RESPONSE_KEYS),
                          values["verification"] or 4 * states)


def _check_certifiable(settings: UncertaintySettings, chance: Sequence[tuple[str, float]]
                       ) -> None:
    """Refuse a sample count that cannot certify a chance constraint (module docstring)."""
    # lazy: as in robust_settings (the statistics load only for a robust problem)
    from chaindrive.robust.chance import minimum_samples
    from chaindrive.robust.sampling import sample_count

    states = sample_count(settings.samples, settings.replicates)
    c = settings.confidence
    for key, alpha in chance:
        need = minimum_samples(alpha, c)
        if states < need:
            raise DesignError("optimize.robust.samples", f"{states} states per design cannot "
                              f"certify P({key}) ≤ {alpha:g} at {c:.0%} confidence: at least "
                              f"{need} are needed (ln(1 − c)/ln(1 − α), Clopper–Pearson with "
                              "no failure); raise samples or leave it out")


class RobustAnalysis(Analysis):
    """An :class:`~chaindrive.analysis.Analysis` that also knows its uncertainty model: the
    ``robust`` stage is the probabilities and statistics of the design's states.

    Parameters
    ----------
    design : Drive
        The design.
    robust : RobustSettings
        ``[optimize.robust]`` and ``[uncertainty]``.
    **kwargs : dict
        As :class:`~chaindrive.analysis.Analysis`.
    """

    def __init__(self, design: Drive, *, robust: RobustSettings, **kwargs: Any) -> None:
        super().__init__(design, **kwargs)
        self.robust_settings = robust

    @cached_property
    def robust(self) -> ReliabilityResult:
        """The design's probabilities of failure and metric statistics over its states."""
        s = self.robust_settings
        # lazy: as in robust_settings (the statistics load only for a robust problem)
        from chaindrive.robust.sampling import reliability
        from chaindrive.robust.uncertainty import uncertainty_model

        return reliability(self, uncertainty_model(self, s.uncertainty), path=s.path,
                           response=s.response)


def robust_statistic(analysis: Analysis, name: str) -> float:
    """The robust objective ``name`` of :data:`ROBUST_OBJECTIVES` of a design [its unit].

    Parameters
    ----------
    analysis : Analysis
        A :class:`RobustAnalysis` (a plain analysis has no uncertainty model).
    name : str
        The objective.

    Returns
    -------
    float
    """
    if not isinstance(analysis, RobustAnalysis):
        raise DesignError("optimize.objectives", f"{name} needs an [optimize.robust] table")
    metric, q, _, _, _ = ROBUST_OBJECTIVES[name]
    value = analysis.robust.quantile(metric, q)
    if not math.isfinite(value):
        raise DesignError("optimize.objectives", f"{name}: no state gave {metric}")
    return value


def chance_statement(result: ReliabilityResult, key: str, alpha: float, confidence: float
                     ) -> tuple[float, int, float, float]:
    """What S states say about P(check ``key`` fails) ≤ α (module docstring).

    Parameters
    ----------
    result : ReliabilityResult
        The states (its ``samples`` independent points; the modal path evaluates each at its
        wear states, a point then counting as the fraction of them that fail).
    key : str
        The check's key.
    alpha : float
        α [–].
    confidence : float
        c, one-sided [–].

    Returns
    -------
    tuple
        (failures k [–], states S [–], upper bound p_up(k, S, c) [–], constraint value
        g = −m₍ₖ*₊₁₎ [–], ≤ 0 exactly when p_up ≤ α for a whole count; for the modal path's
        fractional counts g ≤ 0 implies p_up ≤ α). A model with no random variable
        (S = 1) is exact: p_up = p and g is the margin of the α-quantile.

    References
    ----------
    [ClopperPearson1934], [Rockafellar2000]
    """
    v = result.margins.get(key)
    if v is None or not v.size:
        raise DesignError(f"optimize.robust.chance.{key}", "is not a check of this design "
                          f"(known: {', '.join(result.margins)})")
    m = np.sort(np.where(np.isfinite(v), v, -1.0))
    n = result.samples
    fraction = float(np.mean(m < 0.0))
    if n == 1:  # no random variable: the fraction is exact
        return fraction, 1, fraction, -float(m[min(m.size - 1, math.floor(alpha * m.size))])
    # lazy: as in robust_settings (the statistics load only for a robust problem)
    from chaindrive.robust.chance import allowed_failures, upper_bound

    k_star = allowed_failures(alpha, n, confidence)
    failures = fraction * n
    p_up = upper_bound(min(failures, n), n, confidence)
    if k_star < 0:
        return failures, n, p_up, 1.0  # cannot certify α (refused by robust_settings)
    return failures, n, p_up, -float(m[min(m.size - 1, k_star * m.size // n)])


def robust_constraints(analysis: RobustAnalysis) -> dict[str, float]:
    """Chance constraints g = −m₍ₖ*₊₁₎ ≤ 0 of a design (module docstring), named
    ``P(<key>)``: g ≤ 0 when the one-sided upper confidence bound of P(check fails) over the
    design's states is at most the α asked for.

    Parameters
    ----------
    analysis : RobustAnalysis
        The design's analysis with its ``[optimize.robust]`` chance table.

    Returns
    -------
    dict of str to float
        ``P(<key>)`` → g [-] (minus the (k*+1)-th smallest margin fraction; ≤ 0 is feasible).

    References
    ----------
    [ClopperPearson1934], [Rockafellar2000]
    """
    c = analysis.robust_settings.uncertainty.confidence
    return {f"P({key})": chance_statement(analysis.robust, key, alpha, c)[3]
            for key, alpha in analysis.robust_settings.chance}


@dataclass(frozen=True, slots=True)
class ChanceVerification:
    """A chance constraint of a design found by the search, re-estimated with an independent
    sample (:func:`verify_design`).

    Parameters
    ----------
    key : str
        The check's key.
    alpha : float
        The largest probability asked for [–].
    confidence : float
        One-sided confidence level of the bounds [–].
    search_failures, search_upper : float
        Failed states and the upper bound p_up of the search's own sample [–].
    search_samples : int
        The search's states per design [–].
    probability, low, high : float
        The independent estimate p̂ and its two-sided interval at the same level
        (:func:`chaindrive.robust.sampling.estimate_probability`) [–].
    upper : float
        Its one-sided upper bound p_up [–].
    failures : float
        Failed states of the independent sample [–].
    samples : int
        Its states [–].
    seed : int
        Its seed (the search's + 1).
    search_probability : float
        The search's own estimate p̂ on its path [–].
    search_path : str
        The path of the search ("modal" or "full").
    path : str
        The path of the verification (always "full").
    """

    key: str
    alpha: float
    confidence: float
    search_failures: float
    search_samples: int
    search_upper: float
    probability: float
    low: float
    high: float
    upper: float
    failures: float
    samples: int
    seed: int
    search_probability: float = math.nan
    search_path: str = "full"
    path: str = "full"

    @property
    def certified(self) -> bool:
        """The independent sample on the full path certifies P ≤ α (p_up ≤ α)."""
        return self.path == "full" and self.upper <= self.alpha

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"key": self.key, "alpha": self.alpha, "confidence": self.confidence,
                "search": {"path": self.search_path, "probability": self.search_probability,
                           "failures": self.search_failures, "samples": self.search_samples,
                           "upper": self.search_upper},
                "path": self.path,
                "probability": self.probability, "ci_low": self.low, "ci_high": self.high,
                "upper": self.upper, "failures": self.failures, "samples": self.samples,
                "seed": self.seed, "certified": self.certified}


def verify_design(analysis: RobustAnalysis) -> tuple[ChanceVerification, ...]:
    """Every chance constraint of a design re-estimated with an independent sample: the
    settings' ``verification`` states, another seed, on the full path (module docstring).

    Parameters
    ----------
    analysis : RobustAnalysis
        The design as the search analysed it.

    Returns
    -------
    tuple of ChanceVerification
        One per chance constraint.

    References
    ----------
    [ClopperPearson1934]
    """
    s = analysis.robust_settings
    u = s.uncertainty
    other = replace(u, samples=s.verification, seed=u.seed + 1)
    fresh = RobustAnalysis(analysis.design, robust=replace(s, uncertainty=other, path="full"),
                           limits=analysis.limits, startup=analysis.with_startup)
    out = []
    for key, alpha in s.chance:
        k0, n0, up0, _ = chance_statement(analysis.robust, key, alpha, u.confidence)
        k, n, up, _ = chance_statement(fresh.robust, key, alpha, u.confidence)
        entry = fresh.robust.probability(key)
        p, lo, hi = ((entry.probability, entry.low, entry.high) if entry is not None
                     else (k / n, math.nan, math.nan))
        searched = analysis.robust.probability(key)
        out.append(ChanceVerification(key, alpha, u.confidence, k0, n0, up0, p, lo, hi, up,
                                      k, n, other.seed,
                                      math.nan if searched is None else searched.probability,
                                      s.path, "full"))
    return tuple(out)
