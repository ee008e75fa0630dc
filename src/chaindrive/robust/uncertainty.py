"""The uncertainty model of a drive: the ``[uncertainty]`` table and the random variables it
gives, each with its distribution and its source.

==================== ============================================== ===================================
group                distribution (defaults)                        source
==================== ============================================== ===================================
chain length         ε₀ ~ U(0, 0.15 %) of a new chain                [ISO606] via [TsubakiLength]
wear                 life fraction λ ~ U(0, 1) ("life"), 0 ("new")   [DiamondChainWear], [RegalChainWear]
                     or 1 ("worn"): ε = ε₀ + λ(ε_allow − ε₀)
eccentricity         Rayleigh per sprocket, 99.73 % ≤ e_max = half   [RyleTolerances] (ASME B29.1
                     the commercial runout by root diameter          commercial sprockets)
shaft positions      Normal(0, (t/3)²) in x and y per shaft, t = 1   [TsubakiGuide, §7.1.2.2]
                     mm up to 1 m from the driver, a/1000 beyond
key clearances       Normal(z_max/2, z_max/6) per keyed joint of     [Lyashuk], eq. 7
                     parallel contours
inertias             U(1 − 10 %, 1 + 10 %) per sprocket              estimate (the designer's ±10 %)
chain stiffness      U(1 − 10 %, 1 + 10 %)                           estimate (the designer's ±10 %)
temperature          U(T_min, T_max) for polymer parts               [Delrin500P] modulus curve
==================== ============================================== ===================================

A tolerance is read as ±3σ of a normal process, the reading [Lyashuk] gives the key
clearance (z_max = 6σ_z). The variables split into *geometric* ones (they change the layout,
the slack or the loads: chain length, wear, positions, eccentricity, clearances) and *modal*
ones (they only scale the ring's masses and stiffnesses: inertias, chain stiffness,
temperature), which a batch of modal analyses can take at once.

References
----------
[ISO606], [TsubakiLength], [DiamondChainWear], [RegalChainWear], [DiamondChainTension],
[RyleTolerances], [TsubakiGuide], [Lyashuk], [Delrin500P]
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ndtri

from chaindrive._docstrings import shared_parameters
from chaindrive.analysis import Analysis
from chaindrive.catalog import find_material
from chaindrive.errors import DesignError
from chaindrive.io.design import UNCERTAINTY_FIELDS, parse_section, read_toml
from chaindrive.multicontour.clearance import SIGMAS_IN_RANGE
from chaindrive.robust.perturbation import REFERENCE_TEMPERATURE_C, Perturbation
from chaindrive.robust.wear import allowable_elongation

__all__ = ["ECCENTRICITY_TIR_IN", "GEOMETRIC_GROUPS", "MODAL_GROUPS", "UncertaintyModel",
           "UncertaintySettings", "Variable", "eccentricity_limit", "load_uncertainty",
           "position_tolerance", "uncertainty_model", "uncertainty_settings"]

_IN = 0.0254
#: Commercial sprocket eccentricity, bore to bottom of the teeth, as total indicator reading:
#: (bottom diameter up to [in], TIR [in]) [RyleTolerances] (the ASME B29.1 table for
#: commercial sprockets).
ECCENTRICITY_TIR_IN: tuple[tuple[float, float], ...] = (
    (4, 0.006), (5, 0.008), (7, 0.010), (9, 0.012), (11, 0.014), (13, 0.016), (15, 0.018),
    (20, 0.020), (25, 0.024), (35, 0.026), (45, 0.028), (60, 0.032), (75, 0.040),
    (100, 0.048))
#: Probability a tolerance covers (±3σ of a normal process) [–].
COVERAGE = 0.9973
#: Shaft distance tolerance of the installation: ±1 mm up to 1 m, ±a/1000 from 1 to 10 m,
#: ±10 mm beyond [TsubakiGuide, §7.1.2.2] [m].
POSITION_TOLERANCE = (1e-3, 1e-3, 10e-3)
#: Groups of variables that change the layout, slack or loads.
GEOMETRIC_GROUPS = ("chain length", "wear", "eccentricity", "shaft positions", "key clearances")
#: Groups that only scale the ring's masses and stiffnesses.
MODAL_GROUPS = ("inertias", "chain stiffness", "temperature")
WEAR_STATES = ("new", "worn", "life")


@dataclass(frozen=True, slots=True)
class UncertaintySettings:
    """The ``[uncertainty]`` table in SI (see :data:`chaindrive.io.design.UNCERTAINTY_FIELDS`;
    None: the default of the standards).

    Parameters
    ----------
    samples : int
        Quasi-Monte Carlo samples of the probabilities [–].
    replicates : int
        Independent scramblings (the confidence interval) [–].
    seed : int
        Seed of the scrambling.
    confidence : float
        Confidence level of the intervals [–].
    wear : str
        "new", "worn" or "life".
    smooth_running : bool
        The 1.5 % elongation limit applies.
    allowable_elongation : float | None
        Replacement elongation [–] (None: :func:`~chaindrive.robust.wear.allowable_elongation`).
    chain_length_tolerance : float
        Length tolerance of a new chain, 0 to this fraction [–].
    eccentricity : float | None
        Largest eccentricity of every sprocket [m] (None: :func:`eccentricity_limit`).
    centre_distance_tolerance : float | None
        ± position tolerance of every shaft [m] (None: :func:`position_tolerance`).
    key_fit : str
        Keyway fit of parallel contours ("tight", "normal", "free").
    inertia_scatter, stiffness_scatter : float
        ± relative scatter (uniform) [–].
    temperature_min, temperature_max : float
        Operating temperature range of polymer parts [°C].
    take_up_capacity : float | None
        Chain length the take-up absorbs [m] (None: two pitches [DiamondChainTension]).
    wear_states : int
        Wear states of the modal path over the life [–].
    sensitivity_samples : int
        First base samples N of each replicate design of the Sobol indices [–].
    sensitivity_budget : int
        Evaluations the Sobol sample may grow to [–].
    sensitivity_target : float
        Half-width of every metric's leading total index at which it stops growing [–].
    """

    samples: int = 256
    replicates: int = 8
    seed: int = 0
    confidence: float = 0.95
    wear: str = "life"
    smooth_running: bool = False
    allowable_elongation: float | None = None
    chain_length_tolerance: float = 0.0015
    eccentricity: float | None = None
    centre_distance_tolerance: float | None = None
    key_fit: str = "normal"
    inertia_scatter: float = 0.10
    stiffness_scatter: float = 0.10
    temperature_min: float = REFERENCE_TEMPERATURE_C
    temperature_max: float = REFERENCE_TEMPERATURE_C
    take_up_capacity: float | None = None
    wear_states: int = 8
    sensitivity_samples: int = 32
    sensitivity_budget: int = 16384
    sensitivity_target: float = 0.1

    def __post_init__(self) -> None:
        if self.wear not in WEAR_STATES:
            raise DesignError("uncertainty.wear", f"must be one of {', '.join(WEAR_STATES)}, "
                              f"got {self.wear!r}")
        if self.temperature_max < self.temperature_min:
            raise DesignError("uncertainty.temperature_max",
                              f"must not be below temperature_min ({self.temperature_min:g} °C), "
                              f"got {self.temperature_max:g} °C")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (lengths in mm)."""
        out: dict[str, Any] = {}
        for f in UNCERTAINTY_FIELDS:
            value = getattr(self, f.name)
            if f.kind == "length":
                out[f"{f.name}_mm"] = None if value is None else value * 1e3
            else:
                out[f.name] = value
        return out


