"""The chain and material catalogue: packaged data files plus a user's own files.

Packaged files (``chaindrive/catalog/data/``, each with a ``#`` header naming its sources,
units and every derived or unconfirmed value; see ``docs/catalog.md``):

* ``chains_iso606.csv`` — ISO 606 A and B series, simplex to triplex, with ANSI/ASME B29.1
  numbers for the A series;
* ``chains_gost13568.csv`` — GOST 13568-97 ПР, 2ПР, 3ПР, 4ПР chains with the tabulated
  projected bearing area;
* ``materials.csv`` — sprocket materials (steels, grey cast iron, PA6, PA66, PA6-GF30, POM …).

Everything returned is a :class:`~chaindrive.model.ChainSpec` or
:class:`~chaindrive.model.Material` in SI units. A user's file (CSV with the same columns as
ours, or TOML, see :func:`load_chain_file`) is added with ``extra_files``; its entries replace
packaged entries of the same name.

Bearing area
------------
``ChainSpec.bearing_area`` is the projected hinge bearing area of the whole chain as the
GOST/Russian method uses it (p = Kэ·Ft/A): for n rows A = m_r·A₁ with the row factor
m_r = 1, 1.7, 2.5, 3.0 for 1–4 rows [TrinhChat2006, Table 5.12], [ChainDesignRU, §1]. GOST
chains carry the tabulated value; for ISO chains no source gives A, and it is DERIVED by
:func:`bearing_area_estimate`: A₁ = d₂·B with the bush length B ≈ (b₁ + p_t)/2, or
B ≈ 1.42·b₁ when the transverse pitch is not known (:func:`bush_length_estimate`).
"""

from __future__ import annotations

import csv
import math
import re
import tomllib
import unicodedata
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any, Generic, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._numeric import FloatOrArray, float_or_array
from chaindrive.errors import CatalogError, DesignError, closest
from chaindrive.model import ChainSpec, Material
from chaindrive.units import parse_quantity

__all__ = [
    "PACKAGED_CHAIN_FILES",
    "PACKAGED_MATERIAL_FILES",
    "ROW_FACTORS",
    "bearing_area_estimate",
    "bush_length_estimate",
    "chains",
    "chains_by_pitch",
    "designation_key",
    "find_chain",
    "find_material",
    "load_chain_file",
    "load_material_file",
    "material_key",
    "materials",
    "row_factor",
]

PACKAGED_CHAIN_FILES: tuple[str, ...] = ("chains_iso606.csv", "chains_ansi_b29.csv",
                                         "chains_gost13568.csv", "chains_polymer.csv")
PACKAGED_MATERIAL_FILES: tuple[str, ...] = ("materials.csv",)

#: Row factor m_r of multi-row chains (effective bearing area / single-row area), 1–4 rows
#: [TrinhChat2006, Table 5.12] (ratios of its columns), [ChainDesignRU, §1]. Not the
#: multiple-strand factor of a power rating (:func:`chaindrive.strength.iso10823.strand_factor`).
ROW_FACTORS: dict[int, float] = {1: 1.0, 2: 1.7, 3: 2.5, 4: 3.0}
#: Median ratio of the bush length B to the inner width b₁ of the GOST 13568 ПР chains of
#: 19.05…50.8 mm pitch (17.75/12.70, 22.61/15.88, …) [GOST13568, Table 1].
BUSH_TO_INNER_WIDTH = 1.42

PathLike = str | Path


# --------------------------------------------------------------------------- formulas
def row_factor(strands: int) -> float:
    """Row factor m_r of the bearing area of a multi-row chain.

    Parameters
    ----------
    strands : int
        Number of rows n [-].

    Returns
    -------
    float
        m_r [-]: 1, 1.7, 2.5, 3.0 for 1–4 rows (:data:`ROW_FACTORS`).

    Raises
    ------
    CatalogError
        On ``chain.strands`` beyond 4 rows (no source gives a factor).

    References
    ----------
    [TrinhChat2006, Table 5.12]; [ChainDesignRU, §1].
    """
    try:
        return ROW_FACTORS[strands]
    except KeyError:
        raise CatalogError(
            "chain.strands", f"no row factor for {strands!r} strands (known for 1 to 4)"
        ) from None


