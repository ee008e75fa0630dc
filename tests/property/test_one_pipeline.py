"""One pipeline: a design gives the same numbers whoever asks.

Thirty designs from the neighbourhood of the bundled examples — damping ratios, two
contours side by side, inside sprockets, other tooth counts, positions and powers — are
analysed by ``chaindrive.analyze`` (its JSON document, what the command line, the report and
the web page show) and evaluated by the optimiser (``synthesis.evaluation.evaluate_drive``).
Every objective and every constraint the optimiser sees must equal the analysis's value to
1e-12 relative: the optimiser has no copy of the analysis chain of its own.
"""

from __future__ import annotations

import copy
import math
import tomllib
from typing import Any

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import ChainDriveError
from chaindrive.io.design import drive_from_mapping
from chaindrive.robust.synthesis import ROBUST_OBJECTIVES
from chaindrive.synthesis.evaluation import check_limits, constrained, evaluate_drive
from chaindrive.synthesis.objectives import OBJECTIVES
from chaindrive.synthesis.problem import Constraints
from tests.conftest import EXAMPLES

BASES = ("seed_three_sprocket", "eight_sprocket", "two_sprocket_jindal", "twenty_four_sprocket")
DESIGNS = 30
RTOL = 1e-12


def _quantity(text: str) -> tuple[float, str]:
    value, unit = text.split(maxsplit=1)
    return float(value), unit


def _neighbour(base: dict[str, Any], rng: np.random.Generator) -> dict[str, Any]:
    """A design near ``base``: another damping ratio, maybe two contours, one tooth count,
    one position and the power changed a little; the start-up left out in most (it costs a
    time integration each)."""
    d = copy.deepcopy(base)
    dyn = d.setdefault("dynamics", {})
    dyn["damping_ratio"] = float(rng.uniform(0.02, 0.2))
    dyn["transient"] = bool(rng.random() < 0.2)
    dyn["startup_duration"] = "0.1 s"
    if rng.random() < 0.4:
        d["chain"]["contours"] = 2
    sprockets = d["sprockets"]
    k = int(rng.integers(len(sprockets)))
    sprockets[k]["teeth"] = int(np.clip(sprockets[k]["teeth"] + rng.integers(-2, 3), 9, 120))
    movable = [s for s in sprockets if s.get("role") == "idler" or s.get("adjustable")]
    if movable:
        s = movable[int(rng.integers(len(movable)))]
        y, unit = _quantity(s["y"])
        s["y"] = f"{y + rng.uniform(-5.0, 5.0):.6g} {unit}"
    if "power" in d["drive"]:
        p, unit = _quantity(d["drive"]["power"])
        d["drive"]["power"] = f"{p * rng.uniform(0.7, 1.3):.6g} {unit}"
    return d


def _designs() -> list[tuple[str, dict[str, Any]]]:
    rng = np.random.default_rng(20261124)
    bases = {n: tomllib.loads((EXAMPLES / f"{n}.toml").read_text(encoding="utf-8"))
             for n in BASES}
    out = []
    while len(out) < DESIGNS:
        name = BASES[len(out) % len(BASES)]
        mapping = _neighbour(bases[name], rng)
        try:
            drive_from_mapping(mapping)
        except ChainDriveError:
            continue
        out.append((f"{name}-{len(out)}", mapping))
    return out


def _close(a: float, b: float) -> bool:
    return math.isclose(a, b, rel_tol=RTOL, abs_tol=1e-300) or (math.isinf(a) and a == b)


@pytest.mark.parametrize(("name", "mapping"), _designs(), ids=lambda v: v if isinstance(v, str)
                         else "")
def test_optimiser_sees_what_analyze_reports(name: str, mapping: dict[str, Any]) -> None:
    drive = drive_from_mapping(mapping)
    settings = Constraints(startup_safety=drive.dynamics.transient)
    # the robust objectives need a robust problem ([optimize.robust]): tests/unit/test_robust_synthesis.py
    names = tuple(n for n in OBJECTIVES if n not in ROBUST_OBJECTIVES)
    ev = evaluate_drive(drive, names, settings)
    try:
        analysis = chaindrive.analyze(drive, limits=check_limits(settings))
    except ChainDriveError:  # a design that cannot be built is failed by both
        analysis = None
    if analysis is None:
        assert not ev.feasible and ev.constraints == {"buildable": 1.0}
        return
    doc = analysis.to_dict()
    assert ev.error is None, ev.error
    # objectives, read from the document the command line prints
    reported = {
        "cost": doc["metrics"]["cost"],
        "mass": doc["metrics"]["mass_kg"],
        "volume": doc["metrics"]["volume_m3"],
        "chain_length": doc["geometry"]["chain_length_mm"] / 1e3,
        "coefficient_of_dynamics": doc["dynamics"]["coefficient_of_dynamics"],
        "resonance_margin": next(c["value"] for c in doc["checks"]
                                 if c["key"] == "resonance_margin"),
    }
    for key, value in reported.items():
        assert _close(ev.objectives[key], value), (key, ev.objectives[key], value)
    # the rest from the same analysis object (not in the document)
    for key in set(names) - set(reported):
        assert _close(ev.objectives[key], OBJECTIVES[key].value(analysis)), key
    # every constraint that is a check is the document's check, and every check the problem
    # keeps is a constraint
    checks = {c.key: c for c in analysis.checks()}
    kept = {k for k, c in checks.items() if constrained(c, settings)}
    assert kept <= set(ev.constraints)
    for entry in doc["checks"]:
        if entry["key"] in kept:
            c = checks[entry["key"]]
            assert entry["status"] == c.status
            assert _close(ev.constraints[entry["key"]], c.violation), entry["key"]
            if entry["margin_fraction"] is not None:
                assert _close(ev.constraints[entry["key"]], -entry["margin_fraction"])
    assert ev.feasible == (all(c.passed for k, c in checks.items() if k in kept)
                           and all(v <= 0 for k, v in ev.constraints.items() if k not in kept))
