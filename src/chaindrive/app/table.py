"""The sprocket table of the web page: plain form fields, one row per sprocket.

Streamlit's data editor sends an edit to the server only after a 150 ms pause (a constant
of its compiled front end), which alone took half of the 300 ms an edit may take to show
its results. This table is a Streamlit component (``st.components.v2``, no iframe) of
ordinary text fields, lists and tick boxes (``sprocket_table.js``): a cell committed by
Enter, Tab, leaving the field, a choice or a tick sends the whole table at once. The fields
are real form controls, each labelled with its sprocket and column, so the table can be
used from the keyboard and read by a screen reader.

What the component holds (the session state under its key, ``{"rows": [...]}``) is the
table as shown: the shown columns of every row and the row's place in the loaded design
(``_row``; None for a row added on the page). :func:`merged_rows` puts the loaded rows'
other fields (a train, a flywheel…) back, so nothing the table does not show is lost.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from functools import cache
from importlib import resources
from typing import Any

from chaindrive.app.state import SPROCKET_COLUMNS, is_empty, plain
from chaindrive.model import ROLES, SIDES

__all__ = ["SHORT_LABELS", "WIDTHS", "merged_rows", "shown_rows", "sprocket_table",
           "table_columns", "table_rows_from_state"]

#: Pixel widths of the columns: every column shows whole at 1400 px wide.
WIDTHS = {"name": 56, "teeth": 44, "x_mm": 66, "y_mm": 62, "role": 70, "side": 72,
          "adjustable": 34, "adjust_angle_deg": 62, "speed_rpm": 56, "power_share": 54,
          "inertia_kg_m2": 66, "reduced_mass_kg": 50, "material": 92}
#: Headers of the narrow columns (the full name is the column's tooltip).
SHORT_LABELS = {"adjustable": "adj.", "adjust_angle_deg": "adj. ∠ [°]", "speed_rpm": "n [rpm]",
                "power_share": "P share", "inertia_kg_m2": "J [kg·m²]",
                "reduced_mass_kg": "m [kg]"}
#: Tooltips of the columns (what a column means and what empty gives).
HELP = {"side": "empty: outside", "speed_rpm": "speed [rpm], the driver only",
        "power_share": "share of the power taken off (driven)",
        "inertia_kg_m2": "moment of inertia [kg·m²]; empty: from the material",
        "reduced_mass_kg": "everything turning with the sprocket as a mass at its pitch "
                           "radius [kg]; empty: from the material",
        "material": "empty: steel", "adjustable": "adjustable: this sprocket takes up the chain",
        "adjust_angle_deg": "direction of the line of adjustment [°]"}
#: Kinds of the columns (the rest are numbers).
KINDS = {"name": "text", "teeth": "int", "role": "select", "side": "select",
         "material": "select", "adjustable": "bool"}
#: What an empty list cell means (shown in it).
PLACEHOLDERS = {"role": "driven", "side": "outside", "material": "steel"}


def table_columns(materials: Sequence[str]) -> list[dict[str, Any]]:
    """The columns of the table as the component draws them.

    Parameters
    ----------
    materials : sequence of str
        The sprocket materials of the catalogue (the list of the ``material`` column).

    Returns
    -------
    list of dict
        key, label (header), title (tooltip), kind (text, int, float, select, bool),
        options, width [px], placeholder — in the order of
        :data:`~chaindrive.app.state.SPROCKET_COLUMNS`.
    """
    options = {"role": list(ROLES), "side": list(SIDES), "material": list(materials)}
    out = []
    for c in SPROCKET_COLUMNS:
        title = c.label + (f" — {HELP[c.key]}" if c.key in HELP else "")
        out.append({"key": c.key, "label": SHORT_LABELS.get(c.key, c.label), "title": title,
                    "kind": KINDS.get(c.key, "float"), "options": options.get(c.key, []),
                    "width": WIDTHS.get(c.key, 64),
                    "placeholder": PLACEHOLDERS.get(c.key, "")})
    return out


def _cell(value: Any) -> Any:
    """A shown cell as a JSON value: numbers, text, True/False or None (empty)."""
    value = plain(value)
    if is_empty(value):
        return None
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    return value if isinstance(value, bool | int | str) else str(value)


def shown_rows(rows: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The loaded sprocket rows as the table shows them.

    Parameters
    ----------
    rows : sequence of mapping
        The form's sprocket rows (:class:`~chaindrive.app.state.DesignForm`).

    Returns
    -------
    list of dict
        Per row ``_row`` (its index) and the shown columns as JSON values.
    """
    return [{"_row": i} | {c.key: _cell(r.get(c.key)) for c in SPROCKET_COLUMNS}
            for i, r in enumerate(rows)]


