"""The robust design of docs/robust.md: the optimiser's nominal optimum next to the design it
finds under chance constraints, both verified by the full robust study, and the figures of
the study of the nominal optimum.

The problem is the seed's three-sprocket contour (examples/seed_three_sprocket.toml: fixed
centres, so the wear collects in the slack span) with the tooth counts, the idler's position
and the chain free, objectives cost and mass. ``--take-up``: the same contour and space with
the idler S3 made the take-up (``adjustable = true``: it is moved to keep the installed sag,
and the chain is shortened by two links each time it has taken up two pitches); the
allowable elongation is then 3 % instead of the fixed centres' 1.5 %. The robust run adds
``[uncertainty]`` (the defaults of the standards, the life from new to worn, 8 replicates) and
``[optimize.robust]``:
P(resonance margin below 10 %) ≤ ``--alpha`` (1 %) certified at 95 % (the one-sided
Clopper–Pearson bound; ``samples`` left out: the least Sobol count that can certify it, 512
states per design for 1 %; the batched modal path over 8 wear states). ``--also CHECK``
constrains another check to the same α (e.g. ``teeth_in_mesh[S3]``; it needs the full path,
tens of times slower per design). The optimiser verifies each Pareto design with an independent
sample four times larger (printed); each least-cost design is then analysed by the full path
over ``--verify`` (1024) states of another seed — every check, the probabilities the table
prints — with its resonance line new, half and fully worn and its life curve.

Run: .venv/bin/python benchmarks/robust_demo.py [--figures DIR] [--quick] [--alpha A]
     [--take-up] [--also CHECK] [--population N] [--generations N]
The runs of docs/robust.md: no options; ``--take-up``; ``--take-up --also "teeth_in_mesh[S3]"
--population 12 --generations 8``.
"""

from __future__ import annotations

import argparse
import copy
import os
import time
import tomllib
from pathlib import Path

from chaindrive.io.design import drive_from_mapping
from chaindrive.plotting.robust import life_curve_figure, probability_figure, sensitivity_figure
from chaindrive.robust import (
    Perturbation,
    PerturbedAnalysis,
    UncertaintySettings,
    life_curve,
    nominal_analysis,
    reliability,
    uncertainty_model,
)
from chaindrive.robust.sampling import sample_count
from chaindrive.robust.study import robust_study
from chaindrive.synthesis.problem import problem_from_mapping
from chaindrive.synthesis.solve import SynthesisResult, solve

ROOT = Path(__file__).resolve().parents[1]
KEYS = ("resonance_margin", "teeth_in_mesh[S3]", "k2", "any")


def problem_data(population: int, generations: int, take_up: bool = False) -> dict:
    data = tomllib.loads((ROOT / "examples" / "seed_three_sprocket.toml")
                         .read_text(encoding="utf-8"))
    if take_up:
        next(s for s in data["sprockets"] if s["name"] == "S3")["adjustable"] = True
    data["optimize"] = {
        "objectives": ["cost", "mass"],
        "teeth": {"S1": [13, 21], "S2": [19, 35], "S3": [11, 25]},
        "position": {"S3": {"x": ["500 mm", "860 mm"], "y": ["60 mm", "260 mm"]}},
        "chain": {"designations": ["GOST 13568 ПР-19,05-31,8", "GOST 13568 ПР-25,4-60",
                                   "GOST 13568 ПР-31,75-89"]},
        "solver": {"population": population, "generations": generations, "seed": 1}}
    return data


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load {one:.1f} (5 min {five:.1f})"


def cheapest(result: SynthesisResult) -> dict | None:
    """The Pareto design of least cost (the TOML mapping)."""
    if not result.pareto:
        return None
    return min(result.pareto, key=lambda p: p.objectives["cost"]).design


