"""simulate's progress bar: drawn on a terminal with the elapsed time and the estimate,
nothing when the output is piped (chaindrive.cli.progress.step_progress, the start-up's
startup_progress callback)."""

from __future__ import annotations

import os
import pty
import subprocess
import sys
from pathlib import Path

from tests.conftest import EXAMPLES

SEED = EXAMPLES / "seed_three_sprocket.toml"


def test_piped_simulate_prints_its_summary_alone(tmp_path: Path) -> None:
    proc = subprocess.run([sys.executable, "-m", "chaindrive", "simulate", str(SEED), "-o",
                           str(tmp_path / "h.csv")], capture_output=True, text=True,
                          check=False, timeout=300)
    assert proc.returncode == 0
    assert proc.stderr == ""
    assert proc.stdout.count("\n") == 1 and proc.stdout.startswith("max span force")


def test_simulate_on_a_terminal_draws_the_bar(tmp_path: Path) -> None:
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "chaindrive", "simulate", str(SEED), "-o",
                             str(tmp_path / "h.csv")], stdout=slave, stderr=slave,
                            env={**os.environ, "COLUMNS": "120"})
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the terminal closed with the process
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    assert proc.wait(timeout=300) == 0
    text = b"".join(chunks).decode("utf-8", "replace")
    assert "simulating the start-up" in text
    assert "100 %" in text  # the bar reached the last step
    assert "max span force" in text