def bush_length_estimate(inner_width: ArrayLike, transverse_pitch: ArrayLike) -> FloatOrArray:
    """Bush length B [m] — an approximation derived for chaindrive.

    B ≈ (b₁ + p_t)/2: the transverse pitch spans the inner width, two inner and two outer
    plates, p_t ≈ b₁ + 2s_i + 2s_o; with s_i ≈ s_o the bush (inner-link) length is
    B = b₁ + 2s_i ≈ (b₁ + p_t)/2. Checked against the bush lengths of [TrinhChat2006,
    Table 5.5] (e.g. 16A/ПР-25,4: (15.88 + 29.29)/2 = 22.59 vs 22.61 mm). Where p_t is not
    known (0), B ≈ 1.42·b₁ (:data:`BUSH_TO_INNER_WIDTH`).

    Parameters
    ----------
    inner_width : float or array_like
        Inner width b₁ [m].
    transverse_pitch : float or array_like
        Transverse pitch p_t [m] (0: not known).

    Returns
    -------
    float or numpy.ndarray
        B [m].

    References
    ----------
    [TrinhChat2006, Table 5.5]; [GOST13568, Table 1].
    """
    b1 = np.asarray(inner_width, dtype=float)
    pt = np.asarray(transverse_pitch, dtype=float)
    return float_or_array(np.where(pt > 0, 0.5 * (b1 + pt), BUSH_TO_INNER_WIDTH * b1))


def bearing_area_estimate(pin_diameter: ArrayLike, inner_width: ArrayLike,
                          transverse_pitch: ArrayLike, strands: int = 1) -> FloatOrArray:
    """Projected bearing area of the whole chain A = m_r·d₂·B [m²] (DERIVED, module doc).

    Reproduces the GOST 13568 / table 5.12 areas within 4.5 % for every multi-row GOST chain
    (tested in ``tests/unit/test_catalog.py``).

    Parameters
    ----------
    pin_diameter : float or array_like
        Pin diameter d₂ [m].
    inner_width : float or array_like
        Inner width b₁ [m].
    transverse_pitch : float or array_like
        Transverse pitch p_t [m] (0: not known).
    strands : int
        Rows n [-] (m_r from :func:`row_factor`).

    Returns
    -------
    float or numpy.ndarray
        A [m²], B from :func:`bush_length_estimate`.

    References
    ----------
    [TrinhChat2006, Tables 5.5 and 5.12]; [ChainDesignRU, §1].
    """
    bush = np.asarray(bush_length_estimate(inner_width, transverse_pitch))
    return float_or_array(row_factor(strands) * np.asarray(pin_diameter, dtype=float) * bush)


# --------------------------------------------------------------------------- names
_PREFIX = re.compile(
    r"^(?:ISO606(?::\d{4})?|GOST13568(?:-\d{2})?|ГОСТ13568(?:-\d{2})?|"
    r"ANSI/ASMEB29\.1|ASMEB29\.1|ANSI)[-:]?"
)
_LATIN_OF_CYRILLIC = str.maketrans({"А": "A", "В": "B", "С": "C"})


def designation_key(designation: str) -> str:
    """Normalised look-up key of a chain designation (case, spaces, ',' vs '.' ignored).

    ``"ISO 606 16B"`` → ``"16B-1"``; ``"ANSI 80"`` → ``"80-1"``;
    ``"GOST 13568 ПР-25,4-60"`` and ``"пр-25.40-60"`` → ``"ПР-25.4-60"``.

    Parameters
    ----------
    designation : str
        A chain designation as a user writes it.

    Returns
    -------
    str
        The key the catalogue index uses.
    """
    s = unicodedata.normalize("NFKC", designation).upper()
    s = re.sub(r"\s+", "", s).replace(",", ".")
    s = _PREFIX.sub("", s)
    s = re.sub(r"(\d?)PR-", r"\1ПР-", s)
    if "ПР" not in s:
        s = s.translate(_LATIN_OF_CYRILLIC)
    s = re.sub(r"\.(\d+)", lambda m: ("." + m.group(1).rstrip("0")).rstrip("."), s)
    if re.fullmatch(r"\d{2}[A-Z]|\d{2,3}", s):
        s += "-1"
    return s


