"""The page's identification view: a CSV record uploaded on the page is matched to the
model as `chaindrive identify` matches it (the one entry point,
chaindrive.identification.identify_record); the rows on the page are the document's peaks."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from streamlit.testing.v1 import AppTest

import chaindrive
import chaindrive.app as app_pkg
from chaindrive.app.views import identification_records
from chaindrive.identification import identify_record
from chaindrive.io.record import read_record, record_from_csv_bytes
from tests.conftest import EXAMPLES

RECORD = Path(__file__).resolve().parents[2] / "docs" / "records" / "seed_synthetic.csv"


def test_an_uploaded_record_reads_as_the_file_does() -> None:
    data = RECORD.read_bytes()
    upload, file = record_from_csv_bytes(RECORD.name, data), read_record(RECORD)
    assert upload.sample_rate == file.sample_rate and list(upload.signals) == list(file.signals)
    for k in file.signals:
        assert np.array_equal(upload.signals[k], file.signals[k])


def test_the_rows_are_the_documents_peaks() -> None:
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                           response=False)
    doc = identify_record(read_record(RECORD), a).to_dict()
    rows = identification_records(doc)
    peaks = [p for sig in doc["signals"] for p in sig["peaks"]]
    assert [r["is"] for r in rows] == [p["label"] for p in peaks]
    assert "mode 1" in [r["is"] for r in rows]
    assert all(r["ζ half-power"] == "not resolved" for r, p in zip(rows, peaks, strict=True)
               if p["damping_ratio_half_power"] is None)


def test_the_page_identifies_an_uploaded_run_up() -> None:
    fs, seconds = 1000.0, 10.0
    t = np.arange(int(fs * seconds)) / fs
    n = (100.0 + 15.0 * t) / 60.0                     # 100 → 250 rpm
    theta = 2 * math.pi * np.cumsum(n) / fs
    x = np.sin(15 * theta) + 0.5 * np.sin(2 * math.pi * 73.06 * t)
    text = "time_s,speed_rpm,a_m_s2\n" + "\n".join(
        f"{a:.4f},{60 * b:.3f},{c:.4f}" for a, b, c in zip(t, n, x, strict=True))
    at = AppTest.from_file(str(app_pkg.PAGE), default_timeout=120).run()
    assert not at.exception
    verdicts = len(at.error)                           # the design's own failed checks
    at.file_uploader(key="ident.record").upload("runup.csv", text.encode(), "text/csv").run()
    assert not at.exception and len(at.error) == verdicts
    at.selectbox(key="ident.speed").set_value("speed_rpm").run()
    assert not at.exception and len(at.error) == verdicts
    shown = [df.value for df in at.dataframe if "is" in getattr(df.value, "columns", [])]
    assert shown and "mode 1" in list(shown[-1]["is"])
    assert any("working frequencies listed are the" in c.value for c in at.caption)
