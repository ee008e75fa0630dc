"""Span tension from a measured transverse frequency (the inverse of the string law).

A span of length L [m], mass per metre q [kg/m] and tension T [N], running at the chain
speed v [m/s], vibrates sideways at the frequencies of the axially moving string
([Mote1965], [WickertMote1990]; the forward law is
:func:`chaindrive.dynamics.transverse.span_transverse_frequencies`, the one place it is
written)::

    f_n = n / (2L) · c · (1 − v²/c²) = n / (2L) · (T − q v²) / sqrt(T q),   c² = T / q

Solved for T: with s = sqrt(T) and a = 2 L f sqrt(q) / n the law reads s² − a s − q v² = 0,
whose positive root gives ::

    T = ((a + sqrt(a² + 4 q v²)) / 2)²

— at v = 0 the taut string, T = 4 L² f² q / n². f_n grows monotonically with T above
T = q v² (the critical tension), so the root is the only tension giving f.

Sag: a span hanging under its own weight is a shallow cable. Its out-of-plane (sideways)
modes and its antisymmetric in-plane modes (even n) keep the string's frequencies; its
symmetric in-plane modes (odd n) are stiffened by the stretch they impose, by an amount set
by Irvine's parameter ([IrvineCaughey1974]; [Irvine1981, ch. 3])::

    λ² = (q g L cos ψ / T)² · L / (T L_e / EA),   L_e = L (1 + 8 (d/L)²),
    d = q g L² cos ψ / (8 T)

and the frequency ω̄ = ω L / sqrt(T/q) of the first symmetric mode is the root of
tan(ω̄/2) = ω̄/2 − (4/λ²)(ω̄/2)³ between π (λ² → 0, the string) and 2.86 π (λ² → ∞,
tan x = x). ψ is the span's inclination, g cos ψ the weight normal to the chord (the
inclined-cable reading of [Irvine1981, ch. 3]), EA the chain's axial stiffness
k_link · p. A chain is stiff axially, so λ² of a sagging chain span is large; whether the
hinges and the sprockets (which are not fixed anchors) let that stiffening develop is not
verified, which is why the tool reads a sideways (out-of-plane) pluck by default and names
the stiffening of an in-plane odd mode next to the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from chaindrive.dynamics.stiffness import GRAVITY
from chaindrive.dynamics.transverse import span_transverse_frequencies
from chaindrive.errors import DesignError

__all__ = ["TensionEstimate", "expected_frequency", "irvine_parameter",
           "span_tension_from_frequency", "string_tension", "symmetric_inplane_ratio"]

#: Relative step of the central differences of the uncertainty propagation [-].
_STEP = 1e-6


def _positive(field: str, value: float, unit: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise DesignError(field, f"must be a positive number of {unit}, got {value!r}")
    return float(value)


def _mode(mode: int) -> int:
    if isinstance(mode, bool) or not isinstance(mode, int) or mode < 1:
        raise DesignError("mode", f"must be a whole number ≥ 1, got {mode!r}")
    return mode


def string_tension(frequency: float, length: float, mass_per_length: float, mode: int = 1,
                   speed: float = 0.0) -> float:
    """Span tension T [N] whose n-th transverse frequency as an axially moving string is f.

    T = ((a + sqrt(a² + 4 q v²)) / 2)², a = 2 L f sqrt(q) / n: the inverse of
    f_n = n/(2L)·(T − q v²)/sqrt(T q) (module docstring); at v = 0, T = 4 L² f² q / n².

    Parameters
    ----------
    frequency : float
        Measured transverse frequency f [Hz], positive.
    length : float
        Span length L [m], positive.
    mass_per_length : float
        Chain mass per metre q [kg/m], positive.
    mode : int
        Mode number n [-] the frequency belongs to, at least 1.
    speed : float
        Chain speed v [m/s] (0: a stationary chain).

    Returns
    -------
    float
        T [N], the actual span tension (its centrifugal part q v² included).

    Raises
    ------
    DesignError
        A frequency, length or mass that is not positive, a mode below 1, a negative speed.

    References
    ----------
    [Mote1965], [WickertMote1990].
    """
    f = _positive("frequency", frequency, "Hz")
    L = _positive("length", length, "m")
    q = _positive("mass_per_length", mass_per_length, "kg/m")
    n = _mode(mode)
    if not (math.isfinite(speed) and speed >= 0):
        raise DesignError("speed", f"must be a number ≥ 0 m/s, got {speed!r}")
    a = 2.0 * L * f * math.sqrt(q) / n
    s = 0.5 * (a + math.sqrt(a * a + 4.0 * q * speed * speed))
    return s * s


def irvine_parameter(tension: float, length: float, mass_per_length: float,
                     axial_stiffness: float, inclination: float = 0.0,
                     gravity: float = GRAVITY) -> float:
    """Irvine's parameter λ² [-] of a span hanging under its own weight.

    λ² = (q g L cos ψ / T)² · L / (T L_e / EA), L_e = L (1 + 8 (d/L)²),
    d = q g L² cos ψ / (8 T).

    Parameters
    ----------
    tension : float
        Span tension T [N] (the cable's horizontal component for a level span), positive.
    length : float
        Span (chord) length L [m].
    mass_per_length : float
        q [kg/m].
    axial_stiffness : float
        EA of the chain [N] (k_link · p).
    inclination : float
        ψ of the chord to the horizontal [rad].
    gravity : float
        g [m/s²].

    Returns
    -------
    float
        λ² [-]: ≪ 1 a taut string; 4π² the cross-over where the first symmetric in-plane
        mode reaches the second (antisymmetric) one.

    References
    ----------
    [IrvineCaughey1974]; [Irvine1981, ch. 3].
    """
    T = _positive("tension", tension, "N")
    w = mass_per_length * gravity * math.cos(inclination)
    ratio = w * length / T
    sag_over_l = ratio / 8.0
    effective = length * (1.0 + 8.0 * sag_over_l ** 2)
    return ratio ** 2 * length * axial_stiffness / (T * effective)


def symmetric_inplane_ratio(lambda2: float) -> float:
    """Ratio ω̄₁/π [-] of the first symmetric in-plane frequency of a sagging span to the
    taut string's: the root ω̄ of tan(ω̄/2) = ω̄/2 − (4/λ²)(ω̄/2)³ in (π, 3π), over π.

    Parameters
    ----------
    lambda2 : float
        Irvine's λ² [-], ≥ 0 (0: the taut string, ratio 1).

    Returns
    -------
    float
        From 1 (λ² = 0) through 2 (λ² = 4π²) to 2.861 (λ² → ∞, tan x = x).

    References
    ----------
    [IrvineCaughey1974]; [Irvine1981, ch. 3].
    """
    if not (math.isfinite(lambda2) and lambda2 >= 0):
        raise DesignError("lambda2", f"must be a number ≥ 0, got {lambda2!r}")
    if lambda2 == 0.0:
        return 1.0
    k = 4.0 / lambda2
    eps = 1e-12
    x = brentq(lambda x: math.tan(x) - x + k * x ** 3, 0.5 * math.pi + eps,
               1.5 * math.pi - eps, xtol=1e-14)
    return 2.0 * float(x) / math.pi


@dataclass(frozen=True, slots=True)
class TensionEstimate:
    """Span tension read from a measured transverse frequency, with its uncertainty.

    Parameters
    ----------
    tension : float
        T [N], the actual span tension (centrifugal part included when running).
    std : float
        Its standard uncertainty u(T) [N] (first-order propagation of the input
        uncertainties, independent inputs).
    contributions : dict of str to float
        u(T) [N] from each input alone (length, mass per metre, frequency, speed).
    frequency, length, mass_per_length, speed : float
        The inputs f [Hz], L [m], q [kg/m], v [m/s].
    mode : int
        n [-].
    centrifugal : float
        q v² [N] (0 for a stationary chain).
    sag : float
        Mid-span sag d = q g L² cos ψ / (8 T) [m] at the estimated tension.
    lambda2 : float | None
        Irvine's λ² [-] at the estimated tension (None: the chain's EA not given).
    inplane_ratio : float | None
        [-] How many times higher an in-plane pluck of an odd mode would ring than the sideways
        one, :func:`symmetric_inplane_ratio` (None with ``lambda2``).
    """

    tension: float
    std: float
    contributions: dict[str, float]
    frequency: float
    length: float
    mass_per_length: float
    speed: float
    mode: int
    centrifugal: float
    sag: float
    lambda2: float | None
    inplane_ratio: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {
            "tension_n": self.tension,
            "tension_std_n": self.std,
            "tension_std_by_input_n": dict(self.contributions),
            "frequency_hz": self.frequency,
            "mode": self.mode,
            "length_m": self.length,
            "mass_per_length_kg_m": self.mass_per_length,
            "speed_m_s": self.speed,
            "centrifugal_tension_n": self.centrifugal,
            "sag_m": self.sag,
            "irvine_lambda2": self.lambda2,
            "inplane_odd_mode_ratio": self.inplane_ratio,
        }


def span_tension_from_frequency(frequency: float, length: float, mass_per_length: float, *,
                                mode: int = 1, speed: float = 0.0,
                                frequency_std: float = 0.0, length_std: float = 0.0,
                                mass_std: float = 0.0, speed_std: float = 0.0,
                                axial_stiffness: float | None = None,
                                inclination: float = 0.0) -> TensionEstimate:
    """Span tension from its measured transverse frequency, with its uncertainty.

    T from :func:`string_tension`; u(T)² = Σ (∂T/∂x · u(x))² over the inputs x = f, L, q, v
    (first-order propagation, independent inputs [JCGM100, §5.1]); the partial derivatives by
    central differences of the closed form. With the chain's EA, Irvine's λ² and the
    stiffening of an in-plane odd mode at the estimated tension are given beside it.

    Parameters
    ----------
    frequency : float
        Measured frequency f [Hz] of a sideways (out-of-plane) pluck or of an even in-plane
        mode.
    length : float
        Span length L [m].
    mass_per_length : float
        q [kg/m].
    mode : int
        n [-].
    speed : float
        Chain speed v [m/s] (0: stationary).
    frequency_std, length_std, mass_std, speed_std : float
        Standard uncertainties u(f) [Hz], u(L) [m], u(q) [kg/m], u(v) [m/s], ≥ 0.
    axial_stiffness : float | None
        The chain's EA [N] for λ² (None: not computed).
    inclination : float
        ψ [rad] of the span.

    Returns
    -------
    TensionEstimate

    Raises
    ------
    DesignError
        An input out of its range (named).

    References
    ----------
    [Mote1965], [WickertMote1990], [IrvineCaughey1974], [JCGM100].
    """
    T = string_tension(frequency, length, mass_per_length, mode, speed)
    values = {"frequency": frequency, "length": length, "mass_per_length": mass_per_length,
              "speed": speed}
    stds = {"frequency": frequency_std, "length": length_std, "mass_per_length": mass_std,
            "speed": speed_std}
    contributions: dict[str, float] = {}
    for name, u in stds.items():
        if not (math.isfinite(u) and u >= 0):
            raise DesignError(f"{name}_std", f"must be a number ≥ 0, got {u!r}")
        x = values[name]
        h = _STEP * max(abs(x), 1.0)
        lo = dict(values, **{name: max(x - h, 0.0)})
        hi = dict(values, **{name: x + h})
        dT = (string_tension(hi["frequency"], hi["length"], hi["mass_per_length"], mode,
                             hi["speed"])
              - string_tension(lo["frequency"], lo["length"], lo["mass_per_length"], mode,
                               lo["speed"])) / (hi[name] - lo[name])
        contributions[name] = abs(dT) * u
    std = math.sqrt(sum(c * c for c in contributions.values()))
    w = mass_per_length * GRAVITY * math.cos(inclination)
    lam = ratio = None
    if axial_stiffness is not None:
        lam = irvine_parameter(T, length, mass_per_length,
                               _positive("axial_stiffness", axial_stiffness, "N"), inclination)
        ratio = symmetric_inplane_ratio(lam)
    return TensionEstimate(T, std, contributions, frequency, length, mass_per_length, speed,
                           mode, mass_per_length * speed ** 2, w * length ** 2 / (8.0 * T),
                           lam, ratio)


def expected_frequency(tension: float, length: float, mass_per_length: float, mode: int = 1,
                       speed: float = 0.0) -> float:
    """The n-th transverse frequency [Hz] a span at tension T rings at (what a fitter aims
    for): :func:`chaindrive.dynamics.transverse.span_transverse_frequencies`, one span.

    Parameters
    ----------
    tension : float
        T [N].
    length : float
        L [m].
    mass_per_length : float
        q [kg/m].
    mode : int
        n [-].
    speed : float
        v [m/s].

    Returns
    -------
    float
        f_n [Hz] (0 for a slack span or one at or above its critical speed).

    References
    ----------
    [Mote1965], [WickertMote1990].
    """
    n = _mode(mode)
    return float(np.asarray(span_transverse_frequencies(length, tension, mass_per_length,
                                                        speed, modes=n))[..., n - 1])
