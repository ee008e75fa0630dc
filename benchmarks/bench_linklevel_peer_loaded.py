"""The link-level model against exudyn on a loaded two-sprocket drive: the figures of
docs/linklevel.md §4 ("Loaded").
Run: OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_peer_loaded.py [t_end_s]
     (``--convergence``: the peer's step and chords over the test's 10 ms, about 4 min)

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
#: Exudyn's tooth gap: the seating arc in 100 chords touching it (docs/linklevel.md §4, the
#: peer's convergence). Over 10 ms the tight span's correlation, RMS difference and mean
#: move by 9 %, 8 % and 1.5 % of the test's margins from 400 chords (0.99804 against
#: 0.99886, 12.6 against 10.2 N); the chords lie within 0.38 µm of the arc, the static
#: contact compression's order, so the peer starts seated; 17 s of exudyn CPU instead of
#: 31 s at 200 chords. Its step (a quarter of ours) is set by RK44's stability (half and a
#: third of ours blow up) and converged (an eighth: the same figures to four digits).
CHORDS = 100


def loaded_drive() -> Drive:
    spec = load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec
    return Drive(name="peer", chain=Chain(spec), power=POWER,
                 sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=RPM * math.pi / 30),
                            Sprocket("B", 25, 30 * spec.pitch, 0.0, "driven", adjustable=True)))


def _ours(t_end: float) -> tuple:
    """(model, initial state, our run, our CPU time [s], probed links, sprocket torques)."""
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
    return model, state, r, cpu_ours, probes, torques


def _theirs(r, data: np.ndarray) -> np.ndarray:
    """Exudyn's probed link forces (T, spans) on our record's instants [N]."""
    return np.column_stack([np.interp(r.times, data[:, 0], data[:, 1 + k])
                            for k in range(len(r.span_names))])


def compare(t_end: float, chords: int = CHORDS, divisor: int = 4) -> dict[str, float]:
    """Ours against exudyn at a ``divisor``-th of our step with ``chords`` per seating arc."""
    import _exudyn_chain as peer_model

    model, state, r, cpu_ours, probes, torques = _ours(t_end)
    wall, data = peer_model.run_loaded(model, state, r.dt / divisor, t_end, torques, probes,
                                       n_arc=chords)
    out: dict[str, float] = {"dt_ours_s": r.dt, "dt_exudyn_s": r.dt / divisor,
                             "chords": chords, "cpu_ours_s": cpu_ours, "wall_exudyn_s": wall}
    theirs_all = _theirs(r, data)
    for k, name in enumerate(r.span_names):
        theirs = theirs_all[:, k]
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


def convergence(t_end: float = 0.01) -> None:
    """The table "The peer's discretisation" of docs/linklevel.md §4: the tight span's
    asserted quantities for exudyn's step and chords, and exudyn's history against its own
    at 400 chords (the stable settings only: RK44 at half or a third of our step blows up
    within 1 ms)."""
    import _exudyn_chain as peer_model

    model, state, r, _, probes, torques = _ours(t_end)
    tight = int(np.argmax(r.span_forces.mean(axis=0)))
    ours = r.span_forces[:, tight]
    print(f"tight span {r.span_names[tight]}: ours mean {ours.mean():.2f} N, fluctuation "
          f"{ours.std():.2f} N; step, chords: CPU, mean, correlation, RMS, vs finest "
          "RMS / max, slack correlation")
    finest = None
    for divisor, chords in ((4, 400), (8, 200), (4, 200), (4, 100), (4, 50), (4, 25),
                            (4, 10)):
        t = time.process_time()
        _, data = peer_model.run_loaded(model, state, r.dt / divisor, t_end, torques,
                                        probes, n_arc=chords)
        cpu = time.process_time() - t
        theirs = _theirs(r, data)
        finest = theirs if finest is None else finest
        th, off = theirs[:, tight], theirs[:, tight] - finest[:, tight]
        slack = np.corrcoef(r.span_forces[:, 1 - tight], theirs[:, 1 - tight])[0, 1]
        print(f"   Δt/{divisor}, {chords:3d}: {cpu:5.1f} s, {th.mean():.2f} N, "
              f"{np.corrcoef(ours, th)[0, 1]:.5f}, {np.sqrt(np.mean((ours - th) ** 2)):.2f} N, "
              f"{np.sqrt(np.mean(off ** 2)):.1f} / {np.abs(off).max():.1f} N, {slack:.3f}")


if __name__ == "__main__":
    if "--convergence" in sys.argv:
        convergence()
        sys.exit()
    t_end = float(sys.argv[1]) if len(sys.argv) > 1 else 0.1
    ft = POWER / (15 * load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec.pitch
                  * RPM / 60)
    print(f"loaded peer: 12B 15/25, {RPM:g} rpm, {POWER:g} W (F_t = {ft:.0f} N), "
          f"{t_end * 1e3:g} ms")
    for key, value in compare(t_end).items():
        print(f"   {key}: {value:.4g}")
