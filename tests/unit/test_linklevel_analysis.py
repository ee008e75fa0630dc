"""The link-level model as the analysis' study "links": ``Analysis.link_level`` is the run
(None unless asked), ``to_dict()`` carries its summary and the table beside the whole-drive
model, and the report has its section only on request.

Expected values: the link-level block is the run's own summary (the same numbers, not
recomputed); the whole-drive column is the analysis' own steady state, start-up and modes;
K_D = 1 + F_D/F_t with F_D the RMS of the span dynamic loads [MultimassChainDrives, §3.3]
(closed form); the seed example is the worked example of [MultimassChainDrives].
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import DesignError
from chaindrive.report import build_report, render_html
from tests.conftest import EXAMPLES

#: A short run keeps the suite fast (the model's own validation is
#: tests/validation/test_linklevel.py).
DURATION = 0.05


@pytest.fixture(scope="module")
def seed():
    """The seed example with a 0.1 s start-up of the whole-drive model."""
    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    return replace(drive, dynamics=replace(drive.dynamics, startup_duration=0.1))


@pytest.fixture(scope="module")
def asked(seed):
    return chaindrive.analyze(seed, studies=("links",), link_duration_s=DURATION)


@pytest.fixture(scope="module")
def asked_report(asked):
    """The report of ``asked`` (frozen sections and blocks: the tests only read it)."""
    return build_report(asked, dpi=30)


def test_link_level_only_when_asked(seed) -> None:
    plain = chaindrive.analyze(seed, lazy=True)
    assert plain.link_level is None and plain.link_level_comparison is None
    assert "link_level" not in chaindrive.analyze(seed, response=False).to_dict()


def test_block_is_the_runs_summary(asked) -> None:
    result = asked.link_level
    assert result is not None
    assert result.times[-1] == pytest.approx(DURATION, abs=2 * (result.times[1]
                                                                - result.times[0]))
    block = asked.to_dict()["link_level"]
    own = result.to_dict()
    for key in ("span_names", "span_dynamic_load_n", "peak_span_force_n",
                "coefficient_of_dynamics", "nominal_force_n", "duration_s", "energy_j"):
        assert block[key] == own[key], key
    fd = np.asarray(block["span_dynamic_load_n"])
    assert block["coefficient_of_dynamics"] == pytest.approx(
        1 + np.sqrt(np.mean(fd**2)) / block["nominal_force_n"], rel=1e-12)


def test_comparison_sets_the_two_models_side_by_side(asked) -> None:
    """Each row holds the whole-drive model's figure (its steady state, start-up and first
    mode, as the analysis reports them) beside the run's."""
    rows = {r["quantity"]: r for r in asked.to_dict()["link_level"]["dynamics_comparison"]}
    result, steady, startup = asked.link_level, asked.steady, asked.startup
    kd = rows["coefficient of dynamics K_D"]
    assert kd["whole_drive"] == steady.coefficient_of_dynamics
    assert kd["link_level"] == result.coefficient_of_dynamics
    assert rows["dynamic load F_D (RMS over the spans)"]["whole_drive"] == \
        steady.dynamic_load_rms
    for k, span in enumerate(result.span_names):
        f2 = rows[f"steady dynamic load F₂ of span {span}"]
        assert f2["whole_drive"] == steady.span_dynamic_load[k]
        assert f2["link_level"] == result.span_dynamic_load[k]
        f1 = rows[f"start-up peak F₁max of span {span}"]
        assert f1["whole_drive"] == startup.max_span_force[k]
        assert f1["link_level"] == result.peak_span_force[k]
        assert f1["unit"] == "N"
    first = rows["first natural frequency"]
    assert first["whole_drive"] == asked.dynamics.modal.first_elastic_frequency_hz
    # the link-level's from its linearisation: the seed shares the whole drive's physics,
    # within 5 % (docs/linklevel.md §6: 76.1 against 73.1 Hz)
    assert first["link_level"] == pytest.approx(first["whole_drive"], rel=0.05)
    assert first["unit"] == "Hz" and first["governing"] is None  # not a load
    # of every load the larger governs
    for row in rows.values():
        if row["unit"] == "N" and None not in (row["whole_drive"], row["link_level"]):
            larger = "whole_drive" if row["whole_drive"] >= row["link_level"] else "link_level"
            assert row["governing"] == larger, row["quantity"]
    # 50 ms from rest: the driver is still far from its 300 rpm
    assert asked.to_dict()["link_level"]["settled"] is False


