r"""Amplitude–frequency characteristics (AFC) of a chain contour ([MultimassChainDrives, §3.3], Fig. 3).

The driver speed is swept (default 10 %–150 % of nominal, 2000 points) and, at every speed,
the steady response to the kinematic excitation (:mod:`chaindrive.dynamics.excitation`) is
found by **modal superposition** with the eigen-decomposition computed once: with the
stiffness-proportional damping C = βK of :mod:`chaindrive.dynamics.frequency.steady` the undamped
mass-normalised modes Φ (Φᵀ M Φ = I, Φᵀ K Φ = Ω²) decouple the equations ([Rao2011,
§6.13–6.15]), so each frequency needs only diagonal modal responses::

    q_j = Φ_jᵀ f / (ω_j² (1 + iωβ) − ω²),   f = −(1 + iωβ) Bᵀ C_s D,
    F = (1 + iωβ) C_s (B Φ q + D).

The polygonal amplitudes D do not depend on the speed (only the frequencies k ω_z do), so
the whole sweep is a handful of broadcast array operations. The dynamic load of a span at
one speed is the peak |F_i(t)| over a tooth period (traces with ``samples`` points).
Resonance markers: the tooth frequencies f_j / k that put harmonic k on the natural
frequency f_j (Dynamics I).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    pass

__all__ = ["AfcResult"]




@dataclass(frozen=True, slots=True, eq=False)
class AfcResult:
    """Dynamic load of every span against the driver speed / tooth frequency.

    Parameters
    ----------
    driver_speeds : ndarray
        (S,) driver speeds of the sweep [rad/s].
    tooth_frequencies_hz : ndarray
        (S,) tooth frequencies z₁ω₁/2π [Hz].
    span_load : ndarray
        (S, n) peak dynamic load of every span [N].
    max_span_load : ndarray
        (n,) its largest value over the sweep [N] (F_2max, [MultimassChainDrives, §3.6]).
    natural_frequencies_hz : ndarray
        The elastic natural frequencies of the model [Hz].
    markers : tuple of tuple
        (mode, harmonic, natural frequency [Hz], tooth frequency [Hz]) of every resonance
        inside the sweep.
    peak_tooth_frequencies_hz : ndarray
        Tooth frequencies of the local maxima of max_i span_load [Hz].
    """

    driver_speeds: NDArray[np.float64]
    tooth_frequencies_hz: NDArray[np.float64]
    span_load: NDArray[np.float64]
    max_span_load: NDArray[np.float64]
    natural_frequencies_hz: NDArray[np.float64]
    markers: tuple[tuple[int, int, float, float], ...]
    peak_tooth_frequencies_hz: NDArray[np.float64]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; ``span_dynamic_load_n[i]`` is span i over the sweep."""
        return {
            "driver_speed_rpm": (self.driver_speeds * 30.0 / math.pi).tolist(),
            "tooth_frequency_hz": self.tooth_frequencies_hz.tolist(),
            "span_dynamic_load_n": self.span_load.T.tolist(),
            "max_span_dynamic_load_n": self.max_span_load.tolist(),
            "natural_frequencies_hz": self.natural_frequencies_hz.tolist(),
            "resonances": [{"mode": j, "harmonic": k, "natural_frequency_hz": f,
                            "tooth_frequency_hz": fz} for j, k, f, fz in self.markers],
            "peak_tooth_frequencies_hz": self.peak_tooth_frequencies_hz.tolist(),
        }


@lru_cache(maxsize=16)
def _trace_basis(orders: tuple[float, ...], samples: int) -> NDArray[np.float64]:
    """[cos kθ; sin kθ] (2K, T) on ``samples`` points θ of one period (kept: a search asks
    for the same orders and samples design after design; read-only)."""
    theta = np.linspace(0.0, TWO_PI, samples, endpoint=False)
    kt = np.outer(np.asarray(orders, dtype=float), theta)
    E = np.concatenate([np.cos(kt), np.sin(kt)])
    E.flags.writeable = False
    return E


def peak_over_period(F: NDArray[np.complex128], orders: NDArray[np.float64], samples: int,
                      block: int = 128) -> NDArray[np.float64]:
    """max over one tooth period of |Σ_k Re(F_k e^{i k θ})|, θ on ``samples`` points, for
    every (speed, span): F (S, K, n) → (S, n). The trace of ``block`` speeds at a time is one
    real matrix product [Re F, −Im F]·[cos kθ; sin kθ] (it stays in cache)."""
    S, K, n = F.shape
    E = _trace_basis(tuple(orders.tolist()), int(samples))          # (2K, T)
    A = np.concatenate([F.real, -F.imag], axis=1).transpose(0, 2, 1)  # (S, n, 2K)
    load = np.empty((S, n))
    for a in range(0, S, block):
        trace = A[a:a + block].reshape(-1, 2 * K) @ E              # (b·n, T)
        np.abs(trace, out=trace)
        load[a:a + block] = trace.max(axis=1).reshape(-1, n)
    return load


def local_maxima(y: NDArray[np.float64]) -> NDArray[np.intp]:
    """Interior indices with y[i−1] < y[i] ≥ y[i+1]."""
    if y.size < 3:
        return np.zeros(0, dtype=np.intp)
    return 1 + np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:]))


