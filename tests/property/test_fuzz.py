"""Fuzzing the promise of docs/reliability.md: whatever a design file holds, a command ends
with exit 0 and finite JSON (or its output file written whole), or with exit 2 and one line
on stderr and nothing written — in bounded time, never a traceback.

Hypothesis mutates the bundled examples: the type of a value, its unit, its magnitude (10^±40
and signs), the structure (keys removed, unknown keys, sprockets dropped or repeated, deep
nesting), the rows of a user catalogue the design names, and raw bytes of the file. Each case
runs in this process through the command line's own safety net (``chaindrive.cli.run``), so
hundreds of cases take about a minute.

Profiles: ``make test`` runs :data:`SHORT` cases, the same ones every time (derandomised);
``make fuzz`` runs ``CHAINDRIVE_FUZZ_EXAMPLES`` (default 2000) new random cases.
"""

from __future__ import annotations

import copy
import json
import os
import tomllib
from pathlib import Path
from typing import Any

import pytest
import tomli_w
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from chaindrive.catalog import find_chain
from tests.conftest import EXAMPLES
from tests.property.cli_run import Overtime, run_in_time

SHORT = 200
EXAMPLES_N = int(os.environ.get("CHAINDRIVE_FUZZ_EXAMPLES", SHORT))
LONG = "CHAINDRIVE_FUZZ_EXAMPLES" in os.environ
#: A case running longer than this fails the promise of bounded time [s] (generous: the
#: slowest example takes about a second).
CASE_SECONDS = 120

DESIGNS = {name: tomllib.loads((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))
           for name in ("seed_three_sprocket", "two_sprocket_jindal", "twenty_four_sprocket",
                        "eight_sprocket", "reduction_drive_bhandari")}
UNITS = ["mm", "m", "km", "in", "ft", "parsec", "rpm", "RPM", "1/min", "min⁻¹", "Hz", "rad/s",
         "kW", "kw", "W", "hp", "kg*m^2", "kg", "N", "lbf", "deg", "rad", "s", "ms", "h",
         "m/s", "", "furlongz", "mm**2", "1/s", "°", "mm mm", "%", "**", "kg*m^2*s"]
TEXTS = ["", " ", "x", "0", "-1", "1e999", "nan", "inf", "true", "\n", "a\nb", '"', "\\",
         "ÿ", "²", "1,5 mm", "1 2 mm", "9**9**9 mm", "1" * 400 + " mm", "🙂", "\x00"]
HEADER = ("designation,pitch_mm,roller_diameter_mm,pin_diameter_mm,inner_width_mm,"
          "plate_depth_mm,transverse_pitch_mm,breaking_load_kN,mass_kg_m,strands")



def _catalog_row(designation: str) -> list[str]:
    c = find_chain("ISO 606 08B-1")
    return [designation, f"{c.pitch * 1e3:g}", f"{c.roller_diameter * 1e3:g}",
            f"{c.pin_diameter * 1e3:g}", f"{c.inner_width * 1e3:g}",
            f"{c.plate_depth * 1e3:g}", f"{c.transverse_pitch * 1e3:g}",
            f"{c.breaking_load / 1e3:g}", f"{c.mass_per_length:g}", "1"]


# --- mutations ------------------------------------------------------------------------------

