"""The standard sections of the design report, in order (see :mod:`.content` for the
registry): the verdict page, inputs, geometry, kinematics, selection and strength; the
dynamics sections are in :mod:`.sections_dynamics`; then the checks, the design file and the
references. Each builder returns None when its part of the analysis is absent, defines the
symbols it uses the first time they appear (:meth:`ReportInput.define`) and reads the
analysis only: the report never computes.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence
from typing import TYPE_CHECKING, Any

from chaindrive._docstrings import shared_parameters
from chaindrive.checks import worst
from chaindrive.display import (
    candidate_verdict,
    check_row,
    check_value_text,
    finding_lines,
    fmt,
    margin_percent,
    quantity_text,
    static_state_note,
    warning_text,
)
from chaindrive.plotting import (
    chain_speed,
    contour_layout,
    ratio_pair,
    shaft_loads,
    span_tensions,
    transmission_ratio,
)
from chaindrive.report import sections_dynamics as dyn
from chaindrive.report.bibliography import REFERENCES, cited_keys
from chaindrive.report.content import (
    Block,
    ReportInput,
    Table,
    Text,
    TextKind,
    Verdict,
    plot_block,
    register_section,
    rows,
)
from chaindrive.report.identification import identification_section
from chaindrive.report.robust import robust_section
from chaindrive.report.sources import catalogue_estimates, estimate_note, readable_source

if TYPE_CHECKING:
    from chaindrive.checks import Check

#: How many passing checks with the smallest margins page 1 shows beside the failures.
GOVERNING = 4
#: How many warnings page 1 shows (the section Checks lists them all).
FIRST_WARNINGS = 5


# --- page 1: the verdict -------------------------------------------------------------------------

@shared_parameters
def check_cells(c: Check, inp: ReportInput, *, with_note: bool = True) -> tuple[Any, ...]:
    """(check, subject, value, required, margin %, result, source) of a check.

    Parameters
    ----------
    c : Check
        The check.
    %(inp)s
    with_note : bool
        True adds the check's note to its name when it does not pass.

    Returns
    -------
    tuple
        The cells: name, subject, value with its unit, requirement, margin [%], result,
        source.
    """
    _, _, required, result, source = check_row(c, inp.units)
    shown = check_value_text(c, inp.units)
    note = quantity_text(c.note, c.note_quantities, inp.units) if with_note else ""
    name = c.name + (f" ({note})" if note and not c.passed else "")
    return name, c.subject, shown, required, margin_percent(c), result, readable_source(source)


def governing_checks(checks: Sequence[Check]) -> list[Check]:
    """The checks page 1 shows: every one that does not pass, then the passing ones with the
    smallest margins (:func:`chaindrive.checks.worst` order), at most :data:`GOVERNING`.

    Parameters
    ----------
    checks : sequence of Check
        Every check of the analysis.

    Returns
    -------
    list of Check
        The failed checks, then the passing ones with the smallest margins.
    """
    failed = [c for c in checks if not c.passed]
    passed = sorted((c for c in checks if c.passed),
                    key=lambda c: (c.margin_fraction if c.margin_fraction is not None
                                   else math.inf))
    return failed + passed[:max(GOVERNING - len(failed), 1)]


#: Warning codes of the analysis that say an input was estimated or a default assumed
#: (``dynamics.estimate``: installed sag, link stiffness, rotor inertia; the bearing area of
#: a chain the catalogue gives none for).
ESTIMATE_CODES = ("dynamics.estimate", "strength.bearing-area-estimated")
#: What the estimate warnings are about, by their part, for the short line of one that page 1
#: shows in full among its warnings.
ESTIMATED_PARTS = {"chain.sag": "The installed sag of the chain: assumed",
                   "chain.link_stiffness": "The link stiffness of the chain: computed, an "
                                           "upper bound",
                   "motor.rotor_inertia": "The inertia of the motor's rotor: estimated",
                   "chain": "The bearing area of the chain: estimated"}


def _sentence(text: str) -> str:
    """``text`` with a capital first letter and a full stop."""
    text = text.strip()
    return text[:1].upper() + text[1:] + ("" if text.endswith(".") else ".")


@shared_parameters
def estimates(inp: ReportInput, shown: Collection[str] = ()) -> list[str]:
    """What the results rest on that the design does not give (defaults and estimates), as
    the analysis says it: the damping source of its model, its warnings of estimated inputs
    (:data:`ESTIMATE_CODES`; one whose message is among ``shown`` in one short line), the
    estimates its catalogue row marks, a fatigue strength estimated for want of a catalogue
    value, a service factor the design leaves out, a link-level static state that stopped
    short of its tolerance when a check takes its load from that run, and the reading of K_D.

    %(params_inp)s
    shown : collection of str
        Warning messages already shown in full elsewhere on the page (these get one short
        line here).

    Returns
    -------
    list of str
        One sentence per default or estimate, with what to give instead.
    """
    a = inp.analysis
    d = a.drive
    out = []
    guessed = [s.name for s in d.sprockets if s.inertia is None and s.reduced_mass is None]
    if guessed:
        which = (f"all {len(guessed)} sprockets" if len(guessed) == len(d.sprockets) > 3
                 else ", ".join(guessed))
        out.append(f"Moments of inertia of the bodies of {which} estimated from their "
                   "material and proportions (a plate of the tooth width, or the polymeric "
                   "body of [MultimassChainDrives, §3.4], with the bore 0.19·z·p/π; no hub, "
                   "shaft or coupling): give the inertia of the real parts in the design "
                   "file.")
    source = a.drive_model.damping_source
    if source and not source.startswith("given"):
        out.append(f"Damping ratio {fmt(a.dynamics.damping_ratio)} of the chain by the "
                   f"{source}, not a measurement of this drive: give [dynamics] "
                   "damping_ratio.")
    for w in a.warnings:
        if w.code not in ESTIMATE_CODES:
            continue
        what = ESTIMATED_PARTS.get(w.part)
        text = warning_text(w, inp.units)
        out.append(f"{what} (the warning above)." if what and text in shown
                   else _sentence(text))
    duty = a.duty_summary()
    if duty["service_factor_origin"] == "default":
        st = a.strength
        used = ("" if st is None else f": the strength checks take the operating factor "
                f"{fmt(st.operating_factor)} (section Loads and strength)")
        out.append("Service factor 1.0 by default: no duty classes ([drive] driver, driven) "
                   f"and no service_factor given{used}.")
    if duty["rotation_origin"] != "given":
        out.append(f"Driver's rotation {duty['rotation']} from the order of the sprockets "
                   "([drive] rotation not given): it decides which spans are tight.")
    spec = d.chain.spec
    estimated = catalogue_estimates(spec.source)
    if estimated:
        how = estimate_note(spec.source)
        out.append(_sentence(
            f"{', '.join(estimated)} of the chain {spec.designation}: estimates of the "
            f"catalogue{f' ({how})' if how else ''}, not a maker's data sheet; give the "
            "maker's values in a catalogue file of your own"))
    for c in a.checks():
        if c.name == "fatigue" and c.limit_estimated and c.limit is not None:
            out.append(f"Fatigue strength of the chain {spec.designation} estimated as "
                       f"{fmt(inp.val(c.limit, 'force_k'))} {inp.unit('force_k')}, "
                       f"{fmt(100 * c.limit / spec.breaking_load)} % of its minimum breaking "
                       "load (the low end of a roller chain's fatigue strength as a maker "
                       "states it [IwisFatigue]), no published value in the catalogue: give "
                       "the maker's or the standard's fatigue strength in a catalogue file of "
                       "your own (column fatigue_strength_kN).")
    governed = [c.name for c in a.checks() if c.governing_model == "link_level"]
    stopped = (None if not governed or a.link_level is None else static_state_note(
        a.link_level.equilibrium, inp.units,
        f"the link-level loads the checks {', '.join(dict.fromkeys(governed))} take"))
    if stopped is not None:
        out.append(stopped)
    if a.response is not None:
        out.append("Coefficient of dynamics from the root mean square of the spans' dynamic "
                   "loads: the reading of [MultimassChainDrives, §3.3] this package uses.")
    return out


@shared_parameters
def verdict_of(inp: ReportInput, checks: Sequence[Check], *,
               where: str = "the section Checks") -> Verdict:
    """The verdict of the checks: how many fail and the worst, or that all pass.

    %(params_inp)s
    checks : sequence of Check
        Every check of the analysis.
    where : str
        Where the report lists every check (said when all pass).

    Returns
    -------
    Verdict
        The verdict block.
    """
    failed = [c for c in checks if not c.passed]
    if failed:
        first = worst(failed)
        assert first is not None
        return Verdict(False, f"The design FAILS {len(failed)} of {len(checks)} checks.",
                       f"Worst: {check_cells(first, inp)[0]} on {first.subject}.")
    return Verdict(True, f"The design passes all {len(checks)} checks.",
                   "Each check is listed with its value, limit, margin and source in "
                   f"{where}.")


@shared_parameters
def check_table(inp: ReportInput, checks: Sequence[Check], *, governing: bool = False
                ) -> Table:
    """The table of checks with value, requirement, margin and result (failed rows
    highlighted): every check, failed ones first, or only the governing ones
    (:func:`governing_checks`).

    %(params_inp)s
    checks : sequence of Check
        Every check of the analysis.
    governing : bool
        True: only the governing checks; False: every check, the failed ones first.

    Returns
    -------
    Table
        The table.
    """
    shown = governing_checks(checks) if governing else sorted(checks, key=lambda c: c.passed)
    cells = [check_cells(c, inp) for c in shown]
    columns = ("check", "subject", "value", "required", "margin, %", "result", "source")
    caption = ("Governing checks (those that fail, then the smallest margins)" if governing
               else "Checks")
    return Table(caption, columns, rows(cells),
                 tuple(i for i, c in enumerate(shown) if not c.passed))


@shared_parameters
def summary_section(inp: ReportInput) -> list[Block]:
    """Page 1: the verdict of every check, the governing checks, the warnings, what the
    results rest on, and the design at a glance.

    %(section_blocks)s
    """
    a = inp.analysis
    checks = a.checks()
    blocks: list[Block] = [verdict_of(inp, checks)]
    blocks += inp.define("margin")
    blocks.append(check_table(inp, checks, governing=True))
    warnings = [warning_text(w, inp.units) for w in a.warnings] + inp.notes
    shown = first_warnings(warnings, FIRST_WARNINGS)
    blocks += warning_blocks(warnings, shown, "Warnings", "warning", "the section Checks")
    blocks += rests_on(inp, shown)
    blocks.append(key_results(inp, "The design at a glance"))
    return blocks


def first_warnings(warnings: Sequence[str], most: int) -> list[str]:
    """The warnings a page shows: all when they are at most ``most``, else the first
    ``most - 1`` (the last line then says how many more there are).

    Parameters
    ----------
    warnings : sequence of str
        Every warning, as the report words it.
    most : int
        How many lines the page gives them.

    Returns
    -------
    list of str
        The warnings shown.
    """
    return list(warnings) if len(warnings) <= most else list(warnings[:most - 1])


def warning_blocks(warnings: Sequence[str], shown: Sequence[str], title: str,
                   kind: TextKind, where: str) -> list[Block]:
    """A count of the warnings, those ``shown`` and how many more are listed ``where``.

    Parameters
    ----------
    warnings : sequence of str
        Every warning of the part the page shows.
    shown : sequence of str
        Those the page shows (:func:`first_warnings`).
    title : str
        What they are called ("Warnings", "Other warnings").
    kind : str
        How each is set (a :class:`~chaindrive.report.content.Text` kind).
    where : str
        Where every one of them is listed.

    Returns
    -------
    list of Block
        The blocks.
    """
    if not warnings:
        return [Text(f"No {title.lower()}.", "text")]
    out: list[Block] = [Text(f"{title} ({len(warnings)})", "text"),
                        *(Text(w, kind) for w in shown)]
    if len(shown) < len(warnings):
        out.append(Text(f"… and {len(warnings) - len(shown)} more, every one listed in "
                        f"{where}.", "note"))
    return out


@shared_parameters
def rests_on(inp: ReportInput, shown: Collection[str] = ()) -> list[Block]:
    """The defaults and estimates the results rest on (:func:`estimates`) as a list under
    its heading; nothing when there are none.

    %(params_inp)s
    shown : collection of str
        Warnings the page shows in full (an estimate among them is then one short line).

    Returns
    -------
    list of Block
        The blocks.
    """
    rest = estimates(inp, shown)
    if not rest:
        return []
    return [Text("The results rest on these defaults and estimates:", "text"),
            *(Text(e, "item") for e in rest)]


@shared_parameters
def key_results(inp: ReportInput, caption: str, *, words: bool = False) -> Table:
    """The design at a glance: chain, links, power, speeds, lowest natural frequency, K_D
    and the dynamic safety factors, mass and cost.

    %(params_inp)s
    caption : str
        The table's caption.
    words : bool
        True names the symbols beside the words (K_D, k₁, k₂, k₂min, [k]), for a page that
        defines them in words rather than in a table of symbols.

    Returns
    -------
    Table
        The table (quantity, value, unit).
    """
    a = inp.analysis
    d, g, k = a.drive, a.geometry, a.kinematics
    items: list[tuple[str, Any, str]] = [
        ("chain", d.chain.spec.designation, ""),
        ("links", g.links, ""),
        ("chain length", inp.val(g.chain_length, "length"), inp.unit("length")),
        ("power" + (" P" if words else ""), inp.val(d.power, "power"), inp.unit("power")),
        ("driver speed" + (" n₁" if words else ""), inp.val(d.driver.speed, "speed"), "rpm"),
        ("mean chain speed" + (" v" if words else ""), inp.val(k.chain_speed, "velocity"),
         inp.unit("velocity")),
        ("tooth frequency" + (" f_z (teeth of the driver a second)" if words else ""),
         k.tooth_frequency, "Hz"),
        ("lowest natural frequency", a.dynamics.modal.first_elastic_frequency_hz, "Hz")]
    response = a.response
    if response is not None:
        s = response.strength_dict()
        kd, ks = ("coefficient of dynamics K_D", "dynamic safety factors k₁ (start-up), "
                  f"k₂ (steady), k₂min (run-up); allowable [k] = {fmt(s['allowable_k'])}") \
            if words else ("coefficient of dynamics", "dynamic safety: start-up, steady, "
                           f"run-up (allowable {fmt(s['allowable_k'])})")
        items += [(kd, response.steady.coefficient_of_dynamics, ""),
                  (ks, ", ".join(fmt(s[x]) for x in ("k1", "k2", "k2min")), "")]
    m = a.metrics
    items += [("mass of chain and sprockets", inp.val(m.mass_kg, "mass"), inp.unit("mass")),
              ("cost (estimate)", m.cost, m.cost_breakdown.currency)]
    return Table(caption, ("quantity", "value", "unit"), rows(items))


# --- inputs ----------------------------------------------------------------------------------

@shared_parameters
def inputs_section(inp: ReportInput) -> list[Block]:
    """The design as read, in the report's units.

    %(section_blocks)s
    """
    d = inp.analysis.drive
    duty = inp.analysis.duty_summary()
    spec = d.chain.spec
    blocks = inp.define("P", "n1", "Ks", "p", "d1", "b1", "Q", "q", "z", "zeta")
    same = f" (= ANSI {spec.ansi_twin})" if spec.ansi_twin else ""
    estimated = catalogue_estimates(spec.source)

    def marked(name: str) -> str:
        return f"{name} (estimate)" if name in estimated else name

    items = [("chain", "", spec.designation + same, ""),
             ("pitch", "p", inp.val(spec.pitch, "length"), inp.unit("length")),
             ("strands", "", spec.strands, ""),
             ("roller diameter", "d₁", inp.val(spec.roller_diameter, "length"),
              inp.unit("length")),
             ("width between inner plates", "b₁", inp.val(spec.inner_width, "length"),
              inp.unit("length")),
             (marked("breaking load"), "Q", inp.val(spec.breaking_load, "force_k"),
              inp.unit("force_k")),
             (marked("mass per length"), "q", inp.val(spec.mass_per_length, "linear_density"),
              inp.unit("linear_density"))]
    if spec.allowable_load is not None:
        items.append((marked("allowable load"), "", inp.val(spec.allowable_load, "force_k"),
                      inp.unit("force_k")))
    if spec.max_speed is not None:
        items.append((marked("speed limit"), "", inp.val(spec.max_speed, "velocity"),
                      inp.unit("velocity")))
    if estimated:
        items.append(("chain data from", "", readable_source(spec.source), ""))
    items += [("power", "P", inp.val(d.power, "power"), inp.unit("power")),
              ("service factor", "K_s", f"{fmt(duty['service_factor'])} "
               f"({duty['service_factor_origin']}"
               + (f": {duty['service_factor_note']}" if duty["service_factor_origin"]
                  == "duty classes" else "") + ")", ""),
              ("required life", "", "the rating's basis" if duty["required_life_h"] is None
               else f"{fmt(duty['required_life_h'])} h", ""),
              ("driver's rotation", "", f"{duty['rotation']} ({duty['rotation_origin']})",
               ""),
              ("tooth form", "", d.tooth_form, ""),
              ("damping ratio", "ζ", inp.analysis.dynamics.damping_ratio, ""),
              ("damping ratio from", "", inp.analysis.drive_model.damping_source, "")]
    if d.chain.links is not None:
        items.append(("links (imposed)", "L_p", d.chain.links, ""))
    blocks.append(Table("Drive and chain", ("quantity", "symbol", "value", "unit"),
                        rows(items)))
    blocks.append(Table(
        "Sprockets as given (positions after the take-up)",
        ("name", "role", "teeth z", inp.col("x", "length"), inp.col("y", "length"), "side",
         "speed n, rpm", "adjustable", "material", inp.col("inertia", "inertia"),
         inp.col("reduced mass", "mass"), "power share", "load law"),
        rows([(s.name, s.role, s.teeth, inp.val(s.x, "length"), inp.val(s.y, "length"),
               s.side, inp.val(s.speed, "speed"), s.adjustable, s.material,
               inp.val(s.inertia, "inertia"), inp.val(s.reduced_mass, "mass"),
               s.power_share, s.load) for s in d.sprockets])))
    blocks += _motor_and_trains(inp)
    dyn = d.dynamics
    blocks.append(Table("Dynamics settings ([dynamics])", ("setting", "value"), rows([
        ("harmonics of the tooth frequency in the polygonal excitation (steady response)",
         dyn.harmonics),
        ("start-up simulated", dyn.transient),
        ("start-up duration, s", "automatic (until it settles, at most 60 s)"
         if dyn.startup_duration is None else dyn.startup_duration),
        ("motor law", dyn.motor), ("resistance law", dyn.resistance)])))
    return blocks


def _motor_and_trains(inp: ReportInput) -> list[Block]:
    """The motor as the model uses it (given values, defaults and the rotor inertia, said when
    estimated) and every element of the sprockets' trains, as given."""
    a, d = inp.analysis, inp.analysis.drive
    out: list[Block] = []
    placed = a.drive_model.motor if d.power is not None else None
    if d.motor is not None:
        m, dyn = d.motor, d.dynamics
        out.append(Table("Motor ([motor]; what is not given, from [dynamics] or the drive)",
                         ("quantity", "value", "unit"), rows([
            ("law", m.law or f"{dyn.motor} ([dynamics])", ""),
            ("rated power", inp.val(m.rated_power or d.power, "power"), inp.unit("power")),
            ("rated speed", "the driver's speed through its train" if m.rated_speed is None
             else inp.val(m.rated_speed, "speed"), "rpm"),
            ("rotor inertia" + (" (estimated)" if placed is not None and placed.estimated
                                else ""),
             inp.val(None if placed is None else placed.rotor_inertia, "inertia"),
             inp.unit("inertia")),
            ("breakdown ratio λ = M_k/M_r", m.breakdown_ratio or dyn.breakdown_ratio, ""),
            ("critical slip s_k", m.critical_slip or dyn.critical_slip, "")])))
    elements = [(s.name, e) for s in d.sprockets for e in s.train]
    if elements:
        out.append(Table(
            "Trains of the sprockets (in order from the sprocket outward)",
            ("sprocket", "element", "name", inp.col("inertia", "inertia"),
             inp.col("stiffness", "torsional_stiffness"),
             inp.col("damping", "torsional_damping"), "ratio", "efficiency"),
            rows([(sp, e.kind, e.name or "", inp.val(e.inertia, "inertia"),
                   inp.val(e.stiffness, "torsional_stiffness"),
                   inp.val(e.damping, "torsional_damping"), e.ratio, e.efficiency)
                  for sp, e in elements])))
    return out


