"""Every figure builds for every example drive (issue 6), without touching global state."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive import plotting
from chaindrive.damping import hinge_friction_damping
from chaindrive.dynamics import analyze_dynamics
from chaindrive.multicontour import contour_factor_km, simulate_length_difference

EXAMPLES = sorted(p for p in (Path(__file__).parents[2] / "examples").glob("*.toml")
                  if not p.stem.endswith("_optimize"))


@pytest.fixture(scope="module", params=EXAMPLES, ids=[p.stem for p in EXAMPLES])
def analysis(request: pytest.FixtureRequest) -> chaindrive.analysis.Analysis:
    return chaindrive.analyze(chaindrive.load(request.param))


def _rendered(fig) -> bool:
    fig.set_dpi(30)
    fig.canvas.draw()
    return bool(fig.axes) and all(ax.has_data() for ax in fig.axes if ax.get_visible())


def test_importing_plotting_loads_no_pyplot() -> None:
    assert "matplotlib.pyplot" not in sys.modules


def test_drive_figures_build(analysis) -> None:
    figs = [plotting.contour_layout(analysis.geometry), plotting.chain_speed(analysis.kinematics),
            plotting.transmission_ratio(analysis)]
    if analysis.strength is not None:
        figs += [plotting.span_tensions(analysis), plotting.shaft_loads(analysis)]
    assert all(_rendered(f) for f in figs)


def test_layout_draws_every_span_and_circle(analysis) -> None:
    fig = plotting.contour_layout(analysis.geometry)
    ax = fig.axes[0]
    n = len(analysis.geometry.sprockets)
    assert len(ax.patches) == 2 * n  # pitch and tip circle per sprocket
    radii = sorted(p.get_radius() for p in ax.patches)
    expected = sorted([s.pitch_radius * 1e3 for s in analysis.geometry.sprockets]
                      + [s.tip_diameter / 2e-3 for s in analysis.geometry.sprockets])
    np.testing.assert_allclose(radii, expected)


def test_dynamics_figures_build(analysis) -> None:
    w = analysis.drive.driver.speed
    dyn = analyze_dynamics(analysis.drive, analysis.geometry, speed_range=(0.2 * w, 2 * w),
                           speed_points=15)
    names = [s.name for s in analysis.drive.sprockets]
    fig = plotting.mode_shapes(dyn.modal, names=names)
    assert _rendered(fig)
    elastic = min(4, int((~dyn.modal.rigid_body).sum()))
    assert len(fig.axes[0].patches) == elastic * len(names)  # one bar per mass and mode
    assert _rendered(plotting.campbell_diagram(dyn.campbell, operating_rpm=w * 30 / np.pi))


def test_damping_curves_one_per_tension() -> None:
    results = [hinge_friction_damping(f0, y, 0.6096) for f0 in (250.0, 500.0, 1000.0)
               for y in (0.015, 0.02, 0.03)]
    fig = plotting.absorption_vs_amplitude(results)
    lines = fig.axes[0].get_lines()
    assert len(lines) == 3
    # seed 001: ψ falls with the amplitude and grows with the tension
    for line in lines:
        assert np.all(np.diff(line.get_ydata()) < 0)
    assert lines[0].get_ydata()[0] < lines[-1].get_ydata()[0]


def test_km_distribution_marks_mean_and_risk_value() -> None:
    dl = simulate_length_difference(500, 3, c4=1.0, max_clearance=1e-4)
    km = contour_factor_km(dl, 5e-5)
    fig = plotting.km_distribution(km)
    x = sorted(float(line.get_xdata()[0]) for line in fig.axes[0].get_lines())
    np.testing.assert_allclose(x, sorted([km.mean(), np.quantile(km, 0.05)]))


def test_draws_into_given_axes() -> None:
    from matplotlib.figure import Figure

    a = chaindrive.analyze(chaindrive.load(EXAMPLES[0]))
    fig = Figure()
    ax1, ax2 = fig.subplots(1, 2)
    assert plotting.chain_speed(a.kinematics, ax=ax2) is fig
    assert ax2.has_data() and not ax1.has_data()


def test_response_figures_build() -> None:
    """Start-up oscillogram and speeds, AFC, steady loads, inertia and irregularity
    (issue 6; seed 000 Fig. 2–3) for a drive with a short start-up."""
    from dataclasses import replace

    import chaindrive
    from chaindrive.plotting import (
        afc_curves,
        inertia_and_irregularity,
        startup_oscillogram,
        startup_speeds,
        steady_loads,
    )

    drive = chaindrive.load(EXAMPLES[0])
    drive = replace(drive, dynamics=replace(drive.dynamics, startup_duration=0.05))
    result = chaindrive.analyze(drive)
    response = result.response
    assert response is not None and response.startup is not None
    spans = [f"{s.start_name}→{s.end_name}" for s in result.geometry.spans]
    fig = startup_oscillogram(response.startup, names=spans)
    assert len(fig.axes[0].lines) == min(6, len(spans)) + 2  # spans, F1max mark, settling
    assert startup_speeds(response.startup).axes
    fig = afc_curves(response.afc, names=spans)
    assert fig.axes[0].get_yscale() == "log"
    assert len(steady_loads(response.steady, names=spans).axes[0].patches) == len(spans)
    fig = inertia_and_irregularity(response.steady)
    assert [len(ax.patches) for ax in fig.axes] == [len(drive.sprockets)] * 2
