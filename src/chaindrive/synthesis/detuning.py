"""The detuning task of [MultimassChainDrives, §3.2]: move the natural frequencies out of
bands round the working frequencies and minimise the normalised amplitudes, by varying masses
and/or stiffnesses within bounds.

[MultimassChainDrives, §3.2]: "varying masses and stiffnesses within bounds
(M_k* ≤ M_k ≤ M_k**, C_l* ≤ C_l ≤ C_l**) detunes the spectrum from working frequencies";
"minimising [the normalised amplitude] for the masses near a working frequency reduces
vibroactivity". The objective (minimised)::

    J = W · Σ_{j,w} max(0, b − |f_j − f_w|/f_w)²  +  A,

b the band (default 10 % plus a 1 % safety), f_j the elastic natural frequencies, f_w the
working frequencies, A the largest normalised amplitude at the working frequencies
(:func:`normalised_amplitude_at`) and W = 10⁴ so that
clearing the bands comes first. Solved by differential evolution [StornPrice1997]
(:func:`scipy.optimize.differential_evolution`) in log m, log c over the whole population
at once (stacked eigenproblems), reproducible with a seed.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.dynamics.modes import Modes, inertia_modes_batch
from chaindrive.dynamics.resonance import working_frequencies
from chaindrive.errors import DesignError
from chaindrive.model import Drive
from chaindrive.units import TWO_PI

__all__ = ["DetuningResult", "band_shortfall", "detune", "detune_drive", "detuning_objective",
           "normalised_amplitude_at", "ring_modes_batch"]

BAND = 0.10
PENALTY = 1e4


@shared_parameters
def ring_modes_batch(masses: NDArray[np.float64], stiffness: NDArray[np.float64]
                     ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Elastic frequencies and largest normalised amplitude per mode of B closed rings.

    Parameters
    ----------
    %(batch_masses)s
    stiffness : numpy.ndarray
        (B, n) branch stiffnesses [N/m], branch k between masses k and k+1.

    Returns
    -------
    tuple of numpy.ndarray
        Frequencies (B, n−1) [Hz] and the largest normalised amplitude
        μ_k^(j) = |X_k|/Σ|X_i| of each mode (B, n−1) [-].

    References
    ----------
    [MultimassChainDrives, eq. 2].
    """
    B, n = masses.shape
    d = 1.0 / np.sqrt(masses)
    i = np.arange(n)
    j = (i + 1) % n
    A = np.zeros((B, n, n))
    A[:, i, i] = (stiffness + np.roll(stiffness, 1, axis=1)) / masses
    off = -stiffness * d * d[:, j]
    A[:, i, j] += off
    A[:, j, i] += off
    lam, v = np.linalg.eigh(A)
    X = np.abs(v * d[:, :, None])                                  # M^-1/2 v, columns = modes
    mu = (X / X.sum(axis=1, keepdims=True)).max(axis=1)
    f = np.sqrt(np.maximum(lam, 0.0)) / TWO_PI
    return f[:, 1:], mu[:, 1:]


def band_shortfall(frequencies_hz: NDArray[np.float64], working_hz: ArrayLike,
                   band: float) -> NDArray[np.float64]:
    """Σ max(0, band − |f_j − f_w|/f_w)² over modes and working frequencies, per design.

    Parameters
    ----------
    frequencies_hz : numpy.ndarray
        (B, modes) natural frequencies [Hz].
    working_hz : float or array_like
        Working frequencies [Hz].
    band : float
        Relative half-width of the band [-].

    Returns
    -------
    numpy.ndarray
        (B,) shortfall [-].
    """
    w = np.asarray(working_hz, dtype=float)
    rel = np.abs(frequencies_hz[:, :, None] - w[None, None, :]) / w[None, None, :]
    shortfall: NDArray[np.float64] = (np.maximum(0.0, band - rel) ** 2).sum(axis=(1, 2))
    return shortfall


ModesBatch = Callable[[NDArray[np.float64], NDArray[np.float64]],
                      tuple[NDArray[np.float64], NDArray[np.float64]]]


