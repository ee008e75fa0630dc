"""Chain selection: every catalogue chain of the family checked, ranked, the first chosen.

One rule ranks and chooses: a candidate passes when every check of
:func:`chaindrive.strength.drive_checks.checks_for` passes (a "cannot be verified" is not a
pass); candidates are ranked passing first, then by mass per metre (the lightest chain that
does the job), pitch, strands and the smallest margin (largest first); the chosen chain is the
first of that ranking. The failing ones follow from the closest — laid out, fewest missed
checks, the worst check least short — so when nothing passes, the selection's first row is the
closest candidate it names, with what it misses.

Each candidate is checked by its own method (:func:`chaindrive.strength.ratings.method_for`):
ACA ratings for ISO 606 A / ANSI, the B-series table for ISO 606 B, the Kэ method for GOST
13568, the allowable load for polymer chains. The geometry of every distinct pitch and roller
is built with the contour solver (take-up and link rounding of the design), so teeth in mesh,
wrap and span length are checked for the candidate as it would be laid out.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from chaindrive.catalog import chains
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
    checks_for,
    geometry_checks,
    settings_for,
)
from chaindrive.strength.loads import small_sprocket
from chaindrive.strength.lubrication import LubricationAdvice, lubrication_advice

__all__ = ["KE", "METHODS", "RATING", "Candidate", "SelectionResult", "candidate",
           "estimated_links", "family_method", "rank_chains", "rank_key", "select_chain"]

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


@dataclass(frozen=True, slots=True)
class Candidate:
    """One chain checked on the drive.

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
    passed : bool
        Every check passed.
    margin_fraction : float or None
        Margin of the worst check [-] (None when it cannot be verified).
    governing : str
        The name of that check.
    checks : tuple of Check
        Every check.
    rating : RatingResult or None
        The rating result.
    lubrication : LubricationAdvice or None
        The lubrication advice (None when the chain could not be laid out).
    notes : tuple of str
        Remarks.
    """

    designation: str
    method: str
    pitch: float
    strands: int
    mass_per_length: float
    passed: bool
    margin_fraction: float | None
    governing: str
    checks: tuple[ck.Check, ...] = ()
    rating: ratings.RatingResult | None = None
    lubrication: LubricationAdvice | None = None
    notes: tuple[str, ...] = field(default=())

    @property
    def feasible(self) -> bool:
        """Alias of ``passed``."""
        return self.passed

    @property
    def missed(self) -> tuple[ck.Check, ...]:
        """The checks that did not pass."""
        return tuple(c for c in self.checks if not c.passed)

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
        d: dict[str, Any] = {
            "chain": self.designation, "method": self.method, "pitch_mm": self.pitch * 1e3,
            "strands": self.strands, "mass_kg_m": self.mass_per_length, "passed": self.passed,
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
    """

    candidates: tuple[Candidate, ...]
    specs: dict[str, ChainSpec]
    warnings: tuple[str, ...] = ()

    @property
    def chosen(self) -> Candidate | None:
        """The selected candidate, or None when no chain passes every check."""
        first = self.candidates[0] if self.candidates else None
        return first if first is not None and first.passed else None

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

        Returns
        -------
        text : str
            The sentence (SI).
        quantities : tuple of Quantity
            Its numbers with units: the values and limits of the missed checks, then those
            of the notes it quotes.
        """
        best = self.closest
        if best is None:
            return "no candidate chain", ()
        q = Quantities()
        parts = [_missed_text(c, q) for c in best.missed]
        missed = "; ".join(text for text, _ in parts)
        quantities = (*q.items, *(n for _, notes in parts for n in notes))
        return (f"no chain passes every check: the closest is {best.designation} "
                f"({best.method}), which misses {missed}; try more strands, a larger pitch, "
                "another series or a change to the layout"), quantities

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
        and what it misses, the ranked candidates.

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
    if c.status == ck.UNVERIFIED or c.value is None or c.limit is None:
        return f"{c.name} ({c.status}: {c.note})", c.note_quantities
    rel = "≤" if c.kind == "max" else "≥"
    kind = UNIT_KINDS.get(c.unit)
    if kind is not None:
        return f"{c.name} {q(c.value, kind)} (required {rel} {q(c.limit, kind)})", ()
    value, limit = f"{c.value * c.scale:.4g}", f"{c.limit * c.scale:.4g}"
    return f"{c.name} {value} {c.unit} (required {rel} {limit} {c.unit})".replace("  ", " "), ()


def _closeness(c: Candidate) -> tuple[bool, int, float]:
    """A chain that can be laid out first, then fewer missed checks, then the largest
    (least negative) worst margin."""
    worst = c.margin_fraction if c.margin_fraction is not None else -math.inf
    laid_out = c.governing != "geometry"
    return laid_out, -len(c.missed), worst


def rank_key(c: Candidate) -> tuple[bool, float, float, float, float, float, float]:
    """The one rule: passing first, by mass per metre, pitch, strands, larger margin; then the
    failing ones from the closest (:func:`_closeness`: laid out, fewest missed checks, least
    short worst margin), so that when nothing passes the closest chain heads the table.

    Parameters
    ----------
    c : Candidate
        A candidate.

    Returns
    -------
    tuple
        Its sort key.
    """
    margin = c.margin_fraction if c.margin_fraction is not None else -math.inf
    if c.passed:
        return (False, c.mass_per_length, c.pitch, float(c.strands), -margin, 0.0, 0.0)
    laid_out, fewer_missed, worst = _closeness(c)
    return (True, -float(laid_out), -float(fewer_missed), -worst, c.mass_per_length, c.pitch,
            float(c.strands))


def estimated_links(drive: Drive, pitch: float) -> float:
    """Chain length before the geometry is built: perimeter of the centre polygon / p plus
    the mean tooth count (for two sprockets 2a/p + (z1 + z2)/2, [Shigley2015, Eq. 17-34]
    without the small last term).

    Parameters
    ----------
    drive : Drive
        The design.
    pitch : float
        Chain pitch p [m].

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


