"""Benchmark of the synthesis (issue 8).

1. Designs evaluated per second on one core (geometry, strength, ring model and modes,
   steady state for k2/k2min; objectives cost, mass, volume, chain length) for the 8- and
   24-sprocket examples.
2. The speed-up of a sweep on a Dask LocalCluster of two worker processes over the same
   sweep in one process (results stored in a throw-away SQLite study).
3. pymoo NSGA-II against Optuna's NSGA-II sampler on the 8-sprocket problem
   (examples/eight_sprocket_optimize.toml): the same budget, three seeds; hypervolume of the
   feasible front (objectives normalised by the start design, reference point 1.1) and time.
4. With ``--against TREE``: ``chaindrive optimize examples/eight_sprocket_optimize.toml
   --json`` of this tree and of another source tree (TREE/src on PYTHONPATH, the same
   interpreter), one BLAS thread, run in alternation ``--runs`` times each (3 by default):
   designs/s of the search (evaluations over the search's seconds), the CPU time of the
   command, their medians and the ratio, the load average before and after, and whether
   the two Pareto sets are equal. Only this comparison runs with ``--against``.

Run: .venv/bin/python benchmarks/bench_synthesis.py [--quick] [--against TREE [--runs N]]
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

from chaindrive.io.design import load_drive
from chaindrive.synthesis.evaluation import evaluate_drive
from chaindrive.synthesis.problem import Constraints, load_problem
from chaindrive.synthesis.solve import solve
from chaindrive.synthesis.studies import evaluate_design, run_study, sweep_inputs

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
OBJECTIVES = ("cost", "mass", "volume", "chain_length")


def designs_per_second(name: str, seconds: float = 3.0) -> float:
    """Serial evaluations per second of one example (a fresh state each time)."""
    drive = load_drive(EXAMPLES / name)
    evaluate_drive(drive, OBJECTIVES, Constraints())  # warm-up
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        evaluate_drive(drive, OBJECTIVES, Constraints())
        n += 1
    return n / (time.perf_counter() - t0)


def dask_speedup(name: str, count: int) -> tuple[float, float]:
    """(serial s, two-worker Dask s) for a sweep of ``count`` positions of sprocket 2."""
    from distributed import Client, LocalCluster

    base = tomllib.loads((EXAMPLES / name).read_text(encoding="utf-8"))
    x0 = float(base["sprockets"][1]["x"].split()[0])
    inputs = sweep_inputs(base, {"sprockets[1].x": [f"{x0 + 0.01 * k:.2f} mm"
                                                    for k in range(count)]}, OBJECTIVES)
    evaluate_design(inputs[0])
    t0 = time.perf_counter()
    for x in inputs:
        evaluate_design(x)
    serial = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp, \
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                         dashboard_address=":0") as cluster, Client(cluster) as client:
        client.run(lambda: __import__("chaindrive.synthesis.objectives"))  # warm the workers
        run_study(evaluate_design, inputs[:4], study="warm", db=f"sqlite:///{tmp}/s.db",
                  client=client, progress=False)
        t0 = time.perf_counter()
        run_study(evaluate_design, inputs, study="bench", db=f"sqlite:///{tmp}/s.db",
                  client=client, progress=False)
        parallel = time.perf_counter() - t0
    return serial, parallel


def hypervolume(result: object, start: list[float]) -> float:
    """Hypervolume of the feasible front, objectives divided by the start's, ref 1.1."""
    from pymoo.indicators.hv import HV

    F = np.array([[p.objectives[n] for n in OBJECTIVES] for p in result.pareto])  # type: ignore[attr-defined]
    if F.size == 0:
        return 0.0
    return float(HV(ref_point=np.full(len(OBJECTIVES), 1.1))(F / np.array(start)))