# --- geometry and kinematics -----------------------------------------------------------------

@shared_parameters
def geometry_section(inp: ReportInput) -> list[Block]:
    """Contour summary, sprockets, spans and the layout to scale.

    %(section_blocks)s
    """

    a = inp.analysis
    g = a.geometry
    gost = a.drive.tooth_form == "GOST 591"
    tip, root = ("da_gost", "df_gost") if gost else ("da_iso", "df_iso")
    blocks = inp.define("d", tip, root, "theta", "zm", "ell", "Lp")
    L = inp.unit("length")
    summary = [("links", "L_p", g.links, ""),
               ("chain length L_p·p", "", inp.val(g.chain_length, "length"), L),
               ("tight length Σℓ + Σ θd/2", "", inp.val(g.tight_length, "length"), L),
               ("tight length in pitches", "", g.tight_pitches, ""),
               ("slack (not taken up)", "", inp.val(g.slack, "length"), L),
               ("centre distance (two sprockets)", "a",
                inp.val(g.center_distance, "length"), L),
               ("adjusted sprocket", "", None if g.adjusted is None
                else g.sprockets[g.adjusted].name, ""),
               ("adjustment", "", inp.val(g.adjustment, "length"), L),
               ("direction of travel", "", "counter-clockwise" if g.orientation > 0
                else "clockwise", "")]
    ts, rs = ("D_e", "D_i") if gost else ("d_a", "d_f")
    blocks += [
        Table("Contour", ("quantity", "symbol", "value", "unit"),
              rows([r for r in summary if r[2] is not None])),
        Table("Sprockets", ("name", "teeth z", "side", inp.col("x", "length"),
                            inp.col("y", "length"), inp.col("d", "length"),
                            inp.col(ts, "length"), inp.col(rs, "length"), "θ, °",
                            "teeth in mesh z_m"),
              rows([(s.name, s.teeth, s.side, inp.val(s.x, "length"), inp.val(s.y, "length"),
                     inp.val(s.pitch_diameter, "length"), inp.val(s.tip_diameter, "length"),
                     inp.val(s.root_diameter, "length"), math.degrees(s.wrap_angle),
                     s.teeth_in_mesh) for s in g.sprockets])),
        Table("Spans", ("from", "to", inp.col("ℓ", "length"), "ℓ/p", "inclination, °",
                        "tight"),
              rows([(s.start_name, s.end_name, inp.val(s.length, "length"), s.pitches,
                     math.degrees(s.inclination), s.tight) for s in g.spans])),
        _length_options_table(inp),
        plot_block(contour_layout(g, units=inp.units), "Contour layout to scale (tight span orange)", inp.dpi,
                   "layout"),
    ]
    return blocks


