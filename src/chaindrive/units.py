"""The one place pint is used: strings with units at the edge → SI floats inside.

Each field of a design declares the dimension it expects (e.g. ``"[length]"``); a value
without a unit, with an unknown unit or a unit of the wrong kind is refused with a
one-line :class:`~chaindrive.errors.DesignError` naming the field.

What is read
------------
A quantity is a decimal number followed by a unit expression: ``"25.4 mm"``,
``"0.06 kg*m^2"``, ``"300 min⁻¹"``. The number is read by Python (``float``), never by
pint's expression evaluator, and the unit expression is limited to unit names, ``* / ^ **
· ( )``, the superscripts and exponents of at most two digits: a design file cannot make
the parser compute (``"9**9**9 mm"`` is refused, not evaluated). A text is at most
:data:`MAX_TEXT` characters.

Spellings: pint's names and symbols as written (``MPa`` and ``mPa`` differ), and, where a
name is not defined as written, the case-insensitive common spellings of
:data:`ALIASES` that have one reading only (``kw``, ``KW`` → kW; ``RPM`` → rpm; ``r/min``,
``rev/min`` → rpm; ``in`` → inch; ``Nm`` → N·m).

Rotational speed: ``rpm``, ``rad/s``, ``revolution/s`` and — the rotational frequency of
[ISO80000-3] — ``1/min``, ``min⁻¹``, ``min^-1``, ``1/s`` (revolutions per unit time). A
bare ``Hz`` is refused as ambiguous (it is read as a tooth or a natural frequency too).

References
----------
[ISO80000-3]
"""

from __future__ import annotations

import math
import re
import sys
from functools import lru_cache
from types import ModuleType
from typing import TYPE_CHECKING, Any

from chaindrive.errors import DesignError

if TYPE_CHECKING:  # pint is imported on first use (see _import_pint)
    from pint import UnitRegistry

#: 2π: radians per revolution (ω = 2π f). The one definition in the package
#: (tests/unit/test_constants.py refuses another).
TWO_PI = 2.0 * math.pi
#: rad/s → rpm (revolutions per minute): n = ω·60/(2π) = ω · RPM_PER_RAD_S.
RPM_PER_RAD_S = 30.0 / math.pi
#: rpm → rad/s: ω = 2π n/60 = n · RAD_S_PER_RPM.
RAD_S_PER_RPM = math.pi / 30.0
#: rad → degree: 180/π.
DEG_PER_RAD = 180.0 / math.pi
#: degree → rad: π/180.
RAD_PER_DEG = math.pi / 180.0

#: Dimension name → (pint dimensionality string, SI unit it is converted to, example).
DIMENSIONS: dict[str, tuple[str, str, str]] = {
    "length": ("[length]", "m", "25.4 mm"),
    "angle": ("", "rad", "30 deg"),
    "speed": ("1/[time]", "rad/s", "300 rpm"),
    "velocity": ("[length]/[time]", "m/s", "2 m/s"),
    "power": ("[mass]*[length]**2/[time]**3", "W", "0.5 kW"),
    "torque": ("[mass]*[length]**2/[time]**2", "N*m", "20 N*m"),
    "force": ("[mass]*[length]/[time]**2", "N", "5 kN"),
    "mass": ("[mass]", "kg", "17.26 kg"),
    "inertia": ("[mass]*[length]**2", "kg*m**2", "0.06 kg*m^2"),
    "time": ("[time]", "s", "2400 h"),
    "stiffness": ("[mass]/[time]**2", "N/m", "2e6 N/m"),
    "pressure": ("[mass]/[length]/[time]**2", "Pa", "30 MPa"),
    "density": ("[mass]/[length]**3", "kg/m**3", "7850 kg/m^3"),
    "linear_density": ("[mass]/[length]", "kg/m", "2.6 kg/m"),
    "torsional_stiffness": ("[mass]*[length]**2/[time]**2", "N*m/rad", "1.9e5 N*m/rad"),
    "torsional_damping": ("[mass]*[length]**2/[time]", "N*m*s/rad", "20 N*m*s/rad"),
    "area": ("[length]**2", "m**2", "180 mm^2"),
    "frequency": ("1/[time]", "Hz", "23.4 Hz"),
}

