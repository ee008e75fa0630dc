"""``analyze(drive)``: the one place a design is computed.

The stages — selection → geometry → kinematics → strength → dynamics (modes, steady state,
speed sweep, start-up) → checks — are evaluated lazily and each at most once, on one
:class:`Analysis`. The command line, the report, the web page and the optimiser all read the
same object; the optimiser asks only for the stages its objectives and constraints need.
``Analysis.to_dict()`` is the one place the JSON document is produced and
:meth:`Analysis.checks` the one list of pass/fail rules.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.checks import LINK_LEVEL, WHOLE_DRIVE, Check, CheckLimits, judged
from chaindrive.cost import CostModel, default_cost_model
from chaindrive.dynamics.checks import (
    disturbed_safety_check,
    dynamic_safety_check,
    motor_start_check,
    resonance_check,
    startup_safety_check,
)
from chaindrive.dynamics.damping import (
    PR_12_7_1820_1,
    HingeFrictionResult,
    hinge_friction_grid,
)
from chaindrive.dynamics.excitation import SpanExcitation, polygonal_excitation
from chaindrive.dynamics.frequency.afc import AfcResult
from chaindrive.dynamics.frequency.response import (
    Bands,
    drive_steady,
    drive_sweep,
    frequency_band_factors,
    span_load_maxima,
    span_loads_over,
    uncertainty_bands,
)
from chaindrive.dynamics.frequency.steady import SteadyStateResult
from chaindrive.dynamics.materials import MaterialCase, material_comparison
from chaindrive.dynamics.model.build import DriveModel, drive_model
from chaindrive.dynamics.modes import DriveDynamics, model_dynamics
from chaindrive.dynamics.parameters import RingParameters
from chaindrive.dynamics.published import published_comparison
from chaindrive.dynamics.resonance import resonance_warnings
from chaindrive.dynamics.response import (
    DynamicResponse,
    disturbance_excitations,
    polygonal_law,
)
from chaindrive.dynamics.transient.drive_startup import affordable_duration, model_startup
from chaindrive.dynamics.transient.runup import (
    LONGEST_STARTUP,
    SHORTEST_STARTUP,
    RunUp,
    elastic_stall,
    rigid_runup,
    startup_durations,
)
from chaindrive.dynamics.transient.startup import StartupResult, startup_progress
from chaindrive.dynamics.warnings import dynamics_warnings, startup_warnings
from chaindrive.errors import ChainDriveWarning, DesignError, Quantities
from chaindrive.geometry.contour import contour_geometry, driver_rotation, in_travel_order
from chaindrive.geometry.length_options import LengthChoice, length_options
from chaindrive.geometry.profile import SprocketProfile, sprocket_profiles
from chaindrive.geometry.results import GeometryResult
from chaindrive.geometry.workshop import SprocketWorkshop, sprocket_workshop
from chaindrive.kinematics import KinematicsResult, drive_kinematics, tooth_frequency
from chaindrive.metrics import DesignMetrics, design_metrics
from chaindrive.model import ChainSpec, Drive
from chaindrive.multicontour.drive import contour_check
from chaindrive.strength import (
    SelectionResult,
    StrengthResult,
    strength_of,
)
from chaindrive.strength.drive_checks import geometry_checks, loaded_contour_checks
from chaindrive.strength.duty import duty_warnings, required_life_h, service_factor_for
from chaindrive.strength.loads import installed_pretension, peripheral_force
from chaindrive.strength.lubrication import LubricationAdvice, lubrication_advice
from chaindrive.strength.safety import steady_safety_factor
from chaindrive.strength.selection import ResonanceProbe, banded_resonance_check, rank_chains
from chaindrive.strength.span_checks import fatigue_check, idler_checks, idler_warnings
from chaindrive.units import RPM_PER_RAD_S

if TYPE_CHECKING:
    from collections.abc import Callable

    from chaindrive.linklevel import LinkLevelResult, ModelComparison
    from chaindrive.linklevel.compare import GoverningLoads
    from chaindrive.multicontour.drive import ContourCheck

#: ``startup_progress(callback)``: the start-ups :func:`analyze` integrates within it report
#: their steps to ``callback`` (a presenter's progress bar; re-exported from the start-up).
__all__ = ["SPEED_RANGE", "STUDIES", "Analysis", "analyze", "startup_progress"]

#: Speed range of the Campbell data and of the speed sweep (run-up), as fractions of the
#: nominal driver speed.
SPEED_RANGE = (0.1, 1.5)
#: Speeds of the speed sweep (AFC) over :data:`SPEED_RANGE` (2000 points).
AFC_POINTS = 2000
#: Speeds of the short sweep over the band of the speed factors (the band of K_D).
BAND_POINTS = 101
#: Comparative studies an analysis runs when asked (``studies=``): the four chain/sprocket
#: material pairs on this layout, the hinge-friction damping model over its range, and the
#: link-level model of the drive (a start-up from rest, slower than the ring).
STUDIES = ("material_pairs", "hinge_friction", "links")


class Analysis:
    """Every result of one design, computed on first access and kept.

    Parameters
    ----------
    design : Drive
        The drive as given (its chain may be a request to select one).
    response : bool
        Compute the dynamic response (steady state, speed sweep, start-up) for the JSON
        document and the checks; False stops after the modal analysis.
    limits : CheckLimits
        The required values of the checks (defaults with their sources).
    cost_model : CostModel | None
        Prices for the cost (None: the packaged ones).
    studies : tuple of str
        Comparative studies to run too (:data:`STUDIES`).
    startup : bool
        Run the start-up (when ``[dynamics]`` asks for one); False leaves it and its check
        k₁ out (the optimiser does, unless its problem constrains k₁).
    link_duration_s : float | None
        Simulated time of the link-level run of the study "links" [s], within
        :data:`chaindrive.linklevel.DURATION` (None: the design's start-up duration, at
        most the upper bound of that range).
    sweep_curve : bool
        The checks read the speed sweep's per-span maxima (F₂max, for k₂min) from its whole
        curve (:attr:`afc`); False finds the same maxima by a bounded search of the sweep's
        speeds (:func:`~chaindrive.dynamics.frequency.response.span_load_maxima`) without
        the curve — the optimiser's screening of the designs it ranks. :attr:`afc` is the
        whole curve either way when it is read.

    Attributes are the stages: ``selection``, ``drive`` (with the selected chain, the
    sprockets where the take-up put them), ``geometry``, ``kinematics``, ``strength``,
    ``contours``, ``ring``, ``dynamics``, ``steady``, ``afc``, ``startup``,
    ``disturbances``, ``response``, ``metrics``, ``warnings``.
    """

    def __init__(self, design: Drive, *, response: bool = True,
                 limits: CheckLimits | None = None,
                 cost_model: CostModel | None = None, studies: tuple[str, ...] = (),
                 startup: bool = True, link_duration_s: float | None = None,
                 sweep_curve: bool = True) -> None:
        unknown = sorted(set(studies) - set(STUDIES))
        if unknown:
            raise DesignError("studies", f"unknown {', '.join(unknown)} (known: "
                              f"{', '.join(STUDIES)})")
        if link_duration_s is not None:
            # lazy: the link-level package imports numba (≈0.75 s, -X importtime); only its studies
            # need it
            from chaindrive.linklevel import checked_duration

            link_duration_s = checked_duration(link_duration_s)
        self.link_duration_s = link_duration_s
        self.design = in_travel_order(design)  # the order the driver's rotation runs the chain
        self.with_response = response
        self.with_startup = startup
        self.sweep_curve = sweep_curve
        self.studies = tuple(studies)
        self.limits = limits or CheckLimits()
        self._cost_model = cost_model
        self._selection_warnings: list[ChainDriveWarning] = []

    # ------------------------------------------------------------------ selection, geometry
    @cached_property
    def selection(self) -> SelectionResult | None:
        """Every chain of the family checked on this drive and ranked by the checks
        (:func:`chaindrive.strength.selection.rank_chains`), the resonance check of each
        candidate's own drive judged against its band when the design asks for a chain;
        None without a power."""
        d = self.design
        if d.power is None:
            return None
        request = d.chain.request
        try:  # each of m contours carries its nominal share P/m
            return rank_chains(replace(d, power=d.power / d.chain.contours),
                               standard=request.standard if request else None,
                               series=request.series if request else None,
                               strands=request.strands if request else None,
                               resonance=None if request is None else self._resonance_probe,
                               band_percent=self.limits.resonance_band_percent)
        except DesignError as exc:
            if request is not None:
                raise
            self._selection_warnings.append(ChainDriveWarning("selection.none", "chain",
                                                              f"selection: {exc}"))
            return None

    def _resonance_probe(self, spec: ChainSpec) -> ResonanceProbe:
        """The :attr:`resonance_probe` of this design with chain ``spec`` (modal analysis
        only, no response): what the selection judges a candidate's dynamics by
        (:func:`chaindrive.strength.selection.resonance_verdict`).

        Parameters
        ----------
        spec : ChainSpec
            The candidate chain.

        Returns
        -------
        ResonanceProbe
            The check and its band on the drive with that chain.
        """
        return Analysis(self.design.with_chain(spec), response=False, limits=self.limits,
                        cost_model=self._cost_model).resonance_probe

    @cached_property
    def _resonance_band(self) -> ResonanceProbe:
        """The resonance check of this drive and the detuning band of every resonance row
        (:func:`chaindrive.dynamics.frequency.response.uncertainty_bands` without the K_D sweep:
        the detunings do not need the response)."""
        dyn, u = self.dynamics, self.drive.dynamics.uncertainty
        bands = uncertainty_bands(u, dyn.modal.elastic_frequencies_hz, dyn.resonances)
        return ResonanceProbe(resonance_check(dyn.resonances,
                                              self.limits.resonance_band_percent),
                              bands.detunings, bands.uncertainty, frequency_band_factors(u))

    @cached_property
    def resonance_probe(self) -> ResonanceProbe:
        """The resonance check of this drive, the detuning band of every resonance row, and
        the inputs the frequencies rest on that the design does not give (those of the
        ``dynamics.estimate`` warnings on the sag and the link stiffness)."""
        probe, chain = self._resonance_band, self.drive.chain
        estimates = {w.part for w in dynamics_warnings(
            self.drive_model, self.bands, assumed_sag=chain.sag is None,
            computed_link_stiffness=chain.link_stiffness is None)
            if w.code == "dynamics.estimate"}
        return replace(probe, assumed=tuple((rests, give) for part, rests, give in (
            ("chain.sag", "an assumed installed sag", "the installed sag ([chain] sag)"),
            ("chain.link_stiffness", "a link stiffness computed from the plates and the pin",
             "the maker's measured link stiffness ([chain] link_stiffness)"))
            if part in estimates))

    @cached_property
    def _designed(self) -> Drive:
        """The design with the selected chain when it asked for one (a DesignError naming
        the closest chain and what it misses when no chain passes)."""
        d = self.design
        if d.chain.request is not None and self.selection is not None:
            return d.with_chain(self.selection.chain)
        return d

    @cached_property
    def geometry(self) -> GeometryResult:
        """Contour geometry with the take-up."""
        return contour_geometry(self._designed)

    @cached_property
    def drive(self) -> Drive:
        """The analysed drive: selected chain, sprockets where the take-up put them."""
        d = self._designed
        return d.with_sprockets(tuple(
            s.moved_to(g.x, g.y) for s, g in zip(d.sprockets, self.geometry.sprockets,
                                                 strict=True)))

    @cached_property
    def kinematics(self) -> KinematicsResult:
        """Speeds, chain speed and the polygonal non-uniformity."""
        return drive_kinematics(self.drive, self.geometry)

    @cached_property
    def length_choice(self) -> LengthChoice:
        """The whole link counts below and above the tight length of the layout as designed,
        each laid out with its centre distance, take-up and slack-span sag, and the design's
        pick (:func:`chaindrive.geometry.length_options.length_options`)."""
        return length_options(self._designed, self.geometry)

    @cached_property
    def lubrication(self) -> LubricationAdvice:
        """The lubrication regime of the analysed chain at its mean speed
        (:func:`chaindrive.strength.lubrication.lubrication_advice`)."""
        return lubrication_advice(self.drive.chain.spec, self.kinematics.chain_speed)

    # ------------------------------------------------------------------ strength
    @cached_property
    def _contour_drive(self) -> Drive:
        """One contour of the drive, carrying its nominal share P/m of the power."""
        d, m = self.drive, self.drive.chain.contours
        return d if m == 1 or d.power is None else replace(d, power=d.power / m)

    @cached_property
    def _static(self) -> StrengthResult | None:
        """Strength of one contour at its nominal share."""
        one = self._contour_drive
        return strength_of(one, self.geometry) if one.power is not None else None

    @cached_property
    def contours(self) -> ContourCheck | None:
        """The multi-contour check (K_m at the given risk), None for a single contour."""
        d, st = self.drive, self._static
        m = d.chain.contours
        if m == 1 or st is None or d.power is None or d.driver.speed is None:
            return None
        # imported here: it imports scipy.special, 0.46 s of every command's start-up
        # (python -X importtime), which only drives of several contours need

        return contour_check(m, d.power / d.driver.speed,
                             self.geometry.sprockets[d.driver_index].pitch_radius,
                             st.loads.peripheral_force * m,
                             float(self.ring_parameters.chain_stiffness_n_per_m[
                                 st.loads.tight_span]))

    @cached_property
    def strength(self) -> StrengthResult | None:
        """Loads and static strength; with m contours, of the most loaded one (P/K_m,
        [Lyashuk, eq. 15])."""
        if self.contours is not None and self.drive.power is not None:
            return strength_of(replace(self.drive, power=self.drive.power / self.contours.km),
                               self.geometry)
        return self._static

    # ------------------------------------------------------------------ dynamics
    @cached_property
    def drive_model(self) -> DriveModel:
        """The whole-drive model: the contour with the chain's own mass, every sprocket's
        train, the motor and the machines (:mod:`chaindrive.dynamics.model.build`); the
        static span tensions of one contour set the sag stiffness."""
        st = self._static
        return drive_model(self.drive, self.geometry,
                           span_tensions=None if st is None else st.loads.span_tensions)

    @cached_property
    def ring_parameters(self) -> RingParameters:
        """The ring reduction of the drive (reduced masses, series branch stiffnesses) for the
        ring-model tools (detuning, the inverse problem, the multi-contour check); the
        analysis itself uses :attr:`drive_model`."""
        return self.drive_model.ring

    @cached_property
    def dynamics(self) -> DriveDynamics:
        """Modes, span transverse frequencies, resonance table and Campbell data of the
        whole-drive model."""
        w = self.drive.driver.speed
        return model_dynamics(self.drive, self.geometry, self.drive_model,
                              speed_range=None if w is None
                              else (SPEED_RANGE[0] * w, SPEED_RANGE[1] * w))

    @property
    def _responds(self) -> bool:
        d = self._contour_drive
        return d.power is not None and d.driver.speed is not None and self._static is not None

    @cached_property
    def _excitation(self) -> SpanExcitation:
        """The polygonal excitation at the nominal speed."""
        d = self.drive
        assert d.driver.speed is not None
        return polygonal_excitation(self.geometry, d.driver.teeth * d.driver.speed,
                                    d.dynamics.harmonics)

    @cached_property
    def _nominal_force(self) -> float | None:
        """F_t = P/v̄ of one contour [N], v̄ the mean chain speed of the kinematics stage."""
        d = self._contour_drive
        if d.power is None or d.driver.speed is None:
            return None
        return peripheral_force(d.power, self.kinematics.chain_speed)

    @cached_property
    def afc(self) -> AfcResult | None:
        """The speed sweep over :data:`SPEED_RANGE` (its maxima are F₂max)."""
        if not self._responds:
            return None
        d = self.drive
        assert d.driver.speed is not None
        dyn = self.dynamics
        return drive_sweep(self.drive_model, dyn.modal, self._excitation,
                           np.linspace(*SPEED_RANGE, AFC_POINTS) * d.driver.speed,
                           d.driver.teeth, dyn.modal.elastic_frequencies_hz)

    @cached_property
    def _sweep_maxima(self) -> NDArray[np.float64] | None:
        """F₂max: the largest dynamic load of every span over the speed sweep [N] (the
        :attr:`afc`'s ``max_span_load``, or the same maxima by a bounded search of its speeds
        when the analysis was asked for no curve)."""
        if not self._responds:
            return None
        if self.sweep_curve or "afc" in self.__dict__:
            afc = self.afc
            return None if afc is None else afc.max_span_load
        d = self.drive
        assert d.driver.speed is not None
        return span_load_maxima(self.drive_model, self.dynamics.modal, self._excitation,
                                np.linspace(*SPEED_RANGE, AFC_POINTS) * d.driver.speed
                                * d.driver.teeth)

    @cached_property
    def steady(self) -> SteadyStateResult | None:
        """Steady polygonal response at the nominal speed, K_D, k₂ and k₂min."""
        resonance_loads = self._sweep_maxima
        if resonance_loads is None or self._static is None:
            return None
        return drive_steady(self.drive_model, self._excitation,
                            nominal_force=self._nominal_force,
                            breaking_load=self.drive.chain.spec.breaking_load,
                            operating_forces=self._static.loads.span_tensions,
                            resonance_loads=resonance_loads)

    @cached_property
    def runup(self) -> RunUp | None:
        """The run-up of the drive as one rigid body: the motor's torque against the
        machines', the time to the working speed (None without a motor or a power)."""
        if not self._responds or self.drive.power is None:
            return None
        return rigid_runup(self.drive_model)

    @cached_property
    def startup(self) -> StartupResult | None:
        """The start-up from rest with the motor law on the motor's rotor and the machines'
        moments on theirs (None when the design asks for none). Its duration is the design's
        or, automatic, the first of :func:`~chaindrive.dynamics.transient.runup.startup_durations`
        whose record settles (the last one tried otherwise)."""
        d, s = self.drive, self.drive.dynamics
        if (not self._responds or not s.transient or not self.with_startup or d.power is None
                or d.driver.speed is None):
            return None
        f_z = float(tooth_frequency(d.driver.teeth, d.driver.speed))
        durations: tuple[float, ...] = (s.startup_duration,) if s.startup_duration else \
            startup_durations(self.runup, min(LONGEST_STARTUP,
                                              affordable_duration(self.drive_model, f_z)))
        polygonal, pretension = polygonal_law(self.geometry), installed_pretension(d, self.geometry)
        record = None
        for duration in durations:
            record = model_startup(self.drive_model, polygonal, duration=duration,
                                   pretension=pretension, tooth_frequency_hz=f_z,
                                   breaking_load=d.chain.spec.breaking_load)
            if record.settled or elastic_stall(self.runup, record):
                break
        return record

    @cached_property
    def disturbances(self) -> dict[str, SteadyStateResult]:
        """Steady loads of the optional eccentricity and chain errors of ``[dynamics]``."""
        s = self.drive.dynamics
        if not self._responds:
            return {}
        n = len(self.drive.sprockets)
        return {k: drive_steady(self.drive_model, ex) for k, ex in disturbance_excitations(
            self.drive, self.geometry,
            eccentricity=[s.eccentricity] * n if s.eccentricity > 0 else None,
            pitch_scatter=s.pitch_scatter, accumulated_error=s.accumulated_error).items()}

    @cached_property
    def bands(self) -> Bands:
        """Bands of the natural frequencies, resonance detunings and K_D for stiffness and
        inertia known to ± ``[dynamics] uncertainty``."""
        u = self.drive.dynamics.uncertainty
        dyn = self.dynamics
        sweep = None
        steady = self.steady if self.with_response else None
        if steady is not None and steady.coefficient_of_dynamics is not None:
            lo, hi = frequency_band_factors(u)
            factors = np.linspace(lo, hi, BAND_POINTS)
            loads = span_loads_over(self.drive_model, dyn.modal, self._excitation,
                                    factors * steady.tooth_angular_frequency)
            sweep = (factors, np.sqrt(np.mean(loads**2, axis=1)))
        return uncertainty_bands(u, dyn.modal.elastic_frequencies_hz, dyn.resonances,
                                 sweep=sweep, nominal_force=self._nominal_force,
                                 nominal_kd=None if steady is None
                                 else steady.coefficient_of_dynamics)

    @cached_property
    def response(self) -> DynamicResponse | None:
        """The response stages together (None with ``response=False`` or without a power)."""
        if not self.with_response or self.steady is None or self.afc is None:
            return None
        st = self._static
        assert st is not None
        return DynamicResponse(self.startup, self.steady, self.afc, self.disturbances,
                               np.asarray(st.loads.span_tensions, float),
                               self.drive.chain.spec.breaking_load,
                               self.limits.allowable_dynamic_safety)

    # ------------------------------------------------------------------ studies (on request)
    @cached_property
    def material_pairs(self) -> tuple[MaterialCase, ...] | None:
        """The same layout with metal or polymer chain on metal or polymer sprockets
        ([MultimassChainDrives], Fig. 2–3, Table 1); None unless asked for in ``studies``."""
        if "material_pairs" not in self.studies or not self._responds:
            return None
        return material_comparison(self.drive, self.geometry,
                                   span_tensions=None if self._static is None
                                   else self._static.loads.span_tensions)

    @cached_property
    def hinge_friction(self) -> tuple[HingeFrictionResult, ...] | None:
        """The hinge-friction damping model [ChainHingeDissipation] for its reference chain
        over its published range of tensions and amplitudes; None unless asked for."""
        if "hinge_friction" not in self.studies:
            return None
        c = PR_12_7_1820_1
        return hinge_friction_grid(c, (250.0, 500.0, 750.0, 1000.0),
                                   tuple(np.linspace(0.015, 0.03, 7).tolist()),
                                   c.pitch * 48)  # the paper's span: 49 hinges, a = t(z − 1)

    @cached_property
    def link_level(self) -> LinkLevelResult | None:
        """The link-level model of one contour ([Pedersen2004]; docs/linklevel.md): a
        start-up from rest by the design's motor law over :attr:`link_duration_s` (None:
        the design's start-up duration, at most :data:`chaindrive.linklevel.DURATION`'s
        upper bound); None unless asked for in ``studies`` ("links")."""
        if "links" not in self.studies or not self._responds:
            return None
        # imported here: numba and the link-level kernel (0.6 s) only for this study
        from chaindrive.linklevel import DURATION, simulate

        duration = self.link_duration_s or min(
            self.drive.dynamics.startup_duration or SHORTEST_STARTUP, DURATION.high)
        return simulate(self._contour_drive, duration, geometry=self.geometry,
                        dynamics=self.drive_model)

    @cached_property
    def link_level_comparison(self) -> ModelComparison | None:
        """The summary quantities of the whole-drive model beside the link-level run's
        (:func:`chaindrive.linklevel.model_comparison`); None without the link-level run."""
        result = self.link_level
        if result is None:
            return None
        # lazy: the link-level package imports numba (≈0.75 s, -X importtime); only its studies need
        # it
        from chaindrive.linklevel import model_comparison
        from chaindrive.linklevel.compare import mode_agreement
        from chaindrive.linklevel.modes import rest_and_loaded_modes

        at_rest, loaded = rest_and_loaded_modes(self._contour_drive, geometry=self.geometry)
        link_f1 = at_rest.first_longitudinal_hz
        steady, startup = self.steady, self.startup
        assert self.drive.driver.speed is not None  # _responds
        f1 = self.dynamics.modal.first_elastic_frequency_hz
        return model_comparison(
            result, nominal_speed=self.drive.driver.speed,
            ring_span_dynamic_load=None if steady is None else steady.span_dynamic_load,
            ring_dynamic_load_rms=None if steady is None else steady.dynamic_load_rms,
            ring_kd=None if steady is None else steady.coefficient_of_dynamics,
            ring_startup_peak=None if startup is None else startup.max_span_force,
            first_frequency_hz=f1 if math.isfinite(f1) else None,
            link_first_frequency_hz=link_f1,
            # both models at the link-level's loaded state (at rest when it is not reached)
            modes=mode_agreement(self._contour_drive, geometry=self.geometry,
                                 modes=at_rest if loaded is None else loaded))

    @cached_property
    def governing_loads(self) -> GoverningLoads | None:
        """The span loads the dynamic checks take with the link-level model run beside the
        whole-drive model: per span the larger, where the link-level's is comparable
        (:func:`chaindrive.linklevel.compare.governing_loads`; docs/linklevel.md §6); None
        without the link-level run."""
        comparison, result = self.link_level_comparison, self.link_level
        if comparison is None or result is None:
            return None
        # lazy: the link-level package imports numba (≈0.75 s); only its study needs it
        from chaindrive.linklevel.compare import governing_loads

        steady, startup = self.steady, self.startup if self.with_startup else None
        return governing_loads(
            result, settled=comparison.settled,
            ring_span_dynamic_load=None if steady is None else steady.span_dynamic_load,
            ring_startup_peak=None if startup is None else startup.max_span_force,
            trains=tuple(name for name, train in self.drive_model.trains.items() if train))

    @cached_property
    def published(self) -> tuple[str, tuple[tuple[str, float, float | None, str], ...]] | None:
        """The printed figures of a published example beside this analysis' own
        (:func:`chaindrive.dynamics.published.published_comparison`): (source, rows of
        quantity, printed value, ours, unit); None for a drive that is not one of them."""
        return published_comparison(self)

    # ------------------------------------------------------------------ manufacture
    @cached_property
    def profiles(self) -> tuple[SprocketProfile, ...]:
        """Tooth form, closed outline and body of every sprocket."""
        return sprocket_profiles(self.drive)

    def workshop(self, index: int) -> SprocketWorkshop:
        """What the workshop drawing of sprocket ``index`` states besides its outline (bore
        and fit, keyway, hub, section, measurement over pins, tip diameter, material).

        Parameters
        ----------
        index : int
            The sprocket's place in the design's list [-].

        Returns
        -------
        SprocketWorkshop
            Bore, keyway, hub, section, pins measurement, tip diameter and material
            (:func:`chaindrive.geometry.workshop.sprocket_workshop`).
        """
        return sprocket_workshop(self.drive, self.profiles[index], index)

    def selection_by(self, *, method: str | None = None,
                     strands: int | None = None) -> SelectionResult:
        """The ranking with another method or number of strands than the design asks (what
        ``chaindrive select`` offers).

        The design's power is shared equally among its contours; the chain family (standard,
        series) is the design's request when it names none.

        Parameters
        ----------
        method : str or None
            ``"Kэ"`` or ``"rating"`` to rank every chain by that method
            (:func:`chaindrive.strength.selection.rank_chains`; None: each chain's own).
        strands : int or None
            Only chains of this number of strands [-] (None: the design's request, or every
            count).

        Returns
        -------
        SelectionResult
            The feasible chains ranked, with the shortfall when none fits.
        """
        d = self.design
        request = d.chain.request
        if method is None and strands is None and self.selection is not None:
            return self.selection
        return rank_chains(replace(d, power=(d.power or 0.0) / d.chain.contours),
                           method=method,
                           strands=strands or (request.strands if request else None),
                           standard=request.standard if request else None,
                           series=request.series if request else None,
                           resonance=self._resonance_probe,
                           band_percent=self.limits.resonance_band_percent)

    # ------------------------------------------------------------------ metrics
    @cached_property
    def metrics(self) -> DesignMetrics:
        """Mass, cost and volume."""
        return design_metrics(self.drive, self.geometry,
                              self._cost_model or default_cost_model())

    @cached_property
    def working_frequencies_hz(self) -> NDArray[np.float64]:
        """The working (disturbing) frequencies of the resonance table [Hz]."""
        return np.array([w.frequency for w in self.dynamics.working])

    # ------------------------------------------------------------------ checks
    @cached_property
    def _static_checks(self) -> tuple[Check, ...]:
        """The chain and layout checks (:func:`chaindrive.strength.drive_checks.checks_for`),
        of the most loaded contour; the layout checks alone without a power."""
        d = self.drive
        if d.power is None or d.driver.speed is None:
            what = "power" if d.power is None else "driver speed"
            return (*geometry_checks(d, self.geometry), judged(
                "chain strength", d.chain.spec.designation, None, None, "min", "",
                note=f"no {what} given: the chain's rating, static safety, wear life, speed "
                     "limit and the dynamic checks need the drive's power and speed",
                part="chain"))
        km = self.contours.km if self.contours is not None else d.chain.contours
        return loaded_contour_checks(d, self.geometry, km,
                                     None if self.strength is None else self.strength.loads,
                                     self.limits.required_life_h)

    @cached_property
    def _dynamic_checks(self) -> tuple[Check, ...]:
        out: list[Check] = []
        resonance = banded_resonance_check(self._resonance_band,
                                           self.limits.resonance_band_percent)
        if resonance is not None:
            out.append(resonance)
        start = motor_start_check(self.runup)
        if start is not None:
            out.append(start)
        if self.with_response and self._responds:
            k = self.limits.allowable_dynamic_safety
            gov = self.governing_loads
            q_break = self.drive.chain.spec.breaking_load
            if self.drive.dynamics.transient and self.with_startup:
                startup = self.startup
                largest = None if gov is None else gov.largest_startup()
                if startup is not None and largest is not None and largest[1] == LINK_LEVEL:
                    # the link-level run's larger start-up peak: k₁ = Q/F₁max of it
                    startup = replace(startup, k1=q_break / largest[0])
                check = startup_safety_check(startup, k, missing=self.drive_model.missing,
                                             runup=self.runup)
                if gov is not None and gov.startup_ring is not None:
                    check = _governed(check, gov.startup_note)
                out.append(check)
            steady = self.steady
            k2, worst = self._governing_k2()
            check = dynamic_safety_check("k2", k2, k)
            if gov is not None and worst is not None and gov.steady_ring is not None:
                check = _governed(check, lambda q: gov.steady_note(worst, q))
            out.append(check)
            check = dynamic_safety_check("k2min", None if steady is None else steady.k2_min, k)
            if gov is not None and check.value is not None:
                check = replace(check, governing_model=WHOLE_DRIVE, note=_joined(
                    check.note, "the whole-drive model's resonance loads govern: the "
                    "link-level run has no speed sweep through the resonances"))
            out.append(check)
            if steady is not None and self.disturbances and self._static is not None:
                polygonal = (steady.span_dynamic_load if gov is None
                             or gov.steady_dynamic is None else gov.steady_dynamic)
                disturbed = {n: r.span_dynamic_load for n, r in self.disturbances.items()}
                check = disturbed_safety_check(q_break, self._static.loads.span_tensions,
                                               polygonal, disturbed, k)
                if gov is not None and gov.steady_ring is not None:
                    total = np.asarray(self._static.loads.span_tensions, float) + polygonal
                    total = total + sum((np.asarray(v, float) for v in disturbed.values()),
                                        np.zeros_like(total))
                    span = int(np.argmax(total))
                    check = _governed(check, lambda q: gov.steady_note(span, q))
                out.append(check)
        return tuple(out)

    def _governing_k2(self) -> tuple[float | None, int | None]:
        """k₂ = min_i Q/(F_R,i + F₂,i) [MultimassChainDrives, §3.6] with the governing
        F₂,i (:attr:`governing_loads`; the whole-drive model's without the link-level run)
        and the span that decides it (None, None without the steady response)."""
        steady, st, gov = self.steady, self._static, self.governing_loads
        if steady is None:
            return None, None
        if gov is None or gov.steady_dynamic is None or st is None or steady.k2 is None:
            return steady.k2, None
        total = np.asarray(st.loads.span_tensions, float) + gov.steady_dynamic
        span = int(np.argmax(total))
        return (steady_safety_factor(self.drive.chain.spec.breaking_load,
                                     float(st.loads.span_tensions[span]),
                                     float(gov.steady_dynamic[span])), span)

    @cached_property
    def _span_checks(self) -> tuple[Check, ...]:
        """Idlers on the slack side and, with the response, the largest span force against
        the chain's fatigue strength (:mod:`chaindrive.strength.span_checks`)."""
        st = self._static
        if st is None:
            return ()
        out = idler_checks(self.drive, st.loads)
        if self.with_response and self._responds:
            steady = self.steady
            startup = self.startup if self.with_startup else None
            gov = self.governing_loads
            dynamic = (None if steady is None else steady.span_dynamic_load
                       if gov is None or gov.steady_dynamic is None else gov.steady_dynamic)
            steady_total = (None if dynamic is None
                            else np.asarray(st.loads.span_tensions, float) + dynamic)
            steady_peak = None if steady_total is None else float(np.max(steady_total))
            startup_peak = (None if startup is None else float(np.max(
                startup.max_span_force if gov is None or gov.startup_peak is None
                else gov.startup_peak)))
            check = fatigue_check(self.drive.chain.spec, steady_peak, startup_peak)
            if gov is not None and check.value is not None:
                if check.value == startup_peak and gov.startup_ring is not None:
                    check = _governed(check, gov.startup_note)
                elif steady_total is not None and gov.steady_ring is not None:
                    span = int(np.argmax(steady_total))
                    check = _governed(check, lambda q: gov.steady_note(span, q))
            out.append(check)
        return tuple(out)

    def checks(self) -> tuple[Check, ...]:
        """Every check of the design: the chain's by its method, the layout's (teeth in mesh,
        wrap, span length, idlers on the slack side), resonance, and with the response the
        dynamic safety factors k₁, k₂, k₂min and the fatigue check."""
        return (*self._static_checks, *self._span_checks, *self._dynamic_checks)

    def check(self, key: str) -> Check | None:
        """The check with this :attr:`~chaindrive.checks.Check.key` (None when the design
        has none).

        Parameters
        ----------
        key : str
            A check's stable key, e.g. ``"hinge_pressure"`` or ``"teeth_in_mesh[S3]"``.

        Returns
        -------
        Check or None
            The check of that key among :meth:`checks`, or None.
        """
        return next((c for c in self.checks() if c.key == key), None)

    @cached_property
    def warnings(self) -> tuple[ChainDriveWarning, ...]:
        """Every warning of the analysed stages."""
        out: list[ChainDriveWarning] = list(self.geometry.warnings)
        out += duty_warnings(self.drive)
        if self.drive.rotation is None:
            out.append(ChainDriveWarning(
                "duty.rotation-default", "drive.rotation",
                f"driver {self.drive.driver.name} turns {self.rotation} (default: from the "
                "order of the sprockets; set [drive] rotation to fix which span is tight)"))
        _ = self.selection
        out += self._selection_warnings
        if self.selection is not None and self.design.chain.request is None:
            out += named_chain_warnings(self.design, self.selection)
        if self._static is not None:
            out += self._static.loads.warnings
            out += self._static.warnings
            out += idler_warnings(self.drive, self._static.loads)
        out += resonance_warnings(self.dynamics.resonances)
        out += dynamics_warnings(self.drive_model, self.bands,
                                 assumed_sag=self.drive.chain.sag is None,
                                 computed_link_stiffness=self.drive.chain.link_stiffness is None)
        startup = self.startup if self.with_response else None
        if startup is not None:
            out += startup_warnings(startup, [f"{s.start_name}→{s.end_name}"
                                              for s in self.geometry.spans], self.runup)
        return tuple(dict.fromkeys(out))

    @property
    def rotation(self) -> str:
        """The driver's direction of rotation, "cw" or "ccw" (given, or from the order of
        the sprockets)."""
        return driver_rotation(self.geometry, self.drive.driver_index)

    def duty_summary(self) -> dict[str, Any]:
        """The duty of the drive for the JSON document: the service factor with its origin
        ("given", "duty classes", "default") and table, the duty classes, the required life
        [h] with its origin, and the driver's rotation with its origin."""
        sf = service_factor_for(self.drive)
        life = required_life_h(self.drive)
        return {"service_factor": sf.value, "service_factor_origin": sf.origin,
                "service_factor_table": sf.table, "service_factor_note": sf.note,
                "driver_duty": self.drive.driver_duty, "driven_duty": self.drive.driven_duty,
                "required_life_h": life,
                "required_life_origin": "given" if life is not None else
                "default: the rating method's basis",
                "rotation": self.rotation,
                "rotation_origin": "given" if self.drive.rotation is not None else
                "default: from the order of the sprockets"}

    # ------------------------------------------------------------------ the document
    def evaluate(self) -> Analysis:
        """Compute every stage this analysis reports now (errors are raised here); returns
        itself."""
        _ = self.warnings, self.kinematics, self.strength, self.contours, self.metrics
        if self.with_response:
            _ = self.response
        _ = self.material_pairs, self.hinge_friction, self.link_level_comparison
        return self

    def to_dict(self) -> dict[str, Any]:
        """The JSON document (keys snake_case, units in the names)."""
        strength = None if self.strength is None else self.strength.to_dict()
        if strength is not None and self.contours is not None:
            strength["multicontour"] = self.contours.to_dict()
            strength["contour_factor_km"] = self.contours.km
        dynamics = self.dynamics.to_dict()
        dynamics["bands"] = self.bands.to_dict()
        dynamics["runup"] = None if self.runup is None else self.runup.to_dict()
        if self.response is not None:
            fragment = self.response.to_dict()
            dynamics.update(fragment["dynamics"])
            if strength is not None:
                strength.update(fragment["strength"])
        out: dict[str, Any] = {
            "drive": {**drive_summary(self.drive), **self.duty_summary()},
            "geometry": {**geometry_dict(self.geometry),
                         "length_options": self.length_choice.to_dict()},
            "kinematics": self.kinematics.to_dict(),
            "lubrication": self.lubrication.to_dict(),
            "selection": None if self.selection is None else self.selection.to_dict(),
            "strength": strength,
            "dynamics": dynamics,
            "metrics": self.metrics.to_dict(),
            "checks": [c.to_dict() for c in self.checks()],
            "warnings": [w.to_dict() for w in self.warnings],
        }
        if self.link_level_comparison is not None and self.link_level is not None:
            comparison = self.link_level_comparison.to_dict()
            out["link_level"] = {**self.link_level.to_dict(),
                                 "dynamics_comparison": comparison.pop("rows"), **comparison}
        return out


