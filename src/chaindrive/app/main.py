"""The chaindrive web page (Streamlit): build or load a design, see at once whether it works.

Run it with ``chaindrive app`` (or :func:`chaindrive.app.run_app`). The page only edits and
shows: the form becomes a design mapping (:mod:`chaindrive.app.state`), the mapping is
analysed, and what is on screen comes from :mod:`chaindrive.app.views`; the tabs and
downloads are in :mod:`chaindrive.app.tabs`, the on-demand work in :mod:`chaindrive.app.runs`.

Layout (1400×900 and down to 1024×768): the drive and chain fields and the "edit one
sprocket" form on the left, the contour and the verdict on the right — both above the fold —
then the sprocket table, then the tabs. After an edit the contour, the headline numbers and
the checks are drawn first (:func:`chaindrive.app.views.quick_screen`); the chain selection,
the warnings and the tabs follow in the same run.
"""

from __future__ import annotations

import html
import json
import os
import threading
import time
import zlib
from collections import OrderedDict
from collections.abc import Generator, Iterator
from pathlib import Path
from typing import Any

import streamlit as st

from chaindrive import catalog
from chaindrive.app import runs, tabs
from chaindrive.app.early import (
    CHAIN_PREFIX,
    FORMS,
    chain_values,
    design_from_state,
    drive_values,
)
from chaindrive.app.state import (
    SPROCKET_COLUMNS,
    DesignForm,
    apply_sprocket_edit,
    design_from_form,
    design_to_toml,
    edit_values,
    example_text,
    form_from_design,
    is_empty,
    list_examples,
    read_design_text,
    sprocket_label,
)
from chaindrive.app.table import sprocket_table
from chaindrive.app.uploads import Uploads, design_text
from chaindrive.app.views import Check, Screen, check_records, checks, plain
from chaindrive.display import UNIT_SYSTEMS, UnitSystem, convert, fmt, warning_text
from chaindrive.errors import ChainDriveError
from chaindrive.model import ROLES, SIDES

DEFAULT_EXAMPLE = "seed_three_sprocket"
AUTO_CHAIN = CHAIN_PREFIX + "{})"
STANDARDS = ("ISO 606", "GOST 13568", "ANSI")
UNEXPECTED = tabs.UNEXPECTED
#: Page styles: less space above the page, a compact title, the warnings in a scroll box.
CSS = """<style>
.block-container{padding-top:3.6rem;padding-bottom:2rem}
h1{font-size:1.45rem !important;padding:0 0 .2rem 0 !important}
[data-testid="stMetricValue"]{font-size:1.55rem}
.st-key-warnings{max-height:150px;overflow-y:auto}
.st-key-verdict div[data-testid="stAlert"]{padding:.2rem .2rem}
</style>"""


# --- session state -------------------------------------------------------------------------------

def _load(data: dict[str, Any], source: str) -> None:
    """Put a design mapping into the form (new widget keys, so every field re-reads it)."""
    st.session_state["form"] = form_from_design(data)
    st.session_state["source"] = source
    st.session_state["version"] = st.session_state.get("version", 0) + 1
    st.session_state["loads"] = st.session_state.get("loads", 0) + 1
    st.session_state.pop("load_error", None)
    # a new file: the edit form starts at its first row (its chooser's key is new), the
    # deltas at the file's own numbers
    st.session_state.pop("previous_numbers", None)


def _load_example(name: str) -> None:
    try:
        _load(read_design_text(example_text(name), f"{name}.toml"), f"{name}.toml")
    except ChainDriveError as exc:
        st.session_state["load_error"] = str(exc)


def _init() -> None:
    if "form" in st.session_state:
        return
    examples = list_examples()
    if DEFAULT_EXAMPLE in examples:
        _load_example(DEFAULT_EXAMPLE)
    elif examples:
        _load_example(examples[0])
    else:
        st.session_state["form"] = DesignForm({"name": "new drive"}, {}, [])
        st.session_state["source"] = "design.toml"
        st.session_state["version"] = st.session_state["loads"] = 1


def _key(name: str) -> str:
    """A widget key that changes with each loaded file (its widgets then read the file)."""
    return f"{name}@{st.session_state.get('loads', 0)}"


def _table_key() -> str:
    """The key of the sprocket table: new with each file and each applied edit of the
    "edit one sprocket" form (the table then shows the edited rows); the other widgets keep
    theirs, so an edit redraws the table alone."""
    return _key(f"sprockets.{st.session_state.get('table_rev', 0)}")


