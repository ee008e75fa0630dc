"""Chain length choices: the even link counts below and above the tight length, each with
its centre distance and take-up, and the installed position with a sag allowance.

The tight length L_p of the layout as designed is rarely a whole even number. Rounding up
lengthens the chain and the take-up moves the adjustable sprocket out; rounding down (what
many designers do, e.g. [Jindal2010, ex. 30-2]: 80.21 → 80 links) moves it in. Both are
laid out with the contour solver (:func:`chaindrive.geometry.contour.contour_geometry`), so
they hold for any contour with an adjustable sprocket, not only for two sprockets.

Sag allowance: installed with a slack-span sag s·ℓ, the chain keeps ΔL = (8/3)·s²·ℓ of
slack (:mod:`chaindrive.geometry.sag`) and the adjustable sprocket stops short of the tight
position by that much chain.

References
----------
[Shigley2015] Eq. 17-34/17-35; [Bhandari2010] ex. 14.4 (Δa = 0.002·a); [ChainDesignRU] §6–7.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry, round_links, tight_pitches_of
from chaindrive.geometry.results import GeometryResult
from chaindrive.geometry.sag import sag_of_slack
from chaindrive.geometry.sprocket import pitch_radius
from chaindrive.model import Drive


@dataclass(frozen=True, slots=True)
class LengthOption:
    """One whole link count laid out.

    Parameters
    ----------
    rounding : str
        "round down" or "round up".
    links : int
        The count [-].
    centre_distance : float or None
        Two sprockets: the centre distance [m] (else None).
    take_up : float or None
        How far the adjustable sprocket moved from the designed position [m] (positive:
        out; None without an adjustable sprocket).
    slack_sag : float or None
        Sag of the slack span from the slack the chain keeps [m] (0 when laid out tight).
    error : str or None
        Why this count cannot be laid out (None when it can).
    """

    rounding: str
    links: int
    centre_distance: float | None
    take_up: float | None
    slack_sag: float | None
    error: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm)."""
        def mm(x: float | None) -> float | None:
            return None if x is None else x * 1e3

        return {"rounding": self.rounding, "links": self.links,
                "centre_distance_mm": mm(self.centre_distance), "take_up_mm": mm(self.take_up),
                "slack_sag_mm": mm(self.slack_sag), "error": self.error}


@dataclass(frozen=True, slots=True)
class LengthChoice:
    """The tight length of the layout as designed and the even counts around it.

    Parameters
    ----------
    tight_pitches : float
        L_p of the designed layout [pitches].
    options : tuple of LengthOption
        Round down, round up.
    chosen : str
        The design's pick ("round up" by default, "round down", or "given" for an imposed
        count).
    sag_fraction : float or None
        The installed sag asked for [-] (None: tight).
    """

    tight_pitches: float
    options: tuple[LengthOption, ...]
    chosen: str
    sag_fraction: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"tight_length_pitches": self.tight_pitches, "chosen": self.chosen,
                "sag_fraction": self.sag_fraction,
                "options": [o.to_dict() for o in self.options]}


def _option(drive: Drive, rounding: str, links: int,
            laid: GeometryResult | None = None) -> LengthOption:
    if laid is not None and laid.links == links:
        g = laid  # the design's own layout of this count: not laid out again
    else:
        chain = replace(drive.chain, links=links, request=None)
        try:
            g = contour_geometry(replace(drive, chain=chain))
        except DesignError as exc:
            return LengthOption(rounding, links, None, None, None, str(exc))
    slack_span = g.spans[drive.driver_index]
    sag = sag_of_slack(slack_span.length, g.slack) if g.slack > 0 else 0.0
    return LengthOption(rounding, links, g.center_distance,
                        None if g.adjusted is None else g.adjustment, sag)


@shared_parameters
def tight_pitches_as_designed(drive: Drive) -> float:
    """Tight length at the sprocket positions of the design (no take-up).

    %(drive_returns)s
    float
        L_p [pitches] (:func:`chaindrive.geometry.contour.tight_pitches_of`).
    """
    p = drive.chain.spec.pitch
    centres = np.array([[s.x, s.y] for s in drive.sprockets], dtype=float)
    teeth = np.array([s.teeth for s in drive.sprockets])
    inside = np.array([s.side == "inside" for s in drive.sprockets])
    radii = np.atleast_1d(np.asarray(pitch_radius(p, teeth), dtype=float))
    return tight_pitches_of(centres, radii, inside, teeth, p)


def length_options(drive: Drive, laid: GeometryResult | None = None) -> LengthChoice:
    """The link counts below and above the tight length of a design, laid out.

    Parameters
    ----------
    drive : Drive
        The design (even counts, odd too with ``chain.allow_odd``).
    laid : GeometryResult or None
        The design's own layout (:func:`~chaindrive.geometry.contour.contour_geometry` of
        ``drive``), used for its link count instead of laying that count out again.

    Returns
    -------
    LengthChoice
        Both counts laid out with the take-up and sag allowance (module docstring).

    References
    ----------
    [Shigley2015, Eq. 17-34/17-35]; [Bhandari2010, ex. 14.4]; [ChainDesignRU, §6–7].
    """
    tight = tight_pitches_as_designed(drive)
    odd = drive.chain.allow_odd
    down, up = round_links(tight, odd, down=True), round_links(tight, odd)
    options = [_option(drive, "round down", down, laid)]
    if up != down:
        options.append(_option(drive, "round up", up, laid))
    rule = drive.chain.rounding
    if rule == "nearest":  # the nearer of the two, up on a tie
        rule = "round down" if tight - down < up - tight else "round up"
    chosen = "given" if drive.chain.links is not None else rule
    return LengthChoice(tight, tuple(options), chosen, drive.chain.sag)
