"""Warnings and notes in the output unit system: the numbers with units a warning's or a
note's text writes are recorded with it (:class:`chaindrive.errors.Quantity`: the SI text
as the message writes it, the SI value, the kind), the message and the JSON stay SI, and
:func:`chaindrive.display.warning_text` / :func:`~chaindrive.display.quantity_text` write
them in US customary units for the presenters.

The references are the SI texts themselves (every recorded text must be in its message),
the exact factors of NIST SP 811, App. B [NIST-SP811] (1 in = 25.4 mm, 1 lbf =
4.4482216152605 N, 1 lb = 0.45359237 kg, 1 hp = 745.69987158227022 W, 1 ft = 0.3048 m)
and, for the command line, the SI values of its own ``--json`` document.
"""

from __future__ import annotations

import json
import pickle
import re
from dataclasses import replace

import pytest

import chaindrive
from chaindrive import examples
from chaindrive.analysis import Analysis
from chaindrive.app.views import plain
from chaindrive.display import QUANTITIES, Shown, check_row, quantity_text, warning_text
from chaindrive.dynamics.checks import disturbed_safety_check
from chaindrive.errors import MESSAGE_UNITS, ChainDriveWarning, Quantities, Quantity
from tests.conftest import EXAMPLES, cli_in_process, two_sprocket

IN = 0.0254  # m [NIST-SP811]
LBF = 4.4482216152605  # N [NIST-SP811]
LB_FT2 = 0.45359237 * 0.3048**2  # kg·m² [NIST-SP811]

#: An SI unit a text writes: mm, mm², N, kN, N/m, N·m, kW, m/s, MPa, kg, kg·m² as a whole
#: symbol (not the "m" of "ft/min", the "N" of a name like "N1", or "in²").
SI_UNIT = re.compile(r"(?<![\w/·])(?:N·m|N/m|kg·m²|kg/m|kg|m/s|mm²|mm|kN|kW|MPa|N)(?![\w/·²³])")

PATHS = sorted(EXAMPLES.glob("*.toml"))


@pytest.fixture(scope="module")
def analyses() -> dict[str, Analysis]:
    """Every example analysed in full (the start-up warnings need the response)."""
    return {p.stem: chaindrive.analyze(chaindrive.load(p)) for p in PATHS}


@pytest.mark.parametrize(("text", "found"), [
    ("chain slack 12.1 mm (0.47 pitches)", True), ("(2.16e+08 N/m; the contact", True),
    ("give 2.167 kW beside it", True), ("misses speed limit 1.905 m/s", True),
    ("rotor inertia 0.0067 kg·m² is", True), ("torque 20 N·m", True), ("load 5 kN", True),
    ("A = 170.4 mm² (m·d2·B)", True), ("largest span load 1234 N with", True),
    ("chain slack 0.475 in (0.47 pitches)", False), ("1,230,000 lbf/in;", False),
    ("375 ft/min", False), ("0.0159 lb·ft²", False), ("14.75 lbf·ft", False),
    ("0.2641 in²", False), ("2.906 hp", False), ("3158 psi", False),
    ("tooth x1 at 75.0 Hz of span S1→S2 (N1 sprocket)", False)])
def test_the_si_unit_pattern(text: str, found: bool) -> None:
    """The pattern the tests below use finds the SI symbols and none of the US ones."""
    assert bool(SI_UNIT.search(text)) is found


@pytest.mark.parametrize("name", [p.stem for p in PATHS])
def test_every_example_warning_in_us_units(analyses: dict[str, Analysis], name: str) -> None:
    """Each warning of each example: its recorded SI texts are in its message, SI shows the
    message as it is, US shows no SI unit, and the JSON dict (message SI) gives the same
    text as the warning."""
    a = analyses[name]
    doc = json.loads(json.dumps(a.to_dict()))
    assert len(doc["warnings"]) == len(a.warnings)
    for w, d in zip(a.warnings, doc["warnings"], strict=True):
        assert d["message"] == w.message  # the JSON stays SI
        for q in w.quantities:
            assert q.text in w.message
            assert q.kind in MESSAGE_UNITS and q.text.endswith(" " + MESSAGE_UNITS[q.kind][0])
        assert warning_text(w, "SI") == w.message
        us = warning_text(w, "US")
        assert not SI_UNIT.search(us), (w.code, us)
        assert warning_text(d, "US") == us


