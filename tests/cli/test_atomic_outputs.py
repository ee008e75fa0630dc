"""Outputs are complete or absent (chaindrive.io.atomic): ``report``, ``draw``, ``simulate``
and ``optimize --out`` killed mid-write by SIGINT or SIGTERM, or writing onto a full disk or
into a read-only directory, leave no output file or a complete one — never a partial one,
never a temporary file — and say so in one line.

Signals come two ways: from outside (the test sends it as soon as the command's temporary
output appears), and from inside at a chosen point (``tests.cli.signal_inject``: half-way
through the text, after the first PDF page, after the file is complete but before its
rename). The full disk is a 16 kB tmpfs and the read-only directory a read-only bind mount,
each in a mount namespace of its own (``unshare -m``; skipped where that is not allowed).
"Complete" is judged against an uninterrupted run of the same command: the same bytes for
the deterministic outputs, the closing tag or end-of-file marker otherwise.
"""

from __future__ import annotations

import os
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROOT

pytestmark = pytest.mark.concurrency  # processes and signals

SEED = EXAMPLES / "seed_three_sprocket.toml"
OPT = EXAMPLES / "eight_sprocket_optimize.toml"
ENDINGS = {".html": b"</html>\n", ".pdf": b"%%EOF\n", ".svg": b"</svg>", ".dxf": b"EOF\n"}


@pytest.fixture(scope="module")
def designs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The seed with a 0.05 s start-up, and a small optimisation (4 designs × 2
    generations) of the eight-sprocket example."""
    d = tmp_path_factory.mktemp("designs")
    seed = d / "seed.toml"
    seed.write_text(SEED.read_text(encoding="utf-8")
                    + '\n[dynamics]\nstartup_duration = "0.05 s"\n', encoding="utf-8")
    opt = d / "opt.toml"
    text = OPT.read_text(encoding="utf-8")
    text = text.replace("population = 16", "population = 4").replace("generations = 10",
                                                                    "generations = 2")
    opt.write_text(text, encoding="utf-8")
    return {"seed": seed, "opt": opt}


def _argv(command: str, designs: dict[str, Path], target: Path) -> list[str]:
    if command == "optimize":
        return ["optimize", str(designs["opt"]), "--out", str(target)]
    return [command, str(designs["seed"]), "-o", str(target), *SMALLEST.get(command, [])]


#: The smallest output of each command that reaches the write these tests are about: the
#: report's two-page sheet (``--summary``: write_report builds fewer sections, then the same
#: render_pdf / render_html and the same chaindrive.io.atomic write_bytes as the full report;
#: the figures at 50 dpi), one sprocket's drawing (``--sprocket``: write_drawing draws
#: sprocket_document instead of drawing_document, then the same Drawing.write / svg_string
#: and write_bytes). Each is still larger than the 16 kB full disk (27 kB HTML, 97 kB PDF,
#: 0.43 MB SVG). Written in 0.2-0.5 s instead of 1.6-2.5 s (the full report), 0.25 instead of
#: 1.1-1.5 s (SVG) and 0.15 instead of 0.75 s (DXF; CPU of the writers in one process).
SMALLEST = {"report": ["--dpi", "50", "--summary"], "draw": ["--sprocket", "S3"]}
CASES = {"report-pdf": ("report", "report.pdf"), "report-html": ("report", "report.html"),
         "draw-dxf": ("draw", "layout.dxf"), "draw-svg": ("draw", "layout.svg"),
         "simulate": ("simulate", "history.csv"), "optimize": ("optimize", "pareto")}
#: Interrupted from outside: the outputs that take long to write (a PDF page by page, the
#: set of files of an optimisation) and a quick one.
OUTSIDE = ("report-pdf", "optimize", "simulate")


@pytest.fixture(scope="module")
def references(designs: dict[str, Path], tmp_path_factory: pytest.TempPathFactory
               ) -> dict[str, Path]:
    """Every output written by an uninterrupted run."""
    out = tmp_path_factory.mktemp("reference")
    refs = {}
    for case in OUTSIDE:
        command, name = CASES[case]
        target = out / name
        proc = _cli(_argv(command, designs, target))
        assert proc.returncode == 0, proc.stderr
        refs[case] = target
    return refs


def _cli(argv: list[str], *, prefix: tuple[str, ...] = ("-m", "chaindrive")
         ) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, *prefix, *argv], capture_output=True, text=True,
                          check=False, cwd=ROOT)


def _temporaries(directory: Path) -> list[Path]:
    return [p for p in directory.rglob("*") if ".tmp" in p.name]


def _complete(case: str, target: Path, reference: Path) -> None:
    """``target`` is the same output as the uninterrupted run's."""
    if case == "optimize":
        names = sorted(p.name for p in reference.iterdir())
        assert sorted(p.name for p in target.iterdir()) == names
        for name in names:
            _complete("report-html" if name.endswith(".html") else "file",
                      target / name, reference / name)
        return
    data = target.read_bytes()
    suffix = target.suffix
    if case in ("simulate", "file") and suffix in (".csv", ".toml"):
        assert data == reference.read_bytes()
    elif suffix in ENDINGS:
        assert data.rstrip().endswith(ENDINGS[suffix].rstrip())
        if suffix == ".pdf":
            assert data.count(b"/Type /Page\n") == reference.read_bytes().count(
                b"/Type /Page\n")
    else:
        assert len(data) == len(reference.read_bytes())


