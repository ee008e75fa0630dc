"""The speed sweep's maxima by branch and bound (``span_load_maxima``) against the whole
sweep (``span_loads_over``): the same per-span maxima on every bundled example and on designs
of the 8-sprocket search, whatever the first runs; the bound of a run holds at every speed
of it (the closed-form variation of the complex-mode response, checked against the loads
computed at every speed); and the analysis that screens by the maxima judges the design as
the one with the whole sweep."""

from __future__ import annotations

import numpy as np
import pytest

import chaindrive
from chaindrive import examples
from chaindrive.analysis import AFC_POINTS, SPEED_RANGE, Analysis
from chaindrive.dynamics.frequency import response
from chaindrive.dynamics.frequency.afc import peak_over_period
from chaindrive.dynamics.frequency.response import span_load_maxima, span_loads_over
from chaindrive.synthesis.problem import load_problem
from tests.conftest import EXAMPLES


def _sweep(a: Analysis) -> tuple[object, object, object, np.ndarray]:
    d = a.drive
    assert d.driver.speed is not None
    wz = np.linspace(*SPEED_RANGE, AFC_POINTS) * d.driver.speed * d.driver.teeth
    return a.drive_model, a.dynamics.modal, a._excitation, wz


def _search_designs(count: int) -> list[Analysis]:
    """Designs of the 8-sprocket search that can be built, from seeded random vectors."""
    problem = load_problem(EXAMPLES / "eight_sprocket_optimize.toml")
    lo, hi = (np.array(b, dtype=float) for b in problem.bounds)
    rng = np.random.default_rng(7)
    out: list[Analysis] = []
    while len(out) < count:
        try:
            a = Analysis(problem.decode(lo + rng.random(lo.size) * (hi - lo)))
            _sweep(a)
        except chaindrive.errors.ChainDriveError:
            continue
        out.append(a)
    return out


@pytest.fixture(scope="module")
def analyses() -> list[Analysis]:
    bundled = [Analysis(examples.load(n)) for n in examples.names()
               if n != "eight_sprocket_optimize"]
    return [a for a in bundled if a.afc is not None] + _search_designs(8)


def test_maxima_are_those_of_the_whole_sweep(analyses) -> None:
    for a in analyses:
        model, state, excitation, wz = _sweep(a)
        whole = span_loads_over(model, state, excitation, wz).max(axis=0)
        for first in (1, 5, 128, 4000):
            found = span_load_maxima(model, state, excitation, wz, first=first)
            np.testing.assert_allclose(found, whole, rtol=1e-12, atol=0, err_msg=a.drive.name)


def test_maxima_of_a_grid_of_one_or_two_speeds(analyses) -> None:
    model, state, excitation, wz = _sweep(analyses[0])
    for grid in (wz[:1], wz[[3, 1500]]):
        np.testing.assert_allclose(span_load_maxima(model, state, excitation, grid),
                                   span_loads_over(model, state, excitation, grid).max(axis=0),
                                   rtol=1e-12, atol=0)
    with pytest.raises(chaindrive.errors.DesignError, match="ascending"):
        span_load_maxima(model, state, excitation, wz[::-1])


@pytest.mark.parametrize("width", [2, 16, 64])
def test_the_bound_of_a_run_holds_at_every_speed_of_it(analyses, width: int) -> None:
    """peak(W) ≤ peak(W₀) + Σ_k bound of |F_k(W) − F_k(W₀)| for every speed W of a run."""
    for a in analyses:
        model, state, excitation, wz = _sweep(a)
        loads = span_loads_over(model, state, excitation, wz)
        modal = response._SpanModal.of(model, state, excitation)
        lo = np.arange(0, wz.size - width, width)
        hi = lo + width - 1
        mid = (lo + hi) // 2
        F, cd = modal.forces(wz[mid])
        peak = peak_over_period(F, modal.orders, 64)
        bound = peak + modal.variation(F, cd, wz[lo], wz[mid], wz[hi]).sum(axis=1)
        for j in range(width):
            assert np.all(loads[lo + j] <= bound * (1 + 1e-12)), a.drive.name
        # and each harmonic's variation bounds the change of that harmonic itself
        Fl, _ = modal.forces(wz[lo])
        assert np.all(np.abs(Fl - F) <= modal.variation(F, cd, wz[lo], wz[mid], wz[hi])
                      * (1 + 1e-12) + 1e-9)


def test_the_search_computes_a_fraction_of_the_speeds(analyses, monkeypatch) -> None:
    """What the bound is for: on the 8-sprocket example well under half the speeds."""
    model, state, excitation, wz = _sweep(Analysis(examples.load("eight_sprocket")))
    computed: list[int] = []
    forces = response._SpanModal.forces

    def counted(self, w):  # type: ignore[no-untyped-def]
        computed.append(w.size)
        return forces(self, w)

    monkeypatch.setattr(response._SpanModal, "forces", counted)
    span_load_maxima(model, state, excitation, wz)
    assert sum(computed) < wz.size / 2


def test_screening_analysis_judges_as_the_whole_sweep(analyses) -> None:
    for a in analyses:
        screened = Analysis(a.design, sweep_curve=False)
        ours, whole = screened.checks(), a.checks()
        assert [(c.key, c.status) for c in ours] == [(c.key, c.status) for c in whole]
        assert [c.violation for c in ours] == pytest.approx([c.violation for c in whole],
                                                            rel=1e-12)
        assert "afc" not in screened.__dict__  # the curve was not computed
        assert screened.steady is not None and a.steady is not None
        assert screened.steady.k2_min == pytest.approx(a.steady.k2_min, rel=1e-12)
