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
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
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
    from chaindrive.dynamics.torsional.system import TorsionalSystem
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["DriveDynamics", "Modes", "drive_modes", "inertia_modes_batch", "model_dynamics"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def _no_array() -> FloatArray:
    """The empty, read-only default of an array a model does not give."""
    a = np.zeros(0)
    a.flags.writeable = False
    return a


def _state_matrix_modes(basis: FloatArray, omega: FloatArray, damping: FloatArray
                        ) -> tuple[ComplexArray, ComplexArray, ComplexArray]:
    """(λ, V, V⁻¹) of the first-order form of ÿ + Φᵀ C Φ ẏ + Ω² y = 0 (module docstring).

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
    tuple of ndarray
        (2E,) eigenvalues λ [rad/s], (2E, 2E) right eigenvectors V and left ones V⁻¹ [-].

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
    return lam.astype(complex), V.astype(complex), np.linalg.inv(V).astype(complex)


def _damped(eigenvalues: ComplexArray, natural_rad_s: FloatArray
            ) -> tuple[FloatArray, FloatArray]:
    """(damped frequencies [Hz], damping ratios [-]) of the E elastic modes in the order of
    their undamped frequencies: each mode takes the oscillating eigenvalue (Im λ > 0) of
    nearest |λ|; an overdamped mode (none left) gets a damped frequency 0 and ζ = 1.

    Parameters
    ----------
    eigenvalues : ndarray
        (2E,) complex eigenvalues λ of the state matrix [rad/s].
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
    pool = [complex(x) for x in eigenvalues if x.imag > 1e-12 * max(1.0, abs(x))]
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


@dataclass(frozen=True, slots=True, eq=False)
class Modes:
    """The modes of a linear model: the one modal result the torsional builder
    (:meth:`chaindrive.dynamics.torsional.model.TorsionalModel.modal`, undamped), the ring of
    reduced masses (:meth:`chaindrive.dynamics.ring.RingModel.modal`) and the whole-drive
    model (:func:`drive_modes`, with its damped complex modes) return, and what the resonance
    table, the Campbell data, the detuning and the frequency response read. Frozen, its
    arrays read-only. An array a model does not give is empty (or None), a ratio nan.

    Parameters
    ----------
    frequencies_hz : ndarray
        (M,) undamped natural frequencies [Hz], ascending, rigid-body zeros first.
    rigid_body : ndarray of bool
        (M,) True for a rigid-body mode.
    shapes : ndarray
        (n, M) mode shapes, mass-normalised: at the n sprockets the chain displacement
        R̄_i φ_i [m·kg^-1/2] (whole drive); the ring's X with Xᵀ M X = I [kg^-1/2]; the angle
        of every node [rad] (torsional builder, = ``shape_matrix``).
    damped_frequencies_hz : ndarray
        (M,) damped natural frequencies [Hz] (the ring: f·sqrt(1 − ζ²); empty: an undamped
        analysis, the torsional builder).
    modal_damping_ratios : ndarray
        (M,) damping ratio of each mode [-] (0 for rigid-body modes; empty: an undamped
        analysis).
    masses_kg : ndarray
        (n,) the sprockets' reduced masses J/R² [kg] ([MultimassChainDrives, §3.1]; empty:
        the torsional builder, which has no sprockets).
    stiffness_n_per_m : ndarray
        (n,) span (branch) stiffness of one contour [N/m] (empty: the torsional builder).
    damping_ratio : float
        Damping ratio ζ of the reference mode [-] (the ring: its one ζ,
        [MultimassChainDrives]: D = 0.06; nan: an undamped analysis).
    chain_share : ndarray | None
        (M,) the share of the chain (spans and wraps) in each mode's strain energy [-]
        (whole drive only: None for the ring, whose every spring is the chain).
    system : TorsionalSystem | None
        The assembled system the modes were solved from (None for the ring).
    modal_coordinates : ndarray | None
        (size, M) reduced coordinates q of each mode of ``system``, mass-normalised
        (qᵀ M q = 1 [kg·m²]; massless coordinates recovered statically) [rad] (None for the
        ring).
    scaled_diagonal : ndarray | None
        (n,) K_kk / m_k [rad²/s²] of the ring, the squares of the partial angular
        frequencies (the diagonal terms of [MultimassChainDrives, eq. 2]; None otherwise).
    eigenvalues : ndarray | None
        (2E,) complex eigenvalues λ of the state matrix of the elastic part [rad/s]
        (whole drive only).
    right, left : ndarray | None
        (2E, 2E) right eigenvectors V and left ones V⁻¹ of the state matrix in the modal
        coordinates (y, ẏ) [-] (whole drive only).
    basis : ndarray | None
        (N, E) elastic mass-normalised modes Φ with q = Φ y in the coordinates of the model's
        :class:`~chaindrive.dynamics.model.build.LinearModel` [coordinate units · kg^-1/2]
        (whole drive only).

    References
    ----------
    [Rao2011, ch. 6, §6.14] (modal analysis, mass-normalised and complex modes).
    """

    frequencies_hz: FloatArray
    rigid_body: NDArray[np.bool_]
    shapes: FloatArray
    damped_frequencies_hz: FloatArray = field(default_factory=_no_array)
    modal_damping_ratios: FloatArray = field(default_factory=_no_array)
    masses_kg: FloatArray = field(default_factory=_no_array)
    stiffness_n_per_m: FloatArray = field(default_factory=_no_array)
    damping_ratio: float = math.nan
    chain_share: FloatArray | None = None
    system: TorsionalSystem | None = None
    modal_coordinates: FloatArray | None = None
    scaled_diagonal: FloatArray | None = None
    eigenvalues: ComplexArray | None = None
    right: ComplexArray | None = None
    left: ComplexArray | None = None
    basis: FloatArray | None = None

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
        """μ_k^(j) = |X_k^(j)| / Σ_i |X_i^(j)| over the shapes' rows, columns per mode
        [MultimassChainDrives, eq. 2] (a mode that leaves every row still: zeros)."""
        a = np.abs(self.shapes)
        total = a.sum(axis=0)
        return np.asarray(np.divide(a, total, out=np.zeros_like(a), where=total > 0),
                          dtype=np.float64)

    @property
    def partial_frequencies_hz(self) -> FloatArray:
        """sqrt(K_kk / m_k) / 2π [Hz] of the ring (the diagonal of M^{-1/2} K M^{-1/2});
        empty otherwise."""
        if self.scaled_diagonal is None:
            return np.zeros(0)
        return np.sqrt(self.scaled_diagonal) / TWO_PI

    def complex_modes(self) -> tuple[ComplexArray, ComplexArray, ComplexArray, FloatArray]:
        """(λ, V, V⁻¹, Φ): the damped complex modes of the elastic part (module docstring).

        Returns
        -------
        tuple of ndarray
            ``eigenvalues``, ``right``, ``left`` and ``basis``.

        Raises
        ------
        ValueError
            For modes without them (an undamped analysis, the ring).
        """
        if self.eigenvalues is None or self.right is None or self.left is None \
                or self.basis is None:
            raise ValueError("these modes carry no complex modes (an undamped analysis)")
        return self.eigenvalues, self.right, self.left, self.basis

    def _solved(self) -> tuple[TorsionalSystem, FloatArray]:
        """(system, modal coordinates); ValueError for modes without them (the ring)."""
        if self.system is None or self.modal_coordinates is None:
            raise ValueError("these modes carry no assembled system (the ring's modes)")
        return self.system, self.modal_coordinates

    @property
    def node_names(self) -> tuple[str, ...]:
        """Node names of the system, rows of ``shape_matrix``."""
        return self._solved()[0].node_names

    @property
    def element_names(self) -> tuple[str, ...]:
        """Element names of the system, rows of ``strain_energy_shares``."""
        return self._solved()[0].element_names

    @property
    def element_kinds(self) -> tuple[str, ...]:
        """Element kinds of the system ("span", "wrap", "shaft", …), as ``element_names``."""
        return self._solved()[0].element_kinds

    @property
    def shape_matrix(self) -> FloatArray:
        """(nodes, M) angle of every node of the system in each mode [rad] (mass-normalised)."""
        s, q = self._solved()
        return s.node_factor[:, None] * q[s.node_dof]

    @property
    def strain_energy_shares(self) -> FloatArray:
        """(elements, M) share of each element in the strain energy ½ k e² of each mode
        (columns sum to 1; 0 for rigid-body modes)."""
        s, q = self._solved()
        strain = s.element_incidence @ q
        energy = s.element_stiffness[:, None] * strain * strain
        total = energy.sum(axis=0)
        shares = np.divide(energy, total, out=np.zeros_like(energy), where=total > 0.0)
        shares[:, self.rigid_body] = 0.0
        return np.asarray(shares, dtype=np.float64)

    @property
    def node_shapes(self) -> Mapping[str, FloatArray]:
        """Node name → its angle in every mode [rad] (a row of ``shape_matrix``)."""
        return MappingProxyType(dict(zip(self.node_names, self.shape_matrix, strict=True)))

    @property
    def participation(self) -> Mapping[str, FloatArray]:
        """Element name → its strain-energy share in every mode (which element governs)."""
        return MappingProxyType(dict(zip(self.element_names, self.strain_energy_shares,
                                         strict=True)))

    @property
    def governing(self) -> tuple[str, ...]:
        """(M,) the element holding most of each mode's strain energy ("" for a rigid-body
        mode; empty for the ring)."""
        if self.system is None:
            return ()
        names = self.system.element_names
        if not names:
            return ("",) * self.frequencies_hz.size
        best = np.argmax(self.strain_energy_shares, axis=0).tolist()
        return tuple("" if r else names[k]
                     for r, k in zip(self.rigid_body.tolist(), best, strict=True))

    def governing_element(self, mode: int) -> str:
        """Name of the element with the largest strain-energy share in ``mode``.

        Parameters
        ----------
        mode : int
            Index of the mode (0 the lowest).

        Returns
        -------
        str
            The element's name ("" for a rigid-body mode or a model without elements).
        """
        names = self.element_names
        if self.rigid_body[mode] or not names:
            return ""
        return names[int(np.argmax(self.strain_energy_shares[:, mode]))]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; ``mode_shapes[j]`` lists the shapes' rows in mode j (the
        damped keys with damping, ``governing_elements`` and ``strain_energy_shares`` with an
        assembled system, ``chain_strain_energy_share`` for the whole drive,
        ``partial_frequencies_hz`` for the ring)."""
        out: dict[str, Any] = {
            "natural_frequencies_hz": self.frequencies_hz.tolist(),
            "natural_frequencies_rad_s": self.angular_frequencies_rad_s.tolist(),
        }
        if self.damped_frequencies_hz.size:
            out["damped_frequencies_hz"] = self.damped_frequencies_hz.tolist()
            out["modal_damping_ratios"] = self.modal_damping_ratios.tolist()
        out["rigid_body_modes"] = self.rigid_body.tolist()
        out["mode_shapes"] = self.shapes.T.tolist()
        out["normalized_amplitudes"] = self.normalized_amplitudes.T.tolist()
        if self.system is not None:
            out["governing_elements"] = list(self.governing)
            out["strain_energy_shares"] = dict(zip(
                self.element_names, self.strain_energy_shares.tolist(), strict=True))
        if self.chain_share is not None:
            out["chain_strain_energy_share"] = self.chain_share.tolist()
        if self.masses_kg.size:
            out["reduced_masses_kg"] = self.masses_kg.tolist()
            out["span_stiffness_n_per_m"] = self.stiffness_n_per_m.tolist()
        if self.scaled_diagonal is not None:
            out["partial_frequencies_hz"] = self.partial_frequencies_hz.tolist()
        if not math.isnan(self.damping_ratio):
            out["damping_ratio"] = self.damping_ratio
        return out


def elastic_basis(model: DriveModel, modes: Modes) -> tuple[FloatArray, FloatArray]:
    """(Φ (N, E), Ω (E,) [rad/s]): the elastic mass-normalised modes in the coordinates q of
    the model's :class:`~chaindrive.dynamics.model.build.LinearModel`."""
    if modes.modal_coordinates is None:
        raise ValueError("the modes carry no modal coordinates")
    massed = model.system.mass > 0.0
    Q = modes.modal_coordinates[massed]
    elastic = ~modes.rigid_body
    return Q[:, elastic], modes.angular_frequencies_rad_s[elastic]


