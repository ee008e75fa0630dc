"""Lubrication advice for every chain: the regime by chain speed and pitch.

Regimes, from slow to fast: "manual" (brush or oil can), "drip", "bath/disc" (oil bath or
slinger disc), "forced" (oil stream from a pump) — the ANSI/ACA lubrication types A (manual
or drip), B (bath or disc) and C (stream) [Shigley2015, §17-5]. Boundaries:

* manual up to 0.5 m/s, drip up to about 1.5 m/s [KettenfabrikUnna];
* drip (type A) and bath/disc (type B) upper speeds by chain pitch from the ANSI table of
  [McGuireLube] (ANSI 40 … 160, pitch 12.7 … 50.8 mm). A chain without an ANSI number (ISO B
  series, GOST, user) takes the limits of its pitch: log–log interpolation in pitch between
  the tabulated chains, and outside 12.7 … 50.8 mm the end segments extended (flagged as an
  extrapolation in the note);
* a polymer chain runs dry: "none: dry-running polymer" (the point of a polymer chain; its
  maker's catalogue; no oil).

References
----------
[Shigley2015] §17-5 (lubrication types); [McGuireLube]; [KettenfabrikUnna].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.model import ChainSpec
from chaindrive.strength import iso10823

__all__ = ["ANSI_TYPE", "MANUAL_MAX", "REGIMES", "LubricationAdvice", "lubrication_advice",
           "speed_limits"]

MANUAL_MAX = 0.5  # [m/s] [KettenfabrikUnna]
REGIMES = ("manual", "drip", "bath/disc", "forced", "none: dry-running polymer")
ANSI_TYPE = {"manual": "A", "drip": "A", "bath/disc": "B", "forced": "C"}
_SOURCE = "[McGuireLube]; [KettenfabrikUnna]; [Shigley2015, §17-5]"


@dataclass(frozen=True, slots=True)
class LubricationAdvice:
    """The lubrication regime of a chain at a chain speed.

    Parameters
    ----------
    chain : str
        The chain's designation.
    speed : float
        Chain speed [m/s].
    regime : str
        One of :data:`REGIMES`.
    ansi_type : str or None
        "A", "B", "C" (None for a polymer chain).
    drip_max, bath_max : float or None
        Upper chain speeds of drip and bath/disc lubrication for this pitch [m/s] (None for
        a polymer chain).
    source : str
        Reference keys of the table.
    note : str
        Extrapolation, table used.
    """

    chain: str
    speed: float
    regime: str
    ansi_type: str | None
    drip_max: float | None
    bath_max: float | None
    source: str
    note: str = ""

    @property
    def manual_max(self) -> float | None:
        """Upper chain speed of manual lubrication [m/s] (None for a polymer chain)."""
        return None if self.drip_max is None else MANUAL_MAX

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"chain": self.chain, "chain_speed_m_s": self.speed, "regime": self.regime,
                "ansi_type": self.ansi_type, "manual_max_m_s": self.manual_max,
                "drip_max_m_s": self.drip_max,
                "bath_max_m_s": self.bath_max, "source": self.source, "note": self.note}


def _table() -> list[tuple[float, float, float]]:
    """(pitch [m], drip max [m/s], bath max [m/s]) of the ANSI table, by pitch."""
    rows = [(int(k) / 80.0 * 0.0254, float(v[0]), float(v[1]))
            for k, v in iso10823.data()["lubrication"].items()]
    return sorted(rows)


@shared_parameters
def speed_limits(pitch: float) -> tuple[float, float, str]:
    """Drip (type A) and bath/disc (type B) upper chain speeds for a pitch.

    Parameters
    ----------
    %(pitch)s

    Returns
    -------
    tuple of (float, float, str)
        Drip and bath limits [m/s] and a note when the pitch is outside the table (log–log
        interpolation or extrapolation in pitch; module docstring).

    References
    ----------
    [McGuireLube].
    """
    rows = _table()
    for p, a, b in rows:
        if abs(p - pitch) <= 1e-6:
            return a, b, ""
    if pitch < rows[0][0]:
        lo, hi, note = rows[0], rows[1], "pitch below the table: extrapolated"
    elif pitch > rows[-1][0]:
        lo, hi, note = rows[-2], rows[-1], "pitch above the table: extrapolated"
    else:
        i = next(k for k in range(len(rows) - 1) if rows[k][0] < pitch < rows[k + 1][0])
        lo, hi, note = rows[i], rows[i + 1], "interpolated in pitch"
    t = math.log(pitch / lo[0]) / math.log(hi[0] / lo[0])

    def interp(j: int) -> float:
        return math.exp((1 - t) * math.log(lo[j]) + t * math.log(hi[j]))

    return interp(1), interp(2), note


@shared_parameters
def lubrication_advice(chain: ChainSpec, speed: float) -> LubricationAdvice:
    """The lubrication regime of a chain at a chain speed (module docstring).

    Parameters
    ----------
    %(chain)s
    speed : float
        Chain speed [m/s].

    Returns
    -------
    LubricationAdvice
        Regime, ANSI type and the limits of the pitch.

    References
    ----------
    [Shigley2015, §17-5]; [McGuireLube]; [KettenfabrikUnna].
    """
    if chain.material != "steel":
        return LubricationAdvice(chain.designation, speed, REGIMES[4], None, None, None,
                                 f"chain material {chain.material}: its maker's catalogue",
                                 "runs without oil; keep it clean and dry")
    drip, bath, note = speed_limits(chain.pitch)
    if speed <= MANUAL_MAX:
        regime = "manual"
    elif speed <= drip:
        regime = "drip"
    elif speed <= bath:
        regime = "bath/disc"
    else:
        regime = "forced"
    return LubricationAdvice(chain.designation, speed, regime, ANSI_TYPE[regime], drip, bath,
                             _SOURCE, note)
