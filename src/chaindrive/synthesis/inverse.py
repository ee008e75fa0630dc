"""The inverse eigenvalue problem of the ring model: masses, or stiffnesses, for a spectrum.

Seed 000 §3.2 (seed-notes §1): the inverse problem — masses or rigidities for a prescribed
spectrum of natural frequencies — "is only determinate when just masses, or just as many
stiffnesses as degrees of freedom, are varied". A free ring of n masses has n − 1 elastic
natural frequencies (one is the rigid-body zero), so:

* masses: as many unknown masses as prescribed frequencies (at most n − 1: at least one
  mass, e.g. the motor's, must be known);
* stiffnesses: as many unknown branch stiffnesses as prescribed frequencies (at most the
  n − 1 degrees of freedom: at least one of the n branches must be known);
* never masses and stiffnesses at once.

Anything else is refused with a :class:`~chaindrive.errors.DesignError`. The equations
λ_j(p) = (2π f_j)² are solved by Gauss–Newton (:func:`scipy.optimize.least_squares`) in
log p with the exact eigenvalue derivatives of a symmetric pencil (Fox & Kapoor, AIAA J. 6,
1968): ∂λ_j/∂m_k = −λ_j φ_kj², ∂λ_j/∂c_l = (φ_{l+1,j} − φ_{l,j})², φ mass-normalised.
An inverse eigenproblem has in general several (finitely many) solutions, some close to
each other: the one on the continuation path from ``initial`` (the prescribed spectrum is
approached from the spectrum of the start values in steps) is returned, and the spectrum
of the answer is checked (else ConvergenceError). Without start values seeded restarts are
tried, and any one solution is returned.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from chaindrive.errors import ConvergenceError, DesignError

__all__ = ["masses_for_spectrum", "ring_eigen", "solve_inverse", "stiffnesses_for_spectrum"]

TWO_PI = 2.0 * math.pi
#: relative error of the recovered eigenvalues accepted as a solution
SPECTRUM_TOL = 1e-10
#: steps of the continuation from the start values' spectrum to the prescribed one
CONTINUATION_STEPS = 8
#: random restarts (seeded) when no start values are given and the first start fails
RESTARTS = 20


def ring_eigen(masses: NDArray[np.float64], stiffness: NDArray[np.float64]
               ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Eigenvalues λ = ω² [rad²/s²] (ascending) and mass-normalised vectors of the closed
    ring K φ = λ M φ (K the ring Laplacian, :func:`chaindrive.dynamics.ring_stiffness_matrix`)."""
    from chaindrive.dynamics.ring import ring_stiffness_matrix

    lam, phi = scipy.linalg.eigh(ring_stiffness_matrix(stiffness, True), np.diag(masses))
    return lam, phi


def _parse(values: ArrayLike, path: str) -> NDArray[np.float64]:
    v = np.asarray(values, dtype=float)
    if v.ndim != 1 or v.size < 2:
        raise DesignError(path, f"need a list of at least 2 values, got shape {v.shape}")
    known = v[~np.isnan(v)]
    if np.any(~np.isfinite(known)) or np.any(known <= 0):
        raise DesignError(path, "known values must be positive and finite (nan marks unknowns)")
    return v


def _check_request(m: NDArray, c: NDArray, f: NDArray, modes: NDArray) -> str:
    n = m.size
    if c.size != n:
        raise DesignError("stiffness", f"need one stiffness per mass ({n}), got {c.size}")
    um, uc = int(np.isnan(m).sum()), int(np.isnan(c).sum())
    if um and uc:
        raise DesignError("inverse", f"{um} masses and {uc} stiffnesses unknown: vary either "
                          "the masses or the stiffnesses, not both (seed 000: only then is the "
                          "inverse problem determinate)")
    unknown, what = (um, "masses") if um else (uc, "stiffnesses")
    if unknown == 0:
        raise DesignError("inverse", "nothing to find: mark the unknown masses or stiffnesses "
                          "with nan")
    if f.size != unknown:
        raise DesignError("frequencies_hz", f"indeterminate request: {unknown} unknown {what} but "
                          f"{f.size} prescribed frequencies; give exactly as many frequencies as "
                          f"unknowns (a free ring of {n} masses has {n - 1} elastic frequencies, "
                          f"so at most {n - 1} unknowns: fix at least one)")
    if unknown > n - 1:
        raise DesignError("inverse", f"indeterminate request: {unknown} unknown {what} exceed the "
                          f"{n - 1} degrees of freedom of a free ring of {n} masses; fix at "
                          f"least {unknown - n + 1} of them")
    if np.any(f <= 0) or not np.all(np.isfinite(f)):
        raise DesignError("frequencies_hz", "must be positive and finite [Hz]")
    if modes.size != f.size or len(set(modes.tolist())) != modes.size or np.any(modes < 0) \
            or np.any(modes > n - 2):
        raise DesignError("modes", f"need {f.size} distinct elastic mode indices from 0 to {n - 2}")
    return "masses" if um else "stiffnesses"


