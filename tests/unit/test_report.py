"""The HTML report: the verdict first, every section and figure, failed checks in red, the
symbols defined where they first appear, studies only when asked for.

Numbers are compared with the analysis they come from (the report never computes); the
checks' sign convention is the one of :mod:`chaindrive.checks` (margin ≥ 0 passes).
"""

from __future__ import annotations

import base64
import hashlib
import re
from dataclasses import replace
from pathlib import Path

import pytest

import chaindrive
from chaindrive.checks import CheckLimits
from chaindrive.display import fmt
from chaindrive.errors import DesignError
from chaindrive.report import (
    SECTIONS,
    Text,
    build_report,
    register_section,
    render_html,
    write_report,
)
from chaindrive.report.content import ReportInput
from chaindrive.report.sections import FIRST_WARNINGS, estimates

ROOT = Path(__file__).parents[2]
SEED = ROOT / "examples" / "seed_three_sprocket.toml"
#: The sections of the seed example's report, in order (its design file is echoed).
EXPECTED_SECTIONS = ["summary", "inputs", "geometry", "kinematics", "selection", "strength",
                     "dynamics", "response", "checks", "design_file", "references"]
EXPECTED_PLOTS = {"layout", "chain_speed", "ratio", "tensions", "shaft_loads", "mode_shapes",
                  "campbell", "steady_loads", "inertia", "startup", "startup_speeds", "afc"}


@pytest.fixture(scope="module")
def seed_analysis() -> chaindrive.analysis.Analysis:
    # the example's own 1 s start-up: a shorter record ends before the forces settle, and
    # k1 then cannot be verified
    return chaindrive.analyze(chaindrive.load(SEED))


@pytest.fixture(scope="module")
def seed_html(seed_analysis) -> str:
    return render_html(build_report(seed_analysis, source=SEED, dpi=30))


def _section(html: str, key: str) -> str:
    start = html.index(f'<section id="{key}">')
    return html[start:html.index("</section>", start)]


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


def test_verdict_governing_checks_and_warnings_come_first(seed_analysis, seed_html: str) -> None:
    """The seed's idler S3 has 0.24 teeth in mesh, below the 3 of [Renold-DG], and the whole
    model's f₁ = 73.1 Hz lies 2.7 % below the 75 Hz tooth frequency (docs/dynamics.md §7),
    inside the 10 % band: the verdict says the design fails, names both, and its warnings
    follow. Its polymer sprockets' teeth (no confirmed allowable stress) cannot be verified:
    counted among the checks it fails."""
    summary = _section(seed_html, "summary")
    failed = [c for c in seed_analysis.checks() if c.status == "fail"]
    assert sorted(c.key for c in failed) == ["resonance_margin", "teeth_in_mesh[S3]"]
    unverified = [c for c in seed_analysis.checks() if c.status == "cannot be verified"]
    assert sorted(c.key for c in unverified) == sorted(
        f"{n}[{s}]" for s in ("S1", "S2", "S3")
        for n in ("tooth_root_stress", "tooth_contact_pressure"))
    assert 'class="verdict fail"' in summary
    assert f"FAILS 8 of {len(seed_analysis.checks())} checks" in summary
    assert "<tr class=fail><td>teeth in mesh (idler)</td><td>S3</td>" in summary
    assert "<tr class=fail><td>resonance margin (75 Hz above the natural frequency" in summary
    warnings = seed_analysis.warnings
    shown = warnings if len(warnings) <= FIRST_WARNINGS else warnings[:FIRST_WARNINGS - 1]
    for w in shown:
        assert w.message.split(":")[0] in summary
    if len(shown) < len(warnings):  # page 1 points to the Checks section for the rest
        assert f"… and {len(warnings) - len(shown)} more" in summary


def test_margins_have_the_sign_of_the_checks(seed_analysis, seed_html: str) -> None:
    """Every margin shown is 100 × Check.margin_fraction, negative for a failing check
    (both the idler's teeth in mesh and the resonance margin of the tooth frequency fail
    here: 2.7 % detuning against the 10 % required gives −73 %) and positive for a passing
    one (the static safety factor)."""
    table = _section(seed_html, "checks")
    for key in ("teeth_in_mesh[S3]", "resonance_margin"):
        c = seed_analysis.check(key)
        assert c is not None and c.margin_fraction is not None and c.margin_fraction < 0
        assert f">{fmt(100 * c.margin_fraction)}<" in table
    res = seed_analysis.check("resonance_margin")
    assert res.margin_fraction == pytest.approx(res.value / res.limit - 1.0, rel=1e-12)
    ok = next(c for c in seed_analysis.checks() if c.passed and c.margin_fraction)
    assert ok.margin_fraction > 0 and f">{fmt(100 * ok.margin_fraction)}<" in table
    assert "<tr class=fail><td>teeth in mesh (idler)" in table


def test_failed_check_is_highlighted() -> None:
    drive = chaindrive.load(SEED)
    weak = chaindrive.analyze(replace(drive, power=40e3), response=False)  # 80× the power
    assert not weak.check("hinge_pressure").passed
    html = render_html(build_report(weak, dpi=30))
    head = _section(html, "summary")
    assert 'class="verdict fail"' in head and "hinge pressure" in head
    assert "<tr class=fail><td>hinge pressure</td>" in head


def test_sections_slot_in(seed_analysis) -> None:
    register_section("extra", "Extra part", lambda inp: [Text("extra text")], before="checks")
    register_section("absent", "Absent part", lambda inp: None)
    try:
        html = render_html(build_report(seed_analysis, dpi=30))
    finally:
        SECTIONS[:] = [s for s in SECTIONS if s.key not in ("extra", "absent")]
    assert html.index('id="extra"') < html.index('id="checks"')
    assert 'id="absent"' not in html


