"""What the command line prints for people: TOML table names and user text printed as
written (never read as rich markup), the schema by section with examples that fit each
field, numbers without round-off, and the US customary unit system (1 in = 25.4 mm exactly
[NIST-SP811])."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from chaindrive.display import fmt
from tests.conftest import EXAMPLES, cli_in_process

SEED = EXAMPLES / "seed_three_sprocket.toml"


@pytest.fixture(autouse=True)
def wide_plain_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """200 columns and no colour asked for, as in a clean environment with ``COLUMNS=200``
    (rich and typer read these when a command makes its console)."""
    monkeypatch.setenv("COLUMNS", "200")
    for name in ("FORCE_COLOR", "TTY_COMPATIBLE", "TTY_INTERACTIVE", "TERMINAL_WIDTH"):
        monkeypatch.delenv(name, raising=False)


#: The command run in this process: what these tests assert (what it prints, its exit
#: status) is the command's, not the process's.
run_cli = cli_in_process


def run_process(*args: str) -> subprocess.CompletedProcess[str]:
    """The command run as ``python -m chaindrive`` in a new interpreter with a clean
    environment of 200 columns (the entry point)."""
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False, env={"COLUMNS": "200", "PATH": "/usr/bin"})


def test_schema_by_section_with_titles_articles_and_examples() -> None:
    proc = run_cli("schema")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    for title in ("[drive]", "[chain]", "[[sprockets]]", "[dynamics]"):
        assert re.search(rf"^{re.escape(title)}\s*$", out, re.M), title
    assert "[]" not in out.replace("[[sprockets]]", "")
    assert "a angle" not in out and "a inertia" not in out
    assert "an angle" in out and "an inertia" in out
    duration = next(line for line in out.splitlines() if "startup_duration" in line)
    assert "2400 h" not in duration and "1 s" in duration


@pytest.mark.concurrency  # the entry point itself, in a subprocess (a cheap command: --help)
def test_help_names_the_optimize_table() -> None:
    proc = run_process("optimize", "--help")
    assert proc.returncode == 0
    assert "with an [optimize] table" in " ".join(proc.stdout.split())


def test_markup_in_a_name_prints_as_written(tmp_path: Path) -> None:
    text = SEED.read_text(encoding="utf-8").replace(
        'name = "Seed three-sprocket contour"', 'name = "[/bold] x [red]drive"')
    path = tmp_path / "d.toml"
    path.write_text(text, encoding="utf-8")
    proc = run_cli("analyze", str(path), "--quick")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines()[0].startswith("[/bold] x [red]drive — chain")
    full = run_cli("analyze", str(SEED))  # the dynamic safety line names [k]
    assert full.returncode == 0, full.stderr
    assert "(allowable [k] 2.5)" in full.stdout


def test_numbers_without_round_off_and_us_units() -> None:
    si = run_cli("analyze", str(SEED), "--quick")
    assert si.returncode == 0, si.stderr
    assert not re.search(r"\de-1\d", si.stdout)  # no -6.4e-16 style round-off
    assert "x, mm" in si.stdout
    us = run_cli("analyze", str(SEED), "--quick", "--units", "us")
    assert us.returncode == 0, us.stderr
    assert "x, in" in us.stdout and "x, mm" not in us.stdout
    s1 = next(line for line in us.stdout.splitlines() if line.startswith("│ S1 "))
    assert "53.7" in s1  # x = 1364 mm = 53.70 in
    assert "tension, lbf" in us.stdout
    bad = run_cli("analyze", str(SEED), "--quick", "--units", "imperial")
    assert bad.returncode == 2
    assert bad.stderr.strip() == "error: units: must be SI or US, got 'imperial'"


def test_dynamic_loads_in_the_unit_system() -> None:
    """With --units us the steady and start-up span forces are in lbf (1 lbf = 4.4482216152605
    N, exact [NIST-SP811]), the same figures as the JSON's newtons."""
    doc = json.loads(run_cli("analyze", str(SEED), "--json").stdout)
    us = run_cli("analyze", str(SEED), "--units", "us").stdout.replace("\n", " ")
    steady = max(doc["dynamics"]["steady"]["span_dynamic_load_n"]) / 4.4482216152605
    peak = doc["dynamics"]["startup"]["max_force_n"] / 4.4482216152605
    assert f"largest dynamic span load {fmt(steady)} lbf" in us
    assert f"largest span force {fmt(peak)} lbf" in us


def test_quick_verdict_says_what_it_left_out() -> None:
    """`analyze --quick` computes no dynamic response: its verdict says k1, k2 and k2min were
    not computed, the full analysis says nothing of the kind."""
    quick = run_cli("analyze", str(SEED), "--quick")
    assert quick.returncode == 0, quick.stderr
    assert "k1, k2 and k2min were not computed" in " ".join(quick.stdout.split())
    full = run_cli("analyze", str(SEED))
    assert full.returncode == 0, full.stderr
    assert "were not computed" not in " ".join(full.stdout.split())
