r"""Kinematic excitation of the spans of a chain contour ([MultimassChainDrives, §3.1–3.3]).

Every disturbance is written as a **prescribed elongation** d_i(t) of span i, added to the
elastic elongation of the ring model (docs/dynamic_response.md §1)::

    F_i = c_i (e_i + d_i) + β c_i (ė_i + ḋ_i),    e_i = x_{i+1} − x_i,

x_i is the displacement of mass i along the chain travel (x_i = R_i φ_i, [MultimassChainDrives]); span i
leaves sprocket i and runs onto sprocket i+1 (chain travel from i to i+1, as in
:mod:`chaindrive.geometry.results`). A disturbance that moves the hinge at the **end** of the
span (on sprocket i+1) forward by δ_end pulls δ_end more chain out of the span, one that
moves the hinge at the **start** forward by δ_start pays δ_start more chain into it, so

    d_i = δ_end,i − δ_start,i    (> 0 stretches the span).

A disturbance is stored as a sum of harmonics, d_i(t) = Re Σ_f D[f, i] e^{i ω_f t}
(:class:`SpanExcitation`).

Chain path coordinate
---------------------
The positions of the tangent points along the chain path, in pitches, start at the point
where span 0 leaves sprocket 0: s_start,0 = 0, s_end,i = s_start,i + L_i/p (span length in
pitches, ``SpanGeometry.pitches``), s_start,i+1 = s_end,i + z_{i+1}θ_{i+1}/2π (the wrap of
sprocket i+1 in teeth, ``SprocketGeometry.teeth_in_mesh``). Hinges are p apart along the
chain, so with ψ = 0 meaning "a hinge at the tangent point" (the convention of
:mod:`chaindrive.kinematics`), the **tooth phase** at path position s is

    ψ(s, t) = ω_z t − 2π s,     ω_z = z_1 ω_1 (the common tooth frequency).

The phase between the two ends of a span is therefore −2π·(L/p) (only its fractional part
matters), [MultimassChainDrives]'s "difference of phases between nearby sprockets".

Polygonal effect
----------------
δ(ψ) = Σ_k b_k sin kψ, b_k = (p/π)(−1)^{k+1}/(k(k²z² − 1)) (docs/dynamics.md,
:func:`chaindrive.kinematics.hinge_displacement_coefficients`); harmonic k of the tooth
frequency has the complex amplitude −i b_k e^{−i 2π k s}. The amplitudes do not depend on the
speed: only the frequencies k ω_z do.

Sprocket eccentricity (once per revolution)
-------------------------------------------
A pitch circle whose centre is ε off the axis of rotation changes the lever arm of a span
by ε cos(φ + γ − α) (α: direction of the radius to the tangent point), so the chain end
moves by δ = ε sin(φ + γ − α) beyond the uniform motion. With γ measured from the radius to
the leaving point, the leaving end of sprocket j sees δ_start = ε_j sin(ω_j t + γ_j) and the
arriving end (θ_j earlier along the rotation, θ the wrap angle) δ_end = ε_j sin(ω_j t + γ_j +
θ_j), ω_j = ω_z / z_j its shaft speed.

Pitch scatter and accumulated chain-length error (once per chain revolution)
------------------------------------------------------------------------------
Hinge j of the chain (j = 0…N−1, N links) sits a_j = Σ_{l<j} (ε_l − ε̄) beyond its nominal
place (ε_l the error of pitch l; the mean error ε̄ only lengthens the chain and is taken up by
the tensioner). An accumulated length error Δ adds the first harmonic Δ sin(2πj/N). With
the chain coordinate σ = s − ω_z t/2π of the hinge at path position s, more chain in a span
slackens it: d_i = −[a(s_end − ω_z t/2π) − a(s_start − ω_z t/2π)], a(σ) the trigonometric
interpolation of a_j; harmonic m has the frequency m ω_z/N.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.kinematics import hinge_displacement_coefficients
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult

__all__ = [
    "SpanExcitation",
    "chain_error_excitation",
    "combine_excitations",
    "eccentricity_excitation",
    "path_positions",
    "polygonal_excitation",
    "polygonal_span_elongation",
]



@dataclass(frozen=True, slots=True, eq=False)
class SpanExcitation:
    """Prescribed span elongations d_i(t) = Re Σ_f D[f, i] e^{i ω_f t}.

    Parameters
    ----------
    angular_frequencies : ndarray
        (F,) ω_f [rad/s] at the speed it was built for.
    elongation : ndarray
        (F, n) complex amplitudes D [m].
    orders : ndarray
        (F,) ω_f / ω_z [-], the order with respect to the tooth frequency (so the same
        excitation can be rescaled to another speed).
    source : str
        ``"polygonal"``, ``"eccentricity"``, ``"chain_error"`` or several joined by ``+``.
    """

    angular_frequencies: NDArray[np.float64]
    elongation: NDArray[np.complex128]
    orders: NDArray[np.float64]
    source: str

    def at_tooth_frequency(self, omega_z: float) -> SpanExcitation:
        """The same excitation at another tooth frequency (amplitudes unchanged).

        Parameters
        ----------
        omega_z : float
            Tooth frequency ω_z [rad/s].

        Returns
        -------
        SpanExcitation
            The rescaled excitation.
        """
        return SpanExcitation(self.orders * omega_z, self.elongation, self.orders, self.source)

    def trace(self, times: ArrayLike) -> NDArray[np.float64]:
        """d_i(t) at ``times``.

        Parameters
        ----------
        times : array_like
            (T,) times [s].

        Returns
        -------
        ndarray
            (T, n) span elongations [m].
        """
        t = np.asarray(times, dtype=float)
        phase = np.exp(1j * np.outer(t, self.angular_frequencies))
        return (phase @ self.elongation).real

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (amplitudes |D| in mm)."""
        return {"source": self.source,
                "frequencies_hz": (self.angular_frequencies / TWO_PI).tolist(),
                "orders": self.orders.tolist(),
                "amplitude_mm": (np.abs(self.elongation) * 1e3).tolist()}