def compare_solvers(population: int, generations: int, seeds: tuple[int, ...]) -> None:
    problem = load_problem(EXAMPLES / "eight_sprocket_optimize.toml")
    for method in ("nsga2", "optuna"):
        hvs, secs, fronts = [], [], []
        for seed in seeds:
            r = solve(problem, method=method, population=population, generations=generations,
                      seed=seed)
            start = [r.start.objectives[n] for n in OBJECTIVES]
            hvs.append(hypervolume(r, start))
            secs.append(r.seconds)
            fronts.append(len(r.pareto))
        print(f"  {method:7s} pop {population} × {generations} gen: hypervolume "
              f"{statistics.mean(hvs):.4f} (± {statistics.pstdev(hvs):.4f}), "
              f"time {statistics.mean(secs):.2f} s, front size {statistics.mean(fronts):.1f}")


def optimize_run(tree: Path) -> tuple[float, float, list[object]]:
    """(designs/s of the search, CPU s of the command, Pareto set) of ``chaindrive optimize``
    on the 8-sprocket problem with ``tree``/src first on the path, one BLAS thread."""
    env = {**os.environ, "PYTHONPATH": str(tree / "src"), "OPENBLAS_NUM_THREADS": "1",
           "MKL_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run([sys.executable, "-m", "chaindrive", "optimize",
                           str(EXAMPLES / "eight_sprocket_optimize.toml"), "--json"],
                          env=env, capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    doc = json.loads(done.stdout)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return doc["evaluations"] / doc["seconds"], cpu, doc["pareto"]


def compare_trees(other: Path, runs: int) -> None:
    """Designs/s of ``optimize`` here and in ``other``, in alternation (module docstring)."""
    trees = {"this tree": ROOT, "other": other}
    rate: dict[str, list[float]] = {k: [] for k in trees}
    cpu: dict[str, list[float]] = {k: [] for k in trees}
    fronts: dict[str, list[object]] = {}
    load0 = os.getloadavg()
    for _ in range(runs):
        for name, tree in trees.items():
            r, c, front = optimize_run(tree)
            rate[name].append(r)
            cpu[name].append(c)
            fronts[name] = front
    load1 = os.getloadavg()
    print(f"optimize examples/eight_sprocket_optimize.toml, one BLAS thread, {runs} runs each "
          f"in alternation; load average {load0[0]:.2f} before, {load1[0]:.2f} after")
    for name, tree in trees.items():
        print(f"  {name:10s} {tree}: designs/s {statistics.median(rate[name]):6.1f} "
              f"(runs {', '.join(f'{v:.1f}' for v in rate[name])}), command CPU "
              f"{statistics.median(cpu[name]):.2f} s")
    here, there = statistics.median(rate["this tree"]), statistics.median(rate["other"])
    print(f"  ratio (this/other): designs/s {here / there:.2f}, "
          f"CPU {statistics.median(cpu['other']) / statistics.median(cpu['this tree']):.2f}; "
          f"same Pareto set: {fronts['this tree'] == fronts['other']}")


def main() -> None:
    if "--against" in sys.argv:
        args = sys.argv[sys.argv.index("--against") + 1:]
        runs = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 3
        compare_trees(Path(args[0]).resolve(), runs)
        return
    quick = "--quick" in sys.argv
    print(f"cores {os.cpu_count()}, load average {os.getloadavg()[0]:.2f} (other work skews it)")
    print("designs evaluated per second, one core (geometry + strength + modal + steady):")
    for name in ("eight_sprocket.toml", "twenty_four_sprocket.toml"):
        print(f"  {name:28s} {designs_per_second(name, 1.0 if quick else 3.0):8.1f} /s")
    print("sweep on a Dask LocalCluster of 2 worker processes:")
    for name in ("eight_sprocket.toml", "twenty_four_sprocket.toml"):
        serial, parallel = dask_speedup(name, 100 if quick else 400)
        print(f"  {name:28s} serial {serial:6.2f} s, 2 workers {parallel:6.2f} s, "
              f"speed-up {serial / parallel:4.2f}")
    print("pymoo NSGA-II vs Optuna NSGA-II on examples/eight_sprocket_optimize.toml:")
    compare_solvers(16, 10, (1, 2, 3))
    if not quick:
        compare_solvers(32, 25, (1, 2, 3))


if __name__ == "__main__":
    main()
