"""The page's span-tension tool: a fitter enters a span and its measured transverse frequency
and reads the tension beside what the design expects, as `chaindrive tension` prints it
(chaindrive.identification.span_tension_reading; the string law [Mote1965])."""

from __future__ import annotations

import pytest
from streamlit.testing.v1 import AppTest

import chaindrive
import chaindrive.app as app_pkg
from chaindrive.app.views import tension_reading_records
from chaindrive.identification import span_tension_reading
from tests.conftest import EXAMPLES


def test_the_records_are_the_reading_in_the_units_asked() -> None:
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                           response=False)
    reading = span_tension_reading(a, "S2-S3", 5.0)
    rows = {r["quantity"]: r for r in tension_reading_records(reading.to_dict())}
    # standing string, n = 1: T = 4 L² f² q
    span = a.geometry.spans[1]
    q = a.drive.chain.spec.mass_per_length
    assert float(rows["tension read"]["value"]) == pytest.approx(
        4 * span.length**2 * 25.0 * q, rel=1e-3)
    assert rows["tension read"]["unit"] == "N"
    us = {r["quantity"]: r for r in tension_reading_records(reading.to_dict(), "US")}
    assert us["tension read"]["unit"] == "lbf"
    assert float(us["tension read"]["value"]) == pytest.approx(
        float(rows["tension read"]["value"]) / 4.4482216, rel=1e-3)


def test_the_page_reads_a_tension_from_a_frequency() -> None:
    at = AppTest.from_file(str(app_pkg.PAGE), default_timeout=90).run()
    assert not at.exception
    at.number_input(key="tension.frequency").set_value(5.0).run()
    assert not at.exception
    shown = [df.value for df in at.dataframe]
    assert any("tension read" in list(df["quantity"]) for df in shown
               if "quantity" in getattr(df, "columns", []))
