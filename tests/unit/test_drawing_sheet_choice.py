"""The sheet, scale and arrangement of a drawing are those of drawing it at every scale.

A drawing goes on the first ISO 5457 sheet at the largest ISO 5455 scale, notes (or the
centre table) below or to the right, at which it fits its frame above the ISO 7200 title
block [ISO5457], [ISO5455], [ISO7200]. The drawing module does not draw every candidate: it
passes over a scale at which boxes the drawing takes at least (known before drawing it) fit
no sheet. That is right only while those boxes are no larger than the drawn ones; here each
candidate scale up to the first fit is drawn, its boxes are compared with the least ones,
and the first fit found this way is the module's choice. Examples: metal ISO 606 sprockets
(two_sprocket_jindal), polymeric bodies (seed_three_sprocket_polymer), the GOST 591 tooth
form (seed_three_sprocket drawn with it) and a layout.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import chaindrive
from chaindrive import drawing
from tests.conftest import EXAMPLES


def _analysis(name: str, tooth_form: str | None = None) -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(EXAMPLES / f"{name}.toml")
    if tooth_form is not None:
        drive = dataclasses.replace(drive, tooth_form=tooth_form)
    return chaindrive.analyze(drive, response=False)


def _size(box: tuple[float, float, float, float]) -> tuple[float, float]:
    return box[2] - box[0], box[3] - box[1]


def _first_fit_drawing_every_scale(build: Callable[..., drawing._Arrangements],
                                   least: Callable[[float], tuple[tuple[float, ...], ...]],
                                   size: float, text: float) -> tuple[str, int, bool]:
    """Draw at each candidate scale in turn (the object alone fitting the largest sheet):
    the first (scale, sheet, arrangement) that fits; on the way, the least boxes at each
    scale drawn are no larger than the drawn boxes."""
    sheets = ("A4", "A3")
    room = (max(drawing.ISO5457_SHEETS[sheets[-1]]) - 2 * drawing.SHEET_MARGIN
            - drawing.BORDER_LEFT - drawing.BORDER)
    for n in drawing.ISO5455_SCALES:
        if size / n > room:
            continue
        made = build(drawing._new_document().modelspace(), text * n)
        for right, low in zip((False, True), least(text * n), strict=True):
            drawn = _size(made.box(right))
            assert np.all(np.array(_size(low)) <= np.array(drawn) + 1e-9), (n, right)
        for sheet in sheets:
            for right in (False, True):
                if drawing._fits(made.box(right), sheet, n):
                    return sheet, n, right
    raise AssertionError("no scale fits A3")


@pytest.mark.parametrize(("example", "form"), [("two_sprocket_jindal", None),
                                               ("seed_three_sprocket_polymer", None),
                                               ("seed_three_sprocket", "GOST 591")])
def test_sprocket_sheet_is_the_first_that_fits(example: str, form: str | None) -> None:
    a = _analysis(example, form)
    for i, s in enumerate(a.geometry.sprockets):
        def build(m: Any, h: float, i: int = i) -> drawing._Arrangements:
            return drawing._sprocket_sheet(m, a, i, h)

        def least(h: float, i: int = i) -> tuple[tuple[float, ...], ...]:
            return drawing._sprocket_least(a, i, h)

        size = 1.6 * s.tip_diameter * drawing.MM
        expected = _first_fit_drawing_every_scale(build, least, size, drawing.PAPER_TEXT)
        sheet, n, right, _ = drawing._on_sheet(build, least, size, ("A4", "A3"))
        assert (sheet, n, right) == expected, s.name


def test_layout_sheet_is_the_first_that_fits() -> None:
    a = _analysis("seed_three_sprocket")
    g = a.geometry.sprockets
    size = float(max(np.ptp([s.x for s in g]), np.ptp([s.y for s in g])) * drawing.MM
                 + max(s.tip_diameter for s in g) * drawing.MM)

    def build(m: Any, h: float) -> drawing._Arrangements:
        return drawing._layout_sheet(m, a, h)

    def least(h: float) -> tuple[tuple[float, ...], ...]:
        return drawing._layout_least(a, h)

    expected = _first_fit_drawing_every_scale(build, least, size, drawing.LAYOUT_TEXT)
    sheet, n, right, _ = drawing._on_sheet(build, least, size, ("A4", "A3"),
                                           drawing.LAYOUT_TEXT)
    assert (sheet, n, right) == expected
