"""Do the replicate intervals of the Sobol indices hold what they claim? The coverage figures of
docs/robust.md ("Intervals from independent replicates").

Two checks of :func:`chaindrive.robust.sensitivity.grouped_indices` (R = 8 independently
scrambled Saltelli designs, the pooled Janon estimate, the Student-t interval of the
jackknife across the replicates widened to the pooled bootstrap, N per replicate doubled
until every leading S_T is within ±0.1):

* ``--ishigami T``: T adaptive studies of the Ishigami function, each with its own seed;
  how many of the reported intervals (and of their Student-t and bootstrap parts alone) hold
  the closed forms of S1 and S_T [SobolLevitan1999], and where the studies stopped.
* stores: Saltelli designs of one example, each drawn with its own scrambling seed
  (``robust_sobol_convergence.py --seed``, or ``--pool`` written by this script); they are
  grouped into disjoint sets of R, each set one study whose adaptive stop is replayed on the
  stored prefixes (the design of N begins every larger design of the same seed). The
  reference is the pooled estimate of all the stores at the largest N they all hold. Per
  metric: how many studies' intervals of the leading S_T held the reference, their
  half-widths and stopping N. ``--subsets K`` adds K random sets of R (overlapping, so not
  independent trials: a smoother estimate of the same rate).

    python benchmarks/robust_sobol_coverage.py --ishigami 200
    python benchmarks/robust_sobol_coverage.py --pool seed_three_sprocket 256 100 140 DIR
    python benchmarks/robust_sobol_coverage.py DIR/*.pkl --subsets 500
"""

from __future__ import annotations

import argparse
import math
import pickle
import sys
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from chaindrive.robust.sensitivity import (
    MIN_STOP_BASE,
    REPLICATES,
    SENSITIVITY_METRICS,
    TARGET_HALF_WIDTH,
    _analyse,
    _leading_half_width,
    pick_freeze_indices,
)

Arr = NDArray[np.float64]


def ishigami(trials: int) -> None:
    """Coverage of the closed forms by ``trials`` adaptive studies of the Ishigami function."""
    from chaindrive.robust.sensitivity import grouped_indices
    from chaindrive.robust.uncertainty import UncertaintyModel, UncertaintySettings, Variable

    a, b = 7.0, 0.1
    v1, v2, v13 = 0.5 * (1 + b * math.pi**4 / 5) ** 2, a * a / 8, 8 * b * b * math.pi**8 / 225
    v = v1 + v2 + v13
    exact = np.array([v1 / v, v2 / v, 0.0, (v1 + v13) / v, v2 / v, v13 / v])
    held = {"reported": np.zeros(6, int), "Student-t": np.zeros(6, int),
            "bootstrap": np.zeros(6, int)}
    stops: list[int] = []
    half: list[float] = []
    for seed in range(trials):
        model = UncertaintyModel(UncertaintySettings(seed=1000 + seed), tuple(
            Variable(f"x{k}", f"x{k}", "uniform", -math.pi, math.pi) for k in (1, 2, 3)),
            0.03, None, True, None, 0, 1)
        r = grouped_indices(model, lambda x: {"y": np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2
                                              + b * x[:, 2] ** 4 * np.sin(x[:, 0])},
                            start=32, budget=1 << 20)
        est = np.array(r.first_order["y"] + r.total["y"])
        for name, conf in (("reported", r.first_order_conf["y"] + r.total_conf["y"]),
                           ("Student-t", r.first_order_conf_replicates["y"]
                            + r.total_conf_replicates["y"]),
                           ("bootstrap", r.first_order_conf_bootstrap["y"]
                            + r.total_conf_bootstrap["y"])):
            held[name] += np.abs(est - exact) <= np.array(conf)
        stops.append(r.history[-1].per_replicate)
        half.append(r.leading_half_width("y"))
    n, c = np.unique(stops, return_counts=True)
    print(f"Ishigami, {trials} adaptive studies (R = {REPLICATES}, start N = 32 per replicate): "
          f"stopped at N per replicate {dict(zip(n.tolist(), c.tolist(), strict=True))}, "
          f"leading half-width mean ±{np.mean(half):.3f}")
    for name, h in held.items():
        print(f"    {name:9s} intervals holding the closed form: S1 x1 x2 x3 "
              f"{h[0]} {h[1]} {h[2]}, S_T x1 x2 x3 {h[3]} {h[4]} {h[5]} of {trials} "
              f"(all {h.sum()}/{6 * trials} = {h.sum() / (6 * trials):.1%})")


