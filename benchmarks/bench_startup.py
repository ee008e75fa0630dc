"""Start-up transients (issue 5 §Performance). Run: .venv/bin/python benchmarks/bench_startup.py

1. Linear 24-mass open chain, step torque, 1 s at ts = 1e-4 s: chaindrive ``linear_transient``
   (closed-form modal step responses evaluated on the time grid as block matrix products,
   span forces and speeds as dsim returns them; displacements on access, timed as well;
   and the exact zero-order-hold
   modal recursion of the sampled torque) vs opentorsion ``dsim`` (a Python loop over the
   zero-order-hold discretisation: the same exact-for-a-held-input solution, so the same
   accuracy; the difference is printed). Target: ratio ≥ 10.
2. Nonlinear start-up of examples/twenty_four_sprocket.toml (slack spans, Kloss motor,
   linear resistance, with and without polygonal excitation), 1 s: the numba kernel (its
   ahead-of-time build when present, else just in time; the first call reported separately;
   steady time after warm-up) and the NumPy fallback. Target: < 0.3 s. Then the step
   study: peak force and final speeds at 80/160/320 steps per period against 640 (the
   default is 160).

Times are the best of several repeats (the machine is shared and noisy); the linear case
runs the contenders in alternation (``_timing.interleaved``).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from _timing import interleaved
from chaindrive.dynamics.drive import ring_model
from chaindrive.dynamics.linear import linear_transient
from chaindrive.dynamics.response import drive_startup
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive

N = 24


def best(fn, repeats: int = 7):
    """(best wall time [s], last result)."""
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def linear_case() -> None:
    import opentorsion as ot

    rng = np.random.default_rng(0)
    m = rng.uniform(0.5, 20.0, N)
    c = rng.uniform(1e5, 1e7, N)
    c[-1] = 0.0
    beta = 1e-5
    ts = 1e-4
    t = np.arange(0, 1.0, ts)
    torque = 100.0
    shafts = [ot.Shaft(i, i + 1, k=float(c[i]), c=float(beta * c[i])) for i in range(N - 1)]
    disks = [ot.Disk(i, I=float(m[i])) for i in range(N)]
    asm = ot.Assembly(shafts, disk_elements=disks)
    exc = ot.TransientExcitation(N, t)
    exc.add_transient(0, np.full(t.size, torque))
    f = np.zeros(N)
    f[0] = torque
    ft = np.tile(f, (t.size, 1))
    tm = interleaved({"dsim": (lambda: asm.dsim(exc), 1),
                      "closed": (lambda: linear_transient(m, c, beta, t, f, closed=False), 5),
                      "closed_x": (lambda: linear_transient(m, c, beta, t, f, closed=False)
                                   .displacements, 5),
                      "zoh": (lambda: linear_transient(m, c, beta, t, ft, closed=False), 1)},
                     rounds=9)
    tq, speeds, _ = asm.dsim(exc)
    r = linear_transient(m, c, beta, t, f, closed=False)
    r2 = linear_transient(m, c, beta, t, ft, closed=False)
    t_ot, t_cf, t_cfx, t_zoh = (tm[k].best for k in ("dsim", "closed", "closed_x", "zoh"))
    ref = -tq[:, :].T  # opentorsion: shaft twists × k (sign: φ_i − φ_{i+1})
    scale = np.abs(ref).max()
    print(f"opentorsion dsim, 1 s, {t.size} steps          {t_ot * 1e3:8.1f} ms")
    print(f"chaindrive closed form (step torque)         {t_cf * 1e3:8.1f} ms  ratio "
          f"{t_ot / t_cf:5.1f} (need ≥ 10; medians {tm['dsim'].median / tm['closed'].median:.1f})")
    print(f"  the same with the displacements as well    {t_cfx * 1e3:8.1f} ms  ratio "
          f"{t_ot / t_cfx:5.1f}")
    print(f"chaindrive ZOH modal recursion (sampled)     {t_zoh * 1e3:8.1f} ms  ratio "
          f"{t_ot / t_zoh:5.1f}")
    for name, x in (("closed form", r.span_forces), ("ZOH recursion", r2.span_forces)):
        x = x[:, :N - 1]
        err = min(np.abs(x - ref).max(), np.abs(x + ref).max()) / scale
        print(f"  max |difference to dsim| / max force, {name}: {err:.1e}")
    err_v = np.abs(r.velocities - speeds.T).max() / np.abs(speeds).max()
    print(f"  max |difference to dsim| / max speed, closed form: {err_v:.1e}")


def nonlinear_case() -> None:
    import chaindrive.dynamics.response as response
    from chaindrive.dynamics.kernel_build import compiled_kernel
    from chaindrive.dynamics.startup import simulate_startup

    root = Path(__file__).resolve().parents[1]
    d = load_drive(root / "examples" / "twenty_four_sprocket.toml")
    g = contour_geometry(d)
    model = ring_model(d, g, damping=0.06)
    t_first, _ = best(lambda: drive_startup(d, g, model, duration=0.001), 1)
    how = ("ahead-of-time module, numba not imported" if compiled_kernel() is not None
           else "numba just in time: compiled or loaded from its on-disk cache")
    print(f"kernel first call ({how}): {t_first:.2f} s")
    for poly in (False, True):
        t_run, res = best(lambda poly=poly: drive_startup(d, g, model, polygonal=poly), 5)
        print(f"nonlinear 24-sprocket start-up, 1 s, polygonal={poly!s:5}: {t_run:.3f} s "
              f"({res.steps} steps, {t_run / res.steps * 1e6:.1f} µs/step; target < 0.3 s)")
    original = response.simulate_startup
    response.simulate_startup = lambda *a, **k: simulate_startup(*a, backend="numpy", **k)
    try:
        t_np, _ = best(lambda: drive_startup(d, g, model, polygonal=False), 1)
        print(f"  NumPy fallback loop, polygonal=False:           {t_np:.2f} s")
    finally:
        response.simulate_startup = original
    step_study(d, g, model)


def step_study(d, g, model) -> None:
    """Peak span force and final speeds against the step (Δt = 1/(k f_ref))."""
    f1 = model.modal().first_elastic_frequency_hz
    fz = d.driver.teeth * d.driver.speed / (2 * np.pi)
    f_ref = max(f1, fz)
    runs = {k: drive_startup(d, g, model, polygonal=False, dt=1.0 / (k * f_ref))
            for k in (80, 160, 320, 640)}
    ref = runs[640]
    for k in (80, 160, 320):
        r = runs[k]
        dp = abs(r.max_span_force.max() / ref.max_span_force.max() - 1)
        dw = np.abs(r.speeds[-1] - ref.speeds[-1]).max() / np.abs(ref.speeds[-1]).max()
        print(f"  {k:3d} steps/period: peak force {dp:.2%}, final speeds {dw:.2%} "
              f"(vs 640; limits 2 %, 1 %)")


if __name__ == "__main__":
    linear_case()
    nonlinear_case()
