"""The figures follow the report's unit system: with ``units="US"`` every dimensional axis
reads in, lbf, ft/min … and its data are the SI figure's data times display's exact factor;
the default (SI) figures are unchanged."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import chaindrive
from chaindrive import plotting
from chaindrive.display import QUANTITIES
from chaindrive.dynamics.damping import hinge_friction_damping
from chaindrive.dynamics.materials import MaterialCase

EXAMPLES = Path(__file__).parents[2] / "examples"
IN = QUANTITIES["length"]["US"].factor / QUANTITIES["length"]["SI"].factor  # per mm
LBF = QUANTITIES["force"]["US"].factor
FPM = QUANTITIES["velocity"]["US"].factor
FT = QUANTITIES["distance"]["US"].factor


@pytest.fixture(scope="module")
def analysis() -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    drive = replace(drive, dynamics=replace(drive.dynamics, startup_duration=0.05))
    a = chaindrive.analyze(drive)
    assert a.strength is not None and a.response is not None and a.response.startup is not None
    return a


def _lines(ax) -> list[np.ndarray]:
    return [np.asarray(line.get_ydata(), dtype=float) for line in ax.get_lines()]


def _heights(ax) -> np.ndarray:
    return np.array([p.get_height() for p in ax.patches])


def test_scale_is_display_factor() -> None:
    from chaindrive.plotting._base import scale

    assert scale("length", "SI") == (1e3, "mm")
    assert scale("force", "US") == (LBF, "lbf")
    assert scale("velocity", "US")[1] == "ft/min"


def test_contour_layout_in_inches(analysis) -> None:
    si = plotting.contour_layout(analysis.geometry).axes[0]
    us = plotting.contour_layout(analysis.geometry, units="US").axes[0]
    assert (si.get_xlabel(), si.get_ylabel()) == ("x, mm", "y, mm")
    assert (us.get_xlabel(), us.get_ylabel()) == ("x, in", "y, in")
    assert " mm of chain" in si.get_title() and " in of chain" in us.get_title()
    for a, b in zip(si.get_lines(), us.get_lines(), strict=True):
        np.testing.assert_allclose(b.get_xdata(), np.asarray(a.get_xdata()) * IN, rtol=1e-12)
        np.testing.assert_allclose(b.get_ydata(), np.asarray(a.get_ydata()) * IN, rtol=1e-12)
    np.testing.assert_allclose([p.get_radius() for p in us.patches],
                               [p.get_radius() * IN for p in si.patches], rtol=1e-12)
    # SI unchanged: the radii are the geometry's in mm
    expected = [r * 1e3 for s in analysis.geometry.sprockets
                for r in (s.pitch_radius, s.tip_diameter / 2)]
    np.testing.assert_allclose([p.get_radius() for p in si.patches], expected)


def test_chain_speed_in_feet_per_minute(analysis) -> None:
    si = plotting.chain_speed(analysis.kinematics).axes[0]
    us = plotting.chain_speed(analysis.kinematics, units="US").axes[0]
    assert si.get_ylabel() == "chain speed, m/s" and us.get_ylabel() == "chain speed, ft/min"
    np.testing.assert_array_equal(_lines(si)[0], analysis.kinematics.chain_speed_trace)
    for a, b in zip(_lines(si), _lines(us), strict=True):
        np.testing.assert_allclose(b, a * FPM, rtol=1e-12)
    assert "ft/min" in us.get_legend().get_texts()[1].get_text()
    assert si.get_legend().get_texts()[1].get_text().endswith(" m/s")


@pytest.mark.parametrize(("name", "label"), [("span_tensions", "tension"),
                                             ("shaft_loads", "shaft load")])
def test_static_loads_in_lbf(analysis, name, label) -> None:
    draw = getattr(plotting, name)
    si, us = draw(analysis).axes[0], draw(analysis, units="US").axes[0]
    assert si.get_ylabel() == f"{label}, N" and us.get_ylabel() == f"{label}, lbf"
    np.testing.assert_allclose(_heights(us), _heights(si) * LBF, rtol=1e-12)


def test_startup_oscillogram_in_lbf(analysis) -> None:
    st = analysis.response.startup
    si = plotting.startup_oscillogram(st).axes[0]
    us = plotting.startup_oscillogram(st, units="US").axes[0]
    assert si.get_ylabel() == "span force, N" and us.get_ylabel() == "span force, lbf"
    assert si.get_xlabel() == us.get_xlabel() == "time, ms"
    for a, b in zip(si.get_lines(), us.get_lines(), strict=True):
        np.testing.assert_allclose(b.get_xdata(), a.get_xdata())  # time stays
        np.testing.assert_allclose(np.asarray(b.get_ydata(), float),
                                   np.asarray(a.get_ydata(), float) * LBF, rtol=1e-12)
    assert " lbf (" in "".join(t.get_text() for t in us.texts)
    assert " N (" in "".join(t.get_text() for t in si.texts)


def test_afc_and_steady_loads_in_lbf(analysis) -> None:
    r = analysis.response
    si = plotting.afc_curves(r.afc, operating_hz=10.0).axes[0]
    us = plotting.afc_curves(r.afc, operating_hz=10.0, units="US").axes[0]
    assert si.get_ylabel() == "dynamic load, N" and us.get_ylabel() == "dynamic load, lbf"
    assert us.get_xlabel() == si.get_xlabel() == "tooth frequency f_z, Hz"
    n = np.asarray(r.afc.span_load).shape[1]
    spans_si = sorted(_lines(si)[:n], key=lambda y: float(y.max()))
    spans_us = sorted(_lines(us)[:n], key=lambda y: float(y.max()))
    for a, b in zip(spans_si, spans_us, strict=True):
        np.testing.assert_allclose(b, a * LBF, rtol=1e-12)
    si = plotting.steady_loads(r.steady).axes[0]
    us = plotting.steady_loads(r.steady, units="US").axes[0]
    assert si.get_ylabel() == "dynamic load, N" and us.get_ylabel() == "dynamic load, lbf"
    np.testing.assert_allclose(_heights(us), _heights(si) * LBF, rtol=1e-12)
    fig_si = plotting.inertia_and_irregularity(r.steady)
    fig_us = plotting.inertia_and_irregularity(r.steady, units="US")
    assert fig_si.axes[0].get_ylabel() == "inertia load m·ẍ, N"
    assert fig_us.axes[0].get_ylabel() == "inertia load m·ẍ, lbf"
    np.testing.assert_allclose(_heights(fig_us.axes[0]), _heights(fig_si.axes[0]) * LBF,
                               rtol=1e-12)
    # irregularity is a percentage: the same in both systems
    np.testing.assert_array_equal(_heights(fig_us.axes[1]), _heights(fig_si.axes[1]))


def test_material_chart_in_lbf() -> None:
    cases = [MaterialCase("steel", "steel", 542.0, 300.0, 301.0, 900.0),
             MaterialCase("PA6", "steel", 470.0, 150.0, 151.0, 300.0)]
    si = plotting.material_comparison_chart(cases)
    us = plotting.material_comparison_chart(cases, units="US")
    assert si.axes[0].get_ylabel() == "start-up peak F₁max, N"
    assert us.axes[0].get_ylabel() == "start-up peak F₁max, lbf"
    assert us.axes[1].get_ylabel() == "first resonance amplitude, lbf"
    assert _heights(si.axes[0]).tolist() == [542.0, 470.0]
    for a, b in zip(si.axes, us.axes, strict=True):
        np.testing.assert_allclose(_heights(b), _heights(a) * LBF, rtol=1e-12)


def test_damping_legend_in_lbf() -> None:
    results = [hinge_friction_damping(f0, y, 0.6096) for f0 in (250.0, 500.0)
               for y in (0.01, 0.02)]
    si = plotting.absorption_vs_amplitude(results).axes[0]
    us = plotting.absorption_vs_amplitude(results, units="US").axes[0]
    assert [t.get_text() for t in si.get_legend().get_texts()] == ["F₀ = 250 N", "F₀ = 500 N"]
    assert all(t.get_text().endswith(" lbf") for t in us.get_legend().get_texts())
    for a, b in zip(_lines(si), _lines(us), strict=True):
        np.testing.assert_array_equal(a, b)  # ψ is dimensionless


def _link_result(analysis) -> SimpleNamespace:
    """A stand-in link-level result on the drive's own geometry (the figures only read)."""
    g = analysis.geometry
    rng = np.random.default_rng(1)
    n, times = 40, np.array([0.01, 0.02, 0.03, 0.04])
    centre = np.array([[s.x, s.y] for s in g.sprockets]).mean(axis=0)
    ring = 0.3 * np.column_stack([np.cos(np.linspace(0, 6.2, n)), np.sin(np.linspace(0, 6.2, n))])
    return SimpleNamespace(
        times=times, geometry=g,
        model=SimpleNamespace(pitch=0.0254,
                              tip_radii=np.array([s.tip_diameter / 2 for s in g.sprockets])),
        positions=np.array([centre + ring for _ in times]),
        contact_sprocket=np.where(np.arange(n) % 3 == 0, 0, -1)[None, :].repeat(times.size, 0),
        angles=np.zeros((times.size, len(g.sprockets))),
        link_tensions=rng.uniform(100.0, 900.0, (times.size, n)),
        names=[s.name for s in g.sprockets],
        tooth_loads=[rng.uniform(0.0, 500.0, 6) for _ in g.sprockets])