def candidate(drive: Drive, spec: ChainSpec, geometry: GeometryResult | str,
              settings: CheckSettings,
              layout_checks: tuple[ck.Check, ...] | None = None) -> Candidate:
    """A chain checked on a drive.

    Parameters
    ----------
    drive : Drive
        The design.
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
                        "contour solver", note=geometry)
        return Candidate(spec.designation, method, spec.pitch, spec.strands,
                         spec.mass_per_length, False, None, "geometry", (fail,), rating, lube)
    if layout_checks is None:
        checks = checks_for(on, geometry, settings)
    else:
        checks = (*chain_checks(on, geometry, settings), *layout_checks)
    worst = ck.worst(list(checks))
    return Candidate(spec.designation, method, spec.pitch, spec.strands, spec.mass_per_length,
                     all(c.passed for c in checks),
                     None if worst is None else worst.margin_fraction,
                     "" if worst is None else worst.name, checks, rating, lube)


def _layouts(drive: Drive, family: Sequence[ChainSpec]) -> dict[tuple[float, float],
                                                                 GeometryResult | str]:
    """The contour of ``drive`` for each distinct (pitch, roller diameter) of ``family``
    (links by the design's rounding; an imposed count is dropped: it fits one pitch only)."""
    out: dict[tuple[float, float], GeometryResult | str] = {}
    base = replace(drive, chain=replace(drive.chain, links=None, request=None))
    for spec in family:
        key = (spec.pitch, spec.roller_diameter)
        if key not in out:
            try:
                out[key] = contour_geometry(base.with_chain(spec))
            except DesignError as exc:
                out[key] = str(exc)
    return out


def rank_chains(drive: Drive, *, standard: str | None = None, series: str | None = None,
                strands: int | None = None, method: str | None = None,
                service_factor: float | None = None, design_factor: float = 1.0,
                operating_factor: float | None = None,
                catalog: Sequence[ChainSpec] | None = None,
                extra_files: Sequence[str] = ()) -> SelectionResult:
    """Every chain of the family checked on ``drive`` and ranked (module docstring).

    standard/series: the family (default: that of ``drive.chain``; "ANSI" = every chain with
    an ANSI number); strands: only that number of strands (default: every count); method:
    "Kэ" or "rating" to force one on every chain (default: each chain's own; the legacy name
    "ISO 10823" means "rating"); service_factor K_s, design_factor n_d, operating_factor Kэ
    (defaults ``drive.service_factor`` or 1); catalog: the chains to choose from (default:
    the packaged catalogue and ``extra_files``, the user's catalogue files).

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
    design_factor : float
        n_d [-].
    catalog : sequence of ChainSpec or None
        The chains to choose from.
    extra_files : sequence of str
        The user's catalogue files.

    Returns
    -------
    SelectionResult
        Every candidate ranked.
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
    layouts = _layouts(drive, family)
    layout_checks = {key: tuple(geometry_checks(drive, g)) for key, g in layouts.items()
                     if not isinstance(g, str)}
    found = [candidate(drive, spec, layouts[(spec.pitch, spec.roller_diameter)], settings,
                       layout_checks.get((spec.pitch, spec.roller_diameter)))
             for spec in family]
    found.sort(key=rank_key)
    return SelectionResult(tuple(found), {s.designation: s for s in family})


def select_chain(drive: Drive, *, standard: str | None = None, series: str | None = None,
                 strands: int | None = None, method: str | None = None,
                 service_factor: float | None = None, design_factor: float = 1.0,
                 operating_factor: float | None = None,
                 catalog: Sequence[ChainSpec] | None = None,
                 extra_files: Sequence[str] = ()) -> SelectionResult:
    """:func:`rank_chains`, refusing a drive on which no chain passes.

    Parameters
    ----------
    drive : Drive
        The design.
    standard, series : str or None
        The family.
    strands : int or None
        Only that number of strands [-].
    method : str or None
        Force a method.
    service_factor, operating_factor : float or None
        K_s, Kэ [-].
    design_factor : float
        n_d [-].
    catalog : sequence of ChainSpec or None
        The chains to choose from.
    extra_files : sequence of str
        The user's catalogue files.

    Returns
    -------
    SelectionResult
        Every candidate ranked; the chosen chain passes every check.

    Raises
    ------
    DesignError
        On ``chain``, naming the closest candidate and what it misses, when no chain passes.
    """
    result = rank_chains(drive, standard=standard, series=series, strands=strands,
                         method=method, service_factor=service_factor,
                         design_factor=design_factor, operating_factor=operating_factor,
                         catalog=catalog, extra_files=extra_files)
    if result.chosen is None:
        raise DesignError("chain", result.shortfall())
    return result
