"""Run the command line with a signal sent to itself at a chosen point of writing an output
(for tests/cli/test_atomic_outputs.py)::

    python -m tests.cli.signal_inject <point> <SIGINT|SIGTERM> <chaindrive arguments…>

point ``midwrite``: the signal arrives while the temporary file is being written (after part
of the text or bytes, after the first page of a PDF drawn by matplotlib, after the DXF is
written but before its file is closed); ``written``: after the temporary file is complete,
just before it is renamed. The process's own signal handling (the safety net) does the rest,
as with a signal from outside.
"""

from __future__ import annotations

import os
import pathlib
import signal
import sys
from typing import Any


def _kill(signum: int) -> None:
    os.kill(os.getpid(), signum)


def _midwrite(signum: int) -> None:
    real_write_text = pathlib.Path.write_text

    def write_text(self: pathlib.Path, data: str, *args: Any, **kwargs: Any) -> int:
        if ".tmp" not in str(self):
            return real_write_text(self, data, *args, **kwargs)
        real_write_text(self, data[: len(data) // 2], *args, **kwargs)
        _kill(signum)
        return real_write_text(self, data, *args, **kwargs)  # not reached: the signal raises

    pathlib.Path.write_text = write_text  # type: ignore[method-assign]
    real_write_bytes = pathlib.Path.write_bytes

    def write_bytes(self: pathlib.Path, data: bytes) -> int:
        if ".tmp" not in str(self):
            return real_write_bytes(self, data)
        real_write_bytes(self, data[: len(data) // 2])
        _kill(signum)
        return real_write_bytes(self, data)  # not reached: the signal raises

    pathlib.Path.write_bytes = write_bytes  # type: ignore[method-assign]

    from ezdxf.document import Drawing
    from matplotlib.backends.backend_pdf import PdfPages

    real_savefig = PdfPages.savefig
    pages = {"n": 0}

    def savefig(self: Any, *args: Any, **kwargs: Any) -> None:
        real_savefig(self, *args, **kwargs)
        pages["n"] += 1
        if pages["n"] == 1:
            _kill(signum)

    PdfPages.savefig = savefig  # type: ignore[method-assign]
    real_write = Drawing.write

    def write(self: Any, stream: Any, *args: Any, **kwargs: Any) -> None:
        real_write(self, stream, *args, **kwargs)
        _kill(signum)

    Drawing.write = write  # type: ignore[method-assign]


def _written(signum: int) -> None:
    from chaindrive.io import atomic

    real_sync = atomic._sync

    def sync(path: pathlib.Path) -> None:
        real_sync(path)
        _kill(signum)

    atomic._sync = sync


def main(argv: list[str]) -> None:
    point, name, *args = argv
    signum = int(getattr(signal, name))
    {"midwrite": _midwrite, "written": _written}[point](signum)
    from chaindrive.cli import main as cli_main

    cli_main(args)


if __name__ == "__main__":
    main(sys.argv[1:])
