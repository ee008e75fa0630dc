"""Errors and warnings of chaindrive.

Every error a user can cause is a :class:`ChainDriveError`; its message is one line that
names the field, the value and what is allowed (the command line prints it and exits 2).
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class ChainDriveError(Exception):
    """Base class of every error chaindrive raises for a user's input."""


class DesignError(ChainDriveError, ValueError):
    """A design (file, form or code) is invalid: a field has a value that is not allowed."""

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        super().__init__(f"{field}: {message}" if field else message)


class CatalogError(DesignError):
    """A catalogue entry or catalogue file is missing or malformed."""


class GeometryError(DesignError):
    """The contour cannot be built: sprockets overlap, a span cuts a sprocket, no closure."""


class ConvergenceError(ChainDriveError, RuntimeError):
    """A numerical solution did not converge."""


class ChainDriveWarning(UserWarning):
    """Base class of the engineering warnings chaindrive reports (also listed in results)."""


def closest(name: str, choices: Iterable[str]) -> str | None:
    """Return the choice closest to ``name`` (difflib ratio ≥ 0.5), or None."""
    choices = list(choices)
    lowered = {c.lower(): c for c in choices}
    match = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.5)
    return lowered[match[0]] if match else None


def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """``"; did you mean 'x'?"`` when a close choice exists, else ``""``."""
    best = closest(name, choices)
    return f"; did you mean '{best}'?" if best else ""
