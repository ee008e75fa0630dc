"""One nominal peripheral force F_t = P/v̄ (v̄ = z·p·n/60, [ISO10823]) in strength and dynamics."""

from __future__ import annotations

import pytest

from chaindrive.analysis import analyze
from chaindrive.io.design import load_drive
from chaindrive.strength.loads import peripheral_force
from tests.conftest import EXAMPLES


def test_seed_ft_is_power_over_mean_chain_speed_in_both_stages() -> None:
    # the seed example: P = 500 W, z₁ = 15, p = 25.4 mm, n₁ = 300 rpm →
    # v̄ = 15 · 0.0254 · 300/60 = 1.905 m/s, F_t = 500/1.905 = 262.47 N (closed form)
    a = analyze(load_drive(EXAMPLES / "seed_three_sprocket.toml"))
    expected = 500.0 / (15 * 0.0254 * 300 / 60)
    assert expected == pytest.approx(262.467, abs=1e-3)
    doc = a.to_dict()
    assert doc["strength"]["peripheral_force_n"] == pytest.approx(expected, rel=1e-12)
    # K_D's denominator is the same number (not P/v_max = 2P/(Dω) = 260.55 N)
    assert doc["dynamics"]["steady"]["nominal_force_n"] == pytest.approx(expected, rel=1e-12)
    assert peripheral_force(500.0, 1.905) == pytest.approx(expected, rel=1e-12)
