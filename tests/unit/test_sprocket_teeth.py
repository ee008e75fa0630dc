"""The teeth of polymer sprockets (chaindrive.strength.sprocket_teeth).

Each formula against an independent closed form: the rigid-chain load distribution of
Naji & Marshek [Naji1983, §2.1] as the equilibrium of the roller solved as a linear system
(not Lami's sines), the seat contact pressure as Hertz's line contact in Johnson's form
p₀ = √(P′E*/(πR)) (Johnson, *Contact Mechanics*, 1985, Eq. 4.45) against Roark's constant
[Roark2012, Table 14.1], the root stress against the cantilever σ = 6M/(b s²) written out.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.checks import UNVERIFIED
from chaindrive.strength.sprocket_teeth import (
    ansi_pressure_angles,
    binder_tooth_factors,
    flank_limit_factors,
    iso606_pressure_angle_range,
    root_bending_stress,
    seat_contact_pressure,
    seating_pressure_angle,
)

EXAMPLES = Path(chaindrive.__file__).parent / "examples"


def _equilibrium(teeth: int, half_angle: float) -> tuple[float, float]:
    """(T_out/T_in, N/T_in) of a roller at a vertex of the pitch polygon with its two link
    tensions and the flank normal force (normal at α from the inward radial), by a 2×2
    solve."""
    s = 2.0 * math.pi / teeth
    points = np.array([[math.cos(a), math.sin(a)] for a in (-s, 0.0, s)])
    back = (points[0] - points[1]) / np.linalg.norm(points[0] - points[1])
    ahead = (points[2] - points[1]) / np.linalg.norm(points[2] - points[1])
    normal = np.array([math.cos(half_angle), math.sin(half_angle)])
    t_out, force = np.linalg.solve(np.column_stack([ahead, normal]), -back)
    return float(t_out), float(force)


@pytest.mark.parametrize(("teeth", "alpha_deg"), [(15, 62.0), (17, 62.35), (25, 50.0),
                                                  (40, 55.0)])
def test_flank_limit_factors_are_the_rollers_equilibrium(teeth: int, alpha_deg: float) -> None:
    """[Naji1983, §2.1]: Lami's closed form equals the equilibrium solved as a linear
    system; for z = 15 and α = 62° (ISO 606 mean seating angle) the ratio is 0.4288 (the
    value the link-level model reproduces, docs/linklevel.md §5.2)."""
    alpha = math.radians(alpha_deg)
    q, per_tension = flank_limit_factors(teeth, alpha)
    q_ref, n_ref = _equilibrium(teeth, alpha)
    assert q == pytest.approx(q_ref, rel=1e-12)
    assert per_tension == pytest.approx(n_ref, rel=1e-12)
    if teeth == 15:
        assert q == pytest.approx(math.cos(math.radians(74)) / math.cos(math.radians(50)))
        assert q == pytest.approx(0.4288, abs=5e-5)


@pytest.mark.parametrize("teeth", [9, 15, 25, 60])
@pytest.mark.parametrize("phi_deg", [8.0, 16.0, 27.0])
def test_binder_factors_are_the_rollers_equilibrium_in_his_convention(
        teeth: int, phi_deg: float) -> None:
    """[Binder1956]: sin φ/sin(φ + 2β) and sin 2β/sin(φ + 2β) equal the roller's
    equilibrium built from the pressure angle itself: the tooth's force along the line at
    φ from the centre line of the link carrying T_(k−1), turned towards the sprocket's
    centre; the other link at the interior angle π − 2β of the pitch polygon."""
    phi, half = math.radians(phi_deg), math.pi / teeth
    back = np.array([-math.cos(half), -math.sin(half)])   # towards roller k − 1
    ahead = np.array([math.cos(half), -math.sin(half)])   # towards roller k + 1
    line = np.array([-math.cos(half + phi), -math.sin(half + phi)])  # roller → tooth
    t_out, force = np.linalg.solve(np.column_stack([ahead, -line]), -back)
    q, per_tension = binder_tooth_factors(teeth, phi)
    assert force > 0
    assert q == pytest.approx(t_out, rel=1e-12)
    assert per_tension == pytest.approx(force, rel=1e-12)


@pytest.mark.parametrize("teeth", [9, 15, 25, 60])
def test_seating_pressure_angle_reproduces_the_published_ansi_pressure_angle(
        teeth: int) -> None:
    """[ANSI-B29.1] as reproduced in [Oberg2016]: the ANSI seating curve ends at
    A = 35° + 60°/N off the pitch circle's tangent (seat half-angle from the inward radial
    90° − A), and the form's published pressure angle for new chain is 35° − 120°/N. The
    conversion of a seat's half-angle into Binder's pressure angle (measured from the link's
    centre line) gives the published figure from the published seat."""
    seat_half = math.radians(90.0 - (35.0 + 60.0 / teeth))
    _, new_chain = ansi_pressure_angles(teeth)
    assert seating_pressure_angle(teeth, seat_half) == pytest.approx(new_chain, rel=1e-12)
    assert math.degrees(new_chain) == pytest.approx(35.0 - 120.0 / teeth, rel=1e-12)


@pytest.mark.parametrize("teeth", [15, 25])
def test_iso606_pressure_angle_band(teeth: int) -> None:
    """[ISO606] seating angles 120° − 90°/z … 140° − 90°/z as Binder's pressure angle
    90° − α/2 − 180°/z: 20° − 135°/z … 30° − 135°/z (11° … 21° for z = 15); the
    link-level model's mean seat (65° − 45°/z) lies in the middle."""
    low, high = iso606_pressure_angle_range(teeth)
    assert math.degrees(low) == pytest.approx(20.0 - 135.0 / teeth, rel=1e-12)
    assert math.degrees(high) == pytest.approx(30.0 - 135.0 / teeth, rel=1e-12)
    mean = seating_pressure_angle(teeth, math.radians(65.0 - 45.0 / teeth))
    assert mean == pytest.approx(0.5 * (low + high), rel=1e-12)


