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
:class:`~chaindrive.errors.ChainDriveError` whose text is one sentence, so the page shows
it as one line like any other mistake in a design. At most :data:`MAX_RUNS` runs go at
once; a further one waits for a slot (within its own time limit).

Heavy runs — the link-level model, the robust study: up to a minute of both cores — share
a smaller pool: at most :data:`MAX_HEAVY` of them at once (a further one waits for a heavy
slot), at most :data:`HEAVY_PER_SESSION` per session (a second one of the same session is
refused at once), and in worker processes of their own that run at a lower CPU priority
(:data:`HEAVY_NICE`). So the slots and the cores that the light runs need — the analysis
after every edit, the full analysis, the report — stay theirs: the kernel's scheduler gives
a process of niceness 10 about a tenth of a core that a process of niceness 0 wants.
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

__all__ = ["FULL_SECONDS", "HEAVY_NICE", "HEAVY_PER_SESSION", "INTERACTIVE_SECONDS",
           "MAX_HEAVY", "MAX_IDLE", "MAX_RUNS", "MEMORY_BYTES", "PRELOAD", "RUNS_PER_WORKER",
           "RunLimitError", "run_bounded", "run_bounded_steps"]

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
#: Heavy runs at once (each also takes one of the MAX_RUNS slots): the other slots stay for
#: the light runs.
MAX_HEAVY = 2
#: Heavy runs one session may have going at once.
HEAVY_PER_SESSION = 1
#: Niceness of the worker processes of heavy runs (Linux CFS weights: a process of
#: niceness 10 weighs 110 against 1024 at niceness 0, so it gets about a tenth of a core
#: that a light run wants).
HEAVY_NICE = 10
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
_heavy_slots = threading.BoundedSemaphore(MAX_HEAVY)
_context_lock = threading.Lock()
_context: Any = None
#: Idle workers by (memory limit, niceness) (at most MAX_IDLE in all), guarded by
#: _context_lock.
_idle: dict[tuple[int, int], list[_Worker]] = {}
#: Heavy runs going, by session, guarded by _context_lock.
_heavy_runs: dict[str, int] = {}


class RunLimitError(ChainDriveError):
    """A run of the page passed its time or memory limit, or its process was lost; or a
    heavy run was refused (its session has one going).

    Parameters
    ----------
    message : str
        One sentence for the page.
    """

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple[type, tuple[str]]:
        """Pickle by its message (it crosses from a worker process)."""
        return type(self), (self.message,)


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


def _serve(conn: Connection, memory: int, nice: int = 0) -> None:
    """The worker process: limit its memory (and lower its CPU priority by ``nice``), then
    answer one request (function, arguments, whether it yields steps) after another until
    the server closes the pipe."""
    import resource

    with suppress(ValueError, OSError):  # a hard limit below ours: keep it
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    if nice:
        with suppress(OSError):
            os.nice(nice)
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

    def __init__(self, memory: int, nice: int = 0) -> None:
        ctx = _mp()
        self.memory = memory
        self.nice = nice
        self.runs = 0
        self.conn, child = ctx.Pipe(duplex=True)
        self.process = ctx.Process(target=_serve, args=(child, memory, nice), daemon=True)
        self.process.start()
        child.close()

    def stop(self) -> None:
        """Kill the worker and reap its process."""
        with suppress(OSError):
            self.conn.close()
        if self.process.is_alive():
            self.process.kill()
        self.process.join(5.0)


def _worker(memory: int, nice: int = 0) -> _Worker:
    """An idle worker with this memory limit and niceness, or a new one."""
    with _context_lock:
        idle = _idle.get((memory, nice), [])
        while idle:
            worker = idle.pop()
            if worker.process.is_alive():
                return worker
            worker.stop()
    return _Worker(memory, nice)


def _release(worker: _Worker) -> None:
    """Keep a worker that finished its request for the next run (or retire it)."""
    worker.runs += 1
    with _context_lock:
        if (worker.runs < RUNS_PER_WORKER and worker.process.is_alive()
                and sum(len(v) for v in _idle.values()) < MAX_IDLE):
            _idle.setdefault((worker.memory, worker.nice), []).append(worker)
            return
    worker.stop()


