"""The atomic writers (chaindrive.io.atomic): a target is replaced only by a complete file;
a writer that fails leaves the old target (or none) and no temporary file; an operating
system error is one DesignError line naming the output and the reason."""

from __future__ import annotations

import os
import signal
import threading
from pathlib import Path

import pytest

from chaindrive.errors import DesignError
from chaindrive.io import atomic
from chaindrive.io.atomic import TMP_MARK, atomic_directory, atomic_path, write_text


def _files(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.rglob("*"))


def test_the_target_appears_complete(tmp_path: Path) -> None:
    target = tmp_path / "sub" / "a.html"
    with atomic_path(target) as tmp:
        assert tmp.parent == target.parent and tmp.suffix == ".html" and TMP_MARK in tmp.name
        tmp.write_text("<html></html>", encoding="utf-8")
        assert not target.exists()  # not before the writer is done
    assert target.read_text(encoding="utf-8") == "<html></html>"
    assert _files(tmp_path) == ["a.html", "sub"]


def _write_half_then(target: Path, failure: BaseException) -> None:
    with atomic_path(target) as tmp:
        tmp.write_text("half", encoding="utf-8")
        raise failure


def test_a_failing_writer_leaves_the_old_target(tmp_path: Path) -> None:
    target = tmp_path / "a.csv"
    write_text(target, "old\n")
    with pytest.raises(ZeroDivisionError):
        _write_half_then(target, ZeroDivisionError())
    assert target.read_text(encoding="utf-8") == "old\n"
    assert _files(tmp_path) == ["a.csv"]


def test_an_interrupt_leaves_nothing(tmp_path: Path) -> None:
    with pytest.raises(KeyboardInterrupt):
        _write_half_then(tmp_path / "a.csv", KeyboardInterrupt())
    assert _files(tmp_path) == []


@pytest.mark.parametrize("case", ["file in the way", "directory of that name", "too long"])
def test_os_errors_are_one_line(tmp_path: Path, case: str) -> None:
    (tmp_path / "blocker").write_text("x", encoding="utf-8")
    (tmp_path / "taken.csv").mkdir()
    target = {"file in the way": tmp_path / "blocker" / "a.csv",
              "directory of that name": tmp_path / "taken.csv",
              "too long": tmp_path / ("a" * 3000 + ".csv")}[case]
    before = _files(tmp_path)
    with pytest.raises(DesignError) as info:
        write_text(target, "x")
    line = str(info.value)
    assert line.startswith("output: cannot write") and "\n" not in line and len(line) < 300
    assert _files(tmp_path) == before


def test_a_directory_of_outputs_is_all_or_nothing(tmp_path: Path) -> None:
    out = tmp_path / "pareto"

    def fail_after_one() -> None:
        with atomic_directory(out) as tmp:
            (tmp / "a.toml").write_text("a", encoding="utf-8")
            raise RuntimeError("the report failed")

    with pytest.raises(RuntimeError):
        fail_after_one()
    assert _files(tmp_path) == []
    with atomic_directory(out) as tmp:
        (tmp / "a.toml").write_text("a", encoding="utf-8")
        (tmp / "b.toml").write_text("b", encoding="utf-8")
    assert _files(out) == ["a.toml", "b.toml"]
    with atomic_directory(out) as tmp:  # into an existing directory: files replaced
        (tmp / "a.toml").write_text("A", encoding="utf-8")
    assert (out / "a.toml").read_text(encoding="utf-8") == "A" and _files(tmp_path) == [
        "a.toml", "b.toml", "pareto"]


def test_a_directory_over_a_file_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "x").write_text("file", encoding="utf-8")
    with pytest.raises(DesignError, match="--out: cannot write"), \
            atomic_directory(tmp_path / "x", field="--out"):
        pass
    assert _files(tmp_path) == ["x"]


class _SignalledError(Exception):
    """What the test's SIGTERM handler raises (as the CLI's safety net raises Interrupted)."""


@pytest.mark.parametrize("kind", ["file", "directory"])
def test_a_signal_the_instant_the_temporary_appears_leaves_nothing(
        kind: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """SIGTERM sent by the process to itself right after the temporary file or directory is
    created (what a signal from outside does when it lands in that instant; the CLI test
    sends it as soon as the temporary shows): the handler's exception must still find the
    temporary removed, never left behind (a window that once let a loaded machine keep
    one)."""
    def _raise(signum: int, frame: object) -> None:
        raise _SignalledError(signum)

    if kind == "file":
        real_open = os.open

        def creating(path: object, *args: object, **kwargs: object) -> int:
            fd = real_open(path, *args, **kwargs)  # type: ignore[arg-type]
            if TMP_MARK in str(path):
                os.kill(os.getpid(), signal.SIGTERM)
            return fd
        monkeypatch.setattr(atomic.os, "open", creating)
        context = atomic_path(tmp_path / "a.html")
    else:
        real_mkdir = Path.mkdir

        def mkdir(self: Path, *args: object, **kwargs: object) -> None:
            real_mkdir(self, *args, **kwargs)  # type: ignore[arg-type]
            if TMP_MARK in self.name:
                os.kill(os.getpid(), signal.SIGTERM)
        monkeypatch.setattr(Path, "mkdir", mkdir)
        context = atomic_directory(tmp_path / "pareto")
    previous = signal.signal(signal.SIGTERM, _raise)
    try:
        with pytest.raises(_SignalledError), context as tmp:
            (tmp / "x.txt" if kind == "directory" else tmp).write_text("x", encoding="utf-8")
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert _files(tmp_path) == []


def test_signals_held_are_delivered_once_when_the_block_ends() -> None:
    """A SIGTERM sent twice inside ``signals_held`` does not reach its handler within the
    block, and the handler runs once right after it — also with another thread running,
    which the kernel may choose to take a process-wide signal (why a thread's signal mask
    cannot hold it)."""
    seen: list[int] = []
    stop = threading.Event()
    other = threading.Thread(target=stop.wait, daemon=True)
    other.start()
    previous = signal.signal(signal.SIGTERM, lambda signum, frame: seen.append(signum))
    try:
        with atomic.signals_held():
            os.kill(os.getpid(), signal.SIGTERM)
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(10_000):  # give a handler every chance to run in here
                pass
            inside = len(seen)
        after = len(seen)
    finally:
        signal.signal(signal.SIGTERM, previous)
        stop.set()
    assert (inside, after) == (0, 1)