def test_link_level_figures_in_us(analysis) -> None:
    res = _link_result(analysis)
    si = plotting.tension_along_chain(res, list(res.times)).axes[0]
    us = plotting.tension_along_chain(res, list(res.times), units="US").axes[0]
    assert si.get_ylabel() == "link tension [N]" and us.get_ylabel() == "link tension [lbf]"
    for a, b in zip(_lines(si), _lines(us), strict=True):
        np.testing.assert_allclose(b, a * LBF, rtol=1e-12)
    si = plotting.tooth_loads(res).axes[0]
    us = plotting.tooth_loads(res, units="US").axes[0]
    assert si.get_ylabel() == "mean tooth load [N]" and us.get_ylabel() == "mean tooth load [lbf]"
    for a, b in zip(_lines(si), _lines(us), strict=True):
        np.testing.assert_allclose(b, a * LBF, rtol=1e-12)
    fig_si = plotting.chain_frames(res, list(res.times))
    fig_us = plotting.chain_frames(res, list(res.times), units="US")
    assert fig_si.axes[-1].get_ylabel() == "link tension [N]"
    assert fig_us.axes[-1].get_ylabel() == "link tension [lbf]"
    for a, b in zip(fig_si.axes[:4], fig_us.axes[:4], strict=True):
        for la, lb in zip(a.get_lines(), b.get_lines(), strict=True):
            np.testing.assert_allclose(lb.get_xdata(), np.asarray(la.get_xdata()) * FT,
                                       rtol=1e-12)
        ca, cb = a.collections[0], b.collections[0]
        np.testing.assert_allclose(cb.get_array(), np.asarray(ca.get_array()) * LBF, rtol=1e-12)
        assert cb.get_clim()[1] == pytest.approx(ca.get_clim()[1] * LBF)
    # SI: positions in metres as the result holds them
    roller_x = fig_si.axes[0].get_lines()[-1].get_xdata()
    touching = res.contact_sprocket[0] >= 0
    np.testing.assert_array_equal(roller_x, res.positions[0][touching, 0])