def uncertainty_settings(table: Mapping[str, Any] | None) -> UncertaintySettings:
    """The settings of an ``[uncertainty]`` table (missing fields: defaults); a mistake is
    one :class:`~chaindrive.errors.DesignError` naming the field.

    Parameters
    ----------
    table : mapping | None
        The table as read from TOML (None: no table).

    Returns
    -------
    UncertaintySettings
        The validated settings.
    """
    return UncertaintySettings(**parse_section(table or {}, UNCERTAINTY_FIELDS, "uncertainty"))


@shared_parameters
def load_uncertainty(path: str | Path) -> UncertaintySettings:
    """The ``[uncertainty]`` table of a design file (defaults when it has none).

    %(params_design_path_returns)s
    UncertaintySettings
        The validated settings.
    """
    return uncertainty_settings(read_toml(path).get("uncertainty"))


def eccentricity_limit(root_diameter: float) -> float:
    """Largest eccentricity e_max = TIR/2 of a commercial sprocket (beyond the table: its
    last row).

    Parameters
    ----------
    root_diameter : float
        Root (bottom) diameter d_f [m].

    Returns
    -------
    float
        e_max [m], half the total indicated runout allowed for d_f.

    References
    ----------
    [RyleTolerances]
    """
    d_in = root_diameter / _IN
    tir = next((t for up_to, t in ECCENTRICITY_TIR_IN if d_in <= up_to),
               ECCENTRICITY_TIR_IN[-1][1])
    return 0.5 * tir * _IN


