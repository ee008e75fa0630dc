"""Probabilities of failure over the uncertainty model (chaindrive.robust.sampling).

* Convergence: the estimate with twice the samples lies inside the interval of the first
  (randomised quasi-Monte Carlo, [Owen1997]).
* A drive with no uncertainty is evaluated once: each probability is exactly 0 or 1.
* The interval of an estimate of 0 is the Clopper–Pearson bound 1 − (α/2)^(1/N)
  [ClopperPearson1934] (closed form).
* The batched modal path equals the full path state by state: the same whole-drive model
  (node inertias and element stiffnesses to 1e-12; the stiffness formulas in closed form,
  [Naji1983], [Ernst1965]) and the same natural frequencies and resonance margin (to 1e-9;
  the stacked eigenvalue problems against the analysis's own modal stage).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg

import chaindrive
from chaindrive.model import TrainElement
from chaindrive.robust import (
    Perturbation,
    PerturbedAnalysis,
    UncertaintySettings,
    nominal_analysis,
    reliability,
    uncertainty_model,
)
from chaindrive.robust.modal import (
    _mass_normalised,
    batch_elastic_frequencies,
    batch_system_values,
    modal_margins,
)
from chaindrive.robust.sampling import estimate_probability, sobol_points
from tests.conftest import EXAMPLES

NONE = dict(chain_length_tolerance=0.0, eccentricity=0.0, centre_distance_tolerance=0.0,
            inertia_scatter=0.0, stiffness_scatter=0.0, wear="new")


@pytest.fixture(scope="module")
def seed() -> chaindrive.analysis.Analysis:
    return nominal_analysis(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"))


def test_sobol_points_are_reproducible_scrambled_sets() -> None:
    u = sobol_points(5, 100, 4, seed=3)
    assert u.shape == (4, 32, 5)                      # 100/4 rounded up to 2^5 per replicate
    assert np.all((u > 0) & (u < 1))
    assert np.array_equal(u, sobol_points(5, 100, 4, seed=3))
    assert not np.array_equal(u[0], u[1])             # independent scramblings
    # each replicate is a (0, m, 5)-net: every coordinate stratified over 32 cells
    cells = np.floor(u[0] * 32).astype(int)
    assert all(np.array_equal(np.sort(cells[:, k]), np.arange(32)) for k in range(5))


def test_clopper_pearson_bound_of_no_failure() -> None:
    p, lo, hi = estimate_probability(np.zeros((4, 16), bool), 0.95)
    assert (p, lo) == (0.0, 0.0)
    assert hi == pytest.approx(1 - 0.025 ** (1 / 64))  # closed form for k = 0
    p, lo, hi = estimate_probability(np.ones((4, 16), bool), 0.95)
    assert (p, hi) == (1.0, 1.0) and lo == pytest.approx(0.025 ** (1 / 64))


def test_no_uncertainty_gives_zero_or_one_exactly(seed) -> None:
    """Without a random variable the drive is evaluated once, and every probability is the
    analysis's own verdict, 0 or 1 exactly. The failing checks come from the analysis: the
    seed contour as drawn fails teeth in mesh on its idler S3 and the resonance margin (the
    whole-drive model's f₁ = 73.06 Hz lies 2.7 % below the 75 Hz tooth frequency,
    docs/dynamics.md §7) and passes the rest."""
    model = uncertainty_model(seed, UncertaintySettings(**NONE))
    assert model.dimension == 0
    r = reliability(seed, model)
    assert r.samples == 1
    by_key = {c.key: c for c in r.checks}
    nominal_checks = {c.key: c.status for c in seed.checks()}
    # its polymer sprockets' teeth (no confirmed allowable stress) cannot be verified; its
    # chain's fatigue passes against the estimate 15 % of the breaking load [IwisFatigue]
    teeth = {f"{n}[{s}]" for s in ("S1", "S2", "S3")
             for n in ("tooth_root_stress", "tooth_contact_pressure")}
    assert {k for k, s in nominal_checks.items() if s != "pass"} == {
        "teeth_in_mesh[S3]", "resonance_margin", *teeth}
    for key in ("teeth_in_mesh[S3]", "resonance_margin"):
        assert (by_key[key].probability, by_key[key].low, by_key[key].high) == (1.0, 1.0, 1.0)
    for key in ("hinge_pressure", "k2", "k2min", "static_safety"):
        assert (by_key[key].probability, by_key[key].low, by_key[key].high) == (0.0, 0.0, 0.0)
    for key, status in nominal_checks.items():
        assert by_key[key].probability == (0.0 if status == "pass" else 1.0)


def test_full_path_converges(seed) -> None:
    settings = UncertaintySettings(samples=32, replicates=4, seed=11)
    r1 = reliability(seed, uncertainty_model(seed, settings))
    r2 = reliability(seed, uncertainty_model(seed, replace(settings, samples=64)))
    assert r2.samples == 2 * r1.samples
    for c1 in r1.checks:
        c2 = r2.probability(c1.key)
        assert c2 is not None and c1.low <= c2.probability <= c1.high, c1.key
    res = r1.probability("resonance_margin")
    assert res is not None and 0.0 < res.probability < 1.0   # the test exercises a real spread


def test_modal_path_converges(seed) -> None:
    settings = UncertaintySettings(samples=64, replicates=8, seed=5, wear="life",
                                   inertia_scatter=0.25)
    model = uncertainty_model(seed, settings)
    small = reliability(seed, model, path="modal").checks[0]
    large = reliability(seed, uncertainty_model(seed, replace(settings, samples=128)),
                        path="modal").checks[0]
    assert 0.0 < small.probability < 1.0
    assert small.low <= large.probability <= small.high


@pytest.mark.parametrize("elongation", [0.0, 0.01])
def test_batched_modal_path_equals_the_full_path(elongation: float) -> None:
    drive = chaindrive.load(EXAMPLES / "eight_sprocket.toml")
    polymer = drive.with_sprockets(tuple(replace(s, material="PA66") if s.role == "idler"
                                         else s for s in drive.sprockets))
    nominal = nominal_analysis(polymer)
    state = PerturbedAnalysis(nominal, Perturbation(elongation=elongation), response=False)
    rng = np.random.default_rng(2)
    n = len(polymer.sprockets)
    inertia = rng.uniform(0.9, 1.1, (3, n))
    link = rng.uniform(0.9, 1.1, 3)
    temperature = np.array([0.0, 23.0, 70.0])
    J, k = batch_system_values(state, inertia, link, temperature)
    elastic = batch_elastic_frequencies(state.drive_model.system, J, k)
    f1, margin = modal_margins(state, elastic)
    for s in range(3):
        full = PerturbedAnalysis(nominal, Perturbation(
            elongation=elongation, inertia_factors=tuple(inertia[s]),
            chain_stiffness_factor=float(link[s]), temperature_c=float(temperature[s])),
            response=False)
        system = full.drive_model.system
        assert np.allclose(k[s], system.element_stiffness, rtol=1e-12, atol=0.0)
        assert np.allclose(J[s], system.node_inertia_kg_m2, rtol=1e-12, atol=0.0)
        expected = full.dynamics.modal.elastic_frequencies_hz
        assert np.allclose(elastic[s], expected, rtol=1e-9, atol=0.0)
        assert f1[s] == pytest.approx(expected[0], rel=1e-9)
        assert margin[s] == pytest.approx(full.check("resonance_margin").value, rel=1e-9)
    # the polymer idlers soften with temperature: higher T, lower stiffness of their spans
    cold, warm = batch_system_values(state, np.ones((2, n)), np.ones(2),
                                     np.array([0.0, 70.0]))[1]
    assert np.all(warm <= cold) and np.any(warm < cold)


def test_batched_frequencies_equal_the_engine_with_trains_and_a_massless_node() -> None:
    """The stacked eigenvalue problems equal the torsional engine's own
    (:meth:`TorsionalSystem.updated` then ``frequencies_hz``, a deflated eigenproblem) for a
    drive with trains, a motor and a massless train node, which both condense statically
    [Guyan1965]; the rigid-body mode is the one the model's graph gives."""
    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    d1 = next(i for i, s in enumerate(drive.sprockets) if s.name == "D1")
    sprocket = drive.sprockets[d1]
    train = (TrainElement("shaft", name="mid", stiffness=3e4), *sprocket.train)
    drive = drive.with_sprockets(tuple(replace(s, train=train) if i == d1 else s
                                       for i, s in enumerate(drive.sprockets)))
    state = nominal_analysis(drive)
    system = state.drive_model.system
    assert np.any(system.mass <= 0) and system.rigid_motions.shape[1] == 1
    n = len(drive.sprockets)
    rng = np.random.default_rng(4)
    J, k = batch_system_values(state, rng.uniform(0.8, 1.2, (4, n)), rng.uniform(0.9, 1.1, 4),
                               np.full(4, 23.0))
    elastic = batch_elastic_frequencies(system, J, k)
    for s in range(4):
        engine = system.updated(node_inertia_kg_m2=J[s], element_stiffness=k[s]).frequencies_hz()
        assert np.allclose(elastic[s], engine[1:], rtol=1e-9, atol=0.0)


