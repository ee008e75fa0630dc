"""Power ratings that fit the chain, each naming its method truthfully.

========================  =====================================================  ==========
chain                     method                                                 module
========================  =====================================================  ==========
ISO 606 A, ANSI (B29.1)   ACA formulas (Shigley Eq. 17-32/17-33), "ACA"           iso10823
ISO 606 B (European)      published B-series rating table, "ISO 606 B table";     here
                          the ACA formulas computed beside it
GOST 13568                no power rating: the Kэ method checks pressure, speed   ke_method
polymer                   the manufacturer's allowable load (no power rating)     checks
========================  =====================================================  ==========

Where two methods apply (B-series chains) both are computed and the result says which
governs: the B-series table where it has a value at the operating speed (it is made for
these chains), the ACA formulas otherwise — with a note that they are made for ANSI
proportions and rate B-series chains low (the roller–bush term with K_r = 17 governs at
speed; e.g. 12B at 1400 rpm: ACA 13.5 kW against 18.15 kW in [Bhandari2010, Table 14.2]).

Tooth correction of a table value printed for z_ref teeth: P(z1) = P_table·(z1/z_ref)^1.08
(the ISO 10823 tooth factor (19/z1)^1.08 as quoted by [ISO10823] secondary sources, written
for another reference count; the ACA pre-extreme correction [Shigley2015, Table 17-22] has
the same exponent). Strand factor: 1, 1.7, 2.5, 3.3 … [Shigley2015, Table 17-23].
Interpolation in a table: log–log in speed between two printed values of the same chain;
outside the printed speeds there is no table value (never extrapolated).

References
----------
[Shigley2015] §17-5; [Bhandari2010] Table 14.2; [Jindal2010] Table 30-8; [ISO10823].
"""

from __future__ import annotations

import csv
import io
import itertools
import math
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from chaindrive.errors import Quantities, Quantity
from chaindrive.model import ChainSpec
from chaindrive.strength import iso10823
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["ACA", "B_TABLE", "KE", "METHOD_SOURCES", "POLYMER", "Alternative", "RatingResult",
           "TablePoint", "b_table", "chain_number", "chain_rating", "method_for", "table_rating",
           "tooth_correction"]

ACA = "ACA"
B_TABLE = "ISO 606 B table"
KE = "Kэ"
POLYMER = "allowable load"
METHOD_SOURCES = {
    ACA: "[Shigley2015, Eq. 17-32/17-33]; [ANSI-B29.1]",
    B_TABLE: "[Bhandari2010, Table 14.2]; [Jindal2010, Table 30-8]",
    KE: "[ChainDesignRU]",
    POLYMER: "manufacturer's catalogue (catalogue row 'source')",
}
TOOTH_EXPONENT = 1.08
SPEED_TOL = 1e-6


@dataclass(frozen=True, slots=True)
class TablePoint:
    """One printed rating.

    Parameters
    ----------
    chain : str
        ISO chain number, e.g. "12B".
    speed_rpm : float
        n1 [rpm].
    rating : float
        Single-strand rating [W].
    reference_teeth : int
        Teeth the value is printed for [-].
    life_h : float
        Rating life [h].
    lubrication : str
        Lubrication assumed.
    source : str
        Reference key of the table.
    """

    chain: str
    speed_rpm: float
    rating: float
    reference_teeth: int
    life_h: float
    lubrication: str
    source: str


@cache
def b_table() -> tuple[TablePoint, ...]:
    """The published B-series ratings (``strength/data/ratings_iso606_b.csv``, read once).

    Returns
    -------
    tuple of TablePoint
        Every printed value.

    References
    ----------
    [Bhandari2010, Table 14.2]; [Jindal2010, Table 30-8].
    """
    text = resources.files("chaindrive.strength").joinpath(
        "data/ratings_iso606_b.csv").read_text(encoding="utf-8")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    return tuple(TablePoint(r["chain"], float(r["speed_rpm"]), float(r["rating_kw"]) * 1e3,
                            int(r["reference_teeth"]), float(r["life_h"]), r["lubrication"],
                            r["source"])
                 for r in csv.DictReader(io.StringIO("\n".join(lines))))


