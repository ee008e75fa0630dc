"""GOST 591-69 tooth profile of a sprocket (SI units: metres, radians).

[GOST591] as given by [Anuriev, vol. 2, ch. 5]. Several formulas of the standard carry
dimensional constants in millimetres (e.g. r = 0.5025·d1 + 0.05 mm); they are applied here
with the constants converted to metres.
"""

from __future__ import annotations

import math
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

__all__ = ["GOST591_K_TABLE", "GOST591_LAMBDA_MIN", "Gost591ToothForm",
           "engagement_characteristic", "gost591_root_diameter", "gost591_seating_radius",
           "gost591_tip_diameter", "gost591_tooth_form", "gost591_tooth_height_coefficient"]


#: GOST 591-69 table of the tooth-height coefficient K: (λ upper bound, K), the interval
#: being "over the previous bound up to this one" (св. 1,40 до 1,50 → 1.40 < λ ≤ 1.50).
GOST591_K_TABLE: tuple[tuple[float, float], ...] = (
    (1.50, 0.480), (1.60, 0.532), (1.70, 0.555), (1.80, 0.575), (2.00, 0.565))
GOST591_LAMBDA_MIN = 1.40


@shared_parameters
def engagement_characteristic(pitch: ArrayLike, roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 engagement characteristic λ = t/d1.

    Parameters
    ----------
    %(pitch_t_array)s
    %(roller_diameter_array)s

    Returns
    -------
    float or numpy.ndarray
        λ [-].

    References
    ----------
    [GOST591].
    """
    return _out(_positive("pitch", pitch) / _positive("roller_diameter", roller_diameter))


def gost591_tooth_height_coefficient(lam: ArrayLike) -> FloatOrArray:
    """GOST 591-69 tooth-height coefficient K(λ) from its table (:data:`GOST591_K_TABLE`).

    Parameters
    ----------
    lam : float or array_like
        Engagement characteristic λ = t/d1 [-].

    Returns
    -------
    float or numpy.ndarray
        K [-].

    Raises
    ------
    DesignError
        On ``roller_diameter`` for λ outside 1.40 < λ ≤ 2.00 (the scope of GOST 591-69 is
        λ ≤ 2; the table starts above 1.40).

    References
    ----------
    [GOST591]; [Anuriev, vol. 2, ch. 5].
    """
    lam_arr = np.asarray(lam, dtype=float)
    if np.any(lam_arr > 2.0 + 1e-12) or np.any(lam_arr <= GOST591_LAMBDA_MIN):
        raise DesignError("roller_diameter", "GOST 591-69 needs 1.40 < λ = t/d1 ≤ 2, got "
                          f"λ = {np.round(lam_arr, 4).tolist()}")
    bounds = np.array([b for b, _ in GOST591_K_TABLE])
    values = np.array([k for _, k in GOST591_K_TABLE])
    index = np.searchsorted(bounds, lam_arr - 1e-12, side="left")
    return _out(values[np.minimum(index, len(values) - 1)])


@shared_parameters
def gost591_tip_diameter(pitch: ArrayLike, teeth: ArrayLike,
                         roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 tip diameter De = t·(K + ctg(180°/z)) (not rounded; the standard gives De
    to 0.1 mm).

    %(pitch_t_teeth_roller_returns)s
        De [m].

    References
    ----------
    [GOST591]; [Anuriev, vol. 2, ch. 5].
    """
    p, z = _positive("pitch", pitch), _teeth(teeth)
    K = np.asarray(gost591_tooth_height_coefficient(engagement_characteristic(p, roller_diameter)))
    return _out(p * (K + 1.0 / np.tan(np.pi / z)))


@shared_parameters
def gost591_seating_radius(roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 root (seating) radius r = 0.5025·d1 + 0.05 mm.

    %(roller_diameter_returns)s
    float or numpy.ndarray
        r [m].

    References
    ----------
    [GOST591]; [Anuriev, vol. 2, ch. 5].
    """
    return _out(0.5025 * _positive("roller_diameter", roller_diameter) + 0.05 * _MM)


@shared_parameters
def gost591_root_diameter(pitch: ArrayLike, teeth: ArrayLike,
                          roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 root diameter Di = dд − 2r.

    %(pitch_t_teeth_roller_returns)s
        Di [m].

    References
    ----------
    [GOST591].
    """
    d = np.asarray(pitch_diameter(pitch, teeth))
    return _out(d - 2 * np.asarray(gost591_seating_radius(roller_diameter)))


@shared_parameters
@dataclass(frozen=True, slots=True)
class Gost591ToothForm:
    """GOST 591-69 tooth profile of one sprocket [GOST591], [Anuriev, vol. 2, ch. 5].

    Parameters
    ----------
    %(pitch_t_teeth)s
    %(roller_diameter)s
    lam : float
        λ = t/d1 [-].
    K : float
        Tooth-height coefficient [-].
    pitch_diameter : float
        dд [m].
    tip_diameter : float
        De [m].
    root_diameter : float
        Di [m].
    seating_radius, joining_radius, head_radius : float
        r, r1, r2 [m].
    half_space_angle, joining_angle, half_tooth_angle : float
        α, β, φ [rad].
    straight_part : float
        FC [m].
    head_centre_distance : float
        OO2 [m].
    centre_offset : float
        e = 0.03 t [m].
    rim_width : float
        b = 0.93·Bвн − 0.15 mm (single row) [m].
    side_radius : float
        r3 = 1.7 d1 [m].
    side_radius_height : float
        h3 = 0.8 d1 [m].
    measuring_chord : float
        Lx = dд cos(90°/z) − 2r for odd z; for even z the chord across opposite roots, Di
        [m].
    standard : str
        "GOST 591-69".
    """

    pitch: float
    teeth: int
    roller_diameter: float
    lam: float
    K: float
    pitch_diameter: float
    tip_diameter: float
    root_diameter: float
    seating_radius: float
    joining_radius: float
    head_radius: float
    half_space_angle: float
    joining_angle: float
    half_tooth_angle: float
    straight_part: float
    head_centre_distance: float
    centre_offset: float
    rim_width: float
    side_radius: float
    side_radius_height: float
    measuring_chord: float
    standard: str = "GOST 591-69"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict, lengths in mm (``*_mm``), angles in degrees (``*_deg``)."""
        angles = ("half_space_angle", "joining_angle", "half_tooth_angle")
        lengths = tuple(f.name for f in fields(self)
                        if f.name not in (*angles, "teeth", "lam", "K", "standard"))
        return _dict_with_units(self, lengths, angles)


@shared_parameters
def gost591_tooth_form(pitch: float, teeth: int, roller_diameter: float,
                       inner_width: float) -> Gost591ToothForm:
    """GOST 591-69 tooth profile of a sprocket.

    Parameters
    ----------
    %(pitch_t_teeth)s
    %(roller_diameter)s
    inner_width : float
        Chain inner width Bвн [m] (single-row rim width only: multi-row is not confirmed).

    Returns
    -------
    Gost591ToothForm
        Every dimension of the profile.

    Raises
    ------
    DesignError
        On ``roller_diameter`` when λ = t/d1 is outside 1.40 < λ ≤ 2.

    References
    ----------
    [GOST591] as given by [Anuriev, vol. 2, ch. 5].
    """
    t, d1, z = float(pitch), float(roller_diameter), int(teeth)
    lam = float(engagement_characteristic(t, d1))
    K = float(gost591_tooth_height_coefficient(lam))
    d = float(pitch_diameter(t, z))
    r = float(gost591_seating_radius(d1))
    alpha = math.radians(55.0 - 60.0 / z)
    beta = math.radians(18.0 - 56.0 / z)
    phi = math.radians(17.0 - 64.0 / z)
    b_in = float(_positive("inner_width", inner_width))
    chord = d * math.cos(math.pi / (2 * z)) - 2 * r if z % 2 else d - 2 * r
    return Gost591ToothForm(
        pitch=t, teeth=z, roller_diameter=d1, lam=lam, K=K, pitch_diameter=d,
        tip_diameter=float(gost591_tip_diameter(t, z, d1)), root_diameter=d - 2 * r,
        seating_radius=r, joining_radius=0.8 * d1 + r,
        head_radius=d1 * (1.24 * math.cos(phi) + 0.8 * math.cos(beta) - 1.3025) - 0.05 * _MM,
        half_space_angle=alpha, joining_angle=beta, half_tooth_angle=phi,
        straight_part=d1 * (1.24 * math.sin(phi) - 0.8 * math.sin(beta)),
        head_centre_distance=1.24 * d1, centre_offset=0.03 * t,
        rim_width=0.93 * b_in - 0.15 * _MM, side_radius=1.7 * d1,
        side_radius_height=0.8 * d1, measuring_chord=chord,
    )
