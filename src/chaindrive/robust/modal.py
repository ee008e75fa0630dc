"""The batched modal path of the robust study: the whole-drive model of one geometric state
under S sets of modal factors (sprocket inertias, chain stiffness, polymer temperature), its
natural frequencies and resonance margins, every sample at once.

The model is the analysis's own (:attr:`chaindrive.analysis.Analysis.drive_model`, the
:class:`~chaindrive.dynamics.torsional.system.TorsionalSystem` of
:mod:`chaindrive.dynamics.model.build`); a sample changes only values, never the topology:

* **inertias** — the node of sprocket i carries J_node + J_i (f_i − 1): its own inertia J_i
  times the factor, what else sits on the node (the motor's rotor) unchanged — as
  :class:`~chaindrive.robust.analysis.PerturbedAnalysis` scales the ring's inertias;
* **chain** — per contour, the span stiffness c·s with c = k_link·p/L times the link factor
  and the Dischinger–Ernst sag factor s = 1/(1 + (1/s₀ − 1)·f) for EA scaled by f
  [Ernst1965], and the wrap stiffness by the ladder recursion K ← k_t + k_link·K/(k_link + K)
  over the teeth in mesh [Naji1983] with the tooth stiffness k_t at the sample's
  temperature; the m contours act in parallel (× m), as the model builds them;
* **frequencies** — the stiffness matrices K_s = Bᵀ diag(k_s) B and the mass matrices of the
  S samples are stacked; the massless coordinates are condensed statically [Guyan1965]
  (exact for the undamped modes); with M_s = L Lᵀ the stacked symmetric problems
  L⁻¹ K_s L⁻ᵀ go to one :func:`numpy.linalg.eigvalsh` call; the lowest r eigenvalues, r the
  rigid-body motions of the model's graph, are the rigid-body modes [Rao2011, ch. 6].

What the path leaves out: train elements (shafts, couplings) keep their stiffness at the
reference temperature (a polymer shaft does not soften with the sample's temperature), and
the geometric variables are those of the state (see :mod:`chaindrive.robust.sampling`).

References
----------
[MultimassChainDrives], [Naji1983], [Ernst1965], [Guyan1965], [Rao2011]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.sparse import csr_matrix

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.catalog import find_material
from chaindrive.dynamics.resonance import working_frequencies
from chaindrive.dynamics.stiffness import tooth_contact_width, tooth_stiffness, wrap_stiffness
from chaindrive.dynamics.torsional.system import TorsionalSystem
from chaindrive.dynamics.transverse import span_transverse_frequencies
from chaindrive.kinematics import tooth_frequency
from chaindrive.robust.perturbation import modulus_factors
from chaindrive.units import TWO_PI

__all__ = ["WORKING_HARMONICS", "StackedState", "batch_chain_stiffness",
           "batch_elastic_frequencies", "batch_system_values", "modal_margins",
           "stacked_frequencies", "stacked_margins", "stacked_state"]

FloatArray = NDArray[np.float64]
#: Harmonics of the tooth frequency among the working frequencies of the modal stage (the
#: default of :func:`chaindrive.dynamics.modes.model_dynamics`, which the analysis calls).
WORKING_HARMONICS = 3


def _tooth_stiffness(state: Analysis, temperature: FloatArray) -> FloatArray:
    """Tooth stiffness k_t (S, n) of every sprocket at the temperatures (S,) [N/m]
    (:func:`chaindrive.dynamics.stiffness.tooth_stiffness`, vectorised)."""
    d = state.drive
    spec = d.chain.spec
    width = tooth_contact_width(spec)
    chain = find_material(spec.material)
    e_chain = chain.youngs_modulus * modulus_factors(chain, temperature)
    out = np.empty((temperature.size, len(d.sprockets)))
    materials = {name: find_material(name) for name in {sp.material for sp in d.sprockets}}
    for i, sp in enumerate(d.sprockets):
        m = materials[sp.material]
        e_sprocket = m.youngs_modulus * modulus_factors(m, temperature)
        out[:, i] = tooth_stiffness(width, e_sprocket, e_chain)  # type: ignore[arg-type]
    return out


def batch_chain_stiffness(state: Analysis, link: FloatArray, temperature: FloatArray
                          ) -> tuple[FloatArray, FloatArray]:
    """Span and wrap stiffnesses (S, n) of one contour of a state under S modal factors.

    The model of :func:`chaindrive.dynamics.parameters.drive_ring_parameters`: the span
    c·s, c = k_link·p/L scaled by the link factor f, s = 1/(1 + (1/s₀ − 1)·f) the
    Dischinger–Ernst sag factor for EA scaled by f [Ernst1965]; the wrap by the ladder
    recursion K ← k_t + k_link·K/(k_link + K) over the teeth in mesh [Naji1983].

    Parameters
    ----------
    state : Analysis
        The analysis of one geometric state (at the reference temperature, factors 1).
    link : ndarray
        (S,) factors on the link stiffness [–] (scatter × chain modulus at temperature).
    temperature : ndarray
        (S,) temperatures of the polymer parts [°C].

    Returns
    -------
    tuple of ndarray
        span stiffness c·s [N/m] (span i from sprocket i), wrap stiffness [N/m] (sprocket i).

    References
    ----------
    [MultimassChainDrives], [Naji1983], [Ernst1965]
    """
    p = state.ring_parameters
    k_link = p.link_stiffness_n_per_m * link[:, None]
    k_t = _tooth_stiffness(state, temperature)
    wrap = np.asarray(wrap_stiffness(k_t, k_link, [g.teeth_in_mesh
                                                   for g in state.geometry.sprockets]))
    chain = p.chain_stiffness_n_per_m[None, :] * link[:, None]
    with np.errstate(divide="ignore"):
        sag = np.where(p.sag_factors > 0, 1.0 / (1.0 + (1.0 / p.sag_factors - 1.0)
                                                 * link[:, None]), 0.0)
    return chain * sag, wrap


def _chain_elements(system: TorsionalSystem, n: int) -> tuple[NDArray[np.intp],
                                                              NDArray[np.intp]]:
    """Indices of the span elements (span i) and wrap elements (sprocket i) of a drive model,
    in the order :func:`chaindrive.dynamics.model.build.drive_model` adds them."""
    kinds = np.array(system.element_kinds)
    spans, wraps = np.flatnonzero(kinds == "span"), np.flatnonzero(kinds == "wrap")
    if spans.size != n or wraps.size != n:
        raise ValueError(f"a drive model of {n} sprockets has {spans.size} spans and "
                         f"{wraps.size} wraps")
    return spans, wraps


@shared_parameters
def batch_system_values(state: Analysis, inertia: FloatArray, link: FloatArray,
                        temperature: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Node inertias and element stiffnesses of a state's whole-drive model under S sets of
    modal factors (module docstring): the values
    :meth:`~chaindrive.dynamics.torsional.system.TorsionalSystem.updated` takes.

    %(params_modal_factors)s

    Returns
    -------
    tuple of ndarray
        J (S, nodes) [kg·m²], k (S, elements) [N·m/rad or N/m].

    References
    ----------
    [MultimassChainDrives], [Naji1983], [Ernst1965]
    """
    model = state.drive_model
    system = model.system
    n = len(model.sprocket_names)
    nodes = np.array([system.node_names.index(x) for x in model.sprocket_names])
    J = np.repeat(system.node_inertia_kg_m2[None, :], inertia.shape[0], axis=0)
    J[:, nodes] += model.ring.inertias_kg_m2[None, :] * (inertia - 1.0)
    span, wrap = batch_chain_stiffness(state, link, temperature)
    spans, wraps = _chain_elements(system, n)
    k = np.repeat(system.element_stiffness[None, :], inertia.shape[0], axis=0)
    k[:, spans] = span * model.contours
    k[:, wraps] = wrap * model.contours
    return J, k


