"""Repeat the tests that involve time, threads, processes, Dask, the web server or the browser
(marker ``concurrency``) and report how often each failed: ``make flaky`` runs it.

    python -m tests.flaky [--count N] [--load K] [--workers W] [-k EXPR] [pytest args…]

``--count`` repeats every selected test N times in a row (pytest-repeat, default 30);
``--load`` keeps K busy processes running meanwhile (``--load 2`` keeps both cores of the
project machine busy), so a test that only passes on an idle machine shows up here and not
in CI; ``--workers`` runs the repetitions on W processes at once (pytest-xdist, each test
then runs beside another one, as in ``make test``; 0: one process). The exit status is 0
only when no repetition failed.
"""

from __future__ import annotations

import argparse
import multiprocessing
import re
import sys
import time
from collections import Counter
from typing import Any

import pytest

#: pytest-repeat appends ``-<i>-<count>`` to the test's parameter id (``[3-30]`` alone).
_REPEAT_ID = re.compile(r"(?:\[|-)(\d+)-(\d+)\]$")


def _base(nodeid: str) -> str:
    """The test's id without the repetition's suffix."""
    m = _REPEAT_ID.search(nodeid)
    if m is None:
        return nodeid
    head = nodeid[:m.start()]
    return head if nodeid[m.start()] == "[" else head + "]"


class Tally:
    """pytest plugin: runs and failures per test, over the repetitions."""

    def __init__(self) -> None:
        self.runs: Counter[str] = Counter()
        self.failures: Counter[str] = Counter()

    def pytest_runtest_logreport(self, report: Any) -> None:
        test = _base(report.nodeid)
        if report.when == "call" or (report.when == "setup" and report.failed):
            self.runs[test] += 1  # a setup that fails ends the run without a call
        if report.failed:
            self.failures[test] += 1

    def table(self) -> str:
        width = max((len(t) for t in self.runs), default=10)
        rows = [f"{'test':{width}s}  runs  failures"]
        rows += [f"{t:{width}s}  {self.runs[t]:4d}  {self.failures[t]:8d}"
                 for t in sorted(self.runs)]
        return "\n".join(rows)


def _busy(stop: Any) -> None:
    while not stop.is_set():
        sum(i * i for i in range(10_000))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=30, help="repetitions of each test")
    parser.add_argument("--load", type=int, default=0, help="busy processes meanwhile")
    parser.add_argument("--workers", type=int, default=0, help="test processes (pytest-xdist)")
    args, rest = parser.parse_known_args(argv)
    stop = multiprocessing.Event()
    load = [multiprocessing.Process(target=_busy, args=(stop,), daemon=True)
            for _ in range(args.load)]
    for p in load:
        p.start()
    tally = Tally()
    start = time.monotonic()
    workers = ["-n", str(args.workers), "--dist", "load"] if args.workers > 0 else []
    try:
        code = pytest.main(["-q", "-m", "concurrency", "--count", str(args.count),
                            "-p", "no:cacheprovider", *workers, *rest], plugins=[tally])
    finally:
        stop.set()
        for p in load:
            p.join(5)
    print(f"\n{args.count} repetitions, {args.load} busy processes, {args.workers} workers, "
          f"{time.monotonic() - start:.0f} s")
    print(tally.table())
    failed = sum(tally.failures.values())
    print(f"failures in all: {failed}")
    return 1 if failed or code not in (0, 5) else 0


if __name__ == "__main__":
    sys.exit(main())
