"""HTML rendering of a :class:`~chaindrive.report.content.Report`: one self-contained file
(inline CSS, figures as base64 PNG), readable on screen and printable."""

from __future__ import annotations

import base64
import re
from html import escape

from chaindrive._docstrings import shared_parameters
from chaindrive.display import exponent_parts, fmt, unit_of
from chaindrive.report.content import Block, Definitions, Plot, Report, Table, Text, Verdict
from chaindrive.report.symbols import SYMBOLS, Symbol

CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;
 max-width:1100px;margin:24px auto;padding:0 20px;color:#1b1b1b;line-height:1.45;font-size:15px}
h1{font-size:1.7em;margin-bottom:.2em}
h2{font-size:1.3em;border-bottom:2px solid #0072B2;padding-bottom:3px;margin-top:1.8em}
.meta{color:#555;font-size:.9em}.meta td{padding:1px 12px 1px 0}
nav{font-size:.92em;margin:.8em 0}nav a{margin-right:14px;color:#0072B2}
table.data{border-collapse:collapse;margin:.4em 0 1.2em 0;font-size:.92em}
table.data caption{text-align:left;font-weight:600;padding:4px 0}
table.data th{background:#eef3f8;text-align:left;padding:4px 10px;border-bottom:1px solid #9ab}
table.data td{padding:3px 10px;border-bottom:1px solid #e3e3e3}
table.data td.num{text-align:right;font-variant-numeric:tabular-nums}
table.data tr.fail td{background:#fde2e1;color:#8b0000;font-weight:600}
table.symbols td:first-child{font-weight:600;white-space:nowrap}
p.warning{background:#fff4d6;border-left:5px solid #e69f00;padding:6px 10px;margin:4px 0}
p.fail{background:#fde2e1;border-left:5px solid #c00000;padding:6px 10px;margin:4px 0;font-weight:600}
p.ok{background:#e3f4ea;border-left:5px solid #009e73;padding:6px 10px}
p.note{color:#444;font-style:italic}
div.verdict{padding:10px 16px;margin:.6em 0 1em 0;border-radius:4px}
div.verdict.ok{background:#e3f4ea;border-left:8px solid #009e73}
div.verdict.fail{background:#fde2e1;border-left:8px solid #c00000}
div.verdict strong{font-size:1.35em;display:block}
details{margin:.5em 0 1em 0}pre{background:#f6f6f6;padding:8px;overflow-x:auto;font-size:.85em}
figure{margin:.6em 0 1.4em 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}
figcaption{font-size:.9em;color:#444}
.figs{display:flex;flex-wrap:wrap;gap:12px}.figs figure{flex:1 1 480px;max-width:100%}
"""

_TITLE = re.compile(r"\*([^*]+)\*")


def _italic(m: re.Match[str]) -> str:
    return f"<em>{m.group(1)}</em>"


def number_html(value: object) -> str:
    """A value as HTML by :func:`chaindrive.display.fmt`, an exponent as a power of ten
    (``2.154·10<sup>8</sup>``).

    Parameters
    ----------
    value : object
        A number (in the report's unit, as the table holds it), a text or None.

    Returns
    -------
    str
        HTML, escaped.
    """
    text = fmt(value)
    parts = exponent_parts(text)
    if parts is None:
        return escape(text)
    return f"{escape(parts[0])}·10<sup>{parts[1]}</sup>"


def _cell(value: object) -> str:
    num = isinstance(value, int | float) and not isinstance(value, bool)
    return f'<td class="num">{number_html(value)}</td>' if num else f"<td>{escape(fmt(value))}</td>"


def table_html(t: Table) -> str:
    """A table as HTML (numbers right-aligned, failed rows highlighted).

    Parameters
    ----------
    t : Table
        The table block.

    Returns
    -------
    str
        A ``<table>`` element with its caption.
    """
    head = "".join(f"<th>{escape(c)}</th>" for c in t.columns)
    body = "".join(
        f'<tr{" class=fail" if i in t.highlight else ""}>{"".join(_cell(v) for v in row)}</tr>'
        for i, row in enumerate(t.rows))
    return (f'<table class="data"><caption>{escape(t.caption)}</caption>'
            f"<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>")


def symbol_unit(sym: Symbol, units: str) -> str:
    """The unit shown for a symbol: its kind's unit in ``units``, or its fixed unit.

    Parameters
    ----------
    sym : Symbol
        The symbol (:data:`chaindrive.report.symbols.SYMBOLS`).
    units : str
        The report's unit system, "SI" or "US".

    Returns
    -------
    str
        The unit ("" for a pure number).
    """
    if sym.unit in ("", "1"):
        return "—"
    try:
        return unit_of(sym.unit, units)  # type: ignore[arg-type]
    except KeyError:
        return sym.unit


def definitions_html(d: Definitions) -> str:
    """The symbols a section introduces: symbol, meaning, formula, unit, source.

    Parameters
    ----------
    d : Definitions
        The block.

    Returns
    -------
    str
        A ``<table>`` element of the definitions.
    """
    body = "".join(
        f"<tr><td>{escape(s.text)}</td><td>{escape(s.meaning)}</td>"
        f"<td>{escape(s.formula or '—')}</td><td>{escape(symbol_unit(s, d.units))}</td>"
        f"<td>{escape(s.source)}</td></tr>" for s in (SYMBOLS[k] for k in d.keys))
    return ('<table class="data symbols"><caption>Symbols</caption><thead><tr><th>symbol</th>'
            "<th>meaning</th><th>formula</th><th>unit</th><th>source</th></tr></thead>"
            f"<tbody>{body}</tbody></table>")


def plot_html(p: Plot) -> str:
    """A figure as an <img> with the PNG embedded (base64).

    Parameters
    ----------
    p : Plot
        The figure block.

    Returns
    -------
    str
        A ``<figure>`` element with the image and its caption.
    """
    data = base64.b64encode(p.png).decode("ascii")
    return (f'<figure data-plot="{escape(p.key)}"><img alt="{escape(p.caption)}" '
            f'width="{p.width}" height="{p.height}" src="data:image/png;base64,{data}">'
            f"<figcaption>{escape(p.caption)}</figcaption></figure>")


def block_html(b: Block) -> str:
    """One block as HTML.

    Parameters
    ----------
    b : Block
        A Text, Table, Plot, Verdict or Definitions block.

    Returns
    -------
    str
        Its HTML.
    """
    if isinstance(b, Table):
        return table_html(b)
    if isinstance(b, Plot):
        return plot_html(b)
    if isinstance(b, Definitions):
        return definitions_html(b)
    if isinstance(b, Verdict):
        kind = "ok" if b.passed else "fail"
        return (f'<div class="verdict {kind}" id="verdict"><strong>{escape(b.headline)}'
                f"</strong>{escape(b.detail)}</div>")
    if b.kind == "code":
        return f"<pre>{escape(b.text)}</pre>"
    if b.kind == "item":
        return f"<li>{_TITLE.sub(_italic, escape(b.text))}</li>"
    return f'<p class="{b.kind}">{escape(b.text)}</p>'


def _blocks_html(blocks: tuple[Block, ...]) -> str:
    """Blocks in order; runs of consecutive figures side by side, of items in one list."""
    out: list[str] = []
    run: list[str] = []
    kind = ""

    def flush() -> None:
        if run:
            out.append(f'<div class="figs">{"".join(run)}</div>' if kind == "figs"
                       else f'<ul>{"".join(run)}</ul>')
            run.clear()

    for b in blocks:
        k = "figs" if isinstance(b, Plot) else "items" if (
            isinstance(b, Text) and b.kind == "item") else ""
        if k != kind:
            flush()
            kind = k
        if k:
            run.append(block_html(b))
        else:
            out.append(block_html(b))
    flush()
    return "\n".join(out)


@shared_parameters
def render_html(report: Report) -> str:
    """The whole report as one HTML document.

    %(params_report)s

    Returns
    -------
    str
        The document: inline CSS, figures as base64 PNG.
    """
    meta = "".join(f"<tr><td>{escape(k)}</td><td>{escape(v)}</td></tr>" for k, v in report.meta)
    nav = "".join(f'<a href="#{s.key}">{escape(s.title)}</a>' for s in report.sections)
    body = "\n".join(f'<section id="{s.key}"><h2>{escape(s.title)}</h2>\n'
                     f"{_blocks_html(s.blocks)}</section>" for s in report.sections)
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{escape(report.title)}</title><style>{CSS}</style></head><body>"
            f"<h1>{escape(report.title)}</h1><table class=meta>{meta}</table>"
            f"<nav>{nav}</nav>\n{body}\n</body></html>\n")
