"""The link-level model as a reference: the figures of docs/linklevel.md §2 and §4.
Run (one BLAS thread): OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_linklevel_reference.py

1. Static state: the span tensions at t = 0 against the whole-drive model's pre-tension T₀
   (without gravity) and against the hydrostatic closed form T₀ + q g (y − y_ref) (with
   gravity), and how far they move over 50 ms at rest with no motor (seed, 12B 15/25).
2. Energy: undamped coasting at working speed, no motor (seed, 1 s): drift of the energy
   balance as a fraction of the kinetic energy at Δt, Δt/2, Δt/4, link springs explicit
   and implicit.
3. Step convergence: K_D, span dynamic loads, peaks and means at working speed and power
   over 0.3 s at Δt and Δt/2 (seed; a 12B 15/25 drive of about 200 links), link springs
   explicit and implicit.
4. Speed: CPU seconds per simulated second at working speed (seed, 128 links; the 12B
   15/25 drive; the 24-sprocket example, 744 links), the static state's solve apart, link
   springs explicit and implicit.
5. Step limit (``steps [seed|12B|eight …]``): 1–4× the default step, link springs explicit
   (the implicit dampers keep them stable there) and implicit, the hinge friction implicit
   above the default step, 0.3 s at working speed and power with the run at Δt/2: the
   changes of K_D, F_D, peaks and means and the energy balance (seed, 12B 15/25, the
   eight-sprocket example).
6. What moves the energy balance at a larger step (``hinge``): the seed at Δt and 2Δt with
   and without the hinge friction and the contact dampers; the step convergence without the
   hinge friction at Δt.
"""

from __future__ import annotations

import math
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import span_probes
from chaindrive.model import Chain, Drive, Sprocket

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"


def _two_sprocket(pitches: int, rpm: float, power: float) -> Drive:
    spec = load_drive(EXAMPLES / "eight_sprocket.toml").chain.spec
    return Drive(name="12B", chain=Chain(spec), power=power, tooth_form="ISO 606",
                 sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=rpm * math.pi / 30),
                            Sprocket("B", 25, pitches * spec.pitch, 0.0, "driven",
                                     adjustable=True)))


def static_state() -> None:
    print("1. static state at rest, no motor, 50 ms")
    for name, drive in (("seed", load_drive(EXAMPLES / "seed_three_sprocket.toml")),
                        ("12B 15/25", _two_sprocket(30, 300.0, 1000.0))):
        geometry = contour_geometry(drive)
        for g in (0.0, 9.80665):
            model = build_model(drive, geometry, gravity=g)
            t = time.process_time()
            r = simulate(drive, 0.05, geometry=geometry, model=model, motor=False)
            cpu = time.process_time() - t
            x = r.positions[0]
            mids = 0.5 * (x + np.roll(x, -1, axis=0))[span_probes(r.geometry, x)]
            ref = r.equilibrium["reference_span"]
            closed = model.pretension + model.roller_mass / model.pitch * g * (
                mids[:, 1] - mids[ref, 1])
            t0 = np.asarray(r.equilibrium["span_tension_n"])
            moved = np.abs(r.span_forces[-1] / r.span_forces[0] - 1).max()
            print(f"   {name:9s} g = {g:4.2f}: T0 {model.pretension:7.2f} N, spans at t=0 "
                  f"{np.array2string(t0, precision=2)} N, closed form "
                  f"{np.array2string(closed, precision=2)} N; moved {100 * moved:.2f} % in "
                  f"50 ms; residual {r.equilibrium['residual_force_n']:.1e} N; "
                  f"take-up {r.equilibrium['take_up_sprocket']}; {cpu:.1f} s CPU")


def energy() -> None:
    print("2. undamped coasting at working speed, no motor, seed, 1 s")
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    for implicit in (False, True):
        base = None
        for f in (1.0, 0.5, 0.25):
            kw: dict[str, object] = {"motor": False, "damping": False,
                                     "initial_speed": "working", "implicit_links": implicit}
            if base is not None:
                kw["dt_s"] = base * f
            r = simulate(drive, 1.0, **kw)  # type: ignore[arg-type]
            base = base or r.dt
            print(f"   {'implicit' if implicit else 'explicit'} links, dt = {f:4.2f}·default "
                  f"({r.dt * 1e6:5.2f} µs): drift {r.energy['drift_fraction']:+.2e} of the "
                  f"kinetic energy ({r.energy['start_kinetic_j']:.1f} J)")


def convergence() -> None:
    print("3. step convergence at working speed and power, 0.3 s")
    for name, drive in (("seed", load_drive(EXAMPLES / "seed_three_sprocket.toml")),
                        ("12B 15/25", _two_sprocket(85, 300.0, 1000.0))):
        for implicit in (False, True):
            r = simulate(drive, 0.3, initial_speed="working", check_step=True,
                         implicit_links=implicit)
            c = r.convergence
            print(f"   {name:9s} {'implicit' if implicit else 'explicit'} links, dt "
                  f"{r.dt * 1e6:5.2f} µs: K_D {r.coefficient_of_dynamics:.3f}, largest peak "
                  f"{r.span_forces.max():.0f} N; changes at dt/2: K_D "
                  f"{c['coefficient_of_dynamics_change']:.2%}, F_D "
                  f"{c['span_dynamic_load_change']:.2%}, peaks "
                  f"{c['peak_span_force_change']:.2%}, means {c['span_mean_force_change']:.2%}; "
                  f"converged {c['converged']}")


