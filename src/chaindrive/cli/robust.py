"""Tables of ``chaindrive robust``: a presenter of the JSON document of
:class:`chaindrive.robust.study.RobustResult` (it computes nothing), and the check of its
options."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from chaindrive.io.design import UNCERTAINTY_FIELDS, parse_field

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

    TableMaker = Callable[[str, list[str], list[list[Any]]], Table]

__all__ = ["print_robust", "robust_options"]


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
        con.print(f"note: {note}")
    con.print(make("Life curve", ["elongation %", "f1 Hz", "detuning Δ %", "K_D", "k2",
                                  "take-up mm", "sag %", "failed"],
                   [[s["elongation"] * 100, s["f1_hz"], s["resonance_margin_percent"],
                     s["coefficient_of_dynamics"], s["k2"], s["take_up_travel_mm"],
                     s["sag_ratio"] * 100, ", ".join(s["failed"])] for s in life["states"]]))
    con.print(_life_summary(life))
    con.print(make(f"Probability of failure ({rel['samples']} states, {rel['path']} path, "
                   f"{rel['confidence']:.0%} interval)",
                   ["check", "P", "low", "high", "failures", "source"],
                   [[c["key"], c["probability"], c["ci_low"], c["ci_high"],
                     f"{c['failures']}/{c['samples']}", c["source"]] for c in rel["checks"]]))
    con.print(make("Statistics over the states", ["name", "unit", "mean", "p05", "p50", "p95"],
                   [[m["name"], m["unit"], m["mean"], m["p05"], m["p50"], m["p95"]]
                    for m in rel["metrics"]]))
    sens = doc["sensitivity"]
    if sens is not None:
        metrics = list(sens["metrics"])
        rows = [[g, *[sens["metrics"][m]["total"][k] for m in metrics]]
                for k, g in enumerate(sens["groups"])]
        con.print(make(f"Total Sobol indices S_T ({sens['evaluations']} states)",
                       ["group", *metrics], rows))
