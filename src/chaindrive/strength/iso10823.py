"""Power rating by the ACA formulas (ANSI B29.1 rating basis [Shigley2015, §17-5]), and the
ISO 10823-style correction of the power to select with.

Despite the module's name no ISO 10823 rating chart is implemented here: the ratings are the
ACA envelopes, made for ANSI proportions; :mod:`chaindrive.strength.ratings` chooses the
method that fits each chain (ACA for ISO 606 A / ANSI, the B-series table for B chains).

Procedure [ISO10823], [GBT18150]: correct the transmitted power to the rating basis,
P_sel = P·K_s·n_d / (K_tooth·K_strand), and choose the smallest pitch whose single-strand
rating at the small-sprocket speed is at least P_sel. Ratings come from the ACA envelopes
(link-plate fatigue H1, roller–bush impact H2 [Shigley2015, Eq. 17-32/17-33]) or from a
textbook table (:func:`textbook_rating`). The rating basis is 15 000 h to 3 % elongation,
100 pitches, two 17-tooth sprockets, single strand, service factor 1 [Shigley2015, §17-5].

Data: ``strength/data/iso10823.toml`` and ``textbook_ratings.csv`` (sources in their headers).
The ISO 10823 application-factor table was not available: :func:`service_factor` uses the
values of [Tsubaki, Table 4.2] (same structure), not the ISO table.
"""

from __future__ import annotations

import csv
import io
import math
import tomllib
from functools import cache
from importlib import resources
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray, float_or_array
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.model import ChainSpec
from chaindrive.units import RPM_PER_RAD_S

HP = 745.699872  # 1 hp [W]
INCH = 0.0254  # [m]
LBF = 4.4482216152605  # [N]
FPM = 0.00508  # 1 ft/min in m/s

Lubrication = Literal["A", "B", "C", "C'"]

__all__ = ["FPM", "HP", "INCH", "LBF", "aca_rating", "data", "galling_speed_limit",
           "link_plate_rating_hp", "lubrication_type", "required_rating", "roller_bush_rating_hp",
           "roller_constant", "service_factor", "strand_factor", "textbook_rating",
           "tooth_correction_aca", "tooth_factor_bhandari", "tooth_factor_iso"]


@cache
def data() -> dict[str, Any]:
    """The ISO 10823 / ACA tables (``data/iso10823.toml``, read once).

    Returns
    -------
    dict
        The parsed tables, each with its source in the file's header.
    """
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

    Parameters
    ----------
    load : str
        "smooth", "moderate_shock" or "heavy_shock".
    driver : str
        "electric_motor", "ic_engine_hydraulic" or "ic_engine_mechanical".

    Returns
    -------
    float
        K_s [-].

    References
    ----------
    [Tsubaki, Table 4.2] ([Mott2014, Table 7-17] agrees) — not the ISO 10823 table, which
    was not available.
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


def tooth_factor_iso(teeth: ArrayLike) -> FloatOrArray:
    """ISO 10823 tooth factor f2 = (19/z1)^1.08; multiplies the power to select with.

    A simpler 19/z1 also circulates; the exponent form is used here.

    Parameters
    ----------
    teeth : int or array_like
        z1 [-].

    Returns
    -------
    float or numpy.ndarray
        f2 [-].

    References
    ----------
    [ISO10823] as quoted by [GBT18150].
    """
    return float_or_array((19.0 / np.asarray(teeth, dtype=float)) ** 1.08)


def tooth_correction_aca(teeth: ArrayLike, region: str = "plate") -> FloatOrArray:
    """ACA tooth correction K1 (multiplies the 17-tooth rating).

    Parameters
    ----------
    teeth : int or array_like
        N1 [-].
    region : str
        "plate" (pre-extreme, link-plate fatigue): K1 = (N1/17)^1.08; "impact"
        (post-extreme, roller–bush impact): K1 = (N1/17)^1.5.

    Returns
    -------
    float or numpy.ndarray
        K1 [-].

    References
    ----------
    [Shigley2015, Table 17-22].
    """
    exponent = {"plate": 1.08, "impact": 1.5}.get(region)
    if exponent is None:
        raise DesignError("region", f"must be 'plate' or 'impact', got {region!r}")
    return float_or_array((np.asarray(teeth, dtype=float) / 17.0) ** exponent)


