"""The page's heavy work, off the server: every run in a child process with a time and a
memory limit.

Streamlit runs each session's script in a thread of the server process, next to the event
loop that answers every browser (and the health check). A computation that holds the
interpreter — a start-up of a stiff ring, a large sweep — would stall them all. So the page
hands each analysis, start-up, report and drawing to :func:`run_bounded`: it runs in a
child process under an address-space limit (``RLIMIT_AS``), and that process is killed when
the run goes past its time. The session's thread only waits on a pipe, which holds no lock:
other sessions stay responsive.

The child processes are kept warm: a run goes to an idle worker process when there is one
(forked from a server of preloaded modules, ``forkserver``), which runs one request after
another under its limit. A run that is stopped — past its time, or its results closed
before their end — kills its worker; a worker that ran out of memory exits; and a worker is
retired after :data:`RUNS_PER_WORKER` runs, so that what a run leaves behind in a process
cannot pile up. A fresh fork per run cost the page about 0.1–0.2 s of every edit (the
fork, re-importing the page's script, the first touch of every copied page, the analysis'
caches cold); a warm worker answers at once.

A limit that is hit becomes a :class:`RunLimitError` — a
:class:`~chaindrive.errors.ChainDriveError`, so the page shows it as one line like any
other mistake in a design. At most :data:`MAX_RUNS` runs go at once; a further one waits
for a slot (within its own time limit).
"""

from __future__ import annotations

import multiprocessing
import os
import threading
import time
import traceback
from collections.abc import Callable, Generator, Iterator
from contextlib import suppress
from multiprocessing.connection import Connection
from typing import Any, TypeVar

from chaindrive.errors import ChainDriveError

__all__ = ["FULL_SECONDS", "INTERACTIVE_SECONDS", "MAX_IDLE", "MAX_RUNS", "MEMORY_BYTES",
           "PRELOAD", "RUNS_PER_WORKER", "RunLimitError", "run_bounded", "run_bounded_steps"]

T = TypeVar("T")

#: Time limit of the analysis redrawn after every edit [s] (``CHAINDRIVE_APP_SECONDS``).
INTERACTIVE_SECONDS = float(os.environ.get("CHAINDRIVE_APP_SECONDS", "20"))
#: Time limit of an on-demand run: the full dynamic analysis, the report, the drawing [s]
#: (``CHAINDRIVE_APP_FULL_SECONDS``).
FULL_SECONDS = float(os.environ.get("CHAINDRIVE_APP_FULL_SECONDS", "60"))
#: Address-space limit of a run [bytes] (``CHAINDRIVE_APP_MEMORY_GB``): a run maps about
#: 0.3 GB of modules; the full analysis of the eight-sprocket example with a 60 s start-up
#: (the longest the design file allows) peaks at 1.2 GB resident.
MEMORY_BYTES = int(float(os.environ.get("CHAINDRIVE_APP_MEMORY_GB", "3")) * 1024**3)
#: Runs at once (each may use up to MEMORY_BYTES).
MAX_RUNS = 4
#: Runs a worker process serves before it is retired (a new one is forked for the next).
RUNS_PER_WORKER = 64
#: Idle workers kept warm at most (each holds its imported modules, about 0.2 GB resident).
MAX_IDLE = 2
#: Modules the fork server imports once, so that a run starts without importing them.
#: Streamlit is among them because every run imports the page's script again (the parent's
#: main module, as multiprocessing does); the script only defines functions then, but its
#: ``import streamlit`` alone took over a second a run.
PRELOAD = ["streamlit", "chaindrive.app.worker", "chaindrive.app.preload", "chaindrive.report",
           "chaindrive.drawing"]
