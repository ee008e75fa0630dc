"""Estimated rotor inertia of an IEC standard induction motor from its rated power and speed.

Where a design gives only the motor's rated power P and synchronous speed ω_s, the moment of
inertia of its rotor is estimated from a manufacturer's catalogue of totally enclosed
fan-cooled, cage-induction IEC motors (frame sizes 56–355, 0.06–315 kW, 400 V 50 Hz): the
Motive "Delphi" series, technical data tables for 2, 4 and 6 poles [MotiveDelphi] (107
motors, listed in :data:`CATALOGUE` as printed: type, rated power [kW], rated speed [r/min],
J [kg·m²]). The rotor inertia follows the rated torque at synchronous speed T = P / ω_s (the
rotor volume grows with the torque); a least-squares fit of ln J on ln T over the catalogue::

    ln J = a0 + a1·ln T + a2·(ln T)²,   J [kg·m²], T [N·m]

(:data:`FIT_COEFFICIENTS`, refitted from the table by :func:`fit_coefficients`). Scatter of
the catalogue about the fit: rms of ln(J_catalogue / J_fit) 0.300 (a factor 1.35), all 107
motors within a factor 2.03; one more catalogue entry, 160M-6 (7.5 kW, printed 0.0081
kg·m², ten times below its neighbours 132MB-6 at 0.0449 and 160L-6 at 0.116), is taken as a
misprint and left out. Uprated motors in a smaller frame (e.g. 132MC-2, 15 kW) have less
inertia than the standard frame of the same power; the fit lies between the two.

The result is an estimate: a design that knows its motor should give the motor's inertia.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from chaindrive.errors import DesignError
from chaindrive.units import RPM_PER_RAD_S

__all__ = ["CATALOGUE", "EXCLUDED", "FIT_COEFFICIENTS", "RotorInertiaEstimate",
           "catalogue_points", "estimated_rotor_inertia", "fit_coefficients"]

#: Motive Delphi series, 400 V 50 Hz [MotiveDelphi]: (type, rated power [kW], rated speed
#: [r/min], rotor moment of inertia J [kg·m²]); the type's suffix is the number of poles.
CATALOGUE: tuple[tuple[str, float, float, float], ...] = (
    # 2 poles
    ("56A-2", 0.09, 2700, 8e-05), ("56B-2", 0.13, 2760, 0.0001), ("63A-2", 0.18, 2751, 0.00021),
    ("63B-2", 0.25, 2769, 0.0003), ("63C-2", 0.37, 2796, 0.00043), ("71A-2", 0.37, 2810, 0.00055),
    ("71B-2", 0.55, 2810, 0.0006), ("71C-2", 0.75, 2780, 0.00068), ("80A-2", 0.75, 2854, 0.00075),
    ("80B-2", 1.1, 2861, 0.0009), ("80C-2", 1.5, 2840, 0.00105), ("90S-2", 1.5, 2834, 0.0012),
    ("90L-2", 2.2, 2805, 0.0014), ("90LB-2", 3, 2847, 0.00215), ("100L-2", 3, 2885, 0.0029),
    ("100LB-2", 4, 2885, 0.0042), ("112M-2", 4, 2886, 0.0055), ("112MB-2", 5.5, 2895, 0.0082),
    ("132SA-2", 5.5, 2919, 0.0109), ("112MC-2", 7.5, 2880, 0.01), ("132SB-2", 7.5, 2913, 0.0126),
    ("132MA-2", 9.2, 2943, 0.02), ("132MB-2", 11, 2919, 0.025), ("160MA-2", 11, 2941, 0.0377),
    ("132MC-2", 15, 2936, 0.032), ("160MB-2", 15, 2941, 0.0499), ("160L-2", 18.5, 2950, 0.055),
    ("180M-2", 22, 2959, 0.075), ("200LA-2", 30, 2950, 0.124), ("200LB-2", 37, 2950, 0.139),
    ("225M-2", 45, 2970, 0.233), ("250M-2", 55, 2970, 0.312), ("280S-2", 75, 2970, 0.579),
    ("280M-2", 90, 2970, 0.675), ("315S-2", 110, 2980, 1.18), ("315MA-2", 132, 2980, 1.82),
    ("315LA-2", 160, 2980, 2.08), ("315LB-2", 200, 2980, 2.38), ("355M-2", 250, 2985, 3.0),
    ("355L-2", 315, 2985, 3.5),
    # 4 poles
    ("56A-4", 0.06, 1332, 0.00015), ("56B-4", 0.09, 1346, 0.00015), ("63A-4", 0.13, 1355, 0.0003),
    ("63B-4", 0.18, 1393, 0.0004), ("63C-4", 0.25, 1380, 0.00045), ("71A-4", 0.25, 1370, 0.0005),
    ("71B-4", 0.37, 1366, 0.0008), ("71C-4", 0.55, 1364, 0.0015), ("80A-4", 0.55, 1391, 0.0018),
    ("80B-4", 0.75, 1413, 0.0021), ("80C-4", 1.1, 1376, 0.0022), ("90S-4", 1.1, 1362, 0.0024),
    ("90L-4", 1.5, 1413, 0.003), ("90LB-4", 2.2, 1412, 0.0041), ("100LA-4", 2.2, 1431, 0.0054),
    ("100LB-4", 3, 1418, 0.0067), ("100LC-4", 4, 1415, 0.0081), ("112M-4", 4, 1453, 0.0095),
    ("112MB-4", 5.5, 1448, 0.015), ("132S-4", 5.5, 1455, 0.0214), ("112MC-4", 7.5, 1453, 0.0223),
    ("132MA-4", 7.5, 1462, 0.0296), ("132MB-4", 9.2, 1470, 0.031), ("132MC-4", 11, 1460, 0.04),
    ("160M-4", 11, 1466, 0.061), ("132MD-4", 15, 1457, 0.05), ("160L-4", 15, 1470, 0.0918),
    ("180M-4", 18.5, 1476, 0.139), ("180L-4", 22, 1470, 0.158), ("200L-4", 30, 1480, 0.262),
    ("225S-4", 37, 1480, 0.406), ("225M-4", 45, 1480, 0.469), ("250M-4", 55, 1480, 0.66),
    ("280S-4", 75, 1480, 1.12), ("280M-4", 90, 1485, 1.46), ("315S-4", 110, 1485, 3.11),
    ("315M-4", 132, 1485, 3.62), ("315LA-4", 160, 1485, 4.13), ("315LB-4", 200, 1485, 4.73),
    ("355M-4", 250, 1485, 6.5), ("355L-4", 315, 1485, 8.2),
    # 6 poles
    ("71A-6", 0.18, 929, 0.0011), ("71B-6", 0.25, 933, 0.0014), ("80A-6", 0.37, 924, 0.0016),
    ("80B-6", 0.55, 920, 0.0019), ("90S-6", 0.75, 935, 0.0029), ("90L-6", 1.1, 922, 0.0035),
    ("100L-6", 1.5, 939, 0.0069), ("112M-6", 2.2, 940, 0.014), ("132S-6", 3, 969, 0.0286),
    ("132MA-6", 4, 969, 0.0357), ("132MB-6", 5.5, 972, 0.0449), ("160M-6", 7.5, 976, 0.0081),
    ("160L-6", 11, 970, 0.116), ("180L-6", 15, 970, 0.207), ("200LA-6", 18.5, 970, 0.315),
    ("200LB-6", 22, 970, 0.36), ("225M-6", 30, 980, 0.547), ("250M-6", 37, 980, 0.843),
    ("280S-6", 45, 980, 1.39), ("280M-6", 55, 980, 1.65), ("315S-6", 75, 980, 4.11),
    ("315MA-6", 90, 985, 4.78), ("315LA-6", 110, 985, 5.45), ("315LB-6", 132, 985, 6.12),
    ("355MA-6", 160, 990, 9.5), ("355MB-6", 200, 990, 10.4), ("355L-6", 250, 990, 12.4),
)
#: Catalogue entries left out of the fit (module docstring): the printed J of 160M-6 is ten
#: times below its neighbours.
EXCLUDED = frozenset({"160M-6"})
#: (a0, a1, a2) of ln J = a0 + a1 ln T + a2 (ln T)², least squares over the catalogue.
FIT_COEFFICIENTS = (-8.076344257211018, 1.0045685299156708, 0.05484294861684664)
#: exp(rms of ln(J_catalogue / J_fit)) and exp(max |ln(J_catalogue / J_fit)|) of the fit.
RMS_SCATTER_FACTOR = 1.350
MAX_SCATTER_FACTOR = 2.022
#: Rated torques at synchronous speed covered by the catalogue [N·m].
TORQUE_RANGE_N_M = (0.2864, 2387.4)
#: Synchronous speeds accepted [rad/s]: 8-pole 50 Hz to 2-pole 60 Hz (the catalogue: 6-pole
#: to 2-pole at 50 Hz, 104.7–314.2 rad/s; the fit is in torque only).
SPEED_RANGE_RAD_S = (2.0 * math.pi * 50.0 / 4.0, 2.0 * math.pi * 60.0)


def catalogue_points() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(T, J): rated torque at synchronous speed P/ω_s [N·m] and J [kg·m²] of the catalogue
    motors used in the fit (ω_s = 2π·50 / pole pairs [rad/s]).

    Returns
    -------
    torque : ndarray
        T of every motor [N·m].
    inertia : ndarray
        Its rotor inertia J [kg·m²].

    References
    ----------
    [MotiveDelphi] (the catalogue).
    """
    torque, inertia = [], []
    for motor, power_kw, _speed, j in CATALOGUE:
        if motor in EXCLUDED:
            continue
        pole_pairs = int(motor.rsplit("-", 1)[1]) // 2
        torque.append(power_kw * 1e3 / (2.0 * math.pi * 50.0 / pole_pairs))
        inertia.append(j)
    return np.array(torque), np.array(inertia)


