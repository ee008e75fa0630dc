"""Is the bootstrap interval of the Sobol indices the right width, and would another estimator
of the same indices converge faster? The figures of docs/robust.md ("Bootstrap intervals
against independent replicates", "Other estimators of the same indices").

Reads the states that ``benchmarks/robust_sobol_convergence.py`` stored for several scrambling
seeds of the same example (``--seed``; every store the design of its own seed), and for every
metric's leading group, at every power-of-two N that all stores hold:

* each estimator's estimate per seed, their mean and the spread of the independent
  replicates (z·σ of the estimates across the seeds: the interval a replicate-based method
  would give one estimate);
* the mean bootstrap half-width of one estimate (z·σ of 100 resamples of the base rows, as
  SALib computes it [Herman2017]), for every estimator on the same resamples, and how many of
  the seeds' intervals hold the mean of the seeds' estimates at the largest N.

The estimators, on the rows A, B and AB_j (A with group j's columns from B) of the Saltelli
design [Saltelli2010]:

* first order: Saltelli 2010 ``mean(f(B)(f(AB_j) − f(A)))/V`` (SALib's, the package's) and
  Janon et al. 2014 (the pair f(B), f(AB_j), which share group j, with its own mean and
  variance) [Janon2014];
* total: Jansen 1999 ``mean((f(A) − f(AB_j))²)/2V`` (SALib's, the package's), Sobol' 2007
  ``mean(f(A)(f(A) − f(AB_j)))/V`` [Saltelli2010], and 1 − Janon's estimate of the closed
  index of the other groups from the pair f(A), f(AB_j) (the same squared differences over
  the pair's own variance) [Janon2014].

V is the variance over A and B (SALib's). Outputs are centred and scaled as SALib does.

    python benchmarks/robust_sobol_replicates.py /tmp/seed_s*.pkl
    python benchmarks/robust_sobol_replicates.py --ishigami 50     # closed form, 50 seeds
"""

from __future__ import annotations

import argparse
import math
import pickle
from collections.abc import Callable
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.stats import norm

from chaindrive.robust.sampling import StateOutcome
from chaindrive.robust.sensitivity import SENSITIVITY_METRICS

Arr = NDArray[np.float64]
#: estimator name → f(A, B, AB_j) for (resampled) rows of shape (..., N)
Estimator = Callable[[Arr, Arr, Arr], Arr]


def _var(a: Arr, b: Arr) -> Arr:
    return np.var(np.concatenate([a, b], axis=-1), axis=-1)


def _janon_closed(y: Arr, y2: Arr) -> Arr:
    """Janon et al.'s estimator of the closed index of the variables y and y2 share."""
    m = np.mean((y + y2) / 2, axis=-1)
    return (np.mean(y * y2, axis=-1) - m**2) / (np.mean((y**2 + y2**2) / 2, axis=-1) - m**2)


FIRST: dict[str, Estimator] = {
    "Saltelli 2010": lambda a, b, ab: np.mean(b * (ab - a), axis=-1) / _var(a, b),
    "Janon 2014": lambda a, b, ab: _janon_closed(b, ab),
}
TOTAL: dict[str, Estimator] = {
    "Jansen 1999": lambda a, b, ab: 0.5 * np.mean((a - ab) ** 2, axis=-1) / _var(a, b),
    "Sobol' 2007": lambda a, b, ab: np.mean(a * (a - ab), axis=-1) / _var(a, b),
    "Janon 2014": lambda a, b, ab: 1.0 - _janon_closed(a, ab),
}


def split(y: Arr, groups: int) -> tuple[Arr, Arr, Arr]:
    """(A, B, AB) of a Saltelli design's outputs without second order, centred and scaled."""
    y = (y - y.mean()) / y.std()
    step = groups + 2
    return y[0::step], y[step - 1::step], np.stack([y[j + 1::step] for j in range(groups)])


