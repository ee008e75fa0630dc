"""What the command line prints for people: tables and lines of an analysis, the checks,
the design-file schema, the chain selection and the optimiser's result (rich).

Every piece of text that comes from a design or a catalogue (names, designations,
messages) is escaped for rich, so ``[drive]`` or ``[/bold] x`` prints as written; numbers
go through :func:`chaindrive.display.fmt` and units through the output unit system
(:mod:`chaindrive.display`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from chaindrive._docstrings import shared_parameters
from chaindrive.checks import UNVERIFIED
from chaindrive.display import (
    UnitSystem,
    candidate_verdict,
    check_row,
    check_unit,
    constraint_row,
    doc_value,
    finding_lines,
    fmt,
    header,
    margin_percent,
    quantity_text,
    unit_header,
    warning_text,
)

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

    from chaindrive.checks import Check
    from chaindrive.synthesis.solve import SynthesisResult

__all__ = ["console", "escape", "print_analysis", "print_checks", "print_optimisation",
           "print_schema", "print_selection", "table"]

#: A Pareto set smaller than this is "poor": the table of rejections is printed with it.
POOR_PARETO = 3
#: Columns printed left-aligned (text); the others are numbers, right-aligned.
TEXT_COLUMNS = frozenset({"name", "from", "to", "chain", "field", "method", "governing", "check",
                          "subject", "required", "result", "unit", "direction", "side",
                          "source", "allowed", "description", "example", "working",
                          "position", "span", "constraint", "closest design", "closest miss",
                          "designation", "what", "design", "group", "distribution", "lubrication",
                          "failed", "failures", "verdict"})


def escape(text: object) -> str:
    """``text`` with rich markup escaped (a name like ``[chain]`` prints as written).

    Parameters
    ----------
    text : object
        Anything printed (its ``str``).

    Returns
    -------
    str
        The text, rich markup escaped.
    """
    from rich.markup import escape as rich_escape

    return rich_escape(str(text))


def console() -> Console:
    """The console of the tables (no highlighting, 120 columns, no soft wrap).

    Returns
    -------
    Console
        A rich console on stdout.
    """
    from rich.console import Console  # only the table output needs rich (not --json)

    return Console(highlight=False, soft_wrap=False, width=120)


def table(title: str, columns: Sequence[str], rows: Sequence[Sequence[Any]]) -> Table:
    """A rich table: every cell formatted by :func:`chaindrive.display.fmt` and escaped.

    Parameters
    ----------
    title : str
        The title above it.
    columns : sequence of str
        Column headers (with their units); the ones in :data:`TEXT_COLUMNS` are
        left-aligned, the others (numbers) right-aligned.
    rows : sequence of sequences
        The cells, SI or already converted to the headers' units.

    Returns
    -------
    Table
        The rich table.
    """
    from rich.table import Table

    t = Table(title=escape(title), title_justify="left", header_style="bold")
    for c in columns:
        name = c.split(",")[0]
        t.add_column(escape(c), justify="left" if name in TEXT_COLUMNS else "right")
    for row in rows:
        t.add_row(*[escape(fmt(v)) for v in row])
    return t


def _v(doc: dict[str, Any], key: str, units: UnitSystem) -> Any:
    """The value of ``key`` of a document part in ``units`` (number only)."""
    return doc_value(key, doc[key], units)[0]


def _q(doc: dict[str, Any], key: str, units: UnitSystem, digits: int = 4) -> str:
    """The value of ``key`` with its unit, as text."""
    value, unit = doc_value(key, doc[key], units)
    return fmt(value, digits) if value is None or not unit else f"{fmt(value, digits)} {unit}"


@shared_parameters
def print_analysis(doc: dict[str, Any], checks: Sequence[Check], units: UnitSystem = "SI",
                   *, quick: bool = False) -> None:
    """Readable tables of an analysis document (values in ``units``) on stdout.

    Parameters
    ----------
    doc : dict
        The analysis's JSON document (:meth:`chaindrive.analysis.Analysis.to_dict`).
    checks : sequence of Check
        Its checks (:meth:`chaindrive.analysis.Analysis.checks`).
    %(units)s
    quick : bool
        True for an analysis without the dynamic response: the verdict says which checks it
        leaves out.
    """
    con = console()
    d, g, k = doc["drive"], doc["geometry"], doc["kinematics"]
    same = f" = ANSI {escape(d['ansi_number'])}" if d.get("ansi_number") else ""
    con.print(f"[bold]{escape(d['name'])}[/bold] — chain {escape(d['chain'])}{same} (pitch "
              f"{_q(d, 'pitch_mm', units)}), tooth form {escape(d['tooth_form'])}")
    summary = (f"{g['links']} links, chain length {_q(g, 'chain_length_mm', units)}, tight "
               f"length {_q(g, 'tight_length_mm', units)} ({fmt(g['tight_length_pitches'])} "
               "pitches)")
    if g["center_distance_mm"] is not None:
        summary += f", centre distance {_q(g, 'center_distance_mm', units)}"
    con.print(summary)
    if g["adjusted_sprocket"] is not None:
        con.print(f"take-up: {escape(g['adjusted_sprocket'])} moved "
                  f"{_q(g, 'adjustment_mm', units)}")
    if g.get("sag_allowance_mm"):
        con.print(f"sag allowance: installed centre distance shortened by "
                  f"{_q(g, 'sag_allowance_mm', units)} from the tight position (the design's "
                  f"{escape('[chain]')} sag_allowance; textbooks 0.2 … 0.4 %)")
    con.print(_length_options(g["length_options"], units))
    cols = [("name", "name"), ("teeth", "teeth"), ("side", "side"), ("x", "x_mm"),
            ("y", "y_mm"), ("pitch Ø", "pitch_diameter_mm"), ("tip Ø", "tip_diameter_mm"),
            ("wrap", "wrap_angle_deg"), ("teeth in mesh", "teeth_in_mesh")]
    con.print(_doc_table("Sprockets", cols, g["sprockets"], units))
    spans = [("from", "from"), ("to", "to"), ("length", "length_mm"),
             ("pitches", "length_pitches"), ("inclination", "inclination_deg"),
             ("tight", "tight")]
    con.print(_doc_table("Spans", spans, g["spans"], units))
    con.print(f"chain speed {_q(k, 'chain_speed_m_s', units)} "
              f"({fmt(_v(k, 'chain_speed_min_m_s', units))} to "
              f"{fmt(_v(k, 'chain_speed_max_m_s', units))}), tooth frequency "
              f"{_q(k, 'tooth_frequency_hz', units)}")
    con.print(_doc_table("Kinematics", [("name", "name"), ("speed", "speed_rpm"),
                                        ("direction", "direction"),
                                        ("speed variation, %", "speed_variation_percent")],
                         k["sprockets"], units))
    con.print(_lubrication(doc["lubrication"], units))
    if doc["strength"] is not None:
        _print_strength(con, doc["strength"], [s["name"] for s in g["sprockets"]],
                        [f"{s['from']}→{s['to']}" for s in g["spans"]], units)
    if doc["selection"] is not None:
        sel = doc["selection"]
        con.print(f"selection ({escape(sel['method'])}): "
                  f"{escape(sel['chain'] or _shortfall(sel, units))}")
        _print_findings(con, sel, units)
    k1 = next((c for c in doc["checks"] if c["key"] == "k1"), None)
    _print_dynamics(con, doc["dynamics"], doc["strength"], units, k1)
    print_checks(con, checks, units, left_out=QUICK_LEFT_OUT if quick else "")
    for w in doc["warnings"]:
        con.print(f"[yellow]warning:[/yellow] {escape(warning_text(w, units))}")


def _print_findings(con: Console, selection: dict[str, Any], units: UnitSystem) -> None:
    """The findings beside the selection's choice, one paragraph each."""
    for kind, text in finding_lines(selection, units):
        con.print(f"  [yellow]{escape(kind)}:[/yellow] {escape(text)}")