def _joined(note: str, sentence: str) -> str:
    """``note`` and ``sentence`` as one note ("; " between them when both are given)."""
    return f"{note}; {sentence}" if note else sentence


def _governed(check: Check, said: Callable[[Quantities], tuple[str, str]]) -> Check:
    """``check`` with the model whose load it takes and the note saying so.

    Parameters
    ----------
    check : Check
        A check resting on a dynamic load.
    said : callable
        said(q) → (governing model, sentence), recording the sentence's forces in ``q``
        (:class:`~chaindrive.linklevel.compare.GoverningLoads`).

    Returns
    -------
    Check
        With :attr:`~chaindrive.checks.Check.governing_model` and the sentence added to its
        note (its numbers to its ``note_quantities``).
    """
    q = Quantities()
    model, sentence = said(q)
    return replace(check, governing_model=model, note=_joined(check.note, sentence),
                   note_quantities=(*check.note_quantities, *q.items))


def drive_summary(drive: Drive) -> dict[str, Any]:
    """What was analysed: name, chain, power, speed of the driver."""
    spec = drive.chain.spec
    return {
        "name": drive.name,
        "chain": spec.designation,
        "ansi_number": spec.ansi_twin,
        "pitch_mm": spec.pitch * 1e3,
        "strands": spec.strands,
        "breaking_load_n": spec.breaking_load,
        "mass_per_length_kg_m": spec.mass_per_length,
        "estimated_data": list(spec.estimated),
        "tooth_form": drive.tooth_form,
        "power_w": drive.power,
        "driver": drive.driver.name,
        "driver_speed_rpm": None if drive.driver.speed is None
        else drive.driver.speed * RPM_PER_RAD_S,
    }


