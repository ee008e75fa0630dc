"""Benchmark of the 24-mass modal analysis (issue 4 §Performance). Run:

    .venv/bin/python benchmarks/bench_modal.py

Prints a table: chaindrive RingModel assembly + modal analysis, opentorsion assembly +
undamped modal analysis of the equivalent 24-mass open chain, raw scipy.linalg.eigh(K, M)
on the same matrices, and the batch throughput (designs/s, frequencies only).
For one core set OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 before running.
"""

from __future__ import annotations

import time
import timeit

import numpy as np
import scipy.linalg

from chaindrive.dynamics import RingModel, ring_frequencies_batch, ring_stiffness_matrix

N = 24


def best_us(fn, number: int, repeat: int = 7) -> float:
    """Best time per call [µs] over ``repeat`` runs of ``number`` calls."""
    fn()
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number * 1e6


def main() -> None:
    rng = np.random.default_rng(0)
    m = rng.uniform(0.5, 20.0, N)
    c = rng.uniform(1e5, 1e8, N)
    c_open = c.copy()
    c_open[-1] = 0.0
    rows = []

    t_ours = best_us(lambda: RingModel(m, c_open).modal(), 2000)
    t_ours_closed = best_us(lambda: RingModel(m, c).modal(), 2000)
    K = ring_stiffness_matrix(c_open)
    M = np.diag(m)
    t_eigh = best_us(lambda: scipy.linalg.eigh(K, M), 2000)
    t_ot = float("nan")
    try:
        import opentorsion as ot

        def ot_run() -> None:
            shafts = [ot.Shaft(i, i + 1, k=float(c[i])) for i in range(N - 1)]
            disks = [ot.Disk(i, I=float(m[i])) for i in range(N)]
            ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()

        t_ot = best_us(ot_run, 100)
    except ImportError:
        pass
    rows.append(("chaindrive RingModel(...).modal(), open chain", t_ours, ""))
    rows.append(("chaindrive RingModel(...).modal(), closed ring", t_ours_closed, ""))
    rows.append(("scipy.linalg.eigh(K, M) alone (same matrices)", t_eigh,
                 f"ours / eigh = {t_ours / t_eigh:.2f} (need ≤ 1.5)"))
    rows.append(("opentorsion Assembly + undamped_modal_analysis", t_ot,
                 f"opentorsion / ours = {t_ot / t_ours:.1f} (need ≥ 20)"))

    B = 20000
    mb = rng.uniform(0.5, 20.0, (B, N))
    cb = rng.uniform(1e5, 1e8, (B, N))
    ring_frequencies_batch(mb[:100], cb[:100])
    best = min(_timed(lambda: ring_frequencies_batch(mb, cb)) for _ in range(3))
    print(f"{'case':<52} {'time / call':>14}  note")
    for name, t, note in rows:
        print(f"{name:<52} {t:>11.1f} µs  {note}")
    print(f"{'ring_frequencies_batch, 20 000 designs of 24 masses':<52} {best * 1e3:>11.1f} ms"
          f"  {B / best:,.0f} designs/s (need ≥ 20 000)")


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


if __name__ == "__main__":
    main()
