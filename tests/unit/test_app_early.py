"""The design the page reads from its session state before drawing its widgets
(:func:`chaindrive.app.early.design_from_state`): with no state it is the loaded file's
design; with the sprocket table's edits (the data editor's state: edited, added and deleted
rows) or a changed field it is the edited design — each analysed as ``chaindrive.analyze``
analyses the same edit made in the TOML file (the one pipeline). Not the page itself: the
browser test (tests/e2e/test_app_browser.py) checks the numbers on screen.
"""

from __future__ import annotations

import copy
import tomllib
from typing import Any

import pytest

import chaindrive
from chaindrive.app.early import (
    AUTO_FORM,
    design_from_state,
    sprocket_frame,
    table_rows,
)
from chaindrive.app.state import design_from_form, form_from_design
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
    assert early(data, {}) == design_from_form(form.__class__(
        form.drive, form.chain, table_rows(sprocket_frame(form)), form.other))
    assert links(early(data, {}) or {}) == links(data)


def test_a_tooth_count_typed_in_the_table_is_the_edited_file() -> None:
    """The data editor's state after S2's tooth count is typed as 23 (the browser test's
    first form edit): the design of the TOML file with that count."""
    state = {TABLE: {"edited_rows": {1: {"teeth": 23}}, "added_rows": [], "deleted_rows": []}}
    design = early(BIG, state)
    assert design is not None and design["sprockets"][1]["teeth"] == 23
    edited = copy.deepcopy(BIG)
    edited["sprockets"][1]["teeth"] = 23
    assert links(design) == links(edited) != links(BIG)


def test_a_deleted_row_is_gone() -> None:
    state = {TABLE: {"edited_rows": {}, "added_rows": [], "deleted_rows": [5]}}
    design = early(BIG, state)
    assert design is not None
    names = [r["name"] for r in design["sprockets"]]
    assert names == [r["name"] for i, r in enumerate(BIG["sprockets"]) if i != 5]


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
