"""Imported once by the fork server of :mod:`chaindrive.app.worker`: every run is forked
from a process that has already imported the package and warmed its caches (the unit
registry, the catalogue, the compiled kernels), so a run starts in milliseconds.

Importing it analyses the bundled seed example once, with its full dynamic response and a
report of it — what a run of the page does.
"""

from __future__ import annotations

import tomllib

from chaindrive import examples
from chaindrive.app import runs, views

__all__ = ["warm"]


def warm() -> None:
    """Run what the page runs on the seed example once (errors are the runs' own business:
    a failed warm-up only leaves the caches cold)."""
    try:
        views.recompute(tomllib.loads(examples.text("seed_three_sprocket")))
        runs.full_analysis(examples.load("seed_three_sprocket"))
    except Exception:  # a warm-up must never stop the fork server
        return


warm()