def merged_rows(base: Sequence[Mapping[str, Any]],
                table: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The sprocket rows of the design: the table's rows, each with the fields the table does
    not show taken from its loaded row.

    Parameters
    ----------
    base : sequence of mapping
        The loaded rows.
    table : sequence of mapping
        The rows as the table holds them (:func:`shown_rows`, edited).

    Returns
    -------
    list of dict
        One row per table row, in the table's order.
    """
    out = []
    for shown in table:
        index = shown.get("_row")
        row: dict[str, Any] = (dict(base[index]) if isinstance(index, int)
                               and not isinstance(index, bool) and 0 <= index < len(base)
                               else {c.key: None for c in SPROCKET_COLUMNS})
        row.update({c.key: shown.get(c.key) for c in SPROCKET_COLUMNS})
        out.append(row)
    return out


def table_rows_from_state(state: Any, key: str) -> list[dict[str, Any]] | None:
    """The rows the table holds in the session ``state`` under ``key``; None before its
    first edit.

    Parameters
    ----------
    state : mapping
        The session state.
    key : str
        The table's widget key.

    Returns
    -------
    list of dict | None
        The table's rows (:func:`shown_rows` form).
    """
    if key not in state:
        return None
    held = state[key]
    rows = held.get("rows") if isinstance(held, Mapping) else None
    if not isinstance(rows, list) or not all(isinstance(r, Mapping) for r in rows):
        return None
    return [dict(r) for r in rows]


def _extras_caption(base: Sequence[Mapping[str, Any]]) -> str:
    """The note under the table naming the loaded fields it does not show."""
    shown = {c.key for c in SPROCKET_COLUMNS}
    extra = sorted({str(k) for r in base for k in r} - shown)
    if not extra:
        return ""
    return ("Kept as loaded (not in the table; edit them in the design file): "
            + ", ".join(extra) + ".")


@cache
def _component() -> Any:
    """The registered component (once per process)."""
    import streamlit as st

    files = resources.files("chaindrive.app")
    return st.components.v2.component(
        "chaindrive_sprocket_table",
        js=files.joinpath("sprocket_table.js").read_text(encoding="utf-8"),
        css=files.joinpath("sprocket_table.css").read_text(encoding="utf-8"))


def sprocket_table(base: Sequence[Mapping[str, Any]], key: str,
                   materials: Sequence[str]) -> list[dict[str, Any]]:
    """Draw the table of the loaded rows ``base`` (with the edits it holds) and return the
    sprocket rows it gives.

    Parameters
    ----------
    base : sequence of mapping
        The loaded rows.
    key : str
        The widget key (a new key draws the table afresh from ``base``).
    materials : sequence of str
        The sprocket materials of the catalogue.

    Returns
    -------
    list of dict
        The sprocket rows (:func:`merged_rows`).
    """
    import streamlit as st

    held = table_rows_from_state(st.session_state, key)
    rows = shown_rows(base) if held is None else held
    _component()(key=key, data={"columns": table_columns(materials), "rows": rows,
                                "caption": _extras_caption(base)},
                 default={"rows": rows}, on_rows_change=lambda: None)
    return merged_rows(base, rows)
