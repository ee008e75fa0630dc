"""Benchmark of the torsional model (docs/torsional.md). Run:

    .venv/bin/python benchmarks/bench_torsional.py

Modal analysis of a 24-sprocket contour with a two-element train (coupling hub, machine) on
every sprocket: 72 degrees of freedom, assembly included — built with the low-level API
(``add_inertia``/``add_shaft``/``add_span``) and with ``TorsionalModel.from_contour``, and the
frequencies alone (``frequencies_hz()``, no eigenvectors), and with the assembled topology
reused for new values (``TorsionalSystem.updated``: what an optimiser does, the union–find,
coordinates and incidence built once) — against
opentorsion (Assembly + undamped_modal_analysis) on an open line of 72 disks and 71 shafts,
and scipy.linalg.eigh(K, M) alone on our matrices. The contenders run in alternation over 21
rounds (``_timing.interleaved``); best-against-best and median ratios are printed.
For one core set OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 before running.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from _timing import interleaved
from chaindrive.dynamics import TorsionalModel

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


def main() -> None:
    rng = np.random.default_rng(0)
    d = _data(rng)
    f_low = build_low_level(d).modal().frequencies_hz
    f_plain = build_plain(d).modal().frequencies_hz
    assert f_low.size == 3 * N and np.allclose(f_low, f_plain, rtol=1e-12)
    s = build_low_level(d).system()
    K, M = s.stiffness_matrix(), s.mass_matrix()
    J_new = s.node_inertia_kg_m2 * 1.01
    k_new = s.element_stiffness * 0.99
    assert np.allclose(s.updated(J_new, k_new).modal().frequencies_hz,
                       f_low * np.sqrt(0.99 / 1.01), rtol=1e-9)
    J_line = rng.uniform(0.005, 20.0, 3 * N)
    k_line = rng.uniform(1e4, 1e8, 3 * N - 1)
    contenders = {
        "low": (lambda: build_low_level(d).modal(), 50),
        "plain": (lambda: build_plain(d).modal(), 50),
        "freq": (lambda: build_low_level(d).frequencies_hz(), 50),
        "reuse": (lambda: s.updated(J_new, k_new).modal(), 50),
        "reuse_f": (lambda: s.updated(J_new, k_new).frequencies_hz(), 50),
        "eigh": (lambda: scipy.linalg.eigh(K, M), 50),
    }
    try:
        import opentorsion as ot

        def ot_run() -> None:
            shafts = [ot.Shaft(i, i + 1, k=float(k_line[i])) for i in range(3 * N - 1)]
            disks = [ot.Disk(i, I=float(J_line[i])) for i in range(3 * N)]
            ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()

        contenders["ot"] = (ot_run, 3)
    except ImportError:
        pass
    tm = interleaved(contenders, rounds=21)
    best = {k: v.best * 1e6 for k, v in tm.items()}
    med = {k: v.median * 1e6 for k, v in tm.items()}
    print(f"{'case (72 DOF, assembly included)':<58} {'best':>10} {'median':>10}  note")
    rows = [("TorsionalModel, add_* calls + modal()", "low"),
            ("TorsionalModel.from_contour + modal()", "plain"),
            ("TorsionalModel, add_* calls + frequencies_hz() (no shapes)", "freq"),
            ("topology reused (updated values) + modal()", "reuse"),
            ("topology reused (updated values) + frequencies_hz()", "reuse_f"),
            ("scipy.linalg.eigh(K, M) alone, our matrices", "eigh"),
            ("opentorsion Assembly + undamped_modal_analysis (line)", "ot")]
    for name, key in rows:
        if key not in best:
            continue
        note = ""
        if key in ("low", "plain", "freq", "reuse", "reuse_f") and "ot" in best:
            note = (f"opentorsion / ours = {best['ot'] / best[key]:.1f} best, "
                    f"{med['ot'] / med[key]:.1f} median (need ≥ 20)")
        print(f"{name:<58} {best[key]:>7.0f} µs {med[key]:>7.0f} µs  {note}")


if __name__ == "__main__":
    main()
