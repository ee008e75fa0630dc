"""The checks a chain selection makes: the chain's rules a table (:data:`CHAIN_RULES`, judged
by :func:`chain_check`), the layout's one pure function each.

Every check takes numbers (SI) and returns a :class:`Check`: the value, the limit it is
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
* impacts per second i = z1·n1/(15·Lt) ≤ [i] by pitch (GOST chains) [TrinhChat2006, Table 5.9];
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
from dataclasses import dataclass

from chaindrive.checks import FAIL, PASS, UNVERIFIED, Check, Kind, Status, judged, verdict, worst
from chaindrive.errors import Quantity
from chaindrive.strength.ke_method import MPA
from chaindrive.strength.wear import BASIS_LIFE_H
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["BASIS_LIFE_H", "CHAIN_RULES", "FAIL", "MAX_SPAN_PITCHES",
           "MIN_SAFETY_RATED", "MIN_TEETH_IN_MESH", "MIN_WRAP", "PASS", "UNVERIFIED", "ChainRule",
           "Check", "Status", "chain_check", "span_length_check", "teeth_in_mesh_check",
           "verdict", "worst", "wrap_check"]

#: Least teeth in mesh on any sprocket, idlers included [Renold-DG].
MIN_TEETH_IN_MESH = 3.0
#: Least wrap angle on the driver and the small loaded sprocket [rad] (120°) [Mott2014].
MIN_WRAP = math.radians(120.0)
#: Least static safety factor of a chain checked by its power rating (working load ≤ 1/6 of
#: the minimum ultimate tensile strength) [DiamondChain].
MIN_SAFETY_RATED = 6.0
#: Longest span between two sprockets, in pitches (kа given up to a = 80 t) [TrinhChat2006].
MAX_SPAN_PITCHES = 80.0


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


# --- the rules of the chain: one table, one function ---------------------------------------


@dataclass(frozen=True, slots=True)
class ChainRule:
    """How one rule of the chain is judged and shown (the rules: the module docstring).

    Parameters
    ----------
    kind : {"max", "min"}
        Whether the value is held below or above the limit.
    unit : str
        The unit the check is shown in.
    scale : float
        Factor from SI to ``unit`` [unit/SI].
    missing : str
        The note when the value or the limit is unknown ("cannot be verified").
    source : str
        The reference key the rule is known by ("" where the caller names the source: the
        table, the catalogue row or the rating used).
    """

    kind: Kind
    unit: str
    scale: float
    missing: str
    source: str = ""


#: The rules of the chain itself, by the name of their check. Values [SI]: hinge pressure
#: p = Kэ·F_t/A [Pa]; static safety s [-]; speed limit, small-sprocket speed [rad/s] (or the
#: chain speed [m/s]); power rating, rated power of the whole chain ≥ design power P·K_s·n_d
#: [W]; wear life to the permitted elongation [h]; impacts per second i = z1·n1/(15·Lt)
#: [1/s]; allowable load, chain pull [N].
CHAIN_RULES: dict[str, ChainRule] = {
    "hinge pressure": ChainRule("max", "MPa", 1 / MPA,
                                "no [p] in the table for this pitch and speed",
                                "[ChainDesignRU, Table 2A]"),
    "static safety": ChainRule("min", "", 1.0, "no [s] in the table for this pitch and speed"),
    "speed limit": ChainRule("max", "rpm", RPM_PER_RAD_S, "no speed limit known for this pitch"),
    "power rating": ChainRule("min", "kW", 1e-3, "no rating for this chain at this speed"),
    "wear life": ChainRule("min", "h", 1.0, "no wear-life model for this chain",
                           "[Shigley2015, Eq. 17-40]"),
    "impacts per second": ChainRule("max", "1/s", 1.0, "no [i] for this pitch",
                                    "[TrinhChat2006, Table 5.9]"),
    "allowable load": ChainRule("max", "kN", 1e-3,
                                "the catalogue gives no allowable load for this chain"),
}


def chain_check(rule: str, subject: str, value: float | None, limit: float | None,
                source: str = "", note: str = "", *, linear: bool = False,
                note_quantities: tuple[Quantity, ...] = ()) -> Check:
    """The chain's ``value`` held to ``limit`` by one rule of :data:`CHAIN_RULES`.

    Parameters
    ----------
    rule : str
        A name of :data:`CHAIN_RULES`.
    subject : str
        The chain.
    value, limit : float or None
        The design's value and the limit it is held to [SI, as the rule says]; None (no
        rating, no table entry) → "cannot be verified" with the rule's note.
    source : str
        The rule's reference key ("": the rule's own).
    note : str
        What the verdict rests on.
    linear : bool
        True for a speed limit on the chain speed [m/s] (shown in m/s).
    note_quantities : tuple of Quantity
        The numbers with units ``note`` writes (SI; :class:`chaindrive.checks.Check`).

    Returns
    -------
    Check
        Shown in the rule's unit.

    References
    ----------
    The rule's source (module docstring).
    """
    r = CHAIN_RULES[rule]
    if value is None or limit is None:
        note = note or r.missing
    unit, scale = ("m/s", 1.0) if linear else (r.unit, r.scale)
    return judged(rule, subject, value, limit, r.kind, source or r.source, unit, scale, note,
                  "chain", note_quantities=note_quantities)
