"""What wear elongation does to a roller chain on its sprockets and in its slack span.

A roller chain elongates by wear in the pin–bush joints; its plates do not stretch. The
worn pitch p' = p(1 + ε) no longer fits the sprocket's pitch polygon: the rollers close a
polygon of z sides p' round a sprocket of z teeth by seating higher on the tooth flanks, so
the pitch radius of the chain on the sprocket grows to

    R' = p(1 + ε) / (2 sin(π/z))                                                  (1)

(the pitch diameter of [ISO606] / [GOST591] written with the worn pitch), the rollers rise by
ΔR = ε·p / (2 sin(π/z)) and the large sprocket, where ΔR is largest, limits how far a chain
may wear before it climbs over the teeth. Chain makers turn this into the replacement rule
[DiamondChainWear], [RegalChainWear]: 3 % elongation, but at most 200/z % for a large sprocket
of z teeth (ΔR then reaches p/(z sin(π/z)) ≈ p/π, the height of an ISO 606 tooth tip above the
pitch circle), and about 1.5 % for fixed centre distances, chains running in parallel or
smooth running.

Where no take-up follows the chain, the extra length ε·L collects in the slack span. A span of
horizontal chord ℓ and arc length ℓ + ΔL hangs as a catenary y = a(cosh(x/a) − 1) with

    ℓ + ΔL = 2a·sinh(ℓ/(2a)),   sag f = a(cosh(ℓ/(2a)) − 1),   H = w·a           (2)

[Irvine1981, ch. 1] (w weight per length, H the horizontal pull); for f ≪ ℓ it tends to the
shallow parabola of :mod:`chaindrive.geometry.sag`, ΔL = 8f²/(3ℓ), H = wℓ²/(8f).

Where a take-up follows the chain, it absorbs the growth N·p·ε of a chain of N links until
it has taken up its capacity c; then the chain is shortened by two links, as a take-up must
allow [DiamondChainTension], and the take-up goes back. After k such shortenings the chain
has N − 2k links of the worn pitch and the take-up holds

    ΔL_k = (N − 2k)·p(1 + ε) − N·p ≤ c,   k = max(0, ⌈(N·ε − c/p) / (2(1 + ε))⌉)     (3)

(the least k that keeps ΔL_k within the capacity).

References
----------
[ISO606], [GOST591], [DiamondChainWear], [RegalChainWear], [Irvine1981],
[DiamondChainTension]
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import bracketed_root
from chaindrive.geometry.sprocket import iso606_tip_diameter_range, pitch_radius

__all__ = [
    "ELONGATION_LIMIT",
    "LARGE_SPROCKET_RULE",
    "RESTRICTED_ELONGATION_LIMIT",
    "allowable_elongation",
    "catenary_excess_length",
    "catenary_parameter",
    "catenary_sag",
    "elongated_pitch_radius",
    "equivalent_sag_ratio",
    "iso606_tip_height",
    "links_removed",
    "roller_lift",
]

#: Replacement elongation of a roller chain for most industrial drives [–]
#: [DiamondChainWear], [RegalChainWear].
ELONGATION_LIMIT = 0.03
#: The large-sprocket rule: at most 200/z % of elongation, i.e. 2/z as a fraction [–]
#: [DiamondChainWear] (3 % holds up to 67 teeth), [RegalChainWear] (over 66 teeth).
LARGE_SPROCKET_RULE = 2.0
#: Elongation limit for fixed centre distances, chains in parallel and smooth running [–]
#: [DiamondChainWear] ("approximately 1.5 %").
RESTRICTED_ELONGATION_LIMIT = 0.015


def allowable_elongation(largest_teeth: int, *, fixed_centres: bool = False,
                         parallel: bool = False, smooth: bool = False) -> float:
    """The wear elongation at which a chain is replaced [–].

    ε_allow = min(3 %, 200/z %), and at most 1.5 % for fixed centres, parallel chains or
    smooth running [DiamondChainWear], [RegalChainWear].

    Parameters
    ----------
    largest_teeth : int
        Teeth z of the largest sprocket the chain runs on [–].
    fixed_centres : bool
        No take-up follows the chain (the slack grows with the wear).
    parallel : bool
        Several chains (contours) share the load side by side.
    smooth : bool
        The drive must run smoothly.

    Returns
    -------
    float
        Allowable elongation as a fraction of the pitch [–].

    References
    ----------
    [DiamondChainWear], [RegalChainWear]
    """
    if not (isinstance(largest_teeth, int | np.integer) and largest_teeth >= 1):
        raise DesignError("teeth", f"must be a positive whole number, got {largest_teeth!r}")
    limit = min(ELONGATION_LIMIT, LARGE_SPROCKET_RULE / float(largest_teeth))
    if fixed_centres or parallel or smooth:
        limit = min(limit, RESTRICTED_ELONGATION_LIMIT)
    return limit


@shared_parameters
def elongated_pitch_radius(pitch: ArrayLike, teeth: ArrayLike,
                           elongation: ArrayLike) -> NDArray[np.float64]:
    """Pitch radius R' = p(1 + ε)/(2 sin(π/z)) of a worn chain on a sprocket [m] (eq. 1), p
    the sprocket's nominal pitch.

    %(worn_pitch_teeth_returns)s
        R' [m].

    References
    ----------
    [ISO606] (pitch diameter d = p/sin(π/z)), [GOST591]
    """
    eps = np.asarray(elongation, dtype=float)
    return np.asarray(pitch_radius(pitch, teeth), dtype=float) * (1.0 + eps)


@shared_parameters
def roller_lift(pitch: ArrayLike, teeth: ArrayLike, elongation: ArrayLike) -> NDArray[np.float64]:
    """Rise ΔR = ε·p/(2 sin(π/z)) of the roller centres of a worn chain on a sprocket [m].

    %(worn_pitch_teeth_returns)s
        ΔR [m] (eq. 1 less the nominal radius).

    References
    ----------
    [ISO606], [GOST591]
    """
    eps = np.asarray(elongation, dtype=float)
    out: NDArray[np.float64] = np.asarray(pitch_radius(pitch, teeth), dtype=float) * eps
    return out


def iso606_tip_height(pitch: ArrayLike, teeth: ArrayLike,
                      roller_diameter: ArrayLike) -> NDArray[np.float64]:
    """Height of the tooth tip above the pitch circle, (da,max − d)/2 = 0.625p − 0.5d1 [m],
    for the largest ISO 606 tip diameter.

    Parameters
    ----------
    pitch : array_like
        Chain pitch p [m].
    teeth : array_like
        Teeth z [–].
    roller_diameter : array_like
        Roller diameter d1 [m].

    Returns
    -------
    ndarray
        Tip height [m].

    References
    ----------
    [ISO606] (da,max = d + 1.25p − d1)
    """
    _, tip_max = iso606_tip_diameter_range(pitch, teeth, roller_diameter)
    d = 2.0 * np.asarray(pitch_radius(pitch, teeth), dtype=float)
    return 0.5 * (np.asarray(tip_max, dtype=float) - d)


def catenary_parameter(span: float, extra_length: float) -> float:
    """Catenary parameter a = H/w [m] of a span of chord ℓ carrying the extra length ΔL
    (eq. 2: ℓ + ΔL = 2a·sinh(ℓ/(2a))).

    Solved for x = ℓ/(2a) from sinh(x)/x = 1 + ΔL/ℓ by bracketed regula falsi, started from
    the shallow-parabola root x₀ = √(6ΔL/ℓ).

    Parameters
    ----------
    span : float
        Horizontal chord ℓ of the span [m].
    extra_length : float
        Chain length beyond the chord ΔL > 0 [m].

    Returns
    -------
    float
        a [m].

    References
    ----------
    [Irvine1981, ch. 1]
    """
    if not (math.isfinite(span) and span > 0):
        raise DesignError("span", f"must be a positive length, got {span!r} m")
    if not (math.isfinite(extra_length) and extra_length > 0):
        raise DesignError("extra_length", f"must be a positive length, got {extra_length!r} m")
    ratio = 1.0 + extra_length / span

    def excess(x: float) -> float:
        return math.sinh(x) / x - ratio

    lo = 0.5 * math.sqrt(6.0 * (ratio - 1.0))
    hi = 2.0 * lo
    while excess(hi) < 0.0:
        lo, hi = hi, 2.0 * hi
    x = bracketed_root(excess, lo, hi, excess(lo), excess(hi), xtol=1e-14 * hi)
    return span / (2.0 * x)


def catenary_excess_length(span: float, sag_ratio: float) -> float:
    """Chain length beyond the chord ΔL = 2a·sinh(ℓ/(2a)) − ℓ [m] of the catenary whose
    horizontal pull the shallow-parabola model gives for the sag ratio s, a = ℓ/(8s) (eq. 2;
    the inverse of :func:`equivalent_sag_ratio`).

    Parameters
    ----------
    span : float
        Horizontal chord ℓ [m].
    sag_ratio : float
        Sag ratio s > 0 of the parabola model [–].

    Returns
    -------
    float
        ΔL [m].

    References
    ----------
    [Irvine1981, ch. 1]
    """
    if not (math.isfinite(sag_ratio) and sag_ratio > 0):
        raise DesignError("sag_ratio", f"must be positive, got {sag_ratio!r}")
    a = span / (8.0 * sag_ratio)
    return 2.0 * a * math.sinh(span / (2.0 * a)) - span


def catenary_sag(span: float, extra_length: float) -> float:
    """Mid-span sag f = a(cosh(ℓ/(2a)) − 1) [m] of a span of chord ℓ carrying the extra
    length ΔL (eq. 2).

    Parameters
    ----------
    span : float
        Horizontal chord ℓ [m].
    extra_length : float
        Chain length beyond the chord ΔL [m] (0 or less: a taut span, sag 0).

    Returns
    -------
    float
        f [m].

    References
    ----------
    [Irvine1981, ch. 1]
    """
    if extra_length <= 0.0:
        return 0.0
    a = catenary_parameter(span, extra_length)
    return a * (math.cosh(span / (2.0 * a)) - 1.0)


def equivalent_sag_ratio(span: float, extra_length: float) -> float:
    """The sag ratio s of the shallow-parabola model that gives the catenary's horizontal
    pull: s = ℓ/(8a) [–], so that H = wℓ²/(8sℓ) = w·a (eq. 2).

    This is the ratio the static loads take (:func:`chaindrive.strength.loads.sag_factor`,
    k_f = cos ψ/(8s) + |sin ψ|); for a shallow span it equals f/ℓ.

    Parameters
    ----------
    span : float
        Horizontal chord ℓ [m].
    extra_length : float
        Chain length beyond the chord ΔL > 0 [m].

    Returns
    -------
    float
        s [–].

    References
    ----------
    [Irvine1981, ch. 1]
    """
    return span / (8.0 * catenary_parameter(span, extra_length))


def links_removed(links: int, pitch: float, elongation: float, capacity: float) -> int:
    """How many links a chain with a take-up has lost to shortening by ε (eq. 3): two each
    time the take-up has absorbed its capacity [DiamondChainTension].

    k = max(0, ⌈(N·ε − c/p) / (2(1 + ε))⌉) [–], the least k with
    (N − 2k)·p(1 + ε) − N·p ≤ c.

    Parameters
    ----------
    links : int
        Links N of the chain as installed new [–].
    pitch : float
        Pitch p of the new chain [m].
    elongation : float
        Elongation ε of the chain [–].
    capacity : float
        Chain length c the take-up absorbs before the chain is shortened [m] (> 0).

    Returns
    -------
    int
        Links removed 2k [–].

    References
    ----------
    [DiamondChainTension]
    """
    excess = (links * elongation - capacity / pitch) / (2.0 * (1.0 + elongation))
    return 2 * max(0, math.ceil(excess - 1e-12))
