"""The robust study's outputs: its JSON document, its figures and its report section read
the result and show what it holds (the same numbers as ``RobustResult.to_dict()``)."""

from __future__ import annotations

import json
import math

import pytest

import chaindrive
from chaindrive.plotting.robust import (
    life_curve_figure,
    probability_figure,
    sensitivity_figure,
)
from chaindrive.report import build_report, render_html
from chaindrive.robust import UncertaintySettings, nominal_analysis
from chaindrive.robust.study import robust_study
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def result():
    nominal = nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))
    return robust_study(nominal, UncertaintySettings(samples=8, replicates=2,
                                                     sensitivity_samples=4,
                                                     sensitivity_budget=48), life_points=5)


def test_document_is_json_and_complete(result) -> None:
    doc = json.loads(json.dumps(result.to_dict(), allow_nan=False))
    assert set(doc) == {"drive", "uncertainty", "life", "reliability", "sensitivity"}
    assert len(doc["life"]["states"]) == 5
    assert doc["reliability"]["samples"] == 8
    keys = [c["key"] for c in doc["reliability"]["checks"]]
    assert keys[-1] == "any" and "resonance_margin" in keys and "buildable" in keys
    for c in doc["reliability"]["checks"]:
        assert 0.0 <= c["ci_low"] <= c["probability"] <= c["ci_high"] <= 1.0
    assert doc["reliability"]["evaluated_states"] == 8 and doc["reliability"]["wear_states"] == 0
    assert doc["reliability"]["held_at_nominal"] and len(doc["reliability"]["averaged_over"]) == 3
    assert doc["life"]["held_at_nominal"][0].startswith("every tolerance")
    assert doc["reliability"]["averaged_over"][0].startswith("the life: wear elongation uniform")
    sens = doc["sensitivity"]
    assert sens["evaluations"] == sens["base_samples"] * (len(sens["groups"]) + 2)
    # 8 replicates of N = 4 (256 states, the first N whatever the budget); N = 8 would need
    # 512 > the budget of 48: said so, not converged
    assert (sens["base_samples"], sens["base_samples_per_replicate"], sens["replicates"],
            sens["budget_hit"], sens["converged"]) == (32, 4, 8, True, False)
    assert sens["interval"].startswith("Student-t across independently scrambled replicates")
    for m in sens["metrics"].values():
        if m["rank"] is not None:   # the interval is the wider of its two parts
            assert all(h == pytest.approx(max(b, t if t is not None else 0.0))
                       for h, t, b in zip(m["total_conf"], m["total_conf_replicates"],
                                          m["total_conf_bootstrap"], strict=True))
    assert sens["held_at_nominal"] == doc["reliability"]["held_at_nominal"]
    for m in sens["metrics"].values():
        if m["rank"] is not None:
            assert min(m["rank"]) == 1 and all(0.0 <= v <= 1.0 for v in m["total"])
    assert all(v["source"] for v in doc["uncertainty"]["variables"])


def test_figures_show_the_result(result) -> None:
    fig = life_curve_figure(result.life)
    assert len(fig.axes) == 5                      # three panels, two with a second y axis
    assert fig.axes[2].get_ylabel().startswith("slack-span sag")   # no take-up here
    f1 = fig.axes[0].lines[0].get_ydata()
    assert list(f1) == [s.f1_hz for s in result.life.states]
    fig = probability_figure(result.reliability)
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert labels[-1] == "any check" and "resonance_margin" in labels
    fig = sensitivity_figure(result.sensitivity)
    assert [t.get_text() for t in fig.axes[0].get_xticklabels()] == list(
        result.sensitivity.groups)
    assert all(math.isfinite(b.get_height()) for b in fig.axes[0].patches)


def test_report_section(result) -> None:
    analysis = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                                  response=False)
    plain = build_report(analysis)
    assert "robust" not in [s.key for s in plain.sections]
    report = build_report(analysis, robust=result)
    # the robust section closes the registered sections; the references follow every section
    assert [s.key for s in report.sections][-2:] == ["robust", "references"]
    assert {"robust_life", "robust_probability", "robust_sensitivity"} <= set(report.plots)
    html = render_html(report)
    assert "Life and reliability" in html and "[DiamondChainWear]" in html
