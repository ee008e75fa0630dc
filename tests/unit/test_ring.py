"""Unit tests of the ring model (chaindrive.dynamics.ring / stiffness / resonance)."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from chaindrive.catalog import find_material
from chaindrive.dynamics import (
    RingModel,
    campbell_data,
    coefficient_of_dynamics,
    modal_analysis,
    ring_frequencies_batch,
    ring_stiffness_matrix,
)
from chaindrive.dynamics.model.build import ring_model
from chaindrive.dynamics.parameters import drive_ring_parameters
from chaindrive.dynamics.stiffness import (
    link_stiffness,
    sag_stiffness_factor,
    series_stiffness,
    wrap_stiffness,
)
from chaindrive.errors import DesignError
from chaindrive.geometry.results import GeometryResult, SpanGeometry, SprocketGeometry
from chaindrive.geometry.sprocket import iso606_tooth_width
from chaindrive.model import Chain, ChainSpec, Drive, Sprocket


def _ring_modes(n: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    return rng.uniform(0.5, 20.0, n), rng.uniform(1e5, 1e8, n)


def test_stiffness_matrix_is_laplacian() -> None:
    K = ring_stiffness_matrix([1.0, 2.0, 3.0, 4.0])
    assert_allclose(K, K.T)
    assert_allclose(K.sum(axis=1), 0.0, atol=1e-12)
    assert np.linalg.eigvalsh(K).min() > -1e-12
    assert K[3, 0] == -4.0 and K[0, 0] == 5.0


def test_rigid_body_exact_zero_and_uniform() -> None:
    rng = np.random.default_rng(1)
    m, c = _ring_modes(12, rng)
    r = RingModel(m, c).modal()
    assert r.frequencies_hz[0] == 0.0 and r.rigid_body.tolist() == [True] + [False] * 11
    assert np.ptp(r.shapes[:, 0]) == 0.0  # exactly uniform
    assert np.all(np.diff(r.frequencies_hz) >= 0)
    assert_allclose(r.shapes.T @ np.diag(m) @ r.shapes, np.eye(12), atol=1e-9)
    assert_allclose(r.normalized_amplitudes.sum(axis=0), 1.0)
    assert_allclose(r.angular_frequencies_rad_s, 2 * np.pi * r.frequencies_hz)


def test_two_slack_spans_give_two_rigid_modes() -> None:
    r = RingModel([1.0, 2.0, 3.0, 4.0], [1e6, 0.0, 1e6, 0.0]).modal()
    assert r.rigid_body.sum() == 2
    assert r.frequencies_hz[:2].tolist() == [0.0, 0.0]
    # the two groups (1,2) and (3,4) vibrate independently: ω² = c(1/m_a + 1/m_b)
    expected = np.sqrt([1e6 * (1 + 1 / 2), 1e6 * (1 / 3 + 1 / 4)]) / (2 * np.pi)
    assert_allclose(np.sort(r.elastic_frequencies_hz), np.sort(expected), rtol=1e-12)


def test_partial_frequencies_and_damped() -> None:
    r = RingModel([2.0, 3.0, 4.0], [10.0, 20.0, 30.0], damping_ratio=0.06).modal()
    assert_allclose(r.partial_frequencies_hz * 2 * np.pi,
                    np.sqrt(np.array([40.0, 30.0, 50.0]) / [2.0, 3.0, 4.0]))
    assert_allclose(r.damped_frequencies_hz, r.frequencies_hz * math.sqrt(1 - 0.06**2))


def test_batch_matches_single() -> None:
    rng = np.random.default_rng(2)
    m = rng.uniform(0.5, 20, (50, 24))
    c = rng.uniform(1e5, 1e8, (50, 24))
    c[::5, 7] = 0.0
    for closed in (True, False):
        fb = ring_frequencies_batch(m, c, closed=closed)
        for b in (0, 5, 17, 49):
            assert_allclose(fb[b], modal_analysis(m[b], c[b], closed).frequencies_hz,
                            rtol=1e-9, atol=1e-9)
        assert np.all(fb[:, 0] == 0.0)
    assert_allclose(ring_frequencies_batch([[1.0, 1.0]], [[1.0, 1.0]])[0],
                    [0.0, 2.0 / (2 * np.pi)])


@pytest.mark.parametrize(("masses", "stiffness"), [
    ([1.0], [1.0]), ([1.0, 2.0], [1.0]), ([1.0, -2.0], [1.0, 1.0]),
    ([1.0, 2.0], [1.0, -1.0]), ([1.0, np.nan], [1.0, 1.0]),
])
def test_invalid_models_are_refused(masses: list[float], stiffness: list[float]) -> None:
    with pytest.raises(DesignError):
        RingModel(masses, stiffness)


def test_to_dict_is_json() -> None:
    r = RingModel([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], names=("a", "b", "c"))
    d = r.modal().to_dict()
    json.dumps(d)
    json.dumps(r.to_dict())
    assert len(d["mode_shapes"]) == 3 and len(d["mode_shapes"][0]) == 3
    assert d["natural_frequencies_hz"][0] == 0.0


# --- stiffness parts -----------------------------------------------------------------

def _spec(material: str = "steel") -> ChainSpec:
    # ISO 606 16B-1 dimensions (ISO 606:1994 via GOST 13568-97 Annex A)
    return ChainSpec("ISO 606 16B-1", "ISO 606", "B", 0.0254, 1, 0.01588, 0.00828, 0.01702,
                     0.02108, 0.03188, 60000.0, 2.8, material=material)


def test_link_stiffness_scales_with_modulus_and_strands() -> None:
    spec = _spec()
    k = link_stiffness(spec, 210e9)
    assert 1e8 < k < 2e9  # order of magnitude of steel roller chains of 25.4 mm pitch
    assert_allclose(link_stiffness(spec, 2.1e9), k / 100)
    assert_allclose(link_stiffness(replace(spec, strands=2), 210e9), 2 * k)


def test_wrap_and_series_and_sag() -> None:
    assert wrap_stiffness(1.0, 5.0, 1.5) == 1.0
    k_inf = 0.5 + math.sqrt(0.25 + 5.0)
    assert_allclose(wrap_stiffness(1.0, 5.0, 200), k_inf, rtol=1e-12)
    assert wrap_stiffness(1.0, 5.0, 2) == pytest.approx(1 + 5 / 6)
    # one ladder for a row of sprockets and a batch of states (the robust path): each
    # element is the scalar recursion with its own teeth in mesh
    kt, kl, mesh = np.array([[1.0, 2.0, 3.0]]), np.array([[5.0], [7.0]]), [1.5, 2, 200]
    batch = wrap_stiffness(kt, kl, mesh)
    assert batch.shape == (2, 3)
    for a in range(2):
        for b in range(3):
            assert batch[a, b] == wrap_stiffness(kt[0, b], kl[a, 0], mesh[b])
    assert_allclose(series_stiffness(2.0, 2.0, 1.0), 0.5)
    assert series_stiffness(2.0, 0.0) == 0.0
    # Dischinger-Ernst: taut span → 1, slack → ~0, T ≤ 0 → 0
    s = sag_stiffness_factor(1.2e7, 25.0, 1.0, np.array([1e5, 50.0, 0.0]))
    assert s[0] == pytest.approx(1.0, abs=1e-6) and s[1] < 0.01 and s[2] == 0.0


# --- a 3-sprocket drive with a fake geometry ---------------------------------------

def fake_geometry(drive: Drive) -> GeometryResult:
    """A GeometryResult of a convex contour, all sprockets outside; span lengths taken as
    the centre distances and teeth in mesh as z·(wrap/2π) with wraps summing to 2π
    (an approximation good enough for the stiffness model)."""
    p = drive.chain.pitch
    xy = np.array([(s.x, s.y) for s in drive.sprockets])
    n = len(xy)
    z = np.array([s.teeth for s in drive.sprockets])
    R = p / (2 * np.sin(np.pi / z))
    d = np.roll(xy, -1, axis=0) - xy
    lengths = np.hypot(d[:, 0], d[:, 1])
    wraps = np.pi - np.array([np.arccos(np.clip(np.dot(-d[i - 1], d[i])
                                                / (lengths[i - 1] * lengths[i]), -1, 1))
                              for i in range(n)])
    sprockets = tuple(SprocketGeometry(
        s.name, s.teeth, "outside", s.x, s.y, R[i], 2 * R[i], 2 * R[i] + 0.6 * p,
        2 * R[i] - 0.6 * p, wraps[i], s.teeth * wraps[i] / (2 * np.pi), 1, (s.x, s.y),
        (s.x, s.y)) for i, s in enumerate(drive.sprockets))
    d_idx = drive.driver_index
    spans = tuple(SpanGeometry(
        i, i, (i + 1) % n, drive.sprockets[i].name, drive.sprockets[(i + 1) % n].name,
        lengths[i], lengths[i] / p, tuple(d[i] / lengths[i]), tuple(xy[i]),
        tuple(xy[(i + 1) % n]), math.atan(d[i][1] / d[i][0]) if d[i][0] else math.pi / 2,
        (i + 1) % n == d_idx) for i in range(n))
    return GeometryResult(p, sprockets, spans, 128.0, 128, 128 * p, 128 * p, 0.0, None,
                          None, 0.0, 1)


SEED_MASSES = (17.26, 28.44, 2.0)  # seed 000's reduced masses [kg] (seed-notes §3)


def seed_drive(chain_material: str = "steel", sprocket_material: str = "steel",
               power: float | None = 500.0, seed_masses: bool = False) -> Drive:
    """Seed 000's 3-sprocket example layout (seed-notes §3), 25.4 mm chain, 300 rpm driver;
    sprocket 3 moved up to make a clearly convex contour. ``seed_masses``: inertias
    I = m R² from the seed's reduced masses (the same masses for every material pair)."""
    spec = replace(_spec(chain_material), designation="ПР-25,4-60 (16B dims)")
    teeth = (15, 25, 14)
    inertia = [m * (0.0254 / (2 * math.sin(math.pi / z))) ** 2 if seed_masses else None
               for m, z in zip(SEED_MASSES, teeth, strict=True)]
    sprockets = (
        Sprocket("1", 15, 1.364, 0.0, role="driver", speed=300 * math.pi / 30,
                 material=sprocket_material, inertia=inertia[0]),
        Sprocket("2", 25, 0.0, 0.0, material=sprocket_material, inertia=inertia[1]),
        Sprocket("3", 14, 0.682, 0.06067 + 0.4, material=sprocket_material,
                 inertia=inertia[2]),
    )
    return Drive("seed 3-sprocket", Chain(spec), sprockets, power=power)


