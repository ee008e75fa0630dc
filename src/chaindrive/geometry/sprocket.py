"""Sprocket diameters, tooth forms, proportions, mass and inertia (SI units: metres, radians).

Pure, vectorised functions at the bottom of the geometry layer. Sources:

* pitch diameter d = p / sin(π/z): [ISO606], [DIN8196], [GOST591], [ChainNonUniformity];
* ISO 606 tooth-form limits (minimum and maximum tooth-gap forms): [ISO606], confirmed by
  [Bhandari2010, Example 14.5];
* GOST 591-69 tooth profile: [GOST591] as given by [Anuriev, vol. 2, ch. 5];
* polymeric sprocket proportions: [MultimassChainDrives, §3.4].

Several formulas of the standards carry dimensional constants in millimetres (e.g.
r = 0.5025·d1 + 0.05 mm); they are applied here with the constants converted to metres.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import asdict, dataclass, fields
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import DesignError

TOOTH_FORM_NAMES: tuple[str, ...] = ("ISO 606", "GOST 591")
_MM = 1e-3  # one millimetre [m]


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


def _positive(name: str, value: ArrayLike) -> NDArray[np.float64]:
    arr = np.asarray(value, dtype=float)
    if np.any(~np.isfinite(arr)) or np.any(arr <= 0):
        raise DesignError(name, f"must be a positive length, got {value!r}")
    return arr


def _dict_with_units(obj: Any, lengths: tuple[str, ...], angles: tuple[str, ...]) -> dict:
    """to_dict helper: lengths → ``<name>_mm``, angles → ``<name>_deg``, others as is."""
    out: dict[str, Any] = {}
    for key, value in asdict(obj).items():
        if key in lengths:
            out[f"{key}_mm"] = float(value) / _MM
        elif key in angles:
            out[f"{key}_deg"] = math.degrees(float(value))
        else:
            out[key] = value.item() if isinstance(value, np.generic) else value
    return out


# ---------------------------------------------------------------------------------------
# Pitch circle
# ---------------------------------------------------------------------------------------

def pitch_diameter(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Pitch diameter d = p / sin(π/z) [m] ([ISO606]; dд of [GOST591]; [ChainNonUniformity]).

    pitch : float — chain pitch p [m]; teeth : int — number of teeth z.
    """
    return _out(_positive("pitch", pitch) / np.sin(np.pi / _teeth(teeth)))