# --- sidebar: files ------------------------------------------------------------------------------

def _sidebar(design: dict[str, Any] | None) -> None:
    sb = st.sidebar
    sb.header("Design file")
    examples = list_examples()
    if examples:
        name = sb.selectbox("Bundled examples", list(examples), key="example",
                            index=list(examples).index(DEFAULT_EXAMPLE)
                            if DEFAULT_EXAMPLE in examples else 0)
        if sb.button("Load example", key="load_example", width="stretch"):
            _load_example(name)
            st.rerun()
    upload = sb.file_uploader("Open a design (TOML)", type=["toml"], key="upload")
    if upload is not None and st.session_state.get("uploaded") != upload.file_id:
        st.session_state["uploaded"] = upload.file_id
        try:
            text = design_text(upload.name, upload.getvalue())
            _load(read_design_text(text, upload.name), upload.name)
            st.rerun()
        except ChainDriveError as exc:
            st.session_state["load_error"] = str(exc)
    _catalog_upload(sb)
    if "load_error" in st.session_state:
        sb.error(st.session_state["load_error"])
    if design is not None:
        sb.download_button("Save design (TOML)", design_to_toml(design),
                           file_name=tabs.file_name(".toml"), mime="application/toml",
                           key="save_toml", width="stretch", on_click="ignore")
    sb.radio("Units of the results", UNIT_SYSTEMS, key="units", horizontal=True,
             format_func=lambda u: "SI (mm, N, kW)" if u == "SI" else "US (in, lbf, hp)",
             help="the units of the results, tables and report; the form is in mm, kW, rpm")
    sb.caption(f"Loaded: {st.session_state.get('source', '—')}. Edits apply at once (the "
               "“edit one sprocket” form on Apply); a field with a bad value shows the same "
               "message as `chaindrive analyze`.")


def _catalog_upload(sb: Any) -> None:
    """The catalogue files of this session: a design's ``chain.catalog`` names one of them
    (never a file of the server)."""
    uploads: Uploads = st.session_state.setdefault("uploads", Uploads())
    files = sb.file_uploader("Add a catalogue (CSV or TOML)", type=["csv", "toml"],
                             key="catalog_upload", accept_multiple_files=True)
    seen = st.session_state.setdefault("catalog_ids", set())
    for f in files or []:
        if f.file_id in seen:
            continue
        seen.add(f.file_id)
        try:
            uploads.add(f.name, f.getvalue())
            st.session_state.pop("catalog_error", None)
        except ChainDriveError as exc:
            st.session_state["catalog_error"] = str(exc)
    if "catalog_error" in st.session_state:
        sb.error(st.session_state["catalog_error"])
    if uploads.content:
        sb.caption("Catalogues of this session (name them in chain.catalog): "
                   + ", ".join(uploads.content))


def _catalogs() -> dict[str, str]:
    """Name → file of the catalogues uploaded in this session."""
    uploads: Uploads = st.session_state.setdefault("uploads", Uploads())
    return {k: str(v) for k, v in uploads.paths().items()}


# --- the form ------------------------------------------------------------------------------------

def _chain_options(current: str | None) -> list[str]:

    names = [c.designation for c in catalog.chains()]
    if current and current not in names:
        try:
            current_name = catalog.find_chain(current).designation
        except ChainDriveError:
            current_name = current
        if current_name not in names:
            names.insert(0, current_name)
    return [AUTO_CHAIN.format(s) for s in STANDARDS] + names


def _chain_choice(chain: dict[str, Any]) -> str:

    designation = chain.get("designation")
    if designation:
        try:
            return catalog.find_chain(designation).designation
        except ChainDriveError:
            return str(designation)
    return AUTO_CHAIN.format(chain.get("standard") or "ISO 606")


def _number(label: str, value: Any, key: str, *, step: float | int, help_text: str,
            fmt: str | None = None) -> Any:
    return st.number_input(label, value=None if is_empty(value) else value, step=step,
                           key=_key(key), help=help_text, format=fmt, placeholder="default")


def _field(slots: dict[tuple[str, str], Any], where: tuple[str, str], draw: Any) -> Any:
    """Draw a field and reserve the place under it for its error message."""
    value = draw()
    slots[where] = st.empty()
    return value


