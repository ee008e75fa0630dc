"""The start-up kernel against SciPy's LSODA on the same linearised model, side by side.
Run: .venv/bin/python benchmarks/bench_startup_lsoda.py [--rounds N] [--against SRC] [design.toml ...]

The model: the whole-drive model the analysis integrates for the start-up of a bundled
example (default: examples/twenty_four_sprocket.toml), linearised in its chain — every span
taut and linear (no slack switching), no polygonal excitation — with the design's motor and
machines (their laws are smooth), from rest, 1 s:

    M q̈ + C q̇ + K q = −Bᵀ T₀ + Q_laws(t, q̇).

Contenders: the start-up kernel (``solve_startup``, its ahead-of-time build, at the step of
the accuracy rule) and ``scipy.integrate.solve_ivp(method="LSODA")`` with the analytic
Jacobian, its right-hand side one matrix product. Accuracy is measured against a reference
(LSODA at rtol 1e-11) on the largest span forces and the final speeds; LSODA's tolerance is the
loosest of 1e-3 … 1e-10 whose error is at most the kernel's ("the same accuracy"; where none
is, LSODA is timed at 1e-10, less accurate than the kernel). Times are CPU
times (``time.process_time``), best and median over rounds run in alternation.

``--against SRC`` adds the kernel of another source tree (its ``src`` directory, e.g. a
checkout of the code before a change, with its own ahead-of-time build) as a third
contender: a child process with that tree on its path builds the same problem and runs its
kernel once per round when asked, in alternation with the two others (its CPU time measured
in the child around the solve alone). Both trees' kernels also run the start-up as the
analysis integrates it (slack spans, polygonal excitation, the analysis's duration): the
"analysis" rows.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

import chaindrive.dynamics.transient.drive_startup as drive_startup
from chaindrive.analysis import analyze
from chaindrive.dynamics.transient.startup import StartupProblem, solve_startup
from chaindrive.io.design import load_drive

ROOT = Path(__file__).resolve().parents[1]


def startup_problem(path: Path, linearised: bool = True) -> StartupProblem:
    """The StartupProblem the analysis builds for the design (caught on its way to the
    solver), linearised: every span taut, no polygonal excitation, 1 s (``linearised``
    False: as the analysis integrates it)."""
    caught: list[StartupProblem] = []
    solve = drive_startup.solve_startup

    def catch(p: StartupProblem, backend: Any = "auto") -> Any:
        caught.append(p)
        return solve(p, backend)

    drive_startup.solve_startup = catch  # type: ignore[assignment]
    try:
        _ = analyze(load_drive(path)).startup
    finally:
        drive_startup.solve_startup = solve
    p = caught[-1]
    if not linearised:
        return p
    steps = round(1.0 / p.dt)
    taut = replace(p.linear, span_tension_only=np.zeros_like(p.span_tension_only))
    return replace(p, linear=taut, polygonal=None, steps=steps,
                   record_every=max(1, steps // 2000))


def lsoda_solver(p: StartupProblem) -> Callable[[float], tuple[np.ndarray, np.ndarray]]:
    """solve(rtol) → (largest span forces (S,), final speeds (N,)) by LSODA."""
    n = p.size
    B, c, ds = p.span_incidence, p.span_stiffness, p.span_damping
    K = p.stiffness_linear + (B.T * c) @ B
    C = p.damping_linear + (B.T * ds) @ B
    Minv = np.linalg.inv(p.mass)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -Minv @ K
    A[n:, n:] = -Minv @ C
    f0 = -(p.pretension @ B)
    lk, lg, le = p.load_coordinate, p.load_gain, p.load_efficiency
    lM, lw = p.load_torque, p.load_speed
    kinds = np.array(p.load_kind)
    lin, quad, const = kinds == "linear", kinds == "quadratic", kinds == "constant"
    assert p.motor is not None
    mk, mg, me, motor = p.motor

    def laws(t: float, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Law forces (N,) and their slopes ∂f/∂v on the diagonal (N,)."""
        f, J = np.zeros(n), np.zeros(n)
        r = lg * v[lk] / lw
        phi = np.where(lin, r, 0.0) + np.where(quad, r * np.abs(r), 0.0) \
            + np.where(const, np.clip(r / p.breakaway, -1.0, 1.0), 0.0)
        dphi = np.where(lin, 1.0, 0.0) + np.where(quad, 2.0 * np.abs(r), 0.0) \
            + np.where(const & (np.abs(r) < p.breakaway), 1.0 / p.breakaway, 0.0)
        np.add.at(f, lk, -lg * lM * phi / le)
        np.add.at(J, lk, -lg * lM * dphi * lg / lw / le)
        w = mg * v[mk]
        f[mk] += mg * me * motor(t, w)
        h = 1e-6 * (1.0 + abs(w))
        J[mk] += mg * me * (motor(t, w + h) - motor(t, w)) / h * mg
        return f, J

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        f, _ = laws(t, y[n:])
        out = A @ y
        out[n:] += Minv @ (f0 + f)
        return out

    def jac(t: float, y: np.ndarray) -> np.ndarray:
        _, J = laws(t, y[n:])
        out = A.copy()
        out[n:, n:] += Minv * J[None, :]
        return out

    def solve(rtol: float) -> tuple[np.ndarray, np.ndarray]:
        times = np.arange(p.steps + 1) * p.dt
        sol = solve_ivp(rhs, (0.0, times[-1]), np.zeros(2 * n), method="LSODA", jac=jac,
                        rtol=rtol, atol=rtol * 1e-3, t_eval=times)
        q, v = sol.y[:n].T, sol.y[n:].T
        F = p.pretension + c * (q @ B.T) + ds * (v @ B.T)
        return F.max(axis=0) / p.scale, v[-1]

    return solve


