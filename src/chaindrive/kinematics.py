r"""Polygonal (chordal) kinematics of a roller chain on a sprocket (SI units).

Pure, vectorised laws of [ChainNonUniformity] and of the harmonic excitation of
[MultimassChainDrives, §3.1]; the drive-level kinematics (speeds of every sprocket of a
contour) is built on them at the end (:func:`drive_kinematics`).
The formulas and the derivation of the Fourier series are in ``docs/kinematics.md``.

Conventions
-----------
* ``speed`` ω is the sprocket's angular speed [rad/s] (rpm·π/30), ``pitch`` p = t [m].
* The **tooth phase** ψ [rad] counts sprocket rotation in units of the angular pitch:
  ψ = z·ω·τ + ψ0 advances by 2π per tooth (per period of the tooth frequency). The
  articulation angle of the hinge that drives the span is β = wrap(ψ)/z ∈ [−π/z, π/z)
  ([ChainNonUniformity]: β from −φ1/2 to φ1/2, φ1 = 2π/z). ψ = 0 (β = 0) is the instant when the
  radius to that hinge is perpendicular to the span: the chain speed is then largest.
* The hinge position along the span is R·sin β with R = p/(2 sin(π/z)); over one tooth
  it advances 2R sin(π/z) = p, the same as uniform motion at the mean speed
  v̄ = z p ω/(2π), whose position is (p/2π)·ψ.

Deviation of the terminal hinge from uniform motion (derived in docs/kinematics.md)::

    δ(ψ) = R sin(ψ/z) − p ψ/(2π),          ψ ∈ [−π, π), periodic in 2π
         = (p/π) Σ_{k≥1} (−1)^{k+1} sin(kψ) / (k (k² z² − 1))

δ is odd, zero at ψ = 0 and ψ = ±π and zero-mean; dδ/dτ = v(τ) − v̄.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive._numeric import FloatOrArray
from chaindrive._numeric import float_or_array as _out
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import pitch_radius as _radius
from chaindrive.geometry.sprocket import teeth_array as _teeth
from chaindrive.units import RPM_PER_RAD_S, TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

# ---------------------------------------------------------------------------------------
# Mean motion
# ---------------------------------------------------------------------------------------

def mean_chain_speed(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike) -> FloatOrArray:
    """Mean chain speed v̄ = z·p·ω/(2π) (v = z1 p n1 / 60 000 with n1 in rpm and p in mm).

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m].
    teeth : int or array_like
        Number of teeth z of the sprocket [-].
    speed : float or array_like
        Its angular speed ω [rad/s].

    Returns
    -------
    float or numpy.ndarray
        v̄ [m/s].

    References
    ----------
    [ChainNonUniformity, eq. 4]; [Shigley2015, Eq. 17-30].
    """
    return _out(_teeth(teeth) * np.asarray(pitch, float) * np.asarray(speed, float) / TWO_PI)


def tooth_frequency(teeth: ArrayLike, speed: ArrayLike) -> FloatOrArray:
    """Tooth (mesh) frequency f_z = z·ω/(2π), the same for every sprocket of one contour.

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].
    speed : float or array_like
        Angular speed ω [rad/s].

    Returns
    -------
    float or numpy.ndarray
        f_z [Hz].

    References
    ----------
    [MultimassChainDrives, §3.1] (ω_z = z1 ω1 = z2 ω2 = …).
    """
    return _out(_teeth(teeth) * np.asarray(speed, float) / TWO_PI)


def mean_driven_speed(teeth_driver: ArrayLike, speed_driver: ArrayLike,
                      teeth_driven: ArrayLike) -> FloatOrArray:
    """Mean speed of a sprocket driven by the same chain ω2 = z1·ω1/z2.

    Parameters
    ----------
    teeth_driver : int or array_like
        z1 [-].
    speed_driver : float or array_like
        ω1 [rad/s].
    teeth_driven : int or array_like
        z2 [-].

    Returns
    -------
    float or numpy.ndarray
        ω2 [rad/s].

    References
    ----------
    [ChainNonUniformity, eq. 4] (z1 n1 = z2 n2).
    """
    return _out(_teeth(teeth_driver) * np.asarray(speed_driver, float) / _teeth(teeth_driven))


# ---------------------------------------------------------------------------------------
# Polygonal speed variation
# ---------------------------------------------------------------------------------------

@shared_parameters
def max_chain_speed(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike) -> FloatOrArray:
    """Largest chain speed v_max = R·ω, at β = 0.

    %(pitch_teeth_speed_returns)s
        v_max [m/s].

    References
    ----------
    [ChainNonUniformity].
    """
    z = _teeth(teeth)
    return _out(_radius(pitch, z) * np.asarray(speed, float))


@shared_parameters
def min_chain_speed(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike) -> FloatOrArray:
    """Smallest chain speed v_min = R·ω·cos(π/z), at β = ±π/z.

    %(pitch_teeth_speed_returns)s
        v_min [m/s].

    References
    ----------
    [ChainNonUniformity].
    """
    z = _teeth(teeth)
    return _out(np.asarray(max_chain_speed(pitch, z, speed)) * np.cos(np.pi / z))


def speed_variation_percent(teeth: ArrayLike) -> FloatOrArray:
    """Polygonal speed variation 100·(v_max − v_min)/v_max = 100·(1 − cos(π/z)).

    This is the definition chaindrive reports (docs/kinematics.md): v_max = Rω and
    v_min = Rω cos(π/z) of [ChainNonUniformity], the "Ungleichförmigkeit" of German
    practice [BSWikiPolygon] (z = 16 → 1.92 %). See
    :func:`speed_variation_about_mean_percent` for Shigley's definition.

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].

    Returns
    -------
    float or numpy.ndarray
        The variation [%].

    References
    ----------
    [ChainNonUniformity]; [BSWikiPolygon].
    """
    return _out(100.0 * (1.0 - np.cos(np.pi / _teeth(teeth))))


def speed_variation_about_mean_percent(teeth: ArrayLike) -> FloatOrArray:
    """Chordal speed variation about the mean ΔV/V = (v_max − v_min)/v̄
    = (π/z)·(1/sin(π/z) − 1/tan(π/z)).

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].

    Returns
    -------
    float or numpy.ndarray
        ΔV/V [%].

    References
    ----------
    [Shigley2015, §17-5].
    """
    a = np.pi / _teeth(teeth)
    return _out(100.0 * a * (1.0 / np.sin(a) - 1.0 / np.tan(a)))


# ---------------------------------------------------------------------------------------
# Instantaneous motion over a tooth period
# ---------------------------------------------------------------------------------------

def tooth_phase(teeth: ArrayLike, speed: ArrayLike, time: ArrayLike,
                phase: ArrayLike = 0.0) -> FloatOrArray:
    """Tooth phase ψ = z·ω·τ + ψ0 (2π per tooth).

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].
    speed : float or array_like
        Angular speed ω [rad/s].
    time : float or array_like
        Time τ [s].
    phase : float or array_like
        ψ0 [rad].

    Returns
    -------
    float or numpy.ndarray
        ψ [rad].
    """
    return _out(_teeth(teeth) * np.asarray(speed, float) * np.asarray(time, float)
                + np.asarray(phase, float))


def wrap_phase(phase: ArrayLike) -> FloatOrArray:
    """A tooth phase wrapped into [−π, π).

    Parameters
    ----------
    phase : float or array_like
        ψ [rad].

    Returns
    -------
    float or numpy.ndarray
        wrap(ψ) [rad].
    """
    return _out(np.mod(np.asarray(phase, float) + np.pi, TWO_PI) - np.pi)


def articulation_angle(teeth: ArrayLike, phase: ArrayLike) -> FloatOrArray:
    """Angle β = wrap(ψ)/z ∈ [−π/z, π/z) of the hinge that drives the span.

    Parameters
    ----------
    teeth : int or array_like
        Number of teeth z [-].
    phase : float or array_like
        Tooth phase ψ [rad].

    Returns
    -------
    float or numpy.ndarray
        β [rad].

    References
    ----------
    [ChainNonUniformity].
    """
    return _out(np.asarray(wrap_phase(phase)) / _teeth(teeth))


@shared_parameters
def _rim_speed_and_angle(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike,
                         phase: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Speed R·ω of the pitch circle and angle β = wrap(ψ)/z of the hinge that drives the span.

    Parameters
    ----------
    %(pitch_teeth_speed_phase)s

    Returns
    -------
    rim_speed : numpy.ndarray
        R·ω [m/s].
    beta : numpy.ndarray
        β [rad].
    """
    z = _teeth(teeth)
    rim_speed = np.asarray(max_chain_speed(pitch, z, speed), dtype=float)
    return rim_speed, np.asarray(articulation_angle(z, phase), dtype=float)


