"""The pure layer of the web page (issue 7): form ↔ design mapping ↔ analysis, without a
browser. The page's numbers are checked against the library reading the same design from a
TOML file, and its messages against what ``chaindrive analyze`` prints."""

from __future__ import annotations

import math
import re
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

import chaindrive
from chaindrive import app as app_pkg
from chaindrive.app import runs
from chaindrive.app.state import (
    EDIT_FIELDS,
    SPROCKET_COLUMNS,
    DesignForm,
    Location,
    apply_sprocket_edit,
    design_from_form,
    design_to_toml,
    edit_values,
    evaluate,
    example_text,
    form_from_design,
    is_empty,
    list_examples,
    locate,
    read_design_text,
    sprocket_label,
)
from chaindrive.app.views import (
    check_records,
    headline,
    layout_svg,
    modal_records,
    quick_screen,
    recompute,
)
from chaindrive.cli import app as cli_app
from chaindrive.display import fmt
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # the page runs in Streamlit's script thread

SEED = EXAMPLES / "seed_three_sprocket.toml"


def seed_form() -> DesignForm:
    return form_from_design(tomllib.loads(SEED.read_text(encoding="utf-8")))


def cli_error(design: dict[str, Any], tmp_path: Path) -> str:
    """The line ``chaindrive analyze`` prints for the design written as a TOML file."""
    path = tmp_path / "design.toml"
    path.write_text(design_to_toml(design), encoding="utf-8")
    result = CliRunner().invoke(cli_app, ["analyze", str(path)])
    assert result.exit_code == 2, result.output
    return result.stderr.strip()


# --- form ↔ design ------------------------------------------------------------------------------

def test_seed_form_gives_the_drive_the_file_gives() -> None:
    from chaindrive.io.design import drive_from_mapping

    from_form = drive_from_mapping(design_from_form(seed_form()))
    from_file = chaindrive.load(SEED)
    assert from_form.chain.spec == from_file.chain.spec
    assert from_form.power == pytest.approx(from_file.power)
    for a, b in zip(from_form.sprockets, from_file.sprockets, strict=True):
        assert (a.name, a.teeth, a.role, a.side) == (b.name, b.teeth, b.role, b.side)
        assert (a.x, a.y) == pytest.approx((b.x, b.y), abs=1e-12)
        assert (a.speed is None) == (b.speed is None)
        if a.speed is not None:
            assert a.speed == pytest.approx(b.speed, rel=1e-12)


def test_form_uses_the_table_units() -> None:
    form = seed_form()
    s1 = form.sprockets[0]
    assert set(s1) == {c.key for c in SPROCKET_COLUMNS}
    # seed file: x = "1364 mm", speed = "300 rpm", power = "0.5 kW"
    assert s1["x_mm"] == pytest.approx(1364.0)
    assert s1["speed_rpm"] == pytest.approx(300.0)
    assert form.drive["power_kw"] == pytest.approx(0.5)


def test_other_units_are_converted_on_load() -> None:
    data = tomllib.loads(SEED.read_text(encoding="utf-8"))
    data["sprockets"][0]["x"] = "1.364 m"
    data["sprockets"][0]["speed"] = "31.41592653589793 rad/s"
    data["drive"]["power"] = "500 W"
    form = form_from_design(data)
    assert form.sprockets[0]["x_mm"] == pytest.approx(1364.0)
    assert form.sprockets[0]["speed_rpm"] == pytest.approx(300.0)
    assert form.drive["power_kw"] == pytest.approx(0.5)


