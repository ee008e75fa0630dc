"""``chaindrive tension`` and ``chaindrive identify`` on the command line: the figures of the
compute functions, and bad input refused in one line with exit status 2, nothing written."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, cli_in_process

SEED = str(EXAMPLES / "seed_three_sprocket.toml")


#: The command run in this process: what these tests assert (what it prints and writes, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


def run_process(*args: str) -> subprocess.CompletedProcess[str]:
    """The command run as ``python -m chaindrive`` in a new interpreter (the entry point)."""
    return subprocess.run([sys.executable, "-m", "chaindrive", *args], capture_output=True,
                          text=True, check=False)


@pytest.mark.concurrency  # the one run of the entry point itself, in a subprocess
def test_tension_json_inverts_the_design_running_frequency() -> None:
    # the design's running frequency of S2-S3 read back gives the design's span tension
    out = run_process("tension", SEED, "--span", "S2-S3", "--frequency", "9.853664524265515 Hz",
                  "--running", "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["tension_n"] == pytest.approx(doc["design_running_tension_n"], rel=1e-9)
    assert doc["tension_std_n"] > 0
    assert "mass per metre ± 5 %" in doc["assumed"]


@pytest.mark.parametrize(("args", "message"), [
    (("--span", "S9-S1", "--frequency", "5 Hz"), "--span: unknown span 'S9-S1'; allowed:"),
    (("--span", "S1-S2", "--frequency", "0 Hz"), "--frequency: must be above 0 Hz"),
    (("--span", "S1-S2", "--frequency", "5 mm"), "--frequency: '5 mm' is not a frequency"),
    (("--span", "S1-S2", "--frequency", "5 Hz", "--mass-tolerance", "-1"),
     "--mass-tolerance: must be ≥ 0"),
])
def test_tension_bad_input_is_one_line_exit_2(args: tuple[str, ...], message: str) -> None:
    out = run_cli("tension", SEED, *args)
    assert out.returncode == 2
    assert out.stdout == ""
    assert out.stderr.count("\n") == 1 and message in out.stderr


def _record(path: Path, rows: int = 4096, fs: float = 1000.0, bad_time: bool = False) -> Path:
    import numpy as np

    t = np.arange(rows) / fs
    if bad_time:
        t[100] = t[99]
    x = np.sin(2 * np.pi * 150.0 * t) + 0.05 * np.random.default_rng(3).standard_normal(rows)
    lines = ["time_s,accel_m_s2"] + [f"{a!r},{b!r}" for a, b in zip(t.tolist(), x.tolist(), strict=True)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_identify_labels_the_tooth_harmonic_and_writes_the_plot(tmp_path: Path) -> None:
    rec = _record(tmp_path / "r.csv")
    out = run_cli("identify", SEED, "--record", str(rec), "-o", str(tmp_path / "s.svg"),
                  "--campbell", str(tmp_path / "c.png"), "--json")
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    doc = json.loads(out.stdout)
    peaks = doc["signals"][0]["peaks"]
    assert [p["label"] for p in peaks] == ["tooth x2"]   # 2 × 75 Hz tooth frequency
    assert doc["prominence_db"] == 15.0 and doc["tolerance_percent"] == 5.0
    assert (tmp_path / "s.svg").stat().st_size > 0


@pytest.mark.parametrize(("extra", "message"), [
    ((), "--record.time_s: not increasing at sample 101"),
    (("--tolerance", "0"), "--tolerance: must lie between 0 and 100 %"),
])
def test_identify_bad_input_writes_nothing(tmp_path: Path, extra: tuple[str, ...],
                                           message: str) -> None:
    rec = _record(tmp_path / "r.csv", bad_time=not extra)
    out = run_cli("identify", SEED, "--record", str(rec), "-o", str(tmp_path / "s.svg"), *extra)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and message in out.stderr
    assert not (tmp_path / "s.svg").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.csv"]


def _runup(path: Path) -> Path:
    """A run-up of the seed drive's driver (z₁ = 15) from 100 to 250 rpm in 8 s at 1 kHz:
    the tooth order sin(15 θ) and a fixed line at 73.06 Hz (the model's mode 1)."""
    import numpy as np

    fs = 1000.0
    t = np.arange(8000) / fs
    rpm = 100.0 + 150.0 * t / 8.0
    theta = 2 * np.pi * (100.0 * t + 150.0 * t**2 / 16.0) / 60.0
    x = np.sin(15 * theta) + 0.5 * np.sin(2 * np.pi * 73.06 * t)
    rows = [f"{a:.4f},{b:.4f},{c:.5f}" for a, b, c in zip(t, rpm, x, strict=True)]
    path.write_text("time_s,speed_rpm,accel_m_s2\n" + "\n".join(rows) + "\n",
                    encoding="utf-8")
    return path


def test_identify_a_run_up_gives_its_orders_and_run_up_map(tmp_path: Path) -> None:
    rec = _runup(tmp_path / "r.csv")
    out = run_cli("identify", SEED, "--record", str(rec), "--speed", "speed_rpm", "--orders",
                  str(tmp_path / "o.svg"), "--campbell", str(tmp_path / "c.svg"), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert [s["name"] for s in doc["signals"]] == ["accel_m_s2"]   # the speed is no signal
    orders = doc["orders"]
    assert orders["speed_range_rpm"] == pytest.approx([100.0, 250.0], abs=0.1)
    tooth = [p for p in orders["signals"][0]["peaks"] if p["label"] == "tooth x1"]
    assert len(tooth) == 1
    assert tooth[0]["order"] == pytest.approx(15.0, abs=orders["signals"][0]["resolution_orders"])
    fixed = [p for p in orders["runup_points"] if p["label"] == "mode 1"]
    assert len(fixed) >= 16
    for p in fixed:                                   # the order of a fixed line: f·60/n
        assert p["order"] == pytest.approx(73.06 * 60.0 / p["speed_rpm"],
                                           abs=orders["runup_resolution_hz"] * 60 / p["speed_rpm"])
    assert (tmp_path / "o.svg").stat().st_size > 0 and (tmp_path / "c.svg").stat().st_size > 0


@pytest.mark.parametrize(("extra", "message"), [
    (("--speed", "speed"), "--speed: no column 'speed'"),
    (("--orders", "x.svg"), "--orders: needs the record's speed or tacho column"),
    (("--speed", "speed_rpm", "--tacho", "speed_rpm"), "--tacho: give a speed column or"),
])
def test_identify_a_bad_speed_writes_nothing(tmp_path: Path, extra: tuple[str, ...],
                                             message: str,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    rec = _runup(tmp_path / "r.csv")
    monkeypatch.chdir(tmp_path)  # a relative output name lands in tmp_path
    out = run_cli("identify", SEED, "--record", str(rec), "-o", str(tmp_path / "s.svg"), *extra)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and message in out.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.csv"]


def test_report_with_a_record_has_its_section_and_a_speed_needs_a_record(
        tmp_path: Path) -> None:
    rec = _runup(tmp_path / "r.csv")
    out = run_cli("report", SEED, "--record", str(rec), "--speed", "speed_rpm", "--dpi", "50",
                  "-o", str(tmp_path / "r.html"))
    assert out.returncode == 0, out.stderr
    page = (tmp_path / "r.html").read_text(encoding="utf-8")
    assert "Measured record and the model" in page and "Order peaks of accel_m_s2" in page
    bad = run_cli("report", SEED, "--speed", "speed_rpm", "-o", str(tmp_path / "x.html"))
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1
    assert "--speed: needs --record" in bad.stderr and not (tmp_path / "x.html").exists()


def test_calibrate_writes_a_design_that_loads_with_the_fitted_stiffness(tmp_path: Path) -> None:
    import chaindrive

    out_file = tmp_path / "cal.toml"
    out = run_cli("calibrate", SEED, "--natural", "1=62.3Hz", "--natural", "2=223Hz",
                  "--write-calibrated", str(out_file), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    lo, hi = doc["interval_95_n_per_m"]
    assert lo < doc["fitted_n_per_m"] < hi
    assert doc["assumed"] == ["each frequency ± 1 %"]
    k = chaindrive.load(out_file).chain.link_stiffness
    assert k == pytest.approx(doc["fitted_n_per_m"], rel=1e-9)


def test_calibrate_writes_the_fitted_damping_ratio(tmp_path: Path) -> None:
    import chaindrive

    out_file = tmp_path / "cal.toml"
    out = run_cli("calibrate", SEED, "--damping", "1=0.03", "--damping", "2=0.1",
                  "--write-calibrated", str(out_file), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    z = doc["damping"]
    lo, hi = z["interval_95"]
    assert lo < z["fitted"] < hi and z["initial"] is None
    assert "fitted_n_per_m" not in doc  # no natural frequency: the stiffness is not fitted
    assert doc["assumed"] == ["each damping ratio ± 20 %"]
    assert chaindrive.load(out_file).dynamics.damping_ratio == pytest.approx(z["fitted"],
                                                                             rel=1e-9)
    # the chain's dampers are stiffness-proportional, referred to mode 1, so the model's
    # mode-2 ratio is f₂/f₁ (257.2/73.06 Hz on the seed drive) × its mode-1 ratio: 0.03 and
    # 0.1 pull ζ to between 0.1/(f₂/f₁) and 0.03
    ratio = z["residuals"][1]["model"] / z["residuals"][0]["model"]
    assert ratio == pytest.approx(257.18 / 73.058, rel=1e-3)
    assert 0.1 / ratio < z["fitted"] < 0.03


def test_calibrate_writes_the_jointly_fitted_reduced_mass(tmp_path: Path) -> None:
    import chaindrive

    out_file = tmp_path / "cal.toml"
    out = run_cli("calibrate", SEED, "--natural", "1=65.19Hz", "--natural", "2=212.9Hz",
                  "--natural", "3=741.7Hz", "--tolerance", "0.2Hz", "--uncertain-mass", "S3",
                  "--write-calibrated", str(out_file), "--json")
    assert out.returncode == 0, out.stderr
    m = json.loads(out.stdout)["reduced_mass"]
    assert m["parameter"] == "sprockets[S3].reduced_mass" and m["initial_kg"] == 2.0
    lo, hi = m["interval_95_kg"]
    assert lo < m["fitted_kg"] < hi
    s3 = next(s for s in chaindrive.load(out_file).sprockets if s.name == "S3")
    assert s3.reduced_mass == pytest.approx(m["fitted_kg"], rel=1e-9)


@pytest.mark.parametrize(("args", "message"), [
    (("--natural", "one=62Hz"), "--natural: 'one=62Hz'; allowed: MODE=FREQUENCY"),
    (("--natural", "1=-5Hz"), "--natural: mode 1: frequency -5.0 Hz; allowed: above 0 Hz"),
    (("--natural", "9=62Hz"), "--natural: mode 9; allowed: 1 to 5"),
    ((), "--natural: give either --natural MODE=FREQUENCY or --record FILE"),
    (("--damping", "1=1.3"), "--damping: '1=1.3'; allowed: MODE=ZETA with ZETA above 0 and "
     "below 1"),
    (("--damping", "1=0.03", "--damping-tolerance", "-1"),
     "--damping-tolerance: -1.0; allowed: above 0 and below 1"),
    (("--damping", "9=0.03"), "--damping: mode 9; allowed: 1 to 5"),
    (("--natural", "1=62Hz", "--natural", "2=223Hz", "--uncertain-mass", "S9"),
     "--uncertain-mass: 'S9'; allowed: S1, S2, S3"),
    (("--natural", "1=62Hz", "--uncertain-mass", "S3"),
     "--uncertain-mass: S3: 1 measured frequency; allowed: two or more"),
    (("--damping", "1=0.03", "--uncertain-mass", "S3"),
     "--uncertain-mass: S3: no natural frequency measured"),
    (("--natural", "1=62Hz", "--parameter", "sag"), "--parameter: 'sag' with --model ring"),
    (("--model", "beads", "--natural", "1=80Hz"), "--model: 'beads'; allowed: ring, links"),
    (("--model", "links", "--natural", "2=80Hz"),
     "--natural: mode 2 with --model links; allowed: 1"),
    (("--model", "links", "--natural", "1=80Hz", "--damping", "1=0.03"),
     "--damping: not with --model links"),
    (("--model", "links", "--natural", "1=80Hz", "--parameter", "pitch"),
     "--parameter: 'pitch'; allowed: link_stiffness, sag"),
])
def test_calibrate_bad_input_writes_nothing(tmp_path: Path, args: tuple[str, ...],
                                            message: str) -> None:
    out = run_cli("calibrate", SEED, *args, "--write-calibrated", str(tmp_path / "c.toml"))
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and message in out.stderr, out.stderr
    assert list(tmp_path.iterdir()) == []


def test_tension_writes_the_calibrated_sag_or_nothing(tmp_path: Path) -> None:
    import chaindrive

    good = tmp_path / "sag.toml"
    out = run_cli("tension", SEED, "--span", "S2-S3", "--frequency", "5.1Hz",
                  "--write-calibrated", str(good), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert chaindrive.load(good).chain.sag == pytest.approx(
        doc["calibration"]["fitted_fraction"], rel=1e-12)
    bad = tmp_path / "bad.toml"
    out = run_cli("tension", SEED, "--span", "S2-S3", "--frequency", "9Hz", "--running",
                  "--write-calibrated", str(bad))
    assert out.returncode == 2 and out.stdout == ""
    assert "--running: the sag is calibrated from a stationary span" in out.stderr
    assert not bad.exists()


def test_the_package_own_start_up_record_shows_the_tooth_orders(tmp_path: Path) -> None:
    # a record produced by the whole-drive model (chaindrive simulate: the start-up at 300 rpm,
    # 15 teeth, f_z = 75 Hz): the polygonal action excites the tooth frequency and its
    # harmonics, so every peak is labelled a tooth order and lies within one bin or 1 % (the
    # motor's slip: the drive runs a little below 300 rpm) of k·f_z
    hist = tmp_path / "history.csv"
    assert run_cli("simulate", SEED, "-o", str(hist)).returncode == 0
    out = run_cli("identify", SEED, "--record", str(hist), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert len(doc["signals"]) == 6  # three span forces, three sprocket speeds
    for sig in doc["signals"]:
        assert sig["peaks"]
        for p in sig["peaks"]:
            assert p["kind"] == "tooth", (sig["name"], p)
            k = round(p["frequency_hz"] / 75.0)
            assert abs(p["frequency_hz"] - 75.0 * k) <= max(sig["resolution_hz"], 0.75 * k)


def test_calibrate_with_the_link_level_model_writes_the_fitted_sag(tmp_path: Path) -> None:
    import chaindrive

    # a tap test's first mode along the chain at 80 Hz (the design's, at a sag of 2 %: 76.09
    # Hz) fitted with the link-level model: a smaller sag, the model's frequency at it the
    # measured one (one measurement, no residual), well identified
    out_file = tmp_path / "cal.toml"
    out = run_cli("calibrate", SEED, "--model", "links", "--parameter", "sag",
                  "--natural", "1=80Hz", "--tolerance", "1Hz",
                  "--write-calibrated", str(out_file), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["model"] == "link-level" and doc["parameter"] == "chain.sag"
    lo, hi = doc["interval_95_fraction"]
    assert lo < doc["fitted_fraction"] < hi < doc["initial_fraction"] == 0.02
    assert doc["residuals"][0]["model_hz"] == pytest.approx(80.0, abs=1e-3)
    assert not doc["poorly_identified"] and doc["chi2_per_dof"] is None
    assert doc["assumed"] == []
    assert chaindrive.load(out_file).chain.sag == pytest.approx(doc["fitted_fraction"],
                                                                rel=1e-9)


def test_calibrate_with_the_link_level_model_solves_a_stiff_chain(tmp_path: Path) -> None:
    # at 4 × its link stiffness (2.04e9 N/m) the seed drive's link-level static state is
    # solved at every stiffness the fit tries (up to 5.1e9 N/m; whether the relaxation it
    # replaced settled there depended on the BLAS threads): the fit runs, says the record
    # hardly depends on k (a chain's first mode along it rests on its sagging spans) and
    # writes the design
    design = tmp_path / "stiff.toml"
    design.write_text(Path(SEED).read_text(encoding="utf-8").replace(
        "strands = 1", "strands = 1\nlink_stiffness = \"2.04e9 N/m\"", 1), encoding="utf-8")
    out = run_cli("calibrate", str(design), "--model", "links", "--natural", "1=80Hz",
                  "--write-calibrated", str(tmp_path / "c.toml"), "--json")
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["model"] == "link-level" and doc["poorly_identified"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.toml", "stiff.toml"]
