"""The chaindrive web page (Streamlit): build or load a design, see at once whether it works.

Run it with ``chaindrive app`` (or :func:`chaindrive.app.run_app`). The page only edits and
shows: the form becomes a design mapping (:mod:`chaindrive.app.state`), the mapping is
analysed, and what is on screen comes from :mod:`chaindrive.app.views`; the start-up, AFC,
report and drawing run on demand (:mod:`chaindrive.app.runs`).
"""

from __future__ import annotations

import html
import json
import math
import zlib
from pathlib import Path
from typing import Any

import streamlit as st

from chaindrive.app import runs
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
    plain,
    read_design_text,
    sprocket_label,
)
from chaindrive.app.views import (
    Screen,
    check_records,
    modal_records,
    recompute,
    resonance_records,
    span_records,
    sprocket_records,
)
from chaindrive.display import fmt
from chaindrive.errors import ChainDriveError

DEFAULT_EXAMPLE = "seed_three_sprocket"
AUTO_FORM = "(by chain standard)"
AUTO_CHAIN = "(select for the power: {})"
STANDARDS = ("ISO 606", "GOST 13568", "ANSI")
#: Pixel widths of the sprocket-table columns (fixed, so the table reads the same everywhere).
WIDTHS = {"name": 80, "teeth": 70, "x_mm": 90, "y_mm": 90, "role": 85, "side": 85,
          "adjustable": 100, "adjust_angle_deg": 125, "speed_rpm": 105, "power_share": 105,
          "inertia_kg_m2": 120, "material": 140}
UNEXPECTED = "Something went wrong on the page ({}). Reload the page; if it persists, please "\
             "report it with the design file."


# --- session state -------------------------------------------------------------------------------

def _load(data: dict[str, Any], source: str) -> None:
    """Put a design mapping into the form (new widget keys, so every field re-reads it)."""
    st.session_state["form"] = form_from_design(data)
    st.session_state["source"] = source
    st.session_state["version"] = st.session_state.get("version", 0) + 1
    st.session_state.pop("load_error", None)


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
        st.session_state["version"] = 1


def _key(name: str) -> str:
    return f"{name}@{st.session_state['version']}"


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
            text = upload.getvalue().decode("utf-8")
            _load(read_design_text(text, upload.name), upload.name)
            st.rerun()
        except UnicodeDecodeError:
            st.session_state["load_error"] = f"{upload.name}: cannot read the file (not UTF-8)"
        except ChainDriveError as exc:
            st.session_state["load_error"] = str(exc)
    if "load_error" in st.session_state:
        sb.error(st.session_state["load_error"])
    if design is not None:
        sb.download_button("Save design (TOML)", design_to_toml(design),
                           file_name=_file_name(".toml"), mime="application/toml",
                           key="save_toml", width="stretch")
    sb.caption(f"Loaded: {st.session_state.get('source', '—')}. Edits apply at once (the "
               "“edit one sprocket” form on Apply); a field with a bad value shows the same "
               "message as `chaindrive analyze`.")


def _file_name(suffix: str) -> str:
    return Path(st.session_state.get("source") or "design.toml").stem + suffix


# --- the form ------------------------------------------------------------------------------------

def _chain_options(current: str | None) -> list[str]:
    from chaindrive import catalog

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
    from chaindrive import catalog

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


def _drive_fields(base: DesignForm, slots: dict[tuple[str, str], Any]) -> dict[str, Any]:
    d = base.drive
    c1, c2, c3, c4 = st.columns([3, 1.3, 1.3, 1.6])
    with c1:
        name = st.text_input("Drive name", value=d.get("name") or "", key=_key("drive.name"))
        slots[("drive", "name")] = st.empty()
    with c2:
        power = _number("Power [kW]", d.get("power_kw"), "drive.power", step=0.1,
                        help_text="power transmitted from the driver; empty: no strength "
                                  "check", fmt="%g")
        slots[("drive", "power_kw")] = st.empty()
    with c3:
        sf = _number("Service factor", d.get("service_factor"), "drive.sf", step=0.1,
                     help_text="application factor, 1 to 5", fmt="%g")
        slots[("drive", "service_factor")] = st.empty()
    with c4:
        forms = [AUTO_FORM, "ISO 606", "GOST 591"]
        current = d.get("tooth_form") if d.get("tooth_form") in forms else AUTO_FORM
        tooth_form = st.selectbox("Tooth form", forms, index=forms.index(current),
                                  key=_key("drive.tooth_form"))
        slots[("drive", "tooth_form")] = st.empty()
    extra = {k: v for k, v in d.items()
             if k not in ("name", "power_kw", "service_factor", "tooth_form")}
    return {"name": name, "power_kw": power, "service_factor": sf,
            "tooth_form": None if tooth_form == AUTO_FORM else tooth_form, **extra}


