"""Immutable results of the contour geometry (SI units: metres, radians)."""

from __future__ import annotations

from dataclasses import dataclass

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveWarning


@shared_parameters
@dataclass(frozen=True, slots=True)
class SprocketGeometry:
    """One sprocket of the built contour.

    Parameters
    ----------
    name : str
        The sprocket.
    %(teeth)s
    side : str
        "outside" or "inside" of the contour.
    x, y : float
        Centre after the take-up [m] (x horizontal, y up).
    pitch_radius : float
        R = p / (2 sin(π/z)) [m].
    pitch_diameter : float
        2R [m].
    tip_diameter, root_diameter : float
        By the drive's tooth form [m].
    wrap_angle : float
        θ [rad].
    teeth_in_mesh : float
        z·θ/(2π) [-].
    turn : int
        +1 if the sprocket turns counter-clockwise, −1 clockwise.
    arrive, leave : tuple of float
        Where the chain arrives on / leaves the pitch circle (x, y) [m].
    """

    name: str
    teeth: int
    side: str
    x: float
    y: float
    pitch_radius: float
    pitch_diameter: float
    tip_diameter: float
    root_diameter: float
    wrap_angle: float
    teeth_in_mesh: float
    turn: int
    arrive: tuple[float, float]
    leave: tuple[float, float]


@dataclass(frozen=True, slots=True)
class SpanGeometry:
    """A span (branch) from one sprocket to the next (the last closes the ring).

    Parameters
    ----------
    index : int
        The span's index k.
    start, end : int
        Indices of the sprockets it runs from and to (end = start + 1, cyclic).
    start_name, end_name : str
        Their names.
    length : float
        Between the tangent points of the pitch circles [m].
    pitches : float
        length / p [pitches].
    direction : tuple of float
        Unit vector of chain travel [-].
    start_point, end_point : tuple of float
        The tangent points (x, y) [m].
    inclination : float
        Of the span to the x axis, in [−π/2, π/2] [rad] (x horizontal, y up).
    tight : bool
        True for the span that runs into the driver.
    """

    index: int
    start: int
    end: int
    start_name: str
    end_name: str
    length: float
    pitches: float
    direction: tuple[float, float]
    start_point: tuple[float, float]
    end_point: tuple[float, float]
    inclination: float
    tight: bool


@shared_parameters
@dataclass(frozen=True, slots=True)
class GeometryResult:
    """The contour: sprockets, spans, length and links.

    Parameters
    ----------
    %(pitch)s
    sprockets : tuple of SprocketGeometry
        In contour order.
    spans : tuple of SpanGeometry
        Span k from sprocket k to k+1.
    tight_pitches : float
        Length of the tight chain Σ ℓ/p + Σ z·θ/2π of the final layout [pitches].
    links : int
        Number of links [-].
    chain_length : float
        links·p [m].
    tight_length : float
        tight_pitches·p [m].
    slack : float
        chain_length − tight_length [m] (0 after a take-up).
    center_distance : float or None
        For two-sprocket drives [m].
    adjusted : int or None
        Index of the sprocket moved by the take-up (None if none).
    adjustment : float
        How far it moved [m] (positive: away from the contour).
    orientation : int
        +1 when the chain runs counter-clockwise round the contour, −1 clockwise.
    warnings : tuple of ChainDriveWarning
        Driver wrap, teeth in mesh, untaken slack.
    sag_allowance : float
        How much the installed centre distance of the adjustable sprocket was shortened
        from the tight position by the design's sag allowance, Δa [m] (0: none).
    """

    pitch: float
    sprockets: tuple[SprocketGeometry, ...]
    spans: tuple[SpanGeometry, ...]
    tight_pitches: float
    links: int
    chain_length: float
    tight_length: float
    slack: float
    center_distance: float | None
    adjusted: int | None
    adjustment: float
    orientation: int
    warnings: tuple[ChainDriveWarning, ...] = ()
    sag_allowance: float = 0.0
