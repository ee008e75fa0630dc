"""Studies that outgrow one machine: sweeps, Monte-Carlo tolerance studies and optimiser
populations on Dask, stored in a study database.

* Dask: a :class:`distributed.LocalCluster` of worker processes by default, or an existing
  cluster when a scheduler address is given (``tcp://host:8786``). One cluster serves a
  whole study: :class:`DaskEvaluator` starts it on the optimiser's first population and
  keeps it for every generation (closed with the evaluator).
* Storage: SQLAlchemy, a SQLite file by default (``sqlite:///study.db``) or any URL it
  accepts (``postgresql+psycopg://user@host/db``). Each evaluation is stored once, keyed by
  the SHA-256 of its inputs (and the study and function names). A second insert of a key
  is ignored.
* What is kept when a study stops: evaluations go to the workers in chunks (one Dask task
  per evaluation made a 300-design sweep of the 8-sprocket example 1.6× slower on two
  workers: the scheduler's per-task cost competes with the evaluations for the cores). A
  chunk hands back every evaluation it finished, also when a later one raised, and the
  client stores each finished evaluation of a batch before it re-raises a failure. So a
  study that stops (an exception, Ctrl-C) resumes where it stopped: finished keys are read,
  not recomputed. A worker lost mid-chunk takes only that chunk's work with it; the
  scheduler runs the chunk again elsewhere, and nothing stored is lost. A chunk whose
  workers keep dying (Dask gives up on it after its ``allowed-failures``) is submitted
  again, up to :data:`RESUBMITS` times, with only its unfinished evaluations; and when
  Dask's nanny gives up on a worker (it was lost again while it restarted), a watchdog
  re-creates it, so a LocalCluster never runs out of workers.
* A rich progress bar while it runs, silent when the output is not a terminal.
* Failing cleanly: a cluster without a worker for :data:`LOST_WORKERS_SECONDS` ends the
  study (:class:`LostWorkersError`, one line; it resumes from the database); the workers of
  a local cluster log errors only and write their stderr to :data:`WORKER_LOG`, and Dask's
  logging is silenced while a cluster shuts down, so an interrupt is one line.

Compute functions receive one JSON-ready input mapping and return a JSON-ready mapping;
they must be importable by the workers (module-level functions of an installed package).
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import logging
import os
import re
import sys
import tempfile
import threading
import time
import traceback
import uuid
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager, suppress
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from sqlalchemy import (
    Column,
    DateTime,
    Integer,
    MetaData,
    String,
    Table,
    Text,
    UniqueConstraint,
    create_engine,
    select,
)
from sqlalchemy.exc import DBAPIError, IntegrityError

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.io.design import drive_from_mapping
from chaindrive.synthesis.evaluation import Evaluation, evaluate_drive, evaluate_vector
from chaindrive.synthesis.problem import Constraints, Problem
from chaindrive.synthesis.solve import design_mapping
from chaindrive.units import registry

if TYPE_CHECKING:  # distributed is imported where a study runs: `-X importtime` 1.2–1.4 s
    from distributed import Client, Future, LocalCluster

__all__ = ["LOST_WORKERS_SECONDS", "DaskEvaluator", "LostWorkersError", "StudyResult",
           "StudyStore", "evaluate_design", "input_key",
           "monte_carlo_inputs", "run_study", "set_path", "sweep_inputs"]

DEFAULT_DB = "sqlite:///chaindrive-study.db"
#: A compute function of a study: one JSON-ready input mapping → a JSON-ready mapping (the
#: values are JSON's, hence Any).
StudyFunction = Callable[[Mapping[str, Any]], Mapping[str, Any]]
#: How often a chunk that Dask gave up on (its workers were lost) is submitted again.
RESUBMITS = 3
#: How long a study waits for a cluster that has no worker [s] before it stops
#: (:class:`LostWorkersError`): a LocalCluster's nanny restarts a lost worker in about 2 s, and an
#: external scheduler's workers reconnect within their own 30 s connect timeout.
LOST_WORKERS_SECONDS = 60.0
_META = MetaData()
EVALUATIONS = Table(
    "evaluations", _META,
    Column("id", Integer, primary_key=True),
    Column("study", String(200), nullable=False),
    Column("key", String(64), nullable=False),
    Column("inputs", Text, nullable=False),
    Column("result", Text, nullable=False),
    Column("created", DateTime, nullable=False),
    UniqueConstraint("study", "key", name="one_evaluation_per_key"),
)


def _reason(exc: BaseException) -> str:
    """The first line of a database error's cause, with its type."""
    reason = str(getattr(exc, "orig", None) or exc).splitlines()
    return f"{type(exc).__name__}: {(reason or [''])[0][:200]}"