def _first(chain: str, sprocket: str, power: float | None = None) -> float:
    drive = seed_drive(chain, sprocket, power, seed_masses=True)
    model = ring_model(drive, fake_geometry(drive), material_lookup=find_material)
    return model.modal().first_elastic_frequency_hz


def test_seed_table1_trend() -> None:
    # Seed 000 Table 1 (seed-notes §1): polymer chain ≈ 4× lower first frequency
    # (612.4 → 155.0 rad/s); polymer sprockets about 10 % lower (612.4 → 548.0).
    # Same masses for all pairs (the seed's), closed ring of taut spans.
    steel = _first("steel", "steel")
    polymer_chain = _first("PA6-GF30", "steel")
    polymer_sprockets = _first("steel", "PA6-GF30")
    both = _first("PA6-GF30", "PA6-GF30")
    assert 3.0 <= steel / polymer_chain <= 5.0
    assert 0.05 <= 1 - polymer_sprockets / steel <= 0.15
    # Table 1: polymer chain on polymer sprockets differs little from polymer chain (0.8 %)
    assert 0.0 < 1 - both / polymer_chain < 0.05


def test_table1_trend_loaded_open_chain() -> None:
    # Loaded (8 kW): the slack span sags out and the ring opens; the tight spans are
    # short (0.82 m), so the tooth compliance weighs more than in the seed's Table 1.
    steel = _first("steel", "steel", 8000.0)
    polymer_chain = _first("PA6-GF30", "steel", 8000.0)
    polymer_sprockets = _first("steel", "PA6-GF30", 8000.0)
    assert 3.0 <= steel / polymer_chain <= 5.0
    assert 0.05 <= 1 - polymer_sprockets / steel <= 0.20


