"""Immutable results of the contour geometry (SI units: metres, radians)."""

from __future__ import annotations

from dataclasses import dataclass

from chaindrive.errors import ChainDriveWarning


@dataclass(frozen=True, slots=True)
class SprocketGeometry:
    """One sprocket of the built contour.

    x, y [m]: centre after the take-up; pitch_radius R = p / (2 sin(π/z)) [m];
    tip_diameter / root_diameter [m] by the drive's tooth form; wrap_angle θ [rad];
    teeth_in_mesh = z·θ/(2π); turn = +1 if the sprocket turns counter-clockwise (y up),
    −1 clockwise; arrive/leave: the points where the chain arrives on / leaves the
    pitch circle [m].
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
    """Span (branch) ``index`` from sprocket ``start`` to sprocket ``start+1`` (the last
    closes the ring). length [m] between the tangent points of the pitch circles;
    pitches = length / p; direction: unit vector of chain travel; inclination [rad] of
    the span to the x axis in [−π/2, π/2] (x horizontal, y up); tight: True for the
    span that runs into the driver."""

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


@dataclass(frozen=True, slots=True)
class GeometryResult:
    """The contour: sprockets, spans, length and links.

    tight_pitches: length of the tight chain in pitches (Σ span/p + Σ z·θ/2π) for the
    final layout; links: number of links; chain_length = links·p [m];
    tight_length = tight_pitches·p [m]; slack = chain_length − tight_length [m] (0 after
    a take-up); center_distance [m] for two-sprocket drives; adjusted: index of the
    sprocket moved by the take-up (None if none); adjustment [m] how far it moved
    (positive: away from the contour); orientation +1 when the chain runs
    counter-clockwise round the contour.
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
