"""ISO 606 tooth-form limits of a sprocket (SI units: metres, radians) [ISO606].

The minimum and maximum tooth-gap forms of the standard, confirmed by
[Bhandari2010, Example 14.5]. Several formulas carry dimensional constants in millimetres;
they are applied here with the constants converted.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import DesignError
from chaindrive.geometry.pitch import MM as _MM
from chaindrive.geometry.pitch import dict_with_units as _dict_with_units
from chaindrive.geometry.pitch import pitch_diameter
from chaindrive.geometry.pitch import positive_length as _positive
from chaindrive.geometry.pitch import teeth_array as _teeth

__all__ = ["ToothForm", "iso606_flank_radius_range", "iso606_root_diameter",
           "iso606_root_diameter_range", "iso606_seating_angle_range",
           "iso606_seating_radius_range", "iso606_side_radius", "iso606_side_relief_range",
           "iso606_tip_diameter_range", "iso606_tooth_form", "iso606_tooth_width",
           "multi_strand_width"]


@shared_parameters
def iso606_tip_diameter_range(pitch: ArrayLike, teeth: ArrayLike,
                              roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 tip diameter limits da,max = d + 1.25·p − d1, da,min = d + p·(1 − 1.6/z) − d1.

    %(pitch_teeth_roller_returns)s
    tuple of float or numpy.ndarray
        (da,min, da,max) [m].

    References
    ----------
    [ISO606]; [Bhandari2010, Example 14.5].
    """
    p, z = _positive("pitch", pitch), _teeth(teeth)
    d1 = _positive("roller_diameter", roller_diameter)
    d = p / np.sin(np.pi / z)
    return _out(d + p * (1.0 - 1.6 / z) - d1), _out(d + 1.25 * p - d1)


@shared_parameters
def iso606_root_diameter(pitch: ArrayLike, teeth: ArrayLike,
                         roller_diameter: ArrayLike) -> FloatOrArray:
    """ISO 606 root diameter df = d − d1.

    %(pitch_teeth_roller_returns)s
    float or numpy.ndarray
        df [m].

    References
    ----------
    [ISO606]; [DIN8196].
    """
    d1 = _positive("roller_diameter", roller_diameter)
    return _out(np.asarray(pitch_diameter(pitch, teeth)) - d1)


