"""Tables of ``chaindrive tension`` and ``chaindrive identify``: presenters of the JSON
documents of :mod:`chaindrive.identification` (they compute nothing)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from chaindrive._docstrings import shared_parameters
from chaindrive.cli.tables import console, escape, table
from chaindrive.display import fmt
from chaindrive.io.atomic import atomic_path

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from chaindrive.analysis import Analysis
    from chaindrive.identification import (
        Identification,
        MeasuredDamping,
        MeasuredMode,
        OrderTracking,
    )
    from chaindrive.model import Drive

__all__ = ["measured_dampings", "measured_modes", "measured_tap_modes", "print_calibration",
           "print_identification", "print_link_level_calibration", "print_orders", "print_sag",
           "print_tension", "save_campbell", "save_figure", "save_orders"]


def _check_one_source(natural: list[str] | None, record: Path | None, mode: str) -> None:
    """Raise the error of ``--natural`` unless exactly one of it and ``--record`` is given
    (``mode``: how the hint names the mode, ``"MODE"`` or ``"1"``)."""
    from chaindrive.errors import DesignError  # lazy, as the commands' imports

    if (natural is None) == (record is None):
        raise DesignError("--natural", f"give either --natural {mode}=FREQUENCY or --record FILE")


def _mode_and_value(item: str) -> tuple[int | None, str]:
    """The mode number (None unless a whole number ≥ 1 stands before an ``=``) and the text
    after the ``=`` of a ``MODE=VALUE`` item."""
    mode, sep, value = item.partition("=")
    if not sep or not mode.strip().isdigit() or int(mode) < 1:
        return None, value
    return int(mode), value


@shared_parameters
def measured_modes(drive: Drive, natural: list[str] | None, record: Path | None,
                   tolerance: str | None) -> tuple[list[MeasuredMode], list[str]]:
    """The measured natural frequencies of ``chaindrive calibrate``: from ``--natural
    MODE=FREQUENCY`` (± ``--tolerance``, rectangular: u = a/√3), or from a record's peaks
    matched to the model (:func:`chaindrive.identification.measured_natural_peaks`).

    Parameters
    ----------
    drive : Drive
        The design (for the record's matching).
    natural : list of str | None
        ``["1=62.3Hz", …]``.
    record : Path | None
        A CSV or WAV record.
    tolerance : str | None
        ± of each --natural frequency (None: ±1 % of it, assumed).

    %(measured_modes_assumed)s
    """
    # lazy: the identification stack only for this command
    import chaindrive
    from chaindrive.errors import DesignError
    from chaindrive.identification import identify, measured_natural_peaks, model_lines
    from chaindrive.io.record import read_record

    _check_one_source(natural, record, "MODE")
    if record is not None:
        measured = read_record(record)
        lines = model_lines(chaindrive.analyze(drive, response=False), measured.sample_rate / 2)
        found = measured_natural_peaks(identify(measured, lines))
        if not found:
            raise DesignError("--record", "no peak within 5 % of a natural frequency of the "
                              "model; give --natural MODE=FREQUENCY")
        return found, []
    return _natural_modes(natural or [], tolerance)


def _natural_modes(natural: list[str], tolerance: str | None
                   ) -> tuple[list[MeasuredMode], list[str]]:
    """``--natural MODE=FREQUENCY`` ± ``--tolerance`` (rectangular: u = a/√3), and what is
    assumed."""
    # lazy: the identification stack only for this command
    from chaindrive.errors import DesignError
    from chaindrive.identification import MeasuredMode
    from chaindrive.units import parse_quantity

    out = []
    for item in natural:
        mode, freq = _mode_and_value(item)
        if mode is None:
            raise DesignError("--natural", f"{item!r}; allowed: MODE=FREQUENCY such as 1=62.3Hz")
        f = parse_quantity(freq, "frequency", "--natural")
        a = (0.01 * f if tolerance is None
             else parse_quantity(tolerance, "frequency", "--tolerance"))
        out.append(MeasuredMode(mode, f, a / 3.0 ** 0.5))
    return out, (["each frequency ± 1 %"] if tolerance is None else [])


@shared_parameters
def measured_tap_modes(natural: list[str] | None, record: Path | None, tolerance: str | None
                       ) -> tuple[list[MeasuredMode], list[str]]:
    """The measured first mode along the chain of ``chaindrive calibrate --model links``:
    from ``--natural 1=FREQUENCY`` (± ``--tolerance``, rectangular: u = a/√3), or a record's
    most prominent peak over all its signals (:func:`chaindrive.identification.record_peak`,
    ± half a bin, rectangular: u = Δf/(2√3) [JCGM100, §4.3.7]), taken as mode 1.

    Parameters
    ----------
    natural : list of str | None
        ``["1=76.1Hz"]``.
    record : Path | None
        A CSV or WAV record of the tap test.
    tolerance : str | None
        ± of the --natural frequency (None: ±1 % of it, assumed).

    %(measured_modes_assumed)s
    """
    # lazy: the identification stack only for this command
    from chaindrive.identification import MeasuredMode, record_peak
    from chaindrive.io.record import read_record

    _check_one_source(natural, record, "1")
    if record is not None:
        peak = record_peak(read_record(record))
        return [MeasuredMode(1, peak.frequency, peak.resolution / (2.0 * math.sqrt(3.0)))], []
    return _natural_modes(natural or [], tolerance)


def measured_dampings(damping: list[str] | None, tolerance: float | None
                      ) -> tuple[list[MeasuredDamping], list[str]]:
    """The measured modal damping ratios of ``chaindrive calibrate``: ``--damping MODE=ZETA``
    ± ``--damping-tolerance`` (rectangular: u = a/√3 [JCGM100, §4.3.7]).

    Parameters
    ----------
    damping : list of str | None
        ``["1=0.03", …]``.
    tolerance : float | None
        ± of each ratio [-] (None: ±20 % of it, assumed).

    Returns
    -------
    measured : list of MeasuredDamping
    assumed : list of str
        What rests on an assumed value.
    """
    # lazy: the identification stack only for this command
    from chaindrive.errors import DesignError
    from chaindrive.identification import MeasuredDamping

    if tolerance is not None and not (math.isfinite(tolerance) and 0 < tolerance < 1):
        raise DesignError("--damping-tolerance", f"{tolerance!r}; allowed: above 0 and below 1")
    out = []
    for item in damping or []:
        mode, value = _mode_and_value(item)
        try:
            zeta = float(value)
        except ValueError:
            zeta = math.nan
        if mode is None or not 0 < zeta < 1:
            raise DesignError("--damping", f"{item!r}; allowed: MODE=ZETA with ZETA above 0 "
                              "and below 1, such as 1=0.03")
        a = 0.2 * zeta if tolerance is None else tolerance
        out.append(MeasuredDamping(mode, zeta, a / 3.0 ** 0.5))
    return out, (["each damping ratio ± 20 %"] if out and tolerance is None else [])


def _print_changes(changes: list[dict[str, Any]]) -> None:
    con = console()
    if not changes:
        con.print("no check changed its verdict")
        return
    con.print(table("verdicts changed", ["check", "subject", "before", "after"],
                    [[escape(c["check"]), escape(c["subject"]), c["before"], c["after"]]
                     for c in changes]))


def print_sag(doc: dict[str, Any]) -> None:
    """Print the installed sag calibrated to the tension read and the changed verdicts.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.SagCalibration.to_dict`.
    """
    lo, hi = doc["interval_95_fraction"]
    console().print(f"installed sag s = {_f(100 * doc['fitted_fraction'], 3)} % of the slack "
                    f"span {doc['sag_span']} (the span the design's sag is of), "
                    f"95 % interval {_f(100 * lo, 3)} … {_f(100 * hi, 3)} % (design: "
                    f"{_f(100 * doc['initial_fraction'], 3)} %)")
    _print_changes(doc["verdicts_changed"])


def print_calibration(doc: dict[str, Any]) -> None:
    """Print the fitted link stiffness, its interval, the residuals and the changed verdicts.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.CalibratedDesign.to_dict` with ``assumed``.
    """
    con = console()
    if "fitted_n_per_m" in doc:
        lo, hi = doc["interval_95_n_per_m"]
        con.print(f"link stiffness k_link = {_f(doc['fitted_n_per_m'])} N/m, 95 % interval "
                  f"{_f(lo)} … {_f(hi)} N/m (design: {_f(doc['initial_n_per_m'])} N/m)")
        m = doc["reduced_mass"]
        if m is not None:
            lo, hi = m["interval_95_kg"]
            con.print(f"{escape(m['parameter'])} = {_f(m['fitted_kg'])} kg, 95 % interval "
                      f"{_f(lo)} … {_f(hi)} kg (design: {_f(m['initial_kg'])} kg); correlation "
                      f"with k_link {_f(m['correlation_with_link_stiffness'], 2)}")
        con.print(f"χ²/ν = {_f(doc['chi2_per_dof'], 3)}; {doc['model_evaluations']} model runs")
        con.print(table("residuals", ["mode", "measured Hz", "± Hz", "model Hz", "residual Hz"],
                        [[r["mode"], _f(r["measured_hz"]), _f(r["std_hz"], 2),
                          _f(r["model_hz"]), _f(r["residual_hz"], 3)]
                         for r in doc["residuals"]]))
    z = doc.get("damping")
    if z is not None:
        lo, hi = z["interval_95"]
        design = ("from the materials" if z["initial"] is None else _f(z["initial"], 3))
        con.print(f"chain damping ratio ζ = {_f(z['fitted'], 3)}, 95 % interval "
                  f"{_f(lo, 3)} … {_f(hi, 3)} (design: {design})")
        con.print(f"χ²/ν = {_f(z['chi2_per_dof'], 3)}; {z['model_evaluations']} model runs")
        con.print(table("damping residuals", ["mode", "measured ζ", "± ζ", "model ζ",
                                              "residual"],
                        [[r["mode"], _f(r["measured"], 3), _f(r["std"], 2), _f(r["model"], 3),
                          _f(r["residual"], 2)] for r in z["residuals"]]))
    if doc["assumed"]:
        con.print("assumed: " + escape("; ".join(doc["assumed"])))
    _print_changes(doc["verdicts_changed"])


def print_link_level_calibration(doc: dict[str, Any]) -> None:
    """Print the parameter fitted with the link-level model, its interval, its sensitivity,
    whether the record identifies it, the residuals and the changed verdicts.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.LinkLevelDesign.to_dict` with ``assumed``.
    """
    con = console()
    stiffness = doc["parameter"] == "chain.link_stiffness"
    unit = "n_per_m" if stiffness else "fraction"
    lo, hi = doc[f"interval_95_{unit}"]
    if stiffness:
        con.print(f"link stiffness k_link = {_f(doc['fitted_n_per_m'])} N/m, 95 % interval "
                  f"{_f(lo)} … {_f(hi)} N/m (design: {_f(doc['initial_n_per_m'])} N/m; "
                  "link-level model, first mode along the chain at rest)")
    else:
        con.print(f"installed sag s = {_f(100 * doc['fitted_fraction'])} %, 95 % interval "
                  f"{_f(100 * lo)} … {_f(100 * hi)} % (design: "
                  f"{_f(100 * doc['initial_fraction'])} %; pre-tension T₀ = "
                  f"{_f(doc['fitted_pretension_n'])} N; link-level model, first mode along "
                  "the chain at rest)")
    for r in doc["residuals"]:
        con.print(f"sensitivity d ln f/d ln {'k' if stiffness else 's'} = "
                  f"{_f(r['log_sensitivity'], 3)} (mode {r['mode']})")
    if doc["poorly_identified"]:
        con.print(f"[bold]poorly identified by this record[/bold]: the 95 % interval spans a "
                  f"factor {_f(doc['interval_95_ratio'], 3)}; the frequency hardly depends on "
                  "this parameter")
    for held in doc["held_from_default"]:
        con.print(f"held at {escape(held)}")
    if doc["at_bound"]:
        lo_b, hi_b = doc[f"bounds_{unit}"]
        con.print(f"the fit ended on a bound of its range {_f(lo_b)} … {_f(hi_b)}: the "
                  "measured frequency lies beyond what the model reaches in it")
    con.print(f"χ²/ν = {_f(doc['chi2_per_dof'], 3)}; {doc['model_evaluations']} model runs")
    con.print(table("residuals", ["mode", "measured Hz", "± Hz", "model Hz", "residual Hz"],
                    [[r["mode"], _f(r["measured_hz"]), _f(r["std_hz"], 2),
                      _f(r["model_hz"]), _f(r["residual_hz"], 3)]
                     for r in doc["residuals"]]))
    if doc["assumed"]:
        con.print("assumed: " + escape("; ".join(doc["assumed"])))
    _print_changes(doc["verdicts_changed"])


def save_campbell(result: Identification, analysis: Analysis, output: Path,
                  tracking: OrderTracking | None = None) -> None:
    """Write the model's Campbell diagram with the measured peaks at the design speed
    (:func:`chaindrive.plotting.identification.measured_campbell`), or with the run-up map's
    points at their speeds (:func:`chaindrive.plotting.identification.runup_campbell`),
    atomically.

    Parameters
    ----------
    result : Identification
        The matched record.
    analysis : Analysis
        The analysed design (its Campbell data and driver speed).
    output : Path
        ``.svg``, ``.png`` or ``.pdf``.
    tracking : OrderTracking | None
        The record's order tracking (None: a record at the design speed).

    Raises
    ------
    DesignError
        The design gives no driver speed (no Campbell data).
    """
    # lazy: matplotlib only when a figure is asked for
    from chaindrive.display import RPM_PER_RAD_S
    from chaindrive.errors import DesignError
    from chaindrive.plotting.identification import measured_campbell, runup_campbell

    speed = analysis.drive.driver.speed
    campbell = analysis.dynamics.campbell
    if speed is None or campbell is None:
        raise DesignError("--campbell", "the design gives no driver speed, so no Campbell data")
    fig = (measured_campbell(result, campbell, speed * RPM_PER_RAD_S) if tracking is None
           else runup_campbell(tracking, campbell, speed * RPM_PER_RAD_S))
    _save(fig, output, "--campbell")


def save_orders(tracking: OrderTracking, output: Path) -> None:
    """Write the order spectrum with the shaft and tooth orders
    (:func:`chaindrive.plotting.identification.order_spectrum`) atomically.

    Parameters
    ----------
    tracking : OrderTracking
        The record's order tracking.
    output : Path
        ``.svg``, ``.png`` or ``.pdf``.
    """
    # lazy: matplotlib only when a figure is asked for
    from chaindrive.plotting.identification import order_spectrum

    _save(order_spectrum(tracking), output, "--orders")


def save_figure(result: Identification, output: Path) -> None:
    """Write the measured spectrum with the model's lines
    (:func:`chaindrive.plotting.identification.measured_spectrum`) atomically.

    Parameters
    ----------
    result : Identification
        The matched record.
    output : Path
        ``.svg``, ``.png`` or ``.pdf``.
    """
    # lazy: matplotlib only when a figure is asked for
    from chaindrive.plotting.identification import measured_spectrum

    _save(measured_spectrum(result), output, "--output")


def _save(fig: Figure, output: Path, field: str) -> None:
    """Write ``fig`` atomically to ``output`` in the format its suffix names, at 120 dpi
    (``field``: the option named by an error)."""
    with atomic_path(output, field=field) as tmp:
        fig.savefig(tmp, format=output.suffix.lower().lstrip("."), dpi=120)


def _f(value: Any, digits: int = 4) -> str:
    return "—" if value is None else escape(fmt(value, digits))


def _zeta(peak: dict[str, Any]) -> str:
    """A peak's half-power damping ratio, or "not resolved"."""
    z = peak.get("damping_ratio_half_power")
    return "not resolved" if z is None else _f(z, 3)


def print_tension(doc: dict[str, Any]) -> None:
    """Print the tension read from a span's frequency, its uncertainty and the design's
    expected frequencies.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.SpanTensionReading.to_dict`.
    """
    con = console()
    state = (f"running at {_f(doc['speed_m_s'])} m/s" if doc["speed_m_s"] > 0
             else "stationary")
    con.print(f"span {escape(doc['span'])}: L = {_f(doc['length_m'] * 1000)} mm, "
              f"q = {_f(doc['mass_per_length_kg_m'])} kg/m, {state}, mode {doc['mode']}")
    if doc.get("record") is not None:
        rec = doc["record"]
        con.print(f"frequency read from the record's signal {escape(rec['signal'])}: "
                  f"{_f(rec['frequency_hz'])} Hz ± {_f(rec['resolution_hz'] / 2, 2)} Hz (half a "
                  f"bin; prominence {_f(rec['prominence_db'], 2)} dB)")
    con.print(f"tension T = {_f(doc['tension_n'])} N ± {_f(doc['tension_std_n'], 2)} N "
              "(standard uncertainty)")
    by = doc["tension_std_by_input_n"]
    con.print("  u(T) from " + ", ".join(f"{k.replace('_', ' ')} {_f(v, 2)} N"
                                         for k, v in by.items()))
    if doc["assumed"]:
        con.print("  assumed: " + escape("; ".join(doc["assumed"])))
    if doc["speed_m_s"] > 0:
        con.print(f"  centrifugal part q v² = {_f(doc['centrifugal_tension_n'])} N")
    con.print(f"  sag at this tension {_f(doc['sag_m'] * 1000)} mm; Irvine λ² = "
              f"{_f(doc['irvine_lambda2'], 3)}: a pluck in the plane of the sag would ring "
              f"{_f(doc['inplane_odd_mode_ratio'], 3)}× higher in an odd mode (read a sideways "
              "pluck)")
    rows = [["stationary, design pretension", _f(doc["design_pretension_n"]),
             _f(doc["expected_frequency_standing_hz"])]]
    if doc["expected_frequency_running_hz"] is not None:
        rows.append(["running, design span tension", _f(doc["design_running_tension_n"]),
                     _f(doc["expected_frequency_running_hz"])])
    con.print(table(f"what the design expects (mode {doc['mode']})",
                    ["state", "T N", "f Hz"], rows))


def print_identification(doc: dict[str, Any]) -> None:
    """Print the peaks of a measured record and what each is.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.Identification.to_dict`.
    """
    con = console()
    for sig in doc["signals"]:
        con.print(f"signal {escape(sig['name'])}: {sig['samples']} samples at "
                  f"{_f(sig['sample_rate_hz'])} Hz, resolution {_f(sig['resolution_hz'], 3)} Hz")
        rows = [[_f(p["frequency_hz"]), _f(p["prominence_db"], 3), escape(p["label"]),
                 _f(p["model_frequency_hz"]), _f(p["deviation_percent"], 2),
                 escape(", ".join(p["also_within_tolerance"]) or "—"), _zeta(p)]
                for p in sig["peaks"]]
        con.print(table("peaks", ["f Hz", "prominence dB", "is", "model f Hz", "Δ %",
                                  "also within tolerance", "ζ half-power"], rows))
    con.print(f"tolerance: ±{_f(doc['tolerance_percent'], 3)} % of the model frequency or "
              f"± one frequency bin; prominence ≥ {_f(doc['prominence_db'], 3)} dB")
    con.print("ζ half-power: (f₂ − f₁)/(2 f) from a spectrum whose half-power band spans ≥ 8 "
              "bins, 16 or more segments averaged; \"not resolved\": it does not (a forced "
              "line, or a record too short for that ζ; the JSON gives the reason)")
    for note in doc["notes"]:
        con.print(escape(note))


def print_orders(doc: dict[str, Any]) -> None:
    """Print a run-up record's order peaks and its run-up map, grouped by what each is.

    Parameters
    ----------
    doc : dict
        :meth:`chaindrive.identification.OrderTracking.to_dict`.
    """
    con = console()
    lo, hi = doc["speed_range_rpm"]
    con.print(f"orders: driver angle from {escape(doc['angle_from'])}, {_f(lo)} to {_f(hi)} "
              f"rpm over {_f(doc['duration_s'])} s")
    for sig in doc["signals"]:
        con.print(f"signal {escape(sig['name'])}: {_f(sig['revolutions'])} revolutions, "
                  f"{sig['samples_per_revolution']} samples per revolution, resolution "
                  f"{_f(sig['resolution_orders'], 3)} orders")
        rows = [[_f(p["order"]), _f(p["prominence_db"], 3), escape(p["label"]),
                 _f(p["model_order"]), _f(p["deviation_percent"], 2),
                 escape(", ".join(p["fixed_lines_sweeping_this_order"]) or "—")]
                for p in sig["peaks"]]
        con.print(table("order peaks", ["order", "prominence dB", "is", "model order", "Δ %",
                                        "fixed lines sweeping this order"], rows))
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for p in doc["runup_points"]:
        groups.setdefault((p["signal"], p["label"]), []).append(p)
    rows = []
    for (signal, label), pts in sorted(groups.items(), key=lambda g: (g[0][0], -len(g[1]))):
        rpm = [p["speed_rpm"] for p in pts]
        f = [p["frequency_hz"] for p in pts]
        o = [p["order"] for p in pts]
        rows.append([escape(signal), escape(label), str(len(pts)), f"{_f(min(rpm))}–{_f(max(rpm))}",
                     f"{_f(min(f))}–{_f(max(f))}", f"{_f(min(o), 3)}–{_f(max(o), 3)}"])
    con.print(table(f"run-up map (slices of {_f(doc['runup_slice_s'], 3)} s, bins of "
                    f"{_f(doc['runup_resolution_hz'], 3)} Hz)",
                    ["signal", "is", "points", "rpm", "f Hz", "order"], rows))
    for note in doc["notes"]:
        con.print(escape(note))
