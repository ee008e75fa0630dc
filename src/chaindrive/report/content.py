"""The content model of a report: blocks (text, tables, figures) grouped in sections, and
the registry of section builders.

A section builder is a function ``(ReportInput) -> list[Block] | None``: it reads the parts
of the :class:`~chaindrive.analysis.Analysis` it needs and returns None when they are absent,
so parts added to the analysis later (start-up, AFC, …) slot in with one
:func:`register_section` call. The same blocks are rendered to HTML (:mod:`.html`) and to
PDF (:mod:`.pdf`), which is why builders return blocks rather than HTML fragments.
"""

from __future__ import annotations

import hashlib
import io
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from chaindrive.display import UnitSystem, convert, unit_of

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from chaindrive.analysis import Analysis
    from chaindrive.dynamics.modes import DriveDynamics
    from chaindrive.identification import RecordIdentification
    from chaindrive.robust.study import RobustResult
    from chaindrive.synthesis.solve import SynthesisResult

TextKind = Literal["text", "warning", "fail", "ok", "code", "note", "item"]


@dataclass(frozen=True, slots=True)
class Text:
    """A paragraph.

    Parameters
    ----------
    text : str
        The words (plain text, escaped by the renderers).
    kind : str
        "text", "note", "ok"; "warning" and "fail" are highlighted, "code" is monospaced,
        "item" is a bullet point.
    """

    text: str
    kind: TextKind = "text"


@dataclass(frozen=True, slots=True)
class Verdict:
    """The verdict of the checks, the first thing of the report.

    Parameters
    ----------
    passed : bool
        True when every check passes.
    headline : str
        E.g. ``The design passes all 15 checks``.
    detail : str
        A line of detail (the worst failed check, or where the checks are listed).
    """

    passed: bool
    headline: str
    detail: str = ""


@dataclass(frozen=True, slots=True)
class Definitions:
    """The symbols a section introduces, shown as a table of meaning, formula, unit and
    source.

    Parameters
    ----------
    keys : tuple of str
        Keys of :data:`chaindrive.report.symbols.SYMBOLS`.
    units : str
        The report's unit system, "SI" or "US".
    """

    keys: tuple[str, ...]
    units: str = "SI"


@dataclass(frozen=True, slots=True)
class Table:
    """A table of plain values.

    Parameters
    ----------
    caption : str
        The caption above it.
    columns : tuple of str
        Column headers, each with its unit (``tension, N``).
    rows : tuple of tuple
        The rows of values (numbers formatted by the renderers).
    highlight : tuple of int
        Indices of rows marked as failed checks.
    """

    caption: str
    columns: tuple[str, ...]
    rows: tuple[tuple[Any, ...], ...]
    highlight: tuple[int, ...] = ()


@dataclass(frozen=True, slots=True)
class Plot:
    """A figure rendered to PNG with its caption.

    Parameters
    ----------
    caption : str
        The caption below it.
    png : bytes
        The PNG image.
    width, height : int
        Its size [px].
    key : str
        A name that identifies the figure (listed in :attr:`Report.plots`).
    """

    caption: str
    png: bytes
    width: int
    height: int
    key: str = ""


Block = Text | Table | Plot | Verdict | Definitions


@dataclass(frozen=True, slots=True)
class Section:
    """A titled part of the report.

    Parameters
    ----------
    key : str
        The key of its builder (:func:`register_section`).
    title : str
        Its heading.
    blocks : tuple of Block
        Its content, in order.
    """

    key: str
    title: str
    blocks: tuple[Block, ...]


@dataclass(frozen=True, slots=True)
class SectionSpec:
    """A registered section.

    Parameters
    ----------
    key : str
        Its unique key.
    title : str
        Its heading.
    build : callable
        ``build(ReportInput)`` → its blocks, or None when the analysis lacks its parts.
    """

    key: str
    title: str
    build: Callable[[ReportInput], Sequence[Block] | None]


SECTIONS: list[SectionSpec] = []


