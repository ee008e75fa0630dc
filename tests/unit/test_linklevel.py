"""Unit tests of the link-level model's parts (chaindrive.linklevel): the implicit damper
solve, the roller–gap penetration, the assembly, inputs, outputs and the plotting."""

from __future__ import annotations

import importlib
import math
import pickle

import numpy as np
import pytest

from chaindrive.dynamics.motors import ConstantTorque
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import TorsionalAttachment, build_model, simulate
from chaindrive.linklevel.assembly import assemble_chain, sagging_polygon
from chaindrive.linklevel.kernel import (
    _gap_local,
    _hinge_solve,
    _velocity_update,
    penetration,
)
from tests.conftest import EXAMPLES

# the module (the package's ``simulate`` is the function of the same name)
simulate_module = importlib.import_module("chaindrive.linklevel.simulate")


@pytest.fixture(scope="module")
def jindal():
    drive = load_drive(EXAMPLES / "two_sprocket_jindal.toml")
    return drive, contour_geometry(drive)


@pytest.fixture(scope="module")
def solved_once():
    """The static state of :func:`simulate` solved once per model for this module's runs.

    Every run that takes this fixture simulates the Jindal drive with the default model, so
    its static state (:func:`chaindrive.linklevel.simulate.equilibrium_state`, about 8 s of
    CPU each time; a pure function of its inputs, which the run copies before stepping) is
    the same: it is solved on the first run and handed back to the others, keyed on the
    drive, the pickled model and the take-up. The tests read the inputs' checks, the
    output keys and the figures, none of which depends on solving it again."""
    solve = simulate_module.equilibrium_state
    states: dict[tuple[int, bytes, str | None], object] = {}

    def once(drive, geometry, model, dt, take_up):
        key = (id(drive), pickle.dumps(model), take_up)
        if key not in states:
            states[key] = solve(drive, geometry, model, dt, take_up)
        return states[key]

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(simulate_module, "equilibrium_state", once)
        yield


@pytest.fixture(scope="module")
def steady_run(jindal, solved_once):
    """One 5 ms run from working speed: its outputs and its figures (frames up to 4 ms)."""
    drive, geometry = jindal
    return simulate(drive, 0.005, geometry=geometry, start="steady")


def test_implicit_damper_solves_backward_euler_exactly():
    """The cyclic tridiagonal solve equals the dense backward-Euler step
    (I + h_c AᵀA) v′ = v + h f, A the links' axial-rate operator (closed form)."""
    rng = np.random.default_rng(3)
    for n in (3, 4, 9, 10):
        _check_damper_solve(rng, n)


def test_implicit_damper_solve_holds_for_long_heavily_damped_chains():
    """A long chain of heavily damped links (h_c = 50, the seed's is about 19; 80 and 401
    links, the elimination from both ends meeting after 40 and 200 rows) against the dense
    backward-Euler step (closed form)."""
    rng = np.random.default_rng(5)
    for n in (80, 401):
        _check_damper_solve(rng, n, hc=50.0, tol=1e-11)


def _check_damper_solve(rng: np.random.Generator, n: int, hc: float = 1.7,
                        tol: float = 1e-13) -> None:
    v, f = rng.normal(size=(n, 2)), rng.normal(size=(n, 2))
    angle = rng.uniform(0.0, 2 * math.pi, n)
    ux, uy = np.cos(angle), np.sin(angle)
    h = 0.2
    out, g = v.copy(), np.zeros(n)
    _velocity_update(out, f, h, hc, ux, uy, g, np.empty(n), np.empty(n), np.empty(n),
                     np.empty(n))
    A = np.zeros((n, 2 * n))
    for i in range(n):
        b = (i + 1) % n
        A[i, 2 * b:2 * b + 2] += (ux[i], uy[i])
        A[i, 2 * i:2 * i + 2] -= (ux[i], uy[i])
    dense = np.linalg.solve(np.eye(2 * n) + hc * A.T @ A, (v + h * f).ravel())
    np.testing.assert_allclose(out.ravel(), dense, atol=tol)
    np.testing.assert_allclose(g, A @ dense, atol=tol)


def test_implicit_hinge_friction_solves_backward_euler_exactly():
    """The cyclic pentadiagonal solve of the viscous hinges equals the dense backward-Euler
    step (I + h Gᵀ C G) v′ = v + h f, G = D W the hinges' relative-rate operator (W the
    links' angular rates q_i n_i·(v_{i+1} − v_i), D the cyclic difference), C the viscous
    coefficients (0 at the sliding hinges, whose explicit moments are in f); and the power
    it returns is −Σ M_r ω′_rel,r of the explicit and implicit moments at the new rates
    (closed forms). From 5 links (the smallest the cyclic border allows) to 401."""
    for n, frac in ((5, 0.6), (6, 0.6), (7, 1.0), (12, 0.6), (128, 0.6), (401, 0.6),
                    (50, 0.0)):
        _check_hinge_solve(np.random.default_rng(n), n, frac)


