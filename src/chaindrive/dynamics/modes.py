"""Modes of the whole-drive model: undamped and damped, and what a designer reads of them at
the sprockets (docs/dynamics.md §3).

The undamped modes are those of :meth:`chaindrive.dynamics.torsional.TorsionalModel.modal`
(exact rigid-body modes, mass-normalised shapes). With the model's damping matrix C — not
proportional to K once trains carry their own dampers — the damped modes are the eigenvalues
λ of the first-order form of the elastic part [Rao2011, §6.14], [TisseurMeerbergen2001]::

    ÿ + Φᵀ C Φ ẏ + Ω² y = Φᵀ f,   A = [[0, I], [−Ω², −Φᵀ C Φ]],   q = Φ y,

Φ the elastic mass-normalised modes (the rigid-body motions are strain-free and undamped,
B U = 0 and C U = 0, so no span excitation moves them and they are left out: with them A
would be defective). Damped frequency |Im λ|/2π and damping ratio −Re λ/|λ| of each mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.dynamics.drive_model import DriveModel
    from chaindrive.dynamics.torsional import TorsionalModes

__all__ = ["DriveModes", "StateModes", "drive_modes", "inertia_modes_batch", "state_modes"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, slots=True, eq=False)
class StateModes:
    """Complex modes of the elastic part of a damped model (module docstring).

    Parameters
    ----------
    eigenvalues : ndarray
        (2E,) complex eigenvalues λ of the state matrix A [rad/s].
    right, left : ndarray
        (2E, 2E) right eigenvectors V and left ones V⁻¹ of A in the modal coordinates
        (y, ẏ) [-].
    basis : ndarray
        (N, E) elastic mass-normalised modes Φ with q = Φ y [coordinate units · kg^-1/2].
    """

    eigenvalues: ComplexArray
    right: ComplexArray
    left: ComplexArray
    basis: FloatArray

    def damped(self, natural_rad_s: FloatArray) -> tuple[FloatArray, FloatArray]:
        """(damped frequencies [Hz], damping ratios [-]) of the E elastic modes in the order of
        their undamped frequencies: each mode takes the oscillating eigenvalue (Im λ > 0) of
        nearest |λ|; an overdamped mode (none left) gets a damped frequency 0 and ζ = 1.

        Parameters
        ----------
        natural_rad_s : ndarray
            (E,) undamped natural frequencies [rad/s].

        Returns
        -------
        damped_hz : ndarray
            (E,) damped natural frequencies Im λ / 2π [Hz].
        ratios : ndarray
            (E,) damping ratios ζ = −Re λ / |λ| [-].

        References
        ----------
        [Rao2011, §6.14].
        """
        lam = self.eigenvalues
        pool = [complex(x) for x in lam if x.imag > 1e-12 * max(1.0, abs(x))]
        fd = np.zeros(natural_rad_s.size)
        zeta = np.ones(natural_rad_s.size)
        for j in np.argsort(natural_rad_s):
            if not pool:
                break
            k = int(np.argmin([abs(abs(x) - natural_rad_s[j]) for x in pool]))
            x = pool.pop(k)
            fd[j] = x.imag / TWO_PI
            zeta[j] = -x.real / abs(x)
        return fd, zeta


def state_modes(basis: FloatArray, omega: FloatArray, damping: FloatArray) -> StateModes:
    """Complex modes of ÿ + Φᵀ C Φ ẏ + Ω² y = 0 (module docstring).

    Parameters
    ----------
    basis : ndarray
        (N, E) elastic mass-normalised modes Φ [coordinate units · kg^-1/2].
    omega : ndarray
        (E,) their undamped natural frequencies Ω [rad/s].
    damping : ndarray
        (N, N) damping matrix C of the coordinates [N·s/m or N·m·s/rad, as the coordinates].

    Returns
    -------
    StateModes
        The eigenvalues and eigenvectors of the first-order form.

    References
    ----------
    [Rao2011, §6.14]; [TisseurMeerbergen2001] (the quadratic eigenvalue problem).
    """
    e = omega.size
    A = np.zeros((2 * e, 2 * e))
    A[:e, e:] = np.eye(e)
    A[e:, :e] = -np.diag(omega * omega)
    A[e:, e:] = -(basis.T @ damping @ basis)
    lam, V = np.linalg.eig(A)
    return StateModes(lam.astype(complex), V.astype(complex), np.linalg.inv(V).astype(complex),
                      basis)


@dataclass(frozen=True, slots=True, eq=False)
class DriveModes:
    """Modes of a whole-drive model as a designer reads them (at the sprockets).

    Parameters
    ----------
    frequencies_hz : ndarray
        (M,) undamped natural frequencies [Hz], ascending, rigid-body zeros first.
    rigid_body : ndarray of bool
        (M,) True for a rigid-body mode.
    damped_frequencies_hz : ndarray
        (M,) damped natural frequencies [Hz].
    modal_damping_ratios : ndarray
        (M,) damping ratio of each mode [-] (0 for rigid-body modes).
    shapes : ndarray
        (n, M) chain displacement R̄_i φ_i at sprocket i in each mode, mass-normalised
        [m·kg^-1/2].
    governing : tuple of str
        (M,) the element holding most of each mode's strain energy.
    chain_share : ndarray
        (M,) the share of the chain (spans and wraps) in each mode's strain energy [-].
    masses_kg : ndarray
        (n,) the sprockets' own reduced masses J/R² [kg] ([MultimassChainDrives, §3.1]).
    stiffness_n_per_m : ndarray
        (n,) span stiffness of one contour [N/m].
    damping_ratio : float
        Damping ratio ζ of the reference mode [-].
    torsional : TorsionalModes
        The full modes of the torsional model (every node).
    """

    frequencies_hz: FloatArray
    rigid_body: NDArray[np.bool_]
    damped_frequencies_hz: FloatArray
    modal_damping_ratios: FloatArray
    shapes: FloatArray
    governing: tuple[str, ...]
    chain_share: FloatArray
    masses_kg: FloatArray
    stiffness_n_per_m: FloatArray
    damping_ratio: float
    torsional: TorsionalModes

    @property
    def angular_frequencies_rad_s(self) -> FloatArray:
        """ω_j = 2π f_j [rad/s]."""
        return self.frequencies_hz * TWO_PI

    @property
    def elastic_frequencies_hz(self) -> FloatArray:
        """The elastic natural frequencies [Hz], ascending."""
        return self.frequencies_hz[~self.rigid_body]

    @property
    def first_elastic_frequency_hz(self) -> float:
        """The lowest elastic natural frequency [Hz] (nan if none)."""
        f = self.elastic_frequencies_hz
        return float(f[0]) if f.size else math.nan

    @property
    def normalized_amplitudes(self) -> FloatArray:
        """μ_k^(j) = |X_k^(j)| / Σ_i |X_i^(j)| over the sprockets, columns per mode
        [MultimassChainDrives, eq. 2] (a mode that leaves every sprocket still: zeros)."""
        a = np.abs(self.shapes)
        total = a.sum(axis=0)
        return np.asarray(np.divide(a, total, out=np.zeros_like(a), where=total > 0),
                          dtype=np.float64)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; ``mode_shapes[j]`` lists the sprockets' amplitudes in mode j."""
        return {
            "natural_frequencies_hz": self.frequencies_hz.tolist(),
            "natural_frequencies_rad_s": self.angular_frequencies_rad_s.tolist(),
            "damped_frequencies_hz": self.damped_frequencies_hz.tolist(),
            "modal_damping_ratios": self.modal_damping_ratios.tolist(),
            "rigid_body_modes": self.rigid_body.tolist(),
            "mode_shapes": self.shapes.T.tolist(),
            "normalized_amplitudes": self.normalized_amplitudes.T.tolist(),
            "governing_elements": list(self.governing),
            "chain_strain_energy_share": self.chain_share.tolist(),
            "reduced_masses_kg": self.masses_kg.tolist(),
            "span_stiffness_n_per_m": self.stiffness_n_per_m.tolist(),
            "damping_ratio": self.damping_ratio,
        }