def _drive_fields(base: DesignForm, slots: dict[tuple[str, str], Any]
                  ) -> tuple[dict[str, Any], list[Any]]:
    """Name and tooth form on one row, power and service factor on the next; returns the
    fields' values and the column left on that row for :func:`_chain_fields`."""
    d = base.drive
    c1, c2 = st.columns([2.3, 1.3])
    with c1:
        name = _field(slots, ("drive", "name"), lambda: st.text_input(
            "Drive name", value=d.get("name") or "", key=_key("drive.name")))
    with c2:
        forms: list[str] = list(FORMS)
        given = d.get("tooth_form")
        current = forms.index(given) if given in forms else 0
        tooth_form = _field(slots, ("drive", "tooth_form"), lambda: st.selectbox(
            "Tooth form", forms, index=current, key=_key("drive.tooth_form")))
    c3, c4, c5 = st.columns(3)
    with c3:
        power = _field(slots, ("drive", "power_kw"), lambda: _number(
            "Power [kW]", d.get("power_kw"), "drive.power", step=0.1, fmt="%g",
            help_text="power transmitted from the driver; empty: no strength check"))
    with c4:
        sf = _field(slots, ("drive", "service_factor"), lambda: _number(
            "Service factor", d.get("service_factor"), "drive.sf", step=0.1, fmt="%g",
            help_text="application factor, 1 to 5"))
    return drive_values(d, name, tooth_form, power, sf), [c5]


def _chain_fields(base: DesignForm, slots: dict[tuple[str, str], Any], columns: list[Any]
                  ) -> dict[str, Any]:
    """Strands in ``columns`` (beside the power); the chain, links and contours below, and
    odd links."""
    ch = dict(base.chain)
    (c_strands,) = columns
    with c_strands:
        strands = _field(slots, ("chain", "strands"), lambda: _number(
            "Strands", ch.get("strands"), "chain.strands", step=1,
            help_text="rows of the chain (default 1)"))
    # chain and links on one row; contours, sag and stiffness on the next (three equal
    # columns keep every label whole down to a 1024 px window with the sidebar open); the
    # odd-links box below
    c1, c_links = st.columns([2.2, 1.0], vertical_alignment="bottom")
    with c1:
        options = _chain_options(ch.get("designation"))
        choice = _field(slots, ("chain", "designation"), lambda: st.selectbox(
            "Chain (type to search the catalogue)", options,
            index=options.index(_chain_choice(ch)), key=_key("chain.choice")))
    with c_links:
        links = _field(slots, ("chain", "links"), lambda: _number(
            "Links", ch.get("links"), "chain.links", step=1,
            help_text="impose the number of links; empty: the nearest even number that fits"))
    c_contours, c_sag, c_stiffness = st.columns(3, vertical_alignment="bottom")
    with c_contours:
        contours = _field(slots, ("chain", "contours"), lambda: _number(
            "Contours", ch.get("contours"), "chain.contours", step=1,
            help_text="identical contours side by side on common shafts, default 1"))
    with c_sag:
        sag = _field(slots, ("chain", "sag"), lambda: _number(
            "Installed sag", ch.get("sag"), "chain.sag", step=0.005, fmt="%g",
            help_text="sag of the slack span as a fraction of its length (e.g. 0.02), up to "
            "0.1; empty: laid out tight, the tensions for an assumed 0.02"))
    with c_stiffness:
        stiffness = _field(slots, ("chain", "link_stiffness_n_per_m"), lambda: _number(
            "Link stiffness [N/m]", ch.get("link_stiffness_n_per_m"), "chain.link_stiffness",
            step=1e7, fmt="%.4g", help_text="the maker's measured stiffness of one link of "
            "the whole chain, F/(ε·p); empty: computed from the plates and the pin"))
    allow_odd = _field(slots, ("chain", "allow_odd"), lambda: st.checkbox(
        "Odd number of links", value=bool(ch.get("allow_odd")),
        key=_key("chain.allow_odd"), help="allowed: it needs an offset link"))
    for key in ("standard", "pitch_mm", "series", "catalog"):
        slots[("chain", key)] = slots[("chain", "designation")]
    return chain_values(ch, strands, choice, links, contours, allow_odd, sag, stiffness)


def _sprocket_table(base: DesignForm) -> list[dict[str, Any]]:
    return sprocket_table(base.sprockets, _table_key(), [m.name for m in catalog.materials()])


