"""From measurement to model: a span's tension from its measured transverse frequency, a
measured vibration record's peaks matched to the model's frequencies, and the model's
uncertain inputs calibrated to measured frequencies.

Compute only: the command line reads the files and hands arrays in.

Entry points: :func:`span_tension_from_frequency`, :func:`span_tension_reading` and
:func:`record_peak` (:mod:`.tension`, :mod:`.reading`); :func:`model_lines` and :func:`identify`
(:mod:`.spectrum`); :func:`identify_record` and :func:`track_orders` (:mod:`.orders`, order
tracking of a run-up); :func:`calibrated_design` (:mod:`.calibration`, :mod:`.damping`);
:func:`calibrated_design_link_level` (:mod:`.linklevel_fit`: a tap test fitted with the
link-level model).
"""

from chaindrive.identification.calibration import (
    CalibratedDesign,
    MeasuredMode,
    calibrated_design,
    measured_natural_peaks,
)
from chaindrive.identification.damping import (
    DampingCalibration,
    MeasuredDamping,
    calibrate_damping_ratio,
    free_decay_damping_ratio,
    half_power_damping_ratio,
    log_decrement_damping_ratio,
)
from chaindrive.identification.linklevel_damping import (
    LinkLevelDampingCalibration,
    TapTest,
    calibrate_link_level_damping,
    decay_of_signal,
)
from chaindrive.identification.linklevel_fit import (
    LinkLevelCalibration,
    LinkLevelDesign,
    calibrate_link_level,
    calibrated_design_link_level,
)
from chaindrive.identification.orders import (
    OrderTracking,
    RecordIdentification,
    identify_record,
    track_orders,
)
from chaindrive.identification.reading import (
    RecordPeak,
    SagCalibration,
    SpanTensionReading,
    calibrated_sag,
    record_peak,
    span_tension_reading,
)
from chaindrive.identification.spectrum import Identification, identify, model_lines
from chaindrive.identification.tension import (
    TensionEstimate,
    expected_frequency,
    span_tension_from_frequency,
    string_tension,
)

__all__ = [
    "CalibratedDesign",
    "DampingCalibration",
    "Identification",
    "LinkLevelCalibration",
    "LinkLevelDampingCalibration",
    "LinkLevelDesign",
    "MeasuredDamping",
    "MeasuredMode",
    "OrderTracking",
    "RecordIdentification",
    "RecordPeak",
    "SagCalibration",
    "SpanTensionReading",
    "TapTest",
    "TensionEstimate",
    "calibrate_damping_ratio",
    "calibrate_link_level",
    "calibrate_link_level_damping",
    "calibrated_design",
    "calibrated_design_link_level",
    "calibrated_sag",
    "decay_of_signal",
    "expected_frequency",
    "free_decay_damping_ratio",
    "half_power_damping_ratio",
    "identify",
    "identify_record",
    "log_decrement_damping_ratio",
    "measured_natural_peaks",
    "model_lines",
    "record_peak",
    "span_tension_from_frequency",
    "span_tension_reading",
    "string_tension",
    "track_orders",
]
