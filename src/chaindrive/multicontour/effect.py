"""Where keyed-joint clearances matter: K_m over pitch × teeth [Lyashuk, conclusion 3].

The paper concludes that for pitches below 50.8 mm and fewer than 40 teeth the accuracy of the
keyed joints hardly changes the capacity of multi-contour drives. :func:`effect_map` checks
it with standard parts: ISO 606 A-series chains, a shaft sized for the torque of the
contours, the DIN 6885-1 / ISO 773 / GOST 23360 key for that shaft, the key/keyway clearance
of an ISO 286 fit, and K_m at a risk level (eq. 16–18), with the paper's formula and with the
compatibility-of-deformations one side by side. The assumptions are parameters.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import pitch_radius
from chaindrive.multicontour.capacity import contour_factor_km
from chaindrive.multicontour.clearance import (
    check_positive,
    half_normal_quantile,
    length_difference_stats,
)
from chaindrive.multicontour.joints import (
    PARALLEL_KEYS_MM,
    KeyedJoint,
    clearance_coefficient_c4,
)

#: ISO 606 A-series simplex chains: pitch [mm] → minimum tensile strength Q [kN]
#: ([ISO606] (1994) Table 1 as reproduced in [GOST13568, Annex A]).
ISO606_A_TENSILE_KN: dict[float, float] = {
    12.7: 13.8, 15.875: 21.8, 19.05: 31.1, 25.4: 55.6, 31.75: 86.7, 38.1: 124.6,
    44.45: 169.0, 50.8: 222.4, 63.5: 347.0, 76.2: 500.4,
}
#: Q ≈ 86.2 N/mm²·p² reproduces every row of the table above within 1 % (used off-table).
TENSILE_PER_PITCH_SQUARED = 86.2e6  # [N/m²]
DEFAULT_TEETH: tuple[int, ...] = (11, 15, 19, 25, 31, 39, 45, 57, 75, 95)
#: The region of [Lyashuk, conclusion 3]: pitch below 50.8 mm and fewer than 40 teeth.
CONCLUSION_PITCH_LIMIT = 50.8e-3  # [m]
CONCLUSION_TEETH_LIMIT = 40
#: Pitches of :data:`ISO606_A_TENSILE_KN` [m].
DEFAULT_PITCHES: tuple[float, ...] = tuple(p * 1e-3 for p in ISO606_A_TENSILE_KN)


@shared_parameters
def chain_tensile_strength(pitch: float) -> float:
    """Minimum tensile strength of an ISO 606 A-series simplex chain.

    %(pitch_p_returns)s
    float
        Q [N] (the table, else 86.2 N/mm²·p²).

    References
    ----------
    [ISO606]; [GOST13568, Annex A].
    """
    for p_mm, q_kn in ISO606_A_TENSILE_KN.items():
        if math.isclose(pitch * 1e3, p_mm, rel_tol=1e-6):
            return q_kn * 1e3
    return TENSILE_PER_PITCH_SQUARED * pitch**2


def shaft_diameter_for_torque(torque: float, allowable_shear: float) -> float:
    """Shaft diameter d = ∛(16·T / (π·[τ])), sized in torsion only with a low [τ] that
    allows for bending ([τ] ≈ 15–25 MPa, preliminary design).

    Parameters
    ----------
    torque : float
        T [N·m].
    allowable_shear : float
        [τ] [Pa].

    Returns
    -------
    float
        d [m].

    References
    ----------
    [Reshetov1974] ([Lyashuk, ref. 5]).
    """
    return float((16.0 * torque / (math.pi * allowable_shear)) ** (1.0 / 3.0))


@dataclass(frozen=True, slots=True)
class EffectMap:
    """K_m at a risk level over pitch × teeth (rows: pitches, columns: teeth).

    Parameters
    ----------
    pitches : tuple of float
        [m].
    teeth : tuple of int
        [-].
    risk : float
        The risk level [-].
    fit : str
        The keyway fit.
    km_printed : numpy.ndarray
        Eq. 16 at the risk quantile of |ΔL₃| [-].
    km_linear : numpy.ndarray
        max(1, 2 − q/Δ_y), the compatibility-of-deformations value [-].
    quantile_abs : numpy.ndarray
        q [m].
    span_deformation : numpy.ndarray
        Δ_y per pitch [m].
    shaft_diameter, key_width, max_clearance : numpy.ndarray
        Per cell [m] (NaN where the shaft is outside the key table).
    c4 : numpy.ndarray
        C₄ per cell [-].
    inside_region : numpy.ndarray
        True inside the region of [Lyashuk, conclusion 3] (pitch < 50.8 mm, teeth < 40).
    km_min_inside, km_min_outside : float
        Smallest km_printed inside and outside that region [-].
    km_linear_min_inside, km_linear_min_outside : float
        Likewise for km_linear [-].
    threshold : float
        K_m counted as "close to 2" [-].
    fraction_close_inside, fraction_close_outside : float
        Share of cells with km_printed ≥ threshold [-].
    """

    pitches: tuple[float, ...]
    teeth: tuple[int, ...]
    risk: float
    fit: str
    km_printed: NDArray[np.float64]
    km_linear: NDArray[np.float64]
    quantile_abs: NDArray[np.float64]
    span_deformation: NDArray[np.float64]
    shaft_diameter: NDArray[np.float64]
    key_width: NDArray[np.float64]
    max_clearance: NDArray[np.float64]
    c4: NDArray[np.float64]
    inside_region: NDArray[np.bool_]
    km_min_inside: float
    km_min_outside: float
    km_linear_min_inside: float
    km_linear_min_outside: float
    threshold: float
    fraction_close_inside: float
    fraction_close_outside: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm; NaN as None)."""
        def grid(a: NDArray[np.float64], scale: float = 1.0) -> list[list[float | None]]:
            return [[None if not np.isfinite(v) else float(v) * scale for v in row] for row in a]
        return {
            "pitches_mm": [p * 1e3 for p in self.pitches], "teeth": list(self.teeth),
            "risk": self.risk, "fit": self.fit,
            "km_printed": grid(self.km_printed), "km_linear": grid(self.km_linear),
            "quantile_abs_mm": grid(self.quantile_abs, 1e3),
            "span_deformation_mm": [float(v) * 1e3 for v in self.span_deformation],
            "shaft_diameter_mm": grid(self.shaft_diameter, 1e3),
            "key_width_mm": grid(self.key_width, 1e3),
            "max_clearance_mm": grid(self.max_clearance, 1e3), "c4": grid(self.c4),
            "inside_region": self.inside_region.tolist(),
            "km_min_inside": self.km_min_inside, "km_min_outside": self.km_min_outside,
            "km_linear_min_inside": self.km_linear_min_inside,
            "km_linear_min_outside": self.km_linear_min_outside,
            "threshold": self.threshold, "fraction_close_inside": self.fraction_close_inside,
            "fraction_close_outside": self.fraction_close_outside,
        }


