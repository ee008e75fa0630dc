"""Sobol indices through the package's own machinery (the uncertainty model's inverse CDFs,
the grouped Saltelli designs of independently scrambled replicates, Janon et al.'s estimator,
the replicates' Student-t intervals, the adaptive sample, the clipping and the ranking)
against closed forms:

* the Ishigami function sin x₁ + 7 sin² x₂ + 0.1 x₃⁴ sin x₁, x ~ U(−π, π)³
  [IshigamiHomma1990], whose partial variances are V₁ = (1 + bπ⁴/5)²/2, V₂ = a²/8, V₃ = 0,
  V₁₃ = 8b²π⁸/225 [SobolLevitan1999];
* a grouped linear model Y = Σ aᵢXᵢ of independent normals, whose group indices are the
  groups' shares of the variance, S1 = ST = Σ_{i∈g} aᵢ²σᵢ² / Σ aᵢ²σᵢ² [Saltelli2008].
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from chaindrive.robust.sensitivity import (
    FEW_STATES_SHARE,
    REPLICATES,
    SensitivityResult,
    grouped_indices,
    pick_freeze_indices,
    ranks,
    replicate_indices,
    tail_variance_share,
)
from chaindrive.robust.uncertainty import UncertaintyModel, UncertaintySettings, Variable


def _model(variables: list[Variable], **settings: object) -> UncertaintyModel:
    return UncertaintyModel(UncertaintySettings(**settings),  # type: ignore[arg-type]
                            tuple(variables), 0.03, None, True, None, 0, 1)


def _ishigami(x: np.ndarray, a: float = 7.0, b: float = 0.1) -> dict[str, np.ndarray]:
    return {"y": np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2
            + b * x[:, 2] ** 4 * np.sin(x[:, 0])}


def _ishigami_exact(a: float = 7.0, b: float = 0.1) -> tuple[list[float], list[float]]:
    v1 = 0.5 * (1 + b * math.pi ** 4 / 5) ** 2
    v2 = a * a / 8
    v13 = 8 * b * b * math.pi ** 8 / 225
    v = v1 + v2 + v13
    return [v1 / v, v2 / v, 0.0], [(v1 + v13) / v, v2 / v, v13 / v]


def test_ishigami_indices_against_their_closed_form() -> None:
    model = _model([Variable(f"x{k}", f"x{k}", "uniform", -math.pi, math.pi)
                    for k in (1, 2, 3)])
    r = grouped_indices(model, _ishigami, start=256, budget=REPLICATES * 256 * 5)
    s1, st = _ishigami_exact()
    assert s1[0] == pytest.approx(0.3139, abs=1e-4) and st[2] == pytest.approx(0.2437, abs=1e-4)
    assert r.replicates == REPLICATES == 8
    assert r.base_samples == 8 * 256 and r.evaluations == 8 * 256 * 5 and r.converged
    for k in range(3):
        # each estimate within its own 95 % interval of the closed form, no wider than ±0.1
        assert abs(r.first_order["y"][k] - s1[k]) <= r.first_order_conf["y"][k] <= 0.1
        assert abs(r.total["y"][k] - st[k]) <= r.total_conf["y"][k] <= 0.1
    assert [g for g, _ in r.ranking("y")] == ["x1", "x2", "x3"]


def _linear(coefficients: list[float]):  # type: ignore[no-untyped-def]
    def evaluate(x: np.ndarray) -> dict[str, np.ndarray]:
        return {"y": x @ np.asarray(coefficients)}
    return evaluate


def test_grouped_linear_indices_and_ties_against_the_variance_shares() -> None:
    # groups g1 = {x1, x2}, g2 = {x3}, g3 = {x4, x5}; variances 4 + 5 = 9, 9, 1 + 1 = 2 →
    # shares 9/20, 9/20, 2/20: g1 and g2 cannot be told apart, g3 is clearly below
    sigma = [1.0, 1.0, 3.0, 1.0, 0.5]
    a = [2.0, math.sqrt(5.0), 1.0, 1.0, 2.0]
    groups = ["g1", "g1", "g2", "g3", "g3"]
    model = _model([Variable(f"x{k + 1}", g, "normal", 0.0, s)
                    for k, (g, s) in enumerate(zip(groups, sigma, strict=True))])
    exact = {"g1": 9 / 20, "g2": 9 / 20, "g3": 2 / 20}
    r = grouped_indices(model, _linear(a), start=4, budget=16384)
    assert r.converged and not r.budget_hit
    assert r.history[-1].widest_half_width <= 0.1 < r.history[0].widest_half_width
    for k, g in enumerate(r.groups):
        assert abs(r.first_order["y"][k] - exact[g]) <= r.first_order_conf["y"][k]
        assert abs(r.total["y"][k] - exact[g]) <= r.total_conf["y"][k]
    idx = {i.group: i for i in r.indices("y")}
    assert idx["g1"].rank == idx["g2"].rank == 1 and idx["g3"].rank == 3
    assert r.tied("y") == [sorted(["g1", "g2"], key=lambda g: -idx[g].total_raw)]
    d = r.to_dict()["metrics"]["y"]
    assert d["rank"] == [1, 1, 3] and d["tied"] == r.tied("y")
    assert r.to_dict()["estimator"].startswith("Janon et al. 2014")


def test_adaptive_sample_doubles_and_stops_at_the_budget() -> None:
    sigma = [1.0, 1.0, 3.0, 1.0, 0.5]
    model = _model([Variable(f"x{k + 1}", g, "normal", 0.0, s) for k, (g, s) in
                    enumerate(zip(["g1", "g1", "g2", "g3", "g3"], sigma, strict=True))])
    r = grouped_indices(model, _linear([2.0, 2.0, 1.0, 1.0, 2.0]), start=4, budget=400)
    # 8 replicates of 4 → 8 base points (5 evaluations per point: 160 → 320), 16 would need
    # 640 and pass the budget of 400
    assert [h.per_replicate for h in r.history] == [4, 8]
    assert [h.base_samples for h in r.history] == [32, 64]
    assert r.evaluations == 8 * 8 * 5 and r.budget_hit and not r.converged
    assert r.history[-1].widest_half_width > 0.1
    d = r.to_dict()
    assert d["budget_hit"] and d["budget_evaluations"] == 400 and not d["converged"]
    assert d["replicates"] == 8 and d["base_samples_per_replicate"] == 8
    assert [h["base_samples_per_replicate"] for h in d["history"]] == [4, 8]


def test_the_first_points_of_a_larger_design_are_the_smaller_design() -> None:
    """Growing N re-uses every state: the evaluations of the adaptive sample are those of
    one design of the final N (same indices, each state evaluated once)."""
    model = _model([Variable(f"x{k}", f"x{k}", "uniform", -math.pi, math.pi)
                    for k in (1, 2, 3)])
    seen: list[int] = []

    def counting(x: np.ndarray) -> dict[str, np.ndarray]:
        seen.append(len(x))
        return _ishigami(x)

    grown = grouped_indices(model, counting, start=4, budget=8 * 5 * 32)
    once = grouped_indices(model, _ishigami, start=32, budget=8 * 5 * 32)
    assert [h.per_replicate for h in grown.history] == [4, 8, 16, 32]
    assert sum(seen) == grown.evaluations == once.evaluations == 8 * 5 * 32
    assert grown.total["y"] == pytest.approx(once.total["y"], abs=1e-12)


def test_indices_outside_the_unit_interval_are_clipped_and_flagged() -> None:
    r = SensitivityResult(("a", "b", "c"), {"m": (1.103, -0.02, 0.3)}, {"m": (0.9, 0.1, 0.3)},
                          {"m": (0.05, 0.05, 0.05)}, {"m": (0.05, 0.05, 0.3)}, 32, 160, 0)
    a, b, c = r.indices("m")
    assert (a.first, a.first_raw, a.first_outside) == (1.0, 1.103, True)   # 0.103 > 0.05
    assert (b.first, b.first_outside) == (0.0, False)                       # within ±0.05
    assert not c.first_outside and c.first == 0.3
    # a (0.85…0.95) is clearly above c (0…0.6) and b (0.05…0.15); b and c overlap
    assert [a.rank, b.rank, c.rank] == [1, 2, 2] and r.tied("m") == [["c", "b"]]
    assert ranks([0.5, 0.5], [0.0, 0.0]) == [1, 1]
    # two groups that do not act: estimates of round-off size with no width are one rank
    assert ranks([0.9, 2e-17, -3e-17], [0.1, 0.0, 0.0]) == [1, 2, 2]


def test_intervals_are_reproducible() -> None:
    """The bootstrap intervals are seeded (a seed of 0 is not left unseeded): the same model
    and seed give the same half-widths."""
    model = _model([Variable(f"x{k}", f"x{k}", "uniform", -math.pi, math.pi)
                    for k in (1, 2, 3)], seed=0)
    one = grouped_indices(model, _ishigami, start=64, budget=5 * 64)
    two = grouped_indices(model, _ishigami, start=64, budget=5 * 64)
    assert one.total_conf == two.total_conf and one.first_order_conf == two.first_order_conf


def test_study_reports_its_progress_per_state() -> None:
    """robust_study calls progress(stage, done, total) per state in this process: the stages
    in order, done never decreasing within a stage and ending at its total, the Sobol
    stage's total the states it evaluated (the compute never prints)."""
    import chaindrive
    from chaindrive.robust.study import nominal_analysis, robust_study
    from tests.conftest import EXAMPLES

    calls: list[tuple[str, int, int]] = []
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    result = robust_study(nominal, UncertaintySettings(samples=8, replicates=2,
                                                       sensitivity_samples=4,
                                                       sensitivity_budget=48),
                          life_points=3, progress=lambda *c: calls.append(c))
    stages = list(dict.fromkeys(c[0] for c in calls))
    assert stages == ["probabilities", "life curve", "sensitivity"]
    for stage in stages:
        mine = [(d, t) for s, d, t in calls if s == stage]
        assert all(a[0] <= b[0] for a, b in itertools.pairwise(mine))
        assert mine[-1][0] == mine[-1][1] > 0
    assert [c for c in calls if c[0] == "probabilities"][-1][1:] == (8, 8)
    assert result.sensitivity is not None
    assert [c for c in calls if c[0] == "sensitivity"][-1][1] == result.sensitivity.evaluations


