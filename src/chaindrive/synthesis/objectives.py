"""Objectives and constraints of the synthesis, as registries, and the evaluation of a design.

Seed 000 §3.6 / conclusion: minimum cost, material (mass), occupied volume and weight,
maximum dynamic quality; constraints: the safety factors of both stages, the driver wrap,
teeth in mesh, speed limits, a contour that can be built. Every objective is a
:class:`Metric` in :data:`OBJECTIVES` and every constraint a :class:`Check` in
:data:`CONSTRAINTS` (value g, normalised, satisfied when g ≤ 0); a module adds its own with
:func:`register_objective` / :func:`register_constraint`. The dynamic ones that need the
steady state (coefficient of dynamics K_D, k2, k2min) are registered only when
:mod:`chaindrive.dynamics.steady` is importable.

A design is evaluated through a :class:`DesignState` that computes geometry → strength →
ring model → modes → resonances → steady state lazily, once, and only as far as the chosen
objectives and constraints need.
"""

from __future__ import annotations

import importlib.util
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.errors import ChainDriveError, DesignError
from chaindrive.model import Drive

if TYPE_CHECKING:
    from chaindrive.synthesis.cost import CostModel
    from chaindrive.synthesis.problem import Constraints, Problem

__all__ = [
    "CONSTRAINTS",
    "OBJECTIVES",
    "Check",
    "DesignState",
    "Evaluation",
    "Metric",
    "available_objectives",
    "decode_vector",
    "evaluate_drive",
    "evaluate_vector",
    "normalised_amplitude_at",
    "register_constraint",
    "register_objective",
]

TWO_PI = 2.0 * math.pi
#: objective value given to a design that cannot be built (a finite stand-in for ∞)
FAILED = 1e12
DAMPING_RATIO = 0.06  # seed 000: D = 0.06


# ---------------------------------------------------------------------------- decoding
def _chain_spec(designation: str, strands: int | None) -> Any:
    from chaindrive.catalog import chains, find_chain

    spec = find_chain(designation)
    if strands is None or strands == spec.strands:
        return spec
    same = [c for c in chains() if c.pitch == spec.pitch and c.series == spec.series
            and c.standard == spec.standard and c.strands == strands
            and abs(c.roller_diameter - spec.roller_diameter) < 1e-9]
    if not same:
        raise DesignError("optimize.chain.strands",
                          f"no {strands}-strand version of {spec.designation} in the catalogue")
    return same[0]


def _pick(g: Any, v: float) -> Any:
    k = math.floor(v)
    return g.choices[min(max(k, 0), len(g.choices) - 1)]


def _ratio_teeth(problem: Problem, g: Any, u: float, z_driver: int) -> int:
    """The tooth count that u ∈ [0, 1) picks among those in [low, high] keeping the ratio."""
    base = problem.base
    i0 = base.sprockets[g.index].teeth / base.driver.teeth
    lo, hi = g.choices
    tol = problem.ratio_tolerance
    allowed = [z for z in range(lo, hi + 1) if abs(z / z_driver - i0) <= tol * i0 + 1e-12]
    if not allowed:
        raise DesignError(f"optimize.teeth.{base.sprockets[g.index].name}",
                          f"no tooth count from {lo} to {hi} keeps the ratio {i0:.4g} within "
                          f"±{tol:.1%} for {z_driver} driver teeth")
    return allowed[min(int(u * len(allowed)), len(allowed) - 1)]