def _chain_fields(base: DesignForm, slots: dict[tuple[str, str], Any]) -> dict[str, Any]:
    ch = dict(base.chain)
    c1, c2, c3, c4, c5 = st.columns([3, 1, 1, 1, 1.2])
    with c1:
        options = _chain_options(ch.get("designation"))
        choice = st.selectbox("Chain (type to search the catalogue)", options,
                              index=options.index(_chain_choice(ch)), key=_key("chain.choice"))
        slots[("chain", "designation")] = st.empty()
        slots[("chain", "standard")] = slots[("chain", "designation")]
    with c2:
        strands = _number("Strands", ch.get("strands"), "chain.strands", step=1,
                          help_text="rows of the chain (default 1)")
        slots[("chain", "strands")] = st.empty()
    with c3:
        links = _number("Links", ch.get("links"), "chain.links", step=1,
                        help_text="impose the number of links; empty: the nearest even "
                                  "number that fits")
        slots[("chain", "links")] = st.empty()
    with c4:
        contours = _number("Contours", ch.get("contours"), "chain.contours", step=1,
                           help_text="identical contours side by side (seed 004), default 1")
        slots[("chain", "contours")] = st.empty()
    with c5:
        st.write("")
        allow_odd = st.checkbox("Odd links allowed", value=bool(ch.get("allow_odd")),
                                key=_key("chain.allow_odd"))
        slots[("chain", "allow_odd")] = st.empty()
    for key in ("pitch_mm", "series", "catalog"):
        slots[("chain", key)] = slots[("chain", "designation")]
    if choice.startswith("(select"):
        ch.update(designation=None, standard=choice[len("(select for the power: "):-1])
    else:
        ch.update(designation=choice, standard=None, series=None, pitch_mm=None)
    ch.update(strands=strands, links=links, contours=contours, allow_odd=allow_odd)
    return ch


def _column_config() -> dict[str, Any]:
    from chaindrive import catalog
    from chaindrive.model import ROLES, SIDES

    cc = st.column_config
    labels = {c.key: c.label for c in SPROCKET_COLUMNS}
    w = WIDTHS
    return {
        "name": cc.TextColumn(labels["name"], width=w["name"]),
        "teeth": cc.NumberColumn(labels["teeth"], width=w["teeth"], step=1, format="%d"),
        "x_mm": cc.NumberColumn(labels["x_mm"], width=w["x_mm"], format="%.2f"),
        "y_mm": cc.NumberColumn(labels["y_mm"], width=w["y_mm"], format="%.2f"),
        "role": cc.SelectboxColumn(labels["role"], width=w["role"], options=list(ROLES)),
        "side": cc.SelectboxColumn(labels["side"], width=w["side"], options=list(SIDES),
                                   help="empty: outside"),
        "speed_rpm": cc.NumberColumn(labels["speed_rpm"], width=w["speed_rpm"],
                                     help="the driver only"),
        "power_share": cc.NumberColumn(labels["power_share"], width=w["power_share"],
                                       help="share of the power taken off (driven)"),
        "inertia_kg_m2": cc.NumberColumn(labels["inertia_kg_m2"], width=w["inertia_kg_m2"],
                                         format="%.4g", help="empty: from the material"),
        "material": cc.SelectboxColumn(labels["material"], width=w["material"],
                                       options=[m.name for m in catalog.materials()],
                                       help="empty: steel"),
        "adjustable": cc.CheckboxColumn(labels["adjustable"], width=w["adjustable"]),
        "adjust_angle_deg": cc.NumberColumn(labels["adjust_angle_deg"],
                                            width=w["adjust_angle_deg"]),
    }


