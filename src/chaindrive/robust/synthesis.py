"""Robust synthesis: chance constraints and robust objectives for the optimiser
(:mod:`chaindrive.synthesis`), read from ``[optimize.robust]``::

    [optimize.robust]
    samples = 32                 # states per design (Sobol points)
    path = "auto"                # auto | modal | full
    [optimize.robust.chance]     # check key → largest probability of failing it
    resonance_margin = 0.01      # P(a working frequency within the band) ≤ 1 %
    k2 = 0.001                   # P(k₂ < [k]) ≤ 0.1 %

and objectives such as ``"kd_p95"`` (the 95th percentile of K_D) in ``[optimize]
objectives``. The uncertainty model is the design file's ``[uncertainty]`` table.

A chance constraint P(check fails) ≤ α is imposed on the α-quantile of the check's margin
fraction m (m ≥ 0 passes): g = −q_α(m) ≤ 0, which holds exactly when at most a fraction α of
the design's states fail — a continuous value for the search where the count of failures is
a step [Rockafellar2000]. With S states per design the quantile resolves probabilities down
to about 1/S; verify the design found with ``chaindrive robust`` at many samples. The path
"auto" takes the batched modal path when the constraints and objectives need only the
resonance margin and f₁, and the full path otherwise.

References
----------
[Rockafellar2000], [MultimassChainDrives]
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

from chaindrive.analysis import Analysis
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.io.design import Field, parse_section
from chaindrive.model import Drive
from chaindrive.robust.sampling import ReliabilityResult, reliability
from chaindrive.robust.uncertainty import (
    UncertaintySettings,
    uncertainty_model,
    uncertainty_settings,
)

__all__ = ["MODAL_KEYS", "RESPONSE_KEYS", "ROBUST_FIELDS", "ROBUST_OBJECTIVES", "RobustAnalysis",
           "RobustSettings", "robust_constraints", "robust_settings", "robust_statistic"]

ROBUST_FIELDS: tuple[Field, ...] = (
    Field("samples", "int", "states of the uncertainty model per design (Sobol points)",
          default=32, minimum=4, maximum=1 << 16),
    Field("path", "choice", "auto: the batched modal path when only the resonance margin and "
          "f1 are needed; modal; full", default="auto", choices=("auto", "modal", "full")),
)
#: Robust objectives: name → (metric of the states, quantile, sense, unit, description).
ROBUST_OBJECTIVES: dict[str, tuple[str, float, int, str, str]] = {
    "kd_p95": ("coefficient_of_dynamics", 0.95, 1, "-",
               "95th percentile of K_D over the uncertainty model (minimised)"),
    "k2_p05": ("k2", 0.05, -1, "-", "5th percentile of k2 over the uncertainty model "
               "(maximised)"),
    "resonance_margin_p05": ("resonance_margin_percent", 0.05, -1, "%",
                             "5th percentile of the resonance margin over the uncertainty "
                             "model (maximised)"),
}
#: Check keys and metrics the batched modal path gives.
MODAL_KEYS = frozenset({"resonance_margin", "resonance_margin_percent", "f1_hz"})
#: Check keys and metrics that need the states' dynamic response.
RESPONSE_KEYS = frozenset({"k2", "k2min", "k2_with_errors", "coefficient_of_dynamics"})


@dataclass(frozen=True, slots=True)
class RobustSettings:
    """``[optimize.robust]`` with the ``[uncertainty]`` table.

    Parameters
    ----------
    uncertainty : UncertaintySettings
        The uncertainty model's settings (``samples`` replaced by the table's).
    chance : tuple of (str, float)
        (check key, largest probability of failing it [-]).
    path : str
        "modal" or "full" (resolved from "auto").
    objectives : tuple of str
        The robust objectives the problem asks for.
    response : bool
        The states need the dynamic response (K_D, k₂, k₂min are asked for).
    """

    uncertainty: UncertaintySettings
    chance: tuple[tuple[str, float], ...]
    path: str
    objectives: tuple[str, ...] = ()
    response: bool = True

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"uncertainty": self.uncertainty.to_dict(), "chance": dict(self.chance),
                "path": self.path, "objectives": list(self.objectives)}


def _chance(table: Any) -> tuple[tuple[str, float], ...]:
    if not isinstance(table, Mapping):
        raise DesignError("optimize.robust.chance", f"must be a table of check keys and "
                          f"probabilities, got {type(table).__name__}")
    out = []
    for key, value in table.items():
        path = f"optimize.robust.chance.{key}"
        if isinstance(value, bool) or not isinstance(value, int | float) or not (
                0.0 < float(value) < 0.5):
            raise DesignError(path, f"must be a probability in (0, 0.5), got {value!r}")
        out.append((str(key), float(value)))
    return tuple(out)


def robust_settings(table: Mapping[str, Any], uncertainty: Mapping[str, Any] | None,
                    objectives: Sequence[str] = ()) -> RobustSettings:
    """Read ``[optimize.robust]`` (and ``[uncertainty]``); a mistake is one
    :class:`~chaindrive.errors.DesignError` naming the field.

    Parameters
    ----------
    table : Mapping
        The ``[optimize.robust]`` table.
    uncertainty : Mapping | None
        The design file's ``[uncertainty]`` table.
    objectives : sequence of str
        The problem's objectives (the robust ones decide the path).

    Returns
    -------
    RobustSettings
    """
    known = {f.name for f in ROBUST_FIELDS} | {"chance"}
    for key in table:
        if key not in known:
            raise DesignError(f"optimize.robust.{key}", "unknown field" + did_you_mean(key, known)
                              + f" (known: {', '.join(sorted(known))})")
    values = parse_section({k: v for k, v in table.items() if k != "chance"}, ROBUST_FIELDS,
                           "optimize.robust")
    chance = _chance(table.get("chance", {}))
    robust = tuple(o for o in objectives if o in ROBUST_OBJECTIVES)
    if not chance and not robust:
        raise DesignError("optimize.robust", "asks for nothing: add [optimize.robust.chance] "
                          f"or a robust objective ({', '.join(ROBUST_OBJECTIVES)})")
    needs = {k for k, _ in chance} | {ROBUST_OBJECTIVES[o][0] for o in robust}
    path = values["path"]
    if path == "auto":
        path = "modal" if needs <= MODAL_KEYS else "full"
    elif path == "modal" and not needs <= MODAL_KEYS:
        raise DesignError("optimize.robust.path", "the modal path gives only the resonance "
                          f"margin and f1; {', '.join(sorted(needs - MODAL_KEYS))} need "
                          'path = "full"')
    settings = replace(uncertainty_settings(uncertainty), samples=values["samples"])
    return RobustSettings(settings, chance, path, robust, bool(needs & RESPONSE_KEYS))


class RobustAnalysis(Analysis):
    """An :class:`~chaindrive.analysis.Analysis` that also knows its uncertainty model: the
    ``robust`` stage is the probabilities and statistics of the design's states.

    Parameters
    ----------
    design : Drive
        The design.
    robust : RobustSettings
        ``[optimize.robust]`` and ``[uncertainty]``.
    **kwargs : dict
        As :class:`~chaindrive.analysis.Analysis`.
    """

    def __init__(self, design: Drive, *, robust: RobustSettings, **kwargs: Any) -> None:
        super().__init__(design, **kwargs)
        self.robust_settings = robust

    @cached_property
    def robust(self) -> ReliabilityResult:
        """The design's probabilities of failure and metric statistics over its states."""
        s = self.robust_settings
        return reliability(self, uncertainty_model(self, s.uncertainty), path=s.path,
                           response=s.response)


