"""Transverse vibration of a chain span as an axially moving string.

A span of length L [m], tension T [N] and mass per metre q [kg/m] moving along its axis at
the chain speed v [m/s] has the natural frequencies of the travelling string ([Mote1965],
[WickertMote1990])::

    f_n = n / (2L) · c · (1 − v²/c²),   c² = T / q,   n = 1, 2, …

— at v = 0 the fixed–fixed taut string, f_n = n c / (2L). T is the actual span tension
(including the centrifugal part q v²); at v = c the span loses its stiffness (divergence).

Parametric resonance: a tension pulsating at the tooth frequency f_z,
T(t) = T (1 + μ cos 2π f_z t), makes the span a Mathieu system; the principal instability
zone lies near f_z = 2 f_1 (more generally f_z ≈ 2 f_n / k), of half-width μ/4 in
f_z/(2 f_n) to first order ([Bolotin1964, ch. 1]). [MultimassChainDrives] names the
parametric vibrations of the tight span among the phenomena to check.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError

__all__ = ["parametric_resonance_frequency", "parametric_zone", "span_transverse_frequencies",
           "transverse_wave_speed"]


def transverse_wave_speed(tension: ArrayLike, mass_per_length: ArrayLike) -> NDArray[np.float64]:
    """Transverse wave speed c = sqrt(T / q) [m/s] of a taut span (a slack span, T ≤ 0: 0).

    Parameters
    ----------
    tension : array_like
        Span tension T [N].
    mass_per_length : array_like
        Chain mass per unit length q [kg/m], positive.

    Returns
    -------
    ndarray
        c [m/s], the broadcast shape of the inputs.

    Raises
    ------
    DesignError
        ``mass_per_length`` not positive.

    References
    ----------
    [WickertMote1990] (the taut-string wave equation).
    """
    t = np.asarray(tension, dtype=float)
    q = np.asarray(mass_per_length, dtype=float)
    if np.any(q <= 0):
        raise DesignError("mass_per_length", "must be positive")
    return np.asarray(np.sqrt(np.maximum(t, 0.0) / q), dtype=np.float64)


def span_transverse_frequencies(length: ArrayLike, tension: ArrayLike, mass_per_length: ArrayLike,
                                speed: ArrayLike = 0.0, modes: int = 3) -> NDArray[np.float64]:
    """Transverse natural frequencies f_n [Hz] of spans as axially moving strings.

    f_n = n/(2L)·sqrt(T/q)·(1 − v²/c²), c² = T/q. A slack span (T ≤ 0) or one at or above
    the critical speed (v ≥ c) gives 0.

    Parameters
    ----------
    length : array_like
        Span length L [m], positive.
    tension : array_like
        Span tension T [N] (including the centrifugal part q v²).
    mass_per_length : array_like
        Chain mass per unit length q [kg/m].
    speed : array_like
        Chain speed v [m/s].
    modes : int
        How many modes n = 1 … ``modes`` [-].

    Returns
    -------
    ndarray
        f_n [Hz]: the broadcast shape of the inputs plus a last axis of length ``modes``.

    Raises
    ------
    DesignError
        ``modes`` below 1 or a span length that is not positive.

    References
    ----------
    [Mote1965], [WickertMote1990].
    """
    if modes < 1:
        raise DesignError("modes", f"must be at least 1, got {modes!r}")
    L = np.asarray(length, dtype=float)
    if np.any(L <= 0):
        raise DesignError("length", "span lengths must be positive")
    c = transverse_wave_speed(tension, mass_per_length)
    v = np.asarray(speed, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.where(c > 0, 1.0 - (v / np.where(c > 0, c, 1.0)) ** 2, 0.0)
    f1 = np.maximum(factor, 0.0) * c / (2.0 * L)
    n = np.arange(1, modes + 1)
    return np.asarray(f1)[..., None] * n


def parametric_resonance_frequency(transverse_frequency: ArrayLike,
                                   order: int = 1) -> NDArray[np.float64]:
    """Tooth (tension pulsation) frequency [Hz] of the k-th parametric zone of a span mode:
    f_z = 2 f_n / k (k = 1 is the principal zone, f_z ≈ 2 f_transverse).

    Parameters
    ----------
    transverse_frequency : array_like
        Transverse natural frequency f_n of the span mode [Hz].
    order : int
        Order k of the zone [-], at least 1.

    Returns
    -------
    ndarray
        f_z [Hz].

    Raises
    ------
    DesignError
        ``order`` below 1.

    References
    ----------
    [Bolotin1964, ch. 1] (Mathieu equation).
    """
    if order < 1:
        raise DesignError("order", f"must be at least 1, got {order!r}")
    return 2.0 * np.asarray(transverse_frequency, dtype=float) / order


def parametric_zone(transverse_frequency: ArrayLike,
                    modulation: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Bounds [Hz] of the principal parametric instability zone of a span mode.

    First-order boundaries of the principal Mathieu zone: f_z = 2 f_n (1 ± μ/4); valid for
    small μ.

    Parameters
    ----------
    transverse_frequency : array_like
        Transverse natural frequency f_n [Hz].
    modulation : array_like
        μ = ΔT / T, the relative amplitude of the tension pulsation [-]
        (T(t) = T(1 + μ cos Ωt), so ω² ∝ T is modulated by μ).

    Returns
    -------
    low, high : ndarray
        The tooth frequencies bounding the zone [Hz].

    References
    ----------
    [Bolotin1964, ch. 1].
    """
    f = np.asarray(transverse_frequency, dtype=float)
    mu = np.asarray(modulation, dtype=float)
    return 2.0 * f * (1.0 - mu / 4.0), 2.0 * f * (1.0 + mu / 4.0)