@pytest.mark.parametrize("name", [p.stem for p in PATHS])
def test_every_example_note_in_us_units(analyses: dict[str, Analysis], name: str) -> None:
    """The texts the presenters show beside the tables — the checks with their notes, the
    selection's shortfall, the rating note — carry no SI unit in US, and are the SI text
    in SI."""
    a = analyses[name]
    doc = json.loads(json.dumps(a.to_dict()))
    for c in a.checks():
        assert check_row(c, "SI")[0].endswith(f"({c.note})" if c.note else c.subject)
        label = check_row(c, "US")[0]
        assert not SI_UNIT.search(label), label
    texts = []
    sel = doc["selection"]
    if sel is not None and sel["shortfall"] is not None:
        texts.append((sel["shortfall"], sel["shortfall_quantities"]))
    st = doc["strength"]
    if st is not None:
        texts.append((st["rating_note"], st["rating_note_quantities"]))
    for text, quantities in texts:
        assert all(q["text"] in text for q in quantities)
        assert quantity_text(text, quantities, "SI") == text
        us = quantity_text(text, quantities, "US")
        assert not SI_UNIT.search(us), us


def test_the_audited_texts_are_converted(analyses: dict[str, Analysis]) -> None:
    """The texts the audit found in SI, in US units: the Jindal drive's rating note
    (kW → hp) and link stiffness (N/m → lbf/in), the polymer chain's shortfall (m/s →
    ft/min)."""
    jindal = analyses["two_sprocket_jindal"].to_dict()["strength"]
    (aca,) = jindal["rating_note_quantities"]
    note = quantity_text(jindal["rating_note"], [aca], "US")
    assert f"give {aca['value_si'] / 745.69987158227022:.4g} hp beside it" in note
    stiffness = next(w for w in analyses["two_sprocket_jindal"].warnings
                     if w.part == "chain.link_stiffness")
    (k,) = stiffness.quantities
    shown = re.search(r"\(([\d,]+) lbf/in;", warning_text(stiffness, "US"))
    assert shown is not None
    assert float(shown.group(1).replace(",", "")) == pytest.approx(k.value * IN / LBF, rel=5e-3)
    sel = analyses["seed_three_sprocket_polymer"].to_dict()["selection"]
    text = quantity_text(sel["shortfall"], sel["shortfall_quantities"], "US")
    limit = re.search(r"speed limit ([\d.]+) ft/min \(required ≤ ([\d.]+) ft/min\)", text)
    assert limit is not None
    speeds = [q["value_si"] for q in sel["shortfall_quantities"] if q["kind"] == "velocity"]
    assert [float(limit.group(1)), float(limit.group(2))] == pytest.approx(
        [v / 0.00508 for v in speeds], rel=5e-3)


def test_quantity_text_replaces_whole_numbers_in_order() -> None:
    """A quantity replaces its own text only (not "1.5 mm" inside "11.5 mm"), keeps the
    significant digits of the SI text (at least 3) and is read from the JSON dict too; a
    text not in the message is left out."""
    text = "gap 11.5 mm, then 1.5 mm and 1.5 mm again"
    quantities = [Quantity("1.5 mm", 0.0015, "length"), Quantity("1.5 mm", 0.0015, "length"),
                  Quantity("99 mm", 0.099, "length")]
    assert quantity_text(text, quantities, "SI") == text
    assert quantity_text(text, quantities, "US") == (
        "gap 11.5 mm, then 0.0591 in and 0.0591 in again")  # 1.5/25.4 = 0.05906
    dicts = [q.to_dict() for q in quantities]
    assert quantity_text(text, dicts, "US") == quantity_text(text, quantities, "US")
    assert quantity_text("1363 mm", [Quantity("1363 mm", 1.3634, "length")], "US") == \
        "53.68 in"  # 1363.4/25.4 = 53.677, four digits as written


