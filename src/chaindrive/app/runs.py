"""The page's on-demand work (no Streamlit here): start-up and AFC runs, the report and the
drawing as bytes. Each part may be missing from an installation (a module not written yet,
an optional dependency not installed): :func:`missing` says why, and the page shows that
instead of the tab's button.

The ``bounded_*`` functions are what the page calls: each runs its work in a child process
with a time and memory limit (:func:`chaindrive.app.worker.run_bounded`), so that one
session's heavy design never stalls the server for the others.
"""

from __future__ import annotations

import importlib.util
import io
from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import chaindrive
from chaindrive._docstrings import shared_parameters
from chaindrive.app.state import Location, Outcome
from chaindrive.app.views import Screen, recompute, screens
from chaindrive.app.worker import (
    FULL_SECONDS,
    INTERACTIVE_SECONDS,
    RunLimitError,
    run_bounded,
    run_bounded_steps,
)
from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.io.finite import NonFiniteError, check_document

if TYPE_CHECKING:
    from pathlib import Path

    from matplotlib.figure import Figure

    from chaindrive.analysis import Analysis
    from chaindrive.model import Drive
    from chaindrive.robust.study import RobustResult

#: What each on-demand feature needs: feature → modules that must be importable.
NEEDS: dict[str, tuple[str, ...]] = {
    "startup": ("chaindrive.dynamics.transient.startup", "chaindrive.dynamics.response"),
    "afc": ("chaindrive.dynamics.frequency.afc", "chaindrive.dynamics.response"),
    "response": ("chaindrive.dynamics.response",),
    "report": ("chaindrive.report", "matplotlib"),
    "report_html": ("chaindrive.report", "matplotlib"),
    "report_pdf": ("chaindrive.report", "matplotlib", "typst"),
    "drawing": ("chaindrive.drawing", "ezdxf"),
    "drawing_svg": ("chaindrive.drawing", "ezdxf"),
    "drawing_dxf": ("chaindrive.drawing", "ezdxf"),
    "links": ("chaindrive.linklevel", "numba", "matplotlib"),
    "robust": ("chaindrive.robust", "SALib"),
}


def _importable(name: str) -> bool:
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:
        return False


def missing(feature: str) -> str | None:
    """Whether an on-demand feature can run in this installation.

    Parameters
    ----------
    feature : str
        A key of :data:`NEEDS`.

    Returns
    -------
    str | None
        None when it can run, else the reason it cannot.
    """
    absent = [m for m in NEEDS[feature] if not _importable(m)]
    return None if not absent else f"not available yet (needs {', '.join(absent)})"


@shared_parameters
def full_analysis(drive: Drive) -> Analysis:
    """Every analysis of the drive, with the dynamic response the page leaves out of its
    interactive loop: start-up transient, steady state, AFC sweep and the two-stage check
    (:func:`chaindrive.analyze` with the design's ``[dynamics]`` settings — the same
    numbers as ``chaindrive analyze``).

    %(drive_analysis)s

    Raises
    ------
    RunLimitError
        A sentence, when the analysis holds a NaN or an infinity (it did not converge).
    """
    analysis = chaindrive.analyze(drive)
    try:  # the page shows these numbers: never a NaN or an infinity
        check_document(analysis.to_dict())
    except NonFiniteError as exc:
        raise RunLimitError(f"The dynamic analysis did not converge ({exc}); the design is "
                            "within the allowed ranges, so this is a defect of the program: "
                            "please report it with the design file.") from None
    return analysis


def robust_study(drive: Drive, *, samples: int = 64) -> RobustResult:
    """The robust study of the drive on the page (:func:`chaindrive.robust.study.robust_study`):
    life curve, probabilities over ``samples`` states and the sensitivity indices with the
    ``[uncertainty]`` defaults (the page has no such table).

    Parameters
    ----------
    drive : Drive
        The design.
    samples : int
        Quasi-Monte Carlo states of the probabilities [-].

    Returns
    -------
    RobustResult
        The life curve, probabilities of failure and sensitivity indices.
    """
    # lazy: runs in the bounded worker only; the robust stack imports Dask and SALib (≈2.7 s, -X
    # importtime)
    from chaindrive.robust.study import nominal_analysis
    from chaindrive.robust.study import robust_study as study
    from chaindrive.robust.uncertainty import UncertaintySettings

    return study(nominal_analysis(drive), UncertaintySettings(samples=samples, replicates=8,
                                                              sensitivity_samples=8))


