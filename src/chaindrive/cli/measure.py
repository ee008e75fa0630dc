"""Tables of ``chaindrive tension`` and ``chaindrive identify``: presenters of the JSON
documents of :mod:`chaindrive.identification` (they compute nothing)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from chaindrive.cli.tables import console, escape, table
from chaindrive.display import fmt
from chaindrive.io.atomic import atomic_path

if TYPE_CHECKING:
    from chaindrive.identification import Identification

__all__ = ["print_identification", "print_tension", "save_figure"]


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

    fig = measured_spectrum(result)
    with atomic_path(output, field="--output") as tmp:
        fig.savefig(tmp, format=output.suffix.lower().lstrip("."), dpi=120)


def _f(value: Any, digits: int = 4) -> str:
    return "—" if value is None else escape(fmt(value, digits))


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
                 escape(", ".join(p["also_within_tolerance"]) or "—")]
                for p in sig["peaks"]]
        con.print(table("peaks", ["f Hz", "prominence dB", "is", "model f Hz", "Δ %",
                                  "also within tolerance"], rows))
    con.print(f"tolerance: ±{_f(doc['tolerance_percent'], 3)} % of the model frequency or "
              f"± one frequency bin; prominence ≥ {_f(doc['prominence_db'], 3)} dB")
    for note in doc["notes"]:
        con.print(escape(note))
