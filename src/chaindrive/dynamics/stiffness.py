"""Reduced masses and branch stiffnesses of the ring model of a drive.

Every branch (span) i of the contour is a chain of L_i/p links in series with the wrap of
the chain on the sprockets at both ends (tooth contact compliance), and — for a span with
low tension — reduced by the sag of the span (equivalent-modulus formula)::

    1/c_i = L_i / (p·k_link) + 1/k_wrap(start) + 1/k_wrap(end),   c_i ← c_i · s_sag(T_i)

Masses: m_i = I_i / R_i² ([MultimassChainDrives, §3.1]). See docs/dynamics.md.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as out_value
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from chaindrive.model import ChainSpec

__all__ = [
    "E_STEEL",
    "GRAVITY",
    "TOOTH_STIFFNESS_PER_WIDTH",
    "chain_span_stiffness",
    "link_stiffness",
    "plate_thickness",
    "reduced_mass",
    "sag_stiffness_factor",
    "series_stiffness",
    "tooth_contact_width",
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

    Parameters
    ----------
    inertia : array_like
        Moment of inertia I [kg·m²].
    radius : array_like
        Pitch radius R of the hinge centres [m].

    Returns
    -------
    ndarray
        m [kg].

    References
    ----------
    [MultimassChainDrives, §3.1] ("bringing the revolved masses over to the radii of the end
    hinges").
    """
    return np.asarray(np.asarray(inertia, dtype=float) / np.asarray(radius, dtype=float) ** 2,
                      dtype=np.float64)


def plate_thickness(spec: ChainSpec) -> float:
    """Estimated link plate thickness s [m] of a chain.

    With the transverse pitch p_t known, p_t ≈ b1 + 2 s_inner + 2 s_outer ≈ b1 + 4 s, so
    s = (p_t − b1)/4 (checks: 08A gives 1.63 mm vs 1.5 mm catalogue, 12A 2.55 vs 2.4 mm);
    without it s = p/8 (ANSI plates: 0.12–0.126 p). Our estimate, documented in
    docs/dynamics.md.

    Parameters
    ----------
    spec : ChainSpec
        The catalogue chain (transverse pitch p_t, inner width b1, pitch p).

    Returns
    -------
    float
        s [m].

    References
    ----------
    [ISO606] and [ANSI-B29.1] (the dimensions the estimate is checked against).
    """
    if spec.transverse_pitch and spec.transverse_pitch > spec.inner_width:
        return (spec.transverse_pitch - spec.inner_width) / 4.0
    return spec.pitch / 8.0


