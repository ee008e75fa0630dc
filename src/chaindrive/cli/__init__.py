"""The ``chaindrive`` command line (typer + rich): a presenter, it computes nothing itself.

Every command runs inside the safety net of :mod:`chaindrive.cli.safety`: a user's mistake
prints one line ``error: <field>: <what is wrong>`` on stderr and exits with status 2;
anything unforeseen prints one line naming it and the log file with its traceback, and
exits with status 1. Every file is written atomically (:mod:`chaindrive.io.atomic`): it is
complete or absent, never half-written.
"""

from __future__ import annotations

import functools
import json
import re
import sys
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
import typer

from chaindrive.cli import tables
from chaindrive.cli.safety import EXIT_USER_ERROR, exit_on_signal, guarded, one_line
from chaindrive.cli.threads import limit_blas_threads
from chaindrive.display import RPM_PER_RAD_S, convert, fmt, static_state_note, unit_system
from chaindrive.errors import ChainDriveError, DesignError, did_you_mean
from chaindrive.io.atomic import atomic_directory, write_text
from chaindrive.io.finite import check_document, check_rows
from chaindrive.units import MAX_TEXT, shown

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from chaindrive.analysis import Analysis
    from chaindrive.model import ChainSpec
    from chaindrive.synthesis.solve import SynthesisResult

app = typer.Typer(
    name="chaindrive",
    help="Design and dynamic analysis of roller-chain drives.",
    epilog=("\b\nExit status:\n"
            "  0    the command ran (a design that fails a check is reported, not an error)\n"
            "  2    a mistake in the input: one line names the field, the value and what is allowed\n"
            "  1    an unforeseen error: one line names it and the log file with its traceback\n"
            "  128+N  ended by signal N (130 after Ctrl-C); no file is left half-written"),
    add_completion=False,
    rich_markup_mode=None,  # help texts name TOML tables such as [optimize]: no markup
    no_args_is_help=True,
    pretty_exceptions_enable=False,
)
#: Resolution of the report's figures [dpi]: 50 is legible on screen; 600 prints finer than
#: the eye resolves at reading distance (a 600 dpi figure is 5 000 px wide, 60 MB in memory).
DPI_RANGE = (50, 600)
#: TCP ports the web page may serve on: 0 is not one (the system would pick a free port and
#: the address printed would be wrong), 65535 is the largest port number.
PORT_RANGE = (1, 65535)
UNITS_HELP = "units of the tables: SI (mm, N, kW, MPa) or US (in, lbf, hp, psi)"
# the argument and options many commands take, declared once (typer reads the Annotated alias)
DesignFile = Annotated[Path, typer.Argument(help="design file (TOML)")]
JsonFlag = Annotated[bool, typer.Option("--json", help="print one JSON document")]
UnitsOption = Annotated[str, typer.Option("--units", help=UNITS_HELP)]
PulsesOption = Annotated[int, typer.Option("--pulses-per-rev", help="tacho pulses per driver "
                                           "revolution", min=1)]
# Lazy imports: the commands import inside their bodies only what each runs, so that
# ``--help``, ``schema`` and ``catalog`` start without the heavy stacks (measured with
# ``python -X importtime``, cumulative: chaindrive.analysis ≈0.15 s, chaindrive.report ≈0.5 s
# with matplotlib, chaindrive.synthesis and chaindrive.robust ≈2.7 s each with Optuna, pymoo,
# Dask and SALib; this module itself ≈0.2 s).


@contextmanager
def user_errors() -> Iterator[None]:
    """Turn a ChainDriveError into one line on stderr and exit status 2.

    Yields
    ------
    None
        The block runs; a :class:`~chaindrive.errors.ChainDriveError` it raises becomes
        ``error: <message>`` on stderr and :class:`typer.Exit` with
        :data:`~chaindrive.cli.safety.EXIT_USER_ERROR`.
    """
    try:
        yield
    except ChainDriveError as exc:
        print(one_line(f"error: {exc}"), file=sys.stderr)
        raise typer.Exit(EXIT_USER_ERROR) from None


def _fmt(value: Any) -> str:
    """A value formatted by the presenters' one rule (:func:`chaindrive.display.fmt`)."""
    return fmt(value)


def _write_json(document: dict[str, Any]) -> None:
    """Print one JSON document; a NaN or infinity in it is a computation that did not
    converge (:class:`~chaindrive.io.finite.NonFiniteError`), named by its path.

    The encoder refuses a NaN or infinity itself (``allow_nan=False``), so the document is
    walked for the path of one (:func:`~chaindrive.io.finite.check_document`) only when the
    encoder refused it: a finite document is walked once, not twice."""
    def encoded() -> str:
        return json.dumps(document, indent=2, ensure_ascii=False, allow_nan=False)

    try:
        text = encoded()
    except (ValueError, TypeError):  # walked outside the handler: no chained traceback
        text = None
    if text is None:
        check_document(document)  # names the non-finite number, as before the encoder
        text = encoded()  # refused for another reason: the encoder's own error
    sys.stdout.write(text + "\n")


def _say_written(what: str, path: Path, as_json: bool) -> None:
    """Say where ``what`` (a report, a drawing) was written: ``{what: absolute path}`` as
    JSON, else one line."""
    if as_json:
        _write_json({what: str(path.resolve())})
    else:
        print(f"{what} written to {path}")