def _length_options_table(inp: ReportInput) -> Table:
    """The whole link counts around the tight length as designed, each laid out."""
    lc = inp.analysis.length_choice
    given = "; the design imposes its count" if lc.chosen == "given" else ""
    return Table(f"Chain length options (tight length as designed {fmt(lc.tight_pitches)} "
                 f"pitches{given})",
                 ("links", "rounding", inp.col("a", "length"), inp.col("take-up", "length"),
                  inp.col("slack-span sag", "length"), "note"),
                 rows([(o.links, o.rounding + (" (chosen)" if o.rounding == lc.chosen else ""),
                        inp.val(o.centre_distance, "length"), inp.val(o.take_up, "length"),
                        inp.val(o.slack_sag, "length"),
                        "" if o.error is None else f"cannot be laid out: {o.error}")
                       for o in lc.options]))


@shared_parameters
def kinematics_section(inp: ReportInput) -> list[Block]:
    """Speeds and the polygonal non-uniformity [ChainNonUniformity].

    %(section_blocks)s
    """

    k = inp.analysis.kinematics
    doc = k.to_dict()
    a, b = (inp.analysis.drive.sprockets[i].name for i in ratio_pair(inp.analysis))
    blocks = inp.define("v", "fz", "dv")
    V = inp.unit("velocity")
    blocks += [
        Table("Chain", ("quantity", "symbol", "value", "unit"), rows([
            ("mean chain speed", "v", inp.val(k.chain_speed, "velocity"), V),
            ("least / greatest chain speed", "",
             f"{fmt(inp.val(doc['chain_speed_min_m_s'], 'velocity'))} / "
             f"{fmt(inp.val(doc['chain_speed_max_m_s'], 'velocity'))}", V),
            ("tooth frequency", "f_z", k.tooth_frequency, "Hz")])),
        Table("Sprocket speeds", ("name", "speed n, rpm", "direction", "δ_v, %",
                                  inp.col("hinge deviation peak", "length")),
              rows([(s["name"], s["speed_rpm"], s["direction"], s["speed_variation_percent"],
                     inp.val(s["hinge_deviation_peak_mm"] * 1e-3, "length"))
                    for s in doc["sprockets"]])),
        _lubrication_table(inp),
        plot_block(chain_speed(k, units=inp.units), "Chain speed over one tooth period", inp.dpi,
                   "chain_speed"),
        plot_block(transmission_ratio(inp.analysis), f"Instantaneous transmission ratio "
                   f"ω({a})/ω({b}) of the driver {a} and {b}, the sprocket at the far end of the "
                   "tight span", inp.dpi, "ratio"),
    ]
    return blocks


