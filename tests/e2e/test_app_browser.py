"""The web page driven by a real browser, as a person would use it (issue 7).

Playwright for Python drives Debian's Chromium (``apt-get install -y chromium``; Playwright's
own browser download cannot reach its servers from these machines). The page is started
on a free 127.0.0.1 port in a subprocess; the test loads the seed example, changes a tooth
count (with the keyboard-friendly form under the sprocket table), checks that the link
count and the warnings follow (against
the library's own analysis of the same edit), types a bad tooth count and expects the
command line's message, downloads the report, saves a screenshot to docs/app_seed.png and
stops the server. Skipped (with the reason) only when Chromium or Playwright is missing.
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
import tomllib
import urllib.request
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from chaindrive.app import streamlit_command
from chaindrive.app.state import design_from_form, evaluate, form_from_design

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "examples" / "seed_three_sprocket.toml"
SCREENSHOT = ROOT / "docs" / "app_seed.png"
CHROMIUM = Path(os.environ.get("CHAINDRIVE_CHROMIUM", "/usr/bin/chromium"))
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
#: The row and new tooth count of the edit (S3, the idler of the seed contour).
ROW, SPROCKET, NEW_TEETH, BAD_TEETH = 2, "S3", 30, 3
TIMEOUT_MS = 60_000

if not CHROMIUM.is_file():
    pytest.skip(f"Chromium not found at {CHROMIUM} (apt-get install -y chromium)",
                allow_module_level=True)
try:
    from playwright.sync_api import Page, expect, sync_playwright
except ImportError:
    pytest.skip("Playwright for Python is not installed (pip install playwright)",
                allow_module_level=True)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wait_healthy(url: str, proc: subprocess.Popen[bytes], seconds: float = 60.0) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if proc.poll() is not None:
            raise RuntimeError(f"the app exited with status {proc.returncode}")
        try:
            with urllib.request.urlopen(f"{url}/_stcore/health", timeout=2) as r:
                if r.status == 200:
                    return
        except OSError:
            time.sleep(0.3)
    raise RuntimeError(f"the app did not answer at {url} within {seconds:g} s")


@pytest.fixture(scope="module")
def app_url() -> Iterator[str]:
    port = _free_port()
    proc = subprocess.Popen(streamlit_command("127.0.0.1", port), cwd=ROOT,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    try:
        _wait_healthy(url, proc)
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=5)


@pytest.fixture(scope="module")
def page(app_url: str) -> Iterator[Page]:
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        context = browser.new_context(viewport={"width": 1500, "height": 1500},
                                      accept_downloads=True)
        pg = context.new_page()
        pg.set_default_timeout(TIMEOUT_MS)
        expect.set_options(timeout=TIMEOUT_MS)  # the first run imports numpy, scipy, pint…
        pg.goto(app_url)
        yield pg
        context.close()
        browser.close()


def _expected(teeth: int) -> Any:
    """The library's analysis of the seed with sprocket ROW at ``teeth``."""
    form = form_from_design(tomllib.loads(SEED.read_text(encoding="utf-8")))
    form.sprockets[ROW]["teeth"] = teeth
    return evaluate(design_from_form(form))


def _cli_message(tmp_path: Path, teeth: int) -> str:
    """What ``chaindrive analyze`` prints for the seed with sprocket ROW at ``teeth``."""
    text = SEED.read_text(encoding="utf-8").replace("teeth = 14", f"teeth = {teeth}")
    bad = tmp_path / "bad.toml"
    bad.write_text(text, encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "chaindrive", "analyze", str(bad)],
                         capture_output=True, text=True, timeout=60, check=False)
    assert run.returncode == 2, run.stderr
    return run.stderr.strip().removeprefix("error: ")


def _links(pg: Page) -> str:
    return pg.locator(".st-key-headline [data-testid='stMetricValue']").first.inner_text()


def _idle(pg: Page) -> None:
    """Wait until the app has finished its run (its "Running..." indicator is gone)."""
    pg.wait_for_timeout(300)
    expect(pg.get_by_role("img", name="Running...")).to_have_count(0)


def _edit_teeth(pg: Page, teeth: int) -> None:
    """Change sprocket ROW's tooth count with the keyboard-friendly form under the table:
    choose the sprocket, type the count, press Apply (labels, not coordinates)."""
    _idle(pg)
    pg.get_by_label("Sprocket to edit").click()
    pg.get_by_role("option", name=SPROCKET, exact=True).click()
    count = pg.get_by_label("New tooth count")
    count.fill(str(teeth))
    pg.get_by_role("button", name="Apply").click()
    _idle(pg)


def _edit_until(pg: Page, teeth: int, check: Callable[[float], None]) -> None:
    """Apply the edit, then wait (explicitly, up to the timeout) for ``check`` to pass."""
    _edit_teeth(pg, teeth)
    check(TIMEOUT_MS)


def test_seed_edit_report_and_screenshot(page: Page, tmp_path: Path) -> None:
    pg = page
    pg.get_by_role("button", name="Load example").click()
    _idle(pg)
    expect(pg.locator(".st-key-headline [data-testid='stMetricValue']").first).to_be_visible()
    before = _expected(14)
    after = _expected(NEW_TEETH)
    assert before.ok and after.ok
    links_before = str(before.analysis.geometry.links)
    links_after = str(after.analysis.geometry.links)
    warn_before = before.analysis.to_dict()["warnings"]
    warn_after = after.analysis.to_dict()["warnings"]
    assert links_before != links_after and warn_before != warn_after  # the edit matters
    expect(pg.locator(".st-key-headline [data-testid='stMetricValue']").first
           ).to_have_text(links_before)
    warnings = pg.locator(".st-key-warnings")
    expect(warnings).to_contain_text(warn_before[0])

    headline = pg.locator(".st-key-headline [data-testid='stMetricValue']")
    _edit_until(pg, NEW_TEETH, lambda t: expect(headline.first).to_have_text(links_after,
                                                                          timeout=t))
    for w in warn_after:
        expect(warnings).to_contain_text(w)
    expect(warnings).not_to_contain_text(warn_before[0])
    SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    pg.wait_for_timeout(500)
    pg.screenshot(path=str(SCREENSHOT), full_page=True)

    # a bad value: the command line's message, next to the table, and no traceback
    message = _cli_message(tmp_path, BAD_TEETH)
    shown = pg.get_by_text(message, exact=False)
    _edit_until(pg, BAD_TEETH, lambda t: expect(shown).to_be_visible(timeout=t))
    # (the results of the last valid design, 30 teeth, stay on screen: the report is theirs)

    # the report, downloaded from its tab
    pg.get_by_role("tab", name="Report & files").click()
    pg.get_by_role("button", name="Build report").click()
    download_button = pg.get_by_role("button", name="Download report (HTML)")
    expect(download_button).to_be_visible(timeout=120_000)
    with pg.expect_download() as info:
        download_button.click()
    saved = tmp_path / "report.html"
    info.value.save_as(saved)
    html = saved.read_text(encoding="utf-8")
    assert "<html" in html.lower()
    assert after.analysis.drive.name in html
    assert pg.locator("[data-testid='stException']").count() == 0
    assert "Traceback" not in pg.content()
