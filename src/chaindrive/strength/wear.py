"""Wear life of a roller chain: hours until it has stretched by the permitted elongation.

Model (ACA / Diamond Chain load–life relation, [Shigley2015, Eq. 17-40]): the ACA ratings
are for 15 000 h to 3 % elongation with a 100-pitch chain; at another load the life follows
H^2.5·h/L_p = const (exponent 2.5 identified by the Diamond Chain Co.), i.e.

    h = 15 000 · (H_rated/H_design)^2.5 · (L_p/100) · (Δ/3 %)

The last factor assumes the elongation grows linearly in time (steady wear after running-in,
wear ∝ sliding distance at constant pressure [Archard1953]) so that a permitted elongation Δ
other than 3 % scales the life in proportion. [Shigley2015] notes that in the pre-extreme
(link-plate) region durability estimates other than 15 000 h are not really available; the
same relation is used there as an estimate (flagged in the result).

The relation is identified on ratings and tests near the 15 000 h basis. Far below the
rating it extrapolates without bound (h ∝ (H_rated/H_design)^2.5: a drive at a tenth of its
rating gets 4.7 million hours). Lives beyond :data:`EXTRAPOLATION_LIMIT_H` (ten times the
basis, the design load below 40 % of the rating) are therefore flagged as an
extrapolation: they say that wear does not limit the drive, not how long it lasts. The
factor ten is this package's choice, not a published limit.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._numeric import FloatOrArray, float_or_array

__all__ = ["BASIS_ELONGATION", "BASIS_LIFE_H", "BASIS_LINKS", "EXTRAPOLATION_LIMIT_H",
           "LOAD_LIFE_EXPONENT", "is_extrapolated", "wear_life_hours"]

#: Life of the rating basis [h] [Shigley2015, §17-5].
BASIS_LIFE_H = 15000.0
BASIS_LINKS = 100.0
BASIS_ELONGATION = 0.03
LOAD_LIFE_EXPONENT = 2.5
#: Lives above this are flagged as an extrapolation of the load–life relation [h].
EXTRAPOLATION_LIMIT_H = 10.0 * BASIS_LIFE_H


def is_extrapolated(life_h: float) -> bool:
    """Whether a wear life is an extrapolation of the load–life relation.

    Parameters
    ----------
    life_h : float
        Wear life [h].

    Returns
    -------
    bool
        True beyond :data:`EXTRAPOLATION_LIMIT_H`.
    """
    return life_h > EXTRAPOLATION_LIMIT_H


def wear_life_hours(rated_power: ArrayLike, design_power: ArrayLike,
                    links: float = BASIS_LINKS, elongation: float = BASIS_ELONGATION
                    ) -> FloatOrArray:
    """Hours to the permitted elongation h = 15 000·(H_rated/H_design)^2.5·(L_p/100)·(Δ/3 %).

    Parameters
    ----------
    rated_power : float or array_like
        Rating of the whole chain at the operating speed and teeth [W] (ACA, basis 15 000 h).
    design_power : float or array_like
        Transmitted power × service factor [W].
    links : float
        Chain length L_p [pitches].
    elongation : float
        Permitted elongation Δ [-] (fraction).

    Returns
    -------
    float or numpy.ndarray
        Wear life [h].

    References
    ----------
    [Shigley2015, Eq. 17-40]; [Archard1953] (the scaling in Δ).
    """
    ratio = np.asarray(rated_power, dtype=float) / np.asarray(design_power, dtype=float)
    life = (BASIS_LIFE_H * ratio**LOAD_LIFE_EXPONENT * (links / BASIS_LINKS)
            * (elongation / BASIS_ELONGATION))
    return float_or_array(life)