def kernel_solver(p: StartupProblem) -> Callable[[], tuple[np.ndarray, np.ndarray]]:
    """solve() → (largest span forces (S,), final speeds (N,)) by the start-up kernel."""
    n = p.size

    def solve() -> tuple[np.ndarray, np.ndarray]:
        _, _, states, fmax, _ = solve_startup(p)
        return fmax, states[-1, n:]

    return solve


def error(result: tuple[np.ndarray, np.ndarray], ref: tuple[np.ndarray, np.ndarray]) -> float:
    """Largest relative error of the peak span forces and the final speeds [-]."""
    f, v = result
    fr, vr = ref
    return max(float(np.max(np.abs(f - fr)) / np.max(np.abs(fr))),
               float(np.max(np.abs(v - vr)) / np.max(np.abs(vr))))


def cpu_times(fns: dict[str, Callable[[], object]], rounds: int) -> dict[str, list[float]]:
    """CPU time of each call, the contenders in alternation."""
    out: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(rounds):
        for k, fn in fns.items():
            t0 = time.process_time()
            fn()
            out[k].append(time.process_time() - t0)
    return out


class OtherTree:
    """The kernel of another source tree in a child process (``--against``)."""

    def __init__(self, src: Path, design: Path) -> None:
        env = {**os.environ, "PYTHONPATH": str(src)}
        self.proc = subprocess.Popen([sys.executable, __file__, "--serve", str(design)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                                     env=env)
        assert self.proc.stdout is not None
        self.proc.stdout.readline()  # "ready" once the problem is built and run once

    def run(self, what: str = "linearised") -> tuple[float, tuple[np.ndarray, np.ndarray]]:
        """(CPU s, (peak span forces, final speeds)) of one solve in the child: of the
        linearised problem, or ``what`` = "analysis": of the analysis's own."""
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(what + "\n")
        self.proc.stdin.flush()
        out = json.loads(self.proc.stdout.readline())
        return out["cpu"], (np.array(out["fmax"]), np.array(out["speeds"]))

    def close(self) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.close()
        self.proc.wait()


def serve(design: Path) -> None:
    """Child of ``--against``: solve the design's problem once per line "run" on stdin."""
    solvers = {"linearised": kernel_solver(startup_problem(design)),
               "analysis": kernel_solver(startup_problem(design, linearised=False))}
    for solve in solvers.values():
        solve()
    print("ready", flush=True)
    for line in sys.stdin:
        t0 = time.process_time()
        fmax, speeds = solvers[line.strip()]()
        cpu = time.process_time() - t0
        print(json.dumps({"cpu": cpu, "fmax": fmax.tolist(), "speeds": speeds.tolist()}),
              flush=True)


def compare(path: Path, rounds: int = 5, against: Path | None = None) -> None:
    p = startup_problem(path)
    lsoda, kernel = lsoda_solver(p), kernel_solver(p)
    ref = lsoda(1e-11)
    e_kernel = error(kernel(), ref)
    chosen = None
    for rtol in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
        e = error(lsoda(rtol), ref)
        if e <= e_kernel:
            chosen = rtol, e
            break
    print(f"{path.name}: {p.size} coordinates, {p.steps} kernel steps of {p.dt:.3g} s, "
          f"1 s, every span taut, no polygonal excitation")
    print(f"  kernel error {e_kernel:.2e} (peak span forces, final speeds; against LSODA "
          "rtol 1e-11)")
    if chosen is None:
        # timed at its tightest tolerance all the same: less accurate than the kernel there,
        # so the ratio understates the kernel's lead
        print(f"  LSODA does not reach the kernel's accuracy at rtol 1e-10 (its error "
              f"{e:.2e}); timed at rtol 1e-10, less accurate than the kernel")
        chosen = 1e-10, e
    else:
        print(f"  LSODA at the same accuracy: rtol {chosen[0]:g} (error {chosen[1]:.2e})")
    rtol = chosen[0]
    fns: dict[str, Callable[[], object]] = {"kernel": kernel, "lsoda": lambda: lsoda(rtol),
                                            "analysis": kernel_solver(startup_problem(
                                                path, linearised=False))}
    other = OtherTree(against, path) if against is not None else None
    t: dict[str, list[float]] = {k: [] for k in ("kernel", "other", "lsoda", "analysis",
                                                 "other analysis")}
    try:
        for _ in range(rounds):
            for k, fn in fns.items():
                t0 = time.process_time()
                fn()
                t[k].append(time.process_time() - t0)
                if other is not None and k != "lsoda":
                    cpu, result = other.run("linearised" if k == "kernel" else k)
                    t["other" if k == "kernel" else "other " + k].append(cpu)
                    if k == "kernel":
                        e_other = error(result, ref)
        if other is not None:
            print(f"  kernel of {against}: error {e_other:.2e}")
    finally:
        if other is not None:
            other.close()
    for k, v in t.items():
        if v:
            print(f"  {k:7s} CPU best {min(v) * 1e3:7.1f} ms, "
                  f"median {statistics.median(v) * 1e3:7.1f} ms "
                  f"({statistics.median(v) / p.steps * 1e6:.2f} µs per kernel step)")
    ratio = statistics.median(t["lsoda"]) / statistics.median(t["kernel"])
    print(f"  LSODA / kernel (median CPU): {ratio:.2f}")
    if t["other"]:
        print(f"  LSODA / kernel of {against}: "
              f"{statistics.median(t['lsoda']) / statistics.median(t['other']):.2f}; "
              f"that kernel / this one: "
              f"{statistics.median(t['other']) / statistics.median(t['kernel']):.2f}; "
              "the analysis's own start-up (slack spans, polygonal excitation): "
              f"{statistics.median(t['other analysis']) / statistics.median(t['analysis']):.2f}")


def main(argv: list[str]) -> None:
    if argv[:1] == ["--serve"]:
        serve(Path(argv[1]))
        return
    rounds, against, names = 5, None, []
    it = iter(argv)
    for arg in it:
        if arg == "--rounds":
            rounds = int(next(it))
        elif arg == "--against":
            against = Path(next(it)).resolve()
        else:
            names.append(arg)
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")
    for arg in names or ["twenty_four_sprocket.toml"]:
        compare(Path(arg) if Path(arg).exists() else ROOT / "examples" / arg, rounds, against)
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")


if __name__ == "__main__":
    main(sys.argv[1:])
