"""The span tension read from a frequency, against the link-level model's own spans.

The link-level model (every link a body, gravity on, its static state at the installed
pre-tension; docs/linklevel.md) has transverse modes in each span. Its antisymmetric modes
(even n) are the taut string's whatever the sag ([IrvineCaughey1974]; [Irvine1981]), so:

* each span's n = 2 and n = 4 modes of the link-level model lie within 1.5 % of the string
  law f_n = n/(2L)·sqrt(T/q) at the span's own static tension T ([WickertMote1990], v = 0) —
  the chain of N rollers is a beaded string, which rings lower by sin(x)/x,
  x = nπ/(2(N + 1)): 0.9 % for n = 4 on a 26-link span;
* the tension read back from that link-level frequency (:func:`string_tension`, mode n) is
  the span's static tension within 3 % (T ∝ f²).

The odd (symmetric in-plane) modes are not asserted; what they show is recorded in
docs/identification.md §4.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy.linalg import eigh

import chaindrive
from chaindrive.geometry.contour import contour_geometry
from chaindrive.identification import expected_frequency, string_tension
from chaindrive.linklevel.equilibrium import Balance, installed_geometry, kernel_tables
from chaindrive.linklevel.model import build_model
from chaindrive.linklevel.simulate import COURANT, equilibrium_state
from tests.conftest import EXAMPLES

MODES = 40


@pytest.fixture(scope="module")
def link_level() -> dict[str, Any]:
    """The seed drive's link-level static state, its lowest modes and each span's share of
    every mode's kinetic energy in motion normal to the span's chord."""
    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    geometry, take_up = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry)
    dt = COURANT * 2.0 / (2.0 * math.pi * model.highest_frequency_hz)
    _, eq = equilibrium_state(drive, geometry, model, dt, take_up)
    n = model.centres.shape[0]
    x, th = eq.positions, eq.angles[:n].copy()
    N = x.shape[0]
    bal = Balance(model, kernel_tables(model), np.arange(n, dtype=np.int64), N, 0)
    K = -bal.jacobian(x, th, eq.rest_length, bal(x, th, eq.rest_length))[:-1, :-1]
    K = 0.5 * (K + K.T)
    mass = np.concatenate([np.full(2 * N, model.roller_mass),
                           model.inertias / model.pitch_radii ** 2])
    s = 1.0 / np.sqrt(mass)
    lam, vec = eigh(K * s[:, None] * s[None, :], subset_by_index=[0, MODES - 1])
    shapes = vec * s[:, None]
    freq = np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * math.pi)
    total = (mass[:, None] * shapes ** 2).sum(axis=0)
    share = []
    for sp in geometry.spans:
        a, b = np.asarray(sp.start_point), np.asarray(sp.end_point)
        u = (b - a) / sp.length
        normal = np.array([-u[1], u[0]])
        along, off = (x - a) @ u, (x - a) @ normal
        inside = np.flatnonzero((along > 0.02 * sp.length) & (along < 0.98 * sp.length)
                                & (np.abs(off) < 0.05))
        w = np.einsum("rk,k->r", shapes[:2 * N].reshape(N, 2, -1)[inside].transpose(0, 2, 1)
                      .reshape(-1, 2), normal).reshape(inside.size, -1)
        share.append((model.roller_mass * w ** 2).sum(axis=0) / total)
    return {"spans": geometry.spans, "tensions": eq.span_tensions, "freq": freq,
            "share": share, "q": drive.chain.spec.mass_per_length}


@pytest.mark.parametrize("span", [0, 1, 2])
@pytest.mark.parametrize("n", [2, 4])
def test_even_modes_of_the_link_level_spans_give_back_their_tension(
        link_level: dict[str, Any], span: int, n: int) -> None:
    sp = link_level["spans"][span]
    T = float(link_level["tensions"][span])
    q = link_level["q"]
    f_string = expected_frequency(T, sp.length, q, n)
    mine = np.flatnonzero(link_level["share"][span] > 0.8)
    f_links = link_level["freq"][mine]
    k = int(np.argmin(np.abs(f_links - f_string)))
    assert f_links[k] == pytest.approx(f_string, rel=0.015)
    assert string_tension(float(f_links[k]), sp.length, q, n) == pytest.approx(T, rel=0.03)
