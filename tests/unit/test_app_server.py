"""The web page's server side without a browser: bounded runs (chaindrive.app.worker),
uploads (chaindrive.app.uploads), the saved design file, the server's command line and its
lifecycle (``chaindrive app`` stops its server on SIGTERM).

Outcomes, never timings: a run past its limit ends with the limit's message and its process
gone; a quick run finishes while a slow one is still running; a catalogue is read only
when it was uploaded in the session.
"""

from __future__ import annotations

import copy
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import tomllib
import urllib.request
from pathlib import Path

import pytest

import chaindrive
from chaindrive.app import streamlit_command
from chaindrive.app.state import design_to_toml, evaluate, read_design_text
from chaindrive.app.uploads import MAX_UPLOAD_BYTES, Uploads, design_text
from chaindrive.app.worker import RunLimitError, run_bounded
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping
from tests.conftest import EXAMPLES, ROOT

pytestmark = pytest.mark.concurrency  # child processes, threads, a server

JINDAL = tomllib.loads((EXAMPLES / "two_sprocket_jindal.toml").read_text(encoding="utf-8"))


# --- functions run in the child processes (importable by name) ------------------------------

def spin(flag: str) -> str:
    """Busy until ``flag`` (a file) exists — forever when nobody creates it."""
    while not Path(flag).exists():
        sum(i * i for i in range(10_000))
    return "done"


def allocate(gigabytes: float) -> int:
    """Allocate and touch ``gigabytes`` of memory."""
    block = bytearray(int(gigabytes * 1024**3))
    return len(block)


def refuse() -> None:
    raise DesignError("sprockets[1].teeth", "must be a whole number from 6 to 150, got 3")


def crash() -> None:
    raise ZeroDivisionError("division by zero")


def pid() -> int:
    return os.getpid()


# --- bounded runs ---------------------------------------------------------------------------

def test_a_run_past_its_time_is_stopped(tmp_path: Path) -> None:
    with pytest.raises(RunLimitError, match="took longer than 1 s"):
        run_bounded(spin, str(tmp_path / "never"), seconds=1.0)


def test_a_run_past_its_memory_is_stopped() -> None:
    with pytest.raises(RunLimitError, match="more than 1 GB of memory"):
        run_bounded(allocate, 4.0, memory=1024**3)


def test_errors_of_a_run_come_back() -> None:
    with pytest.raises(DesignError) as info:
        run_bounded(refuse)
    assert info.value.field == "sprockets[1].teeth"
    with pytest.raises(RuntimeError, match="ZeroDivisionError"):
        run_bounded(crash)
    assert run_bounded(pid) != os.getpid()  # in a process of its own


def test_a_quick_run_finishes_while_a_slow_one_runs(tmp_path: Path) -> None:
    """Two sessions: one runs a computation that does not end until told; the other's
    analysis of the seed example completes meanwhile."""
    flag = tmp_path / "stop"
    slow: dict[str, object] = {}
    thread = threading.Thread(target=lambda: slow.update(r=run_bounded(spin, str(flag),
                                                                       seconds=600.0)))
    thread.start()
    try:
        from chaindrive.app.runs import bounded_screen

        screen = bounded_screen(tomllib.loads((EXAMPLES / "seed_three_sprocket.toml")
                                              .read_text(encoding="utf-8")))
        assert screen.outcome.ok
        assert thread.is_alive() and "r" not in slow  # the slow run is still running
    finally:
        flag.touch()
        thread.join()
    assert slow["r"] == "done"


def test_the_page_gives_the_inertia_line_for_1e_minus_10() -> None:
    from chaindrive.app.runs import bounded_screen

    design = copy.deepcopy(JINDAL)
    design["sprockets"][1]["inertia"] = "1e-10 kg*m^2"
    screen = bounded_screen(design)
    assert not screen.outcome.ok and screen.outcome.message is not None
    assert screen.outcome.message.startswith("sprockets[1].inertia: must be")


# --- uploads --------------------------------------------------------------------------------

CATALOG = ("designation,pitch_mm,roller_diameter_mm,pin_diameter_mm,inner_width_mm,"
           "plate_depth_mm,breaking_load_kN,mass_kg_m\nMY 1,9.525,6.35,3.28,5.72,8.2,9.1,0.41\n")