def geometry_dict(g: GeometryResult) -> dict[str, Any]:
    """JSON part of the contour geometry (mm, degrees)."""
    return {
        "links": g.links,
        "chain_length_mm": g.chain_length * 1e3,
        "tight_length_mm": g.tight_length * 1e3,
        "tight_length_pitches": g.tight_pitches,
        "slack_mm": g.slack * 1e3,
        "center_distance_mm": None if g.center_distance is None else g.center_distance * 1e3,
        "adjusted_sprocket": None if g.adjusted is None else g.sprockets[g.adjusted].name,
        "adjustment_mm": g.adjustment * 1e3,
        "sag_allowance_mm": g.sag_allowance * 1e3,
        "direction_of_travel": "ccw" if g.orientation > 0 else "cw",
        "sprockets": [
            {
                "name": s.name,
                "teeth": s.teeth,
                "side": s.side,
                "x_mm": s.x * 1e3,
                "y_mm": s.y * 1e3,
                "pitch_diameter_mm": s.pitch_diameter * 1e3,
                "tip_diameter_mm": s.tip_diameter * 1e3,
                "root_diameter_mm": s.root_diameter * 1e3,
                "wrap_angle_deg": math.degrees(s.wrap_angle),
                "teeth_in_mesh": s.teeth_in_mesh,
            }
            for s in g.sprockets
        ],
        "spans": [
            {
                "from": s.start_name,
                "to": s.end_name,
                "length_mm": s.length * 1e3,
                "length_pitches": s.pitches,
                "inclination_deg": math.degrees(s.inclination),
                "tight": s.tight,
            }
            for s in g.spans
        ],
    }