@shared_parameters
def instantaneous_chain_speed(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike,
                              phase: ArrayLike) -> FloatOrArray:
    """Chain speed along the span v = R·ω·cos β, β = wrap(ψ)/z.

    Parameters
    ----------
    %(pitch_teeth_array)s
    speed : float or array_like
        Angular speed ω [rad/s].
    phase : float or array_like
        Tooth phase ψ [rad] (module docstring; :func:`tooth_phase` for a time).

    Returns
    -------
    float or numpy.ndarray
        v [m/s].

    References
    ----------
    [ChainNonUniformity, eq. 6].
    """
    rim_speed, beta = _rim_speed_and_angle(pitch, teeth, speed, phase)
    return _out(rim_speed * np.cos(beta))


@shared_parameters
def transverse_chain_speed(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike,
                           phase: ArrayLike) -> FloatOrArray:
    """Speed of the span end across the span v' = R·ω·sin β.

    %(pitch_teeth_speed_phase_returns)s
        v' [m/s].

    References
    ----------
    [ChainNonUniformity].
    """
    rim_speed, beta = _rim_speed_and_angle(pitch, teeth, speed, phase)
    return _out(rim_speed * np.sin(beta))


def instantaneous_driven_speed(pitch: ArrayLike, teeth_driver: ArrayLike,
                               teeth_driven: ArrayLike, speed_driver: ArrayLike,
                               phase: ArrayLike, phase_offset: ArrayLike = 0.0) -> FloatOrArray:
    """Angular speed of the driven sprocket ω2 = v / (R2·cos γ).

    v = R1 ω1 cos β is the chain speed set by the driver (β = wrap(ψ)/z1). Model of γ
    (first order, stated): the driven sprocket turns uniformly at its mean speed
    z1 ω1/z2, so its tooth phase advances at the same rate z1 ω1 as the driver's and
    γ = wrap(ψ + phase_offset)/z2. phase_offset [rad] is the tooth-phase difference of the
    two ends of the tight span (2π × the fractional part of the span length in pitches,
    with the sign of the contour's convention). The exact coupled motion differs from this
    at second order in π/z.

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m].
    teeth_driver, teeth_driven : int or array_like
        z1, z2 [-].
    speed_driver : float or array_like
        ω1 [rad/s].
    phase : float or array_like
        Tooth phase ψ of the driver [rad].
    phase_offset : float or array_like
        Tooth-phase difference of the two ends of the tight span [rad].

    Returns
    -------
    float or numpy.ndarray
        ω2 [rad/s].

    References
    ----------
    [ChainNonUniformity, eq. 5–6].
    """
    z1, z2 = _teeth(teeth_driver), _teeth(teeth_driven)
    v = np.asarray(instantaneous_chain_speed(pitch, z1, speed_driver, phase))
    gamma = np.asarray(wrap_phase(np.asarray(phase, float) + np.asarray(phase_offset, float)))
    return _out(v / (_radius(pitch, z2) * np.cos(gamma / z2)))


