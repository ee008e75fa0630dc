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
m_r = 1, 1.7, 2.5, 3.0 for 1–4 rows (Trịnh Chất & Lê Văn Uyển table 5.12; the same factors
in [VN-CODE] of ``shared/data/chain_design_method_ru.md``). GOST chains carry the tabulated
value; for ISO chains no source gives A, and it is DERIVED by
:func:`bearing_area_estimate`: A₁ = d₂·B with the bush length B ≈ (b₁ + p_t)/2.
"""

from __future__ import annotations

import csv
import math
import re
import tomllib
import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from chaindrive.errors import CatalogError, DesignError, closest
from chaindrive.io.limits import MAX_CATALOG_BYTES, check_catalog_value, check_file_size
from chaindrive.model import ChainSpec, Material

__all__ = [
    "PACKAGED_CHAIN_FILES",
    "PACKAGED_MATERIAL_FILES",
    "STRAND_FACTORS",
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
    "strand_factor",
]

PACKAGED_CHAIN_FILES: tuple[str, ...] = ("chains_iso606.csv", "chains_ansi_b29.csv",
                                         "chains_gost13568.csv", "chains_polymer.csv")
PACKAGED_MATERIAL_FILES: tuple[str, ...] = ("materials.csv",)

#: Row factor m_r of multi-row chains (effective bearing area / single-row area), 1–4 rows.
#: Source: Trịnh Chất & Lê Văn Uyển table 5.12 (ratios of its columns); [VN-CODE]
#: ``K_x_arr = [1, 1.7, 2.5, 3.0]`` in ``shared/data/chain_design_method_ru.md`` §1.
STRAND_FACTORS: dict[int, float] = {1: 1.0, 2: 1.7, 3: 2.5, 4: 3.0}

PathLike = str | Path


# --------------------------------------------------------------------------- formulas
def strand_factor(strands: int) -> float:
    """Row factor m_r for ``strands`` rows (1 → 1, 2 → 1.7, 3 → 2.5, 4 → 3.0).

    Source: see :data:`STRAND_FACTORS`. Raises :class:`CatalogError` beyond 4 rows
    (no source gives a factor).
    """
    try:
        return STRAND_FACTORS[strands]
    except KeyError:
        raise CatalogError(
            "chain.strands", f"no row factor for {strands!r} strands (known for 1 to 4)"
        ) from None


def bush_length_estimate(inner_width: Any, transverse_pitch: Any) -> Any:
    """Bush length B ≈ (b₁ + p_t)/2 [m] — an approximation derived for chaindrive.

    The transverse pitch spans the inner width, two inner and two outer plates,
    p_t ≈ b₁ + 2s_i + 2s_o; with s_i ≈ s_o the bush (inner-link) length is
    B = b₁ + 2s_i ≈ (b₁ + p_t)/2. Checked against the bush lengths of Trịnh Chất & Lê Văn
    Uyển table 5.5 (e.g. 16A/ПР-25,4: (15.88 + 29.29)/2 = 22.59 vs 22.61 mm).

    inner_width : float | ndarray — b₁ [m]; transverse_pitch : float | ndarray — p_t [m].
    """
    return 0.5 * (inner_width + transverse_pitch)


def bearing_area_estimate(pin_diameter: Any, inner_width: Any, transverse_pitch: Any,
                          strands: int = 1) -> Any:
    """Projected bearing area of the whole chain A = m_r·d₂·B [m²] (DERIVED, see module doc).

    pin_diameter : d₂ [m]; inner_width : b₁ [m]; transverse_pitch : p_t [m];
    strands : rows n (m_r from :func:`strand_factor`). B from :func:`bush_length_estimate`.
    Reproduces the GOST 13568 / table 5.12 areas within 4.5 % for every multi-row GOST chain
    (tested in ``tests/unit/test_catalog.py``).
    """
    return strand_factor(strands) * pin_diameter * bush_length_estimate(inner_width,
                                                                         transverse_pitch)


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
    """Normalised look-up key of a material name (case, spaces, '-', '.', '/' ignored;
    Cyrillic 'Х' in steel grades read as Latin 'X')."""
    s = unicodedata.normalize("NFKC", name).lower().replace("х", "x")
    return re.sub(r"[\s\-_./]", "", s)


# --------------------------------------------------------------------------- file parsing
@dataclass(frozen=True, slots=True)
class _Named:
    """An entry with the extra names it may be looked up by."""

    item: Any
    aliases: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class _FileContent:
    chains: tuple[_Named, ...]
    materials: tuple[_Named, ...]


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


def _number(text: str, kind: str, where: str, column: str = "") -> float | None:
    """Parse one numeric cell; ``kind`` pos (> 0), nonneg (≥ 0, blank = 0) or opt (blank = None);
    a value outside the plausible range of ``column`` (:mod:`chaindrive.io.limits`) is refused."""
    text = text.strip()
    if not text:
        if kind == "pos":
            raise CatalogError(where, "is empty; a positive number is required")
        return 0.0 if kind == "nonneg" else None
    try:
        value = float(text)
    except ValueError:
        raise CatalogError(where, f"must be a number, got {text[:40]!r}") from None
    if not math.isfinite(value) or value < 0 or (value == 0 and kind != "nonneg"):
        allowed = "zero or positive" if kind == "nonneg" else "positive"
        raise CatalogError(where, f"must be a {allowed} number, got {text[:40]!r}")
    return check_catalog_value(column, value, where) if value or kind != "nonneg" else value


def _strands(text: str, where: str) -> int:
    text = text.strip() or "1"
    if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= 8:
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
    try:
        parsed = list(csv.reader(line for _, line in lines))
    except csv.Error as exc:  # an unterminated quote, a cell over the csv module's limit
        raise CatalogError(name, f"cannot read the CSV ({exc})") from None
    if len(parsed) != len(lines):
        raise CatalogError(name, "a quoted cell runs over the end of its line")
    header = [h.strip() for h in parsed[0]]
    rows = []
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


def _chain_from_cells(cells: dict[str, str], where: str, source: str) -> _Named:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _CHAIN_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'", column)
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


def _material_from_cells(cells: dict[str, str], where: str, source: str) -> _Named:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _MATERIAL_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'", column)
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
    is_chain = "pitch_mm" in header or "designation" in header
    if is_chain:
        _check_columns(header, [*_CHAIN_TEXT, *_CHAIN_NUMBERS], _CHAIN_REQUIRED, name)
    else:
        _check_columns(header, [*_MATERIAL_TEXT, *_MATERIAL_NUMBERS], _MATERIAL_REQUIRED, name)
    build = _chain_from_cells if is_chain else _material_from_cells
    entries = tuple(build(cells, f"{name}: row {i} (line {lineno})", Path(name).name)
                    for i, (lineno, cells) in enumerate(rows, start=1))
    _check_unique(entries, name)
    return _FileContent(entries, ()) if is_chain else _FileContent((), entries)


#: TOML key of a catalogue → (CSV column, factor from the column's unit to SI).
_COLUMN_OF_KEY: dict[str, tuple[str, float]] = {
    field: (column, factor)
    for column, (field, factor, _) in (*_CHAIN_NUMBERS.items(), *_MATERIAL_NUMBERS.items())}


def _toml_value(table: dict[str, Any], key: str, dimension: str, kind: str,
                where: str) -> float | None:
    from chaindrive.units import parse_quantity

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
    column, factor = _COLUMN_OF_KEY[key]
    return check_catalog_value(column, value / factor, f"{where}.{key}") * factor if value \
        else value


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


def _check_keys(table: Any, known: Iterable[str], where: str) -> None:
    if not isinstance(table, dict):
        raise CatalogError(where, "must be a table")
    known = list(known)
    for key in table:
        if key not in known:
            best = closest(key, known)
            raise CatalogError(f"{where}.{key}",
                               "unknown field" + (f"; did you mean '{best}'?" if best else ""))


def _toml_chain(table: dict[str, Any], where: str, source: str) -> _Named:
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


def _toml_material(table: dict[str, Any], where: str, source: str) -> _Named:
    _check_keys(table, [*_MATERIAL_TOML, "friction_vs_steel", *_MATERIAL_TEXT], where)
    values = {key: _toml_value(table, key, dim, kind, where)
              for key, (dim, kind) in _MATERIAL_TOML.items()}
    friction = table.get("friction_vs_steel")
    if friction is not None and (isinstance(friction, bool)
                                 or not isinstance(friction, int | float) or friction <= 0):
        raise CatalogError(f"{where}.friction_vs_steel",
                           f"must be a positive number, got {friction!r}")
    if friction is not None:
        check_catalog_value("friction_vs_steel", float(friction), f"{where}.friction_vs_steel")
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
    except RecursionError:
        raise CatalogError(name, "arrays or tables are nested too deeply to read") from None
    _check_keys(data, ["chains", "materials"], name)
    found: dict[str, tuple[_Named, ...]] = {}
    for key, build in (("chains", _toml_chain), ("materials", _toml_material)):
        tables = data.get(key, [])
        if not isinstance(tables, list):
            raise CatalogError(f"{name}: {key}", f"must be an array of tables ([[{key}]])")
        entries = []
        for i, table in enumerate(tables):
            if not isinstance(table, dict):
                raise CatalogError(f"{name}: {key}[{i}]", "must be a table")
            entries.append(build(table, f"{name}: {key}[{i}]", Path(name).name))
        _check_unique(entries, name)
        found[key] = tuple(entries)
    return _FileContent(found["chains"], found["materials"])


def _check_unique(entries: Sequence[_Named], name: str) -> None:
    seen: set[str] = set()
    for entry in entries:
        label = getattr(entry.item, "designation", None) or entry.item.name
        if label in seen:
            raise CatalogError(name, f"{label!r} is listed twice")
        seen.add(label)


def _read_user_file(path: PathLike) -> _FileContent:
    path = Path(path)
    if path.suffix.lower() not in {".csv", ".toml"}:
        raise CatalogError(str(path), "a catalogue file must be .csv or .toml")
    try:
        check_file_size(path.stat().st_size, MAX_CATALOG_BYTES, str(path), "catalogue file")
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise CatalogError(str(path), "catalogue file not found") from None
    except DesignError as exc:
        raise CatalogError(exc.field, str(exc)[len(exc.field) + 2:]) from None
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else type(exc).__name__
        raise CatalogError(str(path), f"cannot read the file ({reason})") from None
    return _cached_parse(text, str(path), path.suffix.lower())


@lru_cache(maxsize=64)
def _cached_parse(text: str, name: str, suffix: str) -> _FileContent:
    return _parse_toml(text, name) if suffix == ".toml" else _parse_csv(text, name)


@lru_cache(maxsize=1)
def _packaged() -> _FileContent:
    """The packaged chain and material files (read once per process)."""
    data = resources.files("chaindrive.catalog").joinpath("data")
    chain_entries: list[_Named] = []
    material_entries: list[_Named] = []
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
    """
    content = _read_user_file(path)
    if not content.chains:
        raise CatalogError(str(path), "no chains in this file (chain CSV columns or [[chains]])")
    return tuple(entry.item for entry in content.chains)


