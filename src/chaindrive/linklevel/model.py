"""Parameters of the link-level model of a drive (SI units), each from its source.

* Roller (hinge) masses: one pitch of chain per roller, m = q·p [kg] (q the catalogue mass
  per metre) — the chain as mass particles at the roller centres joined by spring–dampers,
  the discrete model of [Pedersen2004] and [Pedersen2005].
* Link (pin–bush joint) stiffness k_link: :func:`chaindrive.dynamics.parameters.chain_link_stiffness`
  (the design's measured value, else plates and pin: the ring model's own value, so both
  models share it); viscous link damping
  c = 2ζ·k_link/ω_ref with the whole-drive model's ζ and ω_ref
  (:func:`chaindrive.dynamics.model.build.drive_model`: ζ the mean of its spans' damping
  ratios, chosen by :func:`chaindrive.dynamics.model.damping.chain_damping` — the design's
  ``[dynamics] damping_ratio``, hinge friction or the material pair; ω_ref the frequency of
  its first chain mode, its ``reference_frequency_hz``): a span of L/p such links is the
  analysis's span damper 2ζ·c_span/ω_ref, so the two models carry the same damping;
  optional clearance Δ (a dead band of the joint).
* Hinge friction: moment f·T̄·d₂/2 opposing the relative rotation of two links,
  f = 0.1 and d₂ the pin diameter [ChainHingeDissipation, eqs. 7–8].
* Roller–tooth contact: linear penalty k_c = the tooth stiffness of
  :func:`chaindrive.dynamics.stiffness.tooth_stiffness` (ISO 6336-1 single-pair stiffness c′
  scaled by the tooth width and the pair's modulus [ISO6336-1]) — the same tooth spring the
  ring model's wrap stiffness is built from, so the two models differ only in what they
  resolve; contact damping c_c = 2ζ_c·√(k_c·m) with ζ_c the damping ratio measured on chain
  drives [MultimassChainDrives, §3.2] (0.06, a restitution of 0.83 for a linear
  spring–dashpot [Gilardi2002]); the force is clamped at 0 (no adhesion).
* Tooth gap: seating radius r_i, seating half-angle α and tip radius R_a of the drive's tooth
  form — ISO 606 (mean of the limits) or GOST 591-69
  (:mod:`chaindrive.geometry.sprocket`); the flanks are taken as the tangents of the seating
  arc at ±α (see docs/linklevel.md: ISO's flank arc r_e ≥ 0.12·d₁(z+2) is nearly straight
  over the roller's travel; GOST's r₁ arc and straight part are replaced by the tangent).
* Sprockets: rigid, rotating about fixed centres, inertia as the ring model
  (``Sprocket.inertia`` or the steel/polymer body of
  :func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`); an optional linear
  torsional system (:class:`TorsionalAttachment`) can be coupled to them.
* Pre-tension T₀: the ring model's start-up pre-tension, the sag tension of the span leaving
  the driver at the installed sag (:func:`chaindrive.strength.loads.installed_pretension`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.catalog import find_material
from chaindrive.dynamics.damping import DEFAULT_DAMPING_RATIO
from chaindrive.dynamics.model.build import DriveModel, drive_model
from chaindrive.dynamics.parameters import drive_ring_parameters
from chaindrive.dynamics.stiffness import (
    GRAVITY,
    tooth_contact_width,
    tooth_stiffness,
)
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import seating_geometry, tip_diameter
from chaindrive.strength.loads import installed_pretension
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, Material

__all__ = ["HINGE_FRICTION", "LinkLevelModel", "TorsionalAttachment", "build_model",
           "seating_geometry"]

#: Friction coefficient in the pin–bush joint, f = 0.1 [ChainHingeDissipation] (worked data).
HINGE_FRICTION = 0.1


@dataclass(frozen=True, slots=True, eq=False)
class TorsionalAttachment:
    """A linear torsional system coupled to the sprockets (e.g. the trains of
    :mod:`chaindrive.dynamics.torsional.model`): rotational coordinates θ = (sprockets…, extra…).

    Parameters
    ----------
    extra_inertias : ndarray
        (e,) moments of inertia of the extra coordinates [kg·m²], each turning in the plane,
        counter-clockwise positive like the sprockets (a coordinate geared to run the other
        way is entered with its sign flipped in K and C).
    stiffness : ndarray
        (n+e, n+e) stiffness on the turns of all coordinates since the start [N·m/rad]
        (symmetric, positive semi-definite: shafts, couplings, gear meshes reduced to one
        speed per coordinate).
    damping : ndarray
        (n+e, n+e) damping on their speeds [N·m·s/rad].
    motor_dof : int or None
        The coordinate the motor drives (None: the driver sprocket).
    load_dofs : tuple of int or None
        (n,) the coordinate that carries sprocket i's moment of resistance (None: each
        sprocket its own).
    """

    extra_inertias: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    motor_dof: int | None = None
    load_dofs: tuple[int, ...] | None = None


@dataclass(frozen=True, slots=True, eq=False)
class LinkLevelModel:
    """Everything the link-level kernel needs, in SI units (module docstring for sources).

    Parameters
    ----------
    names : tuple of str
        Sprocket names.
    links : int
        Number of links N [-].
    pitch : float
        Chain pitch p [m].
    roller_mass : float
        Mass of one roller with its share of the links m [kg].
    roller_radius : float
        Roller radius d₁/2 [m].
    link_stiffness : float
        Axial stiffness of one link [N/m].
    link_damping : float
        Axial damping of one link [N·s/m].
    clearance : float
        Clearance Δ of the pin–bush joint [m].
    hinge_friction : float
        Coefficient of friction f in the hinges [-].
    pin_radius : float
        Pin radius d₂/2 [m].
    pretension : float
        Pre-tension T₀ [N].
    gravity : ndarray
        (2,) acceleration of gravity [m/s²].
    centres : ndarray
        (n, 2) sprocket centres [m].
    teeth : ndarray
        (n,) teeth [-].
    pitch_radii : ndarray
        (n,) pitch radii [m].
    seating_radii : ndarray
        (n,) seating (roller seat) radii r_i [m].
    seating_half_angles : ndarray
        (n,) seating half-angles α [rad].
    tip_radii : ndarray
        (n,) tip radii [m].
    contact_stiffness : ndarray
        (n,) roller–tooth contact stiffness k_c [N/m].
    contact_damping : ndarray
        (n,) roller–tooth contact damping c_c [N·s/m].
    turn : ndarray
        (n,) sense of rotation [-] (+1 counter-clockwise).
    inertias : ndarray
        (n,) sprocket moments of inertia [kg·m²].
    driver : int
        Index of the driver [-].
    reference_frequency_hz : float
        ω_ref/2π of the whole-drive model's chain dampers [Hz] (the link damping; sets the
        record rate).
    torsional : TorsionalAttachment or None
        An attached torsional system (None: none).
    """

    names: tuple[str, ...]
    links: int
    pitch: float
    roller_mass: float
    roller_radius: float
    link_stiffness: float
    link_damping: float
    clearance: float
    hinge_friction: float
    pin_radius: float
    pretension: float
    gravity: NDArray[np.float64]
    centres: NDArray[np.float64]
    teeth: NDArray[np.int64]
    pitch_radii: NDArray[np.float64]
    seating_radii: NDArray[np.float64]
    seating_half_angles: NDArray[np.float64]
    tip_radii: NDArray[np.float64]
    contact_stiffness: NDArray[np.float64]
    contact_damping: NDArray[np.float64]
    turn: NDArray[np.float64]
    inertias: NDArray[np.float64]
    driver: int
    reference_frequency_hz: float
    torsional: TorsionalAttachment | None = field(default=None)

    @property
    def highest_frequency_hz(self) -> float:
        """Bound on the highest natural frequency [Hz]: a roller between two links and one
        tooth, ω² ≤ (4k_link + k_c)/m (Gershgorin bound of the stiffness matrix)."""
        k = 4.0 * self.link_stiffness + float(self.contact_stiffness.max())
        return math.sqrt(k / self.roller_mass) / (2.0 * math.pi)

    @property
    def contact_frequency_hz(self) -> float:
        """Highest natural frequency [Hz] of what stays explicit when the link springs are
        taken implicitly: a roller on one tooth, ω² = k_c/m. The implicit–explicit step is
        stable below 2/ω of the explicit part alone [HughesLiu1978]."""
        return math.sqrt(float(self.contact_stiffness.max()) / self.roller_mass) / (2.0 * math.pi)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready parameters (SI, units in the keys)."""
        return {
            "links": self.links, "pitch_m": self.pitch, "roller_mass_kg": self.roller_mass,
            "roller_radius_m": self.roller_radius,
            "link_stiffness_n_per_m": self.link_stiffness,
            "link_damping_n_s_per_m": self.link_damping, "clearance_m": self.clearance,
            "hinge_friction": self.hinge_friction, "pin_radius_m": self.pin_radius,
            "pretension_n": self.pretension,
            "seating_radius_m": self.seating_radii.tolist(),
            "seating_half_angle_deg": np.degrees(self.seating_half_angles).tolist(),
            "tip_radius_m": self.tip_radii.tolist(),
            "contact_stiffness_n_per_m": self.contact_stiffness.tolist(),
            "contact_damping_n_s_per_m": self.contact_damping.tolist(),
            "sprocket_inertia_kg_m2": self.inertias.tolist(),
            "highest_frequency_hz": self.highest_frequency_hz,
            "contact_frequency_hz": self.contact_frequency_hz,
        }


