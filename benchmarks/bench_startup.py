"""Start-up transients (issue 5 §Performance). Run: .venv/bin/python benchmarks/bench_startup.py

Nonlinear start-up of examples/twenty_four_sprocket.toml on the whole-drive model the
analysis integrates (slack spans, the design's motor and machines, with and without
polygonal excitation), 1 s: the numba kernel (its ahead-of-time build when present, else just
in time; the first call reported separately; steady time after warm-up) and the NumPy
fallback. Target: < 0.3 s.

Times are the best of several repeats (the machine is shared and noisy).
"""

from __future__ import annotations

import time
from pathlib import Path

from chaindrive.analysis import analyze
from chaindrive.dynamics.response import polygonal_law
from chaindrive.dynamics.transient.drive_startup import model_startup
from chaindrive.io.design import load_drive
from chaindrive.kinematics import tooth_frequency
from chaindrive.strength.loads import installed_pretension


def best(fn, repeats: int = 7):
    """(best wall time [s], last result)."""
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def nonlinear_case() -> None:
    from chaindrive.dynamics.transient.kernel_build import compiled_kernel

    root = Path(__file__).resolve().parents[1]
    d = load_drive(root / "examples" / "twenty_four_sprocket.toml")
    a = analyze(d)
    model, g = a.drive_model, a.geometry
    f_z = float(tooth_frequency(d.driver.teeth, d.driver.speed))
    t0 = installed_pretension(d, g)

    def run(duration: float, poly: bool, backend: str = "auto"):
        return model_startup(model, polygonal_law(g) if poly else None, duration=duration,
                             pretension=t0, tooth_frequency_hz=f_z,
                             breaking_load=d.chain.spec.breaking_load, backend=backend)

    t_first, _ = best(lambda: run(0.001, True), 1)
    how = ("ahead-of-time module, numba not imported" if compiled_kernel() is not None
           else "numba just in time: compiled or loaded from its on-disk cache")
    print(f"kernel first call ({how}): {t_first:.2f} s")
    for poly in (False, True):
        t_run, res = best(lambda poly=poly: run(1.0, poly), 5)
        print(f"nonlinear 24-sprocket start-up, 1 s, polygonal={poly!s:5}: {t_run:.3f} s "
              f"({res.steps} steps, {t_run / res.steps * 1e6:.1f} µs/step; target < 0.3 s)")
    t_np, _ = best(lambda: run(1.0, False, "numpy"), 1)
    print(f"  NumPy fallback loop, polygonal=False:           {t_np:.2f} s")


if __name__ == "__main__":
    nonlinear_case()
