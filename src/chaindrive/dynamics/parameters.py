"""The dynamic model of a drive, built from a :class:`~chaindrive.model.Drive` and its
contour geometry, and its modal stage.

* :func:`drive_ring_parameters` — reduced masses m_i = I_i/R_i² and branch stiffnesses of the
  ring (chain, sprocket wrap and sag compliance in series; :mod:`.stiffness` has the
  formulas), with their parts;
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.dynamics.damping import loss_factor, series_loss_factor
from chaindrive.dynamics.stiffness import (
    GRAVITY,
    chain_span_stiffness,
    reduced_mass,
    sag_stiffness_factor,
    series_stiffness,
    tooth_contact_width,
    tooth_stiffness,
    wrap_stiffness,
)
from chaindrive.dynamics.stiffness import (
    link_stiffness as link_stiffness_from_plates,
)
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import sprocket_mass_and_inertia
from chaindrive.strength.loads import loads_of

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import ChainSpec, Drive, Material, Sprocket

__all__ = ["RingParameters", "chain_link_stiffness", "drive_ring_parameters", "static_span_tensions"]


@dataclass(frozen=True, slots=True, eq=False)
class RingParameters:
    """Masses and branch stiffnesses of a drive's ring model with their parts.

    Parameters
    ----------
    masses_kg : ndarray
        (n,) reduced masses m_i = I_i/R_i² [kg].
    inertias_kg_m2 : ndarray
        (n,) moments of inertia I_i used [kg·m²].
    pitch_radii_m : ndarray
        (n,) pitch radii R_i [m].
    stiffness_n_per_m : ndarray
        (n,) branch stiffness [N/m] (branch i joins sprocket i and i+1; all contours).
    chain_stiffness_n_per_m : ndarray
        (n,) the chain of the span alone [N/m] (one contour).
    wrap_stiffness_n_per_m : ndarray
        (n,) each sprocket's wrap (tooth) stiffness [N/m] (one contour).
    sag_factors : ndarray
        (n,) Dischinger–Ernst factors [-] (1: taut; [Ernst1965]).
    span_tensions_n : ndarray or None
        (n,) span tensions [N] (one contour), or None.
    link_stiffness_n_per_m : float
        Stiffness of one link [N/m].
    loss_factors : ndarray
        (n,) material loss factor of every branch [-] (chain and the two wraps in series,
        :func:`chaindrive.dynamics.damping.series_loss_factor`).
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


@shared_parameters
def static_span_tensions(drive: Drive, geometry: GeometryResult) -> NDArray[np.float64] | None:
    """Static span tensions from :func:`chaindrive.strength.loads.loads_of`.

    Parameters
    ----------
    %(drive_geometry)s

    Returns
    -------
    ndarray or None
        (n,) span tensions [N], or None when the drive gives no power.
    """
    if drive.power is None or drive.driver.speed is None:
        return None
    return np.asarray(loads_of(drive, geometry).span_tensions, dtype=float)


def _default_lookup() -> Callable[[str], Material]:
    return find_material


def sprocket_inertia(sprocket: Sprocket, pitch_radius: float, spec: ChainSpec,
                     material: Material) -> float:
    """Moment of inertia [kg·m²] of what turns rigidly with a sprocket (its flywheel aside).

    Parameters
    ----------
    sprocket : Sprocket
        Its ``inertia``, else its ``reduced_mass`` m at the pitch radius, J = m R²
        [MultimassChainDrives, §3.1], else the sprocket body from its geometry
        (:func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`).
    pitch_radius : float
        R [m].
    spec : ChainSpec
        The chain (pitch, width, strands).
    material : Material
        The sprocket's material (density of the body).

    Returns
    -------
    float
        J [kg·m²].
    """
    if sprocket.inertia is not None:
        return sprocket.inertia
    if sprocket.reduced_mass is not None:
        return sprocket.reduced_mass * pitch_radius**2
    return sprocket_mass_and_inertia(spec.pitch, sprocket.teeth, spec.inner_width,
                                     material.density, material.is_polymer,
                                     strands=spec.strands,
                                     transverse_pitch=spec.transverse_pitch).moment_of_inertia