def _sprocket_table(base: DesignForm) -> list[dict[str, Any]]:
    import pandas as pd

    keys = [c.key for c in SPROCKET_COLUMNS]
    extra = sorted({k for r in base.sprockets for k in r} - set(keys))
    frame = pd.DataFrame([{k: r.get(k) for k in keys + extra} for r in base.sprockets],
                         columns=keys + extra)
    for key in ("teeth", "x_mm", "y_mm", "speed_rpm", "power_share", "inertia_kg_m2",
                "adjust_angle_deg"):
        frame[key] = pd.to_numeric(frame[key], errors="coerce").astype("Float64")
    frame["adjustable"] = frame["adjustable"].fillna(False).astype(bool)
    edited = st.data_editor(frame, key=_key("sprockets"), num_rows="dynamic", hide_index=True,
                            column_config=_column_config(), width="stretch",
                            placeholder="")
    return [{k: plain(v) for k, v in row.items()} for row in edited.to_dict("records")]


def _one_sprocket_form(base: DesignForm, drive: dict[str, Any], chain: dict[str, Any],
                      rows: list[dict[str, Any]]) -> None:
    """A small form to change one sprocket's tooth count from the keyboard (the table is
    drawn on a canvas: this is the way in for keyboard users and for browser tests)."""
    names = [str(r.get("name") or f"row {i + 1}") for i, r in enumerate(rows)]
    if not names:
        return
    with st.form(key=_key("one_sprocket"), border=True):
        left, middle, right = st.columns([2, 2, 1], vertical_alignment="bottom")
        index = left.selectbox("Sprocket to edit", range(len(names)),
                               format_func=lambda i: names[i], key=_key("one.sprocket"))
        teeth = middle.number_input("New tooth count", min_value=1, max_value=1000, step=1,
                                    value=None, placeholder="teeth", key=_key("one.teeth"))
        applied = right.form_submit_button("Apply", width="stretch")
    if applied and teeth is not None:
        changed = [dict(r) for r in rows]
        changed[index]["teeth"] = int(teeth)
        st.session_state["form"] = DesignForm(drive, chain, changed, base.other)
        st.session_state["version"] += 1
        st.rerun()


def _sprocket_editor(rows: list[dict[str, Any]]) -> tuple[int, dict[str, Any]] | None:
    """The keyboard-friendly form that edits one sprocket (the table is drawn on a canvas,
    hard to reach with the keyboard or a screen reader). Returns (row, values) when the
    user pressed Apply (or Enter in a field), else None."""
    from chaindrive.model import ROLES, SIDES

    if not rows:
        return None
    if st.session_state.get("edit_row") not in range(len(rows)):
        st.session_state.pop("edit_row", None)
    with st.container(key="sprocket_editor", border=True):
        pick, note = st.columns([1, 3], vertical_alignment="bottom")
        with pick:
            index = st.selectbox("Sprocket to edit", range(len(rows)), key="edit_row",
                                 format_func=lambda i: sprocket_label(i, rows[i]))
        note.caption("Edit one sprocket from the keyboard: choose it, change the fields (Tab "
                     "moves on), press Apply or Enter. An empty field takes the default.")
        v = edit_values(rows[index])
        # keyed by the row's values too, so that an edit in the table shows up here
        tag = f"{index}.{zlib.crc32(repr(sorted(v.items())).encode()):08x}"
        with st.form(_key(f"edit_form.{tag}"), border=False, enter_to_submit=True):
            c = st.columns([1.3, 0.9, 1.1, 1.1, 1.0, 1.15, 1.1, 1.1, 0.9],
                           vertical_alignment="bottom")
            out = {"name": c[0].text_input("Name", value=v["name"] or "",
                                           key=_key(f"edit.name.{tag}")),
                   "teeth": c[1].number_input("Teeth", value=v["teeth"], step=1,
                                              key=_key(f"edit.teeth.{tag}")),
                   "x_mm": c[2].number_input("x [mm]", value=v["x_mm"], step=1.0,
                                             format="%.2f", key=_key(f"edit.x.{tag}")),
                   "y_mm": c[3].number_input("y [mm]", value=v["y_mm"], step=1.0,
                                             format="%.2f", key=_key(f"edit.y.{tag}"))}
            for col, field, options, empty in ((c[4], "role", ROLES, "driven"),
                                               (c[5], "side", SIDES, "outside")):
                opts = list(options)
                out[field] = col.selectbox(field.capitalize(), opts,
                                           index=opts.index(v[field]) if v[field] in opts
                                           else None, placeholder=empty,
                                           key=_key(f"edit.{field}.{tag}"))
            out["speed_rpm"] = c[6].number_input("Speed [rpm]", value=v["speed_rpm"],
                                                 step=10.0, format="%g", placeholder="—",
                                                 key=_key(f"edit.speed.{tag}"),
                                                 help="the driver only")
            out["power_share"] = c[7].number_input("Power share", value=v["power_share"],
                                                   step=0.05, format="%g", placeholder="—",
                                                   key=_key(f"edit.share.{tag}"),
                                                   help="share of the power taken off "
                                                        "(driven)")
            submitted = c[8].form_submit_button("Apply", type="primary", width="stretch")
    if not submitted:
        return None
    out["name"] = out["name"].strip() or None
    return index, out


