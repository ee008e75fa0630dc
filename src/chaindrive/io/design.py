"""Design files: TOML ↔ :class:`~chaindrive.model.Drive`, and the schema of every field.

Every dimensional value in a design file is a string with a unit (``"25.4 mm"``,
``"300 rpm"``), parsed with pint here and nowhere else; inside the package everything is SI.
A mistake gives one :class:`~chaindrive.errors.DesignError` line that names the field,
the value and what is allowed.
"""

from __future__ import annotations

import math
import re
import sys
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w

from chaindrive import catalog
from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.geometry.contour import in_travel_order
from chaindrive.io.limits import MAX_DESIGN_BYTES, check_file_size, shown_key
from chaindrive.io.plausible import check_inertias, check_motor_estimate
from chaindrive.model import (
    BORE_FITS,
    DRIVEN_DUTIES,
    DRIVER_DUTIES,
    LOAD_LAWS,
    MAX_CONTOURS,
    MAX_SPROCKETS,
    MAX_TEETH,
    MAX_TRAIN_ELEMENTS,
    MIN_SPROCKETS,
    MIN_TEETH,
    MOTORS,
    RESISTANCES,
    ROLES,
    ROTATIONS,
    ROUNDINGS,
    SIDES,
    TOOTH_FORMS,
    TRAIN_KINDS,
    Chain,
    ChainRequest,
    ChainSpec,
    Drive,
    DynamicsSettings,
    Motor,
    Sprocket,
    ToothFormName,
    TrainElement,
)
from chaindrive.strength.duty import DRIVEN_EXAMPLES, DRIVER_EXAMPLES
from chaindrive.units import (
    DEG_PER_RAD,
    DIMENSIONS,
    MAX_TEXT,
    RAD_S_PER_RPM,
    RPM_PER_RAD_S,
    TWO_PI,
    parse_quantity,
    shown,
)

#: Largest bore of the DIN 6885-1 key table [m] (chaindrive/data/keyways_iso286.toml).
KEYWAY_MAX_BORE = 0.230
#: The smallest positive normal double (2.2e-308): a number nearer zero than this (a
#: subnormal, down to 5e-324) keeps only some of its digits and overflows when divided into
#: anything; no measured quantity in SI is so small, so every field refuses it.
SMALLEST_NORMAL = sys.float_info.min
#: Longest name or other text field [characters].
MAX_NAME = 200
#: The byte-order mark (U+FEFF) some editors put at the start of a UTF-8 file; a design file
#: is read without it (TOML itself does not allow it).
BOM = "\ufeff"


@dataclass(frozen=True, slots=True)
class Field:
    """One field of a design file: its kind, unit, default, allowed range and meaning.

    Parameters
    ----------
    name : str
        The key in its table.
    kind : str
        A dimension of :data:`chaindrive.units.DIMENSIONS` (the value is a string with a
        unit), or ``"int"``, ``"float"``, ``"str"``, ``"bool"``, ``"choice"``, ``"links"``
        (a whole number or a rounding rule of :data:`chaindrive.model.ROUNDINGS`).
    description : str
        What it means.
    required : bool
        True when a design must give it.
    default : object
        The value when it is left out (SI for a quantity).
    minimum, maximum : float | None
        The bounds of what is physically plausible [SI unit of the field]
        (:mod:`chaindrive.io.limits`).
    choices : tuple of str
        The allowed values of a ``"choice"``.
    exclusive_minimum : bool
        True when ``minimum`` itself is not allowed.
    reason : str
        Where the bounds come from (printed by ``chaindrive schema``).
    example : str
        A value that fits the field, as written in a design file (e.g. ``"25.4 mm"``);
        empty: the example of its dimension when that lies within the bounds, else one
        made from the bounds (:meth:`example_text`).
    smallest : float
        The smallest magnitude other than zero that means something [SI unit of the field]:
        zero is allowed (``minimum`` 0) and means "none", but a value between zero and this
        is refused (an undamped ring is 0, a damping ratio of 5e-324 is a slip). 0: every
        value within the bounds.
    """

    name: str
    kind: str
    description: str
    required: bool = False
    default: Any = None
    minimum: float | None = None
    maximum: float | None = None
    choices: tuple[str, ...] = ()
    exclusive_minimum: bool = False
    reason: str = ""
    example: str = ""
    smallest: float = 0.0

    def example_text(self) -> str:
        """An example value that fits this field.

        Returns
        -------
        str
            The field's own example; else, for a quantity, its dimension's example
            (:data:`chaindrive.units.DIMENSIONS`) when that lies within the field's bounds,
            or else a value made from the bounds (:meth:`_example_in_range`); empty for a
            field of another kind without an example.
        """
        if self.example or self.kind not in DIMENSIONS:
            return self.example
        generic = DIMENSIONS[self.kind][2]
        if self.fits(parse_quantity(generic, self.kind, self.name)):
            return generic
        return self._example_in_range()

    def fits(self, value: float) -> bool:
        """True when ``value`` [SI unit of the field] is finite and within its bounds.

        Parameters
        ----------
        value : float
            The value [SI unit of the field].

        Returns
        -------
        bool
        """
        if not math.isfinite(value) or 0.0 < abs(value) < max(self.smallest, SMALLEST_NORMAL):
            return False
        if self.minimum is not None and (value <= self.minimum if self.exclusive_minimum
                                         else value < self.minimum):
            return False
        return self.maximum is None or value <= self.maximum

    def _example_in_range(self) -> str:
        """An example of a quantity field made from its bounds: its default, else a value
        of one significant digit between the bounds (their geometric mean, or a tenth of
        the upper bound above a lower bound of zero), in the unit its range is written in
        (:data:`DISPLAY_UNITS`; else the SI unit)."""
        unit, factor = DISPLAY_UNITS.get(self.kind, (DIMENSIONS[self.kind][1], 1.0))
        lo, hi = self.minimum, self.maximum
        candidates: list[float] = []
        if isinstance(self.default, int | float) and not isinstance(self.default, bool):
            candidates.append(float(self.default))
        if lo is not None and hi is not None:
            candidates.append(math.sqrt(lo * hi) if lo > 0.0 else hi / 10.0)
        elif hi is not None:
            candidates.append(hi / 10.0 if hi > 0.0 else hi)
        elif lo is not None:
            candidates.append(10.0 * lo if lo > 0.0 else lo + 1.0)
        candidates += [x for x in (hi, lo) if x is not None]
        # the roundest text first (one significant digit); a zero last, as it shows no typical value
        texts = [f"{float(f'{si * factor:.{digits}g}'):g} {unit}"
                 for digits in (1, 3, 12) for si in candidates]
        texts.sort(key=lambda t: t.startswith(("0 ", "-0 ")))
        for text in texts:
            if self.fits(parse_quantity(text, self.kind, self.name)):
                return text
        raise ValueError(f"no example fits the field {self.name!r}: give it one")

    def allowed(self) -> str:
        """Human description of the allowed values."""
        if self.kind == "choice":
            return "one of " + ", ".join(f'"{c}"' for c in self.choices)
        if self.kind == "bool":
            return "true or false"
        if self.kind == "str":
            return "text"
        if self.kind == "tables":
            return "a list of tables"
        unit, factor = DISPLAY_UNITS.get(self.kind, ("", 1.0))
        tail = f" {unit}" if unit else ""
        whole = self.kind in ("int", "links")

        def bound(value: float) -> str:
            """A bound as written: a whole number in full (1048576, not 1.04858e+06)."""
            return str(int(value)) if whole and float(value).is_integer() else f"{value * factor:g}"

        lo = "" if self.minimum is None else (
            f"{'>' if self.exclusive_minimum else '≥'} {bound(self.minimum)}{tail}")
        hi = "" if self.maximum is None else f"≤ {bound(self.maximum)}{tail}"
        if self.smallest > 0.0:
            lo = f"0, or ≥ {bound(self.smallest)}{tail}"
        span = " and ".join(x for x in (lo, hi) if x)
        if whole:
            if self.minimum is not None and self.maximum is not None:
                number = f"a whole number from {bound(self.minimum)} to {bound(self.maximum)}"
            else:
                number = "a whole number" + (f" {span}" if span else "")
            return number + (', "round up" or "round down"' if self.kind == "links" else "")
        if self.kind == "float":
            return "a number" + (f" {span}" if span else "")
        noun = self.kind.replace("_", " ")
        article = "an" if noun[0] in "aeiou" else "a"
        return (f'{article} {noun} with a unit such as "{self.example_text()}"'
                + (f", {span}" if span else ""))