def study(designs: list[tuple[Arr, int]], n: int, estimators: dict[str, Estimator],
          first: bool, resamples: int = 100, z: float = float(norm.ppf(0.975))
          ) -> dict[str, tuple[Arr, Arr, Arr]]:
    """Estimator → (estimates (seeds, G), bootstrap half-widths (seeds, G), ...)."""
    out: dict[str, tuple[Arr, Arr, Arr]] = {}
    for name, f in estimators.items():
        est, half = [], []
        for k, (y, g) in enumerate(designs):
            a, b, ab = split(y[:n * (g + 2)], g)
            e = np.array([f(a, b, ab[j]) for j in range(g)])
            r = np.random.default_rng(k + 1).integers(n, size=(resamples, n))
            boot = np.array([f(a[r], b[r], ab[j][r]) for j in range(g)])
            est.append(e)
            half.append(z * boot.std(axis=-1, ddof=1))
        out[name] = (np.array(est), np.array(half), np.array([]))
    return out


def report(designs: list[tuple[Arr, int]], groups: tuple[str, ...], label: str,
           exact: tuple[list[float], list[float]] | None = None) -> None:
    """Print the comparison at every power-of-two N the designs hold."""
    g = designs[0][1]
    n_max = min(len(y) for y, _ in designs) // (g + 2)
    z = float(norm.ppf(0.975))
    final = study(designs, n_max, TOTAL, first=False)
    final_first = study(designs, n_max, FIRST, first=True)
    n = 32
    while n <= n_max:
        tot = study(designs, n, TOTAL, first=False)
        fir = study(designs, n, FIRST, first=True)
        ref = tot["Jansen 1999"][0].mean(axis=0)
        lead = int(np.argmax(ref))
        print(f"{label} N = {n} ({n * (g + 2)} states), {len(designs)} seeds, "
              f"leading group {groups[lead]}:")
        for kind, res in (("S_T", tot), ("S1", fir)):
            ref = (final if kind == "S_T" else final_first)
            for name, (est, half, _) in res.items():
                e = est[:, lead]
                at_end = ref[name][0][:, lead].mean()
                held = int(np.sum(np.abs(e - at_end) <= half[:, lead]))
                true = "" if exact is None else (
                    f", exact {(exact[1] if kind == 'S_T' else exact[0])[lead]:.3f}")
                print(f"    {kind} {name:14s} mean {e.mean():7.3f}{true}, "
                      f"replicate spread ±{z * e.std(ddof=1):.3f}, "
                      f"mean bootstrap ±{half[:, lead].mean():.3f} "
                      f"(median ±{np.median(half[:, lead]):.3f}); intervals holding the "
                      f"mean at N = {n_max} ({at_end:.3f}): {held}/{len(e)}")
        n *= 2


def ishigami(seeds: int, n: int) -> None:
    """The comparison on the Ishigami function over ``seeds`` scramblings (closed form)."""
    from SALib.sample import sobol as sobol_sample

    problem = {"num_vars": 3, "names": ["x1", "x2", "x3"],
               "bounds": [[-math.pi, math.pi]] * 3}
    designs = []
    for s in range(seeds):
        x = sobol_sample.sample(problem, n, calc_second_order=False, seed=s)
        y = np.sin(x[:, 0]) + 7 * np.sin(x[:, 1]) ** 2 + 0.1 * x[:, 2] ** 4 * np.sin(x[:, 0])
        designs.append((y, 3))
    v1, v2, v13 = 0.5 * (1 + 0.1 * math.pi**4 / 5) ** 2, 49 / 8, 8 * 0.01 * math.pi**8 / 225
    v = v1 + v2 + v13
    report(designs, ("x1", "x2", "x3"), "Ishigami",
           ([v1 / v, v2 / v, 0.0], [(v1 + v13) / v, v2 / v, v13 / v]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stores", nargs="*", type=Path, help="stores of several seeds")
    parser.add_argument("--ishigami", type=int, default=0, help="seeds of the Ishigami check")
    parser.add_argument("--n", type=int, default=256, help="base N of the Ishigami check")
    a = parser.parse_args()
    if a.ishigami:
        ishigami(a.ishigami, a.n)
    stored = [pickle.loads(p.read_bytes()) for p in a.stores]
    if not stored:
        return
    groups = tuple(stored[0]["groups"])
    for metric in SENSITIVITY_METRICS:
        designs = []
        for d in stored:
            y = np.array([StateOutcome.from_dict(o).metrics.get(metric, math.nan)
                          for o in d["outcomes"]])
            y = np.where(np.isfinite(y), y, np.nanmean(y))
            designs.append((y, len(groups)))
        if min(float(np.var(y)) for y, _ in designs) <= 0.0:
            continue
        report(designs, groups, metric)


if __name__ == "__main__":
    main()
