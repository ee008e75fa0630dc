"""The safety net every command runs in: one line on the screen, whatever happens.

* A user's mistake (:class:`~chaindrive.errors.ChainDriveError`, a bad option) prints
  ``error: <field>: <what is wrong>`` on stderr and exits with :data:`EXIT_USER_ERROR` (2).
* Anything unforeseen (a bug: ``OverflowError``, ``RecursionError``, ``MemoryError``, an
  ``OSError`` of the machine, a numpy ``RuntimeWarning`` — warnings of that kind are raised
  as errors inside the net, so a result is never computed from an overflow) prints one line
  naming the command and the error, exits with :data:`EXIT_INTERNAL` (1), and writes the
  full traceback to a log file whose path the line gives (:func:`log_dir`).
* SIGINT and SIGTERM raise :class:`Interrupted` (a ``BaseException``), so every ``finally``
  runs — the atomic writers of :mod:`chaindrive.io.atomic` remove their temporary files —
  and the command exits with 128 + the signal number after one line.

Every line is made one line by :func:`one_line` (control characters escaped), so no value a
design file holds can break the promise.
"""

from __future__ import annotations

import datetime as _dt
import os
import signal
import sys
import tempfile
import threading
import time
import traceback
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path
from types import CodeType, FrameType

import click

import chaindrive
from chaindrive.errors import ChainDriveError
from chaindrive.io.atomic import handlers_installed
from chaindrive.io.finite import NonFiniteError

__all__ = ["EXIT_INTERNAL", "EXIT_USER_ERROR", "LOG_DIR_ENV", "Interrupted", "exit_on_signal",
           "guarded", "log_dir", "one_line", "signals_raise"]

EXIT_USER_ERROR = 2
EXIT_INTERNAL = 1
#: Environment variable naming the directory of the crash logs.
LOG_DIR_ENV = "CHAINDRIVE_LOG_DIR"
#: Longest line printed [characters].
MAX_LINE = 600


class Interrupted(BaseException):
    """SIGINT or SIGTERM arrived: unwinds the command so that its ``finally`` blocks run.

    Parameters
    ----------
    signum : int
        The signal's number.
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum

    @property
    def name(self) -> str:
        """The signal's name, e.g. ``"SIGTERM"``."""
        return signal.Signals(self.signum).name


#: How long after a signal met inside a finaliser it is sent again [s].
REDELIVER_SECONDS = 0.01


def _in_finaliser(frame: FrameType | None, hook: CodeType) -> bool:
    """True when ``frame`` runs inside a ``__del__`` method or the unraisable hook ``hook``
    (its code): an exception raised there is printed as "Exception ignored in …" and
    dropped, and the command goes on as if no signal had come."""
    while frame is not None:
        if frame.f_code.co_name == "__del__" or frame.f_code is hook:
            return True
        frame = frame.f_back
    return False


class _Redelivery:
    """A daemon thread that sends a signal to this process again a moment after it is asked
    to. The handler asks by writing one byte to a pipe: it starts no thread and takes no
    lock (a finaliser can run while the main thread holds one of the threading module's)."""

    def __init__(self) -> None:
        self.closing = False
        self._read, self._write = os.pipe()
        self._thread = threading.Thread(target=self._run, daemon=True,
                                        name="chaindrive-signal-redelivery")
        self._thread.start()

    def ask(self, signum: int) -> None:
        """Send ``signum`` again after :data:`REDELIVER_SECONDS`."""
        with suppress(OSError):
            os.write(self._write, bytes([signum]))

    def _run(self) -> None:
        pid = os.getpid()
        while True:
            data = os.read(self._read, 1)
            if not data or data == b"\0":
                return
            time.sleep(REDELIVER_SECONDS)
            if not self.closing:
                os.kill(pid, data[0])

    def close(self) -> None:
        """Stop (a request still pending is dropped: the command has ended)."""
        if self.closing:
            return
        self.closing = True
        with suppress(OSError):
            os.write(self._write, b"\0")
        self._thread.join(timeout=5)
        for fd in (self._read, self._write):
            with suppress(OSError):
                os.close(fd)