@shared_parameters
def lubrication_text(inp: ReportInput) -> str:
    """The lubrication regime at the chain speed, with its ANSI type when it has one.

    %(params_inp)s

    Returns
    -------
    str
        E.g. ``"drip (ANSI type II)"``.
    """
    lube = inp.analysis.lubrication
    return lube.regime + ("" if lube.ansi_type is None else f" (ANSI type {lube.ansi_type})")


def _lubrication_table(inp: ReportInput) -> Table:
    """The lubrication regime at the chain speed and the limits of the chain's pitch."""
    lube = inp.analysis.lubrication
    V = inp.unit("velocity")
    items: list[tuple[str, Any, str]] = [("regime", lubrication_text(inp), "")]
    if lube.manual_max is not None and lube.drip_max is not None and lube.bath_max is not None:
        items += [("manual (brush, oil can) up to", inp.val(lube.manual_max, "velocity"), V),
                  ("drip up to", inp.val(lube.drip_max, "velocity"), V),
                  ("oil bath or slinger disc up to", inp.val(lube.bath_max, "velocity"), V),
                  ("forced (oil stream) above", inp.val(lube.bath_max, "velocity"), V)]
    if lube.note:
        items.append(("note", lube.note, ""))
    items.append(("source", lube.source, ""))
    return Table(f"Lubrication at the chain speed {fmt(inp.val(lube.speed, 'velocity'))} {V}",
                 ("quantity", "value", "unit"), rows(items))