def material_key(name: str) -> str:
    """Normalised look-up key of a material name.

    Parameters
    ----------
    name : str
        A material name as a user writes it (case, spaces, '-', '.', '/' ignored; Cyrillic
        'Х' in steel grades read as Latin 'X').

    Returns
    -------
    str
        The key the catalogue index uses.
    """
    s = unicodedata.normalize("NFKC", name).lower().replace("х", "x")
    return re.sub(r"[\s\-_./]", "", s)


# --------------------------------------------------------------------------- file parsing
Entry = TypeVar("Entry", ChainSpec, Material)


@dataclass(frozen=True, slots=True)
class _Named(Generic[Entry]):
    """An entry with the extra names it may be looked up by."""

    item: Entry
    aliases: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class _FileContent:
    chains: tuple[_Named[ChainSpec], ...]
    materials: tuple[_Named[Material], ...]


# column → (ChainSpec field, factor to SI, required, kind)  kind: pos | nonneg | opt
_CHAIN_NUMBERS: dict[str, tuple[str, float, str]] = {
    "pitch_mm": ("pitch", 1e-3, "pos"),
    "roller_diameter_mm": ("roller_diameter", 1e-3, "pos"),
    "pin_diameter_mm": ("pin_diameter", 1e-3, "pos"),
    "inner_width_mm": ("inner_width", 1e-3, "pos"),
    "plate_depth_mm": ("plate_depth", 1e-3, "pos"),
    "transverse_pitch_mm": ("transverse_pitch", 1e-3, "nonneg"),
    "breaking_load_kN": ("breaking_load", 1e3, "pos"),
    "mass_kg_m": ("mass_per_length", 1.0, "pos"),
    "bearing_area_mm2": ("bearing_area", 1e-6, "opt"),
    "allowable_load_kN": ("allowable_load", 1e3, "opt"),
    "max_speed_m_s": ("max_speed", 1.0, "opt"),
}
_CHAIN_TEXT = ("designation", "standard", "series", "strands", "ansi", "aliases", "material",
               "source")
_CHAIN_REQUIRED = ("designation", "pitch_mm", "roller_diameter_mm", "pin_diameter_mm",
                   "inner_width_mm", "plate_depth_mm", "breaking_load_kN", "mass_kg_m")
_MATERIAL_NUMBERS: dict[str, tuple[str, float, str]] = {
    "density_kg_m3": ("density", 1.0, "pos"),
    "youngs_modulus_GPa": ("youngs_modulus", 1e9, "pos"),
    "tensile_strength_MPa": ("tensile_strength", 1e6, "opt"),
    "friction_vs_steel": ("friction_vs_steel", 1.0, "opt"),
}
_MATERIAL_TEXT = ("name", "aliases", "family", "source")
_MATERIAL_REQUIRED = ("name", "family", "density_kg_m3", "youngs_modulus_GPa")

# TOML keys → (dimension for chaindrive.units, kind); same fields as the CSV columns.
_CHAIN_TOML: dict[str, tuple[str, str]] = {
    "pitch": ("length", "pos"), "roller_diameter": ("length", "pos"),
    "pin_diameter": ("length", "pos"), "inner_width": ("length", "pos"),
    "plate_depth": ("length", "pos"), "transverse_pitch": ("length", "nonneg"),
    "breaking_load": ("force", "pos"), "mass_per_length": ("linear_density", "pos"),
    "bearing_area": ("area", "opt"),
    "allowable_load": ("force", "opt"), "max_speed": ("velocity", "opt"),
}
_MATERIAL_TOML: dict[str, tuple[str, str]] = {
    "density": ("density", "pos"), "youngs_modulus": ("pressure", "pos"),
    "tensile_strength": ("pressure", "opt"),
}


def _number(text: str, kind: str, where: str) -> float | None:
    """Parse one numeric cell; ``kind`` pos (> 0), nonneg (≥ 0, blank = 0) or opt (blank = None)."""
    text = text.strip()
    if not text:
        if kind == "pos":
            raise CatalogError(where, "is empty; a positive number is required")
        return 0.0 if kind == "nonneg" else None
    try:
        value = float(text)
    except ValueError:
        raise CatalogError(where, f"must be a number, got {text!r}") from None
    if not math.isfinite(value) or value < 0 or (value == 0 and kind != "nonneg"):
        allowed = "zero or positive" if kind == "nonneg" else "positive"
        raise CatalogError(where, f"must be a {allowed} number, got {text!r}")
    return value