def _leaves(node: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    if isinstance(node, dict):
        return [p for k, v in node.items() for p in _leaves(v, (*path, k))] or [path]
    if isinstance(node, list):
        return [p for i, v in enumerate(node) for p in _leaves(v, (*path, i))] or [path]
    return [path]


def _set(root: Any, path: tuple[Any, ...], value: Any) -> None:
    node = root
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value


def _get(root: Any, path: tuple[Any, ...]) -> Any:
    node = root
    for key in path:
        node = node[key]
    return node


@st.composite
def _value(draw: st.DrawFn, old: Any) -> Any:
    """A new value for a leaf: another type, another unit or magnitude, odd text."""
    kind = draw(st.sampled_from(["mild"] * 5 + ["type", "unit", "magnitude", "text", "deep"]))
    if kind == "type":
        return draw(st.one_of(st.integers(-10**30, 10**30), st.floats(allow_nan=True),
                              st.booleans(), st.lists(st.integers(), max_size=3),
                              st.dictionaries(st.text(max_size=3), st.integers(), max_size=2)))
    if kind == "deep":  # written into the text after tomli-w (which cannot nest 3000 deep)
        return f"@@DEEP{draw(st.sampled_from([2, 50, 3000]))}@@"
    if kind == "text":
        return draw(st.one_of(st.sampled_from(TEXTS), st.text(max_size=20)))
    number, _, unit = str(old).partition(" ")
    try:
        base = float(number)
    except ValueError:
        base = 1.0
    if kind == "unit":
        return f"{base:g} {draw(st.sampled_from(UNITS))}".strip()
    if kind == "mild":  # a plausible edit: the analysis should run
        if isinstance(old, bool) or not isinstance(old, int | float | str):
            return old
        factor = draw(st.sampled_from([0.8, 0.95, 1.05, 1.25]))
        if isinstance(old, int):
            return max(int(old * factor), 1) if old > 1 else old
        if isinstance(old, float):
            return old * factor
        return f"{base * factor:g} {unit}".strip() if unit else old
    exponent = draw(st.sampled_from([-40, -12, -6, -3, -1, 0, 1, 3, 6, 12, 40]))
    sign = draw(st.sampled_from([1, -1, 0]))
    magnitude = sign * (base or 1.0) * 10.0**exponent
    return f"{magnitude:g} {unit}".strip() if isinstance(old, str) else magnitude


@st.composite
def designs(draw: st.DrawFn) -> tuple[bytes, str | None]:
    """(bytes of a mutated design file, text of the user catalogue it names or None)."""
    data = copy.deepcopy(DESIGNS[draw(st.sampled_from(sorted(DESIGNS)))])
    catalog = None
    if draw(st.integers(0, 4)) == 0:  # a design on a catalogue of its own, rows mutated
        rows = [_catalog_row("FUZZ 1"), _catalog_row("FUZZ 2")]
        for _ in range(draw(st.integers(0, 3))):
            r, c = draw(st.integers(0, 1)), draw(st.integers(1, len(rows[0]) - 1))
            rows[r][c] = draw(st.one_of(st.sampled_from(
                ["", "0", "-1", "1e300", "1e-300", "nan", "²", '"12', "x" * 200_000, "4,5"]),
                st.floats(allow_nan=True).map(repr)))
        catalog = HEADER + "\n" + "\n".join(",".join(r) for r in rows) + "\n"
        data["chain"] = {"designation": "FUZZ 1", "catalog": "CATALOG"}
    if draw(st.integers(0, 2)) == 0:  # optional inputs no example gives, mutated like the rest
        data.setdefault("chain", {}).update(sag=0.02, link_stiffness="1.7e8 N/m")
    for _ in range(draw(st.integers(0, 3))):
        leaves = _leaves(data)
        path = draw(st.sampled_from(leaves))
        action = draw(st.sampled_from(["value"] * 6 + ["drop", "unknown", "rows"]))
        if action == "value" and path:
            _set(data, path, draw(_value(_get(data, path))))
        elif action == "drop" and path:
            parent = _get(data, path[:-1])
            del parent[path[-1]]
        elif action == "unknown":
            data[draw(st.sampled_from(["drive", "chian", "x\ny"]))] = {"teeht": 1}
        elif action == "rows" and isinstance(data.get("sprockets"), list) and data["sprockets"]:
            rows = data["sprockets"]
            data["sprockets"] = draw(st.sampled_from([rows[:1], rows * 2, rows[::-1], []]))
    try:
        toml = tomli_w.dumps(data)
    except (TypeError, ValueError):  # what TOML cannot hold: its repr, as raw text
        toml = repr(data)
    for depth in (2, 50, 3000):
        toml = toml.replace(f'"@@DEEP{depth}@@"', "[" * depth + "1" + "]" * depth)
    text = toml.encode("utf-8", "replace")
    if draw(st.integers(0, 9)) == 0:  # raw byte edits
        buf = bytearray(text)
        for _ in range(draw(st.integers(1, 4))):
            at = draw(st.integers(0, max(len(buf) - 1, 0)))
            edit = draw(st.sampled_from(["replace", "delete", "insert"]))
            if edit == "replace" and buf:
                buf[at] = draw(st.integers(0, 255))
            elif edit == "delete":
                del buf[at:at + draw(st.integers(1, 20))]
            else:
                buf[at:at] = draw(st.binary(min_size=1, max_size=8))
        text = bytes(buf)
    return text, catalog


COMMANDS = st.sampled_from([["analyze", "--json"]] * 6 + [["analyze", "--json", "--quick"]] * 2
                           + [["select", "--json"], ["draw", "-o", "OUT.dxf"],
                              ["simulate", "-o", "OUT.csv"]])


def _reject(constant: str) -> None:
    raise ValueError(f"{constant} in the JSON")


def _check_case(tmp: Path, design: bytes, catalog: str | None, command: list[str],
                case: int) -> None:
    work = tmp / f"case{case}"
    work.mkdir()
    path = work / "design.toml"
    if catalog is not None:
        (work / f"cat{case}.csv").write_text(catalog, encoding="utf-8")
        design = design.replace(b"CATALOG", f"cat{case}.csv".encode())
    path.write_bytes(design)
    before = sorted(p.name for p in work.iterdir())
    argv = [command[0], str(path), *[a.replace("OUT", str(work / "out")) for a in command[1:]]]
    try:
        status, stdout, stderr = run_in_time(argv, CASE_SECONDS)
    except Overtime:
        pytest.fail(f"{argv} ran past {CASE_SECONDS} s on:\n{design[:2000]!r}")
    lines = stderr.splitlines()
    where = f"{argv}: status {status}, stderr {stderr[:600]!r}, design {design[:1500]!r}"
    assert status in (0, 2), where
    event(f"{command[0]}: exit {status}")
    after = sorted(p.name for p in work.iterdir())
    if status == 2:
        assert len(lines) == 1 and lines[0].startswith("error: "), where
        assert stdout == "", where
        assert after == before, where  # nothing written
        return
    if "--json" in command:
        json.loads(stdout, parse_constant=_reject)  # finite JSON
        assert lines == [], where
    else:
        written = work / Path(command[-1].replace("OUT", "out")).name
        assert written.stat().st_size > 0, where
        assert not [n for n in after if ".tmp" in n], where
        if written.suffix == ".csv":  # no NaN or infinity written
            text = written.read_text(encoding="utf-8").lower()
            assert "nan" not in text and "inf" not in text, where


@pytest.fixture(autouse=True)
def _logs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("CHAINDRIVE_LOG_DIR", str(tmp_path / "logs"))


@settings(max_examples=EXAMPLES_N, derandomize=not LONG, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                 HealthCheck.function_scoped_fixture])
@given(case=designs(), command=COMMANDS)
def test_the_promise_holds_for_mutated_designs(tmp_path: Path,
                                               case: tuple[bytes, str | None],
                                               command: list[str]) -> None:
    counter = getattr(test_the_promise_holds_for_mutated_designs, "_n", 0) + 1
    test_the_promise_holds_for_mutated_designs._n = counter  # type: ignore[attr-defined]
    _check_case(tmp_path, case[0], case[1], command, counter)
