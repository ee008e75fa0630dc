"""Text is text: names a designer writes never reach a math parser or a typesetting engine as
markup (matplotlib's mathtext, Typst, HTML).

Matplotlib reads a text between two dollar signs as a formula (a name "$\\frac{a}{$" stopped the
report with a parse error); Typst reads "#", "[", "]", "*", "_", "$", "@", "<", ">" and "\\" as
markup; HTML reads "<", ">" and "&". Hypothesis writes sprocket names of those characters; every
figure of the layout draws them, and a report with a hostile drive and sprocket name renders to
HTML and PDF with the names as written.
"""

from __future__ import annotations

import dataclasses
import html
import io
import re

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import chaindrive
from chaindrive.plotting import contour_layout, span_tensions
from tests.conftest import EXAMPLES

#: Characters with a meaning to mathtext, Typst or HTML, among ordinary letters.
MARKUP = "$\\{}#[]*_^@<>&\"'`~%=+-/|;:"
names = st.text(alphabet=st.sampled_from(MARKUP + "abcXYZ019 "), min_size=1, max_size=24).filter(
    lambda s: s.strip() != "" and s.isprintable())

SEED = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")


def _renamed(first: str, drive_name: str | None = None) -> chaindrive.Drive:
    sprockets = (dataclasses.replace(SEED.sprockets[0], name=first), *SEED.sprockets[1:])
    d = SEED.with_sprockets(sprockets)
    return dataclasses.replace(d, name=drive_name) if drive_name is not None else d


@settings(max_examples=15, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(name=names)
@example(name="$\\frac{a}{$")  # stopped the drawing with a parse error
@example(name="$x$")  # was drawn as an italic x
def test_figures_draw_any_name_as_written(name: str) -> None:
    analysis = chaindrive.analyze(_renamed(name), response=False)
    for fig in (contour_layout(analysis.geometry), span_tensions(analysis)):
        fig.savefig(io.BytesIO(), format="png", dpi=40)  # a formula parser would raise here
        texts = [t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_parse_math"))]
        assert any(name in t for t in texts)


@pytest.mark.parametrize("name", ["$\\frac{a}{$", "#set page(\"a5\") *b* _c_ @d <e> [f] \\",
                                  "<script>x</script> & $y$"])
@pytest.mark.parametrize("summary", [False, True], ids=["full", "sheet"])
def test_a_report_renders_a_hostile_name_as_text(name: str, summary: bool) -> None:
    from chaindrive.report import build_report, render_html, render_pdf
    from chaindrive.report.pdf import typst_source

    analysis = chaindrive.analyze(_renamed(name, drive_name=f"drive {name}"))
    report = build_report(analysis, dpi=50, summary=summary)
    page = render_html(report)
    assert html.escape(name) in page or html.escape(name, quote=False) in page
    assert "<script>x</script>" not in page
    assert render_pdf(report).startswith(b"%PDF")
    # in the Typst source a name is text only inside a string literal (or escaped): with
    # every string literal taken out, the name as written is nowhere left
    source, _ = typst_source(report)
    assert name not in re.sub(r'"(?:[^"\\]|\\.)*"', '""', source)


def test_a_figure_pickles_and_keeps_its_text_literal() -> None:
    """A figure is one class for every call (not a class made inside a function), so it
    pickles like any matplotlib figure (a process pool or a user keeping it) and the copy still
    draws its names literally."""
    import pickle

    analysis = chaindrive.analyze(_renamed("$\\frac{a}{$"), response=False)
    fig = contour_layout(analysis.geometry)
    copy = pickle.loads(pickle.dumps(fig))
    assert type(copy) is type(fig)
    copy.savefig(io.BytesIO(), format="png", dpi=40)  # a formula parser would raise here
