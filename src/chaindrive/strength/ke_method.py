"""The classical Russian roller-chain method: operating factor Kэ, allowable joint pressure [p].

Kэ = kд·kа·kн·kрег·kсм·kреж; pressure check p = Kэ·Ft/A ≤ [p] (A the projected bearing area of
the whole chain); pitch estimate t ≥ 2.8·∛(T₁·Kэ/(z₁·[p]·mр)) (T₁ [N·mm], [p] [MPa], t [mm]);
recommended z₁ = 29 − 2u; limits on the small-sprocket speed and on chain impacts per second.

Source: the classical Russian method [ChainDesignRU] (the textbooks — Иванов,
Дунаев–Леликов, Решетов, Чернавский, Шейнблит — reached us only through course programs that
reproduce them) and the Russian-derived tables of [TrinhChat2006]; the data, with the tag of
the program each value comes from, in ``strength/data/ke_method.toml``.
"""

from __future__ import annotations

import math
import tomllib
from functools import cache
from importlib import resources
from typing import Any

import numpy as np

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import bearing_area_estimate, row_factor
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.model import ChainSpec
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["MPA", "allowable_impacts", "allowable_pressure", "allowable_safety_factor",
           "bearing_area", "center_distance_factor", "data", "factor", "impacts_per_second",
           "inclination_factor", "max_speed", "operating_factor", "pitch_estimate",
           "recommended_teeth", "row_factor", "teeth_corrected_pressure"]

#: One megapascal [Pa].
MPA = 1e6
PITCH_TOL = 1e-6  # [m] when matching a pitch to a table group


@cache
def data() -> dict[str, Any]:
    """The Kэ-method tables (``data/ke_method.toml``, read once).

    Returns
    -------
    dict
        The parsed tables, each with the tag of its source in the file.
    """
    text = resources.files("chaindrive.strength").joinpath("data/ke_method.toml").read_bytes()
    return tomllib.loads(text.decode("utf-8"))


def factor(kind: str, condition: str | int) -> float:
    """One partial factor of Kэ from its table.

    Parameters
    ----------
    kind : str
        "dynamic" (kд), "adjustment" (kрег), "lubrication" (kсм) or "mode" (kреж).
    condition : str or int
        kд: calm / shocks / heavy_shocks; kрег: adjustable_shaft / idler / none;
        kсм: continuous / drip / periodic; kреж: 1, 2, 3 shifts.

    Returns
    -------
    float
        The factor [-].

    References
    ----------
    [ChainDesignRU, §2]; [TrinhChat2006, Table 5.6].
    """
    tables = data()["factors"]
    if kind not in tables or kind in {"center_distance", "inclination"}:
        raise DesignError("factor", f"unknown kind {kind!r}; use dynamic, adjustment, "
                          f"lubrication or mode (or the functions for kа, kн)")
    table = tables[kind]
    key = str(condition)
    if key not in table:
        raise DesignError(f"ke.{kind}", f"unknown condition {condition!r}"
                          f"{did_you_mean(key, table)}; allowed: {', '.join(table)}")
    return float(table[key])


def center_distance_factor(center_distance: float, pitch: float) -> float:
    """kа by the centre distance in pitches a/t.

    ≤ 25 t: 1.25 (direction of the inequality unconfirmed); up to 60 t: 1.0 (30…50 t in the
    source; 25…30 and 50…60 t are not tabulated and take 1.0 here); ≥ 60 t: 0.8.

    Parameters
    ----------
    center_distance : float
        a [m].
    pitch : float
        t [m].

    Returns
    -------
    float
        kа [-].

    References
    ----------
    [ChainDesignRU, §2]; [TrinhChat2006, Table 5.6].
    """
    ratio = center_distance / pitch
    table = data()["factors"]["center_distance"]
    if ratio <= 25.0:
        return float(table["short"])
    if ratio < 60.0:
        return float(table["normal"])
    return float(table["long"])


