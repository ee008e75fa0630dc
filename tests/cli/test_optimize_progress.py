"""The optimiser's progress: one step a design evaluated, in this process and on a cluster
(the command-line wrapper of the batch evaluator, chaindrive.cli._counted)."""

from __future__ import annotations

from typing import Any

import pytest

import chaindrive.synthesis.solve as solve_module
from chaindrive.cli import _counted


def test_in_this_process_the_bar_moves_design_by_design(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[list[Any]] = []
    monkeypatch.setattr(solve_module, "serial_evaluator",
                        lambda problem, xs: seen.append(list(xs)) or [("ev", x) for x in xs])
    steps: list[int] = []
    counted = _counted(None, lambda label: steps.append(len(seen)))
    out = counted("problem", [[1.0], [2.0], [3.0]])
    assert out == [("ev", [1.0]), ("ev", [2.0]), ("ev", [3.0])]  # same results, same order
    assert steps == [1, 2, 3]  # a step after each design, not after the batch


def test_on_a_cluster_the_batch_goes_whole_and_counts_each_design() -> None:
    calls: list[int] = []

    def cluster(problem: Any, xs: Any) -> list[Any]:
        calls.append(len(xs))
        return [("ev", x) for x in xs]

    steps: list[None] = []
    out = _counted(cluster, lambda label: steps.append(None))("problem", [[1.0], [2.0]])
    assert calls == [2]
    assert len(steps) == 2
    assert out == [("ev", [1.0]), ("ev", [2.0])]
