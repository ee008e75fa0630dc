"""Chain selection: every catalogue chain of the family checked, ranked, the first chosen.

The chain is chosen on its own checks, the layout is judged beside it.

* **Chain checks** — those :func:`chaindrive.strength.drive_checks.chain_checks` makes for
  the chain's method (rating, pressure, speed, static safety, wear life … whatever the
  method checks): a chain that misses one does not do the job.
* **Layout checks** — those :func:`chaindrive.strength.drive_checks.geometry_checks` makes
  (teeth in mesh, wrap, span length): they depend on the chain only through its pitch. A
  chain that passes every chain check and misses a layout check by at most
  :data:`SMALL_LAYOUT_SHORTFALL` of its limit stays selectable; the layout check it misses
  is a finding beside it with the remedy — the teeth or the centre of one sprocket that
  makes it pass, found by laying the changed drive out again
  (:mod:`chaindrive.strength.remedies`). A larger shortfall makes the chain unselectable,
  and the finding names it as passed over, with the same remedies.
* **Dynamic checks** — with ``resonance`` (the analysis gives it), the resonance check of
  each selectable chain's own drive, in rank order: a chain is passed over only when the
  check fails beyond its own uncertainty band (:func:`resonance_verdict`); a check that
  fails inside its band leaves the chain chosen, with a "resonance possible" finding and
  what would settle it.

Candidates are ranked selectable first, then by mass per metre (the lightest chain that
does the job), pitch, strands and the smallest chain margin (largest first); the chosen
chain is the first of that ranking. The others follow from the closest — laid out, fewest
missed checks, the worst check least short — so when nothing is selectable, the selection's
first row is the closest candidate it names, with what it misses.

Each candidate is checked by its own method (:func:`chaindrive.strength.ratings.method_for`):
ACA ratings for ISO 606 A / ANSI, the B-series table for ISO 606 B, the Kэ method for GOST
13568, the allowable load for polymer chains. The geometry of every distinct pitch and roller
is built with the contour solver (take-up and link rounding of the design), so teeth in mesh,
wrap and span length are checked for the candidate as it would be laid out.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import chains
from chaindrive.checks import RESONANCE_BAND_PERCENT
from chaindrive.errors import UNIT_KINDS, DesignError, Quantities, Quantity
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.results import GeometryResult
from chaindrive.kinematics import mean_chain_speed
from chaindrive.model import ChainSpec, Drive
from chaindrive.strength import checks as ck
from chaindrive.strength import ratings
from chaindrive.strength.drive_checks import (
    CheckSettings,
    chain_checks,
    geometry_checks,
    settings_for,
)
from chaindrive.strength.loads import small_sprocket
from chaindrive.strength.lubrication import LubricationAdvice, lubrication_advice
from chaindrive.strength.remedies import Layouts, Remedy, layout_remedies, span_limit_text

__all__ = ["BEYOND_BAND", "INSIDE_BAND", "KE", "LAYOUT_REMEDY", "METHODS", "NAMED_PASSED_OVER",
           "NOT_LAID_OUT", "PASSED_OVER", "RATING", "RESONANCE_PASS", "RESONANCE_POSSIBLE",
           "SMALL_LAYOUT_SHORTFALL", "Candidate", "Finding", "ResonanceProbe",
           "SelectionResult", "banded_resonance_check", "candidate", "estimated_links",
           "family_method", "rank_chains", "rank_key", "resonance_verdict", "select_chain"]

RATING = "rating"
KE = ratings.KE
METHODS = (RATING, KE)
_LEGACY = {"ISO 10823": RATING, "ACA": RATING}


def family_method(standard: str) -> str:
    """The selection method of a chain family (the rating method of each chain is
    :func:`chaindrive.strength.ratings.method_for`).

    Parameters
    ----------
    standard : str
        The family's standard.

    Returns
    -------
    str
        "Kэ" for GOST 13568, "rating" otherwise.
    """
    return KE if standard.upper().startswith("GOST") else RATING


#: The largest shortfall of a layout check (teeth in mesh, wrap, span length) that the
#: selection leaves to the layout, as a fraction of the check's limit [-]: a chain that
#: passes every chain check and misses a layout check by at most this much is chosen, with
#: the layout remedy beside it, instead of a heavier chain. 0.10 because (i) a layout check
#: depends on the chain only through its pitch (sprocket diameters ∝ p, span length in
#: pitches ∝ 1/p) and the smallest step between neighbouring pitches of the catalogue's
#: families is 11 % (ANSI 200H → 240H, 63.5/57.15 mm; ISO 606 and GOST steps are 12.5–33 %),
#: so a shortfall below 10 % is one that the next size clears by its scale alone — a
#: technicality; (ii) it is about one tooth on the sprocket it concerns (one tooth is
#: 1/z ≥ 10 % of the teeth in mesh only below 10 teeth), so the remedy is a small change
#: of the layout (docs/selection.md).
SMALL_LAYOUT_SHORTFALL = 0.10
#: How many lighter chains passed over are named with their findings [-].
NAMED_PASSED_OVER = 3

#: Kinds of :class:`Finding`.
LAYOUT_REMEDY = "layout remedy"
PASSED_OVER = "passed over"
RESONANCE_POSSIBLE = "resonance possible"

#: Verdicts of the resonance check of a candidate's own drive against its band.
RESONANCE_PASS = "pass"
INSIDE_BAND = "inside its band"
BEYOND_BAND = "beyond its band"
NOT_LAID_OUT = "cannot be laid out"


@dataclass(frozen=True, slots=True)
class Finding:
    """A remark of the selection beside its choice: the layout check the chosen chain misses
    and its remedy, a lighter chain passed over and why, or a resonance the uncertainty
    band cannot rule out.

    Parameters
    ----------
    kind : str
        :data:`LAYOUT_REMEDY`, :data:`PASSED_OVER` or :data:`RESONANCE_POSSIBLE`.
    chain : str
        The candidate it is about.
    check : str
        The key of the check (``teeth_in_mesh[T]``, ``resonance_margin`` …).
    shortfall_fraction : float or None
        How far the check's value is short of its limit, −margin [-] (None when it cannot
        be verified).
    text : str
        The finding in words (SI), with the remedies or what would settle it.
    quantities : tuple of Quantity
        The numbers with units ``text`` writes, in order.
    remedies : tuple of Remedy
        The layout changes, each verified by laying the changed drive out again.
    """

    kind: str
    chain: str
    check: str
    shortfall_fraction: float | None
    text: str
    quantities: tuple[Quantity, ...] = ()
    remedies: tuple[Remedy, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (the remedies with their lengths in mm)."""
        return {"kind": self.kind, "chain": self.chain, "check": self.check,
                "shortfall_fraction": self.shortfall_fraction, "text": self.text,
                "quantities": [q.to_dict() for q in self.quantities],
                "remedies": [r.to_dict() for r in self.remedies]}


