"""Whether this tree's link-level step loop gives bit for bit the results of another kernel
(docs/linklevel.md §3, the step loop's cost).

Run (one BLAS thread):
    git show <commit>:src/chaindrive/linklevel/kernel.py > /tmp/kernel_before.py
    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_identical.py /tmp/kernel_before.py

For the seed example, a 12B 15/25 drive 85 pitches apart and the 24-sprocket example, the
arguments of run_kernel are taken from a short run at working speed and power; both kernels
then advance copies of the same state (20 000 steps; 4 000 on the 24 sprockets) as run, with
the link springs implicit (θ = 1/4) and with the settling's velocity relaxation (η = 300 1/s),
and every array the kernel writes — positions, velocities, angles, speeds, the records, the
energy terms, the contact candidates, the engagement windows and events — is compared with
``numpy.array_equal``. Exit status 1 when any differs.
"""

from __future__ import annotations

import importlib
import inspect
import sys
from pathlib import Path
from typing import Any

import numpy as np

import chaindrive.linklevel.kernel as kernel
from chaindrive.io.design import load_drive

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_linklevel_reference import EXAMPLES, _two_sprocket
from bench_linklevel_step import fresh_arguments, kernel_arguments

VARIANTS = (("as run", {}), ("implicit springs", {"theta": 0.25}),
            ("settling (eta)", {"eta": 300.0, "theta": 0.0}))


def arguments(a0: list[Any], steps: int, eta: float | None = None,
              theta: float | None = None) -> list[Any]:
    """A fresh copy of the run_kernel arguments a0 for ``steps`` steps (records zeroed), with
    the settling rate η and the springs' implicitness θ when given."""
    a = fresh_arguments(a0, steps)
    if eta is not None:
        a[47] = eta
    if theta is not None:
        a[48] = theta
    return a


def main() -> int:
    path = Path(sys.argv[1]).resolve()  # imported by name: numba's cache needs one
    sys.path.insert(0, str(path.parent))
    other = importlib.import_module(path.stem)
    # an older kernel takes fewer trailing arguments (the implicit hinge switch came later)
    n = len(inspect.signature(other.run_kernel.py_func).parameters)
    drives = (("seed", load_drive(EXAMPLES / "seed_three_sprocket.toml"), 20_000),
              ("12B 15/25", _two_sprocket(85, 300.0, 1000.0), 20_000),
              ("24 sprockets", load_drive(EXAMPLES / "twenty_four_sprocket.toml"), 4_000))
    differ = 0
    for name, drive, steps in drives:
        a0 = kernel_arguments(drive)
        for variant, kw in VARIANTS:
            a, b = arguments(a0, steps, **kw), arguments(a0, steps, **kw)
            other.run_kernel(*a[:n])
            kernel.run_kernel(*b)
            apart = [i for i, (p, q) in enumerate(zip(a, b, strict=True))
                     if isinstance(p, np.ndarray) and not np.array_equal(p, q, equal_nan=True)]
            differ += bool(apart)
            print(f"{name:12s} {variant:16s} {steps:6d} steps, {int(b[46][0]):3d} events: "
                  + (f"arguments {apart} differ" if apart else "bit-identical"), flush=True)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