def test_sag_and_link_stiffness_are_form_fields() -> None:
    """The installed sag (a fraction) and the measured link stiffness (N/m; read in any
    unit) are fields of the form and come back to the design mapping with their unit."""
    data = tomllib.loads(SEED.read_text(encoding="utf-8"))
    data["chain"].update(sag=0.015, link_stiffness="170 kN/mm")
    form = form_from_design(data)
    assert form.chain["sag"] == 0.015
    assert form.chain["link_stiffness_n_per_m"] == pytest.approx(1.7e8)
    back = design_from_form(form)["chain"]
    assert back["sag"] == 0.015 and back["link_stiffness"] == "170000000 N/m"
    drive = drive_from_mapping(design_from_form(form))
    assert drive.chain.sag == 0.015 and drive.chain.link_stiffness == pytest.approx(1.7e8)


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_example_analyses_as_the_file_does(path: Path) -> None:
    outcome = evaluate(design_from_form(form_from_design(tomllib.loads(path.read_text("utf-8")))))
    assert outcome.ok, outcome.message
    direct = chaindrive.analyze(chaindrive.load(path))
    assert outcome.analysis is not None
    assert outcome.analysis.geometry.links == direct.geometry.links
    assert outcome.analysis.geometry.chain_length == pytest.approx(direct.geometry.chain_length)
    # the page's quick screen runs no start-up: its warnings come with the Start-up tab
    assert outcome.analysis.to_dict()["warnings"] == [
        w for w in direct.to_dict()["warnings"] if not w["code"].startswith("dynamics.startup")]


def test_editing_a_tooth_count_matches_the_edited_file(tmp_path: Path) -> None:
    form = seed_form()
    form.sprockets[2]["teeth"] = 30.0          # what a numeric editor column returns
    outcome = evaluate(design_from_form(form))
    edited = tmp_path / "edited.toml"
    edited.write_text(SEED.read_text("utf-8").replace("teeth = 14", "teeth = 30"), "utf-8")
    direct = chaindrive.analyze(chaindrive.load(edited))
    assert outcome.analysis is not None
    assert outcome.analysis.geometry.links == direct.geometry.links
    before = chaindrive.analyze(chaindrive.load(SEED))
    assert direct.geometry.links != before.geometry.links  # the edit is one that matters



# --- the "edit one sprocket" form ---------------------------------------------------------------

def test_edit_form_shows_the_row_as_the_form_needs_it() -> None:
    row = seed_form().sprockets[0]
    row["teeth"] = 15.0                        # what a numeric editor column returns
    values = edit_values(row)
    assert set(values) == set(EDIT_FIELDS)
    assert values["teeth"] == 15 and isinstance(values["teeth"], int)
    assert values["x_mm"] == pytest.approx(1364.0) and values["speed_rpm"] == pytest.approx(300)
    assert values["name"] == "S1" and values["role"] == "driver"
    assert values["side"] is None and values["power_share"] is None  # empty: the default
    assert edit_values({"teeth": 14.5, "x_mm": math.nan})["teeth"] is None  # not invented
    assert edit_values({"teeth": 14.5, "x_mm": math.nan})["x_mm"] is None


def test_edit_form_names_rows_by_number_and_name() -> None:
    assert sprocket_label(2, {"name": "S3"}) == "row 3: S3"
    assert sprocket_label(0, {"name": None}) == "row 1: unnamed"


def test_applying_the_edit_form_matches_the_edited_file(tmp_path: Path) -> None:
    form = seed_form()
    values = edit_values(form.sprockets[2]) | {"teeth": 30}
    rows = apply_sprocket_edit(form.sprockets, 2, values)
    assert rows[2]["teeth"] == 30 and form.sprockets[2]["teeth"] == 14  # a new list
    assert rows[:2] == form.sprockets[:2]
    edited = tmp_path / "edited.toml"
    edited.write_text(SEED.read_text("utf-8").replace("teeth = 14", "teeth = 30"), "utf-8")
    outcome = evaluate(design_from_form(DesignForm(form.drive, form.chain, rows, form.other)))
    assert outcome.analysis is not None
    assert outcome.analysis.geometry.links == chaindrive.analyze(
        chaindrive.load(edited)).geometry.links


def test_edit_form_clears_a_field_and_ignores_a_bad_row() -> None:
    rows = seed_form().sprockets
    cleared = apply_sprocket_edit(rows, 0, {"speed_rpm": None, "material": "brass"})
    assert "speed" not in design_from_form(DesignForm({}, {}, cleared))["sprockets"][0]
    assert cleared[0]["material"] == rows[0]["material"]  # not a field of the form
    assert apply_sprocket_edit(rows, 7, {"teeth": 9}) == rows

