"""The design the page reads from its session state before drawing its widgets
(:func:`chaindrive.app.early.design_from_state`): with no state it is the loaded file's
design; with the sprocket table's edits (the rows the table sent: edited, added and
deleted rows, :mod:`chaindrive.app.table`) or a changed field it is the edited design —
each analysed as ``chaindrive.analyze`` analyses the same edit made in the TOML file (the
one pipeline). Not the page itself: the browser test (tests/e2e/test_app_browser.py)
checks the numbers on screen.
"""

from __future__ import annotations

import copy
import tomllib
from typing import Any

import pytest

import chaindrive
from chaindrive.app.early import AUTO_FORM, design_from_state
from chaindrive.app.state import SPROCKET_COLUMNS, design_from_form, form_from_design
from chaindrive.app.table import merged_rows, shown_rows, table_columns
from chaindrive.io.design import drive_from_mapping
from tests.conftest import EXAMPLES

BIG = tomllib.loads((EXAMPLES / "twenty_four_sprocket.toml").read_text(encoding="utf-8"))
SEED = tomllib.loads((EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8"))
TABLE = "sprockets@1"


def key(name: str) -> str:
    return f"{name}@1"


def early(data: dict[str, Any], state: dict[str, Any]) -> dict[str, Any] | None:
    """The design read from ``state`` over the form of ``data`` (chain box: the file's)."""
    form = form_from_design(data)
    designation = (data.get("chain") or {}).get("designation")
    choice = str(designation) if designation else "(select for the power: ISO 606)"
    return design_from_state(form, state, key, TABLE, choice, [choice])


def links(design: dict[str, Any]) -> int:
    return chaindrive.analyze(drive_from_mapping(design), response=False).geometry.links


@pytest.mark.parametrize("data", [SEED, BIG], ids=["seed", "24 sprockets"])
def test_no_state_is_the_loaded_design(data: dict[str, Any]) -> None:
    form = form_from_design(data)
    assert early(data, {}) == design_from_form(form)
    # the table untouched gives the same design as no table state at all
    state = {TABLE: {"rows": shown_rows(form.sprockets)}}
    assert early(data, state) == design_from_form(form)
    assert links(early(data, {}) or {}) == links(data)


def table(data: dict[str, Any]) -> list[dict[str, Any]]:
    """The rows the sprocket table holds for the loaded ``data`` (before an edit)."""
    return shown_rows(form_from_design(data).sprockets)


def test_a_tooth_count_typed_in_the_table_is_the_edited_file() -> None:
    """The table's rows after S2's tooth count is typed as 23 (the browser test's first
    table edit): the design of the TOML file with that count."""
    rows = table(BIG)
    rows[1]["teeth"] = 23
    design = early(BIG, {TABLE: {"rows": rows}})
    assert design is not None and design["sprockets"][1]["teeth"] == 23
    edited = copy.deepcopy(BIG)
    edited["sprockets"][1]["teeth"] = 23
    assert links(design) == links(edited) != links(BIG)


def test_a_deleted_row_is_gone() -> None:
    rows = table(BIG)
    del rows[5]
    design = early(BIG, {TABLE: {"rows": rows}})
    assert design is not None
    names = [r["name"] for r in design["sprockets"]]
    assert names == [r["name"] for i, r in enumerate(BIG["sprockets"]) if i != 5]


def test_fields_the_table_does_not_show_are_kept() -> None:
    """The seed example's rows carry a reduced mass (a column) and the conveyor's a train
    (not a column): after an edit of another cell both are still in the design."""
    data = tomllib.loads((EXAMPLES / "conveyor_five_sprocket.toml").read_text(encoding="utf-8"))
    rows = table(data)
    assert not any("train" in r for r in rows)  # the table does not show it
    rows[0]["teeth"] = int(rows[0]["teeth"]) + 1
    design = early(data, {TABLE: {"rows": rows}})
    assert design is not None
    for got, loaded in zip(design["sprockets"], data["sprockets"], strict=True):
        assert got.get("train") == loaded.get("train")
    seed = early(SEED, {TABLE: {"rows": table(SEED)}})
    assert seed is not None
    assert [r["reduced_mass"] for r in seed["sprockets"]] == ["17.26 kg", "28.44 kg", "2 kg"]


def test_a_number_typed_with_its_unit_and_an_added_row() -> None:
    """A cell that is not a plain number goes to the design as typed (the loader reads
    "700 mm", and names the field when it cannot read it); a row added on the page starts
    empty (every default)."""
    rows = table(SEED)
    rows[2]["y_mm"] = "70 mm"
    rows.append({"_row": None} | {c.key: None for c in SPROCKET_COLUMNS})
    design = early(SEED, {TABLE: {"rows": rows}})
    assert design is not None
    assert design["sprockets"][2]["y"] == "70 mm"
    assert design["sprockets"][3] == {}
    with pytest.raises(chaindrive.ChainDriveError, match=r"sprockets\[3\]"):
        drive_from_mapping(design)


def test_merged_rows_ignore_a_row_index_outside_the_loaded_table() -> None:
    base = form_from_design(SEED).sprockets
    shown = shown_rows(base)
    shown[0]["_row"] = 99
    shown[1]["_row"] = True  # not an index
    merged = merged_rows(base, shown)
    assert merged[0]["teeth"] == base[0]["teeth"] and merged[0].get("reduced_mass_kg") == 17.26
    assert [m["name"] for m in merged] == [b["name"] for b in base]


def test_the_columns_are_the_form_columns_in_order() -> None:
    columns = table_columns(["steel", "PA6-GF30"])
    assert [c["key"] for c in columns] == [c.key for c in SPROCKET_COLUMNS]
    kinds = {c["key"]: c["kind"] for c in columns}
    assert kinds["teeth"] == "int" and kinds["role"] == "select" and kinds["x_mm"] == "float"
    assert next(c for c in columns if c["key"] == "material")["options"] == ["steel",
                                                                               "PA6-GF30"]


def test_changed_fields_are_read_from_the_state() -> None:
    state = {key("drive.power"): 0.75, key("drive.tooth_form"): AUTO_FORM,
             key("chain.links"): 130}
    design = early(SEED, state)
    assert design is not None
    edited = copy.deepcopy(SEED)
    edited["drive"]["power"] = "0.75 kW"
    edited["chain"]["links"] = 130
    analysis = chaindrive.analyze(drive_from_mapping(design), response=False)
    reference = chaindrive.analyze(drive_from_mapping(edited), response=False)
    assert analysis.geometry.links == reference.geometry.links == 130
    assert analysis.drive.power == pytest.approx(reference.drive.power, rel=1e-12)


def test_a_chain_not_among_the_options_is_not_guessed() -> None:
    form = form_from_design(SEED)
    assert design_from_state(form, {key("chain.choice"): "no such chain"}, key, TABLE,
                             "08B-1", ["08B-1"]) is None
