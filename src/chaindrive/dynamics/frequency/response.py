r"""Steady responses of the whole-drive model: steady state at a speed, speed sweep (AFC) and
the bands of the natural frequencies, resonance detunings and K_D for uncertain stiffness and inertia
(docs/dynamics.md §4–6).

The kinematic excitation is a prescribed elongation d of the chain spans
(:mod:`chaindrive.dynamics.excitation`); with the model M q̈ + C q̇ + K q = −Bᵀ(c d + d_s ḋ) of
:class:`~chaindrive.dynamics.model.build.LinearModel` a harmonic e^{iωt} of amplitude D gives
[Rao2011, §6.15]::

    (K + iωC − ω²M) X = −Bᵀ (c + iω d_s) D,     F = (c + iω d_s)(B X + D),

one complex solve per harmonic at one speed (:func:`drive_steady`). The sweep solves it over
thousands of speeds with the complex modes of the elastic part computed once
(:mod:`chaindrive.dynamics.modes`): X = Φ y, (y, ẏ) = V (iω − Λ)⁻¹ V⁻¹ [0; Φᵀ f] — exact for
any damping matrix, a handful of broadcast products for the whole sweep.

**Maxima of the sweep** (F₂max of every span, what k₂min needs) without the whole curve
(:func:`span_load_maxima`): per harmonic k the response is a sum of simple poles in W = kω_z,
Q(W) = D_k − Σ_m BV_m (a1_km + r_km/(iW − λ_m)), so its change over a run of speeds is bounded
in closed form by the distance of each pole to the run [Rao2011, §6.15] (partial fractions of
the receptance); runs whose bound stays below the largest load found are not computed.

**Irregularity of rotation** from the speed history: Δ = (ω_max − ω_min)/ω_mean over a tooth
period, for every sprocket and every rotor of the trains; for one harmonic of amplitude x_n
(chain displacement at sprocket n) it is 2 x_n z_n / R̄_n [MultimassChainDrives, §3.3].

**Bands.** With every stiffness within (1 ± u) k and every inertia within (1 ± u) J, each
natural frequency lies within f·[√((1−u)/(1+u)), √((1+u)/(1−u))]: K' ⪯ (1+u)K and
M' ⪰ (1−u)M in the Loewner order, and the eigenvalues of the pencil are monotone in both
(Courant–Fischer minimax [Horn2013, §4.2]). For all stiffnesses scaled by a and all
inertias by b (damping ratios kept) the span forces are a·F(ω√(b/a)) of the nominal model, so
the band of K_D follows from a short sweep of the nominal model around the working speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.frequency.afc import AfcResult, local_maxima, peak_over_period
from chaindrive.dynamics.frequency.quality import coefficient_of_dynamics
from chaindrive.dynamics.frequency.steady import SteadyStateResult
from chaindrive.dynamics.modes import Modes
from chaindrive.errors import DesignError
from chaindrive.strength.safety import steady_safety_factor
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.dynamics.excitation import SpanExcitation
    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.dynamics.resonance import Resonance

__all__ = ["Bands", "drive_steady", "drive_sweep", "frequency_band_factors",
           "span_load_maxima", "span_loads_over", "uncertainty_bands"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def _harmonic(model: DriveModel, w: FloatArray, D: ComplexArray
              ) -> tuple[ComplexArray, ComplexArray]:
    """(X (F, N), span forces of one contour (F, S)) at the angular frequencies w (F,)."""
    lin = model.linear
    M, K, C, B = lin.mass, lin.stiffness(), lin.damping(), lin.span_incidence
    cd = lin.span_stiffness[None, :] + 1j * w[:, None] * lin.span_damping[None, :]  # (F, S)
    A = K[None] + 1j * w[:, None, None] * C[None] - (w * w)[:, None, None] * M[None]
    rhs = -(cd * D) @ B                                                   # (F, N)
    X = np.asarray(np.linalg.solve(A, rhs[..., None])[..., 0], dtype=np.complex128)
    F = np.asarray(cd * (X @ B.T + D) / model.contours, dtype=np.complex128)
    return X, F


def _traces(amplitudes: ComplexArray, w: FloatArray, times: FloatArray) -> FloatArray:
    """Re Σ_f A_f e^{i w_f t} on ``times``: (T, columns)."""
    return np.asarray((np.exp(1j * np.outer(times, w)) @ amplitudes).real, dtype=np.float64)


@shared_parameters
def drive_steady(model: DriveModel, excitation: SpanExcitation, *, samples: int = 128,
                 nominal_force: float | None = None, breaking_load: float | None = None,
                 operating_forces: ArrayLike | None = None,
                 resonance_loads: ArrayLike | None = None) -> SteadyStateResult:
    """Steady response of the whole-drive model to a span excitation (module docstring).

    Parameters
    ----------
    %(drive_model)s
    excitation : SpanExcitation
        Harmonics of the span elongations (its orders with respect to the tooth frequency).
    samples : int
        Samples per tooth period of the traces.
    nominal_force : float | None
        F_t [N] → K_D = 1 + F_D/F_t [MultimassChainDrives, §3.6].
    breaking_load : float | None
        Q of one contour [N] → k₂ with ``operating_forces`` F_R (S,) [N].
    operating_forces : array_like | None
        Static span tensions of one contour [N].
    resonance_loads : array_like | None
        F₂max (S,) [N] → k₂min.

    Returns
    -------
    SteadyStateResult
        Span forces of one contour; displacements and speeds at the sprockets; the
        irregularity Δ of the sprockets and of the rotors from the speed history.
    """
    w = excitation.angular_frequencies
    X, F = _harmonic(model, w, excitation.elongation)
    orders = excitation.orders
    wz = float(w[0] / orders[0]) if w.size else 0.0
    periodic = bool(np.allclose(orders, np.round(orders)) and np.all(orders >= 1))
    # one tooth period; disturbances at other orders: their peaks are the sums of the
    # harmonic amplitudes (exact for incommensurate frequencies, else an upper bound)
    times = np.linspace(0.0, TWO_PI / wz, int(samples), endpoint=False)
    k, g = model.sprocket_coordinate, model.sprocket_gain
    phi = X[:, k] * g                                        # forward angle (F, n) [rad]
    x = phi * model.mean_radii                               # chain displacement [m]
    rot = X[:, model.rotor_coordinate] * model.rotor_gain
    f_tr = _traces(F, w, times)
    x_tr = _traces(x, w, times)
    if periodic:
        f_max = np.abs(f_tr).max(axis=0)
        f_amp = 0.5 * np.ptp(f_tr, axis=0)
        x_amp = 0.5 * np.ptp(x_tr, axis=0)
        acc = np.abs(_traces(-(w * w)[:, None] * phi, w, times)).max(axis=0)
        speed_range = np.ptp(_traces(1j * w[:, None] * phi, w, times), axis=0)
        rot_range = np.ptp(_traces(1j * w[:, None] * rot, w, times), axis=0)
    else:
        f_max = f_amp = np.abs(F).sum(axis=0)
        x_amp = np.abs(x).sum(axis=0)
        acc = np.abs((w * w)[:, None] * phi).sum(axis=0)
        speed_range = 2.0 * np.abs(w[:, None] * phi).sum(axis=0)
        rot_range = 2.0 * np.abs(w[:, None] * rot).sum(axis=0)
    rms = float(np.sqrt(np.mean(f_max**2)))
    kd = (coefficient_of_dynamics(f_max, nominal_force)
          if nominal_force is not None and np.any(f_max > 0) else None)
    k2 = k2min = None
    if breaking_load is not None and operating_forces is not None:
        fr = np.asarray(operating_forces, dtype=float).tolist()
        k2 = min(steady_safety_factor(breaking_load, a, b)
                 for a, b in zip(fr, f_max.tolist(), strict=True))
        if resonance_loads is not None:
            k2min = min(steady_safety_factor(breaking_load, a, b) for a, b in
                        zip(fr, np.asarray(resonance_loads, float).tolist(), strict=True))
    J = model.ring.inertias_kg_m2
    return SteadyStateResult(
        tooth_angular_frequency=wz, angular_frequencies=w, displacement=x, span_force=F,
        times=times, span_force_trace=f_tr, displacement_trace=x_tr, span_dynamic_load=f_max,
        span_load_amplitude=f_amp, inertia_load=J * acc / model.pitch_radii,
        displacement_amplitude=x_amp,
        irregularity_percent=100.0 * speed_range / model.nominal_speeds,
        dynamic_load_rms=rms, coefficient_of_dynamics=kd, k2=k2, k2_min=k2min,
        periodic=periodic, rotor_names=model.rotor_names,
        rotor_irregularity_percent=100.0 * rot_range / model.rotor_nominal_speed,
        nominal_force=nominal_force)


@dataclass(frozen=True, slots=True)
class _SpanModal:
    """The speed-independent factors of the span forces by complex modes (module docstring):
    with P = V⁻¹-rows of the velocities times (BΦ)ᵀ (2E, S) and BV = BΦ times the
    displacement rows of V (S, 2E), a harmonic k at W = k ω_z gives

        Q(W) = D_k − Σ_m BV_m (a0_km + iW a1_km)/(iW − λ_m),   F = (c + iW d_s) Q / m,

    a0 = (c D) Pᵀ, a1 = (d_s D) Pᵀ (K, 2E); a0 + iW a1 = a1 (iW − λ) + r with
    r = a0 + λ a1, so Q(W) − Q(W₀) = −Σ_m BV_m r_km (1/(iW − λ_m) − 1/(iW₀ − λ_m))."""

    D: ComplexArray          # (K, S) span elongation amplitudes [m]
    orders: FloatArray       # (K,) harmonic orders [-]
    stiffness: FloatArray    # (S,) c [N/m]
    damping: FloatArray      # (S,) d_s [N·s/m]
    PT: ComplexArray         # (S, 2E)
    BVT: ComplexArray        # (2E, S)
    eigenvalues: ComplexArray  # (2E,) λ [1/s]
    residues: FloatArray     # (K, 2E) |r| [N/m · m]
    contours: int

    @classmethod
    def of(cls, model: DriveModel, modes: Modes, excitation: SpanExcitation
           ) -> _SpanModal:
        """The factors of a model, its complex modes and an excitation."""
        lin = model.linear
        lam, right, left, basis = modes.complex_modes()
        e = basis.shape[1]
        BPhi = lin.span_incidence @ basis                                # (S, E)
        P = left[:, e:] @ BPhi.T                                         # (2E, S)
        BV = BPhi @ right[:e, :]                                         # (S, 2E)
        PT, BVT = np.ascontiguousarray(P.T), np.ascontiguousarray(BV.T)
        D = excitation.elongation
        r = (lin.span_stiffness * D) @ PT + lam * ((lin.span_damping * D) @ PT)
        return cls(D, excitation.orders, lin.span_stiffness, lin.span_damping, PT, BVT, lam,
                   np.abs(r), model.contours)

    def forces(self, wz: FloatArray) -> tuple[ComplexArray, ComplexArray]:
        """(F (b, K, S) [N] of one contour, c + iW d_s (b, K, S) [N/m]) at the tooth
        frequencies ``wz`` (b,) [rad/s]."""
        D, ns = self.D, self.D.shape[1]
        W = wz[:, None] * self.orders[None, :]                        # (b, K)
        cd = self.stiffness + 1j * W[..., None] * self.damping          # (b, K, S)
        CD = (cd * D).reshape(-1, ns)
        G = -(CD @ self.PT)                                            # (b·K, 2E)
        G /= (1j * W.reshape(-1, 1)) - self.eigenvalues
        F = (G @ self.BVT).reshape(cd.shape)
        F += D
        F *= cd
        F /= self.contours                                             # (b, K, S)
        return F, cd

    def variation(self, F: ComplexArray, cd: ComplexArray, low: FloatArray,
                  centre: FloatArray, high: FloatArray) -> FloatArray:
        """Upper bound of |F_k(W) − F_k(W₀)| [N] for ω_z in [low, high] (b,) about the
        centre (b,) where F, cd were computed: (b, K, S).

        Each modal term varies by at most |BV_m r_km| · min(h/δ², 1/δ + 1/|iW₀ − λ_m|),
        h the largest |W − W₀|, δ the least |iW − λ_m| on the interval (the derivative
        of 1/(iW − λ) is bounded by 1/δ²; or each end by the triangle inequality); then
        F(W) − F(W₀) = [(cd(W) − cd(W₀)) Q(W) + cd(W₀)(Q(W) − Q(W₀))]/m with
        |cd(W) − cd(W₀)| ≤ h d_s and |Q(W)| ≤ |Q(W₀)| + the bound of its variation.
        """
        k, lam = self.orders, self.eigenvalues
        Wl, W0, Wh = low[:, None] * k, centre[:, None] * k, high[:, None] * k   # (b, K)
        h = np.maximum(W0 - Wl, Wh - W0)[..., None]                           # (b, K, 1)
        nu, s2 = lam.imag, lam.real**2
        gap = np.maximum(0.0, np.maximum(Wl[..., None] - nu, nu - Wh[..., None]))
        dist2 = s2 + gap * gap                                                # (b, K, 2E)
        off = W0[..., None] - nu                                              # |iW₀ − λ|² − σ²
        with np.errstate(divide="ignore", invalid="ignore"):
            near = 1.0 / np.sqrt(dist2) + 1.0 / np.sqrt(s2 + off * off)
            weight = self.residues * np.minimum(h / dist2, near)
        dq = weight @ np.abs(self.BVT)                                        # (b, K, S)
        q0 = np.abs(F) * self.contours / np.abs(cd)
        return np.asarray((h * self.damping * (q0 + dq) + np.abs(cd) * dq) / self.contours,
                          dtype=np.float64)


@shared_parameters
def span_loads_over(model: DriveModel, modes: Modes, excitation: SpanExcitation,
                    tooth_angular_frequencies: ArrayLike, samples: int = 64,
                    block: int = 128) -> FloatArray:
    """Peak span force of one contour over a tooth period [N], (speeds, S), at every tooth
    frequency ω_z [rad/s], by the complex modes (module docstring).

    Parameters
    ----------
    %(drive_model)s
    modes : Modes
        Its modes with their complex elastic ones (:func:`chaindrive.dynamics.modes.drive_modes`).
    excitation : SpanExcitation
        Span elongation amplitudes and their orders (whole harmonics).
    tooth_angular_frequencies : array_like
        ω_z of every speed [rad/s].
    samples : int
        Samples per tooth period for the peak.
    block : int
        Speeds per block (bounds the memory).

    Returns
    -------
    ndarray
        (speeds, S) [N].
    """
    modal = _SpanModal.of(model, modes, excitation)
    wz = np.asarray(tooth_angular_frequencies, dtype=float)
    out = np.empty((wz.size, modal.D.shape[1]))
    for a in range(0, wz.size, block):
        out[a:a + block] = peak_over_period(modal.forces(wz[a:a + block])[0], modal.orders,
                                            samples)
    return out


#: relative margin by which a bound must lie below the largest load found to drop speeds
#: (covers the rounding of the loads; a load within it would change the maximum by less)
BOUND_MARGIN = 1e-9


@shared_parameters
def span_load_maxima(model: DriveModel, modes: Modes, excitation: SpanExcitation,
                     tooth_angular_frequencies: ArrayLike, samples: int = 64,
                     first: int = 128) -> FloatArray:
    """The largest peak span force of every span over the speeds [N], (S,): the maxima over
    the speeds of :func:`span_loads_over`, found without computing every speed.

    Branch and bound [LandDoig1960] over the (sorted) speeds: the speeds are cut into runs
    of ``first``; the loads are computed at the middle speed of each run, and a run whose
    upper bound lies below the largest load found so far for every span is dropped; the
    others are split at their middle and bounded again. The bound of a run is the peak at its middle plus
    Σ_k of the bound of |F_k(W) − F_k(W₀)| over it (every sample of the trace moves by at
    most that; :meth:`_SpanModal.variation`). The maxima are those of the whole grid: every
    dropped speed is bounded below the maximum (by :data:`BOUND_MARGIN`, which covers the
    rounding), every other one is computed as :func:`span_loads_over` computes it.

    Parameters
    ----------
    %(drive_model)s
    modes : Modes
        Its modes (their complex elastic modes are read).
    excitation : SpanExcitation
        Span elongation amplitudes and their orders (whole harmonics).
    tooth_angular_frequencies : array_like
        ω_z of every speed [rad/s], ascending.
    samples : int
        Samples per tooth period for the peak.
    first : int
        Speeds per run of the first pass.

    Returns
    -------
    ndarray
        (S,) [N].
    """
    modal = _SpanModal.of(model, modes, excitation)
    wz = np.asarray(tooth_angular_frequencies, dtype=float)
    if wz.ndim != 1 or wz.size < 1 or np.any(np.diff(wz) < 0):
        raise DesignError("tooth_angular_frequencies", "need an ascending 1-D array [rad/s]")
    lo = np.arange(0, wz.size, max(int(first), 1))
    hi = np.minimum(lo + max(int(first), 1) - 1, wz.size - 1)
    best = np.zeros(modal.D.shape[1])
    while lo.size:
        mid = (lo + hi) // 2
        F, cd = modal.forces(wz[mid])
        peak = peak_over_period(F, modal.orders, samples)                   # (b, S)
        best = np.maximum(best, peak.max(axis=0))
        wide = hi > lo                                  # a run of one speed is computed
        lo, hi, mid, F, cd, peak = lo[wide], hi[wide], mid[wide], F[wide], cd[wide], peak[wide]
        bound = peak + modal.variation(F, cd, wz[lo], wz[mid], wz[hi]).sum(axis=1)
        split = ~np.all(bound < best * (1.0 - BOUND_MARGIN), axis=1)
        lo, hi, mid = lo[split], hi[split], mid[split]
        lo, hi = np.concatenate([lo, mid + 1]), np.concatenate([mid - 1, hi])
        lo, hi = lo[lo <= hi], hi[lo <= hi]
    return best


def drive_sweep(model: DriveModel, modes: Modes, excitation: SpanExcitation,
                driver_speeds: ArrayLike, driver_teeth: int,
                natural_frequencies_hz: ArrayLike, samples: int = 64) -> AfcResult:
    """Amplitude–frequency characteristic of the whole model over ``driver_speeds`` [rad/s]
    (its per-span maxima are F₂max of a run-up through them [MultimassChainDrives, §3.6]).

    Parameters
    ----------
    model, modes : the model and its modes (with the complex elastic ones).
    excitation : SpanExcitation
        The excitation at any speed (only its amplitudes and orders are used).
    driver_speeds : array_like
        ω₁ [rad/s], positive.
    driver_teeth : int
        z₁ (ω_z = z₁ω₁).
    natural_frequencies_hz : array_like
        The elastic natural frequencies [Hz] for the resonance markers.
    samples : int
        Samples per tooth period.

    Returns
    -------
    AfcResult
    """
    speeds = np.asarray(driver_speeds, dtype=float)
    if speeds.ndim != 1 or speeds.size < 1 or np.any(speeds <= 0):
        raise DesignError("driver_speeds", "need a 1-D array of positive speeds [rad/s]")
    wz = speeds * driver_teeth
    load = span_loads_over(model, modes, excitation, wz, samples)
    fz_hz = wz / TWO_PI
    nat = np.asarray(natural_frequencies_hz, dtype=float)
    lo, hi = fz_hz.min(), fz_hz.max()
    whole = sorted({round(k) for k in excitation.orders.tolist() if k >= 1})
    markers = tuple((j + 1, int(k), float(f), float(f / k)) for j, f in enumerate(nat)
                    for k in whole if lo <= f / k <= hi)
    peaks = local_maxima(load.max(axis=1))
    return AfcResult(speeds, fz_hz, load, load.max(axis=0), nat, markers, fz_hz[peaks])


def frequency_band_factors(uncertainty: float) -> tuple[float, float]:
    """(low, high) factors on every natural frequency when stiffnesses and inertias are known
    to ±u: √((1−u)/(1+u)) and √((1+u)/(1−u)) [-] (module docstring).

    Parameters
    ----------
    uncertainty : float
        Relative uncertainty u of stiffnesses and inertias [-], from 0 to below 1.

    Returns
    -------
    tuple of float
        The low and high factors [-].

    Raises
    ------
    DesignError
        ``dynamics.uncertainty`` out of range.

    References
    ----------
    [Horn2013, §4.2] (Courant–Fischer minimax: stiffnesses scaled within 1 ± u and inertias
    within 1 ∓ u bound every ω² by the ratio of the extreme scalings).
    """
    u = float(uncertainty)
    if not 0.0 <= u < 1.0:
        raise DesignError("dynamics.uncertainty", f"must be from 0 to below 1, got {u!r}")
    return math.sqrt((1 - u) / (1 + u)), math.sqrt((1 + u) / (1 - u))


@dataclass(frozen=True, slots=True)
class Bands:
    """Bands of the results for stiffness and inertia known to ±u.

    Parameters
    ----------
    uncertainty : float
        Relative uncertainty u [-].
    natural_frequencies_hz : ndarray
        (E, 2) low and high of every elastic natural frequency [Hz].
    detunings : tuple of tuple
        Per resonance row: (label, working frequency [Hz], natural frequency [Hz], signed
        offset (f_w − f_n)/f_n [%], lowest and highest detuning Δ ≥ 0 over the band [%],
        inside: the working frequency lies in the mode's band).
    coefficient_of_dynamics : tuple of float or None
        (nominal, low, high) coefficient of dynamics K_D [-], or None when it is not computed.
    worst_speed_factor : float or None
        The factor ω√(b/a) [-] at which K_D is largest.
    """

    uncertainty: float
    natural_frequencies_hz: FloatArray
    detunings: tuple[tuple[str, float, float, float, float, float, bool], ...]
    coefficient_of_dynamics: tuple[float, float, float] | None
    worst_speed_factor: float | None

    @property
    def resonances_inside(self) -> tuple[str, ...]:
        """Labels of the working frequencies inside the band of a natural frequency."""
        return tuple(m[0] for m in self.detunings if m[6])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (a detuning Δ ≥ 0 with the side of the working frequency, as
        :meth:`chaindrive.dynamics.resonance.Resonance.to_dict`)."""
        kd = self.coefficient_of_dynamics
        return {
            "uncertainty": self.uncertainty,
            "natural_frequencies_hz": self.natural_frequencies_hz.tolist(),
            "resonance_detunings": [
                {"label": m[0], "working_frequency_hz": m[1], "natural_frequency_hz": m[2],
                 "detuning_percent": abs(m[3]),
                 "working_frequency_is": "below" if m[3] < 0 else "above",
                 "detuning_low_percent": m[4], "detuning_high_percent": m[5],
                 "inside_band": m[6]} for m in self.detunings],
            "coefficient_of_dynamics": None if kd is None else
            {"nominal": kd[0], "low": kd[1], "high": kd[2]},
            "worst_speed_factor": self.worst_speed_factor,
        }


def uncertainty_bands(uncertainty: float, elastic_hz: ArrayLike,
                      resonances: tuple[Resonance, ...], *,
                      sweep: tuple[FloatArray, FloatArray] | None = None,
                      nominal_force: float | None = None,
                      nominal_kd: float | None = None) -> Bands:
    """Bands of the natural frequencies, resonance detunings and K_D (module docstring).

    Parameters
    ----------
    uncertainty : float
        u [-]: every stiffness and inertia within (1 ± u) of its value.
    elastic_hz : array_like
        The elastic natural frequencies [Hz].
    resonances : tuple of Resonance
        The resonance table (nominal).
    sweep : (ndarray, ndarray) | None
        Speed factors s (P,) [-] over [low, high] of :func:`frequency_band_factors` and the
        RMS dynamic span load F_D(s) (P,) [N] of the nominal model there.
    nominal_force : float | None
        F_t [N].
    nominal_kd : float | None
        K_D at the nominal speed [-].

    Returns
    -------
    Bands
    """
    lo, hi = frequency_band_factors(uncertainty)
    f = np.asarray(elastic_hz, dtype=float)
    detunings = []
    for r in resonances:
        fn, fw = r.natural_frequency, r.working.frequency
        inside = fn * lo <= fw <= fn * hi
        edges = (abs(fw / (fn * lo) - 1), abs(fw / (fn * hi) - 1))
        low = 0.0 if inside else 100.0 * min(edges)
        detunings.append((r.working.label, fw, fn, r.offset_percent, low, 100.0 * max(edges),
                        bool(inside)))
    kd = None
    worst = None
    if sweep is not None and nominal_force and nominal_kd is not None:
        s, fd = sweep
        u = uncertainty
        a_lo = np.maximum(1 - u, (1 - u) / s**2)
        a_hi = np.minimum(1 + u, (1 + u) / s**2)
        ok = a_lo <= a_hi * (1 + 1e-12)
        k_lo = 1 + a_lo * fd / nominal_force
        k_hi = 1 + a_hi * fd / nominal_force
        kd = (nominal_kd, float(min(k_lo[ok].min(), nominal_kd)),
              float(max(k_hi[ok].max(), nominal_kd)))
        worst = float(s[ok][np.argmax(k_hi[ok])])
    return Bands(float(uncertainty), np.column_stack([f * lo, f * hi]), tuple(detunings), kd,
                 worst)