def test_empty_cells_take_the_defaults() -> None:
    form = seed_form()
    form.sprockets[1].update(side=float("nan"), material="", inertia_kg_m2=None)
    design = design_from_form(form)
    assert not {"side", "material", "inertia"} & set(design["sprockets"][1])
    assert evaluate(design).ok


def test_is_empty_knows_the_missing_values() -> None:
    pd = pytest.importorskip("pandas")
    for value in (None, math.nan, "  ", pd.NA, pd.NaT):
        assert is_empty(value)
    for value in (0, 0.0, False, "S1"):
        assert not is_empty(value)


def test_toml_round_trip_keeps_the_design() -> None:
    design = design_from_form(seed_form())
    assert read_design_text(design_to_toml(design, comment="saved")) == design


def test_saved_design_has_no_round_off() -> None:
    """A design loaded and saved again writes its numbers as given: 700 mm is written
    "700 mm", not "700.0000000000001 mm" (mm → m → mm round-off)."""
    path = EXAMPLES / "twenty_four_sprocket.toml"
    text = design_to_toml(design_from_form(form_from_design(tomllib.loads(
        path.read_text(encoding="utf-8")))))
    assert not re.search(r"\d\.\d*0000000\d", text) and not re.search(r"\d99999999", text)
    from chaindrive.io.design import drive_from_mapping

    again = drive_from_mapping(tomllib.loads(text))
    original = chaindrive.load(path)
    assert [c for s in again.sprockets for c in (s.x, s.y)] == pytest.approx(
        [c for s in original.sprockets for c in (s.x, s.y)], abs=1e-12)


def test_a_half_finished_design_can_be_saved() -> None:
    form = seed_form()
    form.sprockets[0]["teeth"] = 2
    form.sprockets[1]["x_mm"] = "abc"
    text = design_to_toml(design_from_form(form))
    again = read_design_text(text)
    assert again["sprockets"][0]["teeth"] == 2 and again["sprockets"][1]["x"] == "abc"


def test_bad_toml_gives_the_loader_message() -> None:
    with pytest.raises(DesignError, match=r"^upload\.toml: TOML syntax error"):
        read_design_text("[drive\nname = 1", "upload.toml")


def test_examples_are_listed() -> None:
    names = list_examples()
    assert "seed_three_sprocket" in names
    assert example_text("seed_three_sprocket") == SEED.read_text(encoding="utf-8")


# --- bad input: the command line's message, at the right field ----------------------------------

def _edit_row(i: int, **cells: Any) -> DesignForm:
    form = seed_form()
    form.sprockets[i].update(cells)
    return form


BAD: dict[str, tuple[Any, Location]] = {
    "teeth too few": (lambda: _edit_row(2, teeth=3.0), Location("sprockets", 2, "teeth")),
    "teeth not whole": (lambda: _edit_row(2, teeth=15.5), Location("sprockets", 2, "teeth")),
    "role misspelt": (lambda: _edit_row(1, role="drivn"), Location("sprockets", 1, "role")),
    "text in x": (lambda: _edit_row(1, x_mm="abc"), Location("sprockets", 1, "x_mm")),
    "speed on driven": (lambda: _edit_row(1, speed_rpm=100.0),
                        Location("sprockets", 1, "speed_rpm")),
    "two drivers": (lambda: _edit_row(1, role="driver"), Location("sprockets", None, "role")),
    "duplicate name": (lambda: _edit_row(2, name="S1"), Location("sprockets", 2, "name")),
}


def _form_with(section: str, **values: Any) -> DesignForm:
    form = seed_form()
    getattr(form, section).update(values)
    return form


