"""The robust study of a drive: its uncertainty model, its life curve, its probabilities of
failure and the sensitivity indices, in one result — in this process or on Dask with the
study store (:mod:`chaindrive.synthesis.studies`: every state is stored once under the hash
of its inputs, so a study that stops resumes where it stopped).

References
----------
See :mod:`chaindrive.robust.uncertainty`, :mod:`.life`, :mod:`.sampling`, :mod:`.sensitivity`.
"""

from __future__ import annotations

import hashlib
import json
import math
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping, drive_to_mapping, load_drive
from chaindrive.model import Drive
from chaindrive.robust.analysis import PerturbedAnalysis, nominal_analysis
from chaindrive.robust.life import LifeCurve, life_curve
from chaindrive.robust.sampling import (
    METRICS,
    ModalBasis,
    ReliabilityResult,
    StateEvaluator,
    StateOutcome,
    basis_reliability,
    modal_basis,
    reliability,
    state_outcome,
)
from chaindrive.robust.sensitivity import SensitivityResult, sensitivity
from chaindrive.robust.uncertainty import (
    UncertaintyModel,
    UncertaintySettings,
    load_uncertainty,
    uncertainty_model,
    uncertainty_settings,
)
from chaindrive.synthesis.problem import Problem, problem_from_mapping
from chaindrive.synthesis.studies import DEFAULT_DB, StudyStore, run_study

__all__ = ["DaskOptions", "RobustResult", "StudyProgress", "dask_states", "load_robust", "nominal_analysis",
           "robust_batch", "robust_state", "robust_study", "shared_modal_basis",
           "without_flywheels"]


@shared_parameters
def load_robust(path: str | Path) -> tuple[Analysis, UncertaintySettings]:
    """The nominal analysis of a design file and its ``[uncertainty]`` table.

    %(params_design_path_returns)s
    tuple of (Analysis, UncertaintySettings)
        The nominal analysis (:func:`~chaindrive.robust.analysis.nominal_analysis`) and the
        settings (defaults when the file has no ``[uncertainty]`` table).
    """
    return nominal_analysis(load_drive(path)), load_uncertainty(path)


def _design_of(nominal: Analysis) -> Drive:
    """The design with the chain it was analysed with (a selected chain written by name)."""
    d = nominal.design
    return d.with_chain(nominal.drive.chain.spec) if d.chain.request is not None else d


@lru_cache(maxsize=8)
def _rebuilt(design: str, settings: str) -> tuple[Analysis, UncertaintyModel]:
    """A worker's nominal analysis and model, built once per process and design."""
    nominal = nominal_analysis(drive_from_mapping(json.loads(design)))
    return nominal, uncertainty_model(nominal, UncertaintySettings(**json.loads(settings)))


