"""What follows a search: the Pareto designs as design files and their analyses.

The command line writes these (``optimize --out``) and the report presents the chosen one;
both go through :func:`chaindrive.analyze`, so a Pareto design file re-analyses to the
figures the optimiser saw.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from chaindrive.analysis import Analysis, analyze
from chaindrive.io.design import drive_from_mapping, drive_to_toml
from chaindrive.model import Drive
from chaindrive.synthesis.solve import SynthesisResult

__all__ = ["ParetoDesignFile", "chosen_analysis", "pareto_design_files", "pareto_drives"]


@dataclass(frozen=True, slots=True)
class ParetoDesignFile:
    """One Pareto design as a design file.

    Parameters
    ----------
    name : str
        Its file name.
    text : str
        Its TOML text.
    """

    name: str
    text: str


def pareto_drives(result: SynthesisResult, base_dir: Path | None = None) -> tuple[Drive, ...]:
    """The validated drives of the Pareto set.

    Parameters
    ----------
    result : SynthesisResult
        The search.
    base_dir : pathlib.Path or None
        Where relative paths of the designs start.

    Returns
    -------
    tuple of Drive
        In the order of the Pareto set.
    """
    return tuple(drive_from_mapping(p.design, base_dir) for p in result.pareto)


def pareto_design_files(drives: Sequence[Drive], stem: str) -> tuple[ParetoDesignFile, ...]:
    """The Pareto designs as design files ``<stem>_pareto_<k>.toml``.

    Parameters
    ----------
    drives : sequence of Drive
        The Pareto set, validated once (:func:`pareto_drives`).
    stem : str
        Start of the file names.

    Returns
    -------
    tuple of ParetoDesignFile
        One per Pareto design, in the order of the set.
    """
    return tuple(ParetoDesignFile(f"{stem}_pareto_{k:02d}.toml", drive_to_toml(d))
                 for k, d in enumerate(drives, start=1))


def chosen_analysis(drives: Sequence[Drive]) -> Analysis | None:
    """The analysis of the first Pareto design (the one the report presents).

    Parameters
    ----------
    drives : sequence of Drive
        The Pareto set, validated once (:func:`pareto_drives`).

    Returns
    -------
    Analysis or None
        None when the set is empty.
    """
    return analyze(drives[0]) if drives else None
