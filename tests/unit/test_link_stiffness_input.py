"""The chain's measured link stiffness as a design input (``[chain] link_stiffness``): read,
validated, written back, used by the ring, the robust study and the link-level model, and
the computed value said to be an estimate where the spans follow it.

Closed forms: a span of L/p links of stiffness k_link has c = k_link·p/L
(:func:`chaindrive.dynamics.stiffness.chain_span_stiffness`); the plates-and-pin value leaves
compliances out, so a given softer value lowers every elastic natural frequency."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import chaindrive
from chaindrive import examples
from chaindrive.catalog import find_chain, find_material
from chaindrive.dynamics.materials import with_materials
from chaindrive.dynamics.parameters import chain_link_stiffness, drive_ring_parameters
from chaindrive.dynamics.stiffness import link_stiffness
from chaindrive.errors import DesignError
from chaindrive.io.design import drive_from_mapping, drive_to_toml, parse_toml
from chaindrive.linklevel.model import build_model

MEASURED = 1.7e8  # N/m, a value of the order makers' elongation curves give for 25.4 mm

TEXT = ('[drive]\nname = "x"\npower = "1 kW"\n[chain]\ndesignation = "12B-1"\n'
        'link_stiffness = "170 kN/mm"\n[[sprockets]]\nname = "A"\nteeth = 17\n'
        'x = "0 mm"\ny = "0 mm"\nrole = "driver"\nspeed = "1400 rpm"\n[[sprockets]]\n'
        'name = "B"\nteeth = 34\nx = "600 mm"\ny = "0 mm"\nrole = "driven"\n')


def test_read_with_its_unit_and_written_back() -> None:
    drive = drive_from_mapping(parse_toml(TEXT, "x.toml"))
    assert drive.chain.link_stiffness == pytest.approx(1.7e8, rel=1e-12)
    again = drive_from_mapping(parse_toml(drive_to_toml(drive), "y.toml"))
    assert again.chain.link_stiffness == pytest.approx(drive.chain.link_stiffness, rel=1e-12)


@pytest.mark.parametrize(("value", "said"), [
    ('"170 kN"', "chain.link_stiffness"), ('"10 N/m"', "chain.link_stiffness"),
    ('"-1e8 N/m"', "chain.link_stiffness"), ('"1e12 N/m"', "chain.link_stiffness")])
def test_bad_values_name_the_field(value: str, said: str) -> None:
    with pytest.raises(DesignError, match=said):
        drive_from_mapping(parse_toml(TEXT.replace('"170 kN/mm"', value), "x.toml"))
    seed = examples.load("seed_three_sprocket")
    with pytest.raises(DesignError, match="chain.link_stiffness"):
        replace(seed.chain, link_stiffness=float("nan"))


def test_the_ring_and_the_linklevel_model_take_the_given_value() -> None:
    """The span's chain part is k_link·p/L exactly; the elastic frequencies fall."""
    seed = chaindrive.analyze(examples.load("seed_three_sprocket"), response=False)
    d, g = seed.drive, seed.geometry
    measured = replace(d, chain=replace(d.chain, link_stiffness=MEASURED))
    ring = drive_ring_parameters(measured, g)
    lengths = np.array([sp.length for sp in g.spans])
    assert ring.link_stiffness_n_per_m == MEASURED
    np.testing.assert_allclose(ring.chain_stiffness_n_per_m,
                               MEASURED * d.chain.spec.pitch / lengths, rtol=1e-12)
    computed = link_stiffness(d.chain.spec, find_material(d.chain.spec.material).youngs_modulus)
    assert drive_ring_parameters(d, g).link_stiffness_n_per_m == pytest.approx(computed)
    assert computed > MEASURED
    f_computed = seed.dynamics.modal.first_elastic_frequency_hz
    f_measured = chaindrive.analyze(measured, response=False).dynamics.modal \
        .first_elastic_frequency_hz
    assert f_measured < f_computed
    assert build_model(measured, g).link_stiffness == MEASURED


def test_a_measured_value_follows_the_modulus_of_another_state() -> None:
    """A chain measured at E_ref and computed at E: k = k_measured·E/E_ref (the robust
    study's chain at another temperature); with no value given, the plates and the pin."""
    d = replace(examples.load("seed_three_sprocket"), chain=replace(
        examples.load("seed_three_sprocket").chain, link_stiffness=MEASURED))
    assert chain_link_stiffness(d, 1.0e11, reference_modulus=2.0e11) == pytest.approx(
        MEASURED / 2)
    assert chain_link_stiffness(d, 2.0e11) == MEASURED
    bare = examples.load("seed_three_sprocket")
    assert chain_link_stiffness(bare, 2.1e11) == pytest.approx(
        link_stiffness(bare.chain.spec, 2.1e11))


def test_the_computed_value_is_said_where_the_spans_follow_it() -> None:
    """Taut spans (no power given: no static tension to sag at) follow their links: without
    a measured value the analysis says the frequencies rest on the computed one; with it,
    or on the seed's sagging spans (below half their taut stiffness), it does not."""
    seed = examples.load("seed_three_sprocket")
    taut = replace(seed, power=None)

    def said(drive: chaindrive.Drive) -> list[str]:
        return [w.message for w in chaindrive.analyze(drive, response=False).warnings
                if w.part == "chain.link_stiffness"]

    assert len(said(taut)) == 1 and "upper bound" in said(taut)[0]
    assert not said(replace(taut, chain=replace(taut.chain, link_stiffness=MEASURED)))
    assert not said(seed)


def test_the_measured_value_stays_with_its_chain() -> None:
    """A measured stiffness belongs to the chain it was measured on: with a chain to be
    selected it is refused; another catalogue chain (selection, optimiser) drops it; the
    same chain keeps it; the chain in another material (the material-pair study) scales it
    by E_new/E_old, as every compliance of a one-material chain does."""
    seed = examples.load("seed_three_sprocket")
    measured = replace(seed, chain=replace(seed.chain, link_stiffness=MEASURED))
    with pytest.raises(DesignError, match="chain.link_stiffness"):
        drive_from_mapping(parse_toml(TEXT.replace('designation = "12B-1"',
                                                   'standard = "ISO 606"'), "x.toml"))
    other = find_chain("ISO 606 16B-1")
    assert measured.with_chain(other).chain.link_stiffness is None
    assert measured.with_chain(measured.chain.spec).chain.link_stiffness == MEASURED
    e = {m: find_material(m).youngs_modulus for m in ("steel", "PA6-GF30")}
    poly = with_materials(measured, "PA6-GF30", "steel")
    assert poly.chain.link_stiffness == pytest.approx(MEASURED * e["PA6-GF30"] / e["steel"])
