r"""Static equilibrium of the link-level model at the installed pre-tension: the state every
run starts from, solved as a set of equations, not relaxed.

The whole-drive model takes the spans at the pre-tension T₀ of the installed sag
(:func:`chaindrive.strength.loads.installed_pretension`). The link-level chain holds it only
if it is installed: its rollers seated in the gaps (a roller centred on the pitch circle
clears the seat by r_i − r, some 0.1 mm, and a 0.1–0.4 µm link stretch cannot hold T₀
across that) and its spans stretched or hung to T₀. The static state solves the balance of
every roller (gravity, link springs, roller–tooth contacts: the kernel's own forces at
rest, :func:`chaindrive.linklevel.kernel.static_forces`) and every free sprocket (contact
torques; the driver is held, which fixes the free turning of the chain round its loop, and
the torque it takes is reported), with the reference link — the middle of the span leaving
the driver — at T₀, in the unknowns x [m], R_s·θ_s [m] and the links' common rest length
ℓ₀ [m].

1. Installed contour and placement (:func:`installed_geometry`). A contour whose slack is
   not the slack of the installed sag — a fixed-centre design with chain slack left over,
   or a tight take-up — is taken up to the installed sag by the project's own take-up
   (:func:`chaindrive.geometry.contour.contour_geometry` with the design's adjustable
   sprocket, else the sprocket the slack span runs onto, and ``[chain] sag`` the installed
   sag ratio): the chain installed as the whole-drive model assumes. The chain is placed on
   it kinematically (:func:`chaindrive.linklevel.assembly.assemble_chain`: every roller on a
   wrap at the centre of its seating arc, one pitch apart, the sprockets turned under them;
   with gravity the slack hung in a sag), ℓ₀ = p − T₀/k.
2. The balance of forces is the stationarity of the potential energy V
   (:func:`potential_energy`; the contact force is work-conjugate to its penetration), and a
   static state that can be installed is a minimum of it. With the rest length let free
   under a constant pull T̄ — Φ = V + T̄·N·ℓ₀, whose stationarity in ℓ₀ puts the mean link
   tension at T̄, as a hanging-weight tensioner would — the minimum of Φ is found from the
   placement by the trust-region Newton method in its Levenberg–Marquardt form
   ([Nocedal2006, ch. 4], :func:`_minimum`: each step the minimiser of the quadratic model
   within a trust region, (∇²Φ + μI)p = −∇Φ, the shift μ grown or shrunk by the ratio of
   actual to predicted decrease): for a twice differentiable Φ it converges from any start
   to a point where ∇Φ = 0 and ∇²Φ is positive semi-definite; the contacts make this Φ only
   once differentiable, so that is the method's footing, not a proof. The
   Hessian −∂F/∂x is taken by finite differences (step 1 nm) grouped over rollers three
   links apart (a roller's force depends on its own position and its two neighbours',
   [Curtis1974]), symmetrised and kept sparse; the shifted Hessian is factorised by SuperLU
   with diagonal pivots (:func:`_definite_solve`). Every minimisation is followed from a
   soft contact to the real one (:func:`_followed`): Φ minimised with the contact
   stiffness k_c scaled by 10⁻³, 10⁻², 10⁻¹ (:data:`CONTACT_CONTINUATION`) and then 1,
   each from the last — a continuation in k_c ([Nocedal2006, §11.3]). Without it a drive
   with long slack spans at a low T₀ creeps: the spans' sag together with the free
   sprockets' turns is some 10⁷ times softer than the links and contacts (19 N/m against
   1.4·10⁹ N/m on the 24-sprocket example), and a roller grazing its seat, whose stiffness
   jumps between 0 and k_c across δ = 0, drives the shift μ to 10⁴–10⁷ N/m, so that each
   step moves the sag by λ/(λ + μ) ≈ 10⁻⁶–10⁻³ of its Newton step (docs/linklevel.md §1).
   With a soft contact the jump is of the sag's order and the sag settles in tens of
   steps; the stiffer stages then move the seats by nanometres, in directions as stiff as
   the shift. A secant on T̄ (started at T₀, the
   reference carrying the pull up to hydrostatic and polygon offsets) brings the reference
   link to T₀, each minimisation starting from the last.
3. Newton's method on the full residual, bordered with the reference tension = T₀ in the
   unknown ℓ₀ ([Dennis1996, §6.3], backtracking line search; each step's Jacobian kept
   sparse and factorised by SuperLU, not as a dense matrix), polishes the last minimum to
   the force tolerance: Φ's round-off (some 10⁻¹⁸ J against link energies of 10⁻⁵ J) stops
   the trust region near 10⁻⁵ N, where Newton converges quadratically.

Tolerances, consistent with each other (all as fractions of T₀, so in N once multiplied by
it): the minimisations stop at ‖∇Φ‖₂ ≤ :data:`MINIMUM_TOLERANCE` T₀ = 10⁻⁵ T₀; the
reference tension they leave is accurate to about that, so the secant on T̄ stops at
|T_ref − T₀| ≤ :data:`TENSION_TOLERANCE` T₀ = 10⁻⁴ T₀, ten times coarser; the Newton
polish aims at the largest force component ≤ :data:`FORCE_TOLERANCE` T₀ = 10⁻⁶ T₀ (10⁴
times the forces' own round-off, k·ε·|x| ≈ 10⁻⁸ N). Where the polish stops short, the
state is minimised again from it and polished again (three rounds at most). A minimisation
that stops at its step cap (:data:`_TRUST_STEPS`) reads the reference tension with its own
scatter: the secant then stops once T_ref is within :data:`ACCEPTED_RESIDUAL` T₀ and no
renewed minimisation is tried. The state is
converged when its largest residual force is within the minimisation's tolerance and T_ref
within the secant's; one that stops short but has both within :data:`ACCEPTED_RESIDUAL`
T₀ = 10⁻² T₀ is kept with ``converged`` false; the residual (largest component and 2-norm, N) is
reported either way. The solve runs with the linear
algebra held to one thread (``threadpoolctl``), so that its arithmetic, and so its result,
does not depend on the machine's BLAS threads. It refuses (:class:`ConvergenceError`) a
chain whose links cannot carry T₀ at a positive rest length, and a state that none of the
steps brings within those bounds, with the reference tension and the force left.

With gravity the tension along a chain hanging over freely turning wheels is hydrostatic,
T(y) = T_ref + q g (y − y_ref) ([Irvine1981, ch. 1]: dT/ds = q g dy/ds for a cable under its
own weight), so every span's middle carries T₀ + q g (y_k − y_ref); without gravity every
span carries T₀ — both up to the polygon: a free sprocket passes the tension on at arms
between R cos(π/z) and R, so spans may differ by up to 1/cos(π/z) − 1 per sprocket.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import cho_factor, cho_solve
from scipy.sparse import csc_matrix, diags
from scipy.sparse.linalg import splu
from threadpoolctl import threadpool_limits

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ConvergenceError, DesignError, GeometryError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel.kernel import potential_energy, static_forces
from chaindrive.strength.loads import installed_sag_ratio
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.assembly import Assembly
    from chaindrive.linklevel.model import LinkLevelModel
    from chaindrive.model import Drive

__all__ = [
    "Balance",
    "Equilibrium",
    "KernelTables",
    "installed_geometry",
    "kernel_tables",
    "potential_energy",
    "span_probes",
    "static_equilibrium",
]

#: Largest residual force component the Newton polish aims at, as a fraction of T₀ [-].
FORCE_TOLERANCE = 1e-6
#: ‖∇Φ‖₂ at which a trust-region minimisation stops, as a fraction of T₀ [-].
MINIMUM_TOLERANCE = 1e-5
#: |T_ref − T₀| at which the secant on the pull stops, as a fraction of T₀ [-].
TENSION_TOLERANCE = 1e-4
#: Largest residual force and reference tension error of a state kept although the solve
#: stopped short of MINIMUM_TOLERANCE or TENSION_TOLERANCE (``converged`` false, the
#: residual and the error reported), as a fraction of T₀ [-].
ACCEPTED_RESIDUAL = 1e-2
#: Rounds of Newton polish and renewed minimisation at most [-].
_POLISH_ROUNDS = 3
#: Steps of one bordered Newton polish at most [-].
_NEWTON_STEPS = 20
#: Trust-region steps of one minimisation at most [-].
_TRUST_STEPS = 2000
#: Steps refused in a row at which a minimisation has reached Φ's round-off [-].
_REJECTIONS = 30
#: The first shift μ as a fraction of the Hessian's largest diagonal entry [-].
_SHIFT_START = 1e-6
#: Secant steps on the pull at most [-].
_PULL_STEPS = 12
#: The continuation in the contact stiffness: the fractions of k_c at which Φ is minimised,
#: each from the last, before the solve at k_c itself (module docstring, step 2) [-].
CONTACT_CONTINUATION = (1e-3, 1e-2, 1e-1)


@dataclass(frozen=True, slots=True, eq=False)
class KernelTables:
    """The kernel's sprocket tables (see :func:`chaindrive.linklevel.kernel._contacts`).

    Parameters
    ----------
    spr : ndarray
        (12, n) centre, teeth, radii, contact stiffness and damping, gap angle, half-chord
        [SI, each row in its own unit].
    trig : ndarray
        (3, n) cos α, sin α, tan α of the seating half-angle [-].
    gtab : ndarray
        (n, z_max, 2) gap directions in the sprocket frames [-].
    reach : ndarray
        (n,) radius within which a roller is a contact candidate [m].
    """

    spr: NDArray[np.float64]
    trig: NDArray[np.float64]
    gtab: NDArray[np.float64]
    reach: NDArray[np.float64]


def kernel_tables(model: LinkLevelModel) -> KernelTables:
    """Sprocket tables of ``model`` for the kernel (reach: tip circle + roller + p/4).

    Parameters
    ----------
    model : LinkLevelModel
        The model.

    Returns
    -------
    KernelTables
        Its tables.
    """
    n = model.centres.shape[0]
    spr = np.ascontiguousarray(np.vstack([
        model.centres[:, 0], model.centres[:, 1], model.teeth.astype(float), model.pitch_radii,
        np.full(n, model.roller_radius), model.seating_radii, model.seating_half_angles,
        model.tip_radii, model.contact_stiffness, model.contact_damping, TWO_PI / model.teeth,
        model.pitch_radii * np.sin(np.pi / model.teeth)]))
    a = model.seating_half_angles
    trig = np.ascontiguousarray(np.vstack([np.cos(a), np.sin(a), np.tan(a)]))
    zmax = int(model.teeth.max())
    gtab = np.zeros((n, zmax, 2))
    for i, zi in enumerate(model.teeth):
        ang = TWO_PI * np.arange(zi) / zi
        gtab[i, :zi, 0], gtab[i, :zi, 1] = np.cos(ang), np.sin(ang)
    reach = model.tip_radii + model.roller_radius + 0.25 * model.pitch
    return KernelTables(spr, trig, gtab, reach)


def installed_geometry(drive: Drive, geometry: GeometryResult
                       ) -> tuple[GeometryResult, str | None]:
    """The contour with the chain installed at the installed sag (module docstring, step 1).

    Parameters
    ----------
    drive : Drive
        The design.
    geometry : GeometryResult
        Its contour.

    Returns
    -------
    geometry : GeometryResult
        ``geometry`` itself when it is already installed at the design's sag (an adjustable
        sprocket and ``[chain] sag`` given) or cannot be taken up; else the taken-up contour.
    take_up : str or None
        Name of the sprocket moved (None: none).
    """
    if geometry.adjusted is not None and drive.chain.sag is not None:
        return geometry, None
    index = drive.adjustable_index
    if index is None:
        index = geometry.spans[drive.driver_index].end
    sprockets = tuple(replace(s, adjustable=(i == index)) for i, s in enumerate(drive.sprockets))
    chain = replace(drive.chain, sag=installed_sag_ratio(drive), links=geometry.links)
    try:
        return contour_geometry(replace(drive, chain=chain, sprockets=sprockets)), \
            drive.sprockets[index].name
    except (GeometryError, DesignError, ConvergenceError):
        return geometry, None


def span_probes(geometry: GeometryResult, positions: NDArray[np.float64]) -> NDArray[np.int64]:
    """The link whose midpoint is nearest the middle of each span's line.

    Parameters
    ----------
    geometry : GeometryResult
        The contour.
    positions : ndarray
        (N, 2) roller positions [m].

    Returns
    -------
    ndarray of int
        (spans,) link indices [-].
    """
    mids = 0.5 * (positions + np.roll(positions, -1, axis=0))
    out = np.empty(len(geometry.spans), dtype=np.int64)
    for k, sp in enumerate(geometry.spans):
        centre = 0.5 * (np.array(sp.start_point) + np.array(sp.end_point))
        out[k] = int(np.argmin(np.hypot(*(mids - centre).T)))
    return out


@dataclass(frozen=True, slots=True, eq=False)
class Equilibrium:
    """The solved static state (module docstring).

    Parameters
    ----------
    positions : ndarray
        (N, 2) roller centres [m].
    angles : ndarray
        (n,) sprocket angles [rad].
    rest_length : float
        Uniform rest length ℓ₀ of the links [m].
    span_tensions : ndarray
        (spans,) tension of the link at each span's middle [N].
    target : float
        T₀ of the reference span [N].
    reference_span : int
        The span leaving the driver [-].
    residual_force : float
        Largest residual component (roller force, sprocket torque over its pitch radius) [N].
    residual_norm : float
        2-norm of the residual forces [N].
    driver_torque : float
        Torque the held driver takes [N·m].
    take_up : str or None
        The sprocket moved to install the chain (None: none).
    iterations : int
        Trust-region steps of the minimisations, all pulls [-].
    pulls : int
        Minimisations (secant steps on the pull) [-].
    converged : bool
        Whether the residual is within :data:`MINIMUM_TOLERANCE` T₀ and the reference
        tension within :data:`TENSION_TOLERANCE` T₀ (else both within
        :data:`ACCEPTED_RESIDUAL` T₀, the state kept and its residual reported).
    """

    positions: NDArray[np.float64]
    angles: NDArray[np.float64]
    rest_length: float
    span_tensions: NDArray[np.float64]
    target: float
    reference_span: int
    residual_force: float
    residual_norm: float
    driver_torque: float
    take_up: str | None
    iterations: int
    pulls: int
    converged: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI, units in the keys)."""
        return {"pretension_target_n": self.target,
                "reference_span": self.reference_span,
                "span_tension_n": self.span_tensions.tolist(),
                "rest_length_m": self.rest_length,
                "residual_force_n": self.residual_force,
                "residual_force_norm_n": self.residual_norm,
                "reference_tension_error_n": float(self.span_tensions[self.reference_span])
                - self.target,
                "solver_iterations": self.iterations, "solver_pulls": self.pulls,
                "converged": self.converged,
                "driver_holding_torque_n_m": self.driver_torque,
                "take_up_sprocket": self.take_up}