@shared_parameters
def batch_elastic_frequencies(system: TorsionalSystem, node_inertia: FloatArray,
                              element_stiffness: FloatArray) -> FloatArray:
    """Elastic natural frequencies (S, E) [Hz], ascending, of S variants of one torsional
    system (same topology, the values of :meth:`TorsionalSystem.updated`).

    Stacked matrices, static condensation of the massless coordinates [Guyan1965], Cholesky
    M = L Lᵀ and one :func:`numpy.linalg.eigvalsh` of L⁻¹ K L⁻ᵀ; the r lowest eigenvalues (r
    rigid-body motions of the graph) are dropped [Rao2011, ch. 6].

    %(params_system_inertia)s
    element_stiffness : ndarray
        (S, elements) k of every element [N·m/rad or N/m].

    %(elastic_frequencies_returns)s
    """
    return stacked_frequencies(system, node_inertia,
                               _stacked_stiffness(system.element_incidence, element_stiffness))


@shared_parameters
def stacked_frequencies(system: TorsionalSystem, node_inertia: FloatArray,
                        stiffness: FloatArray) -> FloatArray:
    """:func:`batch_elastic_frequencies` of stiffness matrices already stacked.

    %(params_system_inertia)s
    stiffness : ndarray
        (S, N, N) K_s = Bᵀ diag(k_s) B in the system's coordinates [N·m/rad].

    %(elastic_frequencies_returns)s
    """
    K, massed = _condensed(system, stiffness)
    mass = _coordinate_mass(system, node_inertia)[:, massed]
    return _frequencies(system, _mass_normalised(
        K, mass, system.mass_coupling[np.ix_(massed, massed)]))


