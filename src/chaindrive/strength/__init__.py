"""Strength of a chain drive: loads round the contour, safety factors, wear life, selection.

Entry points: :func:`strength_of` (loads + joint pressure + static safety + wear life of the
drive's chain) and :func:`select_chain` (which catalogue chain passes every check, each chain
rated by the method that fits it: ACA, the ISO 606 B table, the Kэ method, allowable load).
Modules: :mod:`.loads`, :mod:`.iso10823`, :mod:`.ke_method`, :mod:`.safety`, :mod:`.wear`,
:mod:`.selection`; tables in ``strength/data`` with their sources in the file headers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveWarning, DesignError, Quantities, Quantity
from chaindrive.geometry.results import GeometryResult
from chaindrive.model import Drive
from chaindrive.strength import ke_method, ratings
from chaindrive.strength.drive_checks import chain_limits
from chaindrive.strength.duty import service_factor_for
from chaindrive.strength.loads import (
    LoadsResult,
    hinge_pressure,
    loads_of,
    small_sprocket,
)
from chaindrive.strength.safety import static_safety_factor
from chaindrive.strength.selection import Candidate, SelectionResult, select_chain
from chaindrive.strength.sprocket_teeth import polymer_tooth_checks
from chaindrive.strength.wear import (
    BASIS_ELONGATION,
    EXTRAPOLATION_LIMIT_H,
    is_extrapolated,
    wear_life_hours,
)

__all__ = ["Candidate", "LoadsResult", "SelectionResult", "StrengthResult", "loads_of",
           "polymer_tooth_checks", "select_chain", "strength_of"]


@dataclass(frozen=True, slots=True)
class StrengthResult:
    """Static strength of a drive.

    Parameters
    ----------
    loads : LoadsResult
        The contour loads.
    operating_factor : float
        Kэ used [-].
    dynamic_factor : float
        kд used [-].
    hinge_pressure : float
        p = F_t·Kэ/A [Pa].
    allowable_pressure : float or None
        [p] [Pa] of the Kэ method (None for rated and non-steel chains, whose method has no
        joint-pressure limit, and outside the table).
    safety_factor_static : float
        s [-].
    allowable_safety_factor : float or None
        [s] [-] of the chain's method (None for non-steel chains and outside the table).
    rated_power : float or None
        Of the chain by ``rating_method`` [W] (None for Kэ and polymer chains).
    wear_life_h : float or None
        Hours to the permitted elongation [h] (None when not applicable).
    elongation : float
        Permitted elongation [-].
    warnings : tuple of ChainDriveWarning
        Estimates and models that do not apply.
    rating_method : str
        ACA, the ISO 606 B table … (:mod:`chaindrive.strength.ratings`).
    rating_note : str
        Which method governs and what the other gives beside it
        (:attr:`chaindrive.strength.ratings.RatingResult.note`).
    rating_note_quantities : tuple of Quantity
        The numbers with units ``rating_note`` writes (SI), for a presenter to write in
        another unit system.
    """

    loads: LoadsResult
    operating_factor: float
    dynamic_factor: float
    hinge_pressure: float
    allowable_pressure: float | None
    safety_factor_static: float
    allowable_safety_factor: float | None
    rated_power: float | None
    wear_life_h: float | None
    elongation: float
    warnings: tuple[ChainDriveWarning, ...] = ()
    rating_method: str = ""
    rating_note: str = ""
    rating_note_quantities: tuple[Quantity, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (the ``strength`` block of ``analyze --json``)."""
        loads = self.loads.to_dict()
        return {
            **loads,
            "operating_factor_ke": self.operating_factor,
            "dynamic_factor_kd": self.dynamic_factor,
            "hinge_pressure_mpa": self.hinge_pressure / 1e6,
            "allowable_pressure_mpa": (None if self.allowable_pressure is None
                                       else self.allowable_pressure / 1e6),
            "safety_factor_static": self.safety_factor_static,
            "allowable_safety_factor": self.allowable_safety_factor,
            "rated_power_w": self.rated_power,
            "rating_method": self.rating_method,
            "rating_note": self.rating_note,
            "rating_note_quantities": [q.to_dict() for q in self.rating_note_quantities],
            "wear_life_h": self.wear_life_h,
            "wear_life_extrapolated": (None if self.wear_life_h is None
                                       else is_extrapolated(self.wear_life_h)),
            "permitted_elongation": self.elongation,
        }


