"""Run one command of the command line in this process, as the fuzzer does
(``chaindrive.cli.run``), with its output captured and its time bounded."""

from __future__ import annotations

import signal
from typing import Any

from tests.conftest import cli_in_process


class Overtime(BaseException):
    """A command ran past its time (a BaseException, so no ``except Exception`` of the
    package swallows it)."""


def _alarm(signum: int, frame: Any) -> None:
    raise Overtime


def run_in_time(argv: list[str], seconds: int) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of ``chaindrive <argv>`` run in this process
    (:func:`tests.conftest.cli_in_process`); :class:`Overtime` past ``seconds`` [s]."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(seconds)
    try:
        proc = cli_in_process(*argv)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    return proc.returncode, proc.stdout, proc.stderr