def _new_sqlite_file(engine: Any) -> Path | None:
    """The file of a SQLite URL when it does not exist yet (this store will create it)."""
    if engine.url.get_backend_name() != "sqlite":
        return None
    name = engine.url.database or ""
    if not name or name == ":memory:" or name.startswith("file:"):
        return None
    path = Path(name)
    return None if path.exists() else path


def _json(value: Any) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), default=_plain)


def _plain(value: Any) -> Any:
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON: {type(value).__name__}")


def input_key(function: str, inputs: Any) -> str:
    """The key of one evaluation.

    Parameters
    ----------
    function : str
        The evaluated function's qualified name.
    inputs : object
        Its JSON-ready inputs.

    Returns
    -------
    str
        SHA-256 (hex) of the function name and the canonical JSON of the inputs.
    """
    return hashlib.sha256(_json([function, inputs]).encode()).hexdigest()


class StudyStore:
    """The study database: one row per (study, key) with the inputs and the result (JSON).

    Parameters
    ----------
    url : str
        SQLAlchemy URL (``sqlite:///study.db``, ``postgresql+psycopg://…``); a URL that
        cannot be opened is one :class:`DesignError` line (field ``db``), and a SQLite file
        it created on the way is removed.

    A write that fails (a full disk, a read-only file) is one :class:`DesignError` line as
    well; the evaluations stored before it stay, so the same command resumes once the cause
    is gone; a SQLite file this store created and could not write a single evaluation to is
    removed (no new file is left by a study that stored nothing).
    """

    def __init__(self, url: str = DEFAULT_DB) -> None:
        self.url = url
        self._created: Path | None = None
        try:
            self.engine = create_engine(url)
            self._created = _new_sqlite_file(self.engine)
            _META.create_all(self.engine)
        except Exception as exc:  # sqlalchemy raises several types for a bad URL or file
            self.discard_if_new()
            raise DesignError("db", f"cannot open the study database {url[:200]!r} "
                              f"({_reason(exc)})") from None

    def discard_if_new(self) -> None:
        """Remove the SQLite file this store created when it holds no evaluation (a study
        that stopped before it stored anything leaves no new file)."""
        path, self._created = self._created, None
        if path is None:
            return
        with suppress(Exception):
            if path.exists() and self.holds_any():
                return
        with suppress(Exception):
            self.engine.dispose()
        for leftover in (path, path.with_name(path.name + "-journal")):
            with suppress(OSError):
                leftover.unlink()

    def holds_any(self) -> bool:
        """True when the database holds an evaluation of any study.

        Returns
        -------
        bool
        """
        with self.engine.connect() as con:
            return con.execute(select(EVALUATIONS.c.id).limit(1)).first() is not None

    def _write_failed(self, exc: BaseException) -> DesignError:
        """The one line of a write that failed (the file removed when this store created it
        and it holds nothing)."""
        self.discard_if_new()
        return DesignError("db", f"cannot write to the study database {self.url[:200]!r} "
                           f"({_reason(exc)}); the evaluations stored before stay in it: "
                           "remove the cause and run the same command again to resume")

    @shared_parameters
    def keys(self, study: str, among: Iterable[str] | None = None) -> set[str]:
        """Keys already stored for ``study``: all of them, or those of ``among``.

        Parameters
        ----------
        %(study)s
        among : iterable of str or None
            Keys to look up (None: every key of the study).

        Returns
        -------
        set of str
        """
        where = EVALUATIONS.c.study == study
        if among is not None:
            where = where & EVALUATIONS.c.key.in_(list(among))
        with self.engine.connect() as con:
            return {r[0] for r in con.execute(select(EVALUATIONS.c.key).where(where))}

    @shared_parameters
    def put(self, study: str, key: str, inputs: Any, result: Any) -> bool:
        """Store one evaluation.

        Parameters
        ----------
        %(study)s
        key : str
            The evaluation's key (:func:`input_key`).
        inputs, result : object
            Its inputs and result (JSON-ready).

        Returns
        -------
        bool
            False (and nothing written) when the key is already there.
        """
        try:
            with self.engine.begin() as con:
                con.execute(EVALUATIONS.insert().values(
                    study=study, key=key, inputs=_json(inputs), result=_json(result),
                    created=datetime.now(UTC).replace(tzinfo=None)))
        except IntegrityError:
            return False
        return True

    @shared_parameters
    def put_many(self, study: str, rows: Sequence[tuple[str, Any, Any]]) -> int:
        """Store rows in one transaction, skipping stored keys.

        Parameters
        ----------
        %(study)s
        rows : sequence of (str, object, object)
            (key, inputs, result) of each evaluation.

        Returns
        -------
        int
            How many were written.
        """
        if not rows:
            return 0
        stored = self.keys(study, [k for k, _, _ in rows])
        fresh = {k: (x, r) for k, x, r in rows if k not in stored}
        now = datetime.now(UTC).replace(tzinfo=None)
        try:
            with self.engine.begin() as con:
                if fresh:
                    con.execute(EVALUATIONS.insert(), [
                        {"study": study, "key": k, "inputs": _json(x), "result": _json(r),
                         "created": now} for k, (x, r) in fresh.items()])
        except IntegrityError:  # another client stored some meanwhile: one by one
            return sum(self.put(study, k, x, r) for k, (x, r) in fresh.items())
        except (DBAPIError, OSError) as exc:  # a full disk, a read-only file, a lost server
            raise self._write_failed(exc) from None
        if fresh:
            self._created = None  # holds evaluations now: kept for a resume
        return len(fresh)

    @shared_parameters
    def get(self, study: str, keys: Iterable[str]) -> dict[str, Any]:
        """Stored results by key.

        Parameters
        ----------
        %(study)s
        keys : iterable of str
            Keys to look up.

        Returns
        -------
        dict
            Key → result (missing keys are absent).
        """
        wanted = list(keys)
        out: dict[str, Any] = {}
        with self.engine.connect() as con:
            for i in range(0, len(wanted), 500):
                rows = con.execute(select(EVALUATIONS.c.key, EVALUATIONS.c.result).where(
                    EVALUATIONS.c.study == study, EVALUATIONS.c.key.in_(wanted[i:i + 500])))
                out.update({k: json.loads(r) for k, r in rows})
        return out

    @shared_parameters
    def count(self, study: str) -> int:
        """Number of evaluations stored for ``study``.

        Parameters
        ----------
        %(study)s

        Returns
        -------
        int
        """
        return len(self.keys(study))

    def close(self) -> None:
        """Release the connections."""
        self.engine.dispose()