def test_seat_contact_pressure_is_hertz_line_contact() -> None:
    """Roark's p = 0.798·√(w/(K_D C_E)) is Johnson's p₀ = √(P′E*/(πR)) with
    1/R = 1/r₁ − 1/r₂ (conformal) and E* = 1/C_E, to Roark's three figures."""
    load, r1, r2, b = 1100.0, 6.035e-3, 6.17e-3, 9.9e-3
    c_e = (1 - 0.3**2) / 2.1e11 + (1 - 0.5**2) / 2.93e9
    radius = 1.0 / (1.0 / r1 - 1.0 / r2)
    johnson = math.sqrt(load / b / c_e / (math.pi * radius))
    assert seat_contact_pressure(load, r1, r2, b, c_e) == pytest.approx(johnson, rel=1e-3)


def test_root_bending_stress_is_the_cantilever() -> None:
    """σ_F = 6·(P sin α)·h/(b s²), h = r_i(1 − cos α), s = 2(R − r_i) sin(π/z), written
    out for a 12B tooth (z = 17)."""
    load, alpha, r_i, b, z = 1100.0, math.radians(62.35), 6.17e-3, 9.9e-3, 17
    radius = 19.05e-3 / (2 * math.sin(math.pi / z))
    s = 2 * (radius - r_i) * math.sin(math.pi / z)
    moment = load * math.sin(alpha) * r_i * (1 - math.cos(alpha))
    assert root_bending_stress(load, alpha, r_i, radius, z, b) == pytest.approx(
        6 * moment / (b * s * s), rel=1e-12)
    # proportional to the load, inversely to the width
    assert root_bending_stress(2 * load, alpha, r_i, radius, z, 2 * b) == pytest.approx(
        root_bending_stress(load, alpha, r_i, radius, z, b), rel=1e-12)


def test_polymer_sprockets_get_tooth_checks_that_cannot_be_verified() -> None:
    """Every polymer sprocket gets a root-stress and a contact-pressure check of its most
    loaded tooth; without a confirmed allowable they cannot be verified (never a pass) and
    say what is missing. A steel drive gets none."""
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket_polymer.toml"),
                           response=False)
    for sp in a.drive.sprockets:
        for name in ("tooth_root_stress", "tooth_contact_pressure"):
            c = a.check(f"{name}[{sp.name}]")
            assert c is not None and c.status == UNVERIFIED and c.part == "sprockets"
            assert c.value is not None and c.value > 0 and "permissible" in c.note
    assert not any(w.code == "strength.polymer-sprocket" for w in a.warnings)
    steel = chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"),
                               response=False)
    assert not any(c.key.startswith("tooth_") for c in steel.checks())


def test_most_loaded_tooth_follows_the_span_tension() -> None:
    """The tooth load is P/T times the larger span tension at the sprocket, K_A applied."""
    from chaindrive.geometry.sprocket import seating_geometry
    from chaindrive.strength.sprocket_teeth import tooth_loads

    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket_polymer.toml"),
                           response=False)
    d, g, loads = a.drive, a.geometry, a.strength.loads
    t = tooth_loads(d, g, loads, (d.driver_index,))[0]
    spans = [s.index for s in g.spans if d.driver_index in (s.start, s.end)]
    tension = (d.service_factor or 1.0) * max(loads.span_tensions[k] for k in spans)
    _, alpha = seating_geometry(d.tooth_form, d.chain.spec.pitch, [d.driver.teeth],
                                d.chain.spec.roller_diameter, d.chain.spec.inner_width)
    _, n_ref = _equilibrium(d.driver.teeth, float(alpha[0]))
    assert t.entering_tension == pytest.approx(tension)
    assert t.load == pytest.approx(n_ref * tension, rel=1e-12)
