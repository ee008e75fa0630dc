"""The classical Russian roller-chain method: operating factor Kэ, allowable joint pressure [p].

Kэ = kд·kа·kн·kрег·kсм·kреж; pressure check p = Kэ·Ft/A ≤ [p] (A the projected bearing area of
the whole chain); pitch estimate t ≥ 2.8·∛(T₁·Kэ/(z₁·[p]·mр)) (T₁ [N·mm], [p] [MPa], t [mm]);
recommended z₁ = 29 − 2u; limits on the small-sprocket speed and on chain impacts per second.

Sources (tags as in ``shared/data/chain_design_method_ru.md``; the textbooks — Иванов,
Дунаев–Леликов, Решетов, Чернавский, Шейнблит — reached us only through course programs that
reproduce them): [JAVA], [PY], [CS], [CPP], [VN-SQL], [VN-CODE]; data in
``strength/data/ke_method.toml``.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

import numpy as np

from chaindrive.errors import DesignError, did_you_mean
from chaindrive.model import ChainSpec
from chaindrive.units import RAD_S_TO_RPM

MPA = 1e6
PITCH_TOL = 1e-6  # [m] when matching a pitch to a table group


@cache
def data() -> dict[str, Any]:
    """The Kэ-method tables (``data/ke_method.toml``)."""
    text = resources.files("chaindrive.strength").joinpath("data/ke_method.toml").read_bytes()
    return tomllib.loads(text.decode("utf-8"))


def factor(kind: str, condition: str | int) -> float:
    """One partial factor of Kэ from its table.

    kind : "dynamic" (kд: calm / shocks / heavy_shocks), "adjustment" (kрег: adjustable_shaft /
    idler / none), "lubrication" (kсм: continuous / drip / periodic), "mode" (kреж: 1, 2, 3
    shifts). Sources: [JAVA], [PY], [CS], [VN-SQL].
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
    """kа by the centre distance in pitches a/t ([VN-SQL], [CS]).

    ≤ 25 t: 1.25 (direction of the inequality unconfirmed); up to 60 t: 1.0 (30…50 t in the
    source; 25…30 and 50…60 t are not tabulated and take 1.0 here); ≥ 60 t: 0.8.
    """
    ratio = center_distance / pitch
    table = data()["factors"]["center_distance"]
    if ratio <= 25.0:
        return float(table["short"])
    if ratio < 60.0:
        return float(table["normal"])
    return float(table["long"])


def inclination_factor(inclination: float) -> float:
    """kн by the inclination ψ [rad] of the line of centres to the horizontal ([VN-SQL] k0):
    1.0 up to 60°, 1.25 above."""
    table = data()["factors"]["inclination"]
    limit = math.radians(table["limit_deg"])
    return float(table["below"] if abs(inclination) <= limit else table["above"])


def operating_factor(kd: float = 1.0, ka: float = 1.0, kn: float = 1.0, kreg: float = 1.0,
                     ksm: float = 1.0, kmode: float = 1.0) -> float:
    """Operating (exploitation) factor Kэ = kд·kа·kн·kрег·kсм·kреж ([JAVA], [CS], [PY], [VN-SQL])."""
    return kd * ka * kn * kreg * ksm * kmode


def row_factor(rows: int) -> float:
    """Row factor mр = 1, 1.7, 2.5, 3.0 for 1…4 rows ([VN-CODE])."""
    table = data()["row_factor"]
    if str(rows) not in table:
        raise DesignError("chain.strands", f"the Kэ method covers 1 to 4 rows, got {rows!r}")
    return float(table[str(rows)])


def _grid_value(section: str, pitch: float, speed: float) -> float | None:
    """Linear interpolation in n1 on the table ``section`` for the pitch group of ``pitch``."""
    table = data()[section]
    n1 = speed * RAD_S_TO_RPM
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
    """Allowable mean joint pressure [p] [Pa] for pitch [m] and small-sprocket speed [rad/s].

    Table 2A of chain_design_method_ru.md ([JAVA], [PY]), interpolated linearly in n1 (below
    50 rpm the 50 rpm value); None outside the table (pitch outside 12.7…50.8 mm, or speed
    above the last column of its group).
    """
    value = _grid_value("allowable_pressure", pitch, speed)
    return None if value is None else value * MPA


def teeth_corrected_pressure(allowable: float, teeth: int) -> float:
    """[p]·[1 + 0.01·(z1 − 17)]: the table is for z1 = 17 (Чернавский, via [CPP])."""
    return allowable * (1.0 + 0.01 * (teeth - 17))


def allowable_safety_factor(pitch: float, speed: float) -> float | None:
    """Allowable static safety factor [s] for pitch [m] and speed [rad/s] (Table 9A, [VN-SQL]
    table 5.10), interpolated in n1; None outside the table."""
    return _grid_value("allowable_safety", pitch, speed)


def _by_pitch(section: str, key: str, pitch: float) -> float | None:
    table = data()[section]
    for p_mm, value in zip(table["pitch_mm"], table[key], strict=True):
        if abs(p_mm * 1e-3 - pitch) <= PITCH_TOL:
            return float(value)
    return None


