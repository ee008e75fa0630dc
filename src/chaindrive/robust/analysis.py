"""The analysis of a drive as built and as worn: :class:`PerturbedAnalysis`, an
:class:`~chaindrive.analysis.Analysis` of the same design in one state of a
:class:`~chaindrive.robust.perturbation.Perturbation`.

It goes through the analysis's own stages; what a state changes enters where the physics does:

* the chain is the design's (selected) chain with the worn pitch p(1 + ε) and the design's
  number of links, so the geometry seats it higher on every sprocket (R' = p(1 + ε)/(2 sin π/z),
  [ISO606]) and the take-up (if any) moves to fit it, or the slack grows; a take-up of known
  capacity has the chain shortened by two links each time it has absorbed that capacity
  [DiamondChainTension] (:func:`chaindrive.robust.wear.links_removed`), so the state has
  N − 2k links and the take-up stays within its travel;
* the slack that no take-up follows hangs in the slack span as a catenary [Irvine1981]: the
  static tensions take the sag ratio of :func:`chaindrive.robust.wear.equivalent_sag_ratio`
  (the static model's 2 % sag [ChainDesignRU] when new), so F₀, the span tensions, the sag
  stiffness of the spans and their transverse frequencies drop as the chain wears;
* sprocket inertias stay those of the drawing (the sprockets do not grow), reduced to the
  worn pitch radius; inertia and chain-stiffness factors and the modulus of polymer parts at
  the operating temperature scale the ring's parameters ([Delrin500P]);
* shaft positions move by the offsets, sprockets turn with their eccentricities (the
  disturbance loads [MultimassChainDrives, §2]), and parallel contours share the load by the
  key clearances of the sample ([Lyashuk], eq. 1–16, by compatibility of deformations);
* the chain's catalogue checks (tables by pitch, ratings) are judged for the catalogue chain,
  with the nominal chain speed: wear lowers F_t = P/v and F₀, so they are judged on the safe
  side; the layout and dynamic checks are the worn drive's.

References
----------
[ISO606], [Irvine1981], [ChainDesignRU], [Delrin500P], [MultimassChainDrives], [Lyashuk],
[DiamondChainWear], [DiamondChainTension]
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import cached_property

import numpy as np

from chaindrive.analysis import Analysis
from chaindrive.catalog import find_material
from chaindrive.checks import Check, judged
from chaindrive.dynamics.frequency.response import drive_steady
from chaindrive.dynamics.frequency.steady import SteadyStateResult
from chaindrive.dynamics.model.build import DriveModel, drive_model
from chaindrive.dynamics.parameters import chain_link_stiffness, drive_ring_parameters
from chaindrive.dynamics.response import disturbance_excitations
from chaindrive.model import Drive, Material
from chaindrive.multicontour.drive import ContourCheck, most_loaded_share
from chaindrive.robust.perturbation import Perturbation, modulus_factor
from chaindrive.robust.wear import catenary_excess_length, equivalent_sag_ratio, links_removed
from chaindrive.strength import StrengthResult, strength_of
from chaindrive.strength.drive_checks import checks_for, geometry_checks, settings_for
from chaindrive.strength.loads import installed_sag_ratio
from chaindrive.strength.safety import steady_safety_factor
from chaindrive.strength.sprocket_teeth import polymer_tooth_checks

__all__ = ["MIN_SAG_RATIO", "PerturbedAnalysis", "nominal_analysis", "perturbed_design",
           "removed_links"]

#: Sag ratio taken when the slack span has no slack left (the chain is pulled taut) [–].
MIN_SAG_RATIO = 1e-3


def nominal_analysis(drive: Drive) -> Analysis:
    """The analysis of a drive as drawn that the robust study perturbs (lazy, no start-up:
    k₁ is not among the robust checks).

    Parameters
    ----------
    drive : Drive
        The design as drawn.

    Returns
    -------
    Analysis
        Its lazy analysis without the start-up transient.
    """
    return Analysis(drive, startup=False)


def removed_links(nominal: Analysis, elongation: float, take_up_capacity: float | None) -> int:
    """Links the chain of ``nominal`` has lost by the elongation ε: two each time its take-up
    has absorbed ``take_up_capacity`` [DiamondChainTension]; 0 without a take-up or without a
    capacity.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn (its links, pitch, take-up).
    elongation : float
        ε [–].
    take_up_capacity : float | None
        Chain length the take-up absorbs [m] (None: it follows the chain without limit).

    Returns
    -------
    int
        2k [–] (:func:`chaindrive.robust.wear.links_removed`).
    """
    g = nominal.geometry
    if g.adjusted is None or take_up_capacity is None or take_up_capacity <= 0:
        return 0
    return links_removed(g.links, nominal.drive.chain.spec.pitch, elongation, take_up_capacity)


def perturbed_design(nominal: Analysis, perturbation: Perturbation, removed: int = 0) -> Drive:
    """The design of ``nominal`` in the state ``perturbation``: its chain (selected if it
    asked for one) with the pitch p(1 + ε) and the nominal number of links less ``removed``,
    the sprocket centres offset, every sprocket's own inertia fixed at the drawing's value.

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn.
    perturbation : Perturbation
        The state.
    removed : int
        Links taken out of the chain at the take-up [–] (:func:`removed_links`).

    Returns
    -------
    Drive
    """
    d = nominal.design
    spec = nominal.drive.chain.spec
    worn = replace(spec, pitch=spec.pitch * (1.0 + perturbation.elongation))
    chain = replace(d.chain, spec=worn, request=None, links=nominal.geometry.links - removed,
                    rounding="round up")
    inertia = nominal.ring_parameters.inertias_kg_m2
    offsets = perturbation.offsets or ((0.0, 0.0),) * len(d.sprockets)
    sprockets = tuple(
        replace(s, x=s.x + dx, y=s.y + dy,
                inertia=max(float(j) - s.flywheel, 1e-12 * float(j)), reduced_mass=None)
        for s, (dx, dy), j in zip(d.sprockets, offsets, inertia, strict=True))
    return replace(d, chain=chain, sprockets=sprockets)


class PerturbedAnalysis(Analysis):
    """The analysis of a drive in one state (module docstring).

    Parameters
    ----------
    nominal : Analysis
        The analysis of the drive as drawn (its chain, links, inertias and limits are kept).
    perturbation : Perturbation
        The state.
    allowable_elongation : float | None
        ε at which the chain is replaced [–] (the check ``chain_elongation``; None: none).
    take_up_capacity : float | None
        Chain length the take-up absorbs before the chain is shortened by two links [m]
        (None: it follows the chain without limit).
    response : bool
        Compute the dynamic response (K_D, k₂, k₂min); False stops after the modes. k₂min
        reads the speed sweep's maxima from a bounded search of its speeds, without the
        curve (``Analysis(sweep_curve=False)``: the same maxima).
    """

    def __init__(self, nominal: Analysis, perturbation: Perturbation, *,
                 allowable_elongation: float | None = None,
                 take_up_capacity: float | None = None, response: bool = True) -> None:
        removed = removed_links(nominal, perturbation.elongation, take_up_capacity)
        super().__init__(perturbed_design(nominal, perturbation, removed), response=response,
                         limits=nominal.limits, startup=False, sweep_curve=False)
        self.nominal = nominal
        self.perturbation = perturbation
        self.links_removed = removed
        self.allowable_elongation = allowable_elongation
        self.take_up_capacity = take_up_capacity

    # ------------------------------------------------------------------ chain and slack
    def _catalogue_chain(self, drive: Drive) -> Drive:
        """``drive`` with the catalogue chain (nominal pitch) for the table checks."""
        return replace(drive, chain=replace(drive.chain, spec=self.nominal.drive.chain.spec))

    @cached_property
    def extra_slack(self) -> float:
        """Chain length in the slack span beyond its chord [m]: the installed sag when new
        (``[chain] sag``, else the static model's 2 % [ChainDesignRU]) plus the slack the
        take-up does not follow (0 with a take-up)."""
        g = self.geometry
        span = g.spans[next(s.index for s in g.spans if s.start == self.drive.driver_index)]
        base = catenary_excess_length(span.length, installed_sag_ratio(self.drive))
        if g.adjusted is not None:
            return base
        return base + (g.slack - self.nominal.geometry.slack)

    @cached_property
    def sag_ratio(self) -> float:
        """Sag ratio of the slack span for the static tensions [–]: the catenary's
        (:func:`chaindrive.robust.wear.equivalent_sag_ratio`), :data:`MIN_SAG_RATIO` when no
        slack is left."""
        g = self.geometry
        span = g.spans[next(s.index for s in g.spans if s.start == self.drive.driver_index)]
        if g.adjusted is not None:
            return installed_sag_ratio(self.drive)
        if self.extra_slack <= catenary_excess_length(span.length, MIN_SAG_RATIO):
            return MIN_SAG_RATIO
        return equivalent_sag_ratio(span.length, self.extra_slack)

    @cached_property
    def _static(self) -> StrengthResult | None:
        one = self._contour_drive
        if one.power is None:
            return None
        return strength_of(self._catalogue_chain(one), self.geometry, sag_ratio=self.sag_ratio)

    @cached_property
    def _static_checks(self) -> tuple[Check, ...]:
        d = self._catalogue_chain(self.drive)
        if d.power is None or d.driver.speed is None:
            return tuple(geometry_checks(d, self.geometry))
        share = self.contours.km if self.contours is not None else d.chain.contours
        loaded = replace(d, power=d.power / share)
        settings = settings_for(loaded)
        if self.limits.required_life_h is not None:
            settings = replace(settings, required_life_h=self.limits.required_life_h)
        teeth = (() if self.strength is None
                 else polymer_tooth_checks(loaded, self.geometry, self.strength.loads))
        return (*checks_for(loaded, self.geometry, settings), *teeth)

    # ------------------------------------------------------------------ ring and contours
    def _material(self, name: str) -> Material:
        m = find_material(name)
        f = modulus_factor(m, self.perturbation.temperature_c)
        return m if f == 1.0 else replace(m, youngs_modulus=m.youngs_modulus * f)

    @cached_property
    def drive_model(self) -> DriveModel:
        """The whole-drive model in this state: the ring reduction of the worn, built drive
        (:func:`chaindrive.dynamics.parameters.drive_ring_parameters` with this state's link
        stiffness, materials at the operating temperature and span tensions), the sprocket
        inertias scaled by the state's factors; the trains as designed."""
        st = self._static
        pert = self.perturbation
        spec = self.nominal.drive.chain.spec  # the plates do not stretch: k_link is nominal
        k_link = (chain_link_stiffness(
            self.nominal.drive, self._material(spec.material).youngs_modulus,
            reference_modulus=find_material(spec.material).youngs_modulus)
            * pert.chain_stiffness_factor)
        tensions = None if st is None else st.loads.span_tensions
        p = drive_ring_parameters(self.drive, self.geometry, span_tensions=tensions,
                                  link_stiffness=k_link, material_lookup=self._material)
        if pert.inertia_factors:
            f = np.asarray(pert.inertia_factors, dtype=float)
            p = replace(p, masses_kg=p.masses_kg * f, inertias_kg_m2=p.inertias_kg_m2 * f)
        return drive_model(self.drive, self.geometry, span_tensions=tensions,
                           material_lookup=self._material, ring=p)

    @cached_property
    def contours(self) -> ContourCheck | None:
        """The multi-contour check with K_m of this state's key clearances ([Lyashuk])."""
        base: ContourCheck | None = Analysis.contours.func(self)  # type: ignore[attr-defined]
        z = self.perturbation.clearances
        if base is None or not z:
            return base
        m = base.contours
        slacks = base.c4 * np.asarray(z, dtype=float).reshape(m, 2).sum(axis=1)
        km = float(1.0 / most_loaded_share(slacks, m * base.span_deformation))
        return replace(base, km=km, km_mean=km, max_share=1.0 / km)

    @cached_property
    def disturbances(self) -> dict[str, SteadyStateResult]:
        """Steady loads of the sprockets' eccentricities of this state (and of the chain
        errors of ``[dynamics]``)."""
        ecc = self.perturbation.eccentricity
        if not ecc or not self._responds:
            return Analysis.disturbances.func(self)  # type: ignore[attr-defined,no-any-return]
        s = self.drive.dynamics
        return {k: drive_steady(self.drive_model, ex) for k, ex in disturbance_excitations(
            self.drive, self.geometry, eccentricity=list(ecc), pitch_scatter=s.pitch_scatter,
            accumulated_error=s.accumulated_error).items()}

    # ------------------------------------------------------------------ the state's own checks
    def take_up_travel(self) -> float:
        """How far the take-up moved beyond its position when new [m] (0 without one; after
        the chain was shortened, from its position when new)."""
        g, g0 = self.geometry, self.nominal.geometry
        return 0.0 if g.adjusted is None else g.adjustment - g0.adjustment

    def k2_with_errors(self) -> float | None:
        """k₂ with the eccentricity loads added: min_i Q/(F_R,i + F₂,i + F_e,i) [–] (None
        without a response or without eccentricities) [MultimassChainDrives, §2, §3.6]."""
        ecc = self.disturbances.get("eccentricity")
        st = self._static
        if ecc is None or st is None or self.steady is None:
            return None
        dynamic = self.steady.span_dynamic_load + ecc.span_dynamic_load
        factors = [steady_safety_factor(self.drive.chain.spec.breaking_load, float(fr), float(fd))
                   for fr, fd in zip(st.loads.span_tensions, dynamic, strict=True)]
        return min(factors)

    def state_checks(self) -> tuple[Check, ...]:
        """The checks of the worn and built state beyond :meth:`checks`: the chain's
        elongation against the replacement rule [DiamondChainWear], the slack left in a
        fixed-centre drive, and k₂ with the eccentricity loads. (A take-up does not fail:
        the chain is shortened by two links when it has absorbed its capacity,
        [DiamondChainTension]; :attr:`links_removed` counts them.)"""
        chain = self.drive.chain.spec.designation
        eps = self.perturbation.elongation
        out: list[Check] = []
        if self.allowable_elongation is not None:
            out.append(judged("chain elongation", chain, eps, self.allowable_elongation, "max",
                              "[DiamondChainWear]", "%", 100.0, part="wear",
                              note="length tolerance of the new chain plus wear"))
        if self.geometry.adjusted is None:
            out.append(judged("installed slack", "slack span", self.extra_slack, 0.0, "min",
                              "[Irvine1981]", "mm", 1e3, part="wear",
                              note=f"sag {self.sag_ratio:.1%} of the slack span"))
        if self.perturbation.eccentricity and self.with_response:
            out.append(judged("k2 with errors", "steady motion with eccentric sprockets",
                              self.k2_with_errors(), self.limits.allowable_dynamic_safety,
                              "min", "[MultimassChainDrives, §2, §3.6]", part="dynamics"))
        return tuple(out)

    def all_checks(self) -> tuple[Check, ...]:
        """:meth:`checks` and :meth:`state_checks` together."""
        return (*self.checks(), *self.state_checks())


def first_elastic_hz(analysis: Analysis) -> float:
    """The first elastic natural frequency f₁ of an analysis [Hz] (nan for none)."""
    f = analysis.dynamics.modal.elastic_frequencies_hz
    return float(f[0]) if f.size else math.nan
