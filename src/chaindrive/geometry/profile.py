"""Sprocket profiles for manufacture: the tooth form of each sprocket by its standard, the
closed toothed outline, and the body of a polymeric sprocket.

Tooth profiles (from the dimensions of :mod:`chaindrive.geometry.sprocket`):

* GOST 591-69 ([GOST591] as given by [Anuriev, vol. 2, ch. 5]): seating
  arc r over the half space angle α, joining arc r1 centred at O1 = 0.8·d1·(sin α, cos α)
  over β, the straight part FC, and the head arc r2 centred at
  O2 = 1.24·d1·(cos 180°/z, sin 180°/z) up to the tip circle De (drawn without the offset
  e of the root-arc centres, which GOST 591 permits);
* ISO 606 [ISO606] (between the minimum and maximum tooth-gap forms): seating arc ri over
  the seating angle α, then the convex flank arc re tangent to it, up to the tip circle da
  (mean); re and α are the means of the two forms, ri the one that puts the root d − 2·ri in
  the middle of the root-diameter tolerance of ISO 606 (d_f = d − d1, upper deviation 0),
  as far as ri,min … ri,max allow (:func:`iso606_drawn_seating_radius`).

The profile of a tooth gap is drawn in a frame at the seat centre (x along the tangent, y
radial outward); teeth end on the tip circle or where the flanks of neighbouring gaps meet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import (
    Gost591ToothForm,
    PolymericProportions,
    SprocketMassProperties,
    ToothForm,
    gost591_tooth_form,
    iso606_tooth_form,
    polymeric_sprocket_proportions,
    sprocket_body,
)
from chaindrive.model import Drive
from chaindrive.units import TWO_PI

__all__ = [
    "BORE_RATIO",
    "ISO606_ROOT_LOWER_DEVIATIONS_MM",
    "IT11_UM",
    "SprocketProfile",
    "gost591_gap_wall",
    "hub_limit_diameter",
    "iso606_drawn_seating_radius",
    "iso606_gap_wall",
    "iso606_root_diameter_tolerance",
    "outline_of",
    "sprocket_outline",
    "sprocket_profiles",
    "tooth_form_of",
]


def _arc(centre: NDArray[np.float64], radius: float, a0: float, a1: float,
         samples: int) -> NDArray[np.float64]:
    t = np.linspace(a0, a1, samples)
    return centre + radius * np.column_stack([np.cos(t), np.sin(t)])


@shared_parameters
def gost591_gap_wall(form: Gost591ToothForm, samples: int = 10) -> NDArray[np.float64]:
    """The left wall (x < 0) of a GOST 591-69 tooth gap in the seat frame.

    From the bottom of the seat up along the head arc (longer than needed; clipped later).

    Parameters
    ----------
    form : Gost591ToothForm
        The tooth profile (dimensions [m], angles [rad]).
    %(wall_returns)s

    References
    ----------
    [GOST591]; [Anuriev, vol. 2, ch. 5].
    """
    d1, a, b = form.roller_diameter, form.half_space_angle, form.joining_angle
    r, r1, r2, fc = form.seating_radius, form.joining_radius, form.head_radius, form.straight_part
    t = np.linspace(0.0, a, samples)
    seat = r * np.column_stack([-np.sin(t), -np.cos(t)])
    o1 = 0.8 * d1 * np.array([math.sin(a), math.cos(a)])
    t = np.linspace(a, a + b, samples)
    joint = o1 + r1 * np.column_stack([-np.sin(t), -np.cos(t)])
    p3 = joint[-1] + fc * np.array([-math.cos(a + b), math.sin(a + b)])
    o2 = 1.24 * d1 * np.array([-math.cos(math.pi / form.teeth), -math.sin(math.pi / form.teeth)])
    a0 = math.atan2(p3[1] - o2[1], p3[0] - o2[0])
    head = _arc(o2, r2, a0, a0 + math.radians(150), 3 * samples)
    wall: NDArray[np.float64] = np.vstack([seat, joint, head])
    return wall


#: ISO 606 root-diameter tolerance: upper deviation 0, lower deviation by the root diameter
#: d_f, as (d_f up to [mm], lower deviation [mm]); above the last row h11 [ISO606].
ISO606_ROOT_LOWER_DEVIATIONS_MM: tuple[tuple[float, float], ...] = ((127.0, -0.25), (250.0, -0.30))

#: Standard tolerance IT11 [µm] for nominal sizes (over, up to] [mm] from 250 mm, the sizes
#: ISO 606 tolerances by h11 [ISO286-1, Table 1].
IT11_UM: tuple[tuple[float, float, float], ...] = (
    (250, 315, 320), (315, 400, 360), (400, 500, 400), (500, 630, 440), (630, 800, 500),
    (800, 1000, 560), (1000, 1250, 660), (1250, 1600, 780), (1600, 2000, 920),
    (2000, 2500, 1100), (2500, 3150, 1350),
)


def iso606_root_diameter_tolerance(root_diameter: float) -> tuple[float, float, str]:
    """ISO 606 deviations of a sprocket's root diameter d_f = d − d1: upper deviation 0, lower
    deviation −0.25 mm up to d_f = 127 mm, −0.30 mm up to 250 mm, h11 above [ISO606].

    Above 3150 mm (the end of the IT11 table of ISO 286-1) the tolerance is the standard's
    formula 100·i with the tolerance unit i = 0.004·D + 2.1 µm at D = d_f.

    Parameters
    ----------
    root_diameter : float
        d_f [m].

    Returns
    -------
    tuple of (float, float, str)
        Upper and lower deviation [m] and the ISO 286 tolerance class ("h11", or "" where
        ISO 606 gives the deviations in millimetres).

    Raises
    ------
    DesignError
        ``root_diameter`` not positive.

    References
    ----------
    [ISO606]; [ISO286-1, Table 1] (IT11).
    """
    df_mm = root_diameter * 1e3
    if not df_mm > 0:
        raise DesignError("root_diameter", f"must be positive, got {root_diameter!r}")
    for up_to, lower in ISO606_ROOT_LOWER_DEVIATIONS_MM:
        if df_mm <= up_to:
            return 0.0, lower * 1e-3, ""
    it11 = next((t for _, up_to, t in IT11_UM if df_mm <= up_to),
                100.0 * (0.004 * df_mm + 2.1))
    return 0.0, -it11 * 1e-6, "h11"


def iso606_drawn_seating_radius(form: ToothForm) -> float:
    """The seating radius ri an ISO 606 outline is drawn with: the one that puts the root
    d − 2·ri in the middle of what both the root-diameter tolerance (d_f = d − d1, upper
    deviation 0, :func:`iso606_root_diameter_tolerance`) and the seating-radius limits
    ri,min … ri,max allow [ISO606].

    Both limits hold together when 0.01·d1 (ri,min = 0.505·d1 puts the root 0.01·d1 below
    d_f) is within the lower deviation, as for every chain up to a roller of 25 mm; for a
    larger roller the outline is drawn with ri,min, its root the closest to the tolerance.

    Parameters
    ----------
    form : ToothForm
        The tooth-form limits (dimensions [m]).

    Returns
    -------
    float
        ri [m], between ri,min and ri,max.

    References
    ----------
    [ISO606].
    """
    d = form.pitch_diameter
    _, lower, _ = iso606_root_diameter_tolerance(form.root_diameter)
    high = min(form.root_diameter, d - 2 * form.seating_radius_min)
    low = max(form.root_diameter + lower, d - 2 * form.seating_radius_max)
    root = 0.5 * (low + high) if low <= high else high
    return 0.5 * (d - root)


@shared_parameters
def iso606_gap_wall(form: ToothForm, samples: int = 10) -> NDArray[np.float64]:
    """The left wall of an ISO 606 tooth gap in the seat frame, between the two tooth-gap
    forms: the means of their flank radius and seating angle, the seating radius of
    :func:`iso606_drawn_seating_radius` (the root within its tolerance).

    Seating arc ri over half the seating angle, then the convex flank re tangent to it.

    Parameters
    ----------
    form : ToothForm
        The tooth-form limits (dimensions [m], angles [rad]).
    %(wall_returns)s

    References
    ----------
    [ISO606].
    """
    ri, re = iso606_drawn_seating_radius(form), form.flank_radius_mean
    half = 0.25 * (form.seating_angle_min + form.seating_angle_max)
    t = np.linspace(0.0, half, samples)
    seat = ri * np.column_stack([-np.sin(t), -np.cos(t)])
    d = np.array([-math.sin(half), -math.cos(half)])
    centre = (ri + re) * d
    a0 = math.atan2(-d[1], -d[0])
    sweep = math.radians(60)
    # the flank turns towards the tooth (away from the gap): pick the sense that rises
    sense = 1.0 if _arc(centre, re, a0, a0 + 1e-3, 2)[1, 1] > seat[-1, 1] else -1.0
    flank = _arc(centre, re, a0, a0 + sense * sweep, 4 * samples)
    wall: NDArray[np.float64] = np.vstack([seat, flank])
    return wall


def _clip_wall(wall: NDArray[np.float64], seat: NDArray[np.float64], u_r: NDArray[np.float64],
               tip_radius: float, half_pitch_angle: float) -> NDArray[np.float64]:
    """Wall points (global, centred on the sprocket) up to the tip circle or the tooth's
    bisector, with the crossing point interpolated."""
    u_t = np.array([-u_r[1], u_r[0]])
    pts: NDArray[np.float64] = seat + wall[:, :1] * u_t + wall[:, 1:] * u_r
    rel = np.arctan2(pts @ u_t, pts @ u_r)
    f = np.maximum(np.hypot(pts[:, 0], pts[:, 1]) / tip_radius - 1.0,
                   (np.abs(rel) - half_pitch_angle) / half_pitch_angle)
    out = np.flatnonzero(f >= 0)
    if out.size == 0:
        return pts
    k = int(out[0])
    if k == 0:
        return pts[:1]
    s = f[k - 1] / (f[k - 1] - f[k])
    return np.vstack([pts[:k], pts[k - 1] + s * (pts[k] - pts[k - 1])])


def sprocket_outline(wall: NDArray[np.float64], teeth: int, pitch_radius: float,
                     tip_radius: float) -> NDArray[np.float64]:
    """Closed outline of a toothed sprocket centred at the origin.

    Parameters
    ----------
    wall : numpy.ndarray
        (k, 2) left wall of one tooth gap in the seat frame [m].
    teeth : int
        Number of teeth z [-]; gap k is centred at the angle 2πk/z.
    pitch_radius : float
        R [m].
    tip_radius : float
        Radius of the tip circle [m].

    Returns
    -------
    numpy.ndarray
        (m, 2) points of the closed outline [m].
    """
    half = math.pi / teeth
    parts = []
    for k in range(teeth):
        th = TWO_PI * k / teeth
        u_r = np.array([math.cos(th), math.sin(th)])
        seat = pitch_radius * u_r
        left = _clip_wall(wall, seat, u_r, tip_radius, half)
        right = _clip_wall(wall * np.array([-1.0, 1.0]), seat, u_r, tip_radius, half)
        parts.append(np.vstack([left[::-1], right[1:]]))
        rel = math.remainder(math.atan2(right[-1, 1], right[-1, 0]) - th, TWO_PI)
        if np.hypot(*right[-1]) > 0.999 * tip_radius:
            # from this gap's right end to the next gap's left end (by symmetry)
            t = np.linspace(th + rel, th + 2 * half - rel, 5)[1:-1]
            parts.append(tip_radius * np.column_stack([np.cos(t), np.sin(t)]))
    outline: NDArray[np.float64] = np.vstack(parts)
    return outline


def tooth_form_of(drive: Drive, teeth: int) -> Gost591ToothForm | ToothForm:
    """The tooth form of a sprocket of a drive, by the drive's standard.

    Parameters
    ----------
    drive : Drive
        The design (chain and tooth form).
    teeth : int
        Number of teeth of the sprocket [-].

    Returns
    -------
    Gost591ToothForm or ToothForm
        The profile by GOST 591-69 or the ISO 606 limits.
    """
    spec = drive.chain.spec
    if drive.tooth_form == "GOST 591":
        return gost591_tooth_form(spec.pitch, teeth, spec.roller_diameter, spec.inner_width)
    return iso606_tooth_form(spec.pitch, teeth, spec.roller_diameter, spec.inner_width,
                             spec.strands)


def outline_of(form: Gost591ToothForm | ToothForm) -> NDArray[np.float64]:
    """Closed toothed outline of a sprocket with a tooth form.

    Parameters
    ----------
    form : Gost591ToothForm or ToothForm
        The tooth form (dimensions [m]).

    Returns
    -------
    numpy.ndarray
        (m, 2) outline centred at the origin [m].
    """
    if isinstance(form, Gost591ToothForm):
        return sprocket_outline(gost591_gap_wall(form), form.teeth, form.pitch_diameter / 2,
                                form.tip_diameter / 2)
    return sprocket_outline(iso606_gap_wall(form), form.teeth, form.pitch_diameter / 2,
                            form.tip_diameter_mean / 2)


@dataclass(frozen=True, slots=True, eq=False)
class SprocketProfile:
    """What a workshop needs of one sprocket.

    Parameters
    ----------
    name : str
        The sprocket.
    form : ToothForm | Gost591ToothForm
        Its tooth form by the drive's standard (dimensions [m]).
    outline : numpy.ndarray
        (k, 2) closed toothed outline centred at the origin [m].
    material : str
        Material name.
    polymeric : bool
        True for a polymer sprocket (its body has the rim–web–hub proportions).
    body : PolymericProportions | None
        The polymeric body's proportions [m] (None for a metal plate sprocket).
    mass : SprocketMassProperties
        Mass [kg] and moment of inertia [kg·m²] of the body.
    density : float
        Density of the material [kg/m³].
    standard : str
        The tooth-form standard ("ISO 606" or "GOST 591").
    bore_diameter : float
        Bore [m]: the polymeric body's, else 0.19·z·p/π [MultimassChainDrives, §3.4].
    hub_limit_diameter : float
        The largest hub the chain's inner plates clear [m] (:func:`hub_limit_diameter`).
    root_deviations : tuple of float
        Upper and lower deviation of the root diameter [m] by the tooth-form standard
        (ISO 606: :func:`iso606_root_diameter_tolerance`; (0, 0): not compiled, GOST 591).
    root_tolerance_class : str
        The ISO 286 class of those deviations ("h11"), or "" when the standard gives them in
        millimetres or they are not compiled.
    """

    name: str
    form: ToothForm | Gost591ToothForm
    outline: NDArray[np.float64]
    material: str
    polymeric: bool
    body: PolymericProportions | None
    mass: SprocketMassProperties
    density: float
    standard: str = "ISO 606"
    bore_diameter: float = 0.0
    hub_limit_diameter: float = 0.0
    root_deviations: tuple[float, float] = (0.0, 0.0)
    root_tolerance_class: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the tooth form in mm and degrees)."""
        return {"name": self.name, "tooth_form": self.form.to_dict(),
                "material": self.material, "polymeric": self.polymeric,
                "body": None if self.body is None else self.body.to_dict(),
                "mass": self.mass.to_dict()}