# --- results -------------------------------------------------------------------------------------

@st.cache_resource(max_entries=32, show_spinner=False)
def _screen(design_json: str) -> Screen:
    return recompute(json.loads(design_json))


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


def _headline(screen: Screen) -> None:
    n = screen.numbers or {}
    before = st.session_state.get("previous_numbers") or {}

    def delta(key: str, fmt: str = "{:+.1f}") -> str | None:
        if key in before and before[key] != n[key]:
            return fmt.format(n[key] - before[key])
        return None

    with st.container(key="headline", horizontal=True):
        st.metric("Links", n["links"], delta=delta("links", "{:+d}"), delta_color="off")
        st.metric("Chain length [mm]", f"{n['chain_length_mm']:.1f}",
                  delta=delta("chain_length_mm"), delta_color="off")
        st.metric("Chain speed [m/s]", f"{n['chain_speed_m_s']:.3f}")
        st.metric("Tooth frequency [Hz]", f"{n['tooth_frequency_hz']:.2f}")
    text = f"Chain {n['chain']}; slack {n['slack_mm']:.1f} mm"
    if n["adjusted_sprocket"]:
        text += f"; take-up: {n['adjusted_sprocket']} moved {n['adjustment_mm']:.2f} mm"
    st.caption(text)
    st.session_state["previous_numbers"] = n


def _checks_and_warnings(screen: Screen) -> None:
    doc = screen.document or {}
    failed = [c for c in screen.checks if not c.passed]
    warnings = doc.get("warnings", [])
    with st.container(key="verdict"):
        if not failed and not warnings:
            st.success(f"All {len(screen.checks)} checks pass; no warnings.")
        elif not failed:
            st.info(f"All {len(screen.checks)} checks pass; {len(warnings)} warning(s).")
        for c in failed:
            st.error(f"{c.result}: {c.name} = {fmt(c.value)} (required {c.required})")
    with st.container(key="warnings"):
        for w in warnings:
            st.warning(w["message"], icon="⚠️")


def _check_table(screen: Screen) -> None:
    if screen.checks:
        st.dataframe(check_records(list(screen.checks)), hide_index=True, width="stretch",
                     height=min(35 * (len(screen.checks) + 1) + 3, 320),
                     column_config={"check": st.column_config.TextColumn("check",
                                                                         width="large")})


def _png(key: str, make: Any) -> None:
    """Show a matplotlib figure (cached by design and figure key)."""
    cache = st.session_state.setdefault("png_cache", {})
    if key not in cache:
        if len(cache) > 24:
            cache.clear()
        cache[key] = runs.figure_png(make())
    st.image(cache[key], width="stretch")


def _tab_geometry(screen: Screen) -> None:
    doc = screen.document or {}
    st.dataframe(sprocket_records(doc), hide_index=True, width="stretch")
    st.dataframe(span_records(doc), hide_index=True, width="stretch")
    a = screen.outcome.analysis
    from chaindrive.plotting import chain_speed, transmission_ratio

    c1, c2 = st.columns(2)
    with c1:
        _png(f"{id(a)}-speed", lambda: chain_speed(a.kinematics))
    with c2:
        _png(f"{id(a)}-ratio", lambda: transmission_ratio(a))