#: Longest text read as a quantity [characters].
MAX_TEXT = 80

#: Common spellings that pint does not define as written, by their lower-case form → the
#: unit they mean. Only spellings with one reading are listed (``mw`` could be mW or MW and
#: is not; ``nm`` is the nanometre and is left to pint).
ALIASES: dict[str, str] = {
    "kw": "kW", "hp": "hp", "rpm": "rpm", "r": "revolution", "rev": "revolution",
    "revs": "revolution", "in": "inch", "inch": "inch", "inches": "inch", "lbf": "lbf",
    "kn": "kN", "nm": "N*m", "knm": "kN*m",
}

#: (dimension, unit as written) → the factor to the SI unit of :data:`DIMENSIONS`, for the
#: units of the shipped designs and their common neighbours: read without pint (importing
#: pint and building its registry is about an eighth of a command-line run). Each factor is
#: the one pint computes, and pint converts by that one multiplication, so the value is
#: pint's to the last bit (tests/unit/test_units_exact.py checks every entry against pint).
EXACT_UNITS: dict[tuple[str, str], float] = {
    ("length", "m"): 1.0, ("length", "mm"): 0.001, ("length", "cm"): 0.01,
    ("angle", "rad"): 1.0, ("angle", "deg"): 0.017453292519943295,
    ("speed", "rpm"): 0.10471975511965977, ("speed", "rad/s"): 1.0,
    ("velocity", "m/s"): 1.0,
    ("power", "W"): 1.0, ("power", "kW"): 1000.0,
    ("torque", "N*m"): 1.0, ("torque", "kN*m"): 1000.0,
    ("force", "N"): 1.0, ("force", "kN"): 1000.0,
    ("mass", "kg"): 1.0, ("mass", "g"): 0.001,
    ("inertia", "kg*m^2"): 1.0, ("inertia", "kg*m**2"): 1.0,
    ("time", "s"): 1.0, ("time", "min"): 60.0, ("time", "h"): 3600.0,
    ("stiffness", "N/m"): 1.0, ("stiffness", "N/mm"): 1000.0, ("stiffness", "kN/mm"): 1e6,
    ("pressure", "Pa"): 1.0, ("pressure", "MPa"): 1e6, ("pressure", "N/mm^2"): 1e6,
    ("density", "kg/m^3"): 1.0, ("linear_density", "kg/m"): 1.0,
    ("torsional_stiffness", "N*m/rad"): 1.0, ("torsional_stiffness", "kN*m/rad"): 1000.0,
    ("torsional_damping", "N*m*s/rad"): 1.0,
    ("area", "m^2"): 1.0, ("area", "mm^2"): 1e-06,
    ("frequency", "Hz"): 1.0,
}

_NUMBER = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*", re.DOTALL)
_UNIT_CHARS = re.compile(r"[^\W_]|[\s*/^·⋅().\-°'\"⁻⁰¹²³⁴⁵⁶⁷⁸⁹µμΩ_]")
_WORD = re.compile(r"[^\W\d_]+")
_LONG_DIGITS = re.compile(r"\d{3,}")


def _import_pint() -> ModuleType:
    """``import pint`` without its optional dask support.

    pint imports dask, when installed, to wrap dask arrays (``pint.compat``); dask is
    installed here for the optimiser's parallel studies, and that import costs about
    0.15 s (``python -X importtime``) of a command-line run that never puts a unit on a
    dask array. A ``None`` in ``sys.modules`` makes that one import fail as if dask were
    absent (the documented meaning of ``None`` there); it is removed at once, so a later
    ``import dask`` works as usual.
    """
    if "pint" in sys.modules or "dask" in sys.modules:
        import pint

        return pint
    sys.modules["dask"] = None  # type: ignore[assignment]
    try:
        import pint
    finally:
        if sys.modules.get("dask", 0) is None:
            del sys.modules["dask"]
    return pint


