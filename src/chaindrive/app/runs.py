"""The page's on-demand work (no Streamlit here): start-up and AFC runs, the report and the
drawing as bytes. Each part may be missing from an installation (a module not written yet,
an optional dependency not installed): :func:`missing` says why, and the page shows that
instead of the tab's button.
"""

from __future__ import annotations

import importlib.util
import io
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from chaindrive.analysis import Analysis
    from chaindrive.model import Drive

#: What each on-demand feature needs: feature → modules that must be importable.
NEEDS: dict[str, tuple[str, ...]] = {
    "startup": ("chaindrive.dynamics.startup", "chaindrive.dynamics.response"),
    "afc": ("chaindrive.dynamics.afc", "chaindrive.dynamics.response"),
    "response": ("chaindrive.dynamics.response",),
    "report": ("chaindrive.report", "matplotlib"),
    "drawing": ("chaindrive.drawing", "ezdxf"),
    "robust": ("chaindrive.robust", "SALib"),
}


def _importable(name: str) -> bool:
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:
        return False


def missing(feature: str) -> str | None:
    """None when ``feature`` (a key of :data:`NEEDS`) can run, else the reason it cannot."""
    absent = [m for m in NEEDS[feature] if not _importable(m)]
    return None if not absent else f"not available yet (needs {', '.join(absent)})"


def full_analysis(drive: Drive) -> Analysis:
    """Every analysis of the drive, with the dynamic response the page leaves out of its
    interactive loop: start-up transient, steady state, AFC sweep and the two-stage check
    (:func:`chaindrive.analyze` with the design's ``[dynamics]`` settings — the same
    numbers as ``chaindrive analyze``)."""
    import chaindrive

    return chaindrive.analyze(drive)


def robust_study(drive: Drive, *, samples: int = 64) -> Any:
    """The robust study of the drive on the page (:func:`chaindrive.robust.study.robust_study`):
    life curve, probabilities over ``samples`` states and the sensitivity indices with the
    ``[uncertainty]`` defaults (the page has no such table)."""
    from chaindrive.robust.study import nominal_analysis
    from chaindrive.robust.study import robust_study as study
    from chaindrive.robust.uncertainty import UncertaintySettings

    return study(nominal_analysis(drive), UncertaintySettings(samples=samples, replicates=8,
                                                              sensitivity_samples=8))


def report_html(analysis: Analysis, *, progress: Callable[[str], None] | None = None) -> bytes:
    """The HTML design report of the analysis (:func:`chaindrive.report.build_report`; give
    it the :func:`full_analysis` so that the dynamic response is in it)."""
    from chaindrive.report import build_report, render_html

    return render_html(build_report(analysis, progress=progress)).encode("utf-8")


def drawing_dxf(analysis: Analysis) -> bytes:
    """The DXF drawing of the drive (:func:`chaindrive.drawing.drawing_document`)."""
    from chaindrive.drawing import drawing_document

    doc = drawing_document(analysis)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode(doc.output_encoding or "utf-8")


def figure_png(fig: Any, dpi: int = 100) -> bytes:
    """A matplotlib Figure rendered to PNG bytes (Agg, no pyplot)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()
