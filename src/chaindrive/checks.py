"""A pass/fail check of a design: its value, the limit it is held to, the verdict and the
source of the rule — the one type every check of chaindrive returns.

The rules live with their subject (:mod:`chaindrive.strength.checks` for the chain and the
layout, :mod:`chaindrive.dynamics.checks` for resonance and the dynamic safety factors);
:meth:`chaindrive.analysis.Analysis.checks` lists them for a design, the selection ranks
chains by them, the optimiser constrains by them and the presenters show them.

A check whose rule has no limit for the design (a table that stops, a value that is missing)
is "cannot be verified": a failure said as such, never a pass.

Sign convention, one for every output: ``margin_fraction`` is limit/value − 1 for an upper
limit (``kind`` "max") and value/limit − 1 for a lower limit ("min"): ≥ 0 when the check
passes. ``violation`` is its negative (≤ 0 satisfied), the optimiser's constraint value.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from chaindrive.errors import Quantity

__all__ = ["ALLOWABLE_DYNAMIC_SAFETY", "FAIL", "LINK_LEVEL", "PASS", "RESONANCE_BAND_PERCENT",
           "UNVERIFIED", "WHOLE_DRIVE",
           "Check", "CheckLimits", "Kind", "Status", "judged", "verdict", "worst"]

Status = Literal["pass", "fail", "cannot be verified"]
Kind = Literal["max", "min"]
PASS: Status = "pass"
FAIL: Status = "fail"
UNVERIFIED: Status = "cannot be verified"
#: Violation of a check that cannot be verified (a failure of unknown size).
UNVERIFIED_VIOLATION = 1.0
#: [k], the allowable dynamic safety factor of the two-stage check k₁, k₂, k₂min [-]
#: [MultimassChainDrives, §3.6].
ALLOWABLE_DYNAMIC_SAFETY = 2.5
#: Least distance of a working frequency from a natural frequency [%] [API684].
RESONANCE_BAND_PERCENT = 10.0
#: The models a check resting on a dynamic load may take it from
#: (:attr:`Check.governing_model`): the whole-drive (ring) model and the link-level model.
WHOLE_DRIVE = "whole_drive"
LINK_LEVEL = "link_level"


@dataclass(frozen=True, slots=True)
class Check:
    """One check: ``value`` against ``limit`` (both SI), its verdict and the rule's source.

    Parameters
    ----------
    name : str
        What is checked ("hinge pressure", "teeth in mesh", "k2" …).
    subject : str
        The chain, sprocket or span it is about.
    value : float or None
        The design's value [SI] (None when it could not be computed).
    limit : float or None
        The limit [SI] (None when no rule covers the design).
    kind : str
        "max" (value ≤ limit) or "min" (value ≥ limit).
    status : str
        "pass", "fail" or "cannot be verified".
    source : str
        The rule's source, a key of docs/references.md.
    unit : str
        The unit the value is read in (e.g. "MPa").
    scale : float
        Factor from SI to ``unit`` [unit/SI] (e.g. 1e-6 for Pa → MPa).
    note : str
        What the verdict rests on (an estimate, a table edge …).
    part : str
        The part of the analysis: "chain", "geometry" or "dynamics".
    item : str
        For a check repeated per sprocket, the sprocket (it names the check's ``key``).
    note_quantities : tuple of Quantity
        The numbers with units that ``note`` writes (SI;
        :class:`chaindrive.errors.Quantities`), for a presenter to write in another unit
        system (:func:`chaindrive.display.quantity_text`).
    governing_model : str or None
        For a check resting on a dynamic load when both the whole-drive and the link-level
        model were run, the model whose load it takes (``"whole_drive"`` or
        ``"link_level"``, :data:`WHOLE_DRIVE`, :data:`LINK_LEVEL`; the note says why); None
        otherwise.
    limit_estimated : bool
        The limit is an estimate, not a published value (the note says from what): every
        presenter writes "estimate" next to it, the JSON carries ``limit_estimated``.
    """

    name: str
    subject: str
    value: float | None
    limit: float | None
    kind: Kind
    status: Status
    source: str
    unit: str = ""
    scale: float = 1.0
    note: str = ""
    part: str = ""
    item: str = ""
    note_quantities: tuple[Quantity, ...] = ()
    governing_model: str | None = None
    limit_estimated: bool = False

    @property
    def key(self) -> str:
        """Stable identifier across designs: ``teeth_in_mesh[S3]``, ``hinge_pressure`` …"""
        base = self.name.replace(" ", "_").replace("-", "_")
        return f"{base}[{self.item}]" if self.item else base

    @property
    def passed(self) -> bool:
        """True only for "pass" ("cannot be verified" is not a pass)."""
        return self.status == PASS

    @property
    def margin_fraction(self) -> float | None:
        """limit/value − 1 for a "max" check, value/limit − 1 for a "min" check (≥ 0 when it
        passes); None when it cannot be verified."""
        if self.value is None or self.limit is None:
            return None
        if self.kind == "max":
            return math.inf if self.value <= 0 else self.limit / self.value - 1.0
        return math.inf if self.limit <= 0 else self.value / self.limit - 1.0

    @property
    def violation(self) -> float:
        """−margin (≤ 0 satisfied, −1 for an unlimited pass); :data:`UNVERIFIED_VIOLATION`
        when it cannot be verified."""
        m = self.margin_fraction
        if m is None or self.status == UNVERIFIED:
            return UNVERIFIED_VIOLATION
        return -1.0 if math.isinf(m) else -m

    def shown(self, x: float | None) -> float | None:
        """A value in the unit the check is read in.

        Parameters
        ----------
        x : float or None
            A value in SI [SI unit of the check].

        Returns
        -------
        float or None
            ``x`` times :attr:`scale` [``unit``] (None for None).
        """
        return None if x is None else x * self.scale

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (value and limit in ``unit``; margin as a fraction)."""
        margin = self.margin_fraction
        return {"key": self.key, "check": self.name, "subject": self.subject,
                "value": self.shown(self.value), "limit": self.shown(self.limit),
                "unit": self.unit, "kind": self.kind, "status": self.status,
                "margin_fraction": None if margin is None or math.isinf(margin) else margin,
                "limit_estimated": self.limit_estimated,
                "source": self.source, "note": self.note, "part": self.part,
                "note_quantities": [q.to_dict() for q in self.note_quantities],
                "governing_model": self.governing_model}


def verdict(value: float | None, limit: float | None, kind: Kind) -> Status:
    """The verdict of a value against its limit.

    Parameters
    ----------
    value : float or None
        The design's value [SI].
    limit : float or None
        The limit [SI, the unit of ``value``].
    kind : {"max", "min"}
        "max": pass when value ≤ limit; "min": pass when value ≥ limit (both to a relative
        1e-12).

    Returns
    -------
    str
        "pass" or "fail"; "cannot be verified" when either is missing or not finite.
    """
    if value is None or limit is None or not (math.isfinite(value) and math.isfinite(limit)):
        return UNVERIFIED
    ok = value <= limit * (1 + 1e-12) if kind == "max" else value >= limit * (1 - 1e-12)
    return PASS if ok else FAIL


def judged(name: str, subject: str, value: float | None, limit: float | None, kind: Kind,
           source: str, unit: str = "", scale: float = 1.0, note: str = "", part: str = "",
           item: str = "", note_quantities: tuple[Quantity, ...] = (),
           limit_estimated: bool = False) -> Check:
    """A :class:`Check` with its verdict decided by :func:`verdict`.

    Parameters
    ----------
    name, subject, source, unit, note, part, item : str
        As in :class:`Check`.
    value : float or None
        The design's value [SI].
    limit : float or None
        The limit [SI].
    kind : {"max", "min"}
        Upper or lower limit.
    scale : float
        Factor from SI to ``unit`` [unit/SI].
    note_quantities : tuple of Quantity
        The numbers with units ``note`` writes (:class:`Check`).
    limit_estimated : bool
        The limit is an estimate (:class:`Check`).

    Returns
    -------
    Check
        The check with its status.
    """
    return Check(name, subject, value, limit, kind, verdict(value, limit, kind), source,
                 unit, scale, note, part, item, tuple(note_quantities),
                 limit_estimated=limit_estimated)


def worst(checks: Sequence[Check]) -> Check | None:
    """The check furthest from passing.

    Parameters
    ----------
    checks : sequence of Check
        The checks to rank.

    Returns
    -------
    Check or None
        A failure with the smallest margin first, then a "cannot be verified", then the
        passing check with the smallest margin; None for no checks.
    """
    if not checks:
        return None

    def key(c: Check) -> tuple[int, float]:
        m = c.margin_fraction
        order = {FAIL: 0, UNVERIFIED: 1, PASS: 2}[c.status]
        return order, (m if m is not None else -math.inf)

    return min(checks, key=key)


@dataclass(frozen=True, slots=True)
class CheckLimits:
    """Limits of the analysis's checks that a designer (or an optimisation problem) sets.

    Parameters
    ----------
    allowable_dynamic_safety : float
        [k] of the two-stage dynamic check k₁, k₂, k₂min [-]; 2.5
        [MultimassChainDrives, §3.6].
    resonance_band_percent : float
        Least distance of every working frequency from a natural frequency [%]; 10
        [API684].
    required_life_h : float or None
        Required wear life [h] (None: the life the chain's rating promises for its length).
    """

    allowable_dynamic_safety: float = ALLOWABLE_DYNAMIC_SAFETY
    resonance_band_percent: float = RESONANCE_BAND_PERCENT
    required_life_h: float | None = None