@lru_cache(maxsize=1)
def registry() -> UnitRegistry:
    """The shared pint UnitRegistry (built lazily: importing chaindrive stays cheap)."""
    pint = _import_pint()

    units: UnitRegistry
    try:  # pint's own cache of the parsed definitions halves the start-up time
        units = pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=":auto:")
    except OSError:  # no writable cache folder: build it from the definitions each time
        units = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    return units


def shown(text: str) -> str:
    """``text`` as an error message quotes it.

    Parameters
    ----------
    text : str
        A value of a design file.

    Returns
    -------
    str
        Its ``repr`` (control characters such as a newline escaped, so the message stays one
        line), cut to :data:`MAX_TEXT` characters.
    """
    r = repr(text)
    return r if len(r) <= MAX_TEXT + 2 else r[:MAX_TEXT] + "…'"


@lru_cache(maxsize=512)
def _defined(word: str) -> bool:
    """True when pint reads ``word`` as a unit (with its prefixes and plurals)."""
    pint = _import_pint()
    try:
        registry().parse_units(word)
    except (pint.errors.UndefinedUnitError, AttributeError, ValueError, TypeError):
        return False
    return True


def _spelled(unit: str) -> str:
    """The unit expression with the common spellings of :data:`ALIASES` replaced where pint
    does not define the word as written."""
    def one(m: re.Match[str]) -> str:
        word = m.group(0)
        if word == "Nm" or not _defined(word):
            return ALIASES.get(word.lower(), word)
        return word

    return _WORD.sub(one, unit)


def _split(text: str, field: str, example: str) -> tuple[float, str]:
    """(number, unit expression) of a quantity text; :class:`DesignError` when it is not one."""
    if len(text) > MAX_TEXT:
        raise DesignError(field, f"{shown(text)} is too long for a quantity (at most "
                          f"{MAX_TEXT} characters); write it like \"{example}\"")
    m = _NUMBER.fullmatch(text)
    if m is None:
        raise DesignError(field, f"cannot read {shown(text)} as a quantity; write it like "
                          f"\"{example}\"")
    number, unit = m.group(1), m.group(2)
    value = float(number)
    if not math.isfinite(value):
        raise DesignError(field, f"{shown(text)} is out of range; write it like \"{example}\"")
    if not unit:
        raise DesignError(field, f"missing unit in {shown(text)}; write it like \"{example}\"")
    if not all(_UNIT_CHARS.fullmatch(c) for c in unit) or _LONG_DIGITS.search(unit):
        raise DesignError(field, f"cannot read the unit of {shown(text)}; write it like "
                          f"\"{example}\"")
    return value, _spelled(unit)


def _units(unit: str, text: str, field: str, example: str) -> Any:
    """The pint unit of a unit expression (no scaling factor, nothing evaluated)."""
    pint = _import_pint()
    try:
        units = registry().parse_units(unit)
    except pint.errors.UndefinedUnitError as exc:
        names = exc.unit_names if isinstance(exc.unit_names, list | tuple) else [exc.unit_names]
        raise DesignError(field, f"unknown unit in {shown(text)} "
                          f"({', '.join(repr(str(n)) for n in names)})") from None
    except Exception:  # pint raises several types for a malformed expression
        raise DesignError(field, f"cannot read the unit of {shown(text)}; write it like "
                          f"\"{example}\"") from None
    return units


def _is_angle(q: Any) -> bool:
    """True for a quantity in an angle unit (radian, degree, revolution …)."""
    return bool(q.dimensionless) and not q.unitless and str(q.to_root_units().units) == "radian"


