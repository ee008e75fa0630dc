"""A static state solved once (:func:`chaindrive.linklevel.simulate.static_state`) and handed
to :func:`chaindrive.linklevel.simulate`: the same run as one that solves it, whatever its
dampers and hinge friction (the static balance is taken at zero speeds, so neither enters
it), and refused by a run of another drive or model."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.identification.calibration import with_chain
from chaindrive.identification.damping import with_damping_ratio
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model, simulate
from chaindrive.linklevel.equilibrium import installed_geometry
from chaindrive.linklevel.simulate import StaticState, static_state
from tests.conftest import EXAMPLES

#: A short tap of S3 (10 ms) from rest, no motor: every damper acts from the first step.
RUN: dict[str, Any] = {"duration_s": 0.01, "motor": False, "initial_speed": "rest",
                       "kick_rad_s": [0.0, 0.0, 1.0]}


@pytest.fixture(scope="module")
def seed() -> dict[str, Any]:
    drive = load_drive(EXAMPLES / "seed_three_sprocket.toml")
    geometry = contour_geometry(drive)
    model = build_model(drive, installed_geometry(drive, geometry)[0])
    return {"drive": drive, "geometry": geometry, "static": static_state(drive, model, geometry)}


def _same_run(a: Any, b: Any) -> None:
    na, ta = a.history()
    nb, tb = b.history()
    assert na == nb
    assert np.array_equal(ta, tb)


@pytest.mark.parametrize(("ratio", "friction", "damping"), [
    (None, 0.05, True), (0.3, None, True), (None, None, False)])
def test_a_run_from_the_state_solved_once_is_the_run_that_solves_it(
        seed: dict[str, Any], ratio: float | None, friction: float | None,
        damping: bool) -> None:
    drive = seed["drive"] if ratio is None else with_damping_ratio(seed["drive"], ratio)
    kw = RUN | {"geometry": seed["geometry"], "hinge_friction": friction, "damping": damping}
    _same_run(simulate(drive, **kw), simulate(drive, static=seed["static"], **kw))


def test_a_state_of_another_drive_or_model_is_refused(seed: dict[str, Any]) -> None:
    drive, static = seed["drive"], seed["static"]
    assert isinstance(static, StaticState)
    model = build_model(drive, installed_geometry(drive, seed["geometry"])[0])
    stiffer = with_chain(drive, link_stiffness=0.5 * model.link_stiffness)
    for run in ({"drive": stiffer},
                {"drive": drive, "model": dataclasses.replace(model, pretension=1.1
                                                               * model.pretension)}):
        with pytest.raises(DesignError) as err:
            simulate(**(RUN | run), geometry=seed["geometry"], static=static)
        assert err.value.field == "static"
