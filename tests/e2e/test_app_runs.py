"""The page's analysis in one bounded run that sends its results as they come
(:func:`chaindrive.app.worker.run_bounded_steps`, :func:`chaindrive.app.runs.bounded_screens`),
and the page's script imported again in a run's child without drawing the page.

Outcomes only: the first result arrives while the run is still going (the child waits for a
file the test creates only afterwards), an error after it is raised where the results stop,
closing the results early ends the child, and the two screens of the seed example are those
of ``chaindrive.analyze`` of the same design.
"""

from __future__ import annotations

import os
import runpy
import tomllib
from collections.abc import Iterator
from pathlib import Path

import pytest

import chaindrive
from chaindrive.app import PAGE, runs
from chaindrive.app.worker import run_bounded_steps
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # child processes

SEED = tomllib.loads((EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8"))


# --- generators run in the child processes (importable by name) -----------------------------

def first_then_wait(flag: str) -> Iterator[str]:
    """Yield "first", then wait for ``flag`` (a file) and yield "second"."""
    yield "first"
    while not Path(flag).exists():
        sum(i * i for i in range(10_000))
    yield "second"


def first_then_refuse() -> Iterator[int]:
    yield 1
    raise DesignError("sprockets[1].teeth", "must be a whole number from 6 to 150, got 3")


def pid_then_spin() -> Iterator[int]:
    yield os.getpid()
    while True:
        sum(i * i for i in range(10_000))


# --- the runs ---------------------------------------------------------------------------------

def test_each_result_arrives_while_the_run_goes_on(tmp_path: Path) -> None:
    flag = tmp_path / "go"
    steps = run_bounded_steps(first_then_wait, str(flag), seconds=60.0)
    assert next(steps) == "first"  # the child is still waiting for the flag
    flag.touch()
    assert list(steps) == ["second"]


def test_an_error_after_a_result_is_raised_where_the_results_stop() -> None:
    steps = run_bounded_steps(first_then_refuse, seconds=60.0)
    assert next(steps) == 1
    with pytest.raises(DesignError) as info:
        next(steps)
    assert info.value.field == "sprockets[1].teeth"


def test_closing_the_results_ends_the_run() -> None:
    steps = run_bounded_steps(pid_then_spin, seconds=60.0)
    child = next(steps)
    assert child != os.getpid()
    steps.close()
    with pytest.raises(ProcessLookupError):  # killed and reaped
        os.kill(child, 0)


def test_the_screens_of_an_edit_come_quick_part_first() -> None:
    """The seed example: the quick screen (contour, numbers, checks; no document yet), then
    the complete one with the document — both of the analysis ``chaindrive.analyze`` gives."""
    screens = list(runs.bounded_screens(SEED))
    assert [s.document is None for s in screens] == [True, False]
    quick, whole = screens
    reference = chaindrive.analyze(drive_from_mapping(SEED), response=False)
    assert quick.numbers is not None and quick.numbers["links"] == reference.geometry.links
    assert whole.document is not None
    assert whole.document["geometry"]["links"] == reference.geometry.links
    assert [c.name for c in quick.checks] == [c.name for c in whole.checks]


def test_a_bad_design_is_one_screen_with_the_loaders_line() -> None:
    bad = {**SEED, "sprockets": [dict(r) for r in SEED["sprockets"]]}
    bad["sprockets"][1]["teeth"] = 3
    screens = list(runs.bounded_screens(bad))
    assert len(screens) == 1 and not screens[0].outcome.ok
    with pytest.raises(DesignError) as info:
        drive_from_mapping(bad)
    assert screens[0].outcome.message == str(info.value)


def test_the_page_script_imported_in_a_child_does_not_draw_the_page(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """multiprocessing imports the parent's main module (the page's script, under
    Streamlit) in every run's child as ``__mp_main__``: there it must start no analysis."""
    started: list[object] = []
    monkeypatch.setattr(runs, "bounded_screens", lambda *a: started.append(a) or iter(()))
    namespace = runpy.run_path(str(PAGE), run_name="__mp_main__")
    assert "page" in namespace
    assert started == []
