"""No NaN or infinity is ever printed, written or reported (docs/reliability.md §1): the
gate of :mod:`chaindrive.io.finite` at every output, and the ranges that refuse the values
that made them (each a case of the fuzzer, its expected line the loader's wording)."""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import tomli_w

from chaindrive.analysis import Analysis
from chaindrive.cli import run
from chaindrive.errors import CatalogError, DesignError
from chaindrive.io.design import drive_from_mapping
from chaindrive.io.finite import NonFiniteError, check_document, check_rows
from tests.conftest import EXAMPLES

SEED = EXAMPLES / "seed_three_sprocket.toml"
JINDAL = tomllib.loads((EXAMPLES / "two_sprocket_jindal.toml").read_text(encoding="utf-8"))


@pytest.fixture(autouse=True)
def logs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    logs = tmp_path / "logs"
    monkeypatch.setenv("CHAINDRIVE_LOG_DIR", str(logs))
    return logs


def test_the_gate_names_the_first_non_finite_number() -> None:
    check_document({"a": [1.0, 2], "b": {"c": "nan"}})  # text is not a number
    with pytest.raises(NonFiniteError, match=r"nan at a\.b\[1\]"):
        check_document({"a": {"b": [0.0, math.nan]}})
    with pytest.raises(NonFiniteError, match=r"inf at x\[2\]"):
        check_document({"x": np.array([0.0, 1.0, np.inf])})
    rows = np.array([[0.0, 1.0], [0.1, -np.inf]])
    with pytest.raises(NonFiniteError, match=r"-inf at h\.csv, row 2, column 'force_n'"):
        check_rows("h.csv", ["time_s", "force_n"], rows)
    check_rows("h.csv", ["time_s", "force_n"], np.zeros((3, 2)))


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def _with_nan(monkeypatch: pytest.MonkeyPatch, where: str) -> None:
    real = Analysis.to_dict

    def with_nan(self: Analysis) -> dict[str, Any]:
        doc = real(self)
        doc["geometry"][where] = math.inf
        return doc

    monkeypatch.setattr(Analysis, "to_dict", with_nan)


@pytest.mark.parametrize("argv", [["analyze", "--quick"], ["analyze", "--quick", "--json"],
                                  ["report", "-o", "OUT.html"], ["draw", "-o", "OUT.dxf"]])
def test_a_non_finite_result_is_one_line_and_nothing_written(
        argv: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str], logs: Path) -> None:
    _with_nan(monkeypatch, "chain_length_mm")
    status = run([argv[0], str(SEED), *(a.replace("OUT", str(tmp_path / "out"))
                                        for a in argv[1:])])
    out, err = capsys.readouterr()
    line = _one_line(err)
    assert status == 1 and out == ""
    assert line.startswith("error: the computation did not converge (inf at "
                           "geometry.chain_length_mm)"), line
    assert "Traceback" in next(logs.glob("crash-*.log")).read_text(encoding="utf-8")
    assert not list(tmp_path.glob("out*")) and not list(tmp_path.glob(".out*"))


