"""The report's section on a measured record: present only when a record is given, its
peaks the identification's own (chaindrive.identification.identify_record), its figures the
spectrum, and for a run-up the order spectrum and the Campbell diagram with the measured
points."""

from __future__ import annotations

from pathlib import Path

import pytest

import chaindrive
from chaindrive.analysis import Analysis
from chaindrive.identification import identify_record
from chaindrive.io.record import read_record
from chaindrive.report import build_report, report_text
from tests.conftest import EXAMPLES

RECORDS = Path(__file__).resolve().parents[2] / "docs" / "records"


@pytest.fixture(scope="module")
def seed() -> Analysis:
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                              response=False)


def test_no_record_no_section(seed: Analysis) -> None:
    report = build_report(seed, dpi=50)
    assert "identification" not in [s.key for s in report.sections]


def test_a_run_up_record_gives_its_peaks_orders_and_campbell(seed: Analysis) -> None:
    result = identify_record(read_record(RECORDS / "seed_runup.csv"), seed, speed="speed_rpm")
    report = build_report(seed, dpi=50, identification=result)
    section = next(s for s in report.sections if s.key == "identification")
    text = report_text([section])
    doc = result.to_dict()
    for p in doc["signals"][0]["peaks"]:
        assert p["label"] in text
    assert "tooth x1" in text and "[Brandt2011]" in text
    assert {"identification_spectrum", "identification_orders",
            "identification_campbell"} <= set(report.plots)
    refs = report_text([s for s in report.sections if s.key == "references"])
    assert "Brandt" in refs and "Ewins" in refs
