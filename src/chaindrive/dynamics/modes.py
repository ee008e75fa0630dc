"""Modes of the whole-drive model: undamped and damped, and what a designer reads of them at
the sprockets (docs/dynamics.md §3).

The undamped modes are those of :meth:`chaindrive.dynamics.torsional.model.TorsionalModel.modal`
(exact rigid-body modes, mass-normalised shapes). With the model's damping matrix C — not
proportional to K once trains carry their own dampers — the damped modes are the eigenvalues
λ of the first-order form of the elastic part [Rao2011, §6.14], [TisseurMeerbergen2001]::

    ÿ + Φᵀ C Φ ẏ + Ω² y = Φᵀ f,   A = [[0, I], [−Ω², −Φᵀ C Φ]],   q = Φ y,

Φ the elastic mass-normalised modes (the rigid-body motions are strain-free and undamped,
B U = 0 and C U = 0, so no span excitation moves them and they are left out: with them A
would be defective). Damped frequency |Im λ|/2π and damping ratio −Re λ/|λ| of each mode.

The modal stage of an analysis (:func:`model_dynamics` → :class:`DriveDynamics`, what
``Analysis.dynamics`` returns) adds the spans' transverse frequencies, the working
frequencies, the resonance table and the Campbell data (docs/dynamics.md §3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._numeric import freeze_arrays
from chaindrive.dynamics.resonance import (
    CampbellData,
    Resonance,
    WorkingFrequency,
    campbell_data,
    resonance_table,
    working_frequencies,
)
from chaindrive.dynamics.transverse import span_transverse_frequencies
from chaindrive.kinematics import mean_chain_speed, tooth_frequency
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.dynamics.model.build import DriveModel
    from chaindrive.dynamics.torsional.model import TorsionalModes
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["DriveDynamics", "Modes", "StateModes", "drive_modes", "inertia_modes_batch",
           "model_dynamics", "state_modes"]

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

    def __post_init__(self) -> None:
        freeze_arrays(self)  # read-only arrays (writeable inputs copied)

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
class Modes:
    """The modes of a chain drive at its sprockets: the one modal result the ring of reduced
    masses (:meth:`chaindrive.dynamics.ring.RingModel.modal`) and the whole-drive model
    (:func:`drive_modes`) return, and what the resonance table, the Campbell data and the
    detuning read. Frozen, its arrays read-only.

    Parameters
    ----------
    frequencies_hz : ndarray
        (M,) undamped natural frequencies [Hz], ascending, rigid-body zeros first.
    rigid_body : ndarray of bool
        (M,) True for a rigid-body mode.
    shapes : ndarray
        (n, M) mode shapes at the n sprockets (ring masses), mass-normalised: the chain
        displacement R̄_i φ_i [m·kg^-1/2] (the ring: X with Xᵀ M X = I [kg^-1/2]).
    damped_frequencies_hz : ndarray
        (M,) damped natural frequencies [Hz] (the ring: f·sqrt(1 − ζ²)).
    modal_damping_ratios : ndarray
        (M,) damping ratio of each mode [-] (0 for rigid-body modes).
    masses_kg : ndarray
        (n,) the sprockets' reduced masses J/R² [kg] ([MultimassChainDrives, §3.1]).
    stiffness_n_per_m : ndarray
        (n,) span (branch) stiffness of one contour [N/m].
    damping_ratio : float
        Damping ratio ζ of the reference mode [-] (the ring: its one ζ,
        [MultimassChainDrives]: D = 0.06).
    governing : tuple of str
        (M,) the element holding most of each mode's strain energy (empty for the ring).
    chain_share : ndarray | None
        (M,) the share of the chain (spans and wraps) in each mode's strain energy [-]
        (None for the ring, whose every spring is the chain).
    torsional : TorsionalModes | None
        The full modes of the whole-drive model at every node (None for the ring).
    scaled_diagonal : ndarray | None
        (n,) K_kk / m_k [rad²/s²] of the ring, the squares of the partial angular
        frequencies (the diagonal terms of [MultimassChainDrives, eq. 2]; None for the whole
        drive).
    """

    frequencies_hz: FloatArray
    rigid_body: NDArray[np.bool_]
    shapes: FloatArray
    damped_frequencies_hz: FloatArray
    modal_damping_ratios: FloatArray
    masses_kg: FloatArray
    stiffness_n_per_m: FloatArray
    damping_ratio: float
    governing: tuple[str, ...] = ()
    chain_share: FloatArray | None = None
    torsional: TorsionalModes | None = None
    scaled_diagonal: FloatArray | None = None

    def __post_init__(self) -> None:
        freeze_arrays(self)  # read-only arrays (writeable inputs copied)

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

    @property
    def partial_frequencies_hz(self) -> FloatArray:
        """sqrt(K_kk / m_k) / 2π [Hz] of the ring (the diagonal of M^{-1/2} K M^{-1/2});
        empty for the whole drive."""
        if self.scaled_diagonal is None:
            return np.zeros(0)
        return np.sqrt(self.scaled_diagonal) / TWO_PI

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; ``mode_shapes[j]`` lists the sprockets' amplitudes in mode j
        (``governing_elements``, ``chain_strain_energy_share`` for the whole drive,
        ``partial_frequencies_hz`` for the ring)."""
        out: dict[str, Any] = {
            "natural_frequencies_hz": self.frequencies_hz.tolist(),
            "natural_frequencies_rad_s": self.angular_frequencies_rad_s.tolist(),
            "damped_frequencies_hz": self.damped_frequencies_hz.tolist(),
            "modal_damping_ratios": self.modal_damping_ratios.tolist(),
            "rigid_body_modes": self.rigid_body.tolist(),
            "mode_shapes": self.shapes.T.tolist(),
            "normalized_amplitudes": self.normalized_amplitudes.T.tolist(),
        }
        if self.torsional is not None:
            out["governing_elements"] = list(self.governing)
        if self.chain_share is not None:
            out["chain_strain_energy_share"] = self.chain_share.tolist()
        out["reduced_masses_kg"] = self.masses_kg.tolist()
        out["span_stiffness_n_per_m"] = self.stiffness_n_per_m.tolist()
        if self.scaled_diagonal is not None:
            out["partial_frequencies_hz"] = self.partial_frequencies_hz.tolist()
        out["damping_ratio"] = self.damping_ratio
        return out