def pitch_radius(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Pitch radius R = p / (2 sin(π/z)) [m]: radius of the hinge centres (R of [ChainNonUniformity])."""
    return _out(0.5 * np.asarray(pitch_diameter(pitch, teeth)))


def approximate_pitch_diameter(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Approximate pitch diameter t·z/π [m] of [MultimassChainDrives, §3.4] and its worked
    example.

    It is the diameter of a circle whose circumference is z pitches; it is smaller than the
    true pitch diameter p/sin(π/z) (121.3 vs 122.2 mm for z = 15, t = 25.4 mm, the worked
    example of [MultimassChainDrives]).
    """
    return _out(_positive("pitch", pitch) * _teeth(teeth) / np.pi)


# ---------------------------------------------------------------------------------------
# ISO 606 tooth-form limits
# ---------------------------------------------------------------------------------------

def iso606_tip_diameter_range(pitch: ArrayLike, teeth: ArrayLike,
                              roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 tip diameter limits (da,min, da,max) [m].

    da,max = d + 1.25·p − d1;  da,min = d + p·(1 − 1.6/z) − d1  (ISO 606; Bhandari Ex. 14.5).
    roller_diameter : float — d1 [m].
    """
    p, z = _positive("pitch", pitch), _teeth(teeth)
    d1 = _positive("roller_diameter", roller_diameter)
    d = p / np.sin(np.pi / z)
    return _out(d + p * (1.0 - 1.6 / z) - d1), _out(d + 1.25 * p - d1)


def iso606_root_diameter(pitch: ArrayLike, teeth: ArrayLike,
                         roller_diameter: ArrayLike) -> FloatOrArray:
    """ISO 606 (DIN 8196) root diameter df = d − d1 [m]."""
    d1 = _positive("roller_diameter", roller_diameter)
    return _out(np.asarray(pitch_diameter(pitch, teeth)) - d1)


def iso606_seating_radius_range(roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 roller-seating radius limits (ri,min, ri,max) [m].

    ri,min = 0.505·d1;  ri,max = 0.505·d1 + 0.069·d1^(1/3)  (d1 and ri in mm in the standard).
    """
    d1_mm = _positive("roller_diameter", roller_diameter) / _MM
    return _out(0.505 * d1_mm * _MM), _out((0.505 * d1_mm + 0.069 * np.cbrt(d1_mm)) * _MM)


def iso606_root_diameter_range(pitch: ArrayLike, teeth: ArrayLike,
                               roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """Root diameter of the two tooth-gap forms, Df = d − 2·ri (min with ri,max) [m].

    Bhandari Ex. 14.5 and Autodesk Inventor (Df = Dp − 2 ri); the nominal ISO 606 df = d − d1
    lies just above this range (ri,min = 0.505 d1 > d1/2).
    """
    d = np.asarray(pitch_diameter(pitch, teeth))
    ri_min, ri_max = iso606_seating_radius_range(roller_diameter)
    return _out(d - 2 * np.asarray(ri_max)), _out(d - 2 * np.asarray(ri_min))


def iso606_flank_radius_range(teeth: ArrayLike,
                              roller_diameter: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 tooth-flank radius limits (re,min, re,max) [m].

    re,min = 0.12·d1·(z + 2);  re,max = 0.008·d1·(z² + 180)  (ISO 606).
    """
    z, d1 = _teeth(teeth), _positive("roller_diameter", roller_diameter)
    return _out(0.12 * d1 * (z + 2)), _out(0.008 * d1 * (z**2 + 180))


def iso606_seating_angle_range(teeth: ArrayLike) -> tuple[FloatOrArray, FloatOrArray]:
    """ISO 606 roller-seating angle limits (α,min, α,max) [rad]: 120° − 90°/z, 140° − 90°/z."""
    z = _teeth(teeth)
    return _out(np.radians(120.0 - 90.0 / z)), _out(np.radians(140.0 - 90.0 / z))


def iso606_tooth_width(pitch: ArrayLike, inner_width: ArrayLike,
                       strands: ArrayLike = 1) -> FloatOrArray:
    """ISO 606 tooth width bf1 [m] from the chain inner width b1 [m].

    ======================  ==========  ============
    strands                 p ≤ 12.7 mm  p > 12.7 mm
    ======================  ==========  ============
    1 (simplex)             0.93·b1     0.95·b1
    2, 3 (duplex, triplex)  0.91·b1     0.93·b1
    4 and more              0.88·b1     0.93·b1
    ======================  ==========  ============

    ISO 606 (Bhandari Ex. 14.5 uses 0.95·b1, simplex p > 12.7). The simplex and
    duplex/triplex factors reproduce the DIN 8187 tooth-width tables (e.g. 12B: 11.1 and
    10.8 mm; 08B: 7.2 and 7.0 mm); the quadruplex row is from ISO 606 as remembered and
    is not confirmed by a source reachable here.
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
    """ISO 606 tooth side relief (chamfer width) ba = 0.10·p … 0.15·p [m]."""
    p = _positive("pitch", pitch)
    return _out(0.10 * p), _out(0.15 * p)


def iso606_side_radius(pitch: ArrayLike) -> FloatOrArray:
    """ISO 606 nominal tooth side radius rx = p [m]."""
    return _out(_positive("pitch", pitch))


def multi_strand_width(tooth_width: ArrayLike, transverse_pitch: ArrayLike,
                       strands: ArrayLike) -> FloatOrArray:
    """Overall width of a multi-strand sprocket bf_k = pt·(k − 1) + bf1 [m] (Autodesk Inventor,
    roller-chain sprocket calculation)."""
    k = np.asarray(strands, dtype=float)
    return _out(np.asarray(transverse_pitch, dtype=float) * (k - 1)
                + np.asarray(tooth_width, dtype=float))


@dataclass(frozen=True, slots=True)
class ToothForm:
    """ISO 606 tooth-form limits of one sprocket (SI: metres, radians).

    Each limited quantity is given as ``*_min``, ``*_max`` and ``*_mean`` (the mean is what
    Bhandari Ex. 14.5 reports). root_diameter is the nominal df = d − d1; root_diameter_min/
    max/mean are d − 2·ri for the two tooth-gap forms.
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


def iso606_tooth_form(pitch: float, teeth: int, roller_diameter: float, inner_width: float,
                      strands: int = 1) -> ToothForm:
    """All ISO 606 tooth-form limits of a sprocket (scalar inputs) — see the functions above.

    pitch : float — p [m]; teeth : int — z; roller_diameter : float — d1 [m];
    inner_width : float — chain inner width b1 [m]; strands : int — chain strands.
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


# ---------------------------------------------------------------------------------------
# GOST 591-69 tooth profile
# ---------------------------------------------------------------------------------------

#: GOST 591-69 table of the tooth-height coefficient K: (λ upper bound, K), the interval
#: being "over the previous bound up to this one" (св. 1,40 до 1,50 → 1.40 < λ ≤ 1.50).
GOST591_K_TABLE: tuple[tuple[float, float], ...] = (
    (1.50, 0.480), (1.60, 0.532), (1.70, 0.555), (1.80, 0.575), (2.00, 0.565))
GOST591_LAMBDA_MIN = 1.40


def engagement_characteristic(pitch: ArrayLike, roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 engagement characteristic λ = t/d1 (dimensionless)."""
    return _out(_positive("pitch", pitch) / _positive("roller_diameter", roller_diameter))


def gost591_tooth_height_coefficient(lam: ArrayLike) -> FloatOrArray:
    """GOST 591-69 tooth-height coefficient K(λ) from the table (Anuriev, т. 2, гл. 5).

    Refuses λ outside 1.40 < λ ≤ 2.00 (the scope of GOST 591-69 is λ ≤ 2; the table starts
    above 1.40) with a DesignError on ``roller_diameter``.
    """
    lam_arr = np.asarray(lam, dtype=float)
    if np.any(lam_arr > 2.0 + 1e-12) or np.any(lam_arr <= GOST591_LAMBDA_MIN):
        raise DesignError("roller_diameter", "GOST 591-69 needs 1.40 < λ = t/d1 ≤ 2, got "
                          f"λ = {np.round(lam_arr, 4).tolist()}")
    bounds = np.array([b for b, _ in GOST591_K_TABLE])
    values = np.array([k for _, k in GOST591_K_TABLE])
    index = np.searchsorted(bounds, lam_arr - 1e-12, side="left")
    return _out(values[np.minimum(index, len(values) - 1)])


def gost591_tip_diameter(pitch: ArrayLike, teeth: ArrayLike,
                         roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 tip diameter De = t·(K + ctg(180°/z)) [m] (not rounded; the standard
    gives De to 0.1 mm)."""
    p, z = _positive("pitch", pitch), _teeth(teeth)
    K = np.asarray(gost591_tooth_height_coefficient(engagement_characteristic(p, roller_diameter)))
    return _out(p * (K + 1.0 / np.tan(np.pi / z)))


def gost591_seating_radius(roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 root (seating) radius r = 0.5025·d1 + 0.05 mm [m]."""
    return _out(0.5025 * _positive("roller_diameter", roller_diameter) + 0.05 * _MM)


def gost591_root_diameter(pitch: ArrayLike, teeth: ArrayLike,
                          roller_diameter: ArrayLike) -> FloatOrArray:
    """GOST 591-69 root diameter Di = dд − 2r [m]."""
    d = np.asarray(pitch_diameter(pitch, teeth))
    return _out(d - 2 * np.asarray(gost591_seating_radius(roller_diameter)))


@dataclass(frozen=True, slots=True)
class Gost591ToothForm:
    """GOST 591-69 tooth profile of one sprocket (SI: metres, radians).

    lam λ = t/d1; K tooth-height coefficient; tip_diameter De; root_diameter Di;
    seating_radius r; joining_radius r1; head_radius r2; half_space_angle α;
    joining_angle β; half_tooth_angle φ; straight_part FC; head_centre_distance OO2;
    centre_offset e = 0.03 t; rim_width b = 0.93·Bвн − 0.15 mm (single row);
    side_radius r3 = 1.7 d1; side_radius_height h3 = 0.8 d1; measuring_chord Lx =
    dд cos(90°/z) − 2r for odd z (for even z the chord across opposite roots, Di).
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


def gost591_tooth_form(pitch: float, teeth: int, roller_diameter: float,
                       inner_width: float) -> Gost591ToothForm:
    """GOST 591-69 tooth profile ([GOST591] as given by [Anuriev, vol. 2, ch. 5]).

    pitch : float — t [m]; teeth : int — z; roller_diameter : float — d1 [m];
    inner_width : float — Bвн [m] (single-row rim width only: multi-row is not confirmed).
    Raises DesignError("roller_diameter") when λ = t/d1 is outside 1.40 < λ ≤ 2.
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


# ---------------------------------------------------------------------------------------
# Convenience used by the contour geometry
# ---------------------------------------------------------------------------------------

def _check_form(form: str) -> None:
    if form not in TOOTH_FORM_NAMES:
        raise DesignError("tooth_form", f"must be one of {', '.join(TOOTH_FORM_NAMES)}, "
                          f"got {form!r}")


def tip_diameter(pitch: ArrayLike, teeth: ArrayLike, roller_diameter: ArrayLike,
                 form: Literal["ISO 606", "GOST 591"] = "ISO 606") -> FloatOrArray:
    """Tip (outside) diameter [m] by the chosen tooth form.

    ISO 606: the mean of the two limits, (da,min + da,max)/2 — the value Bhandari Ex. 14.5
    reports; any value in the range is standard. GOST 591: De = t·(K + ctg(180°/z)).
    """
    _check_form(form)
    if form == "GOST 591":
        return gost591_tip_diameter(pitch, teeth, roller_diameter)
    lo, hi = iso606_tip_diameter_range(pitch, teeth, roller_diameter)
    return _out(0.5 * (np.asarray(lo) + np.asarray(hi)))


def root_diameter(pitch: ArrayLike, teeth: ArrayLike, roller_diameter: ArrayLike,
                  form: Literal["ISO 606", "GOST 591"] = "ISO 606") -> FloatOrArray:
    """Root diameter [m]: ISO 606 df = d − d1 (nominal); GOST 591 Di = dд − 2r."""
    _check_form(form)
    if form == "GOST 591":
        return gost591_root_diameter(pitch, teeth, roller_diameter)
    return iso606_root_diameter(pitch, teeth, roller_diameter)


# ---------------------------------------------------------------------------------------
# Polymeric sprocket proportions, mass and inertia
# ---------------------------------------------------------------------------------------

@dataclass(frozen=True, slots=True)
class PolymericProportions:
    """Proportions of a polymeric sprocket [MultimassChainDrives, §3.4], SI metres.

    The paper's figure naming each diameter is lost. Reading used here (D = t·z/π):

    * ``d_pitch`` d_∂ = D — the paper's pitch diameter;
    * ``rim_inner_diameter`` d_2 = 0.8 D — the rim (toothed ring) runs from d_2 outwards;
    * ``hub_outer_diameter`` d_1 = 0.33 D — the web joins the hub here;
    * ``hole_circle_diameter`` d_H = 0.56 D — lightening holes centred on this circle
      (it lies midway between d_1 and d_2: (0.33 + 0.8)/2 = 0.565);
    * ``d_n`` d_н = 0.3 D — role not identifiable (perhaps a metal bore insert or a hub
      step); kept for reference, not used in the mass model;
    * ``bore_diameter`` d_0 = 0.19 D;
    * ``rim_width`` b = 0.85 B_in; ``web_thickness`` h = 0.5 b; ``hub_length`` l_min = 3 b.
    """

    d_pitch: float
    rim_inner_diameter: float
    hub_outer_diameter: float
    hole_circle_diameter: float
    d_n: float
    bore_diameter: float
    rim_width: float
    web_thickness: float
    hub_length: float

    def to_dict(self) -> dict[str, float]:
        """JSON-ready dict, every length in mm."""
        return {f"{k}_mm": float(v) / _MM for k, v in asdict(self).items()}


def polymeric_sprocket_proportions(pitch: float, teeth: int,
                                   inner_width: float) -> PolymericProportions:
    """Polymeric sprocket proportions from t, z and the chain inner width B_in [MultimassChainDrives, §3.4]:
    d_∂ ≈ tz/π, d_1 ≈ 0.33 tz/π, d_2 ≈ 0.8 tz/π, d_н ≈ 0.3 tz/π, d_H ≈ 0.56 tz/π,
    d_0 ≈ 0.19 tz/π, b ≈ 0.85 B_in, h ≈ 0.5 b, l_min ≈ 3 b. See :class:`PolymericProportions`
    for the reading of each symbol. pitch, inner_width [m]."""
    D = float(approximate_pitch_diameter(pitch, teeth))
    b = 0.85 * float(_positive("inner_width", inner_width))
    return PolymericProportions(
        d_pitch=D, rim_inner_diameter=0.8 * D, hub_outer_diameter=0.33 * D,
        hole_circle_diameter=0.56 * D, d_n=0.3 * D, bore_diameter=0.19 * D,
        rim_width=b, web_thickness=0.5 * b, hub_length=3.0 * b)


@dataclass(frozen=True, slots=True)
class SprocketMassProperties:
    """Mass [kg] and polar moment of inertia about the axis [kg·m²] of a sprocket body;
    ``model`` names the body model used. Unpacks as ``mass, inertia = ...``."""

    mass: float
    moment_of_inertia: float
    model: str

    def __iter__(self) -> Iterator[float]:
        yield self.mass
        yield self.moment_of_inertia

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"mass_kg": self.mass, "moment_of_inertia_kg_m2": self.moment_of_inertia,
                "model": self.model}


def annulus_mass_and_inertia(outer_diameter: ArrayLike, inner_diameter: ArrayLike,
                             width: ArrayLike, density: ArrayLike
                             ) -> tuple[FloatOrArray, FloatOrArray]:
    """Mass m = ρ·w·π(Do² − Di²)/4 [kg] and axial inertia I = m(Do² + Di²)/8 [kg·m²] of a
    thick ring (hollow cylinder) — standard rigid-body result."""
    Do, Di = np.asarray(outer_diameter, float), np.asarray(inner_diameter, float)
    m = np.asarray(density, float) * np.asarray(width, float) * np.pi * (Do**2 - Di**2) / 4
    return _out(m), _out(m * (Do**2 + Di**2) / 8)


def sprocket_mass_and_inertia(pitch: float, teeth: int, inner_width: float, density: float,
                              polymeric: bool, hole_count: int = 6,
                              hole_diameter_ratio: float = 0.5, strands: int = 1,
                              transverse_pitch: float = 0.0) -> SprocketMassProperties:
    """Mass and moment of inertia of a sprocket body from its proportions.

    The toothed ring is replaced by a full ring out to the true pitch diameter d = p/sin(π/z)
    (the teeth above the pitch circle roughly fill the tooth gaps below it).

    * polymeric ([MultimassChainDrives, §3.4], reading of :class:`PolymericProportions`): rim d_2…d of
      width b = 0.85 B_in, web d_1…d_2 of thickness h = 0.5 b with ``hole_count`` lightening
      holes of diameter ``hole_diameter_ratio``·(d_2 − d_1)/2 centred on d_H (the paper gives
      neither number nor size: 6 holes of half the web height are our assumption), and hub
      d_0…d_1 of length l_min = 3 b.
    * steel (plate sprocket, ISO 606 "type A" without hub): a disc of diameter d and
      thickness bf1 (ISO 606 simplex tooth width, :func:`iso606_tooth_width`) minus a bore of
      0.19·tz/π (the paper's bore proportion, so both models share the bore). A hub, if any,
      should be added by the user as an extra inertia. A multi-strand steel sprocket is
      :func:`multi_strand_width` thick (strands, transverse_pitch [m]).

    pitch [m]; teeth z; inner_width B_in [m]; density ρ [kg/m³].
    """
    rho = float(_positive("density", density))
    d = float(pitch_diameter(pitch, teeth))
    prop = polymeric_sprocket_proportions(pitch, teeth, inner_width)
    if not polymeric:
        width = float(multi_strand_width(iso606_tooth_width(pitch, inner_width, strands),
                                         transverse_pitch, strands))
        m, inertia = annulus_mass_and_inertia(d, prop.bore_diameter, width, rho)
        return SprocketMassProperties(float(m), float(inertia), "steel plate disc (d, bf1)")
    parts = [annulus_mass_and_inertia(d, prop.rim_inner_diameter, prop.rim_width, rho),
             annulus_mass_and_inertia(prop.rim_inner_diameter, prop.hub_outer_diameter,
                                      prop.web_thickness, rho),
             annulus_mass_and_inertia(prop.hub_outer_diameter, prop.bore_diameter,
                                      prop.hub_length, rho)]
    m = sum(float(p[0]) for p in parts)
    inertia = sum(float(p[1]) for p in parts)
    dh = hole_diameter_ratio * (prop.rim_inner_diameter - prop.hub_outer_diameter) / 2
    m_hole = rho * prop.web_thickness * math.pi * dh**2 / 4
    rc = prop.hole_circle_diameter / 2
    m -= hole_count * m_hole
    inertia -= hole_count * m_hole * (dh**2 / 8 + rc**2)
    return SprocketMassProperties(m, inertia, "polymeric rim + web with holes + hub [MultimassChainDrives, §3.4]")