def drive_modes(model: DriveModel) -> Modes:
    """The modes of a whole-drive model (module docstring), undamped and damped.

    Parameters
    ----------
    model : DriveModel
        The model (:func:`chaindrive.dynamics.model.build.drive_model`).

    Returns
    -------
    Modes
        At the sprockets, with the model's system, its complex elastic modes and the chain's
        share of the strain energy.
    """
    modes = model.modal()
    basis, omega = elastic_basis(model, modes)
    lam, right, left = _state_matrix_modes(basis, omega, model.linear.damping())
    fd_el, z_el = _damped(lam, omega)
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
    ref = model.reference_frequency_hz
    el = np.flatnonzero(~modes.rigid_body)
    j_ref = int(el[np.argmin(np.abs(modes.frequencies_hz[el] - ref))]) if el.size else 0
    return replace(modes, shapes=phi, damped_frequencies_hz=fd, modal_damping_ratios=zeta,
                   masses_kg=model.ring.masses_kg,
                   stiffness_n_per_m=model.linear.span_stiffness / model.contours,
                   damping_ratio=float(zeta[j_ref]), chain_share=chain, eigenvalues=lam,
                   right=right, left=left, basis=basis)


@shared_parameters
def inertia_modes_batch(model: DriveModel, added_inertia: NDArray[np.float64]
                        ) -> tuple[FloatArray, FloatArray]:
    """Elastic frequencies and the sprockets' largest normalised amplitude per mode of B
    variants of a whole-drive model whose sprockets carry added inertias (flywheels).

    Parameters
    ----------
    %(drive_model)s
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
        Its modes at the sprockets, undamped and damped (:class:`Modes`).
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


@shared_parameters
def model_dynamics(drive: Drive, geometry: GeometryResult, model: DriveModel, *,
                   harmonics: int = 3, transverse_modes: int = 3,
                   speed_range: tuple[float, float] | None = None,
                   speed_points: int = 61) -> DriveDynamics:
    """Modes, span transverse frequencies, resonance table and Campbell data of a drive.

    Parameters
    ----------
    %(drive_geometry)s
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
    modal = drive_modes(model)
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
    return DriveDynamics(model, modal, transverse, working, rows, campbell,
                         modal.damping_ratio)
