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
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Literal

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError

Role = Literal["driver", "driven", "idler"]
Side = Literal["outside", "inside"]
ToothFormName = Literal["ISO 606", "GOST 591"]

ROLES: tuple[str, ...] = ("driver", "driven", "idler")
SIDES: tuple[str, ...] = ("outside", "inside")
#: Hole-basis fits a sprocket's bore may be given (ISO 286, fundamental deviation H).
BORE_FITS: tuple[str, ...] = ("H6", "H7", "H8")
TOOTH_FORMS: tuple[str, ...] = ("ISO 606", "GOST 591")
#: Duty classes of the driver (prime mover), mildest first (:mod:`chaindrive.strength.duty`).
DRIVER_DUTIES: tuple[str, ...] = ("smooth", "slight shock", "moderate shock")
#: Duty classes of the driven machine, mildest first (:mod:`chaindrive.strength.duty`).
DRIVEN_DUTIES: tuple[str, ...] = ("smooth", "moderate shock", "heavy shock")
#: Directions of rotation of the driver seen on the drawing plane (x right, y up).
ROTATIONS: tuple[str, ...] = ("cw", "ccw")
MIN_TEETH, MAX_TEETH = 6, 150
MIN_SPROCKETS, MAX_SPROCKETS = 2, 24
MAX_CONTOURS = 8
ROUNDINGS: tuple[str, ...] = ("round up", "round down", "nearest")


#: What a catalogue row's source writes before the columns it estimates
#: (:attr:`ChainSpec.estimated`).
ESTIMATE_MARK = "ESTIMATED:"


def estimated_columns(source: str) -> tuple[str, ...]:
    """The catalogue columns a row's source lists as estimates: ``"…; ESTIMATED: a|b (how)"``
    → ``("a", "b")`` (empty when it marks none).

    Parameters
    ----------
    source : str
        A catalogue row's source cell.

    Returns
    -------
    tuple of str
    """
    _, mark, tail = source.partition(ESTIMATE_MARK)
    if not mark:
        return ()
    columns = tail.strip().partition(" (")[0]
    return tuple(c.strip() for c in columns.split("|") if c.strip())


# --- the checks of the dataclasses' fields (first failure raised, in the order given) ---

def _positive(v: float) -> bool:
    return math.isfinite(v) and v > 0


def _not_negative(v: float) -> bool:
    return math.isfinite(v) and v >= 0


def _check_choice(field: str, value: object, allowed: tuple[str, ...]) -> None:
    """Refuse a ``value`` that is not one of ``allowed``, naming ``field``."""
    if value not in allowed:
        raise DesignError(field, f"must be one of {', '.join(allowed)}, got {value!r}")


def _check_ranges(where: str, owner: object,
                  ranges: tuple[tuple[str, Callable[[float], bool], str, str], ...]) -> None:
    """Refuse the first field of ``owner`` that is given (not None) and fails its test.

    Each row of ``ranges`` is (field, test, what is allowed, unit written after the value);
    the error names ``<where>.<field>``.
    """
    for name, ok, allowed, unit in ranges:
        value = getattr(owner, name)
        if value is not None and not ok(value):
            raise DesignError(f"{where}.{name}", f"{allowed}, got {value!r}{unit}")


