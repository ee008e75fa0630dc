"""The link-level static state at the installed pre-tension on every bundled example, the
12B 15/25 test drive of tests/validation/test_linklevel.py and the loaded peer's drive
(docs/linklevel.md §1, "Pre-tension"). Run (the solve holds BLAS to one thread itself):
.venv/bin/python benchmarks/bench_linklevel_static.py [example …]

Per drive: links, T₀, the span tensions at the state against T₀, the residual (largest
component and 2-norm, N), the rest length against p − T₀/k, the trust-region steps and the
minimisations (pulls), whether it converged, and the CPU time of the solve
(``time.process_time``; the machine's 2 cores are shared, so the time scatters from run to
run).
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model
from chaindrive.linklevel.equilibrium import installed_geometry
from chaindrive.linklevel.simulate import equilibrium_state
from chaindrive.model import Chain, Drive, Sprocket

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"


def _two_sprocket(rpm: float, power: float) -> Drive:
    """The 12B 15/25 drive, 30 pitches apart (the test drive at 30 rpm, the peer at 300)."""
    spec = load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec
    return Drive(name="12B 15/25", chain=Chain(spec), power=power, tooth_form="ISO 606",
                 sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=rpm * math.pi / 30),
                            Sprocket("B", 25, 30 * spec.pitch, 0.0, "driven",
                                     adjustable=True)))


def drives(names: list[str]) -> list[tuple[str, Drive]]:
    out = [(p.stem, load_drive(p)) for p in sorted(EXAMPLES.glob("*.toml"))
           if not names or p.stem in names]
    if not names or "12B" in names:
        out += [("12B 15/25 test (30 rpm, 300 W)", _two_sprocket(30.0, 300.0)),
                ("12B 15/25 peer (300 rpm, 1 kW)", _two_sprocket(300.0, 1000.0))]
    return out


def main(names: list[str]) -> None:
    for name, drive in drives(names):
        geometry, moved = installed_geometry(drive, contour_geometry(drive))
        model = build_model(drive, geometry)
        t = time.process_time()
        _, eq = equilibrium_state(drive, geometry, model, 1e-6, moved)
        cpu = time.process_time() - t
        t0 = model.pretension
        spans = np.array2string(eq.span_tensions, precision=2, max_line_width=200)
        print(f"{name}: {eq.positions.shape[0]} links, T0 {t0:.2f} N, spans {spans} N "
              f"({eq.span_tensions.min() / t0 - 1:+.3%} … {eq.span_tensions.max() / t0 - 1:+.3%});"
              f" reference off by {eq.span_tensions[eq.reference_span] - t0:.1e} N; residual "
              f"{eq.residual_force:.1e} N (norm {eq.residual_norm:.1e} N); rest length "
              f"{(eq.rest_length - (model.pitch - t0 / model.link_stiffness)) * 1e6:+.3f} µm "
              f"from p - T0/k; {eq.iterations} steps, {eq.pulls} pulls; converged "
              f"{eq.converged}; {cpu:.1f} s CPU",
              flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
