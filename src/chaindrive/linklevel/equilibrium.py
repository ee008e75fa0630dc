r"""Static equilibrium of the link-level model at the installed pre-tension: the state every
run starts from.

The whole-drive model takes the spans at the pre-tension T₀ of the installed sag
(:func:`chaindrive.dynamics.response.startup_pretension`). The link-level chain holds it only
if it is installed: its rollers seated in the gaps (a roller centred on the pitch circle
clears the seat by r_i − r, some 0.1 mm, and a 0.1–0.4 µm link stretch cannot hold T₀
across that) and its spans stretched or hung to T₀. Three steps build that state.

1. Installed contour (:func:`installed_geometry`). A contour whose slack is not the slack
   of the installed sag — a fixed-centre design with chain slack left over, or a tight
   take-up — is taken up to the installed sag by the project's own take-up
   (:func:`chaindrive.geometry.contour.contour_geometry` with the design's adjustable
   sprocket, else the sprocket the slack span runs onto, and ``[chain] sag`` the installed
   sag ratio): the chain installed as the whole-drive model assumes. The chain is assembled
   on it (:func:`chaindrive.linklevel.assembly.assemble_chain`, with gravity the slack hung
   in a sag).
2. Pseudo-transient continuation ([Kelley1998]): from the assembled chain, the model's own
   kernel steps in pseudo-time with no motor, no loads, the driver held and a
   mass-proportional damping η = 2ω_s (ω_s the first transverse mode of the longest span at
   T₀, so every mode decays at least as e^{−ω_s t}) over 8/ω_s: the rollers drop into their
   seats and the spans take their shape. A secant iteration on the links' common rest
   length ℓ₀ (started from the assembled loop less the length c·θ the seats take on each
   wrap, over N, less T₀/k) brings the reference link — the middle of the span leaving the
   driver — to T₀ within 10⁻³.
3. Newton's method ([Dennis1996, §6.3], backtracking line search; Jacobian by finite
   differences grouped over rollers three links apart, [Curtis1974]) on the static balance
   of every roller (gravity, link springs, roller–tooth contacts) and every free sprocket
   (contact torques; the driver is held, which fixes the free turning of the chain round its
   loop, and the torque it takes is reported), bordered with the reference tension = T₀ in
   the unknown ℓ₀: the residual falls to 10⁻⁶ T₀. Where Newton stops short (a contact
   changing state on the way), the best state so far is settled again and polished again,
   three rounds at most; the best state is kept and its residual reported.

ℓ₀ stays within microns of p − T₀/k: the chain keeps the sprockets' pitch.

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

from chaindrive.errors import ConvergenceError, DesignError, GeometryError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel.kernel import run_kernel, static_forces
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
    "span_probes",
    "static_equilibrium",
]

#: Largest residual force on a roller at the solved equilibrium, as a fraction of T₀ [-].
FORCE_TOLERANCE = 1e-6
_NEWTON_STEPS = 20
#: Rounds of settling and Newton polish at most [-].
_POLISH_ROUNDS = 3
_SECANT_STEPS = 8
#: Decay of the settling: e^{−8} of every mode's amplitude (η/2 = ω_s its rate) [-].
_SETTLE_DECAYS = 8.0
#: The settled reference tension is within this fraction of T₀ [-].
_TENSION_SETTLED = 1e-3


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
        Largest residual force on a roller [N].
    driver_torque : float
        Torque the held driver takes [N·m].
    take_up : str or None
        The sprocket moved to install the chain (None: none).
    """

    positions: NDArray[np.float64]
    angles: NDArray[np.float64]
    rest_length: float
    span_tensions: NDArray[np.float64]
    target: float
    reference_span: int
    residual_force: float
    driver_torque: float
    take_up: str | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI, units in the keys)."""
        return {"pretension_target_n": self.target,
                "reference_span": self.reference_span,
                "span_tension_n": self.span_tensions.tolist(),
                "rest_length_m": self.rest_length,
                "residual_force_n": self.residual_force,
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

    def __call__(self, x: NDArray[np.float64], th: NDArray[np.float64],
                 rest: float) -> NDArray[np.float64]:
        m, t = self.model, self.tables
        self.L0.fill(rest)
        static_forces(x, th, self.L0, m.link_stiffness, m.clearance, m.roller_mass,
                      float(m.gravity[0]), float(m.gravity[1]), t.spr, t.trig, t.gtab, t.reach,
                      self.f, self.tq, self.T, self.tr)
        return np.concatenate([self.f.ravel(), self.tq[self.free] / self.radius,
                               [self.T[self.ref] - m.pretension]])

    def jacobian(self, x: NDArray[np.float64], th: NDArray[np.float64], rest: float,
                 r0: NDArray[np.float64]) -> NDArray[np.float64]:
        """d residual / d (x, R_s θ_s, ℓ₀) by forward differences of step h = 1 nm.

        Parameters
        ----------
        x : ndarray
            (N, 2) roller positions [m].
        th : ndarray
            (n,) sprocket angles [rad].
        rest : float
            Rest length of the links [m].
        r0 : ndarray
            The residual at (x, θ, ℓ₀) [N].

        Returns
        -------
        ndarray
            The Jacobian [N/m].
        """
        N, nf = x.shape[0], self.free.size
        h = 1e-9
        size = 2 * N + nf + 1
        J = np.zeros((size, size))
        self(x, th, rest)
        tr0, t0 = self.tr.copy(), self.T.copy()
        sc = self._sprocket_of(x)
        row_of = {int(s): 2 * N + k for k, s in enumerate(self.free)}
        base = N - N % 3
        groups = [np.arange(g, base, 3) for g in range(3)] + [np.array([r]) for r in
                                                             range(base, N)]
        ref, ref_next = self.ref, (self.ref + 1) % N
        for members in groups:
            for c in range(2):
                xp = x.copy()
                xp[members, c] += h
                d = (self(xp, th, rest) - r0) / h
                dtr, dT = (self.tr - tr0) / h, (self.T - t0) / h
                for r in members:
                    col = 2 * r + c
                    for q in ((r - 1) % N, r, (r + 1) % N):
                        J[2 * q:2 * q + 2, col] = d[2 * q:2 * q + 2]
                    if int(sc[r]) in row_of:
                        J[row_of[int(sc[r])], col] = dtr[r] / self.model.pitch_radii[sc[r]]
                    if r in (ref, ref_next):
                        J[-1, col] = dT[ref]
        for k, s in enumerate(self.free):
            tp = th.copy()
            tp[s] += h / self.radius[k]
            J[:, 2 * N + k] = (self(x, tp, rest) - r0) / h
        J[:, -1] = (self(x, th, rest + h) - r0) / h
        return J

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
            J = self.jacobian(x, th, rest, r)
            try:
                du = np.linalg.solve(J, -r)
            except np.linalg.LinAlgError:  # singular: the least-squares step
                du = np.linalg.lstsq(J, -r, rcond=None)[0]
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


def _settle(model: LinkLevelModel, tables: KernelTables, x: NDArray[np.float64],
            th: NDArray[np.float64], rest: float, dt: float, duration: float, eta: float
            ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pseudo-time steps of the model's own kernel at rest (no motor, no loads, the driver
    held, mass-proportional damping η) from (x, θ) over ``duration`` [s]."""
    N, n = x.shape[0], model.centres.shape[0]
    x, th = x.copy(), th.copy()
    v, w = np.zeros_like(x), np.zeros(n)
    J = model.inertias.copy()
    J[model.driver] = 1e30
    steps = max(1, math.ceil(duration / dt))
    rec = (np.empty((2, N, 2)), np.empty((2, n)), np.empty((2, n)), np.empty((2, N)),
           np.empty((2, N)), np.empty((2, N), dtype=np.int64), np.empty((2, N), dtype=np.int64))
    d = x[:, None, :] - model.centres[None, :, :]
    inside = np.hypot(d[..., 0], d[..., 1]) < tables.reach[None, :]
    cand = np.where(inside.any(axis=1), inside.argmax(axis=1), -1).astype(np.int64)
    cmax = model.roller_mass * model.pitch**2 / 2.0 / (4.0 * dt)
    run_kernel(x, v, th, w, 0.0, steps, dt, steps, model.roller_mass, float(model.gravity[0]),
               float(model.gravity[1]), np.full(N, rest), model.link_stiffness,
               model.link_damping, model.clearance, model.hinge_friction * model.pin_radius,
               cmax, tables.spr, tables.trig, tables.gtab, tables.reach, 1, np.ones(n), J,
               np.zeros((0, 0)), np.zeros((0, 0)), 0, np.zeros(3), model.driver, 1.0, 0,
               np.zeros(n), np.ones(n), 1.0, np.ones(n), *rec, np.zeros(6), cand,
               np.full((N, 4), -1.0), np.zeros((1, 4)), np.zeros(1, dtype=np.int64), eta)
    return x, th