def tooth_factor_bhandari(teeth: int) -> float:
    """Tooth correction factor K2 (values for 17, 19, 21 teeth only).

    Parameters
    ----------
    teeth : int
        z1 [-].

    Returns
    -------
    float
        K2 [-].

    References
    ----------
    [Bhandari2010, Table 14.5].
    """
    table = data()["bhandari_tooth_factor"]
    if str(teeth) not in table:
        raise DesignError("z1", f"[Bhandari2010, Table 14.5] gives values for {', '.join(table)} teeth, "
                          f"got {teeth}")
    return float(table[str(teeth)])


def strand_factor(strands: int) -> float:
    """Multiple-strand factor of a power rating (capacity of n strands / one strand).

    Not the row factor of the bearing area (:func:`chaindrive.catalog.row_factor`).

    Parameters
    ----------
    strands : int
        n [-].

    Returns
    -------
    float
        1, 1.7, 2.5, 3.3, 3.9, 4.6, 6.0 for 1, 2, 3, 4, 5, 6, 8 strands [-].

    References
    ----------
    [Shigley2015, Table 17-23] ([Tsubaki, Table 4.1] agrees).
    """
    table = data()["strand_factor"]
    if str(strands) not in table:
        raise DesignError("chain.strands",
                          f"strand factor known for {', '.join(table)} strands, got {strands!r}")
    return float(table[str(strands)])


def link_plate_rating_hp(teeth: float, speed_rpm: ArrayLike, pitch_in: float,
                         light: bool = False) -> FloatOrArray:
    """Link-plate fatigue rating H1 = 0.004·N1^1.08·n1^0.9·p^(3 − 0.07p) per strand.

    Parameters
    ----------
    teeth : float
        N1, teeth of the small sprocket [-].
    speed_rpm : float or array_like
        n1 [rev/min].
    pitch_in : float
        p [in].
    light : bool
        The lightweight ANSI 41 chain (constant 0.0022).

    Returns
    -------
    float or numpy.ndarray
        H1 [hp].

    References
    ----------
    [Shigley2015, Eq. 17-32].
    """
    c = float(data()["aca"]["link_plate_constant_light" if light else "link_plate_constant"])
    return float_or_array(c * teeth**1.08 * np.asarray(speed_rpm, dtype=float) ** 0.9
                          * pitch_in ** (3.0 - 0.07 * pitch_in))


@shared_parameters
def roller_bush_rating_hp(teeth: float, speed_rpm: ArrayLike, pitch_in: float,
                          kr: float, links: float = 100.0, life_h: float = 15000.0
                          ) -> FloatOrArray:
    """Roller–bush impact rating H2 = 1000·Kr·N1^1.5·p^0.8/n1^1.5·(Lp/100)^0.4·(15000/h)^0.4.

    The length/life correction is that of Eq. 17-39/17-40 (H2^2.5·h/Lp = const). The
    digitised Eq. 17-39 shows n1^1; at the rating basis it must reduce to Eq. 17-33, so
    n1^1.5 is used.

    Parameters
    ----------
    teeth : float
        N1 [-].
    speed_rpm : float or array_like
        n1 [rev/min].
    pitch_in : float
        p [in].
    kr : float
        Roller constant K_r [-] (:func:`roller_constant`).
    %(links)s
    life_h : float
        Life h [h].

    Returns
    -------
    float or numpy.ndarray
        H2 [hp].

    References
    ----------
    [Shigley2015, Eq. 17-33, 17-39, 17-40].
    """
    n1 = np.asarray(speed_rpm, dtype=float)
    base = 1000.0 * kr * teeth**1.5 * pitch_in**0.8 / n1**1.5
    return float_or_array(base * (links / 100.0) ** 0.4 * (15000.0 / life_h) ** 0.4)