@shared_parameters
def detuning_objective(masses: NDArray[np.float64], stiffness: NDArray[np.float64],
                       working_hz: ArrayLike, band: float = BAND + 0.01,
                       damping: float = 0.06, modes: ModesBatch | None = None
                       ) -> NDArray[np.float64]:
    """The objective J of the module docstring for B designs.

    Parameters
    ----------
    %(batch_masses)s
    stiffness : numpy.ndarray
        (B, n) branch stiffnesses [N/m].
    working_hz : float or array_like
        Working frequencies [Hz].
    band : float
        Relative half-width of the band [-].
    damping : float
        Damping ratio ζ [-].
    modes : callable or None
        (masses, stiffness) (B, n) → elastic frequencies [Hz] and largest normalised
        amplitudes (B, E) of the model to detune (None: the ring, :func:`ring_modes_batch`).

    Returns
    -------
    numpy.ndarray
        (B,) J [-].

    References
    ----------
    [MultimassChainDrives, §3.2]; [Rao2011, §3.4] (single-mode magnification).
    """
    f, mu = (modes or ring_modes_batch)(masses, stiffness)
    w = np.asarray(working_hz, dtype=float)
    r = w[None, :, None] / f[:, None, :]
    h = 1.0 / np.sqrt((1 - r**2) ** 2 + (2 * damping * r) ** 2)
    amp = (mu[:, None, :] * h).max(axis=(1, 2))
    objective: NDArray[np.float64] = PENALTY * band_shortfall(f, w, band) + amp
    return objective


@dataclass(frozen=True, slots=True, eq=False)
class DetuningResult:
    """The result of a detuning.

    Parameters
    ----------
    masses_kg : numpy.ndarray
        (n,) masses found [kg].
    stiffness_n_per_m : numpy.ndarray
        (n,) stiffnesses found [N/m].
    frequencies_hz : numpy.ndarray
        (n−1,) elastic natural frequencies [Hz].
    working_hz : numpy.ndarray
        Working frequencies [Hz].
    min_distance : float
        Smallest |f_j − f_w|/f_w [-].
    band : float
        The band asked for [-] (``cleared``: min_distance ≥ band).
    objective : float
        J [-].
    """

    masses_kg: NDArray[np.float64]
    stiffness_n_per_m: NDArray[np.float64]
    frequencies_hz: NDArray[np.float64]
    working_hz: NDArray[np.float64]
    min_distance: float
    band: float
    objective: float

    @property
    def cleared(self) -> bool:
        """Every natural frequency at least ``band`` from every working frequency."""
        return self.min_distance >= self.band

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"masses_kg": self.masses_kg.tolist(),
                "stiffness_n_per_m": self.stiffness_n_per_m.tolist(),
                "natural_frequencies_hz": self.frequencies_hz.tolist(),
                "working_frequencies_hz": self.working_hz.tolist(),
                "min_distance_percent": 100 * self.min_distance, "band_percent": 100 * self.band,
                "cleared": self.cleared, "objective": self.objective}


def _bounds(values: NDArray, bounds: ArrayLike | None, path: str) -> NDArray:
    if bounds is None:
        return np.column_stack([values, values])
    b = np.asarray(bounds, dtype=float)
    if b.shape != (values.size, 2) or np.any(b[:, 0] <= 0) or np.any(b[:, 0] > b[:, 1]):
        raise DesignError(path, f"need ({values.size}, 2) positive [low, high] pairs")
    return b


def _de_kwargs(seed: int) -> dict[str, Any]:
    # scipy.optimize (0.2 s) only where the detuning search runs: the optimiser imports
    # this module for the detuning objective alone
    from scipy.optimize import differential_evolution

    name = "rng" if "rng" in inspect.signature(differential_evolution).parameters else "seed"
    return {name: seed}


