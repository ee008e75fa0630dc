"""The page's identification view in a real browser, as a fitter would use it: the record
`docs/records/seed_synthetic.csv` dropped on "Identify a measured record" shows what
`chaindrive identify` finds in it (its notes, from chaindrive.identification.identify_record
of the same design and record), its spectrum and Campbell figures, and no exception. The
server and the browser are those shared by the browser tests (tests/e2e/conftest.py), the
session one of its own as in tests/e2e/test_app_limits.py (skipped, with the reason, when
Chromium or Playwright is not installed)."""

from __future__ import annotations

from typing import Any

import pytest

import chaindrive
from chaindrive.identification import identify_record
from chaindrive.io.record import read_record
from tests.conftest import EXAMPLES, ROOT
from tests.e2e.test_app_limits import _session

pytestmark = pytest.mark.concurrency  # a web server and a browser

RECORD = ROOT / "docs" / "records" / "seed_synthetic.csv"


def test_a_record_dropped_on_the_page_is_identified(browser: Any, app_url: str) -> None:
    from playwright.sync_api import expect

    analysis = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                                  response=False)
    doc = identify_record(read_record(RECORD), analysis).to_dict()
    pg = _session(browser, app_url)
    try:
        view = pg.get_by_test_id("stExpander").filter(has_text="Identify a measured record")
        view.get_by_text("Identify a measured record").click()
        images = view.get_by_test_id("stImage")
        expect(images).to_have_count(0)
        view.locator("input[type='file']").set_input_files(str(RECORD))
        for note in doc["notes"]:
            expect(view.get_by_text(note, exact=False)).to_be_visible()
        expect(images).to_have_count(2)                  # the spectrum and the Campbell
        expect(pg.get_by_test_id("stException")).to_have_count(0)
    finally:
        pg.close()
