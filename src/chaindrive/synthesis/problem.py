"""The ``[optimize]`` table of a design file: variables, objectives, constraints, solver.

[MultimassChainDrives, §3.6] and conclusion: build a contour "meeting the optimal-design requirements:
minimum cost, material, occupied volume and weight, maximum dynamic quality". The table::

    [optimize]
    objectives = ["cost", "mass", "volume", "chain_length"]
    ratio_tolerance = 0.03            # driven speeds kept within ±3 % of the start design

    [optimize.teeth]                  # integer tooth counts, per sprocket
    M = [15, 21]
    [optimize.position.I1]            # idler or adjustable sprockets, within a box
    x = ["1050 mm", "1150 mm"]
    y = ["20 mm", "120 mm"]
    [optimize.chain]                  # categorical
    designations = ["ISO 606 10B-1", "ISO 606 12B-1"]
    strands = [1, 2]
    [optimize.material]
    sprockets = ["steel", "PA66"]     # one material for every sprocket (categorical)
    [optimize.inertia]                # added inertia (flywheel) per shaft
    D3 = ["0 kg*m^2", "0.05 kg*m^2"]
    [optimize.constraints]
    min_driver_wrap = "120 deg"
    [optimize.solver]
    method = "nsga2"; population = 16; generations = 10; seed = 1
    [optimize.robust]                 # chance constraints over [uncertainty] (chaindrive.robust)
    chance = { resonance_margin = 0.01 }

Every mistake is one :class:`~chaindrive.errors.DesignError` line naming the field path, the
value and what is allowed (the style of :mod:`chaindrive.io.design`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from chaindrive.catalog import chains, find_chain, find_material
from chaindrive.checks import ALLOWABLE_DYNAMIC_SAFETY
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.io.design import (
    Field,
    drive_from_mapping,
    parse_field,
    parse_section,
    read_toml,
)
from chaindrive.model import MAX_TEETH, MIN_TEETH, ChainSpec, Drive
from chaindrive.robust.synthesis import ROBUST_OBJECTIVES, RobustSettings, robust_settings
from chaindrive.synthesis.objectives import available_objectives
from chaindrive.units import TWO_PI

__all__ = [
    "CONSTRAINT_FIELDS",
    "SOLVER_FIELDS",
    "Constraints",
    "Gene",
    "Problem",
    "SolverSettings",
    "load_problem",
    "problem_from_mapping",
]

TOP_FIELDS: tuple[Field, ...] = (
    Field("ratio_tolerance", "float", "allowed relative deviation of every driven sprocket's "
          "ratio z_i/z_driver from the start design", default=0.03, minimum=0.0, maximum=0.5),
)
CONSTRAINT_FIELDS: tuple[Field, ...] = (
    Field("min_driver_wrap", "angle", "smallest wrap angle on the driver", default=math.radians(120),
          minimum=0.0, maximum=TWO_PI),
    Field("min_teeth_in_mesh", "float", "smallest number of teeth in mesh on loaded sprockets",
          default=3.0, minimum=0.0, maximum=50.0),
    Field("static_safety", "bool", "static safety factor s ≥ [s] [ChainDesignRU, Table 9A]",
          default=True),
    Field("min_static_safety", "float", "your own [s] where the table gives none (without "
          "it such a design cannot be verified and counts as failing)", minimum=1.0,
          maximum=50.0),
    Field("allowable_dynamic_safety", "float", "[k] for k2 and k2min [MultimassChainDrives, §3.6]",
          default=ALLOWABLE_DYNAMIC_SAFETY, minimum=1.0, maximum=20.0),
    Field("startup_safety", "bool", "k1 = Q/F1max ≥ [k] from the start-up transient (costly: "
          "one time integration per design)", default=False),
    Field("max_chain_speed", "velocity", "highest mean chain speed", default=15.0, minimum=0.0,
          exclusive_minimum=True),
    Field("speed_limit", "bool", "small-sprocket speed ≤ n1max of the pitch "
          "[TrinhChat2006, Table 5.8]", default=True),
    Field("resonance_band", "float", "if given: every working frequency at least this many "
          "percent from every natural frequency", minimum=0.0, maximum=100.0),
)
SOLVER_FIELDS: tuple[Field, ...] = (
    Field("method", "choice", "search library (docs/synthesis.md: optuna chosen by benchmark)",
          default="optuna", choices=("optuna", "nsga2")),
    Field("population", "int", "designs per generation", default=16, minimum=4, maximum=10000),
    Field("generations", "int", "generations", default=10, minimum=1, maximum=10000),
    Field("seed", "int", "random seed (same seed, same result)", default=1, minimum=0,
          maximum=2**31 - 1),
)
SECTIONS = ("objectives", "ratio_tolerance", "teeth", "position", "chain", "material", "inertia",
            "constraints", "solver", "robust")


@dataclass(frozen=True, slots=True)
class Gene:
    """One coordinate of the search vector.

    Parameters
    ----------
    name : str
        E.g. ``teeth.M``.
    kind : str
        ``"int"`` (rounded in [low, high]), ``"ratio"`` (u ∈ [0, 1) picks one of the tooth
        counts that keep the ratio; see :meth:`Problem.decode`), ``"float"``, ``"choice"``
        (index into ``choices``).
    low, high : float
        Bounds [the unit of the target: teeth, m, kg·m², or an index].
    target : str
        What it sets (``teeth``, ``x``, ``y``, ``inertia``, ``chain``, ``strands``,
        ``material``).
    index : int
        Sprocket index (−1 for drive-wide genes).
    choices : tuple
        The categories (or the tooth-count range of a ratio gene).
    """

    name: str
    kind: str
    low: float
    high: float
    target: str
    index: int = -1
    choices: tuple[str | int, ...] = ()


@dataclass(frozen=True, slots=True)
class Constraints:
    """Constraint settings (:data:`CONSTRAINT_FIELDS`).

    Parameters
    ----------
    min_driver_wrap : float
        Smallest wrap on the driver [rad].
    min_teeth_in_mesh : float
        Smallest teeth in mesh on loaded sprockets [-].
    static_safety : bool
        Keep the chain's strength checks.
    min_static_safety : float or None
        The designer's own [s] [-] where the table gives none.
    allowable_dynamic_safety : float
        [k] [-].
    startup_safety : bool
        Keep k₁ (a start-up per design).
    max_chain_speed : float
        Highest mean chain speed [m/s].
    speed_limit : bool
        Keep the small-sprocket speed limit.
    resonance_band : float or None
        Least distance of a working frequency from a natural one [%].
    """

    min_driver_wrap: float = math.radians(120)
    min_teeth_in_mesh: float = 3.0
    static_safety: bool = True
    min_static_safety: float | None = None
    allowable_dynamic_safety: float = ALLOWABLE_DYNAMIC_SAFETY
    startup_safety: bool = False
    max_chain_speed: float = 15.0
    speed_limit: bool = True
    resonance_band: float | None = None


@dataclass(frozen=True, slots=True)
class SolverSettings:
    """The search settings (:data:`SOLVER_FIELDS`).

    Parameters
    ----------
    method : str
        ``nsga2`` = pymoo NSGA-II, ``optuna`` = Optuna NSGA-II sampler [Deb2002].
    population : int
        Designs per generation [-].
    generations : int
        [-].
    seed : int
        Random seed (same seed, same result).
    """

    method: str = "optuna"
    population: int = 16
    generations: int = 10
    seed: int = 1


@dataclass(frozen=True, slots=True, eq=False)
class Problem:
    """A synthesis problem: the start design, the genes, objectives and constraints.

    Parameters
    ----------
    base : Drive
        The start design.
    base_mapping : dict
        The design file's tables without ``[optimize]``.
    genes : tuple of Gene
        The search vector.
    ratio_tolerance : float
        Allowed relative deviation of every driven ratio from the start design [-].
    objectives : tuple of str
        Names in :data:`chaindrive.synthesis.objectives.OBJECTIVES`.
    constraints : Constraints
        The constraint settings.
    solver : SolverSettings
        The search settings.
    robust : RobustSettings | None
        ``[optimize.robust]`` with ``[uncertainty]`` (None: a deterministic problem).
    base_dir : pathlib.Path | None
        Where relative paths of the design file start (its designs are loaded from there).
    """

    base: Drive
    base_mapping: dict[str, Any]
    genes: tuple[Gene, ...]
    ratio_tolerance: float
    objectives: tuple[str, ...]
    constraints: Constraints = field(default_factory=Constraints)
    solver: SolverSettings = field(default_factory=SolverSettings)
    robust: RobustSettings | None = None
    base_dir: Path | None = None

    @property
    def bounds(self) -> tuple[list[float], list[float]]:
        """Lower and upper bounds of the search vector."""
        return [g.low for g in self.genes], [g.high for g in self.genes]

    def start_vector(self) -> list[float]:
        """The search vector of the start design (each gene at the start's value).

        Returns
        -------
        list of float
            One value per gene.
        """
        return [_start_value(self, g) for g in self.genes]

    def decode(self, x: Sequence[float]) -> Drive:
        """The drive of a search vector (see :class:`Gene`).

        Integers are rounded and clipped, categories picked by the integer part, ratio genes
        pick among the tooth counts that keep the ratio; an added inertia becomes the
        sprocket's ``flywheel`` (so the drive, and its design file, analyse to the same masses
        and count the flywheel's mass and cost).

        Parameters
        ----------
        x : sequence of float
            One value per gene [the unit of each gene].

        Returns
        -------
        Drive
            The design.

        Raises
        ------
        DesignError
            When no tooth count keeps a ratio.
        """
        base = self.base
        vals = dict(zip((g.name for g in self.genes), (float(v) for v in x), strict=True))
        sp: list[dict[str, Any]] = [dict(teeth=s.teeth, x=s.x, y=s.y, material=s.material,
                                         flywheel=s.flywheel) for s in base.sprockets]
        designation, strands = base.chain.spec.designation, None
        for g in self.genes:
            v = vals[g.name]
            if g.kind == "int":
                sp[g.index]["teeth"] = round(min(max(v, g.low), g.high))
            elif g.target in ("x", "y"):
                # 0.01 mm: what the design file keeps, so the file re-analyses the same
                sp[g.index][g.target] = round(min(max(v, g.low), g.high), 5)
            elif g.target == "inertia":
                sp[g.index]["flywheel"] = min(max(v, g.low), g.high)
            elif g.target == "chain":
                designation = str(_pick(g, v))
            elif g.target == "strands":
                strands = int(_pick(g, v))
            elif g.target == "material":
                for s in sp:
                    s["material"] = _pick(g, v)
        z1 = sp[base.driver_index]["teeth"]
        for g in self.genes:
            if g.kind == "ratio":
                sp[g.index]["teeth"] = _ratio_teeth(self, g, min(max(vals[g.name], 0.0), 1.0),
                                                  z1)
        spec = _chain_spec(designation, strands)
        sprockets = tuple(replace(s, **new) for s, new in zip(base.sprockets, sp, strict=True))
        return replace(base.with_chain(spec), sprockets=sprockets)


def _start_value(problem: Problem, g: Gene) -> float:
    drive = problem.base
    if g.target == "teeth":
        z = drive.sprockets[g.index].teeth
        if g.kind == "int":
            return float(z)
        lo, hi = _tooth_range(g)  # the start's tooth count among those keeping its ratio
        i0 = z / drive.driver.teeth
        allowed = [k for k in range(lo, hi + 1)
                   if abs(k / drive.driver.teeth - i0) <= problem.ratio_tolerance * i0 + 1e-12]
        return (allowed.index(z) + 0.5) / len(allowed) if z in allowed else 0.5
    if g.target in ("x", "y"):
        return float(getattr(drive.sprockets[g.index], g.target))
    if g.target == "inertia":
        return float(g.low)
    key: str | int
    if g.target == "chain":
        key = _chain_key(drive.chain.spec.designation)
        keys: list[object] = [_chain_key(str(c)) for c in g.choices]
    else:
        key = drive.chain.spec.strands if g.target == "strands" else drive.sprockets[0].material
        keys = list(g.choices)
    return float(keys.index(key)) + 0.5 if key in keys else 0.5


def _chain_key(designation: str) -> str:
    """Designation without the strand suffix ("ISO 606 12B-2" → "ISO 606 12B")."""
    d = designation.strip()
    return d[:-2] if len(d) > 2 and d[-2] == "-" and d[-1].isdigit() else d


def _pair(value: Any, kind: str, path: str, lo: float | None = None,
          hi: float | None = None) -> tuple[float, float]:
    """A [low, high] pair of a field kind, low ≤ high."""
    if not isinstance(value, list) or len(value) != 2:
        raise DesignError(path, f"must be a pair [low, high], got {value!r}")
    f = Field(path.rsplit(".", 1)[-1], kind, "", minimum=lo, maximum=hi)
    a = parse_field(f, value[0], f"{path}[0]")
    b = parse_field(f, value[1], f"{path}[1]")
    if a > b:
        raise DesignError(path, f"low must not exceed high, got {value!r}")
    return float(a), float(b)


def _sprocket_index(drive: Drive, name: str, path: str) -> int:
    names = [s.name for s in drive.sprockets]
    if name not in names:
        raise DesignError(path, f"no sprocket named {name!r}" + did_you_mean(name, names)
                          + f" (sprockets: {', '.join(names)})")
    return names.index(name)


def _table(data: Mapping[str, Any], key: str) -> Mapping[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, Mapping):
        raise DesignError(f"optimize.{key}", f"must be a table, got {type(value).__name__}")
    return value


def _teeth_genes(drive: Drive, table: Mapping[str, Any], tol: float) -> list[Gene]:
    genes: list[Gene] = []
    driver = drive.driver_index
    order = sorted(table, key=lambda n: (n != drive.driver.name, n))  # driver first
    for name in order:
        path = f"optimize.teeth.{name}"
        i = _sprocket_index(drive, name, path)
        if isinstance(table[name], list) and all(isinstance(v, int) and not isinstance(v, bool)
                                                 for v in table[name]):
            lo, hi = _pair(table[name], "int", path, MIN_TEETH, MAX_TEETH)
        else:
            raise DesignError(path, f"must be a pair of whole numbers [low, high] from "
                              f"{MIN_TEETH} to {MAX_TEETH}, got {table[name]!r}")
        loaded = drive.sprockets[i].role == "driven"
        kind = "ratio" if loaded and i != driver else "int"
        genes.append(Gene(f"teeth.{name}", kind, 0.0 if kind == "ratio" else lo,
                          1.0 if kind == "ratio" else hi, "teeth", i,
                          choices=(int(lo), int(hi)) if kind == "ratio" else ()))
    return genes


def _position_genes(drive: Drive, table: Mapping[str, Any]) -> list[Gene]:
    genes: list[Gene] = []
    for name, box in table.items():
        path = f"optimize.position.{name}"
        i = _sprocket_index(drive, name, path)
        s = drive.sprockets[i]
        if s.role != "idler" and not s.adjustable:
            raise DesignError(path, f"only idler or adjustable sprockets may move; {name} is a "
                              f"fixed {s.role} shaft")
        if not isinstance(box, Mapping) or not box or set(box) - {"x", "y"}:
            raise DesignError(path, f"must be a table with x and/or y = [low, high], got {box!r}")
        for axis in ("x", "y"):
            if axis in box:
                lo, hi = _pair(box[axis], "length", f"{path}.{axis}")
                genes.append(Gene(f"{axis}.{name}", "float", lo, hi, axis, i))
    return genes


def _choice_gene(name: str, values: object, path: str, target: str,
                 check: Callable[[object, str], None]) -> Gene:
    if not isinstance(values, list) or not values:
        raise DesignError(path, f"must be a non-empty list, got {values!r}")
    for k, v in enumerate(values):
        check(v, f"{path}[{k}]")
    return Gene(name, "choice", 0.0, float(len(values)), target, -1, tuple(values))


def _in_catalogue(find: Callable[[str], object], what: str) -> Callable[[object, str], None]:
    """A check that a value names an entry of the catalogue (``find`` looks it up)."""

    def check(value: object, path: str) -> None:
        if not isinstance(value, str):
            raise DesignError(path, f"must be {what}, got {value!r}")
        try:
            find(value)
        except DesignError as exc:
            raise DesignError(path, f"{value!r} is not in the catalogue ({exc})") from None

    return check


_check_chain = _in_catalogue(find_chain, "a catalogue designation")
_check_material = _in_catalogue(find_material, "a material name")


def _check_strands(value: object, path: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 4:
        raise DesignError(path, f"must be a whole number from 1 to 4, got {value!r}")


def _categorical_genes(data: Mapping[str, Any]) -> list[Gene]:
    genes: list[Gene] = []
    chain = _table(data, "chain")
    for key in chain:
        if key not in ("designations", "strands"):
            raise DesignError(f"optimize.chain.{key}", "unknown field"
                              + did_you_mean(key, ("designations", "strands"))
                              + " (known: designations, strands)")
    if "designations" in chain:
        genes.append(_choice_gene("chain", chain["designations"], "optimize.chain.designations",
                                  "chain", _check_chain))
    if "strands" in chain:
        genes.append(_choice_gene("strands", chain["strands"], "optimize.chain.strands",
                                  "strands", _check_strands))
    material = _table(data, "material")
    for key in material:
        if key != "sprockets":
            raise DesignError(f"optimize.material.{key}", "unknown field (known: sprockets)")
    if "sprockets" in material:
        genes.append(_choice_gene("material", material["sprockets"],
                                  "optimize.material.sprockets", "material", _check_material))
    return genes


def _inertia_genes(drive: Drive, table: Mapping[str, Any]) -> list[Gene]:
    genes = []
    for name, pair in table.items():
        path = f"optimize.inertia.{name}"
        i = _sprocket_index(drive, name, path)
        lo, hi = _pair(pair, "inertia", path, 0.0)
        genes.append(Gene(f"inertia.{name}", "float", lo, hi, "inertia", i))
    return genes


def _objectives(data: Mapping[str, Any]) -> tuple[str, ...]:
    names = data.get("objectives", ["cost", "mass", "volume"])
    known = available_objectives()
    if not isinstance(names, list) or not names:
        raise DesignError("optimize.objectives", f"must be a non-empty list of names "
                          f"({', '.join(known)}), got {names!r}")
    for k, n in enumerate(names):
        if n not in known:
            raise DesignError(f"optimize.objectives[{k}]", f"unknown objective {n!r}"
                              + did_you_mean(str(n), known) + f" (known: {', '.join(known)})")
    if len(set(names)) != len(names):
        raise DesignError("optimize.objectives", f"names must not repeat, got {names!r}")
    return tuple(names)


def problem_from_mapping(data: Mapping[str, Any], base_dir: Path | None = None) -> Problem:
    """A synthesis problem from the parsed TOML of a design file with ``[optimize]``.

    Parameters
    ----------
    data : mapping
        The design file's tables.
    base_dir : pathlib.Path or None
        Where relative paths of the design file start.

    Returns
    -------
    Problem
        The validated problem.

    Raises
    ------
    DesignError
        Naming the field path, the value and what is allowed.
    """
    base_mapping = {k: v for k, v in data.items() if k != "optimize"}
    drive = drive_from_mapping(base_mapping, base_dir)
    opt = data.get("optimize")
    if not isinstance(opt, Mapping):
        raise DesignError("optimize", "is required: add an [optimize] table (see docs/synthesis.md)")
    for key in opt:
        if key not in SECTIONS:
            raise DesignError(f"optimize.{key}", "unknown field" + did_you_mean(key, SECTIONS)
                              + f" (known: {', '.join(SECTIONS)})")
    top = parse_section({k: opt[k] for k in ("ratio_tolerance",) if k in opt}, TOP_FIELDS,
                        "optimize")
    tol = top["ratio_tolerance"]
    genes = (_teeth_genes(drive, _table(opt, "teeth"), tol)
             + _position_genes(drive, _table(opt, "position"))
             + _categorical_genes(opt) + _inertia_genes(drive, _table(opt, "inertia")))
    if not genes:
        raise DesignError("optimize", "gives no variable: add teeth, position, chain, material "
                          "or inertia tables")
    cons = parse_section(_table(opt, "constraints"), CONSTRAINT_FIELDS, "optimize.constraints")
    solver = parse_section(_table(opt, "solver"), SOLVER_FIELDS, "optimize.solver")
    if drive.power is None:
        raise DesignError("drive.power", "is required for optimisation (strength constraints)")
    objectives = _objectives(opt)
    robust = (robust_settings(_table(opt, "robust"), data.get("uncertainty"), objectives)
              if "robust" in opt else None)
    if robust is None and any(o in ROBUST_OBJECTIVES for o in objectives):
        raise DesignError("optimize.robust", "is required by the robust objectives "
                          f"({', '.join(o for o in objectives if o in ROBUST_OBJECTIVES)})")
    return Problem(base=drive, base_mapping=base_mapping, genes=tuple(genes), ratio_tolerance=tol,
                   objectives=objectives, constraints=Constraints(**cons),
                   solver=SolverSettings(**solver), robust=robust, base_dir=base_dir)


def load_problem(path: str | Path) -> Problem:
    """Read a design file and its ``[optimize]`` table.

    Parameters
    ----------
    path : str or pathlib.Path
        The design file.

    Returns
    -------
    Problem
        The validated problem.
    """
    return problem_from_mapping(read_toml(path), base_dir=Path(path).parent)


# ---------------------------------------------------------------------------- decoding
def _chain_spec(designation: str, strands: int | None) -> ChainSpec:
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


def _tooth_range(g: Gene) -> tuple[int, int]:
    """(low, high) tooth counts of a ratio gene."""
    return int(g.choices[0]), int(g.choices[1])


def _pick(g: Gene, v: float) -> str | int:
    k = math.floor(v)
    return g.choices[min(max(k, 0), len(g.choices) - 1)]


def _ratio_teeth(problem: Problem, g: Gene, u: float, z_driver: int) -> int:
    """The tooth count that u ∈ [0, 1) picks among those in [low, high] keeping the ratio."""
    base = problem.base
    i0 = base.sprockets[g.index].teeth / base.driver.teeth
    lo, hi = _tooth_range(g)
    tol = problem.ratio_tolerance
    allowed = [z for z in range(lo, hi + 1) if abs(z / z_driver - i0) <= tol * i0 + 1e-12]
    if not allowed:
        raise DesignError(f"optimize.teeth.{base.sprockets[g.index].name}",
                          f"no tooth count from {lo} to {hi} keeps the ratio {i0:.4g} within "
                          f"±{tol:.1%} for {z_driver} driver teeth")
    return allowed[min(int(u * len(allowed)), len(allowed) - 1)]
