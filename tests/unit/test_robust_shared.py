"""The modal basis shared by designs that differ only in their flywheels
(chaindrive.robust.study.shared_modal_basis).

* A design with flywheels through the shared basis of its flywheel-free twin gives the
  frequencies, margins and probability of its own batched modal path (built with the
  flywheels, no sharing) to 1e-9 — new and worn (the wear states are rebuilt analyses),
  with and without inertia scatter, and with trains, a motor and a massless node condensed
  statically [Guyan1965].
* The flywheel enters as inertia on the sprocket's node only: J_node = J₀ + ΔJ·f with the
  sample's inertia factor f (closed form, the sum J_i + ΔJ_i scaled by f_i).
* A changed geometric input is never served a stale basis: a design with another tooth count
  gets a basis of its own whose pitch radius is R = p / (2 sin(π/z)) of the new count
  ([ISO606], closed form), and its results equal its own path.
* The split mass normalisation a basis keeps, the per-call one and the uncondensed path give
  the same margins (a similarity; [Guyan1965]).
* ``robust_batch`` (a study's worker) reports for each vector its own path's probability,
  interval and quantiles.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest
import tomli_w

import chaindrive
from chaindrive.model import Drive, TrainElement
from chaindrive.robust import UncertaintySettings, nominal_analysis, uncertainty_model
from chaindrive.robust.modal import (
    _stacked_stiffness,
    batch_system_values,
    stacked_margins,
    stacked_state,
)
from chaindrive.robust.sampling import ReliabilityResult, basis_reliability, modal_reliability
from chaindrive.robust.study import robust_batch, shared_modal_basis, without_flywheels
from chaindrive.robust.uncertainty import uncertainty_settings
from chaindrive.synthesis.problem import problem_from_mapping
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def drive() -> Drive:
    return chaindrive.load(EXAMPLES / "eight_sprocket.toml")


def with_flywheels(drive: Drive, flywheels: dict[str, float]) -> Drive:
    return drive.with_sprockets(tuple(replace(s, flywheel=flywheels.get(s.name, s.flywheel))
                                      for s in drive.sprockets))


def own_path(design: Drive, settings: UncertaintySettings) -> ReliabilityResult:
    nominal = nominal_analysis(design)
    return modal_reliability(nominal, uncertainty_model(nominal, settings))


def assert_same(shared: ReliabilityResult, own: ReliabilityResult) -> None:
    for key in ("f1_hz", "resonance_margin_percent"):
        assert np.allclose(shared.values[key], own.values[key], rtol=1e-9, atol=0.0)
    assert shared.checks[0].probability == own.checks[0].probability
    assert shared.checks[0].failures == own.checks[0].failures


def conveyor_with_massless_node() -> Drive:
    """The conveyor example with a shaft element before D1's train: a massless train node,
    condensed statically [Guyan1965]."""
    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    d1 = next(i for i, s in enumerate(drive.sprockets) if s.name == "D1")
    train = (TrainElement("shaft", name="mid", stiffness=3e4), *drive.sprockets[d1].train)
    return drive.with_sprockets(tuple(replace(s, train=train) if i == d1 else s
                                      for i, s in enumerate(drive.sprockets)))


@pytest.mark.parametrize(("example", "wear", "scatter", "flywheels"), [
    ("eight", "new", 0.2, ({"D1": 0.02, "D3": 0.05}, {"D1": 0.004, "D4": 0.03})),
    ("eight", "worn", 0.2, ({"D1": 0.02, "D3": 0.05}, {"D1": 0.004, "D4": 0.03})),
    # no inertia scatter: only the flywheels change the sprockets' masses; trains, a motor
    # and a massless node
    ("conveyor", "new", 0.0, ({"D1": 0.5}, {"D1": 2.0, "D2": 1.0})),
])
def test_designs_differing_in_flywheels_share_a_basis_and_keep_their_results(
        drive: Drive, example: str, wear: str, scatter: float,
        flywheels: tuple[dict[str, float], dict[str, float]]) -> None:
    base = drive if example == "eight" else conveyor_with_massless_node()
    settings = UncertaintySettings(samples=32, replicates=2, seed=3, wear=wear,
                                   inertia_scatter=scatter)
    first, second = (with_flywheels(base, f) for f in flywheels)
    basis_1, added_1 = shared_modal_basis(first, settings)
    basis_2, added_2 = shared_modal_basis(second, settings)
    assert basis_2 is basis_1                      # built once for both
    assert added_1 is not None and added_2 is not None
    assert_same(basis_reliability(basis_1, added_1), own_path(first, settings))
    assert_same(basis_reliability(basis_2, added_2), own_path(second, settings))
    # the flywheels move the frequencies: the sharing is not blind to them
    assert not np.allclose(basis_reliability(basis_1, added_1).values["f1_hz"],
                           basis_reliability(basis_2, added_2).values["f1_hz"])


def test_flywheel_is_inertia_on_its_node_scaled_with_the_sprocket(drive: Drive) -> None:
    settings = UncertaintySettings(samples=8, replicates=2, seed=1, wear="new",
                                   inertia_scatter=0.2)
    design = with_flywheels(drive, {"D2": 0.03})
    twin, added = without_flywheels(design)
    assert all(s.flywheel == 0.0 for s in twin.sprockets)
    i = [s.name for s in design.sprockets].index("D2")
    assert added[i] == 0.03 and np.count_nonzero(added) == 1
    stacked = shared_modal_basis(design, settings)[0].states[0]
    f = stacked.inertia_factors
    S = f.shape[0]
    # the design's own node inertias under the same factors (flywheel built in)
    J_own = batch_system_values(nominal_analysis(design), f, np.ones(S), np.full(S, 23.0))[0]
    expected = stacked.node_inertia.copy()
    expected[:, stacked.sprocket_nodes[i]] += 0.03 * f[:, i]   # J₀ + ΔJ·f
    assert np.allclose(J_own, expected, rtol=1e-12, atol=0.0)
    assert np.ptp(f[:, i]) > 0.0                   # the factors do scatter


def test_changed_tooth_count_gets_its_own_basis(drive: Drive) -> None:
    settings = UncertaintySettings(samples=16, replicates=2, seed=2, wear="new")
    design = with_flywheels(drive, {"D1": 0.01})
    i = [s.name for s in drive.sprockets].index("D3")
    other = design.with_sprockets(tuple(replace(s, teeth=s.teeth + 2) if k == i else s
                                        for k, s in enumerate(design.sprockets)))
    basis, _ = shared_modal_basis(design, settings)
    changed, added = shared_modal_basis(other, settings)
    assert changed is not basis
    p = drive.chain.spec.pitch
    z = other.sprockets[i].teeth
    radius = changed.states[0].state.geometry.sprockets[i].pitch_radius
    assert radius == pytest.approx(p / (2.0 * math.sin(math.pi / z)), rel=1e-12)
    assert radius != pytest.approx(basis.states[0].state.geometry.sprockets[i].pitch_radius,
                                   rel=1e-6)
    assert_same(basis_reliability(changed, added), own_path(other, settings))


def test_every_branch_of_a_stacked_state_gives_the_same_margins(drive: Drive) -> None:
    """The split mass normalisation (what a shared basis keeps) against the per-call one
    (a varying coordinate mass-coupled) and against no condensation kept (a sprocket on a
    massless coordinate): one eigenvalue problem three ways, the same f₁ and margins to
    1e-9 (the block normalisation is a similarity, [Guyan1965] exact for the undamped
    modes)."""
    settings = UncertaintySettings(samples=16, replicates=2, seed=4, wear="new",
                                   inertia_scatter=0.2)
    stacked = shared_modal_basis(with_flywheels(drive, {"D1": 0.01}), settings)[0].states[0]
    assert stacked.split is not None and stacked.stiffness is None
    system = stacked.state.drive_model.system
    S = stacked.node_inertia.shape[0]
    k = np.repeat(system.element_stiffness[None, :], S, axis=0)
    # rebuild the stack the state keeps: the same link and temperature factors (1 here)
    rebuilt = stacked_state(stacked.state, stacked.inertia_factors, np.ones(S),
                            np.full(S, 23.0))
    K = _stacked_stiffness(system.element_incidence, k)
    per_call = replace(rebuilt, split=None, stiffness=K)
    uncondensed = replace(rebuilt, split=None, massed=None, stiffness=K)
    added = np.linspace(0.0, 0.02, len(drive.sprockets))
    f1, margin = stacked_margins(rebuilt, added)
    for other in (per_call, uncondensed):
        g1, other_margin = stacked_margins(other, added)
        assert np.allclose(g1, f1, rtol=1e-9, atol=0.0)
        assert np.allclose(other_margin, margin, rtol=1e-9, atol=0.0)


def test_robust_batch_gives_each_design_its_own_path() -> None:
    """The worker function of a study of many designs (flywheel genes: one basis for all)
    reports for every vector what the design's own batched modal path gives: probability,
    interval and the 5 % quantiles of f₁ and of the margin."""
    data = tomllib.loads((EXAMPLES / "eight_sprocket.toml").read_text(encoding="utf-8"))
    data["optimize"] = {"objectives": ["cost"],
                        "inertia": {"D1": ["0 kg*m^2", "0.05 kg*m^2"],
                                    "D3": ["0 kg*m^2", "0.05 kg*m^2"]}}
    data["uncertainty"] = {"samples": 16, "replicates": 2, "wear": "new"}
    text = tomli_w.dumps(data)
    vectors = [[0.0, 0.05], [0.02, 0.0], [0.05, 0.01]]
    out = robust_batch({"problem": text, "vectors": vectors})["designs"]
    problem = problem_from_mapping(tomllib.loads(text))
    settings = uncertainty_settings(data["uncertainty"])
    for x, got in zip(vectors, out, strict=True):
        own = own_path(problem.decode(x), settings)
        c = own.checks[0]
        assert (got["resonance_probability"], got["ci_low"], got["ci_high"]) == (
            c.probability, c.low, c.high)
        assert got["f1_p05_hz"] == pytest.approx(own.quantile("f1_hz", 0.05), rel=1e-9)
        assert got["resonance_margin_p05_percent"] == pytest.approx(
            own.quantile("resonance_margin_percent", 0.05), rel=1e-9)
    assert len({round(d["f1_p05_hz"], 9) for d in out}) == 3   # the flywheels tell apart
