"""``chaindrive robust``: the JSON document of a design file's robust study, its report,
and a mistake in ``[uncertainty]`` as one line naming the field (exit status 2)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, cli_in_process

pytestmark = pytest.mark.concurrency  # the Dask study starts a local cluster

SEED = (EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8")


#: The command run in this process: what these tests assert (the JSON document, the tables,
#: the one-line mistakes and their status) is the command's, not the process's.
run_cli = cli_in_process


def test_robust_json_and_report(tmp_path: Path) -> None:
    design = tmp_path / "seed.toml"
    design.write_text(SEED + "\n[uncertainty]\nsamples = 8\nreplicates = 2\n"
                      "sensitivity_samples = 4\nsensitivity_budget = 48\n"
                      '\n[dynamics]\nstartup_duration = "0.05 s"\n',  # a short report
                      encoding="utf-8")
    report = tmp_path / "seed.html"
    proc = run_cli("robust", str(design), "--json", "--report", str(report))
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["reliability"]["samples"] == 8
    assert doc["life"]["allowable_elongation"] == 0.015      # fixed centres [DiamondChainWear]
    assert doc["report"] == str(report.resolve())
    assert "Life and reliability" in report.read_text(encoding="utf-8")
    tables = run_cli("robust", str(design), "--modal", "--samples", "16")
    assert tables.returncode == 0, tables.stderr
    # the states counted as the failures column counts them: points × wear states
    assert ("Probability of failure (modal path, 16 sampled points × 8 wear states = 128 "
            "states" in tables.stdout)
    assert "held at nominal (modal path): chain length: at nominal" in tables.stdout
    assert "averaged over: the life: 8 wear states" in tables.stdout


def test_robust_mistake_is_one_line(tmp_path: Path) -> None:
    design = tmp_path / "bad.toml"
    design.write_text(SEED + '\n[uncertainty]\nwear = "old"\n', encoding="utf-8")
    proc = run_cli("robust", str(design))
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.strip().startswith("error: uncertainty.wear: must be one of")
    assert len(proc.stderr.strip().splitlines()) == 1
    proc = run_cli("robust", str(EXAMPLES / "seed_three_sprocket.toml"),
                   "--sensitivity-budget", "8")
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.strip().startswith("error: --sensitivity-budget:")
    assert len(proc.stderr.strip().splitlines()) == 1


def test_robust_optimisation_runs_on_dask_and_resumes(tmp_path: Path) -> None:
    from chaindrive.synthesis.studies import EVALUATIONS, StudyStore

    design = tmp_path / "robust.toml"
    design.write_text(SEED + """
[uncertainty]
replicates = 2
wear_states = 2

[optimize]
objectives = ["cost", "mass"]
[optimize.teeth]
S3 = [11, 25]
[optimize.position.S3]
y = ["60 mm", "260 mm"]
[optimize.solver]
population = 4
generations = 1
seed = 2
[optimize.robust]
samples = 64
chance = { resonance_margin = 0.05 }
""", encoding="utf-8")
    url = f"sqlite:///{tmp_path / 'study.db'}"
    first = run_cli("optimize", str(design), "--json", "--db", url)
    assert first.returncode == 0, first.stderr
    doc = json.loads(first.stdout)
    assert "P(resonance_margin)" in doc["start"]["constraints"]
    assert all(p["constraints"]["P(resonance_margin)"] <= 0 for p in doc["pareto"])
    store = StudyStore(url)
    with store.engine.connect() as con:
        stored = len(con.execute(EVALUATIONS.select()).fetchall())
    assert stored == doc["evaluations"] == 4
    again = run_cli("optimize", str(design), "--json", "--db", url)
    assert again.returncode == 0, again.stderr
    assert json.loads(again.stdout)["pareto"] == doc["pareto"]
    with store.engine.connect() as con:
        assert len(con.execute(EVALUATIONS.select()).fetchall()) == stored  # resumed
