"""Robust synthesis: ``[optimize.robust]`` chance constraints and robust objectives in the
optimiser (chaindrive.robust.synthesis and its hooks in chaindrive.synthesis).

A chance constraint P(check fails) ≤ α is the α-quantile of the check's margin ≥ 0
(the value-at-risk form, [Rockafellar2000]): a design satisfies it exactly when at most a
fraction α of its states fail — checked here against the counted probability.
"""

from __future__ import annotations

import copy
import math
import tomllib

import pytest

from chaindrive import examples
from chaindrive.errors import DesignError
from chaindrive.robust.synthesis import ROBUST_OBJECTIVES, RobustAnalysis
from chaindrive.synthesis.evaluation import analysis_of, evaluate_drive
from chaindrive.synthesis.objectives import OBJECTIVES
from chaindrive.synthesis.problem import problem_from_mapping
from chaindrive.synthesis.solve import solve


def _data() -> dict:
    data = tomllib.loads(examples.text("eight_sprocket_optimize"))
    data["optimize"]["objectives"] = ["cost", "mass"]
    data["optimize"]["solver"].update(population=4, generations=2, seed=3)
    data["uncertainty"] = {"samples": 16, "replicates": 4, "wear_states": 4}
    return data


def test_robust_table_is_read_and_checked() -> None:
    data = _data()
    assert problem_from_mapping(data).robust is None
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.01}}
    p = problem_from_mapping(data)
    assert p.robust is not None and p.robust.path == "modal"   # resonance only: batched
    assert p.robust.uncertainty.samples == 32                  # [optimize.robust] default
    data["optimize"]["robust"] = {"chance": {"k2": 0.001}, "samples": 8}
    assert problem_from_mapping(data).robust.path == "full"
    for bad, field in (({"chance": {"k2": 0.7}}, "optimize.robust.chance.k2"),
                       ({"samples": 8}, "optimize.robust"),
                       ({"chance": {"k2": 0.01}, "path": "modal"}, "optimize.robust.path"),
                       ({"chanse": {}}, "optimize.robust.chanse")):
        data["optimize"]["robust"] = bad
        with pytest.raises(DesignError, match=field.replace(".", r"\.")):
            problem_from_mapping(data)
    data["optimize"].pop("robust")
    data["optimize"]["objectives"] = ["cost", "kd_p95"]
    with pytest.raises(DesignError, match=r"optimize\.robust"):
        problem_from_mapping(data)
    assert set(ROBUST_OBJECTIVES) <= set(OBJECTIVES)


def test_chance_constraint_is_the_quantile_of_the_margin() -> None:
    data = _data()
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.25}, "samples": 16}
    p = problem_from_mapping(data)
    a = analysis_of(p.base, p.constraints, robust=p.robust)
    assert isinstance(a, RobustAnalysis)
    ev = evaluate_drive(p.base, p.objectives, p.constraints, robust=p.robust)
    g = ev.constraints["P(resonance_margin)"]
    counted = a.robust.probability("resonance_margin").probability
    # g ≤ 0 ⇔ at most 25 % of the states fail the resonance check
    assert (g <= 0) == (counted <= 0.25)
    assert ev.feasible is False                 # the start fails its resonance margin anyway


def test_robust_search_keeps_its_chance_constraint() -> None:
    data = _data()
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.05}, "samples": 16}
    result = solve(problem_from_mapping(data))
    assert result.evaluations == 8
    assert "P(resonance_margin)" in result.start.constraints
    for design in result.pareto:
        assert design.constraints["P(resonance_margin)"] <= 0.0


def test_robust_objective_kd_p95() -> None:
    data = _data()
    data["optimize"]["objectives"] = ["cost", "kd_p95"]
    data["optimize"]["robust"] = {"samples": 8}
    data["uncertainty"].update(replicates=2, wear="new")
    p = problem_from_mapping(data)
    assert p.robust.path == "full"
    ev = evaluate_drive(p.base, p.objectives, p.constraints, robust=p.robust)
    kd = ev.objectives["kd_p95"]
    nominal = evaluate_drive(p.base, ["coefficient_of_dynamics"], p.constraints)
    assert math.isfinite(kd) and kd >= 1.0
    # the 95th percentile over the tolerances is not below the drawing's K_D by much
    assert kd > 0.98 * nominal.objectives["coefficient_of_dynamics"]
    plain = copy.deepcopy(p)
    with pytest.raises(DesignError, match="kd_p95"):
        OBJECTIVES["kd_p95"].value(analysis_of(plain.base, plain.constraints))
