"""Amplitude–frequency characteristics (chaindrive.dynamics.afc)."""

from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose

from chaindrive.dynamics import RingModel
from chaindrive.dynamics.afc import afc_sweep, modal_harmonic_response
from chaindrive.dynamics.excitation import SpanExcitation
from chaindrive.dynamics.steady import damping_beta, harmonic_response


def _model(zeta: float) -> RingModel:
    return RingModel([0.7, 1.9, 0.6, 1.2], [8e5, 4.4e6, 2e6, 3e6], damping_ratio=zeta)


def test_modal_superposition_equals_direct_solve() -> None:
    model = _model(0.06)
    modal = model.modal()
    rng = np.random.default_rng(0)
    D = (rng.normal(size=(3, 4)) + 1j * rng.normal(size=(3, 4))) * 1e-5
    w = np.array([300.0, 1700.0, 4200.0])
    b = damping_beta(model)
    F1 = modal_harmonic_response(modal.shapes, modal.angular_frequencies_rad_s,
                                 model.stiffness_n_per_m, b, w, D)
    _, F2 = harmonic_response(model.masses_kg, model.stiffness_n_per_m, b, w, D)
    assert_allclose(F1, F2, rtol=1e-9, atol=1e-12 * np.abs(F2).max())


def test_afc_peaks_at_natural_frequencies() -> None:
    # light damping (ζ = 0.002: peak shift ~ζ² ≪ the sweep step); one harmonic per span
    model = _model(0.002)
    nat = model.modal().elastic_frequencies_hz
    D = np.array([[1e-5, -0.7e-5, 0.4e-5, 0.9e-5]], complex)
    ex = SpanExcitation(np.array([1.0]), D, np.array([1.0]), "polygonal")
    z = 20
    speeds = np.linspace(0.8 * nat[0], 1.1 * nat[-1], 2000) * 2 * np.pi / z
    afc = afc_sweep(model, ex, speeds, z)
    step = np.diff(afc.tooth_frequencies_hz)[0]
    for f in nat:
        assert np.min(np.abs(afc.peak_tooth_frequencies_hz - f)) <= step
    assert len(afc.markers) == nat.size
    assert set(afc.to_dict()) >= {"tooth_frequency_hz", "span_dynamic_load_n", "resonances"}
