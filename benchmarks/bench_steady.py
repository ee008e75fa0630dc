"""Steady-state sweep, 2000 frequencies, 24-mass open chain: chaindrive vs opentorsion
``Assembly.ss_response`` (issue 5 §Performance). Run: .venv/bin/python benchmarks/bench_steady.py"""

from __future__ import annotations

import time

import numpy as np

from chaindrive.dynamics import RingModel

N, S = 24, 2000


def best(fn, repeat: int = 5) -> float:
    fn()
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out)


def main() -> None:
    import opentorsion as ot

    rng = np.random.default_rng(0)
    m = rng.uniform(0.5, 20.0, N)
    c = rng.uniform(1e5, 1e8, N)
    c[-1] = 0.0
    w = np.linspace(10.0, 20000.0, S)
    node = 5
    f = np.zeros(N)
    f[node] = 1.0
    model = RingModel(m, c, closed=False)
    K = model.stiffness_matrix()
    beta = 1e-5
    shafts = [ot.Shaft(i, i + 1, k=float(c[i])) for i in range(N - 1)]
    disks = [ot.Disk(i, I=float(m[i])) for i in range(N)]
    asm = ot.Assembly(shafts, disk_elements=disks)
    exc = np.tile(f[:, None], (1, S)).astype(complex)

    def ours() -> np.ndarray:
        modal = model.modal()                                   # eigen-decomposition once
        X, wn = modal.shapes, modal.angular_frequencies_rad_s
        q = (X.T @ f)[None, :] / (wn**2 * (1 + 1j * w[:, None] * beta) - w[:, None] ** 2)
        return q @ X.T                                          # (S, N) displacements

    def theirs() -> np.ndarray:
        return asm.ss_response(exc, w, C=beta * K)[0].T

    t1, t2 = best(ours), best(theirs)
    err = np.abs(ours() - theirs()).max() / np.abs(theirs()).max()
    print(f"chaindrive modal sweep ({S} freq.)   {t1 * 1e3:8.2f} ms")
    print(f"opentorsion ss_response ({S} freq.)  {t2 * 1e3:8.2f} ms")
    print(f"ratio opentorsion/chaindrive = {t2 / t1:.1f} (need ≥ 30); max rel. diff {err:.1e}")


if __name__ == "__main__":
    main()
