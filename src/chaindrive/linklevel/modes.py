r"""Natural frequencies of the link-level model from its linearisation about the static state.

About the static equilibrium at T₀ (:mod:`chaindrive.linklevel.equilibrium`) the undamped
model's small motions obey M ü + K u = 0, u the roller displacements (2N) and the sprocket
turns as arc lengths R_s θ_s [m]; M = diag(m, …, J_s/R_s², …), K = −∂f/∂u the tangent
stiffness of the static balance (links with their geometric stiffness T/ℓ, contacts,
gravity's none), by grouped finite differences, symmetrised. The generalised eigenproblem
K φ = ω² M φ is solved densely ([Golub2013, §8.7], the symmetric-definite problem), every
sprocket free: the chain turning round its loop is the (near-)rigid mode below 1 Hz, left out.

Most low modes are transverse string modes of the spans (a few to tens of Hz). The mode the
whole-drive (ring) model's first elastic frequency describes is the first in which the
motion is along the chain: the lowest mode with more than half its kinetic energy in the
rollers' motion along their links and the sprockets' turning (``longitudinal_fraction``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel.equilibrium import Balance, installed_geometry, kernel_tables
from chaindrive.linklevel.model import build_model
from chaindrive.linklevel.simulate import COURANT, equilibrium_state
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.model import LinkLevelModel
    from chaindrive.model import Drive

__all__ = ["LONGITUDINAL", "LinearModes", "linear_modes"]

#: A mode counts as longitudinal when more than this fraction of its kinetic energy is in
#: motion along the chain and sprocket turning [-].
LONGITUDINAL = 0.5
_RIGID_HZ = 1.0


@dataclass(frozen=True, slots=True, eq=False)
class LinearModes:
    """Natural frequencies of the linearised link-level model (module docstring).

    Parameters
    ----------
    frequencies_hz : ndarray
        (k,) elastic natural frequencies, ascending [Hz].
    longitudinal_fraction : ndarray
        (k,) each mode's kinetic energy fraction along the chain and in the sprockets [-].
    first_longitudinal_hz : float or None
        The lowest mode with ``longitudinal_fraction`` > :data:`LONGITUDINAL` [Hz].
    reference_frequency_hz : float
        The whole-drive model's first chain mode [Hz] (the links' damping reference), for
        comparison.
    """

    frequencies_hz: NDArray[np.float64]
    longitudinal_fraction: NDArray[np.float64]
    first_longitudinal_hz: float | None
    reference_frequency_hz: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI, units in the keys)."""
        return {"frequencies_hz": self.frequencies_hz.tolist(),
                "longitudinal_fraction": self.longitudinal_fraction.tolist(),
                "first_longitudinal_hz": self.first_longitudinal_hz,
                "reference_frequency_hz": self.reference_frequency_hz}


def linear_modes(drive: Drive, *, geometry: GeometryResult | None = None,
                 model: LinkLevelModel | None = None, count: int = 100000) -> LinearModes:
    """The lowest ``count`` elastic modes of the link-level model about its static state.

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult or None
        Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).
    model : LinkLevelModel or None
        The parameters (None: :func:`chaindrive.linklevel.model.build_model`).
    count : int
        Number of modes kept [-].

    Returns
    -------
    LinearModes
        Frequencies, longitudinal fractions, the first longitudinal mode.

    References
    ----------
    [Golub2013, §8.7] (symmetric-definite eigenproblem).
    """
    geometry, take_up = installed_geometry(drive, geometry or contour_geometry(drive))
    if model is None:
        model = build_model(drive, geometry)
    dt = COURANT * 2.0 / (2.0 * math.pi * model.highest_frequency_hz)
    _, eq = equilibrium_state(drive, geometry, model, dt, take_up)
    n = model.centres.shape[0]
    x, th = eq.positions, eq.angles[:n].copy()
    N = x.shape[0]
    bal = Balance(model, kernel_tables(model), np.arange(n, dtype=np.int64), N, 0)
    r0 = bal(x, th, eq.rest_length)
    K = -bal.jacobian(x, th, eq.rest_length, r0)[:-1, :-1]
    K = 0.5 * (K + K.T)
    mass = np.concatenate([np.full(2 * N, model.roller_mass),
                           model.inertias / model.pitch_radii**2])
    scale = 1.0 / np.sqrt(mass)
    lam, vec = eigh(K * scale[:, None] * scale[None, :])
    freq = np.sqrt(np.clip(lam, 0.0, None)) / TWO_PI
    keep = np.flatnonzero(freq > _RIGID_HZ)[:count]
    modes = vec[:, keep] * scale[:, None]  # displacements u = M^{-1/2} φ
    d = np.roll(x, -1, axis=0) - x
    t = d / np.hypot(d[:, 0], d[:, 1])[:, None]  # each roller's leading link direction
    ke_rollers_along = model.roller_mass * np.einsum(
        "rk,rkm->rm", t, modes[:2 * N].reshape(N, 2, -1)) ** 2
    ke_total = np.einsum("i,im->m", mass, modes**2)
    ke_sprockets = np.einsum("i,im->m", mass[2 * N:], modes[2 * N:] ** 2)
    fraction = (ke_rollers_along.sum(axis=0) + ke_sprockets) / ke_total
    first = next((float(f) for f, a in zip(freq[keep], fraction, strict=True)
                  if a > LONGITUDINAL), None)
    return LinearModes(freq[keep], fraction, first, model.reference_frequency_hz)
