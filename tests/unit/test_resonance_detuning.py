"""The detuning of a working frequency and the margin of the resonance check are two numbers,
named apart wherever a reader meets them (checks, tables, warnings, JSON).

Closed forms: the detuning Δ = |f_w − f_n|/f_n · 100 % ≥ 0 with the side of the working
frequency ("below"/"above" f_n) [MultimassChainDrives, §3.2]; the check's margin
m = Δ/Δ_required − 1 (a lower limit, :attr:`chaindrive.checks.Check.margin_fraction`),
≥ 0 when it passes. The seed example (examples/seed_three_sprocket.toml) is the case the
issue names: its tooth frequency 75 Hz lies 2.7 % above its first elastic frequency 73.1 Hz
(docs/dynamics.md §7), so Δ = 2.66 % and m = 2.66/10 − 1 = −73.4 %.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pytest

import chaindrive
from chaindrive.display import check_row, margin_percent
from chaindrive.dynamics.resonance import Resonance, WorkingFrequency, resonance_warnings

SEED = Path(__file__).parents[2] / "examples" / "seed_three_sprocket.toml"


@pytest.fixture(scope="module")
def seed():
    drive = chaindrive.load(SEED)
    short = replace(drive.dynamics, startup_duration=0.05)  # the start-up is not read here
    return chaindrive.analyze(replace(drive, dynamics=short))


def _detuning(f_working: float, f_natural: float) -> float:
    """Δ [%] by its closed form."""
    return abs(f_working - f_natural) / f_natural * 100.0


def test_warning_gives_the_detuning_with_its_side_not_a_signed_margin() -> None:
    """90 Hz against 100 Hz: Δ = 10 % below; 110 Hz: Δ = 10 % above (closed form); neither
    warning carries a sign, since a signed percentage reads as a margin (≥ 0 passes)."""
    rows = [Resonance(WorkingFrequency("tooth", "tooth x1", 90.0), 100.0, 1, -10.0),
            Resonance(WorkingFrequency("tooth", "tooth x2", 110.0, 2), 100.0, 1, 10.0)]
    below, above = resonance_warnings(rows, band_percent=15.0)
    assert "tooth x1 at 90.0 Hz is 10.0 % below the natural frequency 100.0 Hz" in below.message
    assert "tooth x2 at 110.0 Hz is 10.0 % above the natural frequency 100.0 Hz" in above.message
    for w in (below, above):
        assert "required detuning ≥ 15 %" in w.message
        assert not re.search(r"[+\-−±]\s?\d", w.message), w.message
        assert "margin" not in w.message
    assert resonance_warnings(rows, band_percent=10.0) == []  # Δ = 10 % is outside a 10 % band


def test_seed_check_value_is_the_detuning_and_its_margin_is_relative_to_the_band(seed) -> None:
    """The resonance check's value is the least Δ of the table (closed form from the rows'
    frequencies), its margin Δ/band − 1; its row names the value the detuning."""
    band = seed.limits.resonance_band_percent
    rows = seed.dynamics.resonances
    least = min(_detuning(r.working.frequency, r.natural_frequency) for r in rows)
    check = seed.check("resonance_margin")
    assert check.value == pytest.approx(least, rel=1e-12)
    assert margin_percent(check) == pytest.approx(100.0 * (least / band - 1.0), rel=1e-12)
    assert least == pytest.approx(2.66, abs=0.01)                    # docs/dynamics.md §7
    assert margin_percent(check) == pytest.approx(-73.4, abs=0.1)
    label = check_row(check)[0]
    assert "75 Hz above the natural frequency 73.06 Hz; the value is their detuning" in label


def test_seed_warning_table_and_json_agree_on_the_detuning(seed) -> None:
    """The warning, the resonance rows and the JSON documents (``dynamics.resonances``,
    ``dynamics.bands.resonance_detunings``) give the same Δ ≥ 0 and side; no key of them is
    called a margin."""
    rows = seed.dynamics.resonances
    closest = rows[0]
    delta = _detuning(closest.working.frequency, closest.natural_frequency)
    side = "below" if closest.working.frequency < closest.natural_frequency else "above"
    assert (closest.detuning_percent, closest.side) == (pytest.approx(delta), side)
    warning = next(w for w in seed.warnings if w.code == "dynamics.resonance")
    assert f"{closest.working.label} at 75.0 Hz is {delta:.1f} % {side}" in warning.message
    assert "+" not in warning.message
    doc = seed.dynamics.to_dict()["resonances"]
    bands = seed.bands.to_dict()["resonance_detunings"]
    for entries in (doc, bands):
        assert not [k for e in entries for k in e if "margin" in k]
        for e in entries:
            fw = e["frequency_hz"] if "frequency_hz" in e else e["working_frequency_hz"]
            fn = e["natural_frequency_hz"]
            assert e["detuning_percent"] == pytest.approx(_detuning(fw, fn), rel=1e-12)
            assert e["working_frequency_is"] == ("below" if fw < fn else "above")