def elastic_basis(model: DriveModel, modes: TorsionalModes) -> tuple[FloatArray, FloatArray]:
    """(Φ (N, E), Ω (E,) [rad/s]): the elastic mass-normalised modes in the coordinates q of
    the model's :class:`~chaindrive.dynamics.drive_model.LinearModel`."""
    massed = model.system.mass > 0.0
    Q = modes.modal_coordinates[massed]
    elastic = ~modes.rigid_body
    return Q[:, elastic], modes.angular_frequencies_rad_s[elastic]


def drive_modes(model: DriveModel) -> tuple[DriveModes, StateModes]:
    """The modes of a whole-drive model (module docstring) and its complex elastic modes.

    Parameters
    ----------
    model : DriveModel
        The model (:func:`chaindrive.dynamics.drive_model.drive_model`).

    Returns
    -------
    tuple of DriveModes and StateModes
    """
    modes = model.modal()
    basis, omega = elastic_basis(model, modes)
    state = state_modes(basis, omega, model.linear.damping())
    fd_el, z_el = state.damped(omega)
    m = modes.frequencies_hz.size
    fd = np.zeros(m)
    zeta = np.zeros(m)
    fd[~modes.rigid_body], zeta[~modes.rigid_body] = fd_el, z_el
    sys = model.system
    rows = np.array([sys.node_names.index(x) for x in model.sprocket_names])
    phi = modes.shape_matrix[rows] * (model.mean_radii * np.sign(model.sprocket_gain))[:, None]
    kinds = np.array(sys.element_kinds)
    shares = modes.strain_energy_shares
    chain = shares[(kinds == "span") | (kinds == "wrap")].sum(axis=0)
    governing = tuple(modes.governing_element(j) for j in range(m))
    ref = model.reference_frequency_hz
    el = np.flatnonzero(~modes.rigid_body)
    j_ref = int(el[np.argmin(np.abs(modes.frequencies_hz[el] - ref))]) if el.size else 0
    return DriveModes(modes.frequencies_hz, modes.rigid_body, fd, zeta, phi, governing, chain,
                      model.ring.masses_kg, model.linear.span_stiffness / model.contours,
                      float(zeta[j_ref]), modes), state