def _default_lookup() -> Callable[[str], Material]:

    return find_material


def build_model(drive: Drive, geometry: GeometryResult, *,
                hinge_friction: float = HINGE_FRICTION, clearance: float = 0.0,
                contact_damping_ratio: float = DEFAULT_DAMPING_RATIO,
                pretension: float | None = None, gravity: float = GRAVITY,
                damping_ratio: float | None = None,
                torsional: TorsionalAttachment | None = None,
                material_lookup: Callable[[str], Material] | None = None,
                dynamics: DriveModel | None = None) -> LinkLevelModel:
    """Link-level parameters of ``drive`` on its built contour ``geometry`` (module docstring).

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult
        Its contour.
    hinge_friction : float
        Coefficient of friction f in the hinges [-] (0: frictionless hinges).
    clearance : float
        Clearance Δ of the pin–bush joint [m].
    contact_damping_ratio : float
        Damping ratio ζ_c of the roller–tooth contact [-].
    pretension : float or None
        Pre-tension T₀ [N] (None: :func:`chaindrive.strength.loads.installed_pretension`).
    gravity : float
        Acceleration of gravity g [m/s²] (acting along −y).
    damping_ratio : float or None
        Damping ratio ζ of the links [-] (None: the mean of the whole-drive model's span
        damping ratios).
    torsional : TorsionalAttachment or None
        An attached torsional system.
    material_lookup : callable or None
        Name → Material (None: :func:`chaindrive.catalog.find_material`).
    dynamics : DriveModel or None
        The analysis's whole-drive model, whose damping ratios and reference frequency the
        links take (None: :func:`chaindrive.dynamics.model.build.drive_model` of ``drive``).

    Returns
    -------
    LinkLevelModel
        The parameters.

    References
    ----------
    [Pedersen2004], [Pedersen2005] (the model); [ChainHingeDissipation] (hinge friction).
    """
    if not (hinge_friction >= 0 and clearance >= 0 and 0 <= contact_damping_ratio < 1):
        raise DesignError("linklevel", "need hinge_friction ≥ 0, clearance ≥ 0 and "
                          f"0 ≤ contact_damping_ratio < 1, got {hinge_friction!r}, "
                          f"{clearance!r}, {contact_damping_ratio!r}")
    lookup = material_lookup or _default_lookup()
    spec = drive.chain.spec
    chain_mat = lookup(spec.material)
    ring = drive_ring_parameters(drive, geometry, material_lookup=lookup)
    k_link = ring.link_stiffness_n_per_m  # the ring's own (chain_link_stiffness): one value
    if dynamics is None:
        dynamics = drive_model(drive, geometry, material_lookup=lookup, ring=ring)
    f_ref = dynamics.reference_frequency_hz
    m = spec.mass_per_length * spec.pitch
    teeth = np.array([s.teeth for s in drive.sprockets], dtype=np.int64)
    width = tooth_contact_width(spec)
    k_c = np.array([tooth_stiffness(width, lookup(s.material).youngs_modulus,
                                    chain_mat.youngs_modulus) for s in drive.sprockets])
    seat_r, seat_a = seating_geometry(drive.tooth_form, spec.pitch, teeth, spec.roller_diameter,
                                      spec.inner_width)
    tips = 0.5 * np.asarray(tip_diameter(spec.pitch, teeth, spec.roller_diameter,
                                         form=drive.tooth_form), dtype=float)
    zeta = (float(np.mean(dynamics.span_damping_ratios)) if damping_ratio is None
            else float(damping_ratio))
    t0 = installed_pretension(drive, geometry) if pretension is None else float(pretension)
    return LinkLevelModel(
        names=tuple(s.name for s in drive.sprockets), links=geometry.links, pitch=spec.pitch,
        roller_mass=m, roller_radius=0.5 * spec.roller_diameter, link_stiffness=k_link,
        link_damping=2.0 * zeta * k_link / (TWO_PI * f_ref) if f_ref > 0 else 0.0,
        clearance=float(clearance), hinge_friction=float(hinge_friction),
        pin_radius=0.5 * spec.pin_diameter, pretension=t0,
        gravity=np.array([0.0, -float(gravity)]),
        centres=np.array([[g.x, g.y] for g in geometry.sprockets], dtype=float),
        teeth=teeth, pitch_radii=np.array([g.pitch_radius for g in geometry.sprockets]),
        seating_radii=seat_r, seating_half_angles=seat_a, tip_radii=tips,
        contact_stiffness=k_c, contact_damping=2.0 * contact_damping_ratio * np.sqrt(k_c * m),
        turn=np.array([float(g.turn) for g in geometry.sprockets]),
        inertias=ring.inertias_kg_m2.copy(), driver=drive.driver_index,
        reference_frequency_hz=float(f_ref), torsional=torsional,
    )
