"""The chaindrive web page: design in dialogue with the computer (docs/app.md).

``run_app()`` starts ``streamlit run`` on :mod:`chaindrive.app.main` and prints its address.
The page is a presenter: :mod:`.state` (form ↔ design mapping ↔ analysis) and :mod:`.views`
(what is on screen) are pure and tested without a browser; :mod:`.runs` holds the on-demand
work (start-up, AFC, report, drawing). Importing this package does not import Streamlit.
"""

from __future__ import annotations

import contextlib
import importlib.util
import subprocess
import sys
from pathlib import Path

from chaindrive.app.uploads import MAX_UPLOAD_MB
from chaindrive.io.atomic import signals_held

__all__ = ["PAGE", "run_app", "stop_server", "streamlit_command"]

#: The Streamlit script of the page.
PAGE = Path(__file__).with_name("main.py")


def streamlit_command(host: str = "127.0.0.1", port: int = 8501) -> list[str]:
    """The ``streamlit run`` command line of the page: headless, no usage statistics, no
    file watcher, uploads of at most :data:`~chaindrive.app.uploads.MAX_UPLOAD_MB` MB, and no
    exception details in the browser (the page catches every error itself; this is the
    safety net that keeps tracebacks off the screen).

    Parameters
    ----------
    host : str
        Address to serve on (this machine only by default).
    port : int
        Port to serve on.

    Returns
    -------
    list of str
        The command line.
    """

    return [sys.executable, "-m", "streamlit", "run", str(PAGE),
            "--server.address", host, "--server.port", str(port),
            "--server.headless", "true", "--server.fileWatcherType", "none",
            "--server.maxUploadSize", str(MAX_UPLOAD_MB),
            "--server.maxMessageSize", "50",
            "--browser.gatherUsageStats", "false", "--client.showErrorDetails", "none",
            "--client.toolbarMode", "viewer", "--theme.base", "light"]


def _die_with_parent() -> None:
    """In the server's process, before it runs: on Linux, ask for SIGTERM when the process
    that started it dies (even by SIGKILL), so the server is never left orphaned."""
    if sys.platform.startswith("linux"):
        import ctypes
        import signal

        with contextlib.suppress(OSError, AttributeError):
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG


def stop_server(proc: subprocess.Popen[bytes]) -> None:
    """Stop the server: SIGTERM (Streamlit shuts down cleanly), SIGKILL after 10 s; the
    command's signals are held meanwhile (:func:`chaindrive.io.atomic.signals_held`).

    Parameters
    ----------
    proc : subprocess.Popen
        The Streamlit server process (:func:`streamlit_command`).
    """

    with signals_held():
        if proc.poll() is None:
            proc.terminate()
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def run_app(host: str = "127.0.0.1", port: int = 8501) -> int:
    """Start the web page, print its address and serve until interrupted.

    The server is a child process; it stops with this one: on SIGINT or SIGTERM (raised in
    here by the command line's safety net, :mod:`chaindrive.cli.safety`) the ``finally``
    stops it, and on Linux it gets SIGTERM even when this process is killed outright.

    Parameters
    ----------
    host : str
        Address to serve on (this machine only unless told otherwise).
    port : int
        Port to serve on.

    Returns
    -------
    int
        The exit status of Streamlit (2 when Streamlit is not installed).
    """
    if importlib.util.find_spec("streamlit") is None:
        print("error: the web page needs Streamlit: pip install 'chaindrive[app]'",
              file=sys.stderr)
        return 2
    print(f"chaindrive app: http://{host}:{port}  (Ctrl+C to stop)", flush=True)
    proc = subprocess.Popen(streamlit_command(host, port), preexec_fn=_die_with_parent)
    try:
        return proc.wait()
    finally:
        stop_server(proc)
