"""Plausibility of a design as a whole, beyond the bounds of its fields
(:mod:`chaindrive.io.limits`): a given inertia cannot be less than the sprocket's own, and a
motor whose rotor inertia is left to the estimate must lie within the estimate's range."""

from __future__ import annotations

import math

from chaindrive.catalog import find_material
from chaindrive.dynamics.motor_inertia import (
    SPEED_RANGE_RAD_S,
    TORQUE_RANGE_N_M,
    estimated_rotor_inertia,
)
from chaindrive.dynamics.motors import KlossMotor
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import sprocket_mass_and_inertia
from chaindrive.io.limits import MIN_INERTIA_SHARE
from chaindrive.model import Drive

__all__ = ["check_inertias", "check_motor_estimate"]

_RPM = 30.0 / math.pi  # rad/s → rev/min


def check_inertias(drive: Drive) -> None:
    """Refuse a sprocket whose given inertia is below :data:`MIN_INERTIA_SHARE` of the
    inertia of its own plate.

    The inertia of a sprocket is that of *everything turning with it*, so it cannot be less
    than the sprocket's own; the plate estimate is the one the dynamics uses when no inertia
    is given (:func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`: a plate of the
    chain's width with lightening holes), and a tenth of it leaves room for spoked or
    polymer wheels. A smaller value is a slip of a unit (g for kg, mm² for m²) — and would
    make the ring's highest natural frequency, and with it the start-up's step count, grow
    as 1/√J.

    Parameters
    ----------
    drive : Drive
        The design as read.

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
        plate = sprocket_mass_and_inertia(
            spec.pitch, s.teeth, spec.inner_width, material.density, material.is_polymer,
            strands=spec.strands, transverse_pitch=spec.transverse_pitch).moment_of_inertia
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


def check_motor_estimate(drive: Drive) -> None:
    """Refuse a ``[motor]`` without ``rotor_inertia`` whose inertia cannot be estimated,
    naming the field the user wrote.

    The dynamics estimates the rotor inertia of an IEC cage motor from its rated torque at
    synchronous speed (:func:`chaindrive.dynamics.motor_inertia.estimated_rotor_inertia`,
    [MotiveDelphi]); the estimate covers synchronous speeds of
    :data:`~chaindrive.dynamics.motor_inertia.SPEED_RANGE_RAD_S` and rated torques of
    :data:`~chaindrive.dynamics.motor_inertia.TORQUE_RANGE_N_M`. The rated power and speed
    are the ones the dynamics uses: ``[motor] rated_power`` else the drive's power;
    ``[motor] rated_speed`` else the driver's speed times the gear ratios of its train; the
    synchronous speed is the Kloss law's (:attr:`KlossMotor.synchronous_speed`).

    Parameters
    ----------
    drive : Drive
        The design as read.

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
    power = m.rated_power or drive.power
    d = drive.driver_index
    driver = drive.sprockets[d]
    if power is None or driver.speed is None:
        return
    gears = [e.ratio for e in driver.train if e.kind == "gear" and e.ratio is not None]
    speed = m.rated_speed or abs(driver.speed * math.prod(gears))
    lam = m.breakdown_ratio or drive.dynamics.breakdown_ratio
    sk = m.critical_slip or drive.dynamics.critical_slip
    synchronous = KlossMotor(power, speed, lam, sk).synchronous_speed
    try:
        estimated_rotor_inertia(power, synchronous)
    except DesignError:
        pass
    else:
        return
    lo_w, hi_w = SPEED_RANGE_RAD_S
    lo_t, hi_t = TORQUE_RANGE_N_M
    give = "give motor.rotor_inertia (the maker's value)"
    source = ("" if m.rated_speed else f" (the driver's speed, sprockets[{d}].speed"
              + (" times the ratios of its train)" if gears else ")"))
    turning = (f"{speed * _RPM:.4g} rpm{source}, a synchronous speed of "
               f"{synchronous * _RPM:.4g} rpm,")
    if not lo_w <= synchronous <= hi_w:
        outside = (f"outside the synchronous speeds {lo_w * _RPM:.0f} to {hi_w * _RPM:.0f} rpm "
                   "(8-pole 50 Hz to 2-pole 60 Hz) over which the rotor inertia is estimated "
                   "[MotiveDelphi]")
        if m.rated_speed:
            raise DesignError("motor.rated_speed", f"{turning} is {outside}; {give}")
        raise DesignError("motor.rotor_inertia", f"is needed: the motor turns at {turning} "
                          f"{outside}; give it (the maker's value), or a gear on the driver's "
                          "train")
    torque = power / synchronous
    what = (f"{_power_text(power)} at {turning} is a rated torque of {torque:.3g} N·m, outside "
            f"the {lo_t:g} to {hi_t:g} N·m of the motor catalogue the rotor inertia is "
            f"estimated from [MotiveDelphi]; {give}")
    if m.rated_power:
        raise DesignError("motor.rated_power", what)
    if m.rated_speed:
        raise DesignError("motor.rated_speed", f"the rated power {what}")
    raise DesignError("motor.rotor_inertia", "is needed: the drive's power (drive.power) "
                      + what.replace(give, "give it (the maker's value)"))
