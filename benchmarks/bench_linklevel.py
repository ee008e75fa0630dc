"""Link-level model (chaindrive.linklevel). Run: .venv/bin/python benchmarks/bench_linklevel.py

1. Speed: 1 s of simulated start-up, one core, of examples/seed_three_sprocket.toml (128
   links; target ≤ 0.5 s wall, i.e. 2× faster than real time), and the eight- and
   twenty-four-sprocket examples (their wall time per simulated second and the factor to
   10× real time). Best of a few repeats after a warm-up (numba compiles once, cached).
2. Step study: the seed's driven speed after 0.05 s and its peak span force at the default
   step (Courant 0.8 of the stability limit 2/ω_max) and half of it, against a quarter, and
   the energy residual of each (pointwise values of an impacting chain are sensitive to
   round-off and need not converge; the energy balance does).
3. Peer: the same two-sprocket chain (12B, 15/25 teeth, 30 pitches apart, 300 rpm,
   coasting, no hinge friction) in exudyn (benchmarks/_exudyn_chain.py: mass points,
   spring–dampers, GeneralContact on the tooth outline), both from the same initial
   state. Accuracy: the driven sprocket's speed history against each engine's own
   solution at an eighth of our step; the peer (exudyn's classical Runge–Kutta RK44: its
   explicit midpoint rule is unstable for undamped oscillators at any step) at the
   largest of our step × 1, ½, ¼ that reaches the accuracy ours has at its default step.
   Ratio = peer's wall time / ours.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from chaindrive.dynamics.motors import ConstantTorque
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import installed_geometry
from chaindrive.linklevel.simulate import initial_state
from chaindrive.model import Chain, Drive, Sprocket

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def best_wall(fn, repeats: int = 3) -> tuple[float, object]:
    """(best wall time [s], result)."""
    out, times = None, []
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def speed() -> None:
    print("1. wall time per simulated second (start-up from rest, default step)")
    for name, duration in (("seed_three_sprocket.toml", 1.0), ("eight_sprocket.toml", 0.5),
                           ("twenty_four_sprocket.toml", 0.25)):
        drive = load_drive(EXAMPLES / name)
        geometry = contour_geometry(drive)
        model = build_model(drive, geometry)
        simulate(drive, 0.002, geometry=geometry, model=model)  # warm-up (compile / cache)
        wall, r = best_wall(lambda d=drive, g=geometry, m=model, t=duration:
                            simulate(d, t, geometry=g, model=m, sample_rate_hz=1000))
        per_s = wall / duration
        print(f"   {name:28s} {geometry.links:4d} links  dt {r.dt * 1e6:5.2f} µs  "
              f"{r.steps:7d} steps  {per_s:6.3f} s per simulated s  "
              f"({1 / per_s:5.2f}× real time; 10× real time needs {per_s / 0.1:5.1f}× faster)")


def step_study() -> None:
    print("2. step study (seed, 0.05 s from rest)")
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    geometry = contour_geometry(drive)
    model = build_model(drive, geometry)
    base = simulate(drive, 0.001, geometry=geometry, model=model).dt
    runs = {f: simulate(drive, 0.05, geometry=geometry, model=model, dt_s=base * f,
                        sample_rate_hz=4000) for f in (1.0, 0.5, 0.25)}
    ref = runs[0.25]
    for f in (1.0, 0.5, 0.25):
        r = runs[f]
        dw = abs(r.sprocket_speeds[-1, 1] - ref.sprocket_speeds[-1, 1]) / ref.sprocket_speeds[-1, 1]
        dp = abs(r.peak_span_force.max() - ref.peak_span_force.max()) / ref.peak_span_force.max()
        de = abs(r.energy_residual_j) / r.energy["motor_work_j"]
        print(f"   dt = {f:4.2f}·default: driven speed off by {dw:.2e}, peak span force by "
              f"{dp:.2e}; energy residual {de:.1e} of the motor's work")


def _peer_drive() -> Drive:
    spec = load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec
    return Drive(name="peer", chain=Chain(spec), power=1000.0,
                 sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=300 * math.pi / 30),
                            Sprocket("B", 25, 30 * spec.pitch, 0.0, "driven", adjustable=True)))


def _error(t: np.ndarray, w: np.ndarray, t_ref: np.ndarray, w_ref: np.ndarray) -> float:
    """RMS difference of two speed histories on the first one's times, relative to the
    reference's mean."""
    return float(np.sqrt(np.mean((w - np.interp(t, t_ref, w_ref)) ** 2)) / np.mean(w_ref))


def peer() -> None:
    try:
        import _exudyn_chain as peer_model
    except ImportError as exc:  # exudyn is in the test extras
        print(f"3. peer skipped: {exc}")
        return
    drive = _peer_drive()
    # the installed contour (the run takes the chain up to its installed sag): the peer's
    # sprockets sit where ours do
    geometry, _ = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry, hinge_friction=0.0)
    state = initial_state(drive, geometry, model, "steady")
    t_end = 0.02
    run = {"geometry": geometry, "model": model, "initial_speed": "working",
           "motor": ConstantTorque(0.0), "resistance": None, "sample_rate_hz": 10000}
    simulate(drive, 0.001, **run)
    dt = simulate(drive, 0.001, **run).dt

    def ours(step: float):
        r = simulate(drive, t_end, dt_s=step, **run)
        return r.times, r.sprocket_speeds[:, 1]

    ref_t, ref_w = ours(dt / 8)
    wall_ours, (t_o, w_o) = best_wall(lambda: ours(dt))
    err_ours = _error(t_o, w_o, ref_t, ref_w)
    print(f"3. peer: {geometry.links} links, {t_end * 1e3:.0f} ms coasting at 300 rpm")
    print(f"   ours    dt {dt * 1e6:5.2f} µs: error {err_ours:.2e}, wall {wall_ours:.3f} s "
          f"({wall_ours / t_end:.2f} s per simulated s)")
    _, exu_ref = peer_model.run(model, state, dt / 8, t_end)
    found = None
    for f in (1.0, 0.5, 0.25):
        wall, data = peer_model.run(model, state, dt * f, t_end)
        ok = np.all(np.isfinite(data[:, 1]))
        err = _error(data[:, 0], data[:, 1], exu_ref[:, 0], exu_ref[:, 1]) if ok else math.inf
        cross = _error(data[:, 0], data[:, 1], ref_t, ref_w) if ok else math.inf
        print(f"   exudyn  dt {dt * f * 1e6:5.2f} µs: error {err:.2e} (against ours: "
              f"{cross:.2e}), wall {wall:.3f} s ({wall / t_end:.2f} s per simulated s)")
        if found is None and err <= err_ours:
            found = wall
    if found is not None:
        print(f"   ratio exudyn/ours at the same accuracy: {found / wall_ours:.0f}×")


if __name__ == "__main__":
    speed()
    step_study()
    peer()