def decode_vector(problem: Problem, x: Sequence[float]) -> Drive:
    """The drive of a search vector (see :class:`chaindrive.synthesis.problem.Gene`).

    Added inertia ΔI is stored on the sprocket as I = I_body + ΔI, so the returned drive (and
    its TOML) re-analyses to the same masses; :func:`added_inertia` recovers ΔI.
    """
    from chaindrive.catalog import find_material
    from chaindrive.geometry.sprocket import sprocket_mass_and_inertia

    base = problem.base
    vals = dict(zip((g.name for g in problem.genes), (float(v) for v in x), strict=True))
    sp = [dict(teeth=s.teeth, x=s.x, y=s.y, material=s.material, inertia=s.inertia)
          for s in base.sprockets]
    designation, strands = base.chain.spec.designation, None
    added = np.zeros(len(sp))
    for g in problem.genes:
        v = vals[g.name]
        if g.kind == "int":
            sp[g.index]["teeth"] = round(min(max(v, g.low), g.high))
        elif g.target in ("x", "y"):
            # 0.01 mm: what drive_to_toml writes back, so the TOML re-analyses the same
            sp[g.index][g.target] = round(min(max(v, g.low), g.high), 5)
        elif g.target == "inertia":
            added[g.index] = min(max(v, g.low), g.high)
        elif g.target == "chain":
            designation = _pick(g, v)
        elif g.target == "strands":
            strands = int(_pick(g, v))
        elif g.target == "material":
            for s in sp:
                s["material"] = _pick(g, v)
    z1 = sp[base.driver_index]["teeth"]
    for g in problem.genes:
        if g.kind == "ratio":
            sp[g.index]["teeth"] = _ratio_teeth(problem, g, min(max(vals[g.name], 0.0), 1.0), z1)
    spec = _chain_spec(designation, strands)
    sprockets = []
    for s, new, dI in zip(base.sprockets, sp, added, strict=True):
        inertia = new["inertia"]
        if dI > 0:
            if inertia is None:
                mat = find_material(new["material"])
                inertia = sprocket_mass_and_inertia(
                    spec.pitch, new["teeth"], spec.inner_width, mat.density, mat.is_polymer,
                    strands=spec.strands, transverse_pitch=spec.transverse_pitch
                ).moment_of_inertia
            inertia += dI
        sprockets.append(replace(s, teeth=new["teeth"], x=new["x"], y=new["y"],
                                 material=new["material"], inertia=inertia))
    notes = dict(base.notes)
    notes["added_inertia_kg_m2"] = ",".join(f"{v:.9g}" for v in added)
    return replace(base.with_chain(spec), sprockets=tuple(sprockets), notes=notes)


def added_inertia(drive: Drive) -> NDArray[np.float64]:
    """ΔI per sprocket [kg·m²] recorded by :func:`decode_vector` (zeros otherwise)."""
    text = drive.notes.get("added_inertia_kg_m2")
    if not text:
        return np.zeros(len(drive.sprockets))
    return np.array([float(v) for v in text.split(",")])


# ---------------------------------------------------------------------------- the state
class DesignState:
    """Lazily computed analyses of one design (each at most once).

    drive : the design; base_ratios : z_i/z_driver of the start design (None: no ratio check);
    ratio_tolerance; cost_model (None: the packaged placeholders); damping ζ.
    """

    def __init__(self, drive: Drive, *, base_ratios: Sequence[float] | None = None,
                 ratio_tolerance: float = 0.03, cost_model: CostModel | None = None,
                 damping: float = DAMPING_RATIO) -> None:
        self.drive = drive
        self.base_ratios = base_ratios
        self.ratio_tolerance = ratio_tolerance
        self._cost_model = cost_model
        self.damping = damping

    @cached_property
    def cost_model(self) -> CostModel:
        from chaindrive.synthesis.cost import default_cost_model

        return self._cost_model or default_cost_model()

    @cached_property
    def geometry(self) -> Any:
        from chaindrive.geometry.contour import contour_geometry

        return contour_geometry(self.drive)

    @cached_property
    def placed(self) -> Drive:
        g = self.geometry
        return self.drive.with_sprockets(tuple(
            s.moved_to(p.x, p.y) for s, p in zip(self.drive.sprockets, g.sprockets, strict=True)))

    @cached_property
    def strength(self) -> Any:
        from chaindrive.strength import strength_of

        return strength_of(self.placed, self.geometry)

    @cached_property
    def parameters(self) -> Any:
        from chaindrive.dynamics.stiffness import drive_ring_parameters

        return drive_ring_parameters(self.placed, self.geometry,
                                     span_tensions=self.strength.loads.span_tensions)

    @cached_property
    def model(self) -> Any:
        from chaindrive.dynamics.ring import RingModel

        p = self.parameters
        return RingModel(p.masses_kg, p.stiffness_n_per_m, closed=True,
                         damping_ratio=self.damping)

    @cached_property
    def modal(self) -> Any:
        return self.model.modal()

    @cached_property
    def working_hz(self) -> NDArray[np.float64]:
        from chaindrive.dynamics.resonance import working_frequencies

        d = self.placed
        assert d.driver.speed is not None
        w = working_frequencies(d.driver.speed, d.driver.teeth, [s.teeth for s in d.sprockets])
        return np.array([x.frequency for x in w])

    @cached_property
    def bodies(self) -> NDArray[np.float64]:
        """Mass of every sprocket body [kg] (seed 000 §3.4 proportions for polymers)."""
        from chaindrive.catalog import find_material
        from chaindrive.geometry.sprocket import sprocket_mass_and_inertia

        spec = self.drive.chain.spec
        out = []
        for s in self.drive.sprockets:
            mat = find_material(s.material)
            out.append(sprocket_mass_and_inertia(spec.pitch, s.teeth, spec.inner_width,
                                                 mat.density, mat.is_polymer, strands=spec.strands,
                                                 transverse_pitch=spec.transverse_pitch).mass)
        return np.array(out)

    @cached_property
    def flywheels(self) -> NDArray[np.float64]:
        """Mass of the added inertia [kg]: a steel disc of the sprocket's pitch radius R,
        m = 2ΔI/R² (solid disc, I = m R²/2)."""
        r = np.array([g.pitch_radius for g in self.geometry.sprockets])
        return 2.0 * added_inertia(self.drive) / r**2

    @cached_property
    def steady(self) -> Any:
        return _steady(self)