def test_from_drive_masses_and_slack_span() -> None:
    drive = seed_drive(power=8000.0)
    geom = fake_geometry(drive)
    model = ring_model(drive, geom, material_lookup=find_material)
    # steel plate disc of the pitch diameter minus the bore, thickness bf1 (ISO 606), its
    # inertia I = m (D² + d0²)/8 reduced to the pitch radius: m_red = I / R²
    spec = drive.chain.spec
    z = drive.sprockets[0].teeth
    D = geom.sprockets[0].pitch_diameter
    d0 = 0.19 * spec.pitch * z / np.pi
    bf1 = iso606_tooth_width(spec.pitch, spec.inner_width, 1)
    mass = 7850 * bf1 * np.pi * (D**2 - d0**2) / 4
    assert_allclose(model.masses_kg[0], mass * (D**2 + d0**2) / 8 / (D / 2) ** 2, rtol=1e-12)
    # with power, only the tight span is taut; the span leaving the driver sags
    params = drive_ring_parameters(drive, geom, material_lookup=find_material)
    assert_allclose(params.stiffness_n_per_m, model.stiffness_n_per_m)
    tight = next(s.index for s in geom.spans if s.tight)
    sag = params.sag_factors
    assert sag[tight] > 0.9 and sag[1] > 0.9 and sag[0] < 0.05
    # tension balance: slack spans carry F_0 + q v², the tight one adds F_t = P/v
    v = 15 * 0.0254 * drive.driver.speed / (2 * np.pi)
    t = params.span_tensions_n
    assert t[tight] - t[0] == pytest.approx(8000 / v + 0.0 * v, rel=0.05)
    # a given inertia overrides the disc
    s0 = replace(drive.sprockets[0], inertia=0.5)
    d2 = drive.with_sprockets((s0, *drive.sprockets[1:]))
    m2 = ring_model(d2, geom, material_lookup=find_material)
    assert_allclose(m2.masses_kg[0], 0.5 / geom.sprockets[0].pitch_radius ** 2)