@dataclass(frozen=True, slots=True)
class ResonanceProbe:
    """The resonance check of a candidate's own drive and its band, as the analysis computes
    them (:meth:`chaindrive.analysis.Analysis._resonance_probe`).

    Parameters
    ----------
    check : Check or None
        The resonance check (None: no working frequency).
    rows : tuple of tuple
        Per resonance row (:attr:`chaindrive.dynamics.frequency.response.Bands.detunings`):
        label, working frequency [Hz], natural frequency [Hz], signed offset [%], lowest and
        highest detuning over the band [%], inside.
    uncertainty : float
        u of the band [-].
    factors : tuple of float
        (low, high) factors of every natural frequency over the band [-].
    assumed : tuple of (str, str)
        The inputs the frequencies rest on that the design does not give, as the analysis's
        warnings name them: what it rests on ("an assumed installed sag") and what to give
        instead ("the installed sag ([chain] sag)").
    """

    check: ck.Check | None
    rows: tuple[tuple[str, float, float, float, float, float, bool], ...]
    uncertainty: float
    factors: tuple[float, float]
    assumed: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class Candidate:
    """One chain checked on the drive.

    The checks are kept by the function that made them: ``chain_checks`` by
    :func:`chaindrive.strength.drive_checks.chain_checks` (strength, speed, life — whatever
    the chain's method checks), ``layout_checks`` by
    :func:`chaindrive.strength.drive_checks.geometry_checks` (or the failed layout), and
    ``dynamic_checks`` by the analysis (the resonance check of the candidate's own drive).

    Parameters
    ----------
    designation : str
        The chain.
    method : str
        Its method ("ACA", "ISO 606 B table", "Kэ", "allowable load").
    pitch : float
        Chain pitch [m].
    strands : int
        Strands [-].
    mass_per_length : float
        [kg/m].
    chain_checks, layout_checks, dynamic_checks : tuple of Check
        The chain's, the layout's and the dynamic checks.
    rating : RatingResult or None
        The rating result.
    lubrication : LubricationAdvice or None
        The lubrication advice (None when the chain could not be laid out).
    notes : tuple of str
        Remarks.
    resonance : str
        The verdict of its resonance check against its band ("" when not tried,
        :data:`RESONANCE_PASS`, :data:`INSIDE_BAND`, :data:`BEYOND_BAND`,
        :data:`NOT_LAID_OUT`).
    findings : tuple of Finding
        The findings of its resonance check.
    geometry : GeometryResult or None
        Its layout (None when it could not be laid out).
    """

    designation: str
    method: str
    pitch: float
    strands: int
    mass_per_length: float
    chain_checks: tuple[ck.Check, ...] = ()
    layout_checks: tuple[ck.Check, ...] = ()
    dynamic_checks: tuple[ck.Check, ...] = ()
    rating: ratings.RatingResult | None = None
    lubrication: LubricationAdvice | None = None
    notes: tuple[str, ...] = field(default=())
    resonance: str = ""
    findings: tuple[Finding, ...] = ()
    geometry: GeometryResult | None = field(default=None, repr=False, compare=False)

    @property
    def checks(self) -> tuple[ck.Check, ...]:
        """Every check: the chain's, the layout's, the dynamic ones."""
        return (*self.chain_checks, *self.layout_checks, *self.dynamic_checks)

    @property
    def passed(self) -> bool:
        """Every check passed."""
        return bool(self.checks) and all(c.passed for c in self.checks)

    @property
    def feasible(self) -> bool:
        """Alias of ``passed``."""
        return self.passed

    @property
    def missed(self) -> tuple[ck.Check, ...]:
        """The checks that did not pass."""
        return tuple(c for c in self.checks if not c.passed)

    @property
    def margin_fraction(self) -> float | None:
        """Margin of the worst check [-] (None when it cannot be verified)."""
        worst = ck.worst(list(self.checks))
        return None if worst is None else worst.margin_fraction

    @property
    def governing(self) -> str:
        """The name of the worst check."""
        worst = ck.worst(list(self.checks))
        return "" if worst is None else worst.name

    @property
    def chain_passed(self) -> bool:
        """Every chain check passed (the chain does the job)."""
        return bool(self.chain_checks) and all(c.passed for c in self.chain_checks)

    @property
    def layout_shortfall(self) -> float:
        """The largest shortfall of a layout check, −margin [-]: 0 when the layout passes,
        infinite when a check cannot be verified or the chain cannot be laid out."""
        missed = [c for c in self.layout_checks if not c.passed]
        margins = [c.margin_fraction for c in missed]
        if any(m is None or c.status == ck.UNVERIFIED for c, m in zip(missed, margins,
                                                                      strict=True)):
            return math.inf
        return max((-m for m in margins if m is not None), default=0.0)

    @property
    def selectable(self) -> bool:
        """The selection may choose it: every chain check passes, no layout check misses by
        more than :data:`SMALL_LAYOUT_SHORTFALL`, and its resonance check (when tried) does
        not fail beyond its band."""
        return (self.chain_passed and self.layout_shortfall <= SMALL_LAYOUT_SHORTFALL
                and self.resonance not in (BEYOND_BAND, NOT_LAID_OUT))

    def to_dict(self, *, with_checks: bool = True) -> dict[str, Any]:
        """JSON-ready dictionary (margin as a fraction).

        Parameters
        ----------
        with_checks : bool
            Include every check and the rating.

        Returns
        -------
        dict
            The candidate.
        """
        shortfall = self.layout_shortfall
        d: dict[str, Any] = {
            "chain": self.designation, "method": self.method, "pitch_mm": self.pitch * 1e3,
            "strands": self.strands, "mass_kg_m": self.mass_per_length, "passed": self.passed,
            "chain_checks_passed": self.chain_passed,
            "layout_shortfall_fraction": None if math.isinf(shortfall) else shortfall,
            "resonance": self.resonance or None, "selectable": self.selectable,
            "margin_fraction": self.margin_fraction, "governing": self.governing,
            "missed": [c.name for c in self.missed],
            "rated_power_w": None if self.rating is None else self.rating.rated_power,
            "lubrication": None if self.lubrication is None else self.lubrication.regime,
            "notes": list(self.notes)}
        if with_checks:
            d["checks"] = [c.to_dict() for c in self.checks]
            d["rating"] = None if self.rating is None else self.rating.to_dict()
        return d


