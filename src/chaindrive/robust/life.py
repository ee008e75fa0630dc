"""The life curve of a drive: what it does as its chain wears from new to the replacement
elongation, and the elongation (and the hours) at which the first check fails.

Each point is a :class:`~chaindrive.robust.analysis.PerturbedAnalysis` at the nominal
tolerances and the chain elongation ε: the first elastic frequency f₁, the resonance margin,
K_D, k₂, the take-up travel or the sag of the slack span, the roller lift on the largest
sprocket and every check. The first failure is found on the grid and refined by bisection on
ε (the check flips between two grid points; a check that fails when new is reported apart).
Hours follow from the wear-life relation of :mod:`chaindrive.strength.wear` (the ACA
load–life relation, life ∝ the permitted elongation [Shigley2015, Eq. 17-40]): h(ε) =
h(3 %)·ε/3 %, for the chain's rating at the design power.

References
----------
[DiamondChainWear], [DiamondChainTension], [Shigley2015], [ISO606]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.errors import ChainDriveError
from chaindrive.robust.analysis import PerturbedAnalysis, first_elastic_hz
from chaindrive.robust.perturbation import REFERENCE_TEMPERATURE_C, Perturbation
from chaindrive.robust.uncertainty import UncertaintyModel
from chaindrive.robust.wear import roller_lift
from chaindrive.strength.duty import service_factor_for
from chaindrive.strength.wear import wear_life_hours

__all__ = ["LifeCurve", "WearState", "life_curve", "wear_state"]

#: Bisection steps refining the first failure between two grid points.
BISECTIONS = 12


@dataclass(frozen=True, slots=True)
class WearState:
    """The drive at one chain elongation.

    Parameters
    ----------
    elongation : float
        ε [–].
    f1_hz : float
        First elastic natural frequency [Hz].
    resonance_margin_percent : float
        Least distance of a working frequency from resonance [%].
    coefficient_of_dynamics : float
        K_D [–] (nan without a response).
    k2 : float
        k₂ [–] (nan without a response).
    take_up_travel_mm : float
        Take-up travel beyond new [mm] (0 without a take-up).
    links_removed : int
        Links taken out at the take-up by this elongation [–] (two each time it absorbed
        its capacity, [DiamondChainTension]).
    sag_ratio : float
        Sag of the slack span as a fraction of its length [–].
    roller_lift_mm : float
        Rise of the rollers on the largest sprocket [mm].
    failed : tuple of str
        Keys of the checks that fail.
    """

    elongation: float
    f1_hz: float
    resonance_margin_percent: float
    coefficient_of_dynamics: float
    k2: float
    take_up_travel_mm: float
    links_removed: int
    sag_ratio: float
    roller_lift_mm: float
    failed: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (nan as None)."""
        out: dict[str, Any] = {}
        for name in ("elongation", "f1_hz", "resonance_margin_percent",
                     "coefficient_of_dynamics", "k2", "take_up_travel_mm", "sag_ratio",
                     "roller_lift_mm"):
            v = getattr(self, name)
            out[name] = v if math.isfinite(v) else None
        out["links_removed"] = self.links_removed
        out["failed"] = list(self.failed)
        return out


def _value(x: float | None) -> float:
    return math.nan if x is None else float(x)


@shared_parameters
def wear_state(nominal: Analysis, model: UncertaintyModel, elongation: float) -> WearState:
    """The drive at the elongation ε with the nominal tolerances.

    %(params_nominal_wear)s
    elongation : float
        ε [–].

    Returns
    -------
    WearState
    """
    a = PerturbedAnalysis(nominal, Perturbation(elongation=elongation),
                          allowable_elongation=model.allowable_elongation,
                          take_up_capacity=model.take_up_capacity)
    d = nominal.drive
    z = max(s.teeth for s in d.sprockets)
    res = a.check("resonance_margin")
    steady = a.steady
    return WearState(
        elongation=elongation, f1_hz=first_elastic_hz(a),
        resonance_margin_percent=_value(None if res is None else res.value),
        coefficient_of_dynamics=_value(None if steady is None
                                       else steady.coefficient_of_dynamics),
        k2=_value(None if steady is None else steady.k2),
        take_up_travel_mm=a.take_up_travel() * 1e3, links_removed=a.links_removed,
        sag_ratio=a.sag_ratio,
        roller_lift_mm=float(roller_lift(d.chain.spec.pitch, z, elongation)) * 1e3,
        failed=tuple(c.key for c in a.all_checks() if not c.passed))


