"""The web page's server and the browser, shared by the browser tests of this directory
(tests/e2e/test_app_browser.py, test_app_limits.py, test_app_identify.py).

One Streamlit server and one Chromium serve every browser test of a test process (session
scope: with ``pytest -n 2 --dist loadfile`` each worker that runs one of these files starts
them once, when its first browser test asks for them, and stops them when it ends). Starting
them is most of what a small browser test costs: the server imports the page, starts its
fork server of preloaded workers and analyses the seed example for its first session, and
Chromium starts its browser, GPU and network processes.

Nothing a test does carries over to the next: every test opens its own page (a tab: a new
session of the page, with its own widgets, uploads and results, as each Streamlit session is
one connection of one tab) and closes it. The tabs are those of one browser context, as a
person opens the page in several tabs of a browser: they share the browser's cache of the
page's scripts and styles (in a context of its own a tab fetched and compiled them again,
0.5 to 1 s of each test's first run of the page). What the sessions share is what the
sessions of a deployed page share too — the server's store of finished screens, keyed by
the design (a design shown twice is the same screen), and its warm worker processes, which
give every design its own results (tests/e2e/test_app_warm_workers.py).

Chromium and Playwright are imported only when a test asks for the browser; the test files
skip themselves (with the reason) when either is missing.
"""

from __future__ import annotations

import os
import socket
import subprocess
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from chaindrive.app import stop_server, streamlit_command
from tests.conftest import ROOT

CHROMIUM = Path(os.environ.get("CHAINDRIVE_CHROMIUM", "/usr/bin/chromium"))
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def healthy(url: str, timeout: float = 2.0) -> bool:
    """Whether the server at ``url`` answers its health check within ``timeout`` [s]."""
    try:
        with urllib.request.urlopen(f"{url}/_stcore/health", timeout=timeout) as r:
            return r.status == 200
    except OSError:
        return False


def _start(log: Path, seconds: float = 90.0) -> tuple[subprocess.Popen[bytes], str]:
    """Start the page on a free 127.0.0.1 port (headless, no usage statistics); retry on
    another port when the server exits early (the port was taken between choosing and
    binding it)."""
    for _ in range(3):
        port = _free_port()
        url = f"http://127.0.0.1:{port}"
        with log.open("ab") as out:
            proc = subprocess.Popen(streamlit_command("127.0.0.1", port), cwd=ROOT,
                                    stdout=out, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL)
        end = time.monotonic() + seconds
        while time.monotonic() < end and proc.poll() is None:
            if healthy(url):
                return proc, url
            time.sleep(0.2)
        stop_server(proc)
    tail = log.read_text(encoding="utf-8", errors="replace")[-2000:]
    raise RuntimeError(f"the app did not start (log {log}):\n{tail}")


@pytest.fixture(scope="session")
def app_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """The address of the page, served for this test process; the server is always stopped
    (the code after ``yield`` is the fixture's finalizer: it runs even when a test fails)."""
    proc, url = _start(tmp_path_factory.mktemp("app") / "streamlit.log")
    try:
        yield url
    finally:
        stop_server(proc)


@pytest.fixture(scope="session")
def browser(app_url: str) -> Iterator[Any]:
    """Chromium's browser context for this test process (each test opens its own page in
    it, :func:`new_tab`; downloads accepted)."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        chromium = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            context = chromium.new_context(accept_downloads=True)
            yield context
        finally:
            chromium.close()


def new_tab(browser: Any, width: int, height: int) -> Any:
    """A new page (tab) of ``browser`` (the :func:`browser` fixture's context) with a
    window of ``width`` × ``height`` pixels, before it opens any address; close it with
    ``page.close()``."""
    page = browser.new_page()
    page.set_viewport_size({"width": width, "height": height})
    return page
