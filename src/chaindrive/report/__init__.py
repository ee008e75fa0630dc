"""The design report: every result of an analysis in one HTML file (figures embedded) or
one PDF (see ``docs/report.md``).

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

from chaindrive.errors import DesignError
from chaindrive.report.content import (
    SECTIONS,
    Block,
    Plot,
    Report,
    ReportInput,
    Section,
    Table,
    Text,
    register_section,
)
from chaindrive.report.sections import register_standard_sections

register_standard_sections()

if TYPE_CHECKING:
    from collections.abc import Callable

    from chaindrive.analysis import Analysis

__all__ = ["SECTIONS", "Block", "Plot", "Report", "ReportInput", "Section", "Table", "Text",
           "build_report", "register_section", "render_html", "write_report"]

FORMATS = (".html", ".htm", ".pdf")


def build_report(analysis: Analysis, *, source: str | Path | None = None, dpi: int = 110,
                 progress: Callable[[str], None] | None = None,
                 synthesis: object = None, robust: object = None) -> Report:
    """Build every registered section of the report of ``analysis``.

    source : the design file (echoed, and its SHA-256 printed); dpi of the figures;
    progress : called
    with each section's title before it is built (e.g. to advance a progress bar);
    synthesis : the optimisation that chose this design (its Pareto set and front);
    robust : its robust study (:class:`chaindrive.robust.study.RobustResult`: life curve,
    probabilities of failure, sensitivity).
    """
    import chaindrive

    register_standard_sections()
    inp = ReportInput(analysis, source=None if source is None else Path(source), dpi=dpi,
                      synthesis=synthesis, robust=robust)
    built: list[Section] = []
    for spec in list(SECTIONS):
        if progress is not None:
            progress(spec.title)
        blocks = spec.build(inp)
        if blocks:
            built.append(Section(spec.key, spec.title, tuple(blocks)))
    meta = [("chaindrive", chaindrive.__version__)]
    if inp.source is not None:
        meta += [("design file", inp.source.name), ("SHA-256 of the file", inp.source_hash or "")]
    meta.append(("generated", _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")))
    plots = tuple(b.key for s in built for b in s.blocks if isinstance(b, Plot))
    return Report(f"Chain drive report — {analysis.drive.name}", tuple(meta), tuple(built), plots)


def render_html(report: Report) -> str:
    """The report as one self-contained HTML document."""
    from chaindrive.report.html import render_html as _render

    return _render(report)


def write_report(analysis: Analysis, path: str | Path, *, source: str | Path | None = None,
                 dpi: int = 110, progress: Callable[[str], None] | None = None,
                 synthesis: object = None, robust: object = None) -> Path:
    """Build the report and write it as HTML or PDF (by the suffix of ``path``)."""
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in FORMATS:
        raise DesignError("output", f"must end in .html or .pdf, got {out.name!r}")
    report = build_report(analysis, source=source, dpi=dpi, progress=progress,
                          synthesis=synthesis, robust=robust)
    out.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".pdf":
        from chaindrive.report.pdf import write_pdf

        write_pdf(report, out)
    else:
        out.write_text(render_html(report), encoding="utf-8")
    return out