def instantaneous_ratio(teeth_driver: ArrayLike, teeth_driven: ArrayLike, phase: ArrayLike,
                        phase_offset: ArrayLike = 0.0) -> FloatOrArray:
    """Instantaneous transmission ratio i = ω1/ω2 = R2 cos γ / (R1 cos β).

    β = wrap(ψ)/z1, γ = wrap(ψ + phase_offset)/z2 as in :func:`instantaneous_driven_speed`;
    independent of the pitch. Its mean over a tooth period is close to (not exactly) z2/z1.

    Parameters
    ----------
    teeth_driver, teeth_driven : int or array_like
        z1, z2 [-].
    phase : float or array_like
        Tooth phase ψ of the driver [rad].
    phase_offset : float or array_like
        Tooth-phase difference of the two ends of the tight span [rad].

    Returns
    -------
    float or numpy.ndarray
        i [-].

    References
    ----------
    [ChainNonUniformity, eq. 5–6].
    """
    z1, z2 = _teeth(teeth_driver), _teeth(teeth_driven)
    beta = np.asarray(wrap_phase(phase)) / z1
    gamma = np.asarray(wrap_phase(np.asarray(phase, float) + np.asarray(phase_offset, float)))
    r_ratio = np.sin(np.pi / z1) / np.sin(np.pi / z2)  # R2/R1
    return _out(r_ratio * np.cos(gamma / z2) / np.cos(beta))


