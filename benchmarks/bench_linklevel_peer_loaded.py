"""The link-level model against exudyn on a loaded two-sprocket drive: the figures of
docs/linklevel.md §4 ("Loaded").
Run: OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_peer_loaded.py [t_end_s]

12B chain, 15/25 teeth, 30 pitches apart, 300 rpm, 1 kW: from the static state at working
speed, a constant motor torque P/ω₁ on the driver and a constant load P/ω₂ on the driven
sprocket from t = 0 (the tight span takes up F_t = P/v). Both engines with the same
bodies, forces and initial state (benchmarks/_exudyn_chain.py; no hinge friction, which
exudyn has no element for). Compared: every span's middle-link tension history —
correlation, RMS difference against the fluctuation (the standard deviation of the history),
means.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from chaindrive.dynamics.motors import ConstantTorque
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import installed_geometry, span_probes
from chaindrive.linklevel.simulate import initial_state
from chaindrive.model import Chain, Drive, Sprocket

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"
POWER = 1000.0
RPM = 300.0


def loaded_drive() -> Drive:
    spec = load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec
    return Drive(name="peer", chain=Chain(spec), power=POWER,
                 sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=RPM * math.pi / 30),
                            Sprocket("B", 25, 30 * spec.pitch, 0.0, "driven", adjustable=True)))


def compare(t_end: float) -> dict[str, float]:
    import _exudyn_chain as peer_model

    drive = loaded_drive()
    geometry, _ = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry, hinge_friction=0.0)
    state = initial_state(drive, geometry, model, "steady")
    w1 = RPM * math.pi / 30
    w2 = w1 * 15 / 25
    m1, m2 = POWER / w1, POWER / w2
    t = time.process_time()
    r = simulate(drive, t_end, geometry=geometry, model=model, initial_speed="working",
                 motor=ConstantTorque(m1), resistance="constant", sample_rate_hz=10000)
    cpu_ours = time.process_time() - t
    probes = [int(i) for i in span_probes(r.geometry, state.positions)]
    torques = np.array([model.turn[0] * m1, -model.turn[1] * m2])
    wall, data = peer_model.run_loaded(model, state, r.dt / 4, t_end, torques, probes)
    out: dict[str, float] = {"dt_ours_s": r.dt, "dt_exudyn_s": r.dt / 4,
                             "cpu_ours_s": cpu_ours, "wall_exudyn_s": wall}
    for k, name in enumerate(r.span_names):
        theirs = np.interp(r.times, data[:, 0], data[:, 1 + k])
        ours = r.span_forces[:, k]
        ok = np.isfinite(theirs).all()
        corr = float(np.corrcoef(ours, theirs)[0, 1]) if ok else math.nan
        rms = float(np.sqrt(np.mean((ours - theirs) ** 2)))
        out[f"span_{name}_mean_ours_n"] = float(ours.mean())
        out[f"span_{name}_mean_exudyn_n"] = float(theirs.mean())
        out[f"span_{name}_correlation"] = corr
        out[f"span_{name}_rms_difference_n"] = rms
        out[f"span_{name}_fluctuation_n"] = float(ours.std())
    return out


if __name__ == "__main__":
    t_end = float(sys.argv[1]) if len(sys.argv) > 1 else 0.1
    ft = POWER / (15 * load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec.pitch
                  * RPM / 60)
    print(f"loaded peer: 12B 15/25, {RPM:g} rpm, {POWER:g} W (F_t = {ft:.0f} N), "
          f"{t_end * 1e3:g} ms")
    for key, value in compare(t_end).items():
        print(f"   {key}: {value:.4g}")
