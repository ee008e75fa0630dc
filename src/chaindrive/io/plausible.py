"""Plausibility of a design as a whole, beyond the bounds of its fields
(:mod:`chaindrive.io.limits`): a given inertia cannot be less than the sprocket's own, and a
motor whose rotor inertia is left to the estimate must lie within the estimate's range."""

from __future__ import annotations

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.dynamics.model.assembly import kloss_parameters, motor_rating
from chaindrive.dynamics.motor_inertia import estimated_rotor_inertia
from chaindrive.dynamics.motors import KlossMotor
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import sprocket_body
from chaindrive.io.limits import MIN_INERTIA_SHARE
from chaindrive.model import Drive
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["check_inertias", "check_motor_estimate"]



@shared_parameters
def check_inertias(drive: Drive) -> None:
    """Refuse a sprocket whose given inertia is below :data:`MIN_INERTIA_SHARE` of the
    inertia of its own plate.

    The inertia of a sprocket is that of *everything turning with it*, so it cannot be less
    than the sprocket's own; the plate estimate is the one the dynamics uses when no inertia
    is given (:func:`chaindrive.geometry.sprocket.sprocket_body`: a plate of the
    chain's width with lightening holes), and a tenth of it leaves room for spoked or
    polymer wheels. A smaller value is a slip of a unit (g for kg, mm² for m²) — and would
    make the ring's highest natural frequency, and with it the start-up's step count, grow
    as 1/√J.

    %(params_drive_read)s

    Raises
    ------
    DesignError
        On ``sprockets[i].inertia`` with the value and the least plausible one [kg·m²].
    """
    spec = drive.chain.spec
    for i, s in enumerate(drive.sprockets):
        if s.inertia is None:
            continue
        material = find_material(s.material, field=f"sprockets[{i}].material")
        plate = sprocket_body(spec, s.teeth, material).moment_of_inertia
        least = MIN_INERTIA_SHARE * plate
        if s.inertia < least:
            raise DesignError(
                f"sprockets[{i}].inertia",
                f"{s.inertia:.3g} kg·m² is less than a tenth of the inertia of the sprocket's "
                f"own plate ({plate:.3g} kg·m² for {s.teeth} teeth of {spec.designation} in "
                f"{material.name}); give the inertia of everything turning with it, at least "
                f"{least:.3g} kg·m²")


def _power_text(watts: float) -> str:
    """A power as a message writes it (W below 1 kW, else kW)."""
    return f"{watts:.4g} W" if watts < 1e3 else f"{watts / 1e3:.4g} kW"


@shared_parameters
def check_motor_estimate(drive: Drive) -> None:
    """Refuse a ``[motor]`` without ``rotor_inertia`` whose inertia cannot be estimated,
    naming the field the user wrote.

    The dynamics estimates the rotor inertia of an IEC cage motor from its rated torque at
    synchronous speed (:func:`chaindrive.dynamics.motor_inertia.estimated_rotor_inertia`,
    [MotiveDelphi]); the estimate covers synchronous speeds of
    :data:`~chaindrive.dynamics.motor_inertia.SPEED_RANGE_RAD_S` and rated torques of
    :data:`~chaindrive.dynamics.motor_inertia.TORQUE_RANGE_N_M`. The rated power and speed
    are the ones the dynamics uses (:func:`chaindrive.dynamics.model.assembly.motor_rating`),
    the synchronous speed the Kloss law's (:attr:`KlossMotor.synchronous_speed`), and the
    range errors the estimate's own, re-addressed to the field the designer wrote.

    %(params_drive_read)s

    Raises
    ------
    DesignError
        On ``motor.rated_speed`` or ``motor.rated_power`` when the value given is outside
        the estimate's range, else on ``motor.rotor_inertia`` (the defaults are): the
        values, the range and what to give instead.
    """
    m = drive.motor
    if m is None or m.rotor_inertia is not None:
        return
    power, speed = motor_rating(drive)
    if power is None or speed is None:
        return
    synchronous = KlossMotor(power, speed, *kloss_parameters(drive)).synchronous_speed
    try:
        estimated_rotor_inertia(power, synchronous)
    except DesignError as exc:
        outside, reason = exc.field, exc.detail  # which range, and it in rpm or N·m
    else:
        return
    d = drive.driver_index
    gears = any(e.kind == "gear" for e in drive.sprockets[d].train)
    source = ("" if m.rated_speed else f" (the driver's speed, sprockets[{d}].speed"
              + (" times the ratios of its train)" if gears else ")"))
    given = "" if m.rated_power else " (the drive's power, drive.power)"
    turning = f"{_power_text(power)}{given} at {speed * RPM_PER_RAD_S:.4g} rpm{source}"
    if outside == "motor.rated_speed" and m.rated_speed:
        raise DesignError("motor.rated_speed", f"{turning}: {reason}; give motor.rotor_inertia "
                          "(the maker's value)")
    if outside == "motor.rated_power" and (m.rated_power or m.rated_speed):
        raise DesignError("motor.rated_power" if m.rated_power else "motor.rated_speed",
                          f"{turning}: {reason}; give motor.rotor_inertia (the maker's value)")
    raise DesignError("motor.rotor_inertia", f"is needed: {turning}: {reason}; give it (the "
                      "maker's value), or a gear on the driver's train")