def test_campbell_crossing_speed() -> None:
    # one mode at 100 Hz; tooth line z1·ω/2π with z1 = 20 crosses it at ω = 2π·100/20
    modal = RingModel([1.0, 1.0], [0.5 * (2 * np.pi * 100) ** 2 / 2] * 2).modal()
    assert_allclose(modal.elastic_frequencies_hz, [100.0])
    cd = campbell_data(modal, np.linspace(10, 100, 37), 20, [20, 40], harmonics=1)
    tooth = [s for e, _, s in cd.crossings if e == "tooth x1"]
    assert_allclose(tooth, [2 * np.pi * 100 / 20 * 60 / (2 * np.pi)], rtol=1e-9)


def test_coefficient_of_dynamics_seed_example() -> None:
    # seed-notes §1: seed 000's 3-sprocket example, "dynamic loading 44.75" at
    # F_t = 60 P/(π D n) with P = 500 W, D = t z/π = 121.3 mm, n = 300 rpm → K_D ≈ 1.17 (printed 1.18)
    f_t = 60 * 500 / (np.pi * 0.0254 * 15 / np.pi * 300)
    assert coefficient_of_dynamics([44.75], f_t) == pytest.approx(1.17, abs=0.005)
    assert coefficient_of_dynamics([3.0, -4.0], 10.0) == pytest.approx(1 + math.sqrt(12.5) / 10)
    with pytest.raises(DesignError):
        coefficient_of_dynamics([], 1.0)


@pytest.mark.parametrize("cut", [None, 23, 5])
def test_tridiagonal_and_dense_solvers_agree(cut: int | None,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    # the two LAPACK paths of modal_analysis (dstevd on the tridiagonal form of an opened
    # ring when SciPy is loaded, NumPy's dense eigh otherwise) give the same frequencies and
    # M-orthonormal shapes, and both satisfy K X = M X Ω² (seed 000 eq. 2) to round-off
    import scipy.linalg  # noqa: F401 - loads the dstevd path

    import chaindrive.dynamics.ring as ring

    rng = np.random.default_rng(7)
    m = rng.uniform(0.5, 20.0, 24)
    c = rng.uniform(1e5, 1e8, 24)
    if cut is not None:
        c[cut] = 0.0
    fast = modal_analysis(m, c)
    monkeypatch.setattr(ring, "_scipy_lapack", lambda: None)
    dense = modal_analysis(m, c)
    assert_allclose(fast.frequencies_hz, dense.frequencies_hz, rtol=1e-10,
                    atol=1e-10 * dense.frequencies_hz.max())
    K = ring_stiffness_matrix(c)
    for r in (fast, dense):
        X, w2 = r.shapes, r.angular_frequencies_rad_s**2
        assert_allclose(X.T @ (m[:, None] * X), np.eye(24), atol=1e-10)
        assert_allclose(K @ X, m[:, None] * X * w2, atol=1e-8 * np.abs(K).max() * np.abs(X).max())