#: The unit the allowed range of a quantity is written in: dimension → (unit, SI → unit).
DISPLAY_UNITS: dict[str, tuple[str, float]] = {
    "length": ("mm", 1e3), "speed": ("rpm", RPM_PER_RAD_S), "power": ("kW", 1e-3),
    "inertia": ("kg·m²", 1.0), "time": ("s", 1.0), "angle": ("deg", DEG_PER_RAD),
}
_POWER = ("1 W to 20 MW: the largest catalogue chain (4 strands of 114.3 mm pitch) carries "
          "about 10 MW at its best speed by the ACA ratings [Shigley2015, eq. 17-32/17-33]")
_SPEED = ("1 to 30 000 rev/min: slower, the start-up and the sweep cover hours of motion; "
          "faster, the tooth frequency of a large sprocket passes 10 kHz, beyond a model of "
          "the chain as springs and masses")
_XY = ("within 100 m of the origin: [ISO10823] centre distances are 30 to 80 pitches, 9 m "
       "at the largest pitch; conveyor layouts stay within some tens of metres")
_INERTIA = ("1e-8 to 1e6 kg·m²: from the smallest catalogue sprocket (6 teeth of 8 mm pitch "
            "in UHMW-PE, 1.7e-8 kg·m²) to a 50 t flywheel of 6 m radius; at least a tenth of "
            "the sprocket's own plate (chaindrive.io.plausible.check_inertias)")
_REDUCED_MASS = ("0.1 g to 1000 t at the pitch radius: the inertia's range (above) over the "
                 "pitch radii of the catalogue's sprockets")
_TORSIONAL_STIFFNESS = ("1 N·m/rad to 1e10 N·m/rad: from a soft elastic coupling of a "
                        "fractional-kW drive to a 0.5 m solid steel shaft 0.1 m long "
                        "(k = G·π·d⁴/32/L [Roark2012, Table 10.1])")
_TORSIONAL_DAMPING = ("at most 2e8 N·m·s/rad: critical damping 2√(kJ) of the stiffest shaft "
                      "on the heaviest rotor allowed")
_SHAFT = "2 mm to 2 m across, 5 mm to 50 m long: shafts of chain drives and line shafts"
_GEAR_RATIO = ("0.01 to 1000: a stage or a whole reducer either way (worm and planetary "
               "reducers reach some hundreds)")
_ROTOR = ("1e-6 to 1e5 kg·m²: from a 10 W micro-motor to the rotor of a 20 MW machine "
          "(the rotor inertias of [MotiveDelphi] grow about as P^1.3)")
_BREAKDOWN = ("above 1 (a motor that could not carry its rated torque) and at most 5 "
              "([IEC60034-12] design N breakdown torques are 1.6 to about 3.5 times rated)")
_TORQUE = "1 mN·m to 10 MN·m: the rated torques of the power and speed limits above"
#: The smallest critical slip of the Kloss law: a slip of 0 (or a subnormal one) divides the
#: torque by zero.
MIN_CRITICAL_SLIP = 1e-3
_CRITICAL_SLIP = ("a slip, a share of the synchronous speed: at most 1; induction motors "
                  "break down at slips of some per cent, the largest at about 1 %, and below "
                  "0.1 % the Kloss torque would be a step at the synchronous speed")
_RUNOUT = ("at most 10 mm: sprocket run-out tolerances are fractions of a millimetre; 10 mm "
           "is the eccentricity of a sprocket bored off-centre by a whole pitch of 05B")
