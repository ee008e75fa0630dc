"""Benchmark: `chaindrive analyze examples/twenty_four_sprocket.toml --json` (target: under a
second on the project machine). Times the whole command (interpreter start, imports, file,
analysis with the 1 s nonlinear start-up, JSON) ten times — wall time and the CPU time of
the child process (user + system), with the machine's load average beside them, since the
2-core machine is shared — and the in-process analysis alone. Run after `make` (it compiles
the start-up kernel ahead of time and the byte code; without them a command pays about
0.7 s of numba set-up and ~0.1 s of compiling). One BLAS thread (as the targets say; on a
busy machine more threads make the small products slower).

Run: .venv/bin/python benchmarks/bench_analyze.py [--against SRC]

``--against SRC`` runs the command of another source tree (its ``src`` directory, e.g. an
earlier commit's ``git archive`` with its byte code compiled) in alternation with this one
and prints both.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before NumPy loads BLAS
os.environ.setdefault("OMP_NUM_THREADS", "1")

import chaindrive

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "examples" / "twenty_four_sprocket.toml"
ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}


def run_once(src: str | None = None) -> tuple[float, float]:
    """(wall, CPU) [s] of one command; ``src``: another tree's source directory."""
    env = dict(ENV, PYTHONPATH=src) if src else ENV
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "chaindrive", "analyze", str(DESIGN), "--json"],
                   check=True, capture_output=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def time_in_process(repeats: int = 20) -> list[float]:
    drive = chaindrive.load(DESIGN)
    chaindrive.analyze(drive)  # warm-up (lazy imports)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        chaindrive.analyze(drive).to_dict()
        times.append(time.perf_counter() - t0)
    return times


def _row(name: str, runs: list[tuple[float, float]]) -> str:
    wall, cpu = [r[0] for r in runs], [r[1] for r in runs]
    return (f"{name:<48}{statistics.median(wall):>10.3f}{max(wall):>8.3f}"
            f"{statistics.median(cpu):>10.3f}")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--against", help="source directory of another tree to compare")
    parser.add_argument("--repeats", type=int, default=10)
    args = parser.parse_args()
    load_before = os.getloadavg()
    ours: list[tuple[float, float]] = []
    theirs: list[tuple[float, float]] = []
    for _ in range(args.repeats):
        ours.append(run_once())
        if args.against:
            theirs.append(run_once(args.against))
    run = time_in_process()
    load_after = os.getloadavg()
    print(f"{'what':<48}{'median s':>10}{'max s':>8}{'CPU s':>10}  (wall median, max; "
          "CPU median)")
    print(_row("chaindrive analyze <24 sprockets> --json", ours))
    if theirs:
        print(_row(f"the same, {args.against}", theirs))
    print(f"{'analyze(drive).to_dict() in process':<48}{statistics.median(run):>10.4f}"
          f"{max(run):>8.4f}")
    print(f"load average (1 min) {load_before[0]:.1f} before, {load_after[0]:.1f} after, "
          f"on {os.cpu_count()} cores")
    from chaindrive.dynamics.transient.kernel_build import compiled_kernel

    print("start-up kernel:", "compiled ahead of time" if compiled_kernel() is not None
          else "numba just in time (run make to build it ahead of time)")
    print("target: the whole command's median under 1 s:",
          "MET" if statistics.median(r[0] for r in ours) < 1.0 else "NOT MET")


if __name__ == "__main__":
    main()
