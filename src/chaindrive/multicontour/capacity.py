"""Load capacity of multi-contour drives: the contour factor K_m and load sharing.

[Lyashuk, eq. 15–18] (after Кривий, Дубиняк, Куцевич 1999, [Lyashuk, ref. 4]) for two
contours; the generalisation to m contours by compatibility of deformations is ours
(docs/multicontour.md): contour j, longer than the tightest by s_j, carries
F_j = k_j·max(0, δ − s_j) once its slack is taken up, with Σ F_j = F.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.multicontour.clearance import (
    check_positive,
    half_normal_quantile,
    length_difference_stats,
    sample_clearances,
)

MAX_CONTOURS = 24


def span_deformation(force: ArrayLike, links: ArrayLike, alpha: float, force_exponent: float,
                     links_exponent: float) -> NDArray[np.float64]:
    """Elastic deformation of the working span Δ_y = α·F^x·N^y.

    The paper gives no α, x, y; with x = y = 1, α = ε·p/F for an elastic strain ε at force F,
    i.e. a linear spring of N links of pitch p.

    Parameters
    ----------
    force : float or array_like
        F [N].
    links : float or array_like
        N, links in the working span [-].
    alpha : float
        α, empirical constant of the chain [m/(N^x)].
    force_exponent, links_exponent : float
        x, y [-].

    Returns
    -------
    numpy.ndarray
        Δ_y [m].

    References
    ----------
    [Lyashuk, eq. 18].
    """
    out: NDArray[np.float64] = alpha * np.asarray(force, dtype=float) ** force_exponent \
        * np.asarray(links, dtype=float) ** links_exponent
    return out


def contour_factor_km(length_difference: ArrayLike,
                      span_deformation: ArrayLike) -> NDArray[np.float64]:
    """Contour factor K_m = 1 + 2Δ_y / (|ΔL₃| + 2Δ_y).

    K_m = 2 with no length difference, 1.5 when |ΔL₃| = 2Δ_y, → 1 as |ΔL₃| → ∞. Read as
    linear load sharing: it is F_II/F_I + 1 with the slacker contour stretched by 2Δ_y and
    the tighter by |ΔL₃| + 2Δ_y (see :func:`contour_factor_compatibility`).

    Parameters
    ----------
    length_difference : float or array_like
        ΔL₃ [m] (sign ignored).
    span_deformation : float or array_like
        Δ_y [m].

    Returns
    -------
    numpy.ndarray
        K_m [-].

    References
    ----------
    [Lyashuk, eq. 16].
    """
    d = np.abs(np.asarray(length_difference, dtype=float))
    two_dy = 2.0 * np.asarray(span_deformation, dtype=float)
    km: NDArray[np.float64] = 1.0 + two_dy / (d + two_dy)
    return km


def allowable_pressure_multicontour(allowable_pressure: ArrayLike,
                                    contour_factor: ArrayLike) -> NDArray[np.float64]:
    """Allowable pressure of a multi-contour drive [p₀]_m = [p₀]·K_m.

    Parameters
    ----------
    allowable_pressure : float or array_like
        [p₀] of one contour [Pa].
    contour_factor : float or array_like
        K_m [-].

    Returns
    -------
    numpy.ndarray
        [p₀]_m [Pa].

    References
    ----------
    [Lyashuk, eq. 15 and 17].
    """
    out: NDArray[np.float64] = np.asarray(allowable_pressure, dtype=float) * np.asarray(
        contour_factor, dtype=float)
    return out


@shared_parameters
def contour_factor_at_risk(c4: float, max_clearance: float, span_deformation: float,
                           risk: float = 0.05) -> float:
    """K_m at a risk level: eq. 16 at the (1 − risk) quantile of |ΔL₃|.

    Parameters
    ----------
    %(c4)s
    %(max_clearance)s
    span_deformation : float
        Δ_y [m].
    risk : float
        Probability that the real K_m is lower [-] (default 5 %, the paper's).

    Returns
    -------
    float
        K_m [-].

    References
    ----------
    [Lyashuk, eq. 16–18].
    """
    if not 0.0 < risk < 1.0:
        raise DesignError("risk", f"must be between 0 and 1, got {risk!r}")
    check_positive("span_deformation", span_deformation)
    sigma = length_difference_stats(c4, max_clearance).sigma
    return float(contour_factor_km(half_normal_quantile(sigma, 1.0 - risk), span_deformation))


@dataclass(frozen=True, slots=True)
class ContourSharingResult:
    """How m parallel contours share a load (compatibility of deformations).

    Parameters
    ----------
    extra_lengths : tuple of float
        s_j, slack of each contour before it takes load [m].
    forces : tuple of float
        F_j [N].
    deformation : float
        Stretch of the tightest contour δ − min s [m].
    shares : tuple of float
        F_j / F [-].
    max_share : float
        Largest share [-].
    effective_contours : float
        F / max F_j [-] (= m when all are equal).
    """

    extra_lengths: tuple[float, ...]
    forces: tuple[float, ...]
    deformation: float
    shares: tuple[float, ...]
    max_share: float
    effective_contours: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm)."""
        return {"extra_lengths_mm": [s * 1e3 for s in self.extra_lengths],
                "forces_n": list(self.forces), "deformation_mm": self.deformation * 1e3,
                "shares": list(self.shares), "max_share": self.max_share,
                "effective_contours": self.effective_contours}


def load_sharing(extra_lengths: ArrayLike, total_force: float,
                 stiffness: ArrayLike) -> ContourSharingResult:
    """Forces in m parallel contours with slacks s_j under a total force F (linear springs).

    F_j = k_j·max(0, δ − s_j), Σ F_j = F, solved exactly: with the contours sorted by s, the
    n tightest carry load and δ = (F + Σ k_j s_j)/Σ k_j over them, n the first count for which
    δ ≤ s_(n+1).

    Parameters
    ----------
    extra_lengths : float or array_like
        s_j [m].
    total_force : float
        F [N].
    stiffness : float or array_like
        k_j [N/m], one value or one per contour.

    Returns
    -------
    ContourSharingResult
        Forces and shares.

    References
    ----------
    [Reshetov1974] (compatibility of deformations of statically indeterminate parallel
    members).
    """
    s = np.asarray(extra_lengths, dtype=float).ravel()
    if not 1 <= s.size <= MAX_CONTOURS or not np.all(np.isfinite(s)):
        raise DesignError("extra_lengths", f"must be 1 to {MAX_CONTOURS} finite lengths")
    check_positive("total_force", total_force)
    k = np.broadcast_to(np.asarray(stiffness, dtype=float), s.shape)
    if np.any(~np.isfinite(k) | (k <= 0)):
        raise DesignError("stiffness", "must be positive")
    order = np.argsort(s, kind="stable")
    s_sorted, k_sorted = s[order], k[order]
    delta = s_sorted[0]
    for n in range(1, s.size + 1):
        delta = (total_force + np.dot(k_sorted[:n], s_sorted[:n])) / k_sorted[:n].sum()
        if n == s.size or delta <= s_sorted[n]:
            break
    forces = k * np.maximum(0.0, delta - s)
    shares = forces / total_force
    return ContourSharingResult(
        extra_lengths=tuple(s.tolist()), forces=tuple(forces.tolist()),
        deformation=float(delta - s.min()), shares=tuple(shares.tolist()),
        max_share=float(shares.max()), effective_contours=float(1.0 / shares.max()),
    )


def contour_factor_compatibility(extra_lengths: ArrayLike, allowable_deformation: ArrayLike,
                                 deformation_exponent: float = 1.0) -> NDArray[np.float64]:
    """Capacity factor K = Σ F_j / F_a of m contours when the most-loaded one is at F_a [–].

    The tightest contour is stretched by its allowable Δ_a (the deformation at the allowable
    force F_a); contour j, s_j − min s longer, is stretched by Δ_a − (s_j − min s) if positive.
    With Δ = α·F^x (eq. 18) the force ratio is (Δ/Δ_a)^(1/x). For m = 2, x = 1:
    K = max(1, 2 − |ΔL₃|/Δ_a); the paper's eq. 16 is this K with Δ_a = |ΔL₃| + 2Δ_y, and
    agrees with it to first order in |ΔL₃| when Δ_a = 2Δ_y.

    Parameters
    ----------
    extra_lengths : array_like
        s, shape (..., m) [m].
    allowable_deformation : float or array_like
        Δ_a [m], broadcast over the leading axes.
    deformation_exponent : float
        x [-].

    Returns
    -------
    numpy.ndarray
        K [-], shape (...).

    References
    ----------
    [Lyashuk, eq. 16 and 18]; [Reshetov1974].
    """
    if not deformation_exponent > 0:
        raise DesignError("deformation_exponent", f"must be positive, got {deformation_exponent!r}")
    s = np.asarray(extra_lengths, dtype=float)
    slack = s - s.min(axis=-1, keepdims=True)
    limit = np.asarray(allowable_deformation, dtype=float)[..., None]
    ratio = np.clip(1.0 - slack / limit, 0.0, None)
    k: NDArray[np.float64] = np.sum(ratio ** (1.0 / deformation_exponent), axis=-1)
    return k


@shared_parameters
@dataclass(frozen=True, slots=True)
class LoadSharingSimulation:
    """Monte-Carlo of m contours with random keyed-joint clearances, at capacity load.

    Parameters
    ----------
    contours : int
        m [-].
    samples : int
        n [-].
    %(risk)s
    km_mean, km_at_risk : float
        Mean and risk-quantile (lower tail) of K, the effective number of contours [-].
    max_share_mean, max_share_at_risk : float
        Mean and (1 − risk) quantile of the most-loaded contour's share (= 1/K) [-].
    km_percentiles : tuple of float
        K at 1, 5, 50, 95, 99 % [-].
    """

    contours: int
    samples: int
    risk: float
    km_mean: float
    km_at_risk: float
    max_share_mean: float
    max_share_at_risk: float
    km_percentiles: tuple[float, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"contours": self.contours, "samples": self.samples, "risk": self.risk,
                "km_mean": self.km_mean, "km_at_risk": self.km_at_risk,
                "max_share_mean": self.max_share_mean,
                "max_share_at_risk": self.max_share_at_risk,
                "km_percentiles": dict(zip(("p1", "p5", "p50", "p95", "p99"),
                                           self.km_percentiles, strict=True))}


@shared_parameters
def simulate_load_sharing(contours: int, n: int, rng: np.random.Generator | int | None = None,
                          *, c4: float, max_clearance: float, allowable_deformation: float,
                          deformation_exponent: float = 1.0, risk: float = 0.05,
                          truncated: bool = False) -> LoadSharingSimulation:
    """K (effective number of contours) over random clearances, m contours on two shafts.

    Each contour j has a keyed driving and driven sprocket with independent clearances
    (eq. 7, all joints clear as in the eq. 13 model), so its slack is s_j = C₄(z_1j + z_2j);
    K per sample from :func:`contour_factor_compatibility`. For m = 2 and x = 1 the result
    is K = max(1, 2 − |ΔL₃|/Δ_a) with |ΔL₃| half-normal (eq. 14).

    Parameters
    ----------
    contours : int
        m, 2 to 24 [-].
    %(samples_rng)s
    %(c4)s
    %(max_clearance)s
    allowable_deformation : float
        Δ_a [m].
    deformation_exponent : float
        x [-].
    %(risk)s
    truncated : bool
        Clearances restricted to [0, z_max].

    Returns
    -------
    LoadSharingSimulation
        K and the largest share at the risk level.

    References
    ----------
    [Lyashuk, eq. 7, 14, 16].
    """
    if not isinstance(contours, int) or not 2 <= contours <= MAX_CONTOURS:
        raise DesignError("contours", f"must be a whole number 2 to {MAX_CONTOURS}, "
                                      f"got {contours!r}")
    if not isinstance(n, int) or n < 1:
        raise DesignError("n", f"must be a positive whole number, got {n!r}")
    if not 0.0 < risk < 1.0:
        raise DesignError("risk", f"must be between 0 and 1, got {risk!r}")
    check_positive("c4", c4)
    check_positive("max_clearance", max_clearance)
    check_positive("allowable_deformation", allowable_deformation)
    gen = np.random.default_rng(rng)
    z = sample_clearances((n, contours, 2), gen, max_clearance, truncated=truncated)
    km = contour_factor_compatibility(c4 * z.sum(axis=-1), allowable_deformation,
                                      deformation_exponent)
    share = 1.0 / km
    return LoadSharingSimulation(
        contours=contours, samples=n, risk=risk, km_mean=float(km.mean()),
        km_at_risk=float(np.quantile(km, risk)), max_share_mean=float(share.mean()),
        max_share_at_risk=float(np.quantile(share, 1.0 - risk)),
        km_percentiles=tuple(float(v) for v in np.quantile(km, [0.01, 0.05, 0.5, 0.95, 0.99])),
    )


@shared_parameters
def contour_factor_linear_at_risk(c4: float, max_clearance: float,
                                  allowable_deformation: float, risk: float = 0.05) -> float:
    """K = max(1, 2 − q/Δ_a) for m = 2, q the (1 − risk) quantile of |ΔL₃| (eq. 14).

    The compatibility-of-deformations counterpart of :func:`contour_factor_at_risk`.

    Parameters
    ----------
    %(c4)s
    %(max_clearance)s
    allowable_deformation : float
        Δ_a [m].
    %(risk)s

    Returns
    -------
    float
        K [-].

    References
    ----------
    [Lyashuk, eq. 14].
    """
    if not 0.0 < risk < 1.0:
        raise DesignError("risk", f"must be between 0 and 1, got {risk!r}")
    check_positive("allowable_deformation", allowable_deformation)
    q = half_normal_quantile(length_difference_stats(c4, max_clearance).sigma, 1.0 - risk)
    return max(1.0, 2.0 - q / allowable_deformation)
