"""Figures of docs/linklevel.md. Run: .venv/bin/python benchmarks/linklevel_figures.py

Writes docs/linklevel_frames.png (the seed contour running, frames coloured by link
tension), docs/linklevel_tooth_loads.png (tooth loads of the quasi-static two-sprocket run
against the rigid model's geometric decay) and docs/linklevel_slow.png (slow running: the
driven speed against the polygonal law).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from chaindrive.dynamics.motors import ConstantTorque
from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.model import Chain, Drive, Sprocket
from chaindrive.plotting.linklevel import chain_frames, tooth_loads

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def frames() -> None:
    drive = load_drive(ROOT / "examples" / "seed_three_sprocket.toml")
    r = simulate(drive, 0.3, initial_speed="working", sample_rate_hz=2000)
    fig = chain_frames(r, [0.1, 0.2, 0.25, 0.3], columns=2)
    fig.savefig(DOCS / "linklevel_frames.png", dpi=90)


def slow() -> None:
    spec = load_drive(ROOT / "examples" / "eight_sprocket.toml").chain.spec
    drive = Drive(name="two", chain=Chain(spec), power=300.0, tooth_form="ISO 606",
                  sprockets=(Sprocket("A", 15, 0.0, 0.0, "driver", speed=math.pi),
                             Sprocket("B", 25, 30 * spec.pitch, 0.0, "driven",
                                      adjustable=True)))
    geometry = contour_geometry(drive)
    model = build_model(drive, geometry)
    model = replace(model, inertias=model.inertias * np.array([1e4, 1.0]))
    r = simulate(drive, 0.6, geometry=geometry, model=model, initial_speed="working",
                 motor=ConstantTorque(drive.power / drive.driver.speed), resistance="constant",
                 sample_rate_hz=2000)
    gd, gn = geometry.sprockets
    step1, step2 = 2 * math.pi / gd.teeth, 2 * math.pi / gn.teeth
    beta = np.mod(math.atan2(gd.arrive[1] - gd.y, gd.arrive[0] - gd.x) - r.angles[:, 0]
                  + step1 / 2, step1) - step1 / 2
    gamma = np.mod(math.atan2(gn.leave[1] - gn.y, gn.leave[0] - gn.x) - r.angles[:, 1]
                   + step2 / 2, step2) - step2 / 2
    law = (gd.pitch_radius * r.sprocket_speeds[:, 0] * np.cos(beta)
           / (gn.pitch_radius * np.cos(gamma)))
    fig = Figure(figsize=(7.0, 3.2), layout="constrained")
    ax = fig.add_subplot()
    late = r.times > 0.2
    ax.plot(r.times[late], r.sprocket_speeds[late, 1], label="link-level model")
    ax.plot(r.times[late], law[late], "--", label="R₁ω₁ cos β / (R₂ cos γ)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("driven speed [rad/s]")
    ax.legend(fontsize="small")
    ax.set_title("Slow running (30 rpm, 15/25 teeth, 12B): polygonal speed law", fontsize="medium")
    fig.savefig(DOCS / "linklevel_slow.png", dpi=90)
    fig = tooth_loads(r)
    fig.savefig(DOCS / "linklevel_tooth_loads.png", dpi=90)


if __name__ == "__main__":
    frames()
    slow()