def _check_hinge_solve(rng: np.random.Generator, n: int, frac: float) -> None:
    v, f = rng.normal(size=(n, 2)), rng.normal(size=(n, 2))
    angle = np.cumsum(rng.normal(0.0, 0.4, n))
    ux, uy = np.cos(angle), np.sin(angle)
    invl = 1.0 / rng.uniform(0.8, 1.2, n)
    cv = np.where(rng.uniform(size=n) < frac, 3.0, 0.0)
    M = np.where(cv > 0.0, 0.0, rng.normal(size=n))
    h = 0.7
    W = np.zeros((n, 2 * n))
    for i in range(n):
        b = (i + 1) % n
        W[i, 2 * b:2 * b + 2] += invl[i] * np.array([-uy[i], ux[i]])
        W[i, 2 * i:2 * i + 2] -= invl[i] * np.array([-uy[i], ux[i]])
    D = np.eye(n) - np.roll(np.eye(n), -1, axis=1)  # (D ω)_r = ω_r − ω_{r−1}
    G = D @ W
    with_moments = f + (G.T @ M).reshape(n, 2)
    dense = np.linalg.solve(np.eye(2 * n) + h * G.T @ np.diag(cv) @ G,
                            (v + h * with_moments).ravel())
    out = with_moments.copy()
    power = _hinge_solve(v, out, h, ux, uy, invl, M, cv, int(np.sum(cv > 0.0)),
                         np.zeros((14, n)))
    np.testing.assert_allclose((v + h * out).ravel(), dense, atol=1e-12)
    wrel = G @ dense
    assert power == pytest.approx(-np.sum((M - cv * wrel) * wrel), rel=1e-12, abs=1e-12)


def test_penetration_of_a_roller_in_its_gap():
    """Closed forms of the gap (seating arc r_i about the gap centre, tangent flanks, tip
    circle R_a): a roller centred in the gap has δ = r − r_i < 0; one moved along the
    seating normal by d has δ = d + r − r_i; one pushed into the flank beyond the arc has
    δ equal to its distance past the flank line; the two kernels agree."""
    z, R, rr, ri, alpha, Ra = 15, 0.0611, 0.00794, 0.00803, math.radians(51.0), 0.0665
    th = 0.3
    centre = R * np.array([math.cos(th), math.sin(th)])
    d, nx, ny, j = penetration(*centre, th, z, R, rr, ri, alpha, Ra)
    assert j == 0 and d == pytest.approx(rr - ri)
    inward = -centre / R
    p = centre + 0.0002 * inward
    d, nx, ny, _ = penetration(*p, th, z, R, rr, ri, alpha, Ra)
    assert d == pytest.approx(0.0002 + rr - ri)
    assert (nx, ny) == pytest.approx(tuple(-inward))
    gx, gy = math.cos(th), math.sin(th)
    same = _gap_local(*p, gx, gy, R, rr, ri, math.cos(alpha), math.sin(alpha),
                      math.tan(alpha), Ra)
    assert same == pytest.approx((d, nx, ny))
    # beyond the arc's end at +α: δ grows as the distance past the tangent line
    tangent = np.array([-gy, gx])
    flank_normal = math.cos(alpha) * inward + math.sin(alpha) * tangent
    end = centre + ri * flank_normal
    along = np.array([-flank_normal[1], flank_normal[0]])  # along the flank line
    if along @ centre < 0:  # the flank runs outwards from the arc's end
        along = -along
    q = end - rr * flank_normal + 0.0001 * flank_normal + 0.001 * along
    d, *_ = penetration(*q, th, z, R, rr, ri, alpha, Ra)
    assert d == pytest.approx(0.0001, abs=1e-9)


