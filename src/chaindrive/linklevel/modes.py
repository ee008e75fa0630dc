r"""Natural frequencies of the link-level model from its linearisation about a static state.

About a static equilibrium (:mod:`chaindrive.linklevel.equilibrium`: at rest at T₀, or
loaded) the undamped model's small motions obey M ü + K u = 0, u the roller displacements
(2N) and the sprocket turns as arc lengths R_s θ_s [m]; M = diag(m, …, J_s/R_s², …),
K = −∂f/∂u the tangent stiffness of the static balance (links with their geometric stiffness
T/ℓ, contacts, gravity's none), by grouped finite differences, symmetrised. The generalised
eigenproblem K φ = ω² M φ is solved densely ([Golub2013, §8.7], the symmetric-definite
problem), every sprocket free: the chain turning round its loop is the (near-)rigid mode
below 1 Hz, left out. As the static solve, it runs with the linear algebra held to one
thread (``threadpoolctl``), so that its result does not depend on the machine's BLAS
threads (the command line runs on one already; on a two-core machine shared with other
work two BLAS threads made the dense eigenproblem of the seed drive 5–50 times slower).

**Where each mode's energy is.** Kinetic: in the rollers' motion along their links and the
sprockets' turning (``longitudinal_fraction``) or across the links (the rest). A mode with
more than half its kinetic energy along the chain belongs to the *longitudinal–torsional*
family — the motion the whole-drive model (sprocket inertias, span and wrap springs) has;
the others are *transverse* span modes, which it has not (it gives them by the string
formula, :mod:`chaindrive.dynamics.transverse`). Of the modes along the chain, those with
most of their strain energy in the contacts (below) are *seat* modes: a sprocket rocking on
the rollers seated in its gaps, whose seating arc (radius r_i > r, ISO 606) holds a roller
sideways only by the load pressing it in — the whole-drive model's wrap spring (the teeth's
bending stiffness [ISO6336-1] in a ladder [Naji1983]) has no such softness.

Strain (``strain_shares``): the tangent stiffness of a link of stiffness k, tension T,
length ℓ and direction t is k t tᵀ + (T/ℓ)(I − t tᵀ) on the relative displacement Δu of its
rollers, so a mode's strain energy uᵀKu splits into the links' stretch k (t·Δu)², the
tension's (T/ℓ)|Δu − t(t·Δu)|² (the string and sag stiffness: what turns a span's end
displacement into sag change) and the contacts' (the remainder) [Irvine1981, ch. 2] — the
same three parts as the whole-drive model's span spring (links, their Dischinger–Ernst sag
factor [Ernst1965]) and wrap spring (teeth, [Naji1983]).

**Loaded state** (``loaded=True``): the driven sprockets carry their moments of resistance
(their power shares of P at the nominal speeds, as the run's), the driver is held and the
chain keeps its length (the installed contour's ℓ₀: the slack spans give up some of their
T₀ as the tight ones stretch, as in the run): from the state at rest, dynamic relaxation
under the full loads [Barnes1999] (damped pseudo-time steps, as the state at rest is
settled), then Newton's method on the static balance [Dennis1996]; accepted when the
largest residual force is below 10⁻³ of the largest F_t = M/R. The modes are then those of
quasi-static running (no centrifugal tension, no polygonal motion).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh
from threadpoolctl import threadpool_limits

from chaindrive.errors import ConvergenceError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel.equilibrium import (
    FORCE_TOLERANCE,
    Balance,
    Equilibrium,
    installed_geometry,
    kernel_tables,
    span_probes,
)
from chaindrive.linklevel.model import build_model
from chaindrive.linklevel.simulate import COURANT, equilibrium_state
from chaindrive.strength.loads import power_shares
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.model import LinkLevelModel
    from chaindrive.model import Drive

__all__ = ["CONTACT", "LONGITUDINAL", "STRAIN_PARTS", "LinearModes", "linear_modes",
           "rest_and_loaded_modes"]

#: A mode counts as longitudinal when more than this fraction of its kinetic energy is in
#: motion along the chain and sprocket turning [-].
LONGITUDINAL = 0.5
#: A mode along the chain is a seat mode when more than this fraction of its strain energy
#: is in the roller–tooth contacts [-].
CONTACT = 0.5
_RIGID_HZ = 1.0
#: Residual force accepted in the loaded state, as a fraction of the largest F_t = M/R [-].
_LOADED_TOLERANCE = 1e-3
#: Dynamic relaxation of the loaded state: its duration in decay times 1/ω of the slowest
#: mode damped [-].
_RELAX_DECAYS = 16.0
_HALF_WAVES = 8
#: The parts of a mode's strain energy (``LinearModes.strain_shares`` columns).
STRAIN_PARTS = ("links", "tension", "contacts")


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
    strain_shares : ndarray
        (k, 3) each mode's strain energy in the links' stretch, the tension (string and sag)
        and the contacts (:data:`STRAIN_PARTS`), rows summing to 1 [-].
    sprocket_turns : ndarray
        (n, k) each mode's sprocket turns θ_s times the sprocket's running sense (so that
        the chain's travel is positive on every sprocket), mass-normalised [rad·kg^-1/2].
    span : ndarray of int
        (k,) the span holding most of a transverse mode's kinetic energy (−1 for the
        longitudinal family) [-].
    half_waves : ndarray of int
        (k,) half-waves n of a transverse mode along that span (0 for the longitudinal
        family) [-].
    span_tensions_n : ndarray
        (spans,) the static state's tension at each span's middle [N].
    span_lengths_m : ndarray
        (spans,) the installed contour's span lengths [m].
    loaded : bool
        True: about the loaded static state; False: at rest at T₀.
    """

    frequencies_hz: NDArray[np.float64]
    longitudinal_fraction: NDArray[np.float64]
    first_longitudinal_hz: float | None
    reference_frequency_hz: float
    strain_shares: NDArray[np.float64]
    sprocket_turns: NDArray[np.float64]
    span: NDArray[np.int64]
    half_waves: NDArray[np.int64]
    span_tensions_n: NDArray[np.float64]
    span_lengths_m: NDArray[np.float64]
    loaded: bool = False

    @property
    def longitudinal(self) -> NDArray[np.bool_]:
        """(k,) True for a mode moving along the chain (``longitudinal_fraction`` above
        :data:`LONGITUDINAL`): the longitudinal–torsional and the seat families."""
        return np.asarray(self.longitudinal_fraction > LONGITUDINAL)

    @property
    def first_longitudinal(self) -> int | None:
        """Index of the first mode along the chain (of :attr:`first_longitudinal_hz`)."""
        idx = np.flatnonzero(self.longitudinal)
        return int(idx[0]) if idx.size else None

    @property
    def family(self) -> tuple[str, ...]:
        """(k,) each mode's family: ``"transverse"`` (most kinetic energy across the links),
        ``"seat"`` (along the chain, most strain energy in the contacts: sprockets rocking
        on their seated rollers) or ``"longitudinal_torsional"`` (along the chain, most
        strain energy in the links' stretch and tension: the whole-drive model's family)."""
        return tuple("transverse" if not a else "seat" if c > CONTACT else
                     "longitudinal_torsional"
                     for a, c in zip(self.longitudinal, self.strain_shares[:, 2], strict=True))

    def first_of(self, family: str) -> int | None:
        """Index of the lowest mode of ``family`` (None: none).

        Parameters
        ----------
        family : str
            ``"transverse"``, ``"seat"`` or ``"longitudinal_torsional"`` (:attr:`family`).

        Returns
        -------
        int or None
            The mode's index [-].
        """
        return next((i for i, f in enumerate(self.family) if f == family), None)

    def to_dict(self, count: int | None = None) -> dict[str, Any]:
        """JSON-ready (SI, units in the keys).

        Parameters
        ----------
        count : int or None
            The lowest modes written [-] (None: all).

        Returns
        -------
        dict
            The record.
        """
        k = slice(None, count)
        return {"state": "loaded" if self.loaded else "rest",
                "frequencies_hz": self.frequencies_hz[k].tolist(),
                "longitudinal_fraction": self.longitudinal_fraction[k].tolist(),
                "family": list(self.family[k]),
                "strain_share": {p: self.strain_shares[k, j].tolist()
                                 for j, p in enumerate(STRAIN_PARTS)},
                "span": self.span[k].tolist(), "half_waves": self.half_waves[k].tolist(),
                "span_tension_n": self.span_tensions_n.tolist(),
                "first_longitudinal_hz": self.first_longitudinal_hz,
                "reference_frequency_hz": self.reference_frequency_hz}


