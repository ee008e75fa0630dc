"""The evaluation of a design by the synthesis: its objectives (:mod:`.objectives`) and
constraints, from its lazy :class:`~chaindrive.analysis.Analysis` — the same stages and
checks as every other command.

The constraints are the analysis's own checks (:meth:`~chaindrive.analysis.Analysis.checks`,
their ``violation`` ≤ 0 when satisfied) that the problem's ``[optimize.constraints]`` selects
and sets the limits of, plus two wishes of the designer that are not engineering rules: the
driven speeds' ratio tolerance and a highest mean chain speed. A design costs only the
stages its objectives and constraints read. A check that cannot be verified is a violated
constraint. A design the optimiser returns is judged by every check, as ``analyze`` judges
its design file (:func:`verify_mapping`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.checks import (
    RESONANCE_BAND_PERCENT,
    UNVERIFIED,
    UNVERIFIED_VIOLATION,
    Check,
    CheckLimits,
)
from chaindrive.cost import CostModel
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping
from chaindrive.kinematics import mean_chain_speed
from chaindrive.model import Drive
from chaindrive.robust.synthesis import RobustAnalysis, RobustSettings, robust_constraints
from chaindrive.synthesis.objectives import OBJECTIVES
from chaindrive.synthesis.problem import Constraints, Problem

__all__ = ["FAILED", "Evaluation", "analysis_of", "base_ratios", "check_limits",
           "constrained", "constraint_names", "evaluate_drive", "evaluate_vector",
           "unverifiable_for_any_design", "verify_mapping"]

#: objective value given to a design that cannot be built (a finite stand-in for ∞)
FAILED = 1e12


def check_limits(settings: Constraints) -> CheckLimits:
    """The limits of the analysis's checks that ``[optimize.constraints]`` sets.

    Parameters
    ----------
    settings : Constraints
        The problem's constraints.

    Returns
    -------
    CheckLimits
        [k] and the resonance band (the default band when the problem sets none).
    """
    return CheckLimits(allowable_dynamic_safety=settings.allowable_dynamic_safety,
                       resonance_band_percent=(settings.resonance_band
                                               if settings.resonance_band
                                               else RESONANCE_BAND_PERCENT))


def unverifiable_for_any_design(check: Check) -> bool:
    """Whether a check cannot be verified on any design of a search: the fatigue check of a
    chain whose catalogue gives no fatigue strength and that has no estimate of it (a chain
    not of steel, :func:`chaindrive.strength.span_checks.estimated_fatigue_strength`; no
    variable of the search supplies it).
    Such a check neither constrains nor ranks the designs; each design names it among its
    unverified checks (:attr:`Evaluation.unverified`), so a result never reads as verified
    where it is not.

    Parameters
    ----------
    check : Check
        An analysis check.

    Returns
    -------
    bool
        True for the fatigue check without a fatigue strength or its estimate.
    """
    return check.name == "fatigue" and check.limit is None


def constrained(check: Check, settings: Constraints) -> bool:
    """Whether ``[optimize.constraints]`` keeps an analysis check as a constraint: every
    check, except the chain's strength checks when ``static_safety = false``, the speed
    limit when ``speed_limit = false`` and k₁ unless ``startup_safety = true`` (it needs a
    time integration per design). Not a constraint: the fatigue check of a chain without a
    fatigue strength in the catalogue or an estimate of it (:func:`unverifiable_for_any_design`),
    which every design names among its unverified checks instead.

    Parameters
    ----------
    check : Check
        An analysis check.
    settings : Constraints
        The problem's constraints.

    Returns
    -------
    bool
        True when the check is a constraint.
    """
    if unverifiable_for_any_design(check):
        return False
    if check.name == "speed limit":
        return settings.speed_limit
    if check.part == "chain":
        return settings.static_safety
    if check.name == "k1":
        return settings.startup_safety
    return True


def constraint_names(analysis: Analysis, settings: Constraints) -> tuple[str, ...]:
    """Keys of the analysis checks that are constraints.

    Parameters
    ----------
    analysis : Analysis
        The analysis of a design.
    settings : Constraints
        The problem's constraints.

    Returns
    -------
    tuple of str
        Check keys (:func:`constrained`).
    """
    return tuple(c.key for c in analysis.checks() if constrained(c, settings))


@shared_parameters
def analysis_of(drive: Drive, settings: Constraints,
                cost_model: CostModel | None = None,
                robust: RobustSettings | None = None, *, sweep_curve: bool = True) -> Analysis:
    """The lazy analysis of a design with the limits the problem sets.

    Parameters
    ----------
    %(drive)s
    settings : Constraints
        The problem's constraints (k₁, a start-up per design, only when they ask for it).
    cost_model : CostModel or None
        Prices (None: the packaged estimates).
    robust : RobustSettings or None
        Robust settings: the analysis is a
        :class:`~chaindrive.robust.synthesis.RobustAnalysis` (its uncertainty model too).
    sweep_curve : bool
        False: the checks read the speed sweep's maxima from a bounded search of its speeds,
        not from the whole curve (the same maxima; ``Analysis(sweep_curve=...)``).

    Returns
    -------
    Analysis
        Lazy: each stage is computed when read.
    """
    if robust is not None:
        return RobustAnalysis(drive, robust=robust, limits=check_limits(settings),
                              cost_model=cost_model, startup=settings.startup_safety,
                              sweep_curve=sweep_curve)
    return Analysis(drive, limits=check_limits(settings), cost_model=cost_model,
                    startup=settings.startup_safety, sweep_curve=sweep_curve)


@dataclass(frozen=True, slots=True)
class Evaluation:
    """The evaluation of one design.

    Parameters
    ----------
    objectives : dict of str to float
        Objective values, natural sign [the unit of each objective, ``Metric.unit``].
    constraints : dict of str to float
        Constraint values g [-] (≤ 0 satisfied).
    feasible : bool
        Every constraint satisfied.
    error : str or None
        Why the design could not be built, or None.
    unverified : dict of str to str
        The constraints that are checks which cannot be verified, each with why (the
        check's note); a failure of unknown size (g = 1).
    """

    objectives: dict[str, float]
    constraints: dict[str, float]
    feasible: bool
    error: str | None = None
    unverified: dict[str, str] = field(default_factory=dict)

    def minimised(self, names: Sequence[str]) -> list[float]:
        """Objective values with the sense applied (every one minimised).

        Parameters
        ----------
        names : sequence of str
            The objectives, in order.

        Returns
        -------
        list of float
            Sense × value.
        """
        return [OBJECTIVES[n].sense * self.objectives[n] for n in names]

    def violation(self) -> float:
        """Sum of the positive constraint values."""
        return float(sum(max(v, 0.0) for v in self.constraints.values()))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"objectives": dict(self.objectives), "constraints": dict(self.constraints),
                "constraints_ok": self.feasible, "error": self.error,
                "unverified": dict(self.unverified)}


def _failed(objectives: Sequence[str], error: str) -> Evaluation:
    return Evaluation({n: OBJECTIVES[n].sense * FAILED for n in objectives}, {"buildable": 1.0},
                      False, error)


def _wishes(a: Analysis, settings: Constraints, ratios: Sequence[float] | None,
            tolerance: float) -> dict[str, float]:
    """The designer's wishes beyond the engineering rules (g ≤ 0 satisfied): mean chain speed
    ≤ the maximum, driver wrap and teeth in mesh on loaded sprockets at least the minima,
    static safety at least the designer's [s] when given, driven ratios within the tolerance
    of the start design."""
    d, g = a.drive, a.geometry
    assert d.driver.speed is not None
    v = float(mean_chain_speed(d.chain.spec.pitch, d.driver.teeth, d.driver.speed))
    out = {"chain_speed": (v - settings.max_chain_speed) / settings.max_chain_speed,
           "min_driver_wrap": (settings.min_driver_wrap
                               - g.sprockets[d.driver_index].wrap_angle)
           / settings.min_driver_wrap}
    if settings.min_teeth_in_mesh > 0:
        fewest = min(sg.teeth_in_mesh for sg, s in zip(g.sprockets, d.sprockets, strict=True)
                     if s.role != "idler")
        out["min_teeth_in_mesh"] = (settings.min_teeth_in_mesh - fewest) / settings.min_teeth_in_mesh
    if settings.min_static_safety is not None and a.strength is not None:
        out["min_static_safety"] = ((settings.min_static_safety - a.strength.safety_factor_static)
                                    / settings.min_static_safety)
    if ratios is not None:
        z1 = d.driver.teeth
        dev = max((abs(sp.teeth / z1 - i0) / i0 for sp, i0 in zip(d.sprockets, ratios,
                                                                   strict=True)
                   if sp.role == "driven"), default=0.0)
        out["ratio"] = (dev - tolerance) / max(tolerance, 1e-3)
    return out


def _startup_unverifiable(a: Analysis) -> str | None:
    """Why ``analyze`` would say k₁ cannot be verified whatever its start-up gives (the
    dynamic model is incomplete: the start-up of bare sprockets is not the drive's), or
    None; a search without start-ups reads it from the model, which it builds anyway."""
    if not (a.with_response and a.drive.dynamics.transient and a.drive.power is not None
            and a.drive.driver.speed is not None):
        return None
    missing = a.drive_model.missing
    if not missing:
        return None
    return (f"the dynamic model is incomplete ({'; '.join(missing)}): its start-up is not "
            "the drive's")


@shared_parameters
def evaluate_drive(drive: Drive, objectives: Sequence[str], settings: Constraints, *,
                   base_ratios: Sequence[float] | None = None, ratio_tolerance: float = 0.03,
                   cost_model: CostModel | None = None,
                   robust: RobustSettings | None = None,
                   every_check: bool = False) -> Evaluation:
    """Objectives and constraints of one design, from its lazy :class:`Analysis`; a design
    that cannot be built (the geometry or strength raises: span interference, impossible
    take-up …) gets objectives :data:`FAILED` and the constraint ``buildable`` = 1.

    A check that cannot be verified is a violated constraint (g = 1) and is named in
    :attr:`Evaluation.unverified` with why; one that cannot be verified on any design
    (:func:`unverifiable_for_any_design`) is named there and constrains nothing. Without the
    start-up (``startup_safety = false``) k₁ is still a constraint where ``analyze`` could not
    verify it whatever the start-up gives: on an incomplete dynamic model. The search's
    designs are screened without the speed sweep's curve: its maxima (k₂min) come from a
    bounded search of its speeds, the same maxima (``Analysis(sweep_curve=False)``); a
    design judged by every check gets the whole sweep, as ``analyze`` computes it.

    Parameters
    ----------
    %(drive)s
    objectives : sequence of str
        Names of the objectives.
    settings : Constraints
        The problem's constraints.
    base_ratios : sequence of float or None
        z_i/z_driver of the start design [-] (None: no ratio constraint).
    ratio_tolerance : float
        Allowed relative deviation of a driven ratio [-].
    cost_model : CostModel or None
        Prices.
    robust : RobustSettings or None
        With robust settings the chance constraints ``P(<check>)`` are added
        (:func:`chaindrive.robust.synthesis.robust_constraints`).
    every_check : bool
        Judge the design as ``analyze`` does: every check of its analysis is a constraint,
        the start-up (k₁) included, whatever ``[optimize.constraints]`` switches off (the
        verdict of a design the optimiser returns).

    Returns
    -------
    Evaluation
        Objectives and constraint values.
    """
    if every_check:
        settings = replace(settings, startup_safety=True)
    a = analysis_of(drive, settings, cost_model, robust, sweep_curve=every_check)
    unverified: dict[str, str] = {}
    try:
        obj = {n: float(OBJECTIVES[n].value(a)) for n in objectives}
        cons: dict[str, float] = {"buildable": 0.0}
        for check in a.checks():
            if unverifiable_for_any_design(check):
                unverified[check.key] = check.note or "no rule covers the design"
            elif every_check or constrained(check, settings):
                cons[check.key] = check.violation
                if check.status == UNVERIFIED:
                    unverified[check.key] = check.note or "no rule covers the design"
        why = None if settings.startup_safety else _startup_unverifiable(a)
        if why is not None:
            cons["k1"], unverified["k1"] = UNVERIFIED_VIOLATION, why
        cons.update(_wishes(a, settings, base_ratios, ratio_tolerance))
        if isinstance(a, RobustAnalysis):
            cons.update(robust_constraints(a))
    except ChainDriveError as exc:
        return _failed(objectives, str(exc))
    if not all(math.isfinite(v) for v in [*obj.values(), *cons.values()]):
        return _failed(objectives, "non-finite result")
    return Evaluation(obj, cons, all(v <= 0 for v in cons.values()), None, unverified)


def verify_mapping(problem: Problem, design: Mapping[str, Any],
                   cost_model: CostModel | None = None) -> Evaluation:
    """The verdict on a design the search found: the design file it is written as, loaded
    and judged by every check of its analysis (:func:`evaluate_drive` with
    ``every_check``), the start-up included.

    Parameters
    ----------
    problem : Problem
        The synthesis problem.
    design : mapping
        The design's TOML mapping (what its design file loads to).
    cost_model : CostModel or None
        Prices.

    Returns
    -------
    Evaluation
        Feasible only when every check passes and the designer's wishes hold.
    """
    try:
        drive = drive_from_mapping(dict(design), problem.base_dir)
    except ChainDriveError as exc:
        return _failed(problem.objectives, str(exc))
    return evaluate_drive(drive, problem.objectives, problem.constraints,
                          base_ratios=base_ratios(problem.base),
                          ratio_tolerance=problem.ratio_tolerance, cost_model=cost_model,
                          robust=problem.robust, every_check=True)


@shared_parameters
def base_ratios(drive: Drive) -> list[float]:
    """The ratio of every sprocket to the driver.

    %(drive_returns)s
    list of float
        z_i/z_driver [-].
    """
    return [s.teeth / drive.driver.teeth for s in drive.sprockets]


def evaluate_vector(problem: Problem, x: Sequence[float],
                    cost_model: CostModel | None = None) -> tuple[Evaluation, Drive | None]:
    """Decode and evaluate one search vector.

    Parameters
    ----------
    problem : Problem
        The synthesis problem.
    x : sequence of float
        The search vector [the unit of each gene] (:class:`chaindrive.synthesis.problem.Gene`).
    cost_model : CostModel or None
        Prices.

    Returns
    -------
    tuple of (Evaluation, Drive or None)
        The evaluation and the drive (None when it cannot be decoded).
    """
    try:
        drive = problem.decode(x)
    except ChainDriveError as exc:
        return _failed(problem.objectives, str(exc)), None
    return evaluate_drive(drive, problem.objectives, problem.constraints,
                          base_ratios=base_ratios(problem.base),
                          ratio_tolerance=problem.ratio_tolerance, cost_model=cost_model,
                          robust=problem.robust), drive