def _steady(state: DesignState) -> Any:
    """Steady response to the polygonal excitation at the working speed, with the resonance
    loads F₂max of the run-up (seed 000 §3.3, §3.6)."""
    from chaindrive.dynamics.excitation import polygonal_excitation
    from chaindrive.dynamics.steady import steady_state

    d, g, loads = state.placed, state.geometry, state.strength.loads
    assert d.driver.speed is not None
    wz = d.driver.teeth * d.driver.speed
    radii = [s.pitch_radius for s in g.sprockets]
    f2max = None
    for fj in state.modal.elastic_frequencies_hz[:3]:
        for k in (1, 2, 3):
            w_res = TWO_PI * fj / k
            if 0.1 * wz <= w_res <= 1.5 * wz:
                r = steady_state(state.model, polygonal_excitation(g, w_res), radii=radii)
                f2max = r.span_dynamic_load if f2max is None else np.maximum(
                    f2max, r.span_dynamic_load)
    return steady_state(state.model, polygonal_excitation(g, wz), radii=radii,
                        nominal_force=loads.peripheral_force,
                        breaking_load=d.chain.spec.breaking_load,
                        operating_forces=loads.span_tensions, resonance_loads=f2max)


# ---------------------------------------------------------------------------- registries
@dataclass(frozen=True, slots=True)
class Metric:
    """An objective: value(state) in ``unit``; sense +1 minimise, −1 maximise."""

    name: str
    unit: str
    sense: int
    value: Callable[[DesignState], float]
    description: str


@dataclass(frozen=True, slots=True)
class Check:
    """A constraint: value(state, settings) → g (≤ 0 satisfied, normalised by the limit) or
    None when it does not apply to the design."""

    name: str
    value: Callable[[DesignState, Any], float | None]
    description: str


OBJECTIVES: dict[str, Metric] = {}
CONSTRAINTS: dict[str, Check] = {}


def register_objective(metric: Metric) -> Metric:
    """Add (or replace) an objective by name."""
    OBJECTIVES[metric.name] = metric
    return metric


def register_constraint(check: Check) -> Check:
    """Add (or replace) a constraint by name."""
    CONSTRAINTS[check.name] = check
    return check


def available_objectives() -> tuple[str, ...]:
    """Names of the registered objectives."""
    return tuple(OBJECTIVES)


def _mass(s: DesignState) -> float:
    spec = s.drive.chain.spec
    m = s.drive.chain.contours
    return float(m * (s.bodies.sum() + spec.mass_per_length * s.geometry.chain_length)
                 + s.flywheels.sum())