def _apply_edit(index: int, keys: dict[str, str], rows: list[dict[str, Any]]) -> None:
    """The "Apply" of the edit form (run by Streamlit before the page's next run): the
    form's values go into row ``index`` of the rows the form was drawn with, which become
    the base of the table; one run then draws the edited design."""
    values = {field: st.session_state.get(key) for field, key in keys.items()}
    values["name"] = (values.get("name") or "").strip() or None
    base: DesignForm = st.session_state["form"]
    st.session_state["form"] = DesignForm(base.drive, base.chain,
                                          apply_sprocket_edit(rows, index, values), base.other)
    st.session_state["version"] += 1
    st.session_state["table_rev"] = st.session_state.get("table_rev", 0) + 1


def _sprocket_editor(rows: list[dict[str, Any]]) -> None:
    """The keyboard-friendly form that edits one sprocket (the table is drawn on a canvas,
    hard to reach with the keyboard or a screen reader); Apply (or Enter in a field) runs
    :func:`_apply_edit`."""

    if not rows:
        return
    if st.session_state.get(_key("edit_row")) not in range(len(rows)):
        st.session_state.pop(_key("edit_row"), None)
    with st.container(key="sprocket_editor", border=True):
        pick, note = st.columns([1.2, 2], vertical_alignment="bottom")
        with pick:
            index = st.selectbox("Sprocket to edit", range(len(rows)), key=_key("edit_row"),
                                 format_func=lambda i: sprocket_label(i, rows[i]))
        note.caption("Edit one sprocket from the keyboard: choose it, change the fields (Tab "
                     "moves on), press Apply or Enter. An empty field takes the default.")
        v = edit_values(rows[index])
        # keyed by the row's values too, so that an edit in the table shows up here
        tag = f"{index}.{zlib.crc32(repr(sorted(v.items())).encode()):08x}"
        with st.form(_key(f"edit_form.{tag}"), border=False, enter_to_submit=True):
            r1 = st.columns([1.4, 0.8, 1.1], vertical_alignment="bottom")
            r2 = st.columns(3, vertical_alignment="bottom")
            r3 = st.columns(3, vertical_alignment="bottom")
            r1[0].text_input("Name", value=v["name"] or "", key=_key(f"edit.name.{tag}"))
            r1[1].number_input("Teeth", value=v["teeth"], step=1,
                               key=_key(f"edit.teeth.{tag}"))
            for col, field, options, empty in ((r1[2], "role", ROLES, "driven"),
                                               (r2[2], "side", SIDES, "outside")):
                opts = list(options)
                col.selectbox(field.capitalize(), opts,
                              index=opts.index(v[field]) if v[field] in opts else None,
                              placeholder=empty, key=_key(f"edit.{field}.{tag}"))
            r2[0].number_input("x [mm]", value=v["x_mm"], step=1.0, format="%.2f",
                               key=_key(f"edit.x.{tag}"))
            r2[1].number_input("y [mm]", value=v["y_mm"], step=1.0, format="%.2f",
                               key=_key(f"edit.y.{tag}"))
            r3[0].number_input("Speed [rpm]", value=v["speed_rpm"], step=10.0, format="%g",
                               placeholder="—", key=_key(f"edit.speed.{tag}"),
                               help="the driver only")
            r3[1].number_input("Power share", value=v["power_share"], step=0.05, format="%g",
                               placeholder="—", key=_key(f"edit.share.{tag}"),
                               help="share of the power taken off (driven)")
            keys = {f: _key(f"edit.{w}.{tag}") for f, w in (
                ("name", "name"), ("teeth", "teeth"), ("x_mm", "x"), ("y_mm", "y"),
                ("role", "role"), ("side", "side"), ("speed_rpm", "speed"),
                ("power_share", "share"))}
            r3[2].form_submit_button("Apply", type="primary", on_click=_apply_edit,
                                     args=(index, keys, [dict(r) for r in rows]),
                                     width="stretch")


# --- results -------------------------------------------------------------------------------------

#: Designs whose screens the page keeps (shared by the sessions).
KEPT = 32


@st.cache_resource(show_spinner=False)
def _finished() -> tuple[OrderedDict[tuple[str, str], Screen], threading.Lock]:
    """The last :data:`KEPT` finished screens (the complete one, or the failure), by design
    and catalogues, and the lock that guards them."""
    return OrderedDict(), threading.Lock()


