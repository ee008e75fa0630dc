r"""Steady periodic response of the ring model to kinematic span excitation (frequency domain).

[MultimassChainDrives, §3.2–3.3]: the equations of motion with the disturbance functions
(prescribed span elongations d, :mod:`chaindrive.dynamics.excitation`)::

    M ẍ + β K ẋ + K x = −Bᵀ C_s (d + β ḋ),      F = C_s (B x + d) + β C_s (B ẋ + ḋ)

B (n×n) is the span incidence (e = B x, B[i, i] = −1, B[i, i+1] = +1), C_s = diag(c_i),
K = Bᵀ C_s B the ring Laplacian of :mod:`chaindrive.dynamics.ring`.

**Damping matrix.** Stiffness-proportional (Rayleigh β-) damping C = β K with
β = 2ζ/ω_ref, ω_ref the first elastic natural frequency, so that mode has exactly the ratio
ζ ([MultimassChainDrives]: D = 0.06; or ζ = ψ/4π from [ChainHingeDissipation]) and mode j
has ζ_j = ζ ω_j/ω_ref
(Rao, Mechanical Vibrations, 6th ed., §6.13 "proportional damping"). Chosen because the
damping of a chain is in the chain (hinge friction, [ChainHingeDissipation]): β K is a dashpot β c_i in
parallel with every span, so the span force, the slack-span rule of the start-up and the
energy balance stay local to the spans, and the same model serves the frequency domain,
the modal sweep (β K is classical: the undamped modes decouple it) and the time domain.
Its cost: higher modes are more damped than the first.

For one angular frequency ω and complex amplitudes D (x = Re X e^{iωt}) the response is one
complex linear solve (Rao §6.15, harmonic response of a damped multi-DOF system)::

    [(1 + iωβ) K − ω² M] X = −(1 + iωβ) Bᵀ C_s D,     F = (1 + iωβ) C_s (B X + D)

All harmonics are solved at once by :func:`numpy.linalg.solve` on the stacked systems.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.dynamics.quality import coefficient_of_dynamics
from chaindrive.errors import DesignError
from chaindrive.strength.safety import steady_safety_factor

if TYPE_CHECKING:
    from chaindrive.dynamics.excitation import SpanExcitation
    from chaindrive.dynamics.ring import RingModel

__all__ = [
    "SteadyStateResult",
    "damping_beta",
    "harmonic_response",
    "span_incidence",
    "steady_state",
]

TWO_PI = 2.0 * math.pi


def span_incidence(n: int, closed: bool = True) -> NDArray[np.float64]:
    """Span incidence B (n×n): e = B x, e_i = x_{i+1} − x_i.

    Parameters
    ----------
    n : int
        Number of masses and spans [-].
    closed : bool
        False for an open chain (the last row is 0).

    Returns
    -------
    ndarray
        (n, n) B [-].
    """
    B = np.zeros((n, n))
    i = np.arange(n)
    B[i, i] -= 1.0
    B[i, (i + 1) % n] += 1.0
    if not closed:
        B[-1] = 0.0
    return B


def damping_beta(model: RingModel, reference_angular_frequency: float | None = None) -> float:
    """β = 2ζ/ω_ref [s] of the stiffness-proportional damping C = βK (module docstring).

    Parameters
    ----------
    model : RingModel
        The ring model (its damping ratio ζ).
    reference_angular_frequency : float or None
        ω_ref [rad/s] (None: the first elastic natural frequency of ``model``).

    Returns
    -------
    float
        β [s]; 0 when the model has no elastic mode or ζ = 0.

    References
    ----------
    [Rao2011, §6.13] (proportional damping).
    """
    w = reference_angular_frequency
    if w is None:
        modal = model.modal()
        el = modal.angular_frequencies_rad_s[~modal.rigid_body]
        w = float(el[0]) if el.size else 0.0
    return 2.0 * model.damping_ratio / w if w > 0 else 0.0


def _stiffness(model: RingModel) -> NDArray[np.float64]:
    c = model.stiffness_n_per_m.copy()
    if not model.closed:
        c[-1] = 0.0
    return c


def harmonic_response(masses: ArrayLike, stiffness: ArrayLike, beta: float,
                      angular_frequencies: ArrayLike, elongation: ArrayLike
                      ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Complex amplitudes of the displacements X and span forces F for prescribed span
    elongations: one stacked :func:`numpy.linalg.solve` of
    [(1 + iωβ) K − ω² M] X = −(1 + iωβ) Bᵀ C_s D (module docstring).

    Parameters
    ----------
    masses : array_like
        (n,) reduced masses [kg].
    stiffness : array_like
        (n,) span stiffnesses c_i [N/m] (0: slack or open).
    beta : float
        β of the damping C = βK [s].
    angular_frequencies : array_like
        (F,) excitation angular frequencies ω > 0 [rad/s].
    elongation : array_like
        (F, n) complex amplitudes D of the prescribed span elongations [m].

    Returns
    -------
    displacement : ndarray
        (F, n) complex amplitudes X [m].
    span_force : ndarray
        (F, n) complex span force amplitudes [N].

    Raises
    ------
    DesignError
        A wrong shape of ``elongation`` or a frequency that is not positive.

    References
    ----------
    [Rao2011, §6.15] (harmonic response of a damped multi-degree-of-freedom system);
    [MultimassChainDrives, §3.2–3.3].
    """
    m = np.asarray(masses, dtype=float)
    c = np.asarray(stiffness, dtype=float)
    w = np.atleast_1d(np.asarray(angular_frequencies, dtype=float))
    D = np.atleast_2d(np.asarray(elongation, dtype=complex))
    n = m.size
    if D.shape != (w.size, n):
        raise DesignError("elongation", f"need shape ({w.size}, {n}), got {D.shape}")
    if np.any(w <= 0):
        raise DesignError("angular_frequencies", "must be > 0 (the static part is not solved)")
    B = span_incidence(n)
    K = B.T @ (c[:, None] * B)
    g = 1.0 + 1j * w * beta                                          # (F,)
    A = g[:, None, None] * K[None] - (w**2)[:, None, None] * np.diag(m)[None]
    rhs = -(g[:, None] * (D * c[None, :])) @ B                       # −g Bᵀ C_s D, row form
    X = np.linalg.solve(A, rhs[..., None])[..., 0]
    F = g[:, None] * c[None, :] * (X @ B.T + D)
    return X, F