# ---------------------------------------------------------------------------------------
# Deviation of a terminal hinge from uniform motion: exact law and Fourier series
# ---------------------------------------------------------------------------------------

@shared_parameters
def hinge_displacement_exact(pitch: ArrayLike, teeth: ArrayLike,
                             phase: ArrayLike) -> FloatOrArray:
    """Deviation δ [m] of the terminal hinge from uniform motion at the mean chain speed.

    δ(ψ) = R·sin(ψ_w/z) − p·ψ_w/(2π), ψ_w = wrap(ψ) ∈ [−π, π) — the position R sin β
    minus the uniform position. Odd in ψ, hence zero-mean; continuous and periodic at the
    tooth period (it vanishes at ψ = ±π because 2R sin(π/z) = p); positive (chain ahead)
    for ψ in (0, π).

    Parameters
    ----------
    %(pitch_teeth_array)s
    phase : float or array_like
        Tooth phase ψ [rad].

    Returns
    -------
    float or numpy.ndarray
        δ [m].

    References
    ----------
    [ChainNonUniformity] (position R sin β); docs/kinematics.md (derivation).
    """
    z = _teeth(teeth)
    psi = np.asarray(wrap_phase(phase))
    p = np.asarray(pitch, float)
    return _out(_radius(p, z) * np.sin(psi / z) - p * psi / TWO_PI)


@shared_parameters
def hinge_displacement_peak(pitch: ArrayLike, teeth: ArrayLike) -> FloatOrArray:
    """Largest deviation max δ, at cos β* = z sin(π/z)/π (where dδ/dψ = 0, i.e. where the
    instantaneous chain speed equals the mean speed).

    Parameters
    ----------
    %(pitch_teeth_array)s

    Returns
    -------
    float or numpy.ndarray
        max δ [m].
    """
    z = _teeth(teeth)
    beta = np.arccos(z * np.sin(np.pi / z) / np.pi)
    p = np.asarray(pitch, float)
    return _out(_radius(p, z) * np.sin(beta) - p * z * beta / TWO_PI)


