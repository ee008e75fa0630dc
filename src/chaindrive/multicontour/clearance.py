"""Random keyed-joint clearances of a two-contour drive and the length difference ΔL₃.

Source: [Lyashuk], eq. 7–14 and Table 1. Joints are named as in the
paper: ``1-I``, ``2-I`` — driving and driven sprocket of contour I; ``1-II``, ``2-II`` — of
contour II. A clearance z in a joint lengthens its contour's working span by C₄·z (eq. 6),
so what loads the contours unequally is the difference ΔL₃ = ΔL_II − ΔL_I (eq. 12).

Two readings of the paper are kept apart (see ``docs/multicontour.md``):

* the **eq. 13 model** — all four joints have a clearance, each z independent and
  Normal(z_max/2, z_max/6) (eq. 7); then ΔL_II, ΔL_I ~ Normal(2C₄z̄, 2C₄²σ_z²) (eq. 11) and
  ΔL₃ ~ Normal(0, (2C₄σ_z)²) (eq. 13), |ΔL₃| half-normal (eq. 14). This is what the paper
  computes; it is placement No. 13 of Table 1, not the "2z" placements (No. 6, 8) that the
  text says it is considering, which would give a non-zero mean C₄·z_max.
* the **placement model** — a placement of Table 1 is drawn (all equally likely, as the
  paper's P(0), P(z), P(2z) assume) and only the joints it marks have a clearance.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from fractions import Fraction
from statistics import NormalDist
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError, did_you_mean
from chaindrive.units import TWO_PI

JOINTS: tuple[str, ...] = ("1-I", "2-I", "1-II", "2-II")
PlacementRule = Literal["table", "all"]
PLACEMENT_RULES: tuple[str, ...] = ("table", "all")
LengthModel = Literal["all_joints", "placements"]
LENGTH_MODELS: tuple[str, ...] = ("all_joints", "placements")
SIGMAS_IN_RANGE = 3.0  # z_max = 6 σ_z, z̄ = z_max/2 [Lyashuk, after eq. 7]
_NORMAL = NormalDist()  # the standard normal: cdf Φ, inv_cdf Φ⁻¹ (scalars)


def check_positive(name: str, value: float) -> None:
    """Refuse a value that is not a finite positive number.

    Parameters
    ----------
    name : str
        The field the value was given in.
    value : float
        The value [its field's unit].

    Raises
    ------
    DesignError
        ``value`` is not finite or not positive.
    """
    if not (math.isfinite(value) and value > 0):
        raise DesignError(name, f"must be a positive number, got {value!r}")


def clearance_pdf(clearance: ArrayLike, max_clearance: float, *,
                  truncated: bool = True) -> NDArray[np.float64]:
    """Density f(z) of the key/keyway clearance z ~ Normal(z̄ = z_max/2, σ_z = z_max/6).

    Parameters
    ----------
    clearance : float or array_like
        z [m].
    max_clearance : float
        z_max [m].
    truncated : bool
        True renormalises it on [0, z_max] (zero outside; peak 2.400/z_max); False is eq. 7
        as printed (peak 6/√(2π)/z_max = 2.394/z_max; the paper's eq. 8 prints the constant
        as 2.382).

    Returns
    -------
    numpy.ndarray
        f(z) [1/m].

    References
    ----------
    [Lyashuk, eq. 7–8].
    """
    check_positive("max_clearance", max_clearance)
    z = np.asarray(clearance, dtype=float)
    sigma = max_clearance / (2.0 * SIGMAS_IN_RANGE)
    u = (z - max_clearance / 2.0) / sigma
    density = np.exp(-0.5 * u**2) / (sigma * math.sqrt(TWO_PI))
    if not truncated:
        return density
    mass = _NORMAL.cdf(SIGMAS_IN_RANGE) - _NORMAL.cdf(-SIGMAS_IN_RANGE)
    return np.where((z >= 0.0) & (z <= max_clearance), density / mass, 0.0)


@dataclass(frozen=True, slots=True)
class ClearancePlacement:
    """One placement of clearances over the four joints (a row of [Lyashuk, Table 1]).

    Parameters
    ----------
    joints : tuple of bool
        Presence of a clearance in (1-I, 2-I, 1-II, 2-II).
    contour_i, contour_ii : int
        Clearances in each contour [z].
    total : int
        |contour_ii − contour_i|, the "total maximal clearance" of the table's last column
        [z].
    """

    joints: tuple[bool, bool, bool, bool]
    contour_i: int
    contour_ii: int
    total: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"clearance_in": [name for name, on in zip(JOINTS, self.joints, strict=True)
                                 if on],
                "contour_i_z": self.contour_i, "contour_ii_z": self.contour_ii,
                "total_z": self.total}


def _table_rule(clear: tuple[int, ...]) -> bool:
    """The paper's enumeration: any set of ≤ 2 joints, or a run of consecutive joints."""
    return len(clear) <= 2 or clear[-1] - clear[0] + 1 == len(clear)


def clearance_placements(rule: str = "table") -> tuple[ClearancePlacement, ...]:
    """Placements of clearances over the joints 1-I, 2-I, 1-II, 2-II, enumerated.

    Each joint has a clearance z or none; a contour's working span grows by z per clear joint
    (eq. 1), and the contours differ by |n_II − n_I|·z (Table 1, last column). The paper
    states no rule; its rows are exactly the sets of at most two joints plus the runs of
    consecutive joints in the order (1-I, 2-I, 1-II, 2-II) — the two split triples
    {1-I, 2-I, 2-II} and {1-I, 1-II, 2-II} are missing although they are as possible as the
    two triples listed (No. 9, 10). See docs/multicontour.md.

    Parameters
    ----------
    rule : str
        ``"all"`` — all 2⁴ = 16 presence/absence patterns; ``"table"`` — the 14 rows of
        Table 1.

    Returns
    -------
    tuple of ClearancePlacement
        The placements.

    References
    ----------
    [Lyashuk, eq. 1 and Table 1].
    """
    if rule not in PLACEMENT_RULES:
        raise DesignError("rule", f"must be one of {PLACEMENT_RULES}, got {rule!r}"
                                  f"{did_you_mean(rule, PLACEMENT_RULES)}")
    rows = []
    for count in range(len(JOINTS) + 1):
        for clear in itertools.combinations(range(len(JOINTS)), count):
            if rule == "table" and not _table_rule(clear):
                continue
            on = tuple(i in clear for i in range(len(JOINTS)))
            n_i, n_ii = on[0] + on[1], on[2] + on[3]
            rows.append(ClearancePlacement(on, n_i, n_ii, abs(n_ii - n_i)))  # type: ignore[arg-type]
    return tuple(rows)


def placement_probabilities(rule: str = "table") -> dict[int, Fraction]:
    """P(total = k·z) for k = 0, 1, 2, every placement equally likely.

    Parameters
    ----------
    rule : str
        ``"table"`` (Table 1): P(0) = P(z) = 6/14, P(2z) = 2/14 (the paper's 42.8 %, 42.8 %,
        14.2 %, truncated); ``"all"``: 6/16, 8/16, 2/16.

    Returns
    -------
    dict of int to fractions.Fraction
        k → P [-].

    References
    ----------
    [Lyashuk, after eq. 10].
    """
    rows = clearance_placements(rule)
    counts: dict[int, int] = {}
    for row in rows:
        counts[row.total] = counts.get(row.total, 0) + 1
    return {k: Fraction(counts[k], len(rows)) for k in sorted(counts)}


@dataclass(frozen=True, slots=True)
class LengthDifferenceStats:
    """Analytic distribution of ΔL₃ in the eq. 13 model [Lyashuk, eq. 11–14].

    Parameters
    ----------
    c4 : float
        C₄ [-].
    max_clearance, clearance_mean, clearance_sigma : float
        z_max, z̄, σ_z [m].
    contour_mean, contour_sigma : float
        2C₄z̄ and √2·C₄σ_z of ΔL_I, ΔL_II (eq. 11) [m].
    sigma : float
        2C₄σ_z of ΔL₃ (eq. 13) [m].
    mean_abs : float
        √(2/π)·σ of |ΔL₃| (eq. 14) [m].
    variance_abs : float
        σ²(1 − 2/π) of |ΔL₃| [m²].
    quantile_95_abs : float
        σ·Φ⁻¹(0.975) [m].
    """

    c4: float
    max_clearance: float
    clearance_mean: float
    clearance_sigma: float
    contour_mean: float
    contour_sigma: float
    sigma: float
    mean_abs: float
    variance_abs: float
    quantile_95_abs: float

    def quantile_abs(self, probability: float) -> float:
        """Quantile of |ΔL₃| (half-normal, eq. 14).

        Parameters
        ----------
        probability : float
            P(|ΔL₃| ≤ q) [-].

        Returns
        -------
        float
            q [m].
        """
        return half_normal_quantile(self.sigma, probability)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm)."""
        mm = {name: getattr(self, name) * 1e3 for name in
              ("max_clearance", "clearance_mean", "clearance_sigma", "contour_mean",
               "contour_sigma", "sigma", "mean_abs", "quantile_95_abs")}
        return {"c4": self.c4, **{f"{k}_mm": v for k, v in mm.items()},
                "variance_abs_mm2": self.variance_abs * 1e6}


def half_normal_quantile(sigma: float, probability: float) -> float:
    """q with P(|X| ≤ q) = probability for X ~ Normal(0, σ²): q = σ·Φ⁻¹((1 + P)/2).

    Parameters
    ----------
    sigma : float
        σ [any unit].
    probability : float
        P in [0, 1) [-].

    Returns
    -------
    float
        q [unit of σ].
    """
    if not 0.0 <= probability < 1.0:
        raise DesignError("probability", f"must be in [0, 1), got {probability!r}")
    return float(sigma * _NORMAL.inv_cdf(0.5 * (1.0 + probability)))


def length_difference_stats(c4: float, max_clearance: float) -> LengthDifferenceStats:
    """Mean, spread and 95 % quantile of ΔL₃ and |ΔL₃|.

    Parameters
    ----------
    c4 : float
        C₄ of eq. 6 [-].
    max_clearance : float
        z_max [m].

    Returns
    -------
    LengthDifferenceStats
        The distribution.

    References
    ----------
    [Lyashuk, eq. 11–14].
    """
    check_positive("c4", c4)
    check_positive("max_clearance", max_clearance)
    z_mean = max_clearance / 2.0
    sigma_z = max_clearance / (2.0 * SIGMAS_IN_RANGE)
    sigma = 2.0 * c4 * sigma_z
    return LengthDifferenceStats(
        c4=c4, max_clearance=max_clearance, clearance_mean=z_mean, clearance_sigma=sigma_z,
        contour_mean=2.0 * c4 * z_mean, contour_sigma=math.sqrt(2.0) * c4 * sigma_z,
        sigma=sigma, mean_abs=math.sqrt(2.0 / math.pi) * sigma,
        variance_abs=sigma**2 * (1.0 - 2.0 / math.pi),
        quantile_95_abs=half_normal_quantile(sigma, 0.95),
    )


def sample_clearances(shape: tuple[int, ...], rng: np.random.Generator, max_clearance: float,
                      *, truncated: bool = False) -> NDArray[np.float64]:
    """Random clearances z ~ Normal(z_max/2, z_max/6).

    Parameters
    ----------
    shape : tuple of int
        Shape of the sample.
    rng : numpy.random.Generator
        The generator.
    max_clearance : float
        z_max [m].
    truncated : bool
        Draw from the same normal restricted to [0, z_max] (inverse CDF).

    Returns
    -------
    numpy.ndarray
        z [m].

    References
    ----------
    [Lyashuk, eq. 7].
    """
    mean, sigma = max_clearance / 2.0, max_clearance / (2.0 * SIGMAS_IN_RANGE)
    if not truncated:
        return rng.normal(mean, sigma, size=shape)
    # lazy: scipy.special costs 0.4 s to import (python -X importtime), more than a third of
    # the 1 s `chaindrive analyze` may take; only the truncated draw needs the vectorised Φ⁻¹
    from scipy.special import ndtri

    lo, hi = _NORMAL.cdf(-SIGMAS_IN_RANGE), _NORMAL.cdf(SIGMAS_IN_RANGE)
    z: NDArray[np.float64] = mean + sigma * ndtri(rng.uniform(lo, hi, size=shape))
    return z


def simulate_length_difference(n: int, rng: np.random.Generator | int | None = None, *,
                               c4: float, max_clearance: float, model: str = "all_joints",
                               rule: str = "table", truncated: bool = False,
                               ) -> NDArray[np.float64]:
    """Monte-Carlo samples of ΔL₃ = (ΔL_1II + ΔL_2II) − (ΔL_1I + ΔL_2I) [m], shape (n,).

    Per sample: a clearance z per joint (eq. 7, ``truncated`` as in :func:`sample_clearances`),
    ΔL = C₄·z (eq. 6), summed per contour (eq. 1) and differenced (eq. 12).
    Parameters
    ----------
    n : int
        Samples [-].
    rng : numpy.random.Generator or int or None
        A generator or the seed of one.
    c4 : float
        C₄ [-].
    max_clearance : float
        z_max [m].
    model : str
        ``"all_joints"`` — every joint has a clearance (the model behind eq. 13, which the
        analytic :func:`length_difference_stats` describes); ``"placements"`` — first a
        placement of :func:`clearance_placements` (``rule``) is drawn uniformly and only its
        joints have a clearance.
    rule : str
        As in :func:`clearance_placements`.
    truncated : bool
        As in :func:`sample_clearances`.

    Returns
    -------
    numpy.ndarray
        (n,) ΔL₃ [m].

    References
    ----------
    [Lyashuk, eq. 1, 6, 7, 12].
    """
    if model not in LENGTH_MODELS:
        raise DesignError("model", f"must be one of {LENGTH_MODELS}, got {model!r}"
                                   f"{did_you_mean(model, LENGTH_MODELS)}")
    if not isinstance(n, int) or n < 1:
        raise DesignError("n", f"must be a positive whole number, got {n!r}")
    check_positive("c4", c4)
    check_positive("max_clearance", max_clearance)
    gen = np.random.default_rng(rng)
    z = sample_clearances((n, len(JOINTS)), gen, max_clearance, truncated=truncated)
    if model == "placements":
        masks = np.array([row.joints for row in clearance_placements(rule)], dtype=float)
        z = z * masks[gen.integers(0, len(masks), size=n)]
    return c4 * ((z[:, 2] + z[:, 3]) - (z[:, 0] + z[:, 1]))