def test_life_curve_take_up_in_inches() -> None:
    states = [SimpleNamespace(elongation=e, f1_hz=20.0, resonance_margin_percent=30.0,
                              coefficient_of_dynamics=1.2, k2=1.1, take_up_travel_mm=t,
                              sag_ratio=0.02)
              for e, t in ((0.0, 0.0), (0.01, 12.0), (0.02, 24.0))]
    life = SimpleNamespace(states=states, allowable_elongation=0.03,
                           first_failure_elongation=None, first_failure=None,
                           take_up_runs_out=None)
    si, us = plotting.life_curve_figure(life).axes, plotting.life_curve_figure(life, units="US").axes
    low_si, low_us = si[2], us[2]  # the third subplot (the twins come after)
    assert low_si.get_ylabel() == "take-up travel [mm]"
    assert low_us.get_ylabel() == "take-up travel [in]"
    np.testing.assert_array_equal(_lines(low_si)[0], [0.0, 12.0, 24.0])
    np.testing.assert_allclose(_lines(low_us)[0], np.array([0.0, 12.0, 24.0]) / 25.4,
                               rtol=1e-12)


def test_us_report_of_the_conveyor_builds() -> None:
    from chaindrive.report import build_report
    from chaindrive.report.content import Plot

    drive = chaindrive.load(EXAMPLES / "conveyor_five_sprocket.toml")
    report = build_report(chaindrive.analyze(drive), units="US")
    plots = [b for s in report.sections for b in s.blocks if isinstance(b, Plot)]
    assert plots
