"""Power rating by the ACA formulas (ANSI B29.1 rating basis, Shigley §17-5), and the
ISO 10823-style correction of the power to select with.

Despite the module's name no ISO 10823 rating chart is implemented here: the ratings are the
ACA envelopes, made for ANSI proportions; :mod:`chaindrive.strength.ratings` chooses the
method that fits each chain (ACA for ISO 606 A / ANSI, the B-series table for B chains).

Procedure (``shared/data/iso10823_method.md`` §1): correct the transmitted power to the
rating basis, P_sel = P·K_s·n_d / (K_tooth·K_strand), and choose the smallest pitch whose
single-strand rating at the small-sprocket speed is at least P_sel. Ratings come from the
ACA envelopes (link-plate fatigue H1, roller–bush impact H2, Shigley Eq. 17-32/17-33) or from
a textbook table (:func:`textbook_rating`). The rating basis is 15 000 h to 3 % elongation,
100 pitches, two 17-tooth sprockets, single strand, service factor 1 (Shigley §17-5).

Data: ``strength/data/iso10823.toml`` and ``textbook_ratings.csv`` (sources in their headers).
The ISO 10823 application-factor table was not available: :func:`service_factor` uses the
Tsubaki Table 4.2 values (same structure), not the ISO table.
"""

from __future__ import annotations

import csv
import io
import math
import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any, Literal

import numpy as np

from chaindrive.errors import DesignError, did_you_mean
from chaindrive.model import ChainSpec
from chaindrive.units import RAD_S_TO_RPM

HP = 745.699872  # 1 hp [W]
INCH = 0.0254  # [m]
LBF = 4.4482216152605  # [N]
FPM = 0.00508  # 1 ft/min in m/s

Lubrication = Literal["A", "B", "C", "C'"]


@cache
def data() -> dict[str, Any]:
    """The ISO 10823 / ACA tables (``data/iso10823.toml``)."""
    text = resources.files("chaindrive.strength").joinpath("data/iso10823.toml").read_bytes()
    return tomllib.loads(text.decode("utf-8"))


@cache
def _textbook_rows() -> tuple[tuple[str, str, float, float], ...]:
    text = resources.files("chaindrive.strength").joinpath("data/textbook_ratings.csv").read_text(
        encoding="utf-8")
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    reader = csv.DictReader(io.StringIO("\n".join(lines)))
    return tuple((r["source"], r["chain"], float(r["speed_rpm"]), float(r["rating_kw"]))
                 for r in reader)


def service_factor(load: str, driver: str = "electric_motor") -> float:
    """Service (application) factor K_s by driven-machine load and driver type.

    load : "smooth", "moderate_shock" or "heavy_shock"; driver : "electric_motor",
    "ic_engine_hydraulic" or "ic_engine_mechanical". Source: Tsubaki Table 4.2 (Mott
    Table 7-17 agrees) — not the ISO 10823 table, which was not available.
    """
    table = data()["service_factor"]
    if load not in table:
        raise DesignError("drive.load", f"unknown load {load!r}{did_you_mean(load, table)}; "
                          f"allowed: {', '.join(table)}")
    row = table[load]
    if driver not in row:
        raise DesignError("drive.driver", f"unknown driver {driver!r}{did_you_mean(driver, row)}; "
                          f"allowed: {', '.join(row)}")
    return float(row[driver])


def tooth_factor_iso(teeth: int | np.ndarray) -> float | np.ndarray:
    """ISO 10823 tooth factor f2 = (19/z1)^1.08; multiplies the power to select with.

    Source: ISO 10823:2004 as quoted by GB/T 18150-2006 ([JW] in iso10823_method.md);
    a simpler 19/z1 also circulates ([BS]) — the exponent form is used here.
    """
    return (19.0 / np.asarray(teeth, dtype=float)) ** 1.08


def tooth_correction_aca(teeth: int | np.ndarray, region: str = "plate"
                         ) -> float | np.ndarray:
    """ACA tooth correction K1 (multiplies the 17-tooth rating), Shigley Table 17-22.

    region "plate" (pre-extreme, link-plate fatigue): K1 = (N1/17)^1.08;
    region "impact" (post-extreme, roller–bush impact): K1 = (N1/17)^1.5.
    """
    exponent = {"plate": 1.08, "impact": 1.5}.get(region)
    if exponent is None:
        raise DesignError("region", f"must be 'plate' or 'impact', got {region!r}")
    return (np.asarray(teeth, dtype=float) / 17.0) ** exponent