#: Bore of a metal sprocket's body, as a fraction of z·p/π (the proportion of the polymeric
#: bodies) [MultimassChainDrives, §3.4].
BORE_RATIO = 0.19


@shared_parameters
def sprocket_profiles(drive: Drive) -> tuple[SprocketProfile, ...]:
    """The profile of every sprocket of a drive.

    %(drive_returns)s
    tuple of SprocketProfile
        In contour order.
    """
    spec = drive.chain.spec
    out = []
    for i, s in enumerate(drive.sprockets):
        form = tooth_form_of(drive, s.teeth)
        mat = find_material(s.material, field=f"sprockets[{i}].material")
        body = (polymeric_sprocket_proportions(spec.pitch, s.teeth, spec.inner_width)
                if mat.is_polymer else None)
        mass = sprocket_body(spec, s.teeth, mat)
        bore = (body.bore_diameter if body is not None
                else BORE_RATIO * s.teeth * spec.pitch / math.pi)
        gost = isinstance(form, Gost591ToothForm)
        upper, lower, grade = ((0.0, 0.0, "") if gost
                               else iso606_root_diameter_tolerance(form.root_diameter))
        out.append(SprocketProfile(
            s.name, form, outline_of(form), mat.name, mat.is_polymer, body, mass, mat.density,
            "GOST 591" if gost else "ISO 606", bore,
            hub_limit_diameter(spec.pitch, s.teeth, spec.plate_depth), (upper, lower), grade))
    return tuple(out)


@shared_parameters
def hub_limit_diameter(pitch: float, teeth: int, plate_depth: float) -> float:
    """ISO 606 absolute maximum shroud (hub) diameter d_g [m]: the largest hub that the inner
    plates of the chain clear, d_g = p·cot(180°/z) − 1.04·h₂ − 0.76 mm [ISO606].

    Parameters
    ----------
    %(pitch)s
    teeth : int
        Number of teeth z.
    plate_depth : float
        Inner plate depth h₂ (maximum) [m].

    Returns
    -------
    float
        d_g [m].

    References
    ----------
    [ISO606]
    """
    return pitch / math.tan(math.pi / teeth) - 1.04 * plate_depth - 0.76e-3