# --- selection and strength -------------------------------------------------------------------

@shared_parameters
def selection_section(inp: ReportInput) -> list[Block] | None:
    """The chain a method of the family selects, with the ranked candidates.

    %(section)s
    """
    sel = inp.analysis.selection
    if sel is None:
        return None
    doc = sel.to_dict()
    cands = doc["candidates"][:10]
    head = (f"Selected ({doc['method']}): {doc['chain']}." if doc["chain"] is not None
            else f"{quantity_text(doc['shortfall'], doc['shortfall_quantities'], inp.units)}.")
    findings = [Text(f"{kind[:1].upper()}{kind[1:]}: {text}")
                for kind, text in finding_lines(doc, inp.units)]
    return [Text(f"{head} The analysis uses the design chain "
                 f"{inp.analysis.drive.chain.spec.designation} (a design that names its chain "
                 "keeps it). Each chain of the family is checked on this drive by the method "
                 "that fits it; it is chosen on its chain checks (a layout check it misses by "
                 f"at most {100 * doc['small_layout_shortfall_fraction']:g} % is the layout's "
                 "to fix, said below with the remedy), and passed over for resonance only when "
                 "the check fails beyond its uncertainty band; the margin is that of its "
                 "governing check."),
            *findings,
            Table("Candidates (best 10, ranked)",
                  ("chain", "method", "strands", inp.col("q", "linear_density"), "verdict",
                   "margin, %", "governing check"),
                  rows([(c["chain"], c["method"], c["strands"],
                         inp.val(c["mass_kg_m"], "linear_density"), candidate_verdict(c),
                         None if c["margin_fraction"] is None else 100 * c["margin_fraction"],
                         c["governing"]) for c in cands]))]


