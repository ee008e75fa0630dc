"""The figure class of the package's plots (imports matplotlib: load it lazily)."""

from __future__ import annotations

from typing import Any

from matplotlib.figure import Figure
from matplotlib.text import Text


class PlainTextFigure(Figure):
    """A figure that draws every text literally (no mathtext).

    Matplotlib reads a text between two dollar signs as a formula; no label of the package's
    figures is one, so each text is set to be drawn as written when the figure is drawn,
    whatever was added to it and whenever.
    """

    def draw(self, renderer: Any) -> None:
        for text in self.findobj(Text):
            text.set_parse_math(False)
        super().draw(renderer)