def fit_coefficients() -> tuple[float, float, float]:
    """Least-squares (a0, a1, a2) of ln J = a0 + a1 ln T + a2 (ln T)² over the catalogue.

    Returns
    -------
    tuple of float
        a0, a1, a2 [-] (J in kg·m², T in N·m).

    References
    ----------
    [MotiveDelphi] (the data), [Press2007, §15.4] (linear least squares).
    """
    torque, inertia = catalogue_points()
    x = np.log(torque)
    A = np.column_stack([np.ones_like(x), x, x * x])
    a = np.linalg.lstsq(A, np.log(inertia), rcond=None)[0]
    return float(a[0]), float(a[1]), float(a[2])


@dataclass(frozen=True, slots=True)
class RotorInertiaEstimate:
    """An estimated rotor inertia (not a catalogue value of the motor in the design).

    Parameters
    ----------
    inertia_kg_m2 : float
        The fit's rotor inertia J [kg·m²].
    low_kg_m2, high_kg_m2 : float
        J divided and multiplied by the largest catalogue scatter factor [kg·m²] (every
        catalogue motor lies in this band).
    rated_torque_n_m : float
        Rated torque at synchronous speed T = P/ω_s [N·m].
    rms_scatter_factor : float
        Root-mean-square scatter factor of the catalogue about the fit [-].
    is_estimate : bool
        True: an estimate, not the motor's own value.
    source : str
        Reference key of the catalogue.
    """

    inertia_kg_m2: float
    low_kg_m2: float
    high_kg_m2: float
    rated_torque_n_m: float
    rms_scatter_factor: float = RMS_SCATTER_FACTOR
    is_estimate: bool = True
    source: str = "[MotiveDelphi]"

    def to_dict(self) -> dict[str, float | bool | str]:
        """JSON-ready dict."""
        return {"rotor_inertia_kg_m2": self.inertia_kg_m2, "low_kg_m2": self.low_kg_m2,
                "high_kg_m2": self.high_kg_m2, "rated_torque_n_m": self.rated_torque_n_m,
                "rms_scatter_factor": self.rms_scatter_factor, "is_estimate": self.is_estimate,
                "source": self.source}