def chain_number(chain: ChainSpec) -> str:
    """The ISO 606 chain number of a catalogue chain: ``"ISO 606 12B-2"`` → ``"12B"``.

    Parameters
    ----------
    chain : ChainSpec
        The chain.

    Returns
    -------
    str
        Its number.
    """
    name = chain.designation.split()[-1]
    return name.split("-")[0]


def method_for(chain: ChainSpec) -> str:
    """The rating method of a chain.

    Parameters
    ----------
    chain : ChainSpec
        The chain.

    Returns
    -------
    str
        Kэ (GOST), allowable load (non-steel), B table (ISO 606 B series), ACA (ISO 606 A,
        ANSI, and user chains of another family).
    """
    if chain.material != "steel":
        return POLYMER
    if chain.standard.upper().startswith("GOST"):
        return KE
    if chain.series == "B":
        return B_TABLE
    return ACA


def tooth_correction(teeth: int, reference_teeth: int) -> float:
    """(z1/z_ref)^1.08: multiplies a rating printed for z_ref teeth (module docstring).

    Parameters
    ----------
    teeth : int
        z1 [-].
    reference_teeth : int
        z_ref [-].

    Returns
    -------
    float
        The correction [-].

    References
    ----------
    [ISO10823]; [Shigley2015, Table 17-22].
    """
    return float((teeth / reference_teeth) ** TOOTH_EXPONENT)


def table_rating(chain: ChainSpec, teeth: int, speed: float) -> tuple[float, str] | None:
    """Single-strand B-table rating and its source.

    A printed value at that speed, or log–log interpolation between the two printed values
    that bracket it.

    Parameters
    ----------
    chain : ChainSpec
        The chain.
    teeth : int
        z1 [-].
    speed : float
        Small-sprocket speed [rad/s].

    Returns
    -------
    tuple of (float, str) or None
        Rating [W] and source; None outside the printed speeds of the chain.

    References
    ----------
    [Bhandari2010, Table 14.2]; [Jindal2010, Table 30-8].
    """
    n1 = speed * RPM_PER_RAD_S
    points = sorted((p for p in b_table() if p.chain == chain_number(chain)),
                    key=lambda p: p.speed_rpm)
    for p in points:
        if abs(p.speed_rpm - n1) <= SPEED_TOL * max(1.0, n1):
            return p.rating * tooth_correction(teeth, p.reference_teeth), p.source
    for lo, hi in itertools.pairwise(points):
        if lo.speed_rpm < n1 < hi.speed_rpm:
            t = math.log(n1 / lo.speed_rpm) / math.log(hi.speed_rpm / lo.speed_rpm)
            value = math.exp((1 - t) * math.log(lo.rating) + t * math.log(hi.rating))
            return (value * tooth_correction(teeth, lo.reference_teeth),
                    f"{lo.source}; {hi.source} (log-log interpolation)")
    return None


@dataclass(frozen=True, slots=True)
class Alternative:
    """A method computed beside the governing one.

    Parameters
    ----------
    method : str
        The method.
    rated_power : float or None
        Rated power of the whole chain [W] (None when the method has no value here).
    source : str
        Reference keys.
    note : str
        What it rests on.
    """

    method: str
    rated_power: float | None
    source: str
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"method": self.method, "rated_power_w": self.rated_power,
                "source": self.source, "note": self.note}


@dataclass(frozen=True, slots=True)
class RatingResult:
    """The power rating of one chain at one operating point (all strands).

    Parameters
    ----------
    chain : str
        The chain.
    method : str
        The method that governs.
    rated_power : float or None
        [W] (None for methods without a power rating: Kэ, allowable load).
    envelope : str
        The ACA envelope that limits ("link-plate fatigue", "roller-bush impact") or
        "table".
    source : str
        Reference keys.
    alternatives : tuple of Alternative
        Every other method computed.
    note : str
        Why this method governs.
    note_quantities : tuple of Quantity
        The numbers with units ``note`` writes (SI; :class:`chaindrive.errors.Quantities`),
        for a presenter to write in another unit system.
    """

    chain: str
    method: str
    rated_power: float | None
    envelope: str
    source: str
    alternatives: tuple[Alternative, ...] = ()
    note: str = ""
    note_quantities: tuple[Quantity, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"chain": self.chain, "method": self.method, "rated_power_w": self.rated_power,
                "envelope": self.envelope, "source": self.source, "note": self.note,
                "note_quantities": [q.to_dict() for q in self.note_quantities],
                "alternatives": [a.to_dict() for a in self.alternatives]}