DRIVE_FIELDS: tuple[Field, ...] = (
    Field("name", "str", "name of the drive", required=True),
    Field("power", "power", "power transmitted from the driver", minimum=1.0, maximum=20e6,
          reason=_POWER),
    Field("tooth_form", "choice", "sprocket tooth form (default: GOST 591 for GOST chains, "
          "ISO 606 otherwise)", choices=TOOTH_FORMS),
    Field("service_factor", "float", "service (application) factor of the drive; overrides "
          "the duty classes driver / driven (neither given: 1.0, said as a warning)",
          minimum=1.0, maximum=5.0, reason="published application factors run from 1 to about "
          "2.5; 5 is twice the largest"),
    Field("driver", "choice", "duty class of the driver (prime mover), with driven it gives "
          "the service factor from the table of the chain's rating method "
          "(chaindrive.strength.duty): " + "; ".join(
              f"{k}: {v}" for k, v in DRIVER_EXAMPLES.items()),
          choices=DRIVER_DUTIES, example="smooth"),
    Field("driven", "choice", "duty class of the driven machine: " + "; ".join(
              f"{k}: {v}" for k, v in DRIVEN_EXAMPLES.items()),
          choices=DRIVEN_DUTIES, example="moderate shock"),
    Field("required_life", "time", "required wear life of the chain, read by the wear-life "
          "check (default: the rating method's basis, 15 000 h × links/100)", minimum=3600.0,
          maximum=1e6 * 3600.0, example="20000 h",
          reason="1 h to 1 000 000 h (114 years of continuous running)"),
    Field("rotation", "choice", "direction of rotation of the driver on the drawing plane "
          "(x right, y up): cw or ccw; the chain runs round the sprockets in the order that "
          "agrees with it and the span the driver pulls in is the tight one (default: the "
          "order of the sprockets decides, said in the output)", choices=ROTATIONS,
          example="ccw"),
)
CHAIN_FIELDS: tuple[Field, ...] = (
    Field("designation", "str", 'catalogue designation, e.g. "ISO 606 16B-1", "ANSI 80", '
          '"GOST 13568 ПР-25,4-60"'),
    Field("standard", "choice", "chain standard, used with pitch when no designation is given "
          "(with a designation it must agree with it)",
          choices=("ISO 606", "ANSI", "GOST 13568", "polymer")),
    Field("series", "choice", "series: ISO 606 A or B, ANSI heavy H (with a designation it "
          "must agree with it)", choices=("A", "B", "H")),
    Field("pitch", "length", "chain pitch, used with standard when no designation is given "
          "(with a designation it must agree with it)", minimum=0.005, maximum=0.2,
          reason="5 to 200 mm: the pitches of [ISO606] chains run from 8 to 114.3 mm"),
    Field("strands", "int", "number of strands (rows)", default=1, minimum=1, maximum=8,
          reason="multi-strand chains are made with up to 8 strands; the catalogue lists 1 to 4"),
    Field("links", "links", 'impose the number of links (the take-up fits it), or how the '
          'tight length is rounded to an even count: "round up" (default), "round down" or '
          '"nearest" (the nearer even count, up on a tie)',
          minimum=4, maximum=10000, reason="4: the shortest closed chain round two sprockets; "
          "10 000: beyond the longest drive chains (80 m at 8 mm pitch)"),
    Field("sag", "float", "installed sag of the slack span as a fraction of its length "
          "(default: the take-up lays the chain out tight, and the span tensions and the "
          "dynamics assume a sag of 2 %)", minimum=0.001, maximum=0.1,
          reason="0.1 % to 10 % of the span: chains are installed with a sag of about 1 to "
          "3 % (a total mid-span movement of 2 to 6 % of the centre distance "
          "[DiamondChainTension]); 0.1 %, a tenth of the tightest, is a chain laid out taut, "
          "whose sag tension F₀ = q·g·a/(8s) would pass 125 times the weight of the span; at "
          "most 10 %: the shallow-sag (parabolic) catenary [Irvine1981]"),
    Field("sag_allowance", "float", "installed centre distance shortened by this fraction of "
          "the centre distance of the adjustable sprocket (to the driver) so that the slack "
          "span sags, e.g. 0.003 for 0.3 % (default: none; not with sag)", minimum=0.0,
          maximum=0.01, exclusive_minimum=True, example="0.003",
          reason="textbooks shorten it by 0.2 to 0.4 % [ChainDesignRU, §7] (0.2 % "
          "[Bhandari2010, ex. 14.4]); 1 % is 2.5 times the largest"),
    Field("link_stiffness", "stiffness", "measured axial stiffness of one link (one pitch) of "
          "the whole chain, all strands, e.g. F/(ε·p) from the maker's elastic-elongation "
          "curve (default: computed from the plates and the pin, the contact of pin, bush "
          "and roller left out)", minimum=1e5, maximum=1e11, example="1.7e8 N/m",
          reason="1e5 N/m: a twentieth of the softest catalogue chain's computed value "
          "(POM 06B-1, 2.6e6 N/m); 1e11 N/m: ten times the stiffest (48B-4, 7.9e9 N/m)"),
    Field("allow_odd", "bool", "allow an odd number of links (needs an offset link)",
          default=False),
    Field("contours", "int", "identical chain contours side by side on common shafts "
          "[Lyashuk]", default=1, minimum=1, maximum=MAX_CONTOURS,
          reason="the load-sharing model of [Lyashuk] for up to 8 contours"),
    Field("catalog", "str", "a catalogue file of your own (CSV or TOML), relative to the "
          "design (on the web page: the name of a catalogue uploaded in the session)"),
)
SPROCKET_FIELDS: tuple[Field, ...] = (
    Field("name", "str", "unique name of the sprocket", required=True),
    Field("teeth", "int", "number of teeth", required=True, minimum=MIN_TEETH, maximum=MAX_TEETH,
          reason="6: the chordal speed variation 1 − cos(180°/z) reaches 13 % "
          "[ChainNonUniformity]; 150: a plausibility bound on large sprockets"),
    Field("x", "length", "x of the centre", required=True, minimum=-100.0, maximum=100.0,
          reason=_XY, example="1364 mm"),
    Field("y", "length", "y of the centre", required=True, minimum=-100.0, maximum=100.0,
          reason=_XY, example="60.67 mm"),
    Field("role", "choice", "driver, driven or idler", default="driven", choices=ROLES),
    Field("speed", "speed", "rotational speed (driver only)", minimum=1.0 * RAD_S_PER_RPM,
          maximum=30_000.0 * RAD_S_PER_RPM, reason=_SPEED),
    Field("side", "choice", "outside: the chain wraps round it; inside: the chain wraps it from "
          "outside the loop (it turns the other way)", default="outside", choices=SIDES),
    Field("adjustable", "bool", "this sprocket moves to take up the chain length", default=False),
    Field("adjust_angle", "angle", "direction of the line of adjustment (default: away from "
          "the contour)", minimum=-TWO_PI, maximum=TWO_PI,
          reason="a direction: one turn either way"),
    Field("inertia", "inertia", "moment of inertia of what turns rigidly with it; without a "
          "train, everything on its shaft (motor, reducer, machine) referred to it (default: "
          "the sprocket body from its geometry)", minimum=1e-8, maximum=1e6, reason=_INERTIA),
    Field("reduced_mass", "mass", "the same as a mass at the pitch radius, m = J/R² (the "
          "'brought mass' of [MultimassChainDrives]); instead of inertia", minimum=1e-4,
          maximum=1e6, exclusive_minimum=True, reason=_REDUCED_MASS),
    Field("flywheel", "inertia", "inertia added as a steel flywheel on the shaft (in the "
          "dynamics, the mass and the cost)", default=0.0, minimum=0.0, maximum=1e6,
          reason="at most a 50 t flywheel of 6 m radius", example="0.05 kg*m^2"),
    Field("material", "str", "sprocket material (catalogue name)", default="steel"),
    Field("power_share", "float", "share of the power taken off here (driven sprockets)",
          minimum=0.0, maximum=1.0, reason="a share of the whole"),
    Field("load", "choice", "law of the driven machine's moment in speed (default: "
          "[dynamics] resistance)", choices=LOAD_LAWS),
    Field("train", "tables", "the open train on its shaft, outward from the sprocket: "
          "[[sprockets.train]] tables (below)"),
    Field("bore", "length", "bore of the sprocket on its drawing (default: the body model's "
          "0.19·z·p/π, said on the drawing)", minimum=0.006, maximum=0.5, exclusive_minimum=True,
          example="32 mm", reason="over 6 mm up to 500 mm: the ISO 286 tolerance table and the "
          "DIN 6885-1 key table (over 6 mm up to 230 mm with a keyway)"),
    Field("bore_fit", "choice", "ISO 286 hole-basis class of the bore", default="H7",
          choices=BORE_FITS),
    Field("keyway", "bool", "the bore has a DIN 6885-1 / ISO 773 hub keyway (false: the "
          "drawing says no keyway)", default=True),
    Field("hardening", "str", 'heat-treatment note of the drawing, e.g. "teeth induction '
          'hardened 45…50 HRC" (default: the drawing says none is given)'),
    Field("bearing_1", "length", "axial position of the shaft's first bearing from the "
          "sprocket's mid-plane, signed along the shaft (with bearing_2: the bearing "
          "reactions to the shaft load)", minimum=-5.0, maximum=5.0, example="-40 mm",
          reason="±5 m: beyond the shafts of chain drives"),
    Field("bearing_2", "length", "axial position of the second bearing (see bearing_1; at "
          "least 1 mm from it)", minimum=-5.0, maximum=5.0, example="60 mm",
          reason="±5 m: beyond the shafts of chain drives"),
)
TRAIN_FIELDS: tuple[Field, ...] = (
    Field("kind", "choice", "shaft or coupling: a torsional spring to a new node; gear: a "
          "rigid gear stage (a reducer as a whole) to a new node; rotor: an inertia on the "
          "current node; ground: a spring from the current node to the frame", required=True,
          choices=TRAIN_KINDS),
    Field("name", "str", "name of the new node (of the current node for a rotor), e.g. "
          '"motor", "reducer", "drum"'),
    Field("inertia", "inertia", "the new node's moment of inertia (rotor: added to the current "
          "node; 0: a massless node)", default=0.0, minimum=0.0, maximum=1e6,
          smallest=1e-8, reason="0 (a massless node), else at least the 1.7e-8 kg·m² of the "
          "smallest catalogue sprocket and at most a 50 t flywheel of 6 m radius"),
    Field("stiffness", "torsional_stiffness", "shaft, coupling or ground: torsional stiffness",
          minimum=1.0, maximum=1e10, reason=_TORSIONAL_STIFFNESS),
    Field("damping", "torsional_damping", "shaft or coupling: viscous damping coefficient",
          default=0.0, minimum=0.0, maximum=2e8, reason=_TORSIONAL_DAMPING),
    Field("diameter", "length", "shaft: diameter of a solid round shaft (with length, "
          "instead of stiffness)", minimum=0.002, maximum=2.0, reason=_SHAFT),
    Field("length", "length", "shaft: length of a solid round shaft", minimum=0.005,
          maximum=50.0, reason=_SHAFT),
    Field("material", "str", "shaft: material (catalogue name)", default="steel"),
    Field("ratio", "float", "gear: input speed / output speed in the direction of the power "
          "flow (motor → driver sprocket, driven sprocket → machine)", minimum=0.01,
          maximum=1000.0, reason=_GEAR_RATIO),
    Field("efficiency", "float", "gear: efficiency", default=1.0, minimum=0.01, maximum=1.0,
          reason="a share of the power passed on; a gear passing less than 1 % of its power "
          "would turn the rest into heat, as no reducer is built"),
)
MOTOR_FIELDS: tuple[Field, ...] = (
    Field("law", "choice", "torque law (default: [dynamics] motor)", choices=MOTORS),
    Field("rated_power", "power", "rated power (default: the drive's power)", minimum=1.0,
          maximum=20e6, reason=_POWER),
    Field("rated_speed", "speed", "rated speed of the motor shaft (default: the driver's speed "
          "times the ratios of its train)", minimum=1.0 * RAD_S_PER_RPM, maximum=30_000.0 * RAD_S_PER_RPM,
          reason=_SPEED),
    Field("rotor_inertia", "inertia", "rotor moment of inertia (default: estimated from the "
          "rated power and synchronous speed, IEC cage motors)", minimum=1e-6, maximum=1e5,
          reason=_ROTOR),
    Field("breakdown_ratio", "float", "Kloss: breakdown torque / rated torque (default: "
          "[dynamics])", minimum=1.0, maximum=5.0, exclusive_minimum=True,
          reason=_BREAKDOWN),
    Field("critical_slip", "float", "Kloss: critical slip (default: [dynamics])",
          minimum=MIN_CRITICAL_SLIP, maximum=1.0, reason=_CRITICAL_SLIP),
    Field("ramp_time", "time", "ramp: time to full torque (default: [dynamics])", minimum=0.0,
          maximum=60.0, exclusive_minimum=True, reason="within the longest start-up simulated"),
    Field("torque", "torque", "constant or ramp law: the torque (default: the rated torque)",
          minimum=1e-3, maximum=1e7, reason=_TORQUE),
)
DYNAMICS_FIELDS: tuple[Field, ...] = (
    Field("damping_ratio", "float", "damping ratio ζ of the chain (default: by the "
          "chain/sprocket material pair, 0.06 metal chain, 0.175 polymer chain)", minimum=0.0,
          maximum=0.9, smallest=1e-4, reason="below 1: an oscillating ring; roller chains show "
          "a few per cent; 0 is an undamped model, and a ratio below 1e-4 (a decay over "
          "thousands of cycles) is none any measurement tells from 0"),
    Field("hinge_friction", "bool", "damp each span by its hinge friction at its own tension "
          "(ζ = ψ/4π) instead", default=False),
    Field("hinge_amplitude", "float", "hinge friction: relative transverse amplitude of the "
          "spans y₀/a", default=0.02, minimum=0.0, maximum=0.1, exclusive_minimum=True,
          reason="[ChainHingeDissipation] measured 0.015 to 0.03"),
    Field("uncertainty", "float", "relative uncertainty of every stiffness and inertia (the "
          "bands of the frequencies, margins and K_D)", default=0.1, minimum=0.0,
          maximum=0.49, reason="below a half: a stiffness or inertia stays positive"),
    Field("require_complete_model", "bool", "an incomplete model (a driver without its motor, "
          "a driven sprocket with nothing on its shaft) is an error, not a warning",
          default=False),
    Field("harmonics", "int", "harmonics of the tooth frequency in the polygonal excitation",
          default=10, minimum=1, maximum=50,
          reason="[MultimassChainDrives]: 10 harmonics are practically exact"),
    Field("transient", "bool", "run the start-up transient", default=True),
    Field("startup_duration", "time", "simulated time of the start-up (default: automatic, "
          "at least 1 s, from the rigid-drive run-up, lengthened until the start-up settles)",
          minimum=0.0, maximum=60.0, exclusive_minimum=True,
          reason="a motor start lasts seconds; 60 s bounds the work of the simulation",
          example="1 s"),
    Field("motor", "choice", "motor law on the driver: induction motor (Kloss), constant "
          "torque or soft-start ramp", default="kloss", choices=MOTORS),
    Field("breakdown_ratio", "float", "Kloss motor: breakdown torque / rated torque",
          default=2.5, minimum=1.0, maximum=5.0, exclusive_minimum=True,
          reason="induction motors have breakdown torques of 1.6 to 3.5 times the rated one"),
    Field("critical_slip", "float", "Kloss motor: critical slip", default=0.25,
          minimum=MIN_CRITICAL_SLIP, maximum=1.0, reason=_CRITICAL_SLIP),
    Field("ramp_time", "time", "ramp motor: time to full torque", default=0.5, minimum=0.0,
          maximum=60.0, exclusive_minimum=True,
          reason="soft starters ramp over seconds; at most the longest start-up",
          example="0.5 s"),
    Field("resistance", "choice", "resistance law on the driven sprockets", default="linear",
          choices=RESISTANCES),
    Field("eccentricity", "length", "eccentricity of every sprocket (disturbance once per "
          "revolution)", default=0.0, minimum=0.0, maximum=0.01, reason=_RUNOUT,
          example="0.1 mm"),
    Field("pitch_scatter", "length", "scatter (standard deviation) of the link pitches",
          default=0.0, minimum=0.0, maximum=0.001,
          reason="at most 1 mm: [ISO606] length tolerances are +0.15 % of the pitch",
          example="0.02 mm"),
    Field("accumulated_error", "length", "accumulated error of the chain length", default=0.0,
          minimum=0.0, maximum=1.0, reason="at most 1 m: a chain is replaced at 3 % "
          "elongation, 1 m on the longest drive chains", example="0.5 mm"),
)
#: ``[uncertainty]``: what scatters in a built drive and how far its chain wears, read by
#: :mod:`chaindrive.robust` (defaults from the standards, sources in docs/robust.md).
UNCERTAINTY_FIELDS: tuple[Field, ...] = (
    Field("samples", "int", "quasi-Monte Carlo samples of the probabilities (Sobol points, a "
          "power of two per replicate)", default=256, minimum=8, maximum=1 << 20,
          reason="8 resolves a probability of 1/8; 2^20 states bound the work of a study"),
    Field("replicates", "int", "independent scramblings of the Sobol points (the spread gives "
          "the confidence interval)", default=8, minimum=2, maximum=64,
          reason="two replicates give a spread [Owen1997]; 64 more add nothing to the "
          "interval's width that the samples would not"),
    Field("seed", "int", "random seed of the scrambling (same seed, same samples)", default=0,
          minimum=0, maximum=2**31 - 1, reason="a non-negative 32-bit integer"),
    Field("confidence", "float", "confidence level of the intervals", default=0.95,
          minimum=0.5, maximum=0.999, reason="an interval of at least even odds; 0.999 "
          "needs more replicates than a study runs"),
    Field("wear", "choice", "wear state of the chain: new, worn to the allowable elongation, "
          "or life (uniform from new to worn)", default="life", choices=("new", "worn", "life")),
    Field("smooth_running", "bool", "the drive must run smoothly: allowable elongation 1.5 % "
          "([DiamondChainWear])", default=False),
    Field("allowable_elongation", "float", "wear elongation at which the chain is replaced "
          "(default: 3 %, 200/z % for a large sprocket, 1.5 % for fixed centres or parallel "
          "chains)", minimum=0.0, maximum=0.1, exclusive_minimum=True,
          reason="[DiamondChainWear]: 1.5 to 3 %; 10 % is far past any replacement rule",
          example="0.03"),
    Field("chain_length_tolerance", "float", "length tolerance of a new chain, 0 to this "
          "fraction (ISO 606: +0.15 %)", default=0.0015, minimum=0.0, maximum=0.05,
          reason="[TsubakiLength]: +0.15 %; 5 % is longer than a worn-out chain"),
    Field("eccentricity", "length", "largest eccentricity of every sprocket (default: half the "
          "ASME B29.1 commercial runout by root diameter)", minimum=0.0, maximum=0.01,
          reason=_RUNOUT, example="0.1 mm"),
    Field("centre_distance_tolerance", "length", "± position tolerance of every shaft "
          "(default: ±1 mm up to 1 m from the driver, ±a/1000 beyond)", minimum=0.0,
          maximum=0.1, reason="[TsubakiGuide]: ±10 mm beyond 10 m; 100 mm is ten times that",
          example="1 mm"),
    Field("key_fit", "choice", "keyway fit of the keyed sprockets of parallel contours "
          "([Lyashuk])", default="normal", choices=("tight", "normal", "free")),
    Field("inertia_scatter", "float", "± relative scatter of every reduced inertia (uniform)",
          default=0.10, minimum=0.0, maximum=0.5,
          reason="below a half: an inertia stays positive"),
    Field("stiffness_scatter", "float", "± relative scatter of the chain stiffness (uniform)",
          default=0.10, minimum=0.0, maximum=0.5,
          reason="below a half: a stiffness stays positive"),
    Field("temperature_min", "float", "lowest operating temperature of polymer parts, °C",
          default=23.0, minimum=-60.0, maximum=150.0,
          reason="[Delrin500P]: the modulus is tabulated from −40 to 100 °C; acetal and "
          "polyamide parts are not used beyond −60 to 150 °C"),
    Field("temperature_max", "float", "highest operating temperature of polymer parts, °C",
          default=23.0, minimum=-60.0, maximum=150.0,
          reason="[Delrin500P]: the modulus is tabulated from −40 to 100 °C; acetal and "
          "polyamide parts are not used beyond −60 to 150 °C"),
    Field("take_up_capacity", "length", "chain length the take-up can absorb before the "
          "chain is shortened by two links (default: two pitches, [DiamondChainTension])",
          minimum=0.0, maximum=1.0,
          exclusive_minimum=True, reason="1 m: a take-up longer than the longest drive "
          "chain's replacement elongation", example="50.8 mm"),
    Field("wear_states", "int", "wear states of the batched modal path over the life "
          "(midpoint rule in the life fraction)", default=8, minimum=1, maximum=64,
          reason="64 midpoints resolve the life fraction to 1.6 %"),
    Field("sensitivity_samples", "int", "first base samples N of each of the 8 independently "
          "scrambled Saltelli designs of the Sobol sensitivity indices (8·N·(groups + 2) "
          "evaluations)", default=32, minimum=4, maximum=1 << 16,
          reason="[Saltelli2010]: N of some tens to thousands; 2^16 bounds the work"),
    Field("sensitivity_budget", "int", "evaluations the Sobol sample may grow to (N doubles "
          "from sensitivity_samples until every metric's leading total index is within "
          "sensitivity_target)", default=16384, minimum=16, maximum=1 << 20,
          reason="16 is the least design of two groups; 2^20 states bound the work of a study"),
    Field("sensitivity_target", "float", "half-width of the interval of every metric's "
          "leading total Sobol index at which the sample stops growing", default=0.1,
          minimum=0.01, maximum=0.5,
          reason="an index lies in [0, 1]: ±0.5 says nothing, below ±0.01 costs 10^5 states"),
)
SECTIONS: dict[str, tuple[Field, ...]] = {
    "drive": DRIVE_FIELDS,
    "chain": CHAIN_FIELDS,
    "sprockets": SPROCKET_FIELDS,
    "sprockets.train": TRAIN_FIELDS,
    "motor": MOTOR_FIELDS,
    "dynamics": DYNAMICS_FIELDS,
    "uncertainty": UNCERTAINTY_FIELDS,
}
#: Sections of :data:`SECTIONS` that are nested in another table, not top-level tables.
NESTED_SECTIONS: tuple[str, ...] = ("sprockets.train",)