def _shortfall(selection: dict[str, Any], units: UnitSystem) -> str:
    """The selection's shortfall (no chain passes) in ``units``."""
    return quantity_text(selection["shortfall"], selection.get("shortfall_quantities"), units)


def _doc_table(title: str, cols: Sequence[tuple[str, str]], items: Sequence[dict[str, Any]],
               units: UnitSystem) -> Table:
    """A table of document items: (label, key) columns, headers with the unit of ``units``."""
    return table(title, [header(label, key, units) for label, key in cols],
                 [[doc_value(key, item[key], units)[0] for _, key in cols] for item in items])


#: What a quick analysis (``--quick``) leaves out, said beside its verdict.
QUICK_LEFT_OUT = ("quick: the dynamic response and its checks k1, k2 and k2min were not "
                  "computed")


@shared_parameters
def print_checks(con: Console, checks: Sequence[Check], units: UnitSystem = "SI",
                 left_out: str = "") -> None:
    """The verdict and the table of checks, failed and unverifiable ones first; the margin
    is :attr:`chaindrive.checks.Check.margin_fraction` in per cent (≥ 0 passes); ``left_out``
    (what the analysis did not check) is said beside the verdict.

    Parameters
    ----------
    con : Console
        Where to print (rich).
    checks : sequence of Check
        The checks of the analysis.
    %(units)s
    left_out : str
        What the analysis left unchecked ("": nothing).
    """
    failed = [c for c in checks if not c.passed]
    besides = f" ({escape(left_out)})" if left_out else ""
    if failed:
        con.print(f"[bold red]{len(failed)} of {len(checks)} checks do not pass[/bold red]"
                  f"{besides}")
    else:
        con.print(f"[bold green]all {len(checks)} checks pass[/bold green]{besides}")
    rows = []
    for c in sorted(checks, key=lambda c: c.passed):
        _, value, required, result, source = check_row(c, units)
        rows.append([c.name, c.subject, value, required, check_unit(c, units),
                     margin_percent(c), result, source])
    con.print(table("Checks", ["check", "subject", "value", "required", "unit", "margin, %",
                               "result", "source"], rows))


