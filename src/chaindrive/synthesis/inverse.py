"""The inverse eigenvalue problem of the ring model: masses, or stiffnesses, for a spectrum.

[MultimassChainDrives, §3.2]: the inverse problem — masses or rigidities for a prescribed
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
log p with the exact eigenvalue derivatives of a symmetric pencil [FoxKapoor1968]:
∂λ_j/∂m_k = −λ_j φ_kj², ∂λ_j/∂c_l = (φ_{l+1,j} − φ_{l,j})², φ mass-normalised.
An inverse eigenproblem has in general several (finitely many) solutions, some close to
each other: the one on the continuation path from ``initial`` (the prescribed spectrum is
approached from the spectrum of the start values in steps) is returned, and the spectrum
of the answer is checked (else ConvergenceError). Without start values seeded restarts are
tried, and any one solution is returned.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from chaindrive.dynamics.ring import ring_stiffness_matrix
from chaindrive.errors import ConvergenceError, DesignError
from chaindrive.units import TWO_PI

__all__ = ["masses_for_spectrum", "ring_eigen", "solve_inverse", "stiffnesses_for_spectrum"]

#: relative error of the recovered eigenvalues accepted as a solution
SPECTRUM_TOL = 1e-10
#: steps of the continuation from the start values' spectrum to the prescribed one
CONTINUATION_STEPS = 8
#: random restarts (seeded) when no start values are given and the first start fails
RESTARTS = 20


def ring_eigen(masses: NDArray[np.float64], stiffness: NDArray[np.float64]
               ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Eigenvalues and mass-normalised vectors of the closed ring K φ = λ M φ.

    Parameters
    ----------
    masses : numpy.ndarray
        (n,) masses [kg].
    stiffness : numpy.ndarray
        (n,) branch stiffnesses [N/m] (K the ring Laplacian,
        :func:`chaindrive.dynamics.ring.ring_stiffness_matrix`).

    Returns
    -------
    tuple of numpy.ndarray
        λ = ω² [rad²/s²] (ascending) and the mass-normalised vectors φ [kg^-1/2].

    References
    ----------
    [MultimassChainDrives, eq. 2].
    """
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
                          "the masses or the stiffnesses, not both (only then is the inverse "
                          "problem determinate [MultimassChainDrives, §3.2])")
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


