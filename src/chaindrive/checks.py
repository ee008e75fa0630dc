"""The pass/fail checks of a design: each with its value, its required limit and the source
of the rule.

:class:`Check` is what every presenter shows and what the optimiser constrains: a check that
cannot be verified (the rule's table does not cover the design, or a value is missing) is a
failure said as such, never a pass. The functions below build the checks from the results of
the analysis stages; :meth:`chaindrive.analysis.Analysis.checks` runs them.

Sign convention, one for every output: ``margin`` is the relative distance from the limit
in the direction that passes, (value − limit)/limit for a lower limit (≥) and
(limit − value)/limit for an upper limit (≤): positive passes, negative fails.
``violation`` is −margin (≤ 0 satisfied), the optimiser's constraint value.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from chaindrive.dynamics.resonance import RESONANCE_BAND_PERCENT, Resonance
from chaindrive.geometry.results import GeometryResult
from chaindrive.model import Drive
from chaindrive.strength import StrengthResult
from chaindrive.strength.safety import ALLOWABLE_DYNAMIC_SAFETY

__all__ = ["Check", "CheckLimits", "Status", "driver_wrap_check", "dynamic_safety_check",
           "hinge_pressure_check", "resonance_check", "speed_limit_check",
           "static_safety_check", "teeth_in_mesh_check"]

Status = Literal["pass", "fail", "cannot be verified"]
Relation = Literal[">=", "<="]
#: Violation given to a check that cannot be verified (a failure of unknown size).
UNVERIFIED_VIOLATION = 1.0


@dataclass(frozen=True, slots=True)
class CheckLimits:
    """The required values of the checks that a designer may set (SI).

    Parameters
    ----------
    min_driver_wrap : float
        Smallest wrap angle on the driver [rad]; 120° [DiamondChain], [Mott2004].
    min_teeth_in_mesh : float
        Smallest number of teeth in mesh on a loaded sprocket [-]; 3 (a rule of thumb of the
        chain makers, kept from the earlier versions; its source is not yet confirmed).
    allowable_dynamic_safety : float
        [k] of the two-stage dynamic check k₁, k₂, k₂min [-]; 2.5
        [MultimassChainDrives, §3.6].
    resonance_band_percent : float
        Least distance of every working frequency from a natural frequency [%]; 10
        [API684].
    static_safety : float | None
        The designer's own [s] where the tabulated one does not apply (outside the tables,
        non-steel chains) [-]; None: such a check cannot be verified.
    """

    min_driver_wrap: float = math.radians(120.0)
    min_teeth_in_mesh: float = 3.0
    allowable_dynamic_safety: float = ALLOWABLE_DYNAMIC_SAFETY
    resonance_band_percent: float = RESONANCE_BAND_PERCENT
    static_safety: float | None = None


@dataclass(frozen=True, slots=True)
class Check:
    """One pass/fail rule applied to a design.

    Parameters
    ----------
    name : str
        Stable key (``"hinge_pressure"``, ``"k2"`` …).
    label : str
        What is checked, for people, with its symbol.
    value : float | None
        The design's value, in ``unit`` (None when it could not be computed).
    limit : float | None
        The required value, in ``unit`` (None when no rule covers the design).
    relation : str
        ``">="`` (value must reach the limit) or ``"<="``.
    unit : str
        Unit of value and limit (SI, or ``"-"``, ``"%"``).
    status : str
        ``"pass"``, ``"fail"`` or ``"cannot be verified"``.
    source : str
        The rule's source, a key of docs/references.md.
    part : str
        The part of the analysis it belongs to (``"geometry"``, ``"strength"``, …).
    note : str
        Where it applies or why it cannot be verified.
    """

    name: str
    label: str
    value: float | None
    limit: float | None
    relation: Relation
    unit: str
    status: Status
    source: str
    part: str
    note: str = ""

    @property
    def passed(self) -> bool:
        """True only for ``status == "pass"``."""
        return self.status == "pass"

    @property
    def margin(self) -> float | None:
        """Relative distance from the limit, positive when it passes (module docstring)."""
        if self.value is None or self.limit is None or self.limit == 0:
            return None
        gap = self.value - self.limit if self.relation == ">=" else self.limit - self.value
        return gap / abs(self.limit)

    @property
    def violation(self) -> float:
        """−margin (≤ 0 satisfied); :data:`UNVERIFIED_VIOLATION` when it cannot be verified."""
        m = self.margin
        return UNVERIFIED_VIOLATION if m is None else -m

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the unit is given in ``unit``)."""
        return {"name": self.name, "label": self.label, "value": self.value,
                "limit": self.limit, "relation": self.relation, "unit": self.unit,
                "status": self.status, "margin": self.margin, "source": self.source,
                "part": self.part, "note": self.note}