def _coordinate_mass(system: TorsionalSystem, node_inertia: FloatArray) -> FloatArray:
    """(S, N) diagonal of the mass matrix of every variant [kg·m²]: the system's, with the
    nodes' inertias changed (a node's J enters its coordinate × its factor²)."""
    onto = np.zeros((len(system.node_names), system.size))
    onto[np.arange(onto.shape[0]), system.node_dof] = system.node_factor**2
    return np.asarray(system.mass[None, :] + (node_inertia - system.node_inertia_kg_m2[None, :])
                      @ onto, dtype=np.float64)


def _condensed(system: TorsionalSystem, K: FloatArray) -> tuple[FloatArray, NDArray[np.bool_]]:
    """The stack K (S, N, N) with the massless coordinates condensed statically
    [Guyan1965], and the mask of the massed coordinates it keeps."""
    massed = system.mass > 0.0
    if massed.all():
        return K, massed
    free = ~massed
    K00 = K[:, free][:, :, free]
    K0m = K[:, free][:, :, massed]
    return K[:, massed][:, :, massed] - np.swapaxes(K0m, 1, 2) @ np.linalg.solve(K00, K0m), \
        massed


def _frequencies(system: TorsionalSystem, A: FloatArray) -> FloatArray:
    """Elastic frequencies (S, E) [Hz] of the stacked mass-normalised problems A: one
    :func:`numpy.linalg.eigvalsh`, the r rigid-body eigenvalues dropped [Rao2011, ch. 6]."""
    lam = np.asarray(np.linalg.eigvalsh(A), dtype=np.float64)
    r = int(system.rigid_motions.shape[1])
    return np.sqrt(np.maximum(lam[:, r:], 0.0)).reshape(A.shape[0], -1) / TWO_PI


def _stacked_stiffness(B: FloatArray, k: FloatArray) -> FloatArray:
    """K_s = Bᵀ diag(k_s) B (S, N, N) of the incidence B (E, N) and the stiffnesses k (S, E):
    K_s = Σ_e k_se b_e b_eᵀ, one sparse product (an element touches two coordinates, so
    b_e b_eᵀ has four entries) instead of a dense one per sample."""
    e, i = np.nonzero(B)
    pairs = e[:, None] == e[None, :]  # entries (i, j) of one element
    a, b = np.nonzero(pairs)
    n = B.shape[1]
    T = csr_matrix((B[e[a], i[a]] * B[e[b], i[b]], (i[a] * n + i[b], e[a])),
                   shape=(n * n, B.shape[0]))
    return np.asarray((T @ k.T).T, dtype=np.float64).reshape(k.shape[0], n, n)