def _tab_strength(screen: Screen) -> None:
    doc = screen.document or {}
    a = screen.outcome.analysis
    sel = doc.get("selection")
    if sel is not None:
        st.write(f"Selection by **{sel['method']}**: {sel['chain']}")
        st.dataframe([{**{k: c.get(k) for k in ("chain", "method", "strands", "mass_kg_m",
                                                 "passed", "governing")},
                       "margin %": None if c.get("margin_fraction") is None
                       else 100 * c["margin_fraction"]}
                      for c in sel.get("candidates", [])[:12]], hide_index=True,
                     width="stretch")
    st_doc = doc.get("strength")
    if st_doc is None:
        st.info("No strength check: give the power of the drive.")
        return
    from chaindrive.plotting import shaft_loads, span_tensions

    c1, c2 = st.columns(2)
    with c1:
        _png(f"{id(a)}-tensions", lambda: span_tensions(a))
    with c2:
        _png(f"{id(a)}-shafts", lambda: shaft_loads(a))
    st.json({k: v for k, v in st_doc.items() if not isinstance(v, list | dict)},
            expanded=False)


def _tab_modes(screen: Screen) -> None:
    doc = screen.document or {}
    a = screen.outcome.analysis
    from chaindrive.plotting import campbell_diagram, mode_shapes

    c1, c2 = st.columns([1, 2])
    with c1:
        st.dataframe(modal_records(doc), hide_index=True, width="stretch")
        res = resonance_records(doc)
        if res:
            st.dataframe(res, hide_index=True, width="stretch")
    with c2:
        if a.dynamics.campbell is not None:
            rpm = doc["drive"]["driver_speed_rpm"]
            _png(f"{id(a)}-campbell",
                 lambda: campbell_diagram(a.dynamics.campbell, operating_rpm=rpm))
        names = [s.name for s in a.drive.sprockets]
        _png(f"{id(a)}-modes", lambda: mode_shapes(a.dynamics.modal, names=names))


def _full(screen: Screen, label: str, button: str) -> Any:
    """The full analysis of the design on screen (run on demand, kept per design), or None
    until the user asks for it (the reason is shown when it cannot run)."""
    reason = runs.missing("response")
    if reason is not None:
        st.info(f"{label}: {reason}.")
        return None
    drive = screen.outcome.drive
    store = st.session_state.setdefault("full", {})
    key = id(screen)
    if key not in store and st.button(button, key=f"run_{label}"):
        with st.status(f"{label}: running the dynamic analysis…", expanded=False) as status:
            try:
                store[key] = runs.full_analysis(drive)
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
        return None
    if result is None:
        st.caption("Runs on demand (a second or so); the results are for the design as it "
                   "is now, with the settings of its [dynamics] table.")
        return None
    if result.response is None:
        st.info("No dynamic response: it needs the power of the drive and the driver speed.")
        return None
    return result