@dataclass(frozen=True, slots=True, eq=False)
class SteadyStateResult:
    """Steady response of the ring to a kinematic excitation ([MultimassChainDrives, §3.3]).

    Parameters
    ----------
    tooth_angular_frequency : float
        ω_z [rad/s].
    angular_frequencies : ndarray
        (F,) angular frequencies of the harmonics [rad/s].
    displacement : ndarray
        (F, n) complex displacement amplitudes [m].
    span_force : ndarray
        (F, n) complex span force amplitudes [N].
    times : ndarray
        (T,) one tooth period [s].
    span_force_trace : ndarray
        (T, n) span forces over it [N].
    displacement_trace : ndarray
        (T, n) displacements over it [m].
    span_dynamic_load : ndarray
        (n,) max |F_i(t)| [N].
    span_load_amplitude : ndarray
        (n,) (max − min)/2 of F_i [N].
    inertia_load : ndarray
        (n,) max |m_i ẍ_i| [N].
    displacement_amplitude : ndarray
        (n,) x_A [m].
    irregularity_percent : ndarray
        (n,) Δ = (ω_max − ω_min)/ω_mean·100 of every sprocket from its speed history [%]
        (2 x_A z/R·100 for one harmonic, [MultimassChainDrives, §3.3]); NaN without radii.
    dynamic_load_rms : float
        F_D, the root mean square of ``span_dynamic_load`` [N].
    coefficient_of_dynamics : float or None
        K_D = 1 + F_D/F_t [-] (None without F_t).
    k2, k2_min : float or None
        Dynamic safety factors [-] ([MultimassChainDrives, §3.6]; None without Q and F_R).
    periodic : bool
        False when the frequencies are not all harmonics of ω_z (then the peaks are the sums
        of harmonic amplitudes: exact for incommensurate frequencies, an upper bound
        otherwise).
    rotor_names : tuple of str
        The rotors of the trains (whole-drive model).
    rotor_irregularity_percent : ndarray
        Their irregularity of rotation Δ [%].
    nominal_force : float or None
        F_t that K_D is taken against [N] (None: none given).
    """

    tooth_angular_frequency: float
    angular_frequencies: NDArray[np.float64]
    displacement: NDArray[np.complex128]
    span_force: NDArray[np.complex128]
    times: NDArray[np.float64]
    span_force_trace: NDArray[np.float64]
    displacement_trace: NDArray[np.float64]
    span_dynamic_load: NDArray[np.float64]
    span_load_amplitude: NDArray[np.float64]
    inertia_load: NDArray[np.float64]
    displacement_amplitude: NDArray[np.float64]
    irregularity_percent: NDArray[np.float64]
    dynamic_load_rms: float
    coefficient_of_dynamics: float | None
    k2: float | None
    k2_min: float | None
    periodic: bool
    rotor_names: tuple[str, ...] = ()
    rotor_irregularity_percent: NDArray[np.float64] = field(
        default_factory=lambda: np.zeros(0))
    nominal_force: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (forces N, displacements mm)."""
        return {
            "tooth_frequency_hz": self.tooth_angular_frequency / TWO_PI,
            "harmonic_frequencies_hz": (self.angular_frequencies / TWO_PI).tolist(),
            "span_dynamic_load_n": self.span_dynamic_load.tolist(),
            "span_load_amplitude_n": self.span_load_amplitude.tolist(),
            "span_load_harmonics_n": np.abs(self.span_force).T.tolist(),
            "inertia_load_n": self.inertia_load.tolist(),
            "displacement_amplitude_mm": (self.displacement_amplitude * 1e3).tolist(),
            "irregularity_percent": self.irregularity_percent.tolist(),
            "rotor_irregularity_percent": dict(zip(
                self.rotor_names, self.rotor_irregularity_percent.tolist(), strict=True)),
            "dynamic_load_rms_n": self.dynamic_load_rms,
            "coefficient_of_dynamics": self.coefficient_of_dynamics,
            "nominal_force_n": self.nominal_force,
            "k2": self.k2,
            "k2min": self.k2_min,
            "periodic": self.periodic,
            "time_s": self.times.tolist(),
            "span_load_trace_n": self.span_force_trace.T.tolist(),
        }


def _peaks(amplitudes: NDArray[np.complex128], trace: NDArray[np.float64] | None
           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(max |y(t)|, (max − min)/2) per column, from the trace or from Σ|Y_f|."""
    if trace is not None:
        return np.abs(trace).max(axis=0), 0.5 * (trace.max(axis=0) - trace.min(axis=0))
    s = np.abs(amplitudes).sum(axis=0)
    return s, s