def link_stiffness(spec: ChainSpec, youngs_modulus: float) -> float:
    """Axial stiffness k_link [N/m] of one link (one pitch) of the whole chain.

    Model (ours, docs/dynamics.md): the two plates of a link in parallel — net section
    (h − d2)·s over a length d2 at the hole, gross section h·s over p − d2 — in series with
    the bending of the pin as a clamped–clamped beam under a uniform load over its span
    l = b1 + 3s (compliance l³/(384 E I), I = π d2⁴/64); all strands in parallel.

    Parameters
    ----------
    spec : ChainSpec
        The catalogue chain (pitch p, plate depth h = h2, pin diameter d2, inner width b1,
        strands).
    youngs_modulus : float
        Young's modulus E of the chain material [Pa].

    Returns
    -------
    float
        k_link [N/m].

    Raises
    ------
    DesignError
        ``chain.plate_depth`` not above the pin diameter.

    References
    ----------
    [Roark2012, Table 8.1 case 2e] (the clamped–clamped pin).
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


@shared_parameters
def chain_span_stiffness(link_k: ArrayLike, span_length: ArrayLike,
                         pitch: float) -> NDArray[np.float64]:
    """Stiffness c = k_link · p / L [N/m] of a span of length L (L/p links in series);
    equivalently c = EA_eff / L with EA_eff = k_link · p.

    Parameters
    ----------
    link_k : array_like
        Stiffness of one link k_link [N/m].
    span_length : array_like
        Span length L [m].
    %(pitch)s

    Returns
    -------
    ndarray
        c [N/m].
    """
    return np.asarray(np.asarray(link_k, dtype=float) * pitch
                      / np.asarray(span_length, dtype=float), dtype=np.float64)


def tooth_contact_width(spec: ChainSpec) -> float:
    """Width of the roller–tooth contact of a chain [m]: the tooth width
    :data:`TOOTH_WIDTH_FACTOR`·b₁ of one strand plus a transverse pitch p_t for every further
    strand (the teeth of an m-strand sprocket stand p_t apart).

    Parameters
    ----------
    spec : ChainSpec
        The chain (inner width b₁, strands m, transverse pitch p_t).

    Returns
    -------
    float
        0.93·b₁ + (m − 1)·p_t [m].

    References
    ----------
    [ISO606] (b_f1 ≈ 0.93·b₁ for p ≤ 12.7 mm, 0.95·b₁ above; p_t).
    """
    return TOOTH_WIDTH_FACTOR * spec.inner_width + (spec.strands - 1) * spec.transverse_pitch


def tooth_stiffness(width: float, e_sprocket: float, e_roller: float,
                    per_width: float = TOOTH_STIFFNESS_PER_WIDTH) -> float:
    """Contact stiffness k_t [N/m] of one sprocket tooth under a roller.

    k_t = c' · b · E_red / E_steel with E_red = 2 E1 E2 / (E1 + E2): the single tooth-pair
    stiffness c' of ISO 6336-1 (≈ 14 N/(mm·µm) for steel) scaled, as ISO 6336-1 does for
    other material pairs, by the reduced modulus of the pair (sprocket and roller). A roller
    seated at the tooth root loads the tooth less in bending than a gear tooth: this is a
    conservative (soft) value.

    Parameters
    ----------
    width : float
        Tooth width b [m].
    e_sprocket, e_roller : float
        Young's moduli of the sprocket and of the roller [Pa].
    per_width : float
        Single tooth-pair stiffness per unit width c' [N/m²] (:data:`TOOTH_STIFFNESS_PER_WIDTH`).

    Returns
    -------
    float
        k_t [N/m].

    References
    ----------
    [ISO6336-1] (c' and its scaling by the moduli).
    """
    e_red = 2.0 * e_sprocket * e_roller / (e_sprocket + e_roller)
    return per_width * width * e_red / E_STEEL


def wrap_stiffness(tooth_k: ArrayLike, link_k: ArrayLike, teeth_in_mesh: ArrayLike
                   ) -> FloatOrArray:
    """Stiffness [N/m] with which the wrap of the chain on a sprocket holds a span's end.

    Ladder model of the load sharing among the N = max(1, ⌊teeth in mesh⌋) teeth: each
    engaged roller is held by a tooth spring k_t, consecutive rollers are joined by a link
    k_link. Input stiffness from the span side, by the recursion (ours)
    K_N = k_t, K_j = k_t + k_link K_{j+1} / (k_link + K_{j+1}); for N → ∞ it tends to
    k_t/2 + sqrt(k_t²/4 + k_t k_link).

    Parameters
    ----------
    tooth_k : float or array_like
        Stiffness of one tooth under a roller k_t [N/m].
    link_k : float or array_like
        Stiffness of one link k_link [N/m].
    teeth_in_mesh : float or array_like
        Teeth in mesh on the sprocket [-] (its whole part is used, at least 1); the three
        broadcast together (a batch of states, a row of sprockets).

    Returns
    -------
    float or ndarray
        K_1 [N/m].

    References
    ----------
    [Naji1983] (spring model of sprocket load distribution).
    """
    kt, kl = np.asarray(tooth_k, dtype=float), np.asarray(link_k, dtype=float)
    n = np.maximum(1, np.floor(np.asarray(teeth_in_mesh, dtype=float))).astype(np.int64)
    k = np.broadcast_to(kt, np.broadcast_shapes(kt.shape, kl.shape, n.shape)).copy()
    for j in range(int(n.max()) - 1):
        k = np.where(j < n - 1, kt + kl * k / (kl + k), k)
    return out_value(k)


def series_stiffness(*stiffnesses: ArrayLike) -> NDArray[np.float64]:
    """Springs in series: 1/c = Σ 1/c_i [N/m] (a zero member gives 0).

    Parameters
    ----------
    *stiffnesses : array_like
        The members' stiffnesses c_i [N/m], broadcast together.

    Returns
    -------
    ndarray
        c [N/m].
    """
    arrays = np.broadcast_arrays(*[np.asarray(s, dtype=float) for s in stiffnesses])
    with np.errstate(divide="ignore"):
        compliance = sum(1.0 / a for a in arrays)
    return np.where(np.isfinite(compliance), 1.0 / compliance, 0.0)


def sag_stiffness_factor(axial_rigidity: ArrayLike, weight_per_length: ArrayLike,
                         horizontal_length: ArrayLike, tension: ArrayLike) -> NDArray[np.float64]:
    """Factor s = 1 / (1 + (w l)² EA / (12 T³)) on the axial stiffness of a sagging span.

    The Dischinger–Ernst equivalent modulus of a sagging cable, E_eq = E / (1 + (γ l)² E /
    (12 σ³)), written with forces; a slack span (T ≤ 0) gets the factor 0.

    Parameters
    ----------
    axial_rigidity : array_like
        EA = k_link·p [N].
    weight_per_length : array_like
        w = q g [N/m].
    horizontal_length : array_like
        l = L cos(inclination) [m].
    tension : array_like
        Span tension T [N].

    Returns
    -------
    ndarray
        s [-], in [0, 1].

    References
    ----------
    [Ernst1965].
    """
    ea = np.asarray(axial_rigidity, dtype=float)
    w = np.asarray(weight_per_length, dtype=float)
    lh = np.asarray(horizontal_length, dtype=float)
    t = np.asarray(tension, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = 1.0 / (1.0 + (w * lh) ** 2 * ea / (12.0 * t**3))
    return np.where(t > 0, s, 0.0)
