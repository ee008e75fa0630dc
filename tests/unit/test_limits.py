"""Plausibility limits and robust reading of design and catalogue files (chaindrive.io):
every numeric field has a lower and an upper bound with a reason, a value beyond one is one
DesignError line naming the field, and no file content reaches a traceback.

Each case is a defect found by fuzzing: the bounds come from the fields' own definitions
(chaindrive.io.design), the expected lines from the loader's wording.
"""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path
from typing import Any

import pytest

from chaindrive.errors import CatalogError, DesignError
from chaindrive.io.design import SECTIONS, Field, drive_from_mapping, load_drive, parse_toml, schema
from chaindrive.io.limits import MAX_DESIGN_BYTES
from chaindrive.units import DIMENSIONS
from tests.conftest import EXAMPLES

NUMERIC = ("int", "float", "links", *DIMENSIONS)
JINDAL = tomllib.loads((EXAMPLES / "two_sprocket_jindal.toml").read_text(encoding="utf-8"))


def _fields() -> list[tuple[str, Field]]:
    return [(section, f) for section, fields in SECTIONS.items() for f in fields
            if f.kind in NUMERIC]


@pytest.mark.parametrize(("section", "field"), _fields(), ids=lambda v: getattr(v, "name", v))
def test_every_numeric_field_has_bounds_and_a_reason(section: str, field: Field) -> None:
    assert field.minimum is not None and field.maximum is not None, field.name
    assert field.minimum < field.maximum
    assert field.reason, f"{section}.{field.name} states no reason for its bounds"


def test_schema_states_the_reasons() -> None:
    doc = schema()
    speed = next(f for f in doc["sprockets"] if f["field"] == "speed")
    assert "30 000 rev/min" in speed["reason"] and speed["allowed"].endswith("≤ 30000 rpm")


def _value(field: Field, si: float) -> Any:
    """A design-file value of ``field`` with the SI value ``si``."""
    if field.kind in ("int", "links"):
        return int(si)
    if field.kind == "float":
        return si
    return f"{si!r} {DIMENSIONS[field.kind][1]}"


#: A train element of each kind a field belongs to (shaft by stiffness, shaft by its size, gear).
_ELEMENT = {"ratio": {"kind": "gear", "name": "wheel", "ratio": 2.0},
            "efficiency": {"kind": "gear", "name": "wheel", "ratio": 2.0},
            "diameter": {"kind": "shaft", "name": "hub", "diameter": "0.05 m", "length": "0.2 m"},
            "length": {"kind": "shaft", "name": "hub", "diameter": "0.05 m", "length": "0.2 m"}}
_SHAFT = {"kind": "shaft", "name": "hub", "stiffness": "1e4 N*m/rad"}


def _design(section: str, name: str, value: Any) -> dict[str, Any]:
    data = copy.deepcopy(JINDAL)
    if section == "sprockets":
        data["sprockets"][0][name] = value
    elif section == "sprockets.train":
        data["sprockets"][0]["train"] = [{**_ELEMENT.get(name, _SHAFT), name: value}]
    else:
        data.setdefault(section, {})[name] = value
    return data


def _path(section: str, name: str) -> str:
    if section == "sprockets":
        return f"sprockets[0].{name}"
    if section == "sprockets.train":
        return f"sprockets[0].train[0].{name}"
    return f"{section}.{name}"


@pytest.mark.parametrize(("section", "field"), _fields(), ids=lambda v: getattr(v, "name", v))
def test_beyond_a_bound_is_one_line_naming_the_field(section: str, field: Field) -> None:
    assert field.maximum is not None and field.minimum is not None
    beyond = (field.maximum * 10 + 10, field.minimum - abs(field.minimum) - 1)
    for si in beyond:
        if field.kind in ("int", "links") and si != int(si):
            si = math.floor(si)
        with pytest.raises(DesignError) as info:
            drive_from_mapping(_design(section, field.name, _value(field, si)))
        path = _path(section, field.name)
        assert str(info.value).startswith(path + ":"), str(info.value)
        assert "\n" not in str(info.value)