def pool(example: str, n_max: int, first: int, last: int, out: Path) -> None:
    """Evaluate the designs of seeds first … last − 1 of ``example`` at ``n_max`` base
    points on the full path, one store each."""
    import tomllib

    from SALib.sample import sobol as sobol_sample

    from chaindrive import examples
    from chaindrive.io.design import drive_from_mapping
    from chaindrive.robust.sampling import serial_states
    from chaindrive.robust.sensitivity import _saltelli_problem
    from chaindrive.robust.study import nominal_analysis
    from chaindrive.robust.uncertainty import uncertainty_model, uncertainty_settings

    data = tomllib.loads(examples.text(example))
    nominal = nominal_analysis(drive_from_mapping(data))
    model = uncertainty_model(nominal, uncertainty_settings(data.get("uncertainty")))
    problem = _saltelli_problem(model)
    out.mkdir(parents=True, exist_ok=True)
    for seed in range(first, last):
        store = out / f"{example}_n{n_max}_s{seed}.pkl"
        if store.exists():
            continue
        t0 = time.process_time()
        x = model.values(sobol_sample.sample(problem, n_max, calc_second_order=False,
                                             seed=seed))
        states = serial_states(nominal, model, x, True)
        metrics = {m: np.array([o.metrics.get(m, math.nan) for o in states])
                   for m in SENSITIVITY_METRICS}
        tmp = store.with_suffix(".tmp")
        tmp.write_bytes(pickle.dumps({"metrics": metrics, "groups": model.groups,
                                      "seed": seed, "cpu": time.process_time() - t0}))
        tmp.rename(store)
        print(f"seed {seed}: {time.process_time() - t0:.1f} s CPU", flush=True)


def _load(path: Path) -> tuple[tuple[str, ...], dict[str, Arr]]:
    d = pickle.loads(path.read_bytes())
    if "metrics" in d:
        return tuple(d["groups"]), {m: np.asarray(v, float) for m, v in d["metrics"].items()}
    return tuple(d["groups"]), {m: np.array([o["metrics"].get(m, math.nan)
                                             if o.get("metrics") else math.nan
                                             for o in d["outcomes"]])
                                for m in SENSITIVITY_METRICS}


def _study(designs: list[dict[str, Arr]], groups: int, n_max: int
           ) -> tuple[int, bool, dict[str, tuple[tuple[float, ...], ...]]]:
    """Replay the adaptive stop on R stored designs: (stopping N per replicate, converged,
    result)."""
    per = groups + 2
    n = 32
    while True:
        outputs = {m: [d[m][:n * per] for d in designs] for m in designs[0]}
        result = _analyse({"groups": list(range(groups))}, outputs, 0.95, 0)
        widths = [_leading_half_width(r[1], r[3]) for r in result.values()]
        ok = all(w <= TARGET_HALF_WIDTH for w in widths if math.isfinite(w))
        if (ok and n * len(designs) >= MIN_STOP_BASE) or 2 * n > n_max:
            return n, ok, result
        n *= 2


def table(designs: list[dict[str, Arr]], groups: tuple[str, ...], n_max: int) -> None:
    """The indices of one study (the first R designs) at every N per replicate."""
    per = len(groups) + 2
    n = 32
    print(f"one study (the first {REPLICATES} designs): leading S_T ± half-width "
          "[Student-t part / bootstrap part] per metric")
    while n <= n_max:
        outputs = {m: [d[m][:n * per] for d in designs[:REPLICATES]] for m in designs[0]}
        result = _analyse({"groups": list(groups)}, outputs, 0.95, 0)
        cells = []
        for m, r in result.items():
            if not all(math.isfinite(v) for v in r[1]):
                continue
            k = int(np.argmax(r[1]))
            cells.append(f"{m} {groups[k]} {r[1][k]:.3f} ± {r[3][k]:.3f} "
                         f"[{r[5][k]:.3f}/{r[7][k]:.3f}]")
        print(f"    N = {n} per replicate ({n * REPLICATES * per} states): " + "; ".join(cells))
        n *= 2


