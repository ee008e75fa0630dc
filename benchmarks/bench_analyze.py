"""Benchmark: `chaindrive analyze examples/twenty_four_sprocket.toml --json` (issue 2 asks for
under a second on the project machine). Times the whole command (interpreter start, imports,
file, analysis with the 1 s nonlinear start-up, JSON) ten times, and the in-process analysis
alone. Run after `make` (it compiles the start-up kernel ahead of time and the byte code;
without them a command pays about 0.7 s of numba set-up and ~0.1 s of compiling).

Run: .venv/bin/python benchmarks/bench_analyze.py
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

import chaindrive

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "examples" / "twenty_four_sprocket.toml"


def time_command(repeats: int = 10) -> list[float]:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "chaindrive", "analyze", str(DESIGN), "--json"],
                       check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return times


def time_in_process(repeats: int = 20) -> list[float]:
    drive = chaindrive.load(DESIGN)
    chaindrive.analyze(drive)  # warm-up (lazy imports)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        chaindrive.analyze(drive).to_dict()
        times.append(time.perf_counter() - t0)
    return times


def main() -> None:
    cmd = time_command()
    run = time_in_process()
    print(f"{'what':<48}{'median s':>10}{'max s':>10}")
    print(f"{'chaindrive analyze <24 sprockets> --json':<48}{statistics.median(cmd):>10.3f}"
          f"{max(cmd):>10.3f}")
    print(f"{'analyze(drive).to_dict() in process':<48}{statistics.median(run):>10.4f}"
          f"{max(run):>10.4f}")
    from chaindrive.dynamics.kernel_build import compiled_kernel

    print("start-up kernel:", "compiled ahead of time" if compiled_kernel() is not None
          else "numba just in time (run make to build it ahead of time)")
    print("target: the whole command under 1 s:",
          "MET" if max(cmd) < 1.0 else "NOT MET")


if __name__ == "__main__":
    main()
