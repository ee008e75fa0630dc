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
import traceback
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path
from types import FrameType

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


def _raise(signum: int, frame: FrameType | None) -> None:
    if _in_finaliser(frame):
        _deliver_later(signum)
        return
    raise Interrupted(signum)


def _in_finaliser(frame: FrameType | None) -> bool:
    """True when ``frame`` runs inside a ``__del__`` method or :func:`_swallowed`: an
    exception raised there is printed as "Exception ignored in …" and dropped, and the
    command goes on as if no signal had come."""
    while frame is not None:
        if frame.f_code.co_name == "__del__" or frame.f_code is _swallowed.__code__:
            return True
        frame = frame.f_back
    return False


def _deliver_later(signum: int) -> None:
    """Send ``signum`` to this process again after :data:`REDELIVER_SECONDS` (from a
    thread: the main thread raises it at its next line outside the finaliser)."""
    timer = threading.Timer(REDELIVER_SECONDS, os.kill, (os.getpid(), signum))
    timer.daemon = True
    timer.start()


def _swallowed(unraisable: sys.UnraisableHookArgs) -> None:
    """``sys.unraisablehook`` while the handlers raise: an :class:`Interrupted` that Python
    could not propagate (raised in a weakref callback or another finaliser not named
    ``__del__``) is delivered again; anything else goes to the hook that was there."""
    if isinstance(unraisable.exc_value, Interrupted):
        _deliver_later(unraisable.exc_value.signum)
        return
    _PREVIOUS_HOOKS[-1](unraisable)


_PREVIOUS_HOOKS: list[Callable[[sys.UnraisableHookArgs], object]] = []


@contextmanager
def signals_raise(signums: Sequence[int] = (signal.SIGINT, signal.SIGTERM)) -> Iterator[None]:
    """Within the block, the signals ``signums`` raise :class:`Interrupted` (the previous
    handlers are restored after it). Outside the main thread, where Python cannot install
    handlers, it does nothing.

    A signal that arrives while a finaliser runs (a ``__del__``, such as a Dask future's,
    which a study drops by the hundred) is sent again a moment later instead: raised there,
    Python printed "Exception ignored in …", dropped it, and an interrupted optimisation
    went on to its last generation.

    Parameters
    ----------
    signums : sequence of int
        The signals.

    Yields
    ------
    None
    """
    with handlers_installed(signums, _raise) as installed:
        if not installed:
            yield
            return
        _PREVIOUS_HOOKS.append(sys.unraisablehook)
        sys.unraisablehook = _swallowed
        try:
            yield
        finally:
            sys.unraisablehook = _PREVIOUS_HOOKS.pop()


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
