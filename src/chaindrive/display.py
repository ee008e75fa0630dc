"""How numbers and units are shown to people: the one formatting rule of every presenter
(command line, report, web page), and the display units.

Presenters format here and nowhere else; the computing modules never format.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from chaindrive.units import RAD_S_TO_RPM

if TYPE_CHECKING:
    from chaindrive.checks import Check

__all__ = ["RAD_S_TO_RPM", "check_row", "fmt", "shown_value"]

#: SI unit → (factor, unit it is read in) for values shown to people.
_READ_IN = {"Pa": (1e-6, "MPa"), "rad": (180.0 / math.pi, "°"), "rad/s": (RAD_S_TO_RPM, "rpm")}


def fmt(value: Any, digits: int = 4) -> str:
    """A table cell as text: None → "—", floats with ``digits`` significant digits (large
    values without exponent), bools yes/no."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        if math.isnan(value):
            return "—"
        if value != 0 and (abs(value) >= 10**digits or abs(value) < 1e-3):
            return f"{value:.{digits}g}" if abs(value) < 1e-3 else f"{value:,.0f}"
        return f"{value:.{digits}g}"
    return str(value)


def shown_value(value: float | None, unit: str) -> tuple[float | None, str]:
    """A value in the unit it is read in (Pa → MPa, rad → °, rad/s → rpm; others as given)."""
    if value is None or unit not in _READ_IN:
        return value, unit
    factor, shown = _READ_IN[unit]
    return value * factor, shown


def check_row(check: Check) -> tuple[str, float | None, str, str, str]:
    """A check as shown: (what, value, required, result, source), value and limit in the
    unit the check is read in, and the result ``pass``, ``FAIL`` or ``CANNOT BE VERIFIED``."""
    sym = "≤" if check.kind == "max" else "≥"
    unit = f" {check.unit}" if check.unit else ""
    limit = check.shown(check.limit)
    required = "—" if limit is None else f"{sym} {fmt(limit)}{unit}"
    label = f"{check.name}: {check.subject}" + (f" ({check.note})" if check.note else "")
    result = "pass" if check.passed else "FAIL" if check.status == "fail" else "CANNOT BE VERIFIED"
    return label, check.shown(check.value), required, result, check.source