def _print_dynamics(con: Console, dyn: dict[str, Any], st: dict[str, Any] | None,
                    units: UnitSystem = "SI", k1: dict[str, Any] | None = None) -> None:
    """Natural frequencies, the closest resonances and the dynamic response (forces in the
    unit system's force unit); the k₁ of a check that cannot be verified says why (its
    note)."""
    freqs = [f for f, rigid in zip(dyn["natural_frequencies_hz"], dyn["rigid_body_modes"],
                                   strict=True) if not rigid]
    more = " …" if len(freqs) > 8 else ""
    con.print(f"natural frequencies (elastic modes), Hz: "
              f"{', '.join(fmt(f) for f in freqs[:8])}{more} (damping ratio "
              f"{fmt(dyn['damping_ratio'])})")
    rows = [[r["label"], r["frequency_hz"], r["natural_frequency_hz"],
             r["detuning_percent"], r["working_frequency_is"]]
            for r in dyn["resonances"][:5]]
    con.print(table("Closest resonances", ["working", "working, Hz", "natural, Hz",
                                           "detuning, %", "position"], rows))
    startup, steady = dyn.get("startup"), dyn.get("steady")
    if steady is not None:
        largest = {"largest_n": max(steady["span_dynamic_load_n"])}
        con.print(f"steady state: largest dynamic span load {_q(largest, 'largest_n', units)}, "
                  f"coefficient of dynamics K_D {fmt(dyn['coefficient_of_dynamics'])}")
    if startup is not None:
        con.print(f"start-up: largest span force {_q(startup, 'max_force_n', units)}; "
                  + startup_times_text(startup))
    if st is not None and "k1" in st:
        partial = (f" (cannot be verified: {k1['note']})"
                   if k1 is not None and k1["status"] == UNVERIFIED
                   else f" (not computed: no start-up, {escape('[dynamics]')} transient = false)"
                   if st["k1"] is None and startup is None else "")
        con.print(f"dynamic safety: k1 {fmt(st['k1'])}{partial}, k2 {fmt(st['k2'])}, k2min "
                  f"{fmt(st['k2min'])} (allowable {escape('[k]')} {fmt(st['allowable_k'])})")