BAD |= {
    "negative power": (lambda: _form_with("drive", power_kw=-1.0),
                       Location("drive", None, "power_kw")),
    "unknown chain": (lambda: _form_with("chain", designation="GOST 13568 ПР-25,4-6O"),
                      Location("chain", None, "designation")),
    "too many strands": (lambda: _form_with("chain", strands=9.0),
                         Location("chain", None, "strands")),
    "sag of a half": (lambda: _form_with("chain", sag=0.5), Location("chain", None, "sag")),
    "soft link": (lambda: _form_with("chain", link_stiffness_n_per_m=10.0),
                  Location("chain", None, "link_stiffness_n_per_m")),
}


@pytest.mark.parametrize("case", list(BAD), ids=list(BAD))
def test_bad_input_shows_the_command_line_message(case: str, tmp_path: Path) -> None:
    make, where = BAD[case]
    design = design_from_form(make())
    outcome = evaluate(design)
    assert not outcome.ok and not outcome.unexpected
    assert f"error: {outcome.message}" == cli_error(design, tmp_path)
    assert outcome.location == where


def test_overlapping_sprockets_point_at_the_row(tmp_path: Path) -> None:
    design = design_from_form(_edit_row(2, x_mm=20.0, y_mm=0.0))
    outcome = evaluate(design)
    assert outcome.message is not None and "overlap" in outcome.message
    assert f"error: {outcome.message}" == cli_error(design, tmp_path)
    assert outcome.location is not None and outcome.location.section == "sprockets"


def test_locate_field_paths() -> None:
    names = ["S1", "S2", "S3"]
    assert locate("sprockets[2].teeth", names) == Location("sprockets", 2, "teeth")
    assert locate("sprockets[S2].speed", names) == Location("sprockets", 1, "speed_rpm")
    assert locate("sprockets[0].adjust_angle", names) == Location("sprockets", 0,
                                                                  "adjust_angle_deg")
    assert locate("sprockets", names) == Location("sprockets")
    assert locate("drive.power", names) == Location("drive", None, "power_kw")
    assert locate("chain.pitch", names) == Location("chain", None, "pitch_mm")
    assert locate("chain.link_stiffness", names) == Location("chain", None,
                                                             "link_stiffness_n_per_m")
    assert locate("chian", names) == Location("design")
    assert locate("", names) == Location("design")


