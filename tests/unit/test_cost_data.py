"""Unit tests of the packaged prices (``chaindrive/data/cost.toml``).

No dated, published price could be read for the packaged tables, so every packaged table is an
estimate; these tests hold the file to what it says about itself:

* every price table has its basis and date in ``[sources]`` and says "estimate";
* the figures a basis quotes follow from the table (closed form: price per metre = price per
  kg × the catalogue mass per metre of the chain [ISO606] row; the stated ranges contain the
  table's values);
* a price file whose source does not say "estimate" is reported as sourced, with its source,
  by :func:`chaindrive.cost.cost_breakdown` (the definition of the flag).
"""

from __future__ import annotations

import re
import tomllib
from importlib import resources

import pytest

from chaindrive.catalog import find_chain
from chaindrive.cost import cost_breakdown, cost_model_from_mapping, default_cost_model
from chaindrive.io.design import drive_from_mapping, parse_toml

PRICE_TABLES = ("chain_per_kg", "material_per_kg", "manufacturing_per_kg", "per_tooth")
STEELS = ("steel", "carbon steel", "alloy steel", "case-hardening steel", "cast steel")
POLYMERS = ("polyamide", "glass-filled polyamide", "acetal", "polyethylene")


def _file() -> dict:
    text = resources.files("chaindrive").joinpath("data/cost.toml").read_text("utf-8")
    return tomllib.loads(text)


def _range(text: str, what: str) -> tuple[float, float]:
    """The 'a-b EUR/kg' range a basis text quotes for ``what``."""
    found = re.search(rf"{what} (\d+(?:\.\d+)?)-(\d+(?:\.\d+)?) EUR/kg", text)
    assert found, f"the basis gives no range for {what}"
    return float(found.group(1)), float(found.group(2))


@pytest.mark.parametrize("table", PRICE_TABLES)
def test_every_packaged_price_table_is_dated_and_flagged_as_an_estimate(table: str):
    sources = default_cost_model().sources
    assert table in sources
    assert sources[table].lower().startswith("estimate (2026-11)")


def test_no_price_per_metre_is_packaged():
    data = _file()
    assert data["chain_per_metre"] == {}
    assert "none packaged" in data["sources"]["chain_per_metre"]


@pytest.mark.parametrize(("designation", "mass_kg_m"), [("ISO 606 08B-1", 0.70),
                                                        ("ISO 606 16B-1", 2.8)])
def test_quoted_prices_per_metre_follow_from_the_price_per_kg(designation: str,
                                                              mass_kg_m: float):
    """price per metre = chain_per_kg × q, q of the catalogue row (ISO 606 B, [ISO606] masses)."""
    model = default_cost_model()
    spec = find_chain(designation)
    assert spec.mass_per_length == pytest.approx(mass_kg_m)
    per_metre = model.chain_price_per_metre(spec.designation, spec.mass_per_length)
    assert per_metre == pytest.approx(model.chain_per_kg * mass_kg_m)
    number = designation.split()[-1]
    quoted = re.search(rf"(\d+(?:\.\d+)?) EUR/m for {number}", model.sources["chain_per_kg"])
    assert quoted and float(quoted.group(1)) == pytest.approx(per_metre, abs=0.05)


def test_quoted_material_ranges_contain_the_table():
    model = default_cost_model()
    basis = model.sources["material_per_kg"]
    low, high = _range(basis, "steels")
    assert all(low <= model.material_per_kg[f] <= high for f in STEELS)
    low, high = _range(basis, "engineering polymers")
    assert all(low <= model.material_per_kg[f] <= high for f in POLYMERS)
    assert f"grey cast iron {model.material_per_kg['grey cast iron']} EUR/kg" in basis


def test_a_sourced_price_is_reported_as_sourced_with_its_source():
    drive = drive_from_mapping(parse_toml(
        '[drive]\nname = "d"\npower = "1 kW"\n[chain]\ndesignation = "08B-1"\n'
        '[[sprockets]]\nname = "A"\nteeth = 17\nx = "0 mm"\ny = "0 mm"\nrole = "driver"\n'
        'speed = "500 rpm"\n[[sprockets]]\nname = "B"\nteeth = 34\nx = "400 mm"\ny = "0 mm"\n'
        'role = "driven"\n', "d.toml"))
    own = cost_model_from_mapping(
        {"chain_per_metre": {drive.chain.spec.designation: 9.5},
         "sources": {"chain_per_metre": "my supplier's quotation no. 17, 2026-11-20"}},
        "my prices")
    chain = cost_breakdown(drive, 1.0, [1.0, 2.0], own).items[-1]
    assert (chain.price, chain.estimate) == (9.5, False)
    assert chain.basis == "my supplier's quotation no. 17, 2026-11-20"
    packaged = cost_breakdown(drive, 1.0, [1.0, 2.0]).items[-1]
    assert packaged.estimate and packaged.basis.startswith("estimate (2026-11)")
