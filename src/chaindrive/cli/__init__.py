"""The ``chaindrive`` command line (typer + rich): a presenter, it computes nothing itself.

A user's mistake prints one line ``error: <field>: <what is wrong>`` on stderr and exits
with status 2; nothing is written half-way.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
import typer

from chaindrive.display import RAD_S_TO_RPM, fmt
from chaindrive.errors import ChainDriveError, DesignError

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

app = typer.Typer(
    name="chaindrive",
    help="Design and dynamic analysis of roller-chain drives.",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
)
EXIT_USER_ERROR = 2
TEXT_COLUMNS = frozenset({"name", "from", "to", "chain", "field", "method", "governing", "check",
                          "subject", "group", "distribution", "failed", "failures",
                          "required", "result", "unit",
                          "direction", "side", "source", "allowed", "description"})


@contextmanager
def user_errors() -> Iterator[None]:
    """Turn a ChainDriveError into one line on stderr and exit status 2."""
    try:
        yield
    except ChainDriveError as exc:
        print(f"error: {exc}", file=sys.stderr)
        raise typer.Exit(EXIT_USER_ERROR) from None


def escape(text: str) -> str:
    """``text`` with rich markup escaped (a name like ``[chain]`` prints as written)."""
    from rich.markup import escape as rich_escape

    return rich_escape(text)


def _console() -> Console:
    from rich.console import Console  # only the table output needs rich (not --json)

    return Console(highlight=False, soft_wrap=False, width=120)


def _table(title: str, columns: list[str], rows: list[list[Any]]) -> Table:
    from rich.table import Table

    table = Table(title=escape(title), title_justify="left", header_style="bold")
    for c in columns:
        table.add_column(escape(c), justify="left" if c in TEXT_COLUMNS else "right")
    for row in rows:
        table.add_row(*[escape(_fmt(v)) for v in row])
    return table


def _fmt(value: Any) -> str:
    """A table cell, formatted by the presenters' one rule (:func:`chaindrive.display.fmt`)."""
    return fmt(value)


def _write_json(document: dict[str, Any]) -> None:
    sys.stdout.write(json.dumps(document, indent=2, ensure_ascii=False) + "\n")


@app.command()
def analyze(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
    quick: Annotated[bool, typer.Option(
        "--quick", help="stop after the modal analysis (no start-up, steady state or sweep)")]
    = False,
) -> None:
    """Analyse a drive: geometry, speeds, chain, strength, modes and dynamic response.

    The dynamic response is the start-up, the steady state and the amplitude–frequency sweep.
    """
    import chaindrive
    from chaindrive.cli.progress import spinner

    with user_errors(), spinner("analysing …", quiet=as_json):
        result = chaindrive.analyze(chaindrive.load(file), response=not quick)
        document = result.to_dict()
    if as_json:
        _write_json(document)
        return
    _print_analysis(document)


def _print_analysis(doc: dict[str, Any]) -> None:
    """Readable tables of an analysis document."""
    con = _console()
    d, g, k = doc["drive"], doc["geometry"], doc["kinematics"]
    con.print(f"[bold]{escape(d['name'])}[/bold] — chain {escape(d['chain'])} (pitch {d['pitch_mm']:g} mm), "
              f"tooth form {d['tooth_form']}")
    summary = (f"links {g['links']}, chain length {g['chain_length_mm']:.1f} mm, tight length "
               f"{g['tight_length_mm']:.1f} mm ({g['tight_length_pitches']:.3f} pitches)")
    if g["center_distance_mm"] is not None:
        summary += f", centre distance {g['center_distance_mm']:.2f} mm"
    con.print(summary)
    if g["adjusted_sprocket"] is not None:
        con.print(f"take-up: {g['adjusted_sprocket']} moved {g['adjustment_mm']:.2f} mm")
    con.print(_table("Sprockets", ["name", "teeth", "side", "x mm", "y mm", "pitch Ø mm",
                                   "tip Ø mm", "wrap °", "teeth in mesh"],
                     [[s["name"], s["teeth"], s["side"], s["x_mm"], s["y_mm"],
                       s["pitch_diameter_mm"], s["tip_diameter_mm"], s["wrap_angle_deg"],
                       s["teeth_in_mesh"]] for s in g["sprockets"]]))
    con.print(_table("Spans", ["from", "to", "length mm", "pitches", "incl. °", "tight"],
                     [[s["from"], s["to"], s["length_mm"], s["length_pitches"],
                       s["inclination_deg"], s["tight"]] for s in g["spans"]]))
    con.print(f"chain speed {k['chain_speed_m_s']:.3f} m/s "
              f"({k['chain_speed_min_m_s']:.3f}…{k['chain_speed_max_m_s']:.3f}), "
              f"tooth frequency {k['tooth_frequency_hz']:.2f} Hz")
    con.print(_table("Kinematics", ["name", "speed rpm", "direction", "speed variation %"],
                     [[s["name"], s["speed_rpm"], s["direction"], s["speed_variation_percent"]]
                      for s in k["sprockets"]]))
    if doc["strength"] is not None:
        _print_strength(con, doc["strength"], [s["name"] for s in g["sprockets"]],
                        [f"{s['from']}→{s['to']}" for s in g["spans"]])
    if doc["selection"] is not None:
        sel = doc["selection"]
        con.print(f"selection ({sel['method']}): {sel['chain'] or sel['shortfall']}")
    _print_dynamics(con, doc["dynamics"], doc["strength"])
    _print_checks(con, doc["checks"])
    for w in doc["warnings"]:
        con.print(f"[yellow]warning:[/yellow] {escape(w['message'])}")


