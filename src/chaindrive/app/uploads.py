"""What the page accepts from a browser: design files and catalogue files, size-limited, and
kept so that a design can only name the catalogues uploaded in its own session.

A design's ``chain.catalog`` on the page is the *name* of an uploaded catalogue, looked up
in the session's :class:`Uploads`; it never reaches the server's file system as a path
(``../../etc/passwd`` or ``/home/x/secret.csv`` is simply a name nobody uploaded). An
uploaded catalogue is written once, under the SHA-256 of its content, to a directory of the
server's temporary directory, where the catalogue reader (which reads files) finds it;
the same content from two sessions is one file, and a session can only reach the files of
its own uploads through its mapping. At most :data:`MAX_STORED` files are kept (the oldest
go first; a session's upload is written again when it is needed after that).
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from chaindrive import catalog
from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.io.atomic import write_bytes
from chaindrive.io.limits import shown_key

__all__ = ["MAX_STORED", "MAX_UPLOAD_BYTES", "MAX_UPLOAD_MB", "Uploads", "design_text",
           "store_dir"]

#: Largest file the page accepts [bytes] (also Streamlit's own limit, ``server.maxUploadSize``
#: in MB): the largest design example is under 4 kB, the packaged ISO 606 catalogue 20 kB.
MAX_UPLOAD_MB = 1
MAX_UPLOAD_BYTES = MAX_UPLOAD_MB * 1024 * 1024
#: Catalogue files kept on the server at once.
MAX_STORED = 200
#: Catalogues a session may hold.
MAX_PER_SESSION = 20
CATALOG_SUFFIXES = (".csv", ".toml")


def store_dir() -> Path:
    """The directory of the uploaded catalogues.

    Returns
    -------
    Path
        ``<temporary directory>/chaindrive-uploads-<uid>``, created private to this user.
    """
    path = Path(tempfile.gettempdir()) / f"chaindrive-uploads-{os.getuid()}"
    path.mkdir(mode=0o700, exist_ok=True)
    return path


def _checked(name: str, data: bytes, suffixes: tuple[str, ...]) -> str:
    """The upload's name when its size and suffix are acceptable."""
    shown = shown_key(name, 100)
    if len(data) > MAX_UPLOAD_BYTES:
        raise DesignError(shown, f"is {len(data):,} bytes; the page accepts files of at most "
                          f"{MAX_UPLOAD_BYTES:,} bytes")
    if Path(name).suffix.lower() not in suffixes:
        raise DesignError(shown, f"must be a {' or '.join(suffixes)} file")
    return shown


@shared_parameters
def design_text(name: str, data: bytes) -> str:
    """The text of an uploaded design file.

    %(params_upload)s

    Returns
    -------
    str
        The text (size, suffix and UTF-8 checked: a :class:`DesignError` line otherwise).
    """
    shown = _checked(name, data, (".toml",))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise DesignError(shown, "cannot read the file (not UTF-8)") from None


def _prune(directory: Path) -> None:
    """Keep at most :data:`MAX_STORED` files (the least recently written go)."""
    files = sorted(directory.glob("*.*"), key=lambda p: p.stat().st_mtime)
    for old in files[:max(len(files) - MAX_STORED, 0)]:
        old.unlink(missing_ok=True)


@dataclass
class Uploads:
    """The catalogues uploaded in one session.

    Parameters
    ----------
    content : dict of str to bytes
        Name → content (kept in the session, so a file pruned from the store is written
        again when needed).
    """

    content: dict[str, bytes] = field(default_factory=dict)

    @shared_parameters
    def add(self, name: str, data: bytes) -> str:
        """Accept a catalogue upload (size, suffix, UTF-8 and content checked — a malformed
        file is refused now with the catalogue reader's line).

        %(params_upload)s

        Returns
        -------
        str
            The name designs use in ``chain.catalog``.
        """

        shown = _checked(name, data, CATALOG_SUFFIXES)
        key = Path(name).name
        if key not in self.content and len(self.content) >= MAX_PER_SESSION:
            raise DesignError(shown, f"a session holds at most {MAX_PER_SESSION} catalogues")
        path = self._path(key, data)
        try:
            catalog.load_chain_file(path)
        except DesignError as chains_error:
            try:
                catalog.load_material_file(path)
            except DesignError:
                raise DesignError(shown, str(chains_error).replace(str(path), "file")) from None
        self.content[key] = data
        return key

    def _path(self, name: str, data: bytes) -> Path:
        directory = store_dir()
        suffix = Path(name).suffix.lower()
        path = directory / f"{hashlib.sha256(data).hexdigest()}{suffix}"
        if not path.is_file():
            write_bytes(path, data)
            _prune(directory)
        return path

    def paths(self) -> dict[str, Path]:
        """Name → file of every catalogue of the session (what
        :func:`chaindrive.io.design.drive_from_mapping` takes as ``catalogs``).

        Returns
        -------
        dict of str to Path
        """
        return {name: self._path(name, data) for name, data in self.content.items()}
