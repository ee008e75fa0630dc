"""Where the link-level step spends its time: the figures of docs/linklevel.md §3.
Run: OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_profile.py

The seed example at working speed: its kernel's arguments are taken from a 50 ms run; each
part of the step (links, hinge friction and link forces, contacts, the implicit dampers'
velocity update, the contact search, the engagement windows) is called 10⁵ times on that
state inside a compiled loop, then the whole kernel runs 20 000 steps. CPU time
(``time.process_time``) per call.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numba
import numpy as np

import chaindrive.linklevel.kernel as kern
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"
CALLS = 100_000
STEPS = 20_000


def kernel_arguments() -> tuple:
    """The arguments of the seed's run_kernel call (a 50 ms run at working speed)."""
    module = sys.modules["chaindrive.linklevel.simulate"]
    original, captured = module.run_kernel, []

    def grab(*args):
        captured.append(args)
        return original(*args)

    module.run_kernel = grab
    try:
        drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
        geometry = contour_geometry(drive)
        simulate(drive, 0.05, geometry=geometry, model=build_model(drive, geometry),
                 initial_speed="working")
    finally:
        module.run_kernel = original
    return captured[-1]


@numba.njit
def _time_links(n, x, v, L0, k, clear):
    N = x.shape[0]
    T, ux, uy, thd, invl, gd = (np.empty(N), np.empty(N), np.empty(N), np.empty(N),
                                np.empty(N), np.empty(N))
    for _ in range(n):
        kern._links(x, v, L0, k, clear, T, ux, uy, thd, invl, gd)
    return T.sum()


@numba.njit
def _time_hinges(n, x, v, L0, k, clear, mu_r, cmax):
    N = x.shape[0]
    T, ux, uy, thd, invl, gd = (np.empty(N), np.empty(N), np.empty(N), np.empty(N),
                                np.empty(N), np.empty(N))
    M, f = np.zeros(N), np.zeros((N, 2))
    kern._links(x, v, L0, k, clear, T, ux, uy, thd, invl, gd)
    s = 0.0
    for _ in range(n):
        s += kern._hinge_moments(T, thd, mu_r, cmax, M)
        kern._link_forces(f, T, ux, uy, invl, M)
    return s


@numba.njit
def _time_contacts(n, x, v, th, w, cand, spr, trig, gtab):
    N = x.shape[0]
    f, tq, Fc = np.zeros((N, 2)), np.zeros(th.size), np.zeros(N)
    Sc, Gc = np.full(N, -1, dtype=np.int64), np.full(N, -1, dtype=np.int64)
    cth, sth = np.empty(spr.shape[1]), np.empty(spr.shape[1])
    s = 0.0
    for _ in range(n):
        s += kern._contacts(x, v, f, th, w, tq, cand, spr, trig, gtab, Fc, Sc, Gc, cth, sth)
    return s


@numba.njit
def _time_velocity(n, x, v0, L0, k, clear, h, hc):
    N = x.shape[0]
    T, ux, uy, thd, invl, gd = (np.empty(N), np.empty(N), np.empty(N), np.empty(N),
                                np.empty(N), np.empty(N))
    kern._links(x, v0, L0, k, clear, T, ux, uy, thd, invl, gd)
    f, g = np.zeros((N, 2)), np.zeros(N)
    rhs, zz, cp, oo = np.empty(N), np.empty(N), np.empty(N), np.empty(N)
    v = v0.copy()
    for _ in range(n):
        v[:] = v0
        kern._velocity_update(v, f, h, hc, ux, uy, g, rhs, zz, cp, oo)
    return g.sum()


@numba.njit
def _time_search(n, x, cx, cy, reach, cand, eng):
    xs, free = np.zeros(x.shape), np.empty(x.shape[0])
    for _ in range(n):
        free[:] = -1.0  # every roller tested (in a run most have moved too little to be)
        kern._search(x, cx, cy, reach, cand, eng, xs, free)
    return cand.sum()


@numba.njit
def _time_engagements(n, Fc, eng, win, events, count):
    for i in range(n):
        kern._engagements(i * 1e-6, Fc, eng, win, events, count)
    return count[0]


def _per_call(fn, *args, calls: int = CALLS) -> float:
    fn(10, *args)  # compile
    t = time.process_time()
    fn(calls, *args)
    return (time.process_time() - t) / calls


def main() -> None:
    a = list(kernel_arguments())
    (x, v, th, w, _t0, _steps, dt, every, m, _gx, _gy, L0, k, c, clear, mu_r, cmax, spr,
     trig, gtab, reach, search) = a[:22]
    cand, eng, events, count = a[43], a[44], a[45], a[46]
    win = a[22]
    N = x.shape[0]
    print(f"seed, {N} rollers, {int((cand >= 0).sum())} within reach of a sprocket; "
          f"dt {dt * 1e6:.2f} µs")
    parts = {
        "links": _per_call(_time_links, x, v, L0, k, clear),
        "hinge friction + link forces": _per_call(_time_hinges, x, v, L0, k, clear, mu_r,
                                                  cmax),
        "contacts": _per_call(_time_contacts, x, v, th, w, cand.copy(), spr, trig, gtab),
        "implicit dampers (velocity update)": _per_call(_time_velocity, x, v, L0, k, clear,
                                                        dt / m, dt * c / m),
        f"contact search (every {search} steps, all tested)": _per_call(
            _time_search, x, spr[0].copy(), spr[1].copy(), reach, cand.copy(), eng.copy(),
            calls=CALLS // search) / search,
        "engagement windows": _per_call(_time_engagements, np.zeros(N), eng.copy(), win,
                                        events.copy(), count.copy()),
    }
    for name, t in parts.items():
        print(f"   {name:38s} {t * 1e9:7.0f} ns per step")
    rows = STEPS // every + 1
    a[0:4] = [x.copy(), v.copy(), th.copy(), w.copy()]
    a[5] = STEPS
    a[35:42] = [np.empty((rows, N, 2)), np.empty((rows, th.size)), np.empty((rows, th.size)),
                np.empty((rows, N)), np.empty((rows, N)), np.empty((rows, N), dtype=np.int64),
                np.empty((rows, N), dtype=np.int64)]
    a[45] = np.zeros((100_000, 4))
    t = time.process_time()
    kern.run_kernel(*a)
    step = (time.process_time() - t) / STEPS
    print(f"   {'whole step':38s} {step * 1e9:7.0f} ns ({step / dt:.3f} s CPU per simulated s)")


if __name__ == "__main__":
    main()