def _cell(pitch: float, teeth: int, *, contours: int, strength_ratio: float,
          allowable_shear: float, fit: str, c4_form: str) -> tuple[float, ...]:
    """Shaft diameter, key width, z_max, C₄ for one sprocket (NaN outside the key table)."""
    r = float(pitch_radius(pitch, teeth))
    torque = contours * chain_tensile_strength(pitch) / strength_ratio * r
    d = shaft_diameter_for_torque(torque, allowable_shear)
    if not PARALLEL_KEYS_MM[0][0] * 1e-3 < d <= PARALLEL_KEYS_MM[-1][1] * 1e-3:
        return (d, math.nan, math.nan, math.nan)
    joint = KeyedJoint.from_standard(r, d, fit)
    return (d, joint.key_width, joint.max_clearance, clearance_coefficient_c4(joint, c4_form))


def effect_map(pitches: tuple[float, ...] = DEFAULT_PITCHES,
               teeth: tuple[int, ...] = DEFAULT_TEETH, *, span_length: float = 1.0,
               span_links: float | None = None, working_strain: float = 0.5e-3, strength_ratio: float = 10.0,
               allowable_shear: float = 20e6, contours: int = 2, fit: str = "normal",
               risk: float = 0.05, c4_form: str = "printed",
               threshold: float = 1.8) -> EffectMap:
    """K_m at ``risk`` for each pitch × teeth [Lyashuk, eq. 16–18 and conclusion 3].

    Per cell: working force F_w = Q/``strength_ratio`` (Q of the ISO 606 A chain), shaft
    torque T = contours·F_w·R_δ, shaft d by :func:`shaft_diameter_for_torque`, the standard
    key and the fit's z_max (:meth:`KeyedJoint.from_standard`), C₄ (eq. 6), the (1 − risk)
    quantile q of |ΔL₃| (eq. 14) and Δ_y = ε·N·p (eq. 18 with x = y = 1, α = ε·p/F_w):
    a working span of N = ``span_length``/p links (or ``span_links`` if given, the same for
    every pitch) stretched by the elastic strain ε = ``working_strain`` at F_w. ε and
    ``strength_ratio`` are estimates, not data of the paper (the paper gives no α, x, y):
    ε ≈ 0.5·10⁻³ is the plate strain at Q/10 (≈ 0.25·10⁻³ for A-series plates) doubled for
    the hinge compliance.

    Parameters
    ----------
    pitches : tuple of float
        Chain pitches [m].
    teeth : tuple of int
        Tooth counts [-].
    span_length : float
        Length of the working span [m].
    span_links : float or None
        Links in the working span [-] (None: span_length/p).
    working_strain : float
        ε at the working force [-].
    strength_ratio : float
        Q / F_w [-].
    allowable_shear : float
        [τ] of the shaft [Pa].
    contours : int
        m [-].
    fit : str
        The keyway fit.
    risk : float
        The risk level [-].
    c4_form : str
        ``"printed"`` or ``"linearised"`` (:func:`.joints.clearance_coefficient_c4`).
    threshold : float
        K_m counted as "close to 2" [-] (default 1.8, at most 10 % below the ideal 2).

    Returns
    -------
    EffectMap
        K_m over pitch × teeth.

    References
    ----------
    [Lyashuk, eq. 14–18 and conclusion 3].
    """
    if not 0.0 < risk < 1.0:
        raise DesignError("risk", f"must be between 0 and 1, got {risk!r}")
    for name, value in (("span_length", span_length), ("working_strain", working_strain),
                        ("strength_ratio", strength_ratio), ("allowable_shear", allowable_shear)):
        check_positive(name, value)
    shape = (len(pitches), len(teeth))
    cells = np.array([[_cell(p, z, contours=contours, strength_ratio=strength_ratio,
                             allowable_shear=allowable_shear, fit=fit, c4_form=c4_form)
                       for z in teeth] for p in pitches], dtype=float).reshape(*shape, 4)
    d, b, z_max, c4 = np.moveaxis(cells, -1, 0)
    sigma = np.array([[length_difference_stats(c, zm).sigma if np.isfinite(c) else math.nan
                       for c, zm in zip(c_row, zm_row, strict=True)]
                      for c_row, zm_row in zip(c4, z_max, strict=True)])
    q = sigma * half_normal_quantile(1.0, 1.0 - risk)
    p_arr = np.asarray(pitches, dtype=float)
    links = span_length / p_arr if span_links is None else np.full_like(p_arr, span_links)
    if np.any(~np.isfinite(links) | (links <= 0)):
        raise DesignError("span_links", f"must be a positive number, got {span_links!r}")
    dy = working_strain * links * p_arr
    km_printed = contour_factor_km(q, dy[:, None])
    km_linear = np.maximum(1.0, 2.0 - q / dy[:, None])
    inside = (np.asarray(pitches)[:, None] < CONCLUSION_PITCH_LIMIT - 1e-9) & (
        np.asarray(teeth)[None, :] < CONCLUSION_TEETH_LIMIT)

    def lowest(a: NDArray[np.float64], mask: NDArray[np.bool_]) -> float:
        values = a[mask & np.isfinite(a)]
        return float(values.min()) if values.size else math.nan

    def close(mask: NDArray[np.bool_]) -> float:
        values = km_printed[mask & np.isfinite(km_printed)]
        return float(np.mean(values >= threshold)) if values.size else math.nan

    return EffectMap(
        pitches=tuple(pitches), teeth=tuple(teeth), risk=risk, fit=fit, km_printed=km_printed,
        km_linear=km_linear, quantile_abs=q, span_deformation=dy, shaft_diameter=d,
        key_width=b, max_clearance=z_max, c4=c4, inside_region=inside,
        km_min_inside=lowest(km_printed, inside), km_min_outside=lowest(km_printed, ~inside),
        km_linear_min_inside=lowest(km_linear, inside),
        km_linear_min_outside=lowest(km_linear, ~inside), threshold=threshold,
        fraction_close_inside=close(inside), fraction_close_outside=close(~inside),
    )
