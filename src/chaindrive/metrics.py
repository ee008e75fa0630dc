"""What a drive weighs, costs and occupies: the quantities the optimiser minimises and the
report shows.

* mass: sprocket bodies (a steel plate disc, or the polymeric rim–web–hub proportions of
  [MultimassChainDrives, §3.4]) + the chain (q·L) + added flywheels, for every contour;
* cost: :class:`chaindrive.cost.CostModel` (prices per kg by material family and per metre
  of chain);
* volume: the bounding box of the tip circles × the overall chain width × contours.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.cost import CostBreakdown, CostModel, cost_breakdown
from chaindrive.dynamics.stiffness import plate_thickness
from chaindrive.geometry.results import GeometryResult
from chaindrive.geometry.sprocket import sprocket_body
from chaindrive.model import ChainSpec, Drive

__all__ = ["DesignMetrics", "chain_width", "design_metrics", "sprocket_body_masses"]


def chain_width(spec: ChainSpec) -> float:
    """Overall chain width b ≈ b₁ + 4 s + (strands − 1) p_t [m].

    Parameters
    ----------
    spec : ChainSpec
        The chain: inner width b₁ [m], transverse pitch p_t [m], strands; plate thickness s
        from :func:`chaindrive.dynamics.stiffness.plate_thickness` (two inner and two outer
        plates).

    Returns
    -------
    float
        Overall width [m].
    """
    return spec.inner_width + 4 * plate_thickness(spec) + (spec.strands - 1) * spec.transverse_pitch


@dataclass(frozen=True, slots=True)
class DesignMetrics:
    """Mass, cost and size of a drive (all contours together).

    Parameters
    ----------
    sprocket_masses_kg : numpy.ndarray
        (n,) mass of each sprocket body of one contour [kg].
    chain_mass_kg : float
        Mass of one contour's chain q·L [kg].
    flywheel_masses_kg : numpy.ndarray
        (n,) mass of the flywheels [kg] (steel discs of the pitch radius).
    contours : int
        Identical contours side by side [-].
    cost_breakdown : CostBreakdown
        The price of every part, with its basis and whether it rests on an estimate.
    volume_m3 : float
        Bounding box of the tip circles × chain width × contours [m³].
    chain_length_m : float
        Length of one contour's chain [m].
    """

    sprocket_masses_kg: NDArray[np.float64]
    chain_mass_kg: float
    flywheel_masses_kg: NDArray[np.float64]
    contours: int
    cost_breakdown: CostBreakdown
    volume_m3: float
    chain_length_m: float

    @property
    def cost(self) -> float:
        """Sprockets, chain and flywheels [currency]."""
        return self.cost_breakdown.total

    @property
    def mass_kg(self) -> float:
        """Sprocket bodies and chain of every contour, plus the flywheels [kg]."""
        return float(self.contours * (self.sprocket_masses_kg.sum() + self.chain_mass_kg)
                     + self.flywheel_masses_kg.sum())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"mass_kg": self.mass_kg,
                "sprocket_masses_kg": self.sprocket_masses_kg.tolist(),
                "chain_mass_kg": self.chain_mass_kg,
                "flywheel_masses_kg": self.flywheel_masses_kg.tolist(),
                "contours": self.contours, "cost": self.cost,
                "cost_breakdown": self.cost_breakdown.to_dict(),
                "volume_m3": self.volume_m3,
                "chain_length_m": self.chain_length_m}


@shared_parameters
def sprocket_body_masses(drive: Drive) -> NDArray[np.float64]:
    """Mass of each sprocket body from its tooth count, the chain and its material.

    %(drive_returns)s
    numpy.ndarray
        (n,) mass of each sprocket body [kg]
        (:func:`chaindrive.geometry.sprocket.sprocket_body`).
    """
    return np.array([
        sprocket_body(drive.chain.spec, s.teeth,
                      find_material(s.material, field=f"sprockets[{i}].material")).mass
        for i, s in enumerate(drive.sprockets)])


def _volume(geometry: GeometryResult, width: float, contours: int) -> float:
    xy = np.array([(p.x, p.y) for p in geometry.sprockets])
    r = np.array([p.tip_diameter / 2 for p in geometry.sprockets])
    box = (xy[:, 0] + r).max() - (xy[:, 0] - r).min(), (xy[:, 1] + r).max() - (xy[:, 1] - r).min()
    return float(box[0] * box[1] * width * contours)


def design_metrics(drive: Drive, geometry: GeometryResult, cost_model: CostModel
                   ) -> DesignMetrics:
    """Mass, cost and volume of ``drive`` built as ``geometry``.

    Parameters
    ----------
    drive : Drive
        The design (chain, sprockets with materials and flywheels, contours).
    geometry : GeometryResult
        Its contour (chain length, pitch radii, tip diameters, positions).
    cost_model : CostModel
        Prices (:func:`chaindrive.cost.default_cost_model` or the designer's file).

    Returns
    -------
    DesignMetrics
        Mass, cost and volume. The flywheel of inertia ΔI is a steel disc of the pitch
        radius R, m = 2ΔI/R² (solid disc, I = m R²/2 [Rao2011]).
    """
    spec = drive.chain.spec
    m = drive.chain.contours
    bodies = sprocket_body_masses(drive)
    radii = np.array([g.pitch_radius for g in geometry.sprockets])
    flywheels = 2.0 * np.array([s.flywheel for s in drive.sprockets]) / radii**2
    chain_mass = spec.mass_per_length * geometry.chain_length
    cost = cost_breakdown(drive, geometry.chain_length, bodies, cost_model, flywheels)
    return DesignMetrics(bodies, float(chain_mass), flywheels, m, cost,
                         _volume(geometry, chain_width(spec), m), float(geometry.chain_length))