def test_an_unexpected_failure_is_a_short_message(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(*_: Any, **__: Any) -> None:
        raise ZeroDivisionError("deep inside")

    monkeypatch.setattr("chaindrive.app.state.analyze", broken)  # where the page looks it up
    outcome = evaluate(design_from_form(seed_form()))
    assert outcome.unexpected and not outcome.ok
    assert outcome.message is not None
    assert "ZeroDivisionError" in outcome.message and "Traceback" not in outcome.message
    assert "\n" not in outcome.message


# --- what the page shows ---------------------------------------------------------------------

def test_recompute_gives_the_screen_of_the_analysis() -> None:
    """The quick part (contour, numbers, checks) and the complete screen (the document, with
    the selection's warnings) are those of chaindrive.analyze on the same design."""
    quick = quick_screen(design_from_form(seed_form()))
    analysis = chaindrive.analyze(chaindrive.load(SEED), response=False)  # what the page shows
    direct = analysis.to_dict()
    assert quick.numbers == headline(analysis) and quick.document is None
    assert quick.numbers["links"] == direct["geometry"]["links"]
    assert [c.result for c in quick.checks] == [
        "pass" if c.passed else "FAIL" if c.status == "fail" else "CANNOT BE VERIFIED"
        for c in analysis.checks()]
    assert quick.svg is not None
    screen = recompute(design_from_form(seed_form()))
    assert screen.document is not None and screen.document["warnings"] == direct["warnings"]
    assert screen.numbers == quick.numbers
    failed = next(c for c in screen.checks if not c.passed)
    # the verdict's line without the check's note (the check table shows it)
    assert failed.line == "FAIL: teeth in mesh: S3 = 0.2382 teeth (required ≥ 3 teeth)"


def test_recompute_of_a_bad_design_has_no_results() -> None:
    screen = recompute(design_from_form(_edit_row(0, teeth=200)))
    assert screen.svg is None and screen.document is None
    assert screen.outcome.message.startswith("sprockets[0].teeth: ")


def test_layout_svg_draws_every_sprocket_and_span() -> None:
    analysis = chaindrive.analyze(chaindrive.load(EXAMPLES / "twenty_four_sprocket.toml"))
    svg = layout_svg(analysis.geometry, highlight="S3")
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    n = len(analysis.geometry.sprockets)
    assert len(root.findall(f"{ns}circle")) == 2 * n          # tip and pitch circle each
    assert len(root.findall(f"{ns}line")) == len(analysis.geometry.spans)
    assert len(root.findall(f"{ns}polygon")) == len(analysis.geometry.spans)  # arrows
    texts = [t.text or "" for t in root.findall(f"{ns}text")]
    assert f"{analysis.geometry.links} links" in texts[-1]
    # to scale: the pitch circle of S1 has the pitch radius in mm
    s1 = analysis.geometry.sprockets[0]
    radii = [float(c.get("r", "0")) for c in root.findall(f"{ns}circle")]
    assert radii[1] == pytest.approx(s1.pitch_radius * 1e3, abs=0.01)


def test_failed_checks_come_first() -> None:
    from chaindrive.app.views import Check

    rows = check_records([Check("a", 1.0, "≥ 2", "FAIL", ""), Check("b", 3.0, "≥ 2", "pass", ""),
                          Check("c", None, "≥ 2", "CANNOT BE VERIFIED", "")][::-1])
    assert [r["result"] for r in rows] == ["CANNOT BE VERIFIED", "FAIL", "pass"]


def test_modal_table_leaves_out_rigid_body_modes() -> None:
    doc = chaindrive.analyze(chaindrive.load(SEED)).to_dict()
    rows = modal_records(doc)
    rigid = doc["dynamics"]["rigid_body_modes"]
    assert len(rows) == len(rigid) - sum(rigid)
    assert all(r["natural, Hz"] > 0 for r in rows)
    # an overdamped mode (ζ ≥ 1: no damped frequency, [Rao2011, §6.14]) shows no number
    ratios = [z for z, r in zip(doc["dynamics"]["modal_damping_ratios"], rigid, strict=True)
              if not r]
    assert any(z >= 1.0 for z in ratios)  # the seed's fifth ring mode, 1226 Hz
    assert [r["damped, Hz"] is None for r in rows] == [z >= 1.0 for z in ratios]


# --- launcher and on-demand parts -------------------------------------------------------------

def test_streamlit_command_serves_the_page_quietly() -> None:
    cmd = app_pkg.streamlit_command("127.0.0.1", 8599)
    assert cmd[1:4] == ["-m", "streamlit", "run"] and Path(cmd[4]) == app_pkg.PAGE
    options = dict(zip(cmd[5::2], cmd[6::2], strict=True))
    assert options["--server.address"] == "127.0.0.1" and options["--server.port"] == "8599"
    assert options["--client.showErrorDetails"] == "none"
    assert app_pkg.PAGE.is_file()


def test_run_app_without_streamlit_says_so(monkeypatch: pytest.MonkeyPatch,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(app_pkg.importlib.util, "find_spec", lambda name: None)
    assert app_pkg.run_app(port=8599) == 2
    assert "Streamlit" in capsys.readouterr().err


def test_missing_feature_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(runs.NEEDS, "startup", ("chaindrive.dynamics.no_such_module",))
    reason = runs.missing("startup")
    assert reason is not None and "not available yet" in reason
    monkeypatch.setitem(runs.NEEDS, "afc", ("chaindrive.analysis",))
    assert runs.missing("afc") is None


# --- the page itself, run headless by Streamlit's AppTest (no browser) --------------------------

def page_test() -> Any:
    testing = pytest.importorskip("streamlit.testing.v1")
    return testing.AppTest.from_file(str(app_pkg.PAGE), default_timeout=60)


def test_page_edit_form_changes_the_tooth_count(tmp_path: Path) -> None:
    at = page_test().run()
    at.selectbox(key=f"edit_row@{at.session_state['loads']}").select(2).run()
    teeth = [n for n in at.number_input if n.label == "Teeth"]
    assert len(teeth) == 1 and teeth[0].value == 14     # the form shows the chosen row
    teeth[0].set_value(30)
    next(b for b in at.button if b.label == "Apply").click().run()
    edited = tmp_path / "edited.toml"
    edited.write_text(SEED.read_text("utf-8").replace("teeth = 14", "teeth = 30"), "utf-8")
    links = chaindrive.analyze(chaindrive.load(edited), response=False).geometry.links
    assert at.metric[0].label == "Links" and at.metric[0].value == str(links)
    assert not at.exception
    # the only red boxes are the checks the edited design fails (30 teeth on the idler leave
    # fewer than 3 in mesh), as the analysis says
    # (the page's screen runs no start-up: k1 comes with its Start-up tab; here the ripple
    # still grows at the end of the 1 s record, so k1 cannot be verified)
    # (nor the response the fatigue check reads: it comes with the dynamic response)
    failed = [c for c in chaindrive.analyze(chaindrive.load(edited)).checks()
              if not c.passed and c.key not in ("k1", "fatigue")]
    assert [e.value.split("\\:")[0] for e in at.error] == [  # Markdown: the colon escaped
        "FAIL" if c.status == "fail" else "CANNOT BE VERIFIED" for c in failed]
    assert at.session_state["form"].sprockets[2]["teeth"] == 30


def test_page_keeps_the_other_tables_of_the_design() -> None:
    at = page_test().run()
    form = at.session_state["form"]
    form.other = {"dynamics": {"transient": False}}
    at.session_state["version"] += 1
    at.run()
    assert at.session_state["last_good"][1]["dynamics"] == {"transient": False}
    next(b for b in at.button if b.label == "Apply").click().run()  # and through the form
    assert at.session_state["form"].other == {"dynamics": {"transient": False}}


def test_page_startup_states_runup_and_decay_apart() -> None:
    """The Start-up tab shows the run-up and the decay after it as the analysis gives them."""
    at = page_test().run()
    at.session_state["tabs"] = "Start-up"  # only the open tab is drawn
    at.run()
    next(b for b in at.button if b.label == "Run the start-up simulation").click().run()
    assert not at.exception
    startup = chaindrive.analyze(chaindrive.load(SEED)).startup
    assert startup is not None
    shown = {m.label: m.value for m in at.metric}
    assert shown["run-up [s]"] == fmt(startup.runup_time)
    assert shown["decay after it [s]"] == fmt(startup.decay_time)
    assert shown["k₁ = Q / F₁max"] == fmt(startup.k1)
    slack = [w.value for w in at.warning if "spans go slack" in w.value]
    assert len(slack) == 1 and "S2→S3" in slack[0]   # as the analysis's warning says
    assert shown["largest span force F₁max [N]"] == fmt(float(startup.max_span_force.max()))
    at.radio(key="units").set_value("US").run()      # the page's unit system: lbf
    shown = {m.label: m.value for m in at.metric}
    assert shown["largest span force F₁max [lbf]"] == fmt(
        float(startup.max_span_force.max()) / 4.4482216152605)


def test_page_startup_k1_of_a_partial_record_says_so() -> None:
    """A start-up record that ends before it settles: the k₁ metric's help says that its
    check cannot be verified (the analysis's k1 check does)."""
    at = page_test().run()
    form = at.session_state["form"]
    form.other = {"dynamics": {"startup_duration": "0.1 s"}}
    at.session_state["version"] += 1
    at.session_state["tabs"] = "Start-up"
    at.run()
    next(b for b in at.button if b.label == "Run the start-up simulation").click().run()
    assert not at.exception
    k1 = next(m for m in at.metric if m.label == "k₁ = Q / F₁max")
    assert "cannot be verified" in (k1.proto.help or "")