@dataclass(frozen=True, slots=True)
class SelectionResult:
    """Every candidate, ranked by the one rule; the chosen chain first.

    Parameters
    ----------
    candidates : tuple of Candidate
        Ranked (:func:`rank_key`).
    specs : dict of str to ChainSpec
        The chains by designation.
    warnings : tuple of str
        Remarks on the selection.
    findings : tuple of Finding
        Beside the choice: the layout remedies of the chosen chain, a resonance its band
        cannot rule out, the lighter chains passed over and why.
    """

    candidates: tuple[Candidate, ...]
    specs: dict[str, ChainSpec]
    warnings: tuple[str, ...] = ()
    findings: tuple[Finding, ...] = ()

    @property
    def chosen(self) -> Candidate | None:
        """The selected candidate (:attr:`Candidate.selectable`), or None when none is."""
        first = self.candidates[0] if self.candidates else None
        return first if first is not None and first.selectable else None

    @property
    def closest(self) -> Candidate | None:
        """The chosen candidate, or the one whose worst check is least short."""
        if self.chosen is not None or not self.candidates:
            return self.chosen
        return max(self.candidates, key=_closeness)

    @property
    def chain(self) -> ChainSpec:
        """The chosen chain (DesignError naming the closest candidate when none passes)."""
        if self.chosen is None:
            raise DesignError("chain", self.shortfall())
        return self.specs[self.chosen.designation]

    @property
    def method(self) -> str:
        """The method of the chosen (or closest) candidate."""
        best = self.closest
        return "" if best is None else best.method

    def shortfall(self) -> str:
        """One sentence: no chain passes; the closest and the checks it misses."""
        return self.shortfall_with_quantities()[0]

    def shortfall_with_quantities(self) -> tuple[str, tuple[Quantity, ...]]:
        """:meth:`shortfall` and the numbers with units it writes (SI;
        :class:`chaindrive.errors.Quantities`), for a presenter to write in another unit
        system.

        When a chain passes every chain check and only its layout (or a resonance beyond its
        band) keeps it out, the sentence names the lightest such chain and the layout
        remedies of its finding: the layout, not the chain, is to change.

        Returns
        -------
        text : str
            The sentence (SI).
        quantities : tuple of Quantity
            Its numbers with units: the values and limits of the missed checks, then those
            of the notes and remedies it quotes.
        """
        best = self.closest
        if best is None:
            return "no candidate chain", ()
        doing = [c for c in self.candidates if c.chain_passed]
        if doing:
            best = min(doing, key=lambda c: (c.mass_per_length, c.pitch, c.strands))
        q = Quantities()
        parts = [_missed_text(c, q) for c in best.missed]
        missed = "; ".join(text for text, _ in parts)
        quantities = (*q.items, *(n for _, notes in parts for n in notes))
        if not doing:
            return (f"no chain passes every check: the closest is {best.designation} "
                    f"({best.method}), which misses {missed}; try more strands, a larger "
                    "pitch, another series or a change to the layout"), quantities
        finding = next((f for f in self.findings if f.chain == best.designation), None)
        remedy = "" if finding is None or not finding.remedies else (
            "; " + "; or ".join(r.text for r in finding.remedies))
        more = () if finding is None else tuple(q for r in finding.remedies
                                                for q in r.quantities)
        return (f"no chain passes every check: {best.designation} ({best.method}), the "
                f"lightest that passes every chain check, misses {missed} — the layout, not "
                f"the chain, is to change{remedy}"), (*quantities, *more)

    def top(self, n: int) -> tuple[Candidate, ...]:
        """The head of the ranking.

        Parameters
        ----------
        n : int
            How many [-].

        Returns
        -------
        tuple of Candidate
            The first ``n`` (the chosen chain is the first).
        """
        if n < 1:
            raise DesignError("top", f"must be a whole number ≥ 1, got {n!r}")
        return self.candidates[:n]

    def to_dict(self, top: int | None = None) -> dict[str, Any]:
        """JSON-ready dictionary: chosen chain (None when nothing passes), closest candidate
        and what it misses, the findings beside the choice, the ranked candidates.

        Parameters
        ----------
        top : int or None
            Only the first ``top`` candidates (None: all).

        Returns
        -------
        dict
            The selection.
        """
        chosen, closest = self.chosen, self.closest
        shown = self.candidates if top is None else self.top(top)
        shortfall = ("", ()) if chosen is not None else self.shortfall_with_quantities()
        return {"chain": None if chosen is None else chosen.designation,
                "ansi_number": None if chosen is None else self._ansi_twin(chosen.designation),
                "method": self.method,
                "closest": None if closest is None else closest.to_dict(),
                "shortfall": None if chosen is not None else shortfall[0],
                "shortfall_quantities": [q.to_dict() for q in shortfall[1]],
                "small_layout_shortfall_fraction": SMALL_LAYOUT_SHORTFALL,
                "findings": [f.to_dict() for f in self.findings],
                "candidate_count": len(self.candidates),
                "candidates": [{**c.to_dict(with_checks=False),
                                "ansi_number": self._ansi_twin(c.designation)} for c in shown],
                "warnings": list(self.warnings)}

    def _ansi_twin(self, designation: str) -> str | None:
        """:attr:`ChainSpec.ansi_twin` of a candidate (None when it is not in ``specs``)."""
        spec = self.specs.get(designation)
        return None if spec is None else spec.ansi_twin


