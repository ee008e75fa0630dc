"""Catalogue files: the packaged CSV files and a user's CSV or TOML files, parsed and checked.

Every malformed file raises a one-line :class:`~chaindrive.errors.CatalogError` naming the
file, the row and the column (or the TOML key).
"""

from __future__ import annotations

import csv
import math
import tomllib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any, Generic, TypeVar

from chaindrive.catalog.bearing import bearing_area_estimate
from chaindrive.errors import CatalogError, DesignError, closest
from chaindrive.io.limits import MAX_CATALOG_BYTES, check_catalog_value, check_file_size
from chaindrive.model import ChainSpec, Material
from chaindrive.units import parse_quantity

__all__ = ["PACKAGED_CHAIN_FILES", "PACKAGED_MATERIAL_FILES", "PathLike", "load_chain_file",
           "load_material_file"]

PACKAGED_CHAIN_FILES: tuple[str, ...] = ("chains_iso606.csv", "chains_ansi_b29.csv",
                                         "chains_gost13568.csv", "chains_polymer.csv")
PACKAGED_MATERIAL_FILES: tuple[str, ...] = ("materials.csv",)

PathLike = str | Path

Entry = TypeVar("Entry", ChainSpec, Material)


@dataclass(frozen=True, slots=True)
class Named(Generic[Entry]):
    """An entry with the extra names it may be looked up by."""

    item: Entry
    aliases: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class FileContent:
    chains: tuple[Named[ChainSpec], ...]
    materials: tuple[Named[Material], ...]


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
    "fatigue_strength_kN": ("fatigue_strength", 1e3, "opt"),
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
    "fatigue_strength": ("force", "opt"),
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