def test_duration_is_bounded(seed) -> None:
    with pytest.raises(DesignError, match="link_duration_s: 20 s is outside"):
        chaindrive.analyze(seed, studies=("links",), link_duration_s=20.0, lazy=True)
    with pytest.raises(DesignError, match="studies"):
        chaindrive.analyze(seed, studies=("link",), lazy=True)


def test_report_section_only_on_request(seed, asked, asked_report) -> None:
    """The section "Link-level model" with its table and three figures when the study ran;
    absent from the report of the same design without it."""
    report = asked_report
    keys = [s.key for s in report.sections]
    assert keys.index("response") < keys.index("links") < keys.index("checks")
    section = next(s for s in report.sections if s.key == "links")
    table = next(b for b in section.blocks if getattr(b, "columns", None))
    assert table.columns == ("quantity", "whole drive", "link level", "unit", "governs")
    assert len(table.rows) == len(asked.link_level_comparison.rows)
    names = {"whole_drive": "whole drive", "link_level": "link level", None: ""}
    assert [r[-1] for r in table.rows] == [names[g] for g in
                                           asked.link_level_comparison.governing]
    plots = [b.key for b in section.blocks if hasattr(b, "png")]
    assert plots == ["link_frames", "link_tensions", "tooth_loads"]
    html = render_html(report)
    assert 'id="links"' in html
    plain = chaindrive.analyze(seed, response=False)
    assert 'id="links"' not in render_html(build_report(plain, dpi=30))


def test_report_section_defines_its_symbols_and_typesets(asked_report) -> None:
    """The rule of tests/unit/test_report_pdf.py on a report with the study: no glossary
    symbol before its definition, no internal reference, and Typst sets the PDF."""
    from chaindrive.report import Definitions, render_pdf
    from chaindrive.report.pdf import typst_source
    from chaindrive.report.symbols import SYMBOLS
    from tests.unit.test_report_pdf import INTERNAL, _occurs, _words

    report = asked_report
    distinctive = {k: s.text for k, s in SYMBOLS.items()
                   if len(s.text) > 1 or not s.text.isascii()}
    defined: set[str] = set()
    for section in report.sections:
        if section.key in ("references", "design_file"):
            continue
        for b in section.blocks:
            if isinstance(b, Definitions):
                defined.update(b.keys)
                continue
            for text in _words(b):
                for key, sym in distinctive.items():
                    assert key in defined or not _occurs(sym, text), (section.key, sym, text)
    assert INTERNAL.search(typst_source(report)[0]) is None
    assert render_pdf(report)[:4] == b"%PDF"


def test_unsettled_run_leaves_the_steady_checks_to_the_whole_drive_model(asked) -> None:
    """50 ms from rest: the link-level steady loads still hold the start-up, so k₂ keeps the
    whole-drive model's value and says why; every check resting on a dynamic load names its
    model (docs/linklevel.md §6)."""
    k2 = asked.check("k2")
    assert k2.value == asked.steady.k2
    assert k2.governing_model == "whole_drive"
    assert "not at its nominal speed" in k2.note
    governed = {c.key: c.governing_model for c in asked.checks() if c.governing_model}
    assert set(governed) >= {"k1", "k2", "k2min", "fatigue"}
    plain = chaindrive.analyze(asked.design, lazy=True)
    assert all(c.governing_model is None for c in plain.checks())
