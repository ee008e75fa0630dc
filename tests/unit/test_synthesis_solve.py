"""Multi-objective synthesis on the 8-sprocket example: a Pareto set of designs that pass
every check `analyze` makes of the design files written for them, reproducible with a seed;
polymer sprockets, whose teeth cannot be verified, never in it; and when a constraint
empties the set, the result says which and on how many designs.

The budget is small (8 × 4 designs, seed 2, ~15 s on the loaded 2-core machine): enough for
a front of two designs, each re-analysed from its written TOML.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import chaindrive
from chaindrive.io.design import drive_from_mapping
from chaindrive.synthesis.evaluation import evaluate_drive
from chaindrive.synthesis.problem import load_problem, problem_from_mapping
from chaindrive.synthesis.solve import dominates, pareto_indices, solve
from chaindrive.synthesis.workflow import pareto_design_files, pareto_drives
from tests.conftest import EXAMPLES

pytest.importorskip("pymoo")
pytest.importorskip("optuna")
FILE = EXAMPLES / "eight_sprocket_optimize.toml"
BUDGET = {"population": 8, "generations": 4, "seed": 2}
#: the designer's wishes beyond the checks (evaluation._wishes)
WISHES = {"buildable", "chain_speed", "min_driver_wrap", "min_teeth_in_mesh", "ratio",
          "min_static_safety"}


@pytest.fixture(scope="module")
def problem():
    return load_problem(FILE)


@pytest.fixture(scope="module")
def result(problem):
    return solve(problem, **BUDGET)


def test_start_is_judged_as_analyze_judges_it(problem, result) -> None:
    assert problem.solver.method == "optuna"  # the example uses the default
    # the example's start lies 5 % from the parametric resonance of a span: analyze fails it
    # and so does the optimiser, on the same checks; the chain's fatigue is judged against
    # the estimate 15 % of the breaking load (no fatigue strength in the catalogue), so it is
    # a constraint like the others and nothing is left unverified
    failed = {c.key for c in chaindrive.analyze(problem.base).checks() if c.status == "fail"}
    assert failed == {"resonance_margin"}
    assert result.start.unverified == {}
    assert not result.start.feasible
    assert {k for k, v in result.start.constraints.items() if v > 0} - WISHES == failed
    assert result.evaluations == 8 * 4  # the start, as the file gives it, is evaluated apart


def test_front_is_non_dominated_and_every_design_re_analyses_clean(problem, result,
                                                                    tmp_path: Path) -> None:
    """Each Pareto design, written as the TOML `optimize --out` writes and loaded back,
    passes every check of `analyze`; no design of the set dominates another."""
    assert len(result.pareto) >= 2, [c.to_dict() for c in result.constraint_report[:3]]
    assert result.verified_passed == len(result.pareto) <= result.verified
    assert result.verified <= result.feasible_in_search
    names = problem.objectives
    vectors = [[p.objectives[n] for n in names] for p in result.pareto]  # all minimised
    assert not any(dominates(a, b) for a in vectors for b in vectors if a is not b)
    for f in pareto_design_files(pareto_drives(result, FILE.parent), "eight"):
        path = tmp_path / f.name
        path.write_text(f.text, encoding="utf-8")
        a = chaindrive.analyze(chaindrive.load(path))
        # no check fails, nor is any left unverified (the chain's fatigue is judged against
        # its estimated strength)
        bad = [(c.key, c.status) for c in a.checks() if not c.passed]
        assert not bad, (f.name, bad)
    for p in result.pareto:
        assert p.constraints_ok and all(v <= 0 for v in p.constraints.values())
        assert p.unverified == {} and p.to_dict()["unverified"] == {}
        assert p.design["sprockets"][0].get("material", "steel") == "steel"


def test_polymer_designs_are_never_feasible(problem) -> None:
    """The example offers PA66 sprockets; their teeth cannot be verified (no confirmed
    allowable), so such a design fails, naming the checks and why."""
    steel = problem.decode(problem.start_vector())
    material = next(i for i, g in enumerate(problem.genes) if g.target == "material")
    x = problem.start_vector()
    x[material] = 1.5  # the second choice: PA66
    polymer = problem.decode(x)
    assert {s.material for s in polymer.sprockets} == {"PA66"}
    ev = evaluate_drive(polymer, problem.objectives, problem.constraints)
    assert not ev.feasible
    teeth = {k for k in ev.unverified if k.startswith("tooth_")}
    assert teeth == {f"{n}[{s.name}]" for s in polymer.sprockets
                     for n in ("tooth_root_stress", "tooth_contact_pressure")}
    assert all(ev.constraints[k] == 1.0 and "permissible" in ev.unverified[k] for k in teeth)
    assert not any(k.startswith("tooth_") for k in
                   evaluate_drive(steel, problem.objectives, problem.constraints).constraints)


def test_an_unverifiable_start_up_empties_the_set_and_is_named(problem) -> None:
    """Asked for a start-up (transient = true) without a motor or machines, k1 cannot be
    verified on any design (analyze says so); the optimiser returns nothing and names k1 as
    the constraint that rejected every design and why, without running a start-up."""
    data = tomllib.loads(FILE.read_text(encoding="utf-8"))
    data["dynamics"]["transient"] = True
    data["optimize"]["solver"].update(population=4, generations=2)
    r = solve(problem_from_mapping(data, FILE.parent))
    assert r.pareto == () and r.verified == 0
    k1 = next(c for c in r.constraint_report if c.name == "k1")
    assert k1.rejected == k1.evaluated == k1.unverified == r.evaluations
    assert k1.least_violation is None and "incomplete" in (k1.unverified_reason or "")
    doc = r.to_dict()
    row = next(c for c in doc["constraints"] if c["constraint"] == "k1")
    assert row["rejected_fraction"] == 1.0 and row["cannot_be_verified"] == r.evaluations
    base = drive_from_mapping({k: v for k, v in data.items() if k != "optimize"}, FILE.parent)
    k1_check = chaindrive.analyze(base).check("k1")
    assert k1_check is not None and k1_check.status == "cannot be verified"
    # the command's table says it in words
    import io

    from rich.console import Console

    from chaindrive.cli import tables

    buffer = io.StringIO()
    tables.print_optimisation("eight", r, [], Console(file=buffer, width=400, highlight=False))
    out = " ".join(buffer.getvalue().split())
    assert f"0 of {r.evaluations} designs met every constraint of the search" in out
    assert f"cannot be verified on {r.evaluations}: the dynamic model is incomplete" in out


def test_same_seed_same_pareto_set(problem) -> None:
    a, b = (solve(problem, population=4, generations=2, seed=5) for _ in range(2))
    assert [p.objectives for p in a.pareto] == [p.objectives for p in b.pareto]
    assert [c.to_dict() for c in a.constraint_report] == [c.to_dict() for c in
                                                           b.constraint_report]


def test_screening_by_the_sweep_maxima_keeps_the_search(problem, monkeypatch) -> None:
    """The search screens designs by the speed sweep's maxima alone (a bounded search of its
    speeds); with the whole sweep for every design instead, as before, the same seed gives
    every design the same constraint values (k₂min among them), hence the same search and
    the same Pareto set."""
    from chaindrive.synthesis import evaluation

    whole, evaluate = evaluation.analysis_of, evaluation.evaluate_drive
    runs: list[list[dict[str, float]]] = []

    def recorded(*args, **kwargs):  # type: ignore[no-untyped-def]
        ev = evaluate(*args, **kwargs)
        runs[-1].append(ev.constraints)
        return ev

    def full_sweep(*args, **kwargs):  # type: ignore[no-untyped-def]
        return whole(*args, **{**kwargs, "sweep_curve": True})

    monkeypatch.setattr(evaluation, "evaluate_drive", recorded)
    runs.append([])
    screened = solve(problem, population=4, generations=2, seed=3).to_dict()
    monkeypatch.setattr(evaluation, "analysis_of", full_sweep)
    runs.append([])
    before = solve(problem, population=4, generations=2, seed=3).to_dict()
    assert sum("k2min" in c for c in runs[0]) >= 4
    assert len(runs[0]) == len(runs[1])
    for a, b in zip(*runs, strict=True):
        assert a.keys() == b.keys() and list(a.values()) == pytest.approx(list(b.values()),
                                                                          rel=1e-12)
    screened.pop("seconds"), before.pop("seconds")
    assert screened == before


def test_pymoo_backend_runs_and_is_reproducible(problem) -> None:
    a = solve(problem, method="nsga2", population=4, generations=2, seed=2)
    b = solve(problem, method="nsga2", population=4, generations=2, seed=2)
    assert 4 <= a.evaluations <= 4 * 2
    assert [p.objectives for p in a.pareto] == [p.objectives for p in b.pareto]


def test_pareto_indices_keeps_non_dominated_rows() -> None:
    import numpy as np

    F = np.array([[1.0, 3.0], [2.0, 2.0], [3.0, 1.0], [2.5, 2.5], [1.0, 3.0]])
    assert pareto_indices(F) == [0, 1, 2]


def test_to_dict_is_json_ready(result) -> None:
    import json

    d = json.loads(json.dumps(result.to_dict()))
    assert {"objectives", "constraints_ok", "design"} <= set(d["pareto"][0])
    assert d["pareto"][0]["design"]["chain"]["designation"].startswith("ISO 606")
    assert d["verification"]["passed"] == len(d["pareto"])
    assert d["feasible_in_search"] == result.feasible_in_search
    assert all(0 <= c["rejected_fraction"] <= 1 for c in d["constraints"])
