"""The pure layer of the web page: the edited form ↔ the design mapping ↔ the analysis.

Nothing here imports Streamlit, so every step the page takes is testable on its own:

* :func:`form_from_design` turns the mapping a TOML design file loads to into the form the
  page edits (drive and chain fields, one row per sprocket with numbers in mm, rpm, kg·m², °);
* :func:`design_from_form` turns the edited form back into that mapping (numbers become
  strings with their unit, empty cells are left out so the defaults of
  :mod:`chaindrive.io.design` apply);
* :func:`evaluate` validates the mapping with :func:`chaindrive.io.design.drive_from_mapping`
  and runs :func:`chaindrive.analyze`; a user's mistake comes back as the
  :class:`~chaindrive.errors.ChainDriveError` line the command line prints, with
  :func:`locate` telling the page which field (section, row, column) to show it next to.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import chaindrive
from chaindrive import examples
from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import analyze
from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.io.design import drive_from_mapping, parse_toml
from chaindrive.units import DEG_PER_RAD, RPM_PER_RAD_S, parse_quantity

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.model import Drive



@dataclass(frozen=True, slots=True)
class Column:
    """One column of the sprocket table.

    Parameters
    ----------
    key : str
        Its key in a row (``x_mm``).
    field : str
        The design-file field it writes (``x``).
    label : str
        Its header on the page, with the unit (``x [mm]``).
    unit : str
        The unit its numbers are in, as the design file writes it (``""`` for plain
        values).
    dimension : str
        The field's kind of quantity for the unit parser (``"length"``; ``""``: a plain
        value).
    from_si : float
        The factor that turns the field's SI value into the column's number [unit/SI]
        (1e3 for m → mm).
    """

    key: str
    field: str
    label: str
    unit: str = ""
    dimension: str = ""
    from_si: float = 1.0


#: The sprocket table, in the order the page shows it.
SPROCKET_COLUMNS: tuple[Column, ...] = (
    Column("name", "name", "name"),
    Column("teeth", "teeth", "teeth"),
    Column("x_mm", "x", "x [mm]", "mm", "length", 1e3),
    Column("y_mm", "y", "y [mm]", "mm", "length", 1e3),
    Column("role", "role", "role"),
    Column("side", "side", "side"),
    Column("adjustable", "adjustable", "adjustable"),
    Column("adjust_angle_deg", "adjust_angle", "adjust angle [°]", "deg", "angle",
           DEG_PER_RAD),
    Column("speed_rpm", "speed", "speed [rpm]", "rpm", "speed", RPM_PER_RAD_S),
    Column("power_share", "power_share", "power share"),
    Column("inertia_kg_m2", "inertia", "inertia [kg·m²]", "kg*m^2", "inertia", 1.0),
    Column("reduced_mass_kg", "reduced_mass", "reduced mass [kg]", "kg", "mass", 1.0),
    Column("material", "material", "material"),
)
COLUMN_OF_FIELD: dict[str, Column] = {c.field: c for c in SPROCKET_COLUMNS}

#: Drive fields the page edits as numbers: form key → (field, unit, SI → number factor).
DRIVE_NUMBERS: dict[str, tuple[str, str, float]] = {"power_kw": ("power", "kW", 1e-3)}
#: Form key of each design-file field that the form shows under another name.
FORM_KEY_OF_FIELD: dict[str, str] = {"power": "power_kw",
                                     "link_stiffness": "link_stiffness_n_per_m"}


@dataclass(slots=True)
class DesignForm:
    """What the page edits: the [drive] and [chain] values and the sprocket rows.

    Parameters
    ----------
    drive : dict
        name, power_kw [kW], service_factor, tooth_form (None: default), and any other
        ``[drive]`` field as read.
    chain : dict
        designation, standard, series, strands, links, allow_odd, contours, catalog,
        pitch_mm [mm], and any other ``[chain]`` field as read.
    sprockets : list of dict
        One dict per row with the keys of :data:`SPROCKET_COLUMNS` (numbers in the
        columns' units).
    other : dict
        Every other table of the design file (``[dynamics]``, …), kept as it was read.
    """

    drive: dict[str, Any] = field(default_factory=dict)
    chain: dict[str, Any] = field(default_factory=dict)
    sprockets: list[dict[str, Any]] = field(default_factory=list)
    other: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class Location:
    """Where a field path such as ``sprockets[2].teeth`` lives in the form.

    Parameters
    ----------
    section : str
        ``drive``, ``chain``, ``sprockets`` or ``design`` (the design as a whole).
    row : int | None
        The sprocket row, 0-based (sprockets only; None for the table as a whole).
    key : str | None
        The form key of the field (None for the whole section or row).
    """

    section: str
    row: int | None = None
    key: str | None = None


@dataclass(frozen=True, slots=True, eq=False)
class Outcome:
    """The result of :func:`evaluate`: the analysis, or the message of what is wrong.

    Parameters
    ----------
    analysis : Analysis | None
        The analysis (None when the design could not be analysed).
    drive : Drive | None
        The validated design, as designed (before the take-up moved a sprocket; None when
        it is invalid).
    message : str | None
        The one line the command line prints after ``error:`` (None when fine).
    location : Location | None
        Where the page shows the message.
    unexpected : bool
        True when the failure is not a user's mistake (the page then shows a short note,
        never a traceback).
    """

    analysis: Analysis | None = None
    drive: Drive | None = None  # as designed (before the take-up moved a sprocket)
    message: str | None = None
    location: Location | None = None
    unexpected: bool = False

    @property
    def ok(self) -> bool:
        """True when the design was analysed."""
        return self.analysis is not None


# --- examples and files ---------------------------------------------------------------------

def list_examples() -> tuple[str, ...]:
    """The bundled examples (package data, :mod:`chaindrive.examples`), sorted by name.

    Returns
    -------
    tuple of str
        Their names (without ``.toml``).
    """
    return examples.names()


def example_text(name: str) -> str:
    """The TOML text of a bundled example.

    Parameters
    ----------
    name : str
        A name of :func:`list_examples`.

    Returns
    -------
    str
        The design file's text.
    """
    return examples.text(name)


def read_design_text(text: str, name: str = "design") -> dict[str, Any]:
    """Parse the text of a TOML design file (errors as :func:`chaindrive.load` gives them).

    Parameters
    ----------
    text : str
        The file's text.
    name : str
        What the error messages call the file.

    Returns
    -------
    dict
        The design mapping.
    """

    return parse_toml(text, name)


# --- design mapping → form ------------------------------------------------------------------

def _si(value: Any, dimension: str, path: str) -> float:

    return parse_quantity(value, dimension, path)


def _cell_from_design(col: Column, value: Any, path: str) -> Any:
    """The table cell of one design-file value (quantities converted to the column unit)."""
    if value is None or not col.dimension:
        return value
    return _si(value, col.dimension, path) * col.from_si


def form_from_design(data: Mapping[str, Any]) -> DesignForm:
    """The editable form of a design mapping (as loaded from TOML).

    Quantities are converted to the units of the form (mm, rpm, kW, kg·m², °); a value that
    cannot be read raises the :class:`DesignError` the command line would print. Unknown
    fields are not dropped silently: they are kept so that :func:`evaluate` names them.

    Parameters
    ----------
    data : mapping
        The design mapping.

    Returns
    -------
    DesignForm
        The form's values.
    """
    drive_in = dict(data.get("drive") or {})
    power = drive_in.pop("power", None)
    drive = {"name": drive_in.pop("name", None),
             "power_kw": None if power is None else _si(power, "power", "drive.power") * 1e-3,
             "service_factor": drive_in.pop("service_factor", None),
             "tooth_form": drive_in.pop("tooth_form", None), **drive_in}
    chain_in = dict(data.get("chain") or {})
    chain = {k: chain_in.pop(k, None) for k in ("designation", "standard", "series", "strands",
                                                "links", "contours", "catalog", "sag")}
    chain["allow_odd"] = chain_in.pop("allow_odd", False)
    pitch = chain_in.pop("pitch", None)
    chain["pitch_mm"] = None if pitch is None else _si(pitch, "length", "chain.pitch") * 1e3
    k_link = chain_in.pop("link_stiffness", None)
    chain["link_stiffness_n_per_m"] = (None if k_link is None else
                                       _si(k_link, "stiffness", "chain.link_stiffness"))
    chain.update(chain_in)
    rows = []
    for i, raw in enumerate(data.get("sprockets") or []):
        if not isinstance(raw, Mapping):
            raise DesignError(f"sprockets[{i}]", f"must be a table, got {type(raw).__name__}")
        row: dict[str, Any] = {c.key: None for c in SPROCKET_COLUMNS}
        for key, value in raw.items():
            col = COLUMN_OF_FIELD.get(key)
            if col is None:
                row[key] = value
            else:
                row[col.key] = _cell_from_design(col, value, f"sprockets[{i}].{key}")
        rows.append(row)
    other = {k: v for k, v in data.items() if k not in ("drive", "chain", "sprockets")}
    return DesignForm(drive, chain, rows, other)


# --- form → design mapping ------------------------------------------------------------------

@shared_parameters
def is_empty(value: Any) -> bool:
    """True for an empty cell: None, NaN (pandas' missing value) or blank text.

    %(params_cell)s

    Returns
    -------
    bool
        Whether the cell is empty.
    """
    if value is None:
        return True
    if isinstance(value, float) and math.isnan(value):
        return True
    if isinstance(value, str) and not value.strip():
        return True
    if type(value).__name__ in ("NAType", "NaTType"):  # pandas' missing values
        return True
    try:  # numpy NaN scalars
        return bool(value != value)
    except (TypeError, ValueError):
        return False


@shared_parameters
def plain(value: Any) -> Any:
    """A cell as plain Python: numpy/pandas scalars unwrapped, whole floats of int columns
    left as floats (the caller decides).

    %(params_cell)s

    Returns
    -------
    object
        The Python value.
    """
    item = getattr(value, "item", None)
    return item() if callable(item) and not isinstance(value, str | bytes) else value


def _number_text(value: Any, unit: str) -> Any:
    """``value`` with its unit as the design file writes it, to 12 significant digits
    (``1364 mm``; the round-off of a unit conversion, ``700.0000000000001``, is not
    written); a non-number is passed through unchanged so that the parser names it."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value
    return f"{value:.12g} {unit}"


def _whole(value: Any) -> Any:
    """A whole float (``15.0`` from a numeric editor column) as an int; anything else as is."""
    if isinstance(value, float) and math.isfinite(value) and value.is_integer():
        return int(value)
    return value


def _row_to_design(row: Mapping[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, raw in row.items():
        value = plain(raw)
        if is_empty(value):
            continue
        col = next((c for c in SPROCKET_COLUMNS if c.key == key), None)
        if col is None:
            out[key] = value
        elif col.dimension:
            out[col.field] = _number_text(value, col.unit)
        elif col.field == "teeth":
            out[col.field] = _whole(value)
        elif col.field == "adjustable":
            if value:  # False is the default: leave it out
                out[col.field] = bool(value)
        else:
            out[col.field] = value
    return out


def _section_to_design(values: Mapping[str, Any], numbers: Mapping[str, tuple[str, str, float]],
                       whole: Iterable[str] = ()) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, raw in values.items():
        value = plain(raw)
        if is_empty(value):
            continue
        if key in numbers:
            name, unit, _ = numbers[key]
            out[name] = _number_text(value, unit)
        elif key in whole:
            out[key] = _whole(value)
        else:
            out[key] = value
    return out


CHAIN_NUMBERS: dict[str, tuple[str, str, float]] = {
    "pitch_mm": ("pitch", "mm", 1e3), "link_stiffness_n_per_m": ("link_stiffness", "N/m", 1.0)}


def design_from_form(form: DesignForm) -> dict[str, Any]:
    """The design mapping (what a TOML design file loads to) of the edited form.

    Parameters
    ----------
    form : DesignForm
        The edited form.

    Returns
    -------
    dict
        The design mapping, numbers written with their units (``"120 mm"``).
    """
    chain = _section_to_design(form.chain, CHAIN_NUMBERS, ("strands", "links", "contours"))
    if chain.get("allow_odd") is False:
        del chain["allow_odd"]
    return {
        "drive": _section_to_design(form.drive, DRIVE_NUMBERS),
        "chain": chain,
        "sprockets": [_row_to_design(r) for r in form.sprockets],
        **form.other,
    }


# --- the design mapping as a TOML file ------------------------------------------------------

def _toml_ready(value: Any) -> Any:
    """``value`` with what TOML cannot hold made TOML: numpy/pandas scalars unwrapped, other
    objects as their text."""
    value = plain(value)
    if isinstance(value, Mapping):
        return {str(k): _toml_ready(v) for k, v in value.items() if not is_empty(v)}
    if isinstance(value, list | tuple):
        return [_toml_ready(v) for v in value]
    if isinstance(value, bool | int | float | str):
        return value
    return str(value)


def design_to_toml(design: Mapping[str, Any], comment: str | None = None) -> str:
    """The design mapping as a TOML design file, written as entered (it need not be valid:
    a half-finished design can be saved and loaded again), by tomli-w: any name — with
    quotes, backslashes or newlines — is written so that it reads back the same.

    Parameters
    ----------
    design : Mapping
        The design mapping (:func:`design_from_form`).
    comment : str | None
        Lines written as ``#`` comments at the top (lines with control characters are
        left out).

    Returns
    -------
    str
        The TOML text.
    """
    import tomli_w

    lines = [f"# {line}" for line in (comment or "").splitlines() if line.isprintable()]
    body = tomli_w.dumps(_toml_ready(design))
    return "\n".join(lines) + ("\n\n" if lines else "") + body


# --- evaluation -----------------------------------------------------------------------------

def _index_of(token: str, names: Sequence[str]) -> int | None:
    if token.isdigit():
        return int(token)
    return names.index(token) if token in names else None


def locate(path: str, names: Sequence[str] = ()) -> Location:
    """Where the field ``path`` of an error lives in the form.

    ``sprockets[2].teeth`` → (sprockets, 2, "teeth"); ``sprockets[S3].speed`` (a name in the
    brackets, as the model writes it) → its row; ``sprockets.role`` → (sprockets, None,
    "role"); ``drive.power`` → (drive, None, "power_kw"); anything else → ("design").

    Parameters
    ----------
    path : str
        The field of a :class:`~chaindrive.errors.DesignError`.
    names : sequence of str
        The sprocket names, in row order (to find ``sprockets[S3]``).

    Returns
    -------
    Location
        Where the page shows the error.
    """
    head, _, rest = path.partition(".")
    section, _, bracket = head.partition("[")
    if section not in ("drive", "chain", "sprockets"):
        return Location("design")
    row = _index_of(bracket.rstrip("]"), names) if bracket else None
    key = rest.split(".")[0] or None
    if section == "sprockets" and key is not None:
        col = COLUMN_OF_FIELD.get(key)
        key = col.key if col is not None else key
    elif key is not None:
        key = FORM_KEY_OF_FIELD.get(key, "pitch_mm" if key == "pitch" else key)
    return Location(section, row, key)


def interactive_analysis(drive: Drive) -> Analysis:
    """The analysis the page redraws after every edit: everything :func:`chaindrive.analyze`
    computes except the time-consuming dynamic response (start-up transient and AFC sweep,
    which the page runs on demand): ``analyze(drive, response=False)``.

    Parameters
    ----------
    drive : Drive
        The validated design.

    Returns
    -------
    Analysis
        Its lazy analysis without the dynamic response.
    """

    return analyze(drive, response=False)


def evaluate(design: Mapping[str, Any], *, base_dir: Path | None = None,
             full: bool = False, catalogs: Mapping[str, Path] | None = None) -> Outcome:
    """Validate the design mapping and analyse it (:func:`interactive_analysis`, or the whole
    :func:`chaindrive.analyze` with ``full``); never raises for a bad design.

    A :class:`~chaindrive.errors.ChainDriveError` gives ``message`` = ``str(error)`` (the
    line the command line prints) and ``location`` from its ``field``; any other exception
    gives a short note with its class name and ``unexpected=True``.

    Parameters
    ----------
    design : Mapping
        The design mapping.
    base_dir : Path | None
        Kept for the callers that pass it; it plays no part in finding a catalogue.
    full : bool
        Analyse with the dynamic response.
    catalogs : Mapping of str to Path | None
        The catalogues uploaded in the session (name → file): ``chain.catalog`` can name
        only these — the page never opens a path a design gives.

    Returns
    -------
    Outcome
    """

    uploaded = dict(catalogs or {})
    names = [str(r.get("name")) for r in design.get("sprockets") or [] if isinstance(r, Mapping)]
    drive = None
    try:
        drive = drive_from_mapping(design, base_dir, catalogs=uploaded)
        analysis = chaindrive.analyze(drive) if full else interactive_analysis(drive)
    except ChainDriveError as exc:
        where = getattr(exc, "field", "")
        message = str(exc)
        for name, path in uploaded.items():  # the upload's name, not the server's file
            message = message.replace(str(path), name)
        return Outcome(drive=drive, message=message, location=locate(where, names))
    except Exception as exc:  # the page must never show a traceback
        return Outcome(drive=drive, unexpected=True, location=Location("design"),
                       message=f"the analysis failed unexpectedly ({type(exc).__name__}); "
                               "please report it with the design file")
    return Outcome(analysis=analysis, drive=drive)


# --- the "edit one sprocket" form -----------------------------------------------------------

#: The fields of the keyboard-friendly "edit one sprocket" form, in its order (row keys of
#: :data:`SPROCKET_COLUMNS`; the table edits every column, the form the everyday ones).
EDIT_FIELDS: tuple[str, ...] = ("name", "teeth", "x_mm", "y_mm", "role", "side", "speed_rpm",
                                "power_share")


def sprocket_label(index: int, row: Mapping[str, Any]) -> str:
    """How the form's sprocket chooser names a row: ``row 3: S3``.

    Parameters
    ----------
    index : int
        The row, 0-based.
    row : mapping
        The row's cells.

    Returns
    -------
    str
        The label.
    """
    name = row.get("name")
    return f"row {index + 1}: {'unnamed' if is_empty(name) else name}"


def edit_values(row: Mapping[str, Any]) -> dict[str, Any]:
    """The values the form shows for a sprocket row: empty cells as None, a whole tooth count
    as an int (a fractional one as None, so the form does not invent a count), numbers as
    float [mm, rpm, –], text as str.

    Parameters
    ----------
    row : mapping
        A row of the sprocket table.

    Returns
    -------
    dict
        :data:`EDIT_FIELDS` → the value the form shows.
    """
    out: dict[str, Any] = {}
    for key in EDIT_FIELDS:
        value = plain(row.get(key))
        if is_empty(value):
            out[key] = None
        elif key == "teeth":
            whole = _whole(float(value)) if isinstance(value, int | float) else None
            out[key] = whole if isinstance(whole, int) else None
        elif key in ("name", "role", "side"):
            out[key] = str(value)
        else:
            out[key] = float(value) if isinstance(value, int | float) else None
    return out


def apply_sprocket_edit(rows: Sequence[Mapping[str, Any]], index: int,
                        values: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The sprocket rows with row ``index`` (0-based) given ``values`` (keys of
    :data:`EDIT_FIELDS`; None empties the cell so the default applies). The other rows and
    the row's other columns are copied unchanged; an index outside the table changes nothing.

    Parameters
    ----------
    rows : sequence of mapping
        The sprocket table.
    index : int
        The row edited, 0-based.
    values : mapping
        :data:`EDIT_FIELDS` → new value (None empties the cell).

    Returns
    -------
    list of dict
        The new table (copies; ``rows`` is not changed).
    """
    out = [dict(r) for r in rows]
    if 0 <= index < len(out):
        out[index].update({k: v for k, v in values.items() if k in EDIT_FIELDS})
    return out
