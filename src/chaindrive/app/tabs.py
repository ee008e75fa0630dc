"""The result tabs and the downloads of the web page (Streamlit): what lies below the
contour and the verdict. Each tab draws only when it is open; figures that take matplotlib
a second are drawn on demand and kept per design, the always-open first tab uses the
browser's own charts. Numbers and units come from :mod:`chaindrive.display` through
:mod:`chaindrive.app.views`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import streamlit as st

from chaindrive._docstrings import shared_parameters
from chaindrive.app import runs
from chaindrive.app.state import design_to_toml
from chaindrive.app.views import (
    Screen,
    identification_records,
    length_option_records,
    line_chart_svg,
    lubrication_records,
    modal_records,
    plain,
    resonance_records,
    selection_records,
    span_records,
    sprocket_records,
    strength_records,
    tension_reading_records,
)
from chaindrive.display import (
    UnitSystem,
    convert,
    finding_lines,
    fmt,
    header,
    quantity_text,
    static_state_note,
    warning_text,
)
from chaindrive.errors import ChainDriveError
from chaindrive.io.record import record_from_csv_bytes
from chaindrive.plotting import campbell_diagram, km_distribution, mode_shapes
from chaindrive.plotting.identification import (
    measured_campbell,
    measured_spectrum,
    order_spectrum,
    runup_campbell,
)
from chaindrive.plotting.robust import (
    life_curve_figure,
    probability_figure,
    sensitivity_figure,
)
from chaindrive.units import RPM_PER_RAD_S

UNEXPECTED = "Something went wrong on the page ({}). Reload the page; if it persists, please "\
             "report it with the design file."
#: The tabs, in order.
TABS = ("Sprockets & spans", "Selection & strength", "Modes & Campbell", "Start-up", "AFC",
        "Link-level model", "Multi-contour", "Life & reliability", "Report & files")


@contextmanager
def _errors_shown() -> Iterator[None]:
    """Run the block; a ChainDriveError it raises is shown as its sentence, anything else as
    :data:`UNEXPECTED` (the page never shows a traceback)."""
    try:
        yield
    except ChainDriveError as exc:
        st.error(str(exc))
    except Exception as exc:
        st.error(UNEXPECTED.format(type(exc).__name__))


def _units() -> UnitSystem:
    return st.session_state.get("units", "SI")  # type: ignore[no-any-return]


def file_name(suffix: str) -> str:
    """The download name: the loaded file's stem with ``suffix``.

    Parameters
    ----------
    suffix : str
        The end of the name (``".pdf"``, ``"_drawing.svg"`` …).

    Returns
    -------
    str
        The file name.
    """
    return Path(st.session_state.get("source") or "design.toml").stem + suffix


def _png(key: str, make: Callable[[], Any]) -> None:
    """Show a matplotlib figure (rendered once per design and figure key)."""
    cache = st.session_state.setdefault("png_cache", {})
    if key not in cache:
        if len(cache) > 24:
            cache.clear()
        cache[key] = runs.figure_png(make())
    st.image(cache[key], width="stretch")


def _spans(screen: Screen) -> list[str]:
    return [f"{s.start_name}→{s.end_name}" for s in screen.outcome.analysis.geometry.spans]


@shared_parameters
def tab_geometry(screen: Screen) -> None:
    """Sprockets and spans; chain speed and ratio over a tooth period (small SVG charts).

    %(params_screen)s
    """
    doc, units = screen.document or {}, _units()
    st.dataframe(sprocket_records(doc, units), hide_index=True, width="stretch")
    st.dataframe(span_records(doc, units), hide_index=True, width="stretch")
    if doc:
        lengths, lube = st.columns([3, 2])
        with lengths:
            tight = doc["geometry"]["length_options"]["tight_length_pitches"]
            st.markdown(f"**Chain length options** (tight length as designed {fmt(tight)} "
                        "pitches; pick one with `links` in `[chain]`)")
            st.dataframe(length_option_records(doc, units), hide_index=True, width="stretch")
        with lube:
            st.markdown("**Lubrication** at the chain speed")
            st.dataframe(lubrication_records(doc, units), hide_index=True, width="stretch")
            note = doc["lubrication"]["note"]
            st.caption(f"{note[:1].upper() + note[1:] + '. ' if note else ''}Source: "
                       f"{doc['lubrication']['source']}")
    a = screen.outcome.analysis
    kin = a.kinematics
    beta = np.degrees(kin.phase)
    factor, unit = convert(1.0, "velocity", units)
    tight = next((s for s in a.geometry.spans if s.tight), a.geometry.spans[0])
    other = a.drive.sprockets[tight.start]
    c1, c2 = st.columns(2)
    c1.image(line_chart_svg(beta, {"chain speed v(β)": np.asarray(kin.chain_speed_trace)
                                  * (factor or 1.0)},
                           x_label="driver rotation within one tooth β [°]",
                           y_label=f"chain speed [{unit}]"), width="stretch")
    c2.image(line_chart_svg(beta, {f"ω₁/ω₂, {a.drive.driver.name} → {other.name}":
                                  kin.ratio_traces[tight.start]},
                           x_label="driver rotation within one tooth β [°]",
                           y_label="transmission ratio"), width="stretch")
    _tension_tool(screen)
    _identify_tool(screen)


def _tension_tool(screen: Screen) -> None:
    """The span tension from a measured transverse frequency (``chaindrive tension``): a
    fitter plucks a span, reads its frequency and sees the tension beside what the design
    expects (docs/identification.md)."""
    a = screen.outcome.analysis
    if a is None:
        return
    with st.expander("Span tension from a measured frequency"):
        names = [f"{s.start_name}-{s.end_name}" for s in a.geometry.spans]
        c1, c2, c3, c4 = st.columns([2, 2, 1, 1])
        span = c1.selectbox("span", names, key="tension.span")
        freq = c2.number_input("measured frequency [Hz]", min_value=0.0, value=0.0,
                               step=0.1, key="tension.frequency")
        mode = int(c3.number_input("mode n", min_value=1, max_value=20, value=1,
                                   key="tension.mode"))
        running = c4.checkbox("running", key="tension.running",
                              disabled=a.drive.driver.speed is None)
        if freq <= 0.0:
            st.caption("Pluck the span sideways, measure its frequency (a phone's spectrum "
                       "app), enter it: the tension is read by the axially moving string law "
                       "with its uncertainty from ±2 mm of span length and ±5 % of the "
                       "chain's mass per metre (assumed; `chaindrive tension` sets them).")
            return
        # imported when a frequency is given: chaindrive.identification imports
        # scipy.signal and scipy.stats, which nothing else of the page needs (1.5 s of a
        # page's first run on the loaded 2-core machine)
        from chaindrive.identification import span_tension_reading

        try:
            reading = span_tension_reading(a, span, float(freq), mode=mode, running=running,
                                           assumed=("length ±2 mm", "mass per metre ±5 %"))
        except ChainDriveError as exc:
            st.error(plain(str(exc)))
            return
        st.dataframe(tension_reading_records(reading.to_dict(), _units()), hide_index=True,
                     width="stretch")
        st.caption("Assumed: span length ±2 mm, mass per metre ±5 % (rectangular); the sag's "
                   "in-plane stiffening is not applied (a sideways pluck).")


@shared_parameters
def tab_strength(screen: Screen) -> None:
    """The chain selection and the loads and static strength, as tables with units.

    %(params_screen)s
    """
    import pandas as pd

    doc, units = screen.document or {}, _units()
    sel = doc.get("selection")
    if sel is not None:
        what = sel["chain"] or quantity_text(sel["shortfall"], sel.get("shortfall_quantities"),
                                             units)
        st.write(f"Selection by **{plain(sel['method'])}**: {plain(what)}")
        for kind, text in finding_lines(sel, units):
            st.warning(f"**{plain(kind)}**: {plain(text)}")
        st.dataframe(selection_records(sel, units), hide_index=True, width="stretch")
    st_doc = doc.get("strength")
    if st_doc is None:
        st.info("No strength check: give the power of the drive.")
        return
    c1, c2 = st.columns([1, 1])
    c1.dataframe(strength_records(st_doc, units), hide_index=True, width="stretch")
    force = header("static tension", "t_n", units)
    factor = convert(1.0, "force", units)[0] or 1.0
    frame = pd.DataFrame({"span": _spans(screen),
                          force: [v * factor for v in st_doc["span_tensions_n"]]})
    c2.bar_chart(frame, x="span", y=force, horizontal=len(frame) > 8, height=320)


@shared_parameters
def tab_modes(screen: Screen) -> None:
    """Natural frequencies, the resonance table, the Campbell diagram and the mode shapes
    (figures drawn when the tab is opened).

    %(params_screen)s
    """
    doc = screen.document or {}
    a = screen.outcome.analysis

    c1, c2 = st.columns([1, 2])
    with c1:
        st.dataframe(modal_records(doc), hide_index=True, width="stretch")
        res = resonance_records(doc, _spans(screen))
        if res:
            st.dataframe(res, hide_index=True, width="stretch")
    with c2:
        if a.dynamics.campbell is not None:
            rpm = doc["drive"]["driver_speed_rpm"]
            band = a.limits.resonance_band_percent
            _png(f"{id(a)}-campbell", lambda: campbell_diagram(
                a.dynamics.campbell, operating_rpm=rpm, band_percent=band))
        names = [s.name for s in a.drive.sprockets]
        _png(f"{id(a)}-modes", lambda: mode_shapes(a.dynamics.modal, names=names))


#: Largest record the page reads [bytes] (Streamlit's upload limit is the same).
MAX_RECORD_BYTES = 1024 * 1024


def _identify_tool(screen: Screen) -> None:
    """A measured record matched to the model (``chaindrive identify``): upload a CSV, pick
    the driver speed column of a run-up if it has one, and read the spectrum with the
    model's frequencies, the peaks' labels and half-power damping ratios, and for a run-up
    the order spectrum and the Campbell diagram with the measured points
    (docs/identification.md)."""
    a = screen.outcome.analysis
    if a is None:
        return
    with st.expander("Identify a measured record"):
        upload = st.file_uploader("record (CSV: a time_s or time_ms column and signals)",
                                  type=["csv"], key="ident.record")
        if upload is None:
            st.caption("A vibration record of the built drive (acceleration, speed, force …; "
                       "each column's unit in its name): its peaks are set against the "
                       "model's natural, working and span frequencies. A run-up with a driver "
                       "speed column (speed_rpm, omega_rad_s) also gives its order spectrum.")
            return
        data = upload.getvalue()
        if len(data) > MAX_RECORD_BYTES:
            st.error(f"{plain(upload.name)}: {len(data):,} bytes; the page reads records of at "
                     f"most {MAX_RECORD_BYTES:,} bytes (use `chaindrive identify` for more)")
            return
        try:
            record = record_from_csv_bytes(upload.name, data)
        except ChainDriveError as exc:
            st.error(plain(str(exc)))
            return
        speed = st.selectbox("driver speed column (a run-up)", ["none", *record.signals],
                             key="ident.speed")
        key = (id(a), hash(data), speed)
        store = st.session_state.setdefault("ident", {})
        if key not in store:
            from chaindrive.identification import identify_record  # as in _tension_tool

            store.clear()
            try:
                store[key] = identify_record(record, a,
                                             speed=None if speed == "none" else speed)
            except ChainDriveError as exc:
                st.error(plain(str(exc)))
                return
        result = store[key]
        doc = result.to_dict()
        st.dataframe(identification_records(doc), hide_index=True, width="stretch")
        for note in doc["notes"]:
            st.caption(plain(note))
        st.caption("ζ half-power: (f₂ − f₁)/(2 f) where the half-power band spans 8 bins or "
                   "more with 16 segments or more averaged; otherwise not resolved (a forced "
                   "line, or a record too short). Matching tolerance ±5 % of a natural or "
                   "span frequency, ±1 % of a working frequency, at least one bin.")
        c1, c2 = st.columns(2)
        with c1:
            _png(f"{key}-spectrum", lambda: measured_spectrum(result.spectrum))
            if result.orders is not None:
                _png(f"{key}-orders", lambda: order_spectrum(result.orders))
        with c2:
            campbell = a.dynamics.campbell
            rpm = screen.document["drive"]["driver_speed_rpm"] if screen.document else None
            if campbell is not None and rpm is not None:
                _png(f"{key}-campbell", lambda: (
                    measured_campbell(result.spectrum, campbell, rpm) if result.orders is None
                    else runup_campbell(result.orders, campbell, rpm)))


def _available(feature: str, label: str) -> bool:
    """Whether the on-demand ``feature`` (a key of :data:`chaindrive.app.runs.NEEDS`) can
    run in this installation; when it cannot, the reason is shown after ``label``."""
    reason = runs.missing(feature)
    if reason is not None:
        st.info(f"{label}: {reason}.")
    return reason is None


def _full(screen: Screen, label: str, button: str, draw: Callable[[Any], None]) -> None:
    """``draw`` the full analysis of the design on screen (run on demand, kept per design);
    until the user asks for it, or when it cannot run, what is missing is shown instead."""
    if not _available("response", label):
        return
    drive = screen.outcome.drive
    store = st.session_state.setdefault("full", {})
    key = id(screen)
    if key not in store and st.button(button, key=f"run_{label}"):
        with st.status(f"{label}: running the dynamic analysis…", expanded=False) as status:
            try:
                store[key] = runs.bounded_full_analysis(drive)
                status.update(label=f"{label}: done", state="complete")
            except ChainDriveError as exc:
                store[key] = exc
                status.update(label=f"{label}: {exc}", state="error")
            except Exception as exc:
                store[key] = RuntimeError(UNEXPECTED.format(type(exc).__name__))
                status.update(label=f"{label}: failed", state="error")
    result = store.get(key)
    if isinstance(result, Exception):
        st.error(str(result))
    elif result is None:
        st.caption("Runs on demand (a second or so); the results are for the design as it "
                   "is now, with the settings of its [dynamics] table.")
    elif result.response is None:
        st.info("No dynamic response: it needs the power of the drive and the driver speed.")
    else:
        draw(result)


def _span_force_chart(full: Any, forces: Any, x: Any, x_label: str, y_label: str) -> None:
    """A line chart of the span forces [N] (one column per span of the full analysis
    ``full``, one row per ``x``), in the page's force unit."""
    import pandas as pd

    names = [f"{s.start_name}→{s.end_name}" for s in full.geometry.spans]
    factor, force = convert(1.0, "force", _units())
    frame = pd.DataFrame(forces * (factor or 1.0), columns=names,
                         index=pd.Index(x, name=x_label))
    st.line_chart(frame, x_label=x_label, y_label=f"{y_label} [{force}]")


