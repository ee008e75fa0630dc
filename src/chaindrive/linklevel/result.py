"""Result of a link-level run and the quantities read from it (SI units).

Span force: the tension of the link nearest the middle of the span's nominal line (the
tangent of :func:`chaindrive.geometry.contour.contour_geometry`); transverse motion: that
link's midpoint offset from the line (positive to the left of the chain travel). Steady
span dynamic load F_D,i = max |F_i(t) − F̄_i| over the closing ``steady_window`` of the run,
and K_D = 1 + F_D/F_t with F_D the RMS over the spans
(:func:`chaindrive.dynamics.frequency.quality.coefficient_of_dynamics`, [MultimassChainDrives]) — the
ring model's definitions, so both sit side by side. Tooth loads: the contact force of each
roller in mesh, binned by its place on the wrap (tooth 0 at the arrival of the chain).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.dynamics.frequency.quality import coefficient_of_dynamics
from chaindrive.kinematics import mean_chain_speed
from chaindrive.linklevel.kernel import (
    E_CONTACT,
    E_HINGE,
    E_LINK,
    E_LOAD,
    E_MOTOR,
    E_TORSION,
    penetration,
)
from chaindrive.strength.loads import peripheral_force
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.linklevel.model import LinkLevelModel
    from chaindrive.model import Drive

__all__ = ["CONVERGENCE_TOLERANCE", "LinkLevelResult", "drift_fraction", "energy_residual",
           "state_energy", "step_convergence"]



def state_energy(model: LinkLevelModel, x: NDArray[np.float64], v: NDArray[np.float64],
                 th: NDArray[np.float64], w: NDArray[np.float64], L0: NDArray[np.float64],
                 spr: NDArray[np.float64], J: NDArray[np.float64],
                 K: NDArray[np.float64], th0: NDArray[np.float64]) -> dict[str, float]:
    """Kinetic, elastic (links, contacts, torsional system on the turns θ − θ₀ since the start)
    and gravity energy [J] of a state.

    Parameters
    ----------
    model : LinkLevelModel
        The parameters.
    x : ndarray
        (N, 2) roller positions [m].
    v : ndarray
        (N, 2) roller velocities [m/s].
    th : ndarray
        (D,) rotational coordinates [rad].
    w : ndarray
        (D,) their speeds [rad/s].
    L0 : ndarray
        (N,) link rest lengths [m].
    spr : ndarray
        (12, n) the kernel's table of sprocket data (centre [m], teeth, pitch, roller,
        seating and tip radii [m], seating half-angle [rad], contact stiffness [N/m] and
        damping [N·s/m], gap angle [rad], half-chord [m]).
    J : ndarray
        (D,) moments of inertia of the rotational coordinates [kg·m²].
    K : ndarray
        (D, D) torsional stiffness [N·m/rad] (empty without an attached system).
    th0 : ndarray
        (D,) rotational coordinates at the start [rad].

    Returns
    -------
    dict of str to float
        ``kinetic_j``, ``link_elastic_j``, ``contact_elastic_j``, ``torsional_elastic_j``,
        ``gravity_j`` [J].
    """
    m = model.roller_mass
    d = np.roll(x, -1, axis=0) - x
    e = np.hypot(d[:, 0], d[:, 1]) - L0
    s = np.sign(e) * np.maximum(np.abs(e) - model.clearance, 0.0)
    contact = 0.0
    for r in range(x.shape[0]):
        rel = x[r] - model.centres
        k = int(np.argmin(np.hypot(rel[:, 0], rel[:, 1])))
        delta = penetration(float(rel[k, 0]), float(rel[k, 1]), float(th[k]), spr[2, k],
                             spr[3, k], spr[4, k], spr[5, k], spr[6, k], spr[7, k])[0]
        if delta > 0:
            contact += 0.5 * spr[8, k] * delta * delta
    return {
        "kinetic_j": 0.5 * m * float(np.sum(v * v)) + 0.5 * float(np.sum(J * w * w)),
        "link_elastic_j": 0.5 * model.link_stiffness * float(np.sum(s * s)),
        "contact_elastic_j": contact,
        "torsional_elastic_j": 0.5 * float((th - th0) @ K @ (th - th0)) if K.size else 0.0,
        "gravity_j": -m * float(np.sum(x @ model.gravity)),
    }


_STORED = ("kinetic_j", "link_elastic_j", "contact_elastic_j", "torsional_elastic_j",
           "gravity_j")


def energy_residual(e: dict[str, float]) -> float:
    """ΔE − W − D of an energy balance: the change of the stored energy less the work of motor
    and loads plus all dissipation.

    Parameters
    ----------
    e : dict of str to float
        The balance (:class:`LinkLevelResult` ``energy`` keys) [J].

    Returns
    -------
    float
        The residual [J] (0 for an exact integration).
    """
    stored = sum(e[f"end_{k}"] - e[f"start_{k}"] for k in _STORED)
    work = e["motor_work_j"] + e["resistance_work_j"]
    lost = (e["link_damping_j"] + e["contact_damping_j"] + e["hinge_friction_j"]
            + e["torsional_damping_j"])
    return stored - work + lost


def drift_fraction(e: dict[str, float]) -> float:
    """Energy drift of a run [-]: :func:`energy_residual` over the energy scale of the run,
    the largest of the kinetic energy at the start and at the end and the work of the motor
    and of the loads (a conservative run — no motor, no dampers — has ΔE = 0 exactly, so
    this is the integration error as a fraction of the kinetic energy). 0 when all of these
    are zero.

    Parameters
    ----------
    e : dict of str to float
        The energy balance [J].

    Returns
    -------
    float
        (ΔE − W − D)/E_scale [-].
    """
    scale = max(e["start_kinetic_j"], e["end_kinetic_j"], abs(e["motor_work_j"]),
                abs(e["resistance_work_j"]))
    return energy_residual(e) / scale if scale > 0 else 0.0


#: Largest relative change of a reported quantity when the step halves, for the run to count
#: as converged in it [-].
CONVERGENCE_TOLERANCE = 0.02


def _relative_change(a: float, b: float) -> float:
    """|a − b|/|b| (0 when both are 0)."""
    return abs(a - b) / abs(b) if b != 0 else (0.0 if a == 0 else math.inf)


def step_convergence(coarse: LinkLevelResult, fine: LinkLevelResult) -> dict[str, Any]:
    """Relative changes of the reported quantities between a run and the same run at half
    its step: K_D, the span dynamic loads F_D,i, the peak span forces and the steady mean
    span forces (the largest over the spans), each against :data:`CONVERGENCE_TOLERANCE`
    (Richardson's principle: a quantity the step no longer moves is resolved by it).

    Parameters
    ----------
    coarse, fine : LinkLevelResult
        The run at Δt and at Δt/2.

    Returns
    -------
    dict
        ``checked`` (True), ``time_step_s``, ``half_step_s``, the ``*_change`` fractions,
        ``tolerance`` and ``converged`` (all changes within it).
    """
    kd_c, kd_f = coarse.coefficient_of_dynamics, fine.coefficient_of_dynamics
    changes = {
        "coefficient_of_dynamics_change":
            None if kd_c is None or kd_f is None else _relative_change(kd_c, kd_f),
        "span_dynamic_load_change": max(_relative_change(float(a), float(b)) for a, b in
                                        zip(coarse.span_dynamic_load, fine.span_dynamic_load,
                                            strict=True)),
        "peak_span_force_change": max(_relative_change(float(a), float(b)) for a, b in
                                      zip(coarse.peak_span_force, fine.peak_span_force,
                                          strict=True)),
        "span_mean_force_change": max(_relative_change(float(a), float(b)) for a, b in
                                      zip(coarse.span_mean_force, fine.span_mean_force,
                                          strict=True)),
    }
    ok = all(v is None or v <= CONVERGENCE_TOLERANCE for v in changes.values())
    return {"checked": True, "time_step_s": coarse.dt, "half_step_s": fine.dt,
            **{k: None if v is None else float(v) for k, v in changes.items()},
            "tolerance": CONVERGENCE_TOLERANCE, "converged": ok}


def _span_probe(geometry: GeometryResult, positions: NDArray[np.float64],
                tensions: NDArray[np.float64]) -> tuple[NDArray[np.float64],
                                                        NDArray[np.float64]]:
    """Span forces (T, n) [N] and mid-span transverse offsets (T, n) [m] (module docstring)."""
    mids = 0.5 * (positions + np.roll(positions, -1, axis=1))
    T = positions.shape[0]
    n = len(geometry.spans)
    force, offset = np.empty((T, n)), np.empty((T, n))
    rows = np.arange(T)
    for k, sp in enumerate(geometry.spans):
        a, b = np.array(sp.start_point), np.array(sp.end_point)
        centre, u = 0.5 * (a + b), np.array(sp.direction)
        rel = mids - centre
        j = np.argmin(np.einsum("tnk,tnk->tn", rel, rel), axis=1)
        force[:, k] = tensions[rows, j]
        offset[:, k] = rel[rows, j, 1] * u[0] - rel[rows, j, 0] * u[1]
    return force, offset


def _tooth_loads(model: LinkLevelModel, geometry: GeometryResult, positions: NDArray[np.float64],
                 forces: NDArray[np.float64], sprockets: NDArray[np.int64]
                 ) -> list[NDArray[np.float64]]:
    """Mean contact force [N] per place on each wrap (tooth 0 where the chain arrives)."""
    out = []
    samples = max(positions.shape[0], 1)
    for i, g in enumerate(geometry.sprockets):
        z = int(model.teeth[i])
        places = max(1, math.ceil(g.teeth_in_mesh) + 1)
        mask = sprockets == i
        rel = positions[mask] - model.centres[i]
        a = np.arctan2(rel[:, 1], rel[:, 0])
        a0 = math.atan2(g.arrive[1] - g.y, g.arrive[0] - g.x)
        turned = np.mod(g.turn * (a - a0) + 0.5 * TWO_PI / z, TWO_PI)
        place = np.floor(turned / (TWO_PI / z)).astype(int)
        ok = place < places
        out.append(np.bincount(place[ok], weights=forces[mask][ok], minlength=places)[:places]
                   / samples)
    return out


@dataclass(frozen=True, slots=True, eq=False)
class LinkLevelResult:
    """Histories and summaries of a link-level run (module docstring).

    Parameters
    ----------
    names : tuple of str
        Sprocket names.
    span_names : tuple of str
        Span names.
    times : ndarray
        (T,) recorded times [s].
    positions : ndarray
        (T, N, 2) roller centres [m].
    angles : ndarray
        (T, D) rotational coordinates [rad] (sprockets first, counter-clockwise positive).
    speeds : ndarray
        (T, D) their speeds [rad/s].
    link_tensions : ndarray
        (T, N) link tensions [N] (link i joins roller i and i+1).
    contact_forces : ndarray
        (T, N) roller–tooth contact force of every roller [N].
    contact_sprocket : ndarray
        (T, N) the sprocket each roller touches (−1: free) [-].
    span_forces : ndarray
        (T, n) span forces [N].
    span_offsets : ndarray
        (T, n) transverse offsets of the span middles [m].
    sprocket_speeds : ndarray
        (T, n) sprocket speeds in the running sense [rad/s].
    tooth_loads : tuple of ndarray
        Per sprocket, the mean load per place on the wrap over the steady window [N].
    impacts : ndarray
        (E, 4) time of the first contact [s], sprocket, roller, peak contact force [N] of
        every engagement.
    energy : dict of str to float
        Energy balance terms [J].
    dt : float
        Time step [s].
    steps : int
        Steps taken [-].
    closing_misfit : float
        Closing misfit of the assembly [m].
    steady_from : float
        Start of the steady window [s].
    nominal_force : float or None
        Nominal peripheral force F_t [N] (None without power).
    model : LinkLevelModel
        The parameters of the run.
    geometry : GeometryResult
        The (installed) contour.
    equilibrium : dict
        The static state the run started from
        (:meth:`chaindrive.linklevel.equilibrium.Equilibrium.to_dict`).
    convergence : dict
        The step-halving check (:func:`step_convergence`; empty when not asked for).
    """

    names: tuple[str, ...]
    span_names: tuple[str, ...]
    times: NDArray[np.float64]
    positions: NDArray[np.float64]
    angles: NDArray[np.float64]
    speeds: NDArray[np.float64]
    link_tensions: NDArray[np.float64]
    contact_forces: NDArray[np.float64]
    contact_sprocket: NDArray[np.int64]
    span_forces: NDArray[np.float64]
    span_offsets: NDArray[np.float64]
    sprocket_speeds: NDArray[np.float64]
    tooth_loads: tuple[NDArray[np.float64], ...]
    impacts: NDArray[np.float64]
    energy: dict[str, float]
    dt: float
    steps: int
    closing_misfit: float
    steady_from: float
    nominal_force: float | None
    model: LinkLevelModel
    geometry: GeometryResult
    equilibrium: dict[str, Any] = field(default_factory=dict)
    convergence: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def build(cls, *, drive: Drive, geometry: GeometryResult, model: LinkLevelModel,
              times: NDArray[np.float64], records: tuple[NDArray[Any], ...], dt: float,
              steps: int, energy_terms: NDArray[np.float64], energy_start: dict[str, float],
              energy_end: dict[str, float], events: NDArray[np.float64], closing_misfit: float,
              steady_window: float, equilibrium: dict[str, Any] | None = None
              ) -> LinkLevelResult:
        """Assemble the result from the kernel's records (see :mod:`.simulate`).

        Parameters
        ----------
        drive : Drive
            The drive.
        geometry : GeometryResult
            Its contour.
        model : LinkLevelModel
            The parameters of the run.
        times : ndarray
            (T,) recorded times [s].
        records : tuple of ndarray
            The kernel's records: positions (T, N, 2) [m], angles (T, D) [rad], speeds (T, D)
            [rad/s], link tensions (T, N) [N], contact forces (T, N) [N], contact sprocket and gap
            (T, N) indices.
        dt : float
            Time step [s].
        steps : int
            Steps taken [-].
        energy_terms : ndarray
            (6,) accumulated work of the motor and the loads and the dissipation in link
            dampers, contacts, hinges and torsional dampers [J].
        energy_start, energy_end : dict of str to float
            :func:`state_energy` at the start and at the end [J].
        events : ndarray
            (E, 4) engagements (time [s], sprocket, roller, peak force [N]).
        closing_misfit : float
            Closing misfit of the assembly [m].
        steady_window : float
            Closing fraction of the run taken as steady [-].
        equilibrium : dict or None
            The static state the run started from.

        Returns
        -------
        LinkLevelResult
            The result.
        """
        pos, ang, spd, ten, fc, sc, _gap = records
        n = model.centres.shape[0]
        span_f, span_y = _span_probe(geometry, pos, ten)
        steady_from = float(times[-1] * (1.0 - steady_window))
        late = times >= steady_from
        loads = _tooth_loads(model, geometry, pos[late], fc[late], sc[late])
        energy = {f"start_{k}": v for k, v in energy_start.items()}
        energy |= {f"end_{k}": v for k, v in energy_end.items()}
        energy |= {"motor_work_j": float(energy_terms[E_MOTOR]),
                   "resistance_work_j": float(energy_terms[E_LOAD]),
                   "link_damping_j": float(energy_terms[E_LINK]),
                   "contact_damping_j": float(energy_terms[E_CONTACT]),
                   "hinge_friction_j": float(energy_terms[E_HINGE]),
                   "torsional_damping_j": float(energy_terms[E_TORSION])}
        energy["drift_fraction"] = drift_fraction(energy)
        ft = None
        if drive.power and drive.driver.speed:
            ft = peripheral_force(drive.power, float(mean_chain_speed(
                model.pitch, model.teeth[model.driver], drive.driver.speed)))
        return cls(
            names=model.names,
            span_names=tuple(f"{s.start_name}-{s.end_name}" for s in geometry.spans),
            times=times, positions=pos, angles=ang, speeds=spd, link_tensions=ten,
            contact_forces=fc, contact_sprocket=sc, span_forces=span_f, span_offsets=span_y,
            sprocket_speeds=spd[:, :n] * model.turn, tooth_loads=tuple(loads), impacts=events,
            energy=energy, dt=dt, steps=steps, closing_misfit=closing_misfit,
            steady_from=steady_from, nominal_force=ft, model=model, geometry=geometry,
            equilibrium=dict(equilibrium or {}))

    # --- summaries ----------------------------------------------------------------------
    @property
    def energy_residual_j(self) -> float:
        """ΔE − W − D [J]: change of the stored energy minus the work of motor and loads plus
        all dissipation (0 for an exact integration)."""
        return energy_residual(self.energy)

    @property
    def span_dynamic_load(self) -> NDArray[np.float64]:
        """F_D,i = max |F_i − F̄_i| over the steady window [N] (module docstring)."""
        f = self.span_forces[self.times >= self.steady_from]
        return np.asarray(np.abs(f - f.mean(axis=0)).max(axis=0), dtype=np.float64)

    @property
    def span_mean_force(self) -> NDArray[np.float64]:
        """F̄_i over the steady window [N]."""
        return np.asarray(self.span_forces[self.times >= self.steady_from].mean(axis=0),
                          dtype=np.float64)

    @property
    def coefficient_of_dynamics(self) -> float | None:
        """K_D = 1 + F_D/F_t (None without power)."""
        if self.nominal_force is None:
            return None
        return coefficient_of_dynamics(self.span_dynamic_load, self.nominal_force)

    @property
    def peak_span_force(self) -> NDArray[np.float64]:
        """Largest span force over the whole run [N] (the start-up peak F₁max from rest)."""
        return np.asarray(self.span_forces.max(axis=0), dtype=np.float64)

    def history(self, links: bool = False) -> tuple[list[str], NDArray[np.float64]]:
        """CSV-ready history: time, sprocket speeds, span forces, span transverse offsets, and
        with ``links`` the tension of every link along the chain (link i joins rollers i and
        i + 1; the rollers are numbered along the chain as assembled, roller 0 where the chain
        arrives on the sprocket after the driver at t = 0).

        Parameters
        ----------
        links : bool
            True adds the tension of every link.

        Returns
        -------
        columns : list of str
            Column names, the unit in each.
        values : ndarray
            (T, columns) the history [units of the columns].
        """
        cols = ["time_s"]
        cols += [f"speed_{s}_rad_s" for s in self.names]
        cols += [f"span_force_{s}_n" for s in self.span_names]
        cols += [f"span_offset_{s}_m" for s in self.span_names]
        parts = [self.times, self.sprocket_speeds, self.span_forces, self.span_offsets]
        if links:
            cols += [f"link_{i}_tension_n" for i in range(self.link_tensions.shape[1])]
            parts.append(self.link_tensions)
        return cols, np.column_stack(parts)

    def to_dict(self, include_history: bool = False) -> dict[str, Any]:
        """JSON-ready dict (SI, unit in the key names).

        Parameters
        ----------
        include_history : bool
            True adds the histories.

        Returns
        -------
        dict
            The summaries (and histories).
        """
        kd = self.coefficient_of_dynamics
        out: dict[str, Any] = {
            "model": "link-level",
            "parameters": self.model.to_dict(),
            "time_step_s": self.dt, "steps": self.steps,
            "duration_s": float(self.times[-1]),
            "closing_misfit_m": self.closing_misfit,
            "span_names": list(self.span_names),
            "span_mean_force_n": self.span_mean_force.tolist(),
            "span_dynamic_load_n": self.span_dynamic_load.tolist(),
            "peak_span_force_n": self.peak_span_force.tolist(),
            "nominal_force_n": self.nominal_force,
            "coefficient_of_dynamics": kd,
            "final_sprocket_speed_rad_s": self.sprocket_speeds[-1].tolist(),
            "tooth_load_n": {s: v.tolist() for s, v in zip(self.names, self.tooth_loads,
                                                             strict=True)},
            "impacts": {"time_s": self.impacts[:, 0].tolist(),
                        "sprocket": [self.names[int(k)] for k in self.impacts[:, 1]],
                        "roller": self.impacts[:, 2].astype(int).tolist(),
                        "peak_force_n": self.impacts[:, 3].tolist()},
            "energy_j": {k: v for k, v in self.energy.items() if k != "drift_fraction"},
            "energy_residual_j": self.energy_residual_j,
            "energy_drift_fraction": self.energy["drift_fraction"],
            "equilibrium": dict(self.equilibrium),
            "step_convergence": dict(self.convergence) or {
                "checked": False,
                "note": "step convergence not checked: simulate(..., check_step=True) runs "
                        "the same simulation at half the step and reports the changes"},
        }
        if include_history:
            cols, data = self.history()
            out["history"] = {c: data[:, k].tolist() for k, c in enumerate(cols)}
            out["link_tension_n"] = self.link_tensions.tolist()
        return out
