"""Robust synthesis: ``[optimize.robust]`` chance constraints and robust objectives in the
optimiser (chaindrive.robust.synthesis and its hooks in chaindrive.synthesis).

A chance constraint P(check fails) ≤ α is a confidence statement: a design satisfies it
when the one-sided Clopper–Pearson upper bound of the failure probability of its S states is
≤ α [ClopperPearson1934], imposed as an order statistic of the check's margin (the
value-at-risk form, [Rockafellar2000]) — checked here against the counted failures; and the
designs a search returns are verified with an independent, larger sample.
"""

from __future__ import annotations

import copy
import math
import tomllib

import pytest

from chaindrive import examples
from chaindrive.errors import DesignError
from chaindrive.robust.chance import allowed_failures, minimum_samples, upper_bound
from chaindrive.robust.sampling import sample_count
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
    # left out, samples is the least that certifies 1 % at 95 %: ⌈ln 0.05 / ln 0.99⌉ = 299
    assert p.robust.uncertainty.samples == 299 == minimum_samples(0.01, 0.95)
    assert p.robust.verification == 4 * sample_count(299, 4)
    data["optimize"]["robust"] = {"chance": {"k2": 0.001}}
    assert problem_from_mapping(data).robust.path == "full"
    for bad, field in (({"chance": {"k2": 0.7}}, "optimize.robust.chance.k2"),
                       ({"chance": {"resonance_margin": 0.01}, "samples": 16},
                        "optimize.robust.samples"),
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


def test_chance_constraint_is_the_upper_confidence_bound() -> None:
    data = _data()
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.25}, "samples": 16}
    p = problem_from_mapping(data)
    a = analysis_of(p.base, p.constraints, robust=p.robust)
    assert isinstance(a, RobustAnalysis)
    ev = evaluate_drive(p.base, p.objectives, p.constraints, robust=p.robust)
    g = ev.constraints["P(resonance_margin)"]
    entry = a.robust.probability("resonance_margin")
    # the modal path pools the wear states: a sampled point counts as its failing fraction
    failures = entry.failures / entry.samples * a.robust.samples
    # g ≤ 0 ⇒ the one-sided 95 % Clopper–Pearson bound of the counted failures is ≤ 25 %, and
    # g > 0 ⇒ the failures exceed the most whole failures the bound allows
    bound = upper_bound(failures, a.robust.samples, 0.95)
    if g <= 0:
        assert bound <= 0.25
    else:
        assert failures > allowed_failures(0.25, a.robust.samples, 0.95)
    assert ev.feasible is False                 # the start fails its resonance margin anyway


def test_clopper_pearson_bound_and_minimum_samples() -> None:
    """Closed forms of the one-sided Clopper–Pearson bound [ClopperPearson1934]: with no
    failure p_up = 1 − (1 − c)^(1/S) (≈ 3/S, [Hanley1983]); S_min = ⌈ln(1 − c)/ln(1 − α)⌉;
    and k* is the last count whose bound is ≤ α."""
    for n in (16, 64, 299, 1000):
        assert upper_bound(0, n, 0.95) == pytest.approx(1.0 - 0.05 ** (1.0 / n), rel=1e-10)
    assert upper_bound(0, 16, 0.95) > 0.17         # 16 states cannot certify 17 %
    for alpha in (0.25, 0.05, 0.01, 0.001):
        need = math.ceil(math.log(0.05) / math.log(1.0 - alpha))
        assert minimum_samples(alpha, 0.95) == need
        assert allowed_failures(alpha, need - 1, 0.95) == -1
        assert allowed_failures(alpha, need, 0.95) == 0
    k = allowed_failures(0.05, 1024, 0.95)
    assert upper_bound(k, 1024, 0.95) <= 0.05 < upper_bound(k + 1, 1024, 0.95)


def test_robust_search_keeps_its_chance_constraint() -> None:
    data = _data()
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.05}, "samples": 64,
                                  "verification": 64}
    result = solve(problem_from_mapping(data))
    assert result.evaluations == 8
    assert "P(resonance_margin)" in result.start.constraints
    for design in result.pareto:
        assert design.constraints["P(resonance_margin)"] <= 0.0
        (v,) = design.verification
        assert v["search"]["upper"] <= 0.05 and v["samples"] == 64 and v["seed"] == 1
        # the certificate is the full path's, the search's own figures kept beside it
        assert v["path"] == "full" and v["search"]["path"] == "modal"
        assert v["certified"] == (v["upper"] <= 0.05)


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


