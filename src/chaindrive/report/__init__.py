"""The design report a checker signs: one HTML file (figures embedded) or one PDF typeset
with Typst (see ``docs/report.md``). Page 1 gives the verdict of every check, the governing
checks and the warnings; then the inputs, the results and the checks, every symbol defined
with its formula and source where it first appears, and the references.

::

    from chaindrive.report import build_report, write_report
    write_report(chaindrive.analyze(drive), "report.html", source="design.toml")

Sections come from a registry (:func:`register_section`): each builder reads the parts of
the analysis it needs and is skipped when they are absent, so new parts slot in.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import TYPE_CHECKING

import chaindrive
from chaindrive._docstrings import shared_parameters
from chaindrive.display import UnitSystem, unit_system
from chaindrive.errors import DesignError
from chaindrive.io.atomic import write_bytes
from chaindrive.report.content import (
    SECTIONS,
    Block,
    Definitions,
    Plot,
    Report,
    ReportInput,
    Section,
    Table,
    Text,
    Verdict,
    register_section,
)
from chaindrive.report.html import render_html
from chaindrive.report.pdf import render_pdf
from chaindrive.report.sections import references_section, register_standard_sections
from chaindrive.report.summary import sheet_sections
from chaindrive.report.symbols import SYMBOLS

register_standard_sections()

if TYPE_CHECKING:
    from collections.abc import Callable

    from chaindrive.analysis import Analysis
    from chaindrive.identification import RecordIdentification
    from chaindrive.robust.study import RobustResult
    from chaindrive.synthesis.solve import SynthesisResult

__all__ = ["SECTIONS", "Block", "Definitions", "Plot", "Report", "ReportInput", "Section",
           "Table", "Text", "Verdict", "build_report", "register_section", "render_html",
           "render_pdf", "report_text", "write_report"]

FORMATS = (".html", ".htm", ".pdf")


@shared_parameters
def build_report(analysis: Analysis, *, source: str | Path | None = None, dpi: int = 110,
                 progress: Callable[[str], None] | None = None,
                 synthesis: SynthesisResult | None = None, units: str = "SI",
                 robust: RobustResult | None = None, summary: bool = False,
                 identification: RecordIdentification | None = None) -> Report:
    """Build every registered section of the report of ``analysis``, then the references;
    or, with ``summary``, the two-page sign-off sheet (:mod:`chaindrive.report.summary`).

    Parameters
    ----------
    analysis : Analysis
        The analysed design (the report reads it and computes nothing).
    %(report_options)s
    robust : RobustResult | None
        Its robust study (:class:`chaindrive.robust.study.RobustResult`: life curve,
        probabilities of failure, sensitivity).
    summary : bool
        True builds the sign-off sheet (verdict page and purchase page) instead of the full
        report.
    identification : RecordIdentification | None
        A measured record matched to the model (its section: peaks, spectrum, orders).

    Returns
    -------
    Report
    """
    system: UnitSystem = unit_system(units)
    register_standard_sections()
    inp = ReportInput(analysis, source=None if source is None else Path(source), dpi=dpi,
                      synthesis=synthesis, units=system, robust=robust,
                      identification=identification)
    built = sheet_sections(inp) if summary else _full_sections(inp, progress)
    date = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    meta = [("chaindrive", chaindrive.__version__)]
    if inp.source is not None:
        meta += [("design file", inp.source.name), ("SHA-256 of the file", inp.source_hash or "")]
    meta += [("generated", date), ("units", "SI (mm, N, kW, MPa)" if system == "SI"
                                   else "US customary (in, lbf, hp, psi)")]
    plots = tuple(b.key for s in built for b in s.blocks if isinstance(b, Plot))
    title = "Chain drive sign-off sheet" if summary else "Chain drive report"
    return Report(f"{title} — {analysis.drive.name}", tuple(meta), tuple(built),
                  plots, drive=analysis.drive.name, version=chaindrive.__version__,
                  date=date, units=system, kind="summary" if summary else "full")


def _full_sections(inp: ReportInput, progress: Callable[[str], None] | None
                   ) -> list[Section]:
    """Every registered section that applies, then the references."""
    built: list[Section] = []
    for spec in list(SECTIONS):
        if progress is not None:
            progress(spec.title)
        blocks = spec.build(inp)
        if blocks:
            built.append(Section(spec.key, spec.title, tuple(blocks)))
    built.append(Section("references", "References",
                         tuple(references_section(inp, report_text(built)))))
    return built


def report_text(sections: list[Section] | tuple[Section, ...]) -> str:
    """All the words of the report's sections (texts, captions, cells, symbol definitions):
    what the references are collected from and what a test reads.

    Parameters
    ----------
    sections : list or tuple of Section
        The built sections.

    Returns
    -------
    str
        Their words, one part a line.
    """
    parts: list[str] = []
    for s in sections:
        parts.append(s.title)
        for b in s.blocks:
            if isinstance(b, Text):
                parts.append(b.text)
            elif isinstance(b, Table):
                parts += [b.caption, *b.columns, *(str(v) for r in b.rows for v in r)]
            elif isinstance(b, Plot):
                parts.append(b.caption)
            elif isinstance(b, Verdict):
                parts += [b.headline, b.detail]
            elif isinstance(b, Definitions):
                for k in b.keys:
                    sym = SYMBOLS[k]
                    parts += [sym.text, sym.meaning, sym.formula, sym.source]
    return "\n".join(parts)


@shared_parameters
def write_report(analysis: Analysis, path: str | Path, *, source: str | Path | None = None,
                 dpi: int = 110, progress: Callable[[str], None] | None = None,
                 synthesis: SynthesisResult | None = None, units: str = "SI",
                 robust: RobustResult | None = None, summary: bool = False,
                 identification: RecordIdentification | None = None) -> Path:
    """Build the report and write it as HTML or PDF (by the suffix of ``path``); the file
    is written at once, after the whole report is built (complete or absent).

    Parameters
    ----------
    analysis : Analysis
        The analysed design (the report reads it and computes nothing).
    path : str | Path
        The file to write: ``.html``/``.htm`` or ``.pdf``.
    %(report_options)s
    robust : RobustResult | None
        Its robust study (:class:`chaindrive.robust.study.RobustResult`).
    summary : bool
        True writes the two-page sign-off sheet instead of the full report.
    identification : RecordIdentification | None
        A measured record matched to the model (its section: peaks, spectrum, orders).

    Returns
    -------
    Path
        The file written.
    """
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in FORMATS:
        raise DesignError("output", f"must end in .html or .pdf, got {out.name!r}")
    report = build_report(analysis, source=source, dpi=dpi, progress=progress,
                          synthesis=synthesis, units=units, robust=robust, summary=summary,
                          identification=identification)
    data = render_pdf(report) if suffix == ".pdf" else render_html(report).encode("utf-8")
    write_bytes(out, data)  # complete or absent, never half-written
    return out