def _print_checks(con: Console, checks: list[dict[str, Any]]) -> None:
    """The verdict and the table of checks (failed and unverifiable ones first)."""
    failed = [c for c in checks if c["status"] != "pass"]
    if failed:
        con.print(f"[bold red]{len(failed)} of {len(checks)} checks do not pass[/bold red]")
    else:
        con.print(f"[bold green]all {len(checks)} checks pass[/bold green]")
    rows = []
    for c in sorted(checks, key=lambda c: c["status"] == "pass"):
        sym = "≤" if c["kind"] == "max" else "≥"
        rows.append([c["check"], c["subject"], c["value"],
                     "—" if c["limit"] is None else f"{sym} {fmt(c['limit'])}", c["unit"],
                     c["status"], c["source"]])
    con.print(_table("Checks", ["check", "subject", "value", "required", "unit", "result",
                                "source"], rows))


def _print_dynamics(con: Console, dyn: dict[str, Any], st: dict[str, Any] | None) -> None:
    """Natural frequencies, the closest resonances and the dynamic response."""
    freqs = ", ".join(f"{f:.1f}" for f in dyn["natural_frequencies_hz"][:8])
    con.print(f"natural frequencies, Hz: {freqs}{' …' if len(dyn['natural_frequencies_hz']) > 8 else ''}"
              f" (damping ratio {dyn['damping_ratio']:.3f})")
    rows = [[r["label"], r["frequency_hz"], r["natural_frequency_hz"], r["margin_percent"]]
            for r in dyn["resonances"][:5]]
    con.print(_table("Closest resonances", ["name", "working Hz", "natural Hz", "margin %"], rows))
    startup, steady = dyn.get("startup"), dyn.get("steady")
    if steady is not None:
        con.print(f"steady state: largest dynamic span load {max(steady['span_dynamic_load_n']):.1f} N,"
                  f" coefficient of dynamics {dyn['coefficient_of_dynamics']:.3f}")
    if startup is not None:
        con.print(f"start-up: largest span force {startup['max_force_n']:.1f} N, settling time "
                  f"{startup['settling_time_s']:.3f} s")
    if st is not None and "k1" in st:
        con.print(f"safety: k1 {_fmt(st['k1'])}, k2 {_fmt(st['k2'])}, k2min {_fmt(st['k2min'])} "
                  f"(allowable {_fmt(st['allowable_k'])})")


def _print_strength(con: Console, st: dict[str, Any], names: list[str], spans: list[str]) -> None:
    """Loads and safety of an analysis document."""
    con.print(_table("Span tensions", ["from", "tension N"],
                     [[sp, t] for sp, t in zip(spans, st["span_tensions_n"], strict=True)]))
    con.print(_table("Shaft loads", ["name", "shaft load N"],
                     [[n, f] for n, f in zip(names, st["shaft_loads_n"], strict=True)]))
    con.print(f"hinge pressure {_fmt(st['hinge_pressure_mpa'])} MPa (allowable "
              f"{_fmt(st['allowable_pressure_mpa'])}), static safety factor "
              f"{_fmt(st['safety_factor_static'])} (allowable {_fmt(st['allowable_safety_factor'])}),"
              f" wear life {_fmt(st['wear_life_h'])} h"
              f"{' (extrapolated: wear does not limit)' if st['wear_life_extrapolated'] else ''}")


