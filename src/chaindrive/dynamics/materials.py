"""The four material pairs of seed 000 (Fig. 2–3, Table 1) on one layout.

Metal or polymer chain on metal or polymer sprockets: for each pair the ring model is rebuilt
(:func:`chaindrive.dynamics.drive.ring_model`: chain E, sprocket E and density from
``chaindrive.catalog.find_material``), then the start-up peak span force
(:func:`chaindrive.dynamics.response.drive_startup`), the first elastic natural frequency and
the first resonance of the AFC (tooth frequency of the largest peak near it and its
amplitude) are tabulated. Seed 000 reports 542 N (metal chain) vs 470 N (polymer chain) at
start-up and a polymer-chain resonance at a lower frequency with ≈ 3× smaller amplitude.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from chaindrive.dynamics.afc import afc_sweep
from chaindrive.dynamics.drive import ring_model
from chaindrive.dynamics.excitation import polygonal_excitation
from chaindrive.dynamics.response import drive_startup

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["MaterialCase", "material_comparison"]


@dataclass(frozen=True, slots=True)
class MaterialCase:
    """One pair: chain and sprocket materials, start-up peak [N], first natural frequency
    [Hz], resonance tooth frequency [Hz] and resonance amplitude [N] (largest span load at
    the AFC peak below 1.5× the first natural frequency)."""

    chain_material: str
    sprocket_material: str
    startup_peak_n: float
    first_natural_frequency_hz: float
    resonance_tooth_frequency_hz: float
    resonance_amplitude_n: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready row."""
        return {"chain_material": self.chain_material,
                "sprocket_material": self.sprocket_material,
                "startup_peak_n": self.startup_peak_n,
                "first_natural_frequency_hz": self.first_natural_frequency_hz,
                "resonance_tooth_frequency_hz": self.resonance_tooth_frequency_hz,
                "resonance_amplitude_n": self.resonance_amplitude_n}


def _case(drive: Drive, geometry: GeometryResult, chain_mat: str, sprocket_mat: str,
          damping: float, duration: float, points: int) -> MaterialCase:
    spec = replace(drive.chain.spec, material=chain_mat)
    d = replace(drive, chain=replace(drive.chain, spec=spec),
                sprockets=tuple(replace(s, material=sprocket_mat) for s in drive.sprockets))
    model = ring_model(d, geometry, damping=damping)
    f1 = model.modal().first_elastic_frequency_hz
    st = drive_startup(d, geometry, model, duration=duration)
    wz = d.driver.teeth * d.driver.speed
    # sweep the tooth frequency through 0.3 f1 … 1.5 f1: the first harmonic crosses f1
    fz = np.linspace(0.3 * f1, 1.5 * f1, points)
    afc = afc_sweep(model, polygonal_excitation(geometry, wz), fz * 2 * np.pi / d.driver.teeth,
                    d.driver.teeth)
    curve = afc.span_load.max(axis=1)
    k = int(np.argmax(curve))
    return MaterialCase(chain_mat, sprocket_mat, float(st.max_span_force.max()), f1,
                        float(afc.tooth_frequencies_hz[k]), float(curve[k]))


def material_comparison(drive: Drive, geometry: GeometryResult, *, metal: str = "steel",
                        polymer: str = "PA6-GF30", damping: float = 0.06,
                        duration: float = 0.3, points: int = 600) -> tuple[MaterialCase, ...]:
    """The four pairs (chain, sprockets): metal/metal, polymer/metal, metal/polymer,
    polymer/polymer (seed 000 Table 1 order); start-up over ``duration`` [s]; AFC with
    ``points`` tooth frequencies."""
    pairs = ((metal, metal), (polymer, metal), (metal, polymer), (polymer, polymer))
    return tuple(_case(drive, geometry, a, b, damping, duration, points) for a, b in pairs)