@shared_parameters
def tab_startup(screen: Screen) -> None:
    """The start-up transient, on demand.

    %(params_screen)s
    """
    _full(screen, "Start-up", "Run the start-up simulation", _startup)


def _startup(full: Any) -> None:
    """The start-up transient of the full analysis ``full``: its figures and span forces."""
    result = full.response.startup
    if result is None:
        st.info("The start-up is switched off (transient = false in [dynamics]).")
        return
    d = result.to_dict()
    units = _units()
    factor, force = convert(1.0, "force", units)
    c = st.columns(4)
    c[0].metric(f"largest span force F₁max [{force}]", fmt(d["max_force_n"] * (factor or 1.0)))
    rigid = full.runup
    c[1].metric("run-up [s]", fmt(d["runup_time_s"]),
                help="the driver at 95 % of its working speed from then on"
                + ("" if rigid is None else
                   f"; the drive as one rigid body: {fmt(rigid.runup_time)} s"))
    c[2].metric("decay after it [s]", fmt(d["decay_time_s"]),
                help=(f"every span force in its final band after {fmt(d['settling_time_s'])} s"
                      if d["settled"] else "the span forces have not settled within the "
                      f"simulated {fmt(d['simulated_time_s'])} s"))
    c[3].metric("k₁ = Q / F₁max", fmt(d["k1"]),
                help=None if d["settled"] else
                "of a start-up record that ends before it settles: its check cannot be "
                "verified, or fails if already below [k]")
    for w in full.warnings:
        if w.code.startswith("dynamics.startup"):
            st.warning(plain(warning_text(w, _units())))
    step = max(1, len(result.times) // 1500)
    _span_force_chart(full, result.span_forces[::step], result.times[::step], "time [s]",
                      "span force")


@shared_parameters
def tab_afc(screen: Screen) -> None:
    """The amplitude–frequency characteristic and the dynamic safety factors, on demand.

    %(params_screen)s
    """
    _full(screen, "AFC", "Run the AFC sweep", _afc)


def _afc(full: Any) -> None:
    """The AFC and the dynamic safety factors of the full analysis ``full``."""
    response = full.response
    afc = response.afc
    _span_force_chart(full, afc.span_load, afc.driver_speeds * RPM_PER_RAD_S,
                      "driver speed [rpm]", "peak dynamic span load")
    s = response.strength_dict()
    c = st.columns(4)
    c[0].metric("K_D", fmt(response.steady.coefficient_of_dynamics))
    c[1].metric("k₂", fmt(s["k2"]))
    c[2].metric("k₂min", fmt(s["k2min"]))
    c[3].metric("allowable [k]", fmt(s["allowable_k"]))


def _comparison_records(doc: dict[str, Any], units: UnitSystem) -> list[dict[str, str]]:
    """The rows of the model comparison for a table, forces in ``units``."""
    out = []
    for r in doc["rows"]:
        whole, link, unit = r["whole_drive"], r["link_level"], r["unit"]
        if unit == "N":
            (whole, unit), (link, _) = convert(whole, "force", units), convert(link, "force",
                                                                               units)
        out.append({"quantity": r["quantity"], "whole drive": fmt(whole),
                    "link level": fmt(link), "unit": "" if unit == "1" else unit})
    return out


@shared_parameters
def tab_links(screen: Screen) -> None:
    """The link-level model beside the whole-drive model, run on request in a bounded child
    process (it is slower than the ring: seconds per simulated second on large contours).

    %(params_screen)s
    """
    if not _available("links", "Link-level model"):
        return
    drive = screen.outcome.drive
    store = st.session_state.setdefault("links", {})
    default = min(drive.dynamics.startup_duration or 1.0, 1.0)
    c1, c2 = st.columns([1, 2], vertical_alignment="bottom")
    seconds = c1.number_input("Simulated time [s]", value=default, min_value=0.001,
                              step=0.1, format="%g", key="links_duration",
                              help="a start-up from rest; at most 10 s")
    key = (id(screen), float(seconds))
    if key not in store and c2.button("Run the link-level model", key="run_links"):
        with st.status("Link-level model: simulating the chain link by link…",
                       expanded=False) as status:
            try:
                store[key] = runs.bounded_link_level(drive, float(seconds))
                status.update(label="Link-level model: done", state="complete")
            except ChainDriveError as exc:
                store[key] = exc
                status.update(label=f"Link-level model: {exc}", state="error")
            except Exception as exc:
                store[key] = RuntimeError(UNEXPECTED.format(type(exc).__name__))
                status.update(label="Link-level model: failed", state="error")
    view = store.get(key)
    if view is None:
        st.caption("Every link a body, every roller on the real tooth gap: runs on request "
                   "(a start-up from rest, slower than the whole-drive model).")
        return
    if isinstance(view, Exception):
        st.error(str(view))
        return
    doc = view.comparison
    st.write(f"Start-up from rest over {fmt(doc['duration_s'])} s (step "
             f"{fmt(view.time_step_s * 1e6)} µs); steady quantities over the closing half, "
             f"from t = {fmt(doc['steady_from_s'])} s.")
    stopped = static_state_note(view.equilibrium, _units())
    if stopped is not None:
        st.warning(stopped)
    if not doc["settled"]:
        st.warning("The driver had not reached its nominal speed by then: the link-level "
                   "steady quantities still hold the start-up; run longer for steady ones.")
    st.dataframe(_comparison_records(doc, _units()), hide_index=True, width="stretch")
    st.image(view.frames_png, width="stretch")
    st.image(view.tensions_png, width="stretch")


@shared_parameters
def tab_contours(screen: Screen) -> None:
    """The load share of identical contours side by side [Lyashuk].

    %(params_screen)s
    """
    a = screen.outcome.analysis
    if a.contours is None:
        st.info("Single contour. Set “Contours” above 1 (identical chains side by side on "
                "common shafts) to check how the load shares between them.")
        return
    rows = [{"quantity": k.replace("_", " "), "value": fmt(v)}
            for k, v in a.contours.to_dict().items() if not isinstance(v, dict | list)]
    st.dataframe(rows, hide_index=True, width="stretch")
    km = getattr(a.contours, "samples", None)
    if km is not None:

        _png(f"{id(a)}-km", lambda: km_distribution(km))


#: The downloads built on demand: kind → (button label, file suffix, MIME type).
DOWNLOADS = {"report_pdf": ("report (PDF)", ".pdf", "application/pdf"),
             "report_html": ("report (HTML)", ".html", "text/html"),
             "drawing_svg": ("drawing (SVG)", ".svg", "image/svg+xml"),
             "drawing_dxf": ("drawing (DXF)", ".dxf", "application/dxf")}


def tab_robust(screen: Screen) -> None:
    """Life and reliability: the robust study on demand (:mod:`chaindrive.robust`), in a
    bounded run (:func:`chaindrive.app.runs.bounded_robust_study`).

    Parameters
    ----------
    screen : Screen
        The quick screen of the design on the page.
    """
    if not _available("robust", "Life and reliability"):
        return
    store = st.session_state.setdefault("robust", {})
    key = id(screen)
    if key not in store and st.button("Run the life and reliability study", key="run_robust"):
        with st.status("Life and reliability: wearing the chain and sampling the tolerances…",
                       expanded=False) as status:
            try:
                store[key] = runs.bounded_robust_study(screen.outcome.drive)
                status.update(label="Life and reliability: done", state="complete")
            except ChainDriveError as exc:
                store[key] = exc
                status.update(label=f"Life and reliability: {exc}", state="error")
    result = store.get(key)
    if isinstance(result, Exception):
        st.error(str(result))
        return
    if result is None:
        st.caption("Runs on demand (half a minute or so): the drive as its chain wears to the "
                   "replacement elongation, the probability of failing each check over the "
                   "tolerances of the standards, and which tolerance matters (docs/robust.md).")
        return

    life = result.life.to_dict()
    c = st.columns(3)
    c[0].metric("replacement elongation", f"{life['allowable_elongation']:.2%}")
    first = life["first_failure_elongation"]
    c[1].metric("first failure", "—" if first is None else f"{first:.3%}",
                help=life["first_failure"])
    c[2].metric("life [h]", "—" if life["life_hours"] is None else f"{life['life_hours']:,.0f}")
    _png(f"{key}-life", lambda: life_curve_figure(result.life))
    st.dataframe([c.to_dict() for c in result.reliability.checks], hide_index=True)
    _png(f"{key}-probability", lambda: probability_figure(result.reliability))
    if result.sensitivity is not None:
        _png(f"{key}-sensitivity", lambda: sensitivity_figure(result.sensitivity))


def _build(kind: str, screen: Screen) -> bytes:
    """The bytes of a download, each built in a bounded run (:mod:`chaindrive.app.runs`):
    the drawing of the design, or the report of its full analysis."""
    if kind.startswith("drawing"):
        return runs.bounded_drawing(screen.outcome.analysis, kind.rsplit("_", 1)[1])
    with st.spinner("Running the full analysis and building the report…"):
        return runs.bounded_report(screen.outcome.drive, kind.rsplit("_", 1)[1], _units())


@shared_parameters
def tab_files(screen: Screen, design: dict[str, Any]) -> None:
    """Downloads: the design (TOML), the report (PDF, HTML) and the drawing (SVG, DXF).

    %(params_screen_design)s
    """
    a = screen.outcome.analysis
    store = st.session_state.setdefault("files", {})
    cols = st.columns(5)
    with cols[0]:
        st.download_button("Download design (TOML)", design_to_toml(design), key="dl_toml",
                           file_name=file_name(".toml"), mime="application/toml",
                           on_click="ignore")
    for col, (kind, (label, suffix, mime)) in zip(cols[1:], DOWNLOADS.items(), strict=True):
        with col:
            if not _available(kind, f"The {label}"):
                continue
            key = (kind, id(a), _units())
            if key not in store and st.button(f"Build {label}", key=f"build_{kind}"):
                with _errors_shown():
                    store[key] = _build(kind, screen)
            if key in store:
                st.download_button(f"Download {label}", store[key],
                                   file_name=file_name(suffix), mime=mime,
                                   key=f"dl_{kind}", type="primary", on_click="ignore")


@shared_parameters
def tabs(screen: Screen, design: dict[str, Any]) -> None:
    """The result tabs; only the open one is drawn, an error in it is shown in it.

    %(params_screen_design)s
    """
    shows = (lambda: tab_geometry(screen), lambda: tab_strength(screen),
             lambda: tab_modes(screen), lambda: tab_startup(screen), lambda: tab_afc(screen),
             lambda: tab_links(screen), lambda: tab_contours(screen),
             lambda: tab_robust(screen),
             lambda: tab_files(screen, design))
    for tab, show in zip(st.tabs(list(TABS), key="tabs", on_change="rerun"), shows,
                         strict=True):
        if tab.open:
            with tab, _errors_shown():
                show()