def _tab_startup(screen: Screen) -> None:
    import pandas as pd

    full = _full(screen, "Start-up", "Run the start-up simulation")
    if full is None:
        return
    result = full.response.startup
    if result is None:
        st.info("The start-up is switched off (transient = false in [dynamics]).")
        return
    d = result.to_dict()
    c = st.columns(3)
    c[0].metric("max span force [N]", f"{d['max_force_n']:.0f}")
    c[1].metric("settling time [s]", f"{d['settling_time_s']:.3f}")
    c[2].metric("k1 = Q / F1max", "—" if d["k1"] is None else f"{d['k1']:.2f}")
    names = [f"{s.start_name}→{s.end_name}" for s in full.geometry.spans]
    step = max(1, len(result.times) // 1500)
    frame = pd.DataFrame(result.span_forces[::step], columns=names,
                         index=pd.Index(result.times[::step], name="time [s]"))
    st.line_chart(frame, x_label="time [s]", y_label="span force [N]")


def _tab_afc(screen: Screen) -> None:
    import pandas as pd

    full = _full(screen, "AFC", "Run the AFC sweep")
    if full is None:
        return
    response = full.response
    afc = response.afc
    names = [f"{s.start_name}→{s.end_name}" for s in full.geometry.spans]
    frame = pd.DataFrame(afc.span_load, columns=names,
                         index=pd.Index(afc.driver_speeds * 30 / math.pi,
                                        name="driver speed [rpm]"))
    st.line_chart(frame, x_label="driver speed [rpm]", y_label="peak dynamic span load [N]")
    s = response.strength_dict()
    kd = response.steady.coefficient_of_dynamics
    c = st.columns(4)
    c[0].metric("K_D", "—" if kd is None else f"{kd:.3f}")
    c[1].metric("k2", "—" if s["k2"] is None else f"{s['k2']:.2f}")
    c[2].metric("k2min", "—" if s["k2min"] is None else f"{s['k2min']:.2f}")
    c[3].metric("allowable [k]", f"{s['allowable_k']:.2f}")


def _tab_contours(screen: Screen) -> None:
    a = screen.outcome.analysis
    if a.contours is None:
        st.info("Single contour. Set “Contours” above 1 (identical chains side by side on "
                "common shafts, seed 004) to check how the load shares between them.")
        return
    st.json(a.contours.to_dict(), expanded=False)
    km = getattr(a.contours, "samples", None)
    if km is not None:
        from chaindrive.plotting import km_distribution

        _png(f"{id(a)}-km", lambda: km_distribution(km))


def _tab_robust(screen: Screen) -> None:
    """Life and reliability: the robust study on demand (chaindrive.robust)."""
    reason = runs.missing("robust")
    if reason is not None:
        st.info(f"Life and reliability: {reason}.")
        return
    store = st.session_state.setdefault("robust", {})
    key = id(screen)
    if key not in store and st.button("Run the life and reliability study", key="run_robust"):
        with st.status("Life and reliability: wearing the chain and sampling the tolerances…",
                       expanded=False) as status:
            try:
                store[key] = runs.robust_study(screen.outcome.drive)
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
    from chaindrive.plotting.robust import (
        life_curve_figure,
        probability_figure,
        sensitivity_figure,
    )

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


def _tab_files(screen: Screen, design: dict[str, Any]) -> None:
    a = screen.outcome.analysis
    store = st.session_state.setdefault("files", {})
    c1, c2, c3 = st.columns(3)
    with c1:
        st.download_button("Download design (TOML)", design_to_toml(design), key="dl_toml",
                           file_name=_file_name(".toml"), mime="application/toml")
    for col, kind, label, make, suffix, mime in (
            (c2, "report", "report (HTML)", lambda x: _make_report(screen), ".html",
             "text/html"),
            (c3, "drawing", "drawing (DXF)", lambda x: runs.drawing_dxf(x), ".dxf",
             "application/dxf")):
        with col:
            reason = runs.missing(kind)
            if reason is not None:
                st.info(f"The {label}: {reason}.")
                continue
            key = (kind, id(a))
            if key not in store and st.button(f"Build {label.split(' ')[0].lower()}",
                                              key=f"build_{kind}"):
                try:
                    store[key] = make(a)
                except ChainDriveError as exc:
                    st.error(str(exc))
                except Exception as exc:
                    st.error(UNEXPECTED.format(type(exc).__name__))
            if key in store:
                st.download_button(f"Download {label}", store[key],
                                   file_name=_file_name(suffix), mime=mime,
                                   key=f"dl_{kind}", type="primary")


def _make_report(screen: Screen) -> bytes:
    """The report of the full analysis (with the dynamic response), with a progress bar."""
    bar = st.progress(0.0, text="Running the full analysis…")
    a = runs.full_analysis(screen.outcome.drive)
    from chaindrive.report.content import SECTIONS

    total = max(len(SECTIONS), 1)
    done = {"n": 0}

    def step(title: str) -> None:
        done["n"] += 1
        bar.progress(min(done["n"] / total, 1.0), text=f"Building the report: {title}")

    data = runs.report_html(a, progress=step)
    bar.empty()
    return data


def _results(screen: Screen, design: dict[str, Any]) -> None:
    left, right = st.columns([3, 2])
    with left:
        st.image(screen.svg, width="stretch")
        _check_table(screen)
    with right:
        _headline(screen)
        _checks_and_warnings(screen)
    tabs = st.tabs(["Sprockets & spans", "Selection & strength", "Modes & Campbell",
                    "Start-up", "AFC", "Multi-contour", "Life & reliability", "Report & files"],
                   key="tabs", on_change="rerun")
    shows = (lambda: _tab_geometry(screen), lambda: _tab_strength(screen),
             lambda: _tab_modes(screen),
             lambda: _tab_startup(screen), lambda: _tab_afc(screen),
             lambda: _tab_contours(screen), lambda: _tab_robust(screen),
             lambda: _tab_files(screen, design))
    for tab, show in zip(tabs, shows, strict=True):
        if tab.open:
            with tab:
                try:
                    show()
                except ChainDriveError as exc:
                    st.error(str(exc))
                except Exception as exc:
                    st.error(UNEXPECTED.format(type(exc).__name__))


# --- page ----------------------------------------------------------------------------------------

def _ready(state: str, screen: Screen | None = None) -> None:
    """The page's own ready marker, written last in every completed run: a status line for
    screen readers (a polite live region, invisible on screen) that says whether the results
    are up to date, with the design version, its file and the row of the "edit one sprocket"
    form in data attributes (the browser test waits for it)."""
    n = (screen.numbers or {}) if screen is not None else {}
    doc = (screen.document or {}) if screen is not None else {}
    text = {"ok": "Results up to date", "error": "Correct the field marked ⚠️",
            "unexpected": "Something went wrong"}.get(state, state)
    if n:
        text += f": {n['links']} links, {len(doc.get('warnings', []))} warning(s)"
    attrs = {"id": "chaindrive-ready", "role": "status", "aria-live": "polite",
             "data-state": state, "data-version": str(st.session_state.get("version", 0)),
             "data-source": str(st.session_state.get("source", "")),
             "data-editing": str(st.session_state.get("edit_row", ""))}
    hidden = ("position:absolute;width:1px;height:1px;margin:-1px;overflow:hidden;"
              "clip:rect(0 0 0 0);white-space:nowrap")
    body = " ".join(f'{k}="{html.escape(v)}"' for k, v in attrs.items())
    st.html(f'<div {body} style="{hidden}">{html.escape(text)}.</div>')


def page() -> None:
    """The whole page, top to bottom (Streamlit reruns it on every edit)."""
    st.set_page_config(page_title="chaindrive — chain drive design", layout="wide",
                       page_icon="⛓️")
    _init()
    base: DesignForm = st.session_state["form"]
    st.title("Chain drive design")
    general = st.empty()
    slots: dict[tuple[str, str], Any] = {}
    drive = _drive_fields(base, slots)
    chain = _chain_fields(base, slots)
    st.subheader("Sprockets, in order round the contour")
    rows = _sprocket_table(base)
    table_slot = st.empty()
    edit = _sprocket_editor(rows)
    if edit is not None:  # the form's values become the base of the form, read afresh
        st.session_state["form"] = DesignForm(drive, chain, apply_sprocket_edit(rows, *edit),
                                              base.other)
        st.session_state["version"] += 1
        st.rerun()
    form = DesignForm(drive, chain, rows, base.other)
    design = design_from_form(form)
    _sidebar(design)
    screen = _screen(json.dumps(design, sort_keys=True, default=str))
    _show_error(screen, slots, table_slot, general, rows)
    if screen.outcome.ok:
        st.session_state["last_good"] = (screen, design)
        _results(screen, design)
        _ready("ok", screen)
        return
    last = st.session_state.get("last_good")
    if last is None:
        st.info("Correct the field marked ⚠️ and the results appear.")
        _ready("error")
        return
    st.info("Correct the field marked ⚠️. Until then the results below are those of the last "
            "design that could be analysed.")
    _results(*last)
    _ready("error", last[0])


def _safe_page() -> None:
    try:
        page()
    except Exception as exc:  # never a traceback on the page
        if type(exc).__module__.startswith("streamlit"):
            raise  # st.rerun / st.stop use exceptions
        st.error(UNEXPECTED.format(type(exc).__name__))
        _ready("unexpected")


_safe_page()
