"""The web page driven by a real browser, as a person would use it (issue 7).

Playwright for Python drives Debian's Chromium (``apt-get install -y chromium``; Playwright's
own browser download cannot reach its servers from these machines). The page is started
on a free 127.0.0.1 port in a subprocess (headless, no usage statistics) and always stopped
again (fixture finalizer). The test loads the seed example from the sidebar, changes a tooth
count through the keyboard-friendly "edit one sprocket" form (the sprocket table is drawn on a
canvas: clicks and keystrokes sent to it are lost while it redraws), checks that the link
count and the warning the page shows change as ``chaindrive.analyze`` of the same edit says,
takes a screenshot (copied to docs/app_seed.png when
CHAINDRIVE_UPDATE_SCREENSHOTS=1), downloads the report, and finally types a bad tooth
count and expects the loader's message. Every wait is on something the page shows (its own
ready marker, the recomputed values), never a fixed sleep. Skipped (with the reason) only
when Chromium or Playwright is not installed.
"""

from __future__ import annotations

import os
import re
import shutil
import socket
import subprocess
import time
import tomllib
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import chaindrive
from chaindrive.app import streamlit_command
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping

pytestmark = pytest.mark.concurrency  # a web server and a browser

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "examples" / "seed_three_sprocket.toml"
SCREENSHOT = ROOT / "docs" / "app_seed.png"
CHROMIUM = Path(os.environ.get("CHAINDRIVE_CHROMIUM", "/usr/bin/chromium"))
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
#: The edited sprocket (0-based row; S3, the idler of the seed contour) and its new counts.
ROW, NEW_TEETH, BAD_TEETH = 2, 30, 3
#: Waits [ms]: the first page run imports numpy, scipy, pint…; later runs take well under a
#: second, the report a few seconds (more on a loaded machine).
FIRST_MS, STEP_MS, REPORT_MS = 90_000, 30_000, 90_000

if not (CHROMIUM.is_file() and os.access(CHROMIUM, os.X_OK)):
    pytest.skip(f"Chromium not found at {CHROMIUM} (apt-get install -y chromium)",
                allow_module_level=True)
try:
    from playwright.sync_api import Locator, Page, expect, sync_playwright
except ImportError:
    pytest.skip("Playwright for Python is not installed (pip install playwright)",
                allow_module_level=True)


# --- the server and the browser ------------------------------------------------------------------

def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _healthy(url: str) -> bool:
    try:
        with urllib.request.urlopen(f"{url}/_stcore/health", timeout=2) as r:
            return r.status == 200
    except OSError:
        return False


def _start(log: Path, seconds: float = 90.0) -> tuple[subprocess.Popen[bytes], str]:
    """Start the page on a free port; retry on another port when the server exits early
    (the port was taken between choosing and binding it)."""
    for _ in range(3):
        port = _free_port()
        url = f"http://127.0.0.1:{port}"
        with log.open("ab") as out:
            proc = subprocess.Popen(streamlit_command("127.0.0.1", port), cwd=ROOT,
                                    stdout=out, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL)
        end = time.monotonic() + seconds
        while time.monotonic() < end and proc.poll() is None:
            if _healthy(url):
                return proc, url
            time.sleep(0.2)
        _stop(proc)
    tail = log.read_text(encoding="utf-8", errors="replace")[-2000:]
    raise RuntimeError(f"the app did not start (log {log}):\n{tail}")


def _stop(proc: subprocess.Popen[bytes]) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=10)


@pytest.fixture(scope="module")
def app_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """The address of the page, served for this module; the server is always stopped (the
    code after ``yield`` is the fixture's finalizer: it runs even when the test fails)."""
    proc, url = _start(tmp_path_factory.mktemp("app") / "streamlit.log")
    try:
        yield url
    finally:
        _stop(proc)


@pytest.fixture(scope="module")
def browser(app_url: str) -> Iterator[Any]:
    """Chromium, for this module."""
    with sync_playwright() as pw:
        chromium = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            yield chromium
        finally:
            chromium.close()


@pytest.fixture
def page(browser: Any, app_url: str) -> Iterator[Page]:
    """A page of its own for each test (a new browser context: a new session of the app, so
    a repeated test never starts from the state the previous one left), after the page's
    first complete run."""
    context = browser.new_context(viewport={"width": 1500, "height": 1400},
                                  accept_downloads=True)
    try:
        pg = context.new_page()
        pg.set_default_timeout(STEP_MS)
        expect.set_options(timeout=STEP_MS)
        pg.goto(app_url)
        _ready(pg, timeout=FIRST_MS)
        yield pg
    finally:
        context.close()


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


def _metric(pg: Page, label: str) -> Locator:
    return (pg.get_by_test_id("stMetric").filter(has=pg.get_by_text(label, exact=True))
            .get_by_test_id("stMetricValue"))