def test_simulate_never_writes_a_non_finite_row(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    """A start-up history with a NaN (as the diverging start-ups wrote 16 273 rows of) is
    one line naming the row and the column, and no CSV."""
    import chaindrive.cli as cli

    real = cli.np.column_stack

    def poisoned(arrays: Any) -> Any:
        table = np.array(real(arrays), dtype=float)
        if table.shape[0] > 10:  # the history, not a small table built on the way
            table[5, 1] = math.nan
        return table

    monkeypatch.setattr(cli.np, "column_stack", poisoned)
    out = tmp_path / "h.csv"
    status = run(["simulate", str(SEED), "-o", str(out)])
    line = _one_line(capsys.readouterr().err)
    assert status == 1 and not out.exists() and not list(tmp_path.glob(".h*"))
    assert "did not converge (nan at h.csv, row 6, column 'span_" in line, line


def _design(section: str, key: str, value: Any, train: bool = False) -> dict[str, Any]:
    data = copy.deepcopy(JINDAL)
    if train:
        data["sprockets"][1]["train"] = [{"kind": "gear", "name": "machine", "ratio": 2.0,
                                          "inertia": "0.1 kg*m^2"}]
        data["sprockets"][1]["train"][0][key] = value
    else:
        data.setdefault(section, {})[key] = value
    return data


@pytest.mark.parametrize(("section", "key", "value", "train", "fragment"), [
    # a Kloss critical slip of 1e-300 divided the torque by zero
    ("dynamics", "critical_slip", 1e-300, False, "≥ 0.001 and ≤ 1"),
    ("motor", "critical_slip", 5e-324, False, "subnormal"),
    # a gear efficiency of 5e-324 overflowed the reduced load
    ("", "efficiency", 5e-324, True, "≥ 0.01 and ≤ 1"),
    ("", "efficiency", 1e-3, True, "≥ 0.01 and ≤ 1"),
    # a damping ratio of 5e-324 gave a modal ζ of -1.8e-30
    ("dynamics", "damping_ratio", 5e-324, False, "0, or ≥ 0.0001"),
    ("dynamics", "damping_ratio", 1e-9, False, "0, or ≥ 0.0001"),
    # a train node of 1.2e-300 kg·m² divided by zero, 5e-324 failed the eigensolver
    ("", "inertia", "1.2e-300 kg*m^2", True, "0, or ≥ 1e-08"),
])
def test_values_that_broke_the_computation_are_refused(section: str, key: str, value: Any,
                                                       train: bool, fragment: str) -> None:
    with pytest.raises(DesignError) as info:
        drive_from_mapping(_design(section, key, value, train))
    assert fragment in str(info.value) and key in info.value.field
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(("section", "key", "value", "train"), [
    ("dynamics", "damping_ratio", 0.0, False),  # an undamped model stays allowed
    ("dynamics", "critical_slip", 0.001, False),
    ("", "efficiency", 0.01, True),
    ("", "inertia", "0 kg*m^2", True),  # a massless node
])
def test_the_edges_of_the_narrowed_ranges_are_allowed(section: str, key: str, value: Any,
                                                      train: bool) -> None:
    drive_from_mapping(_design(section, key, value, train))


def test_the_subnormal_damping_ratio_is_one_line_exit_2(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    path = tmp_path / "d.toml"
    path.write_text(tomli_w.dumps(_design("dynamics", "damping_ratio", 5e-324)),
                    encoding="utf-8")
    assert run(["analyze", str(path), "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and _one_line(err).startswith("error: dynamics.damping_ratio: must be")


# --- user catalogue rows: one chain's dimensions ------------------------------------------

HEADER = ("designation,pitch_mm,roller_diameter_mm,pin_diameter_mm,inner_width_mm,"
          "plate_depth_mm,transverse_pitch_mm,breaking_load_kN,mass_kg_m,strands\n")
ROW = ["X 1", "12.7", "8.51", "4.45", "7.75", "11.8", "13.92", "18.2", "0.7", "1"]


def _catalogue(tmp_path: Path, **cells: str) -> dict[str, Any]:
    columns = HEADER.strip().split(",")
    row = [cells.get(c, v) for c, v in zip(columns, ROW, strict=True)]
    (tmp_path / "mine.csv").write_text(HEADER + ",".join(row) + "\n", encoding="utf-8")
    data = copy.deepcopy(JINDAL)
    data["chain"] = {"designation": "X 1", "catalog": "mine.csv"}
    return data


@pytest.mark.parametrize(("cells", "column", "fragment"), [
    # a roller larger than the pitch gave negative tip and root diameters
    ({"roller_diameter_mm": "13.6"}, "roller_diameter_mm", "smaller than the pitch 12.7 mm"),
    # a 1 mm pitch was accepted with the rollers of a 12.7 mm chain
    ({"pitch_mm": "1"}, "pitch_mm", "plausible range 5 to 500"),
    ({"plate_depth_mm": "8"}, "plate_depth_mm", "larger than the roller diameter 8.51 mm"),
    ({"transverse_pitch_mm": "7"}, "transverse_pitch_mm", "larger than the inner width"),
])
def test_a_catalogue_row_must_be_one_chain(tmp_path: Path, cells: dict[str, str], column: str,
                                           fragment: str) -> None:
    with pytest.raises(CatalogError) as info:
        drive_from_mapping(_catalogue(tmp_path, **cells), tmp_path)
    text = str(info.value)
    assert f"row 1 (line 2), column '{column}'" in text and fragment in text, text
    assert "\n" not in text


def test_a_consistent_catalogue_row_is_read(tmp_path: Path) -> None:
    drive = drive_from_mapping(_catalogue(tmp_path), tmp_path)
    assert drive.chain.spec.roller_diameter == pytest.approx(8.51e-3)


# --- work bounded -----------------------------------------------------------------------------

def test_the_start_up_budget_bounds_a_small_model_in_time() -> None:
    """The budget counted only the matrix products of a step (192 operations for the
    4-coordinate model of a two-sprocket drive): it let a start-up at 30 000 rpm run 20.8
    million steps, 19 s of kernel measured at 0.9 µs a step, past a minute on a loaded
    machine. With what a step costs besides (STEP_OVERHEAD) the budget allows it about 4 s."""
    from chaindrive.dynamics.transient.startup import WORK_BUDGET, work_estimate

    per_step = work_estimate(4, 1) - work_estimate(4, 0)
    steps = (WORK_BUDGET - work_estimate(4, 0)) / per_step
    assert steps * 0.9e-6 < 5.0  # [s] at the measured cost of a step
    assert work_estimate(4, 20_832_612) > WORK_BUDGET  # the 20.8 million steps: refused


def test_the_page_never_shows_a_non_finite_analysis(monkeypatch: pytest.MonkeyPatch) -> None:
    from chaindrive import examples
    from chaindrive.app.runs import full_analysis
    from chaindrive.app.worker import RunLimitError

    _with_nan(monkeypatch, "chain_length_mm")
    with pytest.raises(RunLimitError) as info:
        full_analysis(examples.load("seed_three_sprocket"))
    assert str(info.value).startswith("The dynamic analysis did not converge (inf at "
                                      "geometry.chain_length_mm)")
