"""Chain selection: every catalogue chain checked by both methods, ranked, the lightest chosen.

Methods: "ISO 10823" (ACA rating envelopes, :mod:`chaindrive.strength.iso10823`) for ISO 606
and ANSI chains, "Kэ" (joint pressure, speed and impact limits,
:mod:`chaindrive.strength.ke_method`) for GOST 13568 chains. Candidates are listed for both
methods and ranked feasible first, then by pitch, strands and decreasing margin; the chosen
chain is the lightest (mass per length) feasible chain of the requested number of strands
(simplex by default) checked by the method of its family.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from chaindrive.errors import ChainDriveWarning, DesignError
from chaindrive.model import ChainSpec, Drive
from chaindrive.strength import iso10823, ke_method
from chaindrive.strength.loads import chain_speed, small_sprocket
from chaindrive.units import RAD_S_TO_RPM

ISO = "ISO 10823"
KE = "Kэ"
METHODS = (ISO, KE)


def method_for(standard: str) -> str:
    """The selection method of a chain family: ISO 10823 for ISO 606 and ANSI, Kэ for GOST."""
    return KE if standard.upper().startswith("GOST") else ISO


@dataclass(frozen=True, slots=True)
class Candidate:
    """One chain checked by one method.

    margin: capacity/demand − 1 of the governing limit (≥ 0 when feasible); governing: the
    limit that decides; details: the method's numbers (SI units, names with units).
    """

    designation: str
    method: str
    pitch: float
    strands: int
    mass_per_length: float
    feasible: bool
    margin: float
    governing: str
    details: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"chain": self.designation, "method": self.method, "pitch_mm": self.pitch * 1e3,
                "strands": self.strands, "mass_kg_m": self.mass_per_length,
                "feasible": self.feasible, "margin": self.margin, "governing": self.governing,
                **self.details}


@dataclass(frozen=True, slots=True)
class SelectionResult:
    """The chosen chain, the method that chose it and every candidate checked (ranked)."""

    chain: ChainSpec
    method: str
    candidates: tuple[Candidate, ...]
    warnings: tuple[ChainDriveWarning, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: ``chain`` (designation), ``method``, ``candidates[]``."""
        return {"chain": self.chain.designation, "method": self.method,
                "candidates": [c.to_dict() for c in self.candidates]}


def estimated_links(drive: Drive, pitch: float) -> float:
    """Chain length in pitches before the geometry is built: perimeter of the centre polygon / p
    plus the mean tooth count (exact for the straight part of a two-sprocket drive:
    2a/p + (z1 + z2)/2, Shigley Eq. 17-34 without the small last term)."""
    pts = [(s.x, s.y) for s in drive.sprockets]
    perimeter = sum(math.dist(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts)))
    return perimeter / pitch + sum(s.teeth for s in drive.sprockets) / len(pts)


def _iso_candidate(chain: ChainSpec, drive: Drive, service_factor: float,
                   design_factor: float) -> Candidate:
    assert drive.power is not None
    teeth, speed = small_sprocket(drive)
    check = iso10823.check_rating(chain, drive.power, teeth, speed,
                                  service_factor=service_factor, design_factor=design_factor)
    details = {"rated_power_w": check.rated_power, "required_power_w": check.required_power,
               "lubrication": check.lubrication,
               "galling_limit_rpm": check.galling_limit * RAD_S_TO_RPM}
    return Candidate(chain.designation, ISO, chain.pitch, chain.strands, chain.mass_per_length,
                     check.feasible, check.margin, check.governing, details)


def _ke_candidate(chain: ChainSpec, drive: Drive, operating: float,
                  links: float | None) -> Candidate:
    assert drive.power is not None
    teeth, speed = small_sprocket(drive)
    force = drive.power / chain_speed(teeth, chain.pitch, speed)
    lt = links if links is not None else estimated_links(drive, chain.pitch)
    check = ke_method.check_pressure(chain, force, operating, teeth, speed, lt)
    details = {"pressure_mpa": check.pressure / 1e6,
               "allowable_pressure_mpa": (None if check.allowable_pressure is None
                                          else check.allowable_pressure / 1e6),
               "max_speed_rpm": None if check.max_speed is None else check.max_speed * RAD_S_TO_RPM,
               "impacts_per_s": check.impacts, "allowable_impacts_per_s": check.allowable_impacts,
               "bearing_area_estimated": check.area_estimated}
    return Candidate(chain.designation, KE, chain.pitch, chain.strands, chain.mass_per_length,
                     check.feasible, check.margin, check.governing, details)