def _screens(design_json: str, catalogs_json: str = "{}") -> Generator[Screen, None, None]:
    """The screens of a design: the kept one, or those of one bounded run
    (:func:`chaindrive.app.runs.bounded_screens`: the quick part as soon as it is ready,
    then the complete screen)."""
    kept, lock = _finished()
    key = (design_json, catalogs_json)
    with lock:
        done = kept.get(key)
    if done is not None:
        yield done
        return
    catalogs = {k: Path(v) for k, v in json.loads(catalogs_json).items()}
    for screen in runs.bounded_screens(json.loads(design_json), catalogs):
        if screen.document is not None or not screen.outcome.ok:
            with lock:
                kept[key] = screen
                while len(kept) > KEPT:
                    kept.popitem(last=False)
        yield screen


def _show_error(screen: Screen, slots: dict[tuple[str, str], Any], table_slot: Any,
                general: Any, rows: list[dict[str, Any]]) -> None:
    out = screen.outcome
    loc = out.location
    if out.message is None or loc is None:
        return
    if out.unexpected:
        general.error(f"Could not analyse this design: {out.message}.")
        return
    if loc.section in ("drive", "chain") and (loc.section, loc.key) in slots:
        slots[(loc.section, loc.key)].error(out.message, icon="⚠️")
    elif loc.section == "sprockets":
        where = ""
        if loc.row is not None and loc.row < len(rows):
            label = next((c.label for c in SPROCKET_COLUMNS if c.key == loc.key), loc.key)
            name = rows[loc.row].get("name")
            where = (f"row {loc.row + 1} ({'unnamed' if is_empty(name) else name})"
                     + (f", column “{label}”" if label else "") + " — ")
        table_slot.error(f"{where}{out.message}", icon="⚠️")
    else:
        general.error(out.message, icon="⚠️")


def _units() -> UnitSystem:
    return st.session_state.get("units", "SI")  # type: ignore[no-any-return]


def _headline(screen: Screen) -> None:
    """Links, chain length, chain speed, tooth frequency (with the change the last edit of
    this design made) and a line on the chain and its slack."""
    n = screen.numbers or {}
    before = st.session_state.get("previous_numbers") or {}
    units = _units()
    length, lu = convert(n["chain_length_m"], "length", units)
    speed, vu = convert(n["chain_speed_m_s"], "velocity", units)
    slack, _ = convert(n["slack_m"], "length", units)

    def delta(key: str) -> str | None:
        if key not in before or before[key] == n[key]:
            return None
        change = n[key] - before[key]
        if key == "links":
            return f"{change:+d}"
        return f"{'+' if change > 0 else ''}{fmt(convert(change, 'length', units)[0])}"

    with st.container(key="headline", horizontal=True):
        st.metric("Links", n["links"], delta=delta("links"), delta_color="off")
        st.metric(f"Chain length [{lu}]", fmt(length), delta=delta("chain_length_m"),
                  delta_color="off")
        st.metric(f"Chain speed [{vu}]", fmt(speed))
        st.metric("Tooth frequency [Hz]", fmt(n["tooth_frequency_hz"]))
    text = f"Chain {n['chain']}; slack {fmt(slack)} {lu}"
    if n["adjusted_sprocket"]:
        text += (f"; take-up: {n['adjusted_sprocket']} moved "
                 f"{fmt(convert(n['adjustment_m'], 'length', units)[0])} {lu}")
    st.caption(plain(text))
    st.session_state["previous_numbers"] = n


def _checks(screen: Screen) -> tuple[Check, ...]:
    """The checks of the screen in the page's unit system (the screen holds them in SI)."""
    units, analysis = _units(), screen.outcome.analysis
    if units == "SI" or analysis is None or not screen.checks:
        return screen.checks
    return tuple(checks(analysis, units))


#: What the screen's verdict does not judge (it runs without the dynamic response, as
#: ``analyze --quick`` does, which says the same).
SCREEN_LEAVES_OUT = ("Checked without the dynamic response, which judges k1 (tab Start-up), "
                     "k2 and k2min (tab AFC) and the chain's fatigue (chaindrive analyze).")


def _verdict(screen: Screen) -> None:
    """The verdict of the checks and each one that does not pass."""
    shown = _checks(screen)
    failed = [c for c in shown if not c.passed]
    with st.container(key="verdict"):
        if not failed:
            st.success(f"All {len(shown)} checks of the screen pass.")
        for c in failed:
            st.error(plain(c.line))
        st.caption(SCREEN_LEAVES_OUT)


