"""The loads of the internal disturbances (sprocket eccentricity, chain pitch scatter and
accumulated error) enter a check: k₂ with the disturbances, Q/max_i(F_R + F₂ + Σ F_d) ≥ [k]
[MultimassChainDrives, §3.6]. Once their loads (3e5 N for a 1 m eccentricity, 1.8e7 N for
1 km of accumulated error, against a 60 kN chain) were computed and judged by nothing.
"""

from __future__ import annotations

import dataclasses

import pytest

import chaindrive
from chaindrive import examples
from chaindrive.dynamics.checks import disturbed_safety_check


def test_the_closed_form() -> None:
    check = disturbed_safety_check(60_000.0, [1000.0, 200.0], [300.0, 50.0],
                                   {"eccentricity": [700.0, 10.0], "chain_error": [0.0, 5.0]},
                                   2.5)
    assert check.value == pytest.approx(60_000.0 / (1000.0 + 300.0 + 700.0))
    assert check.status == "pass" and check.kind == "min" and check.limit == 2.5


@pytest.mark.parametrize(("eccentricity", "accumulated"), [(1.0, 0.0), (0.0, 1000.0)])
def test_breaking_disturbances_fail_the_check(eccentricity: float, accumulated: float) -> None:
    """A drive built in code (no file limits) with a 1 m eccentricity or 1 km of accumulated
    error: the analysis fails its check loudly."""
    drive = examples.load("two_sprocket_jindal")
    drive = dataclasses.replace(drive, dynamics=dataclasses.replace(
        drive.dynamics, eccentricity=eccentricity, accumulated_error=accumulated,
        transient=False))
    analysis = chaindrive.analyze(drive)
    check = analysis.check(next(c.key for c in analysis.checks()
                                if c.name == "k2 with disturbances"))
    assert check is not None and check.status == "fail"
    assert check.value is not None and check.value < 1.0  # the loads exceed Q itself


def test_no_disturbance_no_check() -> None:
    analysis = chaindrive.analyze(examples.load("two_sprocket_jindal"))
    assert all(c.name != "k2 with disturbances" for c in analysis.checks())