def register_section(key: str, title: str,
                     build: Callable[[ReportInput], Sequence[Block] | None], *,
                     before: str | None = None) -> None:
    """Add (or replace, by key) a section builder to :data:`SECTIONS`.

    Parameters
    ----------
    key : str
        The section's unique key.
    title : str
        Its heading.
    build : callable
        ``build(ReportInput)`` → its blocks, or None when the analysis lacks its parts.
    before : str | None
        Key of the section it goes in front of (None or unknown: at the end).
    """
    spec = SectionSpec(key, title, build)
    for i, old in enumerate(SECTIONS):
        if old.key == key:
            SECTIONS[i] = spec
            return
    keys = [s.key for s in SECTIONS]
    SECTIONS.insert(keys.index(before) if before in keys else len(SECTIONS), spec)


class ReportInput:
    """What the section builders read: the analysis, the design file it came from, the
    figure resolution, and derived parts computed once.

    Parameters
    ----------
    analysis : Analysis
        The analysed design.
    source : Path | None
        The design file it came from (None: built from an object).
    dpi : int
        Resolution of the figures [1/in].
    synthesis : SynthesisResult | None
        The optimisation that chose the design.
    units : str
        The report's unit system, "SI" or "US".
    robust : RobustResult | None
        The design's robust study.
    identification : RecordIdentification | None
        A measured record matched to the model.
    """

    def __init__(self, analysis: Analysis, *, source: Path | None = None, dpi: int = 110,
                 synthesis: SynthesisResult | None = None, units: UnitSystem = "SI",
                 robust: RobustResult | None = None,
                 identification: RecordIdentification | None = None) -> None:
        self.analysis = analysis
        self.source = source
        self.dpi = dpi
        self.synthesis = synthesis
        self.units: UnitSystem = units
        self.robust = robust
        self.identification = identification
        self.notes: list[str] = []
        self.defined: set[str] = set()

    def define(self, *keys: str) -> list[Block]:
        """A :class:`Definitions` block of the symbols ``keys`` not defined by an earlier
        section, and mark them defined.

        Parameters
        ----------
        *keys : str
            Keys of :data:`chaindrive.report.symbols.SYMBOLS`.

        Returns
        -------
        list of Block
            One Definitions block, or none when every symbol was defined before.
        """
        new = tuple(dict.fromkeys(k for k in keys if k not in self.defined))
        self.defined.update(new)
        return [Definitions(new, self.units)] if new else []

    def col(self, label: str, kind: str) -> str:
        """A column header ``label, unit`` in the report's unit system.

        Parameters
        ----------
        label : str
            What the column holds.
        kind : str
            Kind of quantity (a key of :data:`chaindrive.display.QUANTITIES`).

        Returns
        -------
        str
            ``"<label>, <unit>"``.
        """
        return f"{label}, {unit_of(kind, self.units)}"

    def unit(self, kind: str) -> str:
        """The unit of a kind of quantity in the report's unit system.

        Parameters
        ----------
        kind : str
            Kind of quantity (a key of :data:`chaindrive.display.QUANTITIES`).

        Returns
        -------
        str
            Its unit (e.g. "N" or "lbf").
        """
        return unit_of(kind, self.units)

    def val(self, value: float | None, kind: str) -> float | None:
        """An SI value in the report's unit system.

        Parameters
        ----------
        value : float | None
            The value [SI unit of ``kind``].
        kind : str
            Kind of quantity (a key of :data:`chaindrive.display.QUANTITIES`).

        Returns
        -------
        float | None
            The value in the report's unit [:meth:`unit`] (None stays None).
        """
        return convert(value, kind, self.units)[0]

    @cached_property
    def source_bytes(self) -> bytes | None:
        """The design file's bytes (None when the report is built from an object)."""
        return None if self.source is None else Path(self.source).read_bytes()

    @cached_property
    def source_hash(self) -> str | None:
        """SHA-256 of the design file [hex]."""
        data = self.source_bytes
        return None if data is None else hashlib.sha256(data).hexdigest()

    @cached_property
    def document(self) -> dict[str, Any]:
        """The JSON document of the analysis (the same numbers as ``analyze --json``)."""
        return self.analysis.to_dict()

    @property
    def dynamics(self) -> DriveDynamics:
        """The analysis's dynamics part (:class:`~chaindrive.dynamics.modes.DriveDynamics`)."""
        return self.analysis.dynamics