def test_penetration_at_the_tooth_tip_corner():
    """A roller beyond the corner where the flank meets the tip circle touches the corner
    point, not the flank line extended past the tooth: δ = r − |p − C| (closed form), with
    the normal from C through the centre; a roller 1 mm clear of the corner is clear of the
    tooth (the extended flank line would press it), and the two kernels agree."""
    z, R, rr, ri, alpha, Ra = 15, 0.0611, 0.00794, 0.00803, math.radians(51.0), 0.0665
    th = 0.3
    g = np.array([math.cos(th), math.sin(th)])
    t = np.array([-g[1], g[0]])
    f = -math.cos(alpha) * g + math.sin(alpha) * t  # flank normal into the tooth (+α side)
    u = np.array([f[1], -f[0]])  # along the flank, outwards
    assert u @ g > 0
    p_alpha = R * g + ri * f
    b, c = p_alpha @ u, p_alpha @ p_alpha - Ra * Ra
    corner = p_alpha + (-b + math.sqrt(b * b - c)) * u
    assert np.hypot(*corner) == pytest.approx(Ra)
    outward = -f + corner / Ra  # between the flank's and the tip's outward normals
    outward /= np.hypot(*outward)
    for clearance in (-2e-6, 1e-3):  # 2 µm into the corner; 1 mm clear of it
        p = corner + (rr + clearance) * outward
        d, nx, ny, _ = penetration(*p, th, z, R, rr, ri, alpha, Ra)
        assert d == pytest.approx(-clearance, abs=1e-12)
        assert (nx, ny) == pytest.approx(tuple(outward))
        gx, gy = math.cos(th), math.sin(th)
        same = _gap_local(*p, gx, gy, R, rr, ri, math.cos(alpha), math.sin(alpha),
                          math.tan(alpha), Ra)
        assert same == pytest.approx((d, nx, ny))
        # the flank line extended past the corner would have put the roller into the tooth
        assert (p - p_alpha) @ f + rr > 0


def test_assembly_seats_rollers_one_pitch_apart(jindal):
    """Every link of the assembled chain is one pitch long but those of the closing span
    (misfit shared, µm), and the rollers on each wrap sit on gap centres."""
    drive, geometry = jindal
    asm = assemble_chain(geometry, drive.driver_index)
    p = geometry.pitch
    lengths = np.hypot(*(np.roll(asm.positions, -1, axis=0) - asm.positions).T)
    assert np.all(np.abs(lengths - p) < 1e-4 * p)
    assert np.sum(np.abs(lengths - p) > 1e-9) <= geometry.spans[0].pitches + 2
    for i, g in enumerate(geometry.sprockets):
        on = asm.sprocket_of == i
        rel = asm.positions[on] - (g.x, g.y)
        phase = np.mod(np.arctan2(rel[:, 1], rel[:, 0]) - asm.angles[i], 2 * math.pi / g.teeth)
        phase = np.minimum(phase, 2 * math.pi / g.teeth - phase)
        assert on.sum() >= math.floor(g.teeth_in_mesh) - 1
        assert np.all(phase < 1e-9)
        assert np.allclose(np.hypot(rel[:, 0], rel[:, 1]), g.pitch_radius)


def test_sagging_polygon_has_equal_chords_and_sags_down():
    """count chords of length p between two points closer than count·p, bowing to −y."""
    a, b = np.array([0.0, 0.0]), np.array([1.0, 0.0])
    pts = sagging_polygon(a, b, 40, 0.0254)
    chords = np.hypot(*np.diff(pts, axis=0).T)
    np.testing.assert_allclose(chords, 0.0254, rtol=1e-12)
    np.testing.assert_allclose(pts[-1], b, atol=1e-12)
    assert pts[:, 1].min() < -0.01


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"duration_s": 0.0}, "duration_s"),
    ({"start": "running"}, "start"),
    ({"kick_rad_s": [1.0]}, "kick_rad_s"),
    ({"motor": lambda t, w: 1.0}, "motor"),
    ({"resistance": "cubic"}, "resistance"),
])
def test_bad_input_names_its_field(jindal, solved_once, kwargs, field):
    drive, geometry = jindal
    run = {"duration_s": 0.001, "geometry": geometry} | kwargs
    with pytest.raises(DesignError) as err:
        simulate(drive, **run)
    assert err.value.field == field


def test_result_dict_and_history(jindal, steady_run):
    """Outputs carry their unit in the key; the history is a (times × columns) table."""
    _, geometry = jindal
    r = steady_run
    out = r.to_dict(include_history=True)
    for key in ("span_dynamic_load_n", "peak_span_force_n", "time_step_s", "nominal_force_n",
                "energy_residual_j", "closing_misfit_m"):
        assert key in out
    names, table = r.history()
    assert names[0] == "time_s" and table.shape == (len(r.times), len(names))
    assert all(n.endswith(("_s", "_n", "_m", "_rad_s")) for n in names)
    assert r.link_tensions.shape == (len(r.times), geometry.links)
    assert np.all(np.isfinite(r.positions))


