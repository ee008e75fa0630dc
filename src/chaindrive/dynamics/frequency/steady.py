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

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    pass

__all__ = [
    "SteadyStateResult",
    "span_incidence",
]



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

    @property
    def tooth_frequency_hz(self) -> float:
        """f_z = ω_z/2π [Hz]."""
        return self.tooth_angular_frequency / TWO_PI

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (forces N, displacements mm)."""
        return {
            "tooth_frequency_hz": self.tooth_frequency_hz,
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