#: zlib level of the figures' PNG (1: fastest; the seed report's 12 figures encode in 0.07 s
#: against 0.11 s at Pillow's default 6, and take 529 kB as RGB against 538 kB as RGBA at 6).
PNG_COMPRESSION = 1


def figure_png(fig: Figure, dpi: int) -> bytes:
    """A figure as PNG, drawn once.

    ``Figure.savefig`` draws a figure with a layout engine twice: once (without painting)
    for the layout, then again to paint. Drawing it once on an Agg canvas runs the
    constrained layout within that draw and paints the same pixels (checked on every figure
    of the seed example's report) at about 15 % less CPU. An opaque figure is written as RGB
    (no alpha channel) with fast deflate (:data:`PNG_COMPRESSION`): lossless, a third less
    CPU to encode than Pillow's default, files no larger.

    Parameters
    ----------
    fig : Figure
        The matplotlib figure (its dpi is restored afterwards).
    dpi : int
        Resolution [1/in].

    Returns
    -------
    bytes
        The PNG image.
    """
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    before = fig.get_dpi()
    fig.set_dpi(dpi)
    try:
        canvas = FigureCanvasAgg(fig)
        canvas.draw()
        pixels = np.asarray(canvas.buffer_rgba())
        if (pixels[..., 3] == 255).all():  # opaque (every figure of the package): RGB
            pixels = pixels[..., :3]
        buf = io.BytesIO()
        Image.fromarray(pixels).save(buf, format="png", compress_level=PNG_COMPRESSION)
    finally:
        fig.set_dpi(before)
    return buf.getvalue()


def plot_block(fig: Figure, caption: str, dpi: int, key: str = "") -> Plot:
    """Render a figure to PNG (:func:`figure_png`) into a :class:`Plot` block.

    Parameters
    ----------
    fig : Figure
        The matplotlib figure.
    caption : str
        Its caption.
    dpi : int
        Resolution [1/in].
    key : str
        The figure's name (:attr:`Plot.key`).

    Returns
    -------
    Plot
        The block, its size in pixels from the figure's size in inches times ``dpi``.
    """
    png = figure_png(fig, dpi)
    w, h = fig.get_size_inches()
    return Plot(caption, png, round(w * dpi), round(h * dpi), key)


@dataclass(frozen=True, slots=True)
class Report:
    """A built report (:func:`chaindrive.report.build_report`).

    Parameters
    ----------
    title : str
        The report's title.
    meta : tuple of (str, str)
        Metadata lines (label, value): version, design file and its SHA-256, date, units.
    sections : tuple of Section
        The sections, the references last.
    plots : tuple of str
        The keys of its figures, in order.
    drive : str
        The drive's name (page header).
    version : str
        The chaindrive version (page footer).
    date : str
        When it was built (UTC).
    units : str
        The unit system, "SI" or "US".
    kind : str
        "full" (the report) or "summary" (the two-page sign-off sheet).
    """

    title: str
    meta: tuple[tuple[str, str], ...]
    sections: tuple[Section, ...]
    plots: tuple[str, ...] = field(default=())
    drive: str = ""
    version: str = ""
    date: str = ""
    units: str = "SI"
    kind: str = "full"


def rows(items: Iterable[Sequence[Any]]) -> tuple[tuple[Any, ...], ...]:
    """Table rows as tuples.

    Parameters
    ----------
    items : iterable of sequences
        The rows.

    Returns
    -------
    tuple of tuple
        The rows as tuples.
    """
    return tuple(tuple(r) for r in items)