def _judge(case: str, proc: subprocess.CompletedProcess[str] | subprocess.Popen[str],
           stderr: str, signum: int, target: Path, reference: Path) -> None:
    assert not _temporaries(target.parent), "a temporary output was left behind"
    if proc.returncode in (0, -signum):
        # the signal came after the output was complete: before the process ended (0), or
        # while the interpreter was shutting down, its handlers already reset to the
        # default action (−signum; seen once in 5280 runs under load: the test process was
        # held between seeing the temporary file and sending the signal). Either way the
        # output must be there, whole.
        _complete(case, target, reference)
        return
    assert proc.returncode == 128 + signum, stderr
    lines = stderr.strip().splitlines()  # none when the signal came as the process ended
    assert len(lines) <= 1 and all("interrupted by" in line for line in lines), stderr
    if target.exists():
        _complete(case, target, reference)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["INT", "TERM"])
@pytest.mark.parametrize("case", OUTSIDE)
def test_a_signal_from_outside_mid_write(case: str, signum: int, designs: dict[str, Path],
                                         references: dict[str, Path], tmp_path: Path) -> None:
    command, name = CASES[case]
    target = tmp_path / name
    proc = subprocess.Popen([sys.executable, "-m", "chaindrive",
                             *_argv(command, designs, target)], cwd=ROOT, text=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 300.0  # a bound on a hung run, not a measurement
    while proc.poll() is None and time.monotonic() < deadline:
        if _temporaries(tmp_path):  # the output is being written: interrupt it now
            proc.send_signal(signum)
            break
        time.sleep(0.005)
    _, stderr = proc.communicate(timeout=300)
    _judge(case, proc, stderr, signum, target, references[case])


@pytest.mark.parametrize(("case", "point", "signum"), [
    ("report-pdf", "midwrite", signal.SIGINT), ("report-pdf", "written", signal.SIGTERM),
    ("draw-svg", "midwrite", signal.SIGTERM), ("draw-svg", "written", signal.SIGINT),
    ("draw-dxf", "midwrite", signal.SIGINT), ("simulate", "midwrite", signal.SIGTERM),
    ("simulate", "written", signal.SIGINT), ("optimize", "midwrite", signal.SIGINT),
    ("optimize", "written", signal.SIGTERM)], ids=lambda v: getattr(v, "name", v))
def test_a_signal_at_a_chosen_point_leaves_nothing(case: str, point: str, signum: int,
                                                   designs: dict[str, Path],
                                                   tmp_path: Path) -> None:
    command, name = CASES[case]
    target = tmp_path / name
    proc = _cli([point, signal.Signals(signum).name, *_argv(command, designs, target)],
                prefix=("-m", "tests.cli.signal_inject"))
    assert proc.returncode == 128 + signum, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert not target.exists() and not _temporaries(tmp_path)
    assert list(tmp_path.iterdir()) == []


# --- a full disk and a read-only directory --------------------------------------------------

def _namespace_ok() -> bool:
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True, check=False)
    return probe.returncode == 0


needs_namespace = pytest.mark.skipif(
    sys.platform != "linux" or not _namespace_ok(),
    reason="needs `unshare -m` (a mount namespace) to make a full or read-only file system")


def _in_namespace(mount: str, directory: Path, argv: list[str]
                  ) -> tuple[subprocess.CompletedProcess[str], list[str]]:
    """Run the command line with ``directory`` mounted as ``mount`` ("full": a 16 kB tmpfs,
    smaller than every output; "readonly": a read-only bind mount) in a mount namespace; the
    result and what the directory holds afterwards (listed inside the namespace)."""
    setup = {"full": f"mount -t tmpfs -o size=16k tmpfs {shlex.quote(str(directory))}",
             "readonly": f"mount --bind -o ro {shlex.quote(str(directory))} "
                         f"{shlex.quote(str(directory))}"}[mount]
    command = " ".join(shlex.quote(a) for a in [sys.executable, "-m", "chaindrive", *argv])
    script = (f"{setup} || exit 99\n{command} 2>&1 >/dev/null; status=$?\n"
              f"echo \"--listing--\"; ls -A {shlex.quote(str(directory))}; exit $status")
    proc = subprocess.run(["unshare", "-m", "sh", "-c", script], capture_output=True,
                          text=True, check=False, cwd=ROOT, env={**os.environ})
    assert proc.returncode != 99, proc.stdout + proc.stderr
    out, _, listing = proc.stdout.partition("--listing--\n")
    return subprocess.CompletedProcess(proc.args, proc.returncode, "", out), listing.split()


@needs_namespace
@pytest.mark.parametrize(("case", "mount"), [
    ("report-html", "full"), ("report-pdf", "full"), ("report-html", "readonly"),
    ("draw-svg", "full"), ("simulate", "full"), ("simulate", "readonly"),
    ("optimize", "full")])
def test_full_disk_and_read_only_directory(case: str, mount: str, designs: dict[str, Path],
                                           tmp_path: Path) -> None:
    command, name = CASES[case]
    directory = tmp_path / "out"
    directory.mkdir()
    proc, listing = _in_namespace(mount, directory, _argv(command, designs, directory / name))
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, proc.stderr
    assert len(lines) == 1 and "cannot write" in lines[0], proc.stderr
    reason = {"full": "No space left on device", "readonly": "Read-only file system"}[mount]
    assert reason in lines[0]
    assert listing == []  # nothing written, no temporary file either
