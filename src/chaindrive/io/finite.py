"""The one gate every result passes on its way out: no NaN or infinity is ever printed,
written or reported.

A non-finite number in a result means the computation failed (an input within its allowed
range that a model could not handle): it is never a user's mistake, whose values the ranges
of :mod:`chaindrive.io.design` refuse before any computation. The presenters call
:func:`check_document` on the document they print or write (JSON, the command line's
tables, the report) and :func:`check_rows` on a table they write (CSV); the safety net
(:mod:`chaindrive.cli.safety`) turns :class:`NonFiniteError` into one line, ``error: the
computation did not converge: …``, exit status 1, with the traceback in its log.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["NonFiniteError", "check_document", "check_rows"]


class NonFiniteError(ArithmeticError):
    """A result holds a NaN or an infinity: the computation did not converge.

    Parameters
    ----------
    where : str
        The path of the number (``"startup.span_forces_n[3]"``, ``"out.csv, row 120, column
        'span_S1-S2_n'"``).
    value : float
        The number, NaN, +inf or -inf [the unit of its place].
    """

    def __init__(self, where: str, value: float) -> None:
        self.where = where
        self.value = value
        super().__init__(f"{value} at {where}")


def _first_non_finite(value: Any, path: str) -> tuple[str, float] | None:
    """(path, number) of the first non-finite number in ``value``, or None."""
    if isinstance(value, float | np.floating):
        return None if math.isfinite(value) else (path or "the top", float(value))
    if isinstance(value, dict):
        for k, v in value.items():
            found = _first_non_finite(v, f"{path}.{k}" if path else str(k))
            if found:
                return found
    elif isinstance(value, list | tuple):
        for i, v in enumerate(value):
            found = _first_non_finite(v, f"{path}[{i}]")
            if found:
                return found
    elif isinstance(value, np.ndarray) and value.dtype.kind in "fc":
        bad = np.flatnonzero(~np.isfinite(value))
        if bad.size:
            return f"{path}[{int(bad[0])}]", float(value.ravel()[bad[0]].real)
    return None


def check_document(document: Any, prefix: str = "") -> None:
    """Raise :class:`NonFiniteError` naming the first NaN or infinity in ``document``.

    Parameters
    ----------
    document : object
        A JSON-ready document (dicts, lists, tuples, numbers, text; NumPy arrays too).
    prefix : str
        The path of ``document`` itself, for the message.

    Raises
    ------
    NonFiniteError
        When a number in it is not finite.
    """
    found = _first_non_finite(document, prefix)
    if found:
        raise NonFiniteError(*found)


def check_rows(name: str, header: Sequence[str], rows: NDArray[np.float64]) -> None:
    """Raise :class:`NonFiniteError` naming the row and column of the first NaN or infinity
    of a table about to be written.

    Parameters
    ----------
    name : str
        The file, for the message.
    header : sequence of str
        The column names.
    rows : ndarray, shape (n, len(header))
        The table [the units its header names].

    Raises
    ------
    NonFiniteError
        When a cell is not finite.
    """
    table = np.asarray(rows, dtype=float)
    bad = np.argwhere(~np.isfinite(table))
    if bad.size:
        row, col = (int(i) for i in bad[0]) if table.ndim == 2 else (int(bad[0][0]), 0)
        column = header[col] if col < len(header) else str(col)
        value = float(table[row, col] if table.ndim == 2 else table[row])
        raise NonFiniteError(f"{name}, row {row + 1}, column {column!r}", value)