def _missed_text(c: ck.Check, q: Quantities) -> tuple[str, tuple[Quantity, ...]]:
    """A missed check as the shortfall writes it, value and limit in its unit (recorded in
    ``q`` when they have a kind of quantity), and the quantities of the note it quotes."""
    name = f"{c.name} on {c.item}" if c.item else c.name
    if c.status == ck.UNVERIFIED or c.value is None or c.limit is None:
        return f"{name} ({c.status}: {c.note})", c.note_quantities
    rel = "≤" if c.kind == "max" else "≥"
    kind = UNIT_KINDS.get(c.unit)
    if kind is not None:
        return f"{name} {q(c.value, kind)} (required {rel} {q(c.limit, kind)})", ()
    value, limit = f"{c.value * c.scale:.4g}", f"{c.limit * c.scale:.4g}"
    return f"{name} {value} {c.unit} (required {rel} {limit} {c.unit})".replace("  ", " "), ()


def _closeness(c: Candidate) -> tuple[bool, int, float]:
    """A chain that can be laid out first, then fewer missed checks, then the largest
    (least negative) worst margin."""
    margin = c.margin_fraction
    worst = margin if margin is not None else -math.inf
    laid_out = c.governing != "geometry"
    return laid_out, -len(c.missed), worst


def rank_key(c: Candidate) -> tuple[bool, float, float, float, float, float, float]:
    """The one rule: the selectable chains first (:attr:`Candidate.selectable`: every chain
    check passes, no layout check short by more than :data:`SMALL_LAYOUT_SHORTFALL`, no
    resonance beyond its band), by mass per metre, pitch, strands, larger margin of the chain
    checks; then the others from the closest (:func:`_closeness`: laid out, fewest missed
    checks, least short worst margin), so that when nothing is selectable the closest chain
    heads the table.

    Parameters
    ----------
    c : Candidate
        A candidate.

    Returns
    -------
    tuple
        Its sort key.
    """
    if c.selectable:
        worst = ck.worst(list(c.chain_checks))
        margin = worst.margin_fraction if worst is not None else None
        return (False, c.mass_per_length, c.pitch, float(c.strands),
                -(margin if margin is not None else -math.inf), 0.0, 0.0)
    laid_out, fewer_missed, worst_margin = _closeness(c)
    return (True, -float(laid_out), -float(fewer_missed), -worst_margin, c.mass_per_length,
            c.pitch, float(c.strands))


