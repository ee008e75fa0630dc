"""An empty Pareto set says why: each constraint with the designs it rejected and by how much
the closest of them missed — in the result, its JSON and the command's table.

The closest miss of the chain-speed limit is checked against the closed form of the mean
chain speed v = z₁ p n₁ / 60 [ChainNonUniformity, eq. 4] of the design it names.
"""

from __future__ import annotations

import io
import math
import tomllib
from pathlib import Path

import pytest

from chaindrive.catalog import find_chain
from chaindrive.synthesis.problem import problem_from_mapping
from chaindrive.synthesis.solve import solve

ROOT = Path(__file__).parents[2]
OPTIMIZE = ROOT / "examples" / "eight_sprocket_optimize.toml"
#: A chain-speed limit no chain of the search can meet (the 8-sprocket drive runs at ~5 m/s).
SLOW = 0.5  # m/s


@pytest.fixture(scope="module")
def infeasible():  # type: ignore[no-untyped-def]
    data = tomllib.loads(OPTIMIZE.read_text(encoding="utf-8"))
    data["optimize"]["constraints"]["max_chain_speed"] = f"{SLOW} m/s"
    data["optimize"]["solver"].update(population=8, generations=2)
    return solve(problem_from_mapping(data, OPTIMIZE.parent))


def test_every_design_rejected_names_the_constraint(infeasible) -> None:  # type: ignore[no-untyped-def]
    r = infeasible
    assert r.pareto == ()
    speed = next(c for c in r.constraint_report if c.name == "chain_speed")
    assert speed.rejected == speed.evaluated == r.evaluations
    assert r.constraint_report[0].rejected == r.evaluations  # the most rejecting first
    # the closest miss is the slowest design's (v − v_max)/v_max, v = z1 p n1 / 60
    design = speed.closest
    driver = next(s for s in design["sprockets"] if s.get("role") == "driver")
    spec = find_chain(design["chain"]["designation"])
    n1 = float(driver["speed"].split()[0])
    v = driver["teeth"] * spec.pitch * n1 / 60.0
    assert speed.least_violation == pytest.approx((v - SLOW) / SLOW, rel=1e-9)
    assert all(c.least_violation is None or c.least_violation > 0 for c in r.constraint_report)


def test_json_and_table_carry_the_diagnosis(infeasible) -> None:  # type: ignore[no-untyped-def]
    from rich.console import Console

    from chaindrive.cli import tables

    doc = infeasible.to_dict()
    rows = {c["constraint"]: c for c in doc["constraints"]}
    assert rows["chain_speed"]["rejected"] == infeasible.evaluations
    assert math.isfinite(rows["chain_speed"]["least_violation"])
    buffer = io.StringIO()
    tables.print_optimisation("eight", infeasible, [],
                              Console(file=buffer, width=160, highlight=False))
    out = buffer.getvalue()
    assert "Pareto set (0 designs)" in out
    assert "chain_speed" in out and "no design met every constraint" in out
    assert f"{infeasible.evaluations}" in out and "% of the limit" in out