def load_material_file(path: PathLike) -> tuple[Material, ...]:
    """Materials of a user's file: CSV with the columns of ``materials.csv``
    (density_kg_m3, youngs_modulus_GPa, tensile_strength_MPa …) or TOML ``[[materials]]``
    (``density = "1140 kg/m^3"``, ``youngs_modulus = "2.8 GPa"``, ``friction_vs_steel = 0.3``)."""
    content = _read_user_file(path)
    if not content.materials:
        raise CatalogError(str(path), "no materials in this file")
    return tuple(entry.item for entry in content.materials)


# --------------------------------------------------------------------------- indexes
@dataclass(frozen=True, slots=True)
class _Index:
    items: tuple[Any, ...]
    by_key: dict[str, Any]
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


def _chain_names(entry: _Named) -> list[str]:
    spec: ChainSpec = entry.item
    names = [spec.designation]
    if spec.ansi:
        names.append(f"ANSI {spec.ansi}")
    return names + list(entry.aliases)


def _material_names(entry: _Named) -> list[str]:
    return [entry.item.name, *entry.aliases]


def _build_index(entries: Sequence[_Named], names: Any, key: Any, label: Any) -> _Index:
    """Index entries by every normalised name; later entries replace earlier ones."""
    by_label: dict[str, _Named] = {}
    for entry in entries:
        by_label[label(entry.item)] = entry
    by_key: dict[str, Any] = {}
    display: dict[str, str] = {}
    for entry in by_label.values():
        for name in names(entry):
            by_key[key(name)] = entry.item
            display.setdefault(key(name), name)
    return _Index(tuple(e.item for e in by_label.values()), by_key, display)