@pytest.mark.parametrize("kind", sorted(MESSAGE_UNITS))
def test_message_units_are_the_si_units_of_the_presenters(kind: str) -> None:
    """A message writes each kind in the unit the SI presenters use (so that the SI text is
    what :func:`chaindrive.display.show` would write), and US converts it."""
    unit, factor = MESSAGE_UNITS[kind]
    assert QUANTITIES[kind]["SI"] == Shown(unit, factor)
    assert QUANTITIES[kind]["US"].unit != unit


def test_the_recorder_writes_what_it_records() -> None:
    """:class:`Quantities` writes the value in the message unit and records that text."""
    q = Quantities()
    text = f"slack {q(0.01206, 'length', '.1f')}, stiffness {q(2.159e8, 'stiffness', '.3g')}"
    assert text == "slack 12.1 mm, stiffness 2.16e+08 N/m"
    assert q.items == (Quantity("12.1 mm", 0.01206, "length"),
                       Quantity("2.16e+08 N/m", 2.159e8, "stiffness"))


def test_a_warning_with_quantities_pickles_and_compares() -> None:
    """A warning crosses processes with its quantities; equality and hash stay those of
    (code, part, message)."""
    q = Quantities()
    w = ChainDriveWarning("geometry.slack", "chain", f"chain slack {q(0.0121, 'length', '.1f')}",
                          q.items)
    back = pickle.loads(pickle.dumps(w))
    assert back == w and hash(back) == hash(w)
    assert back.quantities == w.quantities == (Quantity("12.1 mm", 0.0121, "length"),)
    assert back.to_dict() == w.to_dict()
    assert warning_text(back, "US") == "chain slack 0.476 in"  # 12.1/25.4 = 0.4764
    plain = ChainDriveWarning("a.b", "c", "d")
    assert pickle.loads(pickle.dumps(plain)) == plain and plain.quantities == ()
    assert plain.to_dict() == {"code": "a.b", "part": "c", "message": "d", "quantities": []}


def test_rotor_inertia_and_bearing_area_estimates_in_us() -> None:
    """The estimate warnings outside the examples: the motor's rotor inertia (kg·m² →
    lb·ft²) of the conveyor without its given inertia, and the bearing area (mm² → in²) of a
    chain the catalogue gives none for."""
    drive = examples.load("conveyor_five_sprocket")
    assert drive.motor is not None
    a = chaindrive.analyze(replace(drive, motor=replace(drive.motor, rotor_inertia=None)),
                           response=False)
    w = next(w for w in a.warnings if w.part == "motor.rotor_inertia")
    m = a.drive_model.motor
    assert m is not None and w.quantities == (Quantity(f"{m.rotor_inertia:.4g} kg·m²",
                                                       m.rotor_inertia, "inertia"),)
    shown = re.search(r"rotor inertia ([\d.]+) lb·ft² is", warning_text(w, "US"))
    assert shown is not None
    assert float(shown.group(1)) == pytest.approx(m.rotor_inertia / LB_FT2, rel=1e-3)
    b = chaindrive.analyze(replace(two_sprocket(17, 34, 0.6), power=2000.0), response=False)
    area = next(w for w in b.warnings if w.code == "strength.bearing-area-estimated")
    (q,) = area.quantities
    assert q.kind == "area" and q.text in area.message
    assert f"A = {q.value / IN**2:.4g} in²" in warning_text(area, "US")


def test_disturbance_check_note_in_us() -> None:
    """The note of k₂ with disturbances writes the largest span load: lbf in US."""
    c = disturbed_safety_check(60_000.0, [1000.0, 400.0], [200.0, 100.0],
                               {"eccentricity": [34.5, 10.0]}, 2.5)
    assert c.note_quantities == (Quantity("1234 N", 1234.5, "force"),)
    assert "(largest span load 1234 N with" in check_row(c, "SI")[0]
    assert f"(largest span load {1234.5 / LBF:.4g} lbf with" in check_row(c, "US")[0]


