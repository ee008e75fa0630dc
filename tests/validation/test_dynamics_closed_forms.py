"""Closed-form and published checks of the dynamics solvers (issue 4 §Validation)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.dynamics import RingModel, modal_analysis, span_transverse_frequencies


def test_two_masses_on_a_ring() -> None:
    # ω² = (c12 + c21)(1/m1 + 1/m2): the two branches act in parallel (issue 4).
    m1, m2, c12, c21 = 3.0, 7.0, 2.0e6, 5.0e5
    r = RingModel([m1, m2], [c12, c21]).modal()
    assert r.frequencies_hz[0] == 0.0
    assert_allclose(r.angular_frequencies_rad_s[1], math.sqrt((c12 + c21) * (1 / m1 + 1 / m2)),
                    rtol=1e-12)


@pytest.mark.parametrize("n", range(2, 25))
def test_equal_masses_closed_ring(n: int) -> None:
    # n equal masses and stiffnesses on a ring: ω_k = 2 sqrt(c/m) sin(πk/n), k = 0…n−1
    # (circulant Laplacian; e.g. Meirovitch, Fundamentals of Vibrations, periodic chains).
    m, c = 2.5, 4.0e6
    expected = np.sort(2 * math.sqrt(c / m) * np.abs(np.sin(np.pi * np.arange(n) / n)))
    r = RingModel([m] * n, [c] * n).modal()
    assert_allclose(r.angular_frequencies_rad_s, expected, rtol=1e-10, atol=1e-6)
    assert r.frequencies_hz[0] == 0.0


@pytest.mark.parametrize("n", [2, 3, 5, 8, 13, 24])
def test_equal_masses_open_chain(n: int) -> None:
    # free-free chain of n equal masses (one span slack): ω_k = 2 sqrt(c/m) sin(πk/(2n))
    m, c = 1.7, 3.0e6
    expected = 2 * math.sqrt(c / m) * np.sin(np.pi * np.arange(n) / (2 * n))
    stiff = [c] * (n - 1) + [0.0]
    for model in (RingModel([m] * n, stiff), RingModel([m] * n, [c] * n, closed=False)):
        assert_allclose(model.modal().angular_frequencies_rad_s, expected, rtol=1e-10, atol=1e-6)


def test_random_rings_against_dense_eig() -> None:
    # independent solution: eigenvalues of the non-symmetric M⁻¹K with numpy.linalg.eig
    rng = np.random.default_rng(7)
    for n in (3, 6, 11, 24):
        for _ in range(5):
            m = rng.uniform(0.2, 30.0, n)
            c = rng.uniform(1e4, 1e8, n)
            K = np.diag(c + np.roll(c, 1)) - np.diag(c[:-1], 1) - np.diag(c[:-1], -1)
            K[0, -1] = K[-1, 0] = -c[-1]
            lam = np.sort(np.linalg.eig(K / m[:, None])[0].real)
            w_ref = np.sqrt(np.clip(lam, 0, None))
            r = modal_analysis(m, c)
            assert_allclose(r.angular_frequencies_rad_s[1:], w_ref[1:], rtol=1e-8)
            # rigid-body mode uniform and exactly 0
            assert r.frequencies_hz[0] == 0.0
            assert np.all(r.shapes[:, 0] == r.shapes[0, 0])
            # each shape satisfies K x = ω² M x
            for j in range(1, n):
                x = r.shapes[:, j]
                assert_allclose(K @ x, r.angular_frequencies_rad_s[j] ** 2 * m * x,
                                rtol=1e-7, atol=1e-7 * np.abs(K @ x).max())


def test_open_chain_matches_opentorsion() -> None:
    # The same open chain in opentorsion (Aalto-Arotor/openTorsion; Disk I = m, Shaft k = c):
    # undamped_modal_analysis solves eig(K, M); frequencies agree within 1e-6 relative.
    ot = pytest.importorskip("opentorsion")
    rng = np.random.default_rng(3)
    n = 24
    m = rng.uniform(0.5, 20.0, n)
    c = rng.uniform(1e5, 1e8, n - 1)
    shafts = [ot.Shaft(i, i + 1, k=float(c[i])) for i in range(n - 1)]
    disks = [ot.Disk(i, I=float(m[i])) for i in range(n)]
    lam = ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()[0]
    w_ot = np.sort(np.sqrt(np.clip(lam.real, 0, None)))
    r = RingModel(m, [*c, 0.0]).modal()
    assert_allclose(r.angular_frequencies_rad_s[1:], w_ot[1:], rtol=1e-6)
    assert w_ot[0] < 1e-3 * w_ot[1] and r.angular_frequencies_rad_s[0] == 0.0


def _nodes(shape: np.ndarray, positions: np.ndarray) -> list[float]:
    out = []
    for a in range(len(shape) - 1):
        if shape[a] * shape[a + 1] < 0:
            out.append(positions[a] + (positions[a + 1] - positions[a])
                       * shape[a] / (shape[a] - shape[a + 1]))
    return out


def test_khurmi_three_rotor_free_free() -> None:
    # KHURMI-TOM-3ROTOR-OILENGINE-PUMP (validation/cases.yaml): Khurmi & Gupta, Theory of
    # Machines, ch. 24: rotors 0.15, 0.30, 0.09 kg·m² on a 70 mm shaft, G = 84 GPa,
    # A–B 1.5 m, B–C 1.0 m. Published 171 Hz (node 1.146 m from A) and 277 Hz (nodes
    # 0.4356 m from A, 0.726 m from C); tolerance ±0.5 % and ±3 mm (cases.yaml).
    J = math.pi * 0.070**4 / 32
    k_ab, k_bc = 84e9 * J / 1.5, 84e9 * J / 1.0
    r = RingModel([0.15, 0.30, 0.09], [k_ab, k_bc, 0.0]).modal()
    assert_allclose(r.frequencies_hz[1:], [171.0, 277.0], rtol=5e-3)
    assert_allclose(r.frequencies_hz[1:], [170.69, 277.03], rtol=5e-4)  # cases.yaml derived
    pos = np.array([0.0, 1.5, 2.5])
    assert_allclose(_nodes(r.shapes[:, 1], pos), [1.146], atol=3e-3)
    assert_allclose(_nodes(r.shapes[:, 2], pos), [0.4356, 2.5 - 0.726], atol=3e-3)


def test_string_bsc_physics_ch11_ex5() -> None:
    # STRING-BSC-PHYSICS-CH11-EX5 (cases.yaml; Balabhaskar et al., BSc 1st Year Physics,
    # ch. 11 ex. 5, p. 372): steel wire r = 1 mm, ρ = 7930 kg/m³, L = 1 m, T = 1e4 N;
    # f1, f2, f3 = 316.78, 633.56, 950.34 Hz, tolerance rel 1e-3. At v = 0 the moving-string
    # formula is the taut string.
    q = 7930 * math.pi * 0.001**2
    f = span_transverse_frequencies(1.0, 1.0e4, q, 0.0, modes=3)
    assert_allclose(f, [316.78, 633.56, 950.34], rtol=1e-3)


def test_moving_string_reduction() -> None:
    # Mote (1965), Wickert & Mote (1990): f_n = n c (1 − v²/c²) / (2L); at v = c → 0.
    T, q, L = 2000.0, 2.6, 0.8
    c = math.sqrt(T / q)
    f = span_transverse_frequencies(L, T, q, [0.0, 0.5 * c, c, 1.2 * c], modes=2)
    assert_allclose(f[:, 0], np.array([1.0, 0.75, 0.0, 0.0]) * c / (2 * L))
    assert_allclose(f[:, 1], 2 * f[:, 0])
