"""Link-level (discrete) model of a roller-chain drive: every roller a mass particle, every
link a spring–damper with hinge friction, every roller in contact with the actual tooth gap
of the sprocket it runs on, the sprockets rigid bodies driven by the motor and loaded by the
resistance laws ([Pedersen2004], [Pedersen2005]; docs/linklevel.md).

Entry point::

    from chaindrive.linklevel import simulate
    result = simulate(drive, duration_s=1.0)        # a start-up from rest
    result.to_dict()                                 # summaries (SI, units in the keys)
    names, table = result.history()                  # CSV-ready (times × columns)
"""

from __future__ import annotations

from chaindrive.linklevel.compare import (
    DURATION,
    ModelComparison,
    checked_duration,
    model_comparison,
)
from chaindrive.linklevel.kernel import compiled as kernel_compiled
from chaindrive.linklevel.model import LinkLevelModel, TorsionalAttachment, build_model
from chaindrive.linklevel.modes import LinearModes, linear_modes
from chaindrive.linklevel.result import LinkLevelResult
from chaindrive.linklevel.simulate import simulate

__all__ = ["DURATION", "LinearModes", "LinkLevelModel", "LinkLevelResult", "ModelComparison",
           "TorsionalAttachment", "build_model", "checked_duration", "kernel_compiled", "linear_modes",
           "model_comparison", "simulate"]
