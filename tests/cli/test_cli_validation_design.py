"""Bad or unusual design files: a byte-order mark is read, a load law on a sprocket that is
not driven, a sag below the physical range, examples outside their field's range, integer
limits, and messages that name the field the user wrote (not an internal name)."""

from __future__ import annotations

import copy
import math
import re
import tomllib
from pathlib import Path
from typing import Any

import pytest

import chaindrive
from chaindrive.cli import run
from chaindrive.errors import DesignError
from chaindrive.io import design
from chaindrive.io.design import (
    SECTIONS,
    Field,
    drive_from_mapping,
    drive_to_mapping,
    parse_field,
    parse_toml,
)
from chaindrive.robust import synthesis as robust_synthesis
from chaindrive.strength.loads import DEFAULT_SAG_RATIO
from chaindrive.synthesis import problem as synthesis_problem
from tests.conftest import EXAMPLES

JINDAL = EXAMPLES / "two_sprocket_jindal.toml"
BOM = "\ufeff"  # the byte-order mark an editor may put first in a UTF-8 file


def jindal() -> dict[str, Any]:
    """The tables of the Jindal example (a fresh copy)."""
    return copy.deepcopy(tomllib.loads(JINDAL.read_text(encoding="utf-8")))


def within(f: Field, value: float) -> bool:
    """True when ``value`` [SI] lies within the bounds of ``f``."""
    low_ok = f.minimum is None or (value > f.minimum if f.exclusive_minimum
                                   else value >= f.minimum)
    return math.isfinite(value) and low_ok and (f.maximum is None or value <= f.maximum)


def refused(data: dict[str, Any]) -> DesignError:
    """The error the design ``data`` is refused with."""
    with pytest.raises(DesignError) as info:
        drive_from_mapping(data, base_dir=EXAMPLES)
    return info.value


# --------------------------------------------------------------------------- 6: BOM
def test_a_design_file_with_a_byte_order_mark_is_read(tmp_path: Path) -> None:
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + JINDAL.read_bytes())
    assert drive_to_mapping(chaindrive.load(path)) == drive_to_mapping(chaindrive.load(JINDAL))
    assert parse_toml(BOM + JINDAL.read_text(encoding="utf-8"), "upload") == jindal()


def test_a_file_with_a_byte_order_mark_runs_on_the_command_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "bom.toml"
    path.write_text(BOM + JINDAL.read_text(encoding="utf-8"), encoding="utf-8")
    status = run(["select", str(path), "--json", "--top", "1"])
    assert status == 0, capsys.readouterr().err


# --------------------------------------------------------------------------- 7: load law
@pytest.mark.parametrize("role", ["driver", "idler"])
def test_load_law_applies_to_driven_sprockets_only(role: str) -> None:
    data = jindal()
    if role == "driver":
        data["sprockets"][0]["load"] = "constant"
        where = 0
    else:
        data["sprockets"].append({"name": "idler", "teeth": 17, "x": "238 mm", "y": "-80 mm",
                                  "role": "idler", "load": "constant"})
        where = 2
    exc = refused(data)
    assert exc.field == f"sprockets[{where}].load"
    assert "driven sprockets only" in str(exc) and role in str(exc) and "'constant'" in str(exc)


def test_load_law_on_a_driven_sprocket_is_kept() -> None:
    data = jindal()
    data["sprockets"][1]["load"] = "constant"
    assert drive_from_mapping(data, base_dir=EXAMPLES).sprockets[1].load == "constant"


# --------------------------------------------------------------------------- 8: sag
@pytest.mark.parametrize("sag", [1e-9, 1e-4, 0.0009])
def test_sag_below_a_tenth_of_a_percent_is_refused(sag: float) -> None:
    data = jindal()
    data["chain"]["sag"] = sag
    exc = refused(data)
    assert exc.field == "chain.sag" and "≥ 0.001" in str(exc) and repr(sag) in str(exc)