def verify(design: dict, samples: int) -> dict[str, float]:
    """Probabilities of the full path over the default uncertainty model (seed 2: independent
    of the search's 0 and of the optimiser's verification's 1)."""
    nominal = nominal_analysis(drive_from_mapping(design))
    model = uncertainty_model(nominal, UncertaintySettings(samples=samples, replicates=8,
                                                           seed=2))
    r = reliability(nominal, model)
    out = {}
    for key in KEYS:
        c = r.probability(key)
        out[key] = (c.probability, c.low, c.high) if c else None
    mesh = nominal.check("teeth_in_mesh[S3]")
    s3 = next(s for s in nominal.geometry.sprockets if s.name == "S3")
    moved = " after the installation take-up" if nominal.geometry.adjusted is not None else ""
    out["drawn"] = (f"S3 at ({s3.x * 1e3:.1f}, {s3.y * 1e3:.1f}) mm{moved}, "
                    f"{nominal.geometry.links} links, teeth in mesh on S3 "
                    f"{mesh.value if mesh else float('nan'):.2f}")
    res = nominal.check("resonance_margin")
    out["nominal_resonance_margin"] = res.value
    out["resonance_as_drawn"] = f"{res.subject}: {res.note}"
    out["kd_p95"] = r.quantile("coefficient_of_dynamics", 0.95)
    out["states"] = r.samples
    life = life_curve(nominal, model)
    out["life"] = [(w.elongation, w.f1_hz, w.resonance_margin_percent, w.take_up_travel_mm,
                    w.links_removed, w.sag_ratio) for w in life.states]
    out["life_end"] = (life.life_elongation, life.first_failure)
    for state in (nominal, *(PerturbedAnalysis(nominal, Perturbation(elongation=e),
                                               allowable_elongation=model.allowable_elongation,
                                               take_up_capacity=model.take_up_capacity,
                                               response=False)
                             for e in (0.5 * model.allowable_elongation,
                                       model.allowable_elongation))):
        c = state.check("resonance_margin")
        eps = getattr(getattr(state, "perturbation", None), "elongation", 0.0)
        out.setdefault("resonance_states", []).append(
            f"ε {eps:.2%}: margin {c.value:.1f} % ({c.subject}: {c.note})")
    return out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--figures", type=Path, default=None)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--alpha", type=float, default=0.01,
                        help="largest P(resonance) of the robust search")
    parser.add_argument("--verify", type=int, default=1024, help="states of the full path")
    parser.add_argument("--take-up", action="store_true",
                        help="the idler S3 is the take-up (adjustable) instead of fixed centres")
    parser.add_argument("--also", action="append", default=[], metavar="CHECK",
                        help="another check key constrained to P ≤ --alpha (the full path)")
    parser.add_argument("--population", type=int, default=None)
    parser.add_argument("--generations", type=int, default=None)
    args = parser.parse_args()
    pop, gens, samples = (8, 3, 64) if args.quick else (24, 20, args.verify)
    pop, gens = args.population or pop, args.generations or gens
    data = problem_data(pop, gens, args.take_up)
    t0 = time.perf_counter()
    nominal = solve(problem_from_mapping(data))
    t1 = time.perf_counter()
    robust_data = copy.deepcopy(data)
    robust_data["uncertainty"] = {"replicates": 8}
    robust_data["optimize"]["robust"] = {"chance": {key: args.alpha for key in
                                                    ("resonance_margin", *args.also)}}
    problem = problem_from_mapping(robust_data)
    robust = solve(problem)
    t2 = time.perf_counter()
    r = problem.robust
    print(f"nominal search {t1 - t0:.0f} s ({nominal.evaluations} designs), robust search "
          f"{t2 - t1:.0f} s ({robust.evaluations} designs, {r.path} path, "
          f"{sample_count(r.uncertainty.samples, r.uncertainty.replicates)} states each, "
          f"{len(robust.pareto)} Pareto designs certified); {load()}")
    for name, result in (("nominal optimum", nominal), ("robust design", robust)):
        design = cheapest(result)
        if design is None:
            print(f"{name}: no design certified P(resonance) ≤ {args.alpha:g}")
            continue
        p = min(result.pareto, key=lambda q: q.objectives["cost"])
        v = verify(design, samples)
        teeth = " ".join(str(s["teeth"]) for s in design["sprockets"])
        print(f"{name}: chain {design['chain']['designation']}, teeth {teeth}, "
              f"cost {p.objectives['cost']:.1f}, mass {p.objectives['mass']:.2f} kg, "
              f"nominal resonance margin {v['nominal_resonance_margin']:.1f} %, "
              f"K_D p95 {v['kd_p95']:.3f}")
        for c in p.verification:
            print(f"   the optimiser's verification of P({c['key']}) ≤ {c['alpha']:g}: search "
                  f"{c['search']['failures']:.1f}/{c['search']['samples']} failures (bound "
                  f"{c['search']['upper']:.4f}); independent {c['failures']:.1f}/{c['samples']}"
                  f" = {c['probability']:.4f}, 95 % bound {c['upper']:.4f}: "
                  f"{'certified' if c['certified'] else 'NOT certified'}")
        for key in KEYS:
            if v[key] is not None:
                pr, lo, hi = v[key]
                print(f"   full path, {v['states']} states: P({key}) = {pr:.4f} "
                      f"[{lo:.4f}, {hi:.4f}]")
        print(f"   as drawn: {v['drawn']}")
        for line in v["resonance_states"]:
            print(f"   resonance, nominal tolerances, {line}")
        print(f"   life ends at ε = {v['life_end'][0]:.2%} ({v['life_end'][1]}); life curve "
              "(ε, f1 Hz, margin %, take-up mm, links removed, sag):")
        for e, f1, m, tu, rm, sag in v["life"]:
            print(f"      {e:.4f} {f1:7.2f} {m:6.1f} {tu:7.1f} {rm:2d} {sag:.3f}")
    if args.figures is not None and cheapest(nominal) is not None:
        args.figures.mkdir(parents=True, exist_ok=True)
        start = drive_from_mapping(cheapest(nominal) or {})
        study = robust_study(nominal_analysis(start), UncertaintySettings(
            samples=64 if args.quick else 128, replicates=8, sensitivity_samples=16))
        life_curve_figure(study.life).savefig(args.figures / "robust_life.png", dpi=100)
        probability_figure(study.reliability).savefig(args.figures / "robust_probability.png",
                                                      dpi=100)
        if study.sensitivity is not None:
            sensitivity_figure(study.sensitivity).savefig(
                args.figures / "robust_sensitivity.png", dpi=100)
        print(f"figures written to {args.figures}")


if __name__ == "__main__":
    main()