def startup_times_text(startup: dict[str, Any]) -> str:
    """The start-up's run-up, decay and slack share as one clause (JSON keys of
    :meth:`chaindrive.dynamics.transient.startup.StartupResult.to_dict`)."""
    simulated = fmt(startup["simulated_time_s"])
    if startup["runup_time_s"] is None:
        text = f"the driver is not at its working speed within the simulated {simulated} s"
    elif not startup["settled"]:
        text = (f"run-up {fmt(startup['runup_time_s'])} s; the span forces have not settled "
                f"within the simulated {simulated} s (lengthen [dynamics] startup_duration)")
    elif startup["decay_time_s"] > 0:
        text = (f"run-up {fmt(startup['runup_time_s'])} s, then the transient decays in "
                f"{fmt(startup['decay_time_s'])} s (settled after "
                f"{fmt(startup['settling_time_s'])} s)")
    else:
        text = (f"run-up {fmt(startup['runup_time_s'])} s, the span forces already in their "
                "final band then (no decay after it)")
    if startup.get("slack_fraction"):
        text += (f"; a span is slack in {fmt(100 * startup['slack_fraction'])} % of the "
                 "recorded samples")
    return text


def _print_strength(con: Console, st: dict[str, Any], names: list[str], spans: list[str],
                    units: UnitSystem) -> None:
    """Loads and safety of an analysis document."""
    force = header("tension", "t_n", units)
    con.print(table("Span tensions", ["span", force],
                    [[sp, doc_value("t_n", t, units)[0]]
                     for sp, t in zip(spans, st["span_tensions_n"], strict=True)]))
    con.print(table("Shaft loads (direction from +x, counter-clockwise)",
                    ["name", header("shaft load", "f_n", units), header("x", "f_n", units),
                     header("y", "f_n", units), "direction, °"],
                    [[n, doc_value("f_n", f, units)[0], doc_value("f_n", v[0], units)[0],
                      doc_value("f_n", v[1], units)[0], a]
                     for n, f, v, a in zip(names, st["shaft_loads_n"],
                                           st["shaft_load_vectors_n"],
                                           st["shaft_load_directions_deg"], strict=True)]))
    bearings = [(n, b, m) for n, b, m in zip(names, st.get("bearing_load_vectors_n") or [],
                                            st.get("bearing_loads_n") or [], strict=False)
                if b is not None]
    if bearings:  # where the design gives the bearing positions
        con.print(table("Bearing loads (statics of the shaft: the load each bearing carries)",
                        ["name", header("bearing 1", "f_n", units), header("x", "f_n", units),
                         header("y", "f_n", units), header("bearing 2", "f_n", units),
                         header("x", "f_n", units), header("y", "f_n", units)],
                        [[n, *(doc_value("f_n", x, units)[0]
                               for k in (0, 1) for x in (m[k], b[k][0], b[k][1]))]
                         for n, b, m in bearings]))
    allowed = st["allowable_pressure_mpa"]
    life = "—" if st["wear_life_h"] is None else f"{fmt(st['wear_life_h'])} h"
    extrapolated = " (extrapolated: wear does not limit)" if st["wear_life_extrapolated"] else ""
    if st["rated_power_w"] is not None:
        note = quantity_text(st["rating_note"], st.get("rating_note_quantities"), units)
        con.print(f"rated power {_q(st, 'rated_power_w', units)} by {escape(st['rating_method'])} — "
                  f"{escape(note)}")
    con.print(f"hinge pressure {_q(st, 'hinge_pressure_mpa', units)} (allowable "
              f"{'—' if allowed is None else _q(st, 'allowable_pressure_mpa', units)}), static "
              f"safety factor {fmt(st['safety_factor_static'])} (allowable "
              f"{fmt(st['allowable_safety_factor'])}), wear life {life}{extrapolated}")