def test_sag_field_states_its_source_and_the_default_the_code_uses() -> None:
    data = jindal()
    data["chain"]["sag"] = 0.001
    assert drive_from_mapping(data, base_dir=EXAMPLES).chain.sag == 0.001
    sag = next(f for f in SECTIONS["chain"] if f.name == "sag")
    assert "[DiamondChainTension]" in sag.reason and "[Irvine1981]" in sag.reason
    assert "laid out tight)" not in sag.description
    assert f"{100 * DEFAULT_SAG_RATIO:g} %" in sag.description


# --------------------------------------------------------------------------- 9: examples
def _every_field() -> list[tuple[str, Field]]:
    """Every field of the design schema and of the other tables read with the same rules."""
    out = [(f"{section}.{f.name}", f) for section, fields in SECTIONS.items() for f in fields]
    for module in (synthesis_problem, robust_synthesis):
        for name, value in vars(module).items():
            if isinstance(value, tuple) and value and all(isinstance(f, Field) for f in value):
                out += [(f"{module.__name__}.{name}.{f.name}", f) for f in value]
    return out


FIELDS = _every_field()


def _as_written(f: Field, example: str) -> object:
    """The example as a design file holds it (a quantity a string, a number a number)."""
    if f.kind in ("int", "links") and re.fullmatch(r"-?\d+", example):
        return int(example)
    if f.kind == "float":
        return float(example)
    return example


@pytest.mark.parametrize(("path", "f"), FIELDS, ids=[p for p, _ in FIELDS])
def test_every_example_lies_within_its_field(path: str, f: Field) -> None:
    example = f.example_text()
    if not example:
        return
    value = parse_field(f, _as_written(f, example), path)
    if isinstance(value, float):
        assert within(f, value), (path, example)
    assert f'"{example}"' in f.allowed() or f.kind not in design.DIMENSIONS


def test_every_field_of_the_schema_is_checked() -> None:
    assert len({p for p, _ in FIELDS}) == len(FIELDS)
    assert sum(len(fields) for fields in SECTIONS.values()) <= len(FIELDS)


def test_motor_ramp_time_example_fits() -> None:
    ramp = next(f for f in SECTIONS["motor"] if f.name == "ramp_time")
    assert ramp.example_text() != "2400 h"
    with pytest.raises(DesignError) as info:
        parse_field(ramp, "2", "motor.ramp_time")
    shown = re.search(r'write it like "([^"]+)"', str(info.value))
    assert shown is not None, info.value
    parse_field(ramp, shown.group(1), "motor.ramp_time")  # the example itself is allowed


@pytest.mark.parametrize(("kind", "lo", "hi", "exclusive", "default"), [
    ("time", 0.0, 60.0, True, None),
    ("time", 1e-3, 10.0, False, None),
    ("length", 0.0, 0.01, False, 0.0),
    ("speed", 1.0, 2.0, False, None),
    ("power", 5e6, None, True, None),
    ("inertia", None, 1e-7, False, None),
    ("torque", 0.95, 0.999, False, None),
])
def test_an_example_is_made_within_any_bounds(kind: str, lo: float | None, hi: float | None,
                                              exclusive: bool, default: float | None) -> None:
    f = Field("x", kind, "", default=default, minimum=lo, maximum=hi,
              exclusive_minimum=exclusive)
    example = f.example_text()
    assert within(f, parse_field(f, example, "x")), example


# --------------------------------------------------------------------------- 10: integers
def test_integer_limits_print_as_integers() -> None:
    fields = {f.name: f for f in SECTIONS["uncertainty"]}
    assert fields["samples"].allowed() == "a whole number from 8 to 1048576"
    assert fields["seed"].allowed() == "a whole number from 0 to 2147483647"
    with pytest.raises(DesignError, match=r"from 8 to 1048576, got 4194304 "):
        parse_field(fields["samples"], 1 << 22, "uncertainty.samples")
    open_ended = Field("n", "int", "", minimum=1 << 20)
    assert open_ended.allowed() == "a whole number ≥ 1048576"
    for path, f in FIELDS:
        if f.kind in ("int", "links"):
            assert not re.search(r"\de[+-]?\d", f.allowed()), (path, f.allowed())


