"""Multi-strand and multi-contour drives: keyed-joint clearances and load capacity.

[Lyashuk] (eq. 1–18, Table 1) and its generalisation to m contours;
see ``docs/multicontour.md``. Modules: :mod:`.joints` (keys, fits, ΔL), :mod:`.clearance`
(clearance distribution, Table 1, ΔL₃, Monte-Carlo), :mod:`.capacity` (K_m, load sharing),
:mod:`.effect` (the paper's conclusion over pitch × teeth).
"""

from chaindrive.multicontour.capacity import (
    ContourSharingResult,
    LoadSharingSimulation,
    allowable_pressure_multicontour,
    contour_factor_at_risk,
    contour_factor_compatibility,
    contour_factor_km,
    contour_factor_linear_at_risk,
    load_sharing,
    simulate_load_sharing,
    span_deformation,
)
from chaindrive.multicontour.clearance import (
    JOINTS,
    ClearancePlacement,
    LengthDifferenceStats,
    clearance_pdf,
    clearance_placements,
    half_normal_quantile,
    length_difference_stats,
    placement_probabilities,
    sample_clearances,
    simulate_length_difference,
)
from chaindrive.multicontour.drive import ContourCheck, contour_check
from chaindrive.multicontour.effect import (
    EffectMap,
    chain_tensile_strength,
    effect_map,
    shaft_diameter_for_torque,
)
from chaindrive.multicontour.joints import (
    KeyedJoint,
    clearance_coefficient_c4,
    key_corner_angle,
    key_corner_radius,
    keyway_max_clearance,
    length_error_exact,
    length_error_simplified,
    parallel_key,
    sprocket_turn_angle,
)

__all__ = [
    "JOINTS",
    "ClearancePlacement",
    "ContourCheck",
    "ContourSharingResult",
    "EffectMap",
    "KeyedJoint",
    "LengthDifferenceStats",
    "LoadSharingSimulation",
    "allowable_pressure_multicontour",
    "chain_tensile_strength",
    "clearance_coefficient_c4",
    "clearance_pdf",
    "clearance_placements",
    "contour_check",
    "contour_factor_at_risk",
    "contour_factor_compatibility",
    "contour_factor_km",
    "contour_factor_linear_at_risk",
    "effect_map",
    "half_normal_quantile",
    "key_corner_angle",
    "key_corner_radius",
    "keyway_max_clearance",
    "length_difference_stats",
    "length_error_exact",
    "length_error_simplified",
    "load_sharing",
    "parallel_key",
    "placement_probabilities",
    "sample_clearances",
    "shaft_diameter_for_torque",
    "simulate_length_difference",
    "simulate_load_sharing",
    "span_deformation",
    "sprocket_turn_angle",
]
