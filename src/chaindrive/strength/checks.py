"""The checks a chain selection makes, one pure function each.

Every function takes numbers (SI) and returns a :class:`Check`: the value, the limit it is
held to, the verdict — ``"pass"``, ``"fail"`` or ``"cannot be verified"`` (the rule has no
limit for this chain or operating point; a selection treats it as a failure and says so) —
and the source of the rule as a key of ``docs/references.md``. The functions know nothing
about catalogues or drives, so the analysis can list the same checks for the chain it
analyses (``Analysis.checks()``) as the selection made for every candidate.

Rules and their sources
-----------------------
* hinge pressure p = Kэ·F_t/A ≤ [p] (Russian method, GOST chains) [ChainDesignRU, Table 2A];
* static safety s = Q/(kд·F_t + F_0 + F_v) ≥ [s]: [s] by pitch and speed for GOST chains
  [TrinhChat2006, Table 5.10]; for rating-method (ISO/ANSI) chains the working load at most
  1/6 of the breaking load, s ≥ 6 [DiamondChain, §working load];
* speed limit: small-sprocket speed ≤ n1 max by pitch [TrinhChat2006, Table 5.8] (GOST), the
  pin–bush galling limit [Shigley2015, §17-5] (ACA), the manufacturer's chain speed limit
  (polymer chains);
* power rating: rated power ≥ design power (ACA, European table, see
  :mod:`chaindrive.strength.ratings`);
* wear life ≥ the rating basis, 15 000 h to 3 % elongation [Shigley2015, Eq. 17-40];
* teeth in mesh ≥ 3 on every sprocket, idlers included [Renold-DG, idler sprockets];
  wrap ≥ 120° on the driver and the small loaded sprocket [Mott2014, ch. 7];
* longest free span ≤ 80 pitches: the centre-distance factor kа of the Kэ method is given
  up to a = 80 t [TrinhChat2006, Table 5.2] — longer spans are outside every rule found;
* polymer chains: chain pull ≤ the maintenance-free allowable load of the chain
  (catalogue ``allowable_load``).

References
----------
Each rule above names its source; see also ``docs/selection.md``.
"""

from __future__ import annotations

import math

from chaindrive.checks import FAIL, PASS, UNVERIFIED, Check, Status, judged, verdict, worst
from chaindrive.errors import Quantity
from chaindrive.strength.ke_method import MPA
from chaindrive.strength.wear import BASIS_LIFE_H
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["BASIS_LIFE_H", "FAIL", "MAX_SPAN_PITCHES", "MIN_SAFETY_RATED", "MIN_TEETH_IN_MESH",
           "MIN_WRAP", "PASS", "UNVERIFIED", "Check", "Status", "allowable_load_check",
           "hinge_pressure_check", "power_rating_check", "span_length_check",
           "speed_limit_check", "static_safety_check", "teeth_in_mesh_check", "verdict",
           "wear_life_check", "worst", "wrap_check"]

#: Least teeth in mesh on any sprocket, idlers included [Renold-DG].
MIN_TEETH_IN_MESH = 3.0
#: Least wrap angle on the driver and the small loaded sprocket [rad] (120°) [Mott2014].
MIN_WRAP = math.radians(120.0)
#: Least static safety factor of a chain checked by its power rating (working load ≤ 1/6 of
#: the minimum ultimate tensile strength) [DiamondChain].
MIN_SAFETY_RATED = 6.0
#: Longest span between two sprockets, in pitches (kа given up to a = 80 t) [TrinhChat2006].
MAX_SPAN_PITCHES = 80.0


def hinge_pressure_check(subject: str, pressure: float, allowable: float | None,
                         source: str = "[ChainDesignRU, Table 2A]", note: str = "") -> Check:
    """Hinge pressure p ≤ [p].

    Parameters
    ----------
    subject : str
        The chain.
    pressure : float
        p = Kэ·F_t/A [Pa].
    allowable : float or None
        [p] [Pa]; None (outside the table) → "cannot be verified".
    source : str
        The rule's reference key.
    note : str
        What the verdict rests on.

    Returns
    -------
    Check
        Shown in MPa.

    References
    ----------
    [ChainDesignRU, Table 2A].
    """
    if allowable is None:
        note = note or "no [p] in the table for this pitch and speed"
    return judged("hinge pressure", subject, pressure, allowable, "max", source, "MPa",
                  1 / MPA, note, "chain")


def static_safety_check(subject: str, safety: float, allowable: float | None,
                        source: str, note: str = "") -> Check:
    """Static safety s ≥ [s].

    Parameters
    ----------
    subject : str
        The chain.
    safety : float
        s [-].
    allowable : float or None
        [s] [-]; None → "cannot be verified".
    source : str
        The rule's reference key.
    note : str
        What the verdict rests on.

    Returns
    -------
    Check
        The check.

    References
    ----------
    [TrinhChat2006, Table 5.10]; [DiamondChain].
    """
    if allowable is None:
        note = note or "no [s] in the table for this pitch and speed"
    return judged("static safety", subject, safety, allowable, "min", source, note=note,
                  part="chain")


def speed_limit_check(subject: str, speed: float, max_speed: float | None, source: str,
                      note: str = "", *, linear: bool = False) -> Check:
    """Speed ≤ its limit.

    Parameters
    ----------
    subject : str
        The chain.
    speed : float
        Small-sprocket speed [rad/s] (shown in rpm) or, with ``linear``, chain speed [m/s].
    max_speed : float or None
        The limit [rad/s or m/s]; None → "cannot be verified".
    source : str
        The rule's reference key.
    note : str
        What the verdict rests on.
    linear : bool
        True for a chain speed.

    Returns
    -------
    Check
        The check.

    References
    ----------
    [TrinhChat2006, Table 5.8]; [Shigley2015, §17-5].
    """
    if max_speed is None:
        note = note or "no speed limit known for this pitch"
    unit, scale = ("m/s", 1.0) if linear else ("rpm", RPM_PER_RAD_S)
    return judged("speed limit", subject, speed, max_speed, "max", source, unit, scale, note,
                  "chain")


