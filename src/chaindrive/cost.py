"""Cost model of a drive: material and manufacturing per kg, chain per metre.

The packaged numbers (``data/cost.toml``) are **placeholders** chosen for chaindrive,
not prices from a source: they only weigh material, manufacturing and chain against each
other. Users set their own prices with a file of the same form
(:func:`load_cost_model`)::

    cost = Σ_parts m_part · (material[family] + manufacturing[family]) + L_chain · price_per_metre
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from chaindrive.errors import DesignError
from chaindrive.io.design import read_toml

__all__ = ["CostModel", "default_cost_model", "load_cost_model"]


@dataclass(frozen=True, slots=True)
class CostModel:
    """Prices per kg by material family and per metre of chain.

    material_per_kg, manufacturing_per_kg : family → price [currency/kg] (key ``default`` for
    unlisted families, ``flywheel`` for added inertia); chain_per_kg [currency/kg] of chain;
    chain_per_metre : designation → price [currency/m] (overrides chain_per_kg); currency.
    """

    material_per_kg: dict[str, float]
    manufacturing_per_kg: dict[str, float]
    chain_per_kg: float
    chain_per_metre: dict[str, float]
    currency: str = "EUR"
    source: str = "packaged placeholders"

    def part_price_per_kg(self, family: str) -> float:
        """Material + manufacturing price of one kg of a part of ``family`` [currency/kg]."""
        def get(table: dict[str, float]) -> float:
            return table.get(family, table.get("default", 0.0))

        return get(self.material_per_kg) + get(self.manufacturing_per_kg)

    def chain_price_per_metre(self, designation: str, mass_per_length: float) -> float:
        """Price of one metre of chain [currency/m]: listed, else chain_per_kg · q."""
        return self.chain_per_metre.get(designation, self.chain_per_kg * mass_per_length)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"currency": self.currency, "chain_per_kg": self.chain_per_kg,
                "material_per_kg": dict(self.material_per_kg),
                "manufacturing_per_kg": dict(self.manufacturing_per_kg),
                "chain_per_metre": dict(self.chain_per_metre), "source": self.source}


def _prices(data: Any, path: str) -> dict[str, float]:
    if not isinstance(data, dict):
        raise DesignError(path, f"must be a table of prices, got {data!r}")
    out = {}
    for k, v in data.items():
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v < 0:
            raise DesignError(f"{path}.{k}", f"must be a price ≥ 0, got {v!r}")
        out[str(k)] = float(v)
    return out


def cost_model_from_mapping(data: dict[str, Any], source: str) -> CostModel:
    """Validate the tables of a cost file (see the packaged ``cost.toml``)."""
    known = {"currency", "chain_per_kg", "material_per_kg", "manufacturing_per_kg",
             "chain_per_metre"}
    for key in data:
        if key not in known:
            raise DesignError(f"cost.{key}", f"unknown field (known: {', '.join(sorted(known))})")
    per_kg = data.get("chain_per_kg", 0.0)
    if isinstance(per_kg, bool) or not isinstance(per_kg, int | float) or per_kg < 0:
        raise DesignError("cost.chain_per_kg", f"must be a price ≥ 0, got {per_kg!r}")
    return CostModel(_prices(data.get("material_per_kg", {}), "cost.material_per_kg"),
                     _prices(data.get("manufacturing_per_kg", {}), "cost.manufacturing_per_kg"),
                     float(per_kg), _prices(data.get("chain_per_metre", {}),
                                            "cost.chain_per_metre"),
                     str(data.get("currency", "EUR")), source)


def load_cost_model(path: str | Path) -> CostModel:
    """A cost model from a TOML file of the packaged form."""
    return cost_model_from_mapping(read_toml(path, "cost file"), str(Path(path)))


@lru_cache(maxsize=1)
def default_cost_model() -> CostModel:
    """The packaged placeholder prices (``chaindrive/data/cost.toml``)."""
    text = resources.files("chaindrive").joinpath("data/cost.toml").read_text("utf-8")
    return cost_model_from_mapping(tomllib.loads(text), "packaged placeholders (cost.toml)")
