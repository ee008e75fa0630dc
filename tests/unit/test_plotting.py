"""Every figure builds for every example drive (issue 6), without touching global state."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive import plotting
from chaindrive.display import fmt
from chaindrive.dynamics.damping import hinge_friction_damping
from chaindrive.dynamics.modes import model_dynamics
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
    """Importing the plotting package leaves pyplot (its global figure state) unloaded; run
    in a fresh interpreter, since another test in the same process may have loaded it."""
    code = "import sys, chaindrive.plotting; print('matplotlib.pyplot' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"


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
    dyn = model_dynamics(analysis.drive, analysis.geometry, analysis.drive_model,
                         speed_range=(0.2 * w, 2 * w), speed_points=15)
    names = [s.name for s in analysis.drive.sprockets]
    fig = plotting.mode_shapes(dyn.modal, names=names)
    assert _rendered(fig)
    elastic = np.flatnonzero(~dyn.modal.rigid_body)[:4]
    lines = [ln for ln in fig.axes[0].get_lines() if len(ln.get_ydata()) == len(names) + 1]
    assert len(lines) == len(elastic)  # one signed line per elastic mode
    for line, j in zip(lines, elastic, strict=True):
        x = dyn.modal.shapes[:, j]
        expected = x / x[np.argmax(np.abs(x))]  # largest = +1, signs kept (nodes, phase)
        np.testing.assert_allclose(line.get_ydata()[:-1], expected, rtol=1e-12)
        assert line.get_ydata()[-1] == line.get_ydata()[0]  # the ring closes
    assert _rendered(plotting.campbell_diagram(dyn.campbell, operating_rpm=w * 30 / np.pi))


def test_campbell_zoomed_to_the_crossing_near_the_working_speed(analysis) -> None:
    """The tooth line f = z₁·n/60 meets a natural frequency f_j at n = 60 f_j/z₁ (closed
    form): with the working speed there, it is among the crossings that matter (within
    ±30 % of the working speed) and the frequency axis ends at 1.3 × the highest of them —
    the crossing is never lost under a scale set by the highest mode."""
    modal = analysis.dynamics.modal
    z1 = analysis.drive.driver.teeth
    fj = float(modal.elastic_frequencies_hz[0])
    n_cross = 60.0 * fj / z1  # rpm
    w = n_cross * np.pi / 30
    dyn = model_dynamics(analysis.drive, analysis.geometry, analysis.drive_model,
                         speed_range=(0.5 * w, 1.5 * w), speed_points=41)
    fig = plotting.campbell_diagram(dyn.campbell, operating_rpm=n_cross, band_percent=10)
    top = fig.axes[0].get_ylim()[1]
    near, limit = plotting.dynamics.campbell_window(dyn.campbell, n_cross)
    assert any(e == "tooth x1" and abs(s - n_cross) < 1e-6 * n_cross for e, _, s, _ in near)
    assert top == pytest.approx(limit) == pytest.approx(1.3 * max(f for *_, f in near))
    assert top >= 1.3 * fj * (1 - 1e-9)


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
    settled = math.isfinite(response.startup.settling_time)
    # spans, F1max mark, settling line (a 0.05 s record ends before the forces settle)
    assert len(fig.axes[0].lines) == len(spans) + 1 + settled
    assert settled or "not settled within 50 ms" in fig.axes[0].get_title()
    assert startup_speeds(response.startup).axes
    fig = afc_curves(response.afc, names=spans)
    assert fig.axes[0].get_yscale() == "log"
    # peak and amplitude bar per span
    assert len(steady_loads(response.steady, names=spans).axes[0].patches) == 2 * len(spans)
    fig = inertia_and_irregularity(response.steady)
    assert [len(ax.patches) for ax in fig.axes] == [len(drive.sprockets)] * 2


# --- dynamic response, every example drive (issue 6; seed 000 Fig. 2–3, Table 1) -------------

@pytest.fixture(scope="module", params=EXAMPLES, ids=[p.stem for p in EXAMPLES])
def short_response(request: pytest.FixtureRequest):
    """(analysis, span names, sprocket names) with a 0.05 s start-up (fast)."""
    from dataclasses import replace

    drive = chaindrive.load(request.param)
    drive = replace(drive, dynamics=replace(drive.dynamics, startup_duration=0.05))
    a = chaindrive.analyze(drive)
    assert a.response is not None and a.response.startup is not None
    return (a, [f"{s.start_name}→{s.end_name}" for s in a.geometry.spans],
            [s.name for s in a.drive.sprockets])


def test_startup_figures_mark_peak_and_settling(short_response) -> None:
    a, spans, names = short_response
    st = a.response.startup
    fig = plotting.startup_oscillogram(st, names=spans)
    assert _rendered(fig)
    ax = fig.axes[0]
    peak = [ln for ln in ax.get_lines() if ln.get_marker() == "v"]
    assert len(peak) == 1
    np.testing.assert_allclose(peak[0].get_ydata(), [st.max_span_force.max()])
    vlines = [ln for ln in ax.get_lines() if str(ln.get_label()).startswith("settled")]
    if 0 < st.settling_time <= st.times[-1]:
        np.testing.assert_allclose(vlines[0].get_xdata(), [st.settling_time * 1e3] * 2)
    # every span is drawn (most loaded in colour, the rest grey), forces as computed
    curves = [ln for ln in ax.get_lines() if len(ln.get_ydata()) == st.times.size]
    assert len(curves) == len(spans)
    assert max(float(np.max(c.get_ydata())) for c in curves) == pytest.approx(
        st.max_span_force.max())
    assert any(f"F₁max = {fmt(float(st.max_span_force.max()))} N" in t.get_text()
               for t in ax.texts)
    fig = plotting.startup_speeds(st, names=names)
    assert _rendered(fig)
    top = max(float(np.max(ln.get_ydata())) for ln in fig.axes[0].get_lines())
    assert top == pytest.approx(st.speeds.max() * 30 / np.pi)


def test_afc_curves_label_resonances(short_response) -> None:
    a, spans, _ = short_response
    afc = a.response.afc
    fz = a.drive.driver.teeth * a.drive.driver.speed / (2 * np.pi)
    fig = plotting.afc_curves(afc, names=spans, operating_hz=fz, max_markers=5)
    assert _rendered(fig)
    ax = fig.axes[0]
    assert ax.get_yscale() == "log"
    labels = [t.get_text().strip() for t in ax.texts]
    inside = {(j, k): f for j, k, _, f in afc.markers
              if afc.tooth_frequencies_hz.min() <= f <= afc.tooth_frequencies_hz.max()}
    assert 0 < len(labels) <= 5 if inside else labels == []
    for t in ax.texts:  # each label names a resonance and sits on its tooth frequency
        j, k = (int(v) for v in t.get_text().split("mode")[1].split("×"))
        assert t.get_position()[0] == pytest.approx(inside[(j, k)])
    xs = [float(ln.get_xdata()[0]) for ln in ax.get_lines()
          if str(ln.get_label()).startswith("operating")]
    assert xs == [pytest.approx(fz)]
    curves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == afc.tooth_frequencies_hz.size]
    assert len(curves) == len(spans)


def test_steady_bars_are_the_computed_loads(short_response) -> None:
    a, spans, names = short_response
    steady = a.response.steady
    fig = plotting.steady_loads(steady, names=spans)
    assert _rendered(fig)
    heights = [p.get_height() for p in fig.axes[0].patches]
    np.testing.assert_allclose(heights, np.r_[steady.span_dynamic_load,
                                              steady.span_load_amplitude])
    fig = plotting.inertia_and_irregularity(steady, names=names)
    assert _rendered(fig)
    inertia, irregular = ([p.get_height() for p in ax.patches] for ax in fig.axes)
    np.testing.assert_allclose(inertia, steady.inertia_load)
    np.testing.assert_allclose(irregular, steady.irregularity_percent)
    assert [t.get_text() for t in fig.axes[1].get_xticklabels()] == names


def test_names_must_match_the_spans(short_response) -> None:
    a, spans, _ = short_response
    with pytest.raises(ValueError, match="names"):
        plotting.steady_loads(a.response.steady, names=spans[:-1])


def test_material_comparison_chart_one_bar_per_pair() -> None:
    from chaindrive.dynamics.materials import MaterialCase

    cases = [MaterialCase("steel", "steel", 542.0, 300.0, 301.0, 900.0),
             MaterialCase("PA6", "steel", 470.0, 150.0, 151.0, 300.0),
             MaterialCase("steel", "PA6", 500.0, 600.0, 601.0, 400.0)]
    fig = plotting.material_comparison_chart(cases)
    assert _rendered(fig)
    peak, resonance = ([p.get_height() for p in ax.patches] for ax in fig.axes)
    assert peak == [542.0, 470.0, 500.0] and resonance == [900.0, 300.0, 400.0]
    assert "PA6\non steel" in [t.get_text() for t in fig.axes[0].get_xticklabels()]