def _mass_normalised(K: FloatArray, mass: FloatArray, coupling: FloatArray) -> FloatArray:
    """The stacked symmetric problems A = L⁻¹ K L⁻ᵀ (S, N, N) of K (S, N, N) and the mass
    matrices M = coupling + diag(mass) = L Lᵀ, its lower triangle filled (what
    :func:`numpy.linalg.eigvalsh` reads), the coordinates reordered.

    When the coordinates whose mass differs between the samples (v: the sprockets' inertias)
    carry no mass coupling (the chain's consistent span masses couple only chain nodes, f),
    M = blockdiag(M_ff, diag(m_v)) and, with R = L_ff⁻¹ factorised once and D = diag(m_v)^(−½),

        A = [[R K_ff Rᵀ, ·], [D K_vf Rᵀ, D K_vv D]]

    in the order (f, v) — a similarity, the eigenvalues unchanged — as matrix products over
    the whole stack and scalings, instead of two N×N products per sample. Otherwise one
    Cholesky factor per sample.
    """
    varying = np.any(mass != mass[:1], axis=0)
    split = _split(K, mass[0], coupling, varying)
    if split is None:
        M = coupling[None, :, :] + mass[:, :, None] * np.eye(mass.shape[1])[None]
        W = np.linalg.inv(np.linalg.cholesky(M))
        return np.asarray(W @ K @ np.swapaxes(W, 1, 2), dtype=np.float64)
    return _scaled(split, mass[:, split.v])


@dataclass(frozen=True, slots=True, eq=False)
class _Split:
    """The mass-normalised stack of :func:`_mass_normalised` before the masses of the
    coordinates v enter: ``base`` holds R K_ff Rᵀ, K_vf Rᵀ and K_vv in the order (f, v)."""

    f: NDArray[np.intp]
    v: NDArray[np.intp]
    base: FloatArray
    diagonal: FloatArray


def _split(K: FloatArray, mass: FloatArray, coupling: FloatArray, varying: NDArray[np.bool_]
           ) -> _Split | None:
    """:class:`_Split` of K (S, N, N) with the masses (N,) of the coordinates that do not
    vary (None when a varying coordinate is mass-coupled)."""
    coupled = np.any(coupling - np.diag(np.diag(coupling)) != 0.0, axis=1)
    if np.any(varying & coupled):
        return None
    S = K.shape[0]
    f, v = np.flatnonzero(~varying), np.flatnonzero(varying)
    F = f.size
    R = np.linalg.inv(np.linalg.cholesky(coupling[np.ix_(f, f)] + np.diag(mass[f])))
    A = np.zeros_like(K)  # the upper triangle is not read
    # X_s = K_ff,s Rᵀ, then R K_ff,s Rᵀ = X_sᵀ Rᵀ (K_ff symmetric): two products of the stack
    X = (K[:, f[:, None], f].reshape(S * F, F) @ R.T).reshape(S, F, F)
    A[:, :F, :F] = (np.swapaxes(X, 1, 2).reshape(S * F, F) @ R.T).reshape(S, F, F)
    A[:, F:, :F] = (K[:, v[:, None], f].reshape(S * v.size, F) @ R.T).reshape(S, v.size, F)
    A[:, F:, F:] = K[:, v[:, None], v]
    return _Split(f, v, A, np.diag(coupling)[v])


def _scaled(split: _Split, mass_v: FloatArray) -> FloatArray:
    """The stack A of a :class:`_Split` with the masses (S, v) of its coordinates v:
    D = diag(m_v)^(−½) scales the rows (and the columns) of v."""
    F = split.f.size
    d = 1.0 / np.sqrt(mass_v + split.diagonal)
    A = split.base.copy()
    A[:, F:, :F] *= d[:, :, None]
    A[:, F:, F:] *= d[:, :, None]
    A[:, F:, F:] *= d[:, None, :]
    return A


def _excitation(state: Analysis) -> tuple[FloatArray, FloatArray, float]:
    """Working frequencies (W,) [Hz], the spans' first transverse frequencies (n,) [Hz] and
    the tooth frequency [Hz] of a state: what its modal stage compares the natural
    frequencies with (:func:`chaindrive.dynamics.modes.model_dynamics`), from the same
    functions, without the stage's own modes and Campbell data."""
    d = state.drive
    w = d.driver.speed
    if w is None:
        return np.array([]), np.array([]), math.nan
    spec = d.chain.spec
    working = working_frequencies(w, d.driver.teeth, [s.teeth for s in d.sprockets],
                                  [s.name for s in d.sprockets], WORKING_HARMONICS)
    tensions = state.ring_parameters.span_tensions_n
    first = np.array([])
    if tensions is not None:
        v = d.driver.teeth * spec.pitch * w / TWO_PI
        first = span_transverse_frequencies([sp.length for sp in state.geometry.spans],
                                            tensions, spec.mass_per_length, v, modes=1)[:, 0]
    return (np.array([x.frequency for x in working]), first,
            float(tooth_frequency(d.driver.teeth, w)))