def judged(name: str, label: str, value: float | None, limit: float | None,
           relation: Relation, unit: str, source: str, part: str, note: str = "") -> Check:
    """A :class:`Check` with its status decided from value, limit and relation."""
    if value is None or limit is None or not math.isfinite(value):
        status: Status = "cannot be verified"
    elif relation == ">=":
        status = "pass" if value >= limit else "fail"
    else:
        status = "pass" if value <= limit else "fail"
    return Check(name, label, value, limit, relation, unit, status, source, part, note)


def driver_wrap_check(drive: Drive, geometry: GeometryResult, limits: CheckLimits) -> Check:
    """Wrap angle on the driver ≥ the minimum [rad] [DiamondChain], [Mott2004]."""
    wrap = geometry.sprockets[drive.driver_index].wrap_angle
    return judged("driver_wrap", f"wrap angle on the driver {drive.driver.name}", wrap,
                  limits.min_driver_wrap, ">=", "rad", "[DiamondChain], [Mott2004]", "geometry")


def teeth_in_mesh_check(drive: Drive, geometry: GeometryResult, limits: CheckLimits) -> Check:
    """Fewest teeth in mesh on a loaded (driver or driven) sprocket ≥ the minimum."""
    loaded = [(g.teeth_in_mesh, s.name) for g, s in zip(geometry.sprockets, drive.sprockets,
                                                        strict=True) if s.role != "idler"]
    value, name = min(loaded)
    return judged("teeth_in_mesh", f"teeth in mesh on a loaded sprocket (fewest: {name})",
                  value, limits.min_teeth_in_mesh, ">=", "-", "rule of thumb (unconfirmed)",
                  "geometry")


def speed_limit_check(speed: float, limit: float | None, pitch: float) -> Check:
    """Small-sprocket speed ω [rad/s] ≤ n₁max of the pitch, [TrinhChat2006, table 5.8];
    cannot be verified outside that table."""
    return judged("speed_limit", "speed of the small sprocket", speed, limit, "<=", "rad/s",
                  "[TrinhChat2006, table 5.8]", "kinematics",
                  "" if limit is not None else
                  f"pitch {pitch * 1e3:g} mm is outside the table of n₁max")


def hinge_pressure_check(strength: StrengthResult) -> Check:
    """Hinge pressure p = F_t·Kэ/A ≤ [p] [Pa] [Sheinblit1991];
    cannot be verified outside the table or for a non-steel chain."""
    return judged("hinge_pressure", "hinge pressure p", strength.hinge_pressure,
                  strength.allowable_pressure, "<=", "Pa", "[Sheinblit1991]",
                  "strength", "" if strength.allowable_pressure is not None else
                  "the table of [p] does not cover this chain and speed")


def static_safety_check(strength: StrengthResult, limits: CheckLimits) -> Check:
    """Static safety s = Q/(kд F_t + F_0 + F_v) ≥ [s] [TrinhChat2006, table 5.10]; outside
    the table the designer's [s] of ``limits`` is used when given, else it cannot be
    verified."""
    limit, source, note = strength.allowable_safety_factor, "[TrinhChat2006, table 5.10]", ""
    if limit is None and limits.static_safety is not None:
        limit, source = limits.static_safety, "the designer's [s]"
        note = "the table of [s] does not cover this chain and speed"
    elif limit is None:
        note = "the table of [s] does not cover this chain and speed; give your own [s]"
    return judged("static_safety", "static safety factor s", strength.safety_factor_static,
                  limit, ">=", "-", source, "strength", note)


def dynamic_safety_check(name: str, label: str, value: float | None,
                         limits: CheckLimits) -> Check:
    """k₁, k₂ or k₂min ≥ [k] [MultimassChainDrives, §3.6]."""
    return judged(name, label, value, limits.allowable_dynamic_safety, ">=", "-",
                  "[MultimassChainDrives, §3.6]", "dynamics")


def resonance_check(rows: Sequence[Resonance], limits: CheckLimits) -> Check | None:
    """The least distance |f_w − f_n|/f_n of a working frequency from its nearest natural
    frequency (ring modes, and the spans' principal parametric resonance) ≥ the band [%]
    [MultimassChainDrives, §3.2], [API684]; None when there is no working frequency."""
    if not rows:
        return None
    closest = min(rows, key=lambda r: abs(r.margin_percent))
    what = ("parametric resonance of a span" if closest.working.kind == "parametric"
            else "natural frequency")
    return judged("resonance_margin", "distance of the working frequencies from resonance",
                  abs(closest.margin_percent), limits.resonance_band_percent, ">=", "%",
                  "[MultimassChainDrives, §3.2], [API684]", "dynamics",
                  f"closest: {closest.working.label} at {closest.working.frequency:.4g} Hz "
                  f"against the {what} {closest.natural_frequency:.4g} Hz")
