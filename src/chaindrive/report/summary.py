"""The sign-off sheet: the report a checker signs, on two pages (``chaindrive report FILE
--summary``). Page 1: the verdict, the governing checks with their margins, what the results
rest on (every default and estimate) and the drive to scale; page 2: the chain and the
sprockets to buy, and the key results. Every symbol is said in words where it first appears;
the full report (without ``--summary``) is the long form with every formula and source.

The sheet reads the :class:`~chaindrive.analysis.Analysis` through the same pieces as page 1
of the full report (:mod:`.sections`): it computes and judges nothing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from chaindrive._docstrings import shared_parameters
from chaindrive.display import check_row, quantity_text, warning_text
from chaindrive.plotting import contour_layout
from chaindrive.report.content import (
    Block,
    ReportInput,
    Section,
    Table,
    Text,
    plot_block,
    rows,
)
from chaindrive.report.sections import (
    ESTIMATE_CODES,
    check_cells,
    first_warnings,
    governing_checks,
    key_results,
    lubrication_text,
    rests_on,
    verdict_of,
    warning_blocks,
)
from chaindrive.report.symbols import SYMBOLS

if TYPE_CHECKING:
    from chaindrive.checks import Check

__all__ = ["SHEET_WARNINGS", "grouped_checks", "sheet_sections"]

#: How many of the warnings that are not about a default or an estimate page 2 shows (the
#: full report lists them all; the defaults and estimates are always all on page 1).
SHEET_WARNINGS = 8


def _words(key: str) -> str:
    """A symbol said in words at its first use: ``meaning symbol``."""
    s = SYMBOLS[key]
    return f"{s.meaning} {s.text}"


@shared_parameters
def grouped_checks(inp: ReportInput, checks: Sequence[Check]) -> tuple[Table, list[str]]:
    """The governing checks (:func:`~chaindrive.report.sections.governing_checks`) with the
    checks of one name and result on one row (their subjects and values listed), and the
    note of the first of each row that does not pass (why it fails or cannot be verified).

    %(params_inp)s
    checks : sequence of Check
        Every check of the analysis.

    Returns
    -------
    tuple of (Table, list of str)
        The table and the notes.
    """
    groups: dict[tuple[str, bool, str], list[Check]] = {}
    for c in governing_checks(checks):
        groups.setdefault((c.name, c.passed, check_row(c, inp.units)[3]), []).append(c)
    cells, notes, failed = [], [], []
    for i, ((name, passed, _), members) in enumerate(groups.items()):
        each = [check_cells(c, inp, with_note=False) for c in members]
        first = each[0]
        margins = [e[4] for e in each if e[4] is not None]
        cells.append((name, "; ".join(e[1] for e in each), "; ".join(str(e[2]) for e in each),
                      first[3], min(margins) if margins else None, first[5]))
        note = quantity_text(members[0].note, members[0].note_quantities, inp.units)
        if not passed:
            failed.append(i)
            if note:
                notes.append(f"{name} ({members[0].subject}"
                             f"{', and alike' if len(members) > 1 else ''}): {note}")
    table = Table("Governing checks (those that fail, then the smallest margins; checks of "
                  "one kind on one row, with the smallest margin)",
                  ("check", "subject", "value", "required", "margin m, %", "result"),
                  rows(cells), tuple(failed))
    return table, notes


def _verdict_page(inp: ReportInput) -> list[Block]:
    """Page 1 of the sheet: the verdict, the governing checks with their margins, what the
    results rest on and the drive to scale."""
    a = inp.analysis
    checks = a.checks()
    blocks: list[Block] = [verdict_of(inp, checks, where="the full report's section Checks")]
    margin = SYMBOLS["margin"]
    blocks.append(Text(f"The {margin.meaning}; {margin.formula} ({margin.text} in per "
                       "cent). A check that cannot be verified counts as a failure.", "note"))
    table, notes = grouped_checks(inp, checks)
    blocks.append(table)
    blocks += [Text(n, "note") for n in notes]
    blocks += rests_on(inp)
    blocks.append(plot_block(contour_layout(a.geometry, units=inp.units),
                             "The drive to scale (tight span orange)", inp.dpi, "layout"))
    return blocks


def _purchase_page(inp: ReportInput) -> list[Block]:
    """Page 2 of the sheet: the chain and the sprockets to buy, the key results and the
    other warnings."""
    a = inp.analysis
    d, g = a.drive, a.geometry
    spec = d.chain.spec
    L = inp.unit("length")
    chain: list[tuple[str, Any, str]] = [
        ("designation", spec.designation + ("" if spec.ansi_twin is None
                                            else f" (ANSI {spec.ansi_twin})"), ""),
        ("standard, series", f"{spec.standard} {spec.series}".strip(), ""),
        ("chain pitch p", inp.val(spec.pitch, "length"), L),
        ("strands", spec.strands, ""),
        ("number of links L_p (pitches of the closed chain)", g.links, ""),
        ("chain length L_p·p", inp.val(g.chain_length, "length"), L),
        ("breaking load Q (whole chain)", inp.val(spec.breaking_load, "force_k"),
         inp.unit("force_k")),
        ("lubrication", lubrication_text(inp), "")]
    if d.chain.contours > 1:
        chain.append(("identical contours on common shafts", d.chain.contours, ""))
    given = {s.name: s for s in d.sprockets}
    sprockets = [(s.name, given[s.name].role, s.teeth, inp.val(s.pitch_diameter, "length"),
                  inp.val(s.tip_diameter, "length"), inp.val(s.root_diameter, "length"),
                  given[s.name].material, math.degrees(s.wrap_angle))
                 for s in g.sprockets]
    return [
        Table("The chain", ("item", "value", "unit"), rows(chain)),
        Table("The sprockets (d: pitch diameter, the circle through the roller centres; "
              "d_a: tip diameter; d_f: root diameter; θ: wrap angle of the chain)",
              ("name", "role", "teeth z", inp.col("d", "length"), inp.col("d_a", "length"),
               inp.col("d_f", "length"), "material", "θ, °"), rows(sprockets)),
        key_results(inp, "Key results", words=True),
        Text(f"Symbols: {_words('KD')} = 1 + F_D/F_t, the spans' dynamic load F_D (root mean "
             "square over the spans) over the peripheral force F_t = P/v; the safety factors "
             "k₁, k₂, k₂min are the breaking load Q over the largest span force in the "
             "start-up, in steady running and at the resonances of the run-up.", "note"),
        *_other_warnings(inp),
        Text("This sheet is the summary: the full report (chaindrive report FILE -o "
             "report.pdf, without --summary) gives every check, formula, symbol and source "
             "behind these numbers.", "note"),
    ]


def _other_warnings(inp: ReportInput) -> list[Block]:
    """The warnings that are not about a default or an estimate (those are on page 1)."""
    others = [warning_text(w, inp.units) for w in inp.analysis.warnings
              if w.code not in ESTIMATE_CODES] + inp.notes
    return warning_blocks(others, first_warnings(others, SHEET_WARNINGS), "Other warnings",
                          "item", "the full report's section Checks")


@shared_parameters
def sheet_sections(inp: ReportInput) -> list[Section]:
    """The two sections of the sign-off sheet, one a page.

    %(params_inp)s

    Returns
    -------
    list of Section
        The verdict page and the purchase page.
    """
    return [Section("summary", "Verdict", tuple(_verdict_page(inp))),
            Section("purchase", "Chain and sprockets to buy", tuple(_purchase_page(inp)))]
