"""The validated drive model: frozen dataclasses in SI units.

A :class:`Drive` is what every analysis reads. It is built from a design file by
:mod:`chaindrive.io.design`, or in code::

    from chaindrive import Drive, Sprocket, Chain
    from chaindrive.catalog import find_chain
    drive = Drive(
        name="two sprockets",
        chain=Chain(find_chain("ISO 606 08B-1")),
        sprockets=(
            Sprocket("S1", teeth=17, x=0.0, y=0.0, role="driver", speed=2 * pi * 1000 / 60),
            Sprocket("S2", teeth=34, x=0.5, y=0.0, role="driven"),
        ),
        power=2_000.0,
    )
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Literal

from chaindrive.errors import DesignError

Role = Literal["driver", "driven", "idler"]
Side = Literal["outside", "inside"]
ToothFormName = Literal["ISO 606", "GOST 591"]

ROLES: tuple[str, ...] = ("driver", "driven", "idler")
SIDES: tuple[str, ...] = ("outside", "inside")
TOOTH_FORMS: tuple[str, ...] = ("ISO 606", "GOST 591")
MIN_TEETH, MAX_TEETH = 6, 150
MIN_SPROCKETS, MAX_SPROCKETS = 2, 24
MAX_CONTOURS = 8
ROUNDINGS: tuple[str, ...] = ("round up", "round down")


@dataclass(frozen=True, slots=True)
class ChainSpec:
    """One catalogue chain (all strands together), SI units.

    Attributes
    ----------
    designation : str — canonical name, e.g. ``"ISO 606 16B-1"``, ``"GOST 13568 ПР-25,4-60"``
    standard : str — ``"ISO 606"``, ``"ANSI"`` or ``"GOST 13568"``
    series : str — ``"A"``, ``"B"`` (ISO 606) or ``"ПР"`` (GOST)
    pitch : float — chain pitch p [m]
    strands : int — number of strands (rows) 1…
    roller_diameter : float — d1 max [m]
    pin_diameter : float — d2 max [m]
    inner_width : float — b1 min, width between inner plates [m]
    plate_depth : float — inner plate depth h2 max [m]
    transverse_pitch : float — pt [m] (0 for a simplex chain when not given)
    breaking_load : float — minimum tensile strength Q of the whole chain [N]
    mass_per_length : float — q [kg/m] of the whole chain
    bearing_area : float | None — projected bearing area of the whole chain A = m_r·d2·B
        (m_r = 1, 1.7, 2.5, 3.0 for 1–4 rows, GOST table 5.12; see :mod:`chaindrive.catalog`) [m²]
    ansi : str | None — ANSI/ASME B29.1 number (e.g. ``"80"`` or ``"80-2"``)
    material : str — chain material name (``"steel"`` for catalogue chains)
    source : str — where the row comes from
    allowable_load : float | None — the maker's allowable working pull of the whole chain [N]
        (polymer chains; None when the catalogue gives none)
    max_speed : float | None — the maker's highest chain speed [m/s] (None: not given)
    """

    designation: str
    standard: str
    series: str
    pitch: float
    strands: int
    roller_diameter: float
    pin_diameter: float
    inner_width: float
    plate_depth: float
    transverse_pitch: float
    breaking_load: float
    mass_per_length: float
    bearing_area: float | None = None
    ansi: str | None = None
    material: str = "steel"
    source: str = ""
    allowable_load: float | None = None
    max_speed: float | None = None

    def __post_init__(self) -> None:
        for name in ("pitch", "roller_diameter", "pin_diameter", "breaking_load",
                     "mass_per_length"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise DesignError(f"chain.{name}", f"must be a positive number, got {value!r}")
        if not 1 <= self.strands <= 8:
            raise DesignError("chain.strands", f"must be 1 to 8, got {self.strands!r}")


@dataclass(frozen=True, slots=True)
class Material:
    """A sprocket or chain material, SI units (density [kg/m³], E [Pa], strength [Pa])."""

    name: str
    family: str
    density: float
    youngs_modulus: float
    tensile_strength: float | None = None
    friction_vs_steel: float | None = None
    source: str = ""

    @property
    def is_polymer(self) -> bool:
        """True for polyamides, acetals and other plastics."""
        return self.family not in {"carbon steel", "alloy steel", "cast steel",
                                   "case-hardening steel", "grey cast iron", "steel",
                                   "cast iron"}


@dataclass(frozen=True, slots=True)
class ChainRequest:
    """A design that names no chain: the family to select from.

    standard: "ISO 606", "ANSI" or "GOST 13568"; series: "A"/"B" or None; strands: fixed
    number of strands or None (simplex is chosen then).
    """

    standard: str
    series: str | None = None
    strands: int | None = None


@dataclass(frozen=True, slots=True)
class Chain:
    """The chain of a drive: a catalogue entry plus what the design fixes.

    ``links`` imposes the number of links (the take-up then finds the position that fits
    it); otherwise ``rounding`` says how the tight length is rounded to a whole (even)
    number of links: "round up" (the default, the chain is lengthened) or "round down"
    (the take-up shortens the layout); ``sag``: the installed sag of the slack span as a
    fraction of its length (None: laid out tight; see
    :mod:`chaindrive.geometry.length_options`); ``allow_odd`` permits an odd count (which
    needs an offset link); ``contours``: the
    number of identical chain contours side by side on sprockets keyed to common shafts
    ([Lyashuk]; 1 for an ordinary drive). ``request`` is set
    when the design named no chain: ``spec`` is then provisional and
    :func:`chaindrive.analyze` replaces it with the lightest feasible chain of the family.
    """

    spec: ChainSpec
    links: int | None = None
    allow_odd: bool = False
    request: ChainRequest | None = None
    contours: int = 1
    rounding: str = "round up"
    sag: float | None = None

    def __post_init__(self) -> None:
        if self.rounding not in ROUNDINGS:
            raise DesignError("chain.links", f"must be a whole number or one of "
                              f"{', '.join(repr(r) for r in ROUNDINGS)}, got {self.rounding!r}")
        if self.sag is not None and not 0.0 < self.sag <= 0.1:
            raise DesignError("chain.sag", f"must be a fraction of the slack span in (0, 0.1], "
                              f"got {self.sag!r}")
        if (not isinstance(self.contours, int) or isinstance(self.contours, bool)
                or not 1 <= self.contours <= MAX_CONTOURS):
            raise DesignError("chain.contours", f"must be a whole number from 1 to {MAX_CONTOURS}, "
                              f"got {self.contours!r}")
        if self.links is not None:
            if not isinstance(self.links, int) or isinstance(self.links, bool) or self.links < 4:
                raise DesignError("chain.links", f"must be a whole number ≥ 4, got {self.links!r}")
            if self.links % 2 and not self.allow_odd:
                raise DesignError(
                    "chain.links",
                    f"must be even (an odd count needs an offset link: set allow_odd = true), "
                    f"got {self.links}",
                )

    @property
    def pitch(self) -> float:
        """Chain pitch p [m]."""
        return self.spec.pitch



TRAIN_KINDS: tuple[str, ...] = ("shaft", "coupling", "gear", "rotor", "ground")
LOAD_LAWS: tuple[str, ...] = ("constant", "linear", "quadratic")
#: Most elements one sprocket's train may carry (the model stays a few hundred degrees of
#: freedom at most, so that every response is bounded work).
MAX_TRAIN_ELEMENTS = 12


@dataclass(frozen=True, slots=True)
class TrainElement:
    """One element of the open train on a sprocket's shaft, listed outward from the sprocket.

    kind : "shaft" or "coupling" — a torsional spring (``stiffness`` k [N·m/rad], or a solid
        round shaft of ``diameter`` d [m], ``length`` l [m] and ``material``: k = G π d⁴/(32 l))
        with a damper ``damping`` c [N·m·s/rad], from the current node to a new node;
        "gear" — a rigid gear stage (a reducer taken as a whole) of ``ratio`` i = input speed /
        output speed in the direction the power flows (from the motor to the driver sprocket,
        from a driven sprocket to its machine) and ``efficiency`` η, to a new node;
        "rotor" — ``inertia`` added to the current node (a body on the same shaft);
        "ground" — a spring ``stiffness`` (and ``damping``) from the current node to the frame
        (a torque arm, an elastic foundation).
    name : the new node's name (shaft, coupling, gear) or the current node's (rotor); None:
        ``<sprocket>.<k>``.
    inertia : J [kg·m²] of the new node (shaft, coupling: the body at its far end; gear: the
        output-side gear and what turns with it) or added to the current node (rotor).
    """

    kind: str
    name: str | None = None
    inertia: float = 0.0
    stiffness: float | None = None
    damping: float = 0.0
    ratio: float | None = None
    efficiency: float = 1.0
    diameter: float | None = None
    length: float | None = None
    material: str = "steel"

    def __post_init__(self) -> None:
        where = f"train[{self.name or self.kind}]"
        if self.kind not in TRAIN_KINDS:
            raise DesignError(f"{where}.kind", f"must be one of {', '.join(TRAIN_KINDS)}, "
                              f"got {self.kind!r}")
        for key in ("inertia", "damping"):
            v = getattr(self, key)
            if not (math.isfinite(v) and v >= 0):
                raise DesignError(f"{where}.{key}", f"must be finite and ≥ 0, got {v!r}")
        if self.kind == "ground":
            if self.stiffness is None or not (math.isfinite(self.stiffness) and self.stiffness > 0):
                raise DesignError(f"{where}.stiffness", f"a ground spring needs a stiffness > 0, "
                                  f"got {self.stiffness!r}")
        elif self.kind in ("shaft", "coupling"):
            geometric = self.diameter is not None or self.length is not None
            if (self.stiffness is None) == (not geometric) or (
                    geometric and (self.diameter is None or self.length is None)):
                raise DesignError(f"{where}.stiffness", "give the stiffness, or the diameter "
                                  "and the length of a solid shaft (not both)")
            for key in ("stiffness", "diameter", "length"):
                v = getattr(self, key)
                if v is not None and not (math.isfinite(v) and v > 0):
                    raise DesignError(f"{where}.{key}", f"must be positive, got {v!r}")
        elif self.kind == "gear":
            if self.ratio is None or not (math.isfinite(self.ratio) and self.ratio > 0):
                raise DesignError(f"{where}.ratio", f"a gear stage needs a ratio > 0, got "
                                  f"{self.ratio!r}")
            if not (math.isfinite(self.efficiency) and 0 < self.efficiency <= 1):
                raise DesignError(f"{where}.efficiency", f"must be in (0, 1], got "
                                  f"{self.efficiency!r}")
        elif self.kind == "rotor" and not self.inertia > 0:
            raise DesignError(f"{where}.inertia", f"a rotor needs an inertia > 0, got "
                              f"{self.inertia!r}")


@dataclass(frozen=True, slots=True)
class Sprocket:
    """A sprocket of the contour, listed in the order the chain runs round it.

    x, y [m] centre; speed [rad/s] (driver only); inertia [kg·m²] of what turns rigidly with
    it — without a train everything on its shaft referred to it (None: the sprocket body from
    its geometry); ``reduced_mass`` [kg] the same as a mass at the pitch radius, m = J/R²
    [MultimassChainDrives, §3.1] (give one of the two); ``train`` the open train on its
    shaft, outward from it (:class:`TrainElement`); ``load`` the law of the driven machine's
    moment ("constant", "linear", "quadratic" in speed; None: ``[dynamics] resistance``);
    ``flywheel`` [kg·m²] an inertia added as a
    steel flywheel on its shaft (counted in the dynamics, the mass and the cost); ``side``
    is ``"inside"`` when the chain wraps it from the inside of the contour (it then turns the other way);
    ``adjust_angle`` [rad] the direction of its line of adjustment (None: the default,
    see :func:`chaindrive.geometry.contour.adjustment_direction`).
    """

    name: str
    teeth: int
    x: float
    y: float
    role: Role = "driven"
    speed: float | None = None
    side: Side = "outside"
    adjustable: bool = False
    adjust_angle: float | None = None
    inertia: float | None = None
    material: str = "steel"
    power_share: float | None = None
    flywheel: float = 0.0
    reduced_mass: float | None = None
    train: tuple[TrainElement, ...] = ()
    load: str | None = None

    def __post_init__(self) -> None:
        where = f"sprockets[{self.name}]"
        if self.reduced_mass is not None:
            if not (math.isfinite(self.reduced_mass) and self.reduced_mass > 0):
                raise DesignError(f"{where}.reduced_mass", f"must be positive, got "
                                  f"{self.reduced_mass!r} kg")
            if self.inertia is not None:
                raise DesignError(f"{where}.reduced_mass", "give the inertia or the reduced "
                                  "mass, not both")
        if len(self.train) > MAX_TRAIN_ELEMENTS:
            raise DesignError(f"{where}.train", f"at most {MAX_TRAIN_ELEMENTS} elements, got "
                              f"{len(self.train)}")
        if self.load is not None and self.load not in LOAD_LAWS:
            raise DesignError(f"{where}.load", f"must be one of {', '.join(LOAD_LAWS)}, got "
                              f"{self.load!r}")
        if (not isinstance(self.teeth, int) or isinstance(self.teeth, bool)
                or not MIN_TEETH <= self.teeth <= MAX_TEETH):
            raise DesignError(
                f"{where}.teeth",
                f"must be a whole number from {MIN_TEETH} to {MAX_TEETH}, got {self.teeth!r}",
            )
        if self.role not in ROLES:
            raise DesignError(f"{where}.role", f"must be one of {', '.join(ROLES)}, got {self.role!r}")
        if self.side not in SIDES:
            raise DesignError(f"{where}.side", f"must be one of {', '.join(SIDES)}, got {self.side!r}")
        for name in ("x", "y"):
            if not math.isfinite(getattr(self, name)):
                raise DesignError(f"{where}.{name}", f"must be finite, got {getattr(self, name)!r}")
        if self.speed is not None and not (math.isfinite(self.speed) and self.speed > 0):
            raise DesignError(f"{where}.speed", f"must be positive, got {self.speed!r} rad/s")
        if self.inertia is not None and not (math.isfinite(self.inertia) and self.inertia > 0):
            raise DesignError(f"{where}.inertia", f"must be positive, got {self.inertia!r} kg·m²")
        if not (math.isfinite(self.flywheel) and self.flywheel >= 0):
            raise DesignError(f"{where}.flywheel", f"must be ≥ 0, got {self.flywheel!r} kg·m²")
        if self.power_share is not None and not 0 <= self.power_share <= 1:
            raise DesignError(f"{where}.power_share", f"must be from 0 to 1, got {self.power_share!r}")

    def moved_to(self, x: float, y: float) -> Sprocket:
        """A copy of this sprocket at a new centre (used by the take-up)."""
        return replace(self, x=x, y=y)


MOTORS: tuple[str, ...] = ("kloss", "constant", "ramp")
RESISTANCES: tuple[str, ...] = LOAD_LAWS


@dataclass(frozen=True, slots=True)
class Motor:
    """The motor on the driver's train (the ``[motor]`` table of a design file).

    law : "kloss" (induction motor, Kloss formula), "constant" or "ramp" torque (None: the
        ``[dynamics] motor`` law); rated_power [W] (None: the drive's power); rated_speed
        [rad/s] of the motor shaft (None: the driver's speed times the ratios of its train);
        rotor_inertia [kg·m²] (None: estimated from the rated power and synchronous speed,
        :func:`chaindrive.dynamics.motor_inertia.estimated_rotor_inertia`); breakdown_ratio
        λ = M_k/M_r and critical_slip s_k of the Kloss law, ramp_time [s] of the ramp (None:
        the ``[dynamics]`` values); torque [N·m] of the constant or ramp law (None: the rated
        torque). The rotor sits on the outermost node of the driver's train (on the driver's
        shaft when it has no train).
    """

    law: str | None = None
    rated_power: float | None = None
    rated_speed: float | None = None
    rotor_inertia: float | None = None
    breakdown_ratio: float | None = None
    critical_slip: float | None = None
    ramp_time: float | None = None
    torque: float | None = None

    def __post_init__(self) -> None:
        if self.law is not None and self.law not in MOTORS:
            raise DesignError("motor.law", f"must be one of {', '.join(MOTORS)}, got {self.law!r}")
        for key in ("rated_power", "rated_speed", "rotor_inertia", "ramp_time", "torque"):
            v = getattr(self, key)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise DesignError(f"motor.{key}", f"must be positive, got {v!r}")
        if self.breakdown_ratio is not None and not 1 < self.breakdown_ratio <= 5:
            raise DesignError("motor.breakdown_ratio", f"must be in (1, 5], got "
                              f"{self.breakdown_ratio!r}")
        if self.critical_slip is not None and not 0 < self.critical_slip < 1:
            raise DesignError("motor.critical_slip", f"must be in (0, 1), got "
                              f"{self.critical_slip!r}")


@dataclass(frozen=True, slots=True)
class DynamicsSettings:
    """What the dynamic analyses of a drive use (the ``[dynamics]`` table of a design file).

    damping_ratio ζ of the chain spans (None: by the chain/sprocket material pair,
    :data:`chaindrive.dynamics.damping.PAIR_DAMPING_RATIOS`); hinge_friction: each span's ζ
    = ψ/4π at its own tension instead [ChainHingeDissipation], with the relative transverse
    amplitude hinge_amplitude ȳ₀; uncertainty u: stiffnesses and inertias known to ±u (the
    bands of the natural frequencies, margins and K_D); require_complete_model: an incomplete
    model (a driver without its motor, a driven sprocket with nothing on its shaft) is an
    error instead of a warning; harmonics of the tooth frequency in the polygonal
    excitation ([MultimassChainDrives]: 10 are practically exact); transient: run the start-up;
    startup_duration [s]; motor: "kloss" (induction motor with the drive's power and the
    driver speed as rated values, breakdown_ratio λ = M_k/M_r and critical_slip s_k),
    "constant" (rated torque from t = 0) or "ramp" (soft start over ramp_time [s]);
    resistance on the driven sprockets: "constant", "linear" or "quadratic" in speed;
    eccentricity [m] of every sprocket, pitch_scatter σ [m] of the link pitches and
    accumulated_error [m] of the chain length: optional internal disturbances
    ([MultimassChainDrives, §2]).
    """

    damping_ratio: float | None = None
    harmonics: int = 10
    transient: bool = True
    startup_duration: float = 1.0
    motor: str = "kloss"
    breakdown_ratio: float = 2.5
    critical_slip: float = 0.25
    ramp_time: float = 0.5
    resistance: str = "linear"
    eccentricity: float = 0.0
    pitch_scatter: float = 0.0
    accumulated_error: float = 0.0
    hinge_friction: bool = False
    hinge_amplitude: float = 0.02
    uncertainty: float = 0.1
    require_complete_model: bool = False

    def __post_init__(self) -> None:
        if not 0.0 <= self.uncertainty < 0.5:
            raise DesignError("dynamics.uncertainty", f"must be from 0 to below 0.5, got "
                              f"{self.uncertainty!r}")
        if not 0.0 < self.hinge_amplitude <= 0.1:
            raise DesignError("dynamics.hinge_amplitude", f"must be in (0, 0.1], got "
                              f"{self.hinge_amplitude!r}")
        if self.damping_ratio is not None and not 0.0 <= self.damping_ratio < 1.0:
            raise DesignError("dynamics.damping_ratio",
                              f"must be from 0 to below 1, got {self.damping_ratio!r}")
        if self.motor not in MOTORS:
            raise DesignError("dynamics.motor", f"must be one of {', '.join(MOTORS)}, "
                              f"got {self.motor!r}")
        if self.resistance not in RESISTANCES:
            raise DesignError("dynamics.resistance", f"must be one of {', '.join(RESISTANCES)}, "
                              f"got {self.resistance!r}")


@dataclass(frozen=True, slots=True)
class Drive:
    """A chain drive: one closed chain contour round 2 to 24 sprockets.

    power [W] transmitted from the driver (None when only geometry is wanted);
    tooth_form: sprocket tooth form used for tip/root diameters; motor: the motor on the
    driver's train (None: not modelled; the start-up then uses the ``[dynamics]`` law).
    """

    name: str
    chain: Chain
    sprockets: tuple[Sprocket, ...]
    power: float | None = None
    tooth_form: ToothFormName = "ISO 606"
    service_factor: float | None = None
    dynamics: DynamicsSettings = field(default_factory=DynamicsSettings)
    notes: dict[str, str] = field(default_factory=dict)
    motor: Motor | None = None

    def __post_init__(self) -> None:
        n = len(self.sprockets)
        if not MIN_SPROCKETS <= n <= MAX_SPROCKETS:
            raise DesignError(
                "sprockets", f"a contour needs {MIN_SPROCKETS} to {MAX_SPROCKETS} sprockets, got {n}"
            )
        names = [s.name for s in self.sprockets]
        for i, name in enumerate(names):
            if name in names[:i]:
                raise DesignError(f"sprockets[{i}].name", f"duplicate name {name!r}; names must be unique")
        drivers = [s.name for s in self.sprockets if s.role == "driver"]
        if not drivers:
            raise DesignError("sprockets.role", 'the driver is missing: give one sprocket '
                              'role = "driver" and its speed')
        if len(drivers) != 1:
            raise DesignError(
                "sprockets.role",
                f"exactly one sprocket must be the driver, got {len(drivers)}"
                + (f" ({', '.join(drivers)})" if drivers else ""),
            )
        driver = self.sprockets[self.driver_index]
        for s in self.sprockets:
            if s.speed is not None and s.role != "driver":
                raise DesignError(f"sprockets[{s.name}].speed",
                                  "give the speed on the driver only (the others follow from it)")
        if driver.speed is None and self.power is not None:
            raise DesignError(f"sprockets[{driver.name}].speed",
                              "the driver needs a speed when power is given")
        if self.power is not None and not (math.isfinite(self.power) and self.power > 0):
            raise DesignError("drive.power", f"must be positive, got {self.power!r} W")
        if self.tooth_form not in TOOTH_FORMS:
            raise DesignError("drive.tooth_form",
                              f"must be one of {', '.join(TOOTH_FORMS)}, got {self.tooth_form!r}")
        adjustable = [s.name for s in self.sprockets if s.adjustable]
        if len(adjustable) > 1:
            raise DesignError("sprockets.adjustable",
                              f"at most one sprocket may be adjustable, got {', '.join(adjustable)}")

    @property
    def driver_index(self) -> int:
        """Index of the driving sprocket."""
        return next(i for i, s in enumerate(self.sprockets) if s.role == "driver")

    @property
    def driver(self) -> Sprocket:
        """The driving sprocket."""
        return self.sprockets[self.driver_index]

    @property
    def adjustable_index(self) -> int | None:
        """Index of the sprocket that takes up the chain: the one marked adjustable; in a
        two-sprocket drive with none marked, the driven one; otherwise None."""
        for i, s in enumerate(self.sprockets):
            if s.adjustable:
                return i
        if len(self.sprockets) == 2:
            return 1 - self.driver_index
        return None

    def with_chain(self, spec: ChainSpec) -> Drive:
        """A copy with another catalogue chain (links and allow_odd kept; the request is
        answered, so it is cleared)."""
        return replace(self, chain=replace(self.chain, spec=spec, request=None))

    def with_sprockets(self, sprockets: tuple[Sprocket, ...]) -> Drive:
        """A copy with other sprockets (e.g. after the take-up)."""
        return replace(self, sprockets=sprockets)