@shared_parameters
def iso606_seating_radius_range(roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 roller-seating radius limits ri,min = 0.505·d1, ri,max = 0.505·d1 + 0.069·d1^(1/3).

    The standard writes d1 and ri in mm; the constant is applied in mm here.

    %(roller_diameter_returns)s
    tuple of float or numpy.ndarray
        (ri,min, ri,max) [m].

    References
    ----------
    [ISO606].
    """
    d1_mm = _positive("roller_diameter", roller_diameter) / _MM
    return _out(0.505 * d1_mm * _MM), _out((0.505 * d1_mm + 0.069 * np.cbrt(d1_mm)) * _MM)


@shared_parameters
def iso606_root_diameter_range(pitch: ArrayLike, teeth: ArrayLike,
                               roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """Root diameter of the two tooth-gap forms, Df = d − 2·ri (the smaller with ri,max).

    The nominal ISO 606 df = d − d1 lies just above this range (ri,min = 0.505 d1 > d1/2).

    %(pitch_teeth_roller_returns)s
    tuple of float or numpy.ndarray
        (Df,min, Df,max) [m].

    References
    ----------
    [Bhandari2010, Example 14.5]; [InventorSprocket] (Df = Dp − 2 ri).
    """
    d = np.asarray(pitch_diameter(pitch, teeth))
    ri_min, ri_max = iso606_seating_radius_range(roller_diameter)
    return _out(d - 2 * np.asarray(ri_max)), _out(d - 2 * np.asarray(ri_min))


@shared_parameters
def iso606_flank_radius_range(teeth: ArrayLike,
                              roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 tooth-flank radius limits re,min = 0.12·d1·(z + 2), re,max = 0.008·d1·(z² + 180).

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].
    %(roller_diameter_array)s

    Returns
    -------
    tuple of float or numpy.ndarray
        (re,min, re,max) [m].

    References
    ----------
    [ISO606].
    """
    z, d1 = _teeth(teeth), _positive("roller_diameter", roller_diameter)
    return _out(0.12 * d1 * (z + 2)), _out(0.008 * d1 * (z**2 + 180))


@shared_parameters
def iso606_seating_angle_range(teeth: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 roller-seating angle limits α,min = 120° − 90°/z, α,max = 140° − 90°/z.

    %(teeth_returns)s
    tuple of float or numpy.ndarray
        (α,min, α,max) [rad].

    References
    ----------
    [ISO606].
    """
    z = _teeth(teeth)
    return _out(np.radians(120.0 - 90.0 / z)), _out(np.radians(140.0 - 90.0 / z))


def iso606_tooth_width(pitch: ArrayLike, inner_width: ArrayLike,
                       strands: ArrayLike = 1) -> FloatOrArray:
    """ISO 606 tooth width bf1 from the chain inner width b1.

    ======================  ==========  ============
    strands                 p ≤ 12.7 mm  p > 12.7 mm
    ======================  ==========  ============
    1 (simplex)             0.93·b1     0.95·b1
    2, 3 (duplex, triplex)  0.91·b1     0.93·b1
    4 and more              0.88·b1     0.93·b1
    ======================  ==========  ============

    [Bhandari2010, Example 14.5] uses 0.95·b1 (simplex, p > 12.7 mm). The simplex and
    duplex/triplex factors reproduce the tooth-width tables of [DIN8187] (e.g. 12B: 11.1 and
    10.8 mm; 08B: 7.2 and 7.0 mm); the quadruplex row is from [ISO606] as remembered and is
    not confirmed by a source reachable here.

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m].
    inner_width : float or array_like
        Chain inner width b1 [m].
    strands : int or array_like
        Number of strands [-].

    Returns
    -------
    float or numpy.ndarray
        bf1 [m].

    References
    ----------
    [ISO606]; [DIN8187]; [Bhandari2010, Example 14.5].
    """
    p, b1 = _positive("pitch", pitch), _positive("inner_width", inner_width)
    k = np.asarray(strands, dtype=float)
    if np.any(k < 1):
        raise DesignError("strands", f"must be 1 or more, got {strands!r}")
    small = p <= 12.7 * _MM + 1e-12
    factor = np.where(k <= 1, np.where(small, 0.93, 0.95),
                      np.where(k <= 3, np.where(small, 0.91, 0.93),
                               np.where(small, 0.88, 0.93)))
    return _out(factor * b1)


def iso606_side_relief_range(pitch: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 tooth side relief (chamfer width) ba = 0.10·p … 0.15·p.

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m].

    Returns
    -------
    tuple of float or numpy.ndarray
        (ba,min, ba,max) [m].

    References
    ----------
    [ISO606].
    """
    p = _positive("pitch", pitch)
    return _out(0.10 * p), _out(0.15 * p)


def iso606_side_radius(pitch: ArrayLike) -> FloatOrArray:
    """ISO 606 nominal tooth side radius rx = p.

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m].

    Returns
    -------
    float or numpy.ndarray
        rx [m].

    References
    ----------
    [ISO606].
    """
    return _out(_positive("pitch", pitch))


def multi_strand_width(tooth_width: ArrayLike, transverse_pitch: ArrayLike,
                       strands: ArrayLike) -> FloatOrArray:
    """Overall width of a multi-strand sprocket bf_k = pt·(k − 1) + bf1.

    Parameters
    ----------
    tooth_width : float or array_like
        Tooth width of one strand bf1 [m].
    transverse_pitch : float or array_like
        Transverse pitch pt [m].
    strands : int or array_like
        Number of strands k [-].

    Returns
    -------
    float or numpy.ndarray
        bf_k [m].

    References
    ----------
    [InventorSprocket].
    """
    k = np.asarray(strands, dtype=float)
    return _out(np.asarray(transverse_pitch, dtype=float) * (k - 1)
                + np.asarray(tooth_width, dtype=float))


@shared_parameters
@dataclass(frozen=True, slots=True)
class ToothForm:
    """ISO 606 tooth-form limits of one sprocket [ISO606].

    Each limited quantity is given as ``*_min``, ``*_max`` and ``*_mean`` (the mean is what
    [Bhandari2010, Example 14.5] reports).

    Parameters
    ----------
    %(pitch)s
    %(teeth)s
    %(roller_diameter)s
    pitch_diameter : float
        d = p/sin(π/z) [m].
    tip_diameter_min, tip_diameter_max, tip_diameter_mean : float
        Tip diameter da [m].
    root_diameter : float
        Nominal root diameter df = d − d1 [m].
    root_diameter_min, root_diameter_max, root_diameter_mean : float
        d − 2·ri of the two tooth-gap forms [m].
    seating_radius_min, seating_radius_max, seating_radius_mean : float
        Roller-seating radius ri [m].
    flank_radius_min, flank_radius_max, flank_radius_mean : float
        Tooth-flank radius re [m].
    seating_angle_min, seating_angle_max : float
        Roller-seating angle α [rad].
    tooth_width : float
        bf1 [m].
    side_relief_min, side_relief_max, side_relief_mean : float
        Side relief ba [m].
    side_radius : float
        rx [m].
    standard : str
        "ISO 606".
    """

    pitch: float
    teeth: int
    roller_diameter: float
    pitch_diameter: float
    tip_diameter_min: float
    tip_diameter_max: float
    tip_diameter_mean: float
    root_diameter: float
    root_diameter_min: float
    root_diameter_max: float
    root_diameter_mean: float
    seating_radius_min: float
    seating_radius_max: float
    seating_radius_mean: float
    flank_radius_min: float
    flank_radius_max: float
    flank_radius_mean: float
    seating_angle_min: float
    seating_angle_max: float
    tooth_width: float
    side_relief_min: float
    side_relief_max: float
    side_relief_mean: float
    side_radius: float
    standard: str = "ISO 606"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict, lengths in mm (``*_mm``), angles in degrees (``*_deg``)."""
        angles = ("seating_angle_min", "seating_angle_max")
        lengths = tuple(f.name for f in fields(self)
                        if f.name not in (*angles, "teeth", "standard"))
        return _dict_with_units(self, lengths, angles)


@shared_parameters
def iso606_tooth_form(pitch: float, teeth: int, roller_diameter: float, inner_width: float,
                      strands: int = 1) -> ToothForm:
    """All ISO 606 tooth-form limits of a sprocket (the functions above, scalar inputs).

    Parameters
    ----------
    %(pitch)s
    %(teeth)s
    %(roller_diameter)s
    inner_width : float
        Chain inner width b1 [m].
    strands : int
        Chain strands [-].

    Returns
    -------
    ToothForm
        The limits and their means.

    References
    ----------
    [ISO606]; [Bhandari2010, Example 14.5].
    """
    def pair(values: tuple[FloatOrArray, FloatOrArray]) -> tuple[float, float, float]:
        lo, hi = float(values[0]), float(values[1])
        return lo, hi, 0.5 * (lo + hi)

    da = pair(iso606_tip_diameter_range(pitch, teeth, roller_diameter))
    df = pair(iso606_root_diameter_range(pitch, teeth, roller_diameter))
    ri = pair(iso606_seating_radius_range(roller_diameter))
    re = pair(iso606_flank_radius_range(teeth, roller_diameter))
    ba = pair(iso606_side_relief_range(pitch))
    alpha = iso606_seating_angle_range(teeth)
    return ToothForm(
        pitch=float(pitch), teeth=int(teeth), roller_diameter=float(roller_diameter),
        pitch_diameter=float(pitch_diameter(pitch, teeth)),
        tip_diameter_min=da[0], tip_diameter_max=da[1], tip_diameter_mean=da[2],
        root_diameter=float(iso606_root_diameter(pitch, teeth, roller_diameter)),
        root_diameter_min=df[0], root_diameter_max=df[1], root_diameter_mean=df[2],
        seating_radius_min=ri[0], seating_radius_max=ri[1], seating_radius_mean=ri[2],
        flank_radius_min=re[0], flank_radius_max=re[1], flank_radius_mean=re[2],
        seating_angle_min=float(alpha[0]), seating_angle_max=float(alpha[1]),
        tooth_width=float(iso606_tooth_width(pitch, inner_width, strands)),
        side_relief_min=ba[0], side_relief_max=ba[1], side_relief_mean=ba[2],
        side_radius=float(iso606_side_radius(pitch)),
    )