def robust_statistic(analysis: Analysis, name: str) -> float:
    """The robust objective ``name`` of :data:`ROBUST_OBJECTIVES` of a design [its unit].

    Parameters
    ----------
    analysis : Analysis
        A :class:`RobustAnalysis` (a plain analysis has no uncertainty model).
    name : str
        The objective.

    Returns
    -------
    float
    """
    if not isinstance(analysis, RobustAnalysis):
        raise DesignError("optimize.objectives", f"{name} needs an [optimize.robust] table")
    metric, q, _, _, _ = ROBUST_OBJECTIVES[name]
    value = analysis.robust.quantile(metric, q)
    if not math.isfinite(value):
        raise DesignError("optimize.objectives", f"{name}: no state gave {metric}")
    return value


def robust_constraints(analysis: RobustAnalysis) -> dict[str, float]:
    """Chance constraints g = −q_α(margin) ≤ 0 of a design (module docstring), named
    ``P(<key>)``: the α-quantile of a check's margin over the states is ≥ 0 exactly when
    the check fails in at most a fraction α of them [Rockafellar2000].

    Parameters
    ----------
    analysis : RobustAnalysis
        The design's analysis with its ``[optimize.robust]`` chance table.

    Returns
    -------
    dict of str to float
        ``P(<key>)`` → g [-] (−q_α of the margin fraction; ≤ 0 is feasible).
    """
    out = {}
    for key, alpha in analysis.robust_settings.chance:
        q = analysis.robust.margin_quantile(key, alpha)
        if not math.isfinite(q):
            raise DesignError(f"optimize.robust.chance.{key}", "is not a check of this design "
                              f"(known: {', '.join(analysis.robust.margins)})")
        out[f"P({key})"] = -q
    return out
