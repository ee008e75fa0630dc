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
    """A design (file, form or code) is invalid: a field has a value that is not allowed.

    Parameters
    ----------
    field : str
        The field, e.g. ``"sprockets[S1].teeth"`` (empty for a message about no one field).
    message : str
        What is wrong: the value and what is allowed.
    """

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        self.detail = message
        super().__init__(f"{field}: {message}" if field else message)

    def __reduce__(self) -> tuple[type, tuple[str, str]]:
        """Pickle by (field, message), so the error crosses to a worker process and back."""
        return type(self), (self.field, self.detail)


class CatalogError(DesignError):
    """A catalogue entry or catalogue file is missing or malformed."""


class GeometryError(DesignError):
    """The contour cannot be built: sprockets overlap, a span cuts a sprocket, no closure."""


class ConvergenceError(ChainDriveError, RuntimeError):
    """A numerical solution did not converge."""


class ChainDriveWarning(UserWarning):
    """An engineering warning carried on a result: what it is about and what to do.

    Parameters
    ----------
    code : str
        Stable identifier of the kind of warning, ``<part>.<what>``, e.g.
        ``"geometry.driver-wrap"``; tools and tests match on it, never on the wording.
    part : str
        The field or part of the design it concerns, e.g. ``"sprockets[S1]"`` or
        ``"strength"``.
    message : str
        One line for the designer, with the figures.

    The results keep them in ``warnings`` tuples; ``to_dict()`` writes them with their code,
    and ``warnings.warn(w)`` works too (it is a :class:`UserWarning`).
    """

    def __init__(self, code: str, part: str, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.part = part
        self.message = message

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple[type, tuple[str, str, str]]:
        """Pickle by (code, part, message), so results that carry warnings cross processes."""
        return type(self), (self.code, self.part, self.message)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.code!r}, {self.part!r}, {self.message!r})"

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, ChainDriveWarning)
                and (self.code, self.part, self.message) == (other.code, other.part, other.message))

    def __hash__(self) -> int:
        return hash((self.code, self.part, self.message))

    def to_dict(self) -> dict[str, str]:
        """JSON-ready dict: code, part, message."""
        return {"code": self.code, "part": self.part, "message": self.message}


def closest(name: str, choices: Iterable[str]) -> str | None:
    """The choice closest to ``name`` (case-insensitive difflib ratio ≥ 0.5).

    Parameters
    ----------
    name : str
        What the user wrote.
    choices : iterable of str
        The valid names.

    Returns
    -------
    str or None
        The closest valid name, or None when none is close.
    """
    choices = list(choices)
    lowered = {c.lower(): c for c in choices}
    match = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.5)
    return lowered[match[0]] if match else None


def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """The hint of an error message for a misspelt name.

    Parameters
    ----------
    name : str
        What the user wrote.
    choices : iterable of str
        The valid names.

    Returns
    -------
    str
        ``"; did you mean 'x'?"`` when a close choice exists (:func:`closest`), else ``""``.
    """
    best = closest(name, choices)
    return f"; did you mean '{best}'?" if best else ""
