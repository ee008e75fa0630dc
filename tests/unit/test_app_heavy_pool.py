"""Heavy runs of the page (the link-level model, the robust study) in a pool of their own
(chaindrive.app.worker): at most MAX_HEAVY at once, one per session, in worker processes of
lower CPU priority, so that light sessions answer within their usual time while heavy ones
run; every limit message is a sentence (it was shown as a Python tuple)."""

from __future__ import annotations

import os
import statistics
import threading
import time
from pathlib import Path

import pytest

from chaindrive.app import worker
from chaindrive.app.worker import HEAVY_NICE, RunLimitError, run_bounded

pytestmark = pytest.mark.concurrency  # child processes, threads, timing

# --- functions run in the child processes (importable by name) ------------------------------


def burn_until(flag: str, limit_s: float = 60.0) -> int:
    """Busy (one core) until ``flag`` exists (or ``limit_s`` passed); the process's niceness."""
    end = time.monotonic() + limit_s
    while not Path(flag).exists() and time.monotonic() < end:
        sum(i * i for i in range(10_000))
    return os.nice(0)


def light(n: int = 3_000_000) -> int:
    """A light run: a fixed piece of work (about 0.2–0.5 s of one core)."""
    return sum(i * i for i in range(n))


def spin_forever() -> None:
    while True:
        sum(i * i for i in range(10_000))


def _timed_light() -> float:
    start = time.monotonic()
    run_bounded(light, seconds=60.0)
    return time.monotonic() - start


def _wait_until(test: object, seconds: float = 30.0) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if test():  # type: ignore[operator]
            return
        time.sleep(0.05)
    raise AssertionError("timed out")


def test_limit_messages_are_sentences() -> None:
    with pytest.raises(RunLimitError) as info:
        run_bounded(spin_forever, seconds=1.0, what="the link-level model")
    text = str(info.value)
    assert text.startswith("The link-level model took longer than 1 s") and text.endswith(".")
    assert "('run'" not in text and text[0] != "("


def test_light_runs_answer_while_heavy_runs_go_and_a_session_has_one(tmp_path: Path) -> None:
    baseline = statistics.median(_timed_light() for _ in range(3))
    flag = str(tmp_path / "stop")
    results: dict[str, object] = {}

    def heavy(session: str) -> None:
        try:
            results[session] = run_bounded(burn_until, flag, seconds=90.0, heavy=True,
                                           session=session, what="the link-level model")
        except Exception as exc:  # reported by the assertions below
            results[session] = exc

    threads = [threading.Thread(target=heavy, args=(s,)) for s in ("s1", "s2")]
    for t in threads:
        t.start()
    try:
        _wait_until(lambda: sum(worker._heavy_runs.values()) == 2)
        time.sleep(1.0)  # both heavy workers are burning the cores
        # the same session again: refused at once, in a sentence
        started = time.monotonic()
        with pytest.raises(RunLimitError) as info:
            run_bounded(light, heavy=True, session="s1", what="the life and reliability study")
        assert time.monotonic() - started < 1.0
        assert str(info.value).startswith("The life and reliability study was not started: "
                                          "this session already has a heavy computation")
        during = statistics.median(_timed_light() for _ in range(5))
    finally:
        Path(flag).touch()
        for t in threads:
            t.join(60)
    lowered = min(os.nice(0) + HEAVY_NICE, 19)  # 10 below this process (19 is the lowest)
    assert results == {"s1": lowered, "s2": lowered}  # heavy workers ran at lower priority
    # light sessions keep their usual time (the heavy processes yield the cores to them);
    # the margin covers the noise of a machine shared with other work
    print(f"light run: {baseline:.3f} s alone, {during:.3f} s beside two heavy runs")
    assert during <= 2.0 * baseline + 0.3, (baseline, during)
    assert not worker._heavy_runs  # every share given back