@shared_parameters
@dataclass(frozen=True, slots=True)
class StudyResult:
    """The outcome of :func:`run_study`.

    Parameters
    ----------
    %(study)s
    results : tuple
        The results, in the order of the inputs.
    computed : int
        Evaluations computed now.
    reused : int
        Evaluations read from the database.
    """

    study: str
    results: tuple[Any, ...]
    computed: int
    reused: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"study": self.study, "computed": self.computed, "reused": self.reused,
                "results": list(self.results)}


def _safe(func: Callable[[Any], Any], inputs: Any) -> Any:
    """Run one evaluation; a user error becomes a stored ``{"error": …}`` result."""
    try:
        return func(inputs)
    except ChainDriveError as exc:
        return {"error": str(exc)}


def _chunk(func: Callable[[Any], Any], items: list[tuple[str, Any]]
           ) -> tuple[list[tuple[str, Any]], BaseException | None]:
    """One Dask task: a few evaluations, each returned with its key as soon as the chunk ends.

    An evaluation that raises (anything but a user error, which :func:`_safe` stores) stops
    the chunk: the evaluations finished before it are returned with the exception, so the
    client stores them before it re-raises — finished work is never dropped with its chunk.
    The worker's traceback travels with the exception as a note.
    """
    done: list[tuple[str, Any]] = []
    for k, x in items:
        try:
            done.append((k, _safe(func, x)))
        except Exception as exc:
            exc.add_note("".join(traceback.format_exception(exc)))
            return done, exc
    return done, None


