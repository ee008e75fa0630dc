"""Reduced masses and branch stiffnesses of the ring model of a drive.

Every branch (span) i of the contour is a chain of L_i/p links in series with the wrap of
the chain on the sprockets at both ends (tooth contact compliance), and — for a span with
low tension — reduced by the sag of the span (equivalent-modulus formula)::

    1/c_i = L_i / (p·k_link) + 1/k_wrap(start) + 1/k_wrap(end),   c_i ← c_i · s_sag(T_i)

Masses: m_i = I_i / R_i² (seed 000 §3.1, seed-notes §1). See docs/dynamics.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.damping import loss_factor, series_loss_factor
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import sprocket_mass_and_inertia

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import ChainSpec, Drive, Material

__all__ = [
    "E_STEEL",
    "GRAVITY",
    "TOOTH_STIFFNESS_PER_WIDTH",
    "RingParameters",
    "chain_span_stiffness",
    "drive_ring_parameters",
    "link_stiffness",
    "plate_thickness",
    "reduced_mass",
    "ring_damping_ratio",
    "sag_stiffness_factor",
    "series_stiffness",
    "static_span_tensions",
    "tooth_stiffness",
    "wrap_stiffness",
]

GRAVITY = 9.80665
#: Reference Young's modulus of steel in ISO 6336-1 [Pa].
E_STEEL = 206e9
#: Single tooth-pair stiffness per unit face width of steel spur gears, c' ≈ 14 N/(mm·µm)
#: [N/m²] (ISO 6336-1, typical value of c'); used for one sprocket tooth loaded by a roller.
TOOTH_STIFFNESS_PER_WIDTH = 14e9
#: Sprocket tooth (and disc) width as a fraction of the chain inner width b1 (ISO 606:
#: b_f1 ≈ 0.93·b1 for p ≤ 12.7 mm, 0.95·b1 above).
TOOTH_WIDTH_FACTOR = 0.93


def reduced_mass(inertia: ArrayLike, radius: ArrayLike) -> NDArray[np.float64]:
    """Reduced mass m = I / R² [kg] of a rotating mass brought to the hinge radius.

    inertia : I [kg·m²]; radius : R, pitch radius of the hinge centres [m].
    Source: seed 000 §3.1 ("bringing the revolved masses over to the radii of the end
    hinges"), seed-notes §1.
    """
    return np.asarray(inertia, dtype=float) / np.asarray(radius, dtype=float) ** 2


def plate_thickness(spec: ChainSpec) -> float:
    """Estimated link plate thickness s [m] of a chain.

    With the transverse pitch p_t known, p_t ≈ b1 + 2 s_inner + 2 s_outer ≈ b1 + 4 s, so
    s = (p_t − b1)/4 (checks: 08A gives 1.63 mm vs 1.5 mm catalogue, 12A 2.55 vs 2.4 mm);
    without it s = p/8 (ANSI plates: 0.12–0.126 p). Our estimate, documented in
    docs/dynamics.md.
    """
    if spec.transverse_pitch and spec.transverse_pitch > spec.inner_width:
        return (spec.transverse_pitch - spec.inner_width) / 4.0
    return spec.pitch / 8.0


def link_stiffness(spec: ChainSpec, youngs_modulus: float) -> float:
    """Axial stiffness k_link [N/m] of one link (one pitch) of the whole chain.

    Model (ours, docs/dynamics.md): the two plates of a link in parallel — net section
    (h − d2)·s over a length d2 at the hole, gross section h·s over p − d2 — in series with
    the bending of the pin as a clamped–clamped beam under a uniform load over its span
    l = b1 + 3s (compliance l³/(384 E I), I = π d2⁴/64; Roark, Table 8.1 case 2e); all
    strands in parallel. spec: catalogue chain (pitch p, plate depth h = h2, pin diameter
    d2, inner width b1); youngs_modulus E of the chain material [Pa].
    """
    p, h, d2, b1 = spec.pitch, spec.plate_depth, spec.pin_diameter, spec.inner_width
    if not (h > d2 > 0 and b1 > 0):
        raise DesignError("chain.plate_depth",
                          f"plate depth {h!r} m must exceed the pin diameter {d2!r} m")
    s = plate_thickness(spec)
    E = youngs_modulus
    plates = (d2 / (h - d2) + (p - d2) / h) / (E * 2.0 * s)
    span = b1 + 3.0 * s
    pin = span**3 / (384.0 * E * math.pi * d2**4 / 64.0)
    return spec.strands / (plates + pin)


_link_stiffness_from_plates = link_stiffness


def chain_span_stiffness(link_k: ArrayLike, span_length: ArrayLike,
                         pitch: float) -> NDArray[np.float64]:
    """Stiffness c = k_link · p / L [N/m] of a span of length L [m] (L/p links in series).

    link_k : stiffness of one link [N/m]; pitch p [m]. Equivalently c = EA_eff / L with
    EA_eff = k_link · p.
    """
    return np.asarray(link_k, dtype=float) * pitch / np.asarray(span_length, dtype=float)


def tooth_stiffness(width: float, e_sprocket: float, e_roller: float,
                    per_width: float = TOOTH_STIFFNESS_PER_WIDTH) -> float:
    """Contact stiffness k_t [N/m] of one sprocket tooth under a roller.

    k_t = c' · b · E_red / E_steel with E_red = 2 E1 E2 / (E1 + E2): the single tooth-pair
    stiffness c' of ISO 6336-1 (≈ 14 N/(mm·µm) for steel) scaled, as ISO 6336-1 does for
    other material pairs, by the reduced modulus of the pair (sprocket and roller).
    width b [m] (tooth width); e_sprocket, e_roller [Pa]. A roller seated at the tooth root
    loads the tooth less in bending than a gear tooth: this is a conservative (soft) value.
    """
    e_red = 2.0 * e_sprocket * e_roller / (e_sprocket + e_roller)
    return per_width * width * e_red / E_STEEL


def wrap_stiffness(tooth_k: float, link_k: float, teeth_in_mesh: float) -> float:
    """Stiffness [N/m] with which the wrap of the chain on a sprocket holds a span's end.

    Ladder model of the load sharing among the N = max(1, ⌊teeth in mesh⌋) teeth: each
    engaged roller is held by a tooth spring k_t, consecutive rollers are joined by a link
    k_link (spring model of sprocket load distribution, Naji & Marshek, Mech. Mach. Theory
    18(5), 1983). Input stiffness from the span side, by the recursion (ours)
    K_N = k_t, K_j = k_t + k_link K_{j+1} / (k_link + K_{j+1}); for N → ∞ it tends to
    k_t/2 + sqrt(k_t²/4 + k_t k_link).
    """
    n = max(1, math.floor(teeth_in_mesh))
    k = tooth_k
    for _ in range(n - 1):
        k = tooth_k + link_k * k / (link_k + k)
    return k


def series_stiffness(*stiffnesses: ArrayLike) -> NDArray[np.float64]:
    """Springs in series: 1/c = Σ 1/c_i [N/m] (a zero member gives 0)."""
    arrays = np.broadcast_arrays(*[np.asarray(s, dtype=float) for s in stiffnesses])
    with np.errstate(divide="ignore"):
        compliance = sum(1.0 / a for a in arrays)
    return np.where(np.isfinite(compliance), 1.0 / compliance, 0.0)


def sag_stiffness_factor(axial_rigidity: ArrayLike, weight_per_length: ArrayLike,
                         horizontal_length: ArrayLike, tension: ArrayLike) -> NDArray[np.float64]:
    """Factor s = 1 / (1 + (w l)² EA / (12 T³)) on the axial stiffness of a sagging span.

    Dischinger–Ernst equivalent modulus of a sagging cable, E_eq = E / (1 + (γ l)² E / (12
    σ³)) (H.-J. Ernst, Der E-Modul von Seilen unter Berücksichtigung des Durchhanges, Der
    Bauingenieur 40(2), 1965), written with forces: axial_rigidity EA = k_link·p [N];
    weight_per_length w = q g [N/m]; horizontal_length l = L cos(inclination) [m];
    tension T [N] (≤ 0: the span is slack, factor 0).
    """
    ea = np.asarray(axial_rigidity, dtype=float)
    w = np.asarray(weight_per_length, dtype=float)
    lh = np.asarray(horizontal_length, dtype=float)
    t = np.asarray(tension, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = 1.0 / (1.0 + (w * lh) ** 2 * ea / (12.0 * t**3))
    return np.where(t > 0, s, 0.0)


@dataclass(frozen=True, slots=True, eq=False)
class RingParameters:
    """Masses and branch stiffnesses of a drive's ring model with their parts.

    masses_kg (n,) reduced masses; inertias_kg_m2 (n,) I used; pitch_radii_m (n,);
    stiffness_n_per_m (n,) branch stiffness (branch i joins sprocket i and i+1);
    chain_stiffness_n_per_m (n,) chain alone; wrap_stiffness_n_per_m (n,) each sprocket's
    wrap (tooth) stiffness; sag_factors (n,) Dischinger–Ernst factors (1: taut);
    span_tensions_n (n,) or None; link_stiffness_n_per_m per link; loss_factors (n,) material
    loss factor of every branch (chain and the two wraps in series,
    :func:`chaindrive.damping.series_loss_factor`).
    """

    masses_kg: NDArray[np.float64]
    inertias_kg_m2: NDArray[np.float64]
    pitch_radii_m: NDArray[np.float64]
    stiffness_n_per_m: NDArray[np.float64]
    chain_stiffness_n_per_m: NDArray[np.float64]
    wrap_stiffness_n_per_m: NDArray[np.float64]
    sag_factors: NDArray[np.float64]
    span_tensions_n: NDArray[np.float64] | None
    link_stiffness_n_per_m: float
    loss_factors: NDArray[np.float64]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {
            "reduced_masses_kg": self.masses_kg.tolist(),
            "inertias_kg_m2": self.inertias_kg_m2.tolist(),
            "pitch_radii_m": self.pitch_radii_m.tolist(),
            "branch_stiffness_n_per_m": self.stiffness_n_per_m.tolist(),
            "chain_stiffness_n_per_m": self.chain_stiffness_n_per_m.tolist(),
            "wrap_stiffness_n_per_m": self.wrap_stiffness_n_per_m.tolist(),
            "sag_factors": self.sag_factors.tolist(),
            "span_tensions_n": (None if self.span_tensions_n is None
                                else self.span_tensions_n.tolist()),
            "link_stiffness_n_per_m": self.link_stiffness_n_per_m,
            "loss_factors": self.loss_factors.tolist(),
        }


def static_span_tensions(drive: Drive, geometry: GeometryResult) -> NDArray[np.float64] | None:
    """Static span tensions [N] from :func:`chaindrive.strength.loads.loads_of`, or None when
    the drive gives no power."""
    if drive.power is None or drive.driver.speed is None:
        return None
    from chaindrive.strength.loads import loads_of

    return np.asarray(loads_of(drive, geometry).span_tensions, dtype=float)


def _default_lookup() -> Callable[[str], Material]:
    from chaindrive.catalog import find_material

    return find_material


def drive_ring_parameters(drive: Drive, geometry: GeometryResult, *,
                          span_tensions: Sequence[float] | None = None,
                          link_stiffness: float | None = None,
                          material_lookup: Callable[[str], Material] | None = None,
                          ) -> RingParameters:
    """Reduced masses and branch stiffnesses of a drive (the module docstring's model).

    drive, geometry : the drive and its built contour (same sprocket order);
    span_tensions [N] : per span (None: the static tensions of
    :func:`chaindrive.strength.loads.loads_of` when the drive has a power, else the spans
    are taken as taut, no sag); link_stiffness [N/m] : per link, e.g. from
    catalogue data (None: :func:`link_stiffness` from plates and pin with the chain
    material's E); material_lookup : name → Material (default
    ``chaindrive.catalog.find_material``). Sprocket masses: ``Sprocket.inertia`` when
    given, else :func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia` (a steel plate
    disc, or the polymeric rim–web–hub proportions of seed 000 §3.4 for a polymer sprocket).
    With ``drive.chain.contours`` = m identical contours the branch stiffness is m times that
    of one contour (span tensions are then those of one contour); chain_stiffness and
    wrap_stiffness stay per contour.
    """
    lookup = material_lookup or _default_lookup()
    spec = drive.chain.spec
    chain_mat = lookup(spec.material)
    k_link = (link_stiffness if link_stiffness is not None
              else _link_stiffness_from_plates(spec, chain_mat.youngs_modulus))
    n = len(drive.sprockets)
    if len(geometry.sprockets) != n or len(geometry.spans) != n:
        raise DesignError("geometry", f"need {n} sprockets and spans, got "
                          f"{len(geometry.sprockets)} and {len(geometry.spans)}")
    if any(sp.start != i or sp.end != (i + 1) % n for i, sp in enumerate(geometry.spans)):
        raise DesignError("geometry.spans", "span i must join sprocket i and i+1 (ring order)")
    width = TOOTH_WIDTH_FACTOR * spec.inner_width + (spec.strands - 1) * spec.transverse_pitch
    inertia = np.empty(n)
    radius = np.array([g.pitch_radius for g in geometry.sprockets])
    wrap = np.empty(n)
    eta_wrap = np.empty(n)
    for i, (s, g) in enumerate(zip(drive.sprockets, geometry.sprockets, strict=True)):
        mat = lookup(s.material)
        eta_wrap[i] = loss_factor(mat.family, mat.is_polymer)
        inertia[i] = (s.inertia if s.inertia is not None else sprocket_mass_and_inertia(
            spec.pitch, s.teeth, spec.inner_width, mat.density, mat.is_polymer,
            strands=spec.strands, transverse_pitch=spec.transverse_pitch).moment_of_inertia)
        k_t = tooth_stiffness(width, mat.youngs_modulus, chain_mat.youngs_modulus)
        wrap[i] = wrap_stiffness(k_t, k_link, g.teeth_in_mesh)
    lengths = np.array([sp.length for sp in geometry.spans])
    starts = np.arange(n)
    ends = (starts + 1) % n
    chain_c = chain_span_stiffness(k_link, lengths, spec.pitch)
    tensions = (np.asarray(span_tensions, dtype=float) if span_tensions is not None
                else static_span_tensions(drive, geometry))
    if tensions is None:
        sag = np.ones(n)
    else:
        if tensions.shape != (n,):
            raise DesignError("span_tensions", f"need {n} tensions, got {tensions.shape}")
        incl = np.array([sp.inclination for sp in geometry.spans])
        sag = sag_stiffness_factor(k_link * spec.pitch, spec.mass_per_length * GRAVITY,
                                   lengths * np.cos(incl), tensions)
    # m identical contours side by side (seed 004) act in parallel on the common shafts
    stiffness = series_stiffness(chain_c, wrap[starts], wrap[ends]) * sag * drive.chain.contours
    return RingParameters(
        masses_kg=reduced_mass(inertia, radius), inertias_kg_m2=inertia,
        pitch_radii_m=radius, stiffness_n_per_m=stiffness, chain_stiffness_n_per_m=chain_c,
        wrap_stiffness_n_per_m=wrap, sag_factors=sag, span_tensions_n=tensions,
        link_stiffness_n_per_m=float(k_link),
        loss_factors=series_loss_factor(
            [np.full(n, loss_factor(chain_mat.family, chain_mat.is_polymer)), eta_wrap[starts],
             eta_wrap[ends]], [1.0 / chain_c, 1.0 / wrap[starts], 1.0 / wrap[ends]]),
    )


def ring_damping_ratio(params: RingParameters, hinge_damping: float) -> float:
    """Damping ratio ζ of the ring: the hinge-friction (or measured) damping ratio given
    (seed 000: D = 0.06) plus the material part η₁/2 of the first elastic mode by the modal
    strain energy method (:func:`chaindrive.damping.modal_loss_factor`). A steel drive gets
    about +0.0003; a polyamide chain about +0.015 (seed 000 Fig. 2: polymer chains damp more).
    """
    from chaindrive.damping import modal_loss_factor
    from chaindrive.dynamics.ring import modal_analysis

    modal = modal_analysis(params.masses_kg, params.stiffness_n_per_m)
    elastic = np.flatnonzero(~modal.rigid_body)
    if elastic.size == 0:
        return hinge_damping
    eta = modal_loss_factor(params.loss_factors, params.stiffness_n_per_m,
                            modal.shapes[:, elastic[0]])
    return min(0.99, hinge_damping + eta / 2.0)
