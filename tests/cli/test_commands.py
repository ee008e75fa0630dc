"""schema, catalog and select commands: they run, their JSON is complete, mistakes exit 2."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from chaindrive.io.design import SECTIONS
from tests.conftest import EXAMPLES, cli_in_process

#: The command run in this process: what these tests assert (what it prints, its JSON, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


def run_process(*args: str) -> subprocess.CompletedProcess[str]:
    """The command run as ``python -m chaindrive`` in a new interpreter (the entry point)."""
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False)


@pytest.mark.concurrency  # its last command runs the entry point itself, in a subprocess
def test_schema_lists_every_field_with_unit_default_and_range() -> None:
    proc = run_cli("schema", "--json")
    assert proc.returncode == 0
    doc = json.loads(proc.stdout)
    assert set(doc) == set(SECTIONS)
    teeth = next(f for f in doc["sprockets"] if f["field"] == "teeth")
    assert teeth["allowed"] == "a whole number from 6 to 150"
    speed = next(f for f in doc["sprockets"] if f["field"] == "speed")
    assert speed["si_unit"] == "rad/s" and speed["example"] == "300 rpm"
    assert run_process("schema").returncode == 0


def test_catalog_lists_shows_and_refuses() -> None:
    doc = json.loads(run_cli("catalog", "--json").stdout)
    standards = {c["designation"].split(" ")[0] for c in doc["chains"]}
    assert {"ISO", "GOST"} <= standards
    one = json.loads(run_cli("catalog", "ANSI 80", "--json").stdout)["chains"]
    assert one[0]["pitch_mm"] == 25.4
    assert one[0]["ansi"] == "80"
    mats = json.loads(run_cli("catalog", "--materials", "--json").stdout)["materials"]
    assert any(m["name"] == "PA6" for m in mats)
    bad = run_cli("catalog", "ANSI 8O")
    assert bad.returncode == 2
    assert bad.stderr.startswith("error: chain.designation:")


def test_select_ranks_by_every_check_and_shows_the_top() -> None:
    """One rule ranks and chooses: the chosen chain heads the table; margins are fractions."""
    proc = run_cli("select", str(EXAMPLES / "eight_sprocket.toml"), "--json", "--top", "3")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert len(doc["candidates"]) == 3 and doc["candidate_count"] > 3
    assert doc["candidates"][0]["chain"] == doc["chain"] and doc["candidates"][0]["passed"]
    assert doc["method"] == "ACA"  # 12B-1 at this speed: no printed B-series value
    assert all(c["governing"] and "margin_fraction" in c for c in doc["candidates"])
    table = run_cli("select", str(EXAMPLES / "eight_sprocket.toml"), "--top", "2")
    assert table.returncode == 0 and "first 2 of" in table.stdout


def test_design_without_a_chain_gets_the_selected_one(tmp_path) -> None:  # type: ignore[no-untyped-def]
    text = (EXAMPLES / "eight_sprocket.toml").read_text(encoding="utf-8")
    text = text.replace('designation = "ISO 606 12B-1"', 'standard = "ISO 606"\nseries = "B"')
    design = tmp_path / "auto.toml"
    design.write_text(text, encoding="utf-8")
    doc = json.loads(run_cli("analyze", str(design), "--json").stdout)
    assert doc["drive"]["chain"] == doc["selection"]["chain"]
    assert doc["drive"]["chain"].startswith("ISO 606") and "B-1" in doc["drive"]["chain"]
    missing_power = tmp_path / "nopower.toml"
    missing_power.write_text(text.replace('power = "4 kW"\n', ""), encoding="utf-8")
    proc = run_cli("analyze", str(missing_power))
    assert proc.returncode == 2
    assert "drive.power" in proc.stderr


def test_ansi_selection_names_the_ansi_numbers(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Asked for ANSI chains, the selection ranks every chain with an ANSI number; an ISO 606 A
    chain is named with its ANSI twin (the same chain, [ISO606], [ANSI-B29.1]), in the JSON
    and in the table."""
    text = (EXAMPLES / "eight_sprocket.toml").read_text(encoding="utf-8")
    design = tmp_path / "ansi.toml"
    design.write_text(text.replace('designation = "ISO 606 12B-1"', 'standard = "ANSI"'),
                      encoding="utf-8")
    doc = json.loads(run_cli("select", str(design), "--json").stdout)
    iso = [c for c in doc["candidates"] if c["chain"].startswith("ISO 606")]
    assert iso and all(c["ansi_number"] for c in iso)
    assert all(c["ansi_number"] is None for c in doc["candidates"]
               if c["chain"].startswith("ANSI"))
    matched = [(c, re.fullmatch(r"ISO 606 (\d\d)A-(\d)", c["chain"])) for c in iso]
    matched = [(c, m) for c, m in matched if m]
    assert len(matched) >= 5
    for c, m in matched:  # ISO 606 nnA-k is ANSI (5·nn)-k: 16A-2 is ANSI 80-2
        base = str(5 * int(m[1]))
        assert c["ansi_number"] == (base if m[2] == "1" else f"{base}-{m[2]}")
    first = doc["candidates"][0]
    table = run_cli("select", str(design), "--top", "1").stdout
    same = f" = ANSI {first['ansi_number']}" if first["ansi_number"] else ""
    assert f"{first['chain']}{same}" in table
