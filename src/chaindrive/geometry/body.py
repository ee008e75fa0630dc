"""Sprocket bodies: the proportions of a polymeric sprocket, mass and moment of inertia.

Polymeric proportions [MultimassChainDrives, §3.4]; a steel sprocket is a plate disc of the
ISO 606 tooth width [ISO606].
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import asdict, dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import positive
from chaindrive.geometry.iso606 import iso606_tooth_width, multi_strand_width
from chaindrive.geometry.pitch import MM as _MM
from chaindrive.geometry.pitch import approximate_pitch_diameter, pitch_diameter
from chaindrive.geometry.pitch import positive_length as _positive

if TYPE_CHECKING:
    from chaindrive.model import ChainSpec, Material

__all__ = ["PolymericProportions", "SprocketMassProperties", "annulus_mass_and_inertia",
           "polymeric_sprocket_proportions", "sprocket_mass_and_inertia"]


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

    Parameters
    ----------
    d_pitch, rim_inner_diameter, hub_outer_diameter, hole_circle_diameter : float
        D, d_2, d_1, d_H [m] (reading above).
    d_n, bore_diameter : float
        d_н, d_0 [m].
    rim_width, web_thickness, hub_length : float
        b, h, l_min [m].
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


@shared_parameters
def polymeric_sprocket_proportions(pitch: float, teeth: int,
                                   inner_width: float) -> PolymericProportions:
    """Polymeric sprocket proportions from t, z and the chain inner width B_in.

    d_∂ ≈ tz/π, d_1 ≈ 0.33 tz/π, d_2 ≈ 0.8 tz/π, d_н ≈ 0.3 tz/π, d_H ≈ 0.56 tz/π,
    d_0 ≈ 0.19 tz/π, b ≈ 0.85 B_in, h ≈ 0.5 b, l_min ≈ 3 b. See :class:`PolymericProportions`
    for the reading of each symbol.

    Parameters
    ----------
    %(pitch_t_teeth)s
    inner_width : float
        Chain inner width B_in [m].

    Returns
    -------
    PolymericProportions
        The proportions [m].

    References
    ----------
    [MultimassChainDrives, §3.4].
    """
    D = float(approximate_pitch_diameter(pitch, teeth))
    b = 0.85 * float(_positive("inner_width", inner_width))
    return PolymericProportions(
        d_pitch=D, rim_inner_diameter=0.8 * D, hub_outer_diameter=0.33 * D,
        hole_circle_diameter=0.56 * D, d_n=0.3 * D, bore_diameter=0.19 * D,
        rim_width=b, web_thickness=0.5 * b, hub_length=3.0 * b)


@dataclass(frozen=True, slots=True)
class SprocketMassProperties:
    """Mass and polar moment of inertia of a sprocket body; unpacks as ``mass, inertia = ...``.

    Parameters
    ----------
    mass : float
        Mass [kg].
    moment_of_inertia : float
        Polar moment of inertia about the axis [kg·m²].
    model : str
        The body model used.
    """

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
    """Mass m = ρ·w·π(Do² − Di²)/4 and axial inertia I = m(Do² + Di²)/8 of a thick ring.

    Parameters
    ----------
    outer_diameter, inner_diameter : float or array_like
        Do, Di [m].
    width : float or array_like
        Axial width w [m].
    density : float or array_like
        ρ [kg/m³].

    Returns
    -------
    tuple of float or numpy.ndarray
        (m [kg], I [kg·m²]).

    References
    ----------
    [Roark2012] (hollow cylinder, rigid-body properties).
    """
    Do, Di = np.asarray(outer_diameter, float), np.asarray(inner_diameter, float)
    m = np.asarray(density, float) * np.asarray(width, float) * np.pi * (Do**2 - Di**2) / 4
    return _out(m), _out(m * (Do**2 + Di**2) / 8)


@lru_cache(maxsize=1024)  # a search meets the same sprockets again (and drive model and metrics)
@shared_parameters
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
      :func:`multi_strand_width` thick.

    The result of each set of arguments is kept (the last 1024): a drive's model and its
    metrics ask for the same bodies, and a search for the same sprockets design after design.

    Parameters
    ----------
    %(pitch)s
    %(teeth)s
    inner_width : float
        Chain inner width B_in [m].
    density : float
        Density of the material ρ [kg/m³].
    polymeric : bool
        True: the polymeric rim–web–hub body; False: a steel plate disc.
    hole_count : int
        Lightening holes in the web of a polymeric body [-].
    hole_diameter_ratio : float
        Hole diameter as a fraction of the web height (d_2 − d_1)/2 [-].
    strands : int
        Chain strands [-].
    transverse_pitch : float
        Transverse pitch of a multi-strand chain [m].

    Returns
    -------
    SprocketMassProperties
        Mass [kg] and moment of inertia [kg·m²] with the body model's name.

    References
    ----------
    [MultimassChainDrives, §3.4]; [ISO606].
    """
    rho = float(positive("density", density))
    d = float(pitch_diameter(pitch, teeth))
    prop = polymeric_sprocket_proportions(pitch, teeth, inner_width)
    if not polymeric:
        width = float(multi_strand_width(iso606_tooth_width(pitch, inner_width, strands),
                                         transverse_pitch, strands))
        disc_m, disc_i = annulus_mass_and_inertia(d, prop.bore_diameter, width, rho)
        return SprocketMassProperties(float(disc_m), float(disc_i), "steel plate disc (d, bf1)")
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
    return SprocketMassProperties(m, inertia,
                                  "polymeric rim + web with holes + hub [MultimassChainDrives]")


def sprocket_body(spec: ChainSpec, teeth: int, material: Material) -> SprocketMassProperties:
    """The body of a sprocket of a drive: :func:`sprocket_mass_and_inertia` for its chain
    (pitch, inner width, strands, transverse pitch) and its material (density; polymeric or
    steel), the default lightening holes.

    Parameters
    ----------
    spec : ChainSpec
        The drive's chain.
    teeth : int
        The sprocket's teeth z [-].
    material : Material
        The sprocket's material.

    Returns
    -------
    SprocketMassProperties
        Mass [kg] and moment of inertia [kg·m²] with the body model's name.
    """
    return sprocket_mass_and_inertia(spec.pitch, teeth, spec.inner_width, material.density,
                                     material.is_polymer, strands=spec.strands,
                                     transverse_pitch=spec.transverse_pitch)
