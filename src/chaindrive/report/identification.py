"""The report's section on a measured record (``chaindrive report FILE --record data.csv``):
its peaks labelled by the model, each with its half-power damping ratio, the spectrum with
the model's lines, and for a run-up the order spectrum and the Campbell diagram with the
measured points (:func:`chaindrive.identification.identify_record`; docs/identification.md).
The section reads the identification and computes nothing."""

from __future__ import annotations

from typing import Any

from chaindrive.display import RPM_PER_RAD_S
from chaindrive.plotting.identification import (
    measured_campbell,
    measured_spectrum,
    order_spectrum,
    runup_campbell,
)
from chaindrive.report.content import Block, ReportInput, Table, Text, plot_block

__all__ = ["identification_section"]


def _zeta(p: dict[str, Any]) -> Any:
    z = p["damping_ratio_half_power"]
    return "not resolved" if z is None else z


def identification_section(inp: ReportInput) -> list[Block] | None:
    """Peaks and figures of the measured record (None when the report has none).

    Parameters
    ----------
    inp : ReportInput
        The analysis and the report's settings (``identification``).

    Returns
    -------
    list of Block | None
        The section's blocks (None: the section does not apply).
    """
    result = inp.identification
    if result is None:
        return None
    doc = result.to_dict()
    blocks: list[Block] = [Text(
        f"The record {doc['record']} is matched to the model [Welch1967]: a peak takes the "
        f"nearest model line within ±{doc['tolerance_percent']:g} % of a natural or span "
        "frequency or ±1 % of a working frequency (at least one bin); the others within it "
        "are listed; none: unexplained. Each peak's damping ratio is its half-power "
        "bandwidth (f₂ − f₁)/(2f) [Ewins2000, ch. 4], given where the band spans 8 bins or "
        "more with 16 segments or more averaged, otherwise not resolved (a forced line, or a "
        "record too short).")]
    for sig in doc["signals"]:
        blocks.append(Table(
            f"Peaks of {sig['name']} ({sig['samples']} samples at {sig['sample_rate_hz']:.6g} "
            f"Hz, bins of {sig['resolution_hz']:.3g} Hz)",
            ("f, Hz", "prominence, dB", "is", "model f, Hz", "Δ, %", "also within tolerance",
             "ζ half-power"),
            tuple((p["frequency_hz"], p["prominence_db"], p["label"], p["model_frequency_hz"],
                   p["deviation_percent"], ", ".join(p["also_within_tolerance"]) or "–",
                   _zeta(p)) for p in sig["peaks"])))
    blocks += [Text(note, "note") for note in doc["notes"]]
    blocks.append(plot_block(measured_spectrum(result.spectrum),
                             "Measured spectrum with the model's frequencies", inp.dpi,
                             "identification_spectrum"))
    a = inp.analysis
    campbell, speed = a.dynamics.campbell, a.drive.driver.speed
    orders = result.orders
    if orders is not None:
        od = doc["orders"]
        lo, hi = od["speed_range_rpm"]
        blocks.append(Text(
            f"A run-up from {lo:.4g} to {hi:.4g} rpm (driver angle from {od['angle_from']}): "
            "each signal resampled uniformly in shaft angle and its spectrum taken over "
            "orders (computed order tracking [Brandt2011]); the run-up map's slices give "
            f"measured points of the Campbell diagram (slices of {od['runup_slice_s']:.3g} s, "
            f"bins of {od['runup_resolution_hz']:.3g} Hz)."))
        for sig in od["signals"]:
            blocks.append(Table(
                f"Order peaks of {sig['name']} ({sig['revolutions']:.4g} revolutions, bins of "
                f"{sig['resolution_orders']:.3g} orders)",
                ("order", "prominence, dB", "is", "model order", "Δ, %",
                 "fixed lines sweeping this order"),
                tuple((p["order"], p["prominence_db"], p["label"], p["model_order"],
                       p["deviation_percent"],
                       ", ".join(p["fixed_lines_sweeping_this_order"]) or "–")
                      for p in sig["peaks"])))
        blocks += [Text(note, "note") for note in od["notes"]]
        blocks.append(plot_block(order_spectrum(orders), "Order spectrum with the shaft and "
                                 "tooth orders and the bands the natural frequencies sweep",
                                 inp.dpi, "identification_orders"))
    if campbell is not None and speed is not None:
        fig = (measured_campbell(result.spectrum, campbell, speed * RPM_PER_RAD_S)
               if orders is None else runup_campbell(orders, campbell, speed * RPM_PER_RAD_S))
        blocks.append(plot_block(fig, "Campbell diagram with the measured peaks", inp.dpi,
                                 "identification_campbell"))
    return blocks
