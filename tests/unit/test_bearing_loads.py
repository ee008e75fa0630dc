"""Bearing reactions to a sprocket's shaft load where the design gives the two bearing
positions: the statics of a shaft on two simple supports with the load at the sprocket's
mid-plane (z = 0), R1 = F·z2/(z2 − z1), R2 = −F·z1/(z2 − z1) [Shigley2015]: the forces
balance (R1 + R2 = F) and so do the moments about the sprocket (R1·z1 + R2·z2 = 0)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import DesignError
from chaindrive.strength.loads import bearing_loads

EXAMPLE = Path(__file__).parents[2] / "src" / "chaindrive" / "examples" / "two_sprocket_jindal.toml"


@pytest.mark.parametrize(("z1", "z2", "k1", "k2"), [(-0.030, 0.050, 0.625, 0.375),
                                                    (0.040, 0.100, 100 / 60, -40 / 60),
                                                    (0.050, -0.050, 0.5, 0.5)])
def test_statics_of_the_shaft(z1: float, z2: float, k1: float, k2: float) -> None:
    f = (300.0, -400.0)
    r1, r2 = bearing_loads(f, z1, z2)
    np.testing.assert_allclose(r1, np.multiply(f, k1), rtol=1e-12)
    np.testing.assert_allclose(r2, np.multiply(f, k2), rtol=1e-12)
    np.testing.assert_allclose(np.add(r1, r2), f, rtol=1e-12)
    np.testing.assert_allclose(np.multiply(r1, z1) + np.multiply(r2, z2), 0.0, atol=1e-9)


def _design(tmp_path: Path, extra: str) -> Path:
    text = EXAMPLE.read_text().replace('speed = "1000 rpm"\n', 'speed = "1000 rpm"\n' + extra)
    path = tmp_path / "d.toml"
    path.write_text(text)
    return path


def test_analysis_reports_the_bearing_loads(tmp_path: Path) -> None:
    a = chaindrive.analyze(chaindrive.load(_design(tmp_path, 'bearing_1 = "-30 mm"\n'
                                                             'bearing_2 = "50 mm"\n')),
                           response=False)
    doc = a.to_dict()["strength"]
    f = np.array(doc["shaft_load_vectors_n"][0])
    r1, r2 = (np.array(v) for v in doc["bearing_load_vectors_n"][0])
    np.testing.assert_allclose(r1, 0.625 * f, rtol=1e-12)
    np.testing.assert_allclose(r2, 0.375 * f, rtol=1e-12)
    assert doc["bearing_loads_n"][0] == pytest.approx([0.625 * np.hypot(*f),
                                                       0.375 * np.hypot(*f)])
    assert doc["bearing_loads_n"][1] is None and doc["bearing_load_vectors_n"][1] is None


def test_bearing_positions_are_checked(tmp_path: Path) -> None:
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bearing_2.*missing"):
        chaindrive.load(_design(tmp_path, 'bearing_1 = "-30 mm"\n'))
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bearing_2.*within 1 mm"):
        chaindrive.load(_design(tmp_path, 'bearing_1 = "30 mm"\nbearing_2 = "30.5 mm"\n'))
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bearing_1"):
        chaindrive.load(_design(tmp_path, 'bearing_1 = "9 m"\nbearing_2 = "30 mm"\n'))