def max_speed(pitch: float) -> float | None:
    """Highest small-sprocket speed [rad/s] for the pitch [m] ([VN-SQL] table 5.8, column
    n1_z1_15, equal to [JAVA] n1p); None for pitches not in the table."""
    value = _by_pitch("speed_limit", "max_rpm", pitch)
    return None if value is None else value / RAD_S_TO_RPM


def impacts_per_second(teeth: int, speed: float, links: int | float) -> float:
    """Chain impacts (hits) per second i = z1·n1/(15·Lt) [1/s], n1 in rpm; speed [rad/s]
    ([VN-CODE]; the Russian form ν = 4·z1·n1/(60·Lt) is the same)."""
    return teeth * (speed * RAD_S_TO_RPM) / (15.0 * links)


def allowable_impacts(pitch: float) -> float | None:
    """Allowable impacts per second [i] for roller/bush chains ([VN-SQL] table 5.9); None when
    the pitch is not tabulated."""
    return _by_pitch("impacts", "max_per_s", pitch)


def recommended_teeth(ratio: float) -> int:
    """Recommended small-sprocket teeth z1 = 29 − 2u ([JAVA], [PY], [VN-CODE]), rounded to the
    nearest odd number (an even value goes up: more teeth run smoother) and kept ≥ 13
    ([JAVA] rejects z1 < 13)."""
    z = 29.0 - 2.0 * ratio
    odd = 2 * math.floor(z / 2.0) + 1
    return max(13, int(odd))


def pitch_estimate(torque: float, operating: float, teeth: int, allowable: float,
                   rows: int = 1) -> float:
    """Minimum pitch t ≥ 2.8·∛(T₁·Kэ/(z₁·[p]·mр)) [m].

    torque T₁ [N·m] on the small sprocket; allowable [p] [Pa]; rows → mр. The source formula
    takes T₁ in N·mm and [p] in MPa and gives t in mm ([CPP]; same as 28·∛ with T in N·m [PY]).
    """
    t_mm = 2.8 * np.cbrt(torque * 1e3 * operating / (teeth * (allowable / MPA) * row_factor(rows)))
    return float(t_mm) * 1e-3


def links_two_sprocket(center_distance: float, pitch: float, teeth1: int, teeth2: int) -> float:
    """Chain length in pitches Lt = 2·a/t + (z1 + z2)/2 + ((z2 − z1)/2π)²·t/a (not rounded).

    Sources: [CPP], [PY], [CS]; Shigley Eq. 17-34 is the same.
    """
    at = center_distance / pitch
    delta = (teeth2 - teeth1) / (2.0 * math.pi)
    return 2.0 * at + 0.5 * (teeth1 + teeth2) + delta**2 / at


def bearing_area(chain: ChainSpec) -> tuple[float, bool]:
    """Projected bearing area A of the whole chain [m²] and whether it was estimated.

    The catalogue value when present; otherwise A ≈ 1.42·d2·b1·mр, with 1.42 the median ratio
    of bushing length B to inner width Bвн of the GOST 13568 ПР chains of 19.05…50.8 mm pitch
    (``shared/data/gost13568_pr_chains.csv`` [S5]: 17.75/12.70, 22.61/15.88, …) — an estimate
    for chains whose catalogue gives no area.
    """
    if chain.bearing_area:
        return chain.bearing_area, False
    rows = min(chain.strands, 4)
    return 1.42 * chain.pin_diameter * chain.inner_width * row_factor(rows), True


@dataclass(frozen=True, slots=True)
class PressureCheck:
    """Kэ-method check of one chain (SI): pressure p [Pa] vs [p] [Pa], speed vs n1 max [rad/s],
    impacts vs [i] [1/s]; margin = the smallest of allowable/actual − 1; governing names it."""

    pressure: float
    allowable_pressure: float | None
    speed: float
    max_speed: float | None
    impacts: float | None
    allowable_impacts: float | None
    margin: float
    governing: str
    area_estimated: bool

    @property
    def feasible(self) -> bool:
        """True when every limit is met (margin ≥ 0)."""
        return self.margin >= -1e-12


def check_pressure(chain: ChainSpec, force: float, operating: float, teeth: int, speed: float,
                   links: float | None = None) -> PressureCheck:
    """Check p = Kэ·Ft/A ≤ [p], n1 ≤ n1 max and i ≤ [i] for ``chain``.

    force Ft [N]; operating Kэ; speed of the small sprocket [rad/s]; links Lt (None: no
    impacts check). A limit whose table has no entry for this pitch/speed makes the chain
    infeasible with governing "outside the [p] table" (the method has no value there).
    """
    area, estimated = bearing_area(chain)
    p = force * operating / area
    allowed = allowable_pressure(chain.pitch, speed)
    nmax = max_speed(chain.pitch)
    hits = impacts_per_second(teeth, speed, links) if links else None
    hits_max = allowable_impacts(chain.pitch)
    margins: dict[str, float] = {}
    margins["joint pressure"] = (allowed / p - 1.0) if allowed else -1.0
    if nmax is not None:
        margins["speed limit"] = nmax / speed - 1.0
    if hits is not None and hits_max is not None:
        margins["impacts per second"] = hits_max / hits - 1.0
    key = min(margins, key=lambda k: margins[k])
    governing = "outside the [p] table" if allowed is None and key == "joint pressure" else key
    return PressureCheck(p, allowed, speed, nmax, hits, hits_max, margins[key], governing,
                         estimated)
