"""Keyed joints (sprocket – key – shaft): standard key sizes, fit clearances, ΔL of eq. 2–6.

Source of the model: [Lyashuk, eq. 2–6 and Fig. 4]; keys [DIN6885-1], [GOST23360]; fits
[ISO286-1].

Geometry of Fig. 4 (the paper's nominal picture): a parallel key of width b and height h sits
with half its height in the shaft of radius R, so its outer corner A lies at
``R_1 = ½·√(b² + (2R + h)²)`` from the shaft axis. The keyway in the sprocket bore has width
L = b + z; with the clearance z the sprocket can turn on the shaft by α (eq. 4) and the chain's
contact point on the pitch circle (radius R_δ) moves by ΔL = R_δ·α (eq. 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError, did_you_mean

Fit = Literal["tight", "normal", "free"]
C4Form = Literal["printed", "linearised"]
FITS: tuple[str, ...] = ("tight", "normal", "free")
C4_FORMS: tuple[str, ...] = ("printed", "linearised")

#: Parallel keys by shaft diameter: (d over [mm], d up to [mm], b [mm], h [mm]).
#: [DIN6885-1] form A = ISO/R 773 = [GOST23360] (same ranges); checked against the table of
#: [SiemensMD31, p. 7/3].
PARALLEL_KEYS_MM: tuple[tuple[float, float, float, float], ...] = (
    (6, 8, 2, 2), (8, 10, 3, 3), (10, 12, 4, 4), (12, 17, 5, 5), (17, 22, 6, 6),
    (22, 30, 8, 7), (30, 38, 10, 8), (38, 44, 12, 8), (44, 50, 14, 9), (50, 58, 16, 10),
    (58, 65, 18, 11), (65, 75, 20, 12), (75, 85, 22, 14), (85, 95, 25, 14),
    (95, 110, 28, 16), (110, 130, 32, 18), (130, 150, 36, 20), (150, 170, 40, 22),
    (170, 200, 45, 25), (200, 230, 50, 28), (230, 260, 56, 32), (260, 290, 63, 32),
    (290, 330, 70, 36), (330, 380, 80, 40), (380, 440, 90, 45), (440, 500, 100, 50),
)

#: [ISO286-1, Tables 1 and 3] for nominal sizes (over, up to] in mm:
#: standard tolerance IT9, IT10 and the fundamental deviations of holes D (EI) and P (ES = −p,
#: for grades above IT7), all in µm.
ISO286_MM_UM: tuple[tuple[float, float, float, float, float, float], ...] = (
    # over, up to, IT9, IT10, D: EI, P: p
    (0, 3, 25, 40, 20, 6), (3, 6, 30, 48, 30, 12), (6, 10, 36, 58, 40, 15),
    (10, 18, 43, 70, 50, 18), (18, 30, 52, 84, 65, 22), (30, 50, 62, 100, 80, 26),
    (50, 80, 74, 120, 100, 32), (80, 120, 87, 140, 120, 37),
)


def parallel_key(shaft_diameter: float) -> tuple[float, float]:
    """Width and height of the standard parallel key for a shaft diameter.

    Parameters
    ----------
    shaft_diameter : float
        d [m] (a diameter on a boundary of :data:`PARALLEL_KEYS_MM` takes the smaller key).

    Returns
    -------
    tuple of (float, float)
        Key width b and height h [m].

    References
    ----------
    [DIN6885-1]; [GOST23360].
    """
    d_mm = shaft_diameter * 1e3
    for lower, upper, b, h in PARALLEL_KEYS_MM:
        if lower < d_mm <= upper:
            return b * 1e-3, h * 1e-3
    raise DesignError("shaft_diameter", f"must be over 6 mm and at most 500 mm for the "
                                        f"standard key table, got {d_mm:.1f} mm")


def _iso286_row(size_mm: float) -> tuple[float, float, float, float, float, float]:
    for row in ISO286_MM_UM:
        if row[0] < size_mm <= row[1]:
            return row
    raise DesignError("key_width", f"must be at most 120 mm for the tolerance table, "
                                   f"got {size_mm:.1f} mm")


def keyway_max_clearance(key_width: float, fit: str = "normal") -> float:
    """Largest clearance z_max = L_max − b_min between a key (h9) and the hub keyway.

    The paper takes the clearance on [0, z_max] (eq. 7–8); for the tight and normal fits the
    smallest value is an interference, read as zero clearance.

    Parameters
    ----------
    key_width : float
        b [m].
    fit : str
        Hub keyway tolerance: ``"tight"`` P9, ``"normal"`` JS9, ``"free"`` D10; the key is h9
        (ei = −IT9).

    Returns
    -------
    float
        z_max [m].

    References
    ----------
    [DIN6885-1]; [GOST23360]; [ISO286-1] (:data:`ISO286_MM_UM`); [Lyashuk, eq. 7–8].
    """
    if fit not in FITS:
        raise DesignError("fit", f"must be one of {FITS}, got {fit!r}{did_you_mean(fit, FITS)}")
    _, _, it9, it10, d_ei, p_dev = _iso286_row(key_width * 1e3)
    upper_hub = {"tight": -p_dev, "normal": it9 / 2.0, "free": d_ei + it10}[fit]  # ES of hub
    return (upper_hub + it9) * 1e-6  # ES(hub) − ei(key h9) = ES + IT9


def key_corner_radius(shaft_radius: float, key_width: float, key_height: float) -> float:
    """Radius of the key corner A, R_1 = AO = ½·√(b² + (2R + h)²).

    Parameters
    ----------
    shaft_radius : float
        R [m].
    key_width : float
        b [m].
    key_height : float
        h [m].

    Returns
    -------
    float
        R_1 [m].

    References
    ----------
    [Lyashuk, Fig. 4, eq. 3].
    """
    return 0.5 * math.hypot(key_width, 2.0 * shaft_radius + key_height)


def key_corner_angle(key_width: float, shaft_radius: float, key_height: float) -> float:
    """Angle of the key corner β = arcsin(b / √(b² + (2R + h)²)).

    Parameters
    ----------
    key_width : float
        b [m].
    shaft_radius : float
        R [m].
    key_height : float
        h [m].

    Returns
    -------
    float
        β [rad].

    References
    ----------
    [Lyashuk, eq. 3].
    """
    return math.asin(key_width / (2.0 * key_corner_radius(shaft_radius, key_width, key_height)))


def sprocket_turn_angle(key_width: float, shaft_radius: float, key_height: float,
                        keyway_width: ArrayLike) -> NDArray[np.float64]:
    """Free turn of the sprocket α = arcsin((2L − b)/√(b² + (2R + h)²)) − β.

    Parameters
    ----------
    key_width : float
        b [m].
    shaft_radius : float
        R [m].
    key_height : float
        h [m].
    keyway_width : float or array_like
        L = b + z [m].

    Returns
    -------
    numpy.ndarray
        α [rad].

    References
    ----------
    [Lyashuk, eq. 4] (α = δ − β).
    """
    root = 2.0 * key_corner_radius(shaft_radius, key_width, key_height)
    ratio = (2.0 * np.asarray(keyway_width, dtype=float) - key_width) / root
    if np.any(ratio > 1.0):
        raise DesignError("clearance", "is too large for the joint: (2L − b) exceeds "
                                       "√(b² + (2R + h)²) in eq. 4")
    return np.arcsin(ratio) - key_corner_angle(key_width, shaft_radius, key_height)


@dataclass(frozen=True, slots=True)
class KeyedJoint:
    """A sprocket keyed to a shaft by a parallel key.

    Parameters
    ----------
    pitch_radius : float
        R_δ, pitch-circle radius of the sprocket [m].
    shaft_radius : float
        R, nominal shaft radius [m].
    key_width : float
        b [m].
    key_height : float
        h [m].
    max_clearance : float
        z_max, largest key/keyway clearance of the fit [m].
    fit : str
        Name of the fit the clearance comes from (``"given"`` when typed in).
    """

    pitch_radius: float
    shaft_radius: float
    key_width: float
    key_height: float
    max_clearance: float
    fit: str = "given"

    def __post_init__(self) -> None:
        for name in ("pitch_radius", "shaft_radius", "key_width", "key_height"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise DesignError(f"joint.{name}", f"must be a positive length, got {value!r}")
        z = self.max_clearance
        if not (isinstance(z, int | float) and math.isfinite(z) and z >= 0):
            raise DesignError("joint.max_clearance", f"must be ≥ 0, got {z!r}")
        if self.key_width >= 2.0 * self.shaft_radius:
            raise DesignError("joint.key_width", "must be smaller than the shaft diameter")
        if self.pitch_radius <= self.shaft_radius:
            raise DesignError("joint.pitch_radius", "must exceed the shaft radius")

    @classmethod
    def from_standard(cls, pitch_radius: float, shaft_diameter: float,
                      fit: str = "normal") -> KeyedJoint:
        """A joint with the standard key for the shaft and the fit's z_max.

        Parameters
        ----------
        pitch_radius : float
            R_δ [m].
        shaft_diameter : float
            d [m].
        fit : str
            ``"tight"``, ``"normal"`` or ``"free"`` (:func:`keyway_max_clearance`).

        Returns
        -------
        KeyedJoint
            The joint.

        References
        ----------
        [DIN6885-1]; [GOST23360]; [ISO286-1].
        """
        b, h = parallel_key(shaft_diameter)
        return cls(pitch_radius, shaft_diameter / 2.0, b, h, keyway_max_clearance(b, fit), fit)

    @property
    def corner_radius(self) -> float:
        """R_1'' = AO [m], radius of the key corner [Lyashuk, Fig. 4]."""
        return key_corner_radius(self.shaft_radius, self.key_width, self.key_height)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm)."""
        return {
            "pitch_radius_mm": self.pitch_radius * 1e3,
            "shaft_radius_mm": self.shaft_radius * 1e3,
            "key_width_mm": self.key_width * 1e3,
            "key_height_mm": self.key_height * 1e3,
            "max_clearance_mm": self.max_clearance * 1e3,
            "corner_radius_mm": self.corner_radius * 1e3,
            "fit": self.fit,
            "c4": clearance_coefficient_c4(self),
        }


