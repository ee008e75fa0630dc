"""Why the loaded peer's tension histories parted (docs/linklevel.md §4, "What kept them
apart"). Run: OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_peer_diagnosis.py

1. Our step: the loaded drive of benchmarks/bench_linklevel_peer_loaded.py over 20 ms at
   Δt/4 and Δt/16 against Δt/64 (correlation of the middle-link tension histories).
2. Sampling: our history at every step resampled as the benchmark compares exudyn's (its
   samples every 0.1 ms, linearly interpolated onto our 10 kHz record) against itself.
3. Corner contacts: the contact samples of our run whose roller centre lies beyond the
   corner where the flank meets the tip circle (past the flank's end and outside the tip
   circle), with the roller's true clearance from the corner and our contact force.
4. Exudyn's contact in a seat: one roller pressed into the seating arc of the 15-tooth
   sprocket (GeneralContact, the arc in n chords touching it at their midpoints) by 100 and
   1000 N; the static penetration gives the effective stiffness against ours, k_c. Exudyn
   adds a contact for every triangle the roller overlaps; in the nearly conformal seat
   (r_i − r = 0.14 mm) a loaded roller overlaps many chords.
5. Against exudyn (``--peer [t_end_s]``, 50 ms by default: about 8 min of exudyn per run):
   exudyn at Δt/4 against itself at Δt/8, ours at Δt, Δt/4, Δt/16, Δt/64 and ours with
   its contact stiffness k_c × 1, 3, 6, 10 against exudyn at Δt/4 (tight and slack span
   correlations over the first 20 ms and over the run).
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_linklevel_peer_loaded as loaded
from chaindrive.dynamics.motors import ConstantTorque
from chaindrive.geometry.contour import contour_geometry
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import installed_geometry


def _setup():
    drive = loaded.loaded_drive()
    geometry, _ = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry, hinge_friction=0.0)
    return drive, geometry, model, loaded.POWER / (loaded.RPM * math.pi / 30)


def _run(drive, geometry, model, m1, t_end, dt=None):
    return simulate(drive, t_end, geometry=geometry, model=model, initial_speed="working",
                    motor=ConstantTorque(m1), resistance="constant", sample_rate_hz=1e9,
                    dt_s=dt)


def step_and_sampling(t_end: float = 0.02) -> None:
    drive, geometry, model, m1 = _setup()
    base = _run(drive, geometry, model, m1, t_end)
    ref = _run(drive, geometry, model, m1, t_end, base.dt / 64)
    print("1. our step (correlation with Δt/64 over 20 ms: tight, slack)")
    for div in (1, 4, 16):
        r = base if div == 1 else _run(drive, geometry, model, m1, t_end, base.dt / div)
        c = [np.corrcoef(np.interp(ref.times, r.times, r.span_forces[:, k]),
                         ref.span_forces[:, k])[0, 1] for k in range(2)]
        print(f"   Δt/{div:<2d}: {c[0]:.4f}, {c[1]:.4f}")
    print("2. sampling (our history resampled as exudyn's is, against itself)")
    every = max(1, round(1e-4 / base.dt))
    idx = np.arange(0, len(base.times), every)
    instants = np.searchsorted(base.times, np.arange(0.0, t_end, 1e-4) - 1e-12)
    instants = instants[instants < len(base.times)]
    for k, name in enumerate(base.span_names):
        f = base.span_forces[:, k]
        again = np.interp(base.times[idx], base.times[instants], f[instants])
        print(f"   span {name}: correlation {np.corrcoef(f[idx], again)[0, 1]:.4f}")
    print("3. contacts with the roller centre beyond a tooth's tip corner")
    count, total, worst = 0, 0, (0.0, 0.0)
    for i in range(len(base.times)):
        for s in range(2):
            for roller in np.where(base.contact_sprocket[i] == s)[0]:
                total += 1
                clear = _corner_clearance(model, base.positions[i, roller] - model.centres[s],
                                          float(base.angles[i, s]), s)
                if clear is not None:
                    count += 1
                    worst = max(worst, (float(base.contact_forces[i, roller]), clear))
    print(f"   {count} of {total} contact samples; largest force {worst[0]:.0f} N with the "
          f"roller {worst[1] * 1e3:.2f} mm clear of the corner")


def _corner_clearance(model, p, th: float, s: int) -> float | None:
    """The roller's clearance from the tip corner of its gap [m] when its centre lies past
    the flank's end and outside the tip circle (None otherwise)."""
    z, R, ri = int(model.teeth[s]), model.pitch_radii[s], model.seating_radii[s]
    al, Ra, rr = model.seating_half_angles[s], model.tip_radii[s], model.roller_radius
    step = 2 * math.pi / z
    ga = th + math.floor((math.atan2(p[1], p[0]) - th) / step + 0.5) * step
    g = np.array([math.cos(ga), math.sin(ga)])
    t = np.array([-g[1], g[0]])
    sg = 1.0 if (p - R * g) @ t > 0 else -1.0
    f = -math.cos(al) * g + sg * math.sin(al) * t
    u = sg * np.array([f[1], -f[0]])
    p_alpha = R * g + ri * f
    b, c = p_alpha @ u, p_alpha @ p_alpha - Ra * Ra
    length = -b + math.sqrt(b * b - c)
    if (p - p_alpha) @ u <= length or np.hypot(*p) <= Ra:
        return None
    return float(np.hypot(*(p - p_alpha - length * u)) - rr)