# --------------------------------------------------------------------------- 11: field names
def _motor(**table: str) -> DesignError:
    data = jindal()
    data["motor"] = dict(table)
    return refused(data)


def _no_internals(exc: DesignError) -> None:
    text = str(exc)
    assert "synchronous_speed_rad_s" not in text and "rated_power_w" not in text
    assert not re.search(r"\d\.\d{8,}", text), text  # no float repr of 16 digits


def test_motor_rated_speed_outside_the_estimate_names_rated_speed() -> None:
    exc = _motor(rated_speed="100 rpm")
    assert exc.field == "motor.rated_speed"
    assert "100 rpm" in str(exc) and "750 to 3600 rpm" in str(exc)
    assert "motor.rotor_inertia" in str(exc)
    _no_internals(exc)


def test_motor_rated_power_outside_the_estimate_names_rated_power() -> None:
    exc = _motor(rated_power="1 W")
    assert exc.field == "motor.rated_power"
    assert "1 W" in str(exc) and "N·m" in str(exc) and "motor.rotor_inertia" in str(exc)
    _no_internals(exc)


def test_motor_defaults_outside_the_estimate_name_the_rotor_inertia() -> None:
    data = jindal()
    data["motor"] = {"law": "kloss"}
    data["sprockets"][0]["speed"] = "100 rpm"
    exc = refused(data)
    assert exc.field == "motor.rotor_inertia" and "sprockets[0].speed" in str(exc)
    _no_internals(exc)
    data["sprockets"][0]["speed"] = "1000 rpm"
    data["drive"]["power"] = "9 MW"
    exc = refused(data)
    assert exc.field == "motor.rotor_inertia" and "drive.power" in str(exc)
    _no_internals(exc)


def test_motor_within_the_estimate_or_with_its_inertia_is_accepted() -> None:
    data = jindal()
    data["motor"] = {"rated_speed": "100 rpm", "rotor_inertia": "0.01 kg*m^2"}
    assert drive_from_mapping(data, base_dir=EXAMPLES).motor is not None
    data["motor"] = {"rated_power": "3 kW", "rated_speed": "960 rpm"}
    assert drive_from_mapping(data, base_dir=EXAMPLES).motor is not None
    data["sprockets"][0]["speed"] = "100 rpm"  # a 10:1 reducer brings the motor into range
    data["sprockets"][0]["train"] = [{"kind": "gear", "ratio": 10.0, "name": "motor"}]
    data["motor"] = {"law": "kloss"}
    assert drive_from_mapping(data, base_dir=EXAMPLES).motor is not None


def test_unknown_sprocket_material_names_its_field() -> None:
    data = jindal()
    data["sprockets"][1]["material"] = "unobtainium"
    exc = refused(data)
    assert exc.field == "sprockets[1].material" and "'unobtainium'" in str(exc)


def test_unknown_train_material_names_its_field() -> None:
    data = jindal()
    data["sprockets"][1]["train"] = [{"kind": "shaft", "diameter": "30 mm", "length": "200 mm",
                                      "material": "unobtainium"}]
    exc = refused(data)
    assert exc.field == "sprockets[1].train[0].material"


def test_motor_error_on_the_command_line_is_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "motor.toml"
    path.write_text(JINDAL.read_text(encoding="utf-8") + '\n[motor]\nrated_speed = "100 rpm"\n',
                    encoding="utf-8")
    status = run(["analyze", str(path), "--quick"])
    out, err = capsys.readouterr()
    assert status == 2 and out == "" and err.startswith("error: motor.rated_speed: ")
    assert err.count("\n") == 1
