"""Every check of one chain on one laid-out drive: the list the selection ranks by.

:func:`checks_for` returns the :class:`~chaindrive.strength.checks.Check` list of a drive
(its chain, its geometry): the analysis lists the same checks for the chain it analyses as
the selection made for every candidate, so a chosen chain cannot fail a chain check of the
analysis (its layout checks are judged beside it: ``docs/selection.md``).

Which checks, by the chain's method (:func:`chaindrive.strength.ratings.method_for`):

* rating methods (ACA for ISO 606 A / ANSI, the B-series table for ISO 606 B): power
  rating ≥ P·K_s·n_d; wear life [Shigley2015, Eq. 17-40] ≥ the required life (default the
  rating's own basis, 15 000 h·L_p/100); small-sprocket speed ≤ the pin–bush galling
  limit [Shigley2015, §17-5]; static safety ≥ 6 [DiamondChain]. The joint pressure [p] of
  the Russian method is not applied: the rating is the wear and fatigue limit of these
  chains (it is listed by :mod:`.ke_method` for GOST chains);
* Kэ (GOST 13568): hinge pressure p = Kэ·F_t/A ≤ [p]; small-sprocket speed ≤ n1 max;
  impacts per second ≤ [i]; static safety ≥ [s] (tables by pitch and speed);
* polymer: chain pull ≤ the allowable load; chain speed ≤ the maker's limit;
* every chain: teeth in mesh ≥ 3 on every sprocket (idlers included), wrap ≥ 120° on the
  driver and the small loaded sprocket, longest span ≤ 80 pitches.

A table without a value for the pitch or speed gives "cannot be verified" — a failure, said
as such — never a silent pass.

References
----------
See :mod:`chaindrive.strength.checks` and ``docs/selection.md``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from chaindrive._docstrings import shared_parameters
from chaindrive.geometry.results import GeometryResult
from chaindrive.kinematics import mean_chain_speed
from chaindrive.model import ChainSpec, Drive
from chaindrive.strength import checks as ck
from chaindrive.strength import iso10823, ke_method, ratings
from chaindrive.strength.duty import required_life_h as design_life_h
from chaindrive.strength.duty import service_factor_for
from chaindrive.strength.loads import (
    LoadsResult,
    centrifugal_tension,
    hinge_pressure,
    installed_pretension,
    peripheral_force,
    small_sprocket,
)
from chaindrive.strength.safety import static_safety_factor
from chaindrive.strength.sprocket_teeth import polymer_tooth_checks
from chaindrive.strength.wear import BASIS_LIFE_H, BASIS_LINKS, wear_life_hours

__all__ = ["CheckSettings", "chain_checks", "chain_limits", "checks_for", "geometry_checks",
           "loaded_contour_checks", "settings_for"]


@dataclass(frozen=True, slots=True)
class CheckSettings:
    """What the checks are held to.

    Parameters
    ----------
    service_factor, design_factor : float
        K_s and n_d of the design power P·K_s·n_d [-] (rating methods and the polymer
        allowable load).
    operating_factor : float
        Kэ [-] (Kэ method).
    dynamic_factor : float
        kд of the static safety s = Q/(kд·F_t + F_0 + F_v) [-].
    required_life_h : float or None
        Required wear life [h] (None: the life the rating promises for the chain's length,
        15 000 h·L_p/100 — then the check agrees with the rating check; give a service life
        to require more).
    method : str or None
        Force "Kэ" (or a rating method) instead of the chain's own (None).
    """

    service_factor: float = 1.0
    design_factor: float = 1.0
    operating_factor: float = 1.0
    dynamic_factor: float = 1.0
    required_life_h: float | None = None
    method: str | None = None


@shared_parameters
def settings_for(drive: Drive, *, service_factor: float | None = None,
                 design_factor: float | None = None, operating_factor: float | None = None,
                 dynamic_factor: float | None = None, required_life_h: float | None = None,
                 method: str | None = None) -> CheckSettings:
    """Settings with K_s and Kэ defaulting to the drive's service factor (given, from its
    duty classes, else 1: :func:`chaindrive.strength.duty.service_factor_for`) and the
    required life to the design's ``required_life``.

    Parameters
    ----------
    %(drive)s
    service_factor, design_factor, operating_factor, dynamic_factor : float or None
        K_s, n_d, Kэ, kд [-] (None: the default).
    required_life_h : float or None
        Required wear life [h] (None: the design's ``required_life``, else the rating's own).
    method : str or None
        Force a method (None: each chain's own).

    Returns
    -------
    CheckSettings
        The settings.
    """
    base = service_factor_for(drive).value
    if required_life_h is None:
        required_life_h = design_life_h(drive)
    return CheckSettings(
        service_factor=base if service_factor is None else service_factor,
        design_factor=1.0 if design_factor is None else design_factor,
        operating_factor=base if operating_factor is None else operating_factor,
        dynamic_factor=1.0 if dynamic_factor is None else dynamic_factor,
        required_life_h=required_life_h, method=method)


@dataclass(frozen=True, slots=True)
class _Forces:
    """The chain forces the checks need: speed v [m/s], F_t, F_0, F_v [N]."""

    speed: float
    peripheral_force: float
    sag_tension: float
    centrifugal_tension: float


def _forces(drive: Drive, geometry: GeometryResult, loads: LoadsResult | None = None) -> _Forces:
    """The strength stage's ``loads`` where they are known; else v = z·p·ω/2π, F_t = P/v,
    F_v = q·v², F_0 of the span leaving the driver at the installed sag — the same formulas
    and inputs as :func:`chaindrive.strength.loads.loads_of`, without the contour balance."""
    if loads is not None:
        return _Forces(loads.speed, loads.peripheral_force, loads.sag_tension,
                       loads.centrifugal_tension)
    spec, driver = drive.chain.spec, drive.driver
    assert drive.power is not None and driver.speed is not None
    v = float(mean_chain_speed(spec.pitch, driver.teeth, driver.speed))
    return _Forces(v, peripheral_force(drive.power, v), installed_pretension(drive, geometry),
                   centrifugal_tension(spec.mass_per_length, v))


def _rating_checks(drive: Drive, geometry: GeometryResult, loads: _Forces,
                   s: CheckSettings) -> list[ck.Check]:
    spec = drive.chain.spec
    name = spec.designation
    assert drive.power is not None
    teeth, speed = small_sprocket(drive)
    design = drive.power * s.service_factor * s.design_factor
    rating = ratings.chain_rating(spec, teeth, speed)
    out = [ck.chain_check("power rating", name, rating.rated_power, design, rating.source,
                          f"{rating.method}: {rating.note}",
                          note_quantities=rating.note_quantities)]
    life = (None if rating.rated_power is None else
            float(wear_life_hours(rating.rated_power, design, geometry.links)))
    if s.required_life_h is None:  # the life the rating promises for this chain length
        required = BASIS_LIFE_H * geometry.links / BASIS_LINKS
        note = (f"{geometry.links} links: the rating basis 15 000 h × links/100 (set a "
                "required life for a service-life requirement)")
    else:
        required, note = s.required_life_h, f"{geometry.links} links, required life"
    out.append(ck.chain_check("wear life", name, life, required, note=f"{rating.method}; {note}"))
    galling = iso10823.galling_speed_limit(spec.pitch, teeth, design / loads.speed / spec.strands)
    out.append(ck.chain_check("speed limit", name, speed, galling, "[Shigley2015, §17-5]",
                              "pin–bush galling limit"))
    safety = static_safety_factor(spec.breaking_load, loads.peripheral_force, loads.sag_tension,
                                  loads.centrifugal_tension, s.dynamic_factor)
    out.append(ck.chain_check("static safety", name, safety,
                              chain_limits(spec, speed, ratings.ACA)[1], "[DiamondChain]",
                              "working load ≤ 1/6 of the breaking load"))
    return out


def chain_limits(spec: ChainSpec, speed: float, method: str | None = None
                 ) -> tuple[float | None, float | None]:
    """[p] and [s] of the method that checks the chain (the checks below and the strength
    summary, :func:`chaindrive.strength.strength_of`, both take them from here): the Russian
    tables by pitch and speed for GOST chains [ChainDesignRU, Table 2A, Table 9A]; no joint
    pressure limit and s ≥ 6 [DiamondChain] for rated chains (ACA, the ISO 606 B table); none
    for non-steel chains (their allowable load is the check).

    Parameters
    ----------
    spec : ChainSpec
        The chain.
    speed : float
        Small-sprocket speed [rad/s].
    method : str or None
        The method the chain is checked by (None: its own, :func:`ratings.method_for`).

    Returns
    -------
    tuple of (float or None, float or None)
        [p] [Pa] and [s] [-]; None where the method has no such limit or its table no value.
    """
    method = method or ratings.method_for(spec)
    if method == ratings.KE:
        return (ke_method.allowable_pressure(spec.pitch, speed),
                ke_method.allowable_safety_factor(spec.pitch, speed))
    if method == ratings.POLYMER:
        return None, None
    return None, ck.MIN_SAFETY_RATED


def _ke_checks(drive: Drive, geometry: GeometryResult, loads: _Forces,
               s: CheckSettings) -> list[ck.Check]:
    spec = drive.chain.spec
    name = spec.designation
    teeth, speed = small_sprocket(drive)
    area, estimated = ke_method.bearing_area(spec)
    pressure = hinge_pressure(loads.peripheral_force, s.operating_factor, area)
    note = "bearing area estimated" if estimated else ""
    allowed_p, allowed_s = chain_limits(spec, speed, ratings.KE)
    out = [ck.chain_check("hinge pressure", name, pressure, allowed_p, note=note)]
    out.append(ck.chain_check("speed limit", name, speed, ke_method.max_speed(spec.pitch),
                              "[TrinhChat2006, Table 5.8]"))
    out.append(ck.chain_check("impacts per second", name,
                              ke_method.impacts_per_second(teeth, speed, geometry.links),
                              ke_method.allowable_impacts(spec.pitch)))
    safety = static_safety_factor(spec.breaking_load, loads.peripheral_force, loads.sag_tension,
                                  loads.centrifugal_tension, s.dynamic_factor)
    out.append(ck.chain_check("static safety", name, safety, allowed_s,
                              "[TrinhChat2006, Table 5.10]"))
    return out


def _polymer_checks(drive: Drive, loads: _Forces, s: CheckSettings) -> list[ck.Check]:
    spec = drive.chain.spec
    pull = (loads.peripheral_force * s.service_factor * s.design_factor + loads.sag_tension
            + loads.centrifugal_tension)
    return [ck.chain_check("allowable load", spec.designation, pull, spec.allowable_load,
                           f"catalogue row: {spec.source}"),
            ck.chain_check("speed limit", spec.designation, loads.speed, spec.max_speed,
                           f"catalogue row: {spec.source}",
                           "" if spec.max_speed else "the catalogue gives no speed limit",
                           linear=True)]


@shared_parameters
def geometry_checks(drive: Drive, geometry: GeometryResult) -> list[ck.Check]:
    """Teeth in mesh of every sprocket, the wrap of the driver and of the small loaded sprocket
    (the others have no wrap limit: a check that cannot fail is not listed), and the longest
    span (module docstring).

    Parameters
    ----------
    %(drive_geometry)s

    Returns
    -------
    list of Check
        The layout's checks.
    """
    out: list[ck.Check] = []
    loaded = [s for s in drive.sprockets if s.role in ("driver", "driven")]
    small = min(loaded, key=lambda s: s.teeth).name
    for s, g in zip(drive.sprockets, geometry.sprockets, strict=True):
        out.append(ck.teeth_in_mesh_check(s.name, g.teeth_in_mesh, s.role))
        if s.role == "driver" or s.name == small:  # elsewhere no wrap limit: nothing to check
            out.append(ck.wrap_check(s.name, g.wrap_angle, s.role, small=s.name == small))
    longest = max(geometry.spans, key=lambda sp: sp.pitches)
    out.append(ck.span_length_check(f"span {longest.start_name} → {longest.end_name}",
                                    longest.pitches))
    return out


@shared_parameters
def chain_checks(drive: Drive, geometry: GeometryResult, settings: CheckSettings | None = None,
                 loads: LoadsResult | None = None) -> list[ck.Check]:
    """The checks of the chain itself (strength, speed, life) by its method.

    %(checks_params)s
    loads : LoadsResult or None
        The strength stage's loads of this drive (:func:`~chaindrive.strength.loads.loads_of`),
        read for v, F_t, F_0 and F_v; None: those four computed here.

    Returns
    -------
    list of Check
        The chain's checks.
    """
    s = settings or settings_for(drive)
    forces = _forces(drive, geometry, loads)
    method = s.method or ratings.method_for(drive.chain.spec)
    if method == ratings.POLYMER:
        return _polymer_checks(drive, forces, s)
    if method == ratings.KE:
        return _ke_checks(drive, geometry, forces, s)
    return _rating_checks(drive, geometry, forces, s)


@shared_parameters
def checks_for(drive: Drive, geometry: GeometryResult, settings: CheckSettings | None = None,
               loads: LoadsResult | None = None) -> tuple[ck.Check, ...]:
    """Every check of a drive: its chain's and its layout's.

    %(checks_params)s
    loads : LoadsResult or None
        The strength stage's loads of this drive, as :func:`chain_checks` reads them.

    Returns
    -------
    tuple of Check
        :func:`chain_checks` then :func:`geometry_checks`.
    """
    return (*chain_checks(drive, geometry, settings, loads), *geometry_checks(drive, geometry))


@shared_parameters
def loaded_contour_checks(drive: Drive, geometry: GeometryResult, km: float,
                          loads: LoadsResult | None = None,
                          required_life_h: float | None = None) -> tuple[ck.Check, ...]:
    """Every check of the most loaded contour: :func:`checks_for` with the drive's power
    divided by K_m, then the polymer teeth (:func:`polymer_tooth_checks`) where the span
    tensions are known.

    Parameters
    ----------
    %(drive_power)s
    %(geometry)s
    km : float
        K_m, the number of contours the power is divided by for the most loaded one [-]
        (the contours' compatibility factor, or the chain's contour count).
    loads : LoadsResult or None
        The strength stage's loads of the most loaded contour (its speed, forces and span
        tensions [N], read by the chain's and the teeth's checks); None: computed for the
        chain's checks, no tooth checks.
    required_life_h : float or None
        A required life that replaces the drive's own [h].

    Returns
    -------
    tuple of Check
        The chain's, the layout's and the polymer teeth's checks.
    """
    assert drive.power is not None
    loaded = replace(drive, power=drive.power / km)
    settings = settings_for(loaded)
    if required_life_h is not None:
        settings = replace(settings, required_life_h=required_life_h)
    teeth = () if loads is None else polymer_tooth_checks(loaded, geometry, loads)
    return (*checks_for(loaded, geometry, settings, loads), *teeth)
