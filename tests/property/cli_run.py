"""Run one command of the command line in this process, as the fuzzer does
(``chaindrive.cli.run``), with its output captured and its time bounded."""

from __future__ import annotations

import contextlib
import io
import signal
from typing import Any

from chaindrive.cli import run


class Overtime(BaseException):
    """A command ran past its time (a BaseException, so no ``except Exception`` of the
    package swallows it)."""


def _alarm(signum: int, frame: Any) -> None:
    raise Overtime


def run_in_time(argv: list[str], seconds: int) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of ``chaindrive <argv>``; :class:`Overtime` past
    ``seconds`` [s]."""
    out, err = io.StringIO(), io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(seconds)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = run(argv)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    return status, out.getvalue(), err.getvalue()