def _aca(chain: ChainSpec, teeth: int, speed: float, links: float,
         life_h: float) -> tuple[float, str] | None:
    """ACA rating of the whole chain [W] and its envelope; None for strand counts the
    strand-factor table does not give."""
    if str(chain.strands) not in iso10823.data()["strand_factor"]:
        return None
    single, envelope = iso10823.aca_rating(chain, teeth, speed, links=links, life_h=life_h)
    return single * iso10823.strand_factor(chain.strands), envelope


def chain_rating(chain: ChainSpec, teeth: int, speed: float, *, links: float = 100.0,
                 life_h: float = 15000.0) -> RatingResult:
    """Rating of a chain on a small sprocket (the method of each family: module docstring).

    Parameters
    ----------
    chain : ChainSpec
        The chain.
    teeth : int
        Teeth of the small sprocket [-].
    speed : float
        Its speed [rad/s].
    links : float
        Chain length [pitches], for the ACA roller–bush correction.
    life_h : float
        Life [h], likewise.

    Returns
    -------
    RatingResult
        The governing method's rating and the others beside it.

    References
    ----------
    [Shigley2015, Eq. 17-32/17-33, 17-39/17-40]; [Bhandari2010, Table 14.2].
    """
    method = method_for(chain)
    aca = _aca(chain, teeth, speed, links, life_h) if chain.material == "steel" else None
    aca_alt = Alternative(ACA, None if aca is None else aca[0], METHOD_SOURCES[ACA],
                          "" if aca is None else aca[1])
    if method in (KE, POLYMER):
        note = ("GOST chain: checked by the Kэ method (hinge pressure, speed, impacts), "
                "not by a power rating" if method == KE else
                "polymer chain: checked against the manufacturer's allowable load")
        alts = (aca_alt,) if method == KE else ()
        return RatingResult(chain.designation, method, None, "", METHOD_SOURCES[method],
                            alts, note)
    if method == B_TABLE:
        table = table_rating(chain, teeth, speed)
        strands = (iso10823.strand_factor(chain.strands)
                   if str(chain.strands) in iso10823.data()["strand_factor"] else None)
        if table is not None and strands is not None:
            q = Quantities()
            beside = ("no value" if aca is None else
                      f"{q(aca[0], 'power', '.4g')} beside it ({aca[1]} envelope)")
            return RatingResult(chain.designation, B_TABLE, table[0] * strands, "table",
                                table[1], (aca_alt,),
                                "B-series chain: the published B-series table governs; the "
                                f"ACA formulas (ANSI proportions) give {beside}", q.items)
        b_alt = Alternative(B_TABLE, None, METHOD_SOURCES[B_TABLE],
                            "no printed B-series rating at this speed")
        note = ("B-series chain without a printed B-series rating at this speed: the ACA "
                "formulas govern; they are made for ANSI proportions and rate B-series "
                "chains low at speed (conservative)")
        if aca is None:
            return RatingResult(chain.designation, ACA, None, "", METHOD_SOURCES[ACA],
                                (b_alt,), note)
        return RatingResult(chain.designation, ACA, aca[0], aca[1], METHOD_SOURCES[ACA],
                            (b_alt,), note)
    if aca is None:
        return RatingResult(chain.designation, ACA, None, "", METHOD_SOURCES[ACA], (),
                            f"no strand factor for {chain.strands} strands")
    return RatingResult(chain.designation, ACA, aca[0], aca[1], METHOD_SOURCES[ACA], (),
                        "ISO 606 A / ANSI chain: ACA formulas (ANSI B29.1 rating basis)")
