"""Fixes of an audit of the report and its figures: page 1 lists every default and estimate
the analysis says it rests on; the Campbell diagram and the AFC number the modes as the
tables do and name the spans; catalogue estimates are shown short and called estimates; the
F₁max of the start-up figure is written by the tables' rule; the ratio figure names its
pair; the resonance section says which tooth harmonics it covers; the verdict page is not
followed by a nearly empty page.

Every expectation is read from the analysis (the report computes nothing).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

import chaindrive
from chaindrive import plotting
from chaindrive.display import RPM_PER_RAD_S, fmt
from chaindrive.plotting.dynamics import crossing_label
from chaindrive.report import Plot, Table, Text, build_report, report_text
from chaindrive.report.content import ReportInput
from chaindrive.report.pdf import page_map
from chaindrive.report.sections import ESTIMATE_CODES
from chaindrive.report.sections import estimates as rest_on
from chaindrive.report.sections_dynamics import tooth_harmonics
from chaindrive.report.sources import catalogue_estimates, readable_source

EXAMPLES = Path(__file__).parents[2] / "examples"
POLYMER_SOURCE = (
    "catalogue row: dims: ISO 606:1994 16B [ISO606]; material: PA66-GF30 = 30 % glass-fibre "
    "PA66 [HPT] via materials.csv; ESTIMATED: breaking_load_kN|mass_kg_m|allowable_load_kN|"
    "max_speed_m_s (header formulas; speed: [TsubakiGuide] Table 4.1 transferred)")


def _analysis(name: str, **kw: bool) -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(EXAMPLES / f"{name}.toml")
    short = replace(drive.dynamics, startup_duration=0.1)  # a short start-up keeps it fast
    return chaindrive.analyze(replace(drive, dynamics=short), **kw)


@pytest.fixture(scope="module")
def seed() -> chaindrive.analysis.Analysis:
    return _analysis("seed_three_sprocket")


@pytest.fixture(scope="module")
def jindal() -> chaindrive.analysis.Analysis:
    return _analysis("two_sprocket_jindal")


@pytest.fixture(scope="module")
def polymer() -> chaindrive.analysis.Analysis:
    return _analysis("seed_three_sprocket_polymer", response=False)


@pytest.fixture(scope="module")
def eight() -> chaindrive.analysis.Analysis:
    return _analysis("eight_sprocket", response=False)


# one report per analysis serves every test that reads it (a Report is only read)
@pytest.fixture(scope="module")
def seed_report(seed) -> chaindrive.report.Report:
    return build_report(seed, dpi=20)


@pytest.fixture(scope="module")
def jindal_report(jindal) -> chaindrive.report.Report:
    return build_report(jindal, dpi=20)


@pytest.fixture(scope="module")
def polymer_report(polymer) -> chaindrive.report.Report:
    return build_report(polymer, dpi=20)


def _blocks(report: chaindrive.report.Report, key: str) -> tuple[object, ...]:
    return next(s for s in report.sections if s.key == key).blocks


# --- 1. page 1: the defaults and estimates -------------------------------------------------------

@pytest.mark.parametrize("name", ["seed_three_sprocket", "two_sprocket_jindal",
                                  "seed_three_sprocket_polymer", "conveyor_five_sprocket"])
def test_every_estimate_warning_is_listed(name: str) -> None:
    """Each warning of the analysis that says an input was estimated or assumed (installed
    sag, computed link stiffness, …) is in the list, in full or (shown in full among page 1's
    warnings) in one line."""
    a = _analysis(name, response=False)
    items = rest_on(ReportInput(a))
    estimates = [w for w in a.warnings if w.code in ESTIMATE_CODES]
    assert estimates  # every example rests on an assumed sag or a computed link stiffness
    for w in estimates:
        assert any(w.message[1:] in i for i in items), w.message
    short = rest_on(ReportInput(a), shown=[w.message for w in estimates])
    assert len(short) == len(items)
    assert sum("(the warning above)" in i for i in short) == len(estimates)


def test_damping_by_the_material_pair_is_listed_a_given_one_is_not(seed) -> None:
    source = seed.drive_model.damping_source
    assert seed.drive.dynamics.damping_ratio is None and not source.startswith("given")
    items = rest_on(ReportInput(seed))
    line = [i for i in items if i.startswith("Damping ratio")]
    assert len(line) == 1 and fmt(seed.dynamics.damping_ratio) in line[0] and source in line[0]
    drive = seed.drive
    given = chaindrive.analyze(replace(drive, dynamics=replace(drive.dynamics,
                                                               damping_ratio=0.05)),
                               response=False)
    assert given.drive_model.damping_source.startswith("given")
    assert not any(i.startswith("Damping ratio") for i in rest_on(ReportInput(given)))


def test_service_factor_listed_only_when_not_given(seed, jindal, jindal_report) -> None:
    assert seed.drive.service_factor is not None
    assert not any("service_factor" in i for i in rest_on(ReportInput(seed)))
    assert jindal.drive.service_factor is None and jindal.strength is not None
    line = [i for i in rest_on(ReportInput(jindal)) if "service_factor" in i]
    assert len(line) == 1 and fmt(jindal.strength.operating_factor) in line[0]
    inputs = next(b for b in _blocks(jindal_report, "inputs")
                  if isinstance(b, Table) and b.caption == "Drive and chain")
    assert ("service factor", "K_s", "1 (default)", "") in inputs.rows


def test_polymer_chain_data_are_called_estimates(polymer, polymer_report) -> None:
    spec = polymer.drive.chain.spec
    marked = catalogue_estimates(spec.source)
    assert marked == ("breaking load", "mass per length", "allowable load", "speed limit")
    line = [i for i in rest_on(ReportInput(polymer)) if spec.designation in i]
    assert len(line) == 1 and "estimates of the catalogue" in line[0]
    assert all(m in line[0].lower() for m in marked) and "[TsubakiGuide]" in line[0]
    inputs = next(b for b in _blocks(polymer_report, "inputs")
                  if isinstance(b, Table) and b.caption == "Drive and chain")
    labels = [r[0] for r in inputs.rows]
    assert {"breaking load (estimate)", "mass per length (estimate)",
            "allowable load (estimate)", "speed limit (estimate)"} <= set(labels)


# --- 4. catalogue sources ---------------------------------------------------------------------

def test_readable_source_is_short_and_keeps_the_citations() -> None:
    text = readable_source(POLYMER_SOURCE)
    assert text.startswith("catalogue row, estimate: breaking load, mass per length, "
                           "allowable load, speed limit")
    assert "ESTIMATED" not in text and "|" not in text and "materials.csv" not in text
    for key in ("[ISO606]", "[HPT]", "[TsubakiGuide]"):
        assert key in text
    assert readable_source("[Shigley2015, §17-5]") == "[Shigley2015, §17-5]"
    assert catalogue_estimates("dims, Q, q: GOST 13568-97 Table 1") == ()


def test_polymer_check_sources_in_the_report(polymer, polymer_report) -> None:
    report = polymer_report
    cells = [str(v) for s in report.sections for b in s.blocks if isinstance(b, Table)
             for r in b.rows for v in r]
    assert not any("ESTIMATED:" in c for c in cells)
    checks = next(b for b in _blocks(report, "checks") if isinstance(b, Table))
    speed = [r for r in checks.rows if r[0].startswith("speed limit")]
    assert speed and "estimate" in speed[0][-1]
    refs = {b.text.split("]")[0][1:] for b in _blocks(report, "references")
            if isinstance(b, Text)}
    assert {"TsubakiGuide", "HPT", "ISO606"} <= refs


# --- 2. mode numbers and span names of the figures ---------------------------------------------

def test_crossing_labels_number_modes_as_the_tables() -> None:
    assert crossing_label("tooth x1", 0) == "tooth x1 × mode 1"
    assert crossing_label("tooth x3", 1, mode_numbers=[1, 2, 3]) == "tooth x3 × mode 2"
    assert crossing_label("tooth x1", 0, mode_numbers=[2, 3]) == "tooth x1 × mode 2"
    assert (crossing_label("parametric span 6", -1, span_names=[f"s{i}" for i in range(7)])
            == "tooth x1 = 2·f₁ of span s6")
    assert crossing_label("parametric span 6", -1) == "tooth x1 = 2·f₁ of span 7"


def _legend_texts(fig) -> list[str]:
    fig.canvas.draw()
    legend = fig.axes[0].get_legend()
    return [t.get_text() for t in legend.get_texts()]


def test_campbell_of_the_report_names_mode_1_and_spans(seed, eight, seed_report) -> None:
    """The seed's tooth frequency crosses the first elastic mode (73.1 Hz, mode 1 of the
    tables) near the working speed; the eight-sprocket drive's parametric zone is named by
    its span (T→D5), never by an index."""
    for a, report in ((seed, seed_report), (eight, build_report(eight, dpi=20))):
        modal = a.dynamics.modal
        elastic = [j for j in range(len(modal.frequencies_hz)) if not modal.rigid_body[j]]
        spans = [f"{s.start_name}→{s.end_name}" for s in a.geometry.spans]
        fig = plotting.campbell_diagram(a.dynamics.campbell,
                                        operating_rpm=a.drive.driver.speed * RPM_PER_RAD_S,
                                        band_percent=10.0, mode_numbers=elastic,
                                        span_names=spans)
        texts = _legend_texts(fig)
        named = [t for t in texts if "rpm," in t and "operating" not in t]
        assert named
        assert not any("mode 0" in t for t in named)
        for t in named:
            if "of span" in t:
                assert t.split("of span ")[1].split(":")[0] in spans
        caption = next(b.caption for b in _blocks(report, "dynamics")
                       if isinstance(b, Plot) and b.key == "campbell")
        assert "modes numbered as in the tables" in caption
    seed_fig = plotting.campbell_diagram(seed.dynamics.campbell, operating_rpm=300.0,
                                         band_percent=10.0)
    assert any(t.startswith("tooth x1 × mode 1: ") for t in _legend_texts(seed_fig))


def test_afc_labels_take_the_table_numbers(seed) -> None:
    afc = seed.response.afc
    fig = plotting.afc_curves(afc, mode_numbers=[10, 20, 30, 40, 50])
    fig.canvas.draw()
    labels = [t.get_text() for t in fig.axes[0].texts]
    assert labels and all(t.split("mode ")[1].split(" ×")[0] in {"10", "20", "30", "40", "50"}
                          for t in labels)


# --- 5. F₁max by the tables' rule -------------------------------------------------------------

def test_startup_figure_writes_f1max_as_the_table(jindal, jindal_report) -> None:
    startup = jindal.response.startup
    fig = plotting.startup_oscillogram(startup)
    fig.canvas.draw()
    peak = float(startup.max_span_force.max())
    assert any(f"F₁max = {fmt(peak)} N" in t.get_text() for t in fig.axes[0].texts)
    report = jindal_report
    loads = next(b for b in _blocks(report, "response")
                 if isinstance(b, Table) and b.caption == "Dynamic loads")
    row = next(r for r in loads.rows if r[1] == "F₁max")
    assert fmt(row[2]) == fmt(peak)


# --- 6. the ratio figure names its pair -------------------------------------------------------

def test_ratio_figure_names_the_pair(seed, seed_report) -> None:
    i, j = plotting.ratio_pair(seed)
    a, b = seed.drive.sprockets[i], seed.drive.sprockets[j]
    assert (a.name, b.name) == ("S1", "S3")  # the tight span S3→S1 ends on the driver
    fig = plotting.transmission_ratio(seed)
    texts = _legend_texts(fig)
    assert "ω(S1) / ω(S3)" in texts
    assert f"z(S3) / z(S1) = {b.teeth}/{a.teeth} = {fmt(b.teeth / a.teeth)}" in texts
    assert fig.axes[0].get_ylabel() == "ratio ω(S1) / ω(S3)"
    report = seed_report
    caption = next(b.caption for b in _blocks(report, "kinematics")
                   if isinstance(b, Plot) and b.key == "ratio")
    assert "ω(S1)/ω(S3)" in caption and "S3" in caption


# --- 7. cosmetics ----------------------------------------------------------------------------

def test_glance_unit_column_holds_units_and_captions_say_orange(seed, seed_report) -> None:
    report = seed_report
    glance = next(b for b in _blocks(report, "summary")
                  if isinstance(b, Table) and b.caption == "The design at a glance")
    assert not any("allowable" in str(r[2]) for r in glance.rows)
    allow = seed.response.strength_dict()["allowable_k"]
    assert any(f"(allowable {fmt(allow)})" in r[0] for r in glance.rows)
    text = report_text(report.sections)
    assert "tight span red" not in text and "tight span orange" in text


def test_no_nearly_empty_page_after_the_verdict(jindal_report) -> None:
    """Page 1 of the Jindal report runs over: the rest of the summary and the inputs share
    page 2 (a forced page break used to leave the rest alone there); a verdict that fits
    page 1 still stands alone on it."""
    report = jindal_report
    where = page_map(report)
    assert where["summary"] == 1 and where["inputs"] == 2


# --- 8. which tooth harmonics the resonance check covers -------------------------------------

def test_resonance_section_says_its_harmonics(seed, seed_report) -> None:
    ks = sorted(w.harmonic for w in seed.dynamics.working if w.kind == "tooth")
    assert ks == [1, 2, 3] and tooth_harmonics(ReportInput(seed)) == "1–3"
    report = seed_report
    texts = [b.text for b in _blocks(report, "dynamics") if isinstance(b, Text)]
    assert any("harmonics 1–3 of the tooth frequency" in t
               and f"the {seed.drive.dynamics.harmonics} harmonics" in t for t in texts)
    ring = next(b for b in _blocks(report, "dynamics")
                if isinstance(b, Table) and b.caption.startswith("Resonances of the ring"))
    assert "tooth harmonics 1–3" in ring.caption
