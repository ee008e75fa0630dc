"""The command line's safety net (chaindrive.cli.safety), run in this process through
``chaindrive.cli.run``: a mistake is one line and exit 2; anything unforeseen — an overflow,
a recursion, a numpy warning, a NaN in the result — is one line naming the command and a
log file that holds the traceback, exit 1; an output that cannot be written is one line and
leaves nothing behind.

The faults are injected (monkeypatch) where a real one was found by fuzzing; the expected
outcome is the promise of docs/reliability.md.
"""

from __future__ import annotations

import json
import math
import os
import signal
import time
import weakref
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.analysis import Analysis
from chaindrive.cli import run
from tests.conftest import EXAMPLES

SEED = EXAMPLES / "seed_three_sprocket.toml"


@pytest.fixture(autouse=True)
def logs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    logs = tmp_path / "logs"
    monkeypatch.setenv("CHAINDRIVE_LOG_DIR", str(logs))
    return logs


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def _internal(capsys: pytest.CaptureFixture[str], status: int, logs: Path, kind: str) -> None:
    _, err = capsys.readouterr()
    line = _one_line(err)
    assert status == 1
    assert line.startswith("error: internal error in `chaindrive analyze`") and kind in line
    logs_written = list(logs.glob("crash-*.log"))
    assert len(logs_written) == 1 and str(logs_written[0]) in line
    text = logs_written[0].read_text(encoding="utf-8")
    assert "Traceback" in text and kind in text and "command: chaindrive analyze" in text


@pytest.mark.parametrize("fault", [OverflowError("math range error"),
                                   RecursionError("maximum recursion depth exceeded"),
                                   MemoryError(), OSError(5, "Input/output error"),
                                   KeyError("x")])
def test_unforeseen_errors_are_one_line_and_a_log(fault: BaseException,
                                                  monkeypatch: pytest.MonkeyPatch,
                                                  capsys: pytest.CaptureFixture[str],
                                                  logs: Path) -> None:
    def broken(*args: object, **kwargs: object) -> None:
        raise fault

    monkeypatch.setattr(chaindrive, "analyze", broken)
    status = run(["analyze", str(SEED), "--json"])
    _internal(capsys, status, logs, type(fault).__name__)


def test_a_numpy_warning_stops_the_command(monkeypatch: pytest.MonkeyPatch,
                                           capsys: pytest.CaptureFixture[str],
                                           logs: Path) -> None:
    def overflowing(*args: object, **kwargs: object) -> None:
        np.exp(np.array([1000.0]))  # RuntimeWarning: overflow encountered in exp

    monkeypatch.setattr(chaindrive, "analyze", overflowing)
    status = run(["analyze", str(SEED), "--json"])
    _internal(capsys, status, logs, "RuntimeWarning")


def test_a_nan_in_the_result_is_never_printed(monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str],
                                              logs: Path) -> None:
    real = Analysis.to_dict

    def with_nan(self: Analysis) -> dict[str, object]:
        doc = real(self)
        doc["geometry"]["chain_length_mm"] = math.nan
        return doc

    monkeypatch.setattr(Analysis, "to_dict", with_nan)
    status = run(["analyze", str(SEED), "--json", "--quick"])
    out, err = capsys.readouterr()
    assert status == 1 and out == ""
    assert "nan at geometry.chain_length_mm" in _one_line(err)  # the line names where
    assert "Traceback" in next(logs.glob("crash-*.log")).read_text(encoding="utf-8")


def test_a_good_run_gives_finite_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["analyze", str(SEED), "--json", "--quick"]) == 0
    out, err = capsys.readouterr()
    doc = json.loads(out)  # strict: NaN and Infinity are not JSON
    assert doc["drive"]["name"] and err == ""