@pytest.mark.parametrize(("text", "fragment"), [
    ("inertia = \"1e-10 kg*m^2\"", "sprockets[1].inertia"),  # below the bound
    ("inertia = \"1e-8 kg*m^2\"", "less than a tenth of the inertia of the sprocket's own"),
    ("inertia = \"1e-30 kg*m^2\"", "sprockets[1].inertia"),
    ("adjust_angle = \"300 m/s\"", "is not an angle"),
    ("y = \"1 parsec\"", "sprockets[1].y"),
])
def test_driven_sprocket_cases(text: str, fragment: str) -> None:
    body = (EXAMPLES / "two_sprocket_jindal.toml").read_text(encoding="utf-8")
    if text.startswith("y ="):
        body = body.replace('y = "0 mm"\nrole = "driven"', text + '\nrole = "driven"')
    else:
        body = body.replace('role = "driven"', f'role = "driven"\n{text}')
    with pytest.raises(DesignError, match=None) as info:
        drive_from_mapping(parse_toml(body, "x.toml"))
    assert fragment in str(info.value)


def test_a_plausible_inertia_is_accepted() -> None:
    data = copy.deepcopy(JINDAL)
    data["sprockets"][1]["inertia"] = "0.002 kg*m^2"  # about twice the plate's own
    assert drive_from_mapping(data).sprockets[1].inertia == pytest.approx(0.002)


@pytest.mark.parametrize(("extra", "field"), [
    ({"pitch": "25.4 mm"}, "chain.pitch"),
    ({"series": "A"}, "chain.series"),
    ({"standard": "GOST 13568"}, "chain.standard"),
])
def test_a_designation_and_a_contradicting_pitch_series_or_standard(extra: dict[str, str],
                                                                   field: str) -> None:
    data = copy.deepcopy(JINDAL)
    data["chain"].update(extra)
    with pytest.raises(DesignError) as info:
        drive_from_mapping(data)
    assert str(info.value).startswith(field + ":") and "contradicts" in str(info.value)


def test_a_designation_with_agreeing_fields_is_accepted() -> None:
    data = copy.deepcopy(JINDAL)
    data["chain"].update(pitch="9.525 mm", series="B", standard="ISO 606")
    assert drive_from_mapping(data).chain.spec.designation == "ISO 606 06B-1"


def test_deep_toml_is_one_line() -> None:
    text = "x = " + "[" * 3000 + "]" * 3000
    with pytest.raises(DesignError, match="nested too deeply"):
        parse_toml(text, "deep.toml")


def test_an_oversized_design_file(tmp_path: Path) -> None:
    path = tmp_path / "big.toml"
    path.write_text("# " + "x" * MAX_DESIGN_BYTES + "\n", encoding="utf-8")
    with pytest.raises(DesignError, match="too large for a design file"):
        load_drive(path)


def test_a_file_name_too_long_for_the_file_system() -> None:
    with pytest.raises(DesignError) as info:
        load_drive("a" * 3000 + ".toml")
    assert "\n" not in str(info.value) and len(str(info.value)) < 500


def test_a_key_with_a_newline_stays_one_line() -> None:
    data = copy.deepcopy(JINDAL)
    data["drive"]["bad\nkey"] = 1
    with pytest.raises(DesignError) as info:
        drive_from_mapping(data)
    assert "\n" not in str(info.value) and "bad\\nkey" in str(info.value)


def test_a_huge_integer_is_refused() -> None:
    data = copy.deepcopy(JINDAL)
    data["sprockets"][0]["teeth"] = 10**400
    with pytest.raises(DesignError, match="sprockets\\[0\\].teeth: must be a whole number"):
        drive_from_mapping(data)


# --- catalogue files ------------------------------------------------------------------------

HEADER = ("designation,pitch_mm,roller_diameter_mm,pin_diameter_mm,inner_width_mm,"
          "plate_depth_mm,breaking_load_kN,mass_kg_m,strands\n")
