"""What a chance constraint P(check fails) ≤ α can claim from S sampled states: the one-sided
Clopper–Pearson upper bound of the probability, the least S that can certify α at all, and
the number of failures S states may show while the bound still holds.

With k failures among S independent states, the one-sided upper confidence bound at level c
is the c-quantile of the Beta(k + 1, S − k) distribution [ClopperPearson1934]:

    p_up(k, S, c) = B⁻¹(c; k + 1, S − k)        (1 when k = S)

and with no failure it is the closed form p_up(0, S, c) = 1 − (1 − c)^(1/S) (≈ 3/S at
c = 95 %, the "rule of three" [Hanley1983]). Certifying p ≤ α therefore needs, even with no
failure, S ≥ ln(1 − c) / ln(1 − α): 299 states for α = 1 % at 95 %, 59 for 5 %, 2995 for
0.1 %. A search that asks for less cannot keep its promise and is refused.

The bound treats the states as independent draws. The optimiser's states are scrambled
Sobol points (randomised quasi-Monte Carlo [Owen1997]): each is uniform, but the count is not
exactly binomial; and every design of a search sees the same points (common random numbers),
so the search selects designs that happen to pass on them. Both are why the designs a search
returns are verified with an independent, larger sample on the full path
(:func:`chaindrive.robust.synthesis.verify_design`), whose figures are the ones reported: a
design is certified only when that verification's bound holds.

References
----------
[ClopperPearson1934], [Hanley1983], [Owen1997]
"""

from __future__ import annotations

import math

from scipy.stats import beta as beta_dist

__all__ = ["allowed_failures", "minimum_samples", "upper_bound"]


def upper_bound(failures: float, samples: int, confidence: float) -> float:
    """One-sided Clopper–Pearson upper confidence bound of a probability [–].

    p_up = B⁻¹(c; k + 1, S − k), 1 when k = S [ClopperPearson1934].

    Parameters
    ----------
    failures : float
        k, failed states [–] (a fraction of a state where a sampled point stands for several
        wear states).
    samples : int
        S ≥ 1, states [–].
    confidence : float
        c, one-sided confidence level in (0, 1) [–].

    Returns
    -------
    float
        p_up [–].

    References
    ----------
    [ClopperPearson1934]
    """
    if samples < 1 or not 0 <= failures <= samples:
        raise ValueError(f"need 0 ≤ failures ≤ samples, samples ≥ 1; got {failures}, {samples}")
    if failures >= samples:
        return 1.0
    return float(beta_dist.ppf(confidence, failures + 1, samples - failures))


def minimum_samples(alpha: float, confidence: float) -> int:
    """The least number of states whose upper bound with no failure is ≤ α [–].

    S_min = ⌈ln(1 − c) / ln(1 − α)⌉, from p_up(0, S, c) = 1 − (1 − c)^(1/S)
    [ClopperPearson1934], [Hanley1983].

    Parameters
    ----------
    alpha : float
        α in (0, 1), the largest probability of failure asked for [–].
    confidence : float
        c in (0, 1) [–].

    Returns
    -------
    int

    References
    ----------
    [ClopperPearson1934], [Hanley1983]
    """
    n = math.ceil(math.log1p(-confidence) / math.log1p(-alpha) - 1e-9)
    while upper_bound(0, n, confidence) > alpha:  # guard the rounding of the closed form
        n += 1
    return n


def allowed_failures(alpha: float, samples: int, confidence: float) -> int:
    """The largest number of failures k among S states with p_up(k, S, c) ≤ α; −1 when
    even none certifies α (S below :func:`minimum_samples`) [–].

    p_up grows with k, so k is found by bisection over 0 … S [ClopperPearson1934].

    Parameters
    ----------
    alpha : float
        α [–].
    samples : int
        S [–].
    confidence : float
        c [–].

    Returns
    -------
    int

    References
    ----------
    [ClopperPearson1934]
    """
    if upper_bound(0, samples, confidence) > alpha:
        return -1
    lo, hi = 0, samples  # p_up(lo) ≤ α < p_up(hi) = 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if upper_bound(mid, samples, confidence) <= alpha:
            lo = mid
        else:
            hi = mid
    return lo
