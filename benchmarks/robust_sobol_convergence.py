"""Convergence of the Sobol indices of ``chaindrive robust`` with the base sample N on a
bundled example: the figures of docs/robust.md ("How many states the indices need").

The Saltelli design of the largest N is evaluated once on the full path (its base points are
a scrambled Sobol sequence, so its first N·(G + 2) rows are the design of every smaller
power-of-two N: the adaptive sample of :func:`chaindrive.robust.sensitivity.grouped_indices`
sees exactly these prefixes); the indices and their 95 % bootstrap half-widths are then
estimated on each prefix, N = 32, 64, …, by the package's own estimator
(:func:`chaindrive.robust.sensitivity._analyse` on one design: Janon et al.'s, with its
bootstrap — the package's intervals now come from eight independently scrambled designs:
``robust_sobol_coverage.py``). Jansen's
estimator on the same states: ``benchmarks/robust_sobol_replicates.py <store>``.

    python benchmarks/robust_sobol_convergence.py seed_three_sprocket --n-max 1024

Per N: the widest half-width of a metric's leading S_T, and for every metric the leading
group with S_T ± half-width and S1 ± half-width and every group's S_T with its rank
(equal ranks: tied). The states are evaluated in chunks and kept in ``--store`` (a pickle), so
an interrupted run is analysed up to the largest N it completed (``--analyse-only``).
"""

from __future__ import annotations

import argparse
import math
import pickle
import time
from pathlib import Path

import numpy as np
from SALib.sample import sobol as sobol_sample

from chaindrive import examples
from chaindrive.io.design import drive_from_mapping
from chaindrive.robust.sampling import StateOutcome, serial_states
from chaindrive.robust.sensitivity import (
    SENSITIVITY_METRICS,
    _analyse,
    _leading_half_width,
    _saltelli_problem,
    ranks,
)
from chaindrive.robust.study import nominal_analysis
from chaindrive.robust.uncertainty import uncertainty_model, uncertainty_settings


def evaluate(name: str, n_max: int, store: Path, seed: int | None = None,
             chunk: int = 256) -> None:
    """Evaluate the design of ``n_max`` base points in chunks, stored after each (``seed``:
    the scrambling of the design, None: the example's)."""
    import tomllib

    data = tomllib.loads(examples.text(name))
    if seed is not None:
        data.setdefault("uncertainty", {})["seed"] = seed
    nominal = nominal_analysis(drive_from_mapping(data))
    model = uncertainty_model(nominal, uncertainty_settings(data.get("uncertainty")))
    problem = _saltelli_problem(model)
    x = model.values(sobol_sample.sample(problem, n_max, calc_second_order=False,
                                         seed=model.settings.seed))
    out: list[dict] = []
    t0, c0 = time.time(), time.process_time()
    for i in range(0, len(x), chunk):
        out += [o.to_dict() for o in serial_states(nominal, model, x[i:i + chunk], True)]
        store.write_bytes(pickle.dumps({"outcomes": out, "groups": model.groups,
                                        "problem": problem, "wall": time.time() - t0,
                                        "cpu": time.process_time() - c0}))
        print(f"{name}: {len(out)}/{len(x)} states, {time.time() - t0:.0f} s", flush=True)


def analyse(store: Path) -> None:
    """Print the indices of every prefix N of the stored states."""
    d = pickle.loads(store.read_bytes())
    out = [StateOutcome.from_dict(o) for o in d["outcomes"]]
    problem, groups = d["problem"], d["groups"]
    per = len(groups) + 2
    print(f"{len(out)} states, {d['cpu']:.0f} s CPU; groups: {', '.join(groups)}")
    metrics = {m: np.array([o.metrics.get(m, math.nan) for o in out])
               for m in SENSITIVITY_METRICS}
    n = 32
    while n * per <= len(out):
        r = _analyse(problem, {m: [v[:n * per]] for m, v in metrics.items()}, 0.95, 0)
        widths = {m: _leading_half_width(x[1], x[3]) for m, x in r.items()}
        finite = {m: w for m, w in widths.items() if math.isfinite(w)}
        worst = max(finite, key=lambda m: finite[m])
        print(f"N = {n:5d}, {n * per:5d} states: widest leading S_T ±{finite[worst]:.3f} "
              f"({worst})")
        for m, x in r.items():
            if not all(math.isfinite(v) for v in x[1]):
                continue
            k = int(np.argmax(x[1]))
            rank = ranks(x[1], x[3])
            print(f"    {m:26s} leading {groups[k]}: S_T {x[1][k]:.3f} ± {x[3][k]:.3f}, "
                  f"S1 {x[0][k]:.3f} ± {x[2][k]:.3f} | "
                  + ", ".join(f"{g} {x[1][i]:.3f} ± {x[3][i]:.3f} ({rank[i]})"
                              for i, g in enumerate(groups)))
        n *= 2


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("example", help="a bundled example's name")
    parser.add_argument("--n-max", type=int, default=1024, help="largest base N")
    parser.add_argument("--store", type=Path, default=None, help="pickle of the states")
    parser.add_argument("--seed", type=int, default=None,
                        help="scrambling seed of the design (default: the example's)")
    parser.add_argument("--analyse-only", action="store_true")
    a = parser.parse_args()
    store = a.store or Path(f"sobol_convergence_{a.example}.pkl")
    if not a.analyse_only:
        evaluate(a.example, a.n_max, store, a.seed)
    analyse(store)


if __name__ == "__main__":
    main()
