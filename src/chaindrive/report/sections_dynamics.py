"""The dynamics sections of the design report: vibration of the contour (ring model, modes,
resonances of the ring and of the spans, Campbell diagram), the dynamic response (two-stage
check k₁, k₂, k₂min; K_D; loads per span and per mass), the comparative studies (only when
the analysis ran them) and the optimal synthesis. Each reads the analysis only."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.display import (
    check_row,
    constraint_row,
    quantity_text,
    show,
    static_state_note,
    unit_header,
)
from chaindrive.plotting import (
    absorption_vs_amplitude,
    afc_curves,
    campbell_diagram,
    chain_frames,
    frame_times,
    inertia_and_irregularity,
    material_comparison_chart,
    mode_shapes,
    pareto_front,
    startup_oscillogram,
    startup_speeds,
    steady_loads,
    tension_along_chain,
    tooth_loads,
)
from chaindrive.report.content import (
    Block,
    ReportInput,
    Table,
    Text,
    plot_block,
    rows,
)


def _span_names(inp: ReportInput) -> list[str]:
    return [f"{s.start_name}→{s.end_name}" for s in inp.analysis.geometry.spans]


def _elastic_modes(inp: ReportInput) -> list[int]:
    """The numbers of the elastic modes in the tables (their indices among all the modes,
    the rigid rotation 0): the numbers the figures give them too."""
    modal = inp.analysis.dynamics.modal
    return [j for j in range(len(modal.frequencies_hz)) if not modal.rigid_body[j]]


@shared_parameters
def tooth_harmonics(inp: ReportInput) -> str:
    """The harmonics of the tooth frequency among the working frequencies of the resonance
    table, as the analysis lists them ("1–3"; "" when it lists none).

    %(params_inp)s

    Returns
    -------
    str
        "1–3", "1" or "".
    """
    ks = sorted({w.harmonic for w in inp.analysis.dynamics.working if w.kind == "tooth"})
    if not ks:
        return ""
    if len(ks) > 1 and ks == list(range(ks[0], ks[-1] + 1)):
        return f"{ks[0]}–{ks[-1]}"
    return ", ".join(str(k) for k in ks)


@shared_parameters
def resonance_rows(inp: ReportInput, kind: str) -> tuple[list[tuple[Any, ...]], tuple[int, ...]]:
    """Rows of the resonance table of the ring modes (``kind`` "ring") or of the spans'
    parametric resonances ("span"): working frequency, f_w, natural frequency, mode or span,
    detuning Δ ≥ 0, below/above; and the rows inside the band (highlighted).

    %(params_inp)s
    kind : str
        "ring" (the ring modes) or "span" (the spans' parametric resonances).

    Returns
    -------
    tuple of (list of tuple, tuple of int)
        The rows (frequencies in Hz, detuning in %) and the indices of the rows inside the
        band.
    """
    dyn = inp.analysis.dynamics
    band = inp.analysis.limits.resonance_band_percent
    spans = _span_names(inp)
    out: list[tuple[Any, ...]] = []
    inside: list[int] = []
    for r in dyn.resonances:
        parametric = r.working.kind == "parametric"
        if parametric != (kind == "span"):
            continue
        where = (spans[r.mode] if parametric and r.mode < len(spans)
                 else f"mode {r.mode}")
        label = (f"f_z vs 2·f_ℓ of span {where}" if parametric else r.working.label)
        if r.detuning_percent < band:
            inside.append(len(out))
        out.append((label, r.working.frequency, r.natural_frequency, where,
                    r.detuning_percent, r.side))
    return out, tuple(inside)


@shared_parameters
def dynamics_section(inp: ReportInput) -> list[Block] | None:
    """The ring model [MultimassChainDrives, §3.1–3.3]: masses and branches, natural
    frequencies, signed mode shapes along the contour, the resonance tables of the ring and
    of the spans, and the Campbell diagram zoomed to the crossings near the working speed.

    %(section)s
    """

    a = inp.analysis
    dyn = a.dynamics
    modal = dyn.modal
    names = [s.name for s in a.drive.sprockets]
    band = a.limits.resonance_band_percent
    blocks: list[Block] = inp.define("m_i", "c_i", "fj", "X", "mu", "fw", "detuning")
    model = a.drive_model
    blocks.append(Text(
        f"The whole drive is one torsional model: the contour's {len(names)} sprockets, each "
        "with the links wrapped on it, joined by the spans (each span's chain mass "
        "distributed consistently on its two ends), and the open train on every shaft (motor, "
        f"couplings, reducers, machines); {model.linear.size} degrees of freedom. Damping "
        f"ratio ζ = {dyn.damping_ratio:.3g} ({model.damping_source}): the chain's dampers are "
        "proportional to its stiffness, so the reference mode (the first in which the chain "
        "holds most of the strain energy) has ζ, and a mode of frequency f_j about ζ·f_j/f_ref "
        "times the chain's share of its strain energy: the stiff higher modes are heavily "
        "damped or overdamped (their damped frequencies in the table). Mode 0 is the rigid "
        "rotation of the whole drive (0 Hz)."))
    if not model.complete:
        blocks.append(Text("INCOMPLETE MODEL: " + "; ".join(model.missing) + ". Its natural "
                           "frequencies are upper bounds and its start-up is not meaningful.",
                           "note"))
    blocks.append(Table("Masses and branches", ("sprocket", inp.col("m_i", "mass"),
                                                inp.col("c_i to the next", "stiffness")),
                        rows([(n, inp.val(m, "mass"), inp.val(c, "stiffness")) for n, m, c in
                              zip(names, modal.masses_kg.tolist(),
                                  modal.stiffness_n_per_m.tolist(), strict=True)])))
    elastic = _elastic_modes(inp)
    blocks.append(Table("Natural frequencies of the ring", ("mode j", "f_j, Hz",
                                                            "damped, Hz", "largest μ at"),
                        rows([(j, modal.frequencies_hz[j],
                               modal.damped_frequencies_hz[j]
                               if modal.damped_frequencies_hz[j] > 0 else "overdamped",
                               names[int(modal.normalized_amplitudes[:, j].argmax())])
                              for j in elastic])))
    blocks.append(plot_block(mode_shapes(modal, names=names),
                             "Mode shapes X^(j) along the contour, signed (a node where a "
                             "line crosses zero; the first mass is repeated to close the "
                             "ring)", inp.dpi, "mode_shapes"))
    ring, inside = resonance_rows(inp, "ring")
    harmonics = tooth_harmonics(inp)
    if harmonics:
        blocks.append(Text(
            f"The resonance check covers the shaft frequencies and the harmonics {harmonics} "
            f"of the tooth frequency; the {a.drive.dynamics.harmonics} harmonics of the tooth "
            "frequency in the Dynamics settings are those of the polygonal excitation of the "
            "steady response and of the amplitude–frequency sweep."))
    if ring:
        blocks.append(Table(f"Resonances of the ring: every working frequency (shaft "
                            f"frequencies{f', tooth harmonics {harmonics}' if harmonics else ''}"
                            f") against the nearest natural frequency (required Δ ≥ {band:g} %)",
                            ("working frequency", "f_w, Hz", "f_n, Hz", "ring mode",
                             "detuning Δ, %", "f_w is"), rows(ring), inside))
    span, inside = resonance_rows(inp, "span")
    if span:
        blocks += inp.define("fspan")
        blocks.append(Table(f"Parametric resonances of the spans: tooth frequency against "
                            f"twice the span's transverse frequency (required Δ ≥ {band:g} %)",
                            ("working frequency", "f_z, Hz", "2·f_ℓ, Hz", "span",
                             "detuning Δ, %", "f_z is"), rows(span), inside))
    if a.published is not None:
        source, printed = a.published
        blocks += inp.define("FD", "KD", "F1max")
        blocks.append(Table(f"Beside the published figures of this example ({source})",
                            ("quantity", "published", "this analysis", "unit"), rows(printed)))
    if dyn.campbell is not None and a.drive.driver.speed is not None:
        rpm = float(inp.val(a.drive.driver.speed, "speed") or 0.0)
        blocks.append(plot_block(
            campbell_diagram(dyn.campbell, operating_rpm=rpm, band_percent=band,
                             mode_numbers=elastic, span_names=_span_names(inp)),
            f"Campbell diagram: natural frequencies (black), working frequencies against the "
            f"driver speed (dashed; tooth harmonics {harmonics or '—'}), the band ±{band:g} % "
            "round the working speed (shaded) and the crossings (circles; those near the "
            "working speed numbered and named in the legend, modes numbered as in the "
            "tables)", inp.dpi, "campbell"))
    return blocks


def _k_rows(inp: ReportInput) -> list[tuple[str, str, Any, str, Any, str]]:
    """The two-stage check k₁, k₂, k₂min against [k] with its margin."""
    response = inp.analysis.response
    assert response is not None
    k = response.strength_dict()
    allow = response.allowable_k
    out = []
    for name, sym, key in (("start-up", "k₁", "k1"), ("steady motion", "k₂", "k2"),
                           ("resonance in the run-up", "k₂min", "k2min")):
        value = k[key]
        margin = None if value is None else 100 * (value / allow - 1)
        result = "—" if value is None else "pass" if value >= allow else "FAIL"
        out.append((name, sym, value, f"≥ {allow:g}", margin, result))
    return out


@shared_parameters
def response_section(inp: ReportInput) -> list[Block] | None:
    """The dynamic response [MultimassChainDrives, §3.3, §3.6]: the two-stage check, K_D,
    the loads per span and per mass, the start-up, the AFC.

    %(section)s
    """

    a = inp.analysis
    response = a.response
    if response is None:
        return None
    sprockets = [s.name for s in a.drive.sprockets]
    spans = _span_names(inp)
    steady, startup = response.steady, response.startup
    blocks: list[Block] = inp.define("F2", "F2max", "F1max", "FD", "KD", "k1", "k2", "k2min",
                                     "k_allow", "irr")
    blocks.append(Text(
        "Kinematic excitation by the polygonal effect at the tooth frequency and its "
        f"{a.drive.dynamics.harmonics} harmonics, solved in the frequency domain; start-up "
        f"from rest with the {a.drive.dynamics.motor} motor law on the motor's rotor and the "
        "machines' load laws on theirs; the spans carry tension only "
        "[MultimassChainDrives, §3.3]."))
    k_rows = _k_rows(inp)
    blocks.append(Table("Two-stage safety check [MultimassChainDrives, §3.6]",
                        ("stage", "factor", "value", "required", "margin, %", "result"),
                        rows(k_rows), tuple(i for i, r in enumerate(k_rows) if r[5] == "FAIL")))
    F = inp.unit("force")
    load_rows: list[tuple[str, str, Any, str]] = [
        ("coefficient of dynamics", "K_D", steady.coefficient_of_dynamics, ""),
        ("dynamic load", "F_D", inp.val(steady.dynamic_load_rms, "force"), F),
        ("peripheral force at the driver's pitch circle (K_D = 1 + F_D/F_t)", "F_t",
         None if steady.nominal_force is None else inp.val(steady.nominal_force, "force"), F),
        ("tooth frequency", "f_z", steady.tooth_frequency_hz, "Hz")]
    if startup is not None:
        load_rows += [("largest start-up force", "F₁max",
                       inp.val(float(startup.max_span_force.max()), "force"), F),
                      ("run-up time (driver at 95 % of its working speed)", "",
                       None if math.isnan(startup.runup_time) else startup.runup_time * 1e3,
                       "ms"),
                      ("decay of the transient after the run-up", "",
                       None if math.isnan(startup.decay_time) else startup.decay_time * 1e3,
                       "ms"),
                      ("settling time (run-up and decay)", "",
                       *(("not within the simulated time", "")
                         if math.isnan(startup.settling_time)
                         else (startup.settling_time * 1e3, "ms"))),
                      ("samples with a slack span", "", 100.0 * startup.slack_fraction, "%"),
                      ("start-up simulated", "", float(startup.times[-1]) * 1e3, "ms")]
    blocks.append(Table("Dynamic loads", ("quantity", "symbol", "value", "unit"),
                        rows(load_rows)))
    blocks.append(_span_table(inp, spans))
    if startup is not None:
        blocks += [plot_block(startup_oscillogram(startup, names=spans, units=inp.units),
                              "Start-up: span forces", inp.dpi, "startup"),
                   plot_block(startup_speeds(startup, names=sprockets),
                              "Start-up: sprocket speeds", inp.dpi, "startup_speeds")]
    blocks += [
        plot_block(afc_curves(response.afc, names=spans,
                              operating_hz=steady.tooth_frequency_hz,
                              mode_numbers=_elastic_modes(inp), units=inp.units),
                   "Amplitude–frequency characteristic per span (speed sweep); above the "
                   "plot the resonances, mode × harmonic of the tooth frequency (modes "
                   "numbered as in the tables)", inp.dpi, "afc"),
        plot_block(steady_loads(steady, names=spans, units=inp.units), "Steady dynamic load per span",
                   inp.dpi, "steady_loads"),
        Table("Steady motion per mass", ("sprocket", inp.col("inertia load m·ẍ", "force"),
                                         inp.col("displacement amplitude x_A", "length"),
                                         "irregularity Δ_ω, %"),
              rows(zip(sprockets, [inp.val(v, "force") for v in steady.inertia_load.tolist()],
                       [inp.val(v, "length") for v in steady.displacement_amplitude.tolist()],
                       steady.irregularity_percent.tolist(), strict=True))),
        plot_block(inertia_and_irregularity(steady, names=sprockets, units=inp.units),
                   "Inertia load and irregularity per mass", inp.dpi, "inertia"),
    ]
    return blocks


def _span_table(inp: ReportInput, spans: list[str]) -> Table:
    """Per span: static tension, steady peak and amplitude, start-up and run-up peaks and
    the loads of the optional disturbances."""
    response = inp.analysis.response
    assert response is not None
    n = len(spans)
    startup = response.startup

    def forces(values: Sequence[Any]) -> list[Any]:
        return [inp.val(v, "force") for v in values]

    cols: list[tuple[str, Sequence[Any]]] = [
        (inp.col("F_R", "force"), forces(response.span_tensions.tolist())),
        (inp.col("F₂", "force"), forces(response.steady.span_dynamic_load.tolist())),
        (inp.col("amplitude", "force"), forces(response.steady.span_load_amplitude.tolist())),
        (inp.col("F₁max", "force"), [None] * n if startup is None
         else forces(startup.max_span_force.tolist())),
        (inp.col("F₂max", "force"), forces(response.afc.max_span_load.tolist()))]
    cols += [(inp.col(name.replace("_", " "), "force"), forces(r.span_dynamic_load.tolist()))
             for name, r in response.disturbances.items()]
    return Table("Dynamic loads per span", ("span", *(c for c, _ in cols)),
                 rows(zip(spans, *(v for _, v in cols), strict=True)))


@shared_parameters
def materials_section(inp: ReportInput) -> list[Block] | None:
    """The four chain/sprocket material pairs on this layout ([MultimassChainDrives], Fig.
    2–3, Table 1), only when the analysis ran that study.

    %(section)s
    """

    cases = inp.analysis.material_pairs
    if not cases:
        return None
    return [
        Text("Asked for (--study material-pairs): the same layout with metal or polymer chain "
             "on metal or polymer sprockets ([MultimassChainDrives], Fig. 2–3, Table 1); the "
             "ring model rebuilt per pair, start-up over 0.3 s, first resonance from a sweep "
             "through the first natural frequency.", "note"),
        Table("Material pairs", ("chain", "sprockets", inp.col("start-up peak", "force"),
                                 "first f_j, Hz", "resonance f_z, Hz",
                                 inp.col("resonance amplitude", "force")),
              rows([(c.chain_material, c.sprocket_material, inp.val(c.startup_peak_n, "force"),
                     c.first_natural_frequency_hz, c.resonance_tooth_frequency_hz,
                     inp.val(c.resonance_amplitude_n, "force")) for c in cases])),
        plot_block(material_comparison_chart(cases, units=inp.units), "Material pairs: start-up peak and "
                   "first resonance", inp.dpi, "materials"),
    ]


@shared_parameters
def damping_section(inp: ReportInput) -> list[Block] | None:
    """The hinge-friction damping model [ChainHingeDissipation] for its reference chain,
    only when the analysis ran that study.

    %(section)s
    """

    results = inp.analysis.hinge_friction
    if not results:
        return None
    a = results[0].span_length
    span = f"{a * 1e3:.0f} mm" if inp.units == "SI" else show(a, "length", inp.units, 3)
    return [*inp.define("psi"),
            Text("Asked for (--study hinge-friction): the dynamics of this report uses the "
                 "damping ratio ζ; the hinge-friction model gives ψ from a chain's empirical "
                 "coefficients, known only for the reference chain of "
                 "[ChainHingeDissipation] (GOST ПР-12,7). The curves are for that chain at "
                 f"the paper's conditions (span of 49 hinges, a = {span}), not for "
                 "the chain of this drive.", "note"),
            plot_block(absorption_vs_amplitude(list(results), units=inp.units),
                       "Absorption coefficient ψ against the amplitude ȳ₀ (reference chain)",
                       inp.dpi, "damping")]


def _comparison_rows(inp: ReportInput) -> list[tuple[Any, ...]]:
    """The rows of the analysis' model comparison in the report's unit system."""
    comparison = inp.analysis.link_level_comparison
    assert comparison is not None
    out: list[tuple[Any, ...]] = []
    names = {"whole_drive": "whole drive", "link_level": "link level", None: ""}
    for (quantity, ring, link, unit), gov in zip(comparison.rows, comparison.governing,
                                                 strict=True):
        if unit == "N":
            out.append((quantity, inp.val(ring, "force"), inp.val(link, "force"),
                        inp.unit("force"), names[gov]))
        else:
            out.append((quantity, ring, link, "" if unit == "1" else unit, names[gov]))
    return out


def _governed_rows(inp: ReportInput) -> list[tuple[Any, ...]]:
    """(check, subject, value, governing model, its note) of every check that took its load
    from one of the two models (:attr:`chaindrive.checks.Check.governing_model`)."""
    names = {"whole_drive": "whole-drive model", "link_level": "link-level model"}
    out: list[tuple[Any, ...]] = []
    for c in inp.analysis.checks():
        if c.governing_model is None:
            continue
        _, value, _, _, _ = check_row(c, inp.units)
        out.append((c.name, c.subject, value, names[c.governing_model],
                    quantity_text(c.note, c.note_quantities, inp.units)))
    return out


@shared_parameters
def links_section(inp: ReportInput) -> list[Block] | None:
    """The link-level model of the drive beside the whole-drive model ([Pedersen2004],
    [Pedersen2005]), only when the analysis ran that study: the table of the quantities
    both give, frames of the chain, link tension along it and the tooth loads.

    %(section)s
    """

    a = inp.analysis
    result, comparison = a.link_level, a.link_level_comparison
    if result is None or comparison is None:
        return None
    blocks: list[Block] = inp.define("F2", "F1max", "FD", "KD")
    blocks.append(Text(
        "Asked for (--study links): the chain resolved link by link — every roller a "
        "particle of one pitch of chain, every link a spring–damper with hinge friction "
        "[ChainHingeDissipation], every roller in contact with the tooth gap of the sprocket "
        "it runs on ([Pedersen2004], [Pedersen2005]), the sprockets rigid bodies under the "
        f"motor law and the machines' loads. A start-up from rest over "
        f"{comparison.duration_s:.3g} s (step {result.dt * 1e6:.3g} µs); the steady "
        f"quantities are taken over its closing half, from t = {comparison.steady_from_s:.3g} "
        "s, the start-up peaks over the whole run.", "note"))
    stopped = static_state_note(result.equilibrium, inp.units)
    if stopped is not None:
        blocks.append(Text(stopped, "warning"))
    if not comparison.settled:
        blocks.append(Text(
            "The driver had not reached its nominal speed by then: the link-level steady "
            "quantities still hold the start-up. A longer run (chaindrive simulate --model "
            "links --duration) gives the steady ones.", "warning"))
    blocks.append(Table("Whole-drive model beside the link-level model",
                        ("quantity", "whole drive", "link level", "unit", "governs"),
                        rows(_comparison_rows(inp))))
    blocks.append(Text(
        "Where the two differ: the link-level model carries the roller–tooth engagement "
        "impacts and the chain's own mass moving along the spans, which the whole-drive "
        "model's smooth polygonal excitation leaves out; its steady dynamic loads are then "
        "the larger [BinderCovert1948]. Of each load the larger governs (column 'governs'), "
        "and the verdict's checks that rest on a dynamic load take it (the table below), "
        "except where the link-level model's load is not comparable. Its first natural "
        "frequency is the first mode along the chain of its linearisation about the static "
        "state; where it differs from the whole-drive model's, docs/linklevel.md §6 says "
        "which is right. Its impact forces rest on an estimated roller–tooth "
        "stiffness (ISO 6336-1 gear value [ISO6336-1])."))
    governed = _governed_rows(inp)
    if governed:
        blocks.append(Table("Which model's load each check takes",
                            ("check", "subject", "value", "governs", "why"), rows(governed)))
    times = frame_times(result)
    blocks += [
        plot_block(chain_frames(result, times, units=inp.units), "The chain at four instants of the run, "
                   "links coloured by tension (rollers in contact with a tooth filled)",
                   inp.dpi, "link_frames"),
        plot_block(tension_along_chain(result, times, units=inp.units), "Link tension along the chain at the "
                   "same instants", inp.dpi, "link_tensions"),
        plot_block(tooth_loads(result, units=inp.units), "Mean tooth load at each place of every wrap over "
                   "the closing half of the run", inp.dpi, "tooth_loads"),
    ]
    return blocks


@shared_parameters
def synthesis_section(inp: ReportInput) -> list[Block] | None:
    """The optimisation that chose this design: the Pareto set and its front, and why
    designs were rejected.

    %(section)s
    """

    result = inp.synthesis
    if result is None:
        return None
    names = list(result.objectives)
    table_rows = [("start", *[result.start.objectives.get(n) for n in names],
                   result.start.feasible)]
    table_rows += [(str(k), *[p.objectives[n] for n in names], p.constraints_ok)
                   for k, p in enumerate(result.pareto, start=1)]
    blocks: list[Block] = [
        Text(f"{result.evaluations} designs evaluated by {result.method} (random seed "
             f"{result.seed}); {result.feasible_in_search} met every constraint of the "
             f"search, {result.verified} of them were judged as analyze judges their design "
             f"file (every check, the start-up included) and {result.verified_passed} passed; "
             "this report is of Pareto design 1."),
        Table("Pareto set", ("design", *(unit_header(n, u) for n, u in zip(
            names, result.units or ("",) * len(names), strict=True)), "constraints met"),
              rows(table_rows)),
    ]
    report = [c for c in result.constraint_report if c.rejected]
    if report:
        blocks.append(Table("Constraints: the designs each rejected and by how much the "
                            "closest of them missed",
                            ("constraint", "rejected", "of", "closest miss", "closest design"),
                            rows([constraint_row(c) for c in report])))
    if result.verification_report:
        blocks.append(Table("Why designs the search found feasible failed their analysis",
                            ("constraint", "rejected", "of", "closest miss", "closest design"),
                            rows([constraint_row(c) for c in result.verification_report])))
    if result.pareto:
        blocks.append(plot_block(pareto_front(result), "Pareto front", inp.dpi,
                                 "pareto_front"))
    return blocks
