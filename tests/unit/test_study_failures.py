"""Studies that fail loudly and cleanly (docs/reliability.md §6): a cluster that loses every
worker ends the study within its timeout with one line and resumes later from its
database; a database that cannot be opened or written (a full disk) is one line, exit 2,
and no new file; an interrupt is one line; ``robust --modal`` refuses the options of the
Dask path it does not take."""

from __future__ import annotations

import contextlib
import errno
import os
import signal
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from chaindrive.cli import run
from chaindrive.synthesis import studies
from chaindrive.synthesis.studies import LostWorkersError, StudyStore, run_study
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # Dask clusters, threads and signals

distributed = pytest.importorskip("distributed")
OPTIMIZE = EXAMPLES / "eight_sprocket_optimize.toml"


#: Environment of the workers: a file; the evaluations are slow while it exists.
_SLOW_WHILE = "CHAINDRIVE_TEST_SLOW_WHILE"


def _slow_square(inputs: dict) -> dict:
    """Squares ``x``: in a quarter of a second while the file ``$CHAINDRIVE_TEST_SLOW_WHILE``
    exists (a study that is still running when its workers are lost), at once after it is
    gone (the resume, whose speed is not what it is tested for)."""
    flag = os.environ.get(_SLOW_WHILE)
    if flag is None or Path(flag).exists():
        time.sleep(0.25)
    return {"square": inputs["x"] ** 2}


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def test_a_study_whose_workers_are_lost_stops_within_its_timeout_and_resumes(
        tmp_path: Path) -> None:
    """An external scheduler (its address given, as ``--scheduler``) whose workers all go:
    Dask waits for ever; the study stops ``lost_after`` seconds after the last worker left,
    keeps what finished, and a rerun with workers back computes only the rest.

    The evaluations take 0.25 s each until the workers are lost (about 9 s of work left
    then: the study is still running, however loaded the machine), and no time in the
    rerun: what it asserts (only the rest computed, every result right) does not depend on
    how long each takes, and 37 sleeps of 0.25 s made most of the test's 15 s. One
    evaluation a task: the three stored that the workers wait for come after 0.75 s of
    work, not after the first task of ten (2.5 s: the test took 7.1 s with it, 4.8 s now)."""
    url = f"sqlite:///{tmp_path / 'lost.db'}"
    inputs = [{"x": k} for k in range(40)]
    slow = tmp_path / "slow"
    slow.touch()
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=":0",
                                  env={_SLOW_WHILE: str(slow)}) as cluster:
        def lose_workers() -> None:
            watcher = StudyStore(url)
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline and watcher.count("lost") < 3:
                time.sleep(0.05)
            watcher.close()
            cluster.scale(0)  # every worker leaves; none comes back

        StudyStore(url).close()
        thread = threading.Thread(target=lose_workers)
        thread.start()
        started = time.monotonic()
        with pytest.raises(LostWorkersError) as info:
            run_study(_slow_square, inputs, study="lost", db=url, chunk=1,
                      scheduler=cluster.scheduler_address, progress=False, lost_after=2.0)
        waited = time.monotonic() - started
        thread.join()
        line = str(info.value)
        assert "no worker for 2 s" in line and "run the same command again" in line
        assert "\n" not in line
        assert waited < 40  # stopped, not waiting for ever (2 s timeout, loaded machine)
        stored = StudyStore(url).count("lost")
        assert 3 <= stored < len(inputs)
        slow.unlink()  # the rerun's evaluations are quick
        cluster.scale(1)  # workers back: the same study resumes
        result = run_study(_slow_square, inputs, study="lost", db=url,
                           scheduler=cluster.scheduler_address, progress=False)
    assert result.reused == stored and result.computed == len(inputs) - stored
    assert [r["square"] for r in result.results] == [k * k for k in range(40)]


