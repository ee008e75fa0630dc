"""The commands that write files: report, draw, simulate, afc and optimize. Each writes what
it says, and a bad output name is one line with exit status 2 and nothing written."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from chaindrive.display import fmt
from tests.conftest import EXAMPLES, cli_in_process

SEED = EXAMPLES / "seed_three_sprocket.toml"


#: The command run in this process: what these tests assert (what it prints and writes, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


@pytest.fixture(scope="module")
def short_seed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The seed example with a 0.1 s start-up (keeps the test fast)."""
    path = tmp_path_factory.mktemp("d") / "seed.toml"
    path.write_text(SEED.read_text(encoding="utf-8")
                    + '\n[dynamics]\nstartup_duration = "0.1 s"\n', encoding="utf-8")
    return path


def test_simulate_writes_the_histories(short_seed: Path, tmp_path: Path) -> None:
    out = tmp_path / "history.csv"
    proc = run_cli("simulate", str(short_seed), "-o", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    rows = list(csv.reader(out.read_text(encoding="utf-8").splitlines()))
    assert rows[0][0] == "time_s"
    assert len(rows[0]) == 1 + 3 + 3  # time, three span forces, three speeds
    last_time = float(rows[-1][0])
    assert abs(last_time - 0.1) < 1e-3
    peaks = [max(float(r[1 + i]) for r in rows[1:]) for i in range(3)]
    assert max(peaks) == pytest.approx(doc["max_force_n"], rel=1e-6)


def test_startup_times_stated_separately(short_seed: Path, tmp_path: Path) -> None:
    """The run-up and the decay after it are reported apart (settling = run-up + decay), and
    the share of samples with a slack span is the count of such rows in the histories; a
    record that ends while the driver still accelerates (0.1 s of a 0.29 s run-up) has
    neither, says so, and its k1 is marked as of a partial record."""
    out = tmp_path / "history.csv"
    doc = json.loads(run_cli("simulate", str(SEED), "-o", str(out), "--json").stdout)
    assert doc["settled"] and doc["runup_time_s"] is not None
    assert doc["runup_time_s"] + doc["decay_time_s"] == pytest.approx(doc["settling_time_s"])
    rows = [[float(v) for v in r] for r in csv.reader(
        out.read_text(encoding="utf-8").splitlines()[1:])]
    slack = sum(1 for r in rows if min(r[1:4]) <= 0.0)
    assert doc["slack_fraction"] == pytest.approx(slack / len(rows))
    assert doc["slack_samples"] == slack
    text = run_cli("simulate", str(SEED), "-o", str(tmp_path / "h2.csv")).stdout
    assert f"run-up {fmt(doc['runup_time_s'])} s, then the transient decays in " \
        f"{fmt(doc['decay_time_s'])} s" in text
    analysis = run_cli("analyze", str(SEED)).stdout.replace("\n", " ")
    assert f"run-up {fmt(doc['runup_time_s'])} s" in analysis
    assert "k1 " in analysis and "(cannot be verified" not in analysis
    short = json.loads(run_cli("simulate", str(short_seed), "-o", str(tmp_path / "s.csv"),
                               "--json").stdout)
    assert not short["settled"] and short["runup_time_s"] is None
    assert short["settling_time_s"] is None and short["decay_time_s"] is None
    text = run_cli("simulate", str(short_seed), "-o", str(tmp_path / "s2.csv")).stdout
    assert "the driver is not at its working speed within the simulated 0.1 s" in text
    analysis = run_cli("analyze", str(short_seed)).stdout.replace("\n", " ")
    assert "(cannot be verified: the start-up record (0.1 s) ends before" in analysis


def test_afc_writes_the_sweep(short_seed: Path, tmp_path: Path) -> None:
    out = tmp_path / "afc.csv"
    proc = run_cli("afc", str(short_seed), "-o", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.reader(out.read_text(encoding="utf-8").splitlines()))
    assert rows[0][:2] == ["driver_speed_rpm", "tooth_frequency_hz"]
    assert len(rows) == 1 + 2000  # issue 5: 2000 points from 10 % to 150 % of the speed
    assert float(rows[1][0]) == pytest.approx(30.0, rel=1e-6)
    assert float(rows[-1][0]) == pytest.approx(450.0, rel=1e-6)


@pytest.mark.parametrize("command", ["simulate", "afc"])
def test_wrong_suffix_writes_nothing(short_seed: Path, tmp_path: Path, command: str) -> None:
    out = tmp_path / "out.txt"
    proc = run_cli(command, str(short_seed), "-o", str(out))
    assert proc.returncode == 2
    assert proc.stderr.strip() == f"error: output: must end in .csv, got {str(out)!r}"
    assert not out.exists()


def test_report_and_drawing(short_seed: Path, tmp_path: Path) -> None:
    html = tmp_path / "report.html"
    assert run_cli("report", str(short_seed), "-o", str(html)).returncode == 0
    text = html.read_text(encoding="utf-8")
    assert "<html" in text and "Contour geometry" in text
    dxf = tmp_path / "layout.dxf"
    assert run_cli("draw", str(short_seed), "-o", str(dxf)).returncode == 0
    assert dxf.read_text(encoding="utf-8", errors="replace").startswith("  0\nSECTION")


def test_optimize_json(tmp_path: Path) -> None:
    """The optimisation's JSON document and files. A smaller search of the example (4
    designs × 2 generations instead of 16 × 10; a quarter of the test's time) still
    writes every part asserted: the document's keys and units, one TOML per Pareto
    design and the report, whatever the size of the Pareto set."""
    text = (EXAMPLES / "eight_sprocket_optimize.toml").read_text(encoding="utf-8")
    assert "population = 16\n" in text and "generations = 10\n" in text
    small = tmp_path / "design" / "opt.toml"
    small.parent.mkdir()
    small.write_text(text.replace("population = 16\n", "population = 4\n")
                     .replace("generations = 10\n", "generations = 2\n"), encoding="utf-8")
    out = tmp_path / "out"
    proc = run_cli("optimize", str(small), "--json", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["pareto"]
    for p in doc["pareto"]:
        assert {"objectives", "constraints_ok", "design"} <= set(p)
    # every objective names its unit; a price is in the cost model's currency
    # (src/chaindrive/data/cost.toml)
    assert doc["objective_units"] == {"cost": "EUR", "mass": "kg", "volume": "m^3",
                                      "chain_length": "m"}
    # one TOML per Pareto design, and the report of the first with the Pareto set and front
    assert len(doc["files"]) == len(doc["pareto"]) + 1
    assert all(Path(f).exists() for f in doc["files"])
    report = Path(doc["files"][-1]).read_text(encoding="utf-8")
    assert '<section id="synthesis">' in report
    assert 'data-plot="pareto_front"' in report
    no_problem = run_cli("optimize", str(SEED))
    assert no_problem.returncode == 2
    assert no_problem.stderr.startswith("error: ")


def test_simulate_prints_in_the_unit_system(short_seed: Path, tmp_path: Path) -> None:
    """`simulate --units us` prints the largest span force in lbf: the JSON's newtons over
    4.4482216152605 N/lbf (the exact definition, NIST SP 811); the CSV keeps SI."""
    doc = json.loads(run_cli("simulate", str(short_seed), "-o", str(tmp_path / "a.csv"),
                             "--json").stdout)
    us = run_cli("simulate", str(short_seed), "-o", str(tmp_path / "b.csv"), "--units", "us")
    assert us.returncode == 0, us.stderr
    assert f"max span force {fmt(doc['max_force_n'] / 4.4482216152605)} lbf" in us.stdout
    assert "_n," in (tmp_path / "b.csv").read_text(encoding="utf-8").splitlines()[0] + ","
