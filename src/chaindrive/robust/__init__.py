"""Robust design over a chain's life: tolerances, clearances, scatter and wear elongation turned
into the probability that a drive resonates or fails a check, and the optimiser's chance
constraints (docs/robust.md).

Modules: :mod:`.wear` (allowable elongation, the worn chain on the sprockets, catenary sag),
:mod:`.perturbation` (one state of a built drive, polymer moduli against temperature),
:mod:`.analysis` (:class:`PerturbedAnalysis`: the analysis of a state), :mod:`.uncertainty`
(the ``[uncertainty]`` table and its random variables), :mod:`.life` (the life curve),
:mod:`.sampling` (quasi-Monte Carlo probabilities), :mod:`.modal` (the batched modal path on
the whole-drive model), :mod:`.sensitivity` (Sobol indices, SALib), :mod:`.study` (all of it,
in process or on Dask; it imports the synthesis package, so it is not imported here),
:mod:`.synthesis` (``[optimize.robust]``: chance constraints and robust objectives)::

    from chaindrive.robust.study import load_robust, robust_study
    nominal, settings = load_robust("examples/eight_sprocket.toml")
    result = robust_study(nominal, settings)
    result.life.life_elongation, result.reliability.probability("resonance_margin")
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from chaindrive._lazy import lazy_attribute

if TYPE_CHECKING:
    from chaindrive.robust.analysis import PerturbedAnalysis, nominal_analysis
    from chaindrive.robust.life import LifeCurve, WearState, life_curve
    from chaindrive.robust.perturbation import Perturbation
    from chaindrive.robust.sampling import CheckProbability, ReliabilityResult, reliability
    from chaindrive.robust.sensitivity import SensitivityResult, sensitivity
    from chaindrive.robust.uncertainty import (
        UncertaintyModel,
        UncertaintySettings,
        uncertainty_model,
        uncertainty_settings,
    )
    from chaindrive.robust.wear import allowable_elongation

#: Where each name of the package lives: imported on first use (PEP 562), so that importing
#: one submodule (the optimiser imports :mod:`.synthesis`) does not import SciPy's statistics,
#: SALib and pandas with the rest (0.75 s).
_HOME = {
    "PerturbedAnalysis": "analysis", "nominal_analysis": "analysis",
    "LifeCurve": "life", "WearState": "life", "life_curve": "life",
    "Perturbation": "perturbation",
    "CheckProbability": "sampling", "ReliabilityResult": "sampling", "reliability": "sampling",
    "SensitivityResult": "sensitivity", "sensitivity": "sensitivity",
    "UncertaintyModel": "uncertainty", "UncertaintySettings": "uncertainty",
    "uncertainty_model": "uncertainty", "uncertainty_settings": "uncertainty",
    "allowable_elongation": "wear",
}


def __getattr__(name: str) -> Any:
    """The package's names, imported from their submodule on first use."""
    return lazy_attribute(__name__, _HOME, name)


__all__ = [
    "CheckProbability",
    "LifeCurve",
    "Perturbation",
    "PerturbedAnalysis",
    "ReliabilityResult",
    "SensitivityResult",
    "UncertaintyModel",
    "UncertaintySettings",
    "WearState",
    "allowable_elongation",
    "life_curve",
    "nominal_analysis",
    "reliability",
    "sensitivity",
    "uncertainty_model",
    "uncertainty_settings",
]