def _cost(s: DesignState) -> float:
    from chaindrive.catalog import find_material

    cm, spec, m = s.cost_model, s.drive.chain.spec, s.drive.chain.contours
    parts = sum(cm.sprocket_price(find_material(sp.material).family, b, sp.teeth)
                for b, sp in zip(s.bodies, s.drive.sprockets, strict=True))
    chain = s.geometry.chain_length * cm.chain_price_per_metre(spec.designation,
                                                               spec.mass_per_length)
    return float(m * (parts + chain) + s.flywheels.sum() * cm.part_price_per_kg("flywheel"))


def chain_width(spec: Any) -> float:
    """Overall chain width b ≈ b1 + 4 s + (strands − 1) p_t [m] (inner width, two inner and
    two outer plates of thickness s, :func:`chaindrive.dynamics.stiffness.plate_thickness`)."""
    from chaindrive.dynamics.stiffness import plate_thickness

    return spec.inner_width + 4 * plate_thickness(spec) + (spec.strands - 1) * spec.transverse_pitch


def _volume(s: DesignState) -> float:
    """Bounding box of the tip circles × chain width × contours [m³]."""
    g = s.geometry
    xy = np.array([(p.x, p.y) for p in g.sprockets])
    r = np.array([p.tip_diameter / 2 for p in g.sprockets])
    box = (xy[:, 0] + r).max() - (xy[:, 0] - r).min(), (xy[:, 1] + r).max() - (xy[:, 1] - r).min()
    return float(box[0] * box[1] * chain_width(s.drive.chain.spec) * s.drive.chain.contours)


def _margins(s: DesignState) -> NDArray[np.float64]:
    """|f_w − f_j|/f_j·100 for every working frequency and elastic mode (seed 000 §3.3)."""
    fn = s.modal.elastic_frequencies_hz
    return np.abs(s.working_hz[:, None] - fn[None, :]) / fn[None, :] * 100.0


def normalised_amplitude_at(modal: Any, working_hz: Sequence[float], damping: float) -> float:
    """Largest normalised amplitude at the working frequencies:
    max over modes j, masses k and working f_w of μ_k^(j)·H(f_w/f_j), with μ the seed 000
    normalised amplitude (seed-notes §1) and H(r) = 1/√((1−r²)² + (2ζr)²) the single-mode
    magnification (Rao, Mechanical Vibrations §3.4) — large when a mode with a large
    normalised amplitude lies near a working frequency."""
    el = ~modal.rigid_body
    fn = modal.frequencies_hz[el]
    mu = modal.normalized_amplitudes[:, el].max(axis=0)
    r = np.asarray(working_hz, dtype=float)[:, None] / fn[None, :]
    h = 1.0 / np.sqrt((1 - r**2) ** 2 + (2 * damping * r) ** 2)
    return float((mu[None, :] * h).max())


for _m in (
    Metric("cost", "currency", 1, _cost, "material + manufacturing + chain (synthesis/cost.py)"),
    Metric("mass", "kg", 1, _mass, "sprocket bodies + chain + flywheels"),
    Metric("volume", "m^3", 1, _volume, "bounding box of the tip circles × chain width"),
    Metric("chain_length", "m", 1, lambda s: float(s.geometry.chain_length), "chain length"),
    Metric("resonance_margin", "%", -1, lambda s: float(_margins(s).min()),
           "smallest distance of a working from a natural frequency (maximised)"),
    Metric("normalised_amplitude", "-", 1,
           lambda s: normalised_amplitude_at(s.modal, s.working_hz, s.damping),
           "largest normalised amplitude at the working frequencies"),
):
    register_objective(_m)


def _rel(limit: float, value: float) -> float:
    """g = (limit − value)/limit: ≤ 0 when value ≥ limit."""
    return (limit - value) / limit


def _static(s: DesignState, c: Constraints) -> float | None:
    if not c.static_safety:
        return None
    st = s.strength
    return _rel(st.allowable_safety_factor or c.min_static_safety, st.safety_factor_static)