#: What every state of the life curve holds at nominal: it is the drive as drawn, its chain
#: worn to each elongation.
LIFE_HELD_AT_NOMINAL = ("every tolerance of the uncertainty model (chain length, "
                        "eccentricity, shaft positions, key clearances, inertias, chain "
                        "stiffness): the drive as drawn, only the elongation varies",
                        f"temperature: {REFERENCE_TEMPERATURE_C:g} °C")


@dataclass(frozen=True, slots=True)
class LifeCurve:
    """The drive from new to past its replacement elongation.

    Parameters
    ----------
    states : tuple of WearState
        On the grid of elongations.
    allowable_elongation : float
        The replacement rule's ε [–].
    failing_when_new : tuple of str
        Checks that fail already when new (left out of the first failure).
    first_failure_elongation : float | None
        ε at which the first other check fails [–] (None: none up to the grid's end).
    first_failure : str | None
        That check's key.
    life_elongation : float
        ε at which the chain's life ends: the first failure or the replacement rule [–].
    hours_per_elongation : float | None
        Wear hours per unit elongation from the ACA relation [h] (None: the chain has no
        rating).
    take_up_runs_out : float | None
        ε at which the take-up has absorbed its capacity [–] (None: no take-up).
    """

    states: tuple[WearState, ...]
    allowable_elongation: float
    failing_when_new: tuple[str, ...]
    first_failure_elongation: float | None
    first_failure: str | None
    life_elongation: float
    hours_per_elongation: float | None
    take_up_runs_out: float | None

    def hours(self, elongation: float) -> float | None:
        """Wear hours to reach ``elongation`` (linear in the elongation).

        Parameters
        ----------
        elongation : float
            Chain elongation ε [-] (0.01 = 1 %).

        Returns
        -------
        float | None
            The hours [h] (None when the chain has no rating for the wear relation).
        """
        return None if self.hours_per_elongation is None else self.hours_per_elongation * elongation

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"allowable_elongation": self.allowable_elongation,
                "failing_when_new": list(self.failing_when_new),
                "first_failure_elongation": self.first_failure_elongation,
                "first_failure": self.first_failure,
                "life_elongation": self.life_elongation,
                "life_hours": self.hours(self.life_elongation),
                "first_failure_hours": (None if self.first_failure_elongation is None
                                        else self.hours(self.first_failure_elongation)),
                "take_up_runs_out_elongation": self.take_up_runs_out,
                "held_at_nominal": list(LIFE_HELD_AT_NOMINAL),
                "states": [s.to_dict() for s in self.states]}


def _hours_per_elongation(nominal: Analysis) -> float | None:
    """h(ε)/ε of the ACA relation for the chain's rating at the design power [h]."""
    st, d = nominal.strength, nominal.drive
    if st is None or st.rated_power is None or d.power is None:
        return None
    ks = service_factor_for(d).value  # given, from the duty classes, else 1
    return float(wear_life_hours(st.rated_power, d.power * ks / d.chain.contours,
                                 nominal.geometry.links, 1.0))


def _failing(nominal: Analysis, model: UncertaintyModel, eps: float,
             ignore: tuple[str, ...]) -> list[str]:
    try:
        return [k for k in wear_state(nominal, model, eps).failed if k not in ignore]
    except ChainDriveError:
        return ["buildable"]


@shared_parameters
def life_curve(nominal: Analysis, model: UncertaintyModel, *, points: int = 13,
               extent: float = 1.25) -> LifeCurve:
    """The life curve of the drive (module docstring).

    %(params_nominal_wear)s
    points : int
        Grid points from new to ``extent`` × the allowable elongation [–].
    extent : float
        How far past the allowable elongation the grid goes [–].

    Returns
    -------
    LifeCurve
    """
    allow = model.allowable_elongation
    grid = np.linspace(0.0, extent * allow, max(points, 2))
    states = [wear_state(nominal, model, float(e)) for e in grid]
    when_new = states[0].failed
    first: float | None = None
    key: str | None = None
    for lo_state, hi_state in pairwise(states):
        new = [k for k in hi_state.failed if k not in when_new]
        if not new:
            continue
        if new == ["chain_elongation"]:  # the replacement rule itself: exactly its limit
            first, key = allow, new[0]
            break
        lo, hi = lo_state.elongation, hi_state.elongation
        for _ in range(BISECTIONS):
            mid = 0.5 * (lo + hi)
            fails = _failing(nominal, model, mid, when_new)
            if fails:
                hi, new = mid, fails
            else:
                lo = mid
        first, key = hi, new[0]
        break
    capacity = model.take_up_capacity
    runs_out = (None if capacity is None
                else capacity / nominal.geometry.chain_length)
    life = allow if first is None else min(first, allow)
    return LifeCurve(tuple(states), allow, when_new, first, key, life,
                     _hours_per_elongation(nominal), runs_out)