def test_optimize_on_a_scheduler_without_workers_is_one_line(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(studies, "LOST_WORKERS_SECONDS", 1.0)
    db = tmp_path / "s.db"
    with distributed.LocalCluster(n_workers=0, processes=True,
                                  dashboard_address=":0") as cluster:
        started = time.monotonic()
        status = run(["optimize", str(OPTIMIZE), "--scheduler", cluster.scheduler_address,
                      "--db", f"sqlite:///{db}"])
        waited = time.monotonic() - started
    line = _one_line(capsys.readouterr().err)
    assert status == 2 and line.startswith("error: scheduler: the Dask cluster has had no "
                                           "worker for 1 s")
    assert waited < 60
    assert not db.exists()  # it stored nothing: no new file


@pytest.mark.parametrize("kind", ["not a database", "a directory in the way"])
def test_an_unopenable_database_is_one_line_and_no_new_file(
        kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    if kind == "not a database":
        path = tmp_path / "x.db"
        path.write_bytes(b"this is no SQLite file" * 100)
    else:
        (tmp_path / "file").write_text("x", encoding="utf-8")
        path = tmp_path / "file" / "x.db"  # a file where a directory should be
    before = sorted(p.name for p in tmp_path.iterdir())
    status = run(["optimize", str(OPTIMIZE), "--db", f"sqlite:///{path}"])
    line = _one_line(capsys.readouterr().err)
    assert status == 2 and line.startswith("error: db: cannot open the study database")
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_database_created_then_refused_leaves_no_file(tmp_path: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    """SQLite creates the file when it connects; a failure after that (the schema cannot be
    written) removed nothing and left an empty file."""
    path = tmp_path / "x.db"
    real = studies._META.create_all

    def create_then_fail(engine: object) -> None:
        with engine.connect() as con:  # type: ignore[attr-defined]
            con.exec_driver_sql("CREATE TABLE t (a INTEGER)")
            con.commit()
        assert path.exists()
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(studies._META, "create_all", create_then_fail)
    with pytest.raises(studies.DesignError, match="No space left on device"):
        StudyStore(f"sqlite:///{path}")
    assert not path.exists()
    monkeypatch.setattr(studies._META, "create_all", real)


def _full_disk(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every study database opened from now on fails its first write with ENOSPC."""
    real = StudyStore.__init__

    def opened(self: StudyStore, url: str = studies.DEFAULT_DB) -> None:
        real(self, url)

        def begin() -> None:
            raise OSError(errno.ENOSPC, "No space left on device")

        self.engine.begin = begin  # type: ignore[method-assign]

    monkeypatch.setattr(StudyStore, "__init__", opened)


def test_optimize_on_a_full_disk_is_one_line_exit_2_and_no_new_file(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    _full_disk(monkeypatch)
    db = tmp_path / "full.db"
    status = run(["optimize", str(OPTIMIZE), "--db", f"sqlite:///{db}"])
    line = _one_line(capsys.readouterr().err)
    assert status == 2, line
    assert line.startswith("error: db: cannot write to the study database") and \
        "No space left on device" in line
    assert not db.exists()


def test_a_full_disk_keeps_what_was_stored(tmp_path: Path) -> None:
    """A database that holds evaluations stays (it resumes the study); the write that failed
    is one line."""
    url = f"sqlite:///{tmp_path / 'kept.db'}"
    store = StudyStore(url)
    store.put_many("s", [("k1", {"x": 1}, {"y": 1})])

    def begin() -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    store.engine.begin = begin  # type: ignore[method-assign]
    with pytest.raises(studies.DesignError, match="evaluations stored before stay"):
        store.put_many("s", [("k2", {"x": 2}, {"y": 2})])
    assert (tmp_path / "kept.db").exists() and StudyStore(url).count("s") == 1


def test_robust_modal_refuses_the_dask_options(capsys: pytest.CaptureFixture[str],
                                               tmp_path: Path) -> None:
    for option in (["--db", f"sqlite:///{tmp_path / 'r.db'}"], ["--workers", "2"],
                   ["--scheduler", "tcp://127.0.0.1:1"]):
        status = run(["robust", str(EXAMPLES / "two_sprocket_jindal.toml"), "--modal",
                      *option])
        line = _one_line(capsys.readouterr().err)
        assert status == 2 and line.startswith(f"error: {option[0]}: applies to the full "
                                               "study, not to --modal"), line
    assert not list(tmp_path.iterdir())


def _stored(db: Path) -> int:
    """How many evaluations the study database holds (0 while its table is not there)."""
    try:
        with contextlib.closing(sqlite3.connect(f"file:{db}?mode=ro", uri=True,
                                                timeout=1)) as con:
            return int(con.execute("SELECT count(*) FROM evaluations").fetchone()[0])
    except sqlite3.Error:
        return 0


@pytest.mark.parametrize("moment", ["starting", "computing", "third generation"])
def test_an_interrupted_study_prints_one_line(tmp_path: Path, moment: str) -> None:
    """SIGINT to the whole process group (Ctrl-C in a terminal reaches the workers too) in
    the middle of a study on a local cluster: as it starts (0.5 s after it created its
    database), once its first evaluations are stored, and in its third generation (more
    than two populations of 16 stored; Dask futures are dropped by the hundred by then, and
    a signal inside one's ``__del__`` was lost): one line, exit 130 (it printed 76 lines
    with worker tracebacks 3 times in 10), and the evaluations stored stay for the resume.

    The moments are read from the database, not timed: a fixed 3 s or 6 s after it was
    created could still be the cluster's start on a loaded machine."""
    db = tmp_path / "i.db"
    env = {**os.environ, "CHAINDRIVE_LOG_DIR": str(tmp_path / "logs")}
    # a long search: still running when the signal comes, however fast the evaluations
    long = tmp_path / "long.toml"
    text = OPTIMIZE.read_text()
    assert "generations = 10\n" in text and "population = 16\n" in text
    long.write_text(text.replace("generations = 10\n", "generations = 400\n"))
    proc = subprocess.Popen(
        [sys.executable, "-m", "chaindrive", "optimize", str(long), "--db",
         f"sqlite:///{db}"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
        cwd=tmp_path, start_new_session=True, text=True)
    wanted = {"starting": 0, "computing": 1, "third generation": 2 * 16 + 1}[moment]
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None and not (
            db.exists() and db.stat().st_size > 0 and _stored(db) >= wanted):
        time.sleep(0.05)
    if moment == "starting":
        time.sleep(0.5)  # the workers are starting
    reached = _stored(db)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert _one_line(err) == "error: interrupted by SIGINT; no output is left half-written"
    assert reached >= wanted and _stored(db) >= reached  # what was stored stays