def test_the_share_of_variance_in_the_farthest_states_against_closed_forms() -> None:
    # 1 % of a large sample: a uniform output 2·∫_{0.495}^{0.5} u² du / (1/12) ≈ 0.0297, a
    # normal one 2(zφ(z) + 1 − Φ(z)) with z = Φ⁻¹(0.995) ≈ 0.0846 (the tails' share of E[z²])
    from scipy.stats import norm

    z = norm.ppf(0.995)
    rng = np.random.default_rng(1)
    assert tail_variance_share(rng.normal(size=400_000)) == pytest.approx(
        2 * (z * norm.pdf(z) + norm.sf(z)), rel=0.03)
    exact_uniform = 2 * (0.5**3 - 0.495**3) / 3 * 12
    assert tail_variance_share(rng.uniform(size=400_000)) == pytest.approx(exact_uniform,
                                                                          rel=0.03)
    # a resonance crossed by a few states: 0.3 % of them at 30 σ (300·30² against 10⁵·1)
    spiky = rng.normal(size=100_000)
    spiky[:300] += 30.0
    assert tail_variance_share(spiky) > 0.5
    assert math.isnan(tail_variance_share(np.ones(10)))


def test_a_metric_whose_variance_sits_in_a_few_states_says_so() -> None:
    # y = x1 + a spike of 30 where x2 lands in 0.5 % of its range: most of the variance sits
    # in those states; the JSON says so beside the (slowly converging) indices
    model = _model([Variable("x1", "g1", "uniform", 0.0, 1.0),
                    Variable("x2", "g2", "uniform", 0.0, 1.0)])

    def evaluate(x: np.ndarray) -> dict[str, np.ndarray]:
        spike = 30.0 * (np.abs(x[:, 1] - 0.5) < 0.0025)
        return {"smooth": x[:, 0] + x[:, 1], "spiky": x[:, 0] + spike}

    r = grouped_indices(model, evaluate, start=64, budget=64 * 4)
    d = r.to_dict()["metrics"]
    assert d["spiky"]["variance_in_few_states"]
    assert d["spiky"]["variance_share_of_farthest_1pct"] > FEW_STATES_SHARE
    assert not d["smooth"]["variance_in_few_states"]
    assert d["smooth"]["variance_share_of_farthest_1pct"] < 0.1


