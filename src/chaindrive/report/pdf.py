"""PDF rendering of a :class:`~chaindrive.report.content.Report` with matplotlib's PdfPages:
A4 pages laid out top to bottom (headings, wrapped text, tables as monospaced columns,
figures as images). No dependency beyond matplotlib: works on any machine where the plots
work (an HTML→PDF converter would need a browser or Pango/Cairo system libraries)."""

from __future__ import annotations

import io
import textwrap
from pathlib import Path
from typing import TYPE_CHECKING

from chaindrive.display import fmt
from chaindrive.report.content import Block, Plot, Report, Table, Text

if TYPE_CHECKING:
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

A4 = (8.27, 11.69)  # [in]
MARGIN = 0.6  # [in]
LINE = 1.45  # line height / font size
COLOURS = {"warning": "#9a6700", "fail": "#c00000", "ok": "#00734d", "note": "#444444"}


class _Pager:
    """A cursor over A4 pages: y in inches from the top."""

    def __init__(self, pdf: PdfPages) -> None:
        self.pdf, self.fig, self.y = pdf, None, MARGIN
        self.new_page()

    def new_page(self) -> None:
        from matplotlib.figure import Figure

        if self.fig is not None:
            self.pdf.savefig(self.fig)
        self.fig: Figure | None = Figure(figsize=A4)
        self.y = MARGIN

    def room(self, height: float) -> None:
        if self.y + height > A4[1] - MARGIN:
            self.new_page()

    def line(self, text: str, size: float = 9.0, **kw: object) -> None:
        h = size * LINE / 72
        self.room(h)
        assert self.fig is not None
        self.fig.text(MARGIN / A4[0], 1 - (self.y + h * 0.8) / A4[1], text, fontsize=size, **kw)
        self.y += h

    def image(self, plot: Plot) -> None:
        import matplotlib.image as mpimg

        width = A4[0] - 2 * MARGIN
        height = width * plot.height / plot.width
        if height > 0.6 * A4[1]:
            height, width = 0.6 * A4[1], 0.6 * A4[1] * plot.width / plot.height
        self.room(height + 0.3)
        assert self.fig is not None
        ax = self.fig.add_axes((MARGIN / A4[0], 1 - (self.y + height) / A4[1],
                                width / A4[0], height / A4[1]))
        ax.imshow(mpimg.imread(io.BytesIO(plot.png), format="png"))
        ax.set_axis_off()
        self.y += height
        self.line(plot.caption, 8.0, style="italic")

    def close(self) -> None:
        if self.fig is not None:
            self.pdf.savefig(self.fig)
            self.fig = None


def table_lines(t: Table) -> list[str]:
    """A table as monospaced lines (header, rule, rows; failed rows marked with ✗)."""
    cells = [list(t.columns)] + [[fmt(v) for v in row] for row in t.rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(t.columns))]
    def row(r: list[str]) -> str:
        return "  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True))
    lines = [row(cells[0]), "  ".join("─" * w for w in widths)]
    lines += [row(r) + ("  ✗" if i in t.highlight else "") for i, r in enumerate(cells[1:])]
    return lines


def _block(p: _Pager, b: Block) -> None:
    width_in = A4[0] - 2 * MARGIN
    if isinstance(b, Plot):
        p.image(b)
    elif isinstance(b, Table):
        lines = table_lines(b)
        size = min(8.5, width_in * 72 / (0.61 * max(len(s) for s in lines)))
        p.line(b.caption, 9.5, weight="bold")
        for i, s in enumerate(lines):
            fail = i >= 2 and (i - 2) in b.highlight
            p.line(s, size, family="monospace", color=COLOURS["fail"] if fail else "black")
        p.y += 0.12
    elif b.kind == "code":
        p.line("Design file as given:", 9.0, weight="bold")
        for s in b.text.splitlines():
            p.line(s, 7.5, family="monospace")
    else:
        prefix = {"warning": "Warning: ", "fail": "", "ok": "", "note": ""}.get(b.kind, "")
        for s in textwrap.wrap(prefix + b.text, 100) or [""]:
            p.line(s, 9.0, color=COLOURS.get(b.kind, "black"),
                   weight="bold" if b.kind == "fail" else "normal")
        p.y += 0.05


def write_pdf(report: Report, path: Path) -> None:
    """Write the report as a PDF file at ``path``."""
    from matplotlib.backends.backend_pdf import PdfPages

    with PdfPages(path, metadata={"Title": report.title, "Creator": "chaindrive"}) as pdf:
        pager = _Pager(pdf)
        pager.line(report.title, 15, weight="bold")
        for k, v in report.meta:
            pager.line(f"{k}: {v}", 8.5, color="#555555")
        for s in report.sections:
            pager.room(1.2)
            pager.y += 0.15
            pager.line(s.title, 12.5, weight="bold", color="#0b4f7c")
            for b in s.blocks:
                _block(pager, b)
        pager.close()


__all__ = ["Text", "table_lines", "write_pdf"]
