"""``chaindrive tension --record``: a span's tension and installed sag from a record of a
sideways pluck (its most prominent peak ± half a bin), and bad input refused in one line
with exit status 2, nothing written."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import EXAMPLES, cli_in_process

SEED = str(EXAMPLES / "seed_three_sprocket.toml")
#: Pretension [N] of the chain at a sag of 1.5 % of its slack span S1-S2 (k_f q g a,
#: k_f = cos ψ/(8s) + |sin ψ| [ChainDesignRU, §8]; the seed's 1363.4 mm span at
#: ψ = 0.0295 rad, q = 2.6 kg/m), which S2-S3 carries at rest too, and the string frequency
#: (1/2L) sqrt(F₀/q) [Hz] of S2-S3 (683.3 mm) at it.
F0_N = 290.59260115160936
F1_HZ = 7.736395985104492


#: The command run in this process: what these tests assert (what it prints and writes, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


def run_process(*args: str) -> subprocess.CompletedProcess[str]:
    """The command run as ``python -m chaindrive`` in a new interpreter (the entry point)."""
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False)


def _pluck(path: Path) -> Path:
    t = np.arange(0.0, 20.0, 1.0 / 200.0)
    x = (1e-3 * np.exp(-0.05 * t) * np.sin(2 * np.pi * F1_HZ * t)
         + 3e-4 * np.random.default_rng(1).standard_normal(t.size))
    path.write_text("time_s,offset_m\n" + "".join(f"{a!r},{b!r}\n" for a, b in
                                                 zip(t.tolist(), x.tolist(), strict=True)),
                    encoding="utf-8")
    return path


def test_tension_from_a_record_gives_back_the_sag_it_was_made_with(tmp_path: Path) -> None:
    import chaindrive

    out_file = tmp_path / "sag.toml"
    out = run_cli("tension", SEED, "--span", "S2-S3", "--record", str(_pluck(tmp_path / "p.csv")),
                  "--length-tolerance", "0 mm", "--mass-tolerance", "0",
                  "--write-calibrated", str(out_file), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    rec = doc["record"]
    assert rec["signal"] == "offset_m"
    assert abs(rec["frequency_hz"] - F1_HZ) < rec["resolution_hz"] / 2
    # u(f) is the half bin, rectangular: u = Δf/(2√3) [JCGM100, §4.3.7]; T ∝ f² stationary
    u_f = rec["resolution_hz"] / (2 * math.sqrt(3))
    assert doc["tension_std_by_input_n"]["frequency"] == pytest.approx(
        2 * doc["tension_n"] / doc["frequency_hz"] * u_f, rel=1e-3)
    assert doc["assumed"] == []
    lo, hi = doc["calibration"]["interval_95_fraction"]
    assert doc["calibration"]["sag_span"] == "S1-S2"
    assert lo < 0.015 < hi
    assert abs(doc["tension_n"] - F0_N) < 1.96 * doc["tension_std_n"]
    assert chaindrive.load(out_file).chain.sag == pytest.approx(
        doc["calibration"]["fitted_fraction"], rel=1e-12)


@pytest.mark.parametrize(("args", "message", "runner"), [
    # one case through the entry point itself, in a subprocess
    pytest.param(("--span", "S2-S3"), "--frequency: give either --frequency F or --record FILE",
                 run_process, marks=pytest.mark.concurrency),
    (("--span", "S2-S3", "--frequency", "5Hz", "--record", "r.csv"),
     "--frequency: give either --frequency F or --record FILE", run_cli),
    (("--span", "S2-S3", "--record", "missing.csv"), "--record: no such file", run_cli),
])
def test_tension_record_bad_input_is_one_line_exit_2(
        tmp_path: Path, args: tuple[str, ...], message: str,
        runner: Callable[..., subprocess.CompletedProcess[str]]) -> None:
    out = runner("tension", SEED, *args, "--write-calibrated", str(tmp_path / "c.toml"))
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and message in out.stderr, out.stderr
    assert list(tmp_path.iterdir()) == []
