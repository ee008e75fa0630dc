"""The link-level model against the whole-drive model, like with like
(chaindrive.linklevel.modes, chaindrive.linklevel.compare.mode_agreement; docs/linklevel.md
§6 "Agreement").

Closed forms:

* MAC = |aᵀb|²/(aᵀa·bᵀb) [Allemang2003]: 1 for proportional shapes, 0 for orthogonal ones,
  cos² of the angle between them otherwise.
* Two sprockets of reduced masses m₁, m₂ joined by two spans of stiffness k₁, k₂ (the
  chain's mass negligible against theirs): ω² = (k₁ + k₂)(1/m₁ + 1/m₂) [Rao2011, ch. 6]
  — the first frequency of both models where they share the span springs (links, wraps and
  the sag factor of each span at its tension); at a loaded state the tight span is taut
  (sag factor ≈ 1) and the links hold the mode.
* Statics of a free sprocket: the tight span carries the slack span's tension plus the
  load's M/R, up to the polygon's arm, between R cos(π/z) and R.
* A span of length L, tension T and mass per length q: its antisymmetric transverse modes
  (even n) are the taut string's n/(2L)·√(T/q), which sag leaves alone
  [Irvine1981, ch. 2], [Mote1965] (at rest, v = 0).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from chaindrive.dynamics.parameters import drive_ring_parameters
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel.compare import (
    FREQUENCY_TOLERANCE,
    _bare,
    mac,
    mode_agreement,
)
from chaindrive.linklevel.equilibrium import installed_geometry
from chaindrive.linklevel.modes import linear_modes
from chaindrive.strength.loads import power_shares
from tests.conftest import EXAMPLES


def test_mac_closed_forms():
    a = np.array([1.0, -2.0, 0.5])
    assert mac(a, -3.0 * a) == pytest.approx(1.0)
    assert mac(np.array([1.0, 0.0]), np.array([0.0, 2.0])) == pytest.approx(0.0)
    assert mac(np.array([1.0, 1.0]), np.array([1.0, 0.0])) == pytest.approx(0.5)  # cos² 45°
    assert math.isnan(mac(np.zeros(2), a[:2]))


@pytest.fixture(scope="module")
def heavy_pair():
    """The Jindal two-sprocket drive with 40 kg of reduced mass on each sprocket (the
    chain's 1.3 kg then negligible), its installed contour and its loaded modes."""
    drive = load_drive(EXAMPLES / "two_sprocket_jindal.toml")
    drive = replace(drive, sprockets=tuple(replace(s, reduced_mass=40.0, inertia=None)
                                           for s in drive.sprockets))
    geometry, _ = installed_geometry(drive, contour_geometry(drive))
    return drive, geometry, linear_modes(drive, geometry=geometry, loaded=True)


def test_two_sprockets_loaded_first_frequency_is_the_two_mass_closed_form(heavy_pair):
    """Measured: closed form 72.2 Hz, whole drive 72.1 Hz, link level 71.2 Hz (−1.2 %),
    MAC 1.000, 95 % of the link-level mode's strain energy in the links' stretch."""
    drive, geometry, modes = heavy_pair
    ring = drive_ring_parameters(_bare(drive), geometry, span_tensions=modes.span_tensions_n)
    k, m = ring.stiffness_n_per_m, ring.masses_kg
    closed = math.sqrt(k.sum() * (1.0 / m[0] + 1.0 / m[1])) / (2.0 * math.pi)
    agree = mode_agreement(drive, geometry=geometry, modes=modes)
    assert agree.loaded
    assert agree.whole_drive_hz == pytest.approx(closed, rel=0.02)
    assert agree.link_level_hz == pytest.approx(closed, rel=FREQUENCY_TOLERANCE)
    assert agree.agrees
    assert agree.first_mac > 0.99
    assert agree.link_strain[0] > 0.9  # the links hold it, as the whole drive's spans do
    assert agree.whole_strain[0] > 0.9
    out = agree.to_dict()
    assert out["state"] == "loaded" and out["within_tolerance"] is True
    assert (out["governing"], out["reason"]) == ("whole_drive", "shared")
    assert out["link_level_counterpart_hz"] == pytest.approx(agree.link_level_hz)


def test_loaded_state_tight_span_carries_the_slack_span_plus_the_load(heavy_pair):
    """Measured: 775.6 N against 8.2 N + M/R = 775.4 N."""
    drive, geometry, modes = heavy_pair
    driven = next(i for i, s in enumerate(drive.sprockets) if s.role == "driven")
    z = drive.sprockets[driven].teeth
    moment = float(power_shares(drive)[driven]) * drive.power / (
        drive.driver.speed * drive.driver.teeth / z)
    force = moment / geometry.sprockets[driven].pitch_radius
    tight = next(k for k, sp in enumerate(geometry.spans) if sp.tight)
    slack = 1 - tight
    bound = 1.0 / math.cos(math.pi / z) - 1.0
    assert modes.span_tensions_n[tight] - modes.span_tensions_n[slack] == pytest.approx(
        force, rel=bound)


@pytest.fixture(scope="module")
def seed_at_rest():
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    geometry, _ = installed_geometry(drive, contour_geometry(drive))
    modes = linear_modes(drive, geometry=geometry)
    return drive, geometry, modes, mode_agreement(drive, geometry=geometry, modes=modes)


def test_antisymmetric_span_modes_are_the_strings(seed_at_rest):
    """Measured: the even modes at 0.996 of the string (13.35, 13.36, 13.51 Hz …)."""
    drive, geometry, modes, agree = seed_at_rest
    q = drive.chain.spec.mass_per_length
    names = [f"{sp.start_name}-{sp.end_name}" for sp in geometry.spans]
    even = [t for t in agree.transverse if t.half_waves % 2 == 0]
    assert len(even) >= 2
    for t in even:
        k = names.index(t.span)
        string = t.half_waves / (2.0 * geometry.spans[k].length) * math.sqrt(
            modes.span_tensions_n[k] / q)
        assert t.string_hz == pytest.approx(string, rel=1e-9)
        assert t.frequency_hz == pytest.approx(string, rel=0.01)


def test_modes_are_classified_by_where_their_energy_is(seed_at_rest):
    """Transverse modes hold their strain energy in the tension (a string's), every mode's
    three parts sum to 1; at rest the seed's lowest modes are transverse (48 of them below
    its first mode along the chain)."""
    _, _, modes, agree = seed_at_rest
    family = np.array(modes.family)
    np.testing.assert_allclose(modes.strain_shares.sum(axis=1), 1.0, atol=1e-9)
    transverse = family == "transverse"
    assert transverse[:10].all()
    assert np.median(modes.strain_shares[transverse[:50].nonzero()[0], 1]) > 0.95
    assert agree.below >= 10
    assert set(family[:200]) >= {"transverse", "longitudinal_torsional", "seat"}


def test_eight_sprockets_loaded_first_frequencies_agree():
    """Where the two models share their physics — the loaded eight-sprocket drive, its
    tight spans taut (sag factors 0.9–1) — the whole-drive f₁ has a link-level counterpart
    of its shape within 5 %. Measured: 201.7 against 201.3 Hz (−0.2 %), MAC 0.965; below
    it the link-level's seat modes (first 106.6 Hz), which the whole-drive model has not."""
    drive = load_drive(EXAMPLES / "eight_sprocket.toml")
    agree = mode_agreement(drive, loaded=True)
    assert agree.agrees, agree.pairs
    assert agree.counterpart.mac > 0.9
    assert agree.first_seat_hz < agree.counterpart.link_level_hz


def test_a_whole_drive_mode_without_counterpart_is_said_so_in_strict_json():
    """The conveyor at rest: its whole-drive f₁ (14.0 Hz) is a sag mode with no link-level
    mode of its shape within half to twice its frequency; the record says none (null, not
    NaN) and names the link-level model as right for the sag."""
    drive = load_drive(EXAMPLES / "conveyor_five_sprocket.toml")
    agree = mode_agreement(drive)
    out = json.loads(json.dumps(agree.to_dict(), allow_nan=False))
    assert out["state"] == "rest"
    assert out["link_level_counterpart_hz"] is None and out["within_tolerance"] is False
    assert (out["governing"], out["reason"]) == ("link_level", "sag")
    assert out["whole_drive_strain_share"]["sag"] > 0.5
    assert out["whole_drive_first_hz"] > out["lowest_string_hz"]