def print_schema(doc: dict[str, list[dict[str, Any]]]) -> None:
    """Every field of a design file, one table per section with the section's TOML header
    (``[drive]``, ``[[sprockets]]`` …) as its title, on stdout.

    Parameters
    ----------
    doc : dict
        Section → its fields (:func:`chaindrive.io.design.schema`).
    """
    con = console()
    for section, fields in doc.items():
        title = f"[[{section}]]" if section.startswith("sprockets") else f"[{section}]"
        con.print(table(title, ["field", "unit", "default", "required", "allowed", "example",
                                "description"],
                        [[f["field"], f["si_unit"] or "—", _default(f), f["required"],
                          f["allowed"], f["example"] or "—", f["description"]
                          + (f" — limits: {f['reason']}" if f.get("reason") else "")]
                         for f in fields]))


def _default(field: dict[str, Any]) -> Any:
    """A field's default as a design file writes it (with its SI unit for quantities)."""
    value, unit = field["default"], field["si_unit"]
    if value is None or not unit or isinstance(value, bool):
        return value
    return f"{fmt(float(value))} {unit}"


def _length_options(lc: dict[str, Any], units: UnitSystem) -> str:
    """One line: each whole link count around the tight length, laid out (the design's pick
    marked)."""
    parts = []
    for o in lc["options"]:
        picked = ", chosen" if o["rounding"] == lc["chosen"] else ""
        head = f"{o['links']} links ({o['rounding']}{picked})"
        if o["error"] is not None:
            parts.append(f"{head}: cannot be laid out ({escape(o['error'])})")
            continue
        what = []
        if o["centre_distance_mm"] is not None:
            what.append(f"centre distance {_q(o, 'centre_distance_mm', units)}")
        if o["take_up_mm"] is not None:
            what.append(f"take-up {_q(o, 'take_up_mm', units)}")
        what.append(f"slack-span sag {_q(o, 'slack_sag_mm', units)}")
        parts.append(f"{head}: {', '.join(what)}")
    given = "; the design imposes its count" if lc["chosen"] == "given" else ""
    return (f"length options (tight length as designed {fmt(lc['tight_length_pitches'])} "
            f"pitches{given}): " + "; ".join(parts))


def _lubrication(lube: dict[str, Any], units: UnitSystem) -> str:
    """One line: the lubrication regime at the chain speed, the limits of the pitch and the
    source."""
    line = f"lubrication: {escape(lube['regime'])}"
    if lube["ansi_type"] is not None:
        line += (f" (ANSI type {lube['ansi_type']}) at {_q(lube, 'chain_speed_m_s', units)}; "
                 f"this pitch: manual up to {_q(lube, 'manual_max_m_s', units)}, drip up to "
                 f"{_q(lube, 'drip_max_m_s', units)}, bath or disc up to "
                 f"{_q(lube, 'bath_max_m_s', units)}, forced above")
    if lube["note"]:
        line += f" ({escape(lube['note'])})"
    return line + f"; source: {escape(lube['source'])}"


@shared_parameters
def print_selection(doc: dict[str, Any], units: UnitSystem = "SI") -> None:
    """The chain selected and the ranked candidates, on stdout.

    Parameters
    ----------
    doc : dict
        The selection's JSON document (:meth:`chaindrive.strength.selection.SelectionResult.to_dict`).
    %(units)s
    """
    con = console()
    if doc["chain"] is not None:
        same = f" = ANSI {escape(doc['ansi_number'])}" if doc.get("ansi_number") else ""
        con.print(f"selected: [bold]{escape(doc['chain'])}[/bold]{same} "
                  f"({escape(doc['method'])})")
    else:
        con.print(f"[red]{escape(_shortfall(doc, units))}[/red]")
    _print_findings(con, doc, units)
    mass = header("mass", "mass_kg_m", units)
    con.print(table(f"Candidates (first {len(doc['candidates'])} of {doc['candidate_count']}, "
                    "ranked)", ["chain", "method", "strands", mass, "verdict", "margin, %",
                                "governing", "lubrication"],
                    [[c["chain"] + (f" = ANSI {c['ansi_number']}" if c.get("ansi_number")
                                    else ""), c["method"], c["strands"],
                      doc_value("mass_kg_m", c["mass_kg_m"], units)[0], candidate_verdict(c),
                      None if c["margin_fraction"] is None else 100 * c["margin_fraction"],
                      c["governing"], c["lubrication"]] for c in doc["candidates"]]))


