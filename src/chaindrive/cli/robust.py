"""Tables of ``chaindrive robust``: a presenter of the JSON document of
:class:`chaindrive.robust.study.RobustResult` (it computes nothing), and the check of its
options."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from chaindrive.cli.progress import progress_enabled
from chaindrive.cli.tables import escape
from chaindrive.io.design import UNCERTAINTY_FIELDS, parse_field

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

    TableMaker = Callable[[str, list[str], list[list[Any]]], Table]

__all__ = ["print_robust", "robust_options", "robust_progress"]


@contextmanager
def robust_progress(quiet: bool = False) -> Iterator[Callable[[str, int, int], None] | None]:
    """A progress display of the robust study's stages (probabilities, life curve, Sobol
    sample): one bar per stage with the states done, the elapsed time and an estimate of the
    time left, drawn on stderr and removed when done. None (no display) when
    :func:`chaindrive.cli.progress.progress_enabled` is False (``--json``, not a terminal).

    Parameters
    ----------
    quiet : bool
        True in ``--json`` mode.

    Yields
    ------
    callable | None
        ``progress(stage, done, total)``, as :func:`chaindrive.robust.study.robust_study`
        calls it.
    """
    if not progress_enabled(quiet):
        yield None
        return
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TaskID,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  TextColumn("states"), TimeElapsedColumn(), TextColumn("left"),
                  TimeRemainingColumn(), console=Console(stderr=True), transient=True) as bar:
        tasks: dict[str, TaskID] = {}

        def update(stage: str, done: int, total: int) -> None:
            if stage not in tasks:
                tasks[stage] = bar.add_task(stage, total=total or None)
            bar.update(tasks[stage], completed=done, total=total or None)

        yield update


def robust_options(**given: Any) -> dict[str, Any]:
    """The options of ``chaindrive robust`` that override fields of ``[uncertainty]``
    (``--samples``, ``--seed``, ``--wear``), checked by the rules of those fields
    (:data:`chaindrive.io.design.UNCERTAINTY_FIELDS`): a value the design file may not hold
    is refused on the command line too.

    Parameters
    ----------
    **given : object
        Field name → the option's value (None: not given).

    Returns
    -------
    dict
        Field name → checked value, for the options given.

    Raises
    ------
    DesignError
        One line naming the option (``--samples``), the value and what is allowed.
    """
    fields = {f.name: f for f in UNCERTAINTY_FIELDS}
    return {name: parse_field(fields[name], value, f"--{name.replace('_', '-')}")
            for name, value in given.items() if value is not None}


def _pct(x: float | None, digits: int = 3) -> str | None:
    return None if x is None else f"{x * 100:.{digits}g} %"


def _life_summary(life: dict[str, Any]) -> str:
    first = life["first_failure_elongation"]
    text = (f"replacement at {_pct(life['allowable_elongation'])} elongation; "
            + ("no check fails before it" if first is None
               else f"first failure: {life['first_failure']} at {_pct(first)}"))
    if life["life_hours"] is not None:
        text += f"; life {life['life_hours']:,.0f} h (ACA wear relation)"
    else:
        text += "; hours: the chain has no rating for the wear relation"
    if life["take_up_runs_out_elongation"] is not None:
        text += (f"; the take-up runs out at {_pct(life['take_up_runs_out_elongation'])}"
                 " (shorten the chain by two links)")
    if life["failing_when_new"]:
        text += f"; failing when new: {', '.join(life['failing_when_new'])}"
    return text


def _probability_title(rel: dict[str, Any]) -> str:
    """The title of the probability table: the path, the states counted as the failures
    column counts them, the level."""
    if rel["wear_states"]:
        states = (f"{rel['sampled_points']} sampled points × {rel['wear_states']} wear states "
                  f"= {rel['evaluated_states']} states")
    else:
        states = f"{rel['evaluated_states']} states"
    return (f"Probability of failure ({rel['path']} path, {states}, "
            f"{rel['confidence']:.0%} interval)")


def _index(value: float | None, half: float | None, flag: bool = False) -> str:
    if value is None:
        return "–"
    text = f"{value:.2f}±{half:.2f}" if half is not None else f"{value:.2f}"
    return text + ("!" if flag else "")


def _sensitivity_lines(sens: dict[str, Any]) -> list[str]:
    """What the Sobol sample was and whether it converged, the ties and the flags."""
    last = sens["history"][-1] if sens["history"] else None
    widest = (f"widest leading S_T ± {last['widest_leading_half_width']:.3f} "
              f"({last['metric']})" if last and last["widest_leading_half_width"] is not None
              else "no metric varies")
    sizes = " → ".join(str(h.get("base_samples_per_replicate", h["base_samples"]))
                       for h in sens["history"])
    if sens["converged"]:
        verdict = (f"converged: every metric's leading S_T within ±{sens['target_half_width']:g}"
                   f" ({widest})")
    elif sens["budget_hit"]:
        verdict = (f"budget of {sens['budget_evaluations']} states spent before every leading "
                   f"S_T was within ±{sens['target_half_width']:g}: {widest}; rank with care")
    else:
        verdict = widest
    lines = [f"Sobol sample: {sens.get('replicates', 1)} independently scrambled Saltelli "
             f"designs of N = {sizes} base points each, {sens['evaluations']} states "
             f"(Janon et al.'s estimator on the pooled designs; {sens['confidence']:.0%} "
             "intervals: Student-t across the designs, or the pooled bootstrap where wider); "
             f"{verdict}"]
    wide = [f"{metric} ±{m['leading_half_width']:.2f}" + _tail_note(m)
            for metric, m in sens["metrics"].items()
            if m["leading_half_width"] is not None and not m["converged"]]
    if wide:
        lines.append(f"leading S_T wider than ±{sens['target_half_width']:g} (do not rank on "
                     "these): " + ", ".join(wide))
    for metric, m in sens["metrics"].items():
        for tie in m.get("tied") or []:
            lines.append(f"tied on {metric} (intervals overlap, cannot be ranked): "
                         + " = ".join(tie))
    flagged = [f"{metric}: {sens['groups'][k]}" for metric, m in sens["metrics"].items()
               for key in ("first_order_outside", "total_outside")
               for k, f in enumerate(m.get(key) or []) if f]
    if flagged:
        lines.append("! estimate outside [0, 1] by more than its interval (shown clipped): "
                     + "; ".join(flagged))
    if sens["unbuilt"]:
        lines.append(f"{sens['unbuilt']} states could not be built (their metrics took the "
                     "mean of the others)")
    return lines


def print_robust(con: Console, doc: dict[str, Any], make: TableMaker) -> None:
    """Print the robust study as tables.

    Parameters
    ----------
    con : Console
        Where to print.
    doc : dict
        ``RobustResult.to_dict()``.
    make : callable
        Builds a rich table from (title, columns, rows).
    """
    unc, life, rel = doc["uncertainty"], doc["life"], doc["reliability"]
    con.print(f"[bold]{doc['drive']}[/bold] — robust study")
    con.print(make("Uncertainty model", ["name", "group", "distribution", "a", "b", "unit",
                                         "source"],
                   [[v["name"], v["group"], v["distribution"], v["a"], v["b"], v["unit"],
                     v["source"]] for v in unc["variables"]]))
    for note in unc["notes"]:
        con.print(escape(f"note: {note}"))
    con.print(make("Life curve", ["elongation %", "f1 Hz", "detuning Δ %", "K_D", "k2",
                                  "take-up mm", "sag %", "failed"],
                   [[s["elongation"] * 100, s["f1_hz"], s["resonance_margin_percent"],
                     s["coefficient_of_dynamics"], s["k2"], s["take_up_travel_mm"],
                     s["sag_ratio"] * 100, ", ".join(s["failed"])] for s in life["states"]]))
    con.print(escape(_life_summary(life)))
    con.print(escape("held at nominal (life curve): " + "; ".join(life["held_at_nominal"])))
    con.print(make(_probability_title(rel),
                   ["check", "P", "low", "high", "failures", "source"],
                   [[c["key"], c["probability"], c["ci_low"], c["ci_high"],
                     f"{c['failures']}/{c['samples']}", c["source"]] for c in rel["checks"]]))
    con.print(escape("averaged over: " + "; ".join(rel["averaged_over"])))
    con.print(escape(f"held at nominal ({rel['path']} path): "
                     + "; ".join(rel["held_at_nominal"])))
    con.print(make("Statistics over the states", ["name", "unit", "mean", "p05", "p50", "p95"],
                   [[m["name"], m["unit"], m["mean"], m["p05"], m["p50"], m["p95"]]
                    for m in rel["metrics"]]))
    sens = doc["sensitivity"]
    if sens is not None:
        metrics = list(sens["metrics"])
        ms = [sens["metrics"][m] for m in metrics]
        total = [[g, *[_index(m["total"][k], m["total_conf"][k],
                              bool(m.get("total_outside") and m["total_outside"][k]))
                       + ("" if m["rank"] is None else f" {m['rank'][k]}"
                          + ("=" if m["rank"].count(m["rank"][k]) > 1 else ""))
                       for m in ms]] for k, g in enumerate(sens["groups"])]
        first = [[g, *[_index(m["first_order"][k], m["first_order_conf"][k],
                              bool(m.get("first_order_outside") and m["first_order_outside"][k]))
                       for m in ms]] for k, g in enumerate(sens["groups"])]
        con.print(make(f"Total Sobol indices S_T ± {sens['confidence']:.0%} half-width and "
                       f"rank (= tied) ({sens['evaluations']} states, full path)",
                       ["group", *metrics], total))
        con.print(make(f"First-order Sobol indices S1 ± {sens['confidence']:.0%} half-width",
                       ["group", *metrics], first))
        for line in _sensitivity_lines(sens):
            con.print(escape(line))
        con.print(escape("held at nominal (Sobol states): "
                         + "; ".join(sens["held_at_nominal"])))


def _tail_note(metric: dict[str, Any]) -> str:
    """" (1 % of the states hold 87 % of its variance)" where a few states hold much of it
    (why its indices converge slowly), else nothing."""
    if not metric.get("variance_in_few_states"):
        return ""
    share = metric["variance_share_of_farthest_1pct"]
    return f" (1 % of the states hold {share:.0%} of its variance)"