@shared_parameters
@dataclass(frozen=True, slots=True)
class ChainSpec:
    """One catalogue chain (all strands together), SI units.

    Parameters
    ----------
    designation : str
        Canonical name, e.g. ``"ISO 606 16B-1"``, ``"GOST 13568 ПР-25,4-60"``.
    standard : str
        ``"ISO 606"``, ``"ANSI"`` or ``"GOST 13568"`` ([ISO606], [ANSI-B29.1], [GOST13568]).
    series : str
        ``"A"``, ``"B"`` (ISO 606) or ``"ПР"`` (GOST).
    %(pitch)s
    strands : int
        Number of strands (rows), 1 to 8 [-].
    roller_diameter : float
        Roller diameter d₁ max [m].
    pin_diameter : float
        Pin diameter d₂ max [m].
    inner_width : float
        Width between inner plates b₁ min [m].
    plate_depth : float
        Inner plate depth h₂ max [m].
    transverse_pitch : float
        Transverse pitch p_t between strands [m] (0 for a simplex chain when not given).
    breaking_load : float
        Minimum tensile strength Q of the whole chain [N].
    mass_per_length : float
        Mass per unit length q of the whole chain [kg/m].
    bearing_area : float or None
        Projected bearing area of the hinges of the whole chain A = m_r·d₂·B [m²]
        (m_r = 1, 1.7, 2.5, 3.0 for 1–4 rows, [TrinhChat2006, Table 5.12]; see
        :mod:`chaindrive.catalog`); None when the catalogue gives none.
    ansi : str or None
        ANSI/ASME B29.1 number (e.g. ``"80"`` or ``"80-2"``).
    material : str
        Chain material name (``"steel"`` for catalogue chains).
    source : str
        Where the catalogue row comes from.
    allowable_load : float or None
        The maker's allowable working pull of the whole chain [N] (polymer chains; None when
        the catalogue gives none).
    max_speed : float or None
        The maker's highest chain speed [m/s] (None: not given).
    fatigue_strength : float or None
        Fatigue (minimum dynamic) strength of the whole chain [N]: the largest span force it
        carries for the endurance of the test basis ([ISO606] minimum dynamic strength, tested
        to [ISO15654]); None when the catalogue gives none (catalogue column
        ``fatigue_strength_kN``).

    Raises
    ------
    DesignError
        A non-positive pitch, diameter, breaking load or mass, or a strand count outside 1–8.
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
    fatigue_strength: float | None = None

    @property
    def estimated(self) -> tuple[str, ...]:
        """The catalogue columns of this chain that are estimates, not published values
        (e.g. ``("breaking_load_kN", "mass_kg_m")``): the ones its source lists after
        :data:`ESTIMATE_MARK` (the convention of the polymer catalogue); empty for published
        rows."""
        return estimated_columns(self.source)

    @property
    def ansi_twin(self) -> str | None:
        """The ANSI number of an ISO 606 A chain, the same chain under the other standard
        ([ISO606], [ANSI-B29.1]); None for an ANSI entry (its designation names it) and for
        chains without one."""
        return None if self.standard == "ANSI" else self.ansi

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
    """A sprocket or chain material, SI units.

    Parameters
    ----------
    name : str
        The catalogue name (``"steel 45"``, ``"polyamide PA6"`` …).
    family : str
        The family it belongs to (``"carbon steel"``, ``"grey cast iron"``, a plastic …);
        decides :attr:`is_polymer`.
    density : float
        Density ρ [kg/m³].
    youngs_modulus : float
        Young's modulus E [Pa].
    tensile_strength : float or None
        Ultimate tensile strength [Pa] (None: not given).
    friction_vs_steel : float or None
        Coefficient of sliding friction against steel [-] (None: not given).
    source : str
        Where the values come from (a key of docs/references.md).
    """

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

    Parameters
    ----------
    standard : str
        ``"ISO 606"``, ``"ANSI"`` or ``"GOST 13568"``.
    series : str or None
        ``"A"`` or ``"B"`` (ISO 606), or None for any.
    strands : int or None
        A fixed number of strands [-], or None (simplex is chosen then).
    """

    standard: str
    series: str | None = None
    strands: int | None = None