def test_intervals_cover_the_closed_forms_over_independent_studies() -> None:
    """The replicate intervals are not too narrow: over 40 studies (each its own seed, so its
    own 8 scramblings) of 8 × 32 base points, the intervals of S1 and S_T of the Ishigami
    function hold their closed forms [SobolLevitan1999] at least as often as a 95 % interval
    would with probability 99 % (the binomial's 1 % quantile) — the reported ones and their
    Student-t parts alone — and the spread of the 40 estimates (1.96 σ) is no wider than
    the mean reported half-width."""
    from scipy.stats import binom

    s1, st = _ishigami_exact()
    held = held_t = cases = 0
    est, half = [], []
    for seed in range(40):
        model = _model([Variable(f"x{k}", f"x{k}", "uniform", -math.pi, math.pi)
                        for k in (1, 2, 3)], seed=seed)
        r = grouped_indices(model, _ishigami, start=32, budget=8 * 32 * 5)
        for k in range(3):
            for value, exact, conf, conf_t in (
                    (r.first_order["y"][k], s1[k], r.first_order_conf["y"][k],
                     r.first_order_conf_replicates["y"][k]),
                    (r.total["y"][k], st[k], r.total_conf["y"][k],
                     r.total_conf_replicates["y"][k])):
                held += abs(value - exact) <= conf
                held_t += abs(value - exact) <= conf_t
                cases += 1
        est.append(r.total["y"])
        half.append(r.total_conf["y"])
    assert min(held, held_t) >= binom.ppf(0.01, cases, 0.95)
    spread = 1.96 * np.std(np.array(est), axis=0, ddof=1)
    assert np.all(spread <= np.mean(np.array(half), axis=0))


