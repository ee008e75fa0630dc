"""PDF rendering of a :class:`~chaindrive.report.content.Report`, typeset with Typst (the
``typst`` package of PyPI: a compiler in one wheel, no system libraries, no browser).

The report becomes a Typst document (:func:`typst_source`): A4 pages with a header (drive,
chaindrive version) and a footer (date, "page x of y"), the verdict on page 1, tables that
break across pages with their header repeated, symbols and formulas in Typst math, figures
as PNG files next to the source. Typst sets it in the fonts it carries (Libertinus Serif,
New Computer Modern, DejaVu Sans Mono) and does not scan the system's fonts: the same pages
on every machine, and 60 ms less CPU a report. Every section heading and the verdict carry a
``<chaindrive-where>`` metadata with the page they land on, so that a test (or a reader of
the source) can ask where each part is (:func:`page_map`).
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Literal

from chaindrive._docstrings import shared_parameters
from chaindrive.display import exponent_parts, fmt
from chaindrive.report.content import Block, Definitions, Plot, Report, Table, Text, Verdict
from chaindrive.report.html import symbol_unit
from chaindrive.report.symbols import SYMBOLS

__all__ = ["page_map", "render_pdf", "render_png_pages", "typst_source", "write_pdf"]

#: Page set-up, fonts and the look of headings and tables.
PREAMBLE = """
#set document(title: {title}, author: "chaindrive {version}")
#set page(paper: "a4", margin: (x: 16mm, top: 20mm, bottom: 18mm),
  header: context {{
    set text(size: 8pt, fill: luma(90))
    if counter(page).get().first() > 1 [{drive} #h(1fr) {what} · chaindrive {version}]
  }},
  footer: context {{
    set text(size: 8pt, fill: luma(90))
    [{date} · units {units} #h(1fr) page #counter(page).display("1 of 1", both: true)]
  }})
#set text(font: ("Libertinus Serif", "New Computer Modern"), size: 9.5pt, lang: "en")
#set par(justify: false, leading: 0.55em)
#set table(stroke: 0.4pt + luma(180), inset: (x: 4pt, y: 2.6pt))
#show table: set text(size: 8.2pt)
#show heading.where(level: 1): it => block(above: 1.3em, below: 0.7em,
  text(size: 13pt, weight: "bold", fill: rgb("#0b4f7c"), it.body))
#show raw: set text(font: "DejaVu Sans Mono", size: 7.5pt)
"""
#: The sign-off sheet's tighter set-up, after :data:`PREAMBLE` (two pages hold it).
SHEET_PREAMBLE = """
#set page(margin: (x: 13mm, top: 14mm, bottom: 14mm))
#set text(size: 8.6pt)
#set par(leading: 0.45em)
#set list(spacing: 0.45em)
#show table: set text(size: 7.6pt)
#set table(inset: (x: 3pt, y: 2pt))
#set image(height: 6.4cm, fit: "contain")
#show heading.where(level: 1): it => block(above: 0.9em, below: 0.5em,
  text(size: 11.5pt, weight: "bold", fill: rgb("#0b4f7c"), it.body))