@contextmanager
def signals_raise(signums: Sequence[int] = (signal.SIGINT, signal.SIGTERM)) -> Iterator[None]:
    """Within the block, the signals ``signums`` raise :class:`Interrupted` (the previous
    handlers are restored after it). Outside the main thread, where Python cannot install
    handlers, it does nothing.

    A signal that arrives while a finaliser runs (a ``__del__``, such as a Dask future's,
    which a study drops by the hundred) is sent again a moment later instead: raised there,
    Python printed "Exception ignored in …", dropped it, and an interrupted optimisation
    went on to its last generation. An :class:`Interrupted` dropped all the same (raised in
    a finaliser of another kind, a ``weakref.finalize`` callback) reaches
    ``sys.unraisablehook``, which sends the signal again too.

    Parameters
    ----------
    signums : sequence of int
        The signals.

    Yields
    ------
    None
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    redelivery = _Redelivery()
    previous_hook = sys.unraisablehook

    def swallowed(unraisable: sys.UnraisableHookArgs) -> None:
        if isinstance(unraisable.exc_value, Interrupted):
            redelivery.ask(unraisable.exc_value.signum)
        else:
            previous_hook(unraisable)

    def raise_(signum: int, frame: FrameType | None) -> None:
        if redelivery.closing:  # the command has ended
            return
        if _in_finaliser(frame, swallowed.__code__):
            redelivery.ask(signum)
            return
        raise Interrupted(signum)

    try:
        with handlers_installed(signums, raise_):
            sys.unraisablehook = swallowed
            try:
                yield
            finally:
                redelivery.close()
                sys.unraisablehook = previous_hook
    finally:
        redelivery.close()


def _exit_now(signum: int, frame: FrameType | None) -> None:
    with suppress(OSError, ValueError):
        sys.stdout.flush()
    os._exit(128 + signum)


def exit_on_signal(signums: Sequence[int] = (signal.SIGINT, signal.SIGTERM)) -> None:
    """Make ``signums`` end the process at once with 128 + the signal number (stdout
    flushed): what the ``chaindrive`` script does outside its command, where nothing is
    being written and there is nothing to unwind.

    Parameters
    ----------
    signums : sequence of int
        The signals.
    """
    for s in signums:
        signal.signal(s, _exit_now)


def one_line(text: str) -> str:
    """``text`` as one printable line.

    Parameters
    ----------
    text : str
        A message.

    Returns
    -------
    str
        The message with newlines, tabs and other control characters escaped, cut to
        :data:`MAX_LINE` characters.
    """
    out = "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii")
                  for c in text)
    return out if len(out) <= MAX_LINE else out[:MAX_LINE - 1] + "…"


def log_dir() -> Path:
    """The directory of the crash logs.

    Returns
    -------
    Path
        ``$CHAINDRIVE_LOG_DIR``, else ``$XDG_STATE_HOME/chaindrive``
        (``~/.local/state/chaindrive``); the log goes to the temporary directory when that
        cannot be written.
    """
    given = os.environ.get(LOG_DIR_ENV)
    if given:
        return Path(given)
    state = os.environ.get("XDG_STATE_HOME") or str(Path.home() / ".local" / "state")
    return Path(state) / "chaindrive"


def _write_log(argv: Sequence[str], exc: BaseException,
               caught: Sequence[warnings.WarningMessage]) -> Path:
    """Write the traceback of ``exc`` (and the warnings met) to a new log file; its path."""

    stamp = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    text = [f"chaindrive {chaindrive.__version__}, Python {sys.version.split()[0]}, "
            f"{_dt.datetime.now().isoformat(timespec='seconds')}",
            "command: chaindrive " + " ".join(repr(a) if " " in a else a for a in argv), "",
            "".join(traceback.format_exception(exc))]
    if caught:
        text.append("warnings before the failure:")
        text += [f"  {w.filename}:{w.lineno}: {w.category.__name__}: {w.message}" for w in caught]
    body = "\n".join(text) + "\n"
    for directory in (log_dir(), Path(tempfile.gettempdir()) / "chaindrive-logs"):
        try:
            directory.mkdir(parents=True, exist_ok=True)
            fd, name = tempfile.mkstemp(prefix=f"crash-{stamp}-", suffix=".log",
                                        dir=directory)
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(body)
            return Path(name)
        except OSError:
            continue
    raise OSError("no writable directory for the log")


def _command_name(argv: Sequence[str]) -> str:
    words = [a for a in argv if not a.startswith("-")][:1]
    return "chaindrive " + (words[0] if words else "")


def _internal(argv: Sequence[str], exc: BaseException,
              caught: Sequence[warnings.WarningMessage], what: str = "") -> int:
    """One line for an unforeseen failure (``what``: its description, else the error's
    type and text), and the log."""
    if not what:
        name = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
        what = f"internal error in `{_command_name(argv).strip()}` ({name[:200]})"
    try:
        where = f"the traceback is in {_write_log(argv, exc, caught)}"
    except OSError as log_error:
        where = f"no log could be written ({log_error})"
    _say(f"error: {what}; {where}; please report it with the design file")
    return EXIT_INTERNAL


def _say(line: str) -> None:
    """Print one line on stderr (never raises: a closed stderr loses it)."""
    with suppress(OSError, ValueError):
        print(one_line(line), file=sys.stderr, flush=True)


def guarded(invoke: Callable[[], object], argv: Sequence[str]) -> int:
    """Run ``invoke`` (a command with its arguments ``argv``) inside the net; its exit status.

    Parameters
    ----------
    invoke : callable
        Runs the command; returns None or an exit status, or raises.
    argv : sequence of str
        The arguments (for the log and the message).

    Returns
    -------
    int
        0, :data:`EXIT_USER_ERROR`, :data:`EXIT_INTERNAL`, the command's own status, or
        128 + the signal number after SIGINT or SIGTERM.
    """
    with warnings.catch_warnings(record=True) as caught, signals_raise():
        warnings.simplefilter("always")
        warnings.simplefilter("error", RuntimeWarning)
        try:
            status = invoke()
        except ChainDriveError as exc:
            _say(f"error: {exc}")
            return EXIT_USER_ERROR
        except click.UsageError as exc:
            _say(f"error: {exc.format_message()}"
                 + (f" (see `{_command_name(argv)} --help`)" if argv else ""))
            return EXIT_USER_ERROR
        except click.exceptions.Exit as exc:
            return int(exc.exit_code)
        except (Interrupted, KeyboardInterrupt, click.exceptions.Abort) as exc:
            signum = exc.signum if isinstance(exc, Interrupted) else int(signal.SIGINT)
            _say(f"error: interrupted by {signal.Signals(signum).name}; no output is left "
                 "half-written")
            return 128 + signum
        except SystemExit as exc:  # click's answer to a closed pipe
            return exc.code if isinstance(exc.code, int) else EXIT_INTERNAL
        except BrokenPipeError:
            return EXIT_INTERNAL
        except NonFiniteError as exc:
            return _internal(argv, exc, caught, f"the computation did not converge ({exc})")
        except (Exception, RecursionError, MemoryError) as exc:
            return _internal(argv, exc, caught)
    return int(status) if isinstance(status, int) and not isinstance(status, bool) else 0