class Balance:
    """Residual of the static balance — the forces on the rollers, the torques on the free
    sprockets [N·m]/R and the reference link's tension less T₀ [N] — in the unknowns x [m],
    R_s·θ_s [m] and the rest length ℓ₀ [m], and its Jacobian by finite differences grouped
    over rollers three links apart (a roller's force depends on its own position and its
    two neighbours', [Curtis1974]).

    Parameters
    ----------
    model : LinkLevelModel
        The model.
    tables : KernelTables
        Its sprocket tables (:func:`kernel_tables`).
    free : ndarray of int
        Indices of the sprockets free to turn [-].
    N : int
        Number of rollers [-].
    ref : int
        The link whose tension is held at T₀ [-].
    """

    def __init__(self, model: LinkLevelModel, tables: KernelTables, free: NDArray[np.int64],
                 N: int, ref: int) -> None:
        self.model, self.tables, self.free, self.ref = model, tables, free, ref
        n = model.centres.shape[0]
        self.f, self.tq, self.T = np.empty((N, 2)), np.empty(n), np.empty(N)
        self.tr = np.empty(N)
        self.L0 = np.empty(N)
        self.radius = model.pitch_radii[free]
        self._grouping: tuple[int, NDArray[np.int64], NDArray[np.int64], NDArray[np.int64],
                              list[NDArray[np.int64]]] | None = None

    def __call__(self, x: NDArray[np.float64], th: NDArray[np.float64],
                 rest: float) -> NDArray[np.float64]:
        m, t = self.model, self.tables
        self.L0.fill(rest)
        static_forces(x, th, self.L0, m.link_stiffness, m.clearance, m.roller_mass,
                      float(m.gravity[0]), float(m.gravity[1]), t.spr, t.trig, t.gtab, t.reach,
                      self.f, self.tq, self.T, self.tr)
        return np.concatenate([self.f.ravel(), self.tq[self.free] / self.radius,
                               [self.T[self.ref] - m.pretension]])

    @shared_parameters
    def jacobian(self, x: NDArray[np.float64], th: NDArray[np.float64], rest: float,
                 r0: NDArray[np.float64]) -> NDArray[np.float64]:
        """d residual / d (x, R_s θ_s, ℓ₀) by forward differences of step h = 1 nm.

        Parameters
        ----------
        %(balance_point)s

        Returns
        -------
        ndarray
            The Jacobian [N/m].
        """
        return self.sparse_jacobian(x, th, rest, r0).toarray()

    @shared_parameters
    def sparse_jacobian(self, x: NDArray[np.float64], th: NDArray[np.float64], rest: float,
                        r0: NDArray[np.float64]) -> csc_matrix:
        """:meth:`jacobian` as a sparse matrix (its entries gathered without the dense
        array).

        Parameters
        ----------
        %(balance_point)s

        Returns
        -------
        scipy.sparse.csc_matrix
            The Jacobian [N/m].
        """
        rows, cols, vals = self.entries(x, th, rest, r0)
        size = 2 * x.shape[0] + self.free.size + 1
        return csc_matrix((vals, (rows, cols)), shape=(size, size))

    @shared_parameters
    def entries(self, x: NDArray[np.float64], th: NDArray[np.float64], rest: float,
                r0: NDArray[np.float64]
                ) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64]]:
        """The nonzero pattern of :meth:`jacobian` and its entries, each (row, column) once
        (rows, columns, values [N/m]; the last evaluation the one at ℓ₀ + h, as
        :meth:`sparse_jacobian` leaves :attr:`T`).

        Parameters
        ----------
        %(balance_point)s

        Returns
        -------
        tuple of ndarray
            Rows [-], columns [-] and values [N/m] of the entries.
        """
        N, nf = x.shape[0], self.free.size
        h = 1e-9
        size = 2 * N + nf + 1
        self(x, th, rest)
        tr0, t0 = self.tr.copy(), self.T.copy()
        sc = self._sprocket_of(x)
        row_of = np.full(self.model.centres.shape[0] + 1, -1, dtype=np.int64)
        row_of[self.free] = 2 * N + np.arange(nf)
        torque_row = row_of[sc]  # sc = −1 (no sprocket) reads the last entry, −1
        group_of, force_rows, force_cols, groups = self._groups(N)
        ref, ref_next = self.ref, (self.ref + 1) % N
        diff = np.empty((len(groups), 2, size))  # each group's perturbed residual less r0, /h
        dtr = np.empty((2, N))  # each roller's torque change on its sprocket, /h
        dref = np.empty((len(groups), 2))  # the reference tension's change, /h
        for g, members in enumerate(groups):
            for c in range(2):
                xp = x.copy()
                xp[members, c] += h
                diff[g, c] = (self(xp, th, rest) - r0) / h
                dtr[c, members] = ((self.tr - tr0) / h)[members]
                dref[g, c] = ((self.T - t0) / h)[ref]
        held = np.flatnonzero(torque_row >= 0)
        at_ref = np.array([ref, ref_next] if ref_next != ref else [ref], dtype=np.int64)
        c2 = np.arange(2)
        rows = [force_rows.ravel(), np.repeat(torque_row[held], 2),
                np.full(2 * at_ref.size, size - 1)]
        cols = [force_cols.ravel(), (2 * held[:, None] + c2).ravel(),
                (2 * at_ref[:, None] + c2).ravel()]
        vals = [diff[group_of[:, None, None], c2[None, :, None], force_rows].ravel(),
                (dtr[:, held] / self.model.pitch_radii[sc[held]]).T.ravel(),
                dref[group_of[at_ref]].ravel()]
        for k, s in enumerate(self.free):
            tp = th.copy()
            tp[s] += h / self.radius[k]
            self._dense_column(rows, cols, vals, (self(x, tp, rest) - r0) / h, 2 * N + k)
        self._dense_column(rows, cols, vals, (self(x, th, rest + h) - r0) / h, size - 1)
        return np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)

    def _groups(self, N: int) -> tuple[NDArray[np.int64], NDArray[np.int64],
                                       NDArray[np.int64], list[NDArray[np.int64]]]:
        """The rollers perturbed together (three links apart, [Curtis1974]): each roller's
        group, the (N, 2, 6) rows and columns of its two columns' force entries (its own
        force and its two neighbours', both components) and the groups."""
        if self._grouping is None or self._grouping[0] != N:
            base = N - N % 3
            groups = [np.arange(g, base, 3) for g in range(3)] + [np.array([r]) for r in
                                                                 range(base, N)]
            group_of = np.empty(N, dtype=np.int64)
            for g, members in enumerate(groups):
                group_of[members] = g
            near = (np.arange(N)[:, None] + np.array([-1, 0, 1])[None, :]) % N
            force_rows = np.broadcast_to(
                (2 * near[:, :, None] + np.arange(2)[None, None, :]).reshape(N, 1, 6),
                (N, 2, 6))
            force_cols = np.broadcast_to((2 * np.arange(N)[:, None] + np.arange(2))[:, :, None],
                                         (N, 2, 6))
            self._grouping = (N, group_of, force_rows, force_cols, groups)
        _, group_of, force_rows, force_cols, groups = self._grouping
        return group_of, force_rows, force_cols, groups

    @staticmethod
    def _dense_column(rows: list[NDArray[np.int64]], cols: list[NDArray[np.int64]],
                      vals: list[NDArray[np.float64]], column: NDArray[np.float64],
                      index: int) -> None:
        """Append the nonzero entries of a column computed whole."""
        nz = np.flatnonzero(column)
        rows.append(nz)
        cols.append(np.full(nz.size, index))
        vals.append(column[nz])

    def _sprocket_of(self, x: NDArray[np.float64]) -> NDArray[np.int64]:
        """The sprocket whose reach holds each roller (−1: none)."""
        d = x[:, None, :] - self.model.centres[None, :, :]
        inside = np.hypot(d[..., 0], d[..., 1]) < self.tables.reach[None, :]
        return np.where(inside.any(axis=1), inside.argmax(axis=1), -1).astype(np.int64)

    def solve(self, x: NDArray[np.float64], th: NDArray[np.float64], rest: float, tol: float
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], float, float]:
        """Newton's method with a backtracking line search on |residual| [Dennis1996, §6.3]
        from (x, θ, ℓ₀).

        Parameters
        ----------
        x : ndarray
            (N, 2) roller positions to start from [m].
        th : ndarray
            (n,) sprocket angles to start from [rad].
        rest : float
            Rest length of the links to start from [m].
        tol : float
            Largest residual accepted [N].

        Returns
        -------
        tuple of (ndarray, ndarray, float, float)
            Positions [m], angles [rad], rest length [m] and the largest residual [N].
        """
        N = x.shape[0]
        r = self(x, th, rest)
        worst = float(np.abs(r).max())
        for _ in range(_NEWTON_STEPS):
            if worst <= tol:
                break
            J = self.sparse_jacobian(x, th, rest, r)
            try:  # sparse LU: each column holds its roller's and two neighbours' forces
                du = splu(J).solve(-r)
            except RuntimeError:  # singular: the least-squares step
                du = np.linalg.lstsq(J.toarray(), -r, rcond=None)[0]
            norm0 = float(r @ r)
            step = 1.0
            for _ls in range(40):
                xn = x + step * du[:2 * N].reshape(N, 2)
                tn = th.copy()
                tn[self.free] += step * du[2 * N:-1] / self.radius
                ln = rest + step * float(du[-1])
                rn = self(xn, tn, ln)
                if float(rn @ rn) < norm0:
                    break
                step *= 0.5
            x, th, rest, r = xn, tn, ln, rn
            worst = float(np.abs(r).max())
        return x, th, rest, worst