def detune(masses: ArrayLike, stiffness: ArrayLike, working_hz: ArrayLike, *,
           band: float = BAND, mass_bounds: ArrayLike | None = None,
           stiffness_bounds: ArrayLike | None = None, damping: float = 0.06,
           seed: int = 0, maxiter: int = 200, popsize: int = 20,
           modes: ModesBatch | None = None) -> DetuningResult:
    """Masses and/or stiffnesses within bounds that clear ±band round every working
    frequency and minimise the normalised amplitude (module docstring).

    Starts from (and keeps, if no better is found) the given values when they lie inside the
    bounds.

    Parameters
    ----------
    masses : array_like
        (n,) reduced masses [kg].
    stiffness : array_like
        (n,) branch stiffnesses [N/m].
    working_hz : array_like
        Working frequencies [Hz].
    band : float
        Relative half-width of the band to clear [-].
    mass_bounds, stiffness_bounds : array_like or None
        (n, 2) [low, high] per mass [kg] / branch [N/m] (None: fixed; a pair with
        low = high fixes one value).
    damping : float
        Damping ratio ζ [-].
    seed : int
        Seed of the differential evolution.
    maxiter, popsize : int
        Of the differential evolution [-].
    modes : callable or None
        (masses, stiffness) (B, n) → elastic frequencies [Hz] and largest normalised
        amplitudes (B, E) of the model to detune (None: the ring, :func:`ring_modes_batch`).

    Returns
    -------
    DetuningResult
        The masses and stiffnesses found.

    References
    ----------
    [MultimassChainDrives, §3.2]; [StornPrice1997].
    """
    m0 = np.asarray(masses, dtype=float)
    c0 = np.asarray(stiffness, dtype=float)
    if m0.ndim != 1 or m0.shape != c0.shape or m0.size < 2:
        raise DesignError("masses", "need masses and stiffnesses of equal length ≥ 2")
    w = np.asarray(working_hz, dtype=float)
    if w.size == 0 or np.any(w <= 0):
        raise DesignError("working_hz", "need at least one positive working frequency")
    if not 0 < band < 1:
        raise DesignError("band", f"must be a fraction in (0, 1), got {band!r}")
    b = np.log(np.vstack([_bounds(m0, mass_bounds, "mass_bounds"),
                          _bounds(c0, stiffness_bounds, "stiffness_bounds")]))
    free = np.flatnonzero(b[:, 1] > b[:, 0])
    if free.size == 0:
        raise DesignError("detune", "no mass or stiffness may vary: give bounds")
    n = m0.size
    base = np.exp(b[:, 0])
    fixed = b[:, 1] == b[:, 0]
    base[:n][fixed[:n] & (mass_bounds is None)] = m0[fixed[:n] & (mass_bounds is None)]
    base[n:][fixed[n:] & (stiffness_bounds is None)] = c0[fixed[n:] & (stiffness_bounds is None)]

    def unpack(z: NDArray) -> tuple[NDArray, NDArray]:
        p = np.repeat(base[None, :], z.shape[1], axis=0)  # fixed values exactly as given
        p[:, free] = np.exp(z.T)
        return p[:, :n], p[:, n:]

    def func(z: NDArray, /) -> NDArray:
        return detuning_objective(*unpack(z), w, band + 0.01, damping, modes)

    x0 = np.log(np.concatenate([m0, c0]))[free]
    inside = bool(np.all(x0 >= b[free, 0]) and np.all(x0 <= b[free, 1]))
    # vectorized=True: func takes the (free, S) population and returns (S,), which the
    # stubs (a scalar function) do not describe
    from scipy.optimize import differential_evolution

    res = differential_evolution(func, b[free],  # type: ignore[arg-type]
                                 maxiter=maxiter, popsize=popsize, tol=1e-8, polish=False,
                                 vectorized=True, updating="deferred",
                                 x0=x0 if inside else None, **_de_kwargs(seed))
    m, c = unpack(res.x[:, None])
    f, _ = (modes or ring_modes_batch)(m, c)
    dist = float(np.min(np.abs(f[0][:, None] - w[None, :]) / w[None, :]))
    return DetuningResult(m[0], c[0], f[0], w, dist, band, float(func(res.x[:, None])[0]))