class _LoadedBalance(Balance):
    """The static balance with the moments of resistance ``fraction``·M_s on the free
    sprockets, against their running senses, and the reference link held at ``target``."""

    def __init__(self, model: LinkLevelModel, free: NDArray[np.int64], N: int, ref: int,
                 moments: NDArray[np.float64]) -> None:
        super().__init__(model, kernel_tables(model), free, N, ref)
        self.load = (model.turn * moments)[free] / self.radius
        self.fraction = 0.0
        self.target = model.pretension

    def __call__(self, x: NDArray[np.float64], th: NDArray[np.float64],
                 rest: float) -> NDArray[np.float64]:
        r = Balance.__call__(self, x, th, rest)
        r[2 * x.shape[0]:-1] -= self.fraction * self.load
        r[-1] += self.model.pretension - self.target
        return r


def _relaxed(bal: _LoadedBalance, model: LinkLevelModel, x: NDArray[np.float64],
             th: NDArray[np.float64], rest: float, omega: float, dt: float
             ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Dynamic relaxation of the loaded balance [Barnes1999]: the rollers and free sprockets
    stepped in pseudo-time under a mass-proportional damping η = 2ω (ω the slowest mode to
    damp) by the semi-implicit Euler step of the kernel, over :data:`_RELAX_DECAYS`/ω, the
    links' rest length ℓ₀ kept."""
    N = x.shape[0]
    radius = bal.radius
    mass = np.concatenate([np.full(2 * N, model.roller_mass),
                           (model.inertias[bal.free] / radius**2)])
    u = np.concatenate([x.ravel(), np.zeros(bal.free.size)])
    v = np.zeros_like(u)
    th0 = th.copy()
    damp = 1.0 / (1.0 + dt * 2.0 * omega)
    for _ in range(math.ceil(_RELAX_DECAYS / omega / dt)):
        ts = th0.copy()
        ts[bal.free] += u[2 * N:] / radius
        r = bal(u[:2 * N].reshape(N, 2), ts, rest)
        v = (v + dt * r[:-1] / mass) * damp
        u += dt * v
    ts = th0.copy()
    ts[bal.free] += u[2 * N:] / radius
    return u[:2 * N].reshape(N, 2).copy(), ts


def _loaded_state(drive: Drive, model: LinkLevelModel, geometry: GeometryResult,
                  eq: Equilibrium) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """(x, θ, ℓ₀) of the loaded static state (module docstring), from the state at rest:
    dynamic relaxation under the full loads with the chain's length kept, then Newton's
    method with the reference span held at the tension the relaxation left it."""
    n = model.centres.shape[0]
    x, th, rest = eq.positions, eq.angles[:n].copy(), eq.rest_length
    ref = int(span_probes(geometry, x)[eq.reference_span])
    assert drive.power is not None and drive.driver.speed is not None
    z = np.array([s.teeth for s in drive.sprockets], dtype=float)
    moments = np.asarray(power_shares(drive), dtype=float) * drive.power / (
        drive.driver.speed * drive.driver.teeth / z)
    moments[model.driver] = 0.0
    free = np.array([i for i in range(n) if i != model.driver], dtype=np.int64)
    bal = _LoadedBalance(model, free, x.shape[0], ref, moments)
    bal.fraction = 1.0
    longest = max(sp.length for sp in geometry.spans)
    omega = math.pi / longest * math.sqrt(model.pretension * model.pitch / model.roller_mass)
    dt = COURANT * 2.0 / (2.0 * math.pi * model.highest_frequency_hz)
    x, th = _relaxed(bal, model, x, th, rest, omega, dt)
    relaxed = bal(x, th, rest)
    bal.target = float(bal.T[ref])
    xs, ts, rs, _ = bal.solve(x, th, rest, FORCE_TOLERANCE * model.pretension)
    polished = bal(xs, ts, rs)
    worst, best = float(np.abs(relaxed[:-1]).max()), float(np.abs(polished[:-1]).max())
    if best < worst:  # Newton's polish, when it helped
        x, th, rest, worst = xs, ts, rs, best
    accept = _LOADED_TOLERANCE * float(np.max(moments / model.pitch_radii))
    if not worst <= accept:
        raise ConvergenceError(f"the loaded link-level static state did not settle: largest "
                               f"residual {worst:.3g} N against {accept:.3g} N")
    return x, th, rest


def _span_members(geometry: GeometryResult, x: NDArray[np.float64],
                  outside: NDArray[np.bool_]) -> NDArray[np.int64]:
    """(N,) the span each roller outside every sprocket's reach lies on (−1: on a wrap)."""
    dist = np.empty((x.shape[0], len(geometry.spans)))
    for k, sp in enumerate(geometry.spans):
        a, b = np.array(sp.start_point), np.array(sp.end_point)
        ab = b - a
        s = np.clip((x - a) @ ab / float(ab @ ab), 0.0, 1.0)
        dist[:, k] = np.hypot(*(x - a - s[:, None] * ab).T)
    return np.where(outside, dist.argmin(axis=1), -1).astype(np.int64)


def _half_waves(geometry: GeometryResult, x: NDArray[np.float64], members: NDArray[np.int64],
                modes: NDArray[np.float64], span: NDArray[np.int64]) -> NDArray[np.int64]:
    """(k,) half-waves of each transverse mode along its span: the n of the sine
    sin(nπ s/L) its transverse displacements project on most (0 where ``span`` is −1)."""
    out = np.zeros(span.size, dtype=np.int64)
    N = x.shape[0]
    u = modes[:2 * N].reshape(N, 2, -1)
    for m in np.flatnonzero(span >= 0):
        sp = geometry.spans[int(span[m])]
        on = members == span[m]
        a = np.array(sp.start_point)
        d = np.array(sp.direction)
        s = (x[on] - a) @ d / sp.length
        w = u[on, :, m] @ np.array([-d[1], d[0]])
        basis = np.sin(np.pi * np.outer(s, np.arange(1, _HALF_WAVES + 1)))
        proj = (basis.T @ w) ** 2 / np.maximum((basis**2).sum(axis=0), 1e-30)
        out[m] = int(np.argmax(proj)) + 1
    return out


def linear_modes(drive: Drive, *, geometry: GeometryResult | None = None,
                 model: LinkLevelModel | None = None, count: int = 100000,
                 loaded: bool = False) -> LinearModes:
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
    loaded : bool
        About the loaded static state (module docstring; the drive needs a power and a
        driver speed) instead of the state at rest.

    Returns
    -------
    LinearModes
        Frequencies, the energy of each mode by where it is, the first longitudinal mode.

    Raises
    ------
    ConvergenceError
        ``loaded`` and the loaded state did not settle.

    References
    ----------
    [Golub2013, §8.7] (symmetric-definite eigenproblem); [Irvine1981, ch. 2] (the tension's
    stiffness of a span); [Dennis1996] (the loaded state's Newton iteration).
    """
    with threadpool_limits(limits=1):  # the same arithmetic whatever the machine's BLAS
        geometry, model, eq = _rest_state(drive, geometry, model)
        if not loaded:
            return _modes_about(model, geometry, eq.positions, eq.angles, eq.rest_length,
                                count, loaded=False)
        x, th, rest = _loaded_state(drive, model, geometry, eq)
        return _modes_about(model, geometry, x, th, rest, count, loaded=True)


def rest_and_loaded_modes(drive: Drive, *, geometry: GeometryResult | None = None,
                          count: int = 100000) -> tuple[LinearModes, LinearModes | None]:
    """The modes about the state at rest and about the loaded state (:func:`linear_modes`),
    the static state at rest solved once; None for the loaded ones when that state is not
    reached.

    Parameters
    ----------
    drive : Drive
        The drive (with a power and a driver speed).
    geometry : GeometryResult or None
        Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).
    count : int
        Number of modes kept [-].

    Returns
    -------
    tuple of (LinearModes, LinearModes or None)
        At rest and loaded.
    """
    with threadpool_limits(limits=1):  # the same arithmetic whatever the machine's BLAS
        geometry, model, eq = _rest_state(drive, geometry, None)
        rest = _modes_about(model, geometry, eq.positions, eq.angles, eq.rest_length, count,
                            loaded=False)
        try:
            x, th, length = _loaded_state(drive, model, geometry, eq)
        except ConvergenceError:
            return rest, None
        return rest, _modes_about(model, geometry, x, th, length, count, loaded=True)


def _rest_state(drive: Drive, geometry: GeometryResult | None, model: LinkLevelModel | None
                ) -> tuple[GeometryResult, LinkLevelModel, Equilibrium]:
    """(installed contour, model, static state at rest at T₀)."""
    geometry, take_up = installed_geometry(drive, geometry or contour_geometry(drive))
    if model is None:
        model = build_model(drive, geometry)
    dt = COURANT * 2.0 / (2.0 * math.pi * model.highest_frequency_hz)
    _, eq = equilibrium_state(drive, geometry, model, dt, take_up)
    return geometry, model, eq


def _modes_about(model: LinkLevelModel, geometry: GeometryResult, x: NDArray[np.float64],
                 angles: NDArray[np.float64], rest: float, count: int, *, loaded: bool
                 ) -> LinearModes:
    """The modes about the static state (x, θ, ℓ₀) (module docstring)."""
    n = model.centres.shape[0]
    th = angles[:n].copy()
    N = x.shape[0]
    probes = span_probes(geometry, x)
    bal = Balance(model, kernel_tables(model), np.arange(n, dtype=np.int64), N, 0)
    r0 = bal(x, th, rest)
    tension = bal.T.copy()
    K = -bal.jacobian(x, th, rest, r0)[:-1, :-1]
    K = 0.5 * (K + K.T)
    mass = np.concatenate([np.full(2 * N, model.roller_mass),
                           model.inertias / model.pitch_radii**2])
    scale = 1.0 / np.sqrt(mass)
    lam, vec = eigh(K * scale[:, None] * scale[None, :])
    freq = np.sqrt(np.clip(lam, 0.0, None)) / TWO_PI
    keep = np.flatnonzero(freq > _RIGID_HZ)[:count]
    modes = vec[:, keep] * scale[:, None]  # displacements u = M^{-1/2} φ
    d = np.roll(x, -1, axis=0) - x
    length = np.hypot(d[:, 0], d[:, 1])
    t = d / length[:, None]  # each roller's leading link direction
    u = modes[:2 * N].reshape(N, 2, -1)
    along = np.einsum("rk,rkm->rm", t, u)
    ke_total = np.einsum("i,im->m", mass, modes**2)
    ke_sprockets = np.einsum("i,im->m", mass[2 * N:], modes[2 * N:] ** 2)
    fraction = (model.roller_mass * (along**2).sum(axis=0) + ke_sprockets) / ke_total
    first = next((float(f) for f, a in zip(freq[keep], fraction, strict=True)
                  if a > LONGITUDINAL), None)
    # strain energy: links' stretch, tension (string/sag), contacts (the remainder)
    du = np.roll(u, -1, axis=0) - u
    stretch = np.einsum("rk,rkm->rm", t, du)
    across = du - t[:, :, None] * stretch[:, None, :]
    k_link = np.where(tension > 0.0, model.link_stiffness, 0.0)
    links = np.einsum("r,rm->m", k_link, stretch**2)
    strings = np.einsum("r,rkm->m", tension / length, across**2)
    total = np.einsum("im,im->m", modes, K @ modes)
    shares = np.column_stack([links, strings, total - links - strings]) / total[:, None]
    # transverse modes: the span holding most of their motion across the links
    outside = bal._sprocket_of(x) < 0
    members = _span_members(geometry, x, outside)
    ke_across = model.roller_mass * ((u**2).sum(axis=1) - along**2)
    spans = len(geometry.spans)
    per_span = np.stack([ke_across[members == k].sum(axis=0) for k in range(spans)])
    span = np.where(fraction > LONGITUDINAL, -1, per_span.argmax(axis=0)).astype(np.int64)
    half = _half_waves(geometry, x, members, modes, span)
    turns = modes[2 * N:] / model.pitch_radii[:, None] * model.turn[:, None]
    return LinearModes(freq[keep], fraction, first, model.reference_frequency_hz,
                       shares, turns, span, half, tension[probes].copy(),
                       np.array([sp.length for sp in geometry.spans]), loaded)