@lru_cache(maxsize=32)
def _chain_index(stamps: tuple[tuple[str, int], ...]) -> _Index:
    entries = list(_packaged().chains)
    for path, _ in stamps:
        entries += _read_user_file(path).chains
    return _build_index(entries, _chain_names, designation_key, lambda s: s.designation)


@lru_cache(maxsize=32)
def _material_index(stamps: tuple[tuple[str, int], ...]) -> _Index:
    entries = list(_packaged().materials)
    for path, _ in stamps:
        entries += _read_user_file(path).materials
    return _build_index(entries, _material_names, material_key, lambda m: m.name)


def _not_found(what: str, index: _Index, key: str, field: str, hint: str) -> CatalogError:
    best = closest(key, index.display)
    suggestion = f"; did you mean '{index.display[best]}'?" if best else f"; {hint}"
    return CatalogError(field, f"{what} is not in the catalogue{suggestion}")


# --------------------------------------------------------------------------- public API
def chains(extra_files: Sequence[PathLike] = ()) -> tuple[ChainSpec, ...]:
    """Every catalogue chain: packaged ISO 606 and GOST 13568 files, then ``extra_files``."""
    return _chain_index(_file_stamps(extra_files)).items


def find_chain(designation: str, extra_files: Sequence[PathLike] = (), *,
               field: str = "chain.designation") -> ChainSpec:
    """The chain named ``designation`` (case/space-insensitive; ',' or '.' as decimal mark).

    Accepted forms: ``"ISO 606 16B-1"``, ``"16B-1"``, ``"16B"`` (simplex), ``"ANSI 80"``,
    ``"ANSI 80-2"``, ``"80-2"`` (ANSI names resolve to the ISO A-series entry, which keeps
    ``ansi``), ``"GOST 13568 ПР-25,4-60"``, ``"ПР-25.4-60"``, ``"2ПР-25,4-114"`` and the old
    GOST 13568-75 names with the load in kgf (``"ПР-25,4-5670"``). Raises
    :class:`CatalogError` (field ``chain.designation``) suggesting the nearest name.
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
    """Catalogue chains of pitch ``pitch`` [m] (±1 µm), optionally of one standard.

    standard : ``"ISO 606"`` (or ``"ISO"``), ``"ANSI"`` (chains with an ANSI number),
    ``"GOST 13568"`` (or ``"GOST"``), or the ``standard`` of a user's entries.
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
    """Every catalogue material: the packaged ``materials.csv``, then ``extra_files``."""
    return _material_index(_file_stamps(extra_files)).items


def find_material(name: str, extra_files: Sequence[PathLike] = (), *,
                  field: str = "material") -> Material:
    """The material called ``name`` or one of its aliases (case/space/hyphen-insensitive).

    Generic names resolve too: ``"steel"``, ``"cast iron"`` (grey cast iron), ``"polymer"``
    (PA66). Raises :class:`CatalogError` suggesting the nearest name.
    """
    if not isinstance(name, str) or not name.strip():
        raise CatalogError(field, f"must be a material name such as 'steel 45', got {name!r}")
    index = _material_index(_file_stamps(extra_files))
    key = material_key(name)
    if key in index.by_key:
        return index.by_key[key]
    raise _not_found(f"material {name!r}", index, key, field,
                     "run `chaindrive catalog` to list the materials")
