"""Multi-objective search of a synthesis problem: Optuna's NSGA-II sampler (default) or pymoo
NSGA-II.

Both search the same vector (:class:`chaindrive.synthesis.problem.Gene`): integers and
categories are rounded in :meth:`chaindrive.synthesis.problem.Problem.decode`, so one
decoding serves both libraries. The start design (as the file gives it) is evaluated on its
own and its nearest search vector seeds the first generation. The Pareto set is taken from
every design evaluated (an archive), keeping the feasible non-dominated ones [Deb2002]
(constrained domination); each comes back as the dictionary a TOML design file loads to, so
it can be re-analysed or written out. Same seed, same result (serial or through a Dask
evaluator, which keeps the order of a batch). Why Optuna by default: docs/synthesis.md
(benchmark on the 8-sprocket example, benchmarks/bench_synthesis.py).
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.cost import default_cost_model
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_to_mapping
from chaindrive.model import Drive
from chaindrive.robust.synthesis import RobustAnalysis, verify_design
from chaindrive.synthesis.evaluation import (
    Evaluation,
    analysis_of,
    base_ratios,
    evaluate_drive,
    evaluate_vector,
    verify_mapping,
)
from chaindrive.synthesis.objectives import objective_unit
from chaindrive.synthesis.problem import Problem

__all__ = ["BatchEvaluator", "ConstraintReport", "ParetoDesign", "SynthesisResult",
           "constraint_reports", "design_mapping", "dominates", "pareto_indices",
           "serial_evaluator", "solve"]

#: evaluates a batch of search vectors, in order
BatchEvaluator = Callable[[Problem, Sequence[Sequence[float]]],
                          list[tuple[Evaluation, dict[str, Any] | None]]]


@shared_parameters
def design_mapping(drive: Drive) -> dict[str, Any]:
    """The dictionary a design file of a drive loads to.

    %(drive_returns)s
    dict
        :func:`chaindrive.io.design.drive_to_mapping` of it.
    """
    return drive_to_mapping(drive)


def serial_evaluator(problem: Problem, xs: Sequence[Sequence[float]]
                     ) -> list[tuple[Evaluation, dict[str, Any] | None]]:
    """Evaluate a batch of search vectors in this process, in order.

    Parameters
    ----------
    problem : Problem
        The synthesis problem.
    xs : sequence of sequence of float
        The search vectors [the unit of each gene].

    Returns
    -------
    list of (Evaluation, dict or None)
        Each evaluation and its design mapping (None when it cannot be decoded).
    """
    out = []
    for x in xs:
        ev, drive = evaluate_vector(problem, x)
        out.append((ev, None if drive is None else design_mapping(drive)))
    return out


@dataclass(frozen=True, slots=True)
class ParetoDesign:
    """One design of the Pareto set.

    Parameters
    ----------
    objectives : dict of str to float
        Objective values, natural sign [the unit of each objective].
    constraints : dict of str to float
        Constraint values g [-] (≤ 0 satisfied).
    constraints_ok : bool
        Every constraint satisfied.
    design : dict
        The TOML mapping of the design.
    vector : tuple of float
        Its search vector [the unit of each gene].
    verification : tuple of dict
        A robust problem's chance constraints re-estimated with an independent sample
        (:func:`chaindrive.robust.synthesis.verify_design`); empty otherwise.
    unverified : dict of str to str
        The checks of its analysis that cannot be verified on any design of the search (the
        chain's fatigue without a catalogue fatigue strength), each with why: constraints ok
        does not cover them.
    """

    objectives: dict[str, float]
    constraints: dict[str, float]
    constraints_ok: bool
    design: dict[str, Any]
    vector: tuple[float, ...]
    verification: tuple[dict[str, Any], ...] = ()
    unverified: dict[str, str] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the ``pareto[]`` items of ``chaindrive optimize --json``)."""
        out = {"objectives": dict(self.objectives), "constraints_ok": self.constraints_ok,
               "constraints": dict(self.constraints), "unverified": dict(self.unverified),
               "design": self.design}
        if self.verification:
            out["verification"] = list(self.verification)
        return out


@dataclass(frozen=True, slots=True)
class ConstraintReport:
    """How one constraint acted on the designs of a run.

    Parameters
    ----------
    name : str
        The constraint (a check key such as ``teeth_in_mesh[S3]``, a wish such as
        ``chain_speed``, or ``buildable``).
    rejected : int
        Designs it rejected (constraint value g > 0).
    evaluated : int
        Designs evaluated in the run.
    least_violation : float | None
        The smallest g [-] of the designs it rejected: by how much the closest one missed, as
        a fraction of the limit (g = −margin of :mod:`chaindrive.checks`); None when it
        rejected none.
    closest : dict | None
        That design (the mapping a TOML design file loads to; None when it could not be
        built).
    error : str | None
        For ``buildable``: the most frequent reason a design could not be built.
    unverified : int
        Of the designs it rejected, those where it is a check that cannot be verified (they
        have no violation to measure: ``least_violation`` is of the others).
    unverified_reason : str | None
        Why it could not be verified (the most frequent note), or None.
    """

    name: str
    rejected: int
    evaluated: int
    least_violation: float | None
    closest: dict[str, Any] | None = None
    error: str | None = None
    unverified: int = 0
    unverified_reason: str | None = None

    @property
    def share(self) -> float:
        """Rejected/evaluated [-] (0 when nothing was evaluated)."""
        return self.rejected / self.evaluated if self.evaluated else 0.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (``constraints[]`` of ``chaindrive optimize --json``)."""
        return {"constraint": self.name, "rejected": self.rejected,
                "evaluated": self.evaluated, "rejected_fraction": self.share,
                "least_violation": self.least_violation,
                "closest_design": self.closest, "error": self.error,
                "cannot_be_verified": self.unverified,
                "cannot_be_verified_reason": self.unverified_reason}


def constraint_reports(rows: Sequence[tuple[Evaluation, dict[str, Any] | None]]
                       ) -> tuple[ConstraintReport, ...]:
    """Every constraint of the evaluated designs with the designs it rejected and the
    closest miss, the most rejecting first.

    Parameters
    ----------
    rows : sequence of (Evaluation, dict | None)
        Each evaluated design with its design mapping (None when it could not be built).

    Returns
    -------
    tuple of ConstraintReport
        One per constraint, the most rejecting first.
    """
    from collections import Counter

    names = list(dict.fromkeys(k for ev, _ in rows for k in ev.constraints))
    out = []
    for name in names:
        missed = [(ev.constraints[name], ev, d) for ev, d in rows
                  if ev.constraints.get(name, 0.0) > 0]
        if not missed:
            out.append(ConstraintReport(name, 0, len(rows), None))
            continue
        unknown = Counter(ev.unverified[name] for _, ev, _ in missed if name in ev.unverified)
        measured = [m for m in missed if name not in m[1].unverified]
        g, _, design = min(measured or missed, key=lambda m: m[0])
        errors = Counter(ev.error for _, ev, _ in missed if ev.error)
        out.append(ConstraintReport(
            name, len(missed), len(rows), float(g) if measured else None, design,
            errors.most_common(1)[0][0] if errors else None, sum(unknown.values()),
            unknown.most_common(1)[0][0] if unknown else None))
    return tuple(sorted(out, key=lambda c: -c.rejected))


@dataclass(frozen=True, slots=True)
class SynthesisResult:
    """The result of a search.

    Parameters
    ----------
    objectives : tuple of str
        The objectives.
    start : Evaluation
        The start design's evaluation.
    pareto : tuple of ParetoDesign
        The Pareto set, sorted by the first objective.
    evaluations : int
        Designs evaluated [-].
    method : str
        The search library.
    seed : int
        The random seed.
    seconds : float
        Wall time [s].
    constraint_report : tuple of ConstraintReport
        How each constraint acted on the designs, the most rejecting first.
    units : tuple of str
        The unit of each objective's value (the cost model's currency for a price).
    feasible_in_search : int
        Designs that met every constraint of the search [-].
    verified : int
        Designs the search found feasible that were judged as ``analyze`` judges their design
        file (every check, the start-up included) to settle the Pareto set [-].
    verified_passed : int
        Of those, the designs that passed [-].
    verification_report : tuple of ConstraintReport
        How each constraint acted on those designs, the most rejecting first.
    """

    objectives: tuple[str, ...]
    start: Evaluation
    pareto: tuple[ParetoDesign, ...]
    evaluations: int
    method: str
    seed: int
    seconds: float
    constraint_report: tuple[ConstraintReport, ...] = ()
    units: tuple[str, ...] = ()
    feasible_in_search: int = 0
    verified: int = 0
    verified_passed: int = 0
    verification_report: tuple[ConstraintReport, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"objectives": list(self.objectives),
                "objective_units": dict(zip(self.objectives, self.units, strict=False)),
                "method": self.method, "seed": self.seed,
                "evaluations": self.evaluations, "seconds": self.seconds,
                "feasible_in_search": self.feasible_in_search,
                "start": self.start.to_dict(), "pareto": [p.to_dict() for p in self.pareto],
                "constraints": [c.to_dict() for c in self.constraint_report],
                "verification": {
                    "verified": self.verified, "passed": self.verified_passed,
                    "constraints": [c.to_dict() for c in self.verification_report]}}


def dominates(a: Sequence[float], b: Sequence[float]) -> bool:
    """Whether a Pareto-dominates b (all minimised): no worse in every objective, better in one.

    Parameters
    ----------
    a, b : sequence of float
        Objective vectors [the unit of each objective].

    Returns
    -------
    bool
        True when a dominates b.

    References
    ----------
    [Deb2002].
    """
    a_, b_ = np.asarray(a), np.asarray(b)
    return bool(np.all(a_ <= b_) and np.any(a_ < b_))


def pareto_indices(F: NDArray[np.float64]) -> list[int]:
    """Indices of the non-dominated rows of F (minimised), duplicates kept once.

    Parameters
    ----------
    F : numpy.ndarray
        (designs, objectives) objective values [the unit of each objective].

    Returns
    -------
    list of int
        The rows of the Pareto front.

    References
    ----------
    [Deb2002].
    """
    keep: list[int] = []
    for i in range(F.shape[0]):
        dominated = np.any(np.all(F[i] >= F, axis=1) & np.any(F[i] > F, axis=1))
        if not dominated and not any(np.array_equal(F[i], F[j]) for j in keep):
            keep.append(i)
    return keep


class _Archive:
    """Every evaluation of a run, for the Pareto set."""

    def __init__(self, problem: Problem, evaluator: BatchEvaluator) -> None:
        self.problem = problem
        self.evaluator = evaluator
        self.rows: list[tuple[tuple[float, ...], Evaluation, dict[str, Any] | None]] = []

    def evaluate(self, X: Sequence[Sequence[float]]) -> list[Evaluation]:
        results = self.evaluator(self.problem, X)
        for x, (ev, design) in zip(X, results, strict=True):
            self.rows.append((tuple(float(v) for v in x), ev, design))
        return [ev for ev, _ in results]

    def feasible(self) -> list[int]:
        """Rows that met every constraint of the search and could be built."""
        return [i for i, r in enumerate(self.rows) if r[1].feasible and r[2] is not None]

    def pareto(self) -> tuple[tuple[ParetoDesign, ...], dict[int, Evaluation]]:
        """The Pareto set of the designs that pass every check of their analysis.

        The front of the designs the search found feasible is taken; each of its designs not
        yet judged is judged as ``analyze`` judges its design file
        (:func:`chaindrive.synthesis.evaluation.verify_mapping`: every check, the start-up
        included); those that fail leave the set and the front is taken again, until every
        design on it has passed. Every returned design then passes, and every feasible design
        off it is dominated by one on it [Deb2002].

        Returns
        -------
        tuple
            The Pareto set (sorted by the objectives) and every verdict, by row.
        """
        names = self.problem.objectives
        verdicts: dict[int, Evaluation] = {}
        while True:
            ok = [i for i in self.feasible() if i not in verdicts or verdicts[i].feasible]
            if not ok:
                return (), verdicts
            F = np.array([self.rows[i][1].minimised(names) for i in ok])
            front = [ok[k] for k in pareto_indices(F)]
            todo = [i for i in front if i not in verdicts]
            if not todo:
                break
            for i in todo:
                verdicts[i] = verify_mapping(self.problem, self.rows[i][2] or {})
        front.sort(key=lambda i: tuple(self.rows[i][1].minimised(names)))
        return tuple(ParetoDesign(verdicts[i].objectives, verdicts[i].constraints, True,
                                  self.rows[i][2] or {}, self.rows[i][0],
                                  unverified=dict(verdicts[i].unverified)) for i in front), \
            verdicts


def _arrays(problem: Problem, evs: Sequence[Evaluation]) -> tuple[NDArray, NDArray]:
    F = np.array([e.minimised(problem.objectives) for e in evs])
    G = np.array([[e.violation()] for e in evs])
    return F, G


def _solve_pymoo(problem: Problem, archive: _Archive, pop: int, gens: int, seed: int) -> None:
    # lazy: pymoo takes seconds to import and only this search method needs it
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem as PymooProblem
    from pymoo.optimize import minimize

    lo, hi = (np.array(b, dtype=float) for b in problem.bounds)

    class _P(PymooProblem):
        def __init__(self) -> None:
            super().__init__(n_var=lo.size, n_obj=len(problem.objectives), n_ieq_constr=1,
                             xl=lo, xu=hi)

        def _evaluate(self, X: NDArray, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
            out["F"], out["G"] = _arrays(problem, archive.evaluate(X.tolist()))

    rng = np.random.default_rng(seed)
    X0 = lo + rng.random((pop, lo.size)) * (hi - lo)
    X0[0] = problem.start_vector()
    minimize(_P(), NSGA2(pop_size=pop, sampling=X0, eliminate_duplicates=True),
             ("n_gen", gens), seed=seed, verbose=False)


def _suggest(trial: Any, problem: Problem) -> list[float]:
    x = []
    for g in problem.genes:
        if g.kind == "int":
            x.append(float(trial.suggest_int(g.name, int(g.low), int(g.high))))
        elif g.kind == "choice":
            x.append(trial.suggest_categorical(g.name, list(range(len(g.choices)))) + 0.5)
        else:
            x.append(trial.suggest_float(g.name, g.low, g.high))
    return x


def _start_params(problem: Problem) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for g, v in zip(problem.genes, problem.start_vector(), strict=True):
        out[g.name] = round(v) if g.kind == "int" else (
            int(v) if g.kind == "choice" else float(v))
    return out


def _solve_optuna(problem: Problem, archive: _Archive, pop: int, gens: int, seed: int) -> None:
    # lazy: optuna (with sqlalchemy) takes seconds to import and only this method needs it
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
        sampler = optuna.samplers.NSGAIISampler(population_size=pop, seed=seed)
        study = optuna.create_study(directions=["minimize"] * len(problem.objectives),
                                    sampler=sampler)
        study.enqueue_trial(_start_params(problem))
        for _ in range(gens):
            trials = [study.ask() for _ in range(pop)]
            xs = [_suggest(t, problem) for t in trials]
            for t, ev in zip(trials, archive.evaluate(xs), strict=True):
                t.set_constraint("violation", ev.violation())
                study.tell(t, ev.minimised(problem.objectives))


def _verified(problem: Problem, design: ParetoDesign) -> ParetoDesign:
    """A Pareto design of a robust problem with its chance constraints re-estimated on an
    independent sample (:func:`chaindrive.robust.synthesis.verify_design`)."""
    a = analysis_of(problem.decode(design.vector), problem.constraints,
                    robust=problem.robust)
    if not isinstance(a, RobustAnalysis):
        return design
    return replace(design, verification=tuple(v.to_dict() for v in verify_design(a)))


def solve(problem: Problem, *, method: str | None = None, population: int | None = None,
          generations: int | None = None, seed: int | None = None,
          evaluator: BatchEvaluator | None = None) -> SynthesisResult:
    """Search the Pareto set of a synthesis problem.

    Parameters
    ----------
    problem : Problem
        The problem.
    method : str or None
        ``"optuna"`` (Optuna NSGAIISampler) or ``"nsga2"`` (pymoo) [Deb2002].
    population, generations : int or None
        [-] (default: the problem's ``[optimize.solver]``).
    seed : int or None
        Random seed (default: the problem's).
    evaluator : callable or None
        Evaluates a batch of vectors in order (default :func:`serial_evaluator`;
        :class:`chaindrive.synthesis.studies.DaskEvaluator` spreads a population over a Dask
        cluster and stores it in a study database).

    Returns
    -------
    SynthesisResult
        The Pareto set and the start design's evaluation.
    """
    s = problem.solver
    method = method or s.method
    pop, gens = population or s.population, generations or s.generations
    seed = s.seed if seed is None else seed
    archive = _Archive(problem, evaluator or serial_evaluator)
    t0 = time.perf_counter()
    # the start is the design as the file gives it (analysed as ``chaindrive analyze`` does),
    # whatever the search space; its nearest search vector seeds the first generation
    start = evaluate_drive(problem.base, problem.objectives, problem.constraints,
                           base_ratios=base_ratios(problem.base),
                           ratio_tolerance=problem.ratio_tolerance, robust=problem.robust,
                           every_check=True)
    if method == "nsga2":
        _solve_pymoo(problem, archive, pop, gens, seed)
    elif method == "optuna":
        _solve_optuna(problem, archive, pop, gens, seed)
    else:
        raise DesignError("optimize.solver.method", f'must be "nsga2" or "optuna", got {method!r}')
    pareto, verdicts = archive.pareto()
    if problem.robust is not None:  # what a robust search reports is its independent check
        pareto = tuple(_verified(problem, p) for p in pareto)
    currency = default_cost_model().currency  # the designs are priced by the default model
    judged = [(ev, archive.rows[i][2]) for i, ev in verdicts.items()]
    return SynthesisResult(problem.objectives, start, pareto, len(archive.rows),
                           method, seed, time.perf_counter() - t0,
                           constraint_reports([(ev, d) for _, ev, d in archive.rows]),
                           tuple(objective_unit(n, currency) for n in problem.objectives),
                           feasible_in_search=len(archive.feasible()), verified=len(verdicts),
                           verified_passed=sum(ev.feasible for ev in verdicts.values()),
                           verification_report=tuple(
                               c for c in constraint_reports(judged) if c.rejected))
