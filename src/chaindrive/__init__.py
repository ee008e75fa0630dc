"""chaindrive — design and dynamic analysis of roller-chain drives.

``load(path)`` reads a design file into a :class:`Drive`; ``analyze(drive)`` returns an
immutable :class:`~chaindrive.analysis.Analysis` whose ``to_dict()`` is the JSON document.
Nothing heavy is imported here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.model import Chain, ChainRequest, ChainSpec, Drive, Material, Sprocket

if TYPE_CHECKING:
    from pathlib import Path

    from chaindrive.analysis import Analysis

__all__ = ["Chain", "ChainDriveError", "ChainRequest", "ChainSpec", "DesignError", "Drive", "Material",
           "Sprocket", "analyze", "load"]
__version__ = "0.1.0"


def load(path: str | Path) -> Drive:
    """Read a TOML design file into a validated :class:`Drive`."""
    from chaindrive.io.design import load_drive

    return load_drive(path)


def analyze(drive: Drive, **options: Any) -> Analysis:
    """Run every analysis of the drive (``response=False``: stop after the modal analysis);
    see :func:`chaindrive.analysis.analyze`."""
    from chaindrive.analysis import analyze as _analyze

    return _analyze(drive, **options)