@shared_parameters
def chain_link_stiffness(drive: Drive, youngs_modulus: float, *,
                         reference_modulus: float | None = None) -> float:
    """Axial stiffness k_link [N/m] of one link of the drive's chain.

    The design's measured value (``Chain.link_stiffness``, ``[chain] link_stiffness``) when
    given, scaled by E/E_ref when the chain's modulus differs from the one it was measured at
    (a chain at another temperature); else the plates and the pin at E
    (:func:`chaindrive.dynamics.stiffness.link_stiffness`).

    Parameters
    ----------
    %(drive)s
    youngs_modulus : float
        Young's modulus E of the chain material in the state computed [Pa].
    reference_modulus : float or None
        E_ref [Pa] the measured value belongs to (None: E, no scaling).

    Returns
    -------
    float
        k_link [N/m].

    References
    ----------
    [Roark2012, Table 8.1 case 2e] (the pin of the computed value).
    """
    given = drive.chain.link_stiffness
    if given is None:
        return link_stiffness_from_plates(drive.chain.spec, youngs_modulus)
    return given * (youngs_modulus / reference_modulus if reference_modulus else 1.0)


@shared_parameters
def drive_ring_parameters(drive: Drive, geometry: GeometryResult, *,
                          span_tensions: Sequence[float] | None = None,
                          link_stiffness: float | None = None,
                          material_lookup: Callable[[str], Material] | None = None,
                          ) -> RingParameters:
    """Reduced masses and branch stiffnesses of a drive (the module docstring's model).

    Sprocket masses: ``Sprocket.inertia`` when given, else
    :func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia` (a steel plate disc, or the
    polymeric rim–web–hub proportions of [MultimassChainDrives, §3.4] for a polymer
    sprocket). With ``drive.chain.contours`` = m identical contours the branch stiffness is m
    times that of one contour (span tensions are then those of one contour); chain_stiffness
    and wrap_stiffness stay per contour.

    Parameters
    ----------
    %(drive)s
    geometry : GeometryResult
        Its built contour (same sprocket order).
    span_tensions : sequence of float or None
        Tension of every span [N] (None: the static tensions of
        :func:`chaindrive.strength.loads.loads_of` when the drive has a power, else the spans
        are taken as taut, no sag).
    link_stiffness : float or None
        Stiffness of one link [N/m] (None: :func:`chain_link_stiffness`, the design's
        measured value or the plates and pin with the chain material's E).
    material_lookup : callable or None
        Name → Material (None: :func:`chaindrive.catalog.find_material`).

    Returns
    -------
    RingParameters
        The masses and stiffnesses with their parts.

    References
    ----------
    [MultimassChainDrives, §3.1] (reduced masses); [Naji1983] (wrap); [Ernst1965] (sag).
    """
    lookup = material_lookup or _default_lookup()
    spec = drive.chain.spec
    chain_mat = lookup(spec.material)
    k_link = (link_stiffness if link_stiffness is not None
              else chain_link_stiffness(drive, chain_mat.youngs_modulus))
    n = len(drive.sprockets)
    if len(geometry.sprockets) != n or len(geometry.spans) != n:
        raise DesignError("geometry", f"need {n} sprockets and spans, got "
                          f"{len(geometry.sprockets)} and {len(geometry.spans)}")
    if any(sp.start != i or sp.end != (i + 1) % n for i, sp in enumerate(geometry.spans)):
        raise DesignError("geometry.spans", "span i must join sprocket i and i+1 (ring order)")
    width = tooth_contact_width(spec)
    inertia = np.empty(n)
    radius = np.array([g.pitch_radius for g in geometry.sprockets])
    wrap = np.empty(n)
    eta_wrap = np.empty(n)
    for i, (s, g) in enumerate(zip(drive.sprockets, geometry.sprockets, strict=True)):
        mat = lookup(s.material)
        eta_wrap[i] = loss_factor(mat.family, mat.is_polymer)
        inertia[i] = s.flywheel + sprocket_inertia(s, radius[i], spec, mat)
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
    # m identical contours side by side ([Lyashuk]) act in parallel on the common shafts
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
