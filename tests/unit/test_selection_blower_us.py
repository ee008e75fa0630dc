"""A 10 hp blower drive written in US customary units with its duty and the chain left to the
tool (standard = "ANSI"): the service factor comes from the duty classes, nothing is said to be
a default, and the chain chosen is the lightest that passes every chain check.

Service factors: [Mott2014, Table 7-17] (electric motor: smooth 1.0, heavy shock 1.5).
"""

from __future__ import annotations

from pathlib import Path

import pytest

import chaindrive
from chaindrive.strength.duty import service_factor_for

FIXTURE = Path(__file__).parents[1] / "fixtures" / "selection_blower_us.toml"


def _analysis(tmp_path: Path, driven: str) -> chaindrive.Analysis:
    text = FIXTURE.read_text(encoding="utf-8").replace('driven = "smooth"',
                                                       f'driven = "{driven}"')
    path = tmp_path / f"blower_{driven.replace(' ', '_')}.toml"
    path.write_text(text, encoding="utf-8")
    return chaindrive.analyze(chaindrive.load(path), response=False)


@pytest.mark.parametrize(("driven", "factor"), [("smooth", 1.0), ("heavy shock", 1.5)])
def test_the_lightest_chain_that_passes_the_chain_checks_is_chosen(tmp_path: Path, driven: str,
                                                                   factor: float) -> None:
    a = _analysis(tmp_path, driven)
    sf = service_factor_for(a.drive)
    assert (sf.value, sf.origin) == (factor, "duty classes")
    assert not any(w.code == "duty.service-factor-default" for w in a.warnings)
    sel = a.selection
    assert sel is not None and sel.chosen is not None
    chosen = sel.chosen
    assert chosen.chain_passed and chosen.layout_shortfall == 0.0
    lighter = [c for c in sel.candidates if c.mass_per_length < chosen.mass_per_length]
    assert lighter, "the family has lighter chains to pass over"
    assert all(not c.chain_passed for c in lighter)  # each misses a chain check of its own


def test_a_heavier_duty_never_chooses_a_lighter_chain(tmp_path: Path) -> None:
    smooth = _analysis(tmp_path, "smooth").selection
    heavy = _analysis(tmp_path, "heavy shock").selection
    assert smooth is not None and heavy is not None
    assert smooth.chosen is not None and heavy.chosen is not None
    assert heavy.chosen.mass_per_length >= smooth.chosen.mass_per_length