@shared_parameters
def path_positions(geometry: GeometryResult) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Positions s_start, s_end [pitches] of the tangent points of every span along the chain:
    s_start,0 = 0; s_end,i = s_start,i + L_i/p; s_start,i+1 = s_end,i + z_{i+1}θ_{i+1}/2π
    (module docstring).

    Parameters
    ----------
    %(contour_geometry)s

    Returns
    -------
    s_start, s_end : ndarray
        (n,) path positions [pitches].

    Raises
    ------
    DesignError
        ``geometry.spans`` not in ring order.
    """
    spans = geometry.spans
    n = len(spans)
    lengths = np.array([sp.pitches for sp in spans])
    wraps = np.array([geometry.sprockets[sp.end].teeth_in_mesh for sp in spans])
    s_end = np.cumsum(lengths) + np.concatenate(([0.0], np.cumsum(wraps)[:-1]))
    s_start = s_end - lengths
    if n and any(sp.start != i for i, sp in enumerate(spans)):
        raise DesignError("geometry.spans", "span i must start at sprocket i (ring order)")
    return s_start, s_end


@shared_parameters
def polygonal_span_elongation(pitch: float, teeth_start: ArrayLike, teeth_end: ArrayLike,
                              s_start: ArrayLike, s_end: ArrayLike,
                              harmonics: int = 10) -> NDArray[np.complex128]:
    """Complex amplitudes D[k−1, i] [m] of the polygonal elongation of every span.

    d_i = δ_end − δ_start with δ(ψ) = Σ A_k sin kψ + B_k cos kψ (phase ψ0 = −2π s), so
    D_k = (B_k − i A_k)_end − (B_k − i A_k)_start.

    Parameters
    ----------
    %(pitch)s
    teeth_start, teeth_end : array_like
        (n,) teeth of the sprocket at the start and at the end of each span [-].
    s_start, s_end : array_like
        (n,) path positions of the tangent points [pitches] (:func:`path_positions`).
    harmonics : int
        Harmonics N of the tooth frequency [-] ([MultimassChainDrives]: 10).

    Returns
    -------
    ndarray
        (N, n) complex amplitudes D [m].

    References
    ----------
    [ChainNonUniformity] (the hinge displacement of the polygonal effect);
    [MultimassChainDrives, §3.1–3.3].
    """
    a_s, b_s = hinge_displacement_coefficients(pitch, teeth_start, harmonics,
                                               -TWO_PI * np.asarray(s_start, float))
    a_e, b_e = hinge_displacement_coefficients(pitch, teeth_end, harmonics,
                                               -TWO_PI * np.asarray(s_end, float))
    return ((b_e - 1j * a_e) - (b_s - 1j * a_s)).T


def _teeth_by_span(geometry: GeometryResult) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    z = np.array([g.teeth for g in geometry.sprockets], dtype=float)
    starts = np.array([sp.start for sp in geometry.spans])
    ends = np.array([sp.end for sp in geometry.spans])
    return z[starts], z[ends]


@shared_parameters
def polygonal_excitation(geometry: GeometryResult, tooth_angular_frequency: float,
                         harmonics: int = 10) -> SpanExcitation:
    """Polygonal excitation of every span of a contour at the tooth frequency ω_z = z₁ω₁.

    Harmonics k = 1…N of the tooth frequency; the phases follow from the span lengths and
    wraps in pitches (:func:`path_positions`).

    Parameters
    ----------
    %(contour_geometry)s
    %(tooth_angular_frequency)s
    harmonics : int
        Harmonics N kept [-] (default 10, practically exact by [MultimassChainDrives]).

    Returns
    -------
    SpanExcitation
        Orders 1…N, source ``"polygonal"``.

    References
    ----------
    [ChainNonUniformity]; [MultimassChainDrives, §3.1–3.3].
    """
    s_start, s_end = path_positions(geometry)
    z_s, z_e = _teeth_by_span(geometry)
    D = polygonal_span_elongation(geometry.pitch, z_s, z_e, s_start, s_end, harmonics)
    orders = np.arange(1, int(harmonics) + 1, dtype=float)
    return SpanExcitation(orders * tooth_angular_frequency, D, orders, "polygonal")


@shared_parameters
def eccentricity_excitation(geometry: GeometryResult, tooth_angular_frequency: float,
                            eccentricity: ArrayLike, phase: ArrayLike | None = None
                            ) -> SpanExcitation:
    """Once-per-revolution excitation of sprocket eccentricities (module docstring).

    Sprocket j turns at ω_j = ω_z/z_j; sprockets of equal teeth turn at the same speed and are
    summed into one harmonic.

    Parameters
    ----------
    %(contour_geometry)s
    %(tooth_angular_frequency)s
    eccentricity : array_like
        (n,) eccentricity ε_j of every sprocket [m] (0: none).
    phase : array_like or None
        (n,) angle γ_j from the radius to the leaving point [rad] (None: 0).

    Returns
    -------
    SpanExcitation
        Orders 1/z_j, source ``"eccentricity"``.

    Raises
    ------
    DesignError
        A negative or non-finite eccentricity.

    References
    ----------
    [MultimassChainDrives, §2] (the internal disturbances).
    """
    n = len(geometry.sprockets)
    eps = np.broadcast_to(np.asarray(eccentricity, dtype=float), (n,))
    gam = np.zeros(n) if phase is None else np.broadcast_to(np.asarray(phase, float), (n,))
    if np.any(eps < 0) or not np.all(np.isfinite(eps)):
        raise DesignError("eccentricity", "must be finite and ≥ 0 [m]")
    z = np.array([g.teeth for g in geometry.sprockets], dtype=float)
    theta = np.array([g.wrap_angle for g in geometry.sprockets])
    zs = np.unique(z[eps > 0])
    D = np.zeros((zs.size, n), dtype=complex)
    for f, zf in enumerate(zs):
        for j in np.flatnonzero((z == zf) & (eps > 0)):
            # ε sin(ωt + γ) = Re(−i ε e^{iγ} e^{iωt})
            D[f, j] -= -1j * eps[j] * np.exp(1j * gam[j])                    # leaving: span j
            D[f, (j - 1) % n] += -1j * eps[j] * np.exp(1j * (gam[j] + theta[j]))  # arriving
    orders = 1.0 / zs
    return SpanExcitation(orders * tooth_angular_frequency, D, orders, "eccentricity")


def hinge_position_errors(links: int, pitch_errors: ArrayLike | None = None,
                          accumulated_error: float = 0.0) -> NDArray[np.float64]:
    """Position errors a_j [m] of the N hinges: Σ_{l<j}(ε_l − ε̄) + Δ sin(2πj/N).

    pitch_errors : (N,) ε_l [m] of every pitch (None: 0); accumulated_error Δ [m].
    """
    j = np.arange(links)
    a = accumulated_error * np.sin(TWO_PI * j / links)
    if pitch_errors is not None:
        e = np.asarray(pitch_errors, dtype=float)
        if e.shape != (links,):
            raise DesignError("pitch_errors", f"need {links} pitch errors, got {e.shape}")
        a = a + np.concatenate(([0.0], np.cumsum(e - e.mean())[:-1]))
    return a


@shared_parameters
def chain_error_excitation(geometry: GeometryResult, tooth_angular_frequency: float, *,
                           pitch_errors: ArrayLike | None = None, pitch_scatter: float = 0.0,
                           accumulated_error: float = 0.0, harmonics: int = 20,
                           seed: int = 0) -> SpanExcitation:
    """Excitation by the pitch scatter and the accumulated length error of the chain
    (derivation in the module docstring).

    Parameters
    ----------
    %(contour_geometry)s
    %(tooth_angular_frequency)s
    pitch_errors : array_like or None
        (links,) error of every pitch [m] (None: drawn from ``pitch_scatter``, or 0).
    pitch_scatter : float
        Standard deviation σ of the pitch errors drawn as Normal(0, σ²) [m].
    accumulated_error : float
        Accumulated length error Δ of the chain [m] (first harmonic along the chain).
    harmonics : int
        Chain-passage harmonics m = 1…M kept [-] (frequency m ω_z/N).
    seed : int
        Seed of the random draw (reproducible).

    Returns
    -------
    SpanExcitation
        Orders m/N, source ``"chain_error"``.

    References
    ----------
    [MultimassChainDrives, §2] (the internal disturbances).
    """
    links = int(geometry.links)
    if pitch_errors is None and pitch_scatter > 0:
        pitch_errors = np.random.default_rng(seed).normal(0.0, pitch_scatter, links)
    a = hinge_position_errors(links, pitch_errors, accumulated_error)
    M = max(1, min(int(harmonics), (links - 1) // 2))
    c = np.fft.rfft(a)[1:M + 1] / links                       # a(σ) = Σ c_m e^{i2πmσ/N} + cc
    s_start, s_end = path_positions(geometry)
    m = np.arange(1, M + 1, dtype=float)[:, None]
    rot_e = np.exp(-1j * TWO_PI * m * s_end[None, :] / links)
    rot_s = np.exp(-1j * TWO_PI * m * s_start[None, :] / links)
    D = -2.0 * np.conj(c)[:, None] * (rot_e - rot_s)
    orders = m.ravel() / links
    return SpanExcitation(orders * tooth_angular_frequency, D, orders, "chain_error")


def combine_excitations(*parts: SpanExcitation) -> SpanExcitation:
    """All harmonics of several excitations in one (frequencies concatenated).

    Parameters
    ----------
    *parts : SpanExcitation
        The excitations, at least one.

    Returns
    -------
    SpanExcitation
        Their harmonics together, the sources joined by ``+``.
    """
    if not parts:
        raise DesignError("excitation", "need at least one excitation")
    return SpanExcitation(np.concatenate([p.angular_frequencies for p in parts]),
                          np.concatenate([p.elongation for p in parts]),
                          np.concatenate([p.orders for p in parts]),
                          "+".join(p.source for p in parts))