def estimated_rotor_inertia(rated_power_w: float,
                            synchronous_speed_rad_s: float) -> RotorInertiaEstimate:
    """Rotor moment of inertia of an IEC cage-induction motor from the catalogue fit.

    Parameters
    ----------
    rated_power_w : rated (shaft) power P [W]
    synchronous_speed_rad_s : synchronous speed ω_s = 2π f / pole pairs [rad/s]

    Returns
    -------
    RotorInertiaEstimate
        J = exp(a0 + a1 ln T + a2 (ln T)²) [kg·m²] with T = P/ω_s [N·m] (module docstring),
        and the band of the catalogue's scatter.

    References
    ----------
    [MotiveDelphi] technical data tables (2, 4, 6 poles).
    """
    P, w = float(rated_power_w), float(synchronous_speed_rad_s)
    lo_w, hi_w = SPEED_RANGE_RAD_S
    if not (math.isfinite(w) and lo_w * 0.999 <= w <= hi_w * 1.001):
        rpm = RPM_PER_RAD_S
        raise DesignError("motor.rated_speed", f"a synchronous speed of {w * rpm:.4g} rpm is "
                          f"outside the catalogue's {lo_w * rpm:.0f} to {hi_w * rpm:.0f} rpm "
                          "(8-pole 50 Hz to 2-pole 60 Hz)")
    T = P / w
    lo_t, hi_t = TORQUE_RANGE_N_M
    if not (math.isfinite(T) and lo_t * 0.999 <= T <= hi_t * 1.001):
        raise DesignError("motor.rated_power", f"{P:.4g} W at a synchronous speed of "
                          f"{w * RPM_PER_RAD_S:.4g} rpm, a rated torque P/ω_s = {T:.3g} N·m, is outside "
                          f"the catalogue's {lo_t:g} to {hi_t:g} N·m")
    x = math.log(T)
    a0, a1, a2 = FIT_COEFFICIENTS
    J = math.exp(a0 + a1 * x + a2 * x * x)
    return RotorInertiaEstimate(inertia_kg_m2=J, low_kg_m2=J / MAX_SCATTER_FACTOR,
                                high_kg_m2=J * MAX_SCATTER_FACTOR, rated_torque_n_m=T)
