"""How numbers and units are shown to people: the one formatting rule of every presenter
(command line, report, web page, drawings) and the output unit systems.

Presenters format here and nowhere else; the computing modules never format. Inside, every
value is SI; the JSON document stays SI with the unit in the key (``x_mm``,
``tension_n``). What a person reads is converted here to an output unit system:

* ``"SI"`` — mm, N, kW, MPa, m/s, kg/m, kg·m² (engineering multiples of SI);
* ``"US"`` — US customary: in, lbf, hp, psi, ft/min, lb/ft, lb·ft².

Speeds of rotation stay in rpm, frequencies in Hz and angles in degrees in both systems.
The conversion factors are the exact definitions of the international yard and pound
(1 in = 25.4 mm, 1 lb = 0.45359237 kg) and the standard acceleration of gravity
(1 lbf = 0.45359237 kg × 9.80665 m/s²), 1 hp = 550 ft·lbf/s [NIST-SP811, App. B].

References
----------
[NIST-SP811] in docs/references.md.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveWarning, DesignError, Quantity
from chaindrive.units import DEG_PER_RAD, RAD_PER_DEG, RPM_PER_RAD_S

if TYPE_CHECKING:
    from chaindrive.checks import Check
    from chaindrive.synthesis.solve import ConstraintReport

__all__ = [
    "QUANTITIES",
    "RPM_PER_RAD_S",
    "UNIT_SYSTEMS",
    "UnitSystem",
    "candidate_verdict",
    "check_line",
    "check_row",
    "check_unit",
    "check_value",
    "check_value_text",
    "clean",
    "constraint_row",
    "convert",
    "dimension",
    "doc_quantity",
    "doc_value",
    "finding_lines",
    "fmt",
    "header",
    "margin_percent",
    "quantity_text",
    "result_word",
    "show",
    "shown_value",
    "static_state_note",
    "unit_header",
    "unit_of",
    "unit_system",
    "warning_text",
]

UnitSystem = Literal["SI", "US"]
#: The output unit systems a presenter can be asked for.
UNIT_SYSTEMS: tuple[str, ...] = ("SI", "US")

_IN = 0.0254  # m, exact
_FT = 0.3048  # m, exact
_LB = 0.45359237  # kg, exact
_LBF = _LB * 9.80665  # N, exact
_HP = 550 * _FT * _LBF  # W (mechanical horsepower)
_PSI = _LBF / _IN**2  # Pa


@dataclass(frozen=True, slots=True)
class Shown:
    """A unit a quantity is read in: its symbol and the factor from SI to it."""

    unit: str
    factor: float


#: Kind of quantity → {unit system: (unit, factor from SI)}.
QUANTITIES: dict[str, dict[str, Shown]] = {
    "length": {"SI": Shown("mm", 1e3), "US": Shown("in", 1 / _IN)},
    "distance": {"SI": Shown("m", 1.0), "US": Shown("ft", 1 / _FT)},
    "force": {"SI": Shown("N", 1.0), "US": Shown("lbf", 1 / _LBF)},
    "force_k": {"SI": Shown("kN", 1e-3), "US": Shown("lbf", 1 / _LBF)},
    "power": {"SI": Shown("kW", 1e-3), "US": Shown("hp", 1 / _HP)},
    "pressure": {"SI": Shown("MPa", 1e-6), "US": Shown("psi", 1 / _PSI)},
    "velocity": {"SI": Shown("m/s", 1.0), "US": Shown("ft/min", 60 / _FT)},
    "linear_density": {"SI": Shown("kg/m", 1.0), "US": Shown("lb/ft", _FT / _LB)},
    "mass": {"SI": Shown("kg", 1.0), "US": Shown("lb", 1 / _LB)},
    "inertia": {"SI": Shown("kg·m²", 1.0), "US": Shown("lb·ft²", 1 / (_LB * _FT**2))},
    "stiffness": {"SI": Shown("N/m", 1.0), "US": Shown("lbf/in", _IN / _LBF)},
    "torque": {"SI": Shown("N·m", 1.0), "US": Shown("lbf·ft", 1 / (_LBF * _FT))},
    "torsional_stiffness": {"SI": Shown("N·m/rad", 1.0),
                            "US": Shown("lbf·ft/rad", 1 / (_LBF * _FT))},
    "torsional_damping": {"SI": Shown("N·m·s/rad", 1.0),
                          "US": Shown("lbf·ft·s/rad", 1 / (_LBF * _FT))},
    "area": {"SI": Shown("mm²", 1e6), "US": Shown("in²", 1 / _IN**2)},
    "density": {"SI": Shown("kg/m³", 1.0), "US": Shown("lb/ft³", _FT**3 / _LB)},
    "speed": {"SI": Shown("rpm", RPM_PER_RAD_S), "US": Shown("rpm", RPM_PER_RAD_S)},
    "frequency": {"SI": Shown("Hz", 1.0), "US": Shown("Hz", 1.0)},
    "angle": {"SI": Shown("°", DEG_PER_RAD), "US": Shown("°", DEG_PER_RAD)},
    "time": {"SI": Shown("s", 1.0), "US": Shown("s", 1.0)},
    "time_ms": {"SI": Shown("ms", 1e3), "US": Shown("ms", 1e3)},
    "hours": {"SI": Shown("h", 1 / 3600), "US": Shown("h", 1 / 3600)},
}

#: Suffix of a key of the JSON document → (kind of quantity, factor from the key's unit to SI).
#: Longest suffixes first (``_kg_m2`` before ``_kg_m`` before ``_m``).
_KEY_UNITS: tuple[tuple[str, str, float], ...] = (
    ("_n_per_m", "stiffness", 1.0), ("_kg_m2", "inertia", 1.0),
    ("_kg_m3", "density", 1.0), ("_kg_m", "linear_density", 1.0), ("_m_s", "velocity", 1.0),
    ("_mm2", "area", 1e-6), ("_mm", "length", 1e-3), ("_mpa", "pressure", 1e6),
    ("_kn", "force_k", 1e3), ("_n_m", "torque", 1.0), ("_n", "force", 1.0),
    ("_kw", "power", 1e3), ("_w", "power", 1.0), ("_rpm", "speed", 1 / RPM_PER_RAD_S),
    ("_hz", "frequency", 1.0), ("_deg", "angle", RAD_PER_DEG), ("_kg", "mass", 1.0),
    ("_ms", "time_ms", 1e-3), ("_s", "time", 1.0), ("_h", "hours", 3600.0),
)

#: Units of the checks (:attr:`chaindrive.checks.Check.unit`) → kind of quantity.
_CHECK_UNITS = {"MPa": "pressure", "kW": "power", "kN": "force_k", "m/s": "velocity",
                "N": "force", "mm": "length"}


def unit_system(name: str | None) -> UnitSystem:
    """The unit system named ``name`` ("SI", "US", case-insensitive; None → SI).

    Parameters
    ----------
    name : str or None
        The name as a user wrote it (``--units us``, a form field); None for the default.

    Returns
    -------
    {"SI", "US"}
        The unit system.

    Raises
    ------
    chaindrive.errors.DesignError
        ``units``: any other name.
    """
    if name is None:
        return "SI"
    key = name.strip().upper()
    if key not in UNIT_SYSTEMS:

        raise DesignError("units", f"must be SI or US, got {name!r}")
    return key  # type: ignore[return-value]


@shared_parameters
def unit_of(kind: str, system: UnitSystem = "SI") -> str:
    """The unit a kind of quantity (a key of :data:`QUANTITIES`) is read in.

    Parameters
    ----------
    kind : str
        A kind of quantity: ``"length"``, ``"force"``, ``"power"`` … (:data:`QUANTITIES`).
    %(system)s

    Returns
    -------
    str
        The unit's symbol (``"mm"``, ``"lbf"`` …).
    """
    return QUANTITIES[kind][system].unit


#: The finest a shown quantity of each kind resolves [SI unit of the kind]: a length below a
#: micrometre is shown as 0 (a sag of 1.4e-5 mm is a taut span's round-off; ISO 606's
#: tolerances on a chain's parts are tens of micrometres).
RESOLUTION: dict[str, float] = {"length": 1e-6}


@shared_parameters
def convert(value: float | None, kind: str, system: UnitSystem = "SI"
            ) -> tuple[float | None, str]:
    """An SI value in the unit ``system`` reads ``kind`` in: (value, unit); a magnitude below
    the kind's :data:`RESOLUTION` is 0.

    Parameters
    ----------
    value : float or None
        The value in SI [SI unit of ``kind``: m, N, W, Pa, rad/s …]; None for a missing one.
    kind : str
        Its kind of quantity (a key of :data:`QUANTITIES`).
    %(system)s

    Returns
    -------
    value : float or None
        The value in the unit read [unit returned beside it]; None when ``value`` is None.
    unit : str
        That unit's symbol.

    References
    ----------
    [NIST-SP811, App. B] (the factors of the US customary units).
    """
    shown = QUANTITIES[kind][system]
    if value is None:
        return None, shown.unit
    if abs(value) < RESOLUTION.get(kind, 0.0):
        return 0.0, shown.unit
    return value * shown.factor, shown.unit


@shared_parameters
def show(value: float | None, kind: str, system: UnitSystem = "SI", digits: int = 4) -> str:
    """An SI value as text with its unit (``"122.2 mm"``, ``"4.811 in"``).

    Parameters
    ----------
    value : float or None
        The value in SI [SI unit of ``kind``]; None is shown as "—".
    kind : str
        Its kind of quantity (a key of :data:`QUANTITIES`).
    %(system)s
    digits : int
        Significant digits (:func:`fmt`).

    Returns
    -------
    str
        The value and its unit, formatted by :func:`fmt`.
    """
    v, unit = convert(value, kind, system)
    return fmt(v, digits) if v is None else f"{fmt(v, digits)} {unit}"


def doc_quantity(key: str) -> tuple[str, float] | None:
    """(kind, factor to SI) of a key of the JSON document by its unit suffix (``x_mm`` →
    ("length", 1e-3)); None for a key without a unit suffix.

    Parameters
    ----------
    key : str
        A key of the JSON document (``tension_n``, ``x_mm``, ``speed_rpm`` …).

    Returns
    -------
    tuple of (str, float) or None
        The kind of quantity (a key of :data:`QUANTITIES`) and the factor from the key's unit
        to SI [SI per key unit]; None when the key names no unit.
    """
    for suffix, kind, to_si in _KEY_UNITS:
        if key.endswith(suffix):
            return kind, to_si
    return None


@shared_parameters
def doc_value(key: str, value: Any, system: UnitSystem = "SI") -> tuple[Any, str]:
    """A value of the JSON document (in the unit its key names) in ``system``: (value,
    unit); values of keys without a unit suffix, and non-numbers, come back unchanged with
    an empty unit.

    Parameters
    ----------
    key : str
        The value's key in the JSON document; its suffix names the unit (``_mm``, ``_n`` …).
    value : object
        The value as the document holds it (a number in the key's unit, or anything else).
    %(system)s

    Returns
    -------
    value : object
        The number in the unit read [unit returned beside it], or ``value`` unchanged.
    unit : str
        That unit's symbol; empty for a key without a unit suffix.
    """
    q = doc_quantity(key)
    if q is None:
        return value, ""
    kind, to_si = q
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value, unit_of(kind, system)
    return convert(float(value) * to_si, kind, system)


@shared_parameters
def header(label: str, key: str, system: UnitSystem = "SI") -> str:
    """A column header ``label, unit`` for a key of the JSON document (``label`` alone when
    the key carries no unit).

    Parameters
    ----------
    label : str
        The column's name for people.
    key : str
        The key of the JSON document the column shows.
    %(system)s

    Returns
    -------
    str
        The header text.
    """
    q = doc_quantity(key)
    return label if q is None else f"{label}, {unit_of(q[0], system)}"


def unit_header(label: str, unit: str) -> str:
    """A column header ``label, unit`` for a value in a named unit (``label`` alone for a
    dimensionless one: "", "-"); ``_`` in the label read as spaces, ``^2``/``^3`` as
    superscripts.

    Parameters
    ----------
    label : str
        The column's name (e.g. an objective's name, ``chain_length``).
    unit : str
        Its unit (e.g. "m^3", "EUR", "-").

    Returns
    -------
    str
        E.g. "chain length, m", "volume, m³".
    """
    text = label.replace("_", " ")
    if unit in ("", "-"):
        return text
    return f"{text}, {unit.replace('^2', '²').replace('^3', '³')}"


#: Below this magnitude a value shown to people is zero (round-off of a computed zero).
ZERO = 1e-9


def clean(value: float, digits: int = 4) -> float:
    """``value`` rounded to ``digits`` significant digits (round-off such as
    ``700.0000000000001`` or ``-6.4e-16`` next to values of order one removed; −0 → 0).

    Parameters
    ----------
    value : float
        A computed value [any unit, kept].
    digits : int
        Significant digits kept.

    Returns
    -------
    float
        The rounded value [unit of ``value``]; magnitudes below :data:`ZERO` are 0, NaN and
        ±∞ are returned as they are.
    """
    if abs(value) < ZERO or not math.isfinite(value):
        return value if not math.isfinite(value) else 0.0
    out = float(f"{value:.{digits}g}")
    return 0.0 if out == 0 else out


def fmt(value: object, digits: int = 4) -> str:
    """A value as text, by the one rule of every presenter.

    None and NaN → "—"; bools yes/no; ints as they are; floats with ``digits`` significant
    digits (trailing zeros dropped): magnitudes below :data:`ZERO` are 0 (a coordinate of
    −6.4e-16 mm is 0), from 10^digits up to 10^7 whole with thousands separators
    (``12,345``), beyond and below 10⁻³ in exponent form without padding (``2.154e8``,
    ``4.2e-5``); −0 is 0; ±∞ as "∞".

    Parameters
    ----------
    value : object
        The value to show (a number in the unit it is to be read in, a numpy scalar, a bool,
        None, or anything with a ``str``).
    digits : int
        Significant digits of a float.

    Returns
    -------
    str
        The text, without a unit.
    """
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return f"{value:,}" if abs(value) >= 10**digits else str(value)
    if not isinstance(value, float):
        item = getattr(value, "item", None)  # numpy scalars
        if callable(item):
            return fmt(item(), digits)
        return str(value)
    if math.isnan(value):
        return "—"
    if math.isinf(value):
        return "∞" if value > 0 else "−∞"
    a = abs(value)
    if a < ZERO:
        return "0"
    if a >= 1e7 or a < 1e-3:
        mantissa, _, exponent = f"{value:.{digits}g}".partition("e")
        if not exponent:
            return mantissa
        return f"{mantissa}e{int(exponent)}"
    if a >= 10**digits:
        return f"{value:,.0f}"
    text = f"{value:.{digits}g}"
    if "e" in text:  # 9999.5 rounds to 1e+04 at 4 digits
        return f"{float(text):,.0f}"
    return "0" if text in ("-0", "0") else text


_EXPONENT = re.compile(r"^(-?[\d.]+)e(-?\d+)$")


def exponent_parts(text: str) -> tuple[str, int] | None:
    """(mantissa, exponent) of a number :func:`fmt` wrote in exponent form, else None."""
    m = _EXPONENT.match(text)
    return None if m is None else (m.group(1), int(m.group(2)))


def shown_value(value: float | None, unit: str) -> tuple[float | None, str]:
    """A value in the unit it is read in (Pa → MPa, rad → °, rad/s → rpm; others as given).

    Parameters
    ----------
    value : float or None
        The value in ``unit`` [``unit``].
    unit : str
        Its unit symbol as the computing module gives it (``"Pa"``, ``"rad"``, ``"rad/s"``
        are converted; any other is kept).

    Returns
    -------
    value : float or None
        The value in the unit read [unit returned beside it].
    unit : str
        That unit's symbol.
    """
    kinds = {"Pa": "pressure", "rad": "angle", "rad/s": "speed"}
    if value is None or unit not in kinds:
        return value, unit
    return convert(value, kinds[unit])


_SIGNIFICANT = re.compile(r"[1-9][\d.]*")


def _significant_digits(number: str) -> int:
    """Significant digits a number is written with (``"12.1"`` 3, ``"0.47"`` 2,
    ``"2.16e+08"`` 3, ``"1363"`` 4)."""
    mantissa = number.lower().partition("e")[0]
    m = _SIGNIFICANT.search(mantissa)
    return 1 if m is None else max(1, len(m.group(0).replace(".", "")))


def _quantity(q: Quantity | Mapping[str, Any]) -> Quantity:
    """A quantity of a text, from a :class:`~chaindrive.errors.Quantity` or its JSON dict."""
    if isinstance(q, Mapping):
        return Quantity(str(q["text"]), float(q["value_si"]), str(q["kind"]))
    return Quantity(*q)


@shared_parameters
def quantity_text(text: str, quantities: Iterable[Quantity | Mapping[str, Any]] | None,
                  system: UnitSystem = "SI") -> str:
    """A text written in SI (a warning, a note) with each of its quantities written in the
    unit ``system`` reads them in; in SI, or without quantities, the text unchanged.

    Each quantity (:class:`chaindrive.errors.Quantity`: its text as the SI text writes it,
    its SI value and kind) replaces the first occurrence of its text not yet replaced (a
    whole number: ``"1.5 mm"`` is not found in ``"11.5 mm"``); the converted number keeps
    the significant digits of the SI one (at least 3), by :func:`fmt`. A quantity whose
    text is not found is left out.

    Parameters
    ----------
    text : str
        The text as the computing module wrote it (SI).
    quantities : iterable of Quantity or of their JSON dicts, or None
        The numbers with units it writes (``text``, ``value_si``, ``kind`` in a dict).
    %(system)s

    Returns
    -------
    str
        The text in ``system``.
    """
    items = [_quantity(q) for q in quantities or ()]
    if system == "SI" or not items or not text:
        return text
    taken: list[tuple[int, int, str]] = []
    for q in items:
        pattern = re.compile(rf"(?<![\w.]){re.escape(q.text)}(?![\w²³/·])")
        for m in pattern.finditer(text):
            if not any(m.start() < end and start < m.end() for start, end, _ in taken):
                number = q.text.split(" ", 1)[0]
                digits = max(3, _significant_digits(number))
                value, unit = convert(q.value, q.kind, system)
                assert value is not None
                taken.append((m.start(), m.end(), f"{fmt(clean(value, digits), digits)} {unit}"))
                break
    out, pos = [], 0
    for start, end, shown in sorted(taken):
        out += [text[pos:start], shown]
        pos = end
    return "".join(out) + text[pos:]


@shared_parameters
def warning_text(warning: ChainDriveWarning | Mapping[str, Any],
                 system: UnitSystem = "SI") -> str:
    """The text of a warning as a presenter shows it: its message with the numbers with
    units in the unit ``system`` reads them in (:func:`quantity_text`); in SI the message.

    Parameters
    ----------
    warning : ChainDriveWarning or dict
        The warning (:class:`chaindrive.errors.ChainDriveWarning`) or its JSON dict
        (:meth:`~chaindrive.errors.ChainDriveWarning.to_dict`: ``message``,
        ``quantities``).
    %(system)s

    Returns
    -------
    str
        The text to show.
    """
    if isinstance(warning, ChainDriveWarning):
        return quantity_text(warning.message, warning.quantities, system)
    return quantity_text(str(warning["message"]), warning.get("quantities"), system)


@shared_parameters
def static_state_note(equilibrium: Mapping[str, Any], system: UnitSystem = "SI",
                      figures: str = "these figures") -> str | None:
    """The sentence every presenter shows beside the link-level figures when the static
    state the run starts from stopped short of its tolerance (``converged`` false in
    :meth:`chaindrive.linklevel.equilibrium.Equilibrium.to_dict`): the largest force left
    and the reference span's offset from T₀, as the record carries them; None when it
    converged (or carries no ``converged``).

    Parameters
    ----------
    equilibrium : mapping
        The static state's record (``converged``, ``residual_force_n``,
        ``reference_tension_error_n`` [N]).
    %(system)s
    figures : str
        What rests on that state, as the sentence names it.

    Returns
    -------
    str or None
        The sentence, forces in ``system``'s unit; None for a converged state.
    """
    if equilibrium.get("converged", True):
        return None
    offset = float(equilibrium["reference_tension_error_n"])
    return ("The static state the link-level run starts from stopped short of its "
            "tolerance: largest force left "
            f"{show(float(equilibrium['residual_force_n']), 'force', system, 3)}, reference "
            f"span {'+' if offset > 0 else ''}{show(offset, 'force', system, 3)} off T₀; "
            f"{figures} rest on that state.")


def candidate_verdict(candidate: Mapping[str, Any]) -> str:
    """A selection candidate's standing in words, from its JSON flags
    (:meth:`chaindrive.strength.selection.Candidate.to_dict`): "pass", "chain fails",
    "layout 1.8 % short" (with "passed over" when the selection does not take it), "cannot
    be laid out", and "resonance possible" or "resonance beyond band".

    Parameters
    ----------
    candidate : dict
        The candidate's JSON dict.

    Returns
    -------
    str
        The words.
    """
    if not candidate["chain_checks_passed"]:
        return "chain fails"
    short = candidate["layout_shortfall_fraction"]
    words = []
    if short is None:
        words.append("cannot be laid out")
    elif short > 0:
        words.append(f"layout {fmt(100 * short, 2)} % short")
    resonance = candidate.get("resonance")
    if resonance == "inside its band":
        words.append("resonance possible")
    elif resonance == "beyond its band":
        words.append("resonance beyond band")
    if not candidate["selectable"] and short is not None:
        words.append("passed over")
    return "; ".join(words) or "pass"


@shared_parameters
def finding_lines(selection: Mapping[str, Any] | None, system: UnitSystem = "SI"
                  ) -> list[tuple[str, str]]:
    """The findings beside a selection's choice as a presenter shows them: (kind, text), the
    text's numbers with units in ``system`` (:func:`quantity_text`).

    Parameters
    ----------
    selection : dict or None
        The selection's JSON document
        (:meth:`chaindrive.strength.selection.SelectionResult.to_dict`).
    %(system)s

    Returns
    -------
    list of (str, str)
        Kind ("layout remedy", "resonance possible", "passed over") and text, in the
        selection's order; empty without a selection or findings.
    """
    if not selection:
        return []
    return [(str(f["kind"]), quantity_text(str(f["text"]), f.get("quantities"), system))
            for f in selection.get("findings") or ()]


def _check_display(check: Check, system: UnitSystem) -> tuple[float, str]:
    """(factor from SI, unit) of a check in ``system``."""
    kind = _CHECK_UNITS.get(check.unit)
    if kind is None:
        return check.scale, "°" if check.unit == "deg" else check.unit
    shown = QUANTITIES[kind][system]
    return shown.factor, shown.unit


@shared_parameters
def check_row(check: Check, system: UnitSystem = "SI"
              ) -> tuple[str, float | None, str, str, str]:
    """A check as shown: (what, value, required, result, source), value and limit in the
    unit the check is read in (``system``), and the result ``pass``, ``FAIL`` or ``CANNOT BE
    VERIFIED``.

    %(params_check_system)s

    Returns
    -------
    what : str
        The rule and its subject (and note).
    value : float or None
        The check's value in the unit read [:func:`check_unit`]; None when it cannot be
        computed.
    required : str
        The limit with its sense and unit (``"≤ 28 MPa"``), "—" without a limit; followed by
        "(estimate)" when the limit is an estimate (:attr:`Check.limit_estimated`).
    result : str
        :func:`result_word`.
    source : str
        Where the rule and its limit come from (a key of docs/references.md and section).
    """
    factor, unit = _check_display(check, system)
    sym = "≤" if check.kind == "max" else "≥"
    sep = "" if unit in ("°", "%", "") else " "
    limit = None if check.limit is None else check.limit * factor
    required = "—" if limit is None else f"{sym} {fmt(limit)}{sep}{unit}"
    if limit is not None and check.limit_estimated:
        required += " (estimate)"
    note = quantity_text(check.note, check.note_quantities, system)
    label = f"{check.name}: {check.subject}" + (f" ({note})" if note else "")
    value = None if check.value is None else check.value * factor
    return label, value, required, result_word(check), check.source


@shared_parameters
def check_unit(check: Check, system: UnitSystem = "SI") -> str:
    """The unit a check's value and limit are shown in (``system``).

    %(params_check_system)s

    Returns
    -------
    str
        The unit's symbol (empty for a pure number).
    """
    return _check_display(check, system)[1]


@shared_parameters
def check_value(check: Check, value: float | None, system: UnitSystem = "SI") -> float | None:
    """A value of a check (its value or limit, SI) in the unit it is shown in.

    %(params_check)s
    value : float or None
        The check's value or limit in SI [SI unit of the check].
    %(system)s

    Returns
    -------
    float or None
        The value in the unit read [:func:`check_unit`]; None when ``value`` is None.
    """
    return None if value is None else value * _check_display(check, system)[0]


@shared_parameters
def result_word(check: Check) -> str:
    """``pass``, ``FAIL`` or ``CANNOT BE VERIFIED``.

    %(params_check)s

    Returns
    -------
    str
        The result as every presenter writes it.
    """
    if check.passed:
        return "pass"
    return "FAIL" if check.status == "fail" else "CANNOT BE VERIFIED"


@shared_parameters
def margin_percent(check: Check) -> float | None:
    """The check's margin (:attr:`chaindrive.checks.Check.margin_fraction`) in per cent:
    ≥ 0 when it passes, < 0 when it fails; None when it cannot be verified or is unlimited.

    %(params_check)s

    Returns
    -------
    float or None
        The margin [%] of the limit.
    """
    m = check.margin_fraction
    return None if m is None or math.isinf(m) else 100.0 * m


@shared_parameters
def check_line(check: Check, system: UnitSystem = "SI") -> str:
    """A check in one line, the way every presenter writes a failed one:
    ``FAIL: hinge pressure: GOST … = 31 MPa (required ≤ 28 MPa)``.

    %(params_check_system)s

    Returns
    -------
    str
        The line.
    """
    label, _, required, result, _ = check_row(check, system)
    return f"{result}: {label} = {check_value_text(check, system)} (required {required})"


@shared_parameters
def check_value_text(check: Check, system: UnitSystem = "SI") -> str:
    """The check's value with its unit as every presenter writes it (``31 MPa``, ``2.5°``).

    %(params_check_system)s

    Returns
    -------
    str
        The value in the unit read [:func:`check_unit`] and the unit's symbol; ``—`` when
        it cannot be computed.
    """
    value = check_value(check, check.value, system)
    if value is None:
        return fmt(value)
    unit = check_unit(check, system)
    return f"{fmt(value)}{'' if unit in ('°', '%', '') else ' '}{unit}"


def dimension(value: float, decimals: int = 2) -> str:
    """A dimension of a drawing [mm] to ``decimals`` places (``122.18``; −0.00 is 0.00).

    Parameters
    ----------
    value : float
        The dimension [mm].
    decimals : int
        Decimal places.

    Returns
    -------
    str
        The dimension as written on a drawing, without its unit.
    """
    text = f"{value:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def constraint_row(report: ConstraintReport) -> tuple[str, int, int, str, str]:
    """A constraint of an optimisation run as shown (:class:`chaindrive.synthesis.solve.
    ConstraintReport`): (constraint, designs rejected, designs evaluated, by how much the
    closest rejected design missed, that design: its chain and tooth counts).

    Parameters
    ----------
    report : ConstraintReport
        The optimiser's account of one constraint (its name, counts, least violation as a
        fraction of the limit, the closest rejected design as a design mapping).

    Returns
    -------
    name : str
        The constraint.
    rejected, evaluated : int
        Designs it rejected and designs evaluated [-].
    miss : str
        By how much the closest rejected design missed [% of the limit], or why it could not
        be built, and how many designs it could not verify and why; "—" when nothing was
        rejected.
    design : str
        That design's chain and tooth counts; "—" when there is none.
    """
    if report.least_violation is None:
        miss = "—"
    elif report.name == "buildable":
        miss = f"not buildable: {report.error}" if report.error else "not buildable"
    else:
        miss = f"by {fmt(100 * report.least_violation, 3)} % of the limit"
    if report.unverified:
        unknown = (f"cannot be verified on {report.unverified}"
                   + (f": {report.unverified_reason}" if report.unverified_reason else ""))
        miss = unknown if report.least_violation is None else f"{miss}; {unknown}"
    design = report.closest
    if design is None:
        what = "—"
    else:
        chain = (design.get("chain") or {}).get("designation", "")
        teeth = " ".join(str(s.get("teeth")) for s in design.get("sprockets") or [])
        what = f"{chain}, teeth {teeth}".strip(", ")
    return report.name, report.rejected, report.evaluated, miss, what