def inclination_factor(inclination: float) -> float:
    """kн by the inclination of the line of centres to the horizontal: 1.0 up to 60°, 1.25
    above.

    Parameters
    ----------
    inclination : float
        ψ [rad].

    Returns
    -------
    float
        kн [-].

    References
    ----------
    [TrinhChat2006, Table 5.6] (k0); [ChainDesignRU, §2].
    """
    table = data()["factors"]["inclination"]
    limit = math.radians(table["limit_deg"])
    return float(table["below"] if abs(inclination) <= limit else table["above"])


def operating_factor(kd: float = 1.0, ka: float = 1.0, kn: float = 1.0, kreg: float = 1.0,
                     ksm: float = 1.0, kmode: float = 1.0) -> float:
    """Operating (exploitation) factor Kэ = kд·kа·kн·kрег·kсм·kреж.

    Parameters
    ----------
    kd, ka, kn, kreg, ksm, kmode : float
        The partial factors kд, kа, kн, kрег, kсм, kреж [-] (:func:`factor`).

    Returns
    -------
    float
        Kэ [-].

    References
    ----------
    [ChainDesignRU, §2].
    """
    return kd * ka * kn * kreg * ksm * kmode


def _grid_value(section: str, pitch: float, speed: float) -> float | None:
    """Linear interpolation in n1 on the table ``section`` for the pitch group of ``pitch``."""
    table = data()[section]
    n1 = speed * RPM_PER_RAD_S
    for group in table["groups"]:
        lo, hi = group["pitch_min_mm"] * 1e-3, group["pitch_max_mm"] * 1e-3
        if lo - PITCH_TOL <= pitch <= hi + PITCH_TOL:
            values = group["values"]
            grid = table["speeds_rpm"][: len(values)]
            if n1 > grid[-1] + 1e-9:
                return None
            return float(np.interp(n1, grid, values))
    return None


def allowable_pressure(pitch: float, speed: float) -> float | None:
    """Allowable mean joint pressure [p], interpolated linearly in n1 (below 50 rpm the
    50 rpm value).

    Parameters
    ----------
    pitch : float
        Chain pitch [m].
    speed : float
        Small-sprocket speed [rad/s].

    Returns
    -------
    float or None
        [p] [Pa]; None outside the table (pitch outside 12.7…50.8 mm, or speed above the last
        column of its group).

    References
    ----------
    [ChainDesignRU, Table 2A].
    """
    value = _grid_value("allowable_pressure", pitch, speed)
    return None if value is None else value * MPA


def teeth_corrected_pressure(allowable: float, teeth: int) -> float:
    """[p]·[1 + 0.01·(z1 − 17)]: the table is for z1 = 17.

    Parameters
    ----------
    allowable : float
        [p] of the table [Pa].
    teeth : int
        z1 [-].

    Returns
    -------
    float
        The corrected [p] [Pa].

    References
    ----------
    [ChainDesignRU, §3] (after Чернавский).
    """
    return allowable * (1.0 + 0.01 * (teeth - 17))


def allowable_safety_factor(pitch: float, speed: float) -> float | None:
    """Allowable static safety factor [s], interpolated in n1.

    Parameters
    ----------
    pitch : float
        Chain pitch [m].
    speed : float
        Small-sprocket speed [rad/s].

    Returns
    -------
    float or None
        [s] [-]; None outside the table.

    References
    ----------
    [ChainDesignRU, Table 9A]; [TrinhChat2006, Table 5.10].
    """
    return _grid_value("allowable_safety", pitch, speed)


def _by_pitch(section: str, key: str, pitch: float) -> float | None:
    table = data()[section]
    for p_mm, value in zip(table["pitch_mm"], table[key], strict=True):
        if abs(p_mm * 1e-3 - pitch) <= PITCH_TOL:
            return float(value)
    return None