def report_html(analysis: Analysis, *, progress: Callable[[str], None] | None = None) -> bytes:
    """The HTML design report of the analysis (:func:`chaindrive.report.build_report`; give
    it the :func:`full_analysis` so that the dynamic response is in it).

    Parameters
    ----------
    analysis : Analysis
        The analysis to report.
    progress : callable | None
        Called with each section's title before it is built.

    Returns
    -------
    bytes
        The HTML document (UTF-8).
    """
    # lazy: runs in the bounded worker only; the report stack imports matplotlib and Typst (≈0.5 s,
    # -X importtime)
    from chaindrive.report import build_report, render_html

    return render_html(build_report(analysis, progress=progress)).encode("utf-8")


def report_bytes(analysis: Analysis, fmt: str = "pdf", *,
                 progress: Callable[[str], None] | None = None, units: str = "SI") -> bytes:
    """The design report of the analysis as PDF (``fmt`` "pdf", typeset by Typst) or HTML
    ("html"), in the unit system ``units``.

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design.
    fmt : str
        ``"pdf"`` or ``"html"``.
    progress : callable or None
        Called with each section's title before it is built (None: silent).
    units : str
        Unit system of the report, ``"SI"`` or ``"US"``.

    Returns
    -------
    bytes
        The report file's content.
    """
    # lazy: runs in the bounded worker only; the report stack imports matplotlib and Typst (≈0.5 s,
    # -X importtime)
    from chaindrive.report import build_report, render_html, render_pdf

    report = build_report(analysis, progress=progress, units=units)
    return render_pdf(report) if fmt == "pdf" else render_html(report).encode("utf-8")


def drawing_svg(analysis: Analysis) -> bytes:
    """The drawing of the drive as SVG (:func:`chaindrive.drawing.svg_string`).

    Parameters
    ----------
    analysis : Analysis
        The analysis of the design.

    Returns
    -------
    bytes
        The SVG text, UTF-8 encoded.
    """
    # lazy: runs in the bounded worker only; the drawing imports ezdxf (≈0.1 s, -X importtime)
    from chaindrive.drawing import drawing_document, svg_string

    return svg_string(drawing_document(analysis)).encode("utf-8")


def drawing_dxf(analysis: Analysis) -> bytes:
    """The DXF drawing of the drive (:func:`chaindrive.drawing.drawing_document`).

    Parameters
    ----------
    analysis : Analysis
        The analysis whose drive is drawn.

    Returns
    -------
    bytes
        The DXF file.
    """
    # lazy: runs in the bounded worker only; the drawing imports ezdxf (≈0.1 s, -X importtime)
    from chaindrive.drawing import drawing_document

    doc = drawing_document(analysis)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode(doc.output_encoding or "utf-8")