def tooth_factor_bhandari(teeth: int) -> float:
    """Tooth correction factor K2 of Bhandari Table 14.5 (values 17, 19, 21 teeth only)."""
    table = data()["bhandari_tooth_factor"]
    if str(teeth) not in table:
        raise DesignError("z1", f"Bhandari Table 14.5 values known for {', '.join(table)} teeth, "
                          f"got {teeth}")
    return float(table[str(teeth)])


def strand_factor(strands: int) -> float:
    """Multiple-strand factor (capacity of n strands / one strand), Shigley Table 17-23:
    1, 1.7, 2.5, 3.3, 3.9, 4.6, 6.0 for 1, 2, 3, 4, 5, 6, 8 strands (Tsubaki Table 4.1 agrees)."""
    table = data()["strand_factor"]
    if str(strands) not in table:
        raise DesignError("chain.strands",
                          f"strand factor known for {', '.join(table)} strands, got {strands!r}")
    return float(table[str(strands)])


def link_plate_rating_hp(teeth: float, speed_rpm: float | np.ndarray, pitch_in: float,
                         light: bool = False) -> float | np.ndarray:
    """Link-plate fatigue rating H1 = 0.004·N1^1.08·n1^0.9·p^(3 − 0.07p) [hp] per strand.

    N1 teeth of the small sprocket, n1 [rev/min], p [in]; constant 0.0022 for the
    lightweight ANSI 41 chain. Source: Shigley Eq. 17-32 (ACA).
    """
    c = data()["aca"]["link_plate_constant_light" if light else "link_plate_constant"]
    return c * teeth**1.08 * np.asarray(speed_rpm, dtype=float) ** 0.9 * pitch_in ** (
        3.0 - 0.07 * pitch_in)


def roller_bush_rating_hp(teeth: float, speed_rpm: float | np.ndarray, pitch_in: float,
                          kr: float, links: float = 100.0, life_h: float = 15000.0
                          ) -> float | np.ndarray:
    """Roller–bush impact rating H2 = 1000·Kr·N1^1.5·p^0.8/n1^1.5·(Lp/100)^0.4·(15000/h)^0.4 [hp].

    Source: Shigley Eq. 17-33, with the length/life correction of Eq. 17-39/17-40
    (H2^2.5·h/Lp = const). The digitised Eq. 17-39 shows n1^1; at the rating basis it must
    reduce to Eq. 17-33, so n1^1.5 is used.
    """
    n1 = np.asarray(speed_rpm, dtype=float)
    base = 1000.0 * kr * teeth**1.5 * pitch_in**0.8 / n1**1.5
    return base * (links / 100.0) ** 0.4 * (15000.0 / life_h) ** 0.4


def roller_constant(chain: ChainSpec) -> float:
    """Kr of Eq. 17-33: 29 for ANSI 25 and 35, 3.4 for ANSI 41, 17 otherwise (Shigley, MecaPy).

    Chains without an ANSI number: 29 below 1/2 in pitch, 17 from 1/2 in (by pitch class).
    """
    aca = data()["aca"]
    number = (chain.ansi or "").split("-")[0].rstrip("H")  # heavy series: same constants
    if number in {"25", "35"}:
        return float(aca["kr_small"])
    if number == "41":
        return float(aca["kr_light"])
    if not number and chain.pitch < 0.5 * INCH - 1e-9:
        return float(aca["kr_small"])
    return float(aca["kr_standard"])


def aca_rating(chain: ChainSpec, teeth: int, speed: float, *, links: float = 100.0,
               life_h: float = 15000.0) -> tuple[float, str]:
    """Single-strand ACA rating [W] at the small-sprocket speed [rad/s] and the governing envelope.

    min(H1, H2) (Shigley Eq. 17-32/17-33) with the tooth count in the formulas (so no separate
    tooth correction is needed); returns (rating, "link-plate fatigue" | "roller-bush impact").
    """
    p_in = chain.pitch / INCH
    n1 = speed * RAD_S_TO_RPM
    light = (chain.ansi or "").split("-")[0] == "41"
    h1 = float(link_plate_rating_hp(teeth, n1, p_in, light))
    h2 = float(roller_bush_rating_hp(teeth, n1, p_in, roller_constant(chain), links, life_h))
    if h1 <= h2:
        return h1 * HP, "link-plate fatigue"
    return h2 * HP, "roller-bush impact"


