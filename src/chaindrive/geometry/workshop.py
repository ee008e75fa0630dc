"""What a workshop drawing of a sprocket states beyond its tooth outline (SI: metres).

* the bore with its hole-basis fit (ISO 286: H6, H7, H8) and the hub keyway of the
  parallel key for that bore (DIN 6885-1 = ISO/R 773 = GOST 23360: width b with JS9, depth t2
  and its tolerance, dimensioned as d + t2) — :func:`bore_deviations`, :func:`hub_keyway`;
* the measurement over pins M_R of ISO 606 — :func:`measurement_over_pins`;
* the tip diameter chosen inside the ISO 606 range — :func:`chosen_tip_diameter`;
* the tooth chamfer of the axial section (ISO 606 side relief and side radius; GOST 591
  side radius r3 = 1.7 d1 about centres h3 = 0.8 d1 below the tip) —
  :func:`iso606_chamfer`, :func:`gost591_chamfer`;
* the hub (the proportions of the body model) — :func:`hub_proportions`.

Tables: ``chaindrive/data/keyways_iso286.toml`` (sources in its header).
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass
from importlib import resources
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.geometry.profile import IT11_UM, SprocketProfile
from chaindrive.geometry.sprocket import Gost591ToothForm, ToothForm
from chaindrive.model import BORE_FITS, Drive

__all__ = ["BORE_FITS", "HUB_DIAMETER_RATIO", "HUB_LENGTH_RATIO", "Keyway", "SprocketWorkshop",
           "bore_deviations", "chosen_tip_diameter", "gost591_chamfer", "hub_keyway",
           "hub_proportions", "iso286_tolerance", "iso606_chamfer", "measurement_over_pins",
           "sprocket_workshop"]

MM = 1e-3  # millimetres → metres
#: Hub outer diameter and length of the body model: 0.33·D and 3·b with the bore 0.19·D
#: [MultimassChainDrives, §3.4], so the hub is 0.33/0.19 of the bore.
HUB_DIAMETER_RATIO = 0.33 / 0.19
HUB_LENGTH_RATIO = 3.0


@functools.cache
def _tables() -> dict[str, Any]:
    text = resources.files("chaindrive").joinpath("data/keyways_iso286.toml").read_bytes()
    return tomllib.loads(text.decode("utf-8"))


def iso286_tolerance(size: float, grade: int, field: str = "bore") -> float:
    """Standard tolerance IT of a nominal size [ISO286-1, Table 1]; IT11 also above 500 mm
    (the rows to 3150 mm and beyond the standard's 100·i, i = 0.004·D + 2.1 µm, as the root
    diameter's h11 of :func:`chaindrive.geometry.profile.iso606_root_diameter_tolerance`).

    Parameters
    ----------
    size : float
        Nominal size [m], over 0 up to 500 mm (any size for IT11).
    grade : int
        6 to 11.
    field : str
        The design field the size comes from, for the message.

    Returns
    -------
    float
        IT [m].

    Raises
    ------
    DesignError
        A size outside the table.

    References
    ----------
    [ISO286-1, Table 1].
    """
    table = _tables()["it"]
    column = table["columns"].index(f"IT{grade}")
    mm = size / MM
    for row in table["rows"]:
        if row[0] < mm <= row[1]:
            return float(row[column]) * 1e-6
    if grade == 11 and mm > 500:
        return next((t for _, up_to, t in IT11_UM if mm <= up_to),
                    100.0 * (0.004 * mm + 2.1)) * 1e-6
    raise DesignError(field, f"must be over 0 and at most 500 mm for the ISO 286 tolerance "
                             f"table, got {mm:.1f} mm")


def bore_deviations(bore: float, fit: str) -> tuple[float, float]:
    """Upper and lower deviation of a bore with a hole-basis fit: ES = IT, EI = 0.

    Parameters
    ----------
    bore : float
        Bore diameter [m].
    fit : str
        One of :data:`BORE_FITS`.

    Returns
    -------
    tuple of float
        (ES, EI) [m].

    References
    ----------
    [ISO286-1, Tables 1 and 3] (fundamental deviation H: EI = 0).
    """
    if fit not in BORE_FITS:
        raise DesignError("bore_fit", f"must be one of {', '.join(BORE_FITS)}, got {fit!r}")
    return iso286_tolerance(bore, int(fit[1:])), 0.0


@dataclass(frozen=True, slots=True)
class Keyway:
    """The hub keyway of a bore for a parallel key [DIN6885-1] (lengths [m]).

    Parameters
    ----------
    key_width, key_height : float
        The key b × h [m].
    hub_depth : float
        t2, from the bore surface [m].
    depth_upper : float
        Upper deviation of t2 (lower 0) [m].
    width_upper, width_lower : float
        Deviations of the keyway width (JS9: ±IT9/2) [m].
    over_bore : float
        The depth as dimensioned, d + t2 (from the far side of the bore) [m].
    """

    key_width: float
    key_height: float
    hub_depth: float
    depth_upper: float
    width_upper: float
    width_lower: float
    over_bore: float


def hub_keyway(bore: float) -> Keyway:
    """The hub keyway of the DIN 6885-1 parallel key for a bore: width b (JS9, normal
    fit), depth t2 with its tolerance, and d + t2.

    Parameters
    ----------
    bore : float
        Bore (shaft) diameter d [m], over 6 mm and up to 230 mm.

    Returns
    -------
    Keyway
        The keyway.

    Raises
    ------
    DesignError
        A bore outside the table.

    References
    ----------
    [DIN6885-1] (= ISO/R 773, [GOST23360]); [ISO286-1, Table 1] (IT9 of JS9).
    """
    table = _tables()["keyway"]
    mm = bore / MM
    row = next((r for r in table["rows"] if r[0] < mm <= r[1]), None)
    if row is None:
        first, last = table["rows"][0][0], table["rows"][-1][1]
        raise DesignError("keyway", f"the key table runs over {first} up to {last} mm of bore, "
                                    f"got {mm:.1f} mm; give a bore in that range or "
                                    "keyway = false")
    _, _, b, h, _, t2 = row
    depth_upper = next(t for up_to, t in table["depth_tolerance"] if mm <= up_to)
    it9 = iso286_tolerance(b * MM, 9, "keyway")
    return Keyway(b * MM, h * MM, t2 * MM, depth_upper * MM, it9 / 2, -it9 / 2,
                  bore + t2 * MM)


def measurement_over_pins(pitch_diameter: float, teeth: int, pin_diameter: float) -> float:
    """Measurement over pins M_R of a sprocket: two pins of the roller diameter in opposite
    tooth gaps, their centres on the pitch circle: M_R = d + d_R for an even number of teeth,
    M_R = d·cos(90°/z) + d_R for an odd number (the gaps nearest to opposite).

    Parameters
    ----------
    pitch_diameter : float
        d [m].
    teeth : int
        z [-].
    pin_diameter : float
        d_R = d1, the roller diameter [m].

    Returns
    -------
    float
        M_R [m].

    References
    ----------
    [ISO606] (measuring pins d_R = d1); the closed form of the pins' centres on the pitch
    circle, 180° apart for even z and 180° − 180°/z for odd z.
    """
    chord = pitch_diameter if teeth % 2 == 0 else pitch_diameter * math.cos(math.pi / (2 * teeth))
    return chord + pin_diameter


def chosen_tip_diameter(tip_min: float, tip_max: float) -> tuple[float, float, float]:
    """The tip diameter a drawing gives inside the ISO 606 range d_a,min … d_a,max: the mean
    of the range (what the outline is drawn with) rounded down to 0.1 mm, toleranced h11
    (upper deviation 0, lower −IT11); both limits lie inside the range.

    Parameters
    ----------
    tip_min, tip_max : float
        d_a,min and d_a,max [m].

    Returns
    -------
    tuple of float
        (d_a, upper deviation 0, lower deviation −IT11) [m].

    Raises
    ------
    DesignError
        The h11 band does not fit the range (a range narrower than IT11).

    References
    ----------
    [ISO606] (the range); [ISO286-1, Table 1] (IT11).
    """
    da = math.floor((tip_min + tip_max) / 2 / (0.1 * MM) + 1e-9) * 0.1 * MM
    it11 = iso286_tolerance(da, 11, "tip_diameter")
    if da - it11 < tip_min or da > tip_max:
        raise DesignError("tip_diameter", f"h11 of {da / MM:.1f} mm does not fit the ISO 606 "
                                          f"range {tip_min / MM:.2f} … {tip_max / MM:.2f} mm")
    return da, 0.0, -it11


@shared_parameters
def iso606_chamfer(pitch: float) -> tuple[float, float, float]:
    """ISO 606 tooth chamfer of the axial section: side relief b_a (the mean of
    0.10·p … 0.15·p), side radius r_x = p, and the radial depth of the chamfer when the arc
    r_x is tangent to the tooth side and takes b_a off it at the tip:
    h = √(r_x² − (r_x − b_a)²).

    %(pitch_p_returns)s
    tuple of float
        (b_a, r_x, h) [m].

    References
    ----------
    [ISO606] (b_a, r_x); the depth is the closed form of the tangent arc.
    """
    ba, rx = 0.125 * pitch, pitch
    return ba, rx, math.sqrt(rx * rx - (rx - ba) ** 2)


def gost591_chamfer(roller_diameter: float) -> tuple[float, float, float]:
    """GOST 591 tooth chamfer of the axial section: side radius r3 = 1.7·d1 about centres
    h3 = 0.8·d1 below the tip, tangent to the tooth side; it takes
    f = r3 − √(r3² − h3²) = 0.2·d1 off the side at the tip.

    Parameters
    ----------
    roller_diameter : float
        d1 [m].

    Returns
    -------
    tuple of float
        (f, r3, h3) [m].

    References
    ----------
    [GOST591] (r3, h3, as compiled in the project's tooth-form notes §1.4).
    """
    r3, h3 = 1.7 * roller_diameter, 0.8 * roller_diameter
    return r3 - math.sqrt(r3 * r3 - h3 * h3), r3, h3


def hub_proportions(bore: float, rim_width: float, hub_limit: float) -> tuple[float, float]:
    """Hub outer diameter and length: 0.33/0.19 of the bore and 3 rim widths, the proportions
    of the body model, the diameter at most the ISO 606 hub limit d_g.

    Parameters
    ----------
    bore : float
        d [m].
    rim_width : float
        b, the sprocket's face width [m].
    hub_limit : float
        d_g [m].

    Returns
    -------
    tuple of float
        (hub diameter, hub length) [m].

    References
    ----------
    [MultimassChainDrives, §3.4] (hub 0.33·D, bore 0.19·D, hub length 3·b); [ISO606] (d_g).
    """
    return min(HUB_DIAMETER_RATIO * bore, hub_limit), HUB_LENGTH_RATIO * rim_width


@dataclass(frozen=True, slots=True)
class SprocketWorkshop:
    """What the drawing of one sprocket states besides its outline (lengths [m]).

    Parameters
    ----------
    name : str
        The sprocket.
    teeth : int
        z [-].
    standard : str
        "ISO 606" or "GOST 591".
    bore : float
        d [m].
    bore_given : bool
        True when the design gives the bore (else the body model's 0.19·z·p/π).
    bore_fit : str
        Its ISO 286 class ("H7").
    bore_upper, bore_lower : float
        Its deviations [m].
    keyway : Keyway or None
        The hub keyway (None: no keyway, by the design's choice).
    hub_diameter, hub_length, hub_limit : float
        The hub and the largest hub the chain clears (d_g) [m].
    face_width : float
        Tooth width of one strand (ISO 606 b_f1, GOST 591 b) [m].
    overall_width : float
        Width of the toothed rim over all strands [m].
    strands : int
        Chain strands [-].
    transverse_pitch : float
        Between strands [m].
    chamfer_width, chamfer_radius, chamfer_depth : float
        The tooth chamfer: taken off each side at the tip, its radius, its radial depth [m].
    tip_diameter, tip_upper, tip_lower : float
        Tip diameter as dimensioned and its deviations (GOST 591: no deviations compiled)
        [m].
    tip_min, tip_max : float
        The standard's range (GOST 591: both the tip diameter) [m].
    pins_measurement : float
        M_R [m].
    pins_upper, pins_lower : float
        Its deviations (those of the root diameter) [m].
    pin_diameter : float
        d_R [m].
    material : str
        Material (design).
    hardening : str or None
        Heat treatment note (design; None: not given).
    """

    name: str
    teeth: int
    standard: str
    bore: float
    bore_given: bool
    bore_fit: str
    bore_upper: float
    bore_lower: float
    keyway: Keyway | None
    hub_diameter: float
    hub_length: float
    hub_limit: float
    face_width: float
    overall_width: float
    strands: int
    transverse_pitch: float
    chamfer_width: float
    chamfer_radius: float
    chamfer_depth: float
    tip_diameter: float
    tip_upper: float
    tip_lower: float
    tip_min: float
    tip_max: float
    pins_measurement: float
    pins_upper: float
    pins_lower: float
    pin_diameter: float
    material: str
    hardening: str | None


def sprocket_workshop(drive: Drive, profile: SprocketProfile, index: int) -> SprocketWorkshop:
    """Everything the drawing of sprocket ``index`` states besides its outline.

    Parameters
    ----------
    drive : Drive
        The design as analysed (its chain and sprockets).
    profile : SprocketProfile
        The sprocket's profile (tooth form, bore and hub limit).
    index : int
        The sprocket.

    Returns
    -------
    SprocketWorkshop
        The data of the drawing.

    Raises
    ------
    DesignError
        A bore the sprocket cannot take (no hub wall inside d_g), a bore outside the tables.

    References
    ----------
    [ISO606]; [GOST591]; [DIN6885-1]; [ISO286-1]; [MultimassChainDrives, §3.4].
    """
    s, spec = drive.sprockets[index], drive.chain.spec
    where = f"sprockets[{index}]"
    bore = s.bore if s.bore is not None else profile.bore_diameter
    fit = s.bore_fit
    upper, lower = bore_deviations(bore, fit)
    keyway = hub_keyway(bore) if s.keyway else None
    form = profile.form
    if isinstance(form, Gost591ToothForm):
        face = form.rim_width
        chamfer, radius, depth = gost591_chamfer(spec.roller_diameter)
        tip = (form.tip_diameter, 0.0, 0.0)
        tip_range = (form.tip_diameter, form.tip_diameter)
        pins_dev = (0.0, 0.0)
    else:
        iso = form if isinstance(form, ToothForm) else None
        assert iso is not None
        face = iso.tooth_width
        chamfer, radius, depth = iso606_chamfer(spec.pitch)
        tip = chosen_tip_diameter(iso.tip_diameter_min, iso.tip_diameter_max)
        tip_range = (iso.tip_diameter_min, iso.tip_diameter_max)
        pins_dev = profile.root_deviations
    overall = spec.transverse_pitch * (spec.strands - 1) + face
    hub, hub_length = hub_proportions(bore, overall, profile.hub_limit_diameter)
    wall = bore + 2 * (keyway.hub_depth if keyway else 0.0)
    if not wall < hub:
        raise DesignError(f"{where}.bore", f"{bore / MM:.1f} mm leaves no hub wall inside the "
                                           f"largest hub the chain clears, d_g = "
                                           f"{profile.hub_limit_diameter / MM:.1f} mm; allowed: "
                                           "a bore (with its keyway) below it")
    return SprocketWorkshop(
        name=s.name, teeth=s.teeth, standard=profile.standard, bore=bore,
        bore_given=s.bore is not None, bore_fit=fit, bore_upper=upper, bore_lower=lower,
        keyway=keyway, hub_diameter=hub, hub_length=max(hub_length, overall),
        hub_limit=profile.hub_limit_diameter, face_width=face, overall_width=overall,
        strands=spec.strands, transverse_pitch=spec.transverse_pitch, chamfer_width=chamfer,
        chamfer_radius=radius, chamfer_depth=depth, tip_diameter=tip[0], tip_upper=tip[1],
        tip_lower=tip[2], tip_min=tip_range[0], tip_max=tip_range[1],
        pins_measurement=measurement_over_pins(form.pitch_diameter, s.teeth,
                                               spec.roller_diameter),
        pins_upper=pins_dev[0], pins_lower=pins_dev[1], pin_diameter=spec.roller_diameter,
        material=profile.material, hardening=s.hardening)