def test_mass_normalised_stack_has_the_generalised_eigenvalues() -> None:
    """eigvalsh of the stacked L⁻¹ K L⁻ᵀ (lower triangle, coordinates reordered) = the
    eigenvalues of K x = λ M x (the definition, scipy.linalg.eigh's generalised problem) on
    both branches: the varying masses uncoupled (one factor for the common rest) and coupled
    (one factor per sample)."""
    rng = np.random.default_rng(0)
    coupling = np.zeros((4, 4))
    coupling[2, 3] = coupling[3, 2] = 0.4       # a consistent mass couples coordinates 2 and 3
    B = rng.standard_normal((5, 4))
    for varying in (0, 2):
        mass = np.repeat(np.array([[2.0, 3.0, 1.0, 1.5]]), 5, axis=0)
        mass[:, varying] *= rng.uniform(0.8, 1.2, 5)
        k = rng.uniform(1.0, 3.0, (5, 5))
        K = np.einsum("ei,se,ej->sij", B, k, B)
        lam = np.linalg.eigvalsh(_mass_normalised(K, mass, coupling))
        for s in range(5):
            expected = scipy.linalg.eigh(K[s], coupling + np.diag(mass[s]), eigvals_only=True)
            assert np.allclose(lam[s], expected, rtol=1e-12, atol=1e-12)