def _cli(*args: str) -> str:
    """What the command prints, run in this process (:func:`tests.conftest.cli_in_process`:
    the same command as the script's, without a new interpreter per call) with the terminal
    width the subprocess had (``COLUMNS=200``)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("COLUMNS", "200")
        proc = cli_in_process(*args)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_cli_analyze_prints_the_slack_warning_in_inches() -> None:
    """``analyze --units us`` prints the seed's slack warning in inches: the slack, the
    slack span and the sag of its own ``--json`` document divided by 25.4 mm; SI prints the
    JSON's message."""
    seed = str(EXAMPLES / "seed_three_sprocket.toml")
    doc = json.loads(_cli("analyze", seed, "--quick", "--json"))
    w = next(w for w in doc["warnings"] if w["code"] == "geometry.slack")
    slack, span, sag = (q["value_si"] for q in w["quantities"])
    us = " ".join(_cli("analyze", seed, "--quick", "--units", "us").split())
    shown = re.search(r"warning: chain slack ([\d.]+) in \([\d.]+ pitches\) is not taken up: "
                      r"in the slack span \(([\d.]+) in\) it hangs in a sag of ([\d.]+) in", us)
    assert shown is not None, us
    assert [float(g) for g in shown.groups()] == pytest.approx(
        [slack / IN, span / IN, sag / IN], rel=5e-3)
    assert w["quantities"][0]["text"] not in us
    si = " ".join(_cli("analyze", seed, "--quick").split())
    assert f"warning: {w['message']}" in si


def test_cli_select_prints_the_shortfall_in_us_units() -> None:
    """``select --units us`` of the polymer chain writes the speed limit it misses in ft/min,
    as the check table does."""
    polymer = str(EXAMPLES / "seed_three_sprocket_polymer.toml")
    doc = json.loads(_cli("select", polymer, "--json"))
    speeds = [q["value_si"] for q in doc["shortfall_quantities"] if q["kind"] == "velocity"]
    us = " ".join(_cli("select", polymer, "--units", "us").split())
    shown = re.search(r"speed limit ([\d.]+) ft/min \(required ≤ ([\d.]+) ft/min\)", us)
    assert shown is not None, us
    assert [float(g) for g in shown.groups()] == pytest.approx(
        [v / 0.00508 for v in speeds], rel=5e-3)
    assert "m/s" not in us


def test_report_texts_in_us_units(analyses: dict[str, Analysis]) -> None:
    """The report's page 1, selection and checks sections in US write no SI unit in their
    paragraphs (warnings, shortfall, notes) or table cells (checks with their notes)."""
    from chaindrive.report.content import ReportInput, Table, Text
    from chaindrive.report.sections import checks_section, selection_section, summary_section

    for name in ("seed_three_sprocket", "seed_three_sprocket_polymer", "two_sprocket_jindal"):
        inp = ReportInput(analyses[name], units="US")
        blocks = [*summary_section(inp), *(selection_section(inp) or []), *checks_section(inp)]
        texts = [b.text for b in blocks if isinstance(b, Text)]
        texts += [str(cell) for b in blocks if isinstance(b, Table)
                  for cell in (*b.columns, *(c for row in b.rows for c in row))]
        assert any(t.startswith("chain slack") for t in texts) or name == "two_sprocket_jindal"
        for text in texts:
            assert not SI_UNIT.search(text), text


@pytest.mark.concurrency  # Streamlit's AppTest runs the page in a thread
def test_page_warnings_in_the_page_units() -> None:
    """The web page writes its warnings in its unit system: the seed's slack warning in mm,
    then, with US units chosen, in inches (the message's metres / 0.0254), and no warning or
    failed check with an SI unit."""
    testing = pytest.importorskip("streamlit.testing.v1")
    from chaindrive import app as app_pkg

    at = testing.AppTest.from_file(str(app_pkg.PAGE), default_timeout=60).run()
    assert not at.exception
    seed = chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                              response=False)
    w = next(w for w in seed.warnings if w.code == "geometry.slack")
    assert plain(w.message) in [x.value for x in at.warning]  # as Markdown that shows it
    at.radio(key="units").set_value("US").run()
    assert not at.exception
    assert plain(warning_text(w, "US")) in [x.value for x in at.warning]
    slack = re.search(r"chain slack ([\d.]+) in", warning_text(w, "US"))
    assert slack is not None
    assert float(slack.group(1)) == pytest.approx(w.quantities[0].value / IN, rel=5e-3)
    for x in [*at.warning, *at.error]:
        assert not SI_UNIT.search(x.value), x.value
