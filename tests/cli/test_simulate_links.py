"""``chaindrive simulate FILE --model links``: the link-level histories of the seed example
([MultimassChainDrives] worked example, 128 links: "3251 mm = 128 links") written as CSV with
a unit in every column name; a bad --duration is one line and exit status 2, nothing written.
"""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, cli_in_process

SEED = EXAMPLES / "seed_three_sprocket.toml"
#: The seed contour: sprockets S1, S2, S3 and its spans, 128 links [MultimassChainDrives].
SPROCKETS = ("S1", "S2", "S3")
SPANS = ("S1-S2", "S2-S3", "S3-S1")
LINKS = 128


#: The command run in this process: what these tests assert (what it prints and writes, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


def run_process(*args: str) -> subprocess.CompletedProcess[str]:
    """The command run as ``python -m chaindrive`` in a new interpreter (the entry point)."""
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False)


def test_links_history_has_its_columns_and_finite_values(tmp_path: Path) -> None:
    """Columns: time, a speed per sprocket, a force and a transverse offset per span, a
    tension per link (1 + 3 + 3 + 3 + 128); the run ends at the asked 0.05 s (within one
    recorded sample); --json prints the run's summary beside the file."""
    out = tmp_path / "links.csv"
    proc = run_cli("simulate", str(SEED), "--model", "links", "--duration", "0.05 s",
                   "-o", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.reader(out.read_text(encoding="utf-8").splitlines()))
    expected = (["time_s"] + [f"speed_{s}_rad_s" for s in SPROCKETS]
                + [f"span_force_{s}_n" for s in SPANS] + [f"span_offset_{s}_m" for s in SPANS]
                + [f"link_{i}_tension_n" for i in range(LINKS)])
    assert rows[0] == expected
    values = [[float(v) for v in r] for r in rows[1:]]
    assert len(values) > 10 and all(math.isfinite(v) for r in values for v in r)
    step = values[1][0] - values[0][0]
    assert values[0][0] == 0.0 and abs(values[-1][0] - 0.05) <= step
    doc = json.loads(proc.stdout)
    assert doc["model"] == "link-level" and doc["history"] == str(out.resolve())
    assert doc["span_names"] == list(SPANS) and doc["parameters"]["links"] == LINKS
    # the file's largest span force is the summary's start-up peak (same samples)
    for k in range(len(SPANS)):
        peak = max(r[1 + len(SPROCKETS) + k] for r in values)
        assert peak == pytest.approx(doc["peak_span_force_n"][k], rel=1e-6)


@pytest.mark.parametrize(("duration", "says"), [
    ("20 s", "outside 0.001 s to 10 s"),      # beyond the bound of chaindrive.linklevel
    ("0 s", "outside 0.001 s to 10 s"),
    ("5 kg", "is not a time"),                # the strict parser: a unit of time
    ("0.5", "missing unit"),                  # no unit
])
def test_bad_duration_is_one_line_exit_2(duration: str, says: str, tmp_path: Path) -> None:
    out = tmp_path / "links.csv"
    proc = run_cli("simulate", str(SEED), "--model", "links", "--duration", duration,
                   "-o", str(out))
    assert proc.returncode == 2
    assert proc.stderr.startswith("error: --duration:") and says in proc.stderr
    assert proc.stderr.count("\n") == 1 and not out.exists()


@pytest.mark.concurrency  # the entry point itself, in a subprocess
def test_unknown_model_is_one_line_exit_2() -> None:
    proc = run_process("simulate", str(SEED), "--model", "beams")
    assert proc.returncode == 2 and proc.stderr.startswith("error: --model:")
    assert proc.stderr.count("\n") == 1


@pytest.mark.concurrency  # numba reads NUMBA_CACHE_DIR when it starts: a new interpreter
def test_a_cold_kernel_cache_is_said_before_the_first_run(tmp_path) -> None:
    """With numba's cache empty (a fresh NUMBA_CACHE_DIR) the kernel is not compiled, so the
    command says the first run compiles; with the package's cache it is (docs/linklevel.md)."""
    import os
    import subprocess
    import sys

    probe = "from chaindrive.linklevel import kernel_compiled; print(kernel_compiled())"
    cold = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}, check=True,
                          timeout=120)
    assert cold.stdout.strip() == "False"
