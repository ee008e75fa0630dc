"""A damping input of the link-level model fitted to the measured decay of a tap test, with
the link-level model as the forward model.

A tap of a standing drive (one sprocket given a speed at t = 0, no motor, no machine loads)
rings down; the record's decay rate ζ is read by the logarithmic decrement of its maxima
(:func:`chaindrive.identification.damping.free_decay_damping_ratio`, [Inman2014, ch. 1]).
The link-level model (:func:`chaindrive.linklevel.simulate`) is run through the same tap,
and its record read by **the same estimator** (:func:`decay_of_signal`: the same signal, the
same linear trend taken out, the same start, floor and damped frequency), so what is fitted
is the model's reading of the decay, not a modal ratio the model does not have: three
quarters of the link-level decay of the seed drive is hinge friction, a Coulomb moment whose
decrement depends on the amplitude (docs/identification.md §4).

One input x is fitted — the links' damping ratio ζ_c (``[dynamics] damping_ratio``, which
sets the links' dampers c = 2ζ_c k_link/ω_ref, docs/linklevel.md §1) or the hinges'
coefficient of friction f — the other held at its input. The model's reading ζ_m(x) is
evaluated on a grid of x (:data:`GRID_POINTS`, log-spaced over :data:`DAMPING_RATIO_RANGE` or
:data:`HINGE_FRICTION_RANGE`; a run from which the estimator cannot read a decay is left out
and counted) and taken as linear in ln x between the grid's points. The 95 % interval is the
set of x whose ζ_m(x) lies within 1.96 u of the record's ζ, u the estimator's own standard
uncertainty (the straight line's standard error, [JCGM100, §5.1]): the inversion of the test
|ζ_m(x) − ζ| ≤ 1.96 u [CasellaBerger2002, §9.2.1], reported from its lowest to its highest
x (a set in pieces by its hull). Where ζ_m is locally linear and monotone
this is x̂ ± 1.96 u/|dζ_m/dx|, the estimate's uncertainty propagated through the local slope
[JCGM100, §5.1]; where ζ_m is flat or turns back it stays the set the record does not
reject, which a slope would not give. x̂ is the crossing ζ_m(x) = ζ nearest the input (else
the grid point of least |ζ_m − ζ|). An interval that reaches an end of the grid is open
there (``open_below`` / ``open_above``): the record does not bound x on that side, and the
fit is flagged as not identified.

u comes from the scatter of the record's maxima about the line, which holds the beat of the
mode with its neighbours as well as the noise; the model's reading beats the same way, so u
overstates the noise's share and the interval errs wide.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from scipy.signal import detrend

from chaindrive.dynamics.damping import DEFAULT_DAMPING_RATIO
from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.identification.damping import (
    MeasuredDamping,
    free_decay_damping_ratio,
    with_damping_ratio,
)
from chaindrive.identification.fitting import Z95

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.simulate import StaticState
    from chaindrive.model import Drive

__all__ = ["DAMPING_RATIO_RANGE", "GRID_POINTS", "HINGE_FRICTION_RANGE",
           "DecayCurve", "LinkLevelDampingCalibration", "TapTest",
           "calibrate_link_level_damping", "decay_curve", "decay_of_signal",
           "fit_decay_curve", "tap_decay"]

FloatArray = np.ndarray[Any, np.dtype[np.float64]]
Parameter = Literal["damping_ratio", "hinge_friction"]

#: Runs of the link-level tap test on a log-spaced grid of the fitted input [-] (0.5 s of
#: CPU each for 0.5 s of the seed drive's tap).
GRID_POINTS = 13
#: The grid of the links' damping ratio ζ_c [-] (a choice: a factor 100 about the seed's
#: 0.0633).
DAMPING_RATIO_RANGE = (0.005, 0.5)
#: The grid of the hinges' coefficient of friction f [-] (a choice: a factor 20 about the
#: link-level model's default 0.1).
HINGE_FRICTION_RANGE = (0.02, 0.4)


@dataclass(frozen=True, slots=True)
class TapTest:
    """The tap test a decay was recorded from, which the forward model repeats.

    Parameters
    ----------
    sprocket : int
        Index of the tapped sprocket in the design's order [-].
    speed : float
        Speed given to it at t = 0 [rad/s].
    duration : float
        Length of the record [s].
    sample_rate : float
        Requested sample rate [Hz] (the run records at the nearest whole number of steps).
    signal : str
        The recorded column of the link-level history (e.g. ``"speed_S3_rad_s"``).
    frequency : float
        The mode's damped frequency f_d the maxima are spaced by [Hz].
    skip : float
        The start of the record left out (the tap's first transient) [s].
    floor : float
        Maxima below this fraction of the record's largest |x| are not used [-].
    """

    sprocket: int
    speed: float
    duration: float
    sample_rate: float
    signal: str
    frequency: float
    skip: float = 0.02
    floor: float = 0.05


def decay_of_signal(time: FloatArray, signal: FloatArray, test: TapTest) -> tuple[float, float]:
    """ζ and u(ζ) of a tap test's record: its linear trend taken out (a standing drive turns
    slowly under the chain's weight), the first ``test.skip`` seconds left out, then
    :func:`~chaindrive.identification.damping.free_decay_damping_ratio` at
    ``test.frequency`` with the floor ``test.floor`` × the largest |x| left.

    Parameters
    ----------
    time : ndarray
        t [s], evenly spaced.
    signal : ndarray
        The record [any unit].
    test : TapTest
        The test.

    Returns
    -------
    ratio, std : float
        ζ and u(ζ) [-].

    Raises
    ------
    DesignError
        Fewer than 3 maxima above the floor, or maxima that do not decay.
    """
    rate = 1.0 / float(np.median(np.diff(time)))
    x = np.asarray(detrend(np.asarray(signal, dtype=float)), dtype=float)[int(test.skip * rate):]
    return free_decay_damping_ratio(x, rate, test.frequency,
                                    floor=test.floor * float(np.abs(x).max()))


def tap_decay(drive: Drive, test: TapTest, *, hinge_friction: float | None = None,
              geometry: GeometryResult | None = None, static: StaticState | None = None
              ) -> tuple[FloatArray, FloatArray]:
    """The link-level model's record of ``test``: (t [s], the signal) of
    :func:`chaindrive.linklevel.simulate` from the static state, no motor and no machine
    loads, every damper on, the tapped sprocket given ``test.speed``.

    Parameters
    ----------
    drive : Drive
        The design (its ``[dynamics] damping_ratio`` sets the links' dampers).
    test : TapTest
        The test.
    hinge_friction : float or None
        The hinges' coefficient of friction [-] (None: the model's default, 0.1).
    geometry : GeometryResult or None
        The design's contour (None: built here).
    static : StaticState or None
        The drive's static state (:func:`chaindrive.linklevel.simulate.static_state`;
        None: solved here).

    Returns
    -------
    time, signal : ndarray
        [s] and the signal's unit.
    """
    from chaindrive.linklevel import simulate  # lazy: numba's kernels

    kick = [0.0] * len(drive.sprockets)
    kick[test.sprocket] = test.speed
    run = simulate(drive, test.duration, motor=False, initial_speed="rest", damping=True,
                   kick_rad_s=kick, sample_rate_hz=test.sample_rate,
                   hinge_friction=hinge_friction, geometry=geometry, static=static)
    names, table = run.history()
    if test.signal not in names:
        raise DesignError("signal", f"{test.signal!r}; allowed: {', '.join(names[1:])}")
    return (np.asarray(table[:, 0], dtype=float),
            np.asarray(table[:, names.index(test.signal)], dtype=float))


@dataclass(frozen=True, slots=True)
class DecayCurve:
    """The link-level model's reading ζ_m of a tap test's decay over a grid of one input.

    Parameters
    ----------
    parameter : str
        ``"damping_ratio"`` (ζ_c) or ``"hinge_friction"`` (f).
    initial : float
        The input's value in the design (or the model's default) [-].
    grid : ndarray
        The input's values run [-].
    ratios : ndarray
        ζ_m at each [-] (NaN: the estimator read no decay from that run).
    stds : ndarray
        u(ζ_m) the estimator gives each run [-] (NaN where none).
    held : tuple of str
        The damping inputs held, with their values and where they come from.
    """

    parameter: str
    initial: float
    grid: FloatArray
    ratios: FloatArray
    stds: FloatArray
    held: tuple[str, ...]

    @property
    def unread(self) -> int:
        """Runs from which no decay was read [-]."""
        return int(np.count_nonzero(~np.isfinite(self.ratios)))


def decay_curve(drive: Drive, test: TapTest, *, parameter: Parameter = "damping_ratio",
                grid: Sequence[float] | None = None, hinge_friction: float | None = None
                ) -> DecayCurve:
    """Run the tap test on the link-level model at each value of one damping input and read
    each run's decay by :func:`decay_of_signal` (module docstring). The runs share the
    contour and the static state they start from, solved once: neither damping input enters
    the static balance (:func:`chaindrive.linklevel.simulate.static_key`).

    Parameters
    ----------
    drive : Drive
        The design.
    test : TapTest
        The test that was recorded.
    parameter : {"damping_ratio", "hinge_friction"}
        The input varied; the other is held.
    grid : sequence of float or None
        Its values [-] (None: :data:`GRID_POINTS` log-spaced over
        :data:`DAMPING_RATIO_RANGE` or :data:`HINGE_FRICTION_RANGE`).
    hinge_friction : float or None
        The hinges' coefficient of friction held when ζ_c is varied [-] (None: the model's
        default, 0.1).

    Returns
    -------
    DecayCurve

    Raises
    ------
    DesignError
        An unknown parameter, or a grid value out of range.
    """
    from chaindrive.analysis import analyze  # lazy: analysis imports the whole pipeline
    from chaindrive.linklevel.equilibrium import installed_geometry  # lazy: numba's kernels
    from chaindrive.linklevel.model import HINGE_FRICTION, build_model  # lazy: numba's kernels
    from chaindrive.linklevel.simulate import static_state  # lazy: numba's kernels

    zeta_c = float(np.mean(analyze(drive, response=False).dynamics.model.span_damping_ratios))
    zeta_src = ("given ([dynamics] damping_ratio)" if drive.dynamics.damping_ratio is not None
                else "from the design's materials; the design gives none")
    hinge = HINGE_FRICTION if hinge_friction is None else float(hinge_friction)
    hinge_src = ("given" if hinge_friction is not None
                 else "the link-level model's default; the design gives none")
    contact = (f"the roller–tooth contacts' damping ratio {DEFAULT_DAMPING_RATIO:g} (the "
               "link-level model's default)")
    if parameter == "damping_ratio":
        span, initial = DAMPING_RATIO_RANGE, zeta_c
        held = (f"the hinges' coefficient of friction {hinge:g} ({hinge_src})", contact)
    elif parameter == "hinge_friction":
        span, initial = HINGE_FRICTION_RANGE, hinge
        held = (f"the links' damping ratio {zeta_c:.4g} ({zeta_src})", contact)
    else:
        raise DesignError("--parameter", f"{parameter!r}; allowed: damping_ratio, "
                          "hinge_friction")
    xs = (np.geomspace(span[0], span[1], GRID_POINTS) if grid is None
          else np.asarray(sorted(grid), dtype=float))
    upper = 0.999 if parameter == "damping_ratio" else math.inf
    if xs.size < 2 or not np.all((xs > 0) & (xs < upper)):
        raise DesignError("grid", f"{xs.tolist()}; allowed: two or more values above 0"
                          + (" and below 0.999" if parameter == "damping_ratio" else ""))
    ratios = np.full(xs.size, np.nan)
    stds = np.full(xs.size, np.nan)
    geometry = contour_geometry(drive)
    model = build_model(drive, installed_geometry(drive, geometry)[0], hinge_friction=hinge)
    static = static_state(drive, model, geometry)  # refused by a run it does not fit
    for i, x in enumerate(xs):
        if parameter == "damping_ratio":
            t, y = tap_decay(with_damping_ratio(drive, float(x)), test, hinge_friction=hinge,
                             geometry=geometry, static=static)
        else:
            t, y = tap_decay(drive, test, hinge_friction=float(x), geometry=geometry,
                             static=static)
        try:
            ratios[i], stds[i] = decay_of_signal(t, y, test)
        except ChainDriveError:  # the estimator reads no decay from this run: left out
            continue
    return DecayCurve(parameter, float(initial), xs, ratios, stds, held)


@dataclass(frozen=True, slots=True)
class LinkLevelDampingCalibration:
    """One damping input of the link-level model fitted to a tap test's decay (module
    docstring).

    Parameters
    ----------
    curve : DecayCurve
        The model's readings over the grid.
    measured : MeasuredDamping
        The record's ζ and u(ζ) (mode 1: the tapped mode).
    value : float
        x̂ [-].
    interval : tuple of float
        95 % interval [-] (an open end is the grid's end).
    open_below, open_above : bool
        The interval reaches that end of the grid: the record does not bound x there.
    log_slope : float
        d ln ζ_m/d ln x at x̂ (the secant of the grid interval holding it) [-].
    """

    curve: DecayCurve
    measured: MeasuredDamping
    value: float
    interval: tuple[float, float]
    open_below: bool
    open_above: bool
    log_slope: float

    @property
    def identified(self) -> bool:
        """The interval is bounded on both sides within the grid."""
        return not (self.open_below or self.open_above)

    @property
    def fitted_ratio(self) -> float:
        """ζ_m at x̂ [-] (linear in ln x between the grid's points)."""
        return float(_reading(self.curve)(math.log(self.value)))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (dimensionless values: no unit in the keys)."""
        c = self.curve
        return {
            "model": "link-level",
            "parameter": ("dynamics.damping_ratio" if c.parameter == "damping_ratio"
                          else "link-level hinge_friction"),
            "initial": c.initial,
            "fitted": self.value,
            "interval_95": list(self.interval),
            "interval_open_below": self.open_below,
            "interval_open_above": self.open_above,
            "identified": self.identified,
            "measured_decay_ratio": self.measured.ratio,
            "measured_decay_std": self.measured.std,
            "model_decay_ratio": self.fitted_ratio,
            "log_sensitivity": self.log_slope,
            "grid": c.grid.tolist(),
            "grid_decay_ratios": [None if not math.isfinite(z) else float(z)
                                  for z in c.ratios],
            "grid_runs_unread": c.unread,
            "held": list(c.held),
        }


def _reading(curve: DecayCurve) -> Any:
    """ζ_m as a function of ln x: linear between the grid points read (np.interp)."""
    ok = np.isfinite(curve.ratios)
    lx, z = np.log(curve.grid[ok]), curve.ratios[ok]
    return lambda t: np.interp(t, lx, z)


def _band_pieces(lx: FloatArray, r: FloatArray, band: float) -> list[tuple[float, float]]:
    """The pieces of each grid interval [lx_i, lx_i+1] where |r| ≤ band, r linear in
    between (empty ones left out)."""
    pieces = []
    for i in range(lx.size - 1):
        a, b = float(r[i]), float(r[i + 1])
        lo, hi = 0.0, 1.0  # fraction s of the interval, r = a + (b − a) s
        if a == b:
            if abs(a) > band:
                continue
        else:
            s1, s2 = sorted(((band - a) / (b - a), (-band - a) / (b - a)))
            lo, hi = max(lo, s1), min(hi, s2)
            if lo > hi:
                continue
        width = float(lx[i + 1] - lx[i])
        pieces.append((float(lx[i]) + lo * width, float(lx[i]) + hi * width))
    return pieces


def fit_decay_curve(curve: DecayCurve, measured: MeasuredDamping
                    ) -> LinkLevelDampingCalibration:
    """Fit the input to the record's decay on the model's curve (module docstring): x̂ where
    ζ_m(x) = ζ, the 95 % interval {x : |ζ_m(x) − ζ| ≤ 1.96 u}.

    Parameters
    ----------
    curve : DecayCurve
        :func:`decay_curve` of the test the record is of.
    measured : MeasuredDamping
        The record's ζ and u(ζ) (:func:`decay_of_signal`).

    Returns
    -------
    LinkLevelDampingCalibration

    Raises
    ------
    DesignError
        A measured ratio not in (0, 1) or an uncertainty not positive; fewer than 2 grid
        runs read; no x on the grid within 1.96 u of the record (the model cannot give the
        record's decay with the other inputs held).

    References
    ----------
    [CasellaBerger2002, §9.2.1]; [JCGM100, §5.1].
    """
    if not (math.isfinite(measured.ratio) and 0 < measured.ratio < 1):
        raise DesignError("decay", f"damping ratio {measured.ratio!r}; allowed: above 0 and "
                          "below 1")
    if not (math.isfinite(measured.std) and measured.std > 0):
        raise DesignError("decay", f"uncertainty {measured.std!r}; allowed: above 0")
    ok = np.isfinite(curve.ratios)
    if ok.sum() < 2:
        raise DesignError("grid", f"{int(ok.sum())} of {curve.grid.size} runs read a decay; "
                          "allowed: 2 or more")
    lx, r = np.log(curve.grid[ok]), curve.ratios[ok] - measured.ratio
    pieces = _band_pieces(lx, r, Z95 * measured.std)
    if not pieces:
        raise DesignError("decay", f"ζ = {measured.ratio:.4g} ± {measured.std:.2g}: the model "
                          f"reads {np.nanmin(curve.ratios):.4g} to {np.nanmax(curve.ratios):.4g} "
                          f"over {curve.parameter} {curve.grid[0]:.3g} to {curve.grid[-1]:.3g} "
                          "with the other inputs held; allowed: a decay the model can give")
    l0 = math.log(curve.initial)
    roots = [float(lx[i]) for i in range(lx.size) if r[i] == 0]
    roots += [float(lx[i] - r[i] * (lx[i + 1] - lx[i]) / (r[i + 1] - r[i]))
              for i in range(lx.size - 1) if r[i] * r[i + 1] < 0]
    best = (min(roots, key=lambda t: abs(t - l0)) if roots
            else float(lx[int(np.argmin(np.abs(r)))]))
    j = min(max(int(np.searchsorted(lx, best)) - 1, 0), lx.size - 2)
    z = curve.ratios[ok]
    slope = float((math.log(z[j + 1]) - math.log(z[j])) / (lx[j + 1] - lx[j]))
    lo, hi = min(p[0] for p in pieces), max(p[1] for p in pieces)
    tol = 1e-9
    return LinkLevelDampingCalibration(
        curve, measured, math.exp(best), (math.exp(lo), math.exp(hi)),
        lo <= math.log(curve.grid[0]) + tol, hi >= math.log(curve.grid[-1]) - tol, slope)


def calibrate_link_level_damping(drive: Drive, measured: MeasuredDamping, test: TapTest, *,
                                 parameter: Parameter = "damping_ratio",
                                 hinge_friction: float | None = None
                                 ) -> LinkLevelDampingCalibration:
    """Fit ζ_c or the hinges' friction f to the decay of a tap test recorded as ``test``
    (module docstring): :func:`decay_curve` then :func:`fit_decay_curve`.

    Parameters
    ----------
    drive : Drive
        The design.
    measured : MeasuredDamping
        The record's ζ and u(ζ), read by :func:`decay_of_signal` with ``test``.
    test : TapTest
        The tap and how its decay is read.
    parameter : {"damping_ratio", "hinge_friction"}
        What is fitted; the other is held.
    hinge_friction : float or None
        f held when ζ_c is fitted [-] (None: the model's default, 0.1).

    Returns
    -------
    LinkLevelDampingCalibration
    """
    curve = decay_curve(drive, test, parameter=parameter, hinge_friction=hinge_friction)
    return fit_decay_curve(curve, measured)