def run_bounded(func: Callable[..., T], *args: Any, seconds: float = INTERACTIVE_SECONDS,
                memory: int = MEMORY_BYTES, what: str = "the analysis", heavy: bool = False,
                session: str | None = None) -> T:
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
    heavy : bool
        A heavy run (module docstring: its own pool, share and priority).
    session : str | None
        The session it belongs to (None: the Streamlit session running this thread, else
        this thread).

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
    results = _run(func, args, seconds, memory, what, steps=False,
                   heavy=_session(session) if heavy else None)
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


def _session(given: str | None) -> str:
    """The session a run belongs to: ``given``, else the Streamlit session of this thread,
    else this thread."""
    if given is not None:
        return given
    with suppress(Exception):  # outside a Streamlit script run
        from streamlit.runtime.scriptrunner import get_script_run_ctx

        ctx = get_script_run_ctx(suppress_warning=True)
        if ctx is not None:
            return str(ctx.session_id)
    return f"thread-{threading.get_ident()}"


def _take_heavy(session: str, what: str, start: float, seconds: float) -> None:
    """Count a heavy run of ``session`` and take a heavy slot; RunLimitError (a sentence)
    when the session has its share going, or no heavy slot frees within ``seconds``."""
    with _context_lock:
        going = _heavy_runs.get(session, 0)
        if going >= HEAVY_PER_SESSION:
            raise RunLimitError(f"{what[0].upper()}{what[1:]} was not started: this session "
                                "already has a heavy computation running (the link-level "
                                "model or the life and reliability study); wait for it to "
                                "finish, then try again.")
        _heavy_runs[session] = going + 1
    if not _heavy_slots.acquire(timeout=max(seconds - (time.monotonic() - start), 0.0)):
        _give_heavy(session, slot=False)
        raise RunLimitError(f"{what[0].upper()}{what[1:]} waited {seconds:g} s for the server "
                            f"to finish other heavy computations (it runs at most {MAX_HEAVY} "
                            "at once); try again in a minute.")


def _give_heavy(session: str, slot: bool = True) -> None:
    """Undo :func:`_take_heavy`."""
    if slot:
        _heavy_slots.release()
    with _context_lock:
        left = _heavy_runs.get(session, 1) - 1
        if left > 0:
            _heavy_runs[session] = left
        else:
            _heavy_runs.pop(session, None)


def _run(func: Callable[..., Any], args: tuple[Any, ...], seconds: float, memory: int,
         what: str, steps: bool, heavy: str | None = None) -> Generator[Any, None, None]:
    """Send the request to a worker (after a free slot; a heavy run, ``heavy`` its session,
    after a heavy slot first), yield its results; the worker is free again as soon as its
    last message is in (the end of a run comes right after its last item, so the worker is
    released before that item is used)."""
    start = time.monotonic()
    if heavy is not None:
        _take_heavy(heavy, what, start, seconds)
    if not _slots.acquire(timeout=max(seconds - (time.monotonic() - start), 0.0)):
        if heavy is not None:
            _give_heavy(heavy)
        raise RunLimitError(f"{what[0].upper()}{what[1:]} waited {seconds:g} s for a free "
                            f"slot (the server runs at most {MAX_RUNS} computations at once); "
                            "try again.")
    worker: _Worker | None = None
    try:
        worker = _worker(memory, HEAVY_NICE if heavy is not None else 0)
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
        if heavy is not None:
            _give_heavy(heavy)
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
        raise RunLimitError(f"{what[0].upper()}{what[1:]} took longer than {seconds:g} s, "
                            "the limit of one run on this page; simplify the design or run "
                            "`chaindrive analyze` on your own machine.")
    try:
        return worker.conn.recv()  # type: ignore[no-any-return]
    except (EOFError, OSError):
        worker.process.join(5.0)
        raise RunLimitError(f"{what[0].upper()}{what[1:]} stopped (its process ended with "
                            f"status {worker.process.exitcode}); it may have needed more than "
                            f"{memory / 1024**3:.3g} GB of memory.") from None


def _raise(outcome: tuple[Any, ...], memory: int, what: str) -> None:
    """Raise what the child's last message says went wrong (nothing after ("end",))."""
    kind = outcome[0]
    if kind == "end":
        return
    if kind == "error":
        raise outcome[1]
    if kind == "memory":
        raise RunLimitError(f"{what[0].upper()}{what[1:]} needed more than "
                            f"{memory / 1024**3:.3g} GB of memory, the limit of one run on "
                            "this page.")
    raise RuntimeError(f"{what} failed unexpectedly ({outcome[1]})")


def child_pid() -> int:
    """The process id of the process that runs it (a run's worker, in :func:`run_bounded`)."""
    return os.getpid()