def _chain_from_cells(cells: dict[str, str], where: str, source: str) -> Named[ChainSpec]:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _CHAIN_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'", column)
        values[field] = None if value is None else value * factor
    designation = cells["designation"].strip()
    if not designation:
        raise CatalogError(f"{where}, column 'designation'", "is empty")
    strands = _strands(cells.get("strands", ""), f"{where}, column 'strands'")
    return Named(_chain_spec(designation, strands, values, where,
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
    _check_proportions(values, where)
    try:
        return ChainSpec(designation=designation, strands=strands, **values, **text)
    except DesignError as exc:
        raise CatalogError(where, str(exc)) from None


def _check_proportions(values: dict[str, Any], where: str) -> None:
    """Refuse a chain whose dimensions cannot belong to one chain, with one line naming the
    row and the column (the packaged catalogue's ratios are quoted; [ISO606]).

    * the roller is narrower than the pitch: neighbouring rollers of a wider one overlap
      (a roller of 1.07 pitches gave negative tip and root diameters); [ISO606] rollers are
      0.53 to 0.67 pitches;
    * the plate is deeper than the roller: the plate holds the bush the roller turns on
      (1.28 to 1.77 roller diameters);
    * the transverse pitch of the strands, where given, exceeds the inner width: the plates
      of one strand lie between the inner width of the next.
    """
    pitch, roller = values["pitch"], values["roller_diameter"]
    depth, inner = values["plate_depth"], values["inner_width"]
    transverse = values.get("transverse_pitch") or 0.0

    def mm(x: float) -> str:
        return f"{x * 1e3:g} mm"

    if roller >= pitch:
        raise CatalogError(f"{where}, column 'roller_diameter_mm'",
                           f"{mm(roller)} must be smaller than the pitch {mm(pitch)} "
                           "(neighbouring rollers would overlap; ISO 606 rollers are 0.53 to "
                           "0.67 pitches)")
    if depth <= roller:
        raise CatalogError(f"{where}, column 'plate_depth_mm'",
                           f"{mm(depth)} must be larger than the roller diameter {mm(roller)} "
                           "(the plate holds the bush the roller turns on; catalogue plates "
                           "are 1.3 to 1.8 roller diameters deep)")
    if 0.0 < transverse <= inner:
        raise CatalogError(f"{where}, column 'transverse_pitch_mm'",
                           f"{mm(transverse)} must be larger than the inner width {mm(inner)} "
                           "(two plates lie between the inner widths of neighbouring strands)")


def _material_from_cells(cells: dict[str, str], where: str,
                         source: str) -> Named[Material]:
    values: dict[str, Any] = {}
    for column, (field, factor, kind) in _MATERIAL_NUMBERS.items():
        value = _number(cells.get(column, ""), kind, f"{where}, column '{column}'", column)
        values[field] = None if value is None else value * factor
    for column in ("name", "family"):
        if not cells[column].strip():
            raise CatalogError(f"{where}, column '{column}'", "is empty")
    material = Material(name=cells["name"].strip(), family=cells["family"].strip(), **values,
                        source=cells.get("source", "").strip() or source)
    return Named(material, _aliases(cells.get("aliases", "")))


def _parse_csv(text: str, name: str) -> FileContent:
    """Chains or materials of one CSV text (the header tells which)."""
    header, rows = _csv_rows(text, name)
    where = [(f"{name}: row {i} (line {lineno})", cells)
             for i, (lineno, cells) in enumerate(rows, start=1)]
    if "pitch_mm" in header or "designation" in header:
        _check_columns(header, [*_CHAIN_TEXT, *_CHAIN_NUMBERS], _CHAIN_REQUIRED, name)
        chain_rows = tuple(_chain_from_cells(c, w, Path(name).name) for w, c in where)
        _check_unique(chain_rows, name)
        return FileContent(chain_rows, ())
    _check_columns(header, [*_MATERIAL_TEXT, *_MATERIAL_NUMBERS], _MATERIAL_REQUIRED, name)
    material_rows = tuple(_material_from_cells(c, w, Path(name).name) for w, c in where)
    _check_unique(material_rows, name)
    return FileContent((), material_rows)


#: TOML key of a catalogue → (CSV column, factor from the column's unit to SI).
_COLUMN_OF_KEY: dict[str, tuple[str, float]] = {
    field: (column, factor)
    for column, (field, factor, _) in (*_CHAIN_NUMBERS.items(), *_MATERIAL_NUMBERS.items())}


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


def _check_keys(table: object, known: Iterable[str], where: str) -> None:
    if not isinstance(table, dict):
        raise CatalogError(where, "must be a table")
    known = list(known)
    for key in table:
        if key not in known:
            best = closest(key, known)
            raise CatalogError(f"{where}.{key}",
                               "unknown field" + (f"; did you mean '{best}'?" if best else ""))


def _toml_chain(table: dict[str, Any], where: str, source: str) -> Named[ChainSpec]:
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
    return Named(spec, _toml_aliases(table, where))


def _toml_material(table: dict[str, Any], where: str, source: str) -> Named[Material]:
    _check_keys(table, [*_MATERIAL_TOML, "friction_vs_steel", *_MATERIAL_TEXT], where)
    values: dict[str, Any] = {key: _toml_value(table, key, dim, kind, where)
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
    return Named(material, _toml_aliases(table, where))


def _parse_toml(text: str, name: str) -> FileContent:
    """Chains (``[[chains]]``) and materials (``[[materials]]``) of one TOML text."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CatalogError(name, f"TOML syntax error: {exc}") from None
    except RecursionError:
        raise CatalogError(name, "arrays or tables are nested too deeply to read") from None
    _check_keys(data, ["chains", "materials"], name)
    chain_rows = tuple(_toml_chain(table, where, Path(name).name)
                       for where, table in _toml_tables(data, "chains", name))
    material_rows = tuple(_toml_material(table, where, Path(name).name)
                          for where, table in _toml_tables(data, "materials", name))
    _check_unique(chain_rows, name)
    _check_unique(material_rows, name)
    return FileContent(chain_rows, material_rows)


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


def _check_unique(entries: Sequence[Named[ChainSpec]] | Sequence[Named[Material]],
                  name: str) -> None:
    seen: set[str] = set()
    for entry in entries:
        item = entry.item
        label = item.designation if isinstance(item, ChainSpec) else item.name
        if label in seen:
            raise CatalogError(name, f"{label!r} is listed twice")
        seen.add(label)


def read_catalog_file(path: PathLike) -> FileContent:
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
def _cached_parse(text: str, name: str, suffix: str) -> FileContent:
    return _parse_toml(text, name) if suffix == ".toml" else _parse_csv(text, name)


@lru_cache(maxsize=1)
def packaged_content() -> FileContent:
    """The packaged chain and material files (read once per process)."""
    data = resources.files("chaindrive.catalog").joinpath("data")
    chain_entries: list[Named[ChainSpec]] = []
    material_entries: list[Named[Material]] = []
    for file_name in PACKAGED_CHAIN_FILES + PACKAGED_MATERIAL_FILES:
        content = _parse_csv(data.joinpath(file_name).read_text(encoding="utf-8"), file_name)
        chain_entries += content.chains
        material_entries += content.materials
    return FileContent(tuple(chain_entries), tuple(material_entries))


def _entries(path: PathLike, kind: str, pick: Callable[[FileContent], tuple[Named[Entry], ...]],
             hint: str = "") -> tuple[Entry, ...]:
    """The entries of one kind (``pick``: chains or materials) of a user's catalogue file, in
    SI units; a file with none is refused (``hint``: where they would be)."""
    entries = pick(read_catalog_file(path))
    if not entries:
        raise CatalogError(str(path), f"no {kind} in this file{hint}")
    return tuple(entry.item for entry in entries)


def load_chain_file(path: PathLike) -> tuple[ChainSpec, ...]:
    """Chains of a user's catalogue file.

    CSV: the columns of ``chains_iso606.csv`` (required: designation, pitch_mm,
    roller_diameter_mm, pin_diameter_mm, inner_width_mm, plate_depth_mm, breaking_load_kN,
    mass_kg_m; optional: standard, series, strands, transverse_pitch_mm, bearing_area_mm2,
    fatigue_strength_kN, ansi, aliases ('|'-separated), material, source); ``#`` lines are
    comments.
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
    return _entries(path, "chains", lambda c: c.chains, " (chain CSV columns or [[chains]])")


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
    return _entries(path, "materials", lambda c: c.materials)