#: Threads of the linear algebra (OpenBLAS, MKL, OpenMP) in a run: one. The page's
#: eigenproblems are small (a few hundred unknowns), where a second thread only waits on
#: the first (numpy's ``eig`` of a 160×160 matrix took 62 ms with two threads, 22 ms with
#: one, on the loaded 2-core machine), and several runs share the cores anyway.
THREADS = {"OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}

_slots = threading.BoundedSemaphore(MAX_RUNS)
_context_lock = threading.Lock()
_context: Any = None
#: Idle workers by their memory limit (at most MAX_IDLE in all), guarded by _context_lock.
_idle: dict[int, list[_Worker]] = {}


class RunLimitError(ChainDriveError):
    """A run of the page passed its time or memory limit, or its process was lost."""


def _mp() -> Any:
    """The multiprocessing context: a fork server with the page's modules preloaded."""
    global _context
    with _context_lock:
        if _context is None:
            for name, value in THREADS.items():  # read by the fork server when it starts
                os.environ.setdefault(name, value)
            ctx = multiprocessing.get_context("forkserver")
            ctx.set_forkserver_preload(PRELOAD)
            _context = ctx
        return _context


def _outcomes(func: Callable[..., Any], args: tuple[Any, ...], steps: bool
              ) -> Iterator[tuple[Any, ...]]:
    """What the child sends: ("ok", item) for each result — the one result of ``func``, or
    with ``steps`` each item its generator yields — then ("end",); or, where it fails,
    ("error", the ChainDriveError), ("memory",) or ("crash", message, traceback)."""
    try:
        if steps:
            for item in func(*args):
                yield ("ok", item)
        else:
            yield ("ok", func(*args))
        yield ("end",)
    except ChainDriveError as exc:
        yield ("error", exc)
    except MemoryError:
        yield ("memory",)
    except BaseException as exc:
        yield ("crash", f"{type(exc).__name__}: {exc}"[:300], traceback.format_exc())


def _answer(conn: Connection, func: Callable[..., Any], args: tuple[Any, ...],
            steps: bool) -> bool:
    """In the worker: run one request, send each of :func:`_outcomes` as it comes; False
    when the worker must exit (out of memory)."""
    for outcome in _outcomes(func, args, steps):
        try:
            conn.send(outcome)
        except MemoryError:
            conn.send(("memory",))
            return False
        except Exception as exc:  # the result could not be pickled
            conn.send(("crash", f"{type(exc).__name__}: {exc}"[:300], traceback.format_exc()))
            return True
        if outcome[0] == "memory":
            return False
    return True


def _serve(conn: Connection, memory: int) -> None:
    """The worker process: limit its memory, then answer one request (function, arguments,
    whether it yields steps) after another until the server closes the pipe."""
    import resource

    with suppress(ValueError, OSError):  # a hard limit below ours: keep it
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    try:
        while True:
            try:
                func, args, steps = conn.recv()
            except (EOFError, OSError):
                return
            if not _answer(conn, func, args, steps):
                return
    finally:
        conn.close()


class _Worker:
    """A warm worker process and the server's end of its pipe."""

    def __init__(self, memory: int) -> None:
        ctx = _mp()
        self.memory = memory
        self.runs = 0
        self.conn, child = ctx.Pipe(duplex=True)
        self.process = ctx.Process(target=_serve, args=(child, memory), daemon=True)
        self.process.start()
        child.close()

    def stop(self) -> None:
        """Kill the worker and reap its process."""
        with suppress(OSError):
            self.conn.close()
        if self.process.is_alive():
            self.process.kill()
        self.process.join(5.0)


def _worker(memory: int) -> _Worker:
    """An idle worker with this memory limit, or a new one."""
    with _context_lock:
        idle = _idle.get(memory, [])
        while idle:
            worker = idle.pop()
            if worker.process.is_alive():
                return worker
            worker.stop()
    return _Worker(memory)


def _release(worker: _Worker) -> None:
    """Keep a worker that finished its request for the next run (or retire it)."""
    worker.runs += 1
    with _context_lock:
        if (worker.runs < RUNS_PER_WORKER and worker.process.is_alive()
                and sum(len(v) for v in _idle.values()) < MAX_IDLE):
            _idle.setdefault(worker.memory, []).append(worker)
            return
    worker.stop()


def run_bounded(func: Callable[..., T], *args: Any, seconds: float = INTERACTIVE_SECONDS,
                memory: int = MEMORY_BYTES, what: str = "the analysis") -> T:
    """``func(*args)`` in a child process, killed after ``seconds`` or when it needs more
    than ``memory`` bytes of address space.

    Parameters
    ----------
    func : callable
        A module-level function (pickled by name); its arguments and result must pickle.
    *args : object
        Its arguments.
    seconds : float
        Time limit [s], counted from the request (a wait for a slot included).
    memory : int
        Address-space limit of the child [bytes].
    what : str
        What the run is, for the message.

    Returns
    -------
    The function's result.

    Raises
    ------
    ChainDriveError
        The function's own (a user's mistake), or :class:`RunLimitError` for a run past a
        limit or a process lost.
    RuntimeError
        When the function failed unexpectedly (its message; the page shows a short note).
    """
    results = _run(func, args, seconds, memory, what, steps=False)
    try:
        return next(results)  # type: ignore[no-any-return]
    finally:
        results.close()


def run_bounded_steps(func: Callable[..., Iterator[T]], *args: Any,
                      seconds: float = INTERACTIVE_SECONDS, memory: int = MEMORY_BYTES,
                      what: str = "the analysis") -> Generator[T, None, None]:
    """The items the generator ``func(*args)`` yields, each as soon as the child process
    sends it: one run, one process, under one time and memory limit, as
    :func:`run_bounded` (the same errors, raised where the items stop). Closing the
    iterator before its end kills the run.

    Parameters
    ----------
    func : callable
        A module-level generator function; its arguments and items must pickle.
    *args : object
        Its arguments.
    seconds : float
        Time limit of the whole run [s], counted from the request.
    memory : int
        Address-space limit of the child [bytes].
    what : str
        What the run is, for the message.

    Returns
    -------
    Iterator
        The items.
    """
    return _run(func, args, seconds, memory, what, steps=True)


def _run(func: Callable[..., Any], args: tuple[Any, ...], seconds: float, memory: int,
         what: str, steps: bool) -> Generator[Any, None, None]:
    """Send the request to a worker (after a free slot), yield its results; the worker is
    free again as soon as its last message is in (the end of a run comes right after its
    last item, so the worker is released before that item is used)."""
    start = time.monotonic()
    if not _slots.acquire(timeout=seconds):
        raise RunLimitError("run", f"{what} waited {seconds:g} s for a free slot (the server "
                            f"runs at most {MAX_RUNS} computations at once); try again")
    worker: _Worker | None = None
    try:
        worker = _worker(memory)
        worker.conn.send((func, args, steps))
        outcome: tuple[Any, ...] | None = _receive(worker, start, seconds, memory, what)
        while outcome is not None and outcome[0] == "ok":
            item, outcome = outcome[1], None
            if not steps or worker.conn.poll(0):  # one result: its end comes next
                outcome = _receive(worker, start, seconds, memory, what)
                if outcome[0] != "ok":
                    _done(worker, outcome)
                    worker = None
                    yield item
                    break
            yield item
            if outcome is None:
                outcome = _receive(worker, start, seconds, memory, what)
        if worker is not None and outcome is not None:
            _done(worker, outcome)
            worker = None
    finally:
        if worker is not None:  # past its time, lost, or its results closed early
            worker.stop()
        _slots.release()
    assert outcome is not None
    _raise(outcome, memory, what)


def _done(worker: _Worker, outcome: tuple[Any, ...]) -> None:
    """A worker whose run ended with ``outcome``: kept for the next run when the run ended
    in order (its end, or an error it caught), else stopped."""
    if outcome[0] in ("end", "error", "crash"):
        _release(worker)
    else:
        worker.stop()


def _receive(worker: _Worker, start: float, seconds: float, memory: int, what: str
             ) -> tuple[Any, ...]:
    """The worker's next message, within what is left of the run's ``seconds``."""
    if not worker.conn.poll(max(seconds - (time.monotonic() - start), 0.0)):
        raise RunLimitError("run", f"{what} took longer than {seconds:g} s, the limit "
                            "of one run on this page; simplify the design or run "
                            "`chaindrive analyze` on your own machine")
    try:
        return worker.conn.recv()  # type: ignore[no-any-return]
    except (EOFError, OSError):
        worker.process.join(5.0)
        raise RunLimitError("run", f"{what} stopped (its process ended with status "
                            f"{worker.process.exitcode}); it may have needed more than "
                            f"{memory / 1024**3:.3g} GB of memory") from None


def _raise(outcome: tuple[Any, ...], memory: int, what: str) -> None:
    """Raise what the child's last message says went wrong (nothing after ("end",))."""
    kind = outcome[0]
    if kind == "end":
        return
    if kind == "error":
        raise outcome[1]
    if kind == "memory":
        raise RunLimitError("run", f"{what} needed more than {memory / 1024**3:.3g} GB of "
                            "memory, the limit of one run on this page")
    raise RuntimeError(f"{what} failed unexpectedly ({outcome[1]})")


def child_pid() -> int:
    """The process id of the process that runs it (a run's worker, in :func:`run_bounded`)."""
    return os.getpid()
