"""The report's life and reliability section: the robust study of a drive
(:class:`chaindrive.robust.study.RobustResult`), when the report is built with one."""

from __future__ import annotations

from typing import Any

from chaindrive._docstrings import shared_parameters
from chaindrive.plotting.robust import (
    life_curve_figure,
    probability_figure,
    sensitivity_figure,
)
from chaindrive.report.content import Block, ReportInput, Table, Text, plot_block

__all__ = ["robust_section"]


def _rows(rows: list[list[Any]]) -> tuple[tuple[Any, ...], ...]:
    return tuple(tuple(r) for r in rows)


def _summary(life: dict[str, Any]) -> str:
    first = life["first_failure_elongation"]
    text = (f"The chain is replaced at {life['allowable_elongation']:.2%} elongation "
            "[DiamondChainWear]; "
            + ("no check fails before it." if first is None else
               f"the first check to fail as it wears is {life['first_failure']}, at "
               f"{first:.3%}."))
    if life["life_hours"] is not None:
        text += (f" Life to that point: {life['life_hours']:,.0f} h by the ACA wear relation "
                 "[Shigley2015, Eq. 17-40].")
    if life["take_up_runs_out_elongation"] is not None:
        text += (f" The take-up has absorbed its capacity at "
                 f"{life['take_up_runs_out_elongation']:.2%} (then shorten the chain by two "
                 "links) [DiamondChainTension].")
    if life["failing_when_new"]:
        text += f" Failing already when new: {', '.join(life['failing_when_new'])}."
    return text


def _index(m: dict[str, Any], k: int) -> str:
    """S_T ± half-width and rank of group k of a metric's entry ("–": no variance)."""
    v, h = m["total"][k], m["total_conf"][k]
    if v is None or h is None or m["rank"] is None:
        return "–"
    tied = m["rank"].count(m["rank"][k]) > 1
    return (f"{v:.2f} ± {h:.2f} ({m['rank'][k]}{'=' if tied else ''})"
            + (" !" if m["total_outside"][k] else ""))


def _sobol_summary(sens: dict[str, Any]) -> str:
    """The Sobol sample in words: its size, whether it converged, what cannot be ranked."""
    sizes = " → ".join(str(h.get("base_samples_per_replicate", h["base_samples"]))
                       for h in sens["history"])
    text = (f"{sens.get('replicates', 1)} independently scrambled Saltelli samples grown "
            f"N = {sizes} base points each ({sens['evaluations']} states on the full path) "
            "[Saltelli2010], [Herman2017], indices by Janon et al.'s estimator on the pooled "
            "samples [Janon2014], intervals Student-t across the samples [Owen2013]; ")
    if sens["converged"]:
        text += (f"every metric's leading S_T is within ±{sens['target_half_width']:g}.")
    else:
        wide = [f"{m} (±{e['leading_half_width']:.2f})" for m, e in sens["metrics"].items()
                if e["leading_half_width"] is not None and not e["converged"]]
        text += ((f"the budget of {sens['budget_evaluations']} states was spent first; "
                  if sens["budget_hit"] else "")
                 + f"leading S_T wider than ±{sens['target_half_width']:g}, not to be ranked "
                 f"on: {', '.join(wide)}.")
    flagged = [m for m, e in sens["metrics"].items()
               if any(e.get("first_order_outside") or []) or any(e.get("total_outside") or [])]
    if flagged:
        text += (" ! an estimate left [0, 1] by more than its interval (shown clipped): "
                 + ", ".join(flagged) + ".")
    return text


@shared_parameters
def robust_section(inp: ReportInput) -> list[Block] | None:
    """Life curve, probabilities of failure and sensitivity indices (None without a robust
    study).

    %(section)s
    """

    result = inp.robust
    if result is None:
        return None
    doc = result.to_dict()
    life, rel = doc["life"], doc["reliability"]
    blocks: list[Block] = [Text(_summary(life) + " The life curve holds at nominal: "
                                + "; ".join(life["held_at_nominal"]) + ".")]
    blocks.append(Table("Life curve", ("elongation, %", "f1, Hz", "detuning Δ, %", "K_D",
                                       "k2", inp.col("take-up", "length"), "sag, %",
                                       "failed checks"),
                        _rows([[s["elongation"] * 100, s["f1_hz"],
                                s["resonance_margin_percent"], s["coefficient_of_dynamics"],
                                s["k2"], None if s["take_up_travel_mm"] is None
                                else inp.val(s["take_up_travel_mm"] * 1e-3, "length"),
                                s["sag_ratio"] * 100,
                                ", ".join(s["failed"])] for s in life["states"]])))
    blocks.append(plot_block(life_curve_figure(result.life, units=inp.units),
                             "The drive as its chain wears", inp.dpi, "robust_life"))
    states = (f"{rel['sampled_points']} sampled points × {rel['wear_states']} wear states = "
              f"{rel['evaluated_states']} states" if rel["wear_states"]
              else f"{rel['evaluated_states']} states")
    blocks.append(Table(f"Probability of failure over the tolerances ({rel['path']} path, "
                        f"{states}, {rel['confidence']:.0%} interval)",
                        ("check", "probability", "low", "high", "failures", "source"),
                        _rows([[c["key"], c["probability"], c["ci_low"], c["ci_high"],
                                f"{c['failures']}/{c['samples']}", c["source"]]
                               for c in rel["checks"]])))
    blocks.append(Text("Averaged over " + "; ".join(rel["averaged_over"]) + ". Held at "
                       f"nominal on the {rel['path']} path: "
                       + "; ".join(rel["held_at_nominal"]) + "."))
    blocks.append(plot_block(probability_figure(result.reliability),
                             "Probability of failing each check", inp.dpi, "robust_probability"))
    if result.sensitivity is not None:
        sens = doc["sensitivity"]
        metrics = list(sens["metrics"])
        blocks.append(Table(f"Total Sobol indices S_T ± {sens['confidence']:.0%} half-width by "
                            "tolerance group, with the rank (= tied: the intervals overlap)",
                            ("group", *metrics),
                            _rows([[g, *[_index(sens["metrics"][m], k) for m in metrics]]
                                   for k, g in enumerate(sens["groups"])])))
        blocks.append(Text(_sobol_summary(sens)))
        blocks.append(plot_block(sensitivity_figure(result.sensitivity),
                                 "Which tolerance matters", inp.dpi, "robust_sensitivity"))
    blocks += [Text(note, "note") for note in doc["uncertainty"]["notes"]]
    return blocks
