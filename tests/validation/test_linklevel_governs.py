"""With the link-level model run beside the whole-drive model (the analysis' study "links"),
the checks that rest on a dynamic load take the governing one — of each span's load the
larger — and say which (``Check.governing_model``, its note, the JSON and the report),
except where the link-level model's load is not comparable (docs/linklevel.md §6).

Expected values: k₁ = Q/F₁max and k₂ = min_i Q/(F_R,i + F₂,i) [MultimassChainDrives, §3.6]
(closed forms) with the loads each model reports; the seed example is the worked example of
[MultimassChainDrives]; the conveyor is the five-sprocket conveyor example at 7.5 kW with its
motor, reducer and drums (tests/fixtures/selection_conveyor_ansi.toml), whose trains the
link-level model leaves out.
"""

from __future__ import annotations

import numpy as np
import pytest

import chaindrive
from chaindrive.report import build_report
from tests.conftest import EXAMPLES, ROOT

CONVEYOR = ROOT / "tests" / "fixtures" / "selection_conveyor_ansi.toml"


@pytest.fixture(scope="module")
def seed():
    """The seed example with its own start-up and a link-level start-up of its duration."""
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                              studies=("links",))


@pytest.fixture(scope="module")
def conveyor():
    return chaindrive.analyze(chaindrive.load(CONVEYOR), studies=("links",))


def _rows(a):
    return {r["quantity"]: r for r in a.to_dict()["link_level"]["dynamics_comparison"]}


def test_larger_link_level_start_up_peak_sets_k1(seed) -> None:
    """On the seed the link-level start-up peaks exceed the whole-drive model's (its
    engagement impacts ride on the pre-tension; measured 1457 N against 988 N): k₁ and the
    fatigue check's start-up force take them and say "link-level"."""
    q = seed.drive.chain.spec.breaking_load
    ring = float(np.max(seed.startup.max_span_force))
    link = float(np.max(seed.link_level.peak_span_force))
    assert link > 1.2 * ring  # the case this test is about
    assert _rows(seed)["largest start-up span force F₁max"]["governing"] == "link_level"
    k1 = seed.check("k1")
    assert k1.governing_model == "link_level"
    assert k1.value == pytest.approx(q / link, rel=1e-12)
    assert k1.value < seed.startup.k1  # changed from the whole-drive model's Q/F₁max
    assert "link-level model's largest start-up span force" in k1.note
    doc = {c["key"]: c for c in seed.to_dict()["checks"]}
    assert doc["k1"]["governing_model"] == "link_level"
    assert doc["k1"]["value"] == pytest.approx(q / link, rel=1e-12)
    fatigue = seed.check("fatigue")
    st = seed._static.loads.span_tensions
    steady_peak = float(np.max(np.asarray(st) + np.maximum(
        seed.steady.span_dynamic_load, seed.link_level.span_dynamic_load)))
    assert link > steady_peak  # measured 1457 N against 1302 N: the start-up decides
    assert fatigue.value == pytest.approx(link, rel=1e-12)
    assert fatigue.governing_model == "link_level"


def test_k2_takes_each_spans_larger_steady_load(seed) -> None:
    """The run settles (its closing half at the nominal speed): k₂ = min_i Q/(F_R,i +
    max(F₂,i whole drive, F₂,i link level)), the model of the deciding span named."""
    assert seed.link_level_comparison.settled
    q = seed.drive.chain.spec.breaking_load
    fr = np.asarray(seed._static.loads.span_tensions)
    ring, link = seed.steady.span_dynamic_load, seed.link_level.span_dynamic_load
    governing = np.maximum(ring, link)
    k2 = seed.check("k2")
    assert k2.value == pytest.approx(float(np.min(q / (fr + governing))), rel=1e-12)
    span = int(np.argmax(fr + governing))
    assert k2.governing_model == ("link_level" if link[span] > ring[span] else "whole_drive")
    assert seed.link_level.span_names[span] in k2.note
    assert seed.check("k2min").governing_model == "whole_drive"  # no sweep at link level


def test_report_says_which_model_each_check_takes(seed) -> None:
    report = build_report(seed, dpi=30)
    section = next(s for s in report.sections if s.key == "links")
    table = next(b for b in section.blocks
                 if getattr(b, "columns", None) == ("check", "subject", "value", "governs",
                                                    "why"))
    governs = {r[0]: r[3] for r in table.rows}
    assert governs["k1"] == "link-level model"
    assert governs["k2min"] == "whole-drive model"


def test_conveyor_keeps_the_whole_drive_loads_and_says_why(conveyor) -> None:
    """The conveyor's link-level start-up peak is the larger (measured 13 703 N against
    12 259 N) but its sprockets turn without the motor, reducer and drums: every check keeps
    the whole-drive model's load and names the trains it lacks."""
    ring = float(np.max(conveyor.startup.max_span_force))
    link = float(np.max(conveyor.link_level.peak_span_force))
    assert link > ring
    k1 = conveyor.check("k1")
    assert k1.governing_model == "whole_drive"
    assert k1.value == pytest.approx(conveyor.startup.k1, rel=1e-12)
    assert "not comparable" in k1.note and "S1, D1, D2, D3" in k1.note
    k2 = conveyor.check("k2")
    assert k2.governing_model == "whole_drive"
    assert k2.value == pytest.approx(conveyor.steady.k2, rel=1e-12)
    assert "not comparable" in k2.note
    assert conveyor.check("fatigue").value == pytest.approx(max(ring, float(np.max(
        np.asarray(conveyor._static.loads.span_tensions) + conveyor.steady.span_dynamic_load))))
    doc = [c for c in conveyor.to_dict()["checks"] if c["governing_model"] is not None]
    assert {c["key"] for c in doc} >= {"k1", "k2", "k2min", "fatigue"}
    assert {c["governing_model"] for c in doc} == {"whole_drive"}
