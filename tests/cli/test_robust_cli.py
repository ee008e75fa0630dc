"""``chaindrive robust``: the JSON document of a design file's robust study, its report,
and a mistake in ``[uncertainty]`` as one line naming the field (exit status 2)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # each test runs the command in a subprocess

SEED = (EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8")


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False)


def test_robust_json_and_report(tmp_path: Path) -> None:
    design = tmp_path / "seed.toml"
    design.write_text(SEED + "\n[uncertainty]\nsamples = 8\nreplicates = 2\n"
                      "sensitivity_samples = 4\n"
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
    assert "Probability of failure (16 states, modal path" in tables.stdout


def test_robust_mistake_is_one_line(tmp_path: Path) -> None:
    design = tmp_path / "bad.toml"
    design.write_text(SEED + '\n[uncertainty]\nwear = "old"\n', encoding="utf-8")
    proc = run_cli("robust", str(design))
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.strip().startswith("error: uncertainty.wear: must be one of")
    assert len(proc.stderr.strip().splitlines()) == 1
