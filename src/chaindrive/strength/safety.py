"""Safety factors of the chain: static (Russian method) and the two-stage dynamic check.

Static: s = Q/(kд·F_t + F_0 + F_v) ≥ [s] (Q breaking load of the chain) [ChainDesignRU, §9],
[s] from Table 9A by pitch and speed
(:func:`chaindrive.strength.ke_method.allowable_safety_factor`).

Dynamic [MultimassChainDrives, §3.6]: the chain is chosen for life, so the general
machine-building value [k] = 2.5 is used in two stages — start-up k₁ = Q/F₁max, steady state
k₂ = Q/(F_R + F₂) and, at resonance, k₂min = Q/(F_R + F₂max). The forces come from the
dynamic analyses; these functions only take them as input, and the checks of the analysis
(:mod:`chaindrive.dynamics.checks`) hold them to [k].

Polymeric chains: Q must come from the material strength (catalogue ``breaking_load`` of the
polymer chain, or tensile strength × net section); the steel tables [p], [s], n1 max and [i]
do not apply to them, and the wear-life model is for steel bush–pin joints
(see docs/strength.md).
"""

from __future__ import annotations

from chaindrive.checks import ALLOWABLE_DYNAMIC_SAFETY

__all__ = ["ALLOWABLE_DYNAMIC_SAFETY", "startup_safety_factor", "static_safety_factor",
           "steady_safety_factor"]


def static_safety_factor(breaking_load: float, peripheral_force: float, sag_tension: float,
                         centrifugal_tension: float, dynamic_factor: float = 1.0) -> float:
    """Static safety factor s = Q/(kд·F_t + F_0 + F_v).

    Parameters
    ----------
    breaking_load : float
        Breaking load of the chain Q [N].
    peripheral_force : float
        F_t [N].
    sag_tension : float
        F_0 [N].
    centrifugal_tension : float
        F_v [N].
    dynamic_factor : float
        kд [-] (1 in the course programs of [ChainDesignRU]).

    Returns
    -------
    float
        s [-].

    References
    ----------
    [ChainDesignRU, §9].
    """
    return breaking_load / (dynamic_factor * peripheral_force + sag_tension + centrifugal_tension)


def startup_safety_factor(breaking_load: float, max_startup_force: float) -> float:
    """Dynamic safety factor at start-up k₁ = Q/F₁max.

    Parameters
    ----------
    breaking_load : float
        Breaking load of the chain Q [N].
    max_startup_force : float
        F₁max, the largest branch force of the start-up transient [N].

    Returns
    -------
    float
        k₁ [-].

    References
    ----------
    [MultimassChainDrives, §3.6].
    """
    return breaking_load / max_startup_force


def steady_safety_factor(breaking_load: float, operating_force: float,
                         dynamic_force: float) -> float:
    """Dynamic safety factor in steady motion k₂ = Q/(F_R + F₂) (k₂min with F₂max).

    Parameters
    ----------
    breaking_load : float
        Breaking load of the chain Q [N].
    operating_force : float
        F_R, the load from the operating conditions [N].
    dynamic_force : float
        F₂ = c·x_A, the amplitude of the dynamic branch force in steady motion [N]; with
        F₂max (at resonance) the result is k₂min.

    Returns
    -------
    float
        k₂ [-].

    References
    ----------
    [MultimassChainDrives, §3.6].
    """
    return breaking_load / (operating_force + dynamic_force)