#: Sections read by other parts of chaindrive, not by the drive loader: ``[optimize]``
#: (the synthesis problem, :mod:`chaindrive.synthesis`).
OTHER_SECTIONS: tuple[str, ...] = ("optimize",)


def schema() -> dict[str, list[dict[str, Any]]]:
    """Every field of a design file with its kind, unit, default and allowed values.

    Returns
    -------
    dict
        Section → list of {field, kind, si_unit, example, required, default, allowed,
        reason, description}.
    """
    out: dict[str, list[dict[str, Any]]] = {}
    for section, fields in SECTIONS.items():
        out[section] = [
            {
                "field": f.name,
                "kind": f.kind,
                "si_unit": DIMENSIONS[f.kind][1] if f.kind in DIMENSIONS else "",
                "example": f.example_text(),
                "required": f.required,
                "default": f.default,
                "allowed": f.allowed(),
                "reason": f.reason,
                "description": f.description,
            }
            for f in fields
        ]
    return out


def _number_text(value: Any) -> str:
    return shown(value) if isinstance(value, str) else str(value)[:MAX_TEXT]


def _check_range(f: Field, path: str, value: float, given: Any) -> None:
    if not f.fits(value):
        why = f" ({f.reason})" if f.reason else ""
        if 0.0 < abs(value) < SMALLEST_NORMAL:
            why = (f" ({_number_text(given)} is a subnormal number, below the smallest normal "
                   "double 2.2e-308, that no measurement gives"
                   + (f"; {f.reason})" if f.reason else ")"))
        raise DesignError(path, f"must be {f.allowed()}, got {_number_text(given)}{why}")


