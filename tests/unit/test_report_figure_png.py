"""The report draws each figure once (``content.figure_png``: one Agg draw that runs the
constrained layout within it) instead of ``savefig``'s two draws: the same image, compared
pixel by pixel with what ``savefig`` paints (as RGB: an opaque figure is written without its
alpha channel), and the figure's dpi left as it was."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

import chaindrive
from chaindrive.plotting import campbell_diagram, contour_layout, span_tensions
from chaindrive.report.content import figure_png
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def seed() -> chaindrive.Analysis:
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                              response=False)


@pytest.mark.parametrize("make", [lambda a: contour_layout(a.geometry), span_tensions,
                                  lambda a: campbell_diagram(a.dynamics.campbell, operating_rpm=300.0)],
                         ids=["layout", "tensions", "campbell"])
def test_drawn_once_paints_what_savefig_paints(seed, make) -> None:
    fig = make(seed)
    dpi_before = fig.get_dpi()
    image = Image.open(io.BytesIO(figure_png(fig, 70)))
    assert image.mode == "RGB"  # opaque: no alpha channel written
    once = np.asarray(image.convert("RGB"))
    assert fig.get_dpi() == dpi_before
    buf = io.BytesIO()
    make(seed).savefig(buf, format="png", dpi=70)
    twice = np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"))
    assert once.shape == twice.shape
    # sub-pixel differences of anti-aliased edges only, on at most 0.1 % of the pixels
    assert (once != twice).any(axis=-1).mean() < 1e-3
