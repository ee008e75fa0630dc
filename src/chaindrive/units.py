"""The one place pint is used: strings with units at the edge → SI floats inside.

Each field of a design declares the dimension it expects (e.g. ``"[length]"``); a value
without a unit, with an unknown unit or a unit of the wrong kind is refused with a
one-line :class:`~chaindrive.errors.DesignError` naming the field.
"""

from __future__ import annotations

import math
import sys
from functools import lru_cache
from typing import Any

from chaindrive.errors import DesignError

#: rad/s → rpm (revolutions per minute): ω·60/(2π); divide by it for rpm → rad/s.
RAD_S_TO_RPM = 30.0 / math.pi

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
    "area": ("[length]**2", "m**2", "180 mm^2"),
}


def _import_pint() -> Any:
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
def registry() -> Any:
    """The shared pint UnitRegistry (built lazily: importing chaindrive stays cheap)."""
    pint = _import_pint()

    try:  # pint's own cache of the parsed definitions halves the start-up time
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=":auto:")
    except OSError:  # no writable cache folder: build it from the definitions each time
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def parse_quantity(text: object, dimension: str, field: str) -> float:
    """Parse ``text`` such as ``"25.4 mm"`` as a quantity of ``dimension``; return SI float.

    Angular speed: ``rpm`` and ``rad/s`` are both 1/[time] in pint (rad is dimensionless);
    a bare ``Hz``/``1/s`` is taken as revolutions per second is NOT assumed: frequency
    units are converted as rad/s only when written with ``rad`` or ``rpm``/``revolution``.
    """
    pint = _import_pint()

    dim, si_unit, example = DIMENSIONS[dimension]
    if isinstance(text, bool) or not isinstance(text, str):
        raise DesignError(
            field, f"must be a string with a unit such as \"{example}\", got {text!r}"
        )
    ureg = registry()
    try:
        q = ureg.Quantity(text.strip())
    except pint.errors.UndefinedUnitError as exc:
        raise DesignError(field, f"unknown unit in {text!r} ({exc.unit_names!s})") from None
    except Exception:
        raise DesignError(
            field, f"cannot read {text!r} as a quantity; write it like \"{example}\""
        ) from None
    if not isinstance(q, ureg.Quantity) or (q.dimensionless and dimension != "angle"):
        raise DesignError(field, f"missing unit in {text!r}; write it like \"{example}\"")
    if dimension == "speed":
        unit_text = str(q.units)
        if "hertz" in unit_text or unit_text in {"1 / second", "1 / minute"}:
            raise DesignError(
                field,
                f"ambiguous speed unit in {text!r}; use rpm, revolution/s or rad/s (e.g. \"{example}\")",
            )
    if dim and not q.check(dim):
        raise DesignError(
            field,
            f"{text!r} is not {_article(dimension.replace('_', ' '))} (expected a unit like "
            f"\"{example}\", got {q.units:~})",
        )
    value = float(q.to(si_unit).magnitude)
    return value


def _article(noun: str) -> str:
    """``noun`` with its indefinite article ("an angle", "a length")."""
    return f"{'an' if noun[:1] in 'aeiou' else 'a'} {noun}"


def format_si(value: float, unit: str) -> str:
    """Format an SI value for a design file: the inverse of :func:`parse_quantity`."""
    return f"{value:g} {unit}"
