"""Plausibility limits of what chaindrive reads: file sizes, and the physical ranges of the
numbers of a design and of a catalogue row.

A value outside its range is refused with one :class:`~chaindrive.errors.DesignError`
line (the command line exits 2) before any computation: a number no drive can have never
reaches a formula where it would overflow, allocate gigabytes or give a NaN. The ranges are
wide — they bound what is physically possible, not what is good design (the checks judge
that) — and each states its reason; ``chaindrive schema`` prints them. The ranges of the
design fields are on the fields themselves (:mod:`chaindrive.io.design`); this module holds
the file limits, the catalogue columns and the checks that need more than one field.

References
----------
[ISO606], [GOST13568], [ANSI-B29.1]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from chaindrive.errors import CatalogError, DesignError

__all__ = ["CATALOG_LIMITS", "MAX_CATALOG_BYTES", "MAX_DESIGN_BYTES", "MIN_INERTIA_SHARE",
           "Range", "check_catalog_value", "check_file_size", "shown_key"]

#: Largest design file read [bytes]: the largest example is under 4 kB; a design of 24
#: sprockets with every field set and an [optimize] table stays under 20 kB.
MAX_DESIGN_BYTES = 1_000_000
#: Largest catalogue file read [bytes] (the packaged ISO 606 file is about 20 kB).
MAX_CATALOG_BYTES = 5_000_000
#: A sprocket's given inertia must be at least this share of the inertia of its own plate
#: (estimated as the dynamics does when none is given).
MIN_INERTIA_SHARE = 0.1


@dataclass(frozen=True, slots=True)
class Range:
    """An allowed range [low, high], and why.

    Parameters
    ----------
    low, high : float
        The bounds [the unit of the value they bound].
    reason : str
        Where the bounds come from (shown by ``chaindrive schema``).
    """

    low: float
    high: float
    reason: str

    def contains(self, value: float) -> bool:
        """True for a finite value within [low, high].

        Parameters
        ----------
        value : float
            The value [the unit of the bounds].
        """
        return math.isfinite(value) and self.low <= value <= self.high


#: Catalogue columns (CSV name; the TOML keys map to them) → allowed range in the file's
#: units (mm, kN, kg/m, mm², m/s). The packaged catalogue ([ISO606], [GOST13568],
#: [ANSI-B29.1] and polymer chains) spans the ranges quoted; the bounds leave a factor of
#: about 5 beyond them and refuse what no chain can be.
CATALOG_LIMITS: dict[str, Range] = {
    "pitch_mm": Range(5.0, 500.0, "catalogue pitches: 8 to 114.3 mm; at least the 5 mm "
                      "of a design file's chain.pitch"),
    "roller_diameter_mm": Range(0.5, 500.0, "catalogue rollers: 5 to 72.4 mm"),
    "pin_diameter_mm": Range(0.2, 250.0, "below the roller diameter"),
    "inner_width_mm": Range(0.5, 500.0, "catalogue inner widths: 2.4 to 68.6 mm"),
    "plate_depth_mm": Range(0.5, 500.0, "catalogue plate depths: 7.1 to 104 mm"),
    "transverse_pitch_mm": Range(0.0, 1000.0, "catalogue transverse pitches: up to 136 mm"),
    "breaking_load_kN": Range(0.01, 20_000.0,
                              "catalogue breaking loads: 0.73 kN (polymer) to 2 002 kN"),
    "mass_kg_m": Range(0.001, 1000.0, "catalogue masses: 0.057 to 122 kg/m"),
    "bearing_area_mm2": Range(0.1, 1_000_000.0, "projected hinge areas d₂·B of real chains"),
    "allowable_load_kN": Range(0.001, 20_000.0, "at most the breaking-load range"),
    "max_speed_m_s": Range(0.001, 100.0, "roller chains run at up to about 30 m/s"),
    "fatigue_strength_kN": Range(0.001, 20_000.0, "below the breaking-load range"),
    "density_kg_m3": Range(100.0, 25_000.0, "from foamed polymers to tungsten"),
    "youngs_modulus_GPa": Range(0.01, 1000.0, "from soft polymers to carbides"),
    "tensile_strength_MPa": Range(1.0, 10_000.0, "from soft polymers to high-strength steel"),
    "friction_vs_steel": Range(0.01, 2.0, "dry friction coefficients of engineering pairs"),
}


def check_catalog_value(column: str, value: float, where: str) -> float:
    """``value`` of a catalogue ``column`` (in the file's units) when it lies in
    :data:`CATALOG_LIMITS`; otherwise a :class:`CatalogError` naming ``where``.

    Parameters
    ----------
    column : str
        The CSV column name (``pitch_mm`` …).
    value : float
        The number as read [the column's unit].
    where : str
        File, row and column, for the message.

    Returns
    -------
    float
        ``value`` unchanged.
    """
    limit = CATALOG_LIMITS.get(column)
    if limit is not None and not limit.contains(value):
        raise CatalogError(where, f"{value:g} is outside the plausible range {limit.low:g} to "
                           f"{limit.high:g} ({limit.reason})")
    return value


def check_file_size(size: int, limit: int, name: str, what: str) -> None:
    """Refuse a file larger than ``limit`` with one line naming it.

    Parameters
    ----------
    size : int
        The file's size [bytes].
    limit : int
        The largest size allowed [bytes].
    name : str
        The file, for the message.
    what : str
        What kind of file it is (``"design file"``).

    Raises
    ------
    DesignError
        When ``size`` exceeds ``limit``.
    """
    if size > limit:
        raise DesignError(name, f"is {size:,} bytes, too large for a {what} (at most "
                          f"{limit:,} bytes)")


def shown_key(key: object, limit: int = 60) -> str:
    """A key of a design file (or a file name) as an error path shows it.

    Parameters
    ----------
    key : object
        The key or name.
    limit : int
        The most characters shown.

    Returns
    -------
    str
        The key with its control characters escaped (a key with a newline keeps the message
        on one line), cut to ``limit`` characters.
    """
    text = str(key)
    if text.isprintable() and len(text) <= limit:
        return text
    escaped = text if text.isprintable() else text.encode("unicode_escape").decode("ascii")
    return escaped if len(escaped) <= limit else escaped[:limit - 1] + "…"