def test_catalogues_only_from_the_session(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                          ) -> None:
    secret = tmp_path / "secret.csv"
    secret.write_text("TOPSECRET_HEADER,x\n1,2\n", encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    for name in ("secret.csv", str(secret), "../" * 8 + str(secret).lstrip("/")):
        design = copy.deepcopy(JINDAL)
        design["chain"]["catalog"] = name
        outcome = evaluate(design)
        assert outcome.message is not None and "not a catalogue uploaded" in outcome.message
        assert "TOPSECRET" not in outcome.message
    uploads = Uploads()
    assert uploads.add("mine.csv", CATALOG.encode()) == "mine.csv"
    design = copy.deepcopy(JINDAL)
    design["chain"] = {"designation": "MY 1", "catalog": "mine.csv"}
    outcome = evaluate(design, catalogs=uploads.paths())
    assert outcome.ok and outcome.analysis is not None
    assert outcome.analysis.drive.chain.spec.breaking_load == pytest.approx(9100.0)


def test_uploads_are_checked() -> None:
    uploads = Uploads()
    with pytest.raises(DesignError, match="at most"):
        uploads.add("big.csv", b"x" * (MAX_UPLOAD_BYTES + 1))
    with pytest.raises(DesignError, match="must be a .csv or .toml file"):
        uploads.add("x.exe", b"MZ")
    with pytest.raises(DesignError, match="row 1"):
        uploads.add("bad.csv", CATALOG.replace("9.1", "1e300").encode())
    with pytest.raises(DesignError, match="not UTF-8"):
        design_text("d.toml", b"\xff\xfe")
    assert uploads.content == {}


# --- the saved design -----------------------------------------------------------------------

@pytest.mark.parametrize("name", ['quote " in it', "back\\slash", "new\nline", "tab\tand ü"])
def test_save_design_round_trips_any_name(name: str) -> None:
    """Save design writes TOML that reads back to the same design, and the design analyses
    to the same results as the drive it came from (closed form: identity)."""
    design = copy.deepcopy(JINDAL)
    design["drive"]["name"] = name
    design["sprockets"][0]["name"] = name[:8]
    text = design_to_toml(design, comment="saved by the page\nline two")
    again = read_design_text(text, "saved.toml")
    assert again == design
    if name.isprintable():
        a = chaindrive.analyze(drive_from_mapping(again), response=False).to_dict()
        b = chaindrive.analyze(drive_from_mapping(design), response=False).to_dict()
        assert a == b


# --- the server -----------------------------------------------------------------------------

def test_the_server_binds_to_this_machine_and_limits_uploads() -> None:
    cmd = streamlit_command()
    assert cmd[cmd.index("--server.address") + 1] == "127.0.0.1"
    assert int(cmd[cmd.index("--server.maxUploadSize") + 1]) * 1024 * 1024 == MAX_UPLOAD_BYTES


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _healthy(port: int) -> bool:
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/_stcore/health", timeout=2) as r:
            return r.status == 200
    except OSError:
        return False


def _children(parent: int) -> list[int]:
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(parent)], capture_output=True,
                         text=True, check=False).stdout
    return [int(p) for p in out.split()]


def _alive(process: int) -> bool:
    try:
        os.kill(process, 0)
    except ProcessLookupError:
        return False
    return True


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["TERM", "INT"])
def test_chaindrive_app_stops_its_server(signum: int, tmp_path: Path) -> None:
    port = _free_port()
    log = (tmp_path / "app.log").open("wb")
    app = subprocess.Popen([sys.executable, "-m", "chaindrive", "app", "--port", str(port)],
                           cwd=ROOT, stdout=log, stderr=subprocess.STDOUT,
                           stdin=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120  # a bound on a server that never starts
        while not _healthy(port) and app.poll() is None and time.monotonic() < deadline:
            time.sleep(0.2)
        assert _healthy(port), (tmp_path / "app.log").read_text(errors="replace")
        servers = _children(app.pid)
        assert servers
        app.send_signal(signum)
        assert app.wait(timeout=60) == 128 + signum
        for server in servers:  # reaped by its parent: gone, not orphaned
            assert not _alive(server)
        assert not _healthy(port)
    finally:
        if app.poll() is None:
            app.kill()
            app.wait()
        log.close()