def _as_float(value: int | float) -> float:
    """``value`` as a float; an integer too large for one is infinite (and then refused)."""
    try:
        return float(value)
    except OverflowError:
        return math.inf


def _shown_value(value: Any) -> str:
    """A value of a design file as a message quotes it (one line, cut to a readable length)."""
    return shown(value) if isinstance(value, str) else repr(value)[:MAX_TEXT]


def parse_field(f: Field, value: Any, path: str) -> Any:
    """Check and convert one value of a design file.

    Parameters
    ----------
    f : Field
        Its field.
    value : object
        The value as read from TOML.
    path : str
        Its path (``sprockets[1].x``), for the message.

    Returns
    -------
    object
        The value (SI for a quantity).

    Raises
    ------
    DesignError
        One line naming the path, the value and what is allowed.
    """
    if f.kind == "str":
        if not isinstance(value, str) or not value.strip():
            raise DesignError(path, f"must be non-empty text, got {_shown_value(value)}")
        if len(value) > MAX_NAME or not value.strip().isprintable():
            raise DesignError(path, f"must be one line of at most {MAX_NAME} printable "
                              f"characters, got {_shown_value(value)}")
        return value.strip()
    if f.kind == "bool":
        if not isinstance(value, bool):
            raise DesignError(path, f"must be true or false, got {_shown_value(value)}")
        return value
    if f.kind == "choice":
        if not isinstance(value, str) or value not in f.choices:
            raise DesignError(path, f"must be {f.allowed()}, got {_shown_value(value)}"
                              + did_you_mean(str(value)[:MAX_NAME], f.choices))
        return value
    if f.kind == "links" and isinstance(value, str):
        if value not in ROUNDINGS:
            raise DesignError(path, f'must be a whole number, "round up", "round down" or '
                              f'"nearest", got {shown(value)}'
                              + did_you_mean(value[:MAX_NAME], ROUNDINGS))
        return value
    if f.kind in ("int", "links"):
        if isinstance(value, bool) or not isinstance(value, int):
            raise DesignError(path, f"must be {f.allowed()}, got {_number_text(value)}")
        _check_range(f, path, _as_float(value), value)
        return value
    if f.kind == "float":
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise DesignError(path, f"must be {f.allowed()}, got {_number_text(value)}")
        _check_range(f, path, _as_float(value), value)
        return float(value)
    si = parse_quantity_as(value, f.kind, path, f.example_text())
    _check_range(f, path, si, value)
    return si


