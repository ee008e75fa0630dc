"""Inverse eigenvalue problem of the ring model (seed 000 §3.2, seed-notes §1: determinate
only when just masses, or as many stiffnesses as degrees of freedom, are varied).

Source of the check: a ring with known masses and stiffnesses → its spectrum (forward
problem, :func:`chaindrive.dynamics.ring_frequencies_batch`) → the inverse problem must give
the known values back to 1e-6 relative (issue 8 acceptance)."""

from __future__ import annotations

import numpy as np
import pytest

from chaindrive.dynamics.ring import ring_frequencies_batch
from chaindrive.errors import DesignError
from chaindrive.synthesis.inverse import masses_for_spectrum, solve_inverse, stiffnesses_for_spectrum

RNG = np.random.default_rng(2024)
N = 8
MASSES = RNG.uniform(0.5, 5.0, N)          # [kg]
STIFF = RNG.uniform(1e5, 1e6, N)          # [N/m]
SPECTRUM = ring_frequencies_batch(MASSES[None], STIFF[None])[0][1:]  # elastic [Hz]


def test_recovers_known_masses_from_their_spectrum() -> None:
    known = MASSES.copy()
    known[1:] = np.nan                      # the driver's mass is known, 7 unknown
    start = MASSES[1:] * RNG.uniform(0.99, 1.01, N - 1)
    found = masses_for_spectrum(STIFF, SPECTRUM, known, initial=start)
    np.testing.assert_allclose(found, MASSES, rtol=1e-6)


def test_recovers_known_masses_without_start_values() -> None:
    known = MASSES.copy()
    known[1:] = np.nan
    found = masses_for_spectrum(STIFF, SPECTRUM, known)
    # the inverse problem has several solutions: any answer must reproduce the spectrum
    np.testing.assert_allclose(ring_frequencies_batch(found[None], STIFF[None])[0][1:],
                               SPECTRUM, rtol=1e-9)


def test_recovers_known_stiffnesses_from_their_spectrum() -> None:
    known = STIFF.copy()
    known[:-1] = np.nan                     # as many unknowns as degrees of freedom (n − 1)
    start = STIFF[:-1] * RNG.uniform(0.99, 1.01, N - 1)
    found = stiffnesses_for_spectrum(MASSES, SPECTRUM, known, initial=start)
    np.testing.assert_allclose(found, STIFF, rtol=1e-6)


def test_fewer_unknowns_with_chosen_modes() -> None:
    known = MASSES.copy()
    known[[2, 5]] = np.nan
    found = masses_for_spectrum(STIFF, SPECTRUM[[0, 3]], known, modes=[0, 3],
                                initial=MASSES[[2, 5]] * 1.03)
    np.testing.assert_allclose(found, MASSES, rtol=1e-6)


@pytest.mark.parametrize(("masses", "stiff", "freqs", "message"), [
    (np.full(N, np.nan), STIFF, SPECTRUM, "indeterminate request: 8 unknown masses but 7"),
    (np.where(np.arange(N) < 3, np.nan, MASSES), STIFF, SPECTRUM, "3 unknown masses but 7"),
    (MASSES, np.full(N, np.nan), SPECTRUM, "indeterminate request: 8 unknown stiffnesses"),
    (np.where(np.arange(N) == 0, np.nan, MASSES), np.where(np.arange(N) == 1, np.nan, STIFF),
     SPECTRUM[:2], "vary either the masses or the stiffnesses, not both"),
    (MASSES, STIFF, SPECTRUM, "nothing to find"),
])
def test_refuses_an_indeterminate_request(masses, stiff, freqs, message) -> None:
    with pytest.raises(DesignError, match=message):
        solve_inverse(masses, stiff, freqs)
