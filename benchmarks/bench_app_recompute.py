"""Benchmark: what the web page does after an edit of the 24-sprocket contour (issue 7 asks
for the geometry, kinematics, strength and modal results within 300 ms of an edit).

Times the pure layer the page runs on every edit — edited form → design mapping → validated
Drive → ``analyze`` (geometry, kinematics, selection, strength, modal analysis, resonance
table, Campbell data) → JSON document, headline numbers, checks and the layout SVG — for a
tooth-count edit that changes the result each time (so nothing is served from a cache).
For reference it also times what is drawn only when its tab is open (the matplotlib
Campbell diagram) and what the browser adds is not counted (Streamlit's round trip is a few
tens of milliseconds on localhost).

Run: .venv/bin/python benchmarks/bench_app_recompute.py
"""

from __future__ import annotations

import statistics
import time
import tomllib
from pathlib import Path

from chaindrive.app.runs import figure_png
from chaindrive.app.state import design_from_form, form_from_design
from chaindrive.app.views import complete, quick_screen, recompute

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "examples" / "twenty_four_sprocket.toml"
TARGET_S = 0.300
#: Tooth counts the edit cycles through on the second sprocket (an inside idler).
TEETH = (15, 16, 17, 18, 19, 20, 21, 22)


def time_edits(repeats: int = 24) -> tuple[list[float], list[float]]:
    """Per edit: the quick part the page draws first (contour, numbers, checks) and the
    whole screen (plus the document with the chain selection) [s]."""
    form = form_from_design(tomllib.loads(DESIGN.read_text(encoding="utf-8")))
    recompute(design_from_form(form))  # warm-up: lazy imports, pint registry, catalogue
    quick, whole = [], []
    for i in range(repeats):
        form.sprockets[1]["teeth"] = float(TEETH[i % len(TEETH)])
        t0 = time.perf_counter()
        screen = quick_screen(design_from_form(form))
        t1 = time.perf_counter()
        screen = complete(screen)
        quick.append(t1 - t0)
        whole.append(time.perf_counter() - t0)
        assert screen.outcome.ok, screen.outcome.message
    return quick, whole


def time_campbell(repeats: int = 5) -> list[float]:
    from chaindrive.plotting import campbell_diagram

    form = form_from_design(tomllib.loads(DESIGN.read_text(encoding="utf-8")))
    analysis = recompute(design_from_form(form)).outcome.analysis
    assert analysis is not None and analysis.dynamics.campbell is not None
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        figure_png(campbell_diagram(analysis.dynamics.campbell, operating_rpm=250.0))
        times.append(time.perf_counter() - t0)
    return times


def main() -> None:
    quick, edits = time_edits()
    campbell = time_campbell()
    print(f"{'what (24-sprocket contour)':<58}{'median s':>10}{'max s':>10}")
    print(f"{'edit → design → contour, numbers, checks (drawn first)':<58}"
          f"{statistics.median(quick):>10.4f}{max(quick):>10.4f}")
    print(f"{'edit → … and the document with the chain selection':<58}"
          f"{statistics.median(edits):>10.4f}{max(edits):>10.4f}")
    print(f"{'Campbell diagram PNG (only when its tab is open)':<58}"
          f"{statistics.median(campbell):>10.4f}{max(campbell):>10.4f}")
    print(f"target: recompute within {TARGET_S * 1e3:.0f} ms of an edit:",
          "MET" if max(edits) < TARGET_S else "NOT MET",
          "(the browser adds its share: benchmarks/bench_app_browser.py)")


if __name__ == "__main__":
    main()