@shared_parameters
def estimated_links(drive: Drive, pitch: float) -> float:
    """Chain length before the geometry is built: perimeter of the centre polygon / p plus
    the mean tooth count (for two sprockets 2a/p + (z1 + z2)/2, [Shigley2015, Eq. 17-34]
    without the small last term).

    Parameters
    ----------
    %(drive)s
    %(pitch)s

    Returns
    -------
    float
        The estimate [pitches].
    """
    pts = [(s.x, s.y) for s in drive.sprockets]
    perimeter = sum(math.dist(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts)))
    return perimeter / pitch + sum(s.teeth for s in drive.sprockets) / len(pts)


def _catalog(catalog: Sequence[ChainSpec] | None,
             extra_files: Sequence[str]) -> Sequence[ChainSpec]:
    if catalog is not None:
        return catalog
    return chains(extra_files)


def _in_family(c: ChainSpec, standard: str) -> bool:
    if standard.upper() == "ANSI":
        return c.ansi is not None
    return c.standard == standard


def _family(catalog: Sequence[ChainSpec], standard: str, series: str | None,
            strands: int | None) -> list[ChainSpec]:
    family = [c for c in catalog if _in_family(c, standard)
              and (series is None or c.series == series)
              and (strands is None or c.strands == strands)]
    if not family:
        what = f"{standard}" + (f" series {series}" if series else "") + (
            f" with {strands} strands" if strands else "")
        raise DesignError("chain.standard", f"the catalogue has no {what} chain")
    return family


@shared_parameters
def candidate(drive: Drive, spec: ChainSpec, geometry: GeometryResult | str,
              settings: CheckSettings,
              layout_checks: tuple[ck.Check, ...] | None = None) -> Candidate:
    """A chain checked on a drive: its chain checks and its layout checks, each by the
    function that makes them (:class:`Candidate`).

    Parameters
    ----------
    %(drive)s
    spec : ChainSpec
        The chain.
    geometry : GeometryResult or str
        The drive laid out with that chain, or why it could not be laid out (the candidate
        then fails a "geometry" check).
    settings : CheckSettings
        What the checks are held to.
    layout_checks : tuple of Check or None
        The geometry checks of that layout when already made (they do not depend on the
        chain beyond its pitch and roller).

    Returns
    -------
    Candidate
        The chain with every check.
    """
    on = drive.with_chain(spec)
    teeth, speed = small_sprocket(on)
    rating = ratings.chain_rating(spec, teeth, speed)
    lube = lubrication_advice(spec, float(mean_chain_speed(spec.pitch, teeth, speed)))
    method = settings.method or rating.method
    if isinstance(geometry, str):
        fail = ck.Check("geometry", spec.designation, None, None, "min", ck.FAIL,
                        "contour solver", note=geometry, part="geometry")
        return Candidate(spec.designation, method, spec.pitch, spec.strands,
                         spec.mass_per_length, layout_checks=(fail,), rating=rating,
                         lubrication=lube)
    layout = tuple(geometry_checks(on, geometry)) if layout_checks is None else layout_checks
    return Candidate(spec.designation, method, spec.pitch, spec.strands, spec.mass_per_length,
                     chain_checks=tuple(chain_checks(on, geometry, settings)),
                     layout_checks=layout, rating=rating, lubrication=lube, geometry=geometry)


def _layouts(drive: Drive, family: Sequence[ChainSpec]) -> dict[tuple[float, float],
                                                                 GeometryResult | str]:
    """The contour of ``drive`` for each distinct (pitch, roller diameter) of ``family``
    (links by the design's rounding; an imposed count is dropped: it fits one pitch only)."""
    out: dict[tuple[float, float], GeometryResult | str] = {}
    base = _unlinked(drive)
    for spec in family:
        key = (spec.pitch, spec.roller_diameter)
        if key not in out:
            try:
                out[key] = contour_geometry(base.with_chain(spec))
            except DesignError as exc:
                out[key] = str(exc)
    return out


def _unlinked(drive: Drive) -> Drive:
    """The drive as the selection lays it out: links by its rounding, no request."""
    return replace(drive, chain=replace(drive.chain, links=None, request=None))


