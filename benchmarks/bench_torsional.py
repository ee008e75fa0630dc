"""Benchmark of the torsional model (docs/torsional.md §8). Run:

    .venv/bin/python benchmarks/bench_torsional.py

Modal analysis of a 24-sprocket contour with a two-element train (coupling hub, machine) on
every sprocket: 72 degrees of freedom, assembly included — built with the low-level API
(``add_inertia``/``add_shaft``/``add_span``) and with ``TorsionalModel.from_contour``, and the
frequencies alone (``frequencies_hz()``, no eigenvectors), and with the assembled topology
reused for new values (``TorsionalSystem.updated``: what an optimiser does, the union–find,
coordinates and incidence built once) — against opentorsion (Assembly +
undamped_modal_analysis, i.e. ``scipy.linalg.eig(K, M)``) on an open line of 72 disks and 71
shafts, and LAPACK alone on our matrices: ``scipy.linalg.eigh(K, M)``, the symmetric
eigensolver with eigenvectors ``dsyevd`` (``numpy.linalg.eigh``) on M^-1/2 K M^-1/2, and the
banded ``dsbevd`` on the same matrix in a reverse Cuthill–McKee order (bandwidth 6). The
LAPACK-alone rows are the cap: no modal analysis with shapes that calls them can be faster.

The contenders run in alternation over 21 rounds (``_timing.interleaved``), twice in one run:
every contender on one BLAS thread (``threadpoolctl``, as OPENBLAS_NUM_THREADS=1), then every
contender with the process's default number of BLAS threads, where chaindrive limits itself to
one thread for problems up to ``blas_threads.SMALL_PROBLEM_SIZE`` coordinates and opentorsion
does not. Best-against-best and median ratios are printed with the load average, which on
the shared project machine moves every figure by a factor of 2–3 (ratios much less).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from types import ModuleType

import numpy as np
import scipy.linalg
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import reverse_cuthill_mckee
from threadpoolctl import ThreadpoolController

from _timing import Timing, interleaved
from chaindrive.dynamics import TorsionalModel

ot: ModuleType | None
try:
    import opentorsion as ot
except ImportError:  # the peer is a test extra
    ot = None

N = 24  # sprockets


def _data(rng: np.random.Generator) -> dict[str, np.ndarray]:
    return {"J": rng.uniform(0.005, 0.5, N), "R": rng.uniform(0.04, 0.2, N),
            "c": rng.uniform(1e5, 1e8, N), "J_hub": rng.uniform(0.001, 0.05, N),
            "k_hub": rng.uniform(1e4, 1e6, N), "J_mach": rng.uniform(0.05, 20.0, N),
            "k_mach": rng.uniform(1e4, 1e6, N)}


def build_low_level(d: dict[str, np.ndarray]) -> TorsionalModel:
    t = TorsionalModel()
    J, R, c = d["J"].tolist(), d["R"].tolist(), d["c"].tolist()
    for i in range(N):
        t.add_inertia(f"s{i}", J[i])
    for i in range(N):
        b = (i + 1) % N
        t.add_span(f"s{i}", f"s{b}", c[i], R[i], R[b])
    for i in range(N):
        t.add_inertia(f"hub{i}", float(d["J_hub"][i])).add_shaft(f"s{i}", f"hub{i}",
                                                               float(d["k_hub"][i]))
        t.add_inertia(f"m{i}", float(d["J_mach"][i])).add_shaft(f"hub{i}", f"m{i}",
                                                              float(d["k_mach"][i]))
    return t


def build_plain(d: dict[str, np.ndarray]) -> TorsionalModel:
    trains = {f"s{i}": [{"name": f"hub{i}", "inertia": float(d["J_hub"][i]),
                         "stiffness": float(d["k_hub"][i])},
                        {"name": f"m{i}", "inertia": float(d["J_mach"][i]),
                         "stiffness": float(d["k_mach"][i])}] for i in range(N)}
    return TorsionalModel.from_contour([f"s{i}" for i in range(N)], d["J"], d["R"], d["c"],
                                       trains=trains)


def _scaled(K: np.ndarray, m: np.ndarray) -> np.ndarray:
    """M^{-1/2} K M^{-1/2} of a diagonal M (the standard problem the engine solves)."""
    d = 1.0 / np.sqrt(m)
    return np.asarray(K * d[:, None] * d[None, :])


def _banded(A: np.ndarray) -> np.ndarray:
    """A in LAPACK's upper band storage after a reverse Cuthill–McKee ordering."""
    p = reverse_cuthill_mckee(csr_matrix(A != 0.0), symmetric_mode=True)
    Ap = A[np.ix_(p, p)]
    rows, cols = np.nonzero(Ap)
    bw = int(np.abs(rows - cols).max())
    ab = np.zeros((bw + 1, A.shape[0]), order="F")
    for k in range(bw + 1):
        ab[bw - k, k:] = np.diagonal(Ap, k)
    return ab