@dataclass(frozen=True, slots=True)
class _InverseProblem:
    """The equations λ_j(p) = (2π f_j)² in log p of one inverse request."""

    masses: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    kind: str
    unknown: NDArray[np.intp]
    modes: NDArray[np.intp]
    target: NDArray[np.float64]

    def full(self, logp: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(masses, stiffness) with the unknowns set to exp(logp)."""
        mm, cc = self.masses.copy(), self.stiffness.copy()
        (mm if self.kind == "masses" else cc)[self.unknown] = np.exp(logp)
        return mm, cc

    def residual(self, logp: NDArray[np.float64],
                 goal: NDArray[np.float64]) -> NDArray[np.float64]:
        """λ_j/goal_j − 1 of the prescribed modes."""
        lam, _ = ring_eigen(*self.full(logp))
        out: NDArray[np.float64] = lam[1:][self.modes] / goal - 1.0
        return out

    def jacobian(self, logp: NDArray[np.float64],
                 goal: NDArray[np.float64]) -> NDArray[np.float64]:
        """∂(λ_j/goal_j)/∂ log p from the eigenvalue derivatives [FoxKapoor1968]."""
        mm, cc = self.full(logp)
        lam, phi = ring_eigen(mm, cc)
        ph = phi[:, 1:][:, self.modes]                               # (n, F)
        u = self.unknown
        if self.kind == "masses":
            d = -lam[1:][self.modes][None, :] * ph[u] ** 2 * mm[u][:, None]
        else:
            diff = np.roll(ph, -1, axis=0) - ph                      # φ_{l+1} − φ_l
            d = diff[u] ** 2 * cc[u][:, None]
        out: NDArray[np.float64] = (d / goal[None, :]).T
        return out

    def follow(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], float]:
        """Continuation: move the target from the start's own spectrum to the prescribed one
        in CONTINUATION_STEPS geometric steps, following the solution branch of the start;
        the end point and its largest relative error."""
        lam0 = ring_eigen(*self.full(x))[0][1:][self.modes]
        for t in np.linspace(0.0, 1.0, CONTINUATION_STEPS + 1)[1:]:
            goal = lam0 ** (1 - t) * self.target ** t
            x = least_squares(self.residual, x, jac=self.jacobian, args=(goal,), method="lm",
                              xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=500).x
        return x, float(np.max(np.abs(self.residual(x, self.target))))


def solve_inverse(masses: ArrayLike, stiffness: ArrayLike, frequencies_hz: ArrayLike, *,
                  modes: Sequence[int] | None = None, initial: ArrayLike | None = None
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Masses and stiffnesses of a closed ring with the prescribed spectrum.

    Parameters
    ----------
    masses, stiffness : array_like
        (n,) masses [kg] and branch stiffnesses [N/m] with nan for the unknowns (masses or
        stiffnesses, not both).
    frequencies_hz : array_like
        The prescribed elastic natural frequencies [Hz], one per unknown.
    modes : sequence of int or None
        Which elastic modes (0 = lowest elastic) they are (default the lowest, in ascending
        order of the sorted frequencies).
    initial : array_like or None
        Start values of the unknowns [kg or N/m] (default: the mean of the known values of
        that kind, scaled to match the mean frequency).

    Returns
    -------
    tuple of numpy.ndarray
        The full (masses [kg], stiffness [N/m]).

    Raises
    ------
    DesignError
        For an indeterminate request (module docstring).
    ConvergenceError
        When no solution near the start values reproduces the spectrum.

    References
    ----------
    [MultimassChainDrives, §3.2]; [FoxKapoor1968].
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
    problem = _InverseProblem(m, c, kind, unknown, md, target)
    x, err = problem.follow(np.log(p0))
    rng = np.random.default_rng(0)  # restarts only without given start values, reproducible
    for _ in range(0 if initial is not None else RESTARTS):
        if err <= SPECTRUM_TOL:
            break
        x, err = problem.follow(np.log(p0) + rng.uniform(-0.7, 0.7, p0.size))
    if err > SPECTRUM_TOL:
        raise ConvergenceError(f"inverse problem: no {kind} near the start values reproduce the "
                               f"spectrum (largest relative error {err:.2e}); try other initial "
                               "values or frequencies the model can reach")
    return problem.full(x)


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


def _all_known(values: ArrayLike, field: str, solving_for: str) -> NDArray[np.float64]:
    """The fixed side of :func:`masses_for_spectrum` / :func:`stiffnesses_for_spectrum` as
    floats; DesignError on ``field`` when any of it is unknown (nan).

    Parameters
    ----------
    values : array_like
        (n,) the masses [kg] or branch stiffnesses [N/m] held fixed.
    field : str
        Their name, for the error.
    solving_for : str
        What the caller solves for ("masses" or "stiffnesses"), for the error.

    Returns
    -------
    numpy.ndarray
        (n,) the values [kg or N/m].
    """
    v = np.asarray(values, dtype=float)
    if np.any(np.isnan(v)):
        raise DesignError(field, f"must all be known when solving for {solving_for}")
    return v


def masses_for_spectrum(stiffness: ArrayLike, frequencies_hz: ArrayLike,
                        known_masses: ArrayLike, *, modes: Sequence[int] | None = None,
                        initial: ArrayLike | None = None) -> NDArray[np.float64]:
    """Masses giving the prescribed frequencies with the stiffnesses fixed.

    Parameters
    ----------
    stiffness : array_like
        (n,) branch stiffnesses [N/m], all known.
    frequencies_hz : array_like
        The prescribed elastic natural frequencies [Hz].
    known_masses : array_like
        (n,) masses [kg], nan for the unknowns.
    modes : sequence of int or None
        As in :func:`solve_inverse`.
    initial : array_like or None
        Start values of the unknown masses [kg].

    Returns
    -------
    numpy.ndarray
        (n,) masses [kg].
    """
    c = _all_known(stiffness, "stiffness", "masses")
    return solve_inverse(known_masses, c, frequencies_hz, modes=modes, initial=initial)[0]


def stiffnesses_for_spectrum(masses: ArrayLike, frequencies_hz: ArrayLike,
                             known_stiffness: ArrayLike, *, modes: Sequence[int] | None = None,
                             initial: ArrayLike | None = None) -> NDArray[np.float64]:
    """Branch stiffnesses giving the prescribed frequencies with the masses fixed.

    Parameters
    ----------
    masses : array_like
        (n,) masses [kg], all known.
    frequencies_hz : array_like
        The prescribed elastic natural frequencies [Hz].
    known_stiffness : array_like
        (n,) branch stiffnesses [N/m], nan for the unknowns.
    modes : sequence of int or None
        As in :func:`solve_inverse`.
    initial : array_like or None
        Start values of the unknown stiffnesses [N/m].

    Returns
    -------
    numpy.ndarray
        (n,) stiffnesses [N/m].
    """
    m = _all_known(masses, "masses", "stiffnesses")
    return solve_inverse(m, known_stiffness, frequencies_hz, modes=modes, initial=initial)[1]
