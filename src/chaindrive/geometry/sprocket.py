"""Sprocket diameters, tooth forms, proportions, mass and inertia (SI units: metres, radians).

The one place to import them from: the pitch circle (:mod:`.pitch`), the ISO 606 tooth-form
limits (:mod:`.iso606`), the GOST 591-69 profile (:mod:`.gost591`), the sprocket body
(:mod:`.body`), and here the tip and root diameters by the drive's tooth form.

Sources: [ISO606], [DIN8196], [GOST591], [ChainNonUniformity], [Bhandari2010, Example 14.5],
[Anuriev, vol. 2, ch. 5], [MultimassChainDrives, §3.4].
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import DesignError
from chaindrive.geometry.body import (
    PolymericProportions,
    SprocketMassProperties,
    annulus_mass_and_inertia,
    polymeric_sprocket_proportions,
    sprocket_body,
    sprocket_mass_and_inertia,
)
from chaindrive.geometry.gost591 import (
    GOST591_K_TABLE,
    GOST591_LAMBDA_MIN,
    Gost591ToothForm,
    engagement_characteristic,
    gost591_root_diameter,
    gost591_seating_radius,
    gost591_tip_diameter,
    gost591_tooth_form,
    gost591_tooth_height_coefficient,
)
from chaindrive.geometry.iso606 import (
    ToothForm,
    iso606_flank_radius_range,
    iso606_root_diameter,
    iso606_root_diameter_range,
    iso606_seating_angle_range,
    iso606_seating_radius_range,
    iso606_side_radius,
    iso606_side_relief_range,
    iso606_tip_diameter_range,
    iso606_tooth_form,
    iso606_tooth_width,
    multi_strand_width,
)
from chaindrive.geometry.pitch import (
    approximate_pitch_diameter,
    pitch_diameter,
    pitch_radius,
    teeth_array,
)

__all__ = [
    "GOST591_K_TABLE", "GOST591_LAMBDA_MIN", "TOOTH_FORM_NAMES", "Gost591ToothForm",
    "PolymericProportions", "SprocketMassProperties", "ToothForm", "annulus_mass_and_inertia",
    "approximate_pitch_diameter", "engagement_characteristic", "gost591_root_diameter",
    "gost591_seating_radius", "gost591_tip_diameter", "gost591_tooth_form",
    "gost591_tooth_height_coefficient", "iso606_flank_radius_range", "iso606_root_diameter",
    "iso606_root_diameter_range", "iso606_seating_angle_range", "iso606_seating_radius_range",
    "iso606_side_radius", "iso606_side_relief_range", "iso606_tip_diameter_range",
    "iso606_tooth_form", "iso606_tooth_width", "multi_strand_width", "pitch_diameter",
    "pitch_radius", "polymeric_sprocket_proportions", "root_diameter", "seating_geometry",
    "sprocket_body", "sprocket_mass_and_inertia", "teeth_array", "tip_diameter",
]

TOOTH_FORM_NAMES: tuple[str, ...] = ("ISO 606", "GOST 591")



def _check_form(form: str) -> None:
    if form not in TOOTH_FORM_NAMES:
        raise DesignError("tooth_form", f"must be one of {', '.join(TOOTH_FORM_NAMES)}, "
                          f"got {form!r}")


def _iso606_mean_tip_diameter(pitch: ArrayLike, teeth: ArrayLike,
                              roller_diameter: ArrayLike) -> FloatOrArray:
    """ISO 606 tip diameter: the mean (da,min + da,max)/2 of its limits [m]."""
    lo, hi = iso606_tip_diameter_range(pitch, teeth, roller_diameter)
    return _out(0.5 * (np.asarray(lo) + np.asarray(hi)))


#: a diameter of the tooth form [m] of (pitch, teeth, roller_diameter), by the form's name
_DiameterFormula = Callable[[ArrayLike, ArrayLike, ArrayLike], FloatOrArray]
_TIP_DIAMETER: dict[str, _DiameterFormula] = {"ISO 606": _iso606_mean_tip_diameter,
                                              "GOST 591": gost591_tip_diameter}
_ROOT_DIAMETER: dict[str, _DiameterFormula] = {"ISO 606": iso606_root_diameter,
                                               "GOST 591": gost591_root_diameter}


def _of_form(form: str, formulas: dict[str, _DiameterFormula]) -> _DiameterFormula:
    """The formula of ``formulas`` for the tooth form ``form`` (checked first)."""
    _check_form(form)
    return formulas[form]


@shared_parameters
def tip_diameter(pitch: ArrayLike, teeth: ArrayLike, roller_diameter: ArrayLike,
                 form: Literal["ISO 606", "GOST 591"] = "ISO 606") -> FloatOrArray:
    """Tip (outside) diameter by the chosen tooth form.

    ISO 606: the mean of the two limits, (da,min + da,max)/2 — the value
    [Bhandari2010, Example 14.5] reports; any value in the range is standard. GOST 591:
    De = t·(K + ctg(180°/z)).

    %(tooth_form_diameter_returns)s
        Tip diameter [m].

    References
    ----------
    [ISO606]; [GOST591].
    """
    return _of_form(form, _TIP_DIAMETER)(pitch, teeth, roller_diameter)


@shared_parameters
def root_diameter(pitch: ArrayLike, teeth: ArrayLike, roller_diameter: ArrayLike,
                  form: Literal["ISO 606", "GOST 591"] = "ISO 606") -> FloatOrArray:
    """Root diameter by the chosen tooth form: ISO 606 df = d − d1 (nominal); GOST 591
    Di = dд − 2r.

    %(tooth_form_diameter_returns)s
        Root diameter [m].

    References
    ----------
    [ISO606]; [GOST591].
    """
    return _of_form(form, _ROOT_DIAMETER)(pitch, teeth, roller_diameter)


@shared_parameters
def seating_geometry(form: str, pitch: float, teeth: ArrayLike, roller_diameter: float,
                     inner_width: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Seating radius r_i [m] and seating half-angle α [rad] of every sprocket.

    ISO 606: the means of the limits, r_i = (r_i,min + r_i,max)/2 and α = (α_min + α_max)/4
    (the standard gives the full seating angle); GOST 591-69: r = 0.5025·d₁ + 0.05 mm and
    α = 55° − 60°/z (its half-space angle).

    Parameters
    ----------
    form : str
        ``"ISO 606"`` or ``"GOST 591"``.
    %(pitch)s
    teeth : array_like
        (n,) teeth z [-].
    roller_diameter : float
        Roller diameter d₁ [m].
    inner_width : float
        Inner width b₁ of the chain [m].

    Returns
    -------
    seating_radii : ndarray
        (n,) r_i [m].
    half_angles : ndarray
        (n,) α [rad].

    References
    ----------
    [ISO606], [GOST591].
    """
    z = np.atleast_1d(np.asarray(teeth, dtype=int))
    if form == "GOST 591":
        r = np.full(z.size, float(gost591_seating_radius(roller_diameter)))
        alpha = np.array([gost591_tooth_form(pitch, int(k), roller_diameter, inner_width)
                          .half_space_angle for k in z])
        return r, alpha
    lo, hi = iso606_seating_radius_range(roller_diameter)
    a_lo, a_hi = iso606_seating_angle_range(z)
    r = np.full(z.size, 0.5 * (float(lo) + float(hi)))
    return r, 0.25 * (np.asarray(a_lo, float) + np.asarray(a_hi, float))