def parse_quantity_as(text: object, dimension: str, path: str, example: str) -> float:
    """:func:`chaindrive.units.parse_quantity` whose messages show ``example`` — a value that
    fits the field — instead of the example of the whole dimension (``"2400 h"`` is a time,
    but not a ramp time of at most 60 s).

    Parameters
    ----------
    text : object
        The value as read (a string with a unit).
    dimension : str
        A key of :data:`chaindrive.units.DIMENSIONS`.
    path : str
        The field or option, for the message.
    example : str
        A value that fits the field (:meth:`Field.example_text`); empty: the dimension's.

    Returns
    -------
    float
        The value in the SI unit of the dimension.

    Raises
    ------
    DesignError
        One line naming ``path``, the text and, where the message gives one, ``example``.
    """
    try:
        return parse_quantity(text, dimension, path)
    except DesignError as exc:
        generic = f'"{DIMENSIONS[dimension][2]}"'
        if not example or generic not in exc.detail:
            raise
        raise type(exc)(exc.field, exc.detail.replace(generic, f'"{example}"')) from None


def parse_section(data: Any, fields: tuple[Field, ...], path: str) -> dict[str, Any]:
    """Check a TOML table against its fields: unknown names, required ones, values.

    Parameters
    ----------
    data : object
        The table as read.
    fields : tuple of Field
        Its fields.
    path : str
        Its path (``sprockets[1]``), for the messages.

    Returns
    -------
    dict
        Field name → checked value (the default when left out).
    """
    if not isinstance(data, Mapping):
        raise DesignError(path, f"must be a table, got {type(data).__name__}")
    known = {f.name: f for f in fields}
    for key in data:
        if key not in known:
            raise DesignError(f"{path}.{shown_key(key)}", "unknown field"
                              + did_you_mean(str(key)[:MAX_NAME], known)
                              + f" (known: {', '.join(known)})")
    out: dict[str, Any] = {}
    for f in fields:
        if f.name in data:
            out[f.name] = parse_field(f, data[f.name], f"{path}.{f.name}")
        elif f.required:
            raise DesignError(f"{path}.{f.name}", f"is required ({f.allowed()})")
        else:
            out[f.name] = f.default
    return out


_STRANDS_SUFFIX = re.compile(r"-(\d)$")


def _catalog_path(name: str, base_dir: Path | None,
                  catalogs: Mapping[str, Path] | None) -> Path:
    """The file of ``chain.catalog``: with ``catalogs`` (the web page) only a name among its
    keys, never a path of the machine; otherwise the path, relative to ``base_dir``."""
    if catalogs is not None:
        if name not in catalogs:
            uploaded = ", ".join(repr(k) for k in catalogs) or "none"
            raise DesignError("chain.catalog", f"{shown(name)} is not a catalogue uploaded in "
                              f"this session (uploaded: {uploaded}); upload the file first")
        return catalogs[name]
    path = Path(name)
    if base_dir is not None and not path.is_absolute():
        path = base_dir / path
    try:
        found = path.is_file()
    except (OSError, ValueError):  # a name too long, or with a NUL, for the file system
        found = False
    if not found:
        raise DesignError("chain.catalog", f"no such file: {shown(str(path))}")
    return path


def _check_agrees(spec: ChainSpec, values: dict[str, Any]) -> None:
    """With a designation, a standard, series or pitch given too must describe that chain."""
    given = {"standard": values["standard"], "series": values["series"],
             "pitch": values["pitch"]}
    if given["standard"] is not None:
        same = (spec.standard == given["standard"]
                or (given["standard"] == "ANSI" and spec.ansi is not None))
        if not same:
            raise DesignError("chain.standard", f"{given['standard']!r} contradicts the "
                              f"designation {spec.designation!r} ({spec.standard}); give one")
    if given["series"] is not None and spec.series != given["series"]:
        raise DesignError("chain.series", f"{given['series']!r} contradicts the designation "
                          f"{spec.designation!r} (series {spec.series}); give one")
    if given["pitch"] is not None and abs(given["pitch"] - spec.pitch) > 1e-6:
        raise DesignError("chain.pitch", f"{given['pitch'] * 1e3:g} mm contradicts the "
                          f"designation {spec.designation!r} (pitch {spec.pitch * 1e3:g} mm); "
                          "give one")


def resolve_chain(values: dict[str, Any], base_dir: Path | None,
                  catalogs: Mapping[str, Path] | None = None
                  ) -> tuple[ChainSpec, ChainRequest | None]:
    """The catalogue chain named by the [chain] table (designation, or standard + pitch), or
    — when only a standard is given — a provisional chain of that family and the request
    that :func:`chaindrive.analyze` selects from.

    Parameters
    ----------
    values : dict
        The checked [chain] table (:func:`parse_section`) and ``strands_given``.
    base_dir : Path | None
        The design file's directory.
    catalogs : Mapping of str to Path | None
        See :func:`drive_from_mapping`.

    Returns
    -------
    tuple of (ChainSpec, ChainRequest | None)
    """

    extra: tuple[Path, ...] = ()
    if values["catalog"]:
        extra = (_catalog_path(values["catalog"], base_dir, catalogs),)
    strands = values["strands"]
    designation = values["designation"]
    if designation:
        spec = catalog.find_chain(designation, extra_files=extra)
        if spec.strands != strands:
            explicit = _STRANDS_SUFFIX.search(designation.strip()) or designation.strip()[0] in "234"
            if explicit and strands != 1:
                raise DesignError("chain.strands", f"{strands} contradicts the designation "
                                  f"{designation!r} ({spec.strands} strands)")
            if strands != 1:
                spec = _with_strands(spec, strands, extra)
        _check_agrees(spec, values)
        return spec, None
    if values["standard"] is None:
        raise DesignError("chain.designation", "give a designation, or a standard (and a pitch)")
    if values["pitch"] is None:
        family = [c for c in catalog.chains(extra) if c.standard == values["standard"]
                  and (values["series"] is None or c.series == values["series"])]
        if not family:
            raise DesignError("chain.series", f"no {values['standard']} chains of series "
                              f"{values['series']!r} in the catalogue")
        request = ChainRequest(values["standard"], values["series"], values["strands_given"])
        return min(family, key=lambda c: c.breaking_load), request
    found = [c for c in catalog.chains_by_pitch(values["pitch"], values["standard"], extra)
             if c.strands == strands and (values["series"] is None
                                          or c.series == values["series"])]
    if not found:
        raise DesignError("chain.pitch", f"no {values['standard']} chain of pitch "
                          f"{values['pitch'] * 1e3:g} mm with {strands} strand(s) in the catalogue")
    return min(found, key=lambda c: c.breaking_load), None


def _with_strands(spec: ChainSpec, strands: int, extra: tuple[Path, ...]) -> ChainSpec:
    """The same chain with another number of strands, from the catalogue."""

    same = [c for c in catalog.chains(extra) if c.pitch == spec.pitch and c.series == spec.series
            and c.standard == spec.standard and c.strands == strands
            and abs(c.roller_diameter - spec.roller_diameter) < 1e-9]
    if not same:
        raise DesignError("chain.strands", f"no {strands}-strand version of {spec.designation} "
                          "in the catalogue")
    return same[0]


