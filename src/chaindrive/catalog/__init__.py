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
packaged entries of the same name. Modules: :mod:`.files` (reading and checking the files),
:mod:`.bearing` (the bearing-area estimate); this module indexes and looks up.

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

import re
import unicodedata
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Generic

from chaindrive.catalog.bearing import (
    BUSH_TO_INNER_WIDTH,
    ROW_FACTORS,
    bearing_area_estimate,
    bush_length_estimate,
    row_factor,
)
from chaindrive.catalog.files import (
    PACKAGED_CHAIN_FILES,
    PACKAGED_MATERIAL_FILES,
    Entry,
    Named,
    PathLike,
    load_chain_file,
    load_material_file,
    packaged_content,
    read_catalog_file,
)
from chaindrive.errors import CatalogError, closest
from chaindrive.model import ChainSpec, Material

__all__ = [
    "BUSH_TO_INNER_WIDTH",
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


def _chain_names(entry: Named[ChainSpec]) -> list[str]:
    spec = entry.item
    names = [spec.designation]
    if spec.ansi:
        names.append(f"ANSI {spec.ansi}")
    return names + list(entry.aliases)


def _material_names(entry: Named[Material]) -> list[str]:
    return [entry.item.name, *entry.aliases]


def _build_index(entries: Sequence[Named[Entry]], names: Callable[[Named[Entry]], list[str]],
                 key: Callable[[str], str], label: Callable[[Entry], str]) -> _Index[Entry]:
    """Index entries by every normalised name; later entries replace earlier ones."""
    by_label: dict[str, Named[Entry]] = {}
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
    entries = list(packaged_content().chains)
    for path, _ in stamps:
        entries += read_catalog_file(path).chains
    return _build_index(entries, _chain_names, designation_key, lambda s: s.designation)


@lru_cache(maxsize=32)
def _material_index(stamps: tuple[tuple[str, int], ...]) -> _Index[Material]:
    entries = list(packaged_content().materials)
    for path, _ in stamps:
        entries += read_catalog_file(path).materials
    return _build_index(entries, _material_names, material_key, lambda m: m.name)


def _entry(index: _Index[Entry], key: Callable[[str], str], name: object, example: str,
           what: str, field: str, hint: str) -> Entry:
    """The entry called ``name``, or a CatalogError on ``field``: ``name`` is not a non-empty
    string (``example`` says what is), or it is not in the catalogue (naming ``what`` and the
    nearest name, ``hint`` when none is near)."""
    if not isinstance(name, str) or not name.strip():
        raise CatalogError(field, f"must be {example}, got {name!r}")
    k = key(name)
    if k in index.by_key:
        return index.by_key[k]
    best = closest(k, index.display)
    suggestion = f"; did you mean '{index.display[best]}'?" if best else f"; {hint}"
    raise CatalogError(field, f"{what} is not in the catalogue{suggestion}")


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
    return _entry(_chain_index(_file_stamps(extra_files)), designation_key, designation,
                  "a chain designation such as 'ISO 606 16B-1'", repr(designation), field,
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
    return _entry(_material_index(_file_stamps(extra_files)), material_key, name,
                  "a material name such as 'steel 45'", f"material {name!r}", field,
                  "run `chaindrive catalog` to list the materials")