@pytest.mark.parametrize(("argv", "fragment"), [
    (["select", str(SEED), "--strands", "0"], "--strands"),
    (["report", str(SEED), "--dpi", "0"], "--dpi"),
    (["report", str(SEED), "--dpi", "5000"], "--dpi"),
    (["analyze", str(SEED), "--no-such-option"], "No such option"),
    (["no-such-command"], "No such command"),
    (["analyze"], "Missing argument"),
])
def test_usage_errors_are_one_line(argv: list[str], fragment: str,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert run(argv) == 2
    out, err = capsys.readouterr()
    assert fragment in _one_line(err) and out == ""


def test_help_still_works(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["--help"]) == 0
    assert "analyze" in capsys.readouterr().out


def test_a_newline_in_a_key_stays_one_line(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    design = tmp_path / "nl.toml"
    design.write_text(SEED.read_text(encoding="utf-8").replace(
        "[drive]", '[drive]\n"a\\nb" = 1', 1), encoding="utf-8")
    assert run(["analyze", str(design)]) == 2
    assert "a\\nb" in _one_line(capsys.readouterr().err)


@pytest.mark.parametrize("command", ["draw", "simulate", "report"])
def test_outputs_in_the_way_are_one_line_and_nothing_is_left(
        command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A file where the output's directory should be, and a directory with the output's
    name: one line, exit 2, nothing written (no temporary file either)."""
    suffix = {"draw": ".svg", "simulate": ".csv", "report": ".html"}[command]
    blocker = tmp_path / "blocker"
    blocker.write_text("in the way", encoding="utf-8")
    taken = tmp_path / f"taken{suffix}"
    taken.mkdir()
    short = tmp_path / "short.toml"
    short.write_text(SEED.read_text(encoding="utf-8")
                     + '\n[dynamics]\nstartup_duration = "0.05 s"\n', encoding="utf-8")
    # the smallest output that reaches the same write (chaindrive.io.atomic, after the output
    # is built): the report's two-page sheet and one sprocket's drawing (0.2 and 0.25 s
    # instead of 1.6-2.5 and 1.1-1.5 s of CPU for the full report and drawing)
    smallest = {"draw": ["--sprocket", "S3"], "report": ["--summary"]}.get(command, [])
    for target in (blocker / f"out{suffix}", taken):
        before = sorted(p.name for p in tmp_path.rglob("*"))
        assert run([command, str(short), "-o", str(target), *smallest]) == 2
        line = _one_line(capsys.readouterr().err)
        assert line.startswith("error: output: cannot write"), line
        assert sorted(p.name for p in tmp_path.rglob("*")) == before  # nothing new
    assert blocker.read_text(encoding="utf-8") == "in the way"


def test_a_file_name_too_long_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["analyze", "d" * 3000 + ".toml"]) == 2
    assert len(_one_line(capsys.readouterr().err)) < 700


def _signal_inside(kind: str) -> None:
    """Drop an object whose finaliser (``__del__``, or a ``weakref.finalize`` callback)
    receives SIGINT: the handler runs inside it (the signal is sent, then a loop)."""
    def interrupt() -> None:
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(100_000):  # the handler runs here, in the finaliser
            pass

    class Dropped:
        def __del__(self) -> None:
            if kind == "__del__":
                interrupt()

    dropped = Dropped()
    if kind == "weakref.finalize":
        weakref.finalize(dropped, interrupt)
    del dropped


@pytest.mark.parametrize("kind", ["__del__", "weakref.finalize"])
def test_a_signal_inside_a_finaliser_still_interrupts(
        kind: str, capsys: pytest.CaptureFixture[str]) -> None:
    """Python drops an exception raised in a finaliser ("Exception ignored in …"): SIGINT
    that came while a Dask future's ``__del__`` ran was lost, and ``optimize`` went on to
    its last generation. The net sends it again a moment later, and the command stops with
    its one line and 130."""
    from chaindrive.cli.safety import guarded

    went_on: list[float] = []

    def command() -> int:
        _signal_inside(kind)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:  # a command that goes on after the finaliser
            time.sleep(0.001)
        went_on.append(time.monotonic())
        return 0

    status = guarded(command, ["optimize"])
    line = _one_line(capsys.readouterr().err)
    assert status == 128 + signal.SIGINT and not went_on
    assert line == "error: interrupted by SIGINT; no output is left half-written"