def elastic_basis(model: DriveModel, modes: TorsionalModes) -> tuple[FloatArray, FloatArray]:
    """(Φ (N, E), Ω (E,) [rad/s]): the elastic mass-normalised modes in the coordinates q of
    the model's :class:`~chaindrive.dynamics.model.build.LinearModel`."""
    massed = model.system.mass > 0.0
    Q = modes.modal_coordinates[massed]
    elastic = ~modes.rigid_body
    return Q[:, elastic], modes.angular_frequencies_rad_s[elastic]


def drive_modes(model: DriveModel) -> tuple[Modes, StateModes]:
    """The modes of a whole-drive model (module docstring) and its complex elastic modes.

    Parameters
    ----------
    model : DriveModel
        The model (:func:`chaindrive.dynamics.model.build.drive_model`).

    Returns
    -------
    tuple of Modes and StateModes
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
    return Modes(modes.frequencies_hz, modes.rigid_body, phi, fd, zeta, model.ring.masses_kg,
                 model.linear.span_stiffness / model.contours, float(zeta[j_ref]), governing,
                 chain, modes), state


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


@dataclass(frozen=True, slots=True, eq=False)
class DriveDynamics:
    """Everything a designer reads about a drive's vibration (JSON ``dynamics``).

    Parameters
    ----------
    model : DriveModel
        The whole-drive model (:class:`~chaindrive.dynamics.model.build.DriveModel`).
    modal : Modes
        Its modes at the sprockets (:class:`~chaindrive.dynamics.modes.Modes`).
    state : StateModes
        Its complex elastic modes (with damping).
    span_transverse_hz : ndarray
        (spans, modes) transverse natural frequencies of the spans [Hz] (empty without span
        tensions).
    working : tuple of WorkingFrequency
        The working frequencies (tooth frequencies and their harmonics, shaft speeds).
    resonances : tuple of Resonance
        The resonance table: every working frequency against the nearest natural one.
    campbell : CampbellData or None
        Campbell data over the speed range (None: not computed).
    damping_ratio : float
        Damping ratio ζ of the chain's reference mode [-].
    """

    model: DriveModel
    modal: Modes
    state: StateModes
    span_transverse_hz: NDArray[np.float64]
    working: tuple[WorkingFrequency, ...]
    resonances: tuple[Resonance, ...]
    campbell: CampbellData | None
    damping_ratio: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        m = self.modal.to_dict()
        st = self.span_transverse_hz
        return {
            "model": self.model.to_dict(),
            **{k: m[k] for k in ("natural_frequencies_hz", "natural_frequencies_rad_s",
                                 "damped_frequencies_hz", "modal_damping_ratios",
                                 "rigid_body_modes", "mode_shapes", "normalized_amplitudes",
                                 "governing_elements", "chain_strain_energy_share")},
            "span_transverse_frequencies_hz": st[:, 0].tolist() if st.size else [],
            "span_transverse_modes_hz": st.tolist(),
            "working_frequencies": [w.to_dict() for w in self.working],
            "resonances": [r.to_dict() for r in self.resonances],
            "campbell": None if self.campbell is None else self.campbell.to_dict(),
            "damping_ratio": self.damping_ratio,
        }


def model_dynamics(drive: Drive, geometry: GeometryResult, model: DriveModel, *,
                   harmonics: int = 3, transverse_modes: int = 3,
                   speed_range: tuple[float, float] | None = None,
                   speed_points: int = 61) -> DriveDynamics:
    """Modes, span transverse frequencies, resonance table and Campbell data of a drive.

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult
        Its contour.
    model : DriveModel
        Its whole-drive model.
    harmonics : int
        Harmonics of the tooth frequency among the working frequencies.
    transverse_modes : int
        Transverse modes per span.
    speed_range : tuple of float | None
        (ω_min, ω_max) of the driver [rad/s] for the Campbell data (None: none).
    speed_points : int
        Speeds of the Campbell data.

    Returns
    -------
    DriveDynamics

    References
    ----------
    [MultimassChainDrives, §3.2–3.3] (working frequencies, resonances); docs/dynamics.md.
    """
    modal, state = drive_modes(model)
    spec = drive.chain.spec
    driver = drive.driver
    teeth = [s.teeth for s in drive.sprockets]
    names = [s.name for s in drive.sprockets]
    lengths = np.array([sp.length for sp in geometry.spans])
    tensions = model.ring.span_tensions_n
    transverse = np.zeros((0, transverse_modes))
    working: tuple[WorkingFrequency, ...] = ()
    rows: tuple[Resonance, ...] = ()
    fz = None
    if driver.speed is not None:
        v = float(mean_chain_speed(spec.pitch, driver.teeth, driver.speed))
        if tensions is not None:
            transverse = span_transverse_frequencies(lengths, tensions, spec.mass_per_length, v,
                                                     modes=transverse_modes)
        working = working_frequencies(driver.speed, driver.teeth, teeth, names, harmonics)
        fz = float(tooth_frequency(driver.teeth, driver.speed))
    if working:
        rows = resonance_table(modal, working, transverse[:, 0] if transverse.size else None,
                               fz, [f"{sp.start_name}→{sp.end_name}" for sp in geometry.spans])
    campbell = None
    if speed_range is not None:
        speeds = np.linspace(speed_range[0], speed_range[1], speed_points)
        campbell = campbell_data(modal, speeds, driver.teeth, teeth, names, harmonics,
                                 lengths if tensions is not None else None, tensions,
                                 spec.mass_per_length, spec.pitch)
    return DriveDynamics(model, modal, state, transverse, working, rows, campbell,
                         modal.damping_ratio)