def test_replicate_interval_is_the_student_t_of_the_jackknife() -> None:
    """The half-width of :func:`replicate_indices`, recomputed from its definition: the
    pooled Janon estimate, t_{R−1} times the jackknife standard error over the R replicates
    ((R − 1)/R Σ (Ŝ_(−r) − mean)²)^½ [Efron1982], widened to the pooled bootstrap."""
    from scipy.stats import t as student

    rng = np.random.default_rng(3)
    g, n, r = 3, 16, 5
    ys = [rng.normal(size=n * (g + 2)) + np.tile([0.0, 1.0, 0.5, 0.2, 0.9], n)
          for _ in range(r)]
    s1, st, s1_half, st_half, s1_t, st_t, s1_boot, st_boot = replicate_indices(ys, g, 0.95, 7)
    pooled = pick_freeze_indices(np.concatenate(ys), g, 0.95, 7)
    assert s1 == pooled[0] and st == pooled[1] and s1_boot == pooled[2] and st_boot == pooled[3]
    for kind, t_part, half, boot in ((0, s1_t, s1_half, s1_boot), (1, st_t, st_half, st_boot)):
        loo = np.array([pick_freeze_indices(np.concatenate(ys[:k] + ys[k + 1:]), g, 0.95, 7,
                                            resamples=0)[kind] for k in range(r)])
        se = np.sqrt((r - 1) / r * np.sum((loo - loo.mean(axis=0)) ** 2, axis=0))
        assert np.array(t_part) == pytest.approx(student.ppf(0.975, r - 1) * se, rel=1e-12)
        assert np.array(half) == pytest.approx(np.maximum(t_part, boot), rel=1e-12)
    # one replicate: the bootstrap alone
    one = replicate_indices(ys[:1], g, 0.95, 7)
    assert all(math.isnan(v) for v in one[4]) and one[3] == one[7]


def test_a_spike_in_one_group_against_the_variance_shares() -> None:
    """An additive output whose second group holds a spike of 30 on 0.5 % of its range
    (most of the variance in a few states, as a resonance crossed by a few states): the
    indices are the shares V₁ = 1/12 and V₂ = 900 p(1 − p), p = 0.005 [Saltelli2008]; the
    estimates lie within their intervals of them and the adaptive sample stops at ±0.1."""
    p = 0.005
    v1, v2 = 1.0 / 12.0, 900.0 * p * (1.0 - p)
    exact = [v1 / (v1 + v2), v2 / (v1 + v2)]
    model = _model([Variable("x1", "g1", "uniform", 0.0, 1.0),
                    Variable("x2", "g2", "uniform", 0.0, 1.0)])

    def evaluate(x: np.ndarray) -> dict[str, np.ndarray]:
        return {"y": x[:, 0] + 30.0 * (np.abs(x[:, 1] - 0.5) < p / 2)}

    r = grouped_indices(model, evaluate, start=32, budget=8 * 4 * 4096)
    assert r.converged and r.base_samples <= 8 * 4096
    for k in range(2):
        assert abs(r.first_order["y"][k] - exact[k]) <= r.first_order_conf["y"][k]
        assert abs(r.total["y"][k] - exact[k]) <= r.total_conf["y"][k]
    assert r.to_dict()["metrics"]["y"]["variance_in_few_states"]
