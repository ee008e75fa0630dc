"""A link-level static state that stopped short of its tolerance is said next to the
figures wherever they are shown: the shared sentence (:func:`chaindrive.display.static_state_note`),
the report's section "Link-level model", page 1 of the report and the sign-off sheet when a
check takes its load from the link-level run, and the page's link-level view.

Expected values: the sentence carries the record's own figures (the largest force left and
the reference span's offset from T₀), converted to lbf for US units by
1 lbf = 4.4482216152605 N exactly [NIST-SP811]; a converged state adds nothing. The record
is built directly with ``converged`` false on a short run of the seed example (the
24-sprocket example is the bundled case that stops short, but it is slow).
"""

from __future__ import annotations

import copy
from dataclasses import replace

import pytest

import chaindrive
from chaindrive.display import static_state_note
from chaindrive.report import build_report
from chaindrive.report.content import Text
from tests.conftest import EXAMPLES

DURATION = 0.02
LBF = 4.4482216152605  # N [NIST-SP811]
STOPPED = {"converged": False, "residual_force_n": 0.1234, "residual_force_norm_n": 1.37,
           "reference_tension_error_n": 0.0181}


def test_the_sentence_carries_the_records_figures() -> None:
    si = static_state_note(STOPPED)
    assert si is not None
    assert "largest force left 0.123 N" in si and "reference span +0.0181 N off T₀" in si
    assert si.endswith("these figures rest on that state.")
    us = static_state_note({**STOPPED, "reference_tension_error_n": -0.0181}, "US")
    assert us is not None
    assert f"largest force left {0.1234 / LBF:.3g} lbf" in us
    assert f"reference span {-0.0181 / LBF:.3g} lbf off T₀" in us
    assert static_state_note({**STOPPED, "converged": True}) is None
    assert static_state_note({}) is None  # a record without the flag: nothing to say


@pytest.fixture(scope="module")
def analyses():
    """The seed example's analysis with the study "links" as run (converged) and the same
    with its static state's record marked short of its tolerance."""
    seed = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    seed = replace(seed, dynamics=replace(seed.dynamics, startup_duration=0.1))
    ran = chaindrive.analyze(seed, studies=("links",), link_duration_s=DURATION)
    result = ran.link_level
    assert result is not None and result.equilibrium["converged"] is True
    # the second analysis is the first's shallow copy (its own attributes, the same evaluated
    # results: a second identical analysis computed the same ones), its record then replaced
    stopped = copy.copy(ran)
    stopped.__dict__["link_level"] = replace(
        result, equilibrium={**result.equilibrium, **STOPPED})
    return ran, stopped


def _texts(report, key: str) -> list[str]:
    section = next(s for s in report.sections if s.key == key)
    return [b.text for b in section.blocks if isinstance(b, Text)]


def test_the_reports_links_section_says_it(analyses) -> None:
    ran, stopped = analyses
    note = static_state_note(STOPPED)
    assert note in _texts(build_report(stopped, dpi=30), "links")
    assert not any("stopped short" in t for t in _texts(build_report(ran, dpi=30), "links"))
    in_us = build_report(stopped, dpi=30, units="US")
    assert static_state_note(STOPPED, "US") in _texts(in_us, "links")


def test_page_one_and_the_sheet_say_it_when_a_check_takes_the_link_level_load(
        analyses, monkeypatch) -> None:
    """A 20 ms run leaves every check to the whole-drive model (nothing said); with k₁
    taking the link-level start-up peak, the sheet's list of what the results rest on
    says the state and names the check."""
    ran, stopped = analyses
    assert all(c.governing_model != "link_level" for c in stopped.checks())

    def said(analysis) -> list[str]:
        sheet = build_report(analysis, dpi=30, summary=True)
        return [t for s in sheet.sections for t in _texts(sheet, s.key)
                if "stopped short" in t]

    assert said(stopped) == []
    own = stopped.checks()
    monkeypatch.setattr(stopped, "checks", lambda: [
        replace(c, governing_model="link_level") if c.name == "k1" else c for c in own])
    monkeypatch.setattr(ran, "checks", stopped.checks)
    notes = said(stopped)
    assert len(notes) == 1
    assert "largest force left 0.123 N" in notes[0] and "+0.0181 N off T₀" in notes[0]
    assert "the link-level loads the checks k1 take rest on that state" in notes[0]
    assert said(ran) == []  # converged: nothing to say


def test_the_pages_view_carries_the_record(analyses, monkeypatch) -> None:
    from chaindrive.app import runs

    _, stopped = analyses
    monkeypatch.setattr(chaindrive, "analyze", lambda *a, **k: stopped)
    view = runs.link_level_view(stopped.drive, DURATION)
    assert view.equilibrium == stopped.link_level.equilibrium
    assert static_state_note(view.equilibrium) == static_state_note(STOPPED)
