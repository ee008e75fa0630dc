"""Shared fixtures: chains built directly (no catalogue), drives, example paths."""

from __future__ import annotations

import io
import math
import subprocess
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
from hypothesis import settings

from chaindrive.model import Chain, ChainSpec, Drive, Sprocket

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
SHARED = ROOT.parent / "shared"

# Property tests run the same examples on every machine (reproducible CI).
settings.register_profile("chaindrive", derandomize=True, deadline=None)
settings.load_profile("chaindrive")


def pytest_configure(config: pytest.Config) -> None:
    """Each test process runs its BLAS on one thread, as every command does
    (:mod:`chaindrive.cli.threads`): two pytest workers on two cores with two OpenBLAS threads
    each wait on one another. A command run in-process set the same limit already, for the
    rest of its worker's life; set here, the limit no longer depends on which file ran first.
    A test of the thread setting itself sets what it needs (``threadpool_limits`` or a
    subprocess with its own environment)."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


def cli_in_process(*args: str) -> subprocess.CompletedProcess[str]:
    """A command line run in this process: its exit status and what it printed.

    It calls :func:`chaindrive.cli.run`, the function the ``chaindrive`` script runs (the
    script adds only the handling of a signal that comes before or after the command), so a
    test of what a command prints, writes and returns gets the same answer as from a
    subprocess without starting and importing a new interpreter. Tests of the process itself
    (signals, an installed script) keep their subprocess.
    """
    from chaindrive.cli import run

    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        status = run(list(args))
    return subprocess.CompletedProcess(list(args), status, out.getvalue(), err.getvalue())


def rpm(n: float) -> float:
    """rev/min → rad/s."""
    return n * math.pi / 30.0


def make_spec(pitch: float = 0.0254, roller: float | None = None) -> ChainSpec:
    """A steel chain of the given pitch with ISO-like proportions (for geometry tests)."""
    return ChainSpec(
        designation=f"test {pitch * 1e3:g}", standard="ISO 606", series="B", pitch=pitch,
        strands=1, roller_diameter=roller or 0.625 * pitch, pin_diameter=0.31 * pitch,
        inner_width=0.6 * pitch, plate_depth=0.83 * pitch, transverse_pitch=0.0,
        breaking_load=60_000.0 * (pitch / 0.0254) ** 2, mass_per_length=2.6 * (pitch / 0.0254) ** 2,
    )


def two_sprocket(z1: int, z2: int, a: float, pitch: float = 0.0254, links: int | None = None,
                 adjustable: bool = True) -> Drive:
    """A two-sprocket drive with the driver at the origin and the driven on +x."""
    return Drive(
        name="two", chain=Chain(make_spec(pitch), links=links),
        sprockets=(Sprocket("A", z1, 0.0, 0.0, "driver", speed=rpm(100)),
                   Sprocket("B", z2, a, 0.0, "driven", adjustable=adjustable)),
    )


@pytest.fixture
def seed_drive() -> Drive:
    """Seed 000's three-sprocket contour (seed-notes §3), chain pitch 25.4 mm."""
    return Drive(
        name="seed", chain=Chain(make_spec(0.0254, roller=0.01588)),
        sprockets=(Sprocket("S1", 15, 1.364, 0.0, "driver", speed=rpm(300)),
                   Sprocket("S2", 25, 0.0, 0.0, "driven"),
                   Sprocket("S3", 14, 0.682, 0.06067, "idler")),
        power=500.0, tooth_form="GOST 591",
    )