def _chunk_size(count: int, workers: int) -> int:
    """Evaluations per task: about 4 tasks per worker, at most 32 (a lost worker then loses
    at most one unfinished chunk; a chunk of 10 ms designs costs ~0.3 s)."""
    return max(1, min(32, count // (4 * max(workers, 1))))


def _client(scheduler: str | None, n_workers: int | None
            ) -> tuple[Client, LocalCluster | None]:
    """A client of the scheduler at ``scheduler``, or of a new LocalCluster (one try more
    when a worker is lost while the cluster starts)."""
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            return Client(scheduler, timeout="30s"), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise DesignError("scheduler", f"cannot reach the Dask scheduler {scheduler[:200]!r} "
                              f"({type(exc).__name__})") from None
    for attempt in (1, 2):
        cluster = None
        try:
            with _workers_stderr_to_log():
                # the workers log errors only: a task cancelled at an interrupt or an error
                # is a warning of each worker process, lines around the command's one line
                cluster = LocalCluster(n_workers=n_workers, threads_per_worker=1,
                                       processes=True, dashboard_address=":0",
                                       silence_logs=logging.ERROR)
            return Client(cluster), cluster
        except Exception:
            if cluster is not None:
                cluster.close()
            if attempt == 2:
                raise
    raise AssertionError("unreachable")


#: Where the worker processes of a local cluster write their stderr (appended).
WORKER_LOG = Path(tempfile.gettempdir()) / "chaindrive-dask-workers.log"


@contextmanager
def _workers_stderr_to_log() -> Iterator[None]:
    """Start a cluster's worker processes with their stderr in :data:`WORKER_LOG`: they
    inherit the file descriptor 2 of this process when they start, which is the log while
    the block runs. Ctrl-C in a terminal reaches the workers too, and each printed its own
    KeyboardInterrupt traceback among the one line of the interrupt (3 times in 10). The
    signals are left alone: an interrupt while the cluster starts is not lost."""
    try:
        log = os.open(WORKER_LOG, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
    except OSError:  # no log: the workers write where this process does
        yield
        return
    with suppress(OSError, ValueError):
        sys.stderr.flush()
    saved = os.dup(2)
    try:
        os.dup2(log, 2)
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        os.close(log)


@contextmanager
def quiet_shutdown() -> Iterator[None]:
    """Silence Dask's and Tornado's logging while a cluster shuts down: closing it with
    tasks running (an error, an interrupt) logs the cancelled tasks and lost connections,
    tens of lines around the one line of the command."""
    names = ("distributed", "tornado", "asyncio")
    loggers = [logging.getLogger(n) for n in names]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for lg, level in zip(loggers, levels, strict=True):
            lg.setLevel(level)


class _Watchdog:
    """Keeps a LocalCluster at its number of workers while a study runs.

    Dask's nanny restarts a lost worker, but gives up when the new one is lost again while
    it starts: the cluster then shrinks, and with no worker left a study would wait for
    ever. Every ``period`` seconds the watchdog re-creates the workers whose nanny closed
    (seen once, gone now) or failed to start (the cluster lists a worker only once its start
    ended, and one killed while it started may never have been seen running); workers still
    starting are left alone.
    """

    def __init__(self, cluster: LocalCluster, period: float = 1.0) -> None:
        self.cluster = cluster
        self.size = len(cluster.worker_spec)
        self.period = period
        self._seen: set[Any] = set()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True,
                                        name="chaindrive-dask-watchdog")
        self._thread.start()

    def revive(self) -> bool:
        """Re-create the workers that were lost for good; True when it did."""
        workers = dict(self.cluster.workers)
        running = {k for k, w in workers.items()
                   if getattr(w.status, "name", "") not in ("closed", "failed", "closing")}
        self._seen |= running
        gone = [k for k in list(self.cluster.worker_spec)
                if k not in running and (k in self._seen or k in workers)]
        if not gone:
            return False
        for name in gone:
            self.cluster.worker_spec.pop(name, None)
        self.cluster.scale(self.size)
        return True

    def _run(self) -> None:
        while not self._stop.wait(self.period):
            with suppress(Exception):  # the cluster is closing: nothing to keep
                self.revive()

    def stop(self) -> None:
        """Stop watching (before the cluster is closed)."""
        self._stop.set()
        self._thread.join()


def _progress(enabled: bool | None) -> Any:
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeRemainingColumn

    console = Console(stderr=True)
    show = console.is_terminal if enabled is None else enabled
    return Progress("[progress.description]{task.description}", BarColumn(),
                    MofNCompleteColumn(), TimeRemainingColumn(), console=console,
                    disable=not show)


def _lost(exc: BaseException) -> bool:
    """True when a task failed because its workers were lost (not by its own error)."""
    from distributed import KilledWorker

    return isinstance(exc, KilledWorker)


def _submit(client: Client, func: Callable[[Any], Any], items: list[tuple[str, Any]], key: str
            ) -> Future:
    return client.submit(_chunk, func, items, key=key, pure=False)


def _workers(client: Client) -> int:
    """How many workers the scheduler has now (0 when it cannot be asked)."""
    try:
        return len(client.scheduler_info(n_workers=-1)["workers"])
    except Exception:  # the scheduler itself is gone
        return 0


#: Longest wait for a finished future before the workers are counted again [s].
WORKERS_CHECK_SECONDS = 0.2


def _wait_ready(pending: Any, seconds: float) -> None:
    """Return as soon as a future of ``pending`` (a ``distributed.as_completed``) is ready,
    or after ``seconds``. It waits on the condition that ``as_completed`` notifies when it
    queues a finished future (checked under its lock: a notification is never missed); a
    fixed sleep made each generation of a study wait a fraction of those seconds after its
    last future finished."""
    condition = getattr(pending, "thread_condition", None)
    if condition is None:  # not a distributed.as_completed: poll
        time.sleep(seconds)
        return
    with condition:
        if not pending.has_ready():
            condition.wait(timeout=seconds)


def _batches(client: Client, pending: Any, lost_after: float) -> Iterable[list[Any]]:
    """The finished futures of ``pending`` as they arrive; :class:`LostWorkersError` when the
    cluster has had no worker for ``lost_after`` seconds (Dask would wait for ever)."""
    alone_since: float | None = None
    while not pending.is_empty():
        if pending.has_ready():
            alone_since = None
            yield pending.next_batch(block=False)
            continue
        now = time.monotonic()
        if _workers(client) > 0:
            alone_since = None
        elif alone_since is None:
            alone_since = now
        elif now - alone_since >= lost_after:
            raise LostWorkersError(lost_after)
        _wait_ready(pending, WORKERS_CHECK_SECONDS)


class LostWorkersError(ChainDriveError):
    """The cluster lost every worker and none came back within the timeout.

    Parameters
    ----------
    seconds : float
        How long it had no worker [s].
    """

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        super().__init__(f"scheduler: the Dask cluster has had no worker for {seconds:g} s; "
                         "the study stopped (the evaluations finished are stored: start "
                         "workers and run the same command again to resume)")


def _evaluate_on(client: Client, func: Callable[[Any], Any], study: str, todo: dict[str, Any],
                 store: StudyStore, bar: Any, task: Any, chunk: int | None,
                 lost_after: float | None = None,
                 on_stored: Callable[[int], None] | None = None) -> int:
    """Run every evaluation of ``todo`` on ``client``, storing each as it arrives; the count
    stored. A chunk Dask gave up on is submitted again (:data:`RESUBMITS`); any other
    failure is raised after the finished evaluations are stored; a cluster without a worker
    for ``lost_after`` seconds ends the study (:class:`LostWorkersError`)."""
    from distributed import as_completed

    run = uuid.uuid4().hex[:8]  # a fresh task key per run: no stale erred task is reused
    items = list(todo.items())
    size = chunk or _chunk_size(len(items), len(client.scheduler_info()["workers"]))
    chunks = {_submit(client, func, items[i:i + size], f"{study}-{items[i][0]}-{run}"):
              (items[i:i + size], 0) for i in range(0, len(items), size)}
    pending = as_completed(list(chunks))
    computed = 0
    try:
        for batch in _batches(client, pending,
                              LOST_WORKERS_SECONDS if lost_after is None else lost_after):
            failure: BaseException | None = None
            rows: list[tuple[str, Any, Any]] = []
            for fut in batch:
                part, tries = chunks.pop(fut)
                try:
                    done, exc = fut.result()
                except Exception as lost:  # the task itself failed (e.g. its workers died)
                    done, exc = [], lost
                rows += [(k, todo[k], r) for k, r in done]
                finished = {k for k, _ in done}
                rest = [(k, x) for k, x in part if k not in finished]
                if exc is not None and _lost(exc) and rest and tries < RESUBMITS:
                    again = _submit(client, func, rest, f"{study}-{rest[0][0]}-{run}-{tries + 1}")
                    chunks[again] = (rest, tries + 1)
                    pending.add(again)
                    continue
                failure = failure or exc
            computed += store.put_many(study, rows)
            bar.advance(task, len(rows))
            if on_stored is not None and rows:
                on_stored(len(rows))
            if failure is not None:
                raise failure
    finally:
        client.cancel(list(chunks))
    return computed


def run_study(func: StudyFunction, inputs: Sequence[Mapping[str, Any]], *, study: str,
              db: str | StudyStore = DEFAULT_DB, scheduler: str | None = None,
              client: Client | None = None, n_workers: int | None = None,
              progress: bool | None = None, chunk: int | None = None,
              lost_after: float | None = None,
              on_stored: Callable[[int], None] | None = None,
              connect: Callable[[], Client] | None = None) -> StudyResult:
    """Evaluate ``func`` on every input through Dask, storing each result once. Inputs whose
    key is stored are not recomputed (and when every one is, no cluster is asked for).

    Parameters
    ----------
    func : callable
        A module-level function of one JSON-ready input.
    inputs : sequence
        The inputs.
    study : str
        Name of the study in the database.
    db : str | StudyStore
        URL or an open store.
    scheduler : str | None
        Address of an existing Dask scheduler (None: a LocalCluster of ``n_workers``
        processes, closed at the end).
    client : distributed.Client | None
        An existing client (takes precedence; left open).
    n_workers : int | None
        Workers of the LocalCluster (None: Dask's default).
    progress : bool | None
        Progress bar (None: only on a terminal).
    chunk : int | None
        Evaluations per Dask task (None: by the number of workers, :func:`_chunk_size`).
    lost_after : float | None
        Time without a worker [s] after which the study stops with :class:`LostWorkersError`
        (None: :data:`LOST_WORKERS_SECONDS`).
    on_stored : callable | None
        Called with the number of evaluations each time a batch of them is stored (a
        progress bar of the caller's; the evaluations found stored are not counted).
    connect : callable | None
        Returns an existing client (left open), called only when an evaluation is not
        stored yet; used when ``client`` is None.

    Returns
    -------
    StudyResult
    """
    store = db if isinstance(db, StudyStore) else StudyStore(db)
    name = f"{func.__module__}.{func.__qualname__}"
    keys = [input_key(name, x) for x in inputs]
    done = store.keys(study)
    todo: dict[str, Any] = {}
    for k, x in zip(keys, inputs, strict=True):
        if k not in done:
            todo.setdefault(k, x)
    computed = 0
    if todo:
        if client is None and connect is not None:
            client = connect()
        own = client is None
        cluster: LocalCluster | None = None
        watchdog: _Watchdog | None = None
        if client is None:
            client, cluster = _client(scheduler, n_workers)
            watchdog = None if cluster is None else _Watchdog(cluster)
        try:
            with _progress(progress) as bar:
                task = bar.add_task(study, total=len(keys), completed=len(keys) - len(todo))
                computed = _evaluate_on(client, func, study, todo, store, bar, task, chunk,
                                        lost_after, on_stored)
        except BaseException:
            store.discard_if_new()
            raise
        finally:
            if own:
                if watchdog is not None:
                    watchdog.stop()
                with quiet_shutdown():
                    client.close()
                    if cluster is not None:
                        cluster.close()
    stored = store.get(study, keys)
    return StudyResult(study, tuple(stored.get(k) for k in keys), computed,
                       len(keys) - len(todo))


# ---------------------------------------------------------------------- inputs of studies
_PATH = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?")


@shared_parameters
def set_path(mapping: dict[str, Any], path: str, value: Any) -> None:
    """Set a value in a design mapping (in place).

    Parameters
    ----------
    mapping : dict
        The design mapping.
    %(field_path)s
    value : object
        The new value.
    """
    node: Any = mapping
    parts = path.split(".")
    for depth, part in enumerate(parts):
        m = _PATH.fullmatch(part)
        if m is None:
            raise DesignError(path, "is not a field path such as sprockets[2].x or drive.power")
        last = depth == len(parts) - 1
        key, index = m.group(1), m.group(2)
        if index is None and last:
            node[key] = value
            return
        if key not in node:
            raise DesignError(path, f"{key!r} is not in the design")
        node = node[key]
        if index is not None:
            if not isinstance(node, list) or int(index) >= len(node):
                raise DesignError(path, f"{key} has no item {index}")
            if last:
                node[int(index)] = value
                return
            node = node[int(index)]


@shared_parameters
def get_path(mapping: Mapping[str, Any], path: str) -> Any:
    """The value at a path of a design mapping.

    Parameters
    ----------
    mapping : Mapping
        The design mapping.
    %(field_path)s

    Returns
    -------
    object
    """
    node: Any = mapping
    for part in path.split("."):
        m = _PATH.fullmatch(part)
        if m is None or m.group(1) not in node:
            raise DesignError(path, "is not in the design")
        node = node[m.group(1)]
        if m.group(2) is not None:
            node = node[int(m.group(2))]
    return node


def sweep_inputs(base: Mapping[str, Any], grid: Mapping[str, Sequence[Any]],
                 objectives: Sequence[str] = ("cost", "mass", "volume")) -> list[dict[str, Any]]:
    """Inputs of :func:`evaluate_design` for the Cartesian product of ``grid``.

    Parameters
    ----------
    base : Mapping
        The design mapping.
    grid : Mapping of str to sequence
        Path → values, in the design file's notation (e.g.
        ``{"sprockets[1].x": ["790 mm", "810 mm"]}``).
    objectives : sequence of str
        Objectives to evaluate.

    Returns
    -------
    list of dict
    """
    paths = list(grid)
    out = []
    for combo in itertools.product(*(grid[p] for p in paths)):
        design = copy.deepcopy(dict(base))
        for p, v in zip(paths, combo, strict=True):
            set_path(design, p, v)
        out.append({"design": design, "objectives": list(objectives)})
    return out


_QTY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*)$")


def _split(text: Any, path: str) -> tuple[float, str]:
    if isinstance(text, int | float) and not isinstance(text, bool):
        return float(text), ""
    m = _QTY.match(str(text))
    if m is None:
        raise DesignError(path, f"cannot read {text!r} as a number with a unit")
    return float(m.group(1)), m.group(2).strip()


def monte_carlo_inputs(base: Mapping[str, Any], tolerances: Mapping[str, Any], samples: int,
                       seed: int = 0, objectives: Sequence[str] = ("cost", "mass", "volume")
                       ) -> list[dict[str, Any]]:
    """Inputs of :func:`evaluate_design` with normally distributed deviations.

    Parameters
    ----------
    base : Mapping
        The design mapping.
    tolerances : Mapping
        Path → standard deviation in the unit of the value at that path (e.g.
        ``{"sprockets[1].x": "0.2 mm"}`` for ``x = "800 mm"``).
    samples : int
        Number of samples.
    seed : int
        Random seed (same seed, same samples).
    objectives : sequence of str
        Objectives to evaluate.

    Returns
    -------
    list of dict
    """

    ureg = registry()
    rng = np.random.default_rng(seed)
    plan = []
    for path, sigma in tolerances.items():
        value, unit = _split(get_path(base, path), path)
        s, s_unit = _split(sigma, f"tolerances.{path}")
        if unit and s_unit and s_unit != unit:
            s = float(ureg.Quantity(s, s_unit).to(unit).magnitude)
        plan.append((path, value, unit, s))
    out = []
    for _ in range(int(samples)):
        design = copy.deepcopy(dict(base))
        for path, value, unit, s in plan:
            v = value + s * rng.standard_normal()
            set_path(design, path, f"{v:.9g} {unit}".strip() if unit else v)
        out.append({"design": design, "objectives": list(objectives)})
    return out


def evaluate_design(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """Worker function of sweeps and Monte-Carlo studies.

    Parameters
    ----------
    inputs : Mapping
        ``{"design": mapping, "objectives": [...]}``.

    Returns
    -------
    dict
        The evaluation (objectives, constraints, constraints_ok) of that design.
    """

    drive = drive_from_mapping(inputs["design"])
    return evaluate_drive(drive, inputs.get("objectives", ["cost", "mass", "volume"]),
                          Constraints()).to_dict()


def _evaluate_vector(inputs: Mapping[str, Any]) -> dict[str, Any]:

    ev, drive = evaluate_vector(inputs["problem"], inputs["vector"])
    return {"evaluation": ev.to_dict(), "design": None if drive is None else design_mapping(drive)}


def problem_fingerprint(problem: Problem) -> str:
    """A stable hash of a problem's definition (start design, genes, objectives, settings)."""
    parts = [problem.base_mapping, repr(problem.genes), list(problem.objectives),
             repr(problem.constraints), problem.ratio_tolerance]
    if problem.robust is not None:  # [optimize.robust] (chaindrive.robust)
        parts.append(repr(problem.robust))
    return hashlib.sha256(_json(parts).encode()).hexdigest()[:16]


class DaskEvaluator:
    """A batch evaluator for :func:`chaindrive.synthesis.solve.solve` that runs each
    population on one Dask cluster and stores it (study default: ``optimize-<problem
    hash>``), so a rerun with the same seed resumes from the database.

    The cluster (a LocalCluster unless ``scheduler`` or ``client`` is given) starts with the
    first population that has an evaluation not stored yet and serves every generation;
    :meth:`close` (or leaving a ``with`` block) shuts it down. A worker lost at any time
    costs only the chunk it was running, which runs again (:func:`run_study`).

    Parameters
    ----------
    db : str | StudyStore
        The study database.
    study : str | None
        Name of the study (None: from the problem's fingerprint).
    scheduler : str | None
        Address of an existing scheduler.
    client : distributed.Client | None
        An existing client (left open by :meth:`close`).
    progress : bool | None
        Progress bar (None: only on a terminal).
    n_workers : int | None
        Workers of the LocalCluster (None: Dask's default).
    lost_after : float | None
        Time without a worker [s] after which the study stops (:class:`LostWorkersError`;
        None: :data:`LOST_WORKERS_SECONDS`).
    on_stored : callable | None
        Called with the number of evaluations each time a batch of them is stored (as
        :func:`run_study`): progress within a generation.
    """

    def __init__(self, *, db: str | StudyStore = DEFAULT_DB, study: str | None = None,
                 scheduler: str | None = None, client: Client | None = None,
                 progress: bool | None = False, n_workers: int | None = None,
                 lost_after: float | None = None,
                 on_stored: Callable[[int], None] | None = None) -> None:
        self.lost_after = lost_after
        self.on_stored = on_stored
        self.store = db if isinstance(db, StudyStore) else StudyStore(db)
        self.study = study
        self.scheduler = scheduler
        self.progress = progress
        self.n_workers = n_workers
        self._client = client
        self._own = client is None
        self._cluster: LocalCluster | None = None
        self._watchdog: _Watchdog | None = None

    @property
    def client(self) -> Client:
        """The Dask client, started on first use (with a watchdog that keeps its own
        LocalCluster at full strength)."""
        if self._client is None:
            self._client, self._cluster = _client(self.scheduler, self.n_workers)
            if self._cluster is not None:
                self._watchdog = _Watchdog(self._cluster)
        return self._client

    def __call__(self, problem: Problem, xs: Sequence[Sequence[float]]
                 ) -> list[tuple[Evaluation, dict[str, Any] | None]]:

        fp = problem_fingerprint(problem)
        name = self.study or f"optimize-{fp}"
        wrapped = [_VectorInput(problem, [float(v) for v in x], fp) for x in xs]
        # the cluster starts with the first population not all stored (a rerun of a study
        # whose evaluations are all stored starts none)
        res = run_study(_evaluate_vector, wrapped, study=name, db=self.store,
                        connect=lambda: self.client, progress=self.progress,
                        lost_after=self.lost_after, on_stored=self.on_stored)
        out = []
        for r in res.results:
            e = r["evaluation"]
            out.append((Evaluation(e["objectives"], e["constraints"], e["constraints_ok"],
                                   e["error"], dict(e.get("unverified") or {})), r["design"]))
        return out

    def close(self) -> None:
        """Shut down the cluster this evaluator started (an existing client is left open)."""
        if self._own and self._client is not None:
            if self._watchdog is not None:
                self._watchdog.stop()
                self._watchdog = None
            with quiet_shutdown():
                self._client.close()
                if self._cluster is not None:
                    self._cluster.close()
            self._client = self._cluster = None

    def __enter__(self) -> DaskEvaluator:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class _VectorInput(dict[str, Any]):
    """Input of one vector: hashed by (problem fingerprint, vector), carries the problem."""

    def __init__(self, problem: Problem, vector: list[float], fingerprint: str) -> None:
        super().__init__(problem_fingerprint=fingerprint, vector=vector)
        self.problem = problem

    def __getitem__(self, key: str) -> Any:
        return self.problem if key == "problem" else super().__getitem__(key)

    def __reduce__(self) -> Any:
        return (_VectorInput, (self.problem, self["vector"], self["problem_fingerprint"]))