def _nearest(elastic: FloatArray, working: FloatArray) -> FloatArray:
    """The natural frequency (S, W) [Hz] of each row of ``elastic`` (S, E), ascending, nearest
    to each working frequency (W,) [Hz] (the lower one on a tie): one sorted search over
    the rows laid end to end (row s shifted by s·span, the rows kept apart), not an S×W×E
    table of distances."""
    S, E = elastic.shape
    span = 2.0 * (max(float(elastic.max()), float(working.max())) + 1.0)
    offset = np.arange(S)[:, None] * span
    above = np.searchsorted((elastic + offset).ravel(), (working[None, :] + offset).ravel()
                            ).reshape(S, -1) - np.arange(S)[:, None] * E
    hi = np.minimum(above, E - 1)
    lo = np.maximum(above - 1, 0)
    f_hi = np.take_along_axis(elastic, hi, axis=1)
    f_lo = np.take_along_axis(elastic, lo, axis=1)
    return np.where(np.abs(working - f_hi) < np.abs(working - f_lo), f_hi, f_lo)


def modal_margins(state: Analysis, elastic: FloatArray) -> tuple[FloatArray, FloatArray]:
    """First elastic frequency f₁ [Hz] and resonance margin [%] of S variants of a state's
    model, against its working frequencies and its spans' parametric resonance (the rule of
    :func:`chaindrive.dynamics.checks.resonance_check`).

    Parameters
    ----------
    state : Analysis
        The geometric state (working frequencies, span transverse frequencies).
    elastic : ndarray
        (S, E) elastic natural frequencies [Hz] (:func:`batch_elastic_frequencies`).

    Returns
    -------
    tuple of ndarray
        f₁ (S,) [Hz] (nan without an elastic mode), margin (S,) [%] (inf without working
        frequencies).

    References
    ----------
    [MultimassChainDrives, §3.2], [API684], [Bolotin1964]
    """
    return _margins(_excitation(state), elastic)


def _margins(excitation: tuple[FloatArray, FloatArray, float], elastic: FloatArray
             ) -> tuple[FloatArray, FloatArray]:
    """:func:`modal_margins` of a state's excitation (:func:`_excitation`)."""
    S = elastic.shape[0]
    f1 = elastic[:, 0] if elastic.shape[1] else np.full(S, math.nan)
    working, transverse, fz = excitation
    margin = np.full(S, np.inf)
    if working.size and elastic.shape[1]:
        nearest = _nearest(elastic, working)
        margin = np.min(np.abs(working[None, :] - nearest) / nearest * 100.0, axis=1)
    f_span = transverse[transverse > 0]
    if f_span.size:
        margin = np.minimum(margin, float(np.min(np.abs(fz - 2 * f_span) / (2 * f_span)))
                            * 100.0)
    return f1, margin


# ---------------------------------------------------------------------- a state, stacked once
@dataclass(frozen=True, slots=True, eq=False)
class StackedState:
    """One geometric state of a drive under the S samples of its modal variables, stacked
    once: what does not change when only inertias are added on the sprockets' shafts (the
    flywheels an optimiser varies) — the stiffness matrices condensed, their mass
    normalisation but for the sprockets' coordinates, the inertia factors, the working and
    transverse frequencies (:func:`stacked_state`).

    Parameters
    ----------
    state : Analysis
        The geometric state (its model's topology and values).
    inertia_factors : ndarray
        (S, n) factors on the sprockets' own inertias [–].
    node_inertia : ndarray
        (S, nodes) J of every node with the factors, no inertia added [kg·m²].
    stiffness : ndarray | None
        (S, N, N) stacked stiffness matrices [N·m/rad], the massless coordinates condensed
        when ``massed`` is given, else as assembled (None: ``split`` holds them).
    massed : ndarray | None
        Mask of the massed coordinates kept in ``stiffness`` [-] (None: a sprocket sits on
        a massless coordinate, every call condenses anew).
    split : _Split | None
        The mass normalisation of ``stiffness`` with the sprockets' (and every varying)
        coordinate left to scale (None: a varying coordinate is mass-coupled).
    sprocket_nodes : ndarray
        (n,) node index of every sprocket [-].
    excitation : tuple
        Working frequencies (W,) [Hz], the spans' first transverse frequencies (n,) [Hz],
        the tooth frequency [Hz].
    """

    state: Analysis
    inertia_factors: FloatArray
    node_inertia: FloatArray
    stiffness: FloatArray | None
    massed: NDArray[np.bool_] | None
    split: _Split | None
    sprocket_nodes: NDArray[np.intp]
    excitation: tuple[FloatArray, FloatArray, float]