def parse_quantity(text: object, dimension: str, field: str) -> float:
    """Parse ``text`` such as ``"25.4 mm"`` as a quantity of ``dimension``; return SI float.

    Parameters
    ----------
    text : object
        The value of the field (a string with a unit; anything else is refused).
    dimension : str
        A key of :data:`DIMENSIONS`.
    field : str
        The field's path in the design file, for the message.

    Returns
    -------
    float
        The value in the SI unit of the dimension (rad/s for a speed, rad for an angle).

    Raises
    ------
    DesignError
        One line naming the field, the text and what is expected.

    Notes
    -----
    A speed in reciprocal time without an angle unit (``1/min``, ``min⁻¹``, ``1/s``) is a
    rotational frequency n, revolutions per unit time [ISO80000-3]: ω = 2π·n. ``Hz`` is
    refused as ambiguous. An angle needs an angle unit (``deg``, ``rad``, ``revolution``).
    """
    example = DIMENSIONS[dimension][2]
    if isinstance(text, bool) or not isinstance(text, str):
        shown_value = shown(text) if isinstance(text, str) else repr(text)[:MAX_TEXT]
        raise DesignError(
            field, f"must be a string with a unit such as \"{example}\", got {shown_value}"
        )
    exact = _exact(text, dimension)
    if exact is not None:
        return _finite(exact, text, field, example)
    return _with_pint(text, dimension, field)


def _exact(text: str, dimension: str) -> float | None:
    """The SI value of a quantity written in a unit of :data:`EXACT_UNITS` (pint's value,
    without pint); None for any other text (pint reads it, or refuses it)."""
    if len(text) > MAX_TEXT:
        return None
    m = _NUMBER.fullmatch(text)
    if m is None:
        return None
    factor = EXACT_UNITS.get((dimension, m.group(2)))
    if factor is None:
        return None
    value = float(m.group(1))
    return value * factor if math.isfinite(value) else None


def _with_pint(text: str, dimension: str, field: str) -> float:
    """:func:`parse_quantity` of a string by pint (every unit and every refusal)."""
    _dim, si_unit, example = DIMENSIONS[dimension]
    value, unit = _split(text, field, example)
    units = _units(unit, text, field, example)
    q = registry().Quantity(value, units)
    if dimension == "angle":
        if not _is_angle(q):
            raise DesignError(field, f"{shown(text)} is not an angle (expected a unit like "
                              f"\"{example}\", got {q.units:~})")
        return _finite(float(q.to("radian").magnitude), text, field, example)
    if q.dimensionless:
        raise DesignError(field, f"missing unit in {shown(text)}; write it like \"{example}\"")
    if dimension == "speed":
        return _speed(q, text, field, example)
    if not q.check(_dim):
        raise DesignError(
            field,
            f"{shown(text)} is not {_article(dimension.replace('_', ' '))} (expected a unit like "
            f"\"{example}\", got {q.units:~})",
        )
    return _finite(float(q.to(si_unit).magnitude), text, field, example)


def _speed(q: Any, text: str, field: str, example: str) -> float:
    """A rotational speed [rad/s]: angle per time, or revolutions per time (see
    :func:`parse_quantity`)."""
    if "hertz" in str(q.units):
        raise DesignError(field, f"ambiguous speed unit in {shown(text)}; use rpm, min⁻¹, "
                          f"revolution/s or rad/s (e.g. \"{example}\")")
    if not q.check("1/[time]"):
        raise DesignError(field, f"{shown(text)} is not a speed (expected a unit like "
                          f"\"{example}\", got {q.units:~})")
    root = q.to_root_units()
    if "radian" in str(root.units):
        return _finite(float(q.to("rad/s").magnitude), text, field, example)
    return _finite(2.0 * math.pi * float(q.to("1/s").magnitude), text, field, example)


def _finite(value: float, text: str, field: str, example: str) -> float:
    if not math.isfinite(value):
        raise DesignError(field, f"{shown(text)} is out of range; write it like \"{example}\"")
    return value


def _article(noun: str) -> str:
    """``noun`` with its indefinite article ("an angle", "a length")."""
    return f"{'an' if noun[:1] in 'aeiou' else 'a'} {noun}"


def format_si(value: float, unit: str) -> str:
    """Format an SI value for a design file: the inverse of :func:`parse_quantity`.

    Parameters
    ----------
    value : float
        The value [SI unit of ``unit``].
    unit : str
        The SI unit written after it (``"m"``, ``"rad/s"`` …).

    Returns
    -------
    str
        ``"<value> <unit>"``.
    """
    return f"{value:g} {unit}"
