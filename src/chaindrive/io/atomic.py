"""Outputs that are complete or absent: every file chaindrive writes goes through here.

:func:`atomic_path` gives the writer a temporary name in the target's own directory
(hidden: ``.report.html.<random>.tmp.html``, the target's suffix kept so that writers which
choose the format by it still do); when the writer returns, the file is flushed to disk and
renamed over the target in one step (``os.replace``: on the same file system a rename is
atomic). When the writer fails — a full disk, a signal, a bug — the temporary file is
removed and the target is untouched. :func:`atomic_directory` does the same for a set of
files (``optimize --out``): they are written into a temporary directory, renamed to the
target at the end (or, when the target directory exists, moved into it one by one).

SIGINT and SIGTERM are held back while a rename or a clean-up runs, so a signal never
leaves half of one done; a signal that arrives then is delivered right after. An operating
system error (no space, no permission, a file in the way, a name too long) becomes one
:class:`~chaindrive.errors.DesignError` line naming the output and the reason.

Only SIGKILL (or a power cut before the rename) can leave a temporary ``.…tmp…`` file
behind; the target is never partial.
"""

from __future__ import annotations

import os
import secrets
import shutil
import signal
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from types import FrameType

from chaindrive.errors import DesignError
from chaindrive.units import shown

__all__ = ["atomic_directory", "atomic_path", "handlers_installed", "signals_held", "write_bytes",
           "write_file", "write_text"]

#: Marker in the names of temporary files and directories.
TMP_MARK = ".tmp"
_HELD = (signal.SIGINT, signal.SIGTERM)


@contextmanager
def handlers_installed(signums: Iterable[int],
                       handler: Callable[[int, FrameType | None], object]) -> Iterator[bool]:
    """Within the block, ``handler`` handles the signals ``signums``; the previous handlers
    come back after it. Only the main thread can install handlers; elsewhere this does
    nothing.

    Parameters
    ----------
    signums : iterable of int
        The signals.
    handler : callable
        ``handler(signum, frame)``.

    Yields
    ------
    bool
        Whether the handlers were installed (False outside the main thread).
    """
    if threading.current_thread() is not threading.main_thread():
        yield False
        return
    previous = {s: signal.signal(s, handler) for s in signums}
    try:
        yield True
    finally:
        for s, old in previous.items():
            signal.signal(s, old)


@contextmanager
def signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back within the block (they are delivered when it ends).

    The hold is kept by Python's handlers, not by the thread's signal mask: a process-wide
    signal goes to any thread that does not block it (a BLAS or I/O thread), and Python then
    runs its handler in the main thread at once, whatever the main thread's mask says. Within
    the block a handler that only notes the signal stands in for the installed one; at the
    end the installed ones come back and each signal noted is raised again, once, so that
    its own handler runs. Only the main thread can install handlers; elsewhere this does
    nothing.

    Yields
    ------
    None
    """
    noted: list[int] = []

    def _note(signum: int, frame: FrameType | None) -> None:
        noted.append(signum)

    try:
        with handlers_installed(_HELD, _note):
            yield
    finally:
        for signum in dict.fromkeys(noted):
            signal.raise_signal(signum)


def _failed(target: Path, exc: OSError, field: str) -> DesignError:
    reason = exc.strerror or type(exc).__name__
    return DesignError(field, f"cannot write {shown(str(target))} ({reason})")


def _os_error_behind(exc: BaseException) -> OSError | None:
    """The OSError behind ``exc``: itself, or one it was raised while handling (a writer that
    fails to close a file after the disk filled, as a zlib stream left half-flushed)."""
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        if isinstance(current, OSError):
            return current
        seen.add(id(current))
        current = current.__cause__ or current.__context__
    return None


def _temporary_name(target: Path) -> str:
    return f".{target.name[:60]}.{secrets.token_hex(4)}{TMP_MARK}{target.suffix[:16]}"


def _prepare(target: Path, field: str) -> None:
    """The target's directory exists (created when missing) and the target is no directory."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        if target.is_dir():
            raise IsADirectoryError(21, "Is a directory")
    except OSError as exc:
        raise _failed(target, exc, field) from None