@shared_parameters
def resonance_verdict(probe: ResonanceProbe, band_percent: float) -> str:
    """The resonance check against its own band.

    Over the band (every stiffness and inertia within ±u) each working frequency's detuning
    from its natural frequency ranges from its lowest to its highest value
    (:func:`chaindrive.dynamics.frequency.response.uncertainty_bands`). The check fails beyond
    its band when some working frequency stays closer than the limit over the whole band
    (highest detuning < limit): a resonance the uncertainty does not explain away. A check
    that fails at the nominal values only is inside its band: it cannot decide.

    %(probe_returns)s
    str
        :data:`RESONANCE_PASS` (also when there is no working frequency),
        :data:`INSIDE_BAND` or :data:`BEYOND_BAND`.
    """
    if probe.check is None or probe.check.passed:
        return RESONANCE_PASS
    if any(row[5] < band_percent for row in probe.rows):
        return BEYOND_BAND
    return INSIDE_BAND


@shared_parameters
def banded_resonance_check(probe: ResonanceProbe, band_percent: float) -> ck.Check | None:
    """The resonance check with its band in the note when it fails: inside its band (fails
    at the nominal values only — a resonance possible, not decided) or beyond it
    (:func:`resonance_verdict`).

    %(probe_returns)s
    Check or None
        The check (None when there is no working frequency).
    """
    check = probe.check
    verdict = resonance_verdict(probe, band_percent)
    if check is None or verdict == RESONANCE_PASS:
        return check
    u = f"±{100 * probe.uncertainty:g} %"
    if verdict == INSIDE_BAND:
        _, _, _, _, low, high, _ = _closest_row(probe)
        extra = (f"; fails at the nominal values only: over the band of {u} on every "
                 f"stiffness and inertia the detuning spans {low:.3g}–{high:.3g} %, so the "
                 "margin lies inside its own band — resonance possible, not decided")
    else:
        high = min(row[5] for row in probe.rows if row[5] < band_percent)
        extra = (f"; fails over its whole band: at most {high:.3g} % detuning for {u} on "
                 "every stiffness and inertia")
    return replace(check, note=check.note + extra)


def _closest_row(probe: ResonanceProbe) -> tuple[str, float, float, float, float, float, bool]:
    """The resonance row nearest its natural frequency (the one the check judges)."""
    return min(probe.rows, key=lambda r: abs(r[3]))


def _resonance_finding(chain: str, probe: ResonanceProbe, verdict: str,
                       band_percent: float) -> Finding:
    """"Resonance possible" beside a chain kept although its resonance check fails inside its
    band, with what would settle it; "passed over" for one that fails beyond it."""
    assert probe.check is not None
    label, fw, fn, offset, low, high, _ = (
        _closest_row(probe) if verdict == INSIDE_BAND
        else min((r for r in probe.rows if r[5] < band_percent), key=lambda r: r[5]))
    lo, hi = probe.factors
    b = band_percent / 100.0
    u = f"±{100 * probe.uncertainty:g} %"
    rests = ("" if not probe.assumed else
             f" The frequencies rest on {' and '.join(a for a, _ in probe.assumed)}.")
    shortfall = -(probe.check.margin_fraction or 0.0)
    if verdict == BEYOND_BAND:
        text = (f"{chain} passes every chain check but is passed over for resonance: {label} "
                f"({fw:.4g} Hz) lies {abs(offset):.3g} % from the natural frequency "
                f"{fn:.4g} Hz and at most {high:.3g} % over the band of {u} on every "
                f"stiffness and inertia (required ≥ {band_percent:g} %) — it fails beyond its "
                f"band, so a heavier chain is taken.{rests}")
        return Finding(PASSED_OVER, chain, probe.check.key, shortfall, text)
    settle = []
    if probe.assumed:
        settle.append("give " + " and ".join(g for _, g in probe.assumed))
    settle += [f"narrow [dynamics] uncertainty ({u} now) once the stiffnesses and inertias "
               "are known",
               f"move the working frequency ({fw:.4g} Hz) below {(1 - b) * fn * lo:.4g} Hz "
               f"or above {(1 + b) * fn * hi:.4g} Hz (other tooth counts, another driver "
               "speed)",
               "or move the natural frequency with the inertias (flywheel, the machines' "
               "inertias) or the span lengths"]
    text = (f"{chain}: {label} ({fw:.4g} Hz) lies {abs(offset):.3g} % "
            f"from the natural frequency {fn:.4g} Hz (required ≥ {band_percent:g} %), but over "
            f"the band of {u} on every stiffness and inertia that frequency spans "
            f"{fn * lo:.4g}–{fn * hi:.4g} Hz and the detuning {low:.3g}–{high:.3g} %: the "
            "margin lies inside its own band, so the chain is kept rather than a heavier one "
            f"taken.{rests} To settle it: {'; '.join(settle)}.")
    return Finding(RESONANCE_POSSIBLE, chain, probe.check.key, shortfall, text)