def speed() -> None:
    print("4. CPU s per simulated second at working speed (static state apart); load "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    for name, drive, duration in (
            ("seed", load_drive(EXAMPLES / "seed_three_sprocket.toml"), 0.5),
            ("12B 15/25", _two_sprocket(85, 300.0, 1000.0), 0.25),
            ("24 sprockets", load_drive(EXAMPLES / "twenty_four_sprocket.toml"), 0.1)):
        for implicit in (False, True):
            kw = {"initial_speed": "working", "implicit_links": implicit,
                  "sample_rate_hz": 1000}
            simulate(drive, 0.002, **kw)  # type: ignore[arg-type]  # warm-up (compile)
            cpu = []
            for d in (duration, 2 * duration):  # the difference: the static state drops out
                t = time.process_time()
                r = simulate(drive, d, **kw)  # type: ignore[arg-type]
                cpu.append(time.process_time() - t)
            per = (cpu[1] - cpu[0]) / duration
            print(f"   {name:12s} {r.positions.shape[1]:4d} links  "
                  f"{'implicit' if implicit else 'explicit'}  dt {r.dt * 1e6:5.2f} µs  "
                  f"{per:6.3f} s per simulated s ({1 / per:5.1f}× real time; static state "
                  f"{cpu[0] - per * duration:.1f} s); energy balance "
                  f"{r.energy['drift_fraction']:+.1e}", flush=True)


def step_limit() -> None:
    print("5. larger steps, 0.3 s at working speed and power, the run repeated at dt/2 "
          f"(load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores)")
    which = sys.argv[2:] or ["seed", "12B", "eight"]
    drives = {"seed": lambda: load_drive(EXAMPLES / "seed_three_sprocket.toml"),
              "12B": lambda: _two_sprocket(85, 300.0, 1000.0),
              "eight": lambda: load_drive(EXAMPLES / "eight_sprocket.toml")}
    for name in which:
        drive = drives[name]()
        geometry = contour_geometry(drive)
        model = build_model(drive, geometry)
        base = simulate(drive, 0.001, geometry=geometry, model=model).dt
        for implicit in (False, True):
            for f in (1.0, 1.25, 1.5, 2.0, 3.0, 4.0):
                r = simulate(drive, 0.3, geometry=geometry, model=model,
                             initial_speed="working", dt_s=base * f, check_step=True,
                             implicit_links=implicit)
                c = r.convergence
                print(f"   {name:5s} {'implicit' if implicit else 'explicit'} springs, dt = "
                      f"{f:4.2f}·default ({r.dt * 1e6:5.2f} µs): K_D "
                      f"{r.coefficient_of_dynamics:.3f}; changes at dt/2: K_D "
                      f"{c['coefficient_of_dynamics_change']:.2%}, F_D "
                      f"{c['span_dynamic_load_change']:.2%}, peaks "
                      f"{c['peak_span_force_change']:.2%}, means "
                      f"{c['span_mean_force_change']:.2%}; energy balance "
                      f"{r.energy['drift_fraction']:+.1e}", flush=True)


def hinge() -> None:
    print("6. energy balance at Δt and 2Δt, seed, 0.3 s at working speed and power")
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    geometry = contour_geometry(drive)
    full = build_model(drive, geometry)
    models = {"as built": full,
              "no hinge friction": build_model(drive, geometry, hinge_friction=0.0),
              "no contact dampers": replace(full, contact_damping=0.0 * full.contact_damping)}
    base = simulate(drive, 0.001, geometry=geometry, model=full).dt
    for name, model in models.items():
        for f in (1.0, 2.0):
            r = simulate(drive, 0.3, geometry=geometry, model=model, initial_speed="working",
                         dt_s=base * f)
            e = r.energy
            print(f"   {name:19s} dt = {f:3.1f}·default: K_D {r.coefficient_of_dynamics:.3f}, "
                  f"energy balance {e['drift_fraction']:+.1e}; hinge friction "
                  f"{e['hinge_friction_j']:.2f} J, link dampers {e['link_damping_j']:.2f} J, "
                  f"contact dampers {e['contact_damping_j']:.2f} J, motor "
                  f"{e['motor_work_j']:.1f} J", flush=True)
    r = simulate(drive, 0.3, geometry=geometry, model=models["no hinge friction"],
                 initial_speed="working", dt_s=base, check_step=True)
    c = r.convergence
    print(f"   no hinge friction at the default step, changes at dt/2: K_D "
          f"{c['coefficient_of_dynamics_change']:.2%}, F_D {c['span_dynamic_load_change']:.2%}, "
          f"peaks {c['peak_span_force_change']:.2%}, means {c['span_mean_force_change']:.2%}",
          flush=True)


if __name__ == "__main__":
    parts = {"static": static_state, "energy": energy, "convergence": convergence,
             "speed": speed, "steps": step_limit, "hinge": hinge}
    keys = sys.argv[1:] or list(parts)
    for key in keys if keys[0] != "steps" else ["steps"]:
        parts[key]()
