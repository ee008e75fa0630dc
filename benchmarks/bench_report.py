"""Benchmark: the design report of the seed example against its analysis (target: the report
at most 4× the analysis, in CPU time). Times whole commands, as a user runs them, in
alternation round after round (a slow spell of the shared machine falls on all of them
alike): ``chaindrive analyze SEED --json``, ``chaindrive analyze SEED`` (its tables, as a
user reads them), ``chaindrive report SEED -o x.pdf`` (the full
report) and ``chaindrive report SEED --summary -o x.pdf`` (the two-page sign-off sheet) —
the CPU time of each child process (user + system) and its wall time, with the machine's
load average beside them (the 2-core machine is shared). Then the in-process split of the
full report: analysis, figures (matplotlib), the rest of the sections, Typst. One BLAS
thread, as the commands run.

Run: .venv/bin/python benchmarks/bench_report.py [--repeats N] [--against SRC]

``--against SRC`` runs the commands of another source tree (its ``src`` directory, e.g. an
earlier commit's ``git archive``) in the same rounds and prints its ratio too.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before NumPy loads BLAS
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "src" / "chaindrive" / "examples" / "seed_three_sprocket.toml"
ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1",
       "MPLBACKEND": "Agg"}
#: The target: the report's CPU time over the analysis's.
TARGET_RATIO = 4.0


def run_once(args: list[str], src: str | None = None) -> tuple[float, float]:
    """(wall, CPU) [s] of one ``chaindrive`` command; ``src``: another tree's sources."""
    env = dict(ENV, PYTHONPATH=src) if src else ENV
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "chaindrive", *args], check=True,
                   capture_output=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def split_in_process() -> dict[str, float]:
    """CPU time [s] of the parts of one full report, in this process (warm: second run)."""
    import chaindrive
    from chaindrive.report import build_report, content, render_pdf

    spent = {"figures (savefig)": 0.0}
    plot_block = content.plot_block

    def timed(*a: object, **k: object) -> content.Plot:
        t = time.process_time()
        out = plot_block(*a, **k)  # type: ignore[arg-type]
        spent["figures (savefig)"] += time.process_time() - t
        return out

    import chaindrive.report.sections as s
    import chaindrive.report.sections_dynamics as d

    s.plot_block = d.plot_block = timed  # type: ignore[assignment]
    for _ in range(2):
        spent["figures (savefig)"] = 0.0
        t0 = time.process_time()
        a = chaindrive.analyze(chaindrive.load(DESIGN))
        a.to_dict()
        t1 = time.process_time()
        report = build_report(a, source=DESIGN)
        t2 = time.process_time()
        render_pdf(report)
        t3 = time.process_time()
    return {"analysis": t1 - t0, **spent,
            "sections without savefig": t2 - t1 - spent["figures (savefig)"],
            "Typst (PDF)": t3 - t2}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--against", help="source directory of another tree to compare")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        commands = {"analyze": ["analyze", str(DESIGN), "--json"],
                    "analyze (tables)": ["analyze", str(DESIGN)],
                    "report": ["report", str(DESIGN), "-o", f"{tmp}/full.pdf"],
                    "report --summary": ["report", str(DESIGN), "--summary", "-o",
                                         f"{tmp}/sheet.pdf"]}
        trees: dict[str, str | None] = {"this tree": None}
        if args.against:
            trees[args.against] = args.against
        # an earlier tree may not have the sheet: it runs in this tree only
        names = {t: [c for c in commands if src is None or c != "report --summary"]
                 for t, src in trees.items()}
        load_before = os.getloadavg()
        runs: dict[tuple[str, str], list[tuple[float, float]]] = {
            (t, c): [] for t in trees for c in names[t]}
        for _ in range(args.repeats):
            for tree, src in trees.items():
                for name in names[tree]:
                    runs[tree, name].append(run_once(commands[name], src))
        load_after = os.getloadavg()
    print(f"{'tree':<24}{'command':<20}{'CPU s':>8}{'wall s':>8}{'× analyze (CPU)':>17}")
    for tree in trees:
        base = statistics.median(r[1] for r in runs[tree, "analyze"])
        for name in names[tree]:
            cpu = statistics.median(r[1] for r in runs[tree, name])
            wall = statistics.median(r[0] for r in runs[tree, name])
            print(f"{tree:<24}{name:<20}{cpu:>8.2f}{wall:>8.2f}{cpu / base:>17.2f}")
    print(f"load average (1 min) {load_before[0]:.1f} before, {load_after[0]:.1f} after, on "
          f"{os.cpu_count()} cores; medians of {args.repeats} runs")
    print("in process, CPU s:", ", ".join(f"{k} {v:.2f}" for k, v in
                                          split_in_process().items()))
    report = statistics.median(r[1] for r in runs["this tree", "report"])
    for base_name in ("analyze", "analyze (tables)"):
        ratio = report / statistics.median(r[1] for r in runs["this tree", base_name])
        print(f"target: report ≤ {TARGET_RATIO:g}× {base_name} (CPU): "
              f"{'MET' if ratio <= TARGET_RATIO else 'NOT MET'} ({ratio:.2f}×)")


if __name__ == "__main__":
    main()