def stores(paths: list[Path], subsets: int) -> None:
    """Coverage of the reference by disjoint (and random) sets of R stored designs."""
    loaded = [_load(p) for p in paths]
    groups = loaded[0][0]
    g, per = len(groups), len(groups) + 2
    n_max = min(len(next(iter(m.values()))) for _, m in loaded) // per
    n_max = 1 << int(math.log2(n_max))
    designs = [{k: np.where(np.isfinite(v[:n_max * per]), v[:n_max * per],
                            np.nanmean(v[:n_max * per])) for k, v in m.items()}
               for _, m in loaded]
    print(f"{len(designs)} stored designs of N = {n_max} ({n_max * per} states each); groups "
          f"{', '.join(groups)}")
    if len(designs) >= REPLICATES:
        table(designs, groups, n_max)
    reference: dict[str, tuple[float, ...]] = {}
    for m in designs[0]:
        y = np.concatenate([d[m] for d in designs])
        if np.var(y) <= 0.0:
            continue
        reference[m] = pick_freeze_indices((y - y.mean()) / y.std(), g, 0.95, 0,
                                           resamples=0)[1]
        lead = int(np.argmax(reference[m]))
        print(f"    reference {m}: leading {groups[lead]} S_T {reference[m][lead]:.3f} "
              f"(pooled, {len(designs) * n_max} base points)")
    sets = [list(range(k, k + REPLICATES)) for k in range(0, len(designs) - REPLICATES + 1,
                                                          REPLICATES)]
    rng = np.random.default_rng(0)
    for label, chosen in (("disjoint sets (independent studies)", sets),
                          (f"{subsets} random sets (overlapping)",
                           [list(rng.choice(len(designs), REPLICATES, replace=False))
                            for _ in range(subsets)])):
        if not chosen:
            continue
        held = {m: 0 for m in reference}
        held_all = {m: 0 for m in reference}
        half = {m: [] for m in reference}
        stop: list[int] = []
        converged = 0
        for s in chosen:
            n, ok, result = _study([designs[k] for k in s], g, n_max)
            stop.append(n)
            converged += ok
            for m, ref in reference.items():
                est, conf = np.array(result[m][1]), np.array(result[m][3])
                lead = int(np.argmax(ref))
                held[m] += bool(abs(est[lead] - ref[lead]) <= conf[lead])
                held_all[m] += int(np.sum(np.abs(est - np.array(ref)) <= conf))
                half[m].append(float(conf[int(np.argmax(est))]))
        n, c = np.unique(stop, return_counts=True)
        print(f"{label}: {len(chosen)} of R = {REPLICATES} designs; stopped at N per replicate "
              f"{dict(zip(n.tolist(), c.tolist(), strict=True))}, converged {converged}")
        for m in reference:
            print(f"    {m:26s} leading S_T held {held[m]}/{len(chosen)}, every group's "
                  f"{held_all[m]}/{g * len(chosen)}; half-width median ±"
                  f"{np.median(half[m]):.3f} (max ±{np.max(half[m]):.3f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stores", nargs="*", type=Path)
    parser.add_argument("--ishigami", type=int, default=0, help="adaptive Ishigami studies")
    parser.add_argument("--subsets", type=int, default=0, help="random sets of R stores")
    parser.add_argument("--pool", nargs=5, metavar=("EXAMPLE", "N", "FIRST", "LAST", "DIR"),
                        help="evaluate designs of seeds FIRST … LAST − 1")
    a = parser.parse_args()
    if a.pool:
        pool(a.pool[0], int(a.pool[1]), int(a.pool[2]), int(a.pool[3]), Path(a.pool[4]))
        return
    if a.ishigami:
        ishigami(a.ishigami)
    if a.stores:
        stores(a.stores, a.subsets)
    if not (a.ishigami or a.stores):
        sys.exit("nothing to do: give --ishigami, --pool or stores")


if __name__ == "__main__":
    main()