def _screened(candidates: list[Candidate], specs: dict[str, ChainSpec],
              resonance: Callable[[ChainSpec], ResonanceProbe],
              band_percent: float) -> list[Candidate]:
    """The ranking with the resonance check of each selectable candidate's own drive, tried
    in rank order until one does not fail beyond its band (:func:`resonance_verdict`): a
    chain is passed over only for a resonance beyond its band, or when its drive cannot be
    laid out."""
    out = sorted(candidates, key=rank_key)
    for i, c in enumerate(out):
        if not c.selectable:
            break  # ranked: none after it is selectable either
        try:
            probe = resonance(specs[c.designation])
        except DesignError as exc:
            fail = ck.Check("dynamic model", c.designation, None, None, "min", ck.FAIL, "",
                            note=str(exc), part="dynamics")
            out[i] = replace(c, dynamic_checks=(fail,), resonance=NOT_LAID_OUT,
                             notes=(*c.notes, f"cannot be laid out: {exc}"))
            continue
        if probe.check is None:
            break
        verdict = resonance_verdict(probe, band_percent)
        findings = (() if verdict == RESONANCE_PASS
                    else (_resonance_finding(c.designation, probe, verdict, band_percent),))
        out[i] = replace(c, dynamic_checks=(probe.check,), resonance=verdict, findings=findings)
        if verdict != BEYOND_BAND:
            break
    return sorted(out, key=rank_key)


def _layout_finding(drive: Drive, spec: ChainSpec, c: Candidate, chosen: Candidate | None,
                    cache: dict[tuple[float, float, str], tuple[Remedy, ...]]) -> Finding:
    """The layout checks a chain that passes every chain check misses, with their remedies
    (:func:`chaindrive.strength.remedies.layout_remedies`), as a finding: a layout remedy
    beside the chosen chain, or why a lighter chain was passed over."""
    q = Quantities()
    missed = [k for k in c.layout_checks if not k.passed]
    parts: list[str] = []
    remedies: list[Remedy] = []
    notes: list[Quantity] = []
    on = _unlinked(drive).with_chain(spec)
    laid: Layouts = {}  # the changes of ``on`` laid out, shared by its missed checks
    for k in missed:
        text, quoted = _missed_text(k, q)
        margin = k.margin_fraction
        short = "" if margin is None else f", {100 * -margin:.2g} % short"
        parts.append(text + short)
        notes += quoted
        key = (spec.pitch, spec.roller_diameter, k.key)
        if key not in cache and c.geometry is not None and k.value is not None:
            cache[key] = layout_remedies(on, c.geometry, k, laid)
        remedies += cache.get(key, ())
    worst = max(missed, key=lambda k: -(k.margin_fraction or -math.inf))
    span = next((k for k in missed if k.name == "span length" and k.value is not None), None)
    changes = [r.text for r in remedies]
    quoted_changes = [qq for r in remedies for qq in r.quantities]
    if span is not None:
        text, quoted = span_limit_text(span, spec.pitch)
        changes.append(text)
        quoted_changes += quoted
    remedy = ("; or ".join(changes) if changes else
              "no change of one sprocket was found that makes it pass; change the layout")
    missing = "; ".join(parts)
    small = f"{100 * SMALL_LAYOUT_SHORTFALL:g} %"
    if c is chosen:
        text = (f"{c.designation} passes every chain check; the layout misses {missing} — "
                f"within the {small} the selection leaves to the layout, so the chain is kept "
                f"rather than a heavier one taken. Change the layout: {remedy}.")
        kind = LAYOUT_REMEDY
    else:
        taken = ("a heavier chain whose layout passes is taken" if chosen is not None
                 else "no chain is selected")
        text = (f"{c.designation} passes every chain check but misses {missing} — more than "
                f"the {small} the selection leaves to the layout, so {taken}. With the layout "
                f"changed it would do: {remedy}.")
        kind = PASSED_OVER
    margin = worst.margin_fraction
    return Finding(kind, c.designation, worst.key, None if margin is None else -margin,
                   text, (*q.items, *notes, *quoted_changes), tuple(remedies))


def _findings(drive: Drive, ranked: Sequence[Candidate],
              specs: dict[str, ChainSpec]) -> tuple[Finding, ...]:
    """The findings beside the choice: the chosen chain's resonance finding and layout
    remedies, then the lighter chains that pass every chain check and were passed over (the
    lightest :data:`NAMED_PASSED_OVER` of them), each with its reason and remedy."""
    chosen = ranked[0] if ranked and ranked[0].selectable else None
    cache: dict[tuple[float, float, str], tuple[Remedy, ...]] = {}
    out: list[Finding] = []
    if chosen is not None:
        out += chosen.findings
        if chosen.layout_shortfall > 0:
            out.append(_layout_finding(drive, specs[chosen.designation], chosen, chosen,
                                       cache))
    heavy = math.inf if chosen is None else chosen.mass_per_length
    over = sorted((c for c in ranked if c.chain_passed and not c.selectable
                   and c.mass_per_length < heavy),
                  key=lambda c: (c.mass_per_length, c.pitch, c.strands))
    for c in over[:NAMED_PASSED_OVER]:
        out += [f for f in c.findings if f.kind == PASSED_OVER]
        if c.layout_shortfall > SMALL_LAYOUT_SHORTFALL and c.geometry is not None:
            out.append(_layout_finding(drive, specs[c.designation], c, chosen, cache))
    return tuple(out)