@app.command()
def analyze(
    file: DesignFile,
    as_json: JsonFlag = False,
    quick: Annotated[bool, typer.Option(
        "--quick", help="stop after the modal analysis (no start-up, steady state or sweep)")]
    = False,
    units: UnitsOption = "SI",
) -> None:
    """Analyse a drive: geometry, speeds, chain, strength, modes and dynamic response.

    The dynamic response is the start-up, the steady state and the amplitude–frequency sweep.
    """
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.progress import spinner

    with user_errors(), spinner("analysing …", quiet=as_json):
        system = unit_system(units)
        result = chaindrive.analyze(chaindrive.load(file), response=not quick)
        document = result.to_dict()
    if as_json:
        _write_json(document)
        return
    check_document(document)
    tables.print_analysis(document, result.checks(), system, quick=quick)


@app.command()
def select(
    file: DesignFile,
    method: Annotated[str | None, typer.Option(
        help='"Kэ" or "rating" for every chain (default: each chain by its own method)')] = None,
    strands: Annotated[int | None, typer.Option(help="fix the number of strands (1 to 8)",
                                                min=1, max=8)] = None,
    top: Annotated[int, typer.Option(help="show the first N ranked candidates", min=1,
                                     max=10_000)] = 10,
    as_json: JsonFlag = False,
    units: UnitsOption = "SI",
) -> None:
    """Rank the family's chains by every check; the first is the one selected."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.progress import spinner

    with user_errors(), spinner("checking the family's chains …", quiet=as_json):
        system = unit_system(units)
        analysis = chaindrive.analyze(chaindrive.load(file), lazy=True)
        doc = analysis.selection_by(method=method, strands=strands).to_dict(top=top)
    if as_json:
        _write_json(doc)
        return
    check_document(doc)
    tables.print_selection(doc, system)


@app.command()
def simulate(
    file: DesignFile,
    output: Annotated[Path, typer.Option("-o", "--output", help="history.csv")]
    = Path("history.csv"),
    model: Annotated[str, typer.Option(
        "--model", help="ring: the whole-drive model (default); links: the link-level model "
        "(every link a body, slower)")] = "ring",
    duration: Annotated[str | None, typer.Option(
        "--duration", help="simulated time of the link-level run, e.g. 0.5s (default: the "
        "design's start-up duration, at most 10 s)")] = None,
    as_json: JsonFlag = False,
    units: Annotated[str, typer.Option("--units", help=UNITS_HELP + "; the CSV stays SI, "
                                       "its columns named with their units")] = "SI",
) -> None:
    """Start-up transient: write the time histories of every span force and sprocket speed
    (with --model links also the span transverse motion and every link's tension)."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.analysis import startup_progress
    from chaindrive.cli.progress import step_progress

    if model not in ("ring", "links"):
        with user_errors():
            raise DesignError("--model", f"must be ring or links, got {model!r}")
    with user_errors():
        system = unit_system(units)
    if model == "links":
        _simulate_links(file, output, duration, as_json)
        return
    with user_errors(), step_progress("simulating the start-up", quiet=as_json) as update, \
            startup_progress(update):
        if duration is not None:
            raise DesignError("--duration", "applies to --model links; the whole-drive "
                              "start-up lasts [dynamics] startup_duration")
        _csv_suffix(output)
        result = chaindrive.analyze(chaindrive.load(file), lazy=True)
        startup = result.startup
        if startup is None:
            raise DesignError("drive.power", "the start-up needs the power, the driver speed "
                              "and [dynamics] transient = true")
        names = _span_names(result)
        header = (["time_s", *(f"span_{n}_n" for n in names),
                   *(f"speed_{s.name}_rpm" for s in result.drive.sprockets)])
        rows = np.column_stack((startup.times, startup.span_forces, startup.speeds * RPM_PER_RAD_S))
        _write_csv(output, header, rows)
    if as_json:
        _write_json({"history": str(output.resolve()), **startup.to_dict()})
        return
    k1 = "" if startup.k1 is None else f", k1 = {startup.k1:.2f}"
    force, unit = convert(float(startup.max_span_force.max()), "force", system)
    print(f"max span force {fmt(force)} {unit}{k1}; "
          f"{tables.startup_times_text(startup.to_dict())}; histories written to {output}")


def _simulate_links(file: Path, output: Path, duration: str | None, as_json: bool) -> None:
    """``simulate --model links``: the link-level start-up of the analysis (study "links")
    written as CSV (time, sprocket speeds, span forces and transverse offsets, every link's
    tension); its summary with --json."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.progress import progress_bar
    from chaindrive.io.design import Field, parse_quantity_as
    from chaindrive.linklevel import DURATION, checked_duration, kernel_compiled

    what = ("link-level run" if kernel_compiled() else
            "link-level run (the first compiles the model: ≈ 8 s idle)")
    # the link-level kernel runs in one call: the elapsed time, no estimate
    with user_errors(), progress_bar(what, quiet=as_json):
        # the example a message shows lies within the option's range (Field.example_text)
        option = Field("--duration", "time", "simulated time of the link-level run",
                       minimum=DURATION.low, maximum=DURATION.high, reason=DURATION.reason)
        seconds = None if duration is None else checked_duration(
            parse_quantity_as(duration, "time", "--duration", option.example_text()),
            "--duration")
        _csv_suffix(output)
        analysis = chaindrive.analyze(chaindrive.load(file), studies=("links",), lazy=True,
                                      link_duration_s=seconds)
        result = analysis.link_level
        if result is None:
            raise DesignError("drive.power", "the link-level model needs the power and the "
                              "driver speed")
        header, rows = result.history(links=True)
        _write_csv(output, header, rows)
    if as_json:
        _write_json({"history": str(output.resolve()), **result.to_dict()})
        return
    kd = result.coefficient_of_dynamics
    print(f"link-level model, {result.times[-1]:.3f} s simulated: max span force "
          f"{result.peak_span_force.max():.1f} N, K_D = {_fmt(kd)}; histories written to "
          f"{output}")
    note = static_state_note(result.equilibrium)
    if note is not None:
        print(f"note: {note}")


@app.command()
def afc(
    file: DesignFile,
    output: Annotated[Path, typer.Option("-o", "--output", help="afc.csv")] = Path("afc.csv"),
    as_json: JsonFlag = False,
) -> None:
    """Amplitude–frequency characteristic: dynamic load of every span against the speed."""
    # lazy: only what this command runs (see "Lazy imports" above)
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
        rows = np.column_stack((sweep.driver_speeds * RPM_PER_RAD_S, sweep.tooth_frequencies_hz,
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




def _span_names(result: Analysis) -> list[str]:
    return [f"{s.start_name}-{s.end_name}" for s in result.geometry.spans]


def _csv_suffix(path: Path) -> None:
    if path.suffix.lower() != ".csv":
        raise DesignError("output", f"must end in .csv, got {str(path)!r}")


def _write_csv(path: Path, header: list[str], rows: NDArray[np.float64]) -> None:
    """Write a table atomically (:func:`chaindrive.io.atomic.write_text`); a NaN or infinity
    in it is a computation that did not converge, and nothing is written."""
    import io

    check_rows(path.name, header, rows)

    buffer = io.StringIO()
    buffer.write(",".join(header) + "\n")
    np.savetxt(buffer, rows, delimiter=",", fmt="%.9g")
    write_text(path, buffer.getvalue())


@app.command()
def schema(
    as_json: JsonFlag = False,
) -> None:
    """Print every field of a design file with its unit, default and allowed values."""
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.io.design import schema as design_schema

    doc = design_schema()
    if as_json:
        _write_json(doc)
        return
    tables.print_schema(doc)


@app.command()
def report(
    file: DesignFile,
    output: Annotated[Path, typer.Option("-o", "--output", help="report.html or report.pdf")]
    = Path("report.html"),
    dpi: Annotated[int, typer.Option(help=f"resolution of the figures ({DPI_RANGE[0]} to "
                                     f"{DPI_RANGE[1]})", min=DPI_RANGE[0],
                                     max=DPI_RANGE[1])] = 110,
    study: Annotated[list[str] | None, typer.Option(
        "--study", help="add a comparative study: material-pairs, hinge-friction, links (the "
        "link-level model, slower)")] = None,
    as_json: JsonFlag = False,
    units: UnitsOption = "SI",
    summary: Annotated[bool, typer.Option(
        "--summary", help="the two-page sign-off sheet (verdict, governing checks, defaults "
        "and estimates, the drive; the chain and sprockets to buy) instead of the full "
        "report")] = False,
    record: Annotated[Path | None, typer.Option(
        "--record", help="a measured record (CSV/WAV) matched to the model in its own "
        "section, as `chaindrive identify` matches it")] = None,
    speed: Annotated[str | None, typer.Option(
        "--speed", help="the record's driver speed column (a run-up: its orders)")] = None,
    tacho: Annotated[str | None, typer.Option(
        "--tacho", help="or the record's driver tacho column")] = None,
    pulses: PulsesOption = 1,
) -> None:
    """Write the design report: the verdict first, then inputs, results and checks."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.progress import progress_bar
    from chaindrive.report import SECTIONS, write_report

    with user_errors():
        if record is None and (speed is not None or tacho is not None):
            raise DesignError("--speed", "needs --record (the record whose speed it is)")
        studies = tuple(s.replace("-", "_") for s in study or ())
        result = chaindrive.analyze(chaindrive.load(file), studies=studies)
        check_document(result.to_dict())  # the report shows these numbers
        identification = None
        if record is not None:
            # lazy: the record's reading and identification only when a record is given
            from chaindrive.identification import identify_record
            from chaindrive.io.record import read_record

            identification = identify_record(read_record(record), result, speed=speed,
                                             tacho=tacho, pulses_per_revolution=pulses)
            check_document(identification.to_dict())
        with progress_bar("report", total=None if summary else len(SECTIONS) or None,
                          quiet=as_json) as advance:
            path = write_report(result, output, source=file, dpi=dpi, progress=advance,
                                units=unit_system(units), summary=summary,
                                identification=identification)
    _say_written("report", path, as_json)


@app.command()
def draw(
    file: DesignFile,
    output: Annotated[Path, typer.Option("-o", "--output", help="layout.dxf, layout.svg or "
                                         "layout.pdf")]
    = Path("layout.dxf"),
    sprocket: Annotated[str | None, typer.Option(
        "--sprocket", help="draw this sprocket alone (its manufacturing drawing)")] = None,
    as_json: JsonFlag = False,
) -> None:
    """Write the drawing: the dimensioned layout and each sprocket's manufacturing drawing,
    or one sprocket alone (DXF, SVG or PDF, mm; each on an ISO 5457 sheet at its scale)."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.drawing import write_drawing

    with user_errors():
        analysis = chaindrive.analyze(chaindrive.load(file), response=False)
        check_document(analysis.to_dict())  # the numbers the drawing dimensions
        path = write_drawing(analysis, output, sprocket=sprocket)
    _say_written("drawing", path, as_json)


@app.command()
def optimize(
    file: Annotated[Path, typer.Argument(help="design file (TOML) with an [optimize] table")],
    as_json: JsonFlag = False,
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
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.cli.progress import progress_bar
    from chaindrive.synthesis import load_problem
    from chaindrive.synthesis.solve import solve

    with user_errors():
        problem = load_problem(file)
        evaluator = None
        # a robust problem ([optimize.robust]) runs on Dask by default (chaindrive.robust)
        if scheduler is not None or db is not None or problem.robust is not None:
            # lazy: a command imports only what it runs, so that `--help`, `schema` and `catalog`
            # start fast (-X importtime: analysis ≈0.15 s, report ≈0.5 s, synthesis and robust ≈2.7
            # s each)
            from chaindrive.synthesis.studies import DEFAULT_DB, DaskEvaluator

            evaluator = DaskEvaluator(db=db or DEFAULT_DB, scheduler=scheduler, progress=False)
        designs = problem.solver.population * problem.solver.generations
        try:
            with progress_bar("optimising: designs evaluated", total=designs,
                              quiet=as_json) as advance:
                if evaluator is not None:  # the bar moves as each chunk of designs is stored
                    evaluator.on_stored = _steps(advance)
                result = solve(problem, seed=seed, evaluator=_counted(evaluator, advance))
        finally:
            if evaluator is not None:
                evaluator.close()
        written: list[str] = []
        plot = None
        if out is not None:
            written, plot = _write_pareto(result, file, out)
    doc = result.to_dict()
    if as_json:
        _write_json({**doc, "files": written, "plot": None if plot is None else str(plot)})
        return
    check_document(doc)
    tables.print_optimisation(problem.base.name, result,
                              [*written, *([] if plot is None else [str(plot)])])


def _steps(advance: Callable[[str | None], None]) -> Callable[[int], None]:
    """A callback moving the bar ``n`` steps at once."""
    def moved(n: int) -> None:
        for _ in range(n):
            advance(None)

    return moved


def _counted(evaluator: Callable[[Any, Any], list[Any]] | None,
             advance: Callable[[str | None], None]) -> Callable[[Any, Any], list[Any]]:
    """The optimiser's batch evaluator that moves the progress bar one step a design: in this
    process design by design, on a cluster chunk by chunk as they are stored
    (``on_stored`` of the evaluator; designs found stored are not counted)."""
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.synthesis.solve import serial_evaluator

    def counted(problem: Any, xs: Any) -> list[Any]:
        if evaluator is None:
            out = []
            for x in xs:
                out += serial_evaluator(problem, [x])
                advance(None)
            return out
        batch = evaluator(problem, xs)
        if getattr(evaluator, "on_stored", None) is None:  # else moved as chunks are stored
            for _ in batch:
                advance(None)
        return batch

    return counted


def _write_pareto(result: SynthesisResult, file: Path, out: Path) -> tuple[list[str], Path | None]:
    """Write the Pareto designs (one TOML each), the plot of the front and the report of the
    first into ``out`` — all or nothing (:func:`chaindrive.io.atomic.atomic_directory`)."""
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.synthesis.workflow import chosen_analysis, pareto_design_files, pareto_drives

    drives = pareto_drives(result, file.parent)
    files = pareto_design_files(drives, file.stem)
    chosen = chosen_analysis(drives)
    names = [f.name for f in files]
    plot_name = None
    with atomic_directory(out, field="--out") as tmp:
        for f in files:
            (tmp / f.name).write_text(f.text, encoding="utf-8")
        if chosen is not None:
            # lazy: a command imports only what it runs, so that `--help`, `schema` and `catalog`
            # start fast (-X importtime: analysis ≈0.15 s, report ≈0.5 s, synthesis and robust ≈2.7
            # s each)
            from chaindrive.plotting import pareto_front
            from chaindrive.report import write_report

            plot_name = f"{file.stem}_pareto_front.png"
            pareto_front(result).savefig(tmp / plot_name, dpi=120)
            report = write_report(chosen, tmp / f"{file.stem}_pareto_01.html",
                                  source=tmp / files[0].name, synthesis=result)
            names.append(report.name)
    return [str(out / n) for n in names], None if plot_name is None else out / plot_name


@app.command()
def robust(
    file: Annotated[Path, typer.Argument(help="design file (TOML), its [uncertainty] table")],
    as_json: JsonFlag = False,
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
    sensitivity_budget: Annotated[int | None, typer.Option(
        "--sensitivity-budget", help="states the Sobol sample may grow to (default: "
        "[uncertainty] sensitivity_budget)")] = None,
    report_file: Annotated[Path | None, typer.Option(
        "--report", help="also write the design report with its life and reliability "
        "section (.html or .pdf)")] = None,
    scheduler: Annotated[str | None, typer.Option(
        "--scheduler", help="address of a Dask scheduler (tcp://host:8786)")] = None,
    db: Annotated[str | None, typer.Option(
        "--db", help="study database URL; the states run on Dask (a local cluster unless "
        "--scheduler) and a rerun resumes from it")] = None,
    workers: Annotated[int | None, typer.Option(
        "--workers", help="workers of the local Dask cluster (implies Dask)", min=1,
        max=256)] = None,
) -> None:
    """Robust design over the chain's life: the life curve as the chain wears, the
    probability of failing each check over the tolerances, and which tolerance matters
    (docs/robust.md)."""
    from dataclasses import replace as dc_replace

    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.cli.robust import print_robust, robust_options, robust_progress
    from chaindrive.robust.study import DaskOptions, dask_states, load_robust, robust_study

    with user_errors():
        # the options obey the rules of their [uncertainty] fields, before any work
        changes = robust_options(samples=samples, seed=seed, wear=wear,
                                 sensitivity_budget=sensitivity_budget)
        if modal and (db, scheduler, workers) != (None, None, None):
            option = "--db" if db is not None else (
                "--scheduler" if scheduler is not None else "--workers")
            raise DesignError(option, "applies to the full study, not to --modal (the batched "
                              "modal path runs in this process, in seconds, and stores nothing)")
        nominal, settings = load_robust(file)
        settings = dc_replace(settings, **changes)
        evaluator = None
        if scheduler is not None or db is not None or workers is not None:
            # lazy: a command imports only what it runs, so that `--help`, `schema` and `catalog`
            # start fast (-X importtime: analysis ≈0.15 s, report ≈0.5 s, synthesis and robust ≈2.7
            # s each)
            from chaindrive.synthesis.studies import DEFAULT_DB

            evaluator = dask_states(DaskOptions(db=db or DEFAULT_DB, scheduler=scheduler,
                                                n_workers=workers,
                                                progress=None if not as_json else False))
        # a bar per stage on a terminal (Dask draws its own: one live display at a time)
        with robust_progress(quiet=as_json or evaluator is not None) as progress:
            result = robust_study(nominal, settings,
                                  with_sensitivity=sensitivity and not modal,
                                  path="modal" if modal else "full", evaluator=evaluator,
                                  progress=progress)
        written = None
        if report_file is not None:
            # lazy: a command imports only what it runs, so that `--help`, `schema` and `catalog`
            # start fast (-X importtime: analysis ≈0.15 s, report ≈0.5 s, synthesis and robust ≈2.7
            # s each)
            import chaindrive
            from chaindrive.report import write_report

            written = write_report(chaindrive.analyze(nominal.design), report_file,
                                   source=file, robust=result)
    doc = result.to_dict()
    if as_json:
        _write_json({**doc, "report": None if written is None else str(written.resolve())})
        return
    check_document(doc)
    con = tables.console()
    print_robust(con, doc, tables.table)
    if written is not None:
        con.print(f"report written to {written}")


@app.command(name="app")
def app_command(
    host: Annotated[str, typer.Option(help="address to serve on")] = "127.0.0.1",
    port: Annotated[int, typer.Option(help=f"port to serve on ({PORT_RANGE[0]} to {PORT_RANGE[1]})",
                                      min=PORT_RANGE[0], max=PORT_RANGE[1])] = 8501,
) -> None:
    """Start the interactive web page (Streamlit) and print its address."""
    # lazy: only what this command runs (see "Lazy imports" above)
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
    as_json: JsonFlag = False,
) -> None:
    """List the chain and material catalogue, or show one entry."""
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive import catalog as cat

    extra = tuple(file or ())
    with user_errors():
        if materials:
            if standard is not None:
                raise DesignError("--standard", "selects chains; it does not apply with "
                                  "--materials")
            rows: list[Any] = [cat.find_material(name, extra)] if name is not None else list(
                cat.materials(extra))
            doc = [_material_dict(m) for m in rows]
        else:
            every = cat.chains(extra)
            wanted = None if standard is None else catalog_standard(standard, every)
            if name is not None:  # an empty name is refused by the look-up, not read as none
                rows = [cat.find_chain(name, extra)]
                if wanted is not None and not _of_standard(rows[0], wanted):
                    raise DesignError("--standard", f"{rows[0].designation} is not a {wanted} "
                                      f"chain (it is {rows[0].standard})")
            else:
                rows = [c for c in every if wanted is None or _of_standard(c, wanted)]
            doc = [_chain_dict(c) for c in rows]
    if as_json:
        _write_json({"materials" if materials else "chains": doc})
        return
    _print_records(doc, "Materials" if materials else "Chains")


#: Short names of the chain standards (upper case, no spaces) → the standard they name: the
#: spellings a ``[chain] standard`` is read in by :func:`chaindrive.catalog.chains_by_pitch`.
STANDARD_ALIASES = {"ISO": "ISO 606", "ISO606": "ISO 606", "GOST": "GOST 13568",
                    "GOST13568": "GOST 13568", "ГОСТ": "GOST 13568", "ГОСТ13568": "GOST 13568",
                    "ASMEB29.1": "ANSI", "ANSI/ASMEB29.1": "ANSI"}


def catalog_standard(given: str, chains: Iterable[ChainSpec]) -> str:
    """The standard ``--standard`` names among the standards of ``chains``.

    Parameters
    ----------
    given : str
        The option's value: a standard of the catalogue (``"ISO 606"``, ``"ANSI"``,
        ``"GOST 13568"``, ``"polymer"`` or the standard of a user's file), case and spaces
        ignored, or a short name of :data:`STANDARD_ALIASES`.
    chains : iterable of ChainSpec
        The catalogue listed.

    Returns
    -------
    str
        The standard as the catalogue writes it (``"ANSI"``: the chains with an ANSI number).

    Raises
    ------
    DesignError
        On ``--standard`` with the value and the standards allowed.
    """
    known = sorted({c.standard for c in chains} | {"ANSI"})
    spellings = {re.sub(r"\s+", "", k.upper()): k for k in known}
    spellings.update({k: v for k, v in STANDARD_ALIASES.items() if v in known})
    found = spellings.get(re.sub(r"\s+", "", given.upper()))
    if found is None:
        raise DesignError("--standard", f"must be one of {', '.join(repr(k) for k in known)} "
                          f"(or ISO, GOST for short), got {shown(given)}"
                          + did_you_mean(given[:MAX_TEXT], known))
    return found


def _of_standard(chain: ChainSpec, standard: str) -> bool:
    """True when ``chain`` belongs to ``standard`` (``"ANSI"``: it has an ANSI number, as in
    a design file's ``[chain] standard``)."""
    return chain.ansi is not None if standard == "ANSI" else chain.standard == standard


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
    con = tables.console()
    if not doc:
        con.print(f"no {title.lower()}")
        return
    if len(doc) == 1:
        for key, value in doc[0].items():
            con.print(f"{key:>22}: {tables.escape(_fmt(value))}")
        return
    keys = [k for k in (doc[0] if doc else {}) if k in LIST_HEADERS]
    table = tables.table(title, [LIST_HEADERS[k] for k in keys],
                         [[r[k] for k in keys] for r in doc])
    table.columns[0].no_wrap = True
    table.columns[0].justify = "left"
    con.print(table)


@app.command()
def tension(
    file: DesignFile,
    span: Annotated[str, typer.Option("--span", help="the span, FROM-TO (e.g. S1-S2)")],
    frequency: Annotated[str | None, typer.Option(
        "--frequency", help="measured transverse frequency of a sideways pluck, e.g. "
        "23.4Hz")] = None,
    record: Annotated[Path | None, typer.Option(
        "--record", help="or a record of the pluck (CSV/WAV): its most prominent peak, "
        "± half a bin")] = None,
    mode: Annotated[int, typer.Option("--mode", help="its mode number n", min=1)] = 1,
    running: Annotated[bool, typer.Option(
        "--running", help="measured with the chain running at the design speed")] = False,
    frequency_tol: Annotated[str | None, typer.Option(
        "--frequency-tolerance", help="± of the frequency (default 0 Hz, assumed; with "
        "--record half the spectrum's bin)")] = None,
    length_tol: Annotated[str | None, typer.Option(
        "--length-tolerance", help="± of the span length (default 2 mm, assumed)")] = None,
    mass_tol: Annotated[float | None, typer.Option(
        "--mass-tolerance", help="± of the mass per metre in % (default 5, assumed)")] = None,
    write_calibrated: Annotated[Path | None, typer.Option(
        "--write-calibrated", help="write the design with the installed sag whose "
        "pretension is the tension read (stationary only; TOML)")] = None,
    as_json: JsonFlag = False,
) -> None:
    """A span's tension from its measured transverse frequency (stationary or running),
    with its uncertainty and the frequency the design's pretension gives."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.measure import print_sag, print_tension
    from chaindrive.identification import calibrated_sag, record_peak, span_tension_reading
    from chaindrive.io.design import drive_to_toml
    from chaindrive.io.record import read_record
    from chaindrive.units import parse_quantity

    with user_errors():
        check_toml_target(write_calibrated)
        if (frequency is None) == (record is None):
            raise DesignError("--frequency", "give either --frequency F or --record FILE")
        drive = chaindrive.load(file)
        peak = None if record is None else record_peak(read_record(record))
        if peak is not None:
            f = peak.frequency
        else:
            f = parse_quantity(str(frequency), "frequency", "--frequency")
            if not f > 0:
                raise DesignError("--frequency", f"must be above 0 Hz, got {frequency!r}")
        if mass_tol is not None and not mass_tol >= 0:
            raise DesignError("--mass-tolerance", f"must be ≥ 0 %, got {mass_tol!r}")
        assumed = tuple(a for a, given in (("frequency ± 0 Hz", frequency_tol or peak),
                                           ("span length ± 2 mm", length_tol),
                                           ("mass per metre ± 5 %", mass_tol)) if given is None)
        f_tol = (parse_quantity(frequency_tol, "frequency", "--frequency-tolerance")
                 if frequency_tol is not None else
                 0.5 * peak.resolution if peak is not None else 0.0)
        reading = span_tension_reading(
            chaindrive.analyze(drive, response=False), span, f, mode=mode,
            running=running, assumed=assumed, frequency_tolerance=f_tol,
            length_tolerance=parse_quantity(length_tol or "2 mm", "length", "--length-tolerance"),
            mass_tolerance=(5.0 if mass_tol is None else mass_tol) / 100.0)
        doc = reading.to_dict()
        if peak is not None:
            doc["record"] = peak.to_dict()
        if write_calibrated is not None:
            sag = calibrated_sag(drive, reading)
            doc["calibration"] = sag.to_dict()
            check_document(doc)
            write_text(write_calibrated, drive_to_toml(sag.drive), field="--write-calibrated")
    if as_json:
        _write_json(doc)
        return
    check_document(doc)
    print_tension(doc)
    if write_calibrated is not None:
        print_sag(doc["calibration"])
        print(f"calibrated design written to {write_calibrated}")


@app.command()
def identify(
    file: DesignFile,
    record: Annotated[Path, typer.Option("--record", help="measured record: CSV with a "
                                         "time_s (or time_ms) column and signals, or WAV")],
    tolerance: Annotated[float, typer.Option("--tolerance", help="match tolerance in % of "
                                             "the model frequency (at least one bin)")] = 5.0,
    prominence: Annotated[float, typer.Option("--prominence", help="least peak prominence "
                                              "in dB")] = 15.0,
    speed: Annotated[str | None, typer.Option(
        "--speed", help="the record's driver speed column, its unit ending its name "
        "(speed_rpm, omega_rad_s, n_hz): order spectrum and run-up map")] = None,
    tacho: Annotated[str | None, typer.Option(
        "--tacho", help="or the record's driver tacho column (pulses)")] = None,
    pulses: PulsesOption = 1,
    output: Annotated[Path | None, typer.Option("-o", "--output", help="spectrum plot with "
                                                "the model's frequencies (.svg, .png, .pdf)")]
    = None,
    orders: Annotated[Path | None, typer.Option(
        "--orders", help="order spectrum plot with the shaft and tooth orders (needs --speed "
        "or --tacho; .svg, .png, .pdf)")] = None,
    campbell: Annotated[Path | None, typer.Option(
        "--campbell", help="Campbell diagram with the measured peaks at the design speed, or "
        "over the run-up with --speed/--tacho (.svg, .png, .pdf)")] = None,
    as_json: JsonFlag = False,
) -> None:
    """Match a measured record's spectral peaks to the model: natural frequency (mode),
    tooth-order excitation, shaft speed, span transverse frequency, or unexplained; each
    peak's half-power damping ratio; with a speed or tacho column, the order spectrum and
    the run-up map."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.measure import (
        print_identification,
        print_orders,
        save_campbell,
        save_figure,
        save_orders,
    )
    from chaindrive.identification import identify_record
    from chaindrive.io.record import read_record

    with user_errors():
        for name, path in (("--output", output), ("--campbell", campbell),
                           ("--orders", orders)):
            if path is not None and path.suffix.lower() not in (".svg", ".png", ".pdf"):
                raise DesignError(name, f"{str(path)!r}: allowed: a .svg, .png or .pdf file")
        if orders is not None and speed is None and tacho is None:
            raise DesignError("--orders", "needs the record's speed or tacho column "
                              "(--speed or --tacho)")
        analysis = chaindrive.analyze(chaindrive.load(file), response=False)
        result = identify_record(read_record(record), analysis, speed=speed, tacho=tacho,
                                 pulses_per_revolution=pulses, tolerance=tolerance / 100.0,
                                 prominence_db=prominence)
        doc = result.to_dict()
        check_document(doc)
        if output is not None:
            save_figure(result.spectrum, output)
        if orders is not None and result.orders is not None:
            save_orders(result.orders, orders)
        if campbell is not None:
            save_campbell(result.spectrum, analysis, campbell, result.orders)
    if as_json:
        _write_json(doc)
        return
    print_identification(doc)
    if doc["orders"] is not None:
        print_orders(doc["orders"])
    for what, path in (("spectrum", output), ("order spectrum", orders),
                       ("Campbell diagram", campbell)):
        if path is not None:
            print(f"{what} written to {path}")


@app.command()
def calibrate(
    file: DesignFile,
    natural: Annotated[list[str] | None, typer.Option(
        "--natural", help="a measured natural frequency MODE=FREQUENCY, e.g. 1=62.3Hz "
        "(repeat for more modes)")] = None,
    record: Annotated[Path | None, typer.Option(
        "--record", help="or a measured record (CSV/WAV): its peaks matched to the model's "
        "natural frequencies")] = None,
    tolerance: Annotated[str | None, typer.Option(
        "--tolerance", help="± of each --natural frequency (default ±1 % of it, assumed)")]
    = None,
    damping: Annotated[list[str] | None, typer.Option(
        "--damping", help="a measured modal damping ratio MODE=ZETA, e.g. 1=0.03 (from a "
        "logarithmic decrement or half-power bandwidth; repeat for more modes)")] = None,
    damping_tolerance: Annotated[float | None, typer.Option(
        "--damping-tolerance", help="± of each --damping ratio (default ±20 % of it, "
        "assumed)")] = None,
    uncertain_mass: Annotated[str | None, typer.Option(
        "--uncertain-mass", help="a sprocket whose reduced mass is uncertain: fitted with the "
        "link stiffness (needs two or more natural frequencies)")] = None,
    write_calibrated: Annotated[Path | None, typer.Option(
        "--write-calibrated", help="write the calibrated design file (TOML)")] = None,
    model: Annotated[str, typer.Option(
        "--model", help="the forward model: 'ring' (the whole-drive model's elastic modes "
        "at the running state) or 'links' (the link-level model's first mode along the "
        "chain at rest: a tap test of a stationary drive; mode 1 only)")] = "ring",
    parameter: Annotated[str, typer.Option(
        "--parameter", help="with --model links: what is fitted, 'link_stiffness' or 'sag'")]
    = "link_stiffness",
    as_json: JsonFlag = False,
) -> None:
    """Fit the chain's link stiffness to measured natural frequencies and its damping ratio
    to measured modal damping ratios (least squares, 95 % intervals), re-run the checks and
    say which verdicts changed; with --model links, the link stiffness or the sag to a tap
    test's first mode along the chain."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.measure import measured_dampings, measured_modes, print_calibration
    from chaindrive.cli.progress import spinner
    from chaindrive.identification import calibrated_design

    if model not in ("ring", "links"):
        with user_errors():
            raise DesignError("--model", f"{model!r}; allowed: ring, links")
    if model == "links":
        _calibrate_links(file, natural, record, tolerance, parameter, write_calibrated,
                         as_json, damping=bool(damping), uncertain_mass=uncertain_mass)
        return
    with user_errors():
        if parameter != "link_stiffness":
            raise DesignError("--parameter", f"{parameter!r} with --model ring; allowed: "
                              "link_stiffness (sag: with --model links, or chaindrive tension)")
        check_toml_target(write_calibrated)
        drive = chaindrive.load(file)
        measured, assumed = (([], []) if damping and natural is None and record is None
                              else measured_modes(drive, natural, record, tolerance))
        ratios, assumed_z = measured_dampings(damping, damping_tolerance)
        with spinner("fitting the model to the measurements", quiet=as_json):
            result = calibrated_design(drive, measured, ratios, uncertain_mass)
    _calibration_out(result, assumed + assumed_z, write_calibrated, as_json, print_calibration)


def _calibration_out(result: Any, assumed: list[str], write_calibrated: Path | None,
                     as_json: bool, show: Callable[[dict[str, Any]], None]) -> None:
    """What ``chaindrive calibrate`` writes of a fit: its JSON document with the assumed
    inputs (``--json``) or ``show`` of it, and the calibrated design file when asked."""
    # lazy: only what this command runs (see "Lazy imports" above)
    from chaindrive.io.design import drive_to_toml

    with user_errors():
        doc = {**result.to_dict(), "assumed": assumed}
        check_document(doc)
        if write_calibrated is not None:
            write_text(write_calibrated, drive_to_toml(result.drive), field="--write-calibrated")
    if as_json:
        _write_json(doc)
        return
    show(doc)
    if write_calibrated is not None:
        print(f"calibrated design written to {write_calibrated}")


def _calibrate_links(file: Path, natural: list[str] | None, record: Path | None,
                     tolerance: str | None, parameter: str, write_calibrated: Path | None,
                     as_json: bool, *, damping: bool, uncertain_mass: str | None) -> None:
    """``chaindrive calibrate --model links``: the link stiffness or the sag fitted with the
    link-level model (:func:`chaindrive.identification.calibrated_design_link_level`)."""
    # lazy: only what this command runs (see "Lazy imports" above)
    import chaindrive
    from chaindrive.cli.measure import measured_tap_modes, print_link_level_calibration
    from chaindrive.cli.progress import spinner
    from chaindrive.identification import calibrated_design_link_level

    with user_errors():
        if damping:
            raise DesignError("--damping", "not with --model links; allowed: with --model "
                              "ring (the link-level damping is not fitted)")
        if uncertain_mass is not None:
            raise DesignError("--uncertain-mass", "not with --model links; allowed: with "
                              "--model ring")
        if parameter not in ("link_stiffness", "sag"):
            raise DesignError("--parameter", f"{parameter!r}; allowed: link_stiffness, sag")
        check_toml_target(write_calibrated)
        drive = chaindrive.load(file)
        measured, assumed = measured_tap_modes(natural, record, tolerance)
        with spinner("fitting the link-level model to the measurement", quiet=as_json):
            result = calibrated_design_link_level(
                drive, measured, parameter="sag" if parameter == "sag" else "link_stiffness")
    _calibration_out(result, assumed, write_calibrated, as_json, print_link_level_calibration)


def check_toml_target(path: Path | None) -> None:
    """Refuse a ``--write-calibrated`` file that is not TOML (before anything is computed).

    Parameters
    ----------
    path : Path | None
        The file asked for (None: none).

    Raises
    ------
    DesignError
        On ``--write-calibrated`` when the file does not end in ``.toml``.
    """
    if path is not None and path.suffix.lower() != ".toml":
        raise DesignError("--write-calibrated", f"{str(path)!r}: allowed: a .toml file")


@functools.cache
def _click_command() -> Any:
    """The click command of :data:`app`, built once per process: typer builds it anew from
    the commands' signatures and type hints on every call (about 20 ms), and a caller that
    runs several command lines in one process (:func:`run` in a loop) needs it once.

    Returns
    -------
    click.Command
        The group of every ``chaindrive`` command.
    """
    return typer.main.get_command(app)


def run(argv: list[str] | None = None) -> int:
    """Run one command line inside the safety net (:func:`chaindrive.cli.safety.guarded`).

    Parameters
    ----------
    argv : list of str | None
        The arguments (None: the process's).

    Returns
    -------
    int
        The exit status: 0, 2 for a mistake, 1 for anything unforeseen, 128 + the signal
        number after SIGINT or SIGTERM.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    command: Any = _click_command()

    def invoke() -> object:
        limit_blas_threads()  # one BLAS thread unless asked (chaindrive.cli.threads)
        return command.main(args=args, prog_name="chaindrive", standalone_mode=False)

    return guarded(invoke, args)


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``chaindrive`` script: exits with the status of :func:`run`.

    Outside the command (before it starts, after it ended) SIGINT and SIGTERM end the
    process at once with 128 + the signal number, stdout flushed and no traceback
    (:func:`chaindrive.cli.safety.exit_on_signal`).

    Parameters
    ----------
    argv : list of str | None
        The arguments (None: the process's).
    """
    exit_on_signal()
    sys.exit(run(argv))