def galling_speed_limit(pitch: float, teeth: int, tension: float) -> float:
    """Highest small-sprocket speed [rad/s] before pin–bush galling (Shigley §17-5):

    n1 ≤ 1000·[82.5/(7.95^p·1.0278^N1·1.323^(F/1000))]^(1/(1.59·log10 p + 1.873)) rev/min,
    p [in], F chain tension [lbf] (log base 10 assumed — unconfirmed in the source).
    """
    p = pitch / INCH
    f = tension / LBF
    # in logarithms: 1.323^(F/1000) overflows a float for F above about 2.5e6 lbf
    log_ratio = (math.log(82.5) - p * math.log(7.95) - teeth * math.log(1.0278)
                 - f / 1000.0 * math.log(1.323))
    exponent = log_ratio / (1.59 * math.log10(p) + 1.873)
    return 1000.0 * math.exp(min(exponent, 700.0)) / RAD_S_TO_RPM


def lubrication_type(chain: ChainSpec, speed: float) -> Lubrication | None:
    """ANSI lubrication type for chain speed v [m/s]: "A" manual/drip, "B" bath/disc, "C" stream.

    Limits per ANSI chain number from McGuire Bearing's table ([MG]); None when the chain has
    no tabulated ANSI number (40…160). The ISO 10823 lubrication chart was not available.
    """
    number = (chain.ansi or "").split("-")[0].rstrip("H")
    table = data()["lubrication"]
    if number not in table:
        return None
    a_max, b_max = table[number]
    if speed <= a_max:
        return "A"
    if speed <= b_max:
        return "B"
    return "C"


def required_rating(power: float, service_factor: float = 1.0, design_factor: float = 1.0,
                    tooth_factor: float = 1.0, strand_factor: float = 1.0) -> float:
    """Single-strand rating needed [W]: H_tab = n_d·K_s·H_nom/(K1·K2).

    tooth_factor K1 and strand_factor K2 multiply the rating (Shigley Eq. 17-37/17-38;
    Bhandari: kW = P·Ks/(K1·K2) with his K1 = strands, K2 = teeth). For the ISO form
    P_sel = P·f1·f2 pass tooth_factor = 1/f2.
    """
    return power * service_factor * design_factor / (tooth_factor * strand_factor)


def textbook_rating(source: str, chain: str, speed_rpm: float) -> float | None:
    """Single-strand rating [W] printed in a textbook table (``textbook_ratings.csv``), or None.

    source : e.g. "Bhandari table 14.2"; chain : ISO number, e.g. "16A"; speed_rpm : n1.
    Only the values quoted by published worked examples are stored.
    """
    for src, name, rpm, kw in _textbook_rows():
        if src == source and name == chain and math.isclose(rpm, speed_rpm):
            return kw * 1000.0
    return None


@dataclass(frozen=True, slots=True)
class RatingCheck:
    """Result of the rating check of one chain (SI units).

    rated_power [W] of the whole chain (single-strand rating × strand factor);
    required_power [W] = P·K_s·n_d/K_tooth; margin = rated/required − 1;
    governing: the envelope that limits it; lubrication: ANSI type or None;
    galling_limit [rad/s] of the small sprocket.
    """

    rated_power: float
    required_power: float
    margin: float
    governing: str
    lubrication: str | None
    galling_limit: float

    @property
    def feasible(self) -> bool:
        """True when the chain carries the design power (margin ≥ 0)."""
        return self.margin >= -1e-12


def check_rating(chain: ChainSpec, power: float, teeth: int, speed: float, *,
                 service_factor: float = 1.0, design_factor: float = 1.0,
                 links: float = 100.0, life_h: float = 15000.0) -> RatingCheck:
    """ACA rating check of ``chain`` (all strands) for power [W] at speed [rad/s], z1 = teeth.

    The tooth count enters the ACA formulas directly; the strand factor is Shigley Table 17-23.
    When the galling limit (Shigley §17-5) is below the speed, the lubrication type becomes
    C′ ("submit to the manufacturer") and the galling limit governs.
    """
    single, governing = aca_rating(chain, teeth, speed, links=links, life_h=life_h)
    rated = single * strand_factor(chain.strands)
    required = required_rating(power, service_factor, design_factor)
    v = teeth * chain.pitch * speed / (2.0 * math.pi)
    tension = power * service_factor * design_factor / v
    galling = galling_speed_limit(chain.pitch, teeth, tension / chain.strands)
    lube: str | None = lubrication_type(chain, v)
    margin = rated / required - 1.0
    if speed > galling:
        lube, governing = "C'", "pin-bush galling"
        margin = min(margin, galling / speed - 1.0)
    return RatingCheck(rated, required, margin, governing, lube, galling)
