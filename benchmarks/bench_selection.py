"""Benchmark: the chain selection (every chain of the family checked on the laid-out drive)
against one contour layout of the same drive, for the 8- and 24-sprocket examples.

The selection lays the drive out once per distinct (pitch, roller) of the family and checks
every candidate; the ratio to one layout says what the check of the whole catalogue costs.

Run: .venv/bin/python benchmarks/bench_selection.py
"""

from __future__ import annotations

import time
from pathlib import Path

import chaindrive
from chaindrive.geometry.contour import contour_geometry
from chaindrive.strength.selection import rank_chains

ROOT = Path(__file__).resolve().parents[1]
DESIGNS = ("eight_sprocket.toml", "twenty_four_sprocket.toml")


def best_of(fn, repeats: int = 7) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    for name in DESIGNS:
        drive = chaindrive.load(ROOT / "examples" / name)
        rank_chains(drive)  # warm caches (catalogue, tables)
        layout = best_of(lambda d=drive: contour_geometry(d))
        select = best_of(lambda d=drive: rank_chains(d))
        analysis = best_of(lambda d=drive: chaindrive.analyze(d, response=False))
        n = len(rank_chains(drive).candidates)
        print(f"{name}: one layout {layout * 1e3:.2f} ms, selection of {n} chains "
              f"{select * 1e3:.1f} ms ({select / layout:.0f}x one layout), "
              f"analyze(response=False) {analysis * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