def drive_from_mapping(data: Mapping[str, Any], base_dir: Path | None = None, *,
                       catalogs: Mapping[str, Path] | None = None) -> Drive:
    """Build a validated :class:`Drive` from the parsed TOML of a design file.

    Parameters
    ----------
    data : Mapping
        The tables of the design file.
    base_dir : Path | None
        The design file's directory: ``chain.catalog`` is relative to it.
    catalogs : Mapping[str, Path] | None
        None: ``chain.catalog`` is a path of this machine. A mapping (what the web page
        passes): ``chain.catalog`` must be one of its names — the catalogues uploaded in the
        session — and no other file is ever opened.

    Returns
    -------
    Drive
    """
    if not isinstance(data, Mapping):
        raise DesignError("design", f"must be a table, got {type(data).__name__}")
    known = (*(k for k in SECTIONS if k not in NESTED_SECTIONS), *OTHER_SECTIONS)
    for key in data:
        if key not in known:
            raise DesignError(shown_key(key), "unknown section"
                              + did_you_mean(str(key)[:MAX_NAME], known)
                              + f" (known: {', '.join(known)})")
    drive_values = parse_section(data.get("drive", {}), DRIVE_FIELDS, "drive")
    parse_section(data.get("uncertainty", {}), UNCERTAINTY_FIELDS, "uncertainty")  # read by robust
    dynamics = DynamicsSettings(**parse_section(data.get("dynamics", {}), DYNAMICS_FIELDS,
                                                "dynamics"))
    motor = (Motor(**parse_section(data["motor"], MOTOR_FIELDS, "motor"))
             if "motor" in data else None)
    chain_values = parse_section(data.get("chain", {}), CHAIN_FIELDS, "chain")
    raw_sprockets = data.get("sprockets")
    if raw_sprockets is None:
        raise DesignError("sprockets", "is required: list the sprockets as [[sprockets]] tables")
    if not isinstance(raw_sprockets, list):
        raise DesignError("sprockets", "must be a list of [[sprockets]] tables")
    n = len(raw_sprockets)
    if not MIN_SPROCKETS <= n <= MAX_SPROCKETS:
        raise DesignError("sprockets", f"a contour needs {MIN_SPROCKETS} to {MAX_SPROCKETS} "
                          f"sprockets, got {n}")
    sprockets = []
    seen: dict[str, int] = {}
    for i, raw in enumerate(raw_sprockets):
        raw_train = raw.get("train", []) if isinstance(raw, Mapping) else []
        v = parse_section({k: x for k, x in raw.items() if k != "train"}
                          if isinstance(raw, Mapping) else raw,
                          tuple(f for f in SPROCKET_FIELDS if f.kind != "tables"),
                          f"sprockets[{i}]")
        v["train"] = parse_train(raw_train, f"sprockets[{i}].train")
        if v["name"] in seen:
            raise DesignError(f"sprockets[{i}].name", f"duplicate name {v['name']!r} (also "
                              f"sprockets[{seen[v['name']]}]); names must be unique")
        seen[v["name"]] = i
        if v["speed"] is not None and v["role"] != "driver":
            raise DesignError(f"sprockets[{i}].speed", "give the speed on the driver only "
                              f"(this one is {v['role']})")
        if v["load"] is not None and v["role"] != "driven":
            raise DesignError(f"sprockets[{i}].load", "the law of the driven machine's moment "
                              f"applies to driven sprockets only (this one is {v['role']}), "
                              f"got {v['load']!r}")
        catalog.find_material(v["material"], field=f"sprockets[{i}].material")
        b1, b2 = v.pop("bearing_1"), v.pop("bearing_2")
        if (b1 is None) != (b2 is None):
            raise DesignError(f"sprockets[{i}].{'bearing_2' if b2 is None else 'bearing_1'}",
                              "is missing: give both bearing positions or neither")
        if b1 is not None and abs(b2 - b1) < 1e-3:
            raise DesignError(f"sprockets[{i}].bearing_2", f"{b2 * 1e3:g} mm is within 1 mm "
                              f"of bearing_1 ({b1 * 1e3:g} mm); allowed: two distinct bearings")
        v["bearings"] = None if b1 is None else (b1, b2)
        if v["bore"] is not None and v["keyway"] and v["bore"] > KEYWAY_MAX_BORE:
            raise DesignError(f"sprockets[{i}].bore", f"{v['bore'] * 1e3:g} mm is beyond the "
                              f"DIN 6885-1 key table (up to {KEYWAY_MAX_BORE * 1e3:g} mm); "
                              "allowed: a smaller bore, or keyway = false")
        sprockets.append(Sprocket(**v))
    drivers = [i for i, s in enumerate(sprockets) if s.role == "driver"]
    if not drivers:
        raise DesignError("sprockets.role", 'the driver is missing: give one sprocket '
                          'role = "driver" and its speed')
    if len(drivers) != 1:
        shown = ", ".join(f"sprockets[{i}]" for i in drivers) or "none"
        raise DesignError("sprockets.role", f"exactly one sprocket must be the driver, got "
                          f"{len(drivers)} ({shown})")
    if sprockets[drivers[0]].speed is None:
        raise DesignError(f"sprockets[{drivers[0]}].speed", 'the driver needs a speed such as '
                          '"300 rpm"')
    chain_values["strands_given"] = (data.get("chain") or {}).get("strands")
    spec, request = resolve_chain(chain_values, base_dir, catalogs)
    if request is not None and drive_values["power"] is None:
        raise DesignError("drive.power", "is required when the design names no chain "
                          "(the chain is selected for the power)")
    tooth_form: ToothFormName = drive_values["tooth_form"] or (
        "GOST 591" if spec.standard == "GOST 13568" else "ISO 606")
    links = chain_values["links"]
    chain = Chain(spec, links=links if not isinstance(links, str) else None,
                  allow_odd=chain_values["allow_odd"], request=request,
                  contours=chain_values["contours"],
                  rounding=links if isinstance(links, str) else "round up",
                  sag=chain_values["sag"], link_stiffness=chain_values["link_stiffness"],
                  sag_allowance=chain_values["sag_allowance"])
    drive = Drive(name=drive_values["name"], chain=chain, sprockets=tuple(sprockets),
                  power=drive_values["power"], tooth_form=tooth_form,
                  service_factor=drive_values["service_factor"], dynamics=dynamics,
                  motor=motor, driver_duty=drive_values["driver"],
                  driven_duty=drive_values["driven"],
                  required_life=drive_values["required_life"],
                  rotation=drive_values["rotation"])
    drive = in_travel_order(drive)
    check_inertias(drive)
    check_motor_estimate(drive)
    return drive


def parse_train(data: Any, path: str) -> tuple[TrainElement, ...]:
    """The elements of a sprocket's train (a list of tables, outward from the sprocket).

    Parameters
    ----------
    data : object
        The value read from the design file under ``[[sprockets.train]]``: a list of tables,
        each with the fields of :data:`TRAIN_FIELDS` (quantities as strings with units).
    path : str
        Where the list sits in the file (e.g. ``"sprockets[1].train"``), used to name the
        field in a :class:`~chaindrive.errors.DesignError`.

    Returns
    -------
    tuple of TrainElement
        The train's elements in SI units, outward from the sprocket.

    Raises
    ------
    DesignError
        When ``data`` is not a list, has more than :data:`MAX_TRAIN_ELEMENTS` entries, or an
        element is invalid (the error names the element by its place in the file).
    """
    if not isinstance(data, list):
        raise DesignError(path, "must be a list of [[sprockets.train]] tables")
    if len(data) > MAX_TRAIN_ELEMENTS:
        raise DesignError(path, f"at most {MAX_TRAIN_ELEMENTS} elements, got {len(data)}")
    out = []
    for k, raw in enumerate(data):
        v = parse_section(raw, TRAIN_FIELDS, f"{path}[{k}]")
        catalog.find_material(v["material"], field=f"{path}[{k}].material")
        try:
            out.append(TrainElement(**v))
        except DesignError as exc:  # name the element by its place in the file
            field = exc.field.rsplit(".", 1)[-1]
            message = str(exc)[len(exc.field) + 2:] if exc.field else str(exc)
            raise DesignError(f"{path}[{k}].{field}", message) from None
    return tuple(out)


