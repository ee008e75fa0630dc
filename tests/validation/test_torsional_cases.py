"""Published torsional cases, opentorsion and closed forms for the torsional model
(src/chaindrive/dynamics/torsional/model.py, docs/torsional.md).

Textbook answers are the printed values as re-run by the FOSSEE textbook companions
(Python-Textbook-Companions: "The Theory of Machines by T. Bevan", ch15; "Theory Of Machines
by B. K. Sarkar", Chapter11); tolerance 0.5 % (the books print 3 significant figures).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.dynamics import RingModel, TorsionalModel

IN = 0.0254  # m
LB = 0.45359237  # kg
PSI = 6894.757293168  # Pa
LB_IN2 = LB * IN**2  # kg·m²
TON_FT2 = 2240 * LB * 0.3048**2  # kg·m² (long ton)


def polar(d: float) -> float:
    """Polar second moment of area of a solid round shaft, π d⁴/32 [m⁴]."""
    return math.pi * d**4 / 32


def test_bevan_ex9_three_rotors_on_one_shaft() -> None:
    # [Bevan2005] T. Bevan, The Theory of Machines, 3rd ed., ch. 15, Example 9, p. 572: rotors A, B, C of
    # 2.5, 7.5, 3 ton·ft² on an 8.5 in shaft, AB 9.5 ft, BC 25 ft, C = 11.8e6 lb/in²;
    # printed 961 (one node) and 1784 (two nodes) vibrations per minute.
    k = 11.8e6 * PSI * polar(8.5 * IN)
    t = (TorsionalModel().add_inertia("A", 2.5 * TON_FT2).add_inertia("B", 7.5 * TON_FT2)
         .add_inertia("C", 3.0 * TON_FT2)
         .add_shaft("A", "B", k / (9.5 * 0.3048)).add_shaft("B", "C", k / (25 * 0.3048)))
    modes = t.modal()
    assert modes.frequencies_hz[0] == 0.0 and modes.rigid_body.tolist() == [True, False, False]
    assert_allclose(modes.elastic_frequencies_hz * 60, [961, 1784], rtol=5e-3)


def _bevan_ex11(gear_inertia: bool) -> TorsionalModel:
    # [Bevan2005] T. Bevan, The Theory of Machines, 3rd ed., ch. 15, Example 11, p. 587: rotor A
    # (1500 lb·in²) on a 2.75 in shaft to pinion B (54 lb·in²) meshing with wheel C
    # (850 lb·in²), speed ratio 0.6; C on a 3.5 in shaft of 25.5 in to rotor D
    # (50 000 lb·in²); C = 12e6 lb/in². The book reduces the system to a 2.75 in shaft of
    # equivalent length 66.5 in at A's speed; the length of the first shaft is therefore
    # l1 = 66.5 − 25.5·(2.75/3.5)⁴/0.6² in (the FOSSEE companion gives the 66.5 in, not l1).
    G = 12e6 * PSI
    ratio = 1 / 0.6
    l1 = 66.5 - 25.5 * (2.75 / 3.5) ** 4 * ratio**2
    t = TorsionalModel().add_inertia("A", 1500 * LB_IN2).add_inertia("D", 50000 * LB_IN2)
    t.add_inertia("B", 54 * LB_IN2 if gear_inertia else 0.0)
    t.add_inertia("C", 850 * LB_IN2 if gear_inertia else 0.0)
    t.add_shaft("A", "B", G * polar(2.75 * IN) / (l1 * IN))
    t.add_gear_mesh("B", "C", ratio=ratio)
    t.add_shaft("C", "D", G * polar(3.5 * IN) / (25.5 * IN))
    return t


def test_bevan_ex11a_geared_two_rotor_system() -> None:
    # part (a), gear inertias neglected (massless pinion and wheel, condensed): printed
    # 84.8 vibrations per second.
    modes = _bevan_ex11(gear_inertia=False).modal()
    assert modes.frequencies_hz.size == 2  # A and D; B, C condensed out
    assert_allclose(modes.elastic_frequencies_hz, [84.8], rtol=5e-3)


def test_bevan_ex11b_geared_rotors_with_gear_inertias() -> None:
    # part (b), with the gear inertias: printed 83.6 (one node) and 347 (two nodes) per s.
    modes = _bevan_ex11(gear_inertia=True).modal()
    assert_allclose(modes.elastic_frequencies_hz, [83.6, 347], rtol=5e-3)


def test_sarkar_ex12_geared_motor_pump() -> None:
    # [Sarkar2002] B. K. Sarkar, Theory of Machines, Tata McGraw-Hill 2002, ch. 11, Illustration 12,
    # p. 298: motor 400 kg·m² at 1500 rpm on a 45 mm × 0.18 m shaft, pump 1400 kg·m² at
    # 500 rpm on a 90 mm × 0.45 m shaft, C = 84 GPa, gear inertias neglected: printed 4.20 Hz.
    G = 84e9
    t = (TorsionalModel().add_inertia("motor", 400.0)
         .add_shaft("motor", "pinion", G * polar(0.045) / 0.18)
         .add_gear_mesh("pinion", "wheel", ratio=1500 / 500)
         .add_inertia("pump", 1400.0).add_shaft("wheel", "pump", G * polar(0.09) / 0.45))
    assert_allclose(t.modal().elastic_frequencies_hz, [4.20], rtol=5e-3)


def test_sarkar_ex3_rotor_between_two_fixed_ends() -> None:
    # [Sarkar2002] B. K. Sarkar, Theory of Machines, ch. 11, Illustration 3, p. 291: flywheel 450 kg,
    # radius of gyration 0.5 m, on a 50 mm shaft fixed at both ends, 0.9 m and 0.6 m from
    # it, C = 84 GPa: printed 5.673 Hz (the companion's π = 3.147; 5.678 Hz with π).
    G, J = 84e9, polar(0.05)
    t = (TorsionalModel().add_inertia("flywheel", 450 * 0.5**2)
         .add_ground_spring("flywheel", G * J / 0.9, name="left end")
         .add_ground_spring("flywheel", G * J / 0.6, name="right end"))
    modes = t.modal()
    assert not modes.rigid_body.any()
    assert_allclose(modes.frequencies_hz, [5.673], rtol=5e-3)
    shares = modes.participation
    assert_allclose([shares["left end"][0], shares["right end"][0]], [0.4, 0.6], rtol=1e-12)


def test_khurmi_three_rotor() -> None:
    # KHURMI-TOM-3ROTOR-OILENGINE-PUMP (validation/cases.yaml): 171 Hz and 277 Hz printed,
    # 170.69 / 277.03 Hz derived.
    k = 84e9 * polar(0.070)
    t = (TorsionalModel().add_inertia("A", 0.15).add_inertia("B", 0.30).add_inertia("C", 0.09)
         .add_shaft("A", "B", k / 1.5).add_shaft("B", "C", k / 1.0))
    f = t.modal().elastic_frequencies_hz
    assert_allclose(f, [171.0, 277.0], rtol=5e-3)
    assert_allclose(f, [170.69, 277.03], rtol=5e-4)


# -- opentorsion (Aalto-Arotor openTorsion, eig(K, M) with gear constraints) ---------------

def _ot_elastic(assembly: object) -> np.ndarray:
    lam = assembly.undamped_modal_analysis()[0]  # type: ignore[attr-defined]
    w = np.sort(np.sqrt(np.clip(lam.real, 0, None)))
    return w[w > 1e-6 * w.max()] / (2 * math.pi)


def test_open_line_matches_opentorsion() -> None:
    ot = pytest.importorskip("opentorsion")
    rng = np.random.default_rng(11)
    J = rng.uniform(0.5, 50.0, 24)
    k = rng.uniform(1e4, 1e7, 23)
    t = TorsionalModel()
    for i, j in enumerate(J):
        t.add_inertia(f"n{i}", j)
    for i, ki in enumerate(k):
        t.add_shaft(f"n{i}", f"n{i + 1}", ki)
    assembly = ot.Assembly([ot.Shaft(i, i + 1, k=float(ki)) for i, ki in enumerate(k)],
                           disk_elements=[ot.Disk(i, I=float(j)) for i, j in enumerate(J)])
    assert_allclose(t.modal().elastic_frequencies_hz, _ot_elastic(assembly), rtol=1e-6)


def test_bevan_ex11b_matches_opentorsion() -> None:
    # the same geared system with gear inertias; opentorsion's Gear(node, I, R, parent)
    # imposes R_parent φ_parent + R_child φ_child = 0 (external mesh, ratio R_child/R_parent).
    ot = pytest.importorskip("opentorsion")
    ours = _bevan_ex11(gear_inertia=True)
    s = ours.system()
    k1, k2 = s.element_stiffness
    gear1 = ot.Gear(1, I=54 * LB_IN2, R=0.6)
    gear2 = ot.Gear(2, I=850 * LB_IN2, R=1.0, parent=gear1)
    assembly = ot.Assembly([ot.Shaft(0, 1, k=float(k1)), ot.Shaft(2, 3, k=float(k2))],
                           disk_elements=[ot.Disk(0, I=1500 * LB_IN2), ot.Disk(3, I=50000 * LB_IN2)],
                           gear_elements=[gear1, gear2])
    assert_allclose(ours.modal().elastic_frequencies_hz, _ot_elastic(assembly), rtol=1e-6)


def test_branched_gear_train_matches_opentorsion() -> None:
    # a branched train: motor → pinion driving two wheels, each with its own shaft and
    # load (the openTorsion test suite's Friswell-type branched system, values ours).
    ot = pytest.importorskip("opentorsion")
    Jm, Jp, Jw, Jl = 3200.0, 200.0, 800.0, 450.0
    k1, k2, k3 = 4.0e7, 2.5e7, 1.5e7
    t = TorsionalModel().add_inertia("motor", Jm).add_inertia("pinion", Jp)
    t.add_inertia("wheel1", Jw).add_inertia("wheel2", Jw)
    t.add_inertia("load1", Jl).add_inertia("load2", Jl)
    t.add_shaft("motor", "pinion", k1).add_gear_mesh("pinion", "wheel1", ratio=1.6)
    t.add_gear_mesh("pinion", "wheel2", ratio=1.6)
    t.add_shaft("wheel1", "load1", k2).add_shaft("wheel2", "load2", k3)
    g0 = ot.Gear(1, I=Jp, R=0.5)
    gears = [g0, ot.Gear(2, I=Jw, R=0.8, parent=g0), ot.Gear(3, I=Jw, R=0.8, parent=g0)]
    assembly = ot.Assembly(
        [ot.Shaft(0, 1, k=k1), ot.Shaft(2, 4, k=k2), ot.Shaft(3, 5, k=k3)],
        disk_elements=[ot.Disk(0, I=Jm), ot.Disk(4, I=Jl), ot.Disk(5, I=Jl)],
        gear_elements=gears)
    assert_allclose(t.modal().elastic_frequencies_hz, _ot_elastic(assembly), rtol=1e-6)


# -- closed forms ----------------------------------------------------------------------------

def test_two_disc_shaft() -> None:
    # f = (1/2π) sqrt(k (J1 + J2) / (J1 J2)) [Rao2011, ch. 5]
    J1, J2, k = 2.0, 7.0, 3.3e5
    t = TorsionalModel().add_inertia("a", J1).add_inertia("b", J2).add_shaft("a", "b", k)
    modes = t.modal()
    assert modes.frequencies_hz[0] == 0.0
    assert_allclose(modes.frequencies_hz[1], math.sqrt(k * (J1 + J2) / (J1 * J2)) / (2 * math.pi),
                    rtol=1e-12)
    # rigid-body shape exact and uniform, mass-normalised
    assert_allclose(modes.shape_matrix[:, 0], [1 / math.sqrt(J1 + J2)] * 2, rtol=1e-15)


def test_tiny_middle_mass_keeps_its_genuine_low_mode() -> None:
    # masses m, ε, m joined by springs k (open): ω² = 0, k/m, k (1/m + 2/ε) — the 0.159 Hz
    # mode must not be zeroed by a round-off threshold (it was in RingModel).
    m, eps, k = 1.0, 1e-11, 1.0
    expected = np.sqrt([0.0, k / m, k * (1 / m + 2 / eps)]) / (2 * math.pi)
    ring = RingModel(masses_kg=[m, eps, m], stiffness_n_per_m=[k, k, 0]).modal()
    t = (TorsionalModel().add_inertia("a", m).add_inertia("b", eps).add_inertia("c", m)
         .add_span("a", "b", k, 1.0, 1.0).add_span("b", "c", k, 1.0, 1.0))
    for f, rigid in ((ring.frequencies_hz, ring.rigid_body), (t.modal().frequencies_hz,
                                                                t.modal().rigid_body)):
        assert rigid.tolist() == [True, False, False]
        assert f[0] == 0.0
        assert_allclose(f[1:], expected[1:], rtol=1e-5)


def _contour_data(n: int = 6) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(5)
    names = [f"s{i}" for i in range(n)]
    return names, rng.uniform(0.01, 2.0, n), rng.uniform(0.04, 0.25, n), rng.uniform(1e5, 5e6, n)


def test_ring_with_rigid_couplings_is_the_ring_model() -> None:
    # rigid couplings (a same-sense mesh of ratio 1) add the motor's inertia to its sprocket:
    # the frequencies are those of RingModel with m_i = ΣJ / R_i² (exact).
    names, J, R, c = _contour_data()
    Jm = np.linspace(0.5, 3.0, len(names))
    trains = {s: [{"name": f"m{i}", "inertia": float(Jm[i]), "ratio": 1.0, "same_sense": True}]
              for i, s in enumerate(names)}
    t = TorsionalModel.from_contour(names, J, R, c, trains=trains)
    ring = RingModel((J + Jm) / R**2, c).modal()
    modes = t.modal()
    assert_allclose(modes.frequencies_hz, ring.frequencies_hz, rtol=1e-10, atol=1e-9)
    assert t.system().size == len(names)


def test_ring_with_stiff_shafts_converges_to_the_ring_model() -> None:
    # shafts k → ∞: the lowest frequencies tend to those of the ring with m = ΣJ/R².
    names, J, R, c = _contour_data()
    Jm = np.linspace(0.5, 3.0, len(names))
    ring = RingModel((J + Jm) / R**2, c).modal().frequencies_hz
    errors = []
    for k in (1e8, 1e10, 1e12):
        trains = {s: [{"name": f"m{i}", "inertia": float(Jm[i]), "stiffness": k}]
                  for i, s in enumerate(names)}
        f = TorsionalModel.from_contour(names, J, R, c, trains=trains).modal().frequencies_hz
        errors.append(np.max(np.abs(f[1: len(names)] / ring[1:] - 1)))
    # the error falls as 1/k (first-order perturbation): ×1/100 per step
    assert errors[1] < 0.02 * errors[0] and errors[2] < 0.02 * errors[1] and errors[2] < 1e-6


def test_massless_condensation_is_the_limit_of_tiny_inertias() -> None:
    # a massless coupling hub condensed exactly = the same hub with inertia → 0
    def model(j_hub: float) -> TorsionalModel:
        return (TorsionalModel().add_inertia("motor", 0.8).add_inertia("hub", j_hub)
                .add_inertia("sprocket", 0.3).add_inertia("drum", 5.0)
                .add_shaft("motor", "hub", 2e4).add_shaft("hub", "sprocket", 6e4)
                .add_gear_mesh("sprocket", "gear", ratio=4.0).add_shaft("gear", "drum", 3e5))

    f0 = model(0.0).modal().frequencies_hz
    assert f0.size == 3
    for j, tol in ((1e-6, 1e-5), (1e-10, 1e-9)):
        assert_allclose(model(j).modal().frequencies_hz[:3], f0, rtol=tol)


def test_lumped_chain_mass_error_against_a_wave_model() -> None:
    # docs/torsional.md, "Chain mass": two sprockets z = 15 and 25 (reduced masses 17.26 and
    # 28.44 kg, seed-notes §3 [MultimassChainDrives]), 25.4 mm pitch (16A, EA = k_link·p),
    # two 1 m spans, q = 2.6 kg/m. Fine model: every span split into 128 translational
    # elements (longitudinal waves). Measured: the half-and-half lumping lowers f1 by 3.5 %,
    # leaving the chain out raises it by 3.7 %, the consistent span mass is within 0.1 %.
    p, q, L, EA = 0.0254, 2.6, 1.0, 5.077766e8 * 0.0254
    R = [p / (2 * math.sin(math.pi / z)) for z in (15, 25)]
    J = [m * r * r for m, r in zip((17.26, 28.44), R, strict=True)]
    th = math.pi - 2 * math.asin((R[1] - R[0]) / L)
    wrap = [R[0] * th, R[1] * (2 * math.pi - th)]
    c = EA / L

    def lumped(q_: float, consistent: bool = False) -> float:
        return TorsionalModel.from_contour(["s1", "s2"], J, R, [c, c],
                                           chain_mass_per_length_kg_per_m=q_,
                                           span_lengths_m=[L, L], wrap_lengths_m=wrap,
                                           consistent_mass=consistent
                                           ).modal().first_elastic_frequency_hz

    def fine(k: int) -> float:
        t = TorsionalModel()
        t.add_inertia("s1", J[0]).add_inertia("s2", J[1])
        for i, (a, b, ra, rb) in enumerate((("s1", "s2", R[0], R[1]), ("s2", "s1", R[1], R[0]))):
            prev, rp = a, ra
            for j in range(1, k):
                t.add_inertia(f"x{i}.{j}", q * L / k).add_span(prev, f"x{i}.{j}", k * c, rp, 1.0)
                prev, rp = f"x{i}.{j}", 1.0
            t.add_span(prev, b, k * c, rp, rb, name=f"x{i}.end")
        for name, r, w in (("s1", R[0], wrap[0]), ("s2", R[1], wrap[1])):
            t.add_chain_wrap(name, q * w + 2 * q * L / (2 * k), r)  # wrap + end half-elements
        return t.modal().first_elastic_frequency_hz

    f_fine = fine(128)
    assert abs(fine(32) / f_fine - 1) < 1e-4  # converged (the error falls as 1/k²)
    assert_allclose(lumped(q) / f_fine - 1, -0.0353, atol=5e-4)
    assert_allclose(lumped(0.0) / f_fine - 1, 0.0374, atol=5e-4)
    # the consistent span mass (m/3 on each end, m/6 coupling; Rayleigh's linear profile)
    # is the choice of the whole-drive model: +0.03 % (docs/torsional.md §5)
    assert abs(lumped(q, consistent=True) / f_fine - 1) < 1e-3
