"""``analyze(drive)``: every analysis of a drive in order, into one immutable result.

geometry → kinematics → (loads/strength) → (dynamics). ``Analysis.to_dict()`` is the one
place the JSON document is produced, so the command line, the report and the web page show
the same numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from chaindrive.dynamics.resonance import DynamicsResult, analyze_dynamics, resonance_warnings
from chaindrive.dynamics.ring import RingModel
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.results import GeometryResult
from chaindrive.kinematics import KinematicsResult, drive_kinematics
from chaindrive.model import Drive

if TYPE_CHECKING:
    from chaindrive.dynamics.response import DynamicResponse
    from chaindrive.multicontour.drive import ContourCheck
from chaindrive.strength import SelectionResult, StrengthResult, strength_of
from chaindrive.strength.selection import rank_chains

#: Speed range of the Campbell data and of the amplitude–frequency sweep, as fractions of
#: the nominal driver speed (issue 5: 10 %–150 %).
SPEED_RANGE = (0.1, 1.5)


@dataclass(frozen=True, slots=True)
class Analysis:
    """The results of :func:`analyze`: one part per subject, plus the drive they belong to
    (with the selected chain and the sprockets where the take-up put them).

    selection and strength are None when the design gives no power; contours (the
    multi-contour check of seed 004) is None for a single contour.
    """

    drive: Drive
    geometry: GeometryResult
    kinematics: KinematicsResult
    selection: SelectionResult | None
    strength: StrengthResult | None
    dynamics: DynamicsResult
    response: DynamicResponse | None
    contours: ContourCheck | None
    warnings: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        """The JSON document (keys snake_case, units in the names)."""
        strength = None if self.strength is None else self.strength.to_dict()
        if strength is not None and self.contours is not None:
            strength["multicontour"] = self.contours.to_dict()
            strength["contour_factor_km"] = self.contours.km
        dynamics = self.dynamics.to_dict()
        if self.response is not None:
            fragment = self.response.to_dict()
            dynamics.update(fragment["dynamics"])
            if strength is not None:
                strength.update(fragment["strength"])
        selection = None if self.selection is None else self.selection.to_dict()
        warnings = list(self.warnings)
        for part in (strength, selection):
            if part is not None:
                warnings += part.pop("warnings", [])
        return {
            "drive": drive_summary(self.drive),
            "geometry": geometry_dict(self.geometry),
            "kinematics": self.kinematics.to_dict(),
            "selection": selection,
            "strength": strength,
            "dynamics": dynamics,
            "warnings": warnings,
        }


def drive_summary(drive: Drive) -> dict[str, Any]:
    """What was analysed: name, chain, power, speed of the driver."""
    spec = drive.chain.spec
    return {
        "name": drive.name,
        "chain": spec.designation,
        "pitch_mm": spec.pitch * 1e3,
        "strands": spec.strands,
        "breaking_load_n": spec.breaking_load,
        "mass_per_length_kg_m": spec.mass_per_length,
        "tooth_form": drive.tooth_form,
        "power_w": drive.power,
        "driver": drive.driver.name,
        "driver_speed_rpm": None if drive.driver.speed is None
        else drive.driver.speed * 30 / math.pi,
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


def named_chain_warnings(drive: Drive, selection: SelectionResult) -> list[str]:
    """Say when the chain a design names fails a check of the selection."""
    own = [c for c in selection.candidates if c.designation == drive.chain.spec.designation]
    chosen = selection.chosen
    pick = "no chain passes" if chosen is None else f"the selection picks {chosen.designation}"
    return [f"{c.designation} fails checks of the selection ({', '.join(m.name for m in c.missed)})"
            f"; {pick}" for c in own if not c.passed]


def analyze(drive: Drive, *, response: bool = True) -> Analysis:
    """Run the analyses of a drive in order.

    1. selection (when the power is given): the chain a method of its family would choose —
       every check of :mod:`chaindrive.strength.drive_checks`, each chain rated by the method
       that fits it (ACA, the ISO 606 B table, Kэ, allowable load); a design that names no
       chain gets that chain, one that names its chain keeps it and the selection is shown
       beside it;
    2. contour geometry with the take-up; 3. kinematics; 4. loads and static strength;
    5. dynamics: the ring model with the static span tensions (sag), natural frequencies and
       forms, span transverse frequencies, resonance table and Campbell data from 10 % to
       150 % of the driver speed (issue 4), with the damping of ``drive.dynamics``;
    6. dynamic response (when the power is given and ``response``): start-up transient
       (when ``drive.dynamics.transient``), steady state under the polygonal effect (and the
       optional disturbances), amplitude–frequency sweep, coefficient of dynamics and the
       two-stage check k1, k2, k2min (issue 5). ``response=False`` stops after the modal
       analysis: what an interactive page or an optimiser recomputes after every change.
    """
    settings = drive.dynamics
    warnings: list[str] = []
    selection = None
    request = drive.chain.request
    m = drive.chain.contours
    if drive.power is not None:
        try:  # each of m contours carries its nominal share P/m
            selection = rank_chains(
                replace(drive, power=drive.power / m),
                standard=request.standard if request else None,
                series=request.series if request else None,
                strands=request.strands if request else None)
        except DesignError as exc:
            if request is not None:
                raise
            warnings.append(f"selection: {exc}")
        if request is not None and selection is not None:
            drive = drive.with_chain(selection.chain)  # DesignError when nothing passes
        elif selection is not None:
            warnings += named_chain_warnings(drive, selection)
    geometry = contour_geometry(drive)
    placed = drive.with_sprockets(tuple(
        s.moved_to(g.x, g.y) for s, g in zip(drive.sprockets, geometry.sprockets, strict=True)
    ))
    kinematics = drive_kinematics(placed, geometry)
    one = placed if m == 1 or placed.power is None else replace(placed, power=placed.power / m)
    strength = strength_of(one, geometry) if one.power is not None else None
    omega = placed.driver.speed
    dynamics = analyze_dynamics(
        one, geometry, damping=settings.damping_ratio,
        span_tensions=None if strength is None else strength.loads.span_tensions,
        speed_range=None if omega is None else (SPEED_RANGE[0] * omega, SPEED_RANGE[1] * omega))
    contours = None
    if m > 1 and strength is not None and placed.power is not None and omega is not None:
        from chaindrive.multicontour.drive import contour_check  # scipy.special: only here

        loads = strength.loads
        contours = contour_check(
            m, placed.power / omega, geometry.sprockets[placed.driver_index].pitch_radius,
            loads.peripheral_force * m,
            float(dynamics.parameters.chain_stiffness_n_per_m[loads.tight_span]))
        # the most loaded contour carries P/K_m (seed 004 eq. 15: [p]_m = [p]·K_m)
        strength = strength_of(replace(placed, power=placed.power / contours.km), geometry)
    dynamic_response = None
    if response and one.power is not None and omega is not None and strength is not None:
        # the time-domain solvers are imported only when needed
        from chaindrive.dynamics.response import dynamics_response, motor_of

        params = dynamics.parameters
        model = RingModel(params.masses_kg, params.stiffness_n_per_m,
                          damping_ratio=dynamics.damping_ratio,
                          names=tuple(s.name for s in placed.sprockets))
        n = len(placed.sprockets)
        dynamic_response = dynamics_response(
            one, geometry, model, span_tensions=strength.loads.span_tensions,
            harmonics=settings.harmonics, startup=settings.transient,
            startup_duration=settings.startup_duration,
            motor=motor_of(settings, one.power, omega), resistance=settings.resistance,
            speed_range=SPEED_RANGE,
            eccentricity=[settings.eccentricity] * n if settings.eccentricity > 0 else None,
            pitch_scatter=settings.pitch_scatter, accumulated_error=settings.accumulated_error)
    return Analysis(drive=placed, geometry=geometry, kinematics=kinematics, selection=selection,
                    strength=strength, dynamics=dynamics, response=dynamic_response,
                    contours=contours,
                    warnings=(*geometry.warnings, *warnings,
                              *resonance_warnings(dynamics.resonances)))