def test_pdf_and_bad_suffix(seed_analysis, tmp_path: Path) -> None:
    pdf = write_report(seed_analysis, tmp_path / "r.pdf", source=SEED, dpi=30)
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF") and len(re.findall(rb"/Type\s*/Page(?![s\w])", data)) >= 4
    with pytest.raises(DesignError):
        write_report(seed_analysis, tmp_path / "r.docx")


def test_dynamic_safety_factor_below_allowable_fails_red(seed_analysis) -> None:
    """k1 = Q/F1max below [k] ([MultimassChainDrives, §3.6]) is a failed check at the top."""
    strict = chaindrive.analyze(seed_analysis.design,
                                limits=CheckLimits(allowable_dynamic_safety=1e6))
    html = render_html(build_report(strict, dpi=30))
    top = _section(html, "summary")
    assert "<tr class=fail><td>k1</td><td>start-up</td>" in top
    section = _section(html, "response")
    assert re.search(r"<tr class=fail><td>start-up</td><td>k₁</td>", section)


def test_dynamic_response_section_tables(seed_analysis, seed_html: str) -> None:
    """K_D, per-span loads (static, steady, start-up, AFC) and per-mass inertia load and
    irregularity, with the values of the analysis ([MultimassChainDrives, §3.3, §3.6])."""
    response = seed_analysis.response
    section = _section(seed_html, "response")
    assert "<tr class=fail>" not in section  # the seed passes k1, k2, k2min (≥ 2.5)
    assert f"<td class=\"num\">{fmt(response.steady.coefficient_of_dynamics)}</td>" in section
    for caption in ("Two-stage safety check", "Dynamic loads per span", "Steady motion per mass"):
        assert caption in section
    for span, f1 in zip(seed_analysis.geometry.spans, response.startup.max_span_force,
                        strict=True):
        assert f"<td>{span.start_name}→{span.end_name}</td>" in section
        assert f">{fmt(float(f1))}<" in section
    for s, inertia in zip(seed_analysis.drive.sprockets, response.steady.inertia_load,
                          strict=True):
        assert f"<td>{s.name}</td><td class=\"num\">{fmt(float(inertia))}</td>" in section


def test_ring_and_span_resonances_apart(seed_analysis, seed_html: str) -> None:
    """Ring modes are named by their mode, span (parametric) resonances by their span, and
    the detuning is |f_w − f_n|/f_n ≥ 0 in both tables (no "mode 0/1" for a span)."""
    section = _section(seed_html, "dynamics")
    ring = section[section.index("Resonances of the ring"):section.index("Parametric")]
    spans = section[section.index("Parametric resonances of the spans"):]
    for r in seed_analysis.dynamics.resonances:
        row = f"<td class=\"num\">{fmt(r.detuning_percent)}</td>"
        if r.working.kind == "parametric":
            span = seed_analysis.geometry.spans[r.mode]
            assert f"<td>{span.start_name}→{span.end_name}</td>" in spans and row in spans
        else:
            assert f"<td>mode {r.mode}</td>" in ring and row in ring
    assert "mode 0" not in spans


def _body(html: str) -> str:
    """The report without its list of references (whose entries describe whole papers)."""
    return html[:html.index('<section id="references">')]


@pytest.fixture(scope="module")
def quick_html(seed_analysis) -> str:
    """The report of the seed analysed without the response and without studies: one
    render serves the two tests of what such a report leaves out."""
    return render_html(build_report(chaindrive.analyze(seed_analysis.design, response=False),
                                    dpi=30))


def test_no_response_no_section(quick_html: str) -> None:
    html = quick_html
    assert 'id="response"' not in html and "k₁" not in _body(html)


def test_studies_only_when_asked(seed_analysis, quick_html: str) -> None:
    html = _body(quick_html)
    assert 'id="materials"' not in html and 'id="damping"' not in html
    assert "Absorption coefficient" not in html and "ψ" not in html
    asked = chaindrive.analyze(seed_analysis.design, response=False,
                               studies=("hinge_friction",))
    html = render_html(build_report(asked, dpi=30))
    assert 'id="damping"' in html and 'id="materials"' not in html


def test_us_customary_units(seed_analysis) -> None:
    """--units us: lengths in inches (1 in = 25.4 mm exactly [NIST-SP811]), forces in lbf."""
    html = render_html(build_report(seed_analysis, dpi=30, units="US"))
    inputs = _section(html, "inputs")
    assert "x, in" in inputs and "x, mm" not in inputs
    assert f">{fmt(1364 / 25.4)}<" in inputs  # S1 at x = 1364 mm
    assert "F_R, lbf" in _section(html, "strength")
    with pytest.raises(DesignError, match="units"):
        build_report(seed_analysis, units="imperial")


def test_inertia_estimate_named_only_where_the_design_gives_none() -> None:
    """The seed enters a reduced mass for every sprocket (everything that turns with it,
    [MultimassChainDrives, §3.1]): nothing is estimated. The Jindal drive gives neither an
    inertia nor a reduced mass: both bodies are estimated, and the report says so."""
    seed = chaindrive.analyze(chaindrive.load(SEED), response=False)
    assert not any("Moments of inertia" in n for n in estimates(ReportInput(seed)))
    jindal = chaindrive.analyze(chaindrive.load(ROOT / "examples" / "two_sprocket_jindal.toml"),
                                response=False)
    notes = [n for n in estimates(ReportInput(jindal)) if "Moments of inertia" in n]
    names = ", ".join(s.name for s in jindal.drive.sprockets)
    assert len(notes) == 1 and f"of the bodies of {names} estimated" in notes[0]