def position_tolerance(distance: float) -> float:
    """± position tolerance of a shaft: 1 mm up to 1 m from the driver, distance/1000 up to
    10 m, 10 mm beyond.

    Parameters
    ----------
    distance : float
        Distance of the shaft from the driver's [m].

    Returns
    -------
    float
        The tolerance ± [m].

    References
    ----------
    [TsubakiGuide, §7.1.2.2]
    """
    small, per_metre, large = POSITION_TOLERANCE
    if distance <= 1.0:
        return small
    return min(per_metre * distance, large)


@dataclass(frozen=True, slots=True)
class Variable:
    """One random variable of the model.

    Parameters
    ----------
    name : str
        E.g. ``"eccentricity[S1]"``.
    group : str
        The group it belongs to (sensitivity indices are per group).
    distribution : str
        "uniform" on [a, b], "normal" (mean a, standard deviation b) or "rayleigh"
        (scale b).
    a, b : float
        Parameters of the distribution [SI unit of the variable, e.g. m].
    unit : str
        Unit shown; ``scale`` converts SI to it.
    scale : float
        SI → ``unit`` factor [unit/SI].
    source : str
        Where the distribution comes from (a key of docs/references.md or "estimate").
    """

    name: str
    group: str
    distribution: str
    a: float
    b: float
    unit: str = ""
    scale: float = 1.0
    source: str = ""

    def ppf(self, u: ArrayLike) -> NDArray[np.float64]:
        """The values at the probabilities ``u`` (inverse CDF).

        Parameters
        ----------
        u : array_like
            Probabilities ∈ (0, 1) [-] (clipped 1e-12 from the ends).

        Returns
        -------
        ndarray
            The variable's values [SI], the shape of ``u``.
        """
        q = np.clip(np.asarray(u, dtype=float), 1e-12, 1.0 - 1e-12)
        if self.distribution == "uniform":
            out: NDArray[np.float64] = self.a + (self.b - self.a) * q
        elif self.distribution == "normal":
            out = self.a + self.b * ndtri(q)
        else:
            out = self.b * np.sqrt(-2.0 * np.log1p(-q))  # rayleigh
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (parameters in ``unit``)."""
        return {"name": self.name, "group": self.group, "distribution": self.distribution,
                "a": self.a * self.scale, "b": self.b * self.scale, "unit": self.unit,
                "source": self.source}


def _rayleigh_scale(limit: float) -> float:
    """Scale σ with P(e ≤ limit) = :data:`COVERAGE` for e ~ Rayleigh(σ)."""
    return limit / math.sqrt(-2.0 * math.log(1.0 - COVERAGE))


@dataclass(frozen=True, slots=True)
class UncertaintyModel:
    """The random variables of one drive and what they rest on.

    Parameters
    ----------
    settings : UncertaintySettings
        The table it was built from.
    variables : tuple of Variable
        In the order of the sample columns.
    allowable_elongation : float
        Replacement elongation of this drive [–].
    take_up_capacity : float | None
        Chain length the take-up absorbs [m] (None: no take-up).
    fixed_centres : bool
        No take-up follows the chain.
    life_fraction : float | None
        The life fraction λ of every state (0 new, 1 worn; None: sampled) [–].
    sprockets, contours : int
        Sprockets of the contour and parallel contours.
    notes : tuple of str
        What the model leaves out or rests on estimates.
    """

    settings: UncertaintySettings
    variables: tuple[Variable, ...]
    allowable_elongation: float
    take_up_capacity: float | None
    fixed_centres: bool
    life_fraction: float | None
    sprockets: int
    contours: int
    notes: tuple[str, ...] = field(default=())

    @property
    def dimension(self) -> int:
        """Number of random variables."""
        return len(self.variables)

    @property
    def groups(self) -> tuple[str, ...]:
        """The groups present, in order."""
        return tuple(dict.fromkeys(v.group for v in self.variables))

    def modal_only(self, names: tuple[str, ...] = MODAL_GROUPS) -> UncertaintyModel:
        """The model restricted to some groups.

        Parameters
        ----------
        names : tuple of str
            The groups kept (default :data:`MODAL_GROUPS`, the groups that only scale the
            ring's masses and stiffnesses).

        Returns
        -------
        UncertaintyModel
            The same model with only those groups' variables.
        """
        return UncertaintyModel(self.settings, tuple(v for v in self.variables
                                                     if v.group in names),
                                self.allowable_elongation, self.take_up_capacity,
                                self.fixed_centres, self.life_fraction, self.sprockets,
                                self.contours, self.notes)

    def values(self, u: ArrayLike) -> NDArray[np.float64]:
        """Variable values at the probabilities u (each variable's inverse CDF).

        Parameters
        ----------
        u : array_like
            (S, d) probabilities ∈ (0, 1) [-], one column per variable.

        Returns
        -------
        ndarray
            (S, d) variable values [SI].
        """
        q = np.atleast_2d(np.asarray(u, dtype=float))
        if q.shape[1] != self.dimension:
            raise DesignError("samples", f"need {self.dimension} columns, got {q.shape[1]}")
        return np.column_stack([v.ppf(q[:, k]) for k, v in enumerate(self.variables)]
                               ) if self.dimension else np.zeros((q.shape[0], 0))

    def perturbation(self, x: ArrayLike, *, elongation: float | None = None) -> Perturbation:
        """The drive's state for one row of variable values: the chain's elongation
        ε = ε₀ + λ(ε_allow − ε₀) from its length tolerance ε₀ and the life fraction λ.

        Parameters
        ----------
        x : array_like
            (d,) variable values [SI].
        elongation : float | None
            ε replacing the sampled one [–] (for the life curve).

        Returns
        -------
        Perturbation
        """
        row = np.asarray(x, dtype=float)
        by_group: dict[str, list[float]] = {}
        for v, value in zip(self.variables, row, strict=True):
            by_group.setdefault(v.group, []).append(float(value))
        n = self.sprockets
        eps0 = sum(by_group.get("chain length", []))
        life = by_group.get("wear", [self.life_fraction or 0.0])[0]
        eps = (eps0 + life * (self.allowable_elongation - eps0) if elongation is None
               else elongation)
        xy = by_group.get("shaft positions", [])
        offsets: list[tuple[float, float]] = []
        if xy:
            names = [v.name for v in self.variables if v.group == "shaft positions"]
            moved = {name: value for name, value in zip(names, xy, strict=True)}
            offsets = [(moved.get(f"x[{i}]", 0.0), moved.get(f"y[{i}]", 0.0)) for i in range(n)]
        temperature = by_group.get("temperature", [REFERENCE_TEMPERATURE_C])[0]
        stiffness = by_group.get("chain stiffness", [1.0])[0]
        return Perturbation(elongation=eps, offsets=tuple(offsets),
                            eccentricity=tuple(by_group.get("eccentricity", [])),
                            inertia_factors=tuple(by_group.get("inertias", [])),
                            chain_stiffness_factor=stiffness, temperature_c=temperature,
                            clearances=tuple(by_group.get("key clearances", [])))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"settings": self.settings.to_dict(),
                "variables": [v.to_dict() for v in self.variables],
                "allowable_elongation": self.allowable_elongation,
                "take_up_capacity_mm": (None if self.take_up_capacity is None
                                        else self.take_up_capacity * 1e3),
                "fixed_centres": self.fixed_centres,
                "life_fraction": self.life_fraction, "notes": list(self.notes)}


def _wear_variables(s: UncertaintySettings) -> tuple[list[Variable], float | None]:
    out: list[Variable] = []
    if s.chain_length_tolerance > 0:
        out.append(Variable("chain length", "chain length", "uniform", 0.0,
                            s.chain_length_tolerance, "%", 100.0, "[ISO606], [TsubakiLength]"))
    if s.wear == "life":
        out.append(Variable("wear", "wear", "uniform", 0.0, 1.0, "of the life", 1.0,
                            "[DiamondChainWear], [RegalChainWear]"))
    return out, {"new": 0.0, "worn": 1.0, "life": None}[s.wear]


def _sprocket_variables(a: Analysis, s: UncertaintySettings) -> list[Variable]:
    d, g = a.drive, a.geometry
    out: list[Variable] = []
    for sg in g.sprockets:
        e_max = s.eccentricity if s.eccentricity is not None else eccentricity_limit(
            sg.root_diameter)
        if e_max > 0:
            out.append(Variable(f"eccentricity[{sg.name}]", "eccentricity", "rayleigh", 0.0,
                                _rayleigh_scale(e_max), "mm", 1e3,
                                "[RyleTolerances]" if s.eccentricity is None else "design"))
    driver = g.sprockets[d.driver_index]
    for i, sg in enumerate(g.sprockets):
        if i == d.driver_index or i == g.adjusted:
            continue
        t = (s.centre_distance_tolerance if s.centre_distance_tolerance is not None
             else position_tolerance(math.hypot(sg.x - driver.x, sg.y - driver.y)))
        if t > 0:
            for axis in ("x", "y"):
                out.append(Variable(f"{axis}[{i}]", "shaft positions", "normal", 0.0,
                                    t / SIGMAS_IN_RANGE, "mm", 1e3,
                                    "[TsubakiGuide, §7.1.2.2]"
                                    if s.centre_distance_tolerance is None else "design"))
    return out


def _clearance_variables(a: Analysis) -> list[Variable]:
    c = a.contours
    if c is None:
        return []
    z_max = c.joint.max_clearance
    return [Variable(f"key clearance[{j + 1}.{end}]", "key clearances", "normal", z_max / 2.0,
                     z_max / (2.0 * SIGMAS_IN_RANGE), "mm", 1e3, "[Lyashuk], eq. 7")
            for j in range(c.contours) for end in ("driving", "driven")]


def _modal_variables(a: Analysis, s: UncertaintySettings) -> tuple[list[Variable], bool]:
    d = a.drive
    out: list[Variable] = []
    if s.inertia_scatter > 0:
        out += [Variable(f"inertia[{sp.name}]", "inertias", "uniform", 1.0 - s.inertia_scatter,
                         1.0 + s.inertia_scatter, "×", 1.0, "estimate")
                for sp in d.sprockets]
    if s.stiffness_scatter > 0:
        out.append(Variable("chain stiffness", "chain stiffness", "uniform",
                            1.0 - s.stiffness_scatter, 1.0 + s.stiffness_scatter, "×", 1.0,
                            "estimate"))
    polymer = any(find_material(name).is_polymer for name in
                  (d.chain.spec.material, *(sp.material for sp in d.sprockets)))
    if polymer and s.temperature_max > s.temperature_min:
        out.append(Variable("temperature", "temperature", "uniform", s.temperature_min,
                            s.temperature_max, "°C", 1.0, "[Delrin500P]"))
    return out, polymer


def uncertainty_model(analysis: Analysis, settings: UncertaintySettings | None = None
                      ) -> UncertaintyModel:
    """The uncertainty model of the analysed drive (module docstring).

    Parameters
    ----------
    analysis : Analysis
        The analysis of the drive as drawn (geometry, contours, chain).
    settings : UncertaintySettings | None
        The ``[uncertainty]`` table (None: every default).

    Returns
    -------
    UncertaintyModel
    """
    s = settings or UncertaintySettings()
    d, g = analysis.drive, analysis.geometry
    fixed = g.adjusted is None
    allowable = s.allowable_elongation if s.allowable_elongation is not None else (
        allowable_elongation(max(sp.teeth for sp in d.sprockets), fixed_centres=fixed,
                             parallel=d.chain.contours > 1, smooth=s.smooth_running))
    wear, life = _wear_variables(s)
    modal, polymer = _modal_variables(analysis, s)
    variables = (*wear, *_sprocket_variables(analysis, s), *_clearance_variables(analysis),
                 *modal)
    capacity = None if fixed else (s.take_up_capacity if s.take_up_capacity is not None
                                   else 2.0 * d.chain.spec.pitch)
    notes = ["inertia and chain-stiffness scatter: the designer's ±10 % by default (an "
             "estimate, no published value)" if s.inertia_scatter or s.stiffness_scatter
             else "no inertia or stiffness scatter"]
    if polymer:
        notes.append("polymer modulus against temperature: the acetal curve of [Delrin500P] "
                     "applied to every polymer (an estimate for polyamides)")
    if fixed:
        notes.append("fixed centres: the wear collects in the slack span (catenary sag)")
    return UncertaintyModel(s, tuple(variables), allowable, capacity, fixed, life,
                            len(d.sprockets), d.chain.contours, tuple(notes))
