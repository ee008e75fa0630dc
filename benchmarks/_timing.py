"""Side-by-side timing for the benchmarks: the contenders run in alternation, round after
round, so that a slow spell of the (shared, noisy) machine falls on all of them alike.

Each round times ``number`` calls of every contender (timeit's timer, one block per
contender); the result per contender is the best and the median per-call time over the
rounds. The best is what :mod:`timeit` recommends for comparing code (the other values
measure the machine's interference, not the code); the median is printed beside it.
"""

from __future__ import annotations

import statistics
import timeit
from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Timing:
    """Per-call time [s]: best and median over the rounds."""

    best: float
    median: float


def interleaved(contenders: dict[str, tuple[Callable[[], object], int]],
                rounds: int = 15) -> dict[str, Timing]:
    """{name: (fn, calls per round)} → {name: Timing}; every fn is called once first."""
    for fn, _ in contenders.values():
        fn()
    samples: dict[str, list[float]] = {name: [] for name in contenders}
    for _ in range(rounds):
        for name, (fn, number) in contenders.items():
            samples[name].append(timeit.timeit(fn, number=number) / number)
    return {name: Timing(min(s), statistics.median(s)) for name, s in samples.items()}