def power_rating_check(subject: str, rated: float | None, design: float, source: str,
                       note: str = "", *, note_quantities: tuple[Quantity, ...] = ()) -> Check:
    """Rated power of the chain ≥ the design power P·K_s·n_d.

    Parameters
    ----------
    subject : str
        The chain.
    rated : float or None
        Rated power of the whole chain [W]; None → "cannot be verified".
    design : float
        Design power [W].
    source : str
        The rule's reference key.
    note : str
        What the verdict rests on.
    note_quantities : tuple of Quantity
        The numbers with units ``note`` writes (SI; :class:`chaindrive.checks.Check`).

    Returns
    -------
    Check
        Shown in kW.

    References
    ----------
    [Shigley2015, §17-5].
    """
    if rated is None:
        note = note or "no rating for this chain at this speed"
    return judged("power rating", subject, rated, design, "min", source, "kW", 1e-3, note,
                  "chain", note_quantities=note_quantities)


def wear_life_check(subject: str, life_h: float | None, required_h: float = BASIS_LIFE_H,
                    source: str = "[Shigley2015, Eq. 17-40]", note: str = "") -> Check:
    """Wear life to the permitted elongation ≥ the required life.

    Parameters
    ----------
    subject : str
        The chain.
    life_h : float or None
        Wear life [h]; None → "cannot be verified".
    required_h : float
        Required life [h] (default the 15 000 h rating basis).
    source : str
        The rule's reference key.
    note : str
        What the verdict rests on.

    Returns
    -------
    Check
        The check.

    References
    ----------
    [Shigley2015, Eq. 17-40].
    """
    if life_h is None:
        note = note or "no wear-life model for this chain"
    return judged("wear life", subject, life_h, required_h, "min", source, "h", note=note,
                  part="chain")


def teeth_in_mesh_check(sprocket: str, teeth_in_mesh: float, role: str) -> Check:
    """At least 3 teeth in mesh on every sprocket — driver, driven and idler alike: fewer
    lets the chain jump or climb the teeth under load.

    Parameters
    ----------
    sprocket : str
        The sprocket.
    teeth_in_mesh : float
        z·θ/2π [-].
    role : str
        "driver", "driven" or "idler" (the note).

    Returns
    -------
    Check
        Keyed ``teeth_in_mesh[<sprocket>]``.

    References
    ----------
    [Renold-DG].
    """
    return judged("teeth in mesh", sprocket, teeth_in_mesh, MIN_TEETH_IN_MESH, "min",
                  "[Renold-DG, idler sprockets]", "teeth", note=role, part="geometry",
                  item=sprocket)


def wrap_check(sprocket: str, wrap: float, role: str, small: bool = False) -> Check:
    """Wrap angle [rad] ≥ 120° on the driver and on the small loaded sprocket (the one the
    rating refers to) [Mott2014, ch. 7]; other sprockets — the driven sprockets of a
    serpentine contour, idlers — are held to the teeth-in-mesh rule only (the result then
    passes with no limit).

    Parameters
    ----------
    sprocket : str
        The sprocket.
    wrap : float
        Wrap angle [rad] (shown in degrees).
    role : str
        "driver", "driven" or "idler".
    small : bool
        True for the small loaded sprocket.

    Returns
    -------
    Check
        Keyed ``wrap[<sprocket>]``.

    References
    ----------
    [Mott2014, ch. 7].
    """
    limit = MIN_WRAP if role == "driver" or small else 0.0
    note = ("driver" if role == "driver" else "small loaded sprocket") if limit else (
        f"{role}: held to the teeth-in-mesh rule only")
    return judged("wrap", sprocket, wrap, limit, "min", "[Mott2014, ch. 7]", "deg",
                  180.0 / math.pi, note, part="geometry", item=sprocket)


def span_length_check(subject: str, span_pitches: float,
                      limit: float = MAX_SPAN_PITCHES) -> Check:
    """Longest free span ≤ 80 pitches (the kа factor covers a ≤ 80 t): a longer span needs
    guides or intermediate sprockets (whip, sag).

    Parameters
    ----------
    subject : str
        The span.
    span_pitches : float
        Its length [pitches].
    limit : float
        The longest allowed [pitches].

    Returns
    -------
    Check
        The check.

    References
    ----------
    [TrinhChat2006, Table 5.2].
    """
    return judged("span length", subject, span_pitches, limit, "max",
                  "[TrinhChat2006, Table 5.2]", "pitches", part="geometry")


def allowable_load_check(subject: str, tension: float, allowable: float | None,
                         source: str, note: str = "") -> Check:
    """Chain pull ≤ the manufacturer's allowable (working) load.

    Parameters
    ----------
    subject : str
        The chain.
    tension : float
        Chain pull [N].
    allowable : float or None
        Allowable load [N]; None → "cannot be verified".
    source : str
        The catalogue row.
    note : str
        What the verdict rests on.

    Returns
    -------
    Check
        Shown in kN.
    """
    if allowable is None:
        note = note or "the catalogue gives no allowable load for this chain"
    return judged("allowable load", subject, tension, allowable, "max", source, "kN", 1e-3,
                  note, "chain")