def contenders(d: dict[str, np.ndarray],
               rng: np.random.Generator) -> dict[str, tuple[Callable[[], object], int]]:
    """The timed calls: ours, LAPACK alone on our matrices, opentorsion (when installed)."""
    s = build_low_level(d).system()
    K, M = s.stiffness_matrix(), s.mass_matrix()
    A = _scaled(K, s.mass)
    ab = _banded(A)
    J_new = s.node_inertia_kg_m2 * 1.01
    k_new = s.element_stiffness * 0.99
    J_line = rng.uniform(0.005, 20.0, 3 * N)
    k_line = rng.uniform(1e4, 1e8, 3 * N - 1)
    out: dict[str, tuple[Callable[[], object], int]] = {
        "low": (lambda: build_low_level(d).modal(), 50),
        "plain": (lambda: build_plain(d).modal(), 50),
        "freq": (lambda: build_low_level(d).frequencies_hz(), 50),
        "reuse": (lambda: s.updated(J_new, k_new).modal(), 50),
        "reuse_f": (lambda: s.updated(J_new, k_new).frequencies_hz(), 50),
        "eigh": (lambda: scipy.linalg.eigh(K, M), 50),
        "syevd": (lambda: np.linalg.eigh(A), 50),
        "sbevd": (lambda: scipy.linalg.lapack.dsbevd(ab, compute_v=1), 50),
    }
    if ot is not None:
        def ot_run() -> None:
            shafts = [ot.Shaft(i, i + 1, k=float(k_line[i])) for i in range(3 * N - 1)]
            disks = [ot.Disk(i, I=float(J_line[i])) for i in range(3 * N)]
            ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()

        out["ot"] = (ot_run, 3)
    return out


ROWS = (("TorsionalModel, add_* calls + modal()", "low"),
        ("TorsionalModel.from_contour + modal()", "plain"),
        ("TorsionalModel, add_* calls + frequencies_hz() (no shapes)", "freq"),
        ("topology reused (updated values) + modal()", "reuse"),
        ("topology reused (updated values) + frequencies_hz()", "reuse_f"),
        ("scipy.linalg.eigh(K, M) alone, our matrices", "eigh"),
        ("LAPACK dsyevd alone (numpy.linalg.eigh, M^-1/2 K M^-1/2)", "syevd"),
        ("LAPACK dsbevd alone (same, RCM-ordered, band storage)", "sbevd"),
        ("opentorsion Assembly + undamped_modal_analysis (line)", "ot"))
OURS = ("low", "plain", "freq", "reuse", "reuse_f", "syevd", "sbevd")


def report(title: str, tm: dict[str, Timing]) -> None:
    """Print one table: best and median per call [µs], opentorsion's time over ours."""
    best = {k: v.best * 1e6 for k, v in tm.items()}
    med = {k: v.median * 1e6 for k, v in tm.items()}
    print(f"\n{title}")
    print(f"{'case (72 DOF, assembly included)':<58} {'best':>10} {'median':>10}  note")
    for name, key in ROWS:
        if key not in best:
            continue
        note = ""
        if key in OURS and "ot" in best:
            note = (f"opentorsion / this = {best['ot'] / best[key]:.1f} best, "
                    f"{med['ot'] / med[key]:.1f} median"
                    + (" (need ≥ 20)" if key not in ("syevd", "sbevd") else " (the cap)"))
        print(f"{name:<58} {best[key]:>7.0f} µs {med[key]:>7.0f} µs  {note}")


def main() -> None:
    rng = np.random.default_rng(0)
    d = _data(rng)
    f_low = build_low_level(d).modal().frequencies_hz
    f_plain = build_plain(d).modal().frequencies_hz
    assert f_low.size == 3 * N and np.allclose(f_low, f_plain, rtol=1e-12)
    s = build_low_level(d).system()
    assert np.allclose(s.updated(s.node_inertia_kg_m2 * 1.01, s.element_stiffness * 0.99)
                       .modal().frequencies_hz, f_low * np.sqrt(0.99 / 1.01), rtol=1e-9)
    calls = contenders(d, rng)
    controller = ThreadpoolController()
    default = max(lib.num_threads for lib in controller.select(user_api="blas").lib_controllers)
    print(f"load average {os.getloadavg()[0]:.2f} at the start")
    with controller.limit(limits=1, user_api="blas"):
        one = interleaved(calls, rounds=21)
    report("one BLAS thread for every contender (as OPENBLAS_NUM_THREADS=1):", one)
    print(f"load average {os.getloadavg()[0]:.2f}")
    # LAPACK alone on several threads is left out: under load it takes 10-150 ms a call
    # (numpy.linalg.eigh, 72x72) and keeps both cores busy spinning
    mixed = {k: v for k, v in calls.items() if k not in ("eigh", "syevd", "sbevd")}
    report(f"the process's default, {default} BLAS threads, for every contender (chaindrive "
           "limits itself to one below blas_threads.SMALL_PROBLEM_SIZE, opentorsion does "
           "not):", interleaved(mixed, rounds=21))
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
