"""Dynamics of a chain contour: the n-mass ring model, modes, transverse span vibration,
working frequencies and resonances ([MultimassChainDrives]; docs/dynamics.md).

Low-level API::

    from chaindrive.dynamics import RingModel
    model = RingModel(masses_kg=[...], stiffness_n_per_m=[...], closed=True)
    modes = model.modal()

    from chaindrive.dynamics import TorsionalModel   # ring + trains (docs/torsional.md)
    t = TorsionalModel().add_inertia("motor", 400.0).add_shaft("motor", "pinion", 1.88e5)
"""

from __future__ import annotations

from typing import Any

from chaindrive._lazy import lazy_attribute

#: Public name → the submodule that defines it. The submodules are imported on first use
#: (PEP 562), so that ``import chaindrive.dynamics`` does not pull in the time-domain solvers
#: (scipy.linalg, numba) when only the modal analysis is wanted.
_WHERE: dict[str, str] = {
    "AfcResult": "frequency.afc",
    "CampbellData": "resonance",
    "ConstantTorque": "motors",
    "KlossMotor": "motors",
    "Modes": "modes",
    "RampTorque": "motors",
    "ResistanceLaw": "motors",
    "Resonance": "resonance",
    "RingModel": "ring",
    "RotorInertiaEstimate": "motor_inertia",
    "SpanExcitation": "excitation",
    "StartupResult": "transient.startup",
    "SteadyStateResult": "frequency.steady",
    "TorsionalModel": "torsional.model",
    "TorsionalSystem": "torsional.model",
    "WorkingFrequency": "resonance",
    "campbell_data": "resonance",
    "chain_error_excitation": "excitation",
    "coefficient_of_dynamics": "frequency.quality",
    "eccentricity_excitation": "excitation",
    "estimated_rotor_inertia": "motor_inertia",
    "modal_analysis": "ring",
    "parametric_resonance_frequency": "transverse",
    "parametric_zone": "transverse",
    "polygonal_excitation": "excitation",
    "reducer_input_torque": "torsional.model",
    "resonance_table": "resonance",
    "ring_frequencies_batch": "ring",
    "ring_stiffness_matrix": "ring",
    "shaft_frequencies": "resonance",
    "span_transverse_frequencies": "transverse",
    "working_frequencies": "resonance",
}


def __getattr__(name: str) -> Any:
    """Import the submodule that defines ``name`` on first use (PEP 562)."""
    return lazy_attribute(__name__, _WHERE, name)


def __dir__() -> list[str]:
    return sorted(__all__)


__all__ = [
    "AfcResult",
    "CampbellData",
    "ConstantTorque",
    "KlossMotor",
    "Modes",
    "RampTorque",
    "ResistanceLaw",
    "Resonance",
    "RingModel",
    "RotorInertiaEstimate",
    "SpanExcitation",
    "StartupResult",
    "SteadyStateResult",
    "TorsionalModel",
    "TorsionalSystem",
    "WorkingFrequency",
    "campbell_data",
    "chain_error_excitation",
    "coefficient_of_dynamics",
    "eccentricity_excitation",
    "estimated_rotor_inertia",
    "modal_analysis",
    "parametric_resonance_frequency",
    "parametric_zone",
    "polygonal_excitation",
    "reducer_input_torque",
    "resonance_table",
    "ring_frequencies_batch",
    "ring_stiffness_matrix",
    "shaft_frequencies",
    "span_transverse_frequencies",
    "working_frequencies",
]
