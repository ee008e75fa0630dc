"""Safety factors of the chain: static (Russian method) and the seed's two-stage dynamic check.

Static: s = Q/(kд·F_t + F_0 + F_v) ≥ [s] (Q breaking load of the chain; [VN-CODE], [CPP] in
``shared/data/chain_design_method_ru.md`` §9), [s] from Table 9A by pitch and speed
(:func:`chaindrive.strength.ke_method.allowable_safety_factor`).

Dynamic (seed 000 §3.6, ``spec/seed-notes.md`` §2): the chain is chosen for life, so the general
machine-building value [k] = 2.5 is used in two stages — start-up k₁ = Q/F₁max, steady state
k₂ = Q/(F_R + F₂) and, at resonance, k₂min = Q/(F_R + F₂max). The forces come from the
dynamic analyses; these functions only take them as input.

Polymeric chains: Q must come from the material strength (catalogue ``breaking_load`` of the
polymer chain, or tensile strength × net section); the steel tables [p], [s], n1 max and [i]
do not apply to them, and the wear-life model is for steel bush–pin joints
(see docs/strength.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

ALLOWABLE_DYNAMIC_SAFETY = 2.5  # [k], seed 000 §3.6


def static_safety_factor(breaking_load: float, peripheral_force: float, sag_tension: float,
                         centrifugal_tension: float, dynamic_factor: float = 1.0) -> float:
    """s = Q/(kд·F_t + F_0 + F_v); forces [N] ([VN-CODE] s = Q/(kd·Ft + Fv + F0); [CPP] kд = 1)."""
    return breaking_load / (dynamic_factor * peripheral_force + sag_tension + centrifugal_tension)


def startup_safety_factor(breaking_load: float, max_startup_force: float) -> float:
    """k₁ = Q/F₁max: F₁max [N] the largest branch force of the start-up transient (seed 000 §3.6)."""
    return breaking_load / max_startup_force


def steady_safety_factor(breaking_load: float, operating_force: float,
                         dynamic_force: float) -> float:
    """k₂ = Q/(F_R + F₂): F_R [N] load from operating conditions, F₂ = c·x_A [N] the amplitude of
    the dynamic branch force in steady motion; with F₂max (at resonance) this is k₂min
    (seed 000 §3.6)."""
    return breaking_load / (operating_force + dynamic_force)


@dataclass(frozen=True, slots=True)
class TwoStageCheck:
    """The seed's two-stage check: k₁ (start-up), k₂ (steady), k₂min (resonance, None when not
    given) against [k]; ``passed`` when every given factor reaches [k]."""

    k1: float
    k2: float
    k2_min: float | None
    allowable: float

    @property
    def passed(self) -> bool:
        """True when k₁, k₂ (and k₂min if given) are all ≥ [k]."""
        factors = [self.k1, self.k2] + ([self.k2_min] if self.k2_min is not None else [])
        return min(factors) >= self.allowable

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"k1_startup": self.k1, "k2_steady": self.k2, "k2_min_resonance": self.k2_min,
                "allowable_k": self.allowable, "passed": self.passed}


def two_stage_check(breaking_load: float, max_startup_force: float, operating_force: float,
                    dynamic_force: float, resonance_force: float | None = None,
                    allowable: float = ALLOWABLE_DYNAMIC_SAFETY) -> TwoStageCheck:
    """Both stages of seed 000 §3.6 from the dynamic forces [N]: F₁max, F_R, F₂ and F₂max."""
    k2min = (steady_safety_factor(breaking_load, operating_force, resonance_force)
             if resonance_force is not None else None)
    return TwoStageCheck(startup_safety_factor(breaking_load, max_startup_force),
                         steady_safety_factor(breaking_load, operating_force, dynamic_force),
                         k2min, allowable)
