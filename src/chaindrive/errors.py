"""Errors and warnings of chaindrive.

Every error a user can cause is a :class:`ChainDriveError`; its message is one line that
names the field, the value and what is allowed (the command line prints it and exits 2).
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters


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


#: Kind of quantity → (the unit a message writes it in, factor from SI to that unit): the SI
#: units of :data:`chaindrive.display.QUANTITIES`, whose kinds a presenter converts to
#: another unit system.
MESSAGE_UNITS: dict[str, tuple[str, float]] = {
    "length": ("mm", 1e3), "force": ("N", 1.0), "force_k": ("kN", 1e-3), "power": ("kW", 1e-3),
    "pressure": ("MPa", 1e-6), "velocity": ("m/s", 1.0), "stiffness": ("N/m", 1.0),
    "mass": ("kg", 1.0), "torque": ("N·m", 1.0), "inertia": ("kg·m²", 1.0),
    "area": ("mm²", 1e6), "linear_density": ("kg/m", 1.0),
}
#: The unit a message writes → its kind of quantity (the inverse of :data:`MESSAGE_UNITS`).
UNIT_KINDS: dict[str, str] = {unit: kind for kind, (unit, _) in MESSAGE_UNITS.items()}


class Quantity(NamedTuple):
    """A number with a unit in the text of a warning or a note, as the text writes it.

    Parameters
    ----------
    text : str
        The number and its unit exactly as the (SI) text writes them, e.g. ``"12.1 mm"``.
    value : float
        The value in SI [the SI unit of ``kind``: m, N, W, Pa, m/s, N/m, kg …].
    kind : str
        Its kind of quantity, a key of :data:`MESSAGE_UNITS` and of
        :data:`chaindrive.display.QUANTITIES` (``"length"``, ``"force"`` …).
    """

    text: str
    value: float
    kind: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: text (SI, as in the message), value_si, kind."""
        return {"text": self.text, "value_si": self.value, "kind": self.kind}


class Quantities:
    """The numbers with units written into one text, recorded as the text is written, so
    that the text and its :class:`Quantity` cannot differ.

    Calling it writes a value in its SI message unit and records it::

        q = Quantities()
        message = f"chain slack {q(slack, 'length', '.1f')} is not taken up"
        ChainDriveWarning("geometry.slack", "chain", message, q.items)
    """

    def __init__(self) -> None:
        self._items: list[Quantity] = []

    def __call__(self, value: float, kind: str, spec: str = ".4g") -> str:
        """The value as the text writes it, ``"12.1 mm"`` (recorded).

        Parameters
        ----------
        value : float
            The value in SI [the SI unit of ``kind``].
        kind : str
            Its kind of quantity (a key of :data:`MESSAGE_UNITS`).
        spec : str
            The format of the number in the message's unit (``".1f"``, ``".3g"`` …).

        Returns
        -------
        str
            The number in the unit of :data:`MESSAGE_UNITS` and that unit.
        """
        unit, factor = MESSAGE_UNITS[kind]
        text = f"{value * factor:{spec}} {unit}"
        self._items.append(Quantity(text, float(value), kind))
        return text

    @property
    def items(self) -> tuple[Quantity, ...]:
        """The quantities written so far, in the order written."""
        return tuple(self._items)


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
        One line for the designer, with the figures (in SI).
    quantities : tuple of Quantity
        The numbers with units that ``message`` writes (:class:`Quantities`), so that a
        presenter can write them in another unit system
        (:func:`chaindrive.display.warning_text`); empty when it writes none.

    The results keep them in ``warnings`` tuples; ``to_dict()`` writes them with their code,
    and ``warnings.warn(w)`` works too (it is a :class:`UserWarning`). Two warnings are equal
    when code, part and message are (the quantities restate the message's numbers).
    """

    def __init__(self, code: str, part: str, message: str,
                 quantities: Iterable[Quantity] = ()) -> None:
        super().__init__(message)
        self.code = code
        self.part = part
        self.message = message
        self.quantities: tuple[Quantity, ...] = tuple(Quantity(*q) for q in quantities)

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple[type, tuple[str, str, str, tuple[Quantity, ...]]]:
        """Pickle by (code, part, message, quantities), so results that carry warnings
        cross processes."""
        return type(self), (self.code, self.part, self.message, self.quantities)

    def __repr__(self) -> str:
        more = f", {self.quantities!r}" if self.quantities else ""
        return f"{type(self).__name__}({self.code!r}, {self.part!r}, {self.message!r}{more})"

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, ChainDriveWarning)
                and (self.code, self.part, self.message) == (other.code, other.part, other.message))

    def __hash__(self) -> int:
        return hash((self.code, self.part, self.message))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: code, part, message (SI) and the quantities it writes (each its
        text, SI value and kind: :meth:`Quantity.to_dict`)."""
        return {"code": self.code, "part": self.part, "message": self.message,
                "quantities": [q.to_dict() for q in self.quantities]}


@shared_parameters
def closest(name: str, choices: Iterable[str]) -> str | None:
    """The choice closest to ``name`` (case-insensitive difflib ratio ≥ 0.5).

    %(params_name_choices)s

    Returns
    -------
    str or None
        The closest valid name, or None when none is close.
    """
    choices = list(choices)
    lowered = {c.lower(): c for c in choices}
    match = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.5)
    return lowered[match[0]] if match else None


@shared_parameters
def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """The hint of an error message for a misspelt name.

    %(params_name_choices)s

    Returns
    -------
    str
        ``"; did you mean 'x'?"`` when a close choice exists (:func:`closest`), else ``""``.
    """
    best = closest(name, choices)
    return f"; did you mean '{best}'?" if best else ""


def positive(name: str, value: ArrayLike, kind: str = "") -> NDArray[np.float64]:
    """Values as float64, refusing any that is not finite or not above zero.

    Parameters
    ----------
    name : str
        The field an error names.
    value : float or array_like
        The values [SI unit of the field].
    kind : str, optional
        What the values are ("length"), for the message; empty: "must be positive".

    Returns
    -------
    numpy.ndarray
        The values as float64.

    Raises
    ------
    DesignError
        On ``name`` when a value is not finite or ≤ 0.
    """
    arr = np.asarray(value, dtype=float)
    if np.any(~np.isfinite(arr)) or np.any(arr <= 0):
        what = f"a positive {kind}" if kind else "positive"
        raise DesignError(name, f"must be {what}, got {value!r}")
    return arr
