"""The diameter, plus-minus and degree signs of the drawings' notes: written as the DXF
control codes %%c, %%p, %%d (which every CAD program draws with the style's font, also the
shape font "txt" that has no glyph for the Unicode signs), drawn as the glyph Ø in the SVG,
and filled right in the PDF (each contour by its true nesting: ezdxf's matplotlib backend
nests contours by their bounding boxes and fills one of the two counters of Ø)."""

from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np
import pytest

import chaindrive
from chaindrive.drawing import (
    DXF_CODES,
    dxf_text,
    filled_path_orientation,
    svg_string,
    write_drawing,
)
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def jindal() -> chaindrive.analysis.Analysis:
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "two_sprocket_jindal.toml"),
                              response=False)


def test_dxf_text_writes_the_control_codes() -> None:
    assert dxf_text("Bore Ø32.0 H7 (±0.1), 120°") == "Bore %%c32.0 H7 (%%p0.1), 120%%d"
    assert dxf_text("Tooth width bf1 = 5.32") == "Tooth width bf1 = 5.32"
    assert DXF_CODES == {"Ø": "%%c", "±": "%%p", "°": "%%d"}


def test_the_sprocket_drawing_read_back_has_the_diameter_sign(jindal, tmp_path: Path) -> None:
    path = write_drawing(jindal, tmp_path / "driver.dxf", sprocket="driver")
    texts = ezdxf.readfile(path).modelspace().query("TEXT")
    raw = [t.dxf.text for t in texts]
    # no Unicode sign is left for a shape font to miss; the notes carry the codes ...
    assert not [r for r in raw if any(sign in r for sign in DXF_CODES)]
    bore = next(t for t in texts if t.dxf.text.startswith("Bore "))
    assert bore.dxf.text.startswith("Bore %%c") and bore.dxf.style == "Standard"
    # ... and read as the signs (ezdxf decodes them as a CAD program does)
    assert bore.plain_text().startswith("Bore Ø")
    assert any("Hub Ø" in t.plain_text() for t in texts)
    assert any("pins Ø dR" in t.plain_text() for t in texts)
    assert any("°" in t.plain_text() for t in texts)  # the seating angle α in degrees


def _one_text(text: str) -> ezdxf.document.Drawing:
    doc = ezdxf.new("R2010", setup=True, units=4)
    doc.modelspace().add_text(text, height=3.5, dxfattribs={"layer": "TEXT"})
    return doc


def test_the_svg_draws_the_code_as_the_glyph_o_slash() -> None:
    # ezdxf's SVG backend writes text as glyph outlines: the note with %%c is drawn with
    # the very outline of "Ø" (and not that of a "?" or of the three characters "%%c")
    coded = svg_string(_one_text("Bore %%c12.1 H7"))
    assert coded == svg_string(_one_text("Bore Ø12.1 H7"))
    assert coded != svg_string(_one_text("Bore ?12.1 H7"))
    assert coded != svg_string(_one_text("Bore O12.1 H7"))
    assert 'fill-rule="evenodd"' in coded  # the counters of Ø stay open in the SVG


def test_the_drawn_svg_shows_the_signs_of_every_note(jindal, tmp_path: Path) -> None:
    # the sprocket drawing read back from its DXF is drawn as the same SVG as with its notes'
    # codes replaced by the Unicode signs: every %%c is drawn as the glyph Ø (and so on)
    doc = ezdxf.readfile(write_drawing(jindal, tmp_path / "driver.dxf", sprocket="driver"))
    msp = doc.modelspace()
    for hatch in msp.query("HATCH"):  # its pattern lines jitter by a unit from run to run
        msp.delete_entity(hatch)
    coded = svg_string(doc)
    texts = msp.query("TEXT")
    assert sum("%%c" in t.dxf.text for t in texts) >= 3  # bore, hub, pins
    for t in texts:
        t.dxf.text = t.plain_text()
    assert svg_string(doc) == coded


def _ring_with_two_counters() -> list[np.ndarray]:
    """The contours of an Ø made of squares: an outer square and its inside split by the
    diagonal slash into two triangles, side by side, their bounding boxes overlapping."""
    outer = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    upper = np.array([[1.0, 2.0], [8.0, 9.0], [1.0, 9.0]])
    lower = np.array([[2.0, 1.0], [9.0, 1.0], [9.0, 8.0]])
    return [outer, upper, lower]


def test_contours_are_oriented_by_their_true_nesting() -> None:
    # the two counters of Ø are holes (clockwise), the outline is filled (counter-clockwise),
    # though each counter's box holds part of the other's
    assert filled_path_orientation(_ring_with_two_counters()) == [True, False, False]
    # squares nested three deep: outline, hole, island in the hole
    nested = [np.array([[-s, -s], [s, -s], [s, s], [-s, s]]) for s in (3.0, 2.0, 1.0)]
    assert filled_path_orientation(nested) == [True, False, True]
    # two separate shapes are both outlines
    a = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    assert filled_path_orientation([a, a + 5.0]) == [True, True]


def test_the_pdf_leaves_the_counters_of_the_diameter_sign_open(tmp_path: Path) -> None:
    # rasterise the note "Ø" as the PDF draws it (the same backend, on an Agg canvas) and
    # look into each counter: white paper, not ink
    import matplotlib.figure
    from ezdxf.addons.drawing import Frontend, RenderContext, config
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from chaindrive.drawing import _pdf_backend

    doc = _one_text("%%c")
    fig = matplotlib.figure.Figure(figsize=(2, 2), dpi=200)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    cfg = config.Configuration(background_policy=config.BackgroundPolicy.WHITE,
                               color_policy=config.ColorPolicy.BLACK)
    Frontend(RenderContext(doc), _pdf_backend(ax), config=cfg).draw_layout(
        doc.modelspace(), finalize=True)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    pixels = np.asarray(canvas.buffer_rgba())[:, :, :3].mean(axis=2)
    ink = pixels < 128
    rows, cols = np.nonzero(ink)
    assert ink.any()
    # the glyph's box; the counters lie left-above and right-below the slash, a quarter of
    # the box in from the corners
    top, bottom, left, right = rows.min(), rows.max(), cols.min(), cols.max()
    h, w = bottom - top, right - left
    upper_left = (top + int(0.35 * h), left + int(0.3 * w))
    lower_right = (top + int(0.65 * h), left + int(0.7 * w))
    assert not ink[upper_left] and not ink[lower_right]
    # and the ring itself is inked (left and right of the counters)
    middle = top + h // 2
    assert ink[middle, left:left + w // 5].any() and ink[middle, right - w // 5:right + 1].any()
