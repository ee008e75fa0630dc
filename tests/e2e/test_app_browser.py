"""The web page driven by a real browser, as a person would use it.

Playwright for Python drives Debian's Chromium (``apt-get install -y chromium``; Playwright's
own browser download cannot reach its servers from these machines). The page is started
on a free 127.0.0.1 port in a subprocess (headless, no usage statistics) and always stopped
again (fixture finalizer); the server and the browser are shared with the other browser
tests of the test process (tests/e2e/conftest.py), and each test opens its own session
(a tab of its own).
Every wait is on something the page shows — its ready marker (written last in a run), its
results marker (written right after the contour, the headline numbers and the verdict), the
values on screen — never a fixed sleep; every number is checked against ``chaindrive.analyze``
of the same design.

* the seed example: a tooth count changed through the "edit one sprocket" form (links and
  warnings follow), values typed in the sprocket table one after the other (both kept), the
  PDF report downloaded, a bad tooth count (form) and text in a number cell (table) giving
  the loader's message; a screenshot at
  1400×900 (copied to docs/app_seed.png when CHAINDRIVE_UPDATE_SCREENSHOTS=1);
* the 24-sprocket example at 1400×900 and 1024×768: the contour and the verdict above the
  fold, a loaded file resetting the edit form and the deltas, and the time from an edit to
  its results on screen, measured (written to CHAINDRIVE_BENCH_OUT when set, which is how
  ``benchmarks/bench_app_browser.py`` reports it, over eight edits each way; two each way
  otherwise) but never asserted on.

Skipped (with the reason) only when Chromium or Playwright is not installed.
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import time
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import chaindrive
from chaindrive.display import fmt
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping
from tests.e2e.conftest import CHROMIUM, new_tab

pytestmark = pytest.mark.concurrency  # a web server and a browser

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "examples" / "seed_three_sprocket.toml"
BIG = ROOT / "examples" / "twenty_four_sprocket.toml"
SCREENSHOT = ROOT / "docs" / "app_seed.png"
#: The edited sprocket (0-based row; S3, the idler of the seed contour) and its new counts.
ROW, NEW_TEETH, BAD_TEETH = 2, 30, 3
#: Waits [ms]: the first page run imports numpy, scipy, pint…; later runs take well under a
#: second, the report a few seconds (more on a loaded machine).
FIRST_MS, STEP_MS, REPORT_MS = 90_000, 30_000, 120_000
#: The 24-sprocket edits timed: tooth counts of S2 (an inside idler), one design each — in
#: the table, then through the form; no design twice, so that none is served from the
#: page's store of finished screens.
TIMED_TEETH = (16, 17, 18, 19, 20, 21, 22, 15)
FORM_TEETH = (23, 24, 25, 26, 27, 28, 29, 30)
#: Edits made each way when the times are not wanted (no CHAINDRIVE_BENCH_OUT): two, so
#: that each way is checked on a fresh design and on one edited the same way just before.
#: Every further edit takes the same path to the same checks (its own design's markers); the
#: eight a way serve the benchmark's medians only (the test took 31 s of wall with them).
CHECKED_EDITS = 2

if not (CHROMIUM.is_file() and os.access(CHROMIUM, os.X_OK)):
    pytest.skip(f"Chromium not found at {CHROMIUM} (apt-get install -y chromium)",
                allow_module_level=True)
try:
    from playwright.sync_api import Locator, Page, expect
except ImportError:
    pytest.skip("Playwright for Python is not installed (pip install playwright)",
                allow_module_level=True)


# --- a page of its own on the shared server and browser (tests/e2e/conftest.py) -----------------

def _page(browser: Any, app_url: str, width: int, height: int) -> Iterator[Page]:
    """A page of its own (a new tab: a new session of the app, so a repeated test never
    starts from the state the previous one left), after its first complete run."""
    pg = new_tab(browser, width, height)
    try:
        pg.set_default_timeout(STEP_MS)
        expect.set_options(timeout=STEP_MS)
        pg.goto(app_url)
        _ready(pg, timeout=FIRST_MS)
        yield pg
    finally:
        pg.close()


@pytest.fixture
def page(browser: Any, app_url: str) -> Iterator[Page]:
    """The page at 1400×900, the size of the screenshots."""
    yield from _page(browser, app_url, 1400, 900)


# --- what the page shows -------------------------------------------------------------------------

def _ready(pg: Page, version: int | None = None, state: str = "ok",
           timeout: float = STEP_MS) -> int:
    """Wait for the page's ready marker (written last in every completed run) to report
    ``state`` for design ``version`` (any version when None); return the version."""
    marker = pg.locator("#chaindrive-ready")
    if version is not None:
        expect(marker).to_have_attribute("data-version", str(version), timeout=timeout)
    expect(marker).to_have_attribute("data-state", state, timeout=timeout)
    return int(marker.get_attribute("data-version") or "0")


def _design(pg: Page) -> str:
    """The tag of the design the page last completed (ready marker)."""
    return pg.locator("#chaindrive-ready").get_attribute("data-design") or ""


def _changed(pg: Page, marker: str, old: str, timeout: float = STEP_MS) -> None:
    """Wait until ``marker`` (``#chaindrive-results`` or ``#chaindrive-ready``) is written
    for a design other than ``old``."""
    pg.wait_for_function(
        "([m, o]) => { const e = document.querySelector(m); "
        "return e !== null && e.dataset.design !== undefined && e.dataset.design !== o; }",
        arg=[marker, old], timeout=timeout)


def _metric(pg: Page, label: str) -> Locator:
    return (pg.get_by_test_id("stMetric").filter(has=pg.get_by_text(label, exact=True))
            .get_by_test_id("stMetricValue"))


def _choose(pg: Page, box: str, option: str) -> None:
    """Pick ``option`` in the select box labelled ``box`` from the keyboard: type it (the
    list narrows to it), Enter; then the box shows it."""
    combo = pg.get_by_role("combobox", name=box)
    combo.click()
    combo.press_sequentially(option)
    expect(pg.get_by_role("option", name=option, exact=True)).to_be_visible()
    pg.keyboard.press("Enter")
    expect(combo).to_have_value(option)


def _load_example(pg: Page, path: Path) -> int:
    version = _ready(pg)
    _choose(pg, "Bundled examples", path.stem)
    pg.get_by_role("button", name="Load example").click()
    _ready(pg, version + 1)
    expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-source", path.name)
    return version + 1


def _teeth_field(pg: Page) -> Locator:
    field = pg.locator(".st-key-sprocket_editor").get_by_label("Teeth", exact=True)
    expect(field).to_have_count(1)  # the form of the row chosen, not a stale one
    return field


def _edit_teeth(pg: Page, row: int, name: str, shown: int, teeth: int) -> int:
    """Set the tooth count of sprocket ``row`` through the "edit one sprocket" form; returns
    the design version the edit produces."""
    version = _ready(pg)
    _choose(pg, "Sprocket to edit", f"row {row + 1}: {name}")
    expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-editing", str(row))
    field = _teeth_field(pg)
    expect(field).to_have_value(str(shown))  # the form shows the chosen sprocket
    field.fill(str(teeth))
    pg.get_by_role("button", name="Apply", exact=True).click()
    return version + 1


def _cell(pg: Page, column: str, row: int) -> Locator:
    """The field of ``column`` (a row key: ``teeth``, ``x_mm``) in row ``row`` (from 0) of
    the sprocket table, scrolled into view."""
    cell = pg.locator(f'.cd-table [data-row="{row}"][data-column="{column}"]')
    expect(cell).to_have_count(1)
    cell.scroll_into_view_if_needed()
    return cell


# --- the design, computed by the library ---------------------------------------------------------

def _edited(path: Path, **rows: dict[str, Any]) -> dict[str, Any]:
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    for row, values in rows.items():
        data["sprockets"][int(row[1:])].update(values)
    return data


def _analysis(path: Path, **rows: dict[str, Any]) -> Any:
    """``chaindrive.analyze`` of ``path`` with the given rows edited (``r2={"teeth": 30}``),
    the quick part the page redraws after every edit."""
    return chaindrive.analyze(drive_from_mapping(_edited(path, **rows)), response=False)


def _loader_message(teeth: int | str) -> str:
    """The line the loader (and so ``chaindrive analyze``) gives for a bad tooth count."""
    with pytest.raises(ChainDriveError) as info:
        drive_from_mapping(_edited(SEED, **{f"r{ROW}": {"teeth": teeth}}))
    return str(info.value)


# --- the tests -----------------------------------------------------------------------------------

def test_seed_edit_table_report_and_screenshot(page: Page, tmp_path: Path) -> None:
    pg = page
    original = tomllib.loads(SEED.read_text(encoding="utf-8"))["sprockets"][ROW]["teeth"]
    before, after = _analysis(SEED), _analysis(SEED, r2={"teeth": NEW_TEETH})
    warn_before = [w.message for w in before.warnings]
    warn_after = [w.message for w in after.warnings]
    assert before.geometry.links != after.geometry.links  # the edit must show
    assert warn_before and warn_after and warn_before[0] not in warn_after

    _load_example(pg, SEED)
    links, warnings = _metric(pg, "Links"), pg.locator(".st-key-warnings")
    expect(links).to_have_text(str(before.geometry.links))
    expect(warnings).to_contain_text(warn_before[0])
    if os.environ.get("CHAINDRIVE_UPDATE_SCREENSHOTS") == "1":  # docs/ only when asked
        shot = tmp_path / "app.png"
        pg.screenshot(path=str(shot))
        shutil.copyfile(shot, SCREENSHOT)

    # a tooth count through the form: the link count and the warnings follow
    _ready(pg, _edit_teeth(pg, ROW, "S3", original, NEW_TEETH))
    expect(links).to_have_text(str(after.geometry.links))
    for w in warn_after:
        expect(warnings).to_contain_text(w)
    expect(warnings).not_to_contain_text(warn_before[0])

    # two values typed in the table, one after the other from the keyboard (Tab commits the
    # first and moves on): both are kept (in the table and in the results), and stay through
    # a later run of the page (a change of units)
    typed = _analysis(SEED, r2={"teeth": NEW_TEETH + 2, "x": "700 mm"})
    teeth, x = _cell(pg, "teeth", ROW), _cell(pg, "x_mm", ROW)
    expect(teeth).to_have_value(str(NEW_TEETH))  # the table drawn from the form's edit
    old = _design(pg)
    teeth.fill(str(NEW_TEETH + 2))
    teeth.press("Tab")
    _changed(pg, "#chaindrive-ready", old)
    expect(x).to_be_focused()  # the page's run left the focus where Tab put it
    old = _design(pg)
    pg.keyboard.press("Control+A")
    pg.keyboard.type("700")
    pg.keyboard.press("Enter")
    _changed(pg, "#chaindrive-ready", old)
    expect(links).to_have_text(str(typed.geometry.links))
    slack = f"slack {fmt(typed.geometry.slack * 1e3)} mm"  # moved with S3's x
    expect(pg.get_by_text(slack)).to_be_visible()
    pg.get_by_text("US (in, lbf, hp)").click()
    _ready(pg)
    expect(pg.get_by_text(f"slack {fmt(typed.geometry.slack / 0.0254)} in")).to_be_visible()
    pg.get_by_text("SI (mm, N, kW)").click()
    expect(pg.get_by_text(slack)).to_be_visible()
    expect(_cell(pg, "x_mm", ROW)).to_have_value("700")
    expect(_cell(pg, "teeth", ROW)).to_have_value(str(NEW_TEETH + 2))

    # the report of the edited design as a PDF, downloaded from its tab
    pg.get_by_role("tab", name="Report & files").click()
    pg.get_by_role("button", name="Build report (PDF)").click()
    download = pg.get_by_role("button", name="Download report (PDF)")
    expect(download).to_be_visible(timeout=REPORT_MS)
    with pg.expect_download() as info:
        download.click()
    saved = tmp_path / "report.pdf"
    info.value.save_as(saved)
    assert saved.read_bytes()[:5] == b"%PDF-"

    # a bad tooth count: the loader's message on the page, no traceback
    _ready(pg, _edit_teeth(pg, ROW, "S3", NEW_TEETH + 2, BAD_TEETH), state="error")
    expect(pg.get_by_text(_loader_message(BAD_TEETH))).to_be_visible()
    # the run's stale elements can stand a moment after its ready marker (seen once: two
    # "Links" metrics, a strict-mode failure): wait for the one left, then read it
    expect(links).to_have_count(1)
    expect(links).to_have_text(str(typed.geometry.links))  # the last good results stay
    # text typed in a number cell of the table: the loader's line under the table, naming
    # the row and the column
    cell = _cell(pg, "teeth", ROW)
    old = _design(pg)
    cell.fill("abc")
    cell.press("Enter")
    _changed(pg, "#chaindrive-ready", old)
    expect(pg.get_by_text(f"row {ROW + 1} (S3), column “teeth” — "
                          + _loader_message("abc"))).to_be_visible()
    expect(links).to_have_text(str(typed.geometry.links))
    expect(pg.get_by_test_id("stException")).to_have_count(0)
    assert "Traceback" not in pg.content()


def _above_the_fold(pg: Page, height: int) -> None:
    """The contour and the verdict are on screen without scrolling."""
    contour = pg.get_by_test_id("stImage").first  # the contour, the page's first image
    verdict = pg.locator(".st-key-verdict")
    for part in (contour, verdict):
        expect(part).to_be_visible()
        box = part.bounding_box()
        assert box is not None and box["y"] >= 0 and box["y"] + box["height"] <= height, box


def _resize(pg: Page, width: int, height: int) -> None:
    """Resize the window of ``pg`` as a person would, then wait until the page has laid
    itself out at the new size (the window reports it, and two frames are drawn: the
    resize observers of the page's elements run before the first of them)."""
    pg.set_viewport_size({"width": width, "height": height})
    pg.wait_for_function("([w, h]) => window.innerWidth === w && window.innerHeight === h",
                         arg=[width, height])
    pg.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")


def test_24_sprockets_fold_reset_and_edit_time(browser: Any, app_url: str) -> None:
    """At 1400×900 and 1024×768 the contour and the verdict of the 24-sprocket example are
    above the fold; loading a file resets the edit form and the deltas; each timed edit
    shows the results of its own design.

    One session serves both sizes: the window is made 1024×768 once the example is shown at
    1400×900, as a person would resize it, and 1400×900 again for the timed edits. (A session
    of its own at 1024×768 ran the page's first run and loaded the example again: 4.5 s of
    the test's 14.5 s.)"""
    big = _page(browser, app_url, 1400, 900)
    pg = next(big)
    try:
        _choose(pg, "Sprocket to edit", "row 3: S3")
        expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-editing", "2")
        _load_example(pg, BIG)
        _above_the_fold(pg, 900)
        expect(pg.get_by_role("combobox", name="Sprocket to edit")).to_have_value("row 1: S1")
        expect(pg.get_by_test_id("stMetricDelta")).to_have_count(0)  # not against the seed
        _resize(pg, 1024, 768)
        _above_the_fold(pg, 768)
        _resize(pg, 1400, 900)
        times = _time_edits(pg, timed=bool(os.environ.get("CHAINDRIVE_BENCH_OUT")))
    finally:
        big.close()
    out = os.environ.get("CHAINDRIVE_BENCH_OUT")
    if out:
        Path(out).write_text(json.dumps(times, indent=1), encoding="utf-8")
    for way in ("table", "form"):
        print(f"\n{way} edit → results shown: median "
              f"{statistics.median(times[f'{way}_shown_s']):.3f} s; → page complete: median "
              f"{statistics.median(times[f'{way}_complete_s']):.3f} s")


def _timed(pg: Page, edit: Any, commit: Any) -> tuple[float, float]:
    """Make an edit (``edit()``), then time ``commit()`` to the results of the new design on
    screen (results marker) and to the end of the page's run (ready marker) [s]."""
    _ready(pg)
    old = _design(pg)
    edit()
    start = time.perf_counter()
    commit()
    _changed(pg, "#chaindrive-results", old)
    shown = time.perf_counter() - start
    _changed(pg, "#chaindrive-ready", old)
    _ready(pg)
    return shown, time.perf_counter() - start


def _time_edits(pg: Page, timed: bool) -> dict[str, list[float]]:
    """Time edits of S2's tooth count made in the sprocket table (TIMED_TEETH: type, Enter)
    and through the "edit one sprocket" form (FORM_TEETH: type, Apply), each from the key that commits
    it to the results of its design on screen and to the end of the page's run; the last
    design's links are checked against chaindrive.analyze. All of them when ``timed`` (the
    benchmark), the first ``CHECKED_EDITS`` of each otherwise."""
    times: dict[str, list[float]] = {k: [] for k in ("table_shown_s", "table_complete_s",
                                                      "form_shown_s", "form_complete_s")}
    count = len(TIMED_TEETH) if timed else CHECKED_EDITS
    table_teeth, form_teeth = TIMED_TEETH[:count], FORM_TEETH[:count]
    cell = _cell(pg, "teeth", 1)
    for teeth in table_teeth:
        shown, done = _timed(pg, lambda t=teeth: cell.fill(str(t)),
                             lambda: cell.press("Enter"))
        times["table_shown_s"].append(shown)
        times["table_complete_s"].append(done)
    _choose(pg, "Sprocket to edit", "row 2: S2")
    expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-editing", "1")
    for teeth in form_teeth:
        shown, done = _timed(pg, lambda t=teeth: _teeth_field(pg).fill(str(t)),
                             lambda: pg.get_by_role("button", name="Apply", exact=True).click())
        times["form_shown_s"].append(shown)
        times["form_complete_s"].append(done)
    last = _analysis(BIG, r1={"teeth": form_teeth[-1]})
    expect(_metric(pg, "Links")).to_have_text(str(last.geometry.links))
    return times