def length_error_exact(joint: KeyedJoint, clearance: ArrayLike) -> NDArray[np.float64]:
    """Exact length error ΔL = R_δ·α for a key/keyway clearance (L = b + z, α from eq. 4).

    Parameters
    ----------
    joint : KeyedJoint
        The joint.
    clearance : float or array_like
        z [m].

    Returns
    -------
    numpy.ndarray
        ΔL [m].

    References
    ----------
    [Lyashuk, eq. 2–5].
    """
    z = np.asarray(clearance, dtype=float)
    if np.any(z < 0):
        raise DesignError("clearance", "must be ≥ 0")
    alpha = sprocket_turn_angle(joint.key_width, joint.shaft_radius, joint.key_height,
                                joint.key_width + z)
    return joint.pitch_radius * alpha


def clearance_coefficient_c4(joint: KeyedJoint, form: str = "printed") -> float:
    """C₄ = ΔL/z, the clearance-to-length coefficient of eq. 6.

    The two forms differ by the factor cos β = (R + h/2)/R_1 (≈ 0.97–0.99 for standard
    keys).

    Parameters
    ----------
    joint : KeyedJoint
        The joint.
    form : str
        ``"printed"`` — C₄ = R_δ / R_1'' as printed (eq. 6: the arc AC at the key corner is
        taken equal to z); ``"linearised"`` — C₄ = R_δ / (R + h/2), the exact first-order
        limit of eq. 5 as z → 0 (d/dz of eq. 4 at z = 0 is 1/(R_1·cos β) = 1/(R + h/2)).

    Returns
    -------
    float
        C₄ [-].

    References
    ----------
    [Lyashuk, eq. 5–6].
    """
    if form == "printed":
        return joint.pitch_radius / joint.corner_radius
    if form == "linearised":
        return joint.pitch_radius / (joint.shaft_radius + joint.key_height / 2.0)
    raise DesignError("form", f"must be one of {C4_FORMS}, got {form!r}"
                              f"{did_you_mean(form, C4_FORMS)}")


def length_error_simplified(joint: KeyedJoint, clearance: ArrayLike,
                            form: str = "printed") -> NDArray[np.float64]:
    """Simplified length error ΔL = C₄·z.

    Parameters
    ----------
    joint : KeyedJoint
        The joint.
    clearance : float or array_like
        z [m].
    form : str
        As in :func:`clearance_coefficient_c4`.

    Returns
    -------
    numpy.ndarray
        ΔL [m].

    References
    ----------
    [Lyashuk, eq. 6].
    """
    return clearance_coefficient_c4(joint, form) * np.asarray(clearance, dtype=float)
