"""Unit tests: lubrication advice (WENTZELL-MD-EX14.4 of cases.yaml and the [McGuireLube] /
[KettenfabrikUnna] limits), chain length options and the sag allowance (closed forms of a
shallow parabola), the cost breakdown (its definition), and a polymer drive in one line."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

import chaindrive
from chaindrive.catalog import find_chain
from chaindrive.cost import cost_breakdown, default_cost_model
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.length_options import length_options
from chaindrive.geometry.sag import sag_of_slack, slack_for_sag
from chaindrive.io.design import drive_from_mapping, drive_to_toml, parse_toml
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.strength import iso10823
from chaindrive.strength.loads import sag_tension
from chaindrive.strength.lubrication import lubrication_advice, speed_limits

RPM = math.pi / 30


def test_wentzell_no40_at_900_fpm_is_bath_or_disc():
    """WENTZELL-MD-EX14.4 (gate false): No. 40 at 900 ft/min → "bath or disc"."""
    advice = lubrication_advice(find_chain("ANSI 40"), 900 * iso10823.FPM)
    assert advice.regime == "bath/disc" and advice.ansi_type == "B"


@pytest.mark.parametrize(("v", "regime"), [(0.3, "manual"), (0.7, "drip"), (5.0, "bath/disc"),
                                           (9.0, "forced")])
def test_regime_by_speed_for_a_b_series_chain(v, regime):
    """16B-1 (p = 25.4 mm) takes the ANSI 80 limits: drip ≤ 0.86, bath ≤ 7.6 m/s
    [McGuireLube]; manual ≤ 0.5 m/s [KettenfabrikUnna]."""
    advice = lubrication_advice(find_chain("16B-1"), v)
    assert advice.regime == regime and advice.drip_max == pytest.approx(0.86)
    assert advice.to_dict()["chain_speed_m_s"] == v


def test_gost_and_off_table_pitches_get_advice_with_a_note():
    drip, bath, note = speed_limits(0.0095)  # 06B: below the table
    assert drip > 1.52 and bath > 11.7 and "extrapolated" in note
    drip, bath, note = speed_limits(0.0635)  # 40B: above the table
    assert drip < 0.51 and "extrapolated" in note


def test_polymer_runs_dry():
    advice = lubrication_advice(find_chain("POM 08B"), 2.0)
    assert advice.regime.startswith("none: dry-running polymer") and advice.ansi_type is None


def test_sag_closed_forms_are_inverse():
    # parabola: ΔL = 8/3·s²·ℓ, f = √(3ℓΔL/8)
    assert slack_for_sag(1.0, 0.02) == pytest.approx(8 / 3 * 4e-4)
    assert sag_of_slack(0.8, slack_for_sag(0.8, 0.03)) == pytest.approx(0.03 * 0.8)
    assert sag_of_slack(1.0, -1.0) == 0.0


def _two(a: float = 0.6) -> Drive:
    return Drive("t", Chain(find_chain("12B-1")),
                 (Sprocket("A", 17, 0, 0, "driver", speed=1400 * RPM),
                  Sprocket("B", 34, a, 0, "driven")), power=12e3)


def test_sag_allowance_sets_the_installed_centre_distance():
    """With sag s the slack span keeps ΔL = 8/3·s²·ℓ: the sprocket stops short of the tight
    position by ΔL/(2 cos γ) ≈ ΔL/2 (two spans), and the slack span sags by s·ℓ."""
    tight = contour_geometry(_two())
    sagged = contour_geometry(replace(_two(), chain=replace(_two().chain, sag=0.04)))
    assert sagged.links == tight.links
    span = tight.spans[0].length
    expected = slack_for_sag(span, 0.04)
    assert sagged.slack == pytest.approx(expected, rel=0.01)  # ℓ shortens by ΔL/2
    assert tight.center_distance - sagged.center_distance == pytest.approx(expected / 2, rel=0.01)
    assert sag_of_slack(sagged.spans[0].length, sagged.slack) == pytest.approx(
        0.04 * sagged.spans[0].length, rel=0.005)


def test_installed_sag_sets_the_static_tension_and_the_span_stiffness():
    """The slack span installed with sag s carries F₀ = k_f q g ℓ with k_f = cos ψ/(8s) +
    |sin ψ| (the parabolic catenary, H = q g ℓ²/(8f) [ChainDesignRU, §8]): halving the sag
    from the default 2 % to 1 % doubles F₀ on this horizontal drive, and the spans, whose
    sag stiffness rises as T³ [Ernst1965], get stiffer, so f₁ rises."""
    import chaindrive

    default = chaindrive.analyze(_two(), response=False)
    taut = chaindrive.analyze(replace(_two(), chain=replace(_two().chain, sag=0.01)),
                              response=False)
    span = taut.geometry.spans[taut.strength.loads.slack_span]
    q = taut.drive.chain.spec.mass_per_length
    assert taut.strength.loads.sag_tension == pytest.approx(
        sag_tension(q, span.length, span.inclination, 0.01), rel=1e-12)
    psi = span.inclination
    assert taut.strength.loads.sag_factor == pytest.approx(
        math.cos(psi) / (8 * 0.01) + abs(math.sin(psi)), rel=1e-12)
    loose = default.geometry.spans[default.strength.loads.slack_span]
    assert default.strength.loads.sag_tension == pytest.approx(
        sag_tension(q, loose.length, loose.inclination, 0.02), rel=1e-12)
    ratio = taut.strength.loads.sag_tension / default.strength.loads.sag_tension
    assert ratio == pytest.approx(2.0, rel=0.02)  # the installed span is a little shorter
    assert (taut.dynamics.modal.first_elastic_frequency_hz
            > default.dynamics.modal.first_elastic_frequency_hz)


def test_length_options_round_down_and_up():
    lc = length_options(_two())
    down, up = lc.options
    assert down.links < lc.tight_pitches < up.links and down.links % 2 == 0 == up.links % 2
    assert down.centre_distance < up.centre_distance and lc.chosen == "round up"
    assert lc.to_dict()["options"][0]["rounding"] == "round down"


def test_design_file_links_choice_and_sag_round_trip():
    text = ('[drive]\nname = "x"\npower = "1 kW"\n[chain]\ndesignation = "12B-1"\n'
            'links = "round down"\nsag = 0.03\n[[sprockets]]\nname = "A"\nteeth = 17\n'
            'x = "0 mm"\ny = "0 mm"\nrole = "driver"\nspeed = "1400 rpm"\n[[sprockets]]\n'
            'name = "B"\nteeth = 34\nx = "600 mm"\ny = "0 mm"\nrole = "driven"\n')
    drive = drive_from_mapping(parse_toml(text, "x.toml"))
    assert drive.chain.rounding == "round down" and drive.chain.sag == 0.03
    again = drive_from_mapping(parse_toml(drive_to_toml(drive), "y.toml"))
    assert (again.chain.rounding, again.chain.sag) == ("round down", 0.03)
    with pytest.raises(DesignError, match="chain.links"):
        drive_from_mapping(parse_toml(text.replace('"round down"', '"round sideways"'), "z"))


def test_polymer_drive_is_one_line_in_a_design_file(tmp_path):
    path = tmp_path / "poly.toml"
    path.write_text('[drive]\nname = "poly"\npower = "20 W"\n[chain]\n'
                    'designation = "POM 08B"\n[[sprockets]]\nname = "A"\nteeth = 19\n'
                    'x = "0 mm"\ny = "0 mm"\nrole = "driver"\nspeed = "100 rpm"\n'
                    '[[sprockets]]\nname = "B"\nteeth = 38\nx = "500 mm"\ny = "0 mm"\n'
                    'role = "driven"\n', encoding="utf-8")
    drive = chaindrive.load(path)
    assert drive.chain.spec.material == "POM"
    result = chaindrive.analyze(drive, response=False)
    assert result.geometry.links > 0


def test_cost_breakdown_adds_up_and_says_what_is_estimated():
    drive = _two()
    g = contour_geometry(drive)
    cm = default_cost_model()
    bd = cost_breakdown(drive, g.chain_length, [2.0, 5.0], cm)
    assert bd.total == pytest.approx(
        2.0 * cm.part_price_per_kg("steel") + 17 * cm.per_tooth["steel"]
        + 5.0 * cm.part_price_per_kg("steel") + 34 * cm.per_tooth["steel"]
        + g.chain_length * cm.chain_per_kg * drive.chain.spec.mass_per_length)
    d = bd.to_dict()
    assert all(item["estimate"] for item in d["items"]) and "estimate" in d["items"][0]["basis"]


def test_an_assumed_sag_is_said_where_the_spans_follow_it():
    """The seed contour's spans are set by their sag (the slack span keeps about 1 % of its
    taut stiffness): without ``[chain] sag`` the analysis says that the tensions rest on the
    assumed 2 %; with the sag given it does not."""
    import chaindrive
    from chaindrive import examples

    seed = examples.load("seed_three_sprocket")
    said = [w for w in chaindrive.analyze(seed, response=False).warnings
            if w.part == "chain.sag"]
    assert len(said) == 1 and said[0].code == "dynamics.estimate"
    given = replace(seed, chain=replace(seed.chain, sag=0.02))
    assert not [w for w in chaindrive.analyze(given, response=False).warnings
                if w.part == "chain.sag"]


@pytest.mark.parametrize("sag", [None, 0.01])
def test_start_up_and_link_level_pretension_follow_the_installed_sag(sag):
    """The spans at rest carry the F₀ of the static loads (k_f from the installed sag, 2 % when
    not given) in the ring start-up and in the link-level model alike: one pre-tension."""
    from chaindrive.linklevel.model import build_model
    from chaindrive.strength import strength_of
    from chaindrive.strength.loads import installed_pretension

    drive = replace(_two(), chain=replace(_two().chain, sag=sag))
    g = contour_geometry(drive)
    f0 = strength_of(drive, g).loads.sag_tension
    assert installed_pretension(drive, g) == pytest.approx(f0, rel=1e-12)
    assert build_model(drive, g).pretension == pytest.approx(f0, rel=1e-12)
