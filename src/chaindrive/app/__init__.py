"""The chaindrive web page: design in dialogue with the computer (issue 7; docs/app.md).

``run_app()`` starts ``streamlit run`` on :mod:`chaindrive.app.main` and prints its address.
The page is a presenter: :mod:`.state` (form ↔ design mapping ↔ analysis) and :mod:`.views`
(what is on screen) are pure and tested without a browser; :mod:`.runs` holds the on-demand
work (start-up, AFC, report, drawing). Importing this package does not import Streamlit.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

__all__ = ["PAGE", "run_app", "streamlit_command"]

#: The Streamlit script of the page.
PAGE = Path(__file__).with_name("main.py")


def streamlit_command(host: str = "127.0.0.1", port: int = 8501) -> list[str]:
    """The ``streamlit run`` command line of the page on ``host:port``: headless, no usage
    statistics, no file watcher, and no exception details in the browser (the page catches
    every error itself; this is the safety net that keeps tracebacks off the screen)."""
    return [sys.executable, "-m", "streamlit", "run", str(PAGE),
            "--server.address", host, "--server.port", str(port),
            "--server.headless", "true", "--server.fileWatcherType", "none",
            "--browser.gatherUsageStats", "false", "--client.showErrorDetails", "none",
            "--client.toolbarMode", "viewer", "--theme.base", "light"]


def run_app(host: str = "127.0.0.1", port: int = 8501) -> int:
    """Start the web page on ``host:port``, print its address and serve until interrupted
    (Ctrl+C). Returns the exit status of Streamlit (2 when Streamlit is not installed)."""
    if importlib.util.find_spec("streamlit") is None:
        print("error: the web page needs Streamlit: pip install 'chaindrive[app]'",
              file=sys.stderr)
        return 2
    print(f"chaindrive app: http://{host}:{port}  (Ctrl+C to stop)", flush=True)
    try:
        return subprocess.call(streamlit_command(host, port))
    except KeyboardInterrupt:
        return 0
