"""The link-level model against the whole-drive model on every bundled example: the figures of
docs/linklevel.md §6 ("Every bundled example").
Run (one BLAS thread): OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_agreement.py

Per example (the first contour of a drive with several):

1. First natural frequency along the chain: the link-level model's from its linearisation
   about the static state (:func:`chaindrive.linklevel.modes.linear_modes`, the lowest mode
   with most of its kinetic energy along the chain) against the whole-drive model's first
   elastic frequency (``analyze(...).dynamics.modal.first_elastic_frequency_hz``).
2. Steady span loads: the mean span forces over the closing half of a 0.3 s run at working
   speed and power (link level) against the whole-drive model's static span tensions
   (:func:`chaindrive.dynamics.parameters.static_span_tensions`, span by span).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import chaindrive
from chaindrive.dynamics.parameters import static_span_tensions
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import simulate
from chaindrive.linklevel.modes import linear_modes

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"


def compare(path: Path) -> None:
    drive = load_drive(path)
    analysis = chaindrive.analyze(drive)
    f_ring = analysis.dynamics.modal.first_elastic_frequency_hz
    t = time.process_time()
    modes = linear_modes(drive)
    f_link = modes.first_longitudinal_hz
    cpu_modes = time.process_time() - t
    ratio = "n/a" if f_link is None else f"{f_link / f_ring - 1:+.1%}"
    print(f"{path.stem}: f1 whole drive {f_ring:.1f} Hz, link level "
          f"{f_link if f_link is None else round(f_link, 1)} Hz ({ratio}); "
          f"{modes.frequencies_hz.size} modes in {cpu_modes:.1f} s CPU", flush=True)
    geometry = contour_geometry(drive)
    ring = static_span_tensions(drive, geometry)
    t = time.process_time()
    r = simulate(drive, 0.3, geometry=geometry, initial_speed="working")
    cpu = time.process_time() - t
    link = r.span_mean_force
    if ring is None or len(ring) != len(link):
        print(f"   span means link level {np.array2string(link, precision=0)} N; whole drive "
              "none comparable")
        return
    dev = link / ring - 1
    print(f"   steady span means link level {np.array2string(link, precision=0)} N, whole "
          f"drive {np.array2string(np.asarray(ring), precision=0)} N, deviation "
          f"{np.array2string(100 * dev, precision=1)} % (largest span "
          f"{100 * (link.max() / np.max(ring) - 1):+.1f} %); K_D {r.coefficient_of_dynamics:.2f} "
          f"(whole drive {analysis.steady.coefficient_of_dynamics if analysis.steady else None}); "
          f"run {cpu:.1f} s CPU", flush=True)


if __name__ == "__main__":
    names = sys.argv[1:] or sorted(p.stem for p in EXAMPLES.glob("*.toml"))
    for name in names:
        try:
            compare(EXAMPLES / f"{name}.toml")
        except Exception as exc:
            print(f"{name}: {type(exc).__name__}: {exc}")