def solve_inverse(masses: ArrayLike, stiffness: ArrayLike, frequencies_hz: ArrayLike, *,
                  modes: Sequence[int] | None = None, initial: ArrayLike | None = None
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Masses [kg] and stiffnesses [N/m] of a closed ring with the prescribed spectrum.

    masses, stiffness : (n,) with nan for the unknowns (masses or stiffnesses, not both);
    frequencies_hz : the prescribed elastic natural frequencies [Hz], one per unknown;
    modes : which elastic modes (0 = lowest elastic) they are (default the lowest, in
    ascending order of the sorted frequencies); initial : start values of the unknowns
    (default: the mean of the known values of that kind, or scaled to match the mean
    frequency). Returns the full (masses, stiffness).
    """
    m = _parse(masses, "masses")
    c = _parse(stiffness, "stiffness")
    f = np.sort(np.atleast_1d(np.asarray(frequencies_hz, dtype=float)))
    md = np.arange(f.size) if modes is None else np.asarray(modes, dtype=int)
    kind = _check_request(m, c, f, md)
    target = (TWO_PI * f) ** 2
    unknown = np.flatnonzero(np.isnan(m if kind == "masses" else c))
    vec = m if kind == "masses" else c
    p0 = _initial(vec, unknown, initial, m, c, target, kind)

    def full(logp: NDArray) -> tuple[NDArray, NDArray]:
        mm, cc = m.copy(), c.copy()
        (mm if kind == "masses" else cc)[unknown] = np.exp(logp)
        return mm, cc

    def residual(logp: NDArray, goal: NDArray = target) -> NDArray:
        lam, _ = ring_eigen(*full(logp))
        return lam[1:][md] / goal - 1.0

    def jacobian(logp: NDArray, goal: NDArray = target) -> NDArray:
        mm, cc = full(logp)
        lam, phi = ring_eigen(mm, cc)
        ph = phi[:, 1:][:, md]                                       # (n, F)
        if kind == "masses":
            d = -lam[1:][md][None, :] * ph[unknown] ** 2 * mm[unknown][:, None]
        else:
            diff = np.roll(ph, -1, axis=0) - ph                      # φ_{l+1} − φ_l
            d = diff[unknown] ** 2 * cc[unknown][:, None]
        return (d / goal[None, :]).T

    def follow(x: NDArray) -> tuple[NDArray, float]:
        # continuation: move the target from the start's own spectrum to the prescribed one
        # in CONTINUATION_STEPS geometric steps, following the solution branch of the start
        lam0 = ring_eigen(*full(x))[0][1:][md]
        for t in np.linspace(0.0, 1.0, CONTINUATION_STEPS + 1)[1:]:
            goal = lam0 ** (1 - t) * target ** t
            x = least_squares(residual, x, jac=jacobian, args=(goal,), method="lm",
                              xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=500).x
        return x, float(np.max(np.abs(residual(x))))

    x, err = follow(np.log(p0))
    rng = np.random.default_rng(0)  # restarts only without given start values, reproducible
    for _ in range(0 if initial is not None else RESTARTS):
        if err <= SPECTRUM_TOL:
            break
        x, err = follow(np.log(p0) + rng.uniform(-0.7, 0.7, p0.size))
    if err > SPECTRUM_TOL:
        raise ConvergenceError(f"inverse problem: no {kind} near the start values reproduce the "
                               f"spectrum (largest relative error {err:.2e}); try other initial "
                               "values or frequencies the model can reach")
    return full(x)


def _initial(vec: NDArray, unknown: NDArray, initial: ArrayLike | None, m: NDArray,
             c: NDArray, target: NDArray, kind: str) -> NDArray:
    if initial is not None:
        p0 = np.asarray(initial, dtype=float)
        if p0.shape != unknown.shape or np.any(p0 <= 0) or not np.all(np.isfinite(p0)):
            raise DesignError("initial", f"need {unknown.size} positive start values")
        return p0
    known = vec[~np.isnan(vec)]
    p0 = np.full(unknown.size, float(np.mean(known)))
    mm, cc = m.copy(), c.copy()
    (mm if kind == "masses" else cc)[unknown] = p0
    lam, _ = ring_eigen(mm, cc)
    scale = float(np.mean(target) / np.mean(lam[1:][: target.size]))
    return p0 / scale if kind == "masses" else p0 * scale


def masses_for_spectrum(stiffness: ArrayLike, frequencies_hz: ArrayLike,
                        known_masses: ArrayLike, *, modes: Sequence[int] | None = None,
                        initial: ArrayLike | None = None) -> NDArray[np.float64]:
    """Masses [kg] (nan in ``known_masses`` = unknown) giving the prescribed frequencies
    [Hz] with the stiffnesses [N/m] fixed; see :func:`solve_inverse`."""
    c = np.asarray(stiffness, dtype=float)
    if np.any(np.isnan(c)):
        raise DesignError("stiffness", "must all be known when solving for masses")
    return solve_inverse(known_masses, c, frequencies_hz, modes=modes, initial=initial)[0]


def stiffnesses_for_spectrum(masses: ArrayLike, frequencies_hz: ArrayLike,
                             known_stiffness: ArrayLike, *, modes: Sequence[int] | None = None,
                             initial: ArrayLike | None = None) -> NDArray[np.float64]:
    """Branch stiffnesses [N/m] (nan in ``known_stiffness`` = unknown) giving the prescribed
    frequencies [Hz] with the masses [kg] fixed; see :func:`solve_inverse`."""
    m = np.asarray(masses, dtype=float)
    if np.any(np.isnan(m)):
        raise DesignError("masses", "must all be known when solving for stiffnesses")
    return solve_inverse(m, known_stiffness, frequencies_hz, modes=modes, initial=initial)[1]