def _choose(pg: Page, box: str, option: str) -> None:
    """Pick ``option`` in the select box labelled ``box`` as a keyboard user does: focus the
    box, type the option's text (the list filters to it) and press Enter, then wait until the
    box shows it. (Clicking an option of the open list races the list's own re-rendering on a
    busy machine: the option is detached between locating and clicking it.)"""
    combo = pg.get_by_role("combobox", name=box)
    combo.click()
    pg.keyboard.type(option)
    pg.keyboard.press("Enter")
    expect(combo).to_have_value(option)


def _edit_teeth(pg: Page, shown: int, teeth: int) -> int:
    """Set the tooth count of sprocket ROW through the "edit one sprocket" form; returns the
    design version the edit produces."""
    version = _ready(pg)
    _choose(pg, "Sprocket to edit", f"row {ROW + 1}: S{ROW + 1}")
    expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-editing", str(ROW))
    field = pg.locator(".st-key-sprocket_editor").get_by_label("Teeth", exact=True)
    expect(field).to_have_value(str(shown))  # the form shows the chosen sprocket
    field.fill(str(teeth))
    pg.get_by_role("button", name="Apply", exact=True).click()
    return version + 1


# --- the design, computed by the library ---------------------------------------------------------

def _seed(teeth: int) -> dict[str, Any]:
    data = tomllib.loads(SEED.read_text(encoding="utf-8"))
    data["sprockets"][ROW]["teeth"] = teeth
    return data


def _analysis(teeth: int) -> Any:
    """``chaindrive.analyze`` of the seed with sprocket ROW at ``teeth`` (the quick part the
    page redraws after every edit)."""
    return chaindrive.analyze(drive_from_mapping(_seed(teeth)), response=False)


def _loader_message(teeth: int) -> str:
    """The line the loader (and so ``chaindrive analyze``) gives for a bad tooth count."""
    with pytest.raises(ChainDriveError) as info:
        drive_from_mapping(_seed(teeth))
    return str(info.value)


# --- the test ------------------------------------------------------------------------------------

def test_seed_edit_report_and_screenshot(page: Page, tmp_path: Path) -> None:
    pg = page
    original = tomllib.loads(SEED.read_text(encoding="utf-8"))["sprockets"][ROW]["teeth"]
    before, after = _analysis(original), _analysis(NEW_TEETH)
    warn_before = [w["message"] for w in before.to_dict()["warnings"]]
    warn_after = [w["message"] for w in after.to_dict()["warnings"]]
    assert before.geometry.links != after.geometry.links  # the edit must show
    assert warn_before and warn_after and warn_before[0] not in warn_after

    # load the seed example from the sidebar
    version = _ready(pg)
    _choose(pg, "Bundled examples", SEED.stem)
    pg.get_by_role("button", name="Load example").click()
    _ready(pg, version + 1)
    expect(pg.locator("#chaindrive-ready")).to_have_attribute("data-source", SEED.name)
    links, warnings = _metric(pg, "Links"), pg.locator(".st-key-warnings")
    expect(links).to_have_text(str(before.geometry.links))
    expect(warnings).to_contain_text(warn_before[0])
    shown_before = warnings.inner_text()

    # change a tooth count: the link count and the warning follow
    _ready(pg, _edit_teeth(pg, original, NEW_TEETH))
    expect(links).to_have_text(str(after.geometry.links))
    for w in warn_after:
        expect(warnings).to_contain_text(w)
    expect(warnings).not_to_contain_text(warn_before[0])
    assert warnings.inner_text() != shown_before
    shot = tmp_path / "app.png"
    pg.screenshot(path=str(shot), full_page=True)
    assert shot.stat().st_size > 10_000
    if os.environ.get("CHAINDRIVE_UPDATE_SCREENSHOTS") == "1":  # docs/ only when asked
        shutil.copyfile(shot, SCREENSHOT)

    # the report of the edited design, downloaded from its tab
    pg.get_by_role("tab", name="Report & files").click()
    pg.get_by_role("button", name="Build report").click()
    download = pg.get_by_role("button", name="Download report (HTML)")
    expect(download).to_be_visible(timeout=REPORT_MS)
    with pg.expect_download() as info:
        download.click()
    saved = tmp_path / "report.html"
    info.value.save_as(saved)
    report = saved.read_text(encoding="utf-8")
    assert "<html" in report.lower()
    assert after.drive.name in report
    assert re.search(rf"links</td>\s*<td[^>]*>{after.geometry.links}<", report)  # edited

    # a bad tooth count: the loader's message on the page, no traceback
    _ready(pg, _edit_teeth(pg, NEW_TEETH, BAD_TEETH), state="error")
    expect(pg.get_by_text(_loader_message(BAD_TEETH))).to_be_visible()
    expect(links).to_have_text(str(after.geometry.links))  # the last good results stay
    expect(pg.get_by_test_id("stException")).to_have_count(0)
    assert "Traceback" not in pg.content()