def steady_state(model: RingModel, excitation: SpanExcitation, *,
                 radii: ArrayLike | None = None, beta: float | None = None,
                 samples: int = 128, nominal_force: float | None = None,
                 teeth: ArrayLike | None = None,
                 breaking_load: float | None = None,
                 operating_forces: ArrayLike | None = None,
                 resonance_loads: ArrayLike | None = None) -> SteadyStateResult:
    """Steady response of ``model`` to ``excitation`` in the frequency domain.

    Parameters
    ----------
    model : RingModel
        The ring model.
    excitation : SpanExcitation
        The prescribed span elongations.
    radii : array_like or None
        (n,) pitch radii R_i [m], with ``teeth`` for the irregularity of rotation
        Δ = (ω_max − ω_min)/ω_mean·100, ω_mean = ω_z/z_i (None: Δ is NaN).
    beta : float or None
        β of the damping C = βK [s] (None: :func:`damping_beta`).
    samples : int
        Samples per tooth period of the traces [-].
    nominal_force : float or None
        Nominal peripheral force F_t [N] → K_D = 1 + F_D/F_t.
    teeth : array_like or None
        (n,) teeth z_i [-].
    breaking_load : float or None
        Breaking load Q of the chain [N], with ``operating_forces`` → k2.
    operating_forces : array_like or None
        (n,) static span tensions F_R [N]; k2 = min_i Q/(F_R,i + F_2,i).
    resonance_loads : array_like or None
        (n,) F_2max at resonance [N] → k2_min.

    Returns
    -------
    SteadyStateResult
        Amplitudes, one period of traces, loads and the quality indices.

    References
    ----------
    [MultimassChainDrives, §3.3] (dynamic loads, irregularity, K_D);
    [MultimassChainDrives, §3.6] (k2, k2_min).
    """
    m = model.masses_kg
    c = _stiffness(model)
    b = damping_beta(model) if beta is None else float(beta)
    w = excitation.angular_frequencies
    X, F = harmonic_response(m, c, b, w, excitation.elongation)
    orders = excitation.orders
    wz = float(w[0] / orders[0]) if w.size else 0.0
    periodic = bool(np.allclose(orders, np.round(orders)) and np.all(orders >= 1))
    times = np.linspace(0.0, TWO_PI / wz, int(samples), endpoint=False)
    E = np.exp(1j * np.outer(times, w))                              # (T, F)
    f_tr = (E @ F).real
    x_tr = (E @ X).real
    a_tr = (E @ (-(w**2)[:, None] * X)).real
    f_max, f_amp = _peaks(F, f_tr if periodic else None)
    _, x_amp = _peaks(X, x_tr if periodic else None)
    acc, _ = _peaks(-(w**2)[:, None] * X, a_tr if periodic else None)
    R = np.full(m.size, np.nan) if radii is None else np.asarray(radii, dtype=float)
    z = np.full(m.size, np.nan) if teeth is None else np.asarray(teeth, dtype=float)
    v_tr = (E @ (1j * w[:, None] * X)).real
    v_range = np.ptp(v_tr, axis=0) if periodic else 2.0 * np.abs(w[:, None] * X).sum(axis=0)
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
    return SteadyStateResult(
        tooth_angular_frequency=wz, angular_frequencies=w, displacement=X, span_force=F,
        times=times, span_force_trace=f_tr, displacement_trace=x_tr, span_dynamic_load=f_max,
        span_load_amplitude=f_amp, inertia_load=m * acc, displacement_amplitude=x_amp,
        irregularity_percent=100.0 * v_range * z / (R * wz), dynamic_load_rms=rms,
        coefficient_of_dynamics=kd, k2=k2, k2_min=k2min, periodic=periodic,
        nominal_force=nominal_force,
    )