@shared_parameters
def strength_of(drive: Drive, geometry: GeometryResult, *, operating_factor: float | None = None,
                dynamic_factor: float = 1.0, service_factor: float | None = None,
                elongation: float = BASIS_ELONGATION, sag_ratio: float | None = None,
                shaft_load_factor: float = 1.0) -> StrengthResult:
    """Loads, joint pressure, static safety and wear life of a laid-out drive.

    [p] and [s] are those the chain's checks hold it to
    (:func:`chaindrive.strength.drive_checks.chain_limits`): the Russian tables by pitch and
    small-sprocket speed for GOST chains, s ≥ 6 and no joint-pressure limit for rated chains;
    the wear life is the ACA load–life model (:mod:`chaindrive.strength.wear`).
    Non-steel (polymer) chains: [p], [s] and the wear life are not given (the steel tables
    do not apply) and a warning says so; s uses the chain's own breaking load Q (from its
    material strength).

    Parameters
    ----------
    drive : Drive
        The design (power and driver speed needed).
    %(geometry)s
    operating_factor : float or None
        Kэ for p = F_t·Kэ/A [-] (default: the drive's service factor,
        :func:`~chaindrive.strength.duty.service_factor_for`).
    dynamic_factor : float
        kд for s = Q/(kд·F_t + F_0 + F_v) [-].
    service_factor : float or None
        K_s for the wear life [-] (default: the drive's service factor,
        :func:`~chaindrive.strength.duty.service_factor_for`).
    elongation : float
        Permitted elongation for the wear life [-] (default 3 %).
    sag_ratio : float | None
        Sag of the slack span as a fraction of its length [-]; None: the design's installed
        sag (``[chain] sag``), else 0.02.
    shaft_load_factor : float
        kв of the shaft loads [-].

    Returns
    -------
    StrengthResult
        The static strength.

    References
    ----------
    [ChainDesignRU, Table 2A, Table 9A]; [Shigley2015, Eq. 17-40].
    """
    if not 0 < elongation <= 0.1:
        raise DesignError("elongation", f"must be a fraction in (0, 0.1], got {elongation!r}")
    loads = loads_of(drive, geometry, sag_ratio=sag_ratio, shaft_load_factor=shaft_load_factor)
    spec = drive.chain.spec
    base = service_factor_for(drive).value  # given, from the duty classes, else 1
    ke = operating_factor if operating_factor is not None else base
    ks = service_factor if service_factor is not None else base
    teeth, speed = small_sprocket(drive)
    area, estimated = ke_method.bearing_area(spec)
    warnings: list[ChainDriveWarning] = []
    if estimated:
        q = Quantities()
        warnings.append(ChainDriveWarning(
            "strength.bearing-area-estimated", "chain",
            f"{spec.designation}: no bearing area in the catalogue; estimated "
            f"A = {q(area, 'area', '.1f')} (mр·d2·B, chaindrive.catalog.bearing_area_estimate)",
            q.items))
    pressure = hinge_pressure(loads.peripheral_force, ke, area)
    s = static_safety_factor(spec.breaking_load, loads.peripheral_force, loads.sag_tension,
                             loads.centrifugal_tension, dynamic_factor)
    steel = spec.material == "steel"
    allowed_p, allowed_s = chain_limits(spec, speed)
    rated = life = None
    rating = ratings.chain_rating(spec, teeth, speed)
    if steel and rating.rated_power is not None:
        rated = rating.rated_power
        assert drive.power is not None
        life = float(wear_life_hours(rated, drive.power * ks, geometry.links, elongation))
        if is_extrapolated(life):
            warnings.append(ChainDriveWarning(
                "strength.wear-life-extrapolated", "strength",
                f"wear life {life:,.0f} h is an extrapolation of the ACA load–life relation "
                f"(beyond {EXTRAPOLATION_LIMIT_H:,.0f} h, the design power is "
                f"{drive.power * ks / rated:.0%} of the rating): wear does not limit this drive"))
    if not steel:
        warnings.append(ChainDriveWarning(
            "strength.non-steel-chain", "chain",
            f"chain material {spec.material!r}: the steel tables of allowable hinge pressure "
            "and safety factor and the wear-life model do not apply; check the material's "
            "limits"))
    # a pressure or safety beyond its limit, or outside the tables, is a failed check of
    # the analysis (chaindrive.checks), not a warning
    return StrengthResult(loads, ke, dynamic_factor, pressure, allowed_p, s, allowed_s, rated,
                          life, elongation, tuple(warnings), rating.method, rating.note,
                          rating.note_quantities)