def roller_constant(chain: ChainSpec) -> float:
    """Roller constant K_r of Eq. 17-33.

    Parameters
    ----------
    chain : ChainSpec
        The chain (its ANSI number, else its pitch).

    Returns
    -------
    float
        29 for ANSI 25 and 35, 3.4 for ANSI 41, 17 otherwise [-]; chains without an ANSI
        number: 29 below 1/2 in pitch, 17 from 1/2 in.

    References
    ----------
    [Shigley2015, Eq. 17-33].
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


@shared_parameters
def aca_rating(chain: ChainSpec, teeth: int, speed: float, *, links: float = 100.0,
               life_h: float = 15000.0) -> tuple[float, str]:
    """Single-strand ACA rating min(H1, H2) and the governing envelope.

    The tooth count enters the formulas, so no separate tooth correction is needed.

    Parameters
    ----------
    %(chain)s
    %(small_sprocket)s
    speed : float
        Speed of the small sprocket [rad/s].
    links : float
        Chain length [pitches].
    life_h : float
        Life [h].

    Returns
    -------
    tuple of (float, str)
        Rating [W] and "link-plate fatigue" or "roller-bush impact".

    References
    ----------
    [Shigley2015, Eq. 17-32/17-33].
    """
    p_in = chain.pitch / INCH
    n1 = speed * RPM_PER_RAD_S
    light = (chain.ansi or "").split("-")[0] == "41"
    h1 = float(link_plate_rating_hp(teeth, n1, p_in, light))
    h2 = float(roller_bush_rating_hp(teeth, n1, p_in, roller_constant(chain), links, life_h))
    if h1 <= h2:
        return h1 * HP, "link-plate fatigue"
    return h2 * HP, "roller-bush impact"


def galling_speed_limit(pitch: float, teeth: int, tension: float) -> float:
    """Highest small-sprocket speed before pin–bush galling
    n1 ≤ 1000·[82.5/(7.95^p·1.0278^N1·1.323^(F/1000))]^(1/(1.59·log10 p + 1.873)) rev/min
    (p in inches, F in lbf; log base 10 assumed — unconfirmed in the source).

    Parameters
    ----------
    pitch : float
        Chain pitch [m].
    teeth : int
        N1 [-].
    tension : float
        Chain tension F [N].

    Returns
    -------
    float
        The limit [rad/s].

    References
    ----------
    [Shigley2015, §17-5].
    """
    p = pitch / INCH
    f = tension / LBF
    # in logarithms: 1.323^(F/1000) overflows a float for F above about 2.5e6 lbf
    log_ratio = (math.log(82.5) - p * math.log(7.95) - teeth * math.log(1.0278)
                 - f / 1000.0 * math.log(1.323))
    exponent = log_ratio / (1.59 * math.log10(p) + 1.873)
    return float(1000.0 * math.exp(min(exponent, 700.0)) / RPM_PER_RAD_S)


def lubrication_type(chain: ChainSpec, speed: float) -> Lubrication | None:
    """ANSI lubrication type at a chain speed: "A" manual/drip, "B" bath/disc, "C" stream.

    The ISO 10823 lubrication chart was not available.

    Parameters
    ----------
    chain : ChainSpec
        The chain (its ANSI number).
    speed : float
        Chain speed v [m/s].

    Returns
    -------
    str or None
        "A", "B" or "C"; None when the chain has no tabulated ANSI number (40…160).

    References
    ----------
    [McGuireLube].
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
    """Single-strand rating needed H_tab = n_d·K_s·H_nom/(K1·K2).

    For the ISO form P_sel = P·f1·f2 pass ``tooth_factor`` = 1/f2.

    Parameters
    ----------
    power : float
        Transmitted power H_nom [W].
    service_factor : float
        K_s [-].
    design_factor : float
        n_d [-].
    tooth_factor : float
        K1, multiplies the rating [-].
    strand_factor : float
        K2, multiplies the rating [-].

    Returns
    -------
    float
        H_tab [W].

    References
    ----------
    [Shigley2015, §17-5]; [Bhandari2010, §14] (kW = P·Ks/(K1·K2), his K1 = strands,
    K2 = teeth).
    """
    return power * service_factor * design_factor / (tooth_factor * strand_factor)


def textbook_rating(source: str, chain: str, speed_rpm: float) -> float | None:
    """Single-strand rating printed in a textbook table (``textbook_ratings.csv``).

    Only the values quoted by published worked examples are stored.

    Parameters
    ----------
    source : str
        The table, e.g. "Bhandari table 14.2".
    chain : str
        ISO chain number, e.g. "16A".
    speed_rpm : float
        n1 [rev/min].

    Returns
    -------
    float or None
        The rating [W], or None when the table has no such value.

    References
    ----------
    [Bhandari2010, Table 14.2]; [Jindal2010, Table 30-8].
    """
    for src, name, rpm, kw in _textbook_rows():
        if src == source and name == chain and math.isclose(rpm, speed_rpm):
            return kw * 1000.0
    return None
