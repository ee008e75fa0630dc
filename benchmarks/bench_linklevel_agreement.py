"""The link-level model against the whole-drive model on every bundled example, like with
like: the figures of docs/linklevel.md §6 ("Agreement, like with like").
Run (one BLAS thread): OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_agreement.py [NAME …]

Per example (the first contour of a drive with several):

1. First natural frequency along the chain, at one tension state and on one set of masses
   (:func:`chaindrive.linklevel.compare.mode_agreement`): the link-level model linearised
   about its static state at rest (T₀) and about its loaded static state, the whole-drive
   model evaluated at the same span tensions on the same masses (no motor, no trains);
   the first mode of the link-level's longitudinal–torsional family against the
   whole-drive model's first, their MAC on the sprockets' turns, where each holds its
   strain energy; the transverse modes against their spans' strings. Beside it the
   analysis' own whole-drive f₁ (its running tensions, its motor and trains).
2. Steady span loads (:func:`chaindrive.linklevel.compare.span_load_agreement`): the mean
   span forces over the closing half of a 0.3 s run at working speed and power (link
   level) against the whole-drive model's static span tensions, span by span.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

import chaindrive
from chaindrive.dynamics.parameters import static_span_tensions
from chaindrive.errors import ConvergenceError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import simulate
from chaindrive.linklevel.compare import mode_agreement, span_load_agreement

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"


def _one(drive_path: Path) -> dict[str, object]:
    drive = load_drive(drive_path)
    analysis = chaindrive.analyze(drive)
    drive = analysis._contour_drive  # one contour, as the study runs it
    out: dict[str, object] = {
        "analysis_first_hz": analysis.dynamics.modal.first_elastic_frequency_hz}
    geometry = contour_geometry(drive)
    for loaded in (False, True):
        t = time.process_time()
        try:
            agree = mode_agreement(drive, geometry=geometry, loaded=loaded)
        except ConvergenceError as exc:  # the loaded state not reached: say so, go on
            out["loaded" if loaded else "rest"] = {"error": str(exc)}
            print(f"  {'loaded' if loaded else 'rest'}: {exc}", flush=True)
            continue
        out["loaded" if loaded else "rest"] = {**agree.to_dict(),
                                               "cpu_s": time.process_time() - t}
        pairs = [(round(p.whole_drive_hz, 1), p.link_level_hz and round(p.link_level_hz, 1),
                  p.mac and round(p.mac, 3)) for p in agree.pairs]
        strings = [(round(s.frequency_hz, 2), s.span, s.half_waves, round(s.ratio, 3))
                   for s in agree.transverse]
        print(f"  {'loaded' if loaded else 'rest  '}: whole {agree.whole_drive_hz:.1f} Hz, "
              f"first along the chain {agree.link_level_hz} Hz (MAC {agree.first_mac}, "
              f"{agree.below} below), counterpart deviation {agree.deviation}, verdict "
              f"{agree.verdict}, first seat {agree.first_seat_hz}, lowest string "
              f"{agree.lowest_string_hz:.1f} Hz; strain link {np.round(agree.link_strain, 3)}, whole "
              f"{np.round(agree.whole_strain, 3)}; tensions "
              f"{np.round(agree.span_tensions_n, 1)}; pairs {pairs}; strings {strings}",
              flush=True)
    ring = static_span_tensions(drive, geometry)
    t = time.process_time()
    r = simulate(drive, 0.3, geometry=geometry, initial_speed="working")
    if ring is not None and len(ring) == len(r.span_mean_force):
        loads = span_load_agreement(r.span_names, ring, r.span_mean_force)
        out["span_loads"] = loads.to_dict()
        print(f"  span loads: whole {np.round(loads.whole_drive_n, 1)}, link "
              f"{np.round(loads.link_level_n, 1)}, dev {np.round(loads.deviations, 3)}, "
              f"loaded {loads.tight}; K_D {r.coefficient_of_dynamics}; run "
              f"{time.process_time() - t:.1f} s CPU", flush=True)
    return out


if __name__ == "__main__":
    names = sys.argv[1:] or sorted(p.stem for p in EXAMPLES.glob("*.toml"))
    results = {}
    for name in names:
        print(name, flush=True)
        try:
            results[name] = _one(EXAMPLES / f"{name}.toml")
        except Exception as exc:  # one example's failure does not stop the others
            print(f"  {type(exc).__name__}: {exc}", flush=True)
            results[name] = {"error": f"{type(exc).__name__}: {exc}"}
    tag = "_".join(names) if sys.argv[1:] else "all"
    Path(f"bench_linklevel_agreement_{tag}.json").write_text(json.dumps(results, indent=1,
                                                                  default=float))
