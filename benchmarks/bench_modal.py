"""Benchmark of the 24-mass modal analysis (issue 4 §Performance). Run:

    .venv/bin/python benchmarks/bench_modal.py

Prints a table: chaindrive RingModel assembly + modal analysis, opentorsion assembly +
undamped modal analysis of the equivalent 24-mass open chain, raw scipy.linalg.eigh(K, M)
on the same matrices, and the batch throughput (designs/s, frequencies only). The contenders
run in alternation over 21 rounds (``_timing.interleaved``); the best per-call time of each is
compared, the ratio of the medians printed beside it.
For one core set OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 before running.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg

from _timing import interleaved
from chaindrive.dynamics import RingModel, ring_frequencies_batch, ring_stiffness_matrix

N = 24


def main() -> None:
    rng = np.random.default_rng(0)
    m = rng.uniform(0.5, 20.0, N)
    c = rng.uniform(1e5, 1e8, N)
    c_open = c.copy()
    c_open[-1] = 0.0
    K = ring_stiffness_matrix(c_open)
    M = np.diag(m)
    contenders = {
        "ours_open": (lambda: RingModel(m, c_open).modal(), 500),
        "ours_closed": (lambda: RingModel(m, c).modal(), 500),
        "eigh": (lambda: scipy.linalg.eigh(K, M), 500),
    }
    try:
        import opentorsion as ot

        def ot_run() -> None:
            shafts = [ot.Shaft(i, i + 1, k=float(c[i])) for i in range(N - 1)]
            disks = [ot.Disk(i, I=float(m[i])) for i in range(N)]
            ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()

        contenders["ot"] = (ot_run, 25)
    except ImportError:
        pass
    tm = interleaved(contenders, rounds=21)
    us = {k: v.best * 1e6 for k, v in tm.items()}
    med = {k: v.median * 1e6 for k, v in tm.items()}
    t_ot = us.get("ot", float("nan"))
    rows = [
        ("chaindrive RingModel(...).modal(), open chain", "ours_open", ""),
        ("chaindrive RingModel(...).modal(), closed ring", "ours_closed", ""),
        ("scipy.linalg.eigh(K, M) alone (same matrices)", "eigh",
         f"ours / eigh = {us['ours_open'] / us['eigh']:.2f} (need ≤ 1.5)"),
        ("opentorsion Assembly + undamped_modal_analysis", "ot",
         f"opentorsion / ours = {t_ot / us['ours_open']:.1f} (need ≥ 20; medians "
         f"{med.get('ot', float('nan')) / med['ours_open']:.1f})"),
    ]
    B = 20000
    mb = rng.uniform(0.5, 20.0, (B, N))
    cb = rng.uniform(1e5, 1e8, (B, N))
    ring_frequencies_batch(mb[:100], cb[:100])
    best = min(_timed(lambda: ring_frequencies_batch(mb, cb)) for _ in range(3))
    print(f"{'case':<52} {'time / call':>14}  note")
    for name, key, note in rows:
        if key in us:
            print(f"{name:<52} {us[key]:>11.1f} µs  {note}")
    print(f"{'ring_frequencies_batch, 20 000 designs of 24 masses':<52} {best * 1e3:>11.1f} ms"
          f"  {B / best:,.0f} designs/s (need ≥ 20 000)")


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


if __name__ == "__main__":
    main()