def _warnings(screen: Screen) -> None:
    """The warnings of the analysis (from its document), in the page's unit system."""
    warnings, units = (screen.document or {}).get("warnings", []), _units()
    with st.container(key="warnings"):
        if not warnings:
            st.caption("No warnings.")
        for w in warnings:
            st.warning(plain(warning_text(w, units)), icon="⚠️")


def _check_table(screen: Screen) -> None:
    shown = _checks(screen)
    if shown:
        st.dataframe(check_records(list(shown)), hide_index=True, width="stretch",
                     height=min(35 * (len(shown) + 1) + 3, 320),
                     column_config={"check": st.column_config.TextColumn("check",
                                                                         width="large")})


def _quick_results(screen: Screen) -> None:
    """What the page shows first: the contour, the headline numbers and the verdict, and the
    page's marker that they are drawn (its ``data-version`` is the design's)."""
    if screen.svg:
        st.image(screen.svg, width="stretch")
    _headline(screen)
    _verdict(screen)
    _marker("chaindrive-results", {"data-version": str(st.session_state.get("version", 0)),
                                   "data-design": st.session_state.get("design_tag", "")},
            "Results drawn")


def _marker(element_id: str, attrs: dict[str, str], text: str) -> None:
    """A status line for screen readers (a polite live region, invisible on screen) that
    browser tests wait for."""
    hidden = ("position:absolute;width:1px;height:1px;margin:-1px;overflow:hidden;"
              "clip:rect(0 0 0 0);white-space:nowrap")
    body = " ".join(f'{k}="{html.escape(v)}"' for k, v in
                    {"id": element_id, "role": "status", "aria-live": "polite", **attrs}.items())
    st.html(f'<div {body} style="{hidden}">{html.escape(text)}.</div>')


# --- page ----------------------------------------------------------------------------------------

#: File the page appends the time of each phase of its runs to (one JSON line per run) when
#: set (``CHAINDRIVE_APP_TIMING``); ``benchmarks/bench_app_browser.py`` reports them.
TIMING = os.environ.get("CHAINDRIVE_APP_TIMING")


class _Phases:
    """Times of the phases of one run of the page [s from the start of the run]."""

    def __init__(self) -> None:
        self.start = time.perf_counter()
        self.marks: dict[str, float] = {}

    def __call__(self, name: str) -> None:
        self.marks[name] = round(time.perf_counter() - self.start, 4)

    def write(self) -> None:
        if TIMING:
            with open(TIMING, "a", encoding="utf-8") as out:
                out.write(json.dumps({"design": st.session_state.get("design_tag", ""),
                                      **self.marks}) + "\n")


def _ready(state: str, screen: Screen | None = None) -> None:
    """The page's own ready marker, written last in every completed run: a status line for
    screen readers that says whether the results are up to date, with the design version,
    its file and the row of the "edit one sprocket" form in data attributes (the browser
    test waits for it)."""
    n = (screen.numbers or {}) if screen is not None else {}
    doc = (screen.document or {}) if screen is not None else {}
    text = {"ok": "Results up to date", "error": "Correct the field marked ⚠️",
            "unexpected": "Something went wrong"}.get(state, state)
    if n:
        text += f": {n['links']} links, {len(doc.get('warnings', []))} warning(s)"
    _marker("chaindrive-ready", {"data-state": state,
                                 "data-version": str(st.session_state.get("version", 0)),
                                 "data-source": str(st.session_state.get("source", "")),
                                 "data-editing": str(st.session_state.get(_key("edit_row"),
                                                                          "")),
                                 "data-design": st.session_state.get("design_tag", "")},
            text)


def _early(base: DesignForm, catalogs: str, shown: Any) -> tuple[str, Iterator[Screen]] | None:
    """The design read from the session state before the widgets
    (:func:`chaindrive.app.early.design_from_state`), analysed, and its quick results drawn
    in ``shown``: returns its key and the rest of its screens; None when the design could
    not be read there, or was not analysed (the page then goes the usual way)."""
    if st.session_state.pop("early_off", False):
        return None
    try:
        design = design_from_state(base, st.session_state, _key, _table_key(),
                                   _chain_choice(base.chain),
                                   _chain_options(base.chain.get("designation")))
    except Exception:  # whatever the state holds: the widgets will say
        design = None
    if design is None:
        return None
    key = json.dumps(design, sort_keys=True, default=str)
    st.session_state["design_tag"] = f"{zlib.crc32(key.encode()):08x}"
    steps = _screens(key, catalogs)
    screen = next(steps)
    if not screen.outcome.ok:  # the widgets show where the mistake is: the usual way
        steps.close()
        return None
    with shown:
        _quick_results(screen)
    return key, _chain((screen,), steps)


