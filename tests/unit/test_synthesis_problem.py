"""The [optimize] table: variables, objectives, constraints, validation in the one-line
DesignError style of io/design.py; cost model; objective registry."""

from __future__ import annotations

import copy
import math
import tomllib

import pytest

from chaindrive.analysis import Analysis
from chaindrive.cost import cost_model_from_mapping, default_cost_model
from chaindrive.errors import DesignError
from chaindrive.metrics import sprocket_body_masses
from chaindrive.synthesis.evaluation import constraint_names, evaluate_drive, evaluate_vector
from chaindrive.synthesis.objectives import OBJECTIVES
from chaindrive.synthesis.problem import load_problem, problem_from_mapping
from tests.conftest import EXAMPLES

FILE = EXAMPLES / "eight_sprocket_optimize.toml"


@pytest.fixture(scope="module")
def data() -> dict:
    return tomllib.loads(FILE.read_text(encoding="utf-8"))


def test_example_problem_genes_and_start(data) -> None:
    p = load_problem(FILE)
    names = [g.name for g in p.genes]
    assert names[0] == "teeth.M"  # the driver first: the ratio genes depend on it
    assert {"x.I1", "y.I1", "chain", "strands", "material"} <= set(names)
    start = p.decode(p.start_vector())
    assert [s.teeth for s in start.sprockets] == [s.teeth for s in p.base.sprockets]
    assert start.chain.spec.designation == p.base.chain.spec.designation
    assert (start.sprockets[2].x, start.sprockets[2].y) == (p.base.sprockets[2].x,
                                                            p.base.sprockets[2].y)


def test_ratio_genes_keep_the_driven_speeds(data) -> None:
    p = load_problem(FILE)
    for u in (0.0, 0.3, 0.99):
        x = p.start_vector()
        x[0] = 19  # driver teeth
        x[1:6] = [u] * 5
        d = p.decode(x)
        for s, s0 in zip(d.sprockets, p.base.sprockets, strict=True):
            if s.role == "driven":
                i0 = s0.teeth / p.base.driver.teeth
                assert abs(s.teeth / 19 - i0) <= 0.03 * i0 + 1e-12


@pytest.mark.parametrize(("edit", "message"), [
    (lambda o: o.update(objectives=["cost", "weight"]),
     "optimize.objectives[1]: unknown objective 'weight'"),
    (lambda o: o["teeth"].update(X9=[10, 20]), "optimize.teeth.X9: no sprocket named 'X9'"),
    (lambda o: o["teeth"].update(M=[21, 15]), "optimize.teeth.M: low must not exceed high"),
    (lambda o: o["teeth"].update(M=[3, 15]), "optimize.teeth.M[0]: must be a whole number from 6"),
    (lambda o: o["position"].update(D2={"x": ["0 mm", "1 mm"]}),
     "optimize.position.D2: only idler or adjustable sprockets may move"),
    (lambda o: o["position"]["I1"].update(x=["1 kg", "2 kg"]), "optimize.position.I1.x[0]"),
    (lambda o: o["chain"].update(designations=["ISO 606 99Z-1"]),
     "optimize.chain.designations[0]"),
    (lambda o: o["material"].update(sprockets=["unobtainium"]), "optimize.material.sprockets[0]"),
    (lambda o: o["solver"].update(method="genetic"), "optimize.solver.method: must be one of"),
    (lambda o: o["constraints"].update(min_drive_wrap="120 deg"),
     "optimize.constraints.min_drive_wrap: unknown field"),
    (lambda o: o.update(budget=3), "optimize.budget: unknown field"),
])
def test_bad_optimize_tables_give_one_line_errors(data, edit, message) -> None:
    bad = copy.deepcopy(data)
    edit(bad["optimize"])
    with pytest.raises(DesignError) as err:
        problem_from_mapping(bad)
    assert message in str(err.value) and "\n" not in str(err.value)


def test_constraints_parse_units(data) -> None:
    p = problem_from_mapping(data)
    assert p.constraints.min_driver_wrap == pytest.approx(math.radians(120))
    assert p.constraints.max_chain_speed == pytest.approx(15.0)


def test_registry_has_the_objectives_and_the_constraints_are_analysis_checks(data) -> None:
    assert {"cost", "mass", "volume", "chain_length", "coefficient_of_dynamics",
            "resonance_margin", "normalised_amplitude", "detuning"} <= set(OBJECTIVES)
    p = problem_from_mapping(data)
    analysis = Analysis(p.base, startup=False)
    names = constraint_names(analysis, p.constraints)
    assert {"static_safety", "speed_limit", "power_rating", "resonance_margin", "k2",
            "k2min"} <= set(names)
    assert {f"teeth_in_mesh[{s.name}]" for s in p.base.sprockets} <= set(names)
    # every constraint but the designer's wishes is a check of the analysis, except k1
    # (a start-up per design), the idlers' side (no variable changes it) and a fatigue check
    # that cannot be verified for any design (no fatigue strength in the catalogue)
    checks = Analysis(p.base).checks()
    unconstrained = {"k1"} | {c.key for c in checks if c.name == "idler on slack span"
                              or (c.name == "fatigue" and c.limit is None)}
    assert set(names) == {c.key for c in checks} - unconstrained
    ev = evaluate_drive(p.base, p.objectives, p.constraints)
    wishes = {"buildable", "chain_speed", "min_driver_wrap", "min_teeth_in_mesh"}
    assert set(ev.constraints) == wishes | set(names)


def test_objective_values_follow_their_definitions(data) -> None:
    p = problem_from_mapping(data)
    ev, drive = evaluate_vector(p, p.start_vector())
    s = Analysis(drive)
    spec = drive.chain.spec
    bodies = sprocket_body_masses(drive)
    assert ev.objectives["chain_length"] == pytest.approx(s.geometry.chain_length)
    chain_mass = spec.mass_per_length * s.geometry.chain_length
    assert ev.objectives["mass"] == pytest.approx(bodies.sum() + chain_mass)
    cm = default_cost_model()
    expected = (bodies.sum() * cm.part_price_per_kg("steel")
                + sum(sp.teeth for sp in drive.sprockets) * cm.per_tooth["steel"]
                + s.geometry.chain_length * cm.chain_per_kg * spec.mass_per_length)
    assert ev.objectives["cost"] == pytest.approx(expected)
    xs = [g.x for g in s.geometry.sprockets]
    assert ev.objectives["volume"] > (max(xs) - min(xs)) * spec.inner_width * 0.1


def test_unbuildable_design_is_infeasible_not_an_exception(data) -> None:
    p = problem_from_mapping(data)
    crowded = p.base.with_sprockets(tuple(
        s.moved_to(p.base.sprockets[0].x + 1e-3, p.base.sprockets[0].y) if s.name == "I1" else s
        for s in p.base.sprockets))
    ev = evaluate_drive(crowded, p.objectives, p.constraints)
    assert not ev.feasible and ev.constraints == {"buildable": 1.0} and ev.error


def test_cost_model_validation() -> None:
    with pytest.raises(DesignError, match="cost.material_per_kg.steel: must be a price"):
        cost_model_from_mapping({"material_per_kg": {"steel": -1}}, "x")
    cm = cost_model_from_mapping({"chain_per_kg": 2.0, "chain_per_metre": {"A": 5.0}}, "x")
    assert cm.chain_price_per_metre("A", 1.0) == 5.0
    assert cm.chain_price_per_metre("B", 1.5) == 3.0