@dataclass(frozen=True, slots=True)
class Chain:
    """The chain of a drive: a catalogue entry plus what the design fixes.

    Parameters
    ----------
    spec : ChainSpec
        The catalogue chain. When ``request`` is set it is provisional and
        :func:`chaindrive.analyze` replaces it with the lightest feasible chain of the family.
    links : int or None
        Imposed number of links [-] (at least 4; the take-up then finds the position that
        fits it); None: the tight length rounded by ``rounding``.
    allow_odd : bool
        True permits an odd number of links (which needs an offset link).
    request : ChainRequest or None
        Set when the design named no chain: the family to select from.
    contours : int
        Number of identical chain contours side by side on sprockets keyed to common shafts
        [-], 1 for an ordinary drive, at most :data:`MAX_CONTOURS` [Lyashuk].
    rounding : str
        How the tight length is rounded to a whole (even) number of links: ``"round up"``
        (the default, the chain is lengthened), ``"round down"`` (the take-up shortens
        the layout) or ``"nearest"`` (the nearer of the two, up on a tie).
    sag : float or None
        Installed sag of the slack span as a fraction of its length [-], in (0, 0.1]; None:
        laid out tight (see :mod:`chaindrive.geometry.length_options`).
    sag_allowance : float or None
        Installed centre distance shortened by this fraction of the centre distance [-], in
        (0, 0.01] (textbooks: 0.002 … 0.004); None: not shortened. Not with ``sag``.
    link_stiffness : float or None
        Measured axial stiffness of one link (one pitch) of the whole chain, all strands
        [N/m], e.g. from the maker's elastic-elongation curve: k_link = F/(ε p) for a load F
        that stretches the chain by the strain ε = ΔL/L (p: the pitch). None: computed from the
        plates and the pin (:func:`chaindrive.dynamics.stiffness.link_stiffness`, the
        contact compliance of pin, bush and roller left out).

    Raises
    ------
    DesignError
        A rounding rule, sag, contour count or number of links outside what is allowed.
    """

    spec: ChainSpec
    links: int | None = None
    allow_odd: bool = False
    request: ChainRequest | None = None
    contours: int = 1
    rounding: str = "round up"
    sag: float | None = None
    link_stiffness: float | None = None
    sag_allowance: float | None = None

    def __post_init__(self) -> None:
        if self.rounding not in ROUNDINGS:
            raise DesignError("chain.links", f"must be a whole number or one of "
                              f"{', '.join(repr(r) for r in ROUNDINGS)}, got {self.rounding!r}")
        if self.sag is not None and not 0.0 < self.sag <= 0.1:
            raise DesignError("chain.sag", f"must be a fraction of the slack span in (0, 0.1], "
                              f"got {self.sag!r}")
        if self.sag_allowance is not None:
            if not 0.0 < self.sag_allowance <= 0.01:
                raise DesignError("chain.sag_allowance", "must be a fraction of the centre "
                                  f"distance in (0, 0.01], got {self.sag_allowance!r}")
            if self.sag is not None:
                raise DesignError("chain.sag_allowance", "give the installed sag or the sag "
                                  "allowance of the centre distance, not both")
        if self.link_stiffness is not None and not (
                math.isfinite(self.link_stiffness) and self.link_stiffness > 0.0):
            raise DesignError("chain.link_stiffness", "must be a positive finite stiffness "
                              f"[N/m], got {self.link_stiffness!r}")
        if self.link_stiffness is not None and self.request is not None:
            raise DesignError("chain.link_stiffness", "a measured link stiffness belongs to one "
                              "chain: give its designation, or leave the stiffness out to have "
                              "the chain selected")
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

    Parameters
    ----------
    kind : str
        ``"shaft"`` or ``"coupling"``: a torsional spring with a damper from the current node
        to a new node; ``"gear"``: a rigid gear stage (a reducer taken as a whole) to a new
        node; ``"rotor"``: ``inertia`` added to the current node (a body on the same shaft);
        ``"ground"``: a spring (and damper) from the current node to the frame (a torque arm,
        an elastic foundation).
    name : str or None
        The new node's name (shaft, coupling, gear) or the current node's (rotor); None:
        ``<sprocket>.<k>``.
    inertia : float
        Moment of inertia J [kg·m²] of the new node (shaft, coupling: the body at its far
        end; gear: the output-side gear and what turns with it) or added to the current node
        (rotor).
    stiffness : float or None
        Torsional stiffness k [N·m/rad] of a shaft, coupling or ground spring; for a shaft or
        coupling give either this or ``diameter`` and ``length``.
    damping : float
        Viscous torsional damping c [N·m·s/rad] in parallel with the spring.
    ratio : float or None
        Gear ratio i = input speed / output speed [-] in the direction the power flows (from
        the motor to the driver sprocket, from a driven sprocket to its machine).
    efficiency : float
        Efficiency η of a gear stage [-], in (0, 1].
    diameter, length : float or None
        Diameter d [m] and length l [m] of a solid round shaft: k = G π d⁴/(32 l), G of
        ``material`` (:func:`chaindrive.dynamics.model.build.shaft_stiffness`).
    material : str
        Catalogue name of the shaft's material (its shear modulus G).

    Raises
    ------
    DesignError
        An unknown kind, or a value the kind needs missing or out of range.
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
        _check_choice(f"{where}.kind", self.kind, TRAIN_KINDS)
        _check_ranges(where, self, tuple((key, _not_negative, "must be finite and ≥ 0", "")
                                         for key in ("inertia", "damping")))
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

    Parameters
    ----------
    name : str
        Unique name in the drive (``"S1"`` …).
    teeth : int
        Number of teeth z [-], from :data:`MIN_TEETH` to :data:`MAX_TEETH`.
    x, y : float
        Centre [m].
    role : {"driver", "driven", "idler"}
        What it does; exactly one sprocket of a drive is the driver.
    speed : float or None
        Angular speed [rad/s], given on the driver only (the others follow from it).
    side : {"outside", "inside"}
        ``"inside"`` when the chain wraps it from the inside of the contour (it then turns
        the other way).
    adjustable : bool
        True for the one sprocket that takes up the chain.
    adjust_angle : float or None
        Direction of its line of adjustment [rad] (None: the default, see
        :func:`chaindrive.geometry.contour.adjustment_direction`).
    inertia : float or None
        Moment of inertia [kg·m²] of what turns rigidly with it — without a train, everything
        on its shaft referred to it (None: the sprocket body from its geometry). Give this or
        ``reduced_mass``, not both.
    material : str
        Sprocket material (catalogue name).
    power_share : float or None
        Share of the power taken off here [-], from 0 to 1 (driven sprockets; None: an equal
        part of what the others leave, :func:`chaindrive.strength.loads.power_shares`).
    flywheel : float
        Inertia added as a steel flywheel on its shaft [kg·m²] (counted in the dynamics, the
        mass and the cost).
    reduced_mass : float or None
        The inertia as a mass at the pitch radius [kg], m = J/R² [MultimassChainDrives, §3.1].
    train : tuple of TrainElement
        The open train on its shaft, outward from the sprocket.
    load : str or None
        Law of the driven machine's moment in speed: ``"constant"``, ``"linear"`` or
        ``"quadratic"`` (None: ``[dynamics] resistance``).
    bore : float or None
        Bore of the sprocket for its drawing [m] (None: the body model's 0.19·z·p/π).
    bore_fit : str
        ISO 286 hole-basis class of the bore: ``"H6"``, ``"H7"`` or ``"H8"``.
    keyway : bool
        The drawing gives the bore a DIN 6885-1 hub keyway (False: no keyway).
    hardening : str or None
        Heat-treatment note of the drawing (None: not given).
    bearings : tuple of float or None
        Axial positions of the shaft's two bearings from the sprocket's mid-plane [m]
        (signed, along the shaft; None: not given, no bearing reactions).

    Raises
    ------
    DesignError
        A value out of range, naming the sprocket and the field.
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
    bore: float | None = None
    bore_fit: str = "H7"
    keyway: bool = True
    hardening: str | None = None
    bearings: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        where = f"sprockets[{self.name}]"
        if self.bearings is not None and not (
                len(self.bearings) == 2 and all(math.isfinite(z) for z in self.bearings)
                and abs(self.bearings[1] - self.bearings[0]) >= 1e-3):
            raise DesignError(f"{where}.bearings", "must be two finite positions at least 1 mm "
                              f"apart, got {self.bearings!r} m")
        _check_ranges(where, self, (("bore", _positive, "must be positive", " m"),))
        _check_choice(f"{where}.bore_fit", self.bore_fit, BORE_FITS)
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
        if self.load is not None:
            _check_choice(f"{where}.load", self.load, LOAD_LAWS)
        if (not isinstance(self.teeth, int) or isinstance(self.teeth, bool)
                or not MIN_TEETH <= self.teeth <= MAX_TEETH):
            raise DesignError(
                f"{where}.teeth",
                f"must be a whole number from {MIN_TEETH} to {MAX_TEETH}, got {self.teeth!r}",
            )
        _check_choice(f"{where}.role", self.role, ROLES)
        _check_choice(f"{where}.side", self.side, SIDES)
        for name in ("x", "y"):
            if not math.isfinite(getattr(self, name)):
                raise DesignError(f"{where}.{name}", f"must be finite, got {getattr(self, name)!r}")
        _check_ranges(where, self, (
            ("speed", _positive, "must be positive", " rad/s"),
            ("inertia", _positive, "must be positive", " kg·m²"),
            ("flywheel", _not_negative, "must be ≥ 0", " kg·m²"),
            ("power_share", lambda v: 0 <= v <= 1, "must be from 0 to 1", "")))

    def moved_to(self, x: float, y: float) -> Sprocket:
        """A copy of this sprocket at a new centre (used by the take-up).

        Parameters
        ----------
        x, y : float
            The new centre [m].

        Returns
        -------
        Sprocket
            The copy.
        """
        return replace(self, x=x, y=y)


MOTORS: tuple[str, ...] = ("kloss", "constant", "ramp")
RESISTANCES: tuple[str, ...] = LOAD_LAWS


@dataclass(frozen=True, slots=True)
class Motor:
    """The motor on the driver's train (the ``[motor]`` table of a design file).

    The rotor sits on the outermost node of the driver's train (on the driver's shaft when it
    has no train).

    Parameters
    ----------
    law : str or None
        ``"kloss"`` (induction motor, Kloss formula), ``"constant"`` or ``"ramp"`` torque
        (None: the ``[dynamics] motor`` law).
    rated_power : float or None
        Rated power [W] (None: the drive's power).
    rated_speed : float or None
        Rated speed of the motor shaft [rad/s] (None: the driver's speed times the ratios of
        its train).
    rotor_inertia : float or None
        Rotor moment of inertia [kg·m²] (None: estimated from the rated power and
        synchronous speed, :func:`chaindrive.dynamics.motor_inertia.estimated_rotor_inertia`).
    breakdown_ratio : float or None
        λ = M_k/M_r of the Kloss law [-], in (1, 5] (None: the ``[dynamics]`` value).
    critical_slip : float or None
        Critical slip s_k of the Kloss law [-], in (0, 1) (None: the ``[dynamics]`` value).
    ramp_time : float or None
        Duration of the ramp law [s] (None: the ``[dynamics]`` value).
    torque : float or None
        Torque of the constant or ramp law [N·m] (None: the rated torque).

    Raises
    ------
    DesignError
        An unknown law or a value out of range.
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
        if self.law is not None:
            _check_choice("motor.law", self.law, MOTORS)
        _check_ranges("motor", self, (
            *((key, _positive, "must be positive", "")
              for key in ("rated_power", "rated_speed", "rotor_inertia", "ramp_time", "torque")),
            ("breakdown_ratio", lambda v: 1 < v <= 5, "must be in (1, 5]", ""),
            ("critical_slip", lambda v: 0 < v < 1, "must be in (0, 1)", "")))


@dataclass(frozen=True, slots=True)
class DynamicsSettings:
    """What the dynamic analyses of a drive use (the ``[dynamics]`` table of a design file).

    Parameters
    ----------
    damping_ratio : float or None
        Damping ratio ζ of the chain spans [-], from 0 to below 1 (None: by the
        chain/sprocket material pair, :data:`chaindrive.dynamics.damping.PAIR_DAMPING_RATIOS`).
    harmonics : int
        Harmonics of the tooth frequency in the polygonal excitation [-]
        ([MultimassChainDrives]: 10 are practically exact).
    transient : bool
        True runs the start-up.
    startup_duration : float or None
        Simulated duration of the start-up [s] (None: automatic, from the rigid-drive
        run-up, :func:`chaindrive.dynamics.transient.runup.startup_durations`).
    motor : str
        ``"kloss"`` (induction motor with the drive's power and the driver speed as rated
        values), ``"constant"`` (rated torque from t = 0) or ``"ramp"`` (soft start over
        ``ramp_time``).
    breakdown_ratio : float
        λ = M_k/M_r of the Kloss law [-].
    critical_slip : float
        Critical slip s_k of the Kloss law [-].
    ramp_time : float
        Duration of the soft start [s].
    resistance : str
        Moment of resistance on the driven sprockets: ``"constant"``, ``"linear"`` or
        ``"quadratic"`` in speed.
    eccentricity : float
        Eccentricity of every sprocket [m] (an internal disturbance,
        [MultimassChainDrives, §2]).
    pitch_scatter : float
        Standard deviation σ of the link pitches [m] (internal disturbance).
    accumulated_error : float
        Accumulated error of the chain length [m] (internal disturbance).
    hinge_friction : bool
        True gives each span the damping ratio ζ = ψ/4π of hinge friction at its own tension
        [ChainHingeDissipation, eq. 14] instead of ``damping_ratio``.
    hinge_amplitude : float
        Relative transverse amplitude ȳ₀ = y₀/a of the spans for the hinge friction [-], in
        (0, 0.1].
    uncertainty : float
        Relative uncertainty u of stiffnesses and inertias [-] (±u; the bands of the natural
        frequencies, margins and K_D), from 0 to below 0.5.
    require_complete_model : bool
        True makes an incomplete model (a driver without its motor, a driven sprocket with
        nothing on its shaft) an error instead of a warning.

    Raises
    ------
    DesignError
        A value out of range or an unknown law.
    """

    damping_ratio: float | None = None
    harmonics: int = 10
    transient: bool = True
    startup_duration: float | None = None
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
        _check_ranges("dynamics", self, (
            ("uncertainty", lambda v: 0.0 <= v < 0.5, "must be from 0 to below 0.5", ""),
            ("startup_duration", lambda v: 0.0 < v <= 60.0, "must be in (0, 60] s", ""),
            ("hinge_amplitude", lambda v: 0.0 < v <= 0.1, "must be in (0, 0.1]", ""),
            ("damping_ratio", lambda v: 0.0 <= v < 1.0, "must be from 0 to below 1", "")))
        _check_choice("dynamics.motor", self.motor, MOTORS)
        _check_choice("dynamics.resistance", self.resistance, RESISTANCES)


@dataclass(frozen=True, slots=True)
class Drive:
    """A chain drive: one closed chain contour round 2 to 24 sprockets.

    Parameters
    ----------
    name : str
        The design's name.
    chain : Chain
        The chain and what the design fixes about it.
    sprockets : tuple of Sprocket
        The sprockets in the order the chain runs round them (:data:`MIN_SPROCKETS` to
        :data:`MAX_SPROCKETS`, names unique, exactly one driver).
    power : float or None
        Power transmitted from the driver [W] (None when only geometry is wanted).
    tooth_form : {"ISO 606", "GOST 591"}
        Sprocket tooth form for tip and root diameters ([ISO606], [GOST591]).
    service_factor : float or None
        Service (application) factor of the drive [-] (None: 1).
    dynamics : DynamicsSettings
        What the dynamic analyses use.
    notes : dict of str to str
        Free notes carried from the design file (shown, never computed with).
    motor : Motor or None
        The motor on the driver's train (None: not modelled; the start-up then uses the
        ``[dynamics]`` law).
    driver_duty, driven_duty : str or None
        Duty classes of the driver (:data:`DRIVER_DUTIES`) and of the driven machine
        (:data:`DRIVEN_DUTIES`) that give the service factor when ``service_factor`` is not
        given (:func:`chaindrive.strength.duty.service_factor_for`); None: not given.
    required_life : float or None
        Required wear life [s] (None: the rating method's own basis).
    rotation : {"cw", "ccw"} or None
        Direction of rotation of the driver on the drawing plane; the chain runs round the
        sprockets in the order that agrees with it
        (:func:`chaindrive.geometry.contour.in_travel_order`). None: the order of the
        sprockets decides.

    Raises
    ------
    DesignError
        A contour of the wrong size, duplicate names, no driver or several, a speed on a
        sprocket other than the driver, a power without a driver speed, more than one
        adjustable sprocket.
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
    driver_duty: str | None = None
    driven_duty: str | None = None
    required_life: float | None = None
    rotation: str | None = None

    def __post_init__(self) -> None:
        for name, allowed in (("driver_duty", DRIVER_DUTIES), ("driven_duty", DRIVEN_DUTIES),
                              ("rotation", ROTATIONS)):
            value = getattr(self, name)
            if value is not None and value not in allowed:
                key = {"driver_duty": "driver", "driven_duty": "driven"}.get(name, name)
                raise DesignError(f"drive.{key}", f"got {value!r}; allowed: "
                                  + ", ".join(f'"{a}"' for a in allowed))
        if self.required_life is not None and not (math.isfinite(self.required_life)
                                                   and self.required_life > 0):
            raise DesignError("drive.required_life",
                              f"must be a positive time, got {self.required_life!r} s")
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
        answered, so it is cleared; a measured link stiffness is kept for the same chain
        only).

        Parameters
        ----------
        spec : ChainSpec
            The catalogue chain.

        Returns
        -------
        Drive
            The copy.
        """
        same = spec.designation == self.chain.spec.designation
        return replace(self, chain=replace(
            self.chain, spec=spec, request=None,
            link_stiffness=self.chain.link_stiffness if same else None))

    def with_sprockets(self, sprockets: tuple[Sprocket, ...]) -> Drive:
        """A copy with other sprockets (e.g. after the take-up).

        Parameters
        ----------
        sprockets : tuple of Sprocket
            The new sprockets, in the order the chain runs round them.

        Returns
        -------
        Drive
            The copy (validated again).
        """
        return replace(self, sprockets=sprockets)