def _pressure(s: DesignState, c: Constraints) -> float | None:
    st = s.strength
    if not c.static_safety or st.allowable_pressure is None:
        return None
    return (st.hinge_pressure - st.allowable_pressure) / st.allowable_pressure


def _teeth_in_mesh(s: DesignState, c: Constraints) -> float | None:
    loaded = [g.teeth_in_mesh for g, sp in zip(s.geometry.sprockets, s.drive.sprockets,
                                                 strict=True) if sp.role != "idler"]
    return _rel(c.min_teeth_in_mesh, min(loaded)) if c.min_teeth_in_mesh > 0 else None


def _chain_speed(s: DesignState, c: Constraints) -> float:
    d = s.drive
    assert d.driver.speed is not None
    v = d.driver.teeth * d.chain.spec.pitch * d.driver.speed / TWO_PI
    return (v - c.max_chain_speed) / c.max_chain_speed


def _speed_limit(s: DesignState, c: Constraints) -> float | None:
    from chaindrive.strength import ke_method
    from chaindrive.strength.loads import small_sprocket

    limit = ke_method.max_speed(s.drive.chain.spec.pitch) if c.speed_limit else None
    if limit is None:
        return None
    return (small_sprocket(s.drive)[1] - limit) / limit


def _ratios(s: DesignState, c: Constraints) -> float | None:
    if s.base_ratios is None:
        return None
    d = s.drive
    z1 = d.driver.teeth
    dev = max((abs(sp.teeth / z1 - i0) / i0 for sp, i0 in zip(d.sprockets, s.base_ratios,
                                                              strict=True)
               if sp.role == "driven"), default=0.0)
    return (dev - s.ratio_tolerance) / max(s.ratio_tolerance, 1e-3)


def _band(s: DesignState, c: Constraints) -> float | None:
    if c.resonance_band is None or c.resonance_band <= 0:
        return None
    return _rel(c.resonance_band, float(_margins(s).min()))


for _c in (
    Check("static_safety", _static, "s ≥ [s] (Table 9A, or min_static_safety)"),
    Check("hinge_pressure", _pressure, "p ≤ [p]"),
    Check("driver_wrap", lambda s, c: _rel(c.min_driver_wrap,
                                            s.geometry.sprockets[s.drive.driver_index].wrap_angle),
          "wrap on the driver ≥ min_driver_wrap"),
    Check("teeth_in_mesh", _teeth_in_mesh, "teeth in mesh on loaded sprockets ≥ minimum"),
    Check("chain_speed", _chain_speed, "mean chain speed ≤ max_chain_speed"),
    Check("speed_limit", _speed_limit, "small-sprocket speed ≤ n1max of the pitch"),
    Check("ratio", _ratios, "driven speeds within ratio_tolerance of the start design"),
    Check("resonance_band", _band, "working frequencies outside ±band of natural ones"),
):
    register_constraint(_c)


def register_dynamic() -> bool:
    """Register K_D, k2 and k2min when :mod:`chaindrive.dynamics.steady` exists (issue 6);
    returns whether it did."""
    if importlib.util.find_spec("chaindrive.dynamics.steady") is None:
        return False

    def kd(s: DesignState) -> float:
        v = s.steady.coefficient_of_dynamics
        return float(v) if v is not None else 1.0

    def k2(s: DesignState, c: Constraints) -> float | None:
        v = s.steady.k2
        return None if v is None else _rel(c.allowable_dynamic_safety, v)

    def k2min(s: DesignState, c: Constraints) -> float | None:
        v = s.steady.k2_min
        return None if v is None else _rel(c.allowable_dynamic_safety, v)

    register_objective(Metric("coefficient_of_dynamics", "-", 1, kd,
                              "K_D = 1 + F_D/F_t in steady motion (seed-notes §1)"))
    register_constraint(Check("k2", k2, "k2 = Q/(F_R + F_2) ≥ [k] (seed 000 §3.6)"))
    register_constraint(Check("k2_min", k2min, "k2min = Q/(F_R + F_2max) ≥ [k] at resonance"))
    return True


register_dynamic()