def detune_drive(drive: Drive, added_inertia: Mapping[str, tuple[float, float]], *,
                 band: float = BAND, seed: int = 0, harmonics: int = 3,
                 maxiter: int = 200) -> tuple[Drive, DetuningResult]:
    """Detune a drive by added inertia (flywheels) on the named shafts.

    The masses m_k = (I_k + ΔI_k)/R_k² vary, the stiffnesses stay those of the drive (static
    span tensions); the working frequencies are the shafts' and the tooth frequency with its
    harmonics (:func:`chaindrive.dynamics.resonance.working_frequencies`).

    Parameters
    ----------
    drive : Drive
        The design.
    added_inertia : mapping of str to (float, float)
        Sprocket name → (ΔI_min, ΔI_max) [kg·m²].
    band : float
        Relative half-width of the band to clear [-].
    seed : int
        Seed of the differential evolution.
    harmonics : int
        Harmonics of the tooth frequency [-].
    maxiter : int
        Generations of the differential evolution [-].

    Returns
    -------
    tuple of (Drive, DetuningResult)
        The drive with the new inertias (``Sprocket.inertia`` = I_k + ΔI_k) and the result.

    References
    ----------
    [MultimassChainDrives, §3.1–3.2].
    """
    a = Analysis(drive, response=False)
    p = a.ring_parameters
    names = [s.name for s in drive.sprockets]
    bounds = np.column_stack([p.masses_kg, p.masses_kg])
    for name, (lo, hi) in added_inertia.items():
        if name not in names:
            raise DesignError(f"added_inertia.{name}", f"no sprocket named {name!r}")
        if not 0 <= lo <= hi:
            raise DesignError(f"added_inertia.{name}", f"need 0 ≤ low ≤ high, got {(lo, hi)!r}")
        k = names.index(name)
        bounds[k] = (p.inertias_kg_m2[k] + np.array([lo, hi])) / p.pitch_radii_m[k] ** 2
    d = a.drive
    assert d.driver.speed is not None
    w = [x.frequency for x in working_frequencies(d.driver.speed, d.driver.teeth,
                                                  [s.teeth for s in d.sprockets],
                                                  harmonics=harmonics)]
    model = a.drive_model
    m0 = p.masses_kg.copy()

    def modes(masses: NDArray[np.float64], _: NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        # the analysis' whole-drive model with the added inertias (m − m₀)R² on the shafts
        return inertia_modes_batch(model, (masses - m0) * p.pitch_radii_m**2)

    res = detune(p.masses_kg, p.stiffness_n_per_m, w, band=band, mass_bounds=bounds,
                 seed=seed, maxiter=maxiter, modes=modes)
    inertia = res.masses_kg * p.pitch_radii_m**2
    sprockets = tuple(replace(s, inertia=float(inertia[k]), reduced_mass=None)
                      if s.name in added_inertia else s for k, s in enumerate(drive.sprockets))
    return drive.with_sprockets(sprockets), res


def normalised_amplitude_at(modal: Modes, working_hz: ArrayLike,
                            damping: float) -> float:
    """Largest normalised amplitude at the working frequencies.

    max over modes j, masses k and working f_w of μ_k^(j)·H(f_w/f_j), with μ the normalised
    amplitude of [MultimassChainDrives], eq. 2, and H(r) = 1/√((1−r²)² + (2ζr)²) the
    single-mode magnification [Rao2011, §3.4] — large when a mode with a large normalised
    amplitude lies near a working frequency.

    Parameters
    ----------
    modal : Modes
        The modes (of a ring or of a whole drive).
    working_hz : array_like
        Working frequencies [Hz].
    damping : float
        Damping ratio ζ [-].

    Returns
    -------
    float
        The largest μ·H [-].
    """
    el = ~modal.rigid_body
    fn = modal.frequencies_hz[el]
    mu = modal.normalized_amplitudes[:, el].max(axis=0)
    r = np.asarray(working_hz, dtype=float)[:, None] / fn[None, :]
    h = 1.0 / np.sqrt((1 - r**2) ** 2 + (2 * damping * r) ** 2)
    return float((mu[None, :] * h).max())


def detuning_metric_value(frequencies_hz: ArrayLike, working_hz: ArrayLike,
                          band: float = BAND) -> float:
    """Band shortfall of one design, for the objective registry.

    Parameters
    ----------
    frequencies_hz : array_like
        Natural frequencies [Hz].
    working_hz : array_like
        Working frequencies [Hz].
    band : float
        Relative half-width of the band [-].

    Returns
    -------
    float
        Σ squared shortfall [-] (0 when every mode is clear; :func:`band_shortfall`).
    """
    return float(band_shortfall(np.asarray(frequencies_hz, dtype=float)[None, :], working_hz,
                                band)[0])