@shared_parameters
def strength_section(inp: ReportInput) -> list[Block] | None:
    """Loads round the contour and static strength.

    %(section)s
    """

    st = inp.analysis.strength
    if st is None:
        return None
    doc = st.to_dict()
    blocks = inp.define("Ft", "F0", "Fv", "FR", "Fs", "ph", "ph_allow", "s", "s_allow")
    F, P = inp.unit("force"), inp.unit("pressure")
    items = [("chain speed", "v", inp.val(doc["chain_speed_m_s"], "velocity"),
              inp.unit("velocity")),
             ("peripheral force", "F_t", inp.val(doc["peripheral_force_n"], "force"), F),
             ("sag tension (k_f = " + fmt(doc["sag_factor"]) + ")", "F₀",
              inp.val(doc["sag_tension_n"], "force"), F),
             ("centrifugal tension", "F_v", inp.val(doc["centrifugal_tension_n"], "force"), F),
             ("operating factor", "Kэ", doc["operating_factor_ke"], ""),
             ("joint pressure", "p_h", inp.val(st.hinge_pressure, "pressure"), P),
             ("allowable joint pressure", "[p_h]", inp.val(st.allowable_pressure, "pressure"),
              P),
             ("static safety factor", "s", doc["safety_factor_static"], ""),
             ("allowable static safety factor", "[s]", doc["allowable_safety_factor"], "")]
    if st.rated_power is not None:
        blocks += inp.define("Prated", "Lh")
        items += [(f"rated power ({doc['rating_method']})", "P_r",
                   inp.val(st.rated_power, "power"), inp.unit("power")),
                  ("wear life to {:.0%} elongation{}".format(
                      doc["permitted_elongation"],
                      " (extrapolated: wear does not limit)" if doc["wear_life_extrapolated"]
                      else ""), "L_h", doc["wear_life_h"], "h")]
    names = [s.name for s in inp.analysis.drive.sprockets]
    spans = [f"{s.start_name}→{s.end_name}" for s in inp.analysis.geometry.spans]
    rating = quantity_text(doc["rating_note"], doc["rating_note_quantities"], inp.units)
    blocks += [
        Table("Loads and strength", ("quantity", "symbol", "value", "unit"), rows(items)),
        *([Text(f"Rating: {rating}.")] if st.rated_power is not None and rating else []),
        Table("Span tensions and shaft loads", ("span", inp.col("F_R", "force"), "sprocket",
                                                inp.col("F_s", "force")),
              rows([(sp, inp.val(t, "force"), n, inp.val(f, "force")) for sp, t, n, f in zip(
                  spans, doc["span_tensions_n"], names, doc["shaft_loads_n"], strict=True)])),
        plot_block(span_tensions(inp.analysis, units=inp.units), "Static tension per span", inp.dpi,
                   "tensions"),
        plot_block(shaft_loads(inp.analysis, units=inp.units), "Load per shaft", inp.dpi, "shaft_loads"),
    ]
    return blocks


