"""Wear life of a roller chain: hours until it has stretched by the permitted elongation.

Model (ACA / Diamond Chain load–life relation, Shigley §17-5, Eq. 17-40): the ACA ratings
are for 15 000 h to 3 % elongation with a 100-pitch chain; at another load the life follows
H^2.5·h/L_p = const (exponent 2.5 identified by the Diamond Chain Co.), i.e.

    h = 15 000 · (H_rated/H_design)^2.5 · (L_p/100) · (Δ/3 %)

The last factor assumes the elongation grows linearly in time (steady wear after running-in,
wear ∝ sliding distance at constant pressure — Archard) so that a permitted elongation Δ
other than 3 % scales the life in proportion. Shigley notes that in the pre-extreme
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

BASIS_LIFE_H = 15000.0
BASIS_LINKS = 100.0
BASIS_ELONGATION = 0.03
LOAD_LIFE_EXPONENT = 2.5
#: Lives above this are flagged as an extrapolation of the load–life relation [h].
EXTRAPOLATION_LIMIT_H = 10.0 * BASIS_LIFE_H


def is_extrapolated(life_h: float) -> bool:
    """True when a wear life lies beyond :data:`EXTRAPOLATION_LIMIT_H`."""
    return life_h > EXTRAPOLATION_LIMIT_H


def wear_life_hours(rated_power: float | np.ndarray, design_power: float | np.ndarray,
                    links: float = BASIS_LINKS, elongation: float = BASIS_ELONGATION
                    ) -> float | np.ndarray:
    """Hours to the permitted elongation (default 3 %).

    rated_power [W]: rating of the whole chain at the operating speed and teeth (ACA, rating
    basis 15 000 h); design_power [W]: transmitted power × service factor; links L_p;
    elongation Δ permitted (fraction). Source: Shigley Eq. 17-40 (see module docstring).
    """
    ratio = np.asarray(rated_power, dtype=float) / np.asarray(design_power, dtype=float)
    life = (BASIS_LIFE_H * ratio**LOAD_LIFE_EXPONENT * (links / BASIS_LINKS)
            * (elongation / BASIS_ELONGATION))
    return float(life) if np.ndim(life) == 0 else life
