"""Cost model of a drive: sprocket price from material, mass and machining; chain per metre.

    sprocket price = m · (material[family] + manufacturing[family]) + z · per_tooth[family]
    chain price    = L_chain · price_per_metre (listed, else chain_per_kg · q)
    cost           = Σ sprockets + chain (+ flywheels at the "flywheel" family)

The packaged numbers (``data/cost.toml``) are ESTIMATES: no distributor's price
list could be read while they were compiled; each value's basis and date are in the file's
``[sources]`` table and travel with the model (:attr:`CostModel.sources`), so a report says
what rests on an estimate. Users set their own prices with a file of the same form
(:func:`load_cost_model`); :func:`cost_breakdown` gives the parts of the cost of one drive.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.errors import DesignError
from chaindrive.io.design import read_toml
from chaindrive.model import Drive

__all__ = ["CostBreakdown", "CostItem", "CostModel", "cost_breakdown", "cost_model_from_mapping",
           "default_cost_model", "load_cost_model"]


@dataclass(frozen=True, slots=True)
class CostModel:
    """Prices per kg by material family and per metre of chain.

    Parameters
    ----------
    material_per_kg : dict of str to float
        Material family → price of the material [currency/kg] (key ``default`` for unlisted
        families, ``flywheel`` for added inertia).
    manufacturing_per_kg : dict of str to float
        Material family → price of making a part of it [currency/kg].
    chain_per_kg : float
        Price of chain by mass [currency/kg].
    chain_per_metre : dict of str to float
        Chain designation → price [currency/m] (overrides ``chain_per_kg``).
    currency : str
        The currency of every price.
    source : str
        Where the prices come from.
    per_tooth : dict of str to float
        Material family → price of cutting one tooth [currency].
    sources : dict of str to str
        Table name → basis and date of its prices (says what rests on an estimate).
    """

    material_per_kg: dict[str, float]
    manufacturing_per_kg: dict[str, float]
    chain_per_kg: float
    chain_per_metre: dict[str, float]
    currency: str = "EUR"
    source: str = "packaged estimates"
    per_tooth: dict[str, float] = field(default_factory=dict)
    sources: dict[str, str] = field(default_factory=dict)

    def part_price_per_kg(self, family: str) -> float:
        """Material + manufacturing price of one kg of a part.

        Parameters
        ----------
        family : str
            Material family (``default`` covers the unlisted ones).

        Returns
        -------
        float
            Price [currency/kg].
        """
        def get(table: dict[str, float]) -> float:
            return table.get(family, table.get("default", 0.0))

        return get(self.material_per_kg) + get(self.manufacturing_per_kg)

    @shared_parameters
    def sprocket_price(self, family: str, mass: float, teeth: int) -> float:
        """Price of one sprocket: mass × (material + manufacturing per kg) + teeth × the
        tooth-cutting price of its family.

        Parameters
        ----------
        family : str
            Material family of the sprocket.
        mass : float
            Mass of the sprocket body [kg].
        %(teeth)s

        Returns
        -------
        float
            Price [currency].
        """
        cut = self.per_tooth.get(family, self.per_tooth.get("default", 0.0))
        return mass * self.part_price_per_kg(family) + teeth * cut

    def chain_price_per_metre(self, designation: str, mass_per_length: float) -> float:
        """Price of one metre of chain: listed, else ``chain_per_kg`` · q.

        Parameters
        ----------
        designation : str
            The chain.
        mass_per_length : float
            Its mass per metre q [kg/m].

        Returns
        -------
        float
            Price [currency/m].
        """
        return self.chain_per_metre.get(designation, self.chain_per_kg * mass_per_length)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"currency": self.currency, "chain_per_kg": self.chain_per_kg,
                "material_per_kg": dict(self.material_per_kg),
                "manufacturing_per_kg": dict(self.manufacturing_per_kg),
                "chain_per_metre": dict(self.chain_per_metre),
                "per_tooth": dict(self.per_tooth), "source": self.source,
                "sources": dict(self.sources)}


def _prices(data: object, path: str) -> dict[str, float]:
    if not isinstance(data, dict):
        raise DesignError(path, f"must be a table of prices, got {data!r}")
    out = {}
    for k, v in data.items():
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v < 0:
            raise DesignError(f"{path}.{k}", f"must be a price ≥ 0, got {v!r}")
        out[str(k)] = float(v)
    return out


def _table(data: object, path: str) -> dict[str, Any]:
    if not isinstance(data, dict):
        raise DesignError(path, f"must be a table, got {data!r}")
    return {str(k): v for k, v in data.items()}


def cost_model_from_mapping(data: dict[str, Any], source: str) -> CostModel:
    """A cost model from the tables of a cost file (see the packaged ``cost.toml``).

    Parameters
    ----------
    data : dict
        The parsed TOML: ``currency``, ``chain_per_kg`` [currency/kg], ``material_per_kg``,
        ``manufacturing_per_kg`` [currency/kg], ``chain_per_metre`` [currency/m],
        ``per_tooth`` [currency], ``sources``.
    source : str
        Where the tables come from (a file name).

    Returns
    -------
    CostModel
        The validated model.

    Raises
    ------
    DesignError
        Naming the field (``cost.<table>.<key>``) of an unknown field or a price that is not
        a number ≥ 0.
    """
    known = {"currency", "chain_per_kg", "material_per_kg", "manufacturing_per_kg",
             "chain_per_metre", "per_tooth", "sources"}
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
                     str(data.get("currency", "EUR")), source,
                     _prices(data.get("per_tooth", {}), "cost.per_tooth"),
                     {str(k): str(v) for k, v in _table(data.get("sources", {}),
                                                         "cost.sources").items()})


def load_cost_model(path: str | Path) -> CostModel:
    """A cost model from a TOML file of the packaged form.

    Parameters
    ----------
    path : str or pathlib.Path
        The cost file.

    Returns
    -------
    CostModel
        The validated model (:func:`cost_model_from_mapping`).
    """
    return cost_model_from_mapping(read_toml(path, "cost file"), str(Path(path)))


@lru_cache(maxsize=1)
def default_cost_model() -> CostModel:
    """The packaged estimated prices (``chaindrive/data/cost.toml``, read once).

    Returns
    -------
    CostModel
        The estimates, each table's basis in :attr:`CostModel.sources`.
    """
    text = resources.files("chaindrive").joinpath("data/cost.toml").read_text("utf-8")
    return cost_model_from_mapping(tomllib.loads(text), "packaged estimates (cost.toml)")


@dataclass(frozen=True, slots=True)
class CostItem:
    """One priced part.

    Parameters
    ----------
    name : str
        The part (a sprocket's name, the chain's designation).
    kind : str
        "sprocket", "chain" or "flywheel".
    what : str
        Material family or chain designation.
    quantity : float
        Mass of a sprocket or flywheel [kg] or length of chain [m] (see ``unit``).
    unit : str
        "kg" or "m".
    price : float
        Price of the part [currency].
    basis : str
        The table entries the price rests on.
    estimate : bool
        True when the price rests on an estimate.
    """

    name: str
    kind: str
    what: str
    quantity: float
    unit: str
    price: float
    basis: str
    estimate: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"name": self.name, "kind": self.kind, "what": self.what,
                "quantity": self.quantity, "unit": self.unit, "price": self.price,
                "basis": self.basis, "estimate": self.estimate}


@dataclass(frozen=True, slots=True)
class CostBreakdown:
    """The cost of a drive part by part.

    Parameters
    ----------
    items : tuple of CostItem
        Every priced part.
    currency : str
        The currency of the prices.
    source : str
        The cost model's source.
    """

    items: tuple[CostItem, ...]
    currency: str
    source: str

    @property
    def total(self) -> float:
        """Sum of the items [currency]."""
        return sum(i.price for i in self.items)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (the report's cost table)."""
        return {"currency": self.currency, "total": self.total, "source": self.source,
                "items": [i.to_dict() for i in self.items]}