def max_speed(pitch: float) -> float | None:
    """Highest small-sprocket speed for a pitch (column z1 = 15).

    Parameters
    ----------
    pitch : float
        Chain pitch [m].

    Returns
    -------
    float or None
        n1 max [rad/s]; None for pitches not in the table.

    References
    ----------
    [TrinhChat2006, Table 5.8]; [ChainDesignRU, §5].
    """
    value = _by_pitch("speed_limit", "max_rpm", pitch)
    return None if value is None else value / RPM_PER_RAD_S


def impacts_per_second(teeth: int, speed: float, links: int | float) -> float:
    """Chain impacts (hits) per second i = z1·n1/(15·Lt), n1 in rpm (the Russian form
    ν = 4·z1·n1/(60·Lt) is the same).

    Parameters
    ----------
    teeth : int
        z1 [-].
    speed : float
        Small-sprocket speed [rad/s].
    links : int or float
        Lt [links].

    Returns
    -------
    float
        i [1/s].

    References
    ----------
    [ChainDesignRU, §5]; [TrinhChat2006, Table 5.9].
    """
    return teeth * (speed * RPM_PER_RAD_S) / (15.0 * links)


def allowable_impacts(pitch: float) -> float | None:
    """Allowable impacts per second [i] for roller/bush chains.

    Parameters
    ----------
    pitch : float
        Chain pitch [m].

    Returns
    -------
    float or None
        [i] [1/s]; None when the pitch is not tabulated.

    References
    ----------
    [TrinhChat2006, Table 5.9].
    """
    return _by_pitch("impacts", "max_per_s", pitch)


def recommended_teeth(ratio: float) -> int:
    """Recommended small-sprocket teeth z1 = 29 − 2u, rounded to the nearest odd number (an
    even value goes up: more teeth run smoother) and kept ≥ 13.

    Parameters
    ----------
    ratio : float
        Transmission ratio u [-].

    Returns
    -------
    int
        z1 [-].

    References
    ----------
    [ChainDesignRU, §4].
    """
    z = 29.0 - 2.0 * ratio
    odd = 2 * math.floor(z / 2.0) + 1
    return max(13, int(odd))


def pitch_estimate(torque: float, operating: float, teeth: int, allowable: float,
                   rows: int = 1) -> float:
    """Minimum pitch t ≥ 2.8·∛(T₁·Kэ/(z₁·[p]·mр)).

    The source formula takes T₁ in N·mm and [p] in MPa and gives t in mm (the same as 28·∛
    with T in N·m).

    Parameters
    ----------
    torque : float
        T₁ on the small sprocket [N·m].
    operating : float
        Kэ [-].
    teeth : int
        z₁ [-].
    allowable : float
        [p] [Pa].
    rows : int
        Rows of the chain [-] (mр from :func:`chaindrive.catalog.row_factor`).

    Returns
    -------
    float
        t [m].

    References
    ----------
    [ChainDesignRU, §3].
    """
    t_mm = 2.8 * np.cbrt(torque * 1e3 * operating / (teeth * (allowable / MPA) * row_factor(rows)))
    return float(t_mm) * 1e-3


@shared_parameters
def bearing_area(chain: ChainSpec) -> tuple[float, bool]:
    """Projected bearing area A of the whole chain and whether it was estimated.

    The catalogue value when present; otherwise the estimate of the catalogue,
    :func:`chaindrive.catalog.bearing_area_estimate` (A = mр·d2·B, B from the transverse
    pitch, or 1.42·b1 without it).

    Parameters
    ----------
    %(chain)s

    Returns
    -------
    tuple of (float, bool)
        A [m²] and True when it is an estimate.

    References
    ----------
    [TrinhChat2006, Tables 5.5 and 5.12]; [GOST13568, Table 1].
    """
    if chain.bearing_area:
        return chain.bearing_area, False
    area = bearing_area_estimate(chain.pin_diameter, chain.inner_width, chain.transverse_pitch,
                                 min(chain.strands, 4))
    return float(area), True
