"""The standard sections of the design report, in order (see :mod:`.content` for the
registry). Each builder returns None when its part of the analysis is absent."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from chaindrive.display import RAD_S_TO_RPM, check_row, fmt
from chaindrive.report.content import (
    Block,
    ReportInput,
    Table,
    Text,
    plot_block,
    register_section,
)
from chaindrive.report.robust import robust_section


def _rows(rows: Sequence[Sequence[Any]]) -> tuple[tuple[Any, ...], ...]:
    return tuple(tuple(r) for r in rows)


# --- checks and warnings -----------------------------------------------------------------

def check_rows(inp: ReportInput) -> list[tuple[str, Any, str, str, str]]:
    """Every check of the analysis as shown: (check, value, required, result, source)."""
    return [check_row(c) for c in inp.analysis.checks()]


def checks_section(inp: ReportInput) -> list[Block]:
    """Warnings of every part and the failed checks, first thing in the report."""
    blocks: list[Block] = []
    warnings = [w["message"] for w in inp.document.get("warnings", [])] + inp.notes
    checks = check_rows(inp)
    failed = [c for c in checks if c[3] != "pass"]
    if not warnings and not failed:
        blocks.append(Text("No warnings; every check passed.", "ok"))
    for c in failed:
        blocks.append(Text(f"{c[3]}: {c[0]} = {fmt(c[1])} (required {c[2]})", "fail"))
    blocks += [Text(w, "warning") for w in warnings]
    if checks:
        blocks.append(Table("Checks", ("check", "value", "required", "result", "source"),
                            _rows(checks),
                            tuple(i for i, c in enumerate(checks) if c[3] != "pass")))
    return blocks


# --- inputs ----------------------------------------------------------------------------------

def inputs_section(inp: ReportInput) -> list[Block]:
    """The design as read (SI converted to engineering units), and the file itself."""
    d = inp.analysis.drive
    spec = d.chain.spec
    rows = [("chain", spec.designation, ""), ("pitch p", spec.pitch * 1e3, "mm"),
            ("strands", spec.strands, ""), ("roller diameter d1", spec.roller_diameter * 1e3, "mm"),
            ("inner width b1", spec.inner_width * 1e3, "mm"),
            ("breaking load Q", spec.breaking_load / 1e3, "kN"),
            ("mass per length q", spec.mass_per_length, "kg/m"),
            ("power P", None if d.power is None else d.power / 1e3, "kW"),
            ("service factor", d.service_factor, ""), ("tooth form", d.tooth_form, "")]
    if d.chain.links is not None:
        rows.append(("links (imposed)", d.chain.links, ""))
    blocks: list[Block] = [Table("Drive and chain", ("quantity", "value", "unit"), _rows(rows))]
    blocks.append(Table(
        "Sprockets as given (positions after the take-up)",
        ("name", "role", "teeth", "x, mm", "y, mm", "side", "speed, rpm", "adjustable",
         "material", "inertia, kg·m²"),
        _rows([(s.name, s.role, s.teeth, s.x * 1e3, s.y * 1e3, s.side,
                None if s.speed is None else s.speed * RAD_S_TO_RPM, s.adjustable, s.material, s.inertia)
               for s in d.sprockets])))
    if inp.source_bytes is not None:
        blocks.append(Text(inp.source_bytes.decode("utf-8", errors="replace"), "code"))
    return blocks


# --- geometry and kinematics -----------------------------------------------------------------

def geometry_section(inp: ReportInput) -> list[Block]:
    """Contour summary, sprockets, spans and the layout to scale."""
    from chaindrive.plotting import contour_layout

    g = inp.document["geometry"]
    summary = [("links", g["links"], ""), ("chain length", g["chain_length_mm"], "mm"),
               ("tight length", g["tight_length_mm"], "mm"),
               ("tight length", g["tight_length_pitches"], "pitches"),
               ("slack", g["slack_mm"], "mm"),
               ("centre distance", g["center_distance_mm"], "mm"),
               ("adjusted sprocket", g["adjusted_sprocket"], ""),
               ("adjustment", g["adjustment_mm"], "mm"),
               ("direction of travel", g["direction_of_travel"], "")]
    return [
        Table("Contour", ("quantity", "value", "unit"), _rows(summary)),
        Table("Sprockets", ("name", "teeth", "side", "x, mm", "y, mm", "pitch Ø, mm",
                            "tip Ø, mm", "root Ø, mm", "wrap, °", "teeth in mesh"),
              _rows([(s["name"], s["teeth"], s["side"], s["x_mm"], s["y_mm"],
                      s["pitch_diameter_mm"], s["tip_diameter_mm"], s["root_diameter_mm"],
                      s["wrap_angle_deg"], s["teeth_in_mesh"]) for s in g["sprockets"]])),
        Table("Spans", ("from", "to", "length, mm", "pitches", "inclination, °", "tight"),
              _rows([(s["from"], s["to"], s["length_mm"], s["length_pitches"],
                      s["inclination_deg"], s["tight"]) for s in g["spans"]])),
        plot_block(contour_layout(inp.analysis.geometry), "Contour layout to scale",
                   inp.dpi, "layout"),
    ]


def kinematics_section(inp: ReportInput) -> list[Block]:
    """Speeds and the polygonal non-uniformity (seed 003)."""
    from chaindrive.plotting import chain_speed, transmission_ratio

    k = inp.document["kinematics"]
    return [
        Table("Chain", ("quantity", "value", "unit"), _rows([
            ("mean chain speed", k["chain_speed_m_s"], "m/s"),
            ("minimum / maximum", f"{k['chain_speed_min_m_s']:.4g} / "
                                  f"{k['chain_speed_max_m_s']:.4g}", "m/s"),
            ("tooth frequency", k["tooth_frequency_hz"], "Hz")])),
        Table("Sprocket speeds", ("name", "speed, rpm", "direction", "speed variation, %",
                                  "hinge deviation peak, mm"),
              _rows([(s["name"], s["speed_rpm"], s["direction"], s["speed_variation_percent"],
                      s["hinge_deviation_peak_mm"]) for s in k["sprockets"]])),
        plot_block(chain_speed(inp.analysis.kinematics), "Chain speed over one tooth period",
                   inp.dpi, "chain_speed"),
        plot_block(transmission_ratio(inp.analysis), "Instantaneous transmission ratio",
                   inp.dpi, "ratio"),
    ]


# --- selection and strength -------------------------------------------------------------------

def selection_section(inp: ReportInput) -> list[Block] | None:
    """The chain a method of the family selects, with the ranked candidates."""
    sel = inp.document.get("selection")
    if sel is None:
        return None
    cands = sel["candidates"][:10]
    head = (f"Selected ({sel['method']}): {sel['chain']}." if sel["chain"] is not None
            else f"{sel['shortfall']}.")
    return [Text(f"{head} The analysis uses the design chain "
                 f"{inp.analysis.drive.chain.spec.designation} (a design that names its chain keeps it)."),
            Table("Candidates (best 10, ranked)", ("chain", "method", "strands", "mass, kg/m",
                                                   "passed", "margin, %", "governing"),
                  _rows([(c["chain"], c["method"], c["strands"], c["mass_kg_m"], c["passed"],
                          None if c["margin_fraction"] is None else 100 * c["margin_fraction"],
                          c["governing"]) for c in cands]))]


def strength_section(inp: ReportInput) -> list[Block] | None:
    """Loads round the contour and static strength."""
    from chaindrive.plotting import shaft_loads, span_tensions

    st = inp.document.get("strength")
    if st is None:
        return None
    rows = [("chain speed v", st["chain_speed_m_s"], "m/s"),
            ("peripheral force F_t", st["peripheral_force_n"], "N"),
            ("sag tension F_0", st["sag_tension_n"], "N"),
            ("centrifugal tension F_v", st["centrifugal_tension_n"], "N"),
            ("operating factor Kэ", st["operating_factor_ke"], ""),
            ("hinge pressure p", st["hinge_pressure_mpa"], "MPa"),
            ("allowable pressure [p]", st["allowable_pressure_mpa"], "MPa"),
            ("static safety factor s", st["safety_factor_static"], ""),
            ("allowable safety factor [s]", st["allowable_safety_factor"], ""),
            (f"rated power ({st.get('rating_method') or 'ACA'})", None if st["rated_power_w"] is None
             else st["rated_power_w"] / 1e3, "kW"),
            ("wear life to {:.0%} elongation{}".format(
                st["permitted_elongation"],
                " (extrapolated: wear does not limit)" if st["wear_life_extrapolated"] else ""),
             st["wear_life_h"], "h")]
    names = [s.name for s in inp.analysis.drive.sprockets]
    spans = [f"{s.start_name}→{s.end_name}" for s in inp.analysis.geometry.spans]
    return [
        Table("Loads and strength", ("quantity", "value", "unit"), _rows(rows)),
        Table("Span tensions and shaft loads", ("span", "tension, N", "sprocket",
                                                "shaft load, N"),
              _rows([(sp, t, n, f) for sp, t, n, f in zip(
                  spans, st["span_tensions_n"], names, st["shaft_loads_n"], strict=True)])),
        plot_block(span_tensions(inp.analysis), "Static tension per span", inp.dpi, "tensions"),
        plot_block(shaft_loads(inp.analysis), "Load per shaft", inp.dpi, "shaft_loads"),
    ]


# --- dynamics --------------------------------------------------------------------------------

def dynamics_section(inp: ReportInput) -> list[Block] | None:
    """Natural frequencies, mode shapes, resonance table and Campbell diagram (seed 000)."""
    from chaindrive.plotting import campbell_diagram, mode_shapes

    dyn = inp.dynamics
    modal = dyn.modal
    names = [s.name for s in inp.analysis.drive.sprockets]
    blocks: list[Block] = [
        Text(f"Ring model of {len(names)} reduced masses (seed 000), damping ratio "
             f"ζ = {dyn.damping_ratio:g}. Mode 0 is the rigid-body rotation of the contour."),
        Table("Masses and branches", ("sprocket", "reduced mass, kg",
                                      "branch stiffness to next, N/m"),
              _rows(zip(names, modal.masses_kg.tolist(), modal.stiffness_n_per_m.tolist(),
                        strict=True))),
        Table("Natural frequencies", ("mode", "f, Hz", "damped f, Hz", "rigid body"),
              _rows([(j, f, fd, bool(rb)) for j, (f, fd, rb) in enumerate(zip(
                  modal.frequencies_hz, modal.damped_frequencies_hz, modal.rigid_body,
                  strict=True))])),
        plot_block(mode_shapes(modal, names=names), "Mode shapes (relative amplitudes)",
                   inp.dpi, "mode_shapes"),
    ]
    if dyn.resonances:
        band = inp.analysis.limits.resonance_band_percent
        rows = [(r.working.label, r.working.frequency, r.natural_frequency, r.mode,
                 r.margin_percent) for r in dyn.resonances]
        blocks.append(Table("Resonance table (closest first)",
                            ("working frequency", "f, Hz", "natural f, Hz", "mode", "margin, %"),
                            _rows(rows), tuple(i for i, r in enumerate(dyn.resonances)
                                               if abs(r.margin_percent) < band)))
    if dyn.campbell is not None:
        w = inp.analysis.drive.driver.speed
        blocks.append(plot_block(campbell_diagram(dyn.campbell,
                                                  operating_rpm=None if w is None else w * RAD_S_TO_RPM),
                                 "Campbell diagram", inp.dpi, "campbell"))
    return blocks


def _k_rows(response: Any) -> list[tuple[str, Any, str, str]]:
    """The two-stage check k1, k2, k2min against [k] (seed 000 §3.6)."""
    k = response.strength_dict()
    return [(name, k[key], f"≥ {response.allowable_k:g}",
             "—" if k[key] is None else "pass" if k[key] >= response.allowable_k else "FAIL")
            for name, key in (("start-up k1 = Q/F1max", "k1"), ("steady k2 = Q/(F_R + F2)", "k2"),
                              ("at resonance k2min = Q/(F_R + F2max)", "k2min"))]


def _dynamic_load_rows(inp: ReportInput, response: Any) -> list[tuple[str, Any, str]]:
    """K_D, F_D, F_t and the start-up summary."""
    steady, startup = response.steady, response.startup
    st = inp.document.get("strength") or {}
    rows: list[tuple[str, Any, str]] = [
        ("coefficient of dynamics K_D = 1 + F_D/F_t", steady.coefficient_of_dynamics, ""),
        ("dynamic load F_D (RMS of the span peaks)", steady.dynamic_load_rms, "N"),
        ("peripheral force F_t", st.get("peripheral_force_n"), "N"),
        ("tooth frequency", steady.tooth_angular_frequency / (2 * math.pi), "Hz")]
    if startup is not None:
        rows += [("start-up peak F1max", float(startup.max_span_force.max()), "N"),
                 ("settling time", startup.settling_time * 1e3, "ms"),
                 ("start-up record", float(startup.times[-1]) * 1e3, "ms")]
    return rows


def _span_table(spans: list[str], response: Any) -> Table:
    """Per span: static tension, steady dynamic load, start-up and resonance peaks, and the
    loads of the optional disturbances."""
    n = len(spans)
    startup = response.startup
    cols: list[tuple[str, Sequence[Any]]] = [
        ("static F_R, N", response.span_tensions.tolist()),
        ("steady peak F2, N", response.steady.span_dynamic_load.tolist()),
        ("steady amplitude, N", response.steady.span_load_amplitude.tolist()),
        ("start-up F1max, N", [None] * n if startup is None else startup.max_span_force.tolist()),
        ("F2max over the AFC sweep, N", response.afc.max_span_load.tolist())]
    cols += [(f"{name.replace('_', ' ')}, N", r.span_dynamic_load.tolist())
             for name, r in response.disturbances.items()]
    return Table("Dynamic loads per span", ("span", *(c for c, _ in cols)),
                 _rows(zip(spans, *(v for _, v in cols), strict=True)))


def _material_blocks(inp: ReportInput) -> list[Block]:
    """The four material pairs ([MultimassChainDrives], Fig. 2–3, Table 1), when the analysis
    ran that study."""
    from chaindrive.plotting import material_comparison_chart

    cases = inp.analysis.material_pairs
    if not cases:
        return []
    return [
        Text("The same layout with metal or polymer chain on metal or polymer sprockets "
             "([MultimassChainDrives], Fig. 2–3, Table 1): ring model rebuilt per pair, "
             "start-up over 0.3 s, first resonance from a sweep through the first natural "
             "frequency.", "note"),
        Table("Material pairs", ("chain", "sprockets", "start-up peak, N", "first f, Hz",
                                 "resonance f_z, Hz", "resonance amplitude, N"),
              _rows([(c.chain_material, c.sprocket_material, c.startup_peak_n,
                      c.first_natural_frequency_hz, c.resonance_tooth_frequency_hz,
                      c.resonance_amplitude_n) for c in cases])),
        plot_block(material_comparison_chart(cases), "Material pairs: start-up peak and first "
                   "resonance", inp.dpi, "materials"),
    ]


def response_section(inp: ReportInput) -> list[Block] | None:
    """The dynamic response (Dynamics II, seed 000 §3.1–3.3, §3.6): the two-stage check,
    K_D, the loads per span and per mass, the start-up oscillograms, the AFC and the
    material pairs."""
    from chaindrive.plotting import (
        afc_curves,
        inertia_and_irregularity,
        startup_oscillogram,
        startup_speeds,
        steady_loads,
    )

    response = inp.analysis.response
    if response is None:
        return None
    sprockets = [s.name for s in inp.analysis.drive.sprockets]
    spans = [f"{s.start_name}→{s.end_name}" for s in inp.analysis.geometry.spans]
    steady, startup = response.steady, response.startup
    k_rows = _k_rows(response)
    blocks: list[Block] = [
        Text("Kinematic excitation by the polygonal effect at the tooth frequency and its "
             "harmonics, solved in the frequency domain; start-up from rest with the motor law "
             "of the design ([dynamics]); spans carry tension only (seed 000, docs/dynamics2.md)."),
        Table("Two-stage safety check (seed 000 §3.6)", ("check", "value", "required", "result"),
              _rows(k_rows), tuple(i for i, r in enumerate(k_rows) if r[3] == "FAIL")),
        Table("Dynamic loads", ("quantity", "value", "unit"),
              _rows(_dynamic_load_rows(inp, response))),
        _span_table(spans, response),
    ]
    if startup is not None:
        blocks += [plot_block(startup_oscillogram(startup, names=spans),
                              "Start-up oscillogram: span forces", inp.dpi, "startup"),
                   plot_block(startup_speeds(startup, names=sprockets),
                              "Start-up: sprocket speeds", inp.dpi, "startup_speeds")]
    blocks += [
        plot_block(afc_curves(response.afc, names=spans, operating_hz=steady
                              .tooth_angular_frequency / (2 * math.pi)),
                   "Amplitude–frequency characteristic per span", inp.dpi, "afc"),
        plot_block(steady_loads(steady, names=spans), "Steady dynamic load per span", inp.dpi,
                   "steady_loads"),
        Table("Steady motion per mass", ("sprocket", "inertia load m·ẍ, N",
                                         "displacement amplitude, mm", "irregularity Δ, %"),
              _rows(zip(sprockets, steady.inertia_load.tolist(),
                        (steady.displacement_amplitude * 1e3).tolist(),
                        steady.irregularity_percent.tolist(), strict=True))),
        plot_block(inertia_and_irregularity(steady, names=sprockets),
                   "Inertia load and irregularity per mass", inp.dpi, "inertia"),
    ]
    return blocks + _material_blocks(inp)


def damping_section(inp: ReportInput) -> list[Block] | None:
    """The hinge-friction damping model [ChainHingeDissipation] for its reference chain, when
    the analysis ran that study."""
    from chaindrive.plotting import absorption_vs_amplitude

    results = inp.analysis.hinge_friction
    if not results:
        return None
    a = results[0].span_length
    return [Text(f"The dynamics uses a damping ratio; the hinge-friction model gives ψ "
                 f"(ζ = ψ/4π) from a chain's empirical coefficients, known only for the "
                 f"reference chain of [ChainHingeDissipation]. The curves are for that chain "
                 f"at the paper's conditions (span of 49 hinges, a = {a * 1e3:.0f} mm).", "note"),
            plot_block(absorption_vs_amplitude(list(results)),
                       "Absorption coefficient ψ against ȳ₀", inp.dpi, "damping")]


def contours_section(inp: ReportInput) -> list[Block] | None:
    """Multi-contour drives: the contour check of seed 004 (K_m), as a table of its values."""
    part = inp.analysis.contours
    if part is None:
        return None
    flat = [(k, v) for k, v in part.to_dict().items() if not isinstance(v, dict | list)]
    return [Table("Parallel contours (seed 004)", ("quantity", "value"), _rows(flat))]


def synthesis_section(inp: ReportInput) -> list[Block] | None:
    """The optimisation that chose this design (issue 8): the Pareto set and its front."""
    from chaindrive.plotting import pareto_front

    result = inp.synthesis
    if result is None:
        return None
    names = list(result.objectives)
    rows = [("start", *[result.start.objectives.get(n) for n in names], result.start.feasible)]
    rows += [(str(k), *[p.objectives[n] for n in names], p.constraints_ok)
             for k, p in enumerate(result.pareto, start=1)]
    return [
        Text(f"{result.evaluations} designs evaluated by {result.method} (seed {result.seed}); "
             f"this report is of Pareto design 1."),
        Table("Pareto set", ("design", *names, "constraints ok"), _rows(rows)),
        plot_block(pareto_front(result), "Pareto front", inp.dpi, "pareto_front"),
    ]


def register_standard_sections() -> None:
    """Register the standard sections in report order (idempotent)."""
    for key, title, build in (
            ("checks", "Warnings and checks", checks_section),
            ("inputs", "Inputs", inputs_section),
            ("geometry", "Contour geometry", geometry_section),
            ("kinematics", "Kinematics", kinematics_section),
            ("selection", "Chain selection", selection_section),
            ("strength", "Loads and strength", strength_section),
            ("contours", "Parallel contours", contours_section),
            ("dynamics", "Dynamics", dynamics_section),
            ("response", "Dynamic response", response_section),
            ("damping", "Damping", damping_section),
            ("synthesis", "Optimal synthesis", synthesis_section),
            ("robust", "Life and reliability", robust_section)):
        register_section(key, title, build)