@shared_parameters
def contours_section(inp: ReportInput) -> list[Block] | None:
    """Multi-contour drives: the load share of the most loaded contour [Lyashuk].

    %(section)s
    """
    part = inp.analysis.contours
    if part is None:
        return None
    flat = [(k.replace("_", " "), v) for k, v in part.to_dict().items()
            if not isinstance(v, dict | list)]
    return [*inp.define("Km"),
            Text(f"{inp.analysis.drive.chain.contours} identical contours on common shafts; "
                 "the strength checks use the most loaded one, P·K_m/m [Lyashuk, eq. 15]."),
            Table("Parallel contours", ("quantity", "value"), rows(flat))]


# --- checks, design file, references ----------------------------------------------------------

@shared_parameters
def checks_section(inp: ReportInput) -> list[Block]:
    """Every check of the analysis with its value, limit, margin (≥ 0 passes) and source;
    failed rows highlighted.

    %(section_blocks)s
    """
    checks = sorted(inp.analysis.checks(), key=lambda c: c.passed)
    blocks = inp.define("margin")
    blocks.append(Text("Every rule the design is held to. The margin has one sign for every "
                       "check: m ≥ 0 passes, m < 0 fails; a check whose rule has no value "
                       "for this design (a table that stops) cannot be verified and counts "
                       "as a failure."))
    blocks.append(check_table(inp, checks))
    notes = [f"{c.name} ({c.subject}): {quantity_text(c.note, c.note_quantities, inp.units)}"
             for c in checks if c.note and c.passed]
    if notes:
        blocks.append(Text("Notes: " + "; ".join(notes) + ".", "note"))
    warnings = [warning_text(w, inp.units) for w in inp.analysis.warnings] + inp.notes
    if warnings:
        blocks.append(Text(f"Warnings ({len(warnings)})", "text"))
        blocks += [Text(w, "item") for w in warnings]
    return blocks