def test_robust_optimum_is_certified_only_on_the_full_path() -> None:
    """A search that asked for P(resonance) ≤ 5 % at 95 % on the batched modal path (64
    states each, the least Sobol count above ⌈ln 0.05 / ln 0.95⌉ = 59) claims it for its
    Pareto designs; the certificate is the independent sample on the full path (every
    tolerance sampled, another seed), and a design is certified only when that sample's
    one-sided 95 % Clopper–Pearson bound is ≤ α [ClopperPearson1934]. (Before, the
    verification ran on the search's modal path, which holds the geometric tolerances at
    nominal, and certified designs whose full-path bound exceeds α.) Fixed seeds."""
    data = _data()
    data["optimize"]["solver"].update(population=8, generations=3)
    data["optimize"]["robust"] = {"chance": {"resonance_margin": 0.05}, "verification": 128}
    problem = problem_from_mapping(data)
    assert problem.robust.path == "modal"
    assert sample_count(problem.robust.uncertainty.samples, 4) == 64
    result = solve(problem)
    assert result.pareto
    for design in result.pareto:
        (v,) = design.verification
        assert v["samples"] == 128 and v["seed"] != problem.robust.uncertainty.seed
        assert v["search"]["upper"] <= 0.05         # what the search claimed, on its path
        assert v["search"]["path"] == "modal" and 0.0 <= v["search"]["probability"] <= 0.05
        assert v["path"] == "full"
        assert v["upper"] == pytest.approx(upper_bound(v["failures"], 128, 0.95), rel=1e-12)
        assert v["certified"] == (v["upper"] <= 0.05)


def test_certified_probability_against_plain_monte_carlo() -> None:
    """The certificate of a chance constraint (the full path on 512 independent states)
    against plain Monte Carlo with 10⁴ independent uniform draws of the same variables
    (inertias ±15 % per sprocket, chain stiffness ±15 %; new chain, no geometric
    tolerance, so the batched modal engine is the full path state by state, see
    test_robust_sampling) on the seed's polymer drive: the Monte Carlo estimate lies in
    the certificate's 95 % interval and below its one-sided bound, the design is
    certified at α = 15 % and would not be at 2 % [ClopperPearson1934]."""
    import dataclasses

    import numpy as np

    from chaindrive.io.design import drive_from_mapping
    from chaindrive.robust.analysis import nominal_analysis
    from chaindrive.robust.modal import stacked_margins, stacked_state
    from chaindrive.robust.synthesis import RobustSettings, verify_design
    from chaindrive.robust.uncertainty import UncertaintySettings

    design = drive_from_mapping(tomllib.loads(examples.text("seed_three_sprocket_polymer")))
    settings = UncertaintySettings(samples=64, replicates=4, wear="new",
                                   chain_length_tolerance=0.0, eccentricity=0.0,
                                   centre_distance_tolerance=0.0, inertia_scatter=0.15,
                                   stiffness_scatter=0.15)
    robust = RobustSettings(settings, (("resonance_margin", 0.15),), "modal",
                            response=False, verification=512)
    (v,) = verify_design(RobustAnalysis(design, robust=robust))
    assert (v.path, v.search_path, v.samples) == ("full", "modal", 512)

    nominal = nominal_analysis(design)
    rng = np.random.default_rng(20261128)
    draws = 10_000
    stacked = stacked_state(nominal, rng.uniform(0.85, 1.15, (draws, len(design.sprockets))),
                            rng.uniform(0.85, 1.15, draws), np.full(draws, 23.0))
    _, margin = stacked_margins(stacked, None)
    p_mc = float(np.mean(margin < nominal.limits.resonance_band_percent * (1 - 1e-12)))
    assert 0.02 < p_mc < 0.15                     # a case between the two α below
    assert v.low <= p_mc <= v.high and p_mc <= v.upper
    assert v.certified and v.upper <= 0.15
    assert not dataclasses.replace(v, alpha=0.02).certified