@app.command()
def select(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    method: Annotated[str | None, typer.Option(
        help='"Kэ" or "rating" for every chain (default: each chain by its own method)')] = None,
    strands: Annotated[int | None, typer.Option(help="fix the number of strands")] = None,
    top: Annotated[int, typer.Option(help="show the first N ranked candidates")] = 10,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Rank the family's chains by every check; the first is the one selected."""
    import chaindrive

    with user_errors():
        analysis = chaindrive.analyze(chaindrive.load(file), lazy=True)
        doc = analysis.selection_by(method=method, strands=strands).to_dict(top=top)
    if as_json:
        _write_json(doc)
        return
    con = _console()
    if doc["chain"] is not None:
        con.print(f"selected: [bold]{escape(doc['chain'])}[/bold] ({doc['method']})")
    else:
        con.print(f"[red]{escape(doc['shortfall'])}[/red]")
    con.print(_table(f"Candidates (first {len(doc['candidates'])} of {doc['candidate_count']}, "
                     "ranked)", ["chain", "method", "strands", "mass kg/m", "passed",
                                 "margin %", "governing"],
                     [[c["chain"], c["method"], c["strands"], c["mass_kg_m"], c["passed"],
                       None if c["margin_fraction"] is None else 100 * c["margin_fraction"],
                       c["governing"]] for c in doc["candidates"]]))


@app.command()
def simulate(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    output: Annotated[Path, typer.Option("-o", "--output", help="history.csv")]
    = Path("history.csv"),
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Start-up transient: write the time histories of every span force and sprocket speed."""
    import chaindrive
    from chaindrive.cli.progress import spinner

    with user_errors(), spinner("simulating the start-up …", quiet=as_json):
        _csv_suffix(output)
        result = chaindrive.analyze(chaindrive.load(file), lazy=True)
        startup = result.startup
        if startup is None:
            raise DesignError("drive.power", "the start-up needs the power, the driver speed "
                              "and [dynamics] transient = true")
        names = _span_names(result)
        header = (["time_s", *(f"span_{n}_n" for n in names),
                   *(f"speed_{s.name}_rpm" for s in result.drive.sprockets)])
        rows = np.column_stack((startup.times, startup.span_forces, startup.speeds * RAD_S_TO_RPM))
        _write_csv(output, header, rows)
    if as_json:
        _write_json({"history": str(output.resolve()), **startup.to_dict()})
        return
    print(f"max span force {startup.max_span_force.max():.1f} N, settling time "
          f"{startup.settling_time:.3f} s, k1 = {startup.k1:.2f}; histories written to {output}")


@app.command()
def afc(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    output: Annotated[Path, typer.Option("-o", "--output", help="afc.csv")] = Path("afc.csv"),
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Amplitude–frequency characteristic: dynamic load of every span against the speed."""
    import chaindrive
    from chaindrive.cli.progress import spinner

    with user_errors(), spinner("sweeping the speed …", quiet=as_json):
        _csv_suffix(output)
        result = chaindrive.analyze(chaindrive.load(file), lazy=True)
        sweep = result.afc
        if sweep is None:
            raise DesignError("drive.power", "the sweep needs the power and the driver speed")
        header = ["driver_speed_rpm", "tooth_frequency_hz",
                  *(f"span_{n}_n" for n in _span_names(result))]
        rows = np.column_stack((sweep.driver_speeds * RAD_S_TO_RPM, sweep.tooth_frequencies_hz,
                                sweep.span_load))
        _write_csv(output, header, rows)
    if as_json:
        doc = sweep.to_dict()
        _write_json({"afc": str(output.resolve()), "resonances": doc["resonances"],
                     "max_span_dynamic_load_n": doc["max_span_dynamic_load_n"]})
        return
    for j, k, f, fz in sweep.markers:
        print(f"resonance: mode {j} ({f:.1f} Hz) × harmonic {k} at tooth frequency {fz:.1f} Hz")
    print(f"sweep written to {output}")




def _span_names(result: Any) -> list[str]:
    return [f"{s.start_name}-{s.end_name}" for s in result.geometry.spans]


def _csv_suffix(path: Path) -> None:
    if path.suffix.lower() != ".csv":
        raise DesignError("output", f"must end in .csv, got {str(path)!r}")


def _write_csv(path: Path, header: list[str], rows: Any) -> None:
    """Write a table at once (nothing half-way: the text is built before the file opens)."""
    import io

    buffer = io.StringIO()
    buffer.write(",".join(header) + "\n")
    np.savetxt(buffer, rows, delimiter=",", fmt="%.9g")
    try:
        path.write_text(buffer.getvalue(), encoding="utf-8")
    except OSError as exc:
        raise DesignError("output", f"cannot write {str(path)!r} ({exc.strerror})") from None


@app.command()
def schema(
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Print every field of a design file with its unit, default and allowed values."""
    from chaindrive.io.design import schema as design_schema

    doc = design_schema()
    if as_json:
        _write_json(doc)
        return
    con = _console()
    for section, fields in doc.items():
        header = f"[[{section}]]" if section == "sprockets" else f"[{section}]"
        con.print(_table(header, ["field", "unit", "default", "required", "allowed",
                                  "description"],
                         [[f["field"], f["si_unit"] or "—", f["default"], f["required"],
                           f["allowed"], f["description"]] for f in fields]))


@app.command()
def report(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    output: Annotated[Path, typer.Option("-o", "--output", help="report.html or report.pdf")]
    = Path("report.html"),
    dpi: Annotated[int, typer.Option(help="resolution of the figures")] = 110,
    study: Annotated[list[str] | None, typer.Option(
        "--study", help="add a comparative study: material-pairs, hinge-friction")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Write the design report: inputs, every result table and figure, warnings first."""
    import chaindrive
    from chaindrive.cli.progress import progress_bar
    from chaindrive.report import SECTIONS, write_report

    with user_errors():
        studies = tuple(s.replace("-", "_") for s in study or ())
        result = chaindrive.analyze(chaindrive.load(file), studies=studies)
        with progress_bar("report", total=len(SECTIONS) or None, quiet=as_json) as advance:
            path = write_report(result, output, source=file, dpi=dpi, progress=advance)
    if as_json:
        _write_json({"report": str(path.resolve())})
        return
    print(f"report written to {path}")


@app.command()
def draw(
    file: Annotated[Path, typer.Argument(help="design file (TOML)")],
    output: Annotated[Path, typer.Option("-o", "--output", help="layout.dxf or layout.svg")]
    = Path("layout.dxf"),
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """Write the drawing: contour layout and each sprocket's tooth profile (DXF or SVG, mm)."""
    import chaindrive
    from chaindrive.drawing import write_drawing

    with user_errors():
        path = write_drawing(chaindrive.analyze(chaindrive.load(file)), output)
    if as_json:
        _write_json({"drawing": str(path.resolve())})
        return
    print(f"drawing written to {path}")


@app.command()
def optimize(
    file: Annotated[Path, typer.Argument(help="design file (TOML) with an [optimize] table")],
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
    out: Annotated[Path | None, typer.Option("--out", help="directory for the Pareto designs "
                                             "(one TOML each) and the plot of the front")] = None,
    scheduler: Annotated[str | None, typer.Option(
        "--scheduler", help="address of a Dask scheduler (tcp://host:8786); default: this "
        "process (or a local cluster when --db is given or the problem has "
        "[optimize.robust])")] = None,
    db: Annotated[str | None, typer.Option(
        "--db", help="study database URL (sqlite:///study.db or postgresql+psycopg://…); "
        "a rerun with the same seed resumes from it")] = None,
    seed: Annotated[int | None, typer.Option("--seed", help="random seed (default: the "
                                             "file's [optimize.solver] seed)")] = None,
) -> None:
    """Search the Pareto set of a design ([MultimassChainDrives] optimal synthesis;
    docs/synthesis.md)."""
    from chaindrive.synthesis import load_problem
    from chaindrive.synthesis.solve import solve
    from chaindrive.synthesis.workflow import chosen_analysis, pareto_design_files

    with user_errors():
        problem = load_problem(file)
        evaluator = None
        # a robust problem ([optimize.robust]) runs on Dask by default (chaindrive.robust)
        if scheduler is not None or db is not None or problem.robust is not None:
            from chaindrive.synthesis.studies import DEFAULT_DB, dask_evaluator

            evaluator = dask_evaluator(db=db or DEFAULT_DB, scheduler=scheduler, progress=None)
        result = solve(problem, seed=seed, evaluator=evaluator)
        written: list[str] = []
        plot = None
        if out is not None:
            files = pareto_design_files(result, file.stem, file.parent)
            chosen = chosen_analysis(result, file.parent)
            try:
                out.mkdir(parents=True, exist_ok=True)
                for f in files:
                    (out / f.name).write_text(f.text, encoding="utf-8")
                    written.append(str(out / f.name))
                if chosen is not None:
                    from chaindrive.plotting import pareto_front
                    from chaindrive.report import write_report

                    plot = out / f"{file.stem}_pareto_front.png"
                    pareto_front(result).savefig(plot, dpi=120)
                    report = write_report(chosen, out / f"{file.stem}_pareto_01.html",
                                          source=out / files[0].name, synthesis=result)
                    written.append(str(report))
            except OSError as exc:
                raise DesignError("--out", f"cannot write to {str(out)!r} ({exc.strerror})") from None
    doc = result.to_dict()
    if as_json:
        _write_json({**doc, "files": written, "plot": None if plot is None else str(plot)})
        return
    names = list(result.objectives)
    con = _console()
    con.print(f"[bold]{escape(problem.base.name)}[/bold] — {result.evaluations} designs evaluated by "
              f"{result.method} (seed {result.seed}) in {result.seconds:.1f} s")
    con.print(_table("Start design", ["design", *names, "constraints ok"],
                     [["start", *[result.start.objectives[n] for n in names],
                       result.start.feasible]]))
    rows = []
    for k, p in enumerate(result.pareto, start=1):
        d = p.design
        rows.append([str(k), d["chain"]["designation"],
                     " ".join(str(s["teeth"]) for s in d["sprockets"]),
                     *[p.objectives[n] for n in names], p.constraints_ok])
    con.print(_table(f"Pareto set ({len(rows)} designs)",
                     ["name", "chain", "teeth", *names, "constraints ok"], rows))
    if not rows:
        con.print("no design met every constraint: widen the bounds or the budget")
    for path in written:
        con.print(f"wrote {path}")
    if plot is not None:
        con.print(f"wrote {plot}")


@app.command()
def robust(
    file: Annotated[Path, typer.Argument(help="design file (TOML), its [uncertainty] table")],
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
    samples: Annotated[int | None, typer.Option(
        "--samples", help="states of the probabilities (default: [uncertainty] samples)")] = None,
    seed: Annotated[int | None, typer.Option("--seed", help="seed of the Sobol scrambling")]
    = None,
    wear: Annotated[str | None, typer.Option(
        "--wear", help="wear state: new, worn or life (default: [uncertainty] wear)")] = None,
    modal: Annotated[bool, typer.Option(
        "--modal", help="resonance and f1 only, by the batched modal path (fast)")] = False,
    sensitivity: Annotated[bool, typer.Option(
        "--sensitivity/--no-sensitivity", help="Sobol indices of the tolerance groups")] = True,
    report_file: Annotated[Path | None, typer.Option(
        "--report", help="also write the design report with its life and reliability "
        "section (.html or .pdf)")] = None,
    scheduler: Annotated[str | None, typer.Option(
        "--scheduler", help="address of a Dask scheduler (tcp://host:8786)")] = None,
    db: Annotated[str | None, typer.Option(
        "--db", help="study database URL; the states run on Dask (a local cluster unless "
        "--scheduler) and a rerun resumes from it")] = None,
    workers: Annotated[int | None, typer.Option(
        "--workers", help="workers of the local Dask cluster (implies Dask)")] = None,
) -> None:
    """Robust design over the chain's life: the life curve as the chain wears, the
    probability of failing each check over the tolerances, and which tolerance matters
    (docs/robust.md)."""
    from dataclasses import replace as dc_replace

    from chaindrive.cli.robust import print_robust
    from chaindrive.robust.study import DaskOptions, dask_states, load_robust, robust_study

    with user_errors():
        nominal, settings = load_robust(file)
        changes: dict[str, Any] = {k: v for k, v in (("samples", samples), ("seed", seed),
                                                      ("wear", wear)) if v is not None}
        settings = dc_replace(settings, **changes)
        evaluator = None
        if scheduler is not None or db is not None or workers is not None:
            from chaindrive.synthesis.studies import DEFAULT_DB

            evaluator = dask_states(DaskOptions(db=db or DEFAULT_DB, scheduler=scheduler,
                                                n_workers=workers,
                                                progress=None if not as_json else False))
        result = robust_study(nominal, settings, with_sensitivity=sensitivity and not modal,
                              path="modal" if modal else "full", evaluator=evaluator)
        written = None
        if report_file is not None:
            import chaindrive
            from chaindrive.report import write_report

            written = write_report(chaindrive.analyze(nominal.design), report_file,
                                   source=file, robust=result)
    doc = result.to_dict()
    if as_json:
        _write_json({**doc, "report": None if written is None else str(written.resolve())})
        return
    con = _console()
    print_robust(con, doc, _table)
    if written is not None:
        con.print(f"report written to {written}")


@app.command(name="app")
def app_command(
    host: Annotated[str, typer.Option(help="address to serve on")] = "127.0.0.1",
    port: Annotated[int, typer.Option(help="port to serve on")] = 8501,
) -> None:
    """Start the interactive web page (Streamlit) and print its address."""
    from chaindrive.app import run_app

    status = run_app(host=host, port=port)
    if status:
        raise typer.Exit(status)


@app.command()
def catalog(
    name: Annotated[str | None, typer.Argument(help="show one chain or material")] = None,
    materials: Annotated[bool, typer.Option("--materials", help="list materials")] = False,
    standard: Annotated[str | None, typer.Option(help='only this standard, e.g. "ISO 606"')]
    = None,
    file: Annotated[list[Path] | None, typer.Option("--file", help="a catalogue of your own")]
    = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON document")] = False,
) -> None:
    """List the chain and material catalogue, or show one entry."""
    from chaindrive import catalog as cat

    extra = tuple(file or ())
    with user_errors():
        if materials:
            rows: list[Any] = [cat.find_material(name, extra)] if name else list(
                cat.materials(extra))
            doc = [_material_dict(m) for m in rows]
        else:
            if name:
                rows = [cat.find_chain(name, extra)]
            else:
                rows = [c for c in cat.chains(extra)
                        if standard is None or c.standard.lower() == standard.lower()]
            doc = [_chain_dict(c) for c in rows]
    if as_json:
        _write_json({"materials" if materials else "chains": doc})
        return
    _print_records(doc, "Materials" if materials else "Chains")


def _chain_dict(c: Any) -> dict[str, Any]:
    return {
        "designation": c.designation, "standard": c.standard, "ansi": c.ansi,
        "pitch_mm": c.pitch * 1e3, "strands": c.strands,
        "roller_diameter_mm": c.roller_diameter * 1e3, "pin_diameter_mm": c.pin_diameter * 1e3,
        "inner_width_mm": c.inner_width * 1e3, "plate_depth_mm": c.plate_depth * 1e3,
        "transverse_pitch_mm": c.transverse_pitch * 1e3,
        "breaking_load_kn": c.breaking_load / 1e3, "mass_kg_m": c.mass_per_length,
        "bearing_area_mm2": None if c.bearing_area is None else c.bearing_area * 1e6,
        "source": c.source,
    }


def _material_dict(m: Any) -> dict[str, Any]:
    return {
        "name": m.name, "family": m.family, "density_kg_m3": m.density,
        "youngs_modulus_gpa": m.youngs_modulus / 1e9,
        "tensile_strength_mpa": None if m.tensile_strength is None else m.tensile_strength / 1e6,
        "friction_vs_steel": m.friction_vs_steel, "source": m.source,
    }


#: Short column headers of the catalogue listing (key in the JSON → header).
LIST_HEADERS = {
    "designation": "designation", "ansi": "ANSI", "pitch_mm": "p mm", "strands": "rows",
    "roller_diameter_mm": "d1 mm", "pin_diameter_mm": "d2 mm", "inner_width_mm": "b1 mm",
    "breaking_load_kn": "Q kN", "mass_kg_m": "q kg/m", "bearing_area_mm2": "A mm²",
    "name": "name", "density_kg_m3": "ρ kg/m³", "youngs_modulus_gpa": "E GPa",
    "tensile_strength_mpa": "Rm MPa", "friction_vs_steel": "μ vs steel",
}


def _print_records(doc: list[dict[str, Any]], title: str) -> None:
    con = _console()
    if len(doc) == 1:
        for key, value in doc[0].items():
            con.print(f"{key:>22}: {_fmt(value)}")
        return
    keys = [k for k in (doc[0] if doc else {}) if k in LIST_HEADERS]
    table = _table(title, [LIST_HEADERS[k] for k in keys], [[r[k] for k in keys] for r in doc])
    table.columns[0].no_wrap = True
    table.columns[0].justify = "left"
    con.print(table)


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``chaindrive`` script."""
    run: Callable[..., Any] = app
    run(args=argv, prog_name="chaindrive")