def named_chain_warnings(drive: Drive, selection: SelectionResult) -> list[ChainDriveWarning]:
    """Say when the chain a design names fails a check of the selection."""
    own = [c for c in selection.candidates if c.designation == drive.chain.spec.designation]
    chosen = selection.chosen
    pick = "no chain passes" if chosen is None else f"the selection picks {chosen.designation}"
    if chosen is not None and own and own[0] is chosen:
        pick = "the selection picks it all the same: its layout is to change (its finding)"
    return [ChainDriveWarning(
        "selection.named-chain-fails", "chain.designation",
        f"{c.designation} fails checks of the selection "
        f"({', '.join(m.name for m in c.missed)}); {pick}") for c in own if not c.passed]


@shared_parameters
def analyze(drive: Drive, *, response: bool = True, limits: CheckLimits | None = None,
            cost_model: CostModel | None = None, studies: tuple[str, ...] = (),
            lazy: bool = False, link_duration_s: float | None = None) -> Analysis:
    """Analyse a drive: selection, contour geometry with the take-up, kinematics, loads and
    strength, the dynamic model and its modes, and (``response``) the steady state, the speed
    sweep and the start-up, the metrics and the checks.

    Parameters
    ----------
    %(drive)s
    response : bool
        False stops after the modal analysis (what an interactive page recomputes after
        every change).
    limits : CheckLimits | None
        Required values of the checks (None: the defaults with their sources).
    cost_model : CostModel | None
        Prices (None: the packaged ones).
    studies : tuple of str
        Comparative studies to run too (:data:`STUDIES`).
    lazy : bool
        Return at once and compute each stage on first access (what the optimiser does);
        False computes everything the document reports now, so that errors are raised here.
    link_duration_s : float | None
        Simulated time of the link-level run of the study "links" [s] (None: the design's
        start-up duration, at most 10 s).

    Returns
    -------
    Analysis
    """
    a = Analysis(drive, response=response, limits=limits, cost_model=cost_model,
                 studies=studies, link_duration_s=link_duration_s)
    return a if lazy else a.evaluate()
