"""Dynamics of a chain contour: the n-mass ring model, modes, transverse span vibration,
working frequencies and resonances (seed 000; docs/dynamics.md).

Low-level API::

    from chaindrive.dynamics import RingModel
    model = RingModel(masses_kg=[...], stiffness_n_per_m=[...], closed=True)
    modes = model.modal()
"""

from __future__ import annotations

from chaindrive.dynamics.quality import coefficient_of_dynamics, nominal_peripheral_force
from chaindrive.dynamics.resonance import (
    CampbellData,
    DynamicsResult,
    Resonance,
    WorkingFrequency,
    analyze_dynamics,
    campbell_data,
    resonance_table,
    shaft_frequencies,
    tooth_frequency,
    working_frequencies,
)
from chaindrive.dynamics.ring import (
    ModalResult,
    RingModel,
    modal_analysis,
    ring_frequencies_batch,
    ring_stiffness_matrix,
)
from chaindrive.dynamics.transverse import (
    parametric_resonance_frequency,
    parametric_zone,
    span_transverse_frequencies,
)

__all__ = [
    "CampbellData",
    "DynamicsResult",
    "ModalResult",
    "Resonance",
    "RingModel",
    "WorkingFrequency",
    "analyze_dynamics",
    "campbell_data",
    "coefficient_of_dynamics",
    "modal_analysis",
    "nominal_peripheral_force",
    "parametric_resonance_frequency",
    "parametric_zone",
    "resonance_table",
    "ring_frequencies_batch",
    "ring_stiffness_matrix",
    "shaft_frequencies",
    "span_transverse_frequencies",
    "tooth_frequency",
    "working_frequencies",
]