def exudyn_seat() -> None:
    import exudyn as exu
    from exudyn.itemInterface import (
        LoadForceVector,
        MarkerBodyRigid,
        MarkerNodePosition,
        MassPoint2D,
        NodePoint2D,
        ObjectGround,
        SensorNode,
    )

    import _exudyn_chain as peer

    _, _, model, _ = _setup()
    kc, cc, m = model.contact_stiffness[0], model.contact_damping[0], model.roller_mass
    R, ri, al = model.pitch_radii[0], model.seating_radii[0], model.seating_half_angles[0]
    Ra, rr = model.tip_radii[0], model.roller_radius
    print(f"4. exudyn: a roller pressed into its seat (k_c = {kc:.3g} N/m, r_i − r = "
          f"{(ri - rr) * 1e3:.3f} mm)")
    for chords in (200, 50, 10):
        for force in (100.0, 1000.0):
            sc = exu.SystemContainer()
            mbs = sc.AddSystem()
            contact = mbs.AddGeneralContact()
            x0 = np.array([R - (ri - rr), 0.0])  # touching the seat's bottom
            node = mbs.AddNode(NodePoint2D(referenceCoordinates=list(x0)))
            mbs.AddObject(MassPoint2D(physicsMass=m, nodeNumber=node))
            marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
            mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[-force, 0, 0]))
            contact.AddSphereWithMarker(marker, rr, 2 * kc, 2 * cc, 0)
            ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=mbs.AddObject(ObjectGround()),
                                                   localPosition=[0, 0, 0]))
            outline = peer.tooth_outline(int(model.teeth[0]), R, ri, al, Ra, n_arc=chords,
                                         tangent=True)
            points, triangles = peer.extrude(outline, 0.01)
            contact.AddTrianglesRigidBodyBased(ground, 2 * kc, 2 * cc, 0, points, triangles)
            contact.SetFrictionPairings(np.zeros((1, 1)))
            contact.SetSearchTreeBox([-0.1, -0.1, -0.1], [0.1, 0.1, 0.1])
            contact.SetSearchTreeCellSize([20, 20, 1])
            sensor = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True,
                                              outputVariableType=exu.OutputVariableType.Position))
            mbs.Assemble()
            settings = exu.SimulationSettings()
            settings.timeIntegration.numberOfSteps = 4000
            settings.timeIntegration.endTime = 0.004
            settings.timeIntegration.verboseMode = 0
            settings.solutionSettings.writeSolutionToFile = False
            settings.solutionSettings.sensorsWritePeriod = 1e-4
            exu.SolveDynamic(mbs, settings, solverType=exu.DynamicSolverType.RK44)
            data = mbs.GetSensorStoredData(sensor)
            delta = x0[0] - data[len(data) // 2:, 1].mean()  # the oscillation's mean
            print(f"   {chords:3d} chords, {force:5.0f} N: penetration {delta * 1e6:6.3f} µm, "
                  f"stiffness {force / delta / kc:5.2f} k_c")


def against_exudyn(t_end: float) -> None:
    import _exudyn_chain as peer
    from chaindrive.linklevel.equilibrium import span_probes
    from chaindrive.linklevel.simulate import initial_state

    drive, geometry, model, m1 = _setup()
    state = initial_state(drive, geometry, model, "steady")
    base = _run(drive, geometry, model, m1, t_end)
    probes = [int(i) for i in span_probes(base.geometry, state.positions)]
    m2 = m1 * 25 / 15
    torques = np.array([model.turn[0] * m1, -model.turn[1] * m2])
    _, fine = peer.run_loaded(model, state, base.dt / 4, t_end, torques, probes)
    _, finer = peer.run_loaded(model, state, base.dt / 8, t_end, torques, probes)
    te = fine[:, 0]

    def corr(times, forces, k: int, until: float) -> float:
        on = te <= until
        return float(np.corrcoef(np.interp(te[on], times, forces), fine[on, 1 + k])[0, 1])

    print(f"5. against exudyn over {t_end * 1e3:g} ms (tight, slack: first 20 ms / whole run)")
    for k, name in enumerate(base.span_names):
        print(f"   exudyn Δt/8 against Δt/4, span {name}: "
              f"{corr(finer[:, 0], finer[:, 1 + k], k, t_end):.4f}")
    runs = {f"ours Δt/{d}": _run(drive, geometry, model, m1, t_end, base.dt / d)
            for d in (4, 16, 64)}
    runs = {"ours Δt": base, **runs}
    for f in (3.0, 6.0, 10.0):
        stiffer = replace(model, contact_stiffness=model.contact_stiffness * f,
                          contact_damping=model.contact_damping * math.sqrt(f))
        runs[f"ours {f:g} k_c"] = _run(drive, geometry, stiffer, m1, t_end)
    for label, r in runs.items():
        cells = [f"{corr(r.times, r.span_forces[:, k], k, 0.02):.3f} / "
                 f"{corr(r.times, r.span_forces[:, k], k, t_end):.3f}" for k in range(2)]
        print(f"   {label:14s} " + ", ".join(f"span {n}: {c}" for n, c in
                                          zip(r.span_names, cells, strict=True)))


if __name__ == "__main__":
    if "--peer" in sys.argv:
        rest = sys.argv[sys.argv.index("--peer") + 1:]
        against_exudyn(float(rest[0]) if rest else 0.05)
    else:
        step_and_sampling()
        exudyn_seat()