ROW = "X 1,12.7,8.51,4.45,7.75,11.8,18.2,0.7,1\n"


def _with_catalog(tmp_path: Path, text: str) -> dict[str, Any]:
    (tmp_path / "mine.csv").write_text(text, encoding="utf-8")
    data = copy.deepcopy(JINDAL)
    data["chain"] = {"designation": "X 1", "catalog": "mine.csv"}
    return data


def test_a_user_catalogue_row_is_used(tmp_path: Path) -> None:
    drive = drive_from_mapping(_with_catalog(tmp_path, HEADER + ROW), tmp_path)
    assert drive.chain.spec.pitch == pytest.approx(0.0127)


@pytest.mark.parametrize(("text", "fragment"), [
    (HEADER + 'X 1,"12.7,8.51,4.45,7.75,11.8,18.2,0.7,1\n', "must be a number"),  # open quote
    (HEADER + 'X 1,"12.7,8.51,4.45,7.75,11.8,18.2,0.7,1\n' + ROW, "quoted cell"),
    (HEADER + "X 1," + "9" * 200_000 + ",8.51,4.45,7.75,11.8,18.2,0.7,1\n", ""),  # 200 kB cell
    (HEADER + ROW.replace("18.2", "1e300"), "plausible range"),
    (HEADER + ROW.replace(",1\n", ",²\n"), "whole number from 1 to 8"),
    (HEADER + ROW.replace("7.75", "1e-300"), "plausible range"),  # gave NaN in the JSON
])
def test_malformed_catalogue_rows_are_one_line(tmp_path: Path, text: str, fragment: str) -> None:
    with pytest.raises(CatalogError) as info:
        drive_from_mapping(_with_catalog(tmp_path, text), tmp_path)
    assert fragment in str(info.value)
    assert "\n" not in str(info.value) and len(str(info.value)) < 1000


def test_catalogue_only_from_the_given_names(tmp_path: Path) -> None:
    """With ``catalogs`` (the web page), chain.catalog is a name among them, never a path."""
    secret = tmp_path / "secret.csv"
    secret.write_text("TOPSECRET,pitch_mm\n", encoding="utf-8")
    for name in (str(secret), "../../../../" + str(secret), "secret.csv"):
        data = copy.deepcopy(JINDAL)
        data["chain"]["catalog"] = name
        with pytest.raises(DesignError) as info:
            drive_from_mapping(data, tmp_path, catalogs={})
        assert "not a catalogue uploaded in this session" in str(info.value)
        assert "TOPSECRET" not in str(info.value)


@pytest.mark.parametrize(("section", "name", "value", "path"), [
    ("sprockets", "speed", "1e30 rpm", "sprockets[0].speed"),
    ("sprockets", "speed", "1e-6 rpm", "sprockets[0].speed"),
    ("drive", "power", "1e12 W", "drive.power"),
    ("sprockets", "x", "123 km", "sprockets[0].x"),  # a 123 km centre distance passed
    ("dynamics", "eccentricity", "1 m", "dynamics.eccentricity"),
    ("dynamics", "accumulated_error", "1 km", "dynamics.accumulated_error"),
])
def test_the_values_the_fuzzer_found(section: str, name: str, value: str, path: str) -> None:
    with pytest.raises(DesignError) as info:
        drive_from_mapping(_design(section, name, value))
    assert str(info.value).startswith(path + ": must be")


def test_a_possible_design_that_breaks_its_chain_fails_loudly() -> None:
    """30 000 rpm on the Jindal drive (100 m/s of chain): allowed, and its checks fail."""
    import chaindrive

    data = copy.deepcopy(JINDAL)
    data["sprockets"][0]["speed"] = "30000 rpm"
    analysis = chaindrive.analyze(drive_from_mapping(data), response=False)
    failed = {c.name for c in analysis.checks() if c.status != "pass"}
    assert {"speed limit", "static safety", "power rating"} <= failed