"""


def _s(text: object) -> str:
    """A Typst string literal of ``text`` (inserted as plain text: no markup is read)."""
    body = str(text).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{body}"'


def _t(text: object) -> str:
    """Content of plain text: ``[#"text"]``."""
    return f"[#{_s(text)}]"


def _number(value: Any) -> str:
    """A table cell's content: a number by :func:`chaindrive.display.fmt` (an exponent as a
    power of ten in math), anything else as text."""
    text = fmt(value)
    parts = exponent_parts(text) if isinstance(value, float) else None
    if parts is None:
        return _t(text)
    return f"[${parts[0]} times 10^({parts[1]})$]"


def _where(key: str) -> str:
    """A metadata element recording the page ``key`` lands on."""
    return f'#context [#metadata((key: {_s(key)}, page: here().page())) <chaindrive-where>]\n'


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


#: Symbols as the tables write them (Unicode) → Typst math.
MATH_OF_TEXT: dict[str, str] = {**{s.text: s.math for s in SYMBOLS.values()},
                                "Kэ": 'K_"э"', "a": "a", "k₁": "k_1", "k₂": "k_2",
                                "k₂min": "k_(2 min)", "F₀": "F_0", "F₁max": "F_(1 max)"}
#: Columns whose cells are symbols.
SYMBOL_COLUMNS = ("symbol", "factor")


def _symbol_cell(value: Any) -> str:
    math = MATH_OF_TEXT.get(str(value)) if value else None
    return f"[${math}$]" if math else _number(value)


def table_typst(t: Table) -> str:
    """A table: caption in bold, header repeated on every page, numbers right-aligned,
    symbols in math, failed rows highlighted."""
    n = len(t.columns)
    numeric = [all(_is_number(r[i]) or r[i] is None for r in t.rows) and
               any(_is_number(r[i]) for r in t.rows) for i in range(n)]
    align = ", ".join("right" if num else "left" for num in numeric)
    fails = ", ".join(str(i + 1) for i in t.highlight)
    fill = (f"fill: (x, y) => if y in ({fails},) {{ rgb(\"#fde2e1\") }} "
            "else if y == 0 { rgb(\"#eef3f8\") },") if t.highlight else \
        "fill: (x, y) => if y == 0 { rgb(\"#eef3f8\") },"
    head = ", ".join(f"[*#{_s(c)}*]" for c in t.columns)
    cell = [_symbol_cell if c in SYMBOL_COLUMNS else _number for c in t.columns]
    body = ",\n  ".join(", ".join(f(v) for f, v in zip(cell, row, strict=True))
                         for row in t.rows)
    return (f"#block(breakable: true, width: 100%)[#text(weight: \"bold\", size: 9pt, "
            f"{_s(t.caption)})\n#table(columns: {n}, align: ({align},), {fill}\n"
            f"  table.header({head}),\n  {body}{',' if t.rows else ''}\n)]\n")


def definitions_typst(d: Definitions) -> str:
    """The symbols a section introduces, in Typst math with their formulas."""
    cells = []
    for k in d.keys:
        s = SYMBOLS[k]
        formula = f"${s.formula_math}$" if s.formula_math else "—"
        cells.append(f"[${s.math}$], {_t(s.meaning)}, [{formula}], "
                     f"{_t(symbol_unit(s, d.units))}, {_t(s.source)}")
    body = ",\n  ".join(cells)
    return ("#block(breakable: true, width: 100%)[#text(weight: \"bold\", size: 9pt, "
            "\"Symbols\")\n#table(columns: (auto, 1fr, auto, auto, auto), "
            "fill: (x, y) => if y == 0 { rgb(\"#eef3f8\") },\n"
            "  table.header([*symbol*], [*meaning*], [*formula*], [*unit*], [*source*]),\n"
            f"  {body},\n)]\n")


def _text_typst(b: Text) -> str:
    if b.kind == "code":
        return f"#raw(block: true, {_s(b.text)})\n"
    if b.kind == "item":
        return f"- {_title_markup(b.text)}\n"
    colours = {"warning": ("#fff4d6", "#e69f00"), "fail": ("#fde2e1", "#c00000"),
               "ok": ("#e3f4ea", "#009e73")}
    if b.kind in colours:
        fill, edge = colours[b.kind]
        weight = ', weight: "bold"' if b.kind == "fail" else ""
        return (f"#block(width: 100%, fill: rgb(\"{fill}\"), inset: 5pt, "
                f"stroke: (left: 3pt + rgb(\"{edge}\")))[#text({_s(b.text)}{weight})]\n")
    if b.kind == "note":
        return f"#text(style: \"italic\", fill: luma(60), {_s(b.text)})\n\n"
    return f"#text({_s(b.text)})\n\n"


def _title_markup(text: str) -> str:
    """Text with ``*title*`` set in italics, everything else literal."""
    parts = text.split("*")
    out = []
    for i, part in enumerate(parts):
        if not part:
            continue
        out.append(f"#emph({_s(part)})" if i % 2 else f"#{_s(part)}")
    return "".join(out)


def block_typst(b: Block, figures: dict[str, bytes]) -> str:
    """One block as Typst markup; a figure's PNG is added to ``figures`` (file name →
    bytes)."""
    if isinstance(b, Table):
        return table_typst(b)
    if isinstance(b, Definitions):
        return definitions_typst(b)
    if isinstance(b, Plot):
        return plots_typst([b], figures)
    if isinstance(b, Verdict):
        fill, edge = ("#e3f4ea", "#009e73") if b.passed else ("#fde2e1", "#c00000")
        return (_where("verdict")
                + f"#block(width: 100%, fill: rgb(\"{fill}\"), inset: 9pt, radius: 2pt, "
                f"stroke: (left: 6pt + rgb(\"{edge}\")))[#text(size: 14pt, weight: \"bold\", "
                f"{_s(b.headline)})\\ #text({_s(b.detail)})]\n")
    return _text_typst(b)


def plots_typst(plots: Sequence[Plot], figures: dict[str, bytes]) -> str:
    """Figures: one alone at 72 % of the text width, two or more side by side; each PNG is
    added to ``figures`` (file name → bytes)."""
    cells = []
    for p in plots:
        name = f"figure_{len(figures) + 1}.png"
        figures[name] = p.png
        width = "100%" if len(plots) > 1 else "72%"
        cells.append(f"figure(image({_s(name)}, width: {width}), caption: {_t(p.caption)}, "
                     "supplement: none, numbering: none)")
    if len(cells) == 1:
        return f"#{cells[0]}\n"
    return f"#grid(columns: 2, gutter: 8pt, {', '.join(cells)})\n"


def _section_typst(blocks: Sequence[Block], figures: dict[str, bytes]) -> list[str]:
    """A section's blocks; consecutive figures two to a row."""
    out: list[str] = []
    run: list[Plot] = []
    for b in blocks:
        if isinstance(b, Plot):
            run.append(b)
            if len(run) == 2:
                out.append(plots_typst(run, figures))
                run = []
            continue
        if run:
            out.append(plots_typst(run, figures))
            run = []
        out.append(block_typst(b, figures))
    if run:
        out.append(plots_typst(run, figures))
    return out


@shared_parameters
def typst_source(report: Report) -> tuple[str, dict[str, bytes]]:
    """The Typst source of the report and its figures.

    %(params_report)s

    Returns
    -------
    tuple of (str, dict of str to bytes)
        The Typst markup and its figures (file name → PNG bytes).
    """
    figures: dict[str, bytes] = {}
    out = [PREAMBLE.format(title=_s(report.title), version=report.version,
                           drive=f"#{_s(report.drive)}", date=report.date,
                           what="sign-off sheet" if report.kind == "summary"
                           else "chain drive report",
                           units="SI" if report.units == "SI" else "US customary")]
    if report.kind == "summary":
        out.append(SHEET_PREAMBLE)
        out.append(f"#text(size: 14pt, weight: \"bold\", {_s(report.title)})\n\n")
        meta = " · ".join(f"{k} {v}" for k, v in report.meta)
        out.append(f"#text(size: 7pt, fill: luma(70), {_s(meta)})\n")
    else:
        out.append(f"#text(size: 17pt, weight: \"bold\", {_s(report.title)})\n\n")
        meta = ", ".join(f"{_t(k)}, {_t(v)}" for k, v in report.meta)
        out.append("#text(size: 8pt, fill: luma(70), table(columns: 2, stroke: none, "
                   f"inset: (x: 0pt, y: 1.5pt), column-gutter: 10pt, {meta}))\n")
    for i, s in enumerate(report.sections):
        if i == 1:  # the verdict page alone: a new page unless page 1 ran over already
            out.append("#metadata(none) <chaindrive-page-one-end>\n#context if locate("
                       "<chaindrive-page-one-end>).page() == 1 { pagebreak() }\n")
        out.append(f"= #{_s(s.title)}\n" + _where(s.key))
        out += _section_typst(s.blocks, figures)
    return "".join(out), figures


@contextmanager
def _staged(report: Report) -> Iterator[dict[str, Any]]:
    """The Typst source and its figures written to a temporary directory, for as long as
    the context lasts: the keyword arguments of a Typst call on them (``input``, ``root``
    and the fonts: Typst's own, not the system's)."""
    source, figures = typst_source(report)
    with tempfile.TemporaryDirectory(prefix="chaindrive-report-") as tmp:
        root = Path(tmp)
        for name, data in figures.items():
            (root / name).write_bytes(data)
        main = root / "report.typ"
        main.write_text(source, encoding="utf-8")
        yield {"input": str(main), "root": str(root), "ignore_system_fonts": True}


def _compile(report: Report, fmt_: Literal["pdf", "png"], ppi: float | None = None) -> Any:
    """Compile the report with Typst in a temporary directory."""
    import typst

    with _staged(report) as where:
        return typst.compile(**where, format=fmt_, ppi=ppi)


@shared_parameters
def render_pdf(report: Report) -> bytes:
    """The report as PDF, typeset by Typst.

    %(params_report)s

    Returns
    -------
    bytes
        The PDF file's bytes.
    """
    data = _compile(report, "pdf")
    assert isinstance(data, bytes)
    return data


@shared_parameters
def render_png_pages(report: Report, ppi: float = 60.0) -> list[bytes]:
    """Every page of the report as a PNG (what the PDF shows, page by page).

    %(params_report)s
    ppi : float
        Resolution of the images [px/in].

    Returns
    -------
    list of bytes
        One PNG image per page.
    """
    pages = _compile(report, "png", ppi)
    return list(pages) if isinstance(pages, list) else [pages]


@shared_parameters
def page_map(report: Report) -> dict[str, int]:
    """The page each section (by key) and the verdict (``"verdict"``) land on.

    %(params_report)s

    Returns
    -------
    dict of str to int
        Section key → its page number (1 the first).
    """
    import json

    import typst

    with _staged(report) as where:
        found = json.loads(typst.query(**where, selector="<chaindrive-where>"))
    return {item["value"]["key"]: int(item["value"]["page"]) for item in found}


@shared_parameters
def write_pdf(report: Report, path: Path) -> None:
    """Write the report as a PDF file at ``path`` (a plain write; the atomic one is
    :func:`chaindrive.report.write_report`).

    %(params_report)s
    path : Path
        The file to write.
    """
    Path(path).write_bytes(render_pdf(report))


def blocks_of(report: Report) -> Sequence[Block]:
    """Every block of the report in order."""
    return [b for s in report.sections for b in s.blocks]