@shared_parameters
def rank_chains(drive: Drive, *, standard: str | None = None, series: str | None = None,
                strands: int | None = None, method: str | None = None,
                service_factor: float | None = None, design_factor: float = 1.0,
                operating_factor: float | None = None,
                catalog: Sequence[ChainSpec] | None = None,
                extra_files: Sequence[str] = (),
                resonance: Callable[[ChainSpec], ResonanceProbe] | None = None,
                band_percent: float = RESONANCE_BAND_PERCENT) -> SelectionResult:
    """Every chain of the family checked on ``drive`` and ranked (module docstring).

    standard/series: the family (default: that of ``drive.chain``; "ANSI" = every chain with
    an ANSI number); strands: only that number of strands (default: every count); method:
    "Kэ" or "rating" to force one on every chain (default: each chain's own; the legacy name
    "ISO 10823" means "rating"); service_factor K_s, design_factor n_d, operating_factor Kэ
    (defaults ``drive.service_factor`` or 1); catalog: the chains to choose from (default:
    the packaged catalogue and ``extra_files``, the user's catalogue files); resonance: the
    resonance check of a chain's own drive and its band (the analysis gives it), tried on
    the selectable chains in rank order (:func:`resonance_verdict`).

    Parameters
    ----------
    drive : Drive
        The design (power and driver speed needed).
    standard, series : str or None
        The family (default: that of ``drive.chain``; "ANSI" = every chain with an ANSI
        number).
    strands : int or None
        Only that number of strands [-] (default: every count).
    method : str or None
        "Kэ" or "rating" to force one on every chain.
    service_factor, operating_factor : float or None
        K_s, Kэ [-] (default ``drive.service_factor`` or 1).
    %(selection_catalog)s
    resonance : callable or None
        ChainSpec → :class:`ResonanceProbe` of the drive with that chain (None: no dynamic
        check).
    band_percent : float
        The least detuning of the resonance check [%].

    Returns
    -------
    SelectionResult
        Every candidate ranked, with the findings beside the choice.
    """
    if drive.power is None:
        raise DesignError("drive.power", "selection needs the transmitted power")
    if drive.driver.speed is None:
        raise DesignError(f"sprockets[{drive.driver.name}].speed", "selection needs the speed")
    if strands is not None and not 1 <= strands <= 8:
        raise DesignError("chain.strands", f"must be 1 to 8, got {strands!r}")
    forced = None
    if method is not None:
        forced = _LEGACY.get(method, method)
        if forced not in METHODS:
            raise DesignError("method", f"must be one of {', '.join(METHODS)}, got {method!r}")
    standard = standard or drive.chain.spec.standard
    settings = settings_for(drive, service_factor=service_factor, design_factor=design_factor,
                            operating_factor=operating_factor,
                            method=KE if forced == KE else None)
    family = _family(_catalog(catalog, extra_files), standard, series, strands)
    specs = {s.designation: s for s in family}
    layouts = _layouts(drive, family)
    layout_checks = {key: tuple(geometry_checks(drive.with_chain(_first(family, key)), g))
                     for key, g in layouts.items() if not isinstance(g, str)}
    found = [candidate(drive, spec, layouts[(spec.pitch, spec.roller_diameter)], settings,
                       layout_checks.get((spec.pitch, spec.roller_diameter)))
             for spec in family]
    ranked = (sorted(found, key=rank_key) if resonance is None
              else _screened(found, specs, resonance, band_percent))
    return SelectionResult(tuple(ranked), specs, findings=_findings(drive, ranked, specs))


def _first(family: Sequence[ChainSpec], key: tuple[float, float]) -> ChainSpec:
    """The first chain of ``family`` with this (pitch, roller diameter)."""
    return next(s for s in family if (s.pitch, s.roller_diameter) == key)


@shared_parameters
def select_chain(drive: Drive, *, standard: str | None = None, series: str | None = None,
                 strands: int | None = None, method: str | None = None,
                 service_factor: float | None = None, design_factor: float = 1.0,
                 operating_factor: float | None = None,
                 catalog: Sequence[ChainSpec] | None = None,
                 extra_files: Sequence[str] = ()) -> SelectionResult:
    """:func:`rank_chains`, refusing a drive on which no chain is selectable.

    Parameters
    ----------
    %(drive)s
    standard, series : str or None
        The family.
    strands : int or None
        Only that number of strands [-].
    method : str or None
        Force a method.
    service_factor, operating_factor : float or None
        K_s, Kэ [-].
    %(selection_catalog)s

    Returns
    -------
    SelectionResult
        Every candidate ranked; the chosen chain passes every chain check (and any layout
        check it misses is a finding with its remedy).

    Raises
    ------
    DesignError
        On ``chain``, naming the closest candidate and what it misses, when no chain is
        selectable.
    """
    result = rank_chains(drive, standard=standard, series=series, strands=strands,
                         method=method, service_factor=service_factor,
                         design_factor=design_factor, operating_factor=operating_factor,
                         catalog=catalog, extra_files=extra_files)
    if result.chosen is None:
        raise DesignError("chain", result.shortfall())
    return result