def _catalog(catalog: Sequence[ChainSpec] | None) -> Sequence[ChainSpec]:
    if catalog is not None:
        return catalog
    from chaindrive.catalog import chains

    return chains()


def _family(catalog: Sequence[ChainSpec], standard: str, series: str | None,
            strands: int | None) -> list[ChainSpec]:
    family = [c for c in catalog if c.standard == standard and c.material == "steel"
              and (series is None or c.series == series)
              and (strands is None or c.strands == strands)]
    if not family:
        what = f"{standard}" + (f" series {series}" if series else "") + (
            f" with {strands} strands" if strands else "")
        raise DesignError("chain.standard", f"the catalogue has no {what} chain")
    return family


def _rank_key(c: Candidate) -> tuple[bool, float, int, float]:
    return (not c.feasible, c.pitch, c.strands, -c.margin)


def select_chain(drive: Drive, *, standard: str | None = None, series: str | None = None,
                 strands: int | None = None, method: str | None = None,
                 service_factor: float | None = None, design_factor: float = 1.0,
                 operating_factor: float | None = None, links: float | None = None,
                 catalog: Sequence[ChainSpec] | None = None) -> SelectionResult:
    """Choose a chain for ``drive`` (power [W] and driver speed needed).

    standard/series: the family (default: that of ``drive.chain``); strands: fix the number
    of strands (default: candidates of every strand count, chosen simplex); method: "ISO 10823"
    or "Kэ" (default by family, :func:`method_for`); service_factor K_s and design_factor n_d
    for ISO 10823 (default ``drive.service_factor`` or 1); operating_factor Kэ for the Kэ
    method (default ``drive.service_factor`` or 1); links: chain length in pitches for the
    impacts check (default :func:`estimated_links`); catalog: chains to choose from (default
    :func:`chaindrive.catalog.chains`). Raises DesignError when no chain can carry the load,
    naming the best candidate and its shortfall.
    """
    if drive.power is None:
        raise DesignError("drive.power", "selection needs the transmitted power")
    if drive.driver.speed is None:
        raise DesignError(f"sprockets[{drive.driver.name}].speed", "selection needs the speed")
    if strands is not None and not 1 <= strands <= 8:
        raise DesignError("chain.strands", f"must be 1 to 8, got {strands!r}")
    standard = standard or drive.chain.spec.standard
    method = method or method_for(standard)
    if method not in METHODS:
        raise DesignError("method", f"must be one of {', '.join(METHODS)}, got {method!r}")
    ks = service_factor if service_factor is not None else (drive.service_factor or 1.0)
    ke = operating_factor if operating_factor is not None else (drive.service_factor or 1.0)
    family = _family(_catalog(catalog), standard, series, strands)
    candidates: list[Candidate] = []
    for chain in family:
        if chain.strands in (1, 2, 3, 4, 5, 6, 8):
            candidates.append(_iso_candidate(chain, drive, ks, design_factor))
        if chain.strands <= 4:
            candidates.append(_ke_candidate(chain, drive, ke, links))
    candidates.sort(key=_rank_key)
    wanted = strands or 1
    pool = [c for c in candidates if c.method == method and c.strands == wanted]
    feasible = [c for c in pool if c.feasible]
    if not feasible:
        _raise_shortfall(pool, method, drive)
    best = min(feasible, key=lambda c: (c.mass_per_length, c.pitch))
    chosen = next(c for c in family if c.designation == best.designation)
    return SelectionResult(chosen, method, tuple(candidates))


def _raise_shortfall(pool: list[Candidate], method: str, drive: Drive) -> None:
    if not pool:
        raise DesignError("chain.strands", f"no candidate chain can be checked by {method}")
    best = max(pool, key=lambda c: c.margin)
    raise DesignError(
        "chain",
        f"no chain can carry {drive.power:.4g} W by {method}: the best candidate "
        f"{best.designation} falls short by {-best.margin:.1%} ({best.governing}); "
        f"try more strands, a larger pitch or another series",
    )