def robust_state(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """Worker function of a robust study: one perturbed state of a design.

    Parameters
    ----------
    inputs : mapping
        ``{"design": JSON of the design mapping, "settings": JSON of the
        UncertaintySettings, "x": variable values [SI], "response": bool}``.

    Returns
    -------
    dict
        The state's :class:`~chaindrive.robust.sampling.StateOutcome` as a dict.
    """
    nominal, model = _rebuilt(inputs["design"], inputs["settings"])
    state = PerturbedAnalysis(nominal, model.perturbation(np.asarray(inputs["x"], dtype=float)),
                              allowable_elongation=model.allowable_elongation,
                              take_up_capacity=model.take_up_capacity,
                              response=bool(inputs["response"]))
    return state_outcome(state).to_dict()


@dataclass(frozen=True, slots=True)
class DaskOptions:
    """Where a robust study runs and is stored.

    Parameters
    ----------
    db : str | StudyStore
        Study store URL or an open store.
    study : str | None
        Study name (None: ``robust-<hash of design and settings>``).
    scheduler : str | None
        Address of a Dask scheduler (None: a local cluster).
    client : Any
        An existing ``distributed.Client`` (takes precedence).
    n_workers : int | None
        Workers of the local cluster (None: Dask's default).
    progress : bool | None
        Progress bar (None: on a terminal only).
    """

    db: str | StudyStore = DEFAULT_DB
    study: str | None = None
    scheduler: str | None = None
    client: Any = None
    n_workers: int | None = None
    progress: bool | None = None


def dask_states(options: DaskOptions) -> StateEvaluator:
    """A state evaluator that runs on Dask and stores every state (resumable).

    Parameters
    ----------
    options : DaskOptions
        Where the states run and are stored.

    Returns
    -------
    StateEvaluator
        ``evaluate(nominal, model, x, response)`` → one outcome per row of ``x``.
    """

    def evaluate(nominal: Analysis, model: UncertaintyModel, x: NDArray[np.float64],
                 response: bool) -> list[StateOutcome]:
        design = json.dumps(drive_to_mapping(_design_of(nominal)), sort_keys=True)
        settings = json.dumps(asdict(model.settings), sort_keys=True)
        name = options.study or "robust-" + hashlib.sha256(
            (design + settings).encode()).hexdigest()[:16]
        inputs = [{"design": design, "settings": settings, "x": [float(v) for v in row],
                   "response": response} for row in x]
        result = run_study(robust_state, inputs, study=name, db=options.db,
                           scheduler=options.scheduler, client=options.client,
                           n_workers=options.n_workers, progress=options.progress)
        return [StateOutcome.from_dict(r) if "status" in r
                else StateOutcome({}, {}, dict.fromkeys(METRICS, math.nan), str(r.get("error")))
                for r in result.results]

    return evaluate


#: ``progress(stage, done, total)``: a stage of the study ("probabilities", "life curve",
#: "sensitivity") has ``done`` of ``total`` states evaluated (a presenter draws it).
StudyProgress = Callable[[str, int, int], None]


@dataclass(frozen=True, slots=True, eq=False)
class RobustResult:
    """The robust study of a drive.

    Parameters
    ----------
    name : str
        The drive's name.
    model : UncertaintyModel
        Its uncertainty model.
    life : LifeCurve
        From new to past the replacement elongation.
    reliability : ReliabilityResult
        Probabilities of failure (full path).
    sensitivity : SensitivityResult | None
        Sobol indices (None when not asked for or fewer than two groups).
    """

    name: str
    model: UncertaintyModel
    life: LifeCurve
    reliability: ReliabilityResult
    sensitivity: SensitivityResult | None

    def to_dict(self) -> dict[str, Any]:
        """The JSON document of ``chaindrive robust --json``."""
        return {"drive": self.name, "uncertainty": self.model.to_dict(),
                "life": self.life.to_dict(), "reliability": self.reliability.to_dict(),
                "sensitivity": None if self.sensitivity is None else self.sensitivity.to_dict()}


def robust_study(nominal: Analysis, settings: UncertaintySettings | None = None, *,
                 with_sensitivity: bool = True, life_points: int = 13, path: str = "full",
                 evaluator: StateEvaluator | None = None,
                 sensitivity_budget: int | None = None,
                 sensitivity_target: float | None = None,
                 progress: StudyProgress | None = None) -> RobustResult:
    """Life curve, probabilities of failure and sensitivity indices of a drive.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn (:func:`nominal_analysis`).
    settings : UncertaintySettings | None
        Its ``[uncertainty]`` table (None: defaults).
    with_sensitivity : bool
        Compute the Sobol indices too (of the metrics, and of the margins of up to three
        checks whose probability of failure lies strictly between 0 and 1).
    life_points : int
        Points of the life curve.
    path : str
        "full" or "modal" for the probabilities (:func:`chaindrive.robust.sampling.reliability`).
    evaluator : StateEvaluator | None
        Where the states run (None: this process; :func:`dask_states` for Dask).
    sensitivity_budget : int | None
        Evaluations the adaptive Sobol sample may spend [–]
        (:func:`chaindrive.robust.sensitivity.sensitivity`; None: the settings').
    sensitivity_target : float | None
        Half-width it aims at for every metric's leading total index [–] (None: the
        settings').
    progress : callable | None
        ``progress(stage, done, total)`` as the states are evaluated (per state in this
        process; per stage on Dask, which draws its own bar).

    Returns
    -------
    RobustResult
    """
    def stage(name: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress(name, done, total)

    model = uncertainty_model(nominal, settings)
    step = stage("probabilities")
    if step is not None:
        step(0, 0)
    rel = reliability(nominal, model, path=path, evaluator=evaluator, progress=step)
    if step is not None:
        step(rel.evaluated_states, rel.evaluated_states)
    step = stage("life curve")
    if step is not None:
        step(0, life_points)
    life = life_curve(nominal, model, points=life_points)
    if step is not None:
        step(life_points, life_points)
    uncertain = [c.key for c in rel.checks
                 if 0.0 < c.probability < 1.0 and c.key not in ("any", "buildable")][:3]
    return RobustResult(
        nominal.drive.name, model, life, rel,
        sensitivity(nominal, model, evaluator=evaluator, checks=uncertain,
                    budget=model.settings.sensitivity_budget if sensitivity_budget is None
                    else sensitivity_budget,
                    target=model.settings.sensitivity_target if sensitivity_target is None
                    else sensitivity_target,
                    progress=stage("sensitivity"))
        if with_sensitivity else None)


#: Bases kept per process by :func:`shared_modal_basis` (most recently used last).
_SHARED_BASES: dict[str, ModalBasis] = {}
#: How many bases a process keeps (one takes ≈ 2.5 MB per geometric state for 24 sprockets
#: and 128 samples; a search whose variables move the geometry misses every time).
SHARED_BASES = 4


def without_flywheels(design: Drive) -> tuple[Drive, NDArray[np.float64]]:
    """The design with no flywheel on any shaft, and the flywheels it had.

    Parameters
    ----------
    design : Drive
        The design.

    Returns
    -------
    tuple of (Drive, ndarray)
        The design without flywheels; (n,) the flywheels ΔJ [kg·m²] in sprocket order.
    """
    added = np.array([s.flywheel for s in design.sprockets], dtype=float)
    return replace(design, sprockets=tuple(replace(s, flywheel=0.0) if s.flywheel else s
                                           for s in design.sprockets)), added


def shared_modal_basis(design: Drive, settings: UncertaintySettings
                       ) -> tuple[ModalBasis, NDArray[np.float64] | None]:
    """The batched modal path of a design built up to its frequencies, shared by every design
    this process sees that differs from it only in its flywheels.

    A flywheel enters the modal path only as inertia on its sprocket's shaft
    (:func:`chaindrive.robust.modal.stacked_margins`): the geometry, the static tensions,
    the stiffnesses, the model's topology, the working frequencies and the uncertainty model
    do not depend on it. So the basis is that of the design without flywheels
    (:func:`without_flywheels`), kept under the value of that design and of the settings —
    their ``repr``, which for these frozen dataclasses of numbers, strings and tuples
    spells every value out (a float's repr reads back to the same float), so any other
    input (a tooth count, a position, a chain, a material, a train) gives another key and
    a basis of its own. A design whose chain is to be selected is not shared (the selection
    checks the resonance of each candidate, which the flywheels move): its basis is its own,
    flywheels included.

    Parameters
    ----------
    design : Drive
        The design.
    settings : UncertaintySettings
        Its ``[uncertainty]`` table.

    Returns
    -------
    tuple of (ModalBasis, ndarray | None)
        The basis and the inertias (n,) to add on the shafts [kg·m²] (None: none, the basis
        is the design's own).
    """
    if design.chain.request is not None:
        nominal = nominal_analysis(design)
        return modal_basis(nominal, uncertainty_model(nominal, settings)), None
    twin, added = without_flywheels(design)
    key = repr((twin, settings))
    basis = _SHARED_BASES.pop(key, None)
    if basis is None:
        nominal = nominal_analysis(twin)
        basis = modal_basis(nominal, uncertainty_model(nominal, settings))
    _SHARED_BASES[key] = basis
    while len(_SHARED_BASES) > SHARED_BASES:
        del _SHARED_BASES[next(iter(_SHARED_BASES))]
    return basis, added


@lru_cache(maxsize=4)
def _problem(text: str) -> Problem:
    """An optimisation problem read once per process and text."""
    return problem_from_mapping(tomllib.loads(text))


def robust_batch(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """Worker function of a robust study of many designs by the batched modal path:
    ``{"problem": TOML text of a design file with [optimize] (and [uncertainty]),
    "vectors": search vectors}`` → ``{"designs": [...]}``, per vector the probability of the
    resonance check with its interval, the 5 % quantiles of f₁ [Hz] and of the resonance
    margin [%] (or the reason the design cannot be built).

    The designs are the problem's (:meth:`chaindrive.synthesis.problem.Problem.decode`), the
    uncertainty model its ``[uncertainty]`` table (``[optimize.robust]`` samples when given).
    Designs that differ only in their flywheels share one basis (:func:`shared_modal_basis`).

    Parameters
    ----------
    inputs : mapping
        ``{"problem": TOML text, "vectors": list of search vectors}``.

    Returns
    -------
    dict
        ``{"designs": [...]}``, one entry per vector: ``resonance_probability``,
        ``ci_low``, ``ci_high`` [-], ``samples``, ``f1_p05_hz`` [Hz],
        ``resonance_margin_p05_percent`` [%]; or ``{"error": message}``.
    """
    problem = _problem(inputs["problem"])
    settings = (problem.robust.uncertainty if problem.robust is not None
                else uncertainty_settings(tomllib.loads(inputs["problem"]).get("uncertainty")))
    out: list[dict[str, Any]] = []
    for x in inputs["vectors"]:
        try:
            basis, added = shared_modal_basis(problem.decode(x), settings)
            r = basis_reliability(basis, added)
        except ChainDriveError as exc:
            out.append({"error": str(exc)})
            continue
        c = r.checks[0]
        out.append({"resonance_probability": c.probability, "ci_low": c.low,
                    "ci_high": c.high, "samples": c.samples,
                    "f1_p05_hz": r.quantile("f1_hz", 0.05),
                    "resonance_margin_p05_percent": r.quantile("resonance_margin_percent",
                                                               0.05)})
    return {"designs": out}