@shared_parameters
def hinge_displacement_coefficients(pitch: ArrayLike, teeth: ArrayLike, harmonics: int,
                                    phase: ArrayLike = 0.0
                                    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Fourier coefficients (A_k, B_k), k = 1…N, of δ at the harmonics of the tooth frequency.

    δ(ψ + ψ0) = Σ_k A_k sin(kψ) + B_k cos(kψ), with the exact coefficients
    b_k = (p/π)·(−1)^{k+1} / (k (k² z² − 1)) [m] (docs/kinematics.md),
    A_k = b_k cos(kψ0), B_k = b_k sin(kψ0). A shift ψ0 of the tooth phase shifts harmonic k by
    k·ψ0. The last axis of each array is k; leading axes broadcast over pitch, teeth, phase.

    Parameters
    ----------
    %(pitch_teeth_array)s
    harmonics : int
        Number of harmonics N [-].
    phase : float or array_like
        Shift ψ0 of the tooth phase [rad].

    Returns
    -------
    tuple of numpy.ndarray
        (A_k, B_k) [m], last axis k = 1…N.

    References
    ----------
    docs/kinematics.md (derivation); [MultimassChainDrives, §3.1] (harmonic excitation).
    """
    if int(harmonics) < 1:
        raise DesignError("harmonics", f"must be a whole number ≥ 1, got {harmonics!r}")
    z = _teeth(teeth)[..., None]
    k = np.arange(1, int(harmonics) + 1, dtype=float)
    p = np.asarray(pitch, float)[..., None]
    b = (p / np.pi) * np.where(k % 2 == 1, 1.0, -1.0) / (k * (k**2 * z**2 - 1.0))
    shift = k * np.asarray(phase, float)[..., None]
    return b * np.cos(shift), b * np.sin(shift)


def hinge_displacement_fourier(pitch: ArrayLike, teeth: ArrayLike, phase: ArrayLike,
                               harmonics: int = 10) -> FloatOrArray:
    """δ(ψ) summed over the first N harmonics
    δ_N(ψ) = (p/π) Σ_{k=1..N} (−1)^{k+1} sin(kψ)/(k(k²z² − 1)).

    Converges to :func:`hinge_displacement_exact` like N⁻³; [MultimassChainDrives] uses
    N = 10.

    Parameters
    ----------
    pitch : float or array_like
        Chain pitch p [m] (broadcast with ``phase``).
    teeth : int or array_like
        Number of teeth z [-] (broadcast with ``phase``).
    phase : float or array_like
        Tooth phase ψ [rad].
    harmonics : int
        N [-].

    Returns
    -------
    float or numpy.ndarray
        δ_N [m].

    References
    ----------
    [MultimassChainDrives, §3.1]; docs/kinematics.md.
    """
    A, _ = hinge_displacement_coefficients(pitch, teeth, harmonics)
    psi = np.asarray(phase, float)[..., None]
    k = np.arange(1, int(harmonics) + 1, dtype=float)
    return _out(np.sum(A * np.sin(k * psi), axis=-1))


@shared_parameters
def hinge_velocity_deviation(pitch: ArrayLike, teeth: ArrayLike, speed: ArrayLike,
                             phase: ArrayLike) -> FloatOrArray:
    """Speed deviation of the hinge dδ/dτ = v(τ) − v̄ = R ω cos β − z p ω/(2π).

    %(pitch_teeth_speed_phase_returns)s
        dδ/dτ [m/s].
    """
    z = _teeth(teeth)
    v = np.asarray(instantaneous_chain_speed(pitch, z, speed, phase))
    return _out(v - np.asarray(mean_chain_speed(pitch, z, speed)))


# --- the drive ------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class SprocketMotion:
    """Motion of one sprocket.

    Parameters
    ----------
    name : str
        The sprocket.
    speed : float
        Mean angular speed [rad/s].
    direction : str
        "ccw" or "cw".
    speed_variation_percent : float
        Polygonal speed variation [%] (:func:`speed_variation_percent`).
    hinge_deviation_peak : float
        Peak deviation of its terminal hinge from uniform motion [m].
    ratio_min, ratio_max : float
        Range of the instantaneous ratio ω_driver/ω over one tooth period [-] (1 for the
        driver) [ChainNonUniformity].
    """

    name: str
    speed: float
    direction: str
    speed_variation_percent: float
    hinge_deviation_peak: float
    ratio_min: float
    ratio_max: float

    @property
    def speed_rpm(self) -> float:
        """Mean speed [rpm]."""
        return self.speed * RPM_PER_RAD_S


@dataclass(frozen=True, slots=True)
class KinematicsResult:
    """Speeds of a contour.

    Parameters
    ----------
    chain_speed : float
        Mean chain speed [m/s].
    tooth_frequency : float
        [Hz].
    sprockets : tuple of SprocketMotion
        Per-sprocket motion.
    phase : numpy.ndarray
        (samples,) angle of the driver within ±π/z over one tooth period [rad].
    chain_speed_trace : numpy.ndarray
        (samples,) instantaneous chain speed [m/s].
    ratio_traces : numpy.ndarray
        (n, samples) instantaneous ratio ω_driver/ω_i of every sprocket [-] (1 for the
        driver).
    """

    chain_speed: float
    tooth_frequency: float
    sprockets: tuple[SprocketMotion, ...]
    phase: NDArray[np.float64]
    chain_speed_trace: NDArray[np.float64]
    ratio_traces: NDArray[np.float64]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready document (units in the key names)."""
        return {
            "chain_speed_m_s": self.chain_speed,
            "chain_speed_min_m_s": float(np.min(self.chain_speed_trace)),
            "chain_speed_max_m_s": float(np.max(self.chain_speed_trace)),
            "tooth_frequency_hz": self.tooth_frequency,
            "sprockets": [
                {
                    "name": s.name,
                    "speed_rpm": s.speed_rpm,
                    "speed_rad_s": s.speed,
                    "direction": s.direction,
                    "speed_variation_percent": s.speed_variation_percent,
                    "hinge_deviation_peak_mm": s.hinge_deviation_peak * 1e3,
                    "ratio_min": s.ratio_min,
                    "ratio_max": s.ratio_max,
                }
                for s in self.sprockets
            ],
        }


def tooth_phase_offsets(geometry: GeometryResult) -> NDArray[np.float64]:
    """Tooth-phase offset of every sprocket against the driver.

    2π × the fractional part of the chain path, in pitches, from the point where the chain
    leaves sprocket i to the point where it arrives on the driver (spans ℓ/p plus wraps
    z·θ/2π in between): the ``phase_offset`` of :func:`instantaneous_ratio`.

    Parameters
    ----------
    geometry : GeometryResult
        The contour; the driver is the sprocket its tight span runs into.

    Returns
    -------
    numpy.ndarray
        (n,) offsets [rad], 0 for the driver.
    """
    n = len(geometry.sprockets)
    d = next(sp.end for sp in geometry.spans if sp.tight)
    out = np.zeros(n)
    for i in range(n):
        if i == d:
            continue
        path, k = 0.0, i
        while k != d:
            path += geometry.spans[k].pitches
            k = (k + 1) % n
            if k != d:
                g = geometry.sprockets[k]
                path += g.teeth * g.wrap_angle / TWO_PI
        out[i] = TWO_PI * (path % 1.0)
    return out


@shared_parameters
def drive_kinematics(drive: Drive, geometry: GeometryResult, samples: int = 257) -> KinematicsResult:
    """Kinematics of a contour: every sprocket's speed and direction, chain speed, tooth
    frequency and polygonal non-uniformity.

    The tooth (mesh) frequency f_z = z_i·n_i is the same for every sprocket of one
    contour, so ω_i = ω_driver·z_driver/z_i; a sprocket on the inside of the contour
    turns the other way (its ``turn`` in the geometry).

    Parameters
    ----------
    drive : Drive
        The design (the driver's speed is needed).
    %(geometry)s
    samples : int
        Points over one tooth period of the driver [-].

    Returns
    -------
    KinematicsResult
        Speeds, tooth frequency and the traces over one tooth period.

    References
    ----------
    [ChainNonUniformity]; [MultimassChainDrives, §3.1].
    """
    driver = drive.driver
    if driver.speed is None:
        raise DesignError(f"sprockets[{driver.name}].speed", "the driver needs a speed")
    p = geometry.pitch
    omega_d = driver.speed
    z_d = driver.teeth
    phase = np.linspace(-math.pi / z_d, math.pi / z_d, samples)
    psi = phase * z_d  # tooth phase over one period
    offsets = tooth_phase_offsets(geometry)
    teeth = np.array([s.teeth for s in drive.sprockets])[:, None]
    ratios = np.asarray(instantaneous_ratio(z_d, teeth, psi[None, :], offsets[:, None]))
    ratios[drive.driver_index] = 1.0
    motions = []
    for i, (s, g) in enumerate(zip(drive.sprockets, geometry.sprockets, strict=True)):
        omega = float(mean_driven_speed(z_d, omega_d, s.teeth))
        ratio = ratios[i]
        motions.append(SprocketMotion(
            name=s.name, speed=omega, direction="ccw" if g.turn > 0 else "cw",
            speed_variation_percent=float(speed_variation_percent(s.teeth)),
            hinge_deviation_peak=float(hinge_displacement_peak(p, s.teeth)),
            ratio_min=float(ratio.min()), ratio_max=float(ratio.max()),
        ))
    r_d = geometry.sprockets[drive.driver_index].pitch_radius
    trace = r_d * omega_d * np.cos(phase)  # v = R₁ω₁ cos β [ChainNonUniformity, eq. 6]
    return KinematicsResult(
        chain_speed=float(mean_chain_speed(p, z_d, omega_d)),
        tooth_frequency=float(tooth_frequency(z_d, omega_d)),
        sprockets=tuple(motions), phase=phase, chain_speed_trace=trace, ratio_traces=ratios,
    )