def register_startup() -> bool:
    """Register k1 (start-up, seed 000 §3.6) when :mod:`chaindrive.dynamics.response` exists;
    computed only for problems with ``startup_safety = true`` (one time integration each)."""
    if importlib.util.find_spec("chaindrive.dynamics.response") is None:
        return False

    def k1(s: DesignState, c: Constraints) -> float | None:
        if not c.startup_safety:
            return None
        from chaindrive.dynamics.response import drive_startup

        v = drive_startup(s.placed, s.geometry, s.model).k1
        return None if v is None else _rel(c.allowable_dynamic_safety, v)

    register_constraint(Check("k1", k1, "k1 = Q/F1max ≥ [k] in the start-up (seed 000 §3.6)"))
    return True


register_startup()


# ---------------------------------------------------------------------------- evaluation
@dataclass(frozen=True, slots=True)
class Evaluation:
    """Objectives (natural sign and unit), constraint values g (≤ 0 satisfied), feasible,
    error (why the design could not be built, or None)."""

    objectives: dict[str, float]
    constraints: dict[str, float]
    feasible: bool
    error: str | None = None

    def minimised(self, names: Sequence[str]) -> list[float]:
        """Objective values with the sense applied (every one minimised)."""
        return [OBJECTIVES[n].sense * self.objectives[n] for n in names]

    def violation(self) -> float:
        """Sum of the positive constraint values."""
        return float(sum(max(v, 0.0) for v in self.constraints.values()))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"objectives": dict(self.objectives), "constraints": dict(self.constraints),
                "constraints_ok": self.feasible, "error": self.error}


def evaluate_drive(drive: Drive, objectives: Sequence[str], settings: Constraints, *,
                   base_ratios: Sequence[float] | None = None, ratio_tolerance: float = 0.03,
                   cost_model: CostModel | None = None) -> Evaluation:
    """Objectives and constraints of one design; a design that cannot be built (the geometry
    or strength raises: span interference, impossible take-up …) gets objectives
    :data:`FAILED` and the constraint ``buildable`` = 1."""
    state = DesignState(drive, base_ratios=base_ratios, ratio_tolerance=ratio_tolerance,
                        cost_model=cost_model)
    try:
        obj = {n: OBJECTIVES[n].value(state) for n in objectives}
        cons: dict[str, float] = {"buildable": 0.0}
        for name, check in CONSTRAINTS.items():
            v = check.value(state, settings)
            if v is not None:
                cons[name] = float(v)
    except ChainDriveError as exc:
        return Evaluation({n: OBJECTIVES[n].sense * FAILED for n in objectives},
                          {"buildable": 1.0}, False, str(exc))
    bad = [v for v in [*obj.values(), *cons.values()] if not math.isfinite(v)]
    if bad:
        return Evaluation({n: OBJECTIVES[n].sense * FAILED for n in objectives},
                          {"buildable": 1.0}, False, "non-finite result")
    return Evaluation(obj, cons, all(v <= 0 for v in cons.values()))


def base_ratios(drive: Drive) -> list[float]:
    """z_i/z_driver of every sprocket."""
    return [s.teeth / drive.driver.teeth for s in drive.sprockets]


def evaluate_vector(problem: Problem, x: Sequence[float],
                    cost_model: CostModel | None = None) -> tuple[Evaluation, Drive | None]:
    """Decode and evaluate one search vector; the drive is None when it cannot be decoded."""
    try:
        drive = decode_vector(problem, x)
    except ChainDriveError as exc:
        return (Evaluation({n: OBJECTIVES[n].sense * FAILED for n in problem.objectives},
                           {"buildable": 1.0}, False, str(exc)), None)
    return evaluate_drive(drive, problem.objectives, problem.constraints,
                          base_ratios=base_ratios(problem.base),
                          ratio_tolerance=problem.ratio_tolerance, cost_model=cost_model), drive


def _detuning(s: DesignState) -> float:
    from chaindrive.synthesis.detuning import BAND, detuning_metric_value

    return detuning_metric_value(s.modal.elastic_frequencies_hz, s.working_hz, BAND)


register_objective(Metric("detuning", "-", 1, _detuning,
                          "Σ squared shortfall of the natural frequencies inside ±10 % of the "
                          "working frequencies (seed 000 detuning; 0 = clear)"))