@shared_parameters
def parse_toml(text: str, name: str) -> dict[str, Any]:
    """The mapping of a TOML text.

    Parameters
    ----------
    text : str
        The TOML text (a leading byte-order mark, :data:`BOM`, is dropped).
    name : str
        Where it comes from, for the message.

    %(returns_toml)s

    Raises
    ------
    DesignError
        On a syntax error, a text over :data:`~chaindrive.io.limits.MAX_DESIGN_BYTES`, or
        arrays nested too deeply for the parser: one line naming ``name``.
    """
    where = shown_key(name, 300)
    check_file_size(len(text.encode("utf-8", "surrogatepass")), MAX_DESIGN_BYTES, where,
                    "design file")
    text = text.removeprefix(BOM)  # a byte-order mark some editors write: not TOML's
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(where, f"TOML syntax error: {exc}") from None
    except RecursionError:
        raise DesignError(where, "arrays or tables are nested too deeply to read") from None


@shared_parameters
def read_toml(path: str | Path, what: str = "design file") -> dict[str, Any]:
    """The mapping of a TOML file.

    Parameters
    ----------
    path : str | Path
        The file.
    what : str
        What kind of file is expected, for the message.

    %(returns_toml)s

    Raises
    ------
    DesignError
        For a missing, unreadable, oversized or malformed file: one line naming it.
    """
    p = Path(path)
    name = shown_key(path, 300)
    try:
        if not p.is_file():
            raise DesignError(name, f"no such {what}")
        check_file_size(p.stat().st_size, MAX_DESIGN_BYTES, name, what)
        text = p.read_text(encoding="utf-8-sig")  # a leading byte-order mark is dropped
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        if isinstance(exc, DesignError):
            raise
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else type(exc).__name__
        raise DesignError(name, f"cannot read the file ({reason})") from None
    return parse_toml(text, str(path))


def load_drive(path: str | Path) -> Drive:
    """Read and validate a TOML design file.

    Parameters
    ----------
    path : str | Path
        The design file.

    Returns
    -------
    Drive
    """
    return drive_from_mapping(read_toml(path), base_dir=Path(path).parent)


def _q(value: float, factor: float, unit: str) -> str:
    """A quantity as the design file writes it: SI value × factor in ``unit``, 12 significant
    digits (re-read to 1e-12 relative)."""
    return f"{value * factor:.12g} {unit}"


@shared_parameters
def drive_to_mapping(drive: Drive) -> dict[str, Any]:
    """The tables of a design file of ``drive`` (lengths in mm, speeds in rpm): what
    :func:`drive_from_mapping` reads back to the same drive. A chain that was selected is
    written by its designation.

    %(params_drive)s

    Returns
    -------
    dict
        The tables [drive], [chain], [[sprockets]] and [dynamics].
    """
    chain: dict[str, Any] = {"designation": drive.chain.spec.designation}
    if drive.chain.links is not None:
        chain["links"] = drive.chain.links
    elif drive.chain.rounding != "round up":
        chain["links"] = drive.chain.rounding
    if drive.chain.sag is not None:
        chain["sag"] = drive.chain.sag
    if drive.chain.sag_allowance is not None:
        chain["sag_allowance"] = drive.chain.sag_allowance
    if drive.chain.link_stiffness is not None:
        chain["link_stiffness"] = _q(drive.chain.link_stiffness, 1.0, "N/m")
    if drive.chain.allow_odd:
        chain["allow_odd"] = True
    if drive.chain.contours != 1:
        chain["contours"] = drive.chain.contours
    head: dict[str, Any] = {"name": drive.name}
    if drive.power is not None:
        head["power"] = _q(drive.power, 1e-3, "kW")
    head["tooth_form"] = drive.tooth_form
    if drive.service_factor is not None:
        head["service_factor"] = drive.service_factor
    if drive.driver_duty is not None:
        head["driver"] = drive.driver_duty
    if drive.driven_duty is not None:
        head["driven"] = drive.driven_duty
    if drive.required_life is not None:
        head["required_life"] = _q(drive.required_life, 1.0 / 3600.0, "h")
    if drive.rotation is not None:
        head["rotation"] = drive.rotation
    out: dict[str, Any] = {"drive": head, "chain": chain,
                           "sprockets": [_sprocket_table(s) for s in drive.sprockets]}
    if drive.motor is not None:
        out["motor"] = _motor_table(drive.motor)
    out["dynamics"] = _dynamics_table(drive.dynamics)
    return out


def _fields_table(obj: object, fields: Sequence[Field],
                  units: Mapping[str, tuple[float, str]],
                  skip_default: bool = False) -> dict[str, Any]:
    """The given fields of ``obj`` as a TOML table, each with its unit where it has one.

    A field whose value is None (or, with ``skip_default``, its default) is left out.
    """
    out: dict[str, Any] = {}
    for f in fields:
        value = getattr(obj, f.name)
        if value is None or (skip_default and value == f.default):
            continue
        out[f.name] = _q(value, *units[f.name]) if f.name in units else value
    return out


def _motor_table(m: Motor) -> dict[str, Any]:
    units = {"rated_power": (1e-3, "kW"), "rated_speed": (RPM_PER_RAD_S, "rpm"),
             "rotor_inertia": (1.0, "kg*m^2"), "ramp_time": (1.0, "s"),
             "torque": (1.0, "N*m")}
    return _fields_table(m, MOTOR_FIELDS, units)


def _train_table(e: TrainElement) -> dict[str, Any]:
    units = {"inertia": (1.0, "kg*m^2"), "stiffness": (1.0, "N*m/rad"),
             "damping": (1.0, "N*m*s/rad"), "diameter": (1e3, "mm"), "length": (1e3, "mm")}
    return {"kind": e.kind, **_fields_table(e, TRAIN_FIELDS[1:], units, skip_default=True)}


def _sprocket_table(s: Sprocket) -> dict[str, Any]:
    t: dict[str, Any] = {"name": s.name, "teeth": s.teeth, "x": _q(s.x, 1e3, "mm"),
                         "y": _q(s.y, 1e3, "mm"), "role": s.role}
    if s.speed is not None:
        t["speed"] = _q(s.speed, RPM_PER_RAD_S, "rpm")
    if s.side != "outside":
        t["side"] = s.side
    if s.adjustable:
        t["adjustable"] = True
    if s.adjust_angle is not None:
        t["adjust_angle"] = _q(s.adjust_angle, DEG_PER_RAD, "deg")
    if s.inertia is not None:
        t["inertia"] = _q(s.inertia, 1.0, "kg*m^2")
    if s.flywheel:
        t["flywheel"] = _q(s.flywheel, 1.0, "kg*m^2")
    if s.material != "steel":
        t["material"] = s.material
    if s.power_share is not None:
        t["power_share"] = s.power_share
    if s.reduced_mass is not None:
        t["reduced_mass"] = _q(s.reduced_mass, 1.0, "kg")
    if s.load is not None:
        t["load"] = s.load
    if s.train:
        t["train"] = [_train_table(e) for e in s.train]
    if s.bore is not None:
        t["bore"] = _q(s.bore, 1e3, "mm")
    if s.bore_fit != "H7":
        t["bore_fit"] = s.bore_fit
    if not s.keyway:
        t["keyway"] = False
    if s.hardening is not None:
        t["hardening"] = s.hardening
    if s.bearings is not None:
        t["bearing_1"], t["bearing_2"] = (_q(z, 1e3, "mm") for z in s.bearings)
    return t


def _dynamics_table(d: DynamicsSettings) -> dict[str, Any]:
    units = {"startup_duration": (1.0, "s"), "ramp_time": (1.0, "s"),
             "eccentricity": (1e3, "mm"), "pitch_scatter": (1e3, "mm"),
             "accumulated_error": (1e3, "mm")}
    return _fields_table(d, DYNAMICS_FIELDS, units)


@shared_parameters
def drive_to_toml(drive: Drive) -> str:
    """A design file of ``drive`` (TOML written by tomli-w from :func:`drive_to_mapping`).

    %(params_drive)s

    Returns
    -------
    str
        The TOML text.
    """
    return tomli_w.dumps(drive_to_mapping(drive))
