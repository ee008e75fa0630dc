"""The teeth of polymer sprockets: the load on the most loaded tooth, its root bending stress
and its contact pressure, and the checks against the material's allowables.

A steel sprocket is held by the chain's rules (its teeth outlast the chain); a polymer one
may fail first, at the tooth root or at the flank, so every polymer sprocket gets two checks:

* **load on the most loaded tooth** — the rigid roller chain on a rigid sprocket with every
  seated roller on its flank [Naji1983, §2.1]: a roller's two link tensions and the flank's
  normal force are in equilibrium (Lami's theorem). With the rollers on the pitch polygon
  (articulation angle 2π/z) and the flank normal at the seating half-angle α from the
  inward radial, the tension falls from link to link by q = cos(α + π/z)/cos(α − π/z) and
  the tooth under the first seated roller carries P₁ = T₀·sin(2π/z)/cos(α − π/z), T₀ the
  tension of the span running onto the wrap. This is Binder's law [Binder1956]
  T_k/T_(k−1) = sin φ/sin(φ + 2π/z) written with the seat's half-angle: his pressure angle
  φ, between the tooth force's line of action and the link's centre line, is
  φ = π/2 − α − π/z (the convention of the ANSI tooth form's published pressure angles
  [ANSI-B29.1], which it reproduces from their seating angle: :func:`seating_pressure_angle`).
  The first tooth is the most loaded (q < 1); T₀ is the larger tension of the sprocket's
  two spans, the design's service factor K_A applied to it as to the nominal force of a
  plastic gear [VDI2736, Part 2].
* **root bending stress** (a Lewis-type cantilever; the reading is ours): the tooth is a
  cantilever on the chord between the bottoms of its two seats, s = 2·(R − r_i)·sin(π/z),
  of the rim width b of the polymeric proportions b ≈ 0.85·B_in
  [MultimassChainDrives, §3.4] (one row per strand); the component P₁·sin α across the
  tooth acts at the height r_i·(1 − cos α) of the contact above that chord:
  σ_F = 6·P₁·sin α·r_i·(1 − cos α)/(b·s²). A nominal stress: no notch factor.
* **contact pressure**: the roller (radius r₁) in its seat (radius r_i ≥ r₁), a cylinder in
  a cylindrical socket [Roark2012, Table 14.1, case 2c]:
  p = 0.798·√(w/(K_D·C_E)), w = P₁/b, K_D = 2r₁·2r_i/(2r_i − 2r₁),
  C_E = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂; ν = 0.3 for a metal [Roark2012], and for a polymer,
  whose Poisson ratio the catalogue does not give, the incompressible bound ν = 0.5 (the
  largest p).

The allowables are the material's permissible root stress σ_FP and flank pressure σ_HP
at its tooth temperature (the plastic-gear rating of [VDI2736, Part 2] gives them from
the material's fatigue data at that temperature). No confirmed value of either is known to
the package for any polymer, so both checks "cannot be verified" and say which input is
missing: a design on polymer sprockets is never reported as passing its checks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.checks import Check, judged
from chaindrive.errors import Quantities
from chaindrive.geometry.body import polymeric_sprocket_proportions
from chaindrive.geometry.iso606 import iso606_seating_angle_range
from chaindrive.geometry.results import GeometryResult
from chaindrive.geometry.sprocket import seating_geometry
from chaindrive.model import Drive, Material
from chaindrive.strength.loads import LoadsResult

__all__ = ["METAL_POISSON", "POLYMER_POISSON_BOUND", "ToothLoad", "ansi_pressure_angles",
           "binder_tooth_factors", "flank_limit_factors", "iso606_pressure_angle_range",
           "polymer_tooth_checks", "root_bending_stress", "seat_contact_pressure",
           "seating_pressure_angle", "tooth_loads"]

#: Poisson ratio of a metal roller or sprocket [-] (steel) [Roark2012].
METAL_POISSON = 0.3
#: Poisson ratio taken for a polymer, whose value the catalogue does not give: the
#: incompressible bound, which gives the largest contact pressure [-].
POLYMER_POISSON_BOUND = 0.5
#: Roark's constant of the line contact, √(2/π) to three figures [Roark2012, Table 14.1].
_ROARK_LINE = 0.798

_SOURCE = "[VDI2736, Part 2]"


def binder_tooth_factors(teeth: int, pressure_angle: float) -> tuple[float, float]:
    """Binder's tension ratio from tooth to tooth and load of a tooth per entering tension:
    a rigid roller chain on a rigid sprocket, every seated roller bearing on its flank.

    T_k/T_(k−1) = sin φ/sin(φ + 2β) and P_k/T_(k−1) = sin 2β/sin(φ + 2β), 2β = 2π/z the
    articulation angle (Lami's theorem for the roller's two link tensions and the flank's
    force), so T_k = T₀·(sin φ/sin(φ + 2β))^k along the wrap from its tight end.

    Parameters
    ----------
    teeth : int
        z [-].
    pressure_angle : float
        Binder's pressure angle φ: the angle between the line of action of the tooth's
        force on the roller (the flank normal through the roller's centre) and the centre
        line of the link that carries the larger tension [rad].

    Returns
    -------
    tuple of float
        (T_k/T_(k−1), P_k/T_(k−1)) [-].

    References
    ----------
    [Binder1956] (the law and its pressure angle); [Naji1983, §2.1] (the same rigid-chain
    equilibrium, written with the flank's contact point).
    """
    articulation = 2.0 * math.pi / teeth
    ahead = math.sin(pressure_angle + articulation)
    return math.sin(pressure_angle) / ahead, math.sin(articulation) / ahead


def seating_pressure_angle(teeth: int, half_angle: float) -> float:
    """Binder's pressure angle of a roller at the end of its seating curve.

    φ = π/2 − α − π/z: the flank normal there lies at the seating half-angle α from the
    inward radial, the link's centre line (a side of the pitch polygon) at π/2 − π/z.
    With the ANSI seat's end at A = 35° + 60°/N off the pitch circle's tangent
    (α = 90° − A) it gives 35° − 120°/N, the ANSI pressure angle for new chain.

    Parameters
    ----------
    teeth : int
        z [-].
    half_angle : float
        Seating half-angle α: the flank normal from the inward radial [rad].

    Returns
    -------
    float
        φ [rad].

    References
    ----------
    [Binder1956] (φ from the link's centre line); [ANSI-B29.1] (the tooth form whose
    published pressure angle it reproduces).
    """
    return 0.5 * math.pi - half_angle - math.pi / teeth


def iso606_pressure_angle_range(teeth: int) -> tuple[float, float]:
    """Binder's pressure angle at the ends of the ISO 606 band of seating curves.

    φ = 90° − α_s/2 − 180°/z for the full seating angle α_s between its limits
    120° − 90°/z and 140° − 90°/z: φ from 20° − 135°/z (the maximum seating angle, the
    minimum tooth-gap form) to 30° − 135°/z (the minimum seating angle).

    Parameters
    ----------
    teeth : int
        z [-].

    Returns
    -------
    tuple of float
        (φ_min, φ_max) [rad].

    References
    ----------
    [ISO606] (the seating angle limits); [Binder1956] (the pressure angle).
    """
    low, high = iso606_seating_angle_range(teeth)
    return (seating_pressure_angle(teeth, 0.5 * float(high)),
            seating_pressure_angle(teeth, 0.5 * float(low)))


def ansi_pressure_angles(teeth: int) -> tuple[float, float]:
    """The pressure angles the ANSI (ASME B29.1) tooth form publishes: 17° − 64°/N
    (minimum, the roller at the top of the working curve) and 35° − 120°/N (new chain,
    the roller at the end of the seating curve).

    Parameters
    ----------
    teeth : int
        N [-].

    Returns
    -------
    tuple of float
        (φ_min, φ_new) [rad].

    References
    ----------
    [ANSI-B29.1] (the tooth form table, reproduced in [Oberg2016]); [Kidd1999] (35° − 120°/N).
    """
    return math.radians(17.0 - 64.0 / teeth), math.radians(35.0 - 120.0 / teeth)


def flank_limit_factors(teeth: int, half_angle: float) -> tuple[float, float]:
    """Tension ratio from link to link and load of a tooth per entering tension, for a rigid
    roller chain on a rigid sprocket with every roller on its flank at the end of its seat.

    q = cos(α + π/z)/cos(α − π/z) and P/T = sin(2π/z)/cos(α − π/z): Binder's law
    (:func:`binder_tooth_factors`) at the pressure angle of the seat's end
    (:func:`seating_pressure_angle`).

    Parameters
    ----------
    teeth : int
        z [-].
    half_angle : float
        Seating half-angle α: the flank normal from the inward radial [rad].

    Returns
    -------
    tuple of float
        (q, P/T) [-]: T_k = q·T_(k−1), the k-th tooth carries (P/T)·T_(k−1).

    References
    ----------
    [Naji1983, §2.1] (rigid chain, rigid stationary sprocket); [Binder1956].
    """
    return binder_tooth_factors(teeth, seating_pressure_angle(teeth, half_angle))


def root_bending_stress(load: float, half_angle: float, seating_radius: float,
                        pitch_radius: float, teeth: int, width: float) -> float:
    """Lewis-type root bending stress of a sprocket tooth (reading in the module docstring).

    σ_F = 6·P·sin α·r_i·(1 − cos α)/(b·s²), s = 2·(R − r_i)·sin(π/z).

    Parameters
    ----------
    load : float
        Tooth load P [N].
    half_angle : float
        Seating half-angle α [rad].
    seating_radius : float
        Seating radius r_i [m].
    pitch_radius : float
        Pitch radius R [m].
    teeth : int
        z [-].
    width : float
        Tooth width b [m].

    Returns
    -------
    float
        σ_F [Pa].

    References
    ----------
    [MultimassChainDrives, §3.4] (the width); the cantilever is ours.
    """
    s = 2.0 * (pitch_radius - seating_radius) * math.sin(math.pi / teeth)
    arm = seating_radius * (1.0 - math.cos(half_angle))
    return 6.0 * load * math.sin(half_angle) * arm / (width * s * s)


def seat_contact_pressure(load: float, roller_radius: float, seating_radius: float,
                          width: float, compliance: float) -> float:
    """Largest contact pressure of a roller in its seat (a cylinder in a cylindrical socket).

    p = 0.798·√(w/(K_D·C_E)), w = P/b, K_D = D₁D₂/(D₂ − D₁).

    Parameters
    ----------
    load : float
        Tooth load P [N].
    roller_radius : float
        r₁ [m].
    seating_radius : float
        r_i [m] (> r₁; an equal radius has no Hertzian contact: the pressure is then taken
        for the roller on a flat, the smaller conformity).
    width : float
        Contact length b [m].
    compliance : float
        C_E = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ [1/Pa].

    Returns
    -------
    float
        p [Pa].

    References
    ----------
    [Roark2012, Table 14.1, cases 2a and 2c].
    """
    d1, d2 = 2.0 * roller_radius, 2.0 * seating_radius
    k_d = d1 * d2 / (d2 - d1) if d2 > d1 else d1
    return _ROARK_LINE * math.sqrt(load / width / (k_d * compliance))


def _compliance(material: Material) -> float:
    nu = POLYMER_POISSON_BOUND if material.is_polymer else METAL_POISSON
    return (1.0 - nu * nu) / material.youngs_modulus


@dataclass(frozen=True, slots=True)
class ToothLoad:
    """The most loaded tooth of one sprocket.

    Parameters
    ----------
    sprocket : str
        Its name.
    entering_tension : float
        T₀ with K_A: the larger tension of its two spans [N].
    load : float
        P₁ on the first seated tooth [N].
    root_stress : float
        σ_F [Pa].
    contact_pressure : float
        p [Pa].
    width : float
        Tooth width b, all strands [m].
    """

    sprocket: str
    entering_tension: float
    load: float
    root_stress: float
    contact_pressure: float
    width: float


@shared_parameters
def tooth_loads(drive: Drive, geometry: GeometryResult, loads: LoadsResult,
                indices: tuple[int, ...]) -> tuple[ToothLoad, ...]:
    """The most loaded tooth of each of the given sprockets (module docstring).

    Parameters
    ----------
    %(drive_geometry)s
    loads : LoadsResult
        Its span tensions [N].
    indices : tuple of int
        The sprockets.

    Returns
    -------
    tuple of ToothLoad
        In the order of ``indices``.

    References
    ----------
    [Naji1983]; [Roark2012]; [MultimassChainDrives, §3.4]; [VDI2736, Part 2] (K_A).
    """
    spec = drive.chain.spec
    k_a = drive.service_factor or 1.0
    roller = find_material(spec.material, field="chain.material")
    out = []
    for i in indices:
        sp, sg = drive.sprockets[i], geometry.sprockets[i]
        radii, halves = seating_geometry(drive.tooth_form, spec.pitch, [sp.teeth],
                                         spec.roller_diameter, spec.inner_width)
        r_i, alpha = float(radii[0]), float(halves[0])
        tension = k_a * max(loads.span_tensions[s.index] for s in geometry.spans
                            if i in (s.start, s.end))
        _, per_tension = flank_limit_factors(sp.teeth, alpha)
        load = per_tension * tension
        width = spec.strands * polymeric_sprocket_proportions(
            spec.pitch, sp.teeth, spec.inner_width).rim_width
        material = find_material(sp.material, field=f"sprockets[{i}].material")
        out.append(ToothLoad(
            sp.name, tension, load,
            root_bending_stress(load, alpha, r_i, sg.pitch_radius, sp.teeth, width),
            seat_contact_pressure(load, 0.5 * spec.roller_diameter, r_i, width,
                                  _compliance(material) + _compliance(roller)),
            width))
    return tuple(out)


@shared_parameters
def polymer_tooth_checks(drive: Drive, geometry: GeometryResult,
                         loads: LoadsResult) -> tuple[Check, ...]:
    """Root bending stress and contact pressure of the most loaded tooth of every polymer
    sprocket against the material's allowables (module docstring): "cannot be verified"
    while the allowables at the tooth temperature are unknown, the note naming them.

    Parameters
    ----------
    %(drive_geometry)s
    loads : LoadsResult
        Its span tensions [N].

    Returns
    -------
    tuple of Check
        Keyed ``tooth_root_stress[<sprocket>]`` and ``tooth_contact_pressure[<sprocket>]``
        (part "sprockets"); empty when no sprocket is of a polymer.

    References
    ----------
    [Naji1983]; [Roark2012]; [MultimassChainDrives, §3.4]; [VDI2736, Part 2].
    """
    polymer = tuple(i for i, sp in enumerate(drive.sprockets)
                    if find_material(sp.material, field=f"sprockets[{i}].material").is_polymer)
    out: list[Check] = []
    for i, t in zip(polymer, tooth_loads(drive, geometry, loads, polymer), strict=True):
        material = drive.sprockets[i].material
        q = Quantities()
        base = (f"most loaded tooth P₁ = {q(t.load, 'force', '.4g')} from the span tension "
                f"{q(t.entering_tension, 'force', '.4g')} (K_A applied), tooth width "
                f"{q(t.width, 'length', '.3g')}")
        for name, value, allowable in (
                ("tooth root stress", t.root_stress, "σ_FP"),
                ("tooth contact pressure", t.contact_pressure, "σ_HP")):
            out.append(judged(
                name, t.sprocket, value, None, "max", _SOURCE, "MPa", 1e-6,
                note=f"{base}; no confirmed permissible {allowable} of {material} at its "
                     "tooth temperature is known: give the maker's value to verify it",
                part="sprockets", item=t.sprocket, note_quantities=tuple(q.items)))
    return tuple(out)
