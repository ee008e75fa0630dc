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
from typing import TYPE_CHECKING, TypeVar

from chaindrive._docstrings import shared_parameters

if TYPE_CHECKING:
    from rich.progress import Progress, ProgressColumn

T = TypeVar("T")


def progress_enabled(quiet: bool = False) -> bool:
    """Whether a bar should be drawn.

    Parameters
    ----------
    quiet : bool
        True in ``--json`` mode.

    Returns
    -------
    bool
        True when not ``quiet`` and stdout is a terminal.
    """
    return not quiet and sys.stdout.isatty()


def _no_progress(label: str | None = None) -> None:
    """What ``advance`` is when no bar is drawn."""


def _bar(count: ProgressColumn, *, remaining: bool) -> Progress:
    """The one bar of the CLI on stderr, cleared when done: description, bar, ``count``, the
    elapsed time and (``remaining``) an estimate of the time left."""
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    return Progress(TextColumn("{task.description}"), BarColumn(), count, TimeElapsedColumn(),
                    *([TimeRemainingColumn()] if remaining else []),
                    console=Console(stderr=True), transient=True)


@contextmanager
def progress_bar(description: str, total: int | None = None, *,
                 quiet: bool = False) -> Iterator[Callable[[str | None], None]]:
    """A context giving ``advance(label=None)``, which moves the bar one step (and shows
    ``label``). A no-op when :func:`progress_enabled` is False. The bar is drawn on stderr
    and removed when done, so stdout stays clean.

    Parameters
    ----------
    description : str
        What runs.
    total : int | None
        Steps in all (None: unknown).
    quiet : bool
        True in ``--json`` mode (no bar).

    Yields
    ------
    callable
        ``advance(label=None)``.
    """
    if not progress_enabled(quiet):
        yield _no_progress
        return
    from rich.progress import TextColumn

    # the estimate of what is left only where the steps are counted
    with _bar(TextColumn("{task.fields[step]}"), remaining=bool(total)) as bar:
        task = bar.add_task(description, total=total, step="")

        def advance(label: str | None = None) -> None:
            bar.update(task, advance=1, step=label or "")

        yield advance


@shared_parameters
@contextmanager
def step_progress(description: str, *, quiet: bool = False
                  ) -> Iterator[Callable[[int, int], None]]:
    """A context giving ``update(done, total)`` for a computation that counts its own steps
    (a start-up: its time steps): a bar with the elapsed time and an estimate of what is
    left; same rules as :func:`progress_bar`.

    %(params_progress)s

    Yields
    ------
    callable
        ``update(done, total)``.
    """
    if not progress_enabled(quiet):
        yield _no_steps
        return
    from rich.progress import TextColumn

    with _bar(TextColumn("{task.percentage:>3.0f} %"), remaining=True) as bar:
        task = bar.add_task(description, total=None)

        def update(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total)

        yield update


def _no_steps(done: int, total: int) -> None:
    """What ``update`` is when no bar is drawn."""


def track(items: Iterable[T], description: str, total: int | None = None, *,
          quiet: bool = False) -> Iterator[T]:
    """Iterate over ``items`` with a progress bar (see :func:`progress_bar`).

    Parameters
    ----------
    items : iterable
        What to iterate over.
    description : str
        What runs.
    total : int | None
        Steps in all (None: ``len(items)`` when it has one).
    quiet : bool
        True in ``--json`` mode (no bar).

    Yields
    ------
    object
        Each item.
    """
    if total is None and hasattr(items, "__len__"):
        total = len(items)  # type: ignore[arg-type]
    with progress_bar(description, total, quiet=quiet) as advance:
        for item in items:
            yield item
            advance(None)


@shared_parameters
@contextmanager
def spinner(description: str, *, quiet: bool = False) -> Iterator[None]:
    """An indeterminate indicator (a spinner with the elapsed time) for one long call, such
    as an analysis with the start-up transient; same rules as :func:`progress_bar`.

    %(params_progress)s

    Yields
    ------
    None
    """
    if not progress_enabled(quiet):
        yield
        return
    from rich.console import Console

    with Console(stderr=True).status(description):
        yield
