"""The pitch circle of a sprocket and the checks of its inputs (SI units: metres).

Pure, vectorised functions at the bottom of the geometry layer: pitch diameter
d = p / sin(π/z) [ISO606], [DIN8196], [GOST591], [ChainNonUniformity], and the approximate
diameter t·z/π of [MultimassChainDrives, §3.4].
"""

from __future__ import annotations

import math
from dataclasses import asdict
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import DesignError, positive

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

__all__ = ["MM", "approximate_pitch_diameter", "dict_with_units", "pitch_diameter",
           "pitch_radius", "positive_length", "teeth_array"]

MM = 1e-3  # one millimetre [m]


def teeth_array(teeth: ArrayLike) -> NDArray[np.float64]:
    """Tooth counts as floats, refusing anything below 3 or not finite.

    Parameters
    ----------
    teeth : array_like
        Numbers of teeth z [-].

    Returns
    -------
    numpy.ndarray
        z as float64 [-].

    Raises
    ------
    DesignError
        On the field ``teeth`` when a count is below 3 or not finite.
    """
    z = np.asarray(teeth, dtype=float)
    if np.any(~np.isfinite(z)) or np.any(z < 3):
        raise DesignError("teeth", f"must be a whole number of at least 3, got {teeth!r}")
    return z


_teeth = teeth_array


def positive_length(name: str, value: ArrayLike) -> NDArray[np.float64]:
    """Lengths [m] as float64, refusing any not finite or not above zero
    (:func:`chaindrive.errors.positive`, named as a length).

    Parameters
    ----------
    name : str
        The field an error names.
    value : float or array_like
        The lengths [m].

    Returns
    -------
    numpy.ndarray
        The lengths as float64 [m].
    """
    return positive(name, value, "length")


_positive = positive_length


def dict_with_units(obj: DataclassInstance, lengths: tuple[str, ...],
                    angles: tuple[str, ...]) -> dict[str, Any]:
    """The ``to_dict`` of a dataclass of dimensions: lengths in mm, angles in degrees.

    Parameters
    ----------
    obj : dataclass instance
        The dimensions (SI).
    lengths : tuple of str
        Fields that are lengths [m], written as ``<name>_mm``.
    angles : tuple of str
        Fields that are angles [rad], written as ``<name>_deg``.

    Returns
    -------
    dict
        JSON-ready dictionary; other fields as they are.
    """
    out: dict[str, Any] = {}
    for key, value in asdict(obj).items():
        if key in lengths:
            out[f"{key}_mm"] = float(value) / MM
        elif key in angles:
            out[f"{key}_deg"] = math.degrees(float(value))
        else:
            out[key] = value.item() if isinstance(value, np.generic) else value
    return out


# ---------------------------------------------------------------------------------------
# Pitch circle
# ---------------------------------------------------------------------------------------

@shared_parameters
def pitch_diameter(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Pitch diameter d = p / sin(π/z).

    %(pitch_teeth_returns)s
    float or numpy.ndarray
        d [m].

    References
    ----------
    [ISO606]; dд of [GOST591]; [ChainNonUniformity].
    """
    return _out(_positive("pitch", pitch) / np.sin(np.pi / _teeth(teeth)))


@shared_parameters
def pitch_radius(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Pitch radius R = p / (2 sin(π/z)): radius of the hinge centres.

    %(pitch_teeth_returns)s
    float or numpy.ndarray
        R [m].

    References
    ----------
    R of [ChainNonUniformity]; [ISO606].
    """
    return _out(0.5 * np.asarray(pitch_diameter(pitch, teeth)))


def approximate_pitch_diameter(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Approximate pitch diameter t·z/π of [MultimassChainDrives, §3.4] and its worked example.

    It is the diameter of a circle whose circumference is z pitches; it is smaller than the
    true pitch diameter p/sin(π/z) (121.3 vs 122.2 mm for z = 15, t = 25.4 mm, the worked
    example of [MultimassChainDrives]).

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch t [m].
    teeth : int or array_like
        Number of teeth z [-].

    Returns
    -------
    float or numpy.ndarray
        t·z/π [m].

    References
    ----------
    [MultimassChainDrives, §3.4].
    """
    return _out(_positive("pitch", pitch) * _teeth(teeth) / np.pi)