class _Tensioned:
    """The chain's potential energy with its rest length let free under a constant pull:
    Φ(u, R_sθ_s, w) = V(x₀ + u, θ, ℓ₀ + w/N) + T̄·w, w the change of the loop's rest length
    [m] (module docstring, step 2), with its gradient [N] and its Hessian [N/m] (from
    :meth:`Balance.jacobian`, symmetrised)."""

    def __init__(self, model: LinkLevelModel, tables: KernelTables, bal: Balance,
                 x0: NDArray[np.float64], th0: NDArray[np.float64], rest0: float) -> None:
        self.model, self.tables, self.bal = model, tables, bal
        self.x0, self.th0, self.rest0 = x0, th0, rest0
        self.N = x0.shape[0]
        self.pull = model.pretension

    def state(self, z: NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """(x [m], θ [rad], ℓ₀ [m]) of the unknowns z."""
        N, free = self.N, self.bal.free
        x = self.x0 + z[:2 * N].reshape(N, 2)
        th = self.th0.copy()
        th[free] += z[2 * N:-1] / self.bal.radius
        return x, th, self.rest0 + float(z[-1]) / N

    def value(self, z: NDArray[np.float64]) -> float:
        """Φ [J]."""
        m, t = self.model, self.tables
        x, th, rest = self.state(z)
        return float(potential_energy(
            x, z[:2 * self.N].reshape(self.N, 2), th, rest, m.link_stiffness, m.clearance,
            m.roller_mass, float(m.gravity[0]), float(m.gravity[1]), t.spr,
            t.reach)) + self.pull * float(z[-1])

    def gradient(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        """∇Φ [N]: minus the roller forces and the sprocket torques over R, T̄ − mean T."""
        r = self.bal(*self.state(z))
        return np.concatenate([-r[:-1], [self.pull - float(self.bal.T.mean())]])

    def hessian(self, z: NDArray[np.float64]) -> csc_matrix:
        """∇²Φ [N/m], sparse: the symmetric part ½(H + Hᵀ) of the Jacobian's, in canonical
        form (sorted rows, no zero entries), as ``0.5 * (H + H.T)`` gives it."""
        x, th, rest = self.state(z)
        rows, cols, vals = self.bal.entries(x, th, rest, self.bal(x, th, rest))
        N, m = self.N, self.model
        size = 2 * N + self.bal.free.size + 1
        last = size - 1
        inner = (rows < last) & (cols < last)
        side = (cols == last) & (rows < last)  # the column of w = N·Δℓ₀, ∂F/∂ℓ₀/N
        stretched = np.count_nonzero(np.abs(self.bal.T) > 0.0)
        # the tension row is replaced by the pull's, ∂(T̄ − mean T)/∂(x, w): the side
        # column transposed and k·(stretched links)/N² on the diagonal
        hr = np.concatenate([rows[inner], rows[side], np.full(side.sum(), last), [last]])
        hc = np.concatenate([cols[inner], cols[side], rows[side], [last]])
        hv = np.concatenate([-vals[inner], -vals[side] / N, -vals[side] / N,
                             [m.link_stiffness * stretched / N**2]])
        return _symmetric_part(hr, hc, hv, size)


def _symmetric_part(rows: NDArray[np.int64], cols: NDArray[np.int64],
                    vals: NDArray[np.float64], size: int) -> csc_matrix:
    """½(H + Hᵀ) of the (size × size) H with these entries (each (row, column) once) as
    ``csc_matrix(0.5 * (H + H.T))`` gives it: each entry H_ij + H_ji (one addition, so
    either order), those summing to zero left out, then halved; sorted by column, then
    row."""
    keys = np.concatenate([cols * size + rows, rows * size + cols])
    both = np.concatenate([vals, vals])
    order = np.argsort(keys, kind="stable")
    keys, both = keys[order], both[order]
    start = np.flatnonzero(np.concatenate([[True], keys[1:] != keys[:-1]]))
    if np.any(np.diff(np.append(start, keys.size)) > 2):  # an entry given twice: scipy's sum
        H = csc_matrix((vals, (rows, cols)), shape=(size, size))
        return csc_matrix(0.5 * (H + H.T))
    summed = np.add.reduceat(both, start)
    keep = summed != 0.0
    keys = keys[start[keep]]
    col = keys // size
    indptr = np.zeros(size + 1, dtype=np.int64)
    np.cumsum(np.bincount(col, minlength=size), out=indptr[1:])
    return csc_matrix((summed[keep] * 0.5, keys - col * size, indptr), shape=(size, size))


@dataclass(frozen=True, slots=True, eq=False)
class _Shift:
    """The pattern of A + μI for a canonical A: A's with its diagonal stored (indices,
    indptr), where A's entries go (``source``) and where the diagonal lies (``diagonal``)
    in its data."""

    indices: NDArray[np.integer[Any]]
    indptr: NDArray[np.integer[Any]]
    source: NDArray[np.int64]
    diagonal: NDArray[np.int64]


def _shift_pattern(A: csc_matrix) -> _Shift:
    """The pattern of A + μI (:class:`_Shift`) for a canonical ``A`` (sorted rows, each
    entry once)."""
    n = A.shape[0]
    cols = np.repeat(np.arange(n), np.diff(A.indptr))
    on = A.indices == cols
    missing = np.ones(n, dtype=bool)
    missing[cols[on]] = False
    if not missing.any():
        return _Shift(A.indices, A.indptr, np.arange(A.nnz), np.flatnonzero(on))
    absent = np.flatnonzero(missing)
    at = np.searchsorted(cols * n + A.indices, absent * (n + 1))  # where each goes
    indices = np.insert(A.indices, at, absent)
    indptr = A.indptr + np.searchsorted(absent, np.arange(n + 1))  # diagonals left of each
    source = np.arange(A.nnz) + np.searchsorted(at, np.arange(A.nnz), side="right")
    cols = np.repeat(np.arange(n), np.diff(indptr))
    return _Shift(indices, indptr, source, np.flatnonzero(indices == cols))


def _shifted(A: csc_matrix, pattern: _Shift, mu: float) -> csc_matrix:
    """A + μI as ``csc_matrix(A + diags(μ))`` gives it (``pattern`` from
    :func:`_shift_pattern`): μ added to A's diagonal (to zero where it is not stored);
    where a diagonal entry sums to zero (scipy's sum leaves it out), by scipy's sum."""
    data = np.zeros(pattern.indices.size)
    data[pattern.source] = A.data
    data[pattern.diagonal] += mu
    if np.all(data[pattern.diagonal] != 0.0):
        return csc_matrix((data, pattern.indices.copy(), pattern.indptr.copy()),
                          shape=A.shape)
    return csc_matrix(A + diags(np.full(A.shape[0], mu)))


def _definite_solve(A: csc_matrix, b: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """−A⁻¹b for a symmetric A that is positive definite, else None: A is sparse (a roller
    couples to its two neighbours, the sprockets to their wraps, ℓ₀ to all), so it is
    factorised by SuperLU with a fill-reducing symmetric ordering and diagonal pivots,
    PᵀAP = LDLᵀ in effect, whose pivots D are all positive exactly when A is (Sylvester's
    law of inertia, [Golub2013, §4.2 and §8.1]); where SuperLU left the diagonal, Cholesky."""
    lu = splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    if np.array_equal(lu.perm_r, lu.perm_c):
        return None if np.any(lu.U.diagonal() <= 0.0) else -lu.solve(b)
    try:
        return np.asarray(-cho_solve(cho_factor(A.toarray()), b), dtype=float)
    except np.linalg.LinAlgError:
        return None


def _minimum(phi: _Tensioned, tol: float, steps: int = _TRUST_STEPS,
             shifts: list[float] | None = None) -> tuple[NDArray[np.float64], int]:
    """The local minimum of Φ nearest the placement by the trust-region Newton method in its
    Levenberg–Marquardt form.

    The step that minimises the quadratic model within a radius solves
    (∇²Φ + μI)p = −∇Φ for some μ ≥ 0 with ∇²Φ + μI positive semi-definite
    ([Nocedal2006, §4.3, Theorem 4.1]); μ starts at :data:`_SHIFT_START` times the
    Hessian's largest diagonal entry (a link's or a contact's stiffness). (The elliptical
    region D = diag|∇²Φ| of [Nocedal2006, §4.5] was tried: it left the conveyor and the
    24-sprocket drive short of the tolerance.) μ is raised fourfold while the
    shifted Hessian is not positive definite (:func:`_definite_solve`) or the step's actual
    decrease of Φ is below a quarter of the predicted one, and lowered fourfold after a step
    whose ratio exceeds three quarters (the ratio test of [Nocedal2006, Algorithm 4.1]).

    Parameters
    ----------
    phi : _Tensioned
        The energy with its pull.
    tol : float
        ‖∇Φ‖₂ at which it stops [N].
    steps : int, optional
        The step cap [-].
    shifts : list of float, optional
        When given, μ after each step is appended to it [N/m] (the conditioning study of
        benchmarks/bench_linklevel_static_conditioning.py).

    Returns
    -------
    tuple of (ndarray, int)
        The unknowns and the steps taken: at ‖∇Φ‖₂ ≤ tol, or where Φ's round-off hides the
        decrease (:data:`_REJECTIONS` steps refused in a row), or after ``steps``.
    """
    z = np.zeros(2 * phi.N + phi.bal.free.size + 1)
    f, g = phi.value(z), phi.gradient(z)
    mu = -1.0
    for step in range(steps):
        if float(np.linalg.norm(g)) <= tol:
            return z, step
        H = phi.hessian(z)
        pattern = _shift_pattern(H)
        if mu < 0.0:
            mu = _SHIFT_START * float(np.abs(H.diagonal()).max())
        refused = 0
        while True:
            p = _definite_solve(_shifted(H, pattern, mu), g)
            if p is None:  # not positive definite: a larger shift
                mu = 4.0 * mu
                continue
            predicted = -float(g @ p + 0.5 * p @ (H @ p))
            fn = phi.value(z + p)
            ratio = (f - fn) / predicted if predicted > 0.0 else -1.0
            if ratio > 0.25:
                z, f, g = z + p, fn, phi.gradient(z + p)
                if ratio > 0.75:
                    mu *= 0.25
                break
            mu *= 4.0
            refused += 1
            if refused >= _REJECTIONS:
                return z, step
        if shifts is not None:
            shifts.append(mu)
    return z, steps


def _followed(phi: _Tensioned, tol: float
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], float, int, int]:
    """The minimum of Φ followed from a soft contact to the real one: Φ at ``phi``'s pull
    minimised (:func:`_minimum`) with the contact stiffness k_c scaled by each fraction of
    :data:`CONTACT_CONTINUATION` in turn and then at k_c itself, each minimisation from the
    last (a continuation in the contact stiffness, [Nocedal2006, §11.3]; module
    docstring, step 2).

    Parameters
    ----------
    phi : _Tensioned
        The energy at the real k_c with its pull and the state to start from.
    tol : float
        ‖∇Φ‖₂ at which each minimisation stops [N].

    Returns
    -------
    tuple of (ndarray, ndarray, float, int, int)
        Positions [m], angles [rad] and rest length [m] of the minimum, the trust-region
        steps of all the minimisations and those of the last, at k_c [-].
    """
    x, th, rest, steps, nit = phi.x0, phi.th0, phi.rest0, 0, 0
    for fraction in (*CONTACT_CONTINUATION, 1.0):
        spr = phi.tables.spr.copy()
        spr[8] *= fraction
        soft = replace(phi.tables, spr=spr)
        stage = _Tensioned(phi.model, soft,
                           Balance(phi.model, soft, phi.bal.free, phi.N, phi.bal.ref),
                           x, th, rest)
        stage.pull = phi.pull
        z, nit = _minimum(stage, tol)
        steps += nit
        x, th, rest = stage.state(z)
    return x, th, rest, steps, nit


def static_equilibrium(model: LinkLevelModel, geometry: GeometryResult, asm: Assembly,
                       reference_span: int, take_up: str | None = None) -> Equilibrium:
    """Solve the static state at the installed pre-tension (module docstring, steps 2–3).

    Parameters
    ----------
    model : LinkLevelModel
        The parameters (T₀ its ``pretension``).
    geometry : GeometryResult
        The installed contour.
    asm : Assembly
        The chain assembled on it (the placement the solve starts from).
    reference_span : int
        The span whose middle carries T₀ (the span leaving the driver) [-].
    take_up : str or None
        The sprocket moved to install the chain (recorded only).

    Returns
    -------
    Equilibrium
        The solved state and its residual.

    Raises
    ------
    ConvergenceError
        When no static state at T₀ exists (links that cannot carry it) or none is found
        within the module's bounds (one line, with the reason).

    References
    ----------
    [Nocedal2006] (trust-region Newton, §11.3 continuation); [Dennis1996] (Newton's method);
    [Curtis1974] (grouped differences); [Irvine1981, ch. 1] (hydrostatic tension).
    """
    t0 = model.pretension
    rest = model.pitch - t0 / model.link_stiffness
    if not (math.isfinite(t0) and t0 > 0.0 and rest > 0.0):
        raise ConvergenceError(
            f"the link-level static state does not exist: T₀ = {t0:.4g} N on links of "
            f"stiffness {model.link_stiffness:.4g} N/m and pitch {model.pitch:.4g} m leaves "
            f"them a rest length of {rest:.4g} m (must be positive)")
    with threadpool_limits(limits=1):  # the same arithmetic whatever the machine's BLAS
        return _solve(model, geometry, asm, reference_span, take_up, rest)


def _solve(model: LinkLevelModel, geometry: GeometryResult, asm: Assembly,
           reference_span: int, take_up: str | None, rest: float) -> Equilibrium:
    """:func:`static_equilibrium` inside its thread limit."""
    tables = kernel_tables(model)
    n = model.centres.shape[0]
    free = (np.array([i for i in range(n) if i != model.driver], dtype=np.int64)
            if model.torsional is None else np.zeros(0, dtype=np.int64))
    t0 = model.pretension
    x, th = asm.positions.copy(), asm.angles.copy()
    ref = int(span_probes(geometry, x)[reference_span])
    bal = Balance(model, tables, free, x.shape[0], ref)
    phi = _Tensioned(model, tables, bal, x, th, rest)
    iterations, history = 0, []
    for _ in range(_PULL_STEPS):  # the secant on the pull T̄ that puts T₀ on the reference
        x, th, rest, steps, nit = _followed(phi, MINIMUM_TOLERANCE * t0)
        iterations += steps
        error = float(bal(x, th, rest)[-1])
        history.append((phi.pull, error))
        if abs(error) <= TENSION_TOLERANCE * t0:
            break
        if nit >= _TRUST_STEPS and abs(error) <= ACCEPTED_RESIDUAL * t0:
            break  # a minimisation stopped short reads the error with its own scatter
        if len(history) == 1:
            phi.pull -= error  # the reference carries the pull up to small offsets
        else:
            (p0, e0), (p1, e1) = history[-2], history[-1]
            phi.pull = p1 - e1 * (p1 - p0) / (e1 - e0) if e1 != e0 else p1 - e1
        phi.x0, phi.th0, phi.rest0 = x, th, rest  # the next minimisation starts here
    # (a secant left short, its minimisations short of their tolerance, hands the reference
    # tension to the bordered polish, which holds it at T₀ exactly)
    for round_ in range(_POLISH_ROUNDS + 1):  # polish; short of it, minimise again from it
        before = float(np.abs(bal(x, th, rest)).max())
        xs, ths, rests, worst = bal.solve(x, th, rest, FORCE_TOLERANCE * t0)
        if worst < before:  # the polish kept only where it improved on the minimum
            x, th, rest = xs, ths, rests
        r = bal(x, th, rest)
        if float(np.abs(r[:-1]).max()) <= MINIMUM_TOLERANCE * t0 or round_ == _POLISH_ROUNDS:
            break
        if nit >= _TRUST_STEPS:
            break  # the last minimisation stopped at its cap: another would stop there too
        phi.x0, phi.th0, phi.rest0 = x, th, rest
        phi.pull -= float(r[-1])  # one more secant-like step towards T₀ on the reference
        x, th, rest, steps, nit = _followed(phi, MINIMUM_TOLERANCE * t0)
        iterations += steps
    r = bal(x, th, rest)
    left = float(np.abs(r[:-1]).max())
    if max(abs(float(r[-1])), left) > ACCEPTED_RESIDUAL * t0:
        raise ConvergenceError(
            f"the link-level static state was not found: reference span at "
            f"{r[-1] + t0:.4g} N against T₀ = {t0:.4g} N, largest force left {left:.3g} N")
    probes = span_probes(geometry, x)
    return Equilibrium(positions=x, angles=th, rest_length=float(rest),
                       span_tensions=bal.T[probes].copy(), target=t0,
                       reference_span=reference_span,
                       residual_force=float(np.abs(r[:-1]).max()),
                       residual_norm=float(np.linalg.norm(r[:-1])),
                       driver_torque=float(bal.tq[model.driver]), take_up=take_up,
                       iterations=iterations, pulls=len(history),
                       converged=left <= MINIMUM_TOLERANCE * t0
                       and abs(float(r[-1])) <= TENSION_TOLERANCE * t0)
