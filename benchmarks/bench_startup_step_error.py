"""What limits the start-up kernel's step: its error at 1, 2, 4, 8 times the step of the
accuracy rule, against its own run at an eighth of the step.
Run: .venv/bin/python benchmarks/bench_startup_step_error.py [--split] [--laws] design.toml ...

The problem is the one the analysis integrates (caught on its way to the solver, as in
``bench_startup_lsoda.py``), in four variants that switch its inexact terms off one at a
time: as analysed (slack spans, polygonal excitation, laws), without the polygonal
excitation, without slack (every span linear), neither (the laws alone; the held
pre-tension is a constant force, exact under the zero-order hold). Printed per factor: the
largest relative error of the peak span forces over the spans whose peak is above 5 % of the
largest (as the accuracy rule is stated in docs/performance.md), the same over every span in
brackets (a span that only keeps its pre-tension, 1 % of the largest force, can carry the
largest relative error), and the error of the final speeds (the state at the last step, an
instantaneous sample where a ripple remains).

``--split`` also prints, per factor, the error of the span forces along the run (the largest
difference at the coarse step's times against the run at 1/64 of that step, relative to the
peak): the trajectory error, of which the peak's error is one sample. ``--laws`` adds two
variants of "neither" that take one law's speed dependence out: the motor's moment frozen at
its value at rest (a known function of time, exact under the hold but for its time
variation), the machines' moments zero.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from bench_startup_lsoda import startup_problem
from chaindrive.dynamics.transient.startup import StartupProblem, solve_startup

FACTORS = (1, 2, 4, 8)


def run(p: StartupProblem, factor: float) -> tuple[np.ndarray, np.ndarray]:
    """(peak span forces (S,) [N], final speeds (N,)) at ``factor`` times the step."""
    dt = p.dt * factor
    steps = max(1, round(p.dt * p.steps / dt))
    q = replace(p, dt=dt, steps=steps, record_every=max(1, steps // 2000))
    _, _, states, fmax, _ = solve_startup(q, "auto")
    return fmax, states[-1, p.size:]


def trajectory_error(p: StartupProblem, factor: float) -> float:
    """Largest span-force difference at the times of the step ``factor`` × Δt against the
    run at 1/64 of that step, relative to its peak [-]."""
    dt = p.dt * factor
    steps = round(p.dt * p.steps / dt)
    coarse = solve_startup(replace(p, dt=dt, steps=steps, record_every=1), "auto")
    fine = solve_startup(replace(p, dt=dt / 64, steps=steps * 64, record_every=64), "auto")
    m = min(len(coarse[1]), len(fine[1]))
    return float(np.max(np.abs(coarse[1][:m] - fine[1][:m]).max(axis=0) / fine[3]))


def variants(p: StartupProblem, laws: bool = False) -> dict[str, StartupProblem]:
    """The problem with its inexact terms switched off one at a time (``laws``: and the
    laws' speed dependence, module docstring)."""
    taut = replace(p.linear, span_tension_only=np.zeros_like(p.span_tension_only))
    out = {"as analysed": p, "no polygonal": replace(p, polygonal=None),
           "no slack": replace(p, linear=taut),
           "neither": replace(p, linear=taut, polygonal=None)}
    if laws and p.motor is not None:
        mk, mg, me, law = p.motor

        def frozen(t: float, w: float) -> float:
            return float(law(t, 0.0))

        out["neither, motor frozen"] = replace(out["neither"], motor=(mk, mg, me, frozen))
        out["neither, no machines"] = replace(
            out["neither"], load_torque=np.zeros_like(p.load_torque))
    return out


def main(argv: list[str]) -> None:
    split, laws = "--split" in argv, "--laws" in argv
    for path in (Path(a) for a in argv if not a.startswith("--")):
        try:
            p0 = startup_problem(path, linearised=False)
        except IndexError:  # the analysis integrated no start-up
            print(f"{path.stem}: no start-up in its analysis")
            continue
        print(f"{path.stem}: {p0.size} coordinates, step {p0.dt:.3g} s, {p0.steps} steps")
        for name, p in variants(p0, laws).items():
            f_ref, v_ref = run(p, 1 / 8)
            big = f_ref > 0.05 * f_ref.max()
            cells = []
            for factor in FACTORS:
                fm, v = run(p, factor)
                e = np.abs(fm - f_ref) / f_ref
                ev = np.max(np.abs(v - v_ref)) / np.max(np.abs(v_ref))
                cell = (f"x{factor}: F {100 * e[big].max():.3f} % ({100 * e.max():.3f} %) "
                        f"v {100 * ev:.3f} %")
                if split and factor > 1:
                    cell += f" (along the run {100 * trajectory_error(p, factor):.3f} %)"
                cells.append(cell)
            print(f"  {name:21s} " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
