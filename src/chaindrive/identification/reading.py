"""A span's tension read from its measured frequency, set beside the design's (the drive
level of :mod:`chaindrive.identification.tension`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from chaindrive.errors import DesignError
from chaindrive.identification.tension import (
    TensionEstimate,
    expected_frequency,
    span_tension_from_frequency,
)
from chaindrive.strength.loads import installed_sag_ratio, sag_tension

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis

__all__ = ["SpanTensionReading", "rectangular_std", "span_index", "span_tension_reading"]


def rectangular_std(half_width: float) -> float:
    """Standard uncertainty a/√3 [same unit] of a quantity known to lie within ±a
    (rectangular distribution, [JCGM100, §4.3.7]).

    Parameters
    ----------
    half_width : float
        a [any unit], ≥ 0.

    Returns
    -------
    float
        u = a / √3.
    """
    return half_width / math.sqrt(3.0)


def span_index(analysis: Analysis, span: str) -> int:
    """Index of the span named ``FROM-TO`` (sprocket names) in the analysed contour.

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    span : str
        ``"S1-S2"``.

    Returns
    -------
    int

    Raises
    ------
    DesignError
        No span of that name (the message lists the spans).
    """
    names = [f"{s.start_name}-{s.end_name}" for s in analysis.geometry.spans]
    if span not in names:
        raise DesignError("--span", f"unknown span {span!r}; allowed: {', '.join(names)}")
    return names.index(span)


@dataclass(frozen=True, slots=True)
class SpanTensionReading:
    """A span's tension from its measured frequency, with what the design expects.

    Parameters
    ----------
    span : str
        ``FROM-TO``.
    estimate : TensionEstimate
        The tension read from the frequency.
    pretension : float
        The design's static (sag) pretension F_0 of the span [N] at its installed sag.
    expected_standing : float
        The frequency [Hz] of mode n of the stationary span at F_0.
    running_tension : float | None
        The design's span tension in operation [N] (None: the design gives no power).
    expected_running : float | None
        The frequency [Hz] of mode n of the running span at that tension.
    assumed : tuple of str
        The inputs that rest on an assumed value (named, with the value).
    """

    span: str
    estimate: TensionEstimate
    pretension: float
    expected_standing: float
    running_tension: float | None
    expected_running: float | None
    assumed: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return {
            "span": self.span,
            **self.estimate.to_dict(),
            "design_pretension_n": self.pretension,
            "expected_frequency_standing_hz": self.expected_standing,
            "design_running_tension_n": self.running_tension,
            "expected_frequency_running_hz": self.expected_running,
            "assumed": list(self.assumed),
        }


def span_tension_reading(analysis: Analysis, span: str, frequency: float, *, mode: int = 1,
                         running: bool = False, frequency_tolerance: float = 0.0,
                         length_tolerance: float = 0.002, mass_tolerance: float = 0.05,
                         assumed: tuple[str, ...] = ()) -> SpanTensionReading:
    """The tension of one span of a design from its measured transverse frequency.

    The span's length, inclination and the chain's q and EA = k_link·p come from the
    analysis; a running chain moves at the mean chain speed v̄. Tolerances are half-widths
    of rectangular distributions (:func:`rectangular_std`). The expected frequencies are the
    string law at the design's pretension F_0 ([ChainDesignRU, §8], stationary) and at its
    span tension in operation (running).

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    span : str
        ``FROM-TO``.
    frequency : float
        Measured f [Hz].
    mode : int
        n [-].
    running : bool
        The chain was running at the design speed when measured.
    frequency_tolerance : float
        ±[Hz] of the measured frequency.
    length_tolerance : float
        ±[m] of the span length.
    mass_tolerance : float
        ± relative [-] of the mass per metre.
    assumed : tuple of str
        Which of the tolerances were not given (named in the result).

    Returns
    -------
    SpanTensionReading

    Raises
    ------
    DesignError
        Unknown span, an input out of range, or ``running`` for a design without speed.

    References
    ----------
    [Mote1965], [WickertMote1990], [JCGM100, §4.3.7, §5.1], [ChainDesignRU, §8].
    """
    i = span_index(analysis, span)
    for name, value in (("--frequency-tolerance", frequency_tolerance),
                        ("--length-tolerance", length_tolerance),
                        ("--mass-tolerance", mass_tolerance)):
        if not (math.isfinite(value) and value >= 0):
            raise DesignError(name, f"must be ≥ 0, got {value!r}")
    drive = analysis.drive
    spec = drive.chain.spec
    sp = analysis.geometry.spans[i]
    ring = analysis.ring_parameters
    speed = 0.0
    if running:
        if drive.driver.speed is None:
            raise DesignError("--running", "the design gives no driver speed")
        speed = float(analysis.kinematics.chain_speed)
    q = spec.mass_per_length
    estimate = span_tension_from_frequency(
        frequency, sp.length, q, mode=mode, speed=speed,
        frequency_std=rectangular_std(frequency_tolerance),
        length_std=rectangular_std(length_tolerance),
        mass_std=rectangular_std(mass_tolerance * q),
        axial_stiffness=ring.link_stiffness_n_per_m * spec.pitch,
        inclination=sp.inclination)
    f0 = sag_tension(q, sp.length, sp.inclination, installed_sag_ratio(drive))
    tensions = ring.span_tensions_n
    running_t = None if tensions is None else float(tensions[i])
    running_f = None
    if running_t is not None and drive.driver.speed is not None:
        running_f = expected_frequency(running_t, sp.length, q, mode,
                                       float(analysis.kinematics.chain_speed))
    return SpanTensionReading(span, estimate, f0, expected_frequency(f0, sp.length, q, mode),
                              running_t, running_f, assumed)
