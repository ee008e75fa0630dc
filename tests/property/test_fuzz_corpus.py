"""The held-out corpus: the designs on which the fuzzer of docs/reliability.md §7 once broke
the promise, each run through its command as the fuzzer runs it (``chaindrive.cli.run``,
in this process) and held to the same promise: exit 0 with finite JSON or a whole output
file holding no NaN or infinity, or exit 2 with one line ``error: …`` and nothing written;
within bounded time.

The designs (tests/fixtures/fuzz_corpus/) are the bundled examples with the one value that
broke them: a driver at 1 rpm, a critical slip of 1e-300, a gear efficiency and a damping
ratio of 5e-324, a train node of 1e-300 kg·m² or a stiff shaft on a 1e-9 kg·m² node, a
user catalogue with a roller larger than the pitch or a 1 mm pitch, a driver at 30 000 rpm
with 1 W. The start-ups that once diverged at 1 rpm and on a stiff light train (the
integrator's fault, docs/reliability.md §7a) now run to a finite result like the others."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from tests.conftest import ROOT
from tests.property.cli_run import Overtime, run_in_time

CORPUS = ROOT / "tests" / "fixtures" / "fuzz_corpus"
#: A case running longer than this breaks the promise of bounded time [s].
CASE_SECONDS = 60

CASES = [
    ("eight_sprocket_1rpm", ["analyze", "--json"]),
    ("eight_sprocket_1rpm", ["simulate", "-o", "OUT.csv"]),
    ("eight_sprocket_1rpm", ["report", "-o", "OUT.html"]),
    ("twenty_four_sprocket_1rpm", ["simulate", "-o", "OUT.csv"]),
    ("stiff_light_train_1e-8", ["simulate", "-o", "OUT.csv"]),
    ("stiff_light_train", ["simulate", "-o", "OUT.csv"]),
    ("kloss_slip_1e-300", ["analyze", "--json"]),
    ("motor_slip_1e-300", ["analyze", "--json"]),
    ("gear_efficiency_5e-324", ["analyze", "--json"]),
    ("damping_5e-324", ["analyze", "--json"]),
    ("train_inertia_1e-300", ["analyze", "--json"]),
    ("catalogue_roller_over_pitch", ["analyze", "--json"]),
    ("catalogue_roller_over_pitch", ["draw", "-o", "OUT.dxf"]),
    ("catalogue_pitch_1mm", ["analyze", "--json"]),
    ("fast_30000rpm_1W", ["report", "-o", "OUT.html"]),
    ("fast_30000rpm_1W", ["simulate", "-o", "OUT.csv"]),
]



@pytest.fixture(autouse=True)
def _logs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("CHAINDRIVE_LOG_DIR", str(tmp_path / "logs"))


def _reject(constant: str) -> None:
    raise ValueError(f"{constant} in the JSON")


def _run_case(name: str, command: list[str], tmp_path: Path
              ) -> tuple[int, str, str, list[str], list[str], Path, list[str]]:
    """Run one case; (status, stdout, stderr, files before, files after, work dir, argv)."""
    work = tmp_path / "case"
    work.mkdir()
    for f in CORPUS.glob("*.csv"):
        shutil.copy(f, work / f.name)
    design = work / f"{name}.toml"
    shutil.copy(CORPUS / f"{name}.toml", design)
    before = sorted(p.name for p in work.iterdir())
    argv = [command[0], str(design), *(a.replace("OUT", str(work / "out")) for a in command[1:])]
    try:
        status, stdout, stderr = run_in_time(argv, CASE_SECONDS)
    except Overtime:
        pytest.fail(f"{argv} ran past {CASE_SECONDS} s")
    return status, stdout, stderr, before, sorted(
        p.name for p in work.iterdir()), work, argv


@pytest.mark.parametrize(("name", "command"),
                         [p.values if hasattr(p, "values") else p for p in CASES])
def test_no_case_prints_or_writes_a_non_finite_number(name: str, command: list[str],
                                                      tmp_path: Path) -> None:
    """Every case, the diverging start-ups included: the promise, or one line saying the
    computation did not converge (exit 1) and nothing written."""
    status, out, err, before, after, _, argv = _run_case(name, command, tmp_path)
    if status == 1:
        lines = err.splitlines()
        assert len(lines) == 1 and lines[0].startswith(
            "error: the computation did not converge ("), (argv, err)
        assert out == "" and after == before, argv
    else:
        assert status in (0, 2), (argv, status, err)


@pytest.mark.parametrize(("name", "command"), CASES)
def test_the_promise_holds_on_the_corpus(name: str, command: list[str], tmp_path: Path) -> None:
    status, out_text, err_text, before, after, work, argv = _run_case(name, command, tmp_path)
    lines = err_text.splitlines()
    where = f"{argv}: status {status}, stderr {err_text[:600]!r}"
    assert status in (0, 2), where
    if status == 2:
        assert len(lines) == 1 and lines[0].startswith("error: "), where
        assert out_text == "" and after == before, where
        return
    if "--json" in command:
        json.loads(out_text, parse_constant=_reject)
        assert lines == [], where
        return
    written = work / Path(command[-1]).name.replace("OUT", "out")
    assert written.stat().st_size > 0 and not [n for n in after if ".tmp" in n], where
    if written.suffix == ".csv":
        text = written.read_text(encoding="utf-8").lower()
        assert "nan" not in text and "inf" not in text, where