def _strands(text: str, where: str) -> int:
    text = text.strip() or "1"
    if not text.isdigit() or not 1 <= int(text) <= 8:
        raise CatalogError(where, f"must be a whole number from 1 to 8, got {text!r}")
    return int(text)


def _aliases(text: str) -> tuple[str, ...]:
    return tuple(a.strip() for a in text.split("|") if a.strip())


def _csv_rows(text: str, name: str) -> tuple[list[str], list[tuple[int, dict[str, str]]]]:
    """Header and (line number, row) pairs of a CSV text whose '#' lines are comments."""
    lines = [(i, line) for i, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise CatalogError(name, "no header line (the file is empty or only comments)")
    parsed = list(csv.reader(line for _, line in lines))
    header = [h.strip() for h in parsed[0]]
    rows: list[tuple[int, dict[str, str]]] = []
    for (lineno, _), cells in zip(lines[1:], parsed[1:], strict=True):
        if len(cells) > len(header):
            raise CatalogError(f"{name}: row {len(rows) + 1} (line {lineno})",
                               f"has {len(cells)} cells but the header has {len(header)} columns")
        rows.append((lineno, dict(zip(header, cells + [""] * (len(header) - len(cells)),
                                      strict=True))))
    return header, rows


def _check_columns(header: list[str], known: Iterable[str], required: Iterable[str],
                   name: str) -> None:
    known = list(known)
    for column in header:
        if column not in known:
            best = closest(column, known)
            hint = f"; did you mean '{best}'?" if best else f" (known: {', '.join(known)})"
            raise CatalogError(f"{name}: header, column '{column}'", f"unknown column{hint}")
    for column in required:
        if column not in header:
            raise CatalogError(f"{name}: header", f"missing required column '{column}'")


def _chain_from_cells(cells: dict[str, str], where: str, source: str) -> _Named[ChainSpec]:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _CHAIN_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'")
        values[field] = None if value is None else value * factor
    designation = cells["designation"].strip()
    if not designation:
        raise CatalogError(f"{where}, column 'designation'", "is empty")
    strands = _strands(cells.get("strands", ""), f"{where}, column 'strands'")
    return _Named(_chain_spec(designation, strands, values, where,
                              standard=cells.get("standard", "").strip() or "user",
                              series=cells.get("series", "").strip(),
                              ansi=cells.get("ansi", "").strip() or None,
                              material=cells.get("material", "").strip() or "steel",
                              source=cells.get("source", "").strip() or source),
                  _aliases(cells.get("aliases", "")))


def _chain_spec(designation: str, strands: int, values: dict[str, Any], where: str,
                **text: Any) -> ChainSpec:
    """Build a ChainSpec, deriving the bearing area when it is not given (module doc)."""
    if values.get("bearing_area") is None and values["transverse_pitch"] and strands <= 4:
        values["bearing_area"] = bearing_area_estimate(
            values["pin_diameter"], values["inner_width"], values["transverse_pitch"], strands)
    if values["pin_diameter"] >= values["roller_diameter"]:
        raise CatalogError(f"{where}, column 'pin_diameter_mm'",
                           "must be smaller than the roller diameter")
    try:
        return ChainSpec(designation=designation, strands=strands, **values, **text)
    except DesignError as exc:
        raise CatalogError(where, str(exc)) from None


def _material_from_cells(cells: dict[str, str], where: str,
                         source: str) -> _Named[Material]:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _MATERIAL_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'")
        values[field] = None if value is None else value * factor
    for column in ("name", "family"):
        if not cells[column].strip():
            raise CatalogError(f"{where}, column '{column}'", "is empty")
    material = Material(name=cells["name"].strip(), family=cells["family"].strip(), **values,
                        source=cells.get("source", "").strip() or source)
    return _Named(material, _aliases(cells.get("aliases", "")))


def _parse_csv(text: str, name: str) -> _FileContent:
    """Chains or materials of one CSV text (the header tells which)."""
    header, rows = _csv_rows(text, name)
    where = [(f"{name}: row {i} (line {lineno})", cells)
             for i, (lineno, cells) in enumerate(rows, start=1)]
    if "pitch_mm" in header or "designation" in header:
        _check_columns(header, [*_CHAIN_TEXT, *_CHAIN_NUMBERS], _CHAIN_REQUIRED, name)
        chain_rows = tuple(_chain_from_cells(c, w, Path(name).name) for w, c in where)
        _check_unique(chain_rows, name)
        return _FileContent(chain_rows, ())
    _check_columns(header, [*_MATERIAL_TEXT, *_MATERIAL_NUMBERS], _MATERIAL_REQUIRED, name)
    material_rows = tuple(_material_from_cells(c, w, Path(name).name) for w, c in where)
    _check_unique(material_rows, name)
    return _FileContent((), material_rows)


def _toml_value(table: dict[str, Any], key: str, dimension: str, kind: str,
                where: str) -> float | None:
    if key not in table:
        if kind == "pos":
            raise CatalogError(f"{where}.{key}", "is missing")
        return 0.0 if kind == "nonneg" else None
    try:
        value = parse_quantity(table[key], dimension, f"{where}.{key}")
    except CatalogError:
        raise
    except DesignError as exc:
        raise CatalogError(exc.field, str(exc)[len(exc.field) + 2:]) from None
    if not math.isfinite(value) or value < 0 or (value == 0 and kind != "nonneg"):
        raise CatalogError(f"{where}.{key}", f"must be positive, got {table[key]!r}")
    return value


def _toml_text(table: dict[str, Any], key: str, where: str, default: str = "") -> str:
    value = table.get(key, default)
    if not isinstance(value, str):
        raise CatalogError(f"{where}.{key}", f"must be a string, got {value!r}")
    return value.strip()


def _toml_aliases(table: dict[str, Any], where: str) -> tuple[str, ...]:
    value = table.get("aliases", [])
    if not isinstance(value, list) or not all(isinstance(a, str) for a in value):
        raise CatalogError(f"{where}.aliases", f"must be a list of strings, got {value!r}")
    return tuple(value)


def _check_keys(table: object, known: Iterable[str], where: str) -> None:
    if not isinstance(table, dict):
        raise CatalogError(where, "must be a table")
    known = list(known)
    for key in table:
        if key not in known:
            best = closest(key, known)
            raise CatalogError(f"{where}.{key}",
                               "unknown field" + (f"; did you mean '{best}'?" if best else ""))


def _toml_chain(table: dict[str, Any], where: str, source: str) -> _Named[ChainSpec]:
    _check_keys(table, [*_CHAIN_TOML, *_CHAIN_TEXT], where)
    values = {key: _toml_value(table, key, dim, kind, where)
              for key, (dim, kind) in _CHAIN_TOML.items()}
    designation = _toml_text(table, "designation", where)
    if not designation:
        raise CatalogError(f"{where}.designation", "is missing")
    strands = table.get("strands", 1)
    if isinstance(strands, bool) or not isinstance(strands, int) or not 1 <= strands <= 8:
        raise CatalogError(f"{where}.strands",
                           f"must be a whole number from 1 to 8, got {strands!r}")
    spec = _chain_spec(designation, strands, values, where,
                       standard=_toml_text(table, "standard", where) or "user",
                       series=_toml_text(table, "series", where),
                       ansi=_toml_text(table, "ansi", where) or None,
                       material=_toml_text(table, "material", where) or "steel",
                       source=_toml_text(table, "source", where) or source)
    return _Named(spec, _toml_aliases(table, where))


def _toml_material(table: dict[str, Any], where: str, source: str) -> _Named[Material]:
    _check_keys(table, [*_MATERIAL_TOML, "friction_vs_steel", *_MATERIAL_TEXT], where)
    values: dict[str, Any] = {key: _toml_value(table, key, dim, kind, where)
                              for key, (dim, kind) in _MATERIAL_TOML.items()}
    friction = table.get("friction_vs_steel")
    if friction is not None and (isinstance(friction, bool)
                                 or not isinstance(friction, int | float) or friction <= 0):
        raise CatalogError(f"{where}.friction_vs_steel",
                           f"must be a positive number, got {friction!r}")
    name = _toml_text(table, "name", where)
    family = _toml_text(table, "family", where)
    if not name or not family:
        raise CatalogError(f"{where}.{'family' if name else 'name'}", "is missing")
    material = Material(name=name, family=family, friction_vs_steel=friction,
                        source=_toml_text(table, "source", where) or source, **values)
    return _Named(material, _toml_aliases(table, where))


def _parse_toml(text: str, name: str) -> _FileContent:
    """Chains (``[[chains]]``) and materials (``[[materials]]``) of one TOML text."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CatalogError(name, f"TOML syntax error: {exc}") from None
    _check_keys(data, ["chains", "materials"], name)
    chain_rows = tuple(_toml_chain(table, where, Path(name).name)
                       for where, table in _toml_tables(data, "chains", name))
    material_rows = tuple(_toml_material(table, where, Path(name).name)
                          for where, table in _toml_tables(data, "materials", name))
    _check_unique(chain_rows, name)
    _check_unique(material_rows, name)
    return _FileContent(chain_rows, material_rows)


def _toml_tables(data: dict[str, Any], key: str, name: str) -> list[tuple[str, dict[str, Any]]]:
    """(where, table) of each ``[[key]]`` table of a parsed catalogue file."""
    tables = data.get(key, [])
    if not isinstance(tables, list):
        raise CatalogError(f"{name}: {key}", f"must be an array of tables ([[{key}]])")
    out = []
    for i, table in enumerate(tables):
        if not isinstance(table, dict):
            raise CatalogError(f"{name}: {key}[{i}]", "must be a table")
        out.append((f"{name}: {key}[{i}]", table))
    return out


def _check_unique(entries: Sequence[_Named[ChainSpec]] | Sequence[_Named[Material]],
                  name: str) -> None:
    seen: set[str] = set()
    for entry in entries:
        item = entry.item
        label = item.designation if isinstance(item, ChainSpec) else item.name
        if label in seen:
            raise CatalogError(name, f"{label!r} is listed twice")
        seen.add(label)


def _read_user_file(path: PathLike) -> _FileContent:
    path = Path(path)
    if path.suffix.lower() not in {".csv", ".toml"}:
        raise CatalogError(str(path), "a catalogue file must be .csv or .toml")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise CatalogError(str(path), "catalogue file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise CatalogError(str(path), f"cannot read the file ({exc})") from None
    return _cached_parse(text, str(path), path.suffix.lower())


@lru_cache(maxsize=64)
def _cached_parse(text: str, name: str, suffix: str) -> _FileContent:
    return _parse_toml(text, name) if suffix == ".toml" else _parse_csv(text, name)


@lru_cache(maxsize=1)
def _packaged() -> _FileContent:
    """The packaged chain and material files (read once per process)."""
    data = resources.files("chaindrive.catalog").joinpath("data")
    chain_entries: list[_Named[ChainSpec]] = []
    material_entries: list[_Named[Material]] = []
    for file_name in PACKAGED_CHAIN_FILES + PACKAGED_MATERIAL_FILES:
        content = _parse_csv(data.joinpath(file_name).read_text(encoding="utf-8"), file_name)
        chain_entries += content.chains
        material_entries += content.materials
    return _FileContent(tuple(chain_entries), tuple(material_entries))


def load_chain_file(path: PathLike) -> tuple[ChainSpec, ...]:
    """Chains of a user's catalogue file.

    CSV: the columns of ``chains_iso606.csv`` (required: designation, pitch_mm,
    roller_diameter_mm, pin_diameter_mm, inner_width_mm, plate_depth_mm, breaking_load_kN,
    mass_kg_m; optional: standard, series, strands, transverse_pitch_mm, bearing_area_mm2,
    ansi, aliases ('|'-separated), material, source); ``#`` lines are comments.
    TOML: ``[[chains]]`` tables with the same fields without the unit suffix, dimensional
    values as strings with units (``pitch = "25.4 mm"``, ``breaking_load = "60 kN"``,
    ``mass_per_length = "2.6 kg/m"``, ``bearing_area = "180 mm^2"``), ``aliases`` a list.
    A blank bearing area is derived as in :func:`bearing_area_estimate` when p_t is given.
    A malformed file raises a one-line :class:`CatalogError` naming file, row and column.

    Parameters
    ----------
    path : str or pathlib.Path
        The user's catalogue file (``.csv`` or ``.toml``).

    Returns
    -------
    tuple of ChainSpec
        Its chains, in SI units.
    """
    content = _read_user_file(path)
    if not content.chains:
        raise CatalogError(str(path), "no chains in this file (chain CSV columns or [[chains]])")
    return tuple(entry.item for entry in content.chains)


def load_material_file(path: PathLike) -> tuple[Material, ...]:
    """Materials of a user's file.

    Parameters
    ----------
    path : str or pathlib.Path
        CSV with the columns of ``materials.csv`` (density_kg_m3, youngs_modulus_GPa,
        tensile_strength_MPa …) or TOML ``[[materials]]`` (``density = "1140 kg/m^3"``,
        ``youngs_modulus = "2.8 GPa"``, ``friction_vs_steel = 0.3``).

    Returns
    -------
    tuple of Material
        Its materials, in SI units.
    """
    content = _read_user_file(path)
    if not content.materials:
        raise CatalogError(str(path), "no materials in this file")
    return tuple(entry.item for entry in content.materials)


# --------------------------------------------------------------------------- indexes
@dataclass(frozen=True, slots=True)
class _Index(Generic[Entry]):
    items: tuple[Entry, ...]
    by_key: dict[str, Entry]
    display: dict[str, str]


def _file_stamps(extra_files: Sequence[PathLike]) -> tuple[tuple[str, int], ...]:
    """(path, modification time) of each extra file: the cache key of an index."""
    stamps = []
    for p in extra_files:
        try:
            stamps.append((str(p), Path(p).stat().st_mtime_ns))
        except OSError:
            stamps.append((str(p), -1))
    return tuple(stamps)


def _chain_names(entry: _Named[ChainSpec]) -> list[str]:
    spec = entry.item
    names = [spec.designation]
    if spec.ansi:
        names.append(f"ANSI {spec.ansi}")
    return names + list(entry.aliases)


def _material_names(entry: _Named[Material]) -> list[str]:
    return [entry.item.name, *entry.aliases]


def _build_index(entries: Sequence[_Named[Entry]], names: Callable[[_Named[Entry]], list[str]],
                 key: Callable[[str], str], label: Callable[[Entry], str]) -> _Index[Entry]:
    """Index entries by every normalised name; later entries replace earlier ones."""
    by_label: dict[str, _Named[Entry]] = {}
    for entry in entries:
        by_label[label(entry.item)] = entry
    by_key: dict[str, Entry] = {}
    display: dict[str, str] = {}
    for entry in by_label.values():
        for name in names(entry):
            by_key[key(name)] = entry.item
            display.setdefault(key(name), name)
    return _Index(tuple(e.item for e in by_label.values()), by_key, display)


@lru_cache(maxsize=32)
def _chain_index(stamps: tuple[tuple[str, int], ...]) -> _Index[ChainSpec]:
    entries = list(_packaged().chains)
    for path, _ in stamps:
        entries += _read_user_file(path).chains
    return _build_index(entries, _chain_names, designation_key, lambda s: s.designation)


@lru_cache(maxsize=32)
def _material_index(stamps: tuple[tuple[str, int], ...]) -> _Index[Material]:
    entries = list(_packaged().materials)
    for path, _ in stamps:
        entries += _read_user_file(path).materials
    return _build_index(entries, _material_names, material_key, lambda m: m.name)


def _not_found(what: str, index: _Index[ChainSpec] | _Index[Material], key: str, field: str,
               hint: str) -> CatalogError:
    best = closest(key, index.display)
    suggestion = f"; did you mean '{index.display[best]}'?" if best else f"; {hint}"
    return CatalogError(field, f"{what} is not in the catalogue{suggestion}")


# --------------------------------------------------------------------------- public API
def chains(extra_files: Sequence[PathLike] = ()) -> tuple[ChainSpec, ...]:
    """Every catalogue chain.

    Parameters
    ----------
    extra_files : sequence of str or pathlib.Path
        The user's catalogue files; their entries replace packaged ones of the same name.

    Returns
    -------
    tuple of ChainSpec
        The packaged ISO 606, ANSI, GOST 13568 and polymer chains, then the user's.
    """
    return _chain_index(_file_stamps(extra_files)).items


def find_chain(designation: str, extra_files: Sequence[PathLike] = (), *,
               field: str = "chain.designation") -> ChainSpec:
    """The chain named ``designation`` (case/space-insensitive; ',' or '.' as decimal mark).

    Accepted forms: ``"ISO 606 16B-1"``, ``"16B-1"``, ``"16B"`` (simplex), ``"ANSI 80"``,
    ``"ANSI 80-2"``, ``"80-2"`` (ANSI names resolve to the ISO A-series entry, which keeps
    ``ansi``), ``"GOST 13568 ПР-25,4-60"``, ``"ПР-25.4-60"``, ``"2ПР-25,4-114"`` and the old
    GOST 13568-75 names with the load in kgf (``"ПР-25,4-5670"``).

    Parameters
    ----------
    designation : str
        The chain's name.
    extra_files : sequence of str or pathlib.Path
        The user's catalogue files.
    field : str
        The field an error names.

    Returns
    -------
    ChainSpec
        The chain, in SI units.

    Raises
    ------
    CatalogError
        On ``field``, suggesting the nearest name.
    """
    if not isinstance(designation, str) or not designation.strip():
        raise CatalogError(field, f"must be a chain designation such as 'ISO 606 16B-1', "
                                  f"got {designation!r}")
    index = _chain_index(_file_stamps(extra_files))
    key = designation_key(designation)
    if key in index.by_key:
        return index.by_key[key]
    raise _not_found(repr(designation), index, key, field,
                     "run `chaindrive catalog` to list the chains")


_STANDARD_ALIASES = {"ISO": "ISO 606", "ISO606": "ISO 606", "GOST": "GOST 13568",
                     "GOST13568": "GOST 13568", "ГОСТ": "GOST 13568", "ГОСТ13568": "GOST 13568",
                     "ANSI": "ANSI", "ASMEB29.1": "ANSI", "ANSI/ASMEB29.1": "ANSI"}


def chains_by_pitch(pitch: float, standard: str | None = None,
                    extra_files: Sequence[PathLike] = ()) -> tuple[ChainSpec, ...]:
    """Catalogue chains of one pitch, optionally of one standard.

    Parameters
    ----------
    pitch : float
        Chain pitch p [m] (matched to ±1 µm).
    standard : str or None
        ``"ISO 606"`` (or ``"ISO"``), ``"ANSI"`` (chains with an ANSI number),
        ``"GOST 13568"`` (or ``"GOST"``), or the ``standard`` of a user's entries.
    extra_files : sequence of str or pathlib.Path
        The user's catalogue files.

    Returns
    -------
    tuple of ChainSpec
        Sorted by standard, strands and designation; empty when none has that pitch.
    """
    every = chains(extra_files)
    selected = [s for s in every if abs(s.pitch - pitch) <= 1e-6]
    if standard is not None:
        key = re.sub(r"\s+", "", standard.upper())
        wanted = _STANDARD_ALIASES.get(key, standard.strip())
        known = {s.standard for s in every} | {"ANSI"}
        if wanted not in known:
            best = closest(standard, known)
            raise CatalogError("chain.standard", f"unknown standard {standard!r}"
                               + (f"; did you mean '{best}'?" if best else ""))
        selected = [s for s in selected
                    if (s.ansi is not None if wanted == "ANSI" else s.standard == wanted)]
    return tuple(sorted(selected, key=lambda s: (s.standard, s.strands, s.designation)))


def materials(extra_files: Sequence[PathLike] = ()) -> tuple[Material, ...]:
    """Every catalogue material.

    Parameters
    ----------
    extra_files : sequence of str or pathlib.Path
        The user's material files.

    Returns
    -------
    tuple of Material
        The packaged ``materials.csv``, then the user's.
    """
    return _material_index(_file_stamps(extra_files)).items


def find_material(name: str, extra_files: Sequence[PathLike] = (), *,
                  field: str = "material") -> Material:
    """The material called ``name`` or one of its aliases (case/space/hyphen-insensitive).

    Generic names resolve too: ``"steel"``, ``"cast iron"`` (grey cast iron), ``"polymer"``
    (PA66).

    Parameters
    ----------
    name : str
        The material's name or alias.
    extra_files : sequence of str or pathlib.Path
        The user's material files.
    field : str
        The field an error names.

    Returns
    -------
    Material
        The material, in SI units.

    Raises
    ------
    CatalogError
        On ``field``, suggesting the nearest name.
    """
    if not isinstance(name, str) or not name.strip():
        raise CatalogError(field, f"must be a material name such as 'steel 45', got {name!r}")
    index = _material_index(_file_stamps(extra_files))
    key = material_key(name)
    if key in index.by_key:
        return index.by_key[key]
    raise _not_found(f"material {name!r}", index, key, field,
                     "run `chaindrive catalog` to list the materials")
