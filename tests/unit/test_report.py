"""The report contains each section and figure, in HTML and PDF (issue 6)."""

from __future__ import annotations

import base64
import hashlib
import re
from dataclasses import replace
from pathlib import Path

import pytest

import chaindrive
from chaindrive.checks import CheckLimits
from chaindrive.errors import DesignError
from chaindrive.report import (
    SECTIONS,
    Text,
    build_report,
    register_section,
    render_html,
    write_report,
)

ROOT = Path(__file__).parents[2]
SEED = ROOT / "examples" / "seed_three_sprocket.toml"
EXPECTED_SECTIONS = ["checks", "inputs", "geometry", "kinematics", "selection", "strength",
                     "dynamics", "response", "damping"]  # "contours": multi-contour drives only
EXPECTED_PLOTS = {"layout", "chain_speed", "ratio", "tensions", "shaft_loads", "mode_shapes",
                  "campbell", "steady_loads", "inertia", "startup", "startup_speeds", "afc",
                  "materials", "damping"}


@pytest.fixture(scope="module")
def seed_analysis() -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(SEED)
    short = replace(drive.dynamics, startup_duration=0.05)  # a short start-up keeps it fast
    return chaindrive.analyze(replace(drive, dynamics=short),
                              studies=("material_pairs", "hinge_friction"))


@pytest.fixture(scope="module")
def seed_html(seed_analysis) -> str:
    return render_html(build_report(seed_analysis, source=SEED, dpi=30))


def test_every_section_and_figure(seed_html: str) -> None:
    ids = re.findall(r'<section id="([a-z_]+)">', seed_html)
    assert ids == EXPECTED_SECTIONS
    plots = set(re.findall(r'<figure data-plot="([a-z_]+)">', seed_html))
    assert plots == EXPECTED_PLOTS
    for data in re.findall(r'src="data:image/png;base64,([^"]+)"', seed_html):
        assert base64.b64decode(data)[:8] == b"\x89PNG\r\n\x1a\n"


def test_self_contained_with_version_hash_and_inputs(seed_html: str) -> None:
    assert not re.search(r'(src|href)="(http|file|/)', seed_html)  # nothing external
    assert chaindrive.__version__ in seed_html
    assert hashlib.sha256(SEED.read_bytes()).hexdigest() in seed_html
    assert "GOST 13568 ПР-25,4-60" in seed_html and "300" in seed_html


def test_warnings_come_first(seed_analysis, seed_html: str) -> None:
    warnings = seed_analysis.to_dict()["warnings"]
    assert warnings  # the seed example's slack is not taken up
    first = seed_html.index('<section id="inputs">')
    for w in warnings:
        assert 0 <= seed_html.find('class="warning"') < first
        assert w["message"].split(":")[0] in seed_html[:first]


def test_failed_check_is_highlighted() -> None:
    drive = chaindrive.load(SEED)
    weak = chaindrive.analyze(replace(drive, power=40e3), response=False)  # 80× the power
    assert not weak.check("hinge_pressure").passed
    html = render_html(build_report(weak, dpi=30))
    head = html[:html.index('<section id="inputs">')]
    assert 'class="fail"' in head and "hinge pressure" in head
    assert "<tr class=fail>" in head


def test_sections_slot_in(seed_analysis) -> None:
    register_section("extra", "Extra part", lambda inp: [Text("extra text")], before="damping")
    register_section("absent", "Absent part", lambda inp: None)
    try:
            html = render_html(build_report(seed_analysis, dpi=30))
    finally:
        SECTIONS[:] = [s for s in SECTIONS if s.key not in ("extra", "absent")]
    assert html.index('id="extra"') < html.index('id="damping"')
    assert 'id="absent"' not in html


def test_pdf_and_bad_suffix(seed_analysis, tmp_path: Path) -> None:
    pdf = write_report(seed_analysis, tmp_path / "r.pdf", source=SEED, dpi=30)
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF") and data.count(b"/Type /Page") >= 4
    with pytest.raises(DesignError):
        write_report(seed_analysis, tmp_path / "r.docx")


def test_dynamic_safety_factor_below_allowable_fails_red(seed_analysis) -> None:
    """k1 = Q/F1max below [k] ([MultimassChainDrives] §3.6) is a failed check at the top."""
    drive = seed_analysis.design
    strict = chaindrive.analyze(drive, limits=CheckLimits(allowable_dynamic_safety=1e6))
    html = render_html(build_report(strict, dpi=30))
    top = html[:html.index('<section id="inputs">')]
    assert "FAIL: k1: start-up" in top
    assert "FAIL: k2: steady motion" in top
    # and the row of k1 in the section's own table is red
    section = html[html.index('<section id="response">'):]
    assert re.search(r"<tr class=fail><td>start-up k1 = Q/F1max</td>", section)


def test_dynamic_response_section_tables(seed_analysis, seed_html: str) -> None:
    """K_D, per-span loads (static, steady, start-up, AFC) and per-mass inertia load and
    irregularity, with the values of the analysis (seed 000 §3.3, §3.6)."""
    from chaindrive.display import fmt

    response = seed_analysis.response
    section = seed_html[seed_html.index('<section id="response">'):
                        seed_html.index('<section id="damping">')]
    assert "<tr class=fail>" not in section  # the seed passes k1, k2, k2min (≥ 2.5)
    assert f"<td class=\"num\">{fmt(response.steady.coefficient_of_dynamics)}</td>" in section
    for caption in ("Two-stage safety check", "Dynamic loads per span", "Steady motion per mass",
                    "Material pairs"):
        assert caption in section
    for span, f1 in zip(seed_analysis.geometry.spans, response.startup.max_span_force,
                        strict=True):
        assert f"<td>{span.start_name}→{span.end_name}</td>" in section
        assert f">{fmt(float(f1))}<" in section
    for s, inertia in zip(seed_analysis.drive.sprockets, response.steady.inertia_load,
                          strict=True):
        assert f"<td>{s.name}</td><td class=\"num\">{fmt(float(inertia))}</td>" in section


def test_no_response_no_section(seed_analysis) -> None:
    html = render_html(build_report(chaindrive.analyze(seed_analysis.design, response=False),
                                    dpi=30))
    assert 'id="response"' not in html and "safety factor k₁" not in html


def test_studies_only_when_asked(seed_analysis) -> None:
    html = render_html(build_report(chaindrive.analyze(seed_analysis.design, response=False),
                                    dpi=30))
    assert 'id="damping"' not in html and "Material pairs" not in html
