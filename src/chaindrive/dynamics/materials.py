"""The four chain/sprocket material pairs of [MultimassChainDrives] (Fig. 2–3, Table 1) on one
layout, with the whole-drive model.

Metal or polymer chain on metal or polymer sprockets: for each pair the whole-drive model is
rebuilt (:func:`chaindrive.dynamics.model.build.drive_model`: the chain's E and the sprockets'
E from ``chaindrive.catalog.find_material``; the damping ratio of the pair, Table 1), then the
start-up peak span force, the first elastic natural frequency, its damped value and the first
resonance of the AFC (the tooth frequency of the largest peak of a sweep through 0.3–1.5 f₁,
and its amplitude) are tabulated. A polymer chain has the catalogue chain's dimensions and
its mass per length scaled by the densities, q·ρ/ρ_chain (the estimate of the packaged
polymer chains, catalog/data/chains_polymer.csv). The paper reports 542 N (metal chain) vs
470 N (polymer chain) at start-up and a polymer-chain resonance at a lower frequency with
≈ 3× smaller amplitude.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.dynamics.excitation import polygonal_excitation
from chaindrive.dynamics.frequency.response import drive_sweep
from chaindrive.dynamics.model.build import drive_model
from chaindrive.dynamics.modes import drive_modes
from chaindrive.dynamics.response import polygonal_law
from chaindrive.dynamics.transient.drive_startup import model_startup
from chaindrive.kinematics import tooth_frequency
from chaindrive.strength.loads import installed_pretension
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["MaterialCase", "material_comparison", "with_materials"]



@dataclass(frozen=True, slots=True)
class MaterialCase:
    """One chain/sprocket material pair of the comparison and what it does to the drive.

    Parameters
    ----------
    chain_material, sprocket_material : str
        The materials of the pair (catalogue names).
    startup_peak_n : float
        Largest span force during the start-up [N].
    first_natural_frequency_hz : float
        First elastic natural frequency [Hz].
    resonance_tooth_frequency_hz : float
        Tooth frequency at the largest peak of the amplitude–frequency characteristic [Hz].
    resonance_amplitude_n : float
        Largest span load at that peak [N].
    first_damped_frequency_hz : float
        Damped first natural frequency [Hz] (NaN when not computed).

    References
    ----------
    [MultimassChainDrives, Table 1] (the same comparison for steel and polymer pairs).
    """

    chain_material: str
    sprocket_material: str
    startup_peak_n: float
    first_natural_frequency_hz: float
    resonance_tooth_frequency_hz: float
    resonance_amplitude_n: float
    first_damped_frequency_hz: float = math.nan

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready row."""
        return {"chain_material": self.chain_material,
                "sprocket_material": self.sprocket_material,
                "startup_peak_n": self.startup_peak_n,
                "first_natural_frequency_hz": self.first_natural_frequency_hz,
                "first_damped_frequency_hz": self.first_damped_frequency_hz,
                "resonance_tooth_frequency_hz": self.resonance_tooth_frequency_hz,
                "resonance_amplitude_n": self.resonance_amplitude_n}


@shared_parameters
def with_materials(drive: Drive, chain_material: str, sprocket_material: str) -> Drive:
    """The drive with its chain and all its sprockets of other materials (module docstring:
    the chain's mass per length scales with the density, a measured link stiffness with the
    Young's modulus).

    Parameters
    ----------
    %(drive)s
    chain_material, sprocket_material : str
        Catalogue names.

    Returns
    -------
    Drive
    """
    spec = drive.chain.spec
    new, old = find_material(chain_material), find_material(spec.material)
    spec = replace(spec, material=chain_material,
                   mass_per_length=spec.mass_per_length * new.density / old.density)
    k_link = drive.chain.link_stiffness
    if k_link is not None:  # every compliance of a one-material chain scales as 1/E
        k_link *= new.youngs_modulus / old.youngs_modulus
    return replace(drive, chain=replace(drive.chain, spec=spec, link_stiffness=k_link),
                   sprockets=tuple(replace(s, material=sprocket_material)
                                   for s in drive.sprockets))


def _case(drive: Drive, geometry: GeometryResult, chain_mat: str, sprocket_mat: str,
          span_tensions: Sequence[float] | None, duration: float, points: int) -> MaterialCase:
    d = with_materials(drive, chain_mat, sprocket_mat)
    model = drive_model(d, geometry, span_tensions=span_tensions)
    modes = drive_modes(model)
    j = int(np.flatnonzero(~modes.rigid_body)[0])
    f1 = float(modes.frequencies_hz[j])
    w = d.driver.speed
    assert w is not None
    fz = float(tooth_frequency(d.driver.teeth, w))
    peak = math.nan
    if duration > 0 and d.power is not None:
        st = model_startup(model, polygonal_law(geometry), duration=duration,
                           pretension=installed_pretension(d, geometry), tooth_frequency_hz=fz)
        peak = float(st.max_span_force.max())
    # sweep the tooth frequency through 0.3 f1 … 1.5 f1: the first harmonic crosses f1
    ex = polygonal_excitation(geometry, d.driver.teeth * w)
    speeds = np.linspace(0.3 * f1, 1.5 * f1, points) * TWO_PI / d.driver.teeth
    afc = drive_sweep(model, modes, ex, speeds, d.driver.teeth, modes.elastic_frequencies_hz)
    curve = afc.span_load.max(axis=1)
    k = int(np.argmax(curve))
    return MaterialCase(chain_mat, sprocket_mat, peak, f1, float(afc.tooth_frequencies_hz[k]),
                        float(curve[k]), float(modes.damped_frequencies_hz[j]))


@shared_parameters
def material_comparison(drive: Drive, geometry: GeometryResult, *,
                        span_tensions: Sequence[float] | None = None, metal: str = "steel",
                        polymer: str = "PA6-GF30", duration: float = 0.3,
                        points: int = 600) -> tuple[MaterialCase, ...]:
    """The four pairs (chain, sprockets): metal/metal, polymer/metal, metal/polymer,
    polymer/polymer ([MultimassChainDrives] Table 1 order).

    Parameters
    ----------
    drive : Drive
        The drive (its power and driver speed).
    %(geometry)s
    span_tensions : sequence of float | None
        Static span tensions of one contour [N] (the sag stiffness).
    metal, polymer : str
        Catalogue names of the two materials.
    duration : float
        Start-up simulated [s] (0: none, the peak is nan).
    points : int
        Tooth frequencies of the sweep.

    Returns
    -------
    tuple of MaterialCase
    """
    pairs = ((metal, metal), (polymer, metal), (metal, polymer), (polymer, polymer))
    return tuple(_case(drive, geometry, a, b, span_tensions, duration, points)
                 for a, b in pairs)