def _sync(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


@contextmanager
def atomic_path(target: str | Path, *, field: str = "output") -> Iterator[Path]:
    """A temporary path for the writer of ``target``; renamed to ``target`` on success.

    Parameters
    ----------
    target : str | Path
        The file to write.
    field : str
        What the output is called in an error line (``"output"``, ``"--out"`` …).

    Yields
    ------
    Path
        An empty file in the target's directory, to be written (by name or opened).

    Raises
    ------
    DesignError
        When the file cannot be written (the operating system's reason in the line); the
        writer's own exceptions pass unchanged. Either way the temporary file is removed.
    """
    final = Path(target)
    _prepare(final, field)
    tmp = final.with_name(_temporary_name(final))
    created = done = False
    try:
        # created under held signals and inside the block whose `finally` removes it: a
        # signal that arrives as the file appears is delivered after `created` is set
        with signals_held():
            try:
                os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            except OSError as exc:
                raise _failed(final, exc, field) from None
            created = True
        yield tmp
        _sync(tmp)
        with signals_held():
            os.replace(tmp, final)
            done = True
    except Exception as exc:
        cause = _os_error_behind(exc)
        if cause is None:
            raise
        raise _failed(final, cause, field) from None
    finally:
        if created and not done:
            with signals_held():
                tmp.unlink(missing_ok=True)


def write_file(target: str | Path, content: str | bytes, *, field: str = "output") -> Path:
    """Write ``content`` to ``target`` atomically (:func:`atomic_path`); text is written
    as UTF-8.

    Parameters
    ----------
    target : str | Path
        The file to write.
    content : str | bytes
        Its whole content.
    field : str
        What the output is called in an error line.

    Returns
    -------
    Path
        ``target``.
    """
    data = content.encode("utf-8") if isinstance(content, str) else content
    with atomic_path(target, field=field) as tmp:
        tmp.write_bytes(data)
    return Path(target)


#: The names the writers of text and of bytes call it by.
write_text = write_bytes = write_file


def _move_into(tmp: Path, final: Path) -> None:
    """Move every entry of ``tmp`` into the existing directory ``final``, then remove
    ``tmp`` (signals held by the caller)."""
    for entry in sorted(tmp.iterdir()):
        dest = final / entry.name
        if dest.is_dir() and not entry.is_dir():
            raise IsADirectoryError(21, "Is a directory", str(dest))
        os.replace(entry, dest)
    tmp.rmdir()


@contextmanager
def atomic_directory(target: str | Path, *, field: str = "output") -> Iterator[Path]:
    """A temporary directory for a set of outputs; it becomes ``target`` on success.

    Parameters
    ----------
    target : str | Path
        The directory to write into (created when missing; an existing one keeps what else
        it holds, and files of the same names are replaced).
    field : str
        What the output is called in an error line.

    Yields
    ------
    Path
        An empty directory next to ``target``: write every file there.

    Raises
    ------
    DesignError
        When the directory cannot be written; the temporary directory is removed.
    """
    final = Path(target)
    try:
        final.parent.mkdir(parents=True, exist_ok=True)
        if final.exists() and not final.is_dir():
            raise NotADirectoryError(20, "Not a directory")
    except OSError as exc:
        raise _failed(final, exc, field) from None
    tmp = final.with_name(_temporary_name(final))
    created = done = False
    try:
        # as in atomic_path: a signal that arrives as the directory appears is delivered
        # inside the block that removes it
        with signals_held():
            try:
                tmp.mkdir()
            except OSError as exc:
                raise _failed(final, exc, field) from None
            created = True
        yield tmp
        for entry in tmp.iterdir():
            if entry.is_file():
                _sync(entry)
        with signals_held():
            if final.is_dir():
                _move_into(tmp, final)
            else:
                os.rename(tmp, final)
            done = True
    except OSError as exc:
        raise _failed(final, exc, field) from None
    finally:
        if created and not done:
            with signals_held():
                shutil.rmtree(tmp, ignore_errors=True)
