"""Benchmark: the time from an edit of the 24-sprocket example to its results on screen, in
a real browser (Chromium driven by Playwright), at 1400×900.

The measurement is the browser test's own
(``tests/e2e/test_app_browser.py::test_24_sprockets_fold_reset_and_edit_time``): eight edits
of a tooth count typed in the sprocket table (committed by Enter) and eight through the
"edit one sprocket" form (committed by Apply), each timed from the committing key to

* the results of its design on screen: the contour, the headline numbers and the verdict
  (the page's results marker, written right after them), and
* the end of the page's run (its ready marker, written after the chain selection, the
  warnings and the open tab).

This script runs that test ``--runs`` times and reports the medians and the worst edit, and
the server's side of the same edits, phase by phase (the page writes them to the file named
by ``CHAINDRIVE_APP_TIMING``): the script up to the design (widgets, table), the bounded run
to its quick screen (fork, analysis, result sent back), drawing the quick results, the rest
of the run to the complete screen, and the tabs.
Beside it, ``bench_app_recompute.py`` times the server side alone (the analysis the page
runs after an edit). The machine is shared: run it idle, and read ``uptime`` beside it.

Run: .venv/bin/python benchmarks/bench_app_browser.py [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TEST = ("tests/e2e/test_app_browser.py::test_24_sprockets_fold_reset_and_edit_time")
TARGET_S = 0.300


#: The page's phases (marks of CHAINDRIVE_APP_TIMING, in order) and what each span is.
PHASES = (("early", "design read from the state, run, drawn"),
          ("form", "script up to the design (widgets, table)"),
          ("quick_run", "bounded run → quick screen"),
          ("shown", "quick results drawn"),
          ("complete_run", "run goes on → complete screen"),
          ("done", "warnings, checks, tabs"))


def server_phases(path: Path) -> dict[str, list[float]]:
    """The spans between the page's phase marks [s], for each run of the page that ran an
    analysis (a design not seen before: its run took over 50 ms)."""
    spans: dict[str, list[float]] = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        marks = json.loads(line)
        if marks.get("early", 0.0) + marks["quick_run"] - marks["form"] < 0.05:
            continue
        marks.setdefault("early", 0.0)
        before = 0.0
        for key, _ in PHASES:
            spans.setdefault(key, []).append(marks[key] - before)
            before = marks[key]
    return spans


def run_once() -> dict[str, list[float]]:
    """One run of the browser test; its measured times and the server's phases [s]."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "times.json"
        phases = Path(tmp) / "phases.jsonl"
        env = {**os.environ, "CHAINDRIVE_BENCH_OUT": str(out),
               "CHAINDRIVE_APP_TIMING": str(phases)}
        proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                               TEST], cwd=ROOT, env=env, capture_output=True, text=True,
                              check=False)
        if proc.returncode != 0 or not out.exists():
            raise SystemExit(f"the browser test failed:\n{proc.stdout[-3000:]}")
        times: dict[str, list[float]] = json.loads(out.read_text(encoding="utf-8"))
        server = server_phases(phases) if phases.exists() else {}
        return times | {f"server_{k}": v for k, v in server.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="runs of the browser test")
    args = parser.parse_args()
    load = os.getloadavg()[0]
    merged: dict[str, list[float]] = {}
    for _ in range(args.runs):
        for key, values in run_once().items():
            merged.setdefault(key, []).extend(values)
    print(f"24-sprocket example at 1400x900, {args.runs} run(s), load average {load:.1f} "
          f"at the start, {os.getloadavg()[0]:.1f} at the end")
    print(f"{'edit':32s} {'median s':>9s} {'max s':>7s}")
    for way in ("table", "form"):
        for what in ("shown", "complete"):
            v = merged[f"{way}_{what}_s"]
            label = f"{way}: results shown" if what == "shown" else f"{way}: page complete"
            print(f"{label:32s} {statistics.median(v):9.3f} {max(v):7.3f}")
    if "server_form" in merged:
        print(f"server side of the edits that ran an analysis "
              f"({len(merged['server_form'])} runs of the page):")
        for key, label in PHASES:
            v = merged[f"server_{key}"]
            print(f"  {label:38s} {statistics.median(v):9.3f} {max(v):7.3f}")
    met = all(statistics.median(merged[f"{w}_shown_s"]) <= TARGET_S for w in ("table", "form"))
    print(f"target: results shown within {TARGET_S * 1e3:.0f} ms (median): "
          f"{'met' if met else 'NOT MET'}")


if __name__ == "__main__":
    main()