def test_attached_torsional_system_keeps_the_energy_balance(jindal):
    """A load inertia on a shaft spring behind the driven sprocket (a torsional train)
    carrying the driven sprocket's moment of resistance: the work of the motor and the load
    equals the change of stored energy plus the dissipation (closed form energy balance) to
    1 % of the motor's work, and the train turns with the sprocket."""
    drive, geometry = jindal
    k, c = 2.0e3, 0.5
    K = np.array([[0, 0, 0], [0, k, -k], [0, -k, k]], dtype=float)
    C = np.array([[0, 0, 0], [0, c, -c], [0, -c, c]], dtype=float)
    train = TorsionalAttachment(np.array([5e-3]), K, C, load_dofs=(0, 2))
    model = build_model(drive, geometry, torsional=train)
    r = simulate(drive, 0.05, geometry=geometry, model=model, motor=ConstantTorque(25.0),
                 resistance="linear")
    assert abs(r.energy_residual_j) < 0.01 * r.energy["motor_work_j"]
    assert r.energy["resistance_work_j"] < 0 and r.energy["torsional_damping_j"] > 0
    assert r.speeds[-1, 2] * model.turn[1] > 0.5 * r.sprocket_speeds[-1, 1] > 0


def test_plotting_draws_frames_and_tooth_loads(steady_run):
    from chaindrive.plotting.linklevel import chain_frame, chain_frames, tooth_loads

    r = steady_run
    assert chain_frame(r, magnify=10).axes
    assert len(chain_frames(r, [0.0, 0.002, 0.004], columns=2).axes) >= 3
    assert tooth_loads(r).axes[0].get_lines()


def test_link_damping_is_the_analysis_damping() -> None:
    # one damping selector: the links' c = 2ζ k_link/ω_ref with ζ (the mean of the spans'
    # ratios) and ω_ref of the whole-drive model the analysis builds (seed: ζ 0.0633 of the
    # steel pair with its polymer-free sprockets, f_ref 73.06 Hz; not the ring's 0.0688 and
    # 52.7 Hz)
    from chaindrive.analysis import analyze

    a = analyze(load_drive(EXAMPLES / "seed_three_sprocket.toml"))
    dm = a.drive_model
    model = build_model(a.drive, a.geometry)
    assert model.reference_frequency_hz == pytest.approx(dm.reference_frequency_hz, rel=1e-12)
    assert model.reference_frequency_hz == pytest.approx(
        a.dynamics.modal.first_elastic_frequency_hz, rel=1e-9)  # a chain mode on the seed
    zeta = float(np.mean(dm.span_damping_ratios))
    assert model.link_damping == pytest.approx(
        2 * zeta * model.link_stiffness / (2 * np.pi * dm.reference_frequency_hz), rel=1e-12)


def test_hinge_friction_is_implicit_exactly_above_its_explicit_stability_limit(jindal):
    """The regularised hinge friction's viscous coefficient c_max = m p²/(8Δt_e) puts the
    explicit law's zigzag mode (λ_max = 16/p², forward Euler: Δt·c_max·λ_max/m ≤ 2) at
    its stability limit exactly at the explicit step Δt_e (closed form): the kernel takes it
    explicitly there and below, implicitly above (docs/linklevel.md §2)."""
    from chaindrive.linklevel.simulate import default_step, hinge_implicit, hinge_regularisation

    drive, geometry = jindal
    model = build_model(drive, geometry)
    dte = default_step(model, False)
    cmax = hinge_regularisation(model)
    assert dte * cmax * 16.0 / (model.roller_mass * model.pitch**2) == pytest.approx(2.0)
    assert not hinge_implicit(model, dte)
    assert not hinge_implicit(model, 0.5 * dte)
    assert hinge_implicit(model, 1.01 * dte)


def test_implicit_hinge_friction_keeps_the_energy_balance_at_twice_the_step():
    """The seed at working speed and power over 0.1 s at twice the explicit step Δt_e,
    where the explicit hinge friction's zigzag mode is unstable: with the viscous hinges
    implicit the energy balance closes to 10⁻³ (measured 9·10⁻⁵; the explicit law gave
    6.3·10⁻³) and K_D stays within 2 % of the run at Δt_e (measured 0.9 %; explicit 4.0 %)
    — the energy balance of docs/linklevel.md §5.4 and the step rule of §2."""
    from chaindrive.linklevel.simulate import default_step

    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    geometry = contour_geometry(drive)
    model = build_model(drive, geometry)
    dte = default_step(model, False)
    kw = {"geometry": geometry, "model": model, "initial_speed": "working"}
    ref = simulate(drive, 0.1, dt_s=dte, **kw)
    big = simulate(drive, 0.1, dt_s=2.0 * dte, **kw)
    assert abs(big.energy["drift_fraction"]) < 1e-3
    assert big.coefficient_of_dynamics == pytest.approx(ref.coefficient_of_dynamics, rel=0.02)