def print_optimisation(name: str, result: SynthesisResult, written: Sequence[str],
                       con: Console | None = None) -> None:
    """The optimiser's start design, Pareto set and, when the set is empty or poor, each
    constraint with the designs it rejected and how far the best of them missed.

    Parameters
    ----------
    name : str
        The drive's name.
    result : SynthesisResult
        The optimiser's result.
    written : sequence of str
        The files written (Pareto designs, plot, report), listed at the end.
    con : Console | None
        Where to print (None: :func:`console`).
    """
    names = list(result.objectives)
    heads = [unit_header(n, u) for n, u in zip(names, result.units or ("",) * len(names),
                                                strict=True)]
    con = con or console()
    con.print(f"[bold]{escape(name)}[/bold] — {result.evaluations} designs evaluated by "
              f"{escape(result.method)} (seed {result.seed}) in {fmt(result.seconds, 3)} s")
    con.print(table("Start design", ["design", *heads, "constraints ok"],
                    [["start", *[result.start.objectives[n] for n in names],
                      result.start.feasible]]))
    rows = []
    for k, p in enumerate(result.pareto, start=1):
        d = p.design
        rows.append([str(k), d["chain"].get("designation", "—"),
                     " ".join(str(s["teeth"]) for s in d["sprockets"]),
                     *[p.objectives[n] for n in names],
                     fmt(p.constraints_ok) + (f"; not verified: {', '.join(p.unverified)}"
                                              if p.unverified else "")])
    con.print(table(f"Pareto set ({len(rows)} designs)",
                    ["design", "chain", "teeth", *heads, "constraints ok"], rows))
    checked = [[str(k), f"P({v['key']}) ≤ {fmt(100 * v['alpha'], 3)} %",
                f"{fmt(v['search']['failures'], 3)} / {v['search']['samples']}",
                f"{fmt(100 * v['search'].get('probability', float('nan')), 3)} "
                f"({v['search'].get('path', '?')})",
                f"{fmt(v['failures'], 3)} / {v['samples']}",
                f"{fmt(100 * v['probability'], 3)} [{fmt(100 * v['ci_low'], 3)}, "
                f"{fmt(100 * v['ci_high'], 3)}]", fmt(100 * v['upper'], 3),
                "yes" if v["certified"] else "NO: fails on the full path"]
               for k, p in enumerate(result.pareto, start=1) for v in p.verification]
    if checked:  # a robust search: what its independent sample says, not the search's
        con.print(table("Chance constraints verified on an independent sample on the full "
                        "path (95 % one-sided Clopper–Pearson bound)",
                        ["design", "constraint", "search failures", "search P, % (path)",
                         "failures", "P, %", "bound, %", "certified"], checked))
    con.print(f"{result.feasible_in_search} of {result.evaluations} designs met every "
              f"constraint of the search; {result.verified} of them judged as analyze judges "
              f"their design file (every check, the start-up included): "
              f"{result.verified_passed} passed")
    diagnostics = [c for c in result.constraint_report if c.rejected]
    if diagnostics and len(rows) < POOR_PARETO:
        con.print(table("Why designs were rejected: each constraint, the designs it rejected "
                        "and by how much the closest of them missed",
                        ["constraint", "rejected", "of", "closest miss", "closest design"],
                        [list(constraint_row(c)) for c in diagnostics]))
    if result.verification_report:
        con.print(table("Why designs the search found feasible failed their analysis",
                        ["constraint", "rejected", "of", "closest miss", "closest design"],
                        [list(constraint_row(c)) for c in result.verification_report]))
    if not rows:
        worst = diagnostics[0].name if diagnostics else "a constraint"
        con.print(f"[red]no design met every constraint[/red]: {escape(worst)} rejected the "
                  "most designs; relax it, widen the bounds of the variables it depends on, "
                  "or give the search more designs")
    for path in written:
        con.print(f"wrote {escape(path)}")
