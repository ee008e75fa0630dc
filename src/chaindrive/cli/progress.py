"""A progress bar for long runs (sweeps, Monte-Carlo, reports with dynamics): shown on a
terminal, silent when stdout is not a terminal or in ``--json`` mode.

::

    with progress_bar("report", total=8, quiet=as_json) as advance:
        for part in parts:
            ...
            advance(part.title)
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import TypeVar

T = TypeVar("T")


def progress_enabled(quiet: bool = False) -> bool:
    """True when a bar should be drawn: not ``quiet`` (``--json``) and stdout is a terminal."""
    return not quiet and sys.stdout.isatty()


@contextmanager
def progress_bar(description: str, total: int | None = None, *,
                 quiet: bool = False) -> Iterator[Callable[[str | None], None]]:
    """A context giving ``advance(label=None)``, which moves the bar one step (and shows
    ``label``). A no-op when :func:`progress_enabled` is False. The bar is drawn on stderr
    and removed when done, so stdout stays clean."""
    if not progress_enabled(quiet):
        yield lambda label=None: None
        return
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.fields[step]}"),
                  TimeElapsedColumn(), console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task(description, total=total, step="")

        def advance(label: str | None = None) -> None:
            bar.update(task, advance=1, step=label or "")

        yield advance


def track(items: Iterable[T], description: str, total: int | None = None, *,
          quiet: bool = False) -> Iterator[T]:
    """Iterate over ``items`` with a progress bar (see :func:`progress_bar`)."""
    if total is None and hasattr(items, "__len__"):
        total = len(items)  # type: ignore[arg-type]
    with progress_bar(description, total, quiet=quiet) as advance:
        for item in items:
            yield item
            advance(None)


@contextmanager
def spinner(description: str, *, quiet: bool = False) -> Iterator[None]:
    """An indeterminate indicator (a spinner with the elapsed time) for one long call, such
    as an analysis with the start-up transient; same rules as :func:`progress_bar`."""
    if not progress_enabled(quiet):
        yield
        return
    from rich.console import Console

    with Console(stderr=True).status(description):
        yield