@shared_parameters
def stacked_state(state: Analysis, inertia: FloatArray, link: FloatArray,
                  temperature: FloatArray) -> StackedState:
    """A state's model under S sets of modal factors, stacked once
    (:func:`batch_system_values`, the stiffness matrices K_s = Bᵀ diag(k_s) B condensed
    [Guyan1965] and normalised by the masses that no added inertia changes, the factor
    R = L_ff⁻¹ of :func:`_mass_normalised`).

    %(params_modal_factors)s

    Returns
    -------
    StackedState

    References
    ----------
    [MultimassChainDrives], [Naji1983], [Ernst1965], [Guyan1965]
    """
    model = state.drive_model
    system = model.system
    J, k = batch_system_values(state, inertia, link, temperature)
    nodes = np.array([system.node_names.index(x) for x in model.sprocket_names], dtype=np.intp)
    K = _stacked_stiffness(system.element_incidence, k)
    sprockets = np.zeros(system.size, dtype=bool)
    sprockets[system.node_dof[nodes]] = True
    massed: NDArray[np.bool_] | None = system.mass > 0.0
    split = None
    if np.all(system.mass[sprockets] > 0.0):
        K, massed = _condensed(system, K)
        mass = _coordinate_mass(system, J)[:, massed]
        varying = np.any(mass != mass[:1], axis=0) | sprockets[massed]
        split = _split(K, mass[0], system.mass_coupling[np.ix_(massed, massed)], varying)
    else:
        massed = None
    return StackedState(state, np.asarray(inertia, dtype=float), J,
                        None if split is not None else K, massed, split, nodes,
                        _excitation(state))


def stacked_margins(stacked: StackedState, added_inertia: FloatArray | None = None
                    ) -> tuple[FloatArray, FloatArray]:
    """f₁ [Hz] and resonance margin [%] of the S samples of a stacked state with inertias
    ΔJ added on the sprockets' shafts (:func:`modal_margins`).

    A flywheel ΔJ_i is part of sprocket i's own inertia (the inertia factor f_i scales the
    sum, as :func:`chaindrive.dynamics.parameters.drive_ring_parameters` adds it): the node of
    sprocket i carries J_node + J_i (f_i − 1) + ΔJ_i f_i, nothing else changes.

    Parameters
    ----------
    stacked : StackedState
        The state (:func:`stacked_state`, of the design without those inertias).
    added_inertia : ndarray | None
        (n,) inertia added on every sprocket's shaft [kg·m²] (None: none).

    Returns
    -------
    tuple of ndarray
        f₁ (S,) [Hz], margin (S,) [%].

    References
    ----------
    [MultimassChainDrives, §3.1, §3.2], [Guyan1965]
    """
    J = stacked.node_inertia
    if added_inertia is not None and np.any(added_inertia):
        J = J.copy()
        J[:, stacked.sprocket_nodes] += (np.asarray(added_inertia, dtype=float)[None, :]
                                         * stacked.inertia_factors)
    system = stacked.state.drive_model.system
    if stacked.split is not None and stacked.massed is not None:
        mass = _coordinate_mass(system, J)[:, stacked.massed]
        return _margins(stacked.excitation,
                        _frequencies(system, _scaled(stacked.split, mass[:, stacked.split.v])))
    K = stacked.stiffness
    if K is None:
        raise ValueError("a stacked state without its split keeps its stiffness matrices")
    if stacked.massed is None:
        elastic = stacked_frequencies(system, J, K)
    else:
        massed = stacked.massed
        elastic = _frequencies(system, _mass_normalised(
            K, _coordinate_mass(system, J)[:, massed],
            system.mass_coupling[np.ix_(massed, massed)]))
    return _margins(stacked.excitation, elastic)