@shared_parameters
def design_file_section(inp: ReportInput) -> list[Block] | None:
    """The design file as given, with its SHA-256 (absent when the report is built from an
    object).

    %(section)s
    """
    if inp.source_bytes is None:
        return None
    return [Text(f"{inp.source.name if inp.source else ''}, SHA-256 {inp.source_hash}",
                 "note"),
            Text(inp.source_bytes.decode("utf-8", errors="replace"), "code")]


@shared_parameters
def references_section(inp: ReportInput, cited: str) -> list[Block]:
    """The bibliography: every source the report cites (``cited`` is the report's text).

    %(params_inp)s
    cited : str
        The report's text (:func:`chaindrive.report.report_text`), searched for keys of
        docs/references.md in square brackets.

    Returns
    -------
    list of Block
        One item per source cited, sorted by key.
    """
    return [Text(f"[{key}] {REFERENCES[key][1]}", "item")
            for key in sorted(cited_keys(cited), key=str.lower)]


def register_standard_sections() -> None:
    """Register the standard sections in report order (idempotent)."""

    for key, title, build in (
            ("summary", "Verdict", summary_section),
            ("inputs", "Inputs", inputs_section),
            ("geometry", "Contour geometry", geometry_section),
            ("kinematics", "Kinematics", kinematics_section),
            ("selection", "Chain selection", selection_section),
            ("strength", "Loads and strength", strength_section),
            ("contours", "Parallel contours", contours_section),
            ("dynamics", "Vibration of the contour", dyn.dynamics_section),
            ("response", "Dynamic response", dyn.response_section),
            ("materials", "Study: material pairs", dyn.materials_section),
            ("damping", "Study: hinge-friction damping", dyn.damping_section),
            ("links", "Link-level model", dyn.links_section),
            ("checks", "Checks", checks_section),
            ("synthesis", "Optimal synthesis", dyn.synthesis_section),
            ("robust", "Life and reliability", robust_section),
            ("identification", "Measured record and the model", identification_section),
            ("design_file", "Design file", design_file_section)):
        register_section(key, title, build)
