"""CPU time of the link-level step loop, this tree's kernel against another one in the same
run (docs/linklevel.md §3, docs/performance.md).

Run (one BLAS thread):
    git show <commit>:src/chaindrive/linklevel/kernel.py > /tmp/kernel_before.py
    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_step.py /tmp/kernel_before.py

For each drive — the seed example (128 links), a 12B 15/25 drive 85 pitches apart (192
links) and the 24-sprocket example (744 links) — the arguments of its run_kernel call are
taken from a short run at working speed and power (the static state apart); then each
kernel advances the same state the same number of steps, the two alternating (the machine is
shared: the load average is printed), best of the repeats. CPU time (``time.process_time``)
per step and per simulated second, and how far the two kernels' roller positions end apart.
Without an argument, this tree's kernel alone.
"""

from __future__ import annotations

import importlib
import inspect
import os
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import chaindrive.linklevel.kernel as kernel
from chaindrive.io.design import load_drive
from chaindrive.linklevel import simulate

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_linklevel_reference import EXAMPLES, _two_sprocket

REPEATS = 4


def kernel_arguments(drive: Any) -> list[Any]:
    """The arguments of ``drive``'s run_kernel call (a 10 ms run at working speed)."""
    module = sys.modules["chaindrive.linklevel.simulate"]
    original, captured = module.run_kernel, []

    def grab(*args: Any) -> None:
        captured.append(args)
        original(*args)

    module.run_kernel = grab
    try:
        simulate(drive, 0.01, initial_speed="working", sample_rate_hz=1000)
    finally:
        module.run_kernel = original
    return list(captured[-1])


def fresh_arguments(a0: list[Any], steps: int) -> list[Any]:
    """A copy of the run_kernel arguments a0 for ``steps`` steps: every array copied, the
    records, the energy terms and the engagement events zeroed."""
    a = [np.array(z, copy=True) if isinstance(z, np.ndarray) else z for z in a0]
    N, D, every = a0[0].shape[0], a0[2].size, a0[7]
    a[5] = steps
    rows = steps // every + 1
    a[35:42] = [np.zeros((rows, N, 2)), np.zeros((rows, D)), np.zeros((rows, D)),
                np.zeros((rows, N)), np.zeros((rows, N)), np.zeros((rows, N), dtype=np.int64),
                np.zeros((rows, N), dtype=np.int64)]
    a[42] = np.zeros(6)
    a[45], a[46] = np.zeros((100_000, 4)), np.zeros(1, dtype=np.int64)
    return a


def run(kern: Any, a0: list[Any], steps: int) -> tuple[float, np.ndarray]:
    """(CPU seconds per step, final positions) of ``steps`` steps of ``kern`` from a0."""
    a = fresh_arguments(a0, steps)
    n = len(inspect.signature(kern.run_kernel.py_func).parameters)  # an older kernel: fewer
    t = time.process_time()
    kern.run_kernel(*a[:n])
    return (time.process_time() - t) / steps, a[0]


def main() -> None:
    kernels: dict[str, Any] = {"this tree": kernel}
    if len(sys.argv) > 1:
        path = Path(sys.argv[1]).resolve()  # imported by name: numba's cache needs one
        sys.path.insert(0, str(path.parent))
        kernels = {"other": importlib.import_module(path.stem), "this tree": kernel}
    drives = (("seed", load_drive(EXAMPLES / "seed_three_sprocket.toml"), 40_000),
              ("12B 15/25", _two_sprocket(85, 300.0, 1000.0), 30_000),
              ("24 sprockets", load_drive(EXAMPLES / "twenty_four_sprocket.toml"), 6_000))
    for name, drive, steps in drives:
        a0 = kernel_arguments(drive)
        dt = float(a0[6])
        for k in kernels.values():
            run(k, a0, 10)  # compile or load the cache
        best = {key: np.inf for key in kernels}
        ends: dict[str, np.ndarray] = {}
        loads = []
        for _ in range(REPEATS):
            for key, k in kernels.items():
                per, ends[key] = run(k, a0, steps)
                best[key] = min(best[key], per)
                loads.append(os.getloadavg()[0])
        parts = [f"{key}: {best[key] * 1e9:5.0f} ns a step, {best[key] / dt:6.3f} s per "
                 f"simulated s ({dt / best[key]:4.1f}× real time)" for key in kernels]
        apart = (f"; positions apart after {steps} steps: "
                 f"{np.abs(ends['other'] - ends['this tree']).max():.1e} m"
                 if len(kernels) > 1 else "")
        ratio = (f"; ratio {best['other'] / best['this tree']:.2f}" if len(kernels) > 1
                 else "")
        print(f"{name:12s} {a0[0].shape[0]:4d} links, dt {dt * 1e6:5.2f} µs: "
              + "; ".join(parts) + ratio + apart
              + f"; load {min(loads):.1f}–{max(loads):.1f} on {os.cpu_count()} cores",
              flush=True)


if __name__ == "__main__":
    main()
