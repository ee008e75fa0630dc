"""Frequency-domain steady state (chaindrive.dynamics.steady, excitation)."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from chaindrive.dynamics import RingModel
from chaindrive.dynamics.excitation import polygonal_span_elongation
from chaindrive.dynamics.steady import harmonic_response, span_incidence
from chaindrive.kinematics import hinge_displacement_fourier

GROUND = 1e9  # a mass this large stands for the ground: mass 0 becomes a 1-DOF oscillator


def _one_dof(zeta: float, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    m, c = 2.0, 8e5
    wn = math.sqrt(c / m)
    beta = 2 * zeta / wn
    D = np.zeros((r.size, 2), complex)
    D[:, 1] = 1e-4  # span 1 joins mass 1 (ground) to mass 0: moves the "base"
    X, _ = harmonic_response([m, GROUND], [0.0, c], beta, r * wn, D)
    return np.abs(X[:, 0]), np.full(r.size, 1e-4)


def test_base_excitation_resonance_amplitude() -> None:
    # Rao, Mechanical Vibrations, §3.6.2 (base excitation): X/Y = sqrt(1+(2ζr)²)/
    # sqrt((1−r²)²+(2ζr)²); at r = 1 ≈ 1/(2ζ) for light damping
    for zeta in (0.02, 0.06):
        X, Y = _one_dof(zeta, np.array([1.0]))
        assert_allclose(X / Y, math.sqrt(1 + 4 * zeta**2) / (2 * zeta), rtol=1e-6)
        assert_allclose(X / Y, 1 / (2 * zeta), rtol=2 * zeta**2 + 1e-3)


def test_base_excitation_full_curve() -> None:
    zeta = 0.06
    r = np.linspace(0.05, 3.0, 200)
    X, Y = _one_dof(zeta, r)
    expected = np.sqrt(1 + (2 * zeta * r) ** 2) / np.sqrt((1 - r**2) ** 2 + (2 * zeta * r) ** 2)
    assert_allclose(X / Y, expected, rtol=1e-6)


def _ring() -> tuple[np.ndarray, np.ndarray, float]:
    return np.array([0.7, 1.9, 0.6]), np.array([8e4, 4.4e6, 4.4e6]), 2 * 0.06 / 2050.0


def test_energy_balance_over_a_period() -> None:
    # input work of the imposed elongations ∮ΣF ḋ dt = damping dissipation ∮Σβc(ė+ḋ)² dt
    m, c, beta = _ring()
    rng = np.random.default_rng(3)
    w = 2 * math.pi * 150.0 * np.arange(1, 6)
    D = (rng.normal(size=(5, 3)) + 1j * rng.normal(size=(5, 3))) * 1e-5
    X, F = harmonic_response(m, c, beta, w, D)
    B = span_incidence(3)
    E = X @ B.T
    # mean power per harmonic: ½ Re(F · conj(iω D)); dissipation ½ βc ω² |E + D|²
    w_in = 0.5 * np.sum((F * np.conj(1j * w[:, None] * D)).real / w[:, None])
    w_d = 0.5 * np.sum(beta * c * np.abs(E + D) ** 2 * w[:, None])
    assert_allclose(w_in, w_d, rtol=1e-2)
    assert w_d > 0


def test_frequency_domain_equals_time_integration_tail() -> None:
    # the periodic tail of a long, tight integration of the same linear system (2 %)
    m, c, beta = _ring()
    wz = 2 * math.pi * 200.0
    k = np.arange(1, 4)
    D = np.array([[1e-5, -2e-5j, 1e-5 + 1e-5j], [5e-6j, 3e-6, -4e-6],
                  [1e-6, 1e-6j, 2e-6]])
    _, F = harmonic_response(m, c, beta, k * wz, D)
    B = span_incidence(3)
    K = B.T @ (c[:, None] * B)

    def d_of(t: float) -> tuple[np.ndarray, np.ndarray]:
        e = np.exp(1j * k * wz * t)
        return (e @ D).real, ((1j * k * wz * e) @ D).real

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        d, dd = d_of(t)
        x, v = y[:3], y[3:]
        f = -K @ x - beta * K @ v - B.T @ (c * (d + beta * dd))
        return np.concatenate([v, f / m])

    T = 2 * math.pi / wz
    t_end = 60 * T
    ts = t_end - T + np.linspace(0, T, 64, endpoint=False)
    sol = solve_ivp(rhs, (0, t_end), np.zeros(6), method="DOP853", t_eval=ts,
                    rtol=1e-10, atol=1e-14)
    x, v = sol.y[:3].T, sol.y[3:].T
    dd = np.array([d_of(t) for t in ts])
    Ft = c * (x @ B.T + dd[:, 0]) + beta * c * (v @ B.T + dd[:, 1])
    Ff = (np.exp(1j * np.outer(ts, k * wz)) @ F).real
    scale = np.abs(Ff).max(axis=0)
    assert_allclose(Ft / scale, Ff / scale, atol=0.02)


def test_polygonal_elongation_matches_hinge_series() -> None:
    # d = δ_end − δ_start with δ from chaindrive.kinematics (seed-notes §1), ψ = ω_z t − 2π s
    p, zs, ze, s0, s1 = 0.0254, np.array([15.0]), np.array([25.0]), np.array([0.0]), np.array([53.68])
    D = polygonal_span_elongation(p, zs, ze, s0, s1, 10)
    psi = np.linspace(0, 2 * math.pi, 50)
    d = (np.exp(1j * np.outer(psi, np.arange(1, 11))) @ D).real[:, 0]
    ref = (hinge_displacement_fourier(p, 25, psi - 2 * math.pi * s1[0])
           - hinge_displacement_fourier(p, 15, psi))
    assert_allclose(d, ref, atol=1e-12)


def test_steady_state_result_dict_keys() -> None:
    from chaindrive.dynamics.excitation import SpanExcitation
    from chaindrive.dynamics.steady import steady_state

    m, c, _ = _ring()
    ex = SpanExcitation(np.array([1000.0, 2000.0]), np.full((2, 3), 1e-5 + 0j),
                        np.array([1.0, 2.0]), "polygonal")
    res = steady_state(RingModel(m, c, damping_ratio=0.06), ex, radii=[0.06, 0.1, 0.06],
                       nominal_force=262.0, breaking_load=6e4,
                       operating_forces=[300.0, 40.0, 40.0], resonance_loads=[500.0] * 3)
    out = res.to_dict()
    for key in ("span_dynamic_load_n", "inertia_load_n", "irregularity_percent",
                "coefficient_of_dynamics", "k2", "k2min"):
        assert key in out
    assert out["k2"] >= out["k2min"]
    assert_allclose(out["coefficient_of_dynamics"], 1 + res.dynamic_load_rms / 262.0)
