"""The link-level model's static state at the installed pre-tension, its energy balance and
its step convergence (chaindrive.linklevel.equilibrium, docs/linklevel.md §2, §4).

Tolerances: on a free sprocket the chain's tension passes from one span to the next on the
arm of its polygon, between R cos(π/z) and R, so the spans of the polygonal chain may differ
by up to 1/cos(π/z) − 1 per sprocket passed from the continuous chain's equal tensions —
the bound the span tensions are held to; the reference span carries T₀ to the solver's
tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import installed_geometry, kernel_tables, span_probes
from chaindrive.linklevel.kernel import static_forces
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def seed():
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    return drive, contour_geometry(drive)


def _chordal_bound(teeth: np.ndarray) -> float:
    """Σ (1/cos(π/z) − 1) over the sprockets [-] (module docstring)."""
    return float(np.sum(1.0 / np.cos(np.pi / teeth) - 1.0))


def _reference(drive, geometry) -> int:
    return next(k for k, s in enumerate(geometry.spans) if s.start == drive.driver_index)


@pytest.fixture(scope="module")
def weightless(seed):
    """The seed drive without gravity, at rest, no motor, 50 ms."""
    drive, geometry = seed
    model = build_model(drive, geometry, gravity=0.0)
    return simulate(drive, 0.05, geometry=geometry, model=model, motor=False,
                    initial_speed="rest")


def test_installed_contour_takes_up_the_untaken_slack(seed):
    """The seed contour leaves 12 mm of chain slack with fixed centres; installed at the
    installed sag its slack is the sag's ΔL = (8/3)s²ℓ of the slack span (the take-up of
    chaindrive.geometry.contour)."""
    drive, geometry = seed
    installed, moved = installed_geometry(drive, geometry)
    assert geometry.slack > 0.01 and moved is not None
    slack = next(s for s in installed.spans if s.start == drive.driver_index)
    assert installed.slack == pytest.approx(8.0 / 3.0 * 0.02**2 * slack.length, rel=0.05)


def test_static_state_without_gravity_holds_the_pretension(seed, weightless):
    """No gravity: every span at T₀ (the whole-drive model's start-up pre-tension) within
    the chordal bound, the reference span to 10⁻⁴; the rollers seated (every roller on a
    wrap touches its tooth); after 50 ms at rest with no motor every span still within 1 %
    of its start."""
    drive, _geometry = seed
    r = weightless
    eq = r.equilibrium
    t0 = r.model.pretension
    tensions = np.asarray(eq["span_tension_n"])
    assert tensions[_reference(drive, r.geometry)] == pytest.approx(t0, rel=1e-4)
    np.testing.assert_allclose(tensions, t0, rtol=_chordal_bound(r.model.teeth))
    np.testing.assert_allclose(r.span_forces[0], tensions, rtol=1e-6)
    np.testing.assert_allclose(r.span_forces[-1], r.span_forces[0], rtol=0.01)
    assert eq["residual_force_n"] < 1e-4 * t0
    # seated: the rollers on the wraps (inside a pitch circle) touch their teeth at t = 0,
    # all but the two at each wrap's ends that the spans lift
    dist = np.hypot(*(r.positions[0][:, None, :] - r.model.centres[None]).transpose(2, 0, 1))
    for s in range(r.model.centres.shape[0]):
        on = dist[:, s] < r.model.pitch_radii[s]
        assert on.sum() >= 1
        assert np.sum(r.contact_forces[0][on] <= 0) <= 2
    inside = dist < r.model.pitch_radii[None, :]
    assert np.mean(r.contact_forces[0][inside.any(axis=1)] > 0) > 0.8


def test_static_state_with_gravity_is_the_hanging_chain(seed):
    """With gravity the tension along a chain over freely turning wheels is hydrostatic,
    T = T₀ + q g (y − y_ref) [Irvine1981, ch. 1]: every span's middle link against that
    closed form within the chordal bound; the state barely moves over 50 ms at rest (2 %;
    measured 1.1 %: the driver, held in the solve, takes a torque the run no longer applies,
    ``driver_holding_torque_n_m``, 0.34 N·m here, under which the chain's weight starts to
    turn the drive)."""
    drive, geometry = seed
    r = simulate(drive, 0.05, geometry=geometry, motor=False, initial_speed="rest")
    eq = r.equilibrium
    x = r.positions[0]
    probes = span_probes(r.geometry, x)
    mids = 0.5 * (x + np.roll(x, -1, axis=0))[probes]
    ref = _reference(drive, r.geometry)
    q_g = r.model.roller_mass / r.model.pitch * 9.80665
    closed = r.model.pretension + q_g * (mids[:, 1] - mids[ref, 1])
    tensions = np.asarray(eq["span_tension_n"])
    assert tensions[ref] == pytest.approx(r.model.pretension, rel=1e-3)
    np.testing.assert_allclose(tensions, closed, rtol=_chordal_bound(r.model.teeth))
    np.testing.assert_allclose(r.span_forces[-1], r.span_forces[0], rtol=0.02)


def test_static_state_is_a_solution_of_the_balance(seed, weightless):
    """The state the run starts from balances every roller (the kernel's own forces at rest:
    gravity, links, contacts) to 10⁻⁶ T₀."""
    r = weightless
    m = r.model
    t = kernel_tables(m)
    x = np.ascontiguousarray(r.positions[0])
    th = np.ascontiguousarray(r.angles[0, :m.centres.shape[0]])
    N, n = x.shape[0], m.centres.shape[0]
    f, tq, T, tr = np.empty((N, 2)), np.empty(n), np.empty(N), np.empty(N)
    static_forces(x, th, np.full(N, r.equilibrium["rest_length_m"]), m.link_stiffness,
                  m.clearance, m.roller_mass, 0.0, 0.0, t.spr, t.trig, t.gtab, t.reach,
                  f, tq, T, tr)
    assert np.abs(f).max() < 1e-6 * m.pretension + 1e-9
    # the links keep the chain's pitch: ℓ₀ within 0.1 % of p − T₀/k
    assert r.equilibrium["rest_length_m"] == pytest.approx(
        m.pitch - m.pretension / m.link_stiffness, rel=1e-3)


def test_undamped_coasting_conserves_energy(seed):
    """No dampers, no friction, no motor, no loads, every body at its working speed: the
    energy is constant (closed form ΔE = 0); the integrator's drift over 0.2 s within 0.5 %
    of the kinetic energy (measured on the seed: +0.27 % over 1 s at the default step,
    −0.014 % at half of it, docs/linklevel.md §4)."""
    drive, geometry = seed
    r = simulate(drive, 0.2, geometry=geometry, motor=False, damping=False,
                 initial_speed="working")
    e = r.energy
    assert e["link_damping_j"] == e["contact_damping_j"] == e["hinge_friction_j"] == 0.0
    assert e["motor_work_j"] == e["resistance_work_j"] == 0.0
    assert e["start_kinetic_j"] > 10.0
    assert abs(e["drift_fraction"]) < 0.005
    out = r.to_dict()
    assert out["energy_drift_fraction"] == e["drift_fraction"]
    assert out["step_convergence"]["checked"] is False  # not asked: said so, not passed


def test_halving_the_step_moves_the_reported_loads_less_than_two_percent(seed):
    """Step convergence (Richardson's principle): the seed at working speed and power over
    0.1 s, run again at Δt/2 — K_D, the span dynamic loads, peaks and means within 2 %."""
    drive, geometry = seed
    r = simulate(drive, 0.1, geometry=geometry, initial_speed="working", check_step=True)
    c = r.convergence
    assert c["half_step_s"] == pytest.approx(0.5 * r.dt)
    for key in ("coefficient_of_dynamics_change", "span_dynamic_load_change",
                "peak_span_force_change", "span_mean_force_change"):
        assert c[key] < 0.02, key
    assert c["converged"] is True
    assert r.to_dict()["step_convergence"]["converged"] is True


def test_implicit_link_springs_run_stably_beyond_the_explicit_limit(seed):
    """Link springs implicit (θ = 1/4, [HughesLiu1978]): for a linear spring Newmark's
    β = 1/4 is unconditionally stable and conserves energy, so at 1.5× the explicit
    stability limit 2/ω_max (the explicit run's energy grows without bound there) the
    undamped coasting seed keeps its energy to 1 % over 0.1 s; the default implicit step
    resolves the contact (ω_c Δt = 0.5) up to twice the explicit step (docs/linklevel.md §2)."""
    from chaindrive.linklevel.simulate import COURANT, default_step

    drive, geometry = seed
    model = build_model(drive, geometry)
    explicit = default_step(model, False)
    assert explicit == pytest.approx(COURANT * 2 / (2 * math.pi * model.highest_frequency_hz))
    implicit = default_step(model, True)
    resolved = 0.5 / (2 * math.pi * model.contact_frequency_hz)
    assert implicit == pytest.approx(max(explicit, min(resolved, 2 * explicit)))
    assert implicit < COURANT * 2 / (2 * math.pi * model.contact_frequency_hz)  # stable
    dt = 1.5 * explicit / COURANT  # 1.5× the explicit limit 2/ω_max
    kw = {"geometry": geometry, "motor": False, "damping": False, "initial_speed": "working",
          "dt_s": dt}
    r = simulate(drive, 0.1, implicit_links=True, **kw)
    assert r.energy["start_kinetic_j"] > 10.0
    assert abs(r.energy["drift_fraction"]) < 0.01
    with np.errstate(all="ignore"):
        x = simulate(drive, 0.02, implicit_links=False, **kw)
    drift = x.energy["drift_fraction"]
    assert not np.isfinite(drift) or abs(drift) > 1.0


def test_bad_initial_speed_names_its_field(seed):
    from chaindrive.errors import DesignError

    drive, geometry = seed
    with pytest.raises(DesignError) as err:
        simulate(drive, 0.001, geometry=geometry, initial_speed="running")
    assert err.value.field == "initial_speed"
    assert math.isfinite(simulate(drive, 0.001, geometry=geometry, motor=False).dt)


@pytest.fixture(scope="module")
def seed_modes(seed):
    from chaindrive.linklevel.modes import linear_modes

    drive, geometry = seed
    return linear_modes(drive, geometry=geometry)


def test_linearised_span_mode_is_the_string(seed, seed_modes):
    """About the static state the longest span's first antisymmetric transverse mode is the
    string's second, f = (1/a)√(T/q) — sag leaves the antisymmetric in-plane modes of a
    shallow cable unchanged [Irvine1981, ch. 2] — T the span's static tension, a its length;
    a mode within 2 %."""
    drive, geometry = seed
    installed, _ = installed_geometry(drive, geometry)
    model = build_model(drive, installed)
    ref = _reference(drive, installed)
    span = installed.spans[ref]
    tension = model.pretension
    closed = math.sqrt(tension / drive.chain.spec.mass_per_length) / span.length
    assert np.min(np.abs(seed_modes.frequencies_hz / closed - 1)) < 0.02


def test_linearised_first_mode_along_the_chain_is_a_seat_mode(seed_modes):
    """The link-level model's first mode along the chain at rest (more than half its kinetic
    energy in motion along the links and sprocket turning) is not the whole-drive model's
    first mode: more than half of its strain energy is in the roller-seat contacts (family
    "seat", measured 98 % on the seed), a stiffness the whole-drive model does not have. The
    like-with-like comparison is tests/unit/test_linklevel_agreement.py (docs/linklevel.md
    §6); the transverse span modes come first."""
    k = seed_modes.first_longitudinal
    assert k is not None
    assert seed_modes.family[k] == "seat"
    assert seed_modes.strain_shares[k, 2] > 0.5
    # the transverse span modes come first and are not it
    assert seed_modes.frequencies_hz[0] < 0.2 * seed_modes.frequencies_hz[k]
    assert seed_modes.longitudinal_fraction[0] < 0.1


def test_potential_energy_is_the_potential_of_the_static_forces(seed):
    """The solve minimises the potential energy, so its gradient must be minus the kernel's
    static forces (links, gravity, contacts with the tip-corner rule) and torques: central
    differences of V (step 1 nm, 1 µrad) against static_forces on a state with rollers
    pressed into their teeth, within 10⁻⁵ of the largest force."""
    from chaindrive.linklevel.equilibrium import potential_energy

    drive, geometry = seed
    m = build_model(drive, geometry)
    t = kernel_tables(m)
    r = simulate(drive, 0.002, geometry=geometry, model=m, initial_speed="working")
    x = np.ascontiguousarray(r.positions[-1])
    th = np.ascontiguousarray(r.angles[-1, :m.centres.shape[0]])
    assert np.count_nonzero(r.contact_forces[-1] > 0) > 10  # contacts in the sample
    N, n = x.shape[0], m.centres.shape[0]
    rest = np.full(N, m.pitch - m.pretension / m.link_stiffness)
    f, tq, T, tr = np.empty((N, 2)), np.empty(n), np.empty(N), np.empty(N)
    static_forces(x, th, rest, m.link_stiffness, m.clearance, m.roller_mass,
                  float(m.gravity[0]), float(m.gravity[1]), t.spr, t.trig, t.gtab, t.reach,
                  f, tq, T, tr)

    def energy(xx, tt):
        return potential_energy(xx, xx - x, tt, float(rest[0]), m.link_stiffness, m.clearance,
                                m.roller_mass, float(m.gravity[0]), float(m.gravity[1]),
                                t.spr, t.reach)

    h, scale = 1e-9, float(np.abs(f).max())
    for i in range(N):
        for c in range(2):
            xp, xm = x.copy(), x.copy()
            xp[i, c] += h
            xm[i, c] -= h
            assert -(energy(xp, th) - energy(xm, th)) / (2 * h) == pytest.approx(
                f[i, c], abs=1e-5 * scale)
    for s in range(n):
        tp, tm = th.copy(), th.copy()
        tp[s] += 1e-6
        tm[s] -= 1e-6
        assert -(energy(x, tp) - energy(x, tm)) / 2e-6 == pytest.approx(
            tq[s], abs=1e-5 * scale * m.pitch_radii[s])


def test_static_solve_reports_its_residual_and_is_deterministic(seed):
    """The static state's residual is reported (largest component and norm, N) within the
    module's tolerances, the reference span at T₀ to 10⁻⁴ T₀, and the solve gives the same
    state bit for bit whatever the BLAS threads outside it (it holds them to one)."""
    from threadpoolctl import threadpool_limits

    from chaindrive.linklevel.equilibrium import (
        MINIMUM_TOLERANCE,
        TENSION_TOLERANCE,
    )
    from chaindrive.linklevel.simulate import equilibrium_state

    drive, geometry = seed
    installed, moved = installed_geometry(drive, geometry)
    model = build_model(drive, installed)
    states = []
    for threads in (1, 2):
        with threadpool_limits(limits=threads):
            states.append(equilibrium_state(drive, installed, model, 1e-6, moved)[1])
    a, b = states
    assert np.array_equal(a.positions, b.positions) and a.rest_length == b.rest_length
    out = a.to_dict()
    t0 = model.pretension
    assert 0 <= out["residual_force_n"] <= out["residual_force_norm_n"]
    assert out["residual_force_n"] <= MINIMUM_TOLERANCE * t0
    assert abs(out["reference_tension_error_n"]) <= TENSION_TOLERANCE * t0
    assert out["solver_iterations"] >= 1 and out["solver_pulls"] >= 1
    assert out["converged"] is True


def test_links_that_cannot_carry_the_pretension_are_refused(seed):
    """A link stiffness at which T₀ would stretch a link by more than its pitch leaves no
    positive rest length: no static state exists, one line says why."""
    from dataclasses import replace

    from chaindrive.errors import ConvergenceError
    from chaindrive.linklevel.assembly import assemble_chain
    from chaindrive.linklevel.equilibrium import static_equilibrium

    drive, geometry = seed
    installed, _ = installed_geometry(drive, geometry)
    model = build_model(drive, installed)
    soft = replace(model, link_stiffness=0.5 * model.pretension / model.pitch)
    with pytest.raises(ConvergenceError, match="rest length") as err:
        static_equilibrium(soft, installed, assemble_chain(installed, drive.driver_index), 0)
    assert "\n" not in str(err.value)


def test_the_twenty_four_sprocket_static_state_converges():
    """The 24-sprocket example, whose soft sag-and-idler modes (19 N/m against 1.4·10⁹ N/m)
    and grazing seat contacts held the minimisation at its step cap (0.12 N left, converged
    false), is solved within the module's tolerances by the continuation in the contact
    stiffness, and its spans carry the hydrostatic tension T₀ + q g (y − y_ref)
    [Irvine1981, ch. 1] within the chordal bound (module docstring)."""
    from chaindrive.linklevel.equilibrium import MINIMUM_TOLERANCE, TENSION_TOLERANCE
    from chaindrive.linklevel.simulate import equilibrium_state

    drive = load_drive(EXAMPLES / "twenty_four_sprocket.toml")
    installed, moved = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, installed)
    _, eq = equilibrium_state(drive, installed, model, 1e-6, moved)
    t0 = model.pretension
    assert eq.converged is True
    assert eq.residual_force <= MINIMUM_TOLERANCE * t0
    ref = eq.reference_span
    assert abs(eq.span_tensions[ref] - t0) <= TENSION_TOLERANCE * t0
    x = eq.positions
    mids = 0.5 * (x + np.roll(x, -1, axis=0))[span_probes(installed, x)]
    q_g = model.roller_mass / model.pitch * 9.80665
    closed = t0 + q_g * (mids[:, 1] - mids[ref, 1])
    np.testing.assert_allclose(eq.span_tensions, closed, rtol=_chordal_bound(model.teeth))