def figure_png(fig: Figure, dpi: int = 100) -> bytes:
    """A matplotlib Figure rendered to PNG bytes (Agg, no pyplot).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    dpi : int
        Resolution [dots per inch].

    Returns
    -------
    bytes
        The PNG image.
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()


def full_report(drive: Drive, fmt: str = "html", units: str = "SI") -> bytes:
    """The report of the :func:`full_analysis` of ``drive`` (one run: analysis and report in
    the same process).

    Parameters
    ----------
    drive : Drive
        The design.
    fmt : str
        "pdf" (typeset by Typst) or "html".
    units : str
        The unit system of the report's tables ("SI" or "US").

    Returns
    -------
    bytes
        The document.
    """
    return report_bytes(full_analysis(drive), fmt, units=units)


@shared_parameters
def bounded_screen(design: dict[str, Any], catalogs: dict[str, Path] | None = None) -> Screen:
    """:func:`chaindrive.app.views.recompute` in a bounded run; a run past its limit is shown
    as the design's message (never raises).

    %(params_form_catalogs)s

    Returns
    -------
    Screen
    """

    return _bounded(recompute, design, catalogs)


@shared_parameters
def bounded_screens(design: dict[str, Any], catalogs: dict[str, Path] | None = None
                    ) -> Generator[Screen, None, None]:
    """:func:`chaindrive.app.views.screens` in one bounded run: the quick screen as soon as
    the child has it, then the complete one; a failure, or a run past its limit, is the
    last screen, as the design's message (never raises).

    %(params_form_catalogs)s

    Returns
    -------
    Iterator of Screen
    """

    steps = run_bounded_steps(screens, design, catalogs, seconds=INTERACTIVE_SECONDS,
                              what="the analysis")
    try:
        yield from steps
    except Exception as exc:  # shown as the design's message
        yield _failed(exc)
    finally:
        steps.close()


def _bounded(func: Callable[..., Screen], design: dict[str, Any],
             catalogs: dict[str, Path] | None) -> Screen:
    try:
        return run_bounded(func, design, catalogs, seconds=INTERACTIVE_SECONDS,
                           what="the analysis")
    except Exception as exc:  # shown as the design's message
        return _failed(exc)


def _failed(exc: Exception) -> Screen:
    """The screen of a run that failed: its ChainDriveError's line (a limit, a mistake), or
    a short note — the page must never show a traceback."""

    if isinstance(exc, ChainDriveError):
        return Screen(Outcome(message=str(exc), location=Location("design")))
    return Screen(Outcome(unexpected=True, location=Location("design"),
                          message=f"the analysis failed unexpectedly ({exc})"[:300]))


@shared_parameters
def bounded_full_analysis(drive: Drive) -> Analysis:
    """:func:`full_analysis` in a bounded run (raises its ChainDriveError, or
    RunLimitError).

    %(drive_analysis)s
    """
    return run_bounded(full_analysis, drive, seconds=FULL_SECONDS,
                       what="the dynamic analysis")


def bounded_report(drive: Drive, fmt: str = "html", units: str = "SI") -> bytes:
    """:func:`full_report` in a bounded run.

    Parameters
    ----------
    drive : Drive
        The design.
    fmt : str
        "pdf" or "html".
    units : str
        "SI" or "US".

    Returns
    -------
    bytes
        The document.
    """
    return run_bounded(full_report, drive, fmt, units, seconds=FULL_SECONDS,
                       what="the report")


def bounded_drawing(analysis: Analysis, fmt: str = "dxf") -> bytes:
    """:func:`drawing_dxf` or :func:`drawing_svg` in a bounded run.

    Parameters
    ----------
    analysis : Analysis
        The analysis whose drive is drawn.
    fmt : str
        "dxf" or "svg".

    Returns
    -------
    bytes
        The drawing file.
    """
    return run_bounded(drawing_svg if fmt == "svg" else drawing_dxf, analysis,
                       seconds=FULL_SECONDS, what="the drawing")


@dataclass(frozen=True, slots=True)
class LinkLevelView:
    """What the page shows of the link-level model.

    Parameters
    ----------
    comparison : dict
        The analysis' comparison with the whole-drive model
        (:meth:`chaindrive.linklevel.ModelComparison.to_dict`: rows of quantity, whole_drive,
        link_level, unit in SI; settled; steady_from_s; duration_s).
    time_step_s : float
        The run's time step [s].
    frames_png : bytes
        The frames of the chain (PNG).
    tensions_png : bytes
        The link tension along the chain (PNG).
    equilibrium : dict
        The static state the run started from
        (:meth:`chaindrive.linklevel.equilibrium.Equilibrium.to_dict`: ``converged``, its
        residual and the reference span's offset from T₀, SI).
    """

    comparison: dict[str, Any]
    time_step_s: float
    frames_png: bytes
    tensions_png: bytes
    equilibrium: dict[str, Any]


def link_level_view(drive: Drive, duration_s: float | None = None) -> LinkLevelView:
    """The link-level model of ``drive`` (the analysis' study "links", a start-up from rest
    over ``duration_s`` [s], None: the design's start-up duration) beside the whole-drive
    model, with its figures rendered.

    Parameters
    ----------
    drive : Drive
        The design.
    duration_s : float | None
        Simulated time [s] (bounded by :data:`chaindrive.linklevel.DURATION`).

    Returns
    -------
    LinkLevelView
    """
    # lazy: runs in the bounded worker only; plotting imports matplotlib (≈0.12 s, -X importtime)
    from chaindrive.plotting import chain_frames, frame_times, tension_along_chain

    analysis = chaindrive.analyze(drive, studies=("links",), lazy=True,
                                  link_duration_s=duration_s)
    result, comparison = analysis.link_level, analysis.link_level_comparison
    if result is None or comparison is None:
        raise DesignError("drive.power", "the link-level model needs the power and the "
                              "driver speed")
    times = frame_times(result)
    return LinkLevelView(comparison.to_dict(), result.dt,
                         figure_png(chain_frames(result, times), dpi=90),
                         figure_png(tension_along_chain(result, times), dpi=90),
                         dict(result.equilibrium))


def bounded_link_level(drive: Drive, duration_s: float | None = None) -> LinkLevelView:
    """:func:`link_level_view` in a bounded run (raises its ChainDriveError, or
    RunLimitError).

    Parameters
    ----------
    drive : Drive
        The design.
    duration_s : float | None
        Simulated time [s].

    Returns
    -------
    LinkLevelView
    """
    return run_bounded(link_level_view, drive, duration_s, seconds=FULL_SECONDS,
                       what="the link-level model", heavy=True)


def bounded_robust_study(drive: Drive) -> RobustResult:
    """:func:`robust_study` in a bounded run.

    Parameters
    ----------
    drive : Drive
        The design.

    Returns
    -------
    RobustResult
        The life curve, probabilities of failure and sensitivity indices.
    """
    return run_bounded(robust_study, drive, seconds=FULL_SECONDS,
                       what="the life and reliability study", heavy=True)