def _chain(first: tuple[Screen, ...], rest: Iterator[Screen]) -> Iterator[Screen]:
    yield from first
    yield from rest


def page() -> None:
    """The whole page (Streamlit reruns it on every edit): the quick results of the design
    read from the session state first (:func:`_early`, top right), then the form and the
    table, then the rest; when the form's design is not the one read first, the page runs
    again with it."""
    st.set_page_config(page_title="chaindrive — chain drive design", layout="wide",
                       page_icon="⛓️")
    phase = _Phases()
    st.html(CSS)
    _init()
    base: DesignForm = st.session_state["form"]
    left, right = st.columns([1.08, 1], gap="medium")
    with right:
        shown = st.container()
        warnings = st.container()
    table_box = st.container()
    catalogs = json.dumps(_catalogs(), sort_keys=True)
    previous = st.session_state.get("previous_numbers")
    early = _early(base, catalogs, shown)
    phase("early")
    with left:
        st.title("Chain drive design")
        general = st.empty()
        slots: dict[tuple[str, str], Any] = {}
        drive, columns = _drive_fields(base, slots)
        chain = _chain_fields(base, slots, columns)
    with table_box:
        st.subheader("Sprockets, in order round the contour")
        rows = _sprocket_table(base)
        table_slot = st.empty()
    with left:
        _sprocket_editor(rows)
    design = design_from_form(DesignForm(drive, chain, rows, base.other))
    _sidebar(design)
    phase("form")
    key = json.dumps(design, sort_keys=True, default=str)
    catalogs_now = json.dumps(_catalogs(), sort_keys=True)
    if early is not None and (early[0], catalogs) != (key, catalogs_now):
        # the results drawn first are of another design: run again with the form's
        st.session_state["previous_numbers"] = previous
        st.session_state["early_off"] = True
        st.rerun()
    if early is not None:
        steps = early[1]
        screen = next(steps)
        phase("quick_run")
    else:
        st.session_state["design_tag"] = f"{zlib.crc32(key.encode()):08x}"
        steps = _screens(key, catalogs_now)
        screen = next(steps)
        phase("quick_run")
        _show_error(screen, slots, table_slot, general, rows)
        if screen.outcome.ok:
            with shown:
                _quick_results(screen)
    if screen.outcome.ok:
        phase("shown")
        screen = next(steps, screen)
        phase("complete_run")
        if not screen.outcome.ok:  # the document failed: say so where the fields are
            _show_error(screen, slots, table_slot, general, rows)
    if screen.outcome.ok:
        st.session_state["last_good"] = (screen, design)
        with warnings:
            _warnings(screen)
        _results(screen, design)
        _ready("ok", screen)
        phase("done")
        phase.write()
        return
    last = st.session_state.get("last_good")
    with right:
        if last is None:
            st.info("Correct the field marked ⚠️ and the results appear.")
        else:
            st.info("Correct the field marked ⚠️. Until then the results below are those of "
                    "the last design that could be analysed.")
            _quick_results(last[0])
            _warnings(last[0])
    if last is None:
        _ready("error")
        return
    _results(*last)
    _ready("error", last[0])


def _results(screen: Screen, design: dict[str, Any]) -> None:
    """The table of checks and the tabs, below the sprocket table."""
    with st.expander(f"Checks ({len(screen.checks)}): value, requirement, margin (≥ 0 "
                     "passes) and source", expanded=False):
        _check_table(screen)
    tabs.tabs(screen, design)


def _safe_page() -> None:
    try:
        page()
    except Exception as exc:  # never a traceback on the page
        if type(exc).__module__.startswith("streamlit"):
            raise  # st.rerun / st.stop use exceptions
        st.error(UNEXPECTED.format(type(exc).__name__))
        _ready("unexpected")


# Streamlit runs this file as ``__main__``. Every bounded run (:mod:`chaindrive.app.worker`)
# imports the parent's main module again in its child, as ``__mp_main__``: there it must
# only define the functions, never draw the page (which took seconds a run).
if __name__ == "__main__":
    _safe_page()