def inertia_modes_batch(model: DriveModel, added_inertia: NDArray[np.float64]
                        ) -> tuple[FloatArray, FloatArray]:
    """Elastic frequencies and the sprockets' largest normalised amplitude per mode of B
    variants of a whole-drive model whose sprockets carry added inertias (flywheels).

    Parameters
    ----------
    model : DriveModel
        The model.
    added_inertia : ndarray
        (B, n) inertia added on every sprocket's shaft [kg·m²].

    Returns
    -------
    tuple of ndarray
        f (B, E) elastic natural frequencies [Hz], ascending; μ (B, E) the largest
        μ_k = |X_k|/Σ_i|X_i| over the sprockets of every mode [MultimassChainDrives, eq. 2].
        Stacked Cholesky factors and symmetric eigenproblems (one NumPy call each); the
        rigid-body modes (their count from the model's graph) are the lowest eigenvalues.
    """
    lin = model.linear
    dJ = np.atleast_2d(np.asarray(added_inertia, dtype=float))
    k, g = model.sprocket_coordinate, model.sprocket_gain
    M = np.repeat(lin.mass[None], dJ.shape[0], axis=0)
    rows = np.arange(dJ.shape[0])[:, None]
    np.add.at(M, (rows, k[None, :], k[None, :]), dJ * g * g)
    L = np.linalg.cholesky(M)
    Y = np.linalg.solve(L, np.broadcast_to(lin.stiffness(), M.shape))
    A = np.linalg.solve(L, np.swapaxes(Y, 1, 2))
    lam, V = np.linalg.eigh(0.5 * (A + np.swapaxes(A, 1, 2)))
    r = int(model.system.rigid_motions.shape[1])
    X = np.linalg.solve(np.swapaxes(L, 1, 2), V)[:, k, r:] * (
        model.mean_radii * g)[None, :, None]
    a = np.abs(X)
    mu = (a / np.maximum(a.sum(axis=1, keepdims=True), 1e-300)).max(axis=1)
    return np.sqrt(np.maximum(lam[:, r:], 0.0)) / TWO_PI, mu
