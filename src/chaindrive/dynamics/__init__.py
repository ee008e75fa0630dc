"""Dynamics of a chain contour: the n-mass ring model, modes, transverse span vibration,
working frequencies and resonances (seed 000; docs/dynamics.md).

Low-level API::

    from chaindrive.dynamics import RingModel
    model = RingModel(masses_kg=[...], stiffness_n_per_m=[...], closed=True)
    modes = model.modal()
"""

from __future__ import annotations

from chaindrive.dynamics.afc import AfcResult, afc_sweep
from chaindrive.dynamics.excitation import (
    SpanExcitation,
    chain_error_excitation,
    eccentricity_excitation,
    polygonal_excitation,
)
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
from chaindrive.dynamics.startup import (
    ConstantTorque,
    KlossMotor,
    RampTorque,
    ResistanceLaw,
    StartupResult,
    linear_transient,
    simulate_startup,
)
from chaindrive.dynamics.steady import SteadyStateResult, harmonic_response, steady_state
from chaindrive.dynamics.transverse import (
    parametric_resonance_frequency,
    parametric_zone,
    span_transverse_frequencies,
)

__all__ = [
    "AfcResult",
    "CampbellData",
    "ConstantTorque",
    "DynamicsResult",
    "KlossMotor",
    "ModalResult",
    "RampTorque",
    "ResistanceLaw",
    "Resonance",
    "RingModel",
    "SpanExcitation",
    "StartupResult",
    "SteadyStateResult",
    "WorkingFrequency",
    "afc_sweep",
    "analyze_dynamics",
    "campbell_data",
    "chain_error_excitation",
    "coefficient_of_dynamics",
    "eccentricity_excitation",
    "harmonic_response",
    "linear_transient",
    "modal_analysis",
    "nominal_peripheral_force",
    "parametric_resonance_frequency",
    "parametric_zone",
    "polygonal_excitation",
    "resonance_table",
    "ring_frequencies_batch",
    "ring_stiffness_matrix",
    "shaft_frequencies",
    "simulate_startup",
    "span_transverse_frequencies",
    "steady_state",
    "tooth_frequency",
    "working_frequencies",
]