def _estimated(model: CostModel, *keys: str) -> tuple[str, bool]:
    notes = [model.sources[k] for k in keys if k in model.sources]
    return "; ".join(notes) or model.source, any("estimate" in n.lower() for n in notes)


def cost_breakdown(drive: Drive, chain_length: float, sprocket_masses: Iterable[float],
                   model: CostModel | None = None,
                   flywheel_masses: Iterable[float] | None = None) -> CostBreakdown:
    """The cost of a drive, part by part.

    Parameters
    ----------
    drive : Drive
        The design: sprockets with their materials, the chain, the number of contours.
    chain_length : float
        Length of one contour's chain [m] (× contours).
    sprocket_masses : sequence of float
        Mass of each sprocket body [kg] (one per contour on its shaft).
    model : CostModel or None
        Prices (None: :func:`default_cost_model`).
    flywheel_masses : sequence of float or None
        Mass of each sprocket's flywheel [kg], priced at the ``flywheel`` family.

    Returns
    -------
    CostBreakdown
        Sprockets, flywheels and chain with their prices and bases.
    """
    cm = model or default_cost_model()
    m = drive.chain.contours
    items = []
    for i, (s, mass) in enumerate(zip(drive.sprockets, sprocket_masses, strict=True)):
        family = find_material(s.material, field=f"sprockets[{i}].material").family
        basis, est = _estimated(cm, "material_per_kg", "manufacturing_per_kg", "per_tooth")
        items.append(CostItem(s.name, "sprocket", family, float(mass) * m, "kg",
                              m * cm.sprocket_price(family, float(mass), s.teeth), basis, est))
    for s, mass in zip(drive.sprockets, () if flywheel_masses is None else flywheel_masses,
                       strict=False):
        if mass > 0:
            basis, est = _estimated(cm, "material_per_kg", "manufacturing_per_kg")
            items.append(CostItem(f"{s.name} flywheel", "flywheel", "flywheel", float(mass),
                                  "kg", float(mass) * cm.part_price_per_kg("flywheel"), basis,
                                  est))
    spec = drive.chain.spec
    length = chain_length * drive.chain.contours
    listed = spec.designation in cm.chain_per_metre
    basis, est = _estimated(cm, "chain_per_metre" if listed else "chain_per_kg")
    items.append(CostItem(spec.designation, "chain", spec.designation, length, "m",
                          length * cm.chain_price_per_metre(spec.designation,
                                                            spec.mass_per_length), basis, est))
    return CostBreakdown(tuple(items), cm.currency, cm.source)
