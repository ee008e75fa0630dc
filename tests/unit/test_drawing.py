"""DXF/SVG drawings read back with the right entities and diameters (issue 6)."""

from __future__ import annotations

import dataclasses
import math
from collections import Counter
from pathlib import Path

import ezdxf
import numpy as np
import pytest

import chaindrive
from chaindrive.drawing import write_drawing
from chaindrive.errors import DesignError
from chaindrive.geometry.profile import outline_of, tooth_form_of

ROOT = Path(__file__).parents[2]
EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*.toml") if not p.stem.endswith("_optimize"))


@pytest.mark.parametrize("example", EXAMPLES[:2] + EXAMPLES[3:], ids=lambda p: p.stem)
def test_dxf_reads_back(example: Path, tmp_path: Path) -> None:
    a = chaindrive.analyze(chaindrive.load(example))
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "layout.dxf"))
    msp = doc.modelspace()
    n = len(a.geometry.sprockets)
    kinds = Counter((e.dxftype(), e.dxf.layer) for e in msp)
    assert kinds[("LINE", "CHAIN")] == len(a.geometry.spans)
    assert kinds[("LWPOLYLINE", "PROFILE")] == n
    assert kinds[("DIMENSION", "DIM")] == 3 * n
    # the layout's pitch circles: at the sprocket centres, with the pitch diameters [mm]
    for s in a.geometry.sprockets:
        hits = [c for c in msp.query("CIRCLE[layer=='PITCH']")
                if math.isclose(c.dxf.center.x, s.x * 1e3, abs_tol=1e-6)
                and math.isclose(c.dxf.center.y, s.y * 1e3, abs_tol=1e-6)]
        assert len(hits) == 1
        np.testing.assert_allclose(2 * hits[0].dxf.radius, s.pitch_diameter * 1e3, rtol=1e-12)
    assert doc.header["$INSUNITS"] == 4  # millimetres


def test_outline_lies_between_root_and_tip() -> None:
    a = chaindrive.analyze(chaindrive.load(ROOT / "examples" / "seed_three_sprocket.toml"))
    for s in a.geometry.sprockets:
        form = tooth_form_of(a.drive, s.teeth)
        r = np.hypot(*outline_of(form).T)
        np.testing.assert_allclose(r.max(), form.tip_diameter / 2, rtol=1e-6)
        np.testing.assert_allclose(r.min(), form.root_diameter / 2, rtol=1e-6)
        # z teeth: the radius has z maxima round the outline
        peaks = np.sum((r > np.roll(r, 1)) & (r >= np.roll(r, -1)) & (r > 0.99 * r.max()))
        assert peaks >= s.teeth


def test_polymeric_body_and_svg(tmp_path: Path) -> None:
    d = chaindrive.load(ROOT / "examples" / "two_sprocket_jindal.toml")
    d = d.with_sprockets((d.sprockets[0], dataclasses.replace(d.sprockets[1], material="PA6")))
    a = chaindrive.analyze(d)
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "p.dxf"))
    body = doc.modelspace().query("*[layer=='BODY']")
    assert len(body.query("LWPOLYLINE")) == 2 and len(body.query("CIRCLE")) == 9
    texts = " ".join(t.dxf.text for t in doc.modelspace().query("TEXT"))
    assert "mass = " in texts and "inertia = " in texts
    svg = write_drawing(a, tmp_path / "p.svg").read_text()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg
    with pytest.raises(DesignError):
        write_drawing(a, tmp_path / "p.png")