def static_equilibrium(model: LinkLevelModel, geometry: GeometryResult, asm: Assembly,
                       reference_span: int, dt: float, take_up: str | None = None
                       ) -> Equilibrium:
    """Solve the static state at the installed pre-tension (module docstring, step 3).

    Parameters
    ----------
    model : LinkLevelModel
        The parameters (T₀ its ``pretension``).
    geometry : GeometryResult
        The installed contour.
    asm : Assembly
        The chain assembled on it.
    reference_span : int
        The span whose middle carries T₀ (the span leaving the driver) [-].
    dt : float
        Time step of the pseudo-time steps [s].
    take_up : str or None
        The sprocket moved to install the chain (recorded only).

    Returns
    -------
    Equilibrium
        The solved state.

    Raises
    ------
    ConvergenceError
        When the tension cannot be brought to T₀.

    References
    ----------
    [Kelley1998] (pseudo-transient continuation); [Dennis1996] (Newton with line search);
    [Curtis1974] (grouped differences); [Irvine1981, ch. 1] (hydrostatic tension).
    """
    tables = kernel_tables(model)
    n = model.centres.shape[0]
    free = (np.array([i for i in range(n) if i != model.driver], dtype=np.int64)
            if model.torsional is None else np.zeros(0, dtype=np.int64))
    t0 = model.pretension
    tol = FORCE_TOLERANCE * t0
    # the slowest mode the settling must damp: the longest span's first transverse mode
    longest = max(sp.length for sp in geometry.spans)
    omega = math.pi / longest * math.sqrt(t0 * model.pitch / model.roller_mass)
    eta, duration = 2.0 * omega, _SETTLE_DECAYS / omega
    x, th = asm.positions.copy(), asm.angles.copy()
    # ℓ₀: the assembled loop less what the rollers give up dropping into their seats
    # (c = r_i − r on the pitch line over each wrap angle), shared by the N links, at T₀
    lengths = np.hypot(*(np.roll(x, -1, axis=0) - x).T)
    drop = sum(float(model.seating_radii[i] - model.roller_radius) * sg.wrap_angle
               for i, sg in enumerate(geometry.sprockets))
    rest = (float(lengths.sum()) - drop) / x.shape[0] - t0 / model.link_stiffness
    bal = Balance(model, tables, free, x.shape[0], 0)
    history: list[tuple[float, float]] = []
    for _ in range(_SECANT_STEPS):
        x, th = _settle(model, tables, x, th, rest, dt, duration, eta)
        bal.ref = int(span_probes(geometry, x)[reference_span])
        bal(x, th, rest)
        error = float(bal.T[bal.ref]) - t0
        history.append((rest, error))
        if abs(error) <= _TENSION_SETTLED * t0:
            break
        if len(history) == 1:  # a straight chain's stiffness per link: the smallest step
            rest -= error / model.link_stiffness
        else:
            (r0, e0), (r1, e1) = history[-2], history[-1]
            rest = r1 - e1 * (r1 - r0) / (e1 - e0) if e1 != e0 else r1
        duration = 0.5 * _SETTLE_DECAYS / omega
    def merit(r: NDArray[np.float64]) -> float:
        """Largest residual force, infinite unless the reference span is at T₀."""
        return float(np.abs(r[:-1]).max()) if abs(r[-1]) <= _TENSION_SETTLED * t0 \
            else math.inf

    best = (merit(bal(x, th, rest)), x, th, rest)
    for _ in range(_POLISH_ROUNDS):
        xs, ths, rests, worst = bal.solve(x, th, rest, tol)
        score = merit(bal(xs, ths, rests))
        if score < best[0]:
            best = (score, xs, ths, rests)
        if worst <= tol:
            break
        # Newton stopped short (a contact changing state on the way): settle further
        # from the best state and polish again (the bordered Newton restores T₀)
        x, th = _settle(model, tables, best[1], best[2], best[3], dt,
                        _SETTLE_DECAYS / omega, eta)
        rest = best[3]
    _, x, th, rest = best
    res = bal(x, th, rest)
    worst = float(np.abs(res[:-1]).max())
    if abs(res[-1]) > _TENSION_SETTLED * t0:
        raise ConvergenceError(
            f"the link-level static state did not reach the pre-tension: reference span at "
            f"{res[-1] + t0:.4g} N against T₀ = {t0:.4g} N")
    probes = span_probes(geometry, x)
    return Equilibrium(positions=x, angles=th, rest_length=float(rest),
                       span_tensions=bal.T[probes].copy(), target=t0,
                       reference_span=reference_span, residual_force=worst,
                       driver_torque=float(bal.tq[model.driver]), take_up=take_up)
