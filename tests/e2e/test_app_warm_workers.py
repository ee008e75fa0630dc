"""The page's warm worker processes (:mod:`chaindrive.app.worker`): a run that ended in
order leaves its worker for the next run; a run stopped by its time limit, by its memory
limit or by its results closed early takes its worker with it; a worker is retired after
``RUNS_PER_WORKER`` runs; and a worker that analysed one design gives the next design its
own results, those of ``chaindrive.analyze`` (the one pipeline).

Outcomes only (process ids, results, errors), never timings.
"""

from __future__ import annotations

import os
import tomllib
from collections.abc import Iterator
from pathlib import Path

import pytest

import chaindrive
from chaindrive.app import runs, views, worker
from chaindrive.app.worker import RunLimitError, run_bounded, run_bounded_steps
from chaindrive.io.design import drive_from_mapping
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # child processes

BIG = tomllib.loads((EXAMPLES / "twenty_four_sprocket.toml").read_text(encoding="utf-8"))


# --- functions run in the workers (importable by name) --------------------------------------

def pid() -> int:
    return os.getpid()


def spin(flag: str) -> str:
    """Busy until ``flag`` (a file) exists — forever when nobody creates it."""
    while not Path(flag).exists():
        sum(i * i for i in range(10_000))
    return "done"


def pid_then_allocate(gigabytes: float) -> Iterator[int]:
    """Yield the process id, then allocate and touch ``gigabytes`` of memory."""
    yield os.getpid()
    block = bytearray(int(gigabytes * 1024**3))
    yield len(block)


def pid_then_more() -> Iterator[int]:
    yield os.getpid()
    yield 0


def _gone(process: int) -> bool:
    try:
        os.kill(process, 0)
    except ProcessLookupError:
        return True
    return False


# --- the workers ------------------------------------------------------------------------------

def test_a_finished_run_leaves_its_worker_for_the_next() -> None:
    first = run_bounded(pid)
    assert first != os.getpid()
    assert run_bounded(pid) == first
    steps = list(run_bounded_steps(pid_then_more))
    assert steps == [first, 0]
    assert run_bounded(pid) == first  # the steps ran to their end: the worker stays


def test_a_run_past_its_time_takes_its_worker_with_it(tmp_path: Path) -> None:
    warm = run_bounded(pid)
    with pytest.raises(RunLimitError, match="took longer than 1 s"):
        run_bounded(spin, str(tmp_path / "never"), seconds=1.0)  # on the warm worker
    assert _gone(warm)
    assert run_bounded(pid) not in (warm, os.getpid())


def test_a_worker_out_of_memory_is_not_reused() -> None:
    steps = run_bounded_steps(pid_then_allocate, 4.0, memory=1024**3)
    child = next(steps)
    with pytest.raises(RunLimitError, match="more than 1 GB of memory"):
        next(steps)
    assert _gone(child)
    assert run_bounded(pid, memory=1024**3) != child


def test_results_closed_early_take_the_worker_with_them() -> None:
    steps = run_bounded_steps(pid_then_more)
    child = next(steps)
    steps.close()
    assert _gone(child)


def test_a_worker_is_retired_after_its_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(worker, "RUNS_PER_WORKER", 2)
    monkeypatch.setattr(worker, "_idle", {})  # a fresh worker: no runs counted yet
    first = run_bounded(pid)
    assert run_bounded(pid) == first  # its second run: then retired
    assert _gone(first)
    assert run_bounded(pid) != first


def test_a_warm_worker_gives_each_design_its_own_results() -> None:
    """Edits of the 24-sprocket example (S2's tooth count) one after the other on the same
    worker: each screen's links and checks are those ``chaindrive.analyze`` gives for that
    design (nothing carried over from the design before)."""
    for teeth in (16, 23, 16):
        design = {**BIG, "sprockets": [dict(r) for r in BIG["sprockets"]]}
        design["sprockets"][1]["teeth"] = teeth
        quick, whole = list(runs.bounded_screens(design))
        reference = chaindrive.analyze(drive_from_mapping(design), response=False)
        assert quick.numbers is not None
        assert quick.numbers["links"] == reference.geometry.links
        assert quick.numbers["chain_length_m"] == reference.geometry.chain_length
        assert [(c.name, c.result) for c in quick.checks] == [
            (c.name, c.result) for c in whole.checks]
        assert [(c.name, c.value) for c in quick.checks] == [
            (c.name, c.value) for c in views.checks(reference)]
