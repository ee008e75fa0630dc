"""chaindrive — design and dynamic analysis of roller-chain drives.

``load(path)`` reads a design file into a :class:`Drive`; ``analyze(drive)`` returns an
immutable :class:`~chaindrive.analysis.Analysis` whose ``to_dict()`` is the JSON document.
Nothing heavy is imported here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.model import Chain, ChainRequest, ChainSpec, Drive, Material, Sprocket

if TYPE_CHECKING:
    from pathlib import Path

    from chaindrive.analysis import Analysis
    from chaindrive.checks import CheckLimits
    from chaindrive.cost import CostModel

__all__ = ["Chain", "ChainDriveError", "ChainRequest", "ChainSpec", "DesignError", "Drive", "Material",
           "Sprocket", "analyze", "load"]
__version__ = "0.1.0"


@shared_parameters
def load(path: str | Path) -> Drive:
    """Read a TOML design file into a validated :class:`Drive`.

    Parameters
    ----------
    %(design_path)s

    Returns
    -------
    Drive
        The validated design.
    """
    # lazy: the design-file reader brings pint, which `import chaindrive` does not need
    from chaindrive.io.design import load_drive

    return load_drive(path)


@shared_parameters
def analyze(drive: Drive, *, response: bool = True, limits: CheckLimits | None = None,
            cost_model: CostModel | None = None, studies: tuple[str, ...] = (),
            lazy: bool = False, link_duration_s: float | None = None) -> Analysis:
    """Run every analysis of the drive; see :func:`chaindrive.analysis.analyze`.

    Parameters
    ----------
    %(drive)s
    response : bool
        False stops after the modal analysis.
    limits : CheckLimits or None
        Limits of the checks a designer sets (None: the defaults).
    cost_model : CostModel or None
        Prices (None: the packaged estimates).
    studies : tuple of str
        Optional studies to run as well.
    lazy : bool
        True computes each stage on first access only.
    link_duration_s : float or None
        Simulated time of the study "links" [s] (None: the design's start-up duration).

    Returns
    -------
    Analysis
        The analysis of the drive.
    """
    # lazy: the analysis brings scipy and the dynamics, which `import chaindrive` (and the
    # commands that only read or list) do not need
    from chaindrive.analysis import analyze as _analyze

    return _analyze(drive, response=response, limits=limits, cost_model=cost_model,
                    studies=studies, lazy=lazy, link_duration_s=link_duration_s)
