"""Drawings for the workshop read back with ezdxf: the layout with its centre distances and
wrap angles dimensioned and a title block; a sprocket drawn alone with its toothed outline as
ONE closed, simple polyline whose every point lies within the tooth form of its standard.

The tooth forms are recomputed here from the formulas of the standards, not read from the
package: ISO 606 — the tooth gap between the minimum form (ri,min = 0.505 d1, re,max =
0.008 d1 (z² + 180), α,max = 140° − 90°/z) and the maximum form (ri,max = 0.505 d1 +
0.069 d1^(1/3), re,min = 0.12 d1 (z + 2), α,min = 120° − 90°/z), tip diameter between
d + p(1 − 1.6/z) − d1 and d + 1.25 p − d1 [ISO606]; GOST 591-69 — seating arc r = 0.5025 d1
+ 0.05 mm, joining arc r1 = 0.8 d1 + r about O1 = 0.8 d1 (sin α, cos α), straight part FC,
head arc r2 about O2 = 1.24 d1 (cos 180°/z, sin 180°/z), tip De = p (K + cot 180°/z)
[GOST591] (shared/data/gost591_sprocket_profile.md §1.3 and §2).
"""

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
from chaindrive.geometry.profile import hub_limit_diameter

ROOT = Path(__file__).parents[2]
EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*.toml") if not p.stem.endswith("_optimize"))
MM = 1e3


def _analysis(name: str, tooth_form: str | None = None) -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(ROOT / "examples" / f"{name}.toml")
    if tooth_form is not None:
        drive = dataclasses.replace(drive, tooth_form=tooth_form)
    return chaindrive.analyze(drive, response=False)


@pytest.mark.parametrize("example", EXAMPLES[:2] + EXAMPLES[3:], ids=lambda p: p.stem)
def test_layout_reads_back(example: Path, tmp_path: Path) -> None:
    """Chain spans, one outline per sprocket, pitch circles at the centres with the pitch
    diameters, a centre distance per pair of neighbours, a wrap angle per wrapped sprocket,
    a title block with the drive, chain and links."""
    a = chaindrive.analyze(chaindrive.load(example), response=False)
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "layout.dxf"))
    msp = doc.modelspace()
    n = len(a.geometry.sprockets)
    kinds = Counter((e.dxftype(), e.dxf.layer) for e in msp)
    assert kinds[("LINE", "CHAIN")] == len(a.geometry.spans)
    assert kinds[("LWPOLYLINE", "OUTLINE")] == n
    dims = [d for d in msp.query("DIMENSION")]
    centres = [(s.x * MM, s.y * MM) for s in a.geometry.sprockets]

    def at_centres(d: ezdxf.entities.Dimension) -> bool:
        return all(min(math.dist((p.x, p.y), c) for c in centres) < 1e-6
                   for p in (d.dxf.defpoint2, d.dxf.defpoint3))

    # linear or aligned between centres (the sprocket sections' linear dimensions are not)
    aligned = [d for d in dims if d.dimtype in (0, 1) and at_centres(d)]
    assert len(aligned) == (n if n > 2 else 1)
    for d in aligned:  # each measures the distance between two neighbouring centres
        p1, p2 = (d.dxf.defpoint2.x, d.dxf.defpoint2.y), (d.dxf.defpoint3.x, d.dxf.defpoint3.y)
        assert min(math.dist(p1, c) for c in centres) < 1e-6
        assert min(math.dist(p2, c) for c in centres) < 1e-6
        assert d.get_measurement() == pytest.approx(math.dist(p1, p2), rel=1e-9)
    wrapped = sum(1 for s in a.geometry.sprockets if s.wrap_angle >= math.radians(1))
    assert sum(1 for d in dims if d.dimtype in (2, 5)) >= wrapped
    for s in a.geometry.sprockets:
        hits = [c for c in msp.query("CIRCLE[layer=='PITCH']")
                if math.isclose(c.dxf.center.x, s.x * MM, abs_tol=1e-6)
                and math.isclose(c.dxf.center.y, s.y * MM, abs_tol=1e-6)]
        assert len(hits) == 1
        np.testing.assert_allclose(2 * hits[0].dxf.radius, s.pitch_diameter * MM, rtol=1e-12)
    texts = " ".join(t.plain_text() for t in msp.query("TEXT"))
    assert a.drive.name in texts and a.drive.chain.spec.designation in texts
    assert f"{a.geometry.links} (length" in texts and "chaindrive" in texts
    assert "_mm" not in texts and "_deg" not in texts  # labels, not keys
    assert doc.header["$INSUNITS"] == 4  # millimetres


def _segments_cross(pts: np.ndarray) -> bool:
    """True when two non-adjacent edges of the closed polygon ``pts`` intersect."""
    a, b = pts, np.roll(pts, -1, axis=0)
    n = len(pts)

    def orient(p, q, r):  # type: ignore[no-untyped-def]
        return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                       - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))

    for i in range(n):
        j = np.arange(i + 2, n if i else n - 1)
        if j.size == 0:
            continue
        o1 = orient(a[i], b[i], a[j])
        o2 = orient(a[i], b[i], b[j])
        o3 = orient(a[j], b[j], a[i][None, :])
        o4 = orient(a[j], b[j], b[i][None, :])
        if np.any((o1 * o2 < 0) & (o3 * o4 < 0)):
            return True
    return False


def _outline(path: Path) -> np.ndarray:
    """The one closed polyline of layer OUTLINE, as (k, 2) [mm]."""
    doc = ezdxf.readfile(path)
    lines = doc.modelspace().query("LWPOLYLINE[layer=='OUTLINE']")
    assert len(lines) == 1
    poly = lines[0]
    assert poly.closed
    assert all(b == 0 for *_, b in poly.get_points("xyseb"))  # straight edges only
    return np.array([p[:2] for p in poly.get_points("xy")])


@pytest.mark.parametrize(("example", "form"), [("seed_three_sprocket", "GOST 591"),
                                               ("two_sprocket_jindal", "ISO 606"),
                                               ("seed_three_sprocket", "ISO 606")])
def test_sprocket_alone_is_one_closed_simple_outline(example: str, form: str,
                                                     tmp_path: Path) -> None:
    a = _analysis(example, form)
    s = a.drive.sprockets[0]
    path = write_drawing(a, tmp_path / "s.dxf", sprocket=s.name)
    pts = _outline(path)
    steps = np.hypot(*np.diff(pts, axis=0, append=pts[:1]).T)
    assert steps.min() > 1e-3  # no repeated point, closed by the flag only
    assert not _segments_cross(pts)
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    assert area > 0.5 * math.pi * (a.geometry.sprockets[0].root_diameter * MM / 2) ** 2
    bores = ezdxf.readfile(path).modelspace().query("CIRCLE[layer=='BORE']")
    assert len(bores) == 1 and bores[0].dxf.radius < np.hypot(*pts.T).min()
    svg = write_drawing(a, tmp_path / "s.svg", sprocket=s.name).read_text()
    assert svg.count("<path") >= 2


def _seat_frame(pts: np.ndarray, z: int, radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ρ, φ, r) of every point: distance and angle (from the line to the sprocket centre)
    about the seat centre of its tooth gap, and its distance from the sprocket centre."""
    theta = np.arctan2(pts[:, 1], pts[:, 0])
    k = np.round(theta / (2 * math.pi / z))
    th = k * 2 * math.pi / z
    ur = np.column_stack([np.cos(th), np.sin(th)])
    ut = np.column_stack([-np.sin(th), np.cos(th)])
    rel = pts - radius * ur
    xt, yr = np.sum(rel * ut, axis=1), np.sum(rel * ur, axis=1)
    return np.hypot(xt, yr), np.arctan2(np.abs(xt), -yr), np.hypot(*pts.T)


def _iso_gap(phi: np.ndarray, ri: float, re: float, alpha: float, inf: float) -> np.ndarray:
    """Distance from the seat centre of an ISO 606 tooth-gap form along the angle φ: the
    seating arc ri up to α/2, then the convex flank re tangent to it; ``inf`` where the ray
    no longer meets the flank."""
    delta = phi - alpha / 2
    c = ri + re
    disc = re**2 - (c * np.sin(delta)) ** 2
    flank = np.where(disc >= 0, c * np.cos(delta) - np.sqrt(np.maximum(disc, 0)), inf)
    return np.where(delta <= 0, ri, flank)


def test_iso606_outline_between_the_minimum_and_maximum_forms(tmp_path: Path) -> None:
    a = _analysis("two_sprocket_jindal")
    spec = a.drive.chain.spec
    for s in a.drive.sprockets:
        z, p, d1 = s.teeth, spec.pitch * MM, spec.roller_diameter * MM
        d = p / math.sin(math.pi / z)
        pts = _outline(write_drawing(a, tmp_path / f"{s.name}.dxf", sprocket=s.name))
        rho, phi, r = _seat_frame(pts, z, d / 2)
        ri_min, ri_max = 0.505 * d1, 0.505 * d1 + 0.069 * d1 ** (1 / 3)
        re_min, re_max = 0.12 * d1 * (z + 2), 0.008 * d1 * (z**2 + 180)
        a_min, a_max = math.radians(120 - 90 / z), math.radians(140 - 90 / z)
        da_min, da_max = d + p * (1 - 1.6 / z) - d1, d + 1.25 * p - d1
        tol = 2e-3  # mm: chords of the sampled arcs
        assert np.all(r <= da_max / 2 + tol) and np.all(r >= d / 2 - ri_max - tol)
        assert r.max() >= da_min / 2 - tol  # the teeth reach the tip circle's band
        wall = r < da_min / 2 - tol  # below the tip band: the tooth gap itself
        assert wall.sum() > 20 * z  # every gap, seat and flank
        low = _iso_gap(phi[wall], ri_min, re_max, a_max, -np.inf)
        high = _iso_gap(phi[wall], ri_max, re_min, a_min, np.inf)
        assert np.all(rho[wall] >= low - tol), float(np.min(rho[wall] - low))
        assert np.all(rho[wall] <= high + tol), float(np.max(rho[wall] - high))


def test_gost591_outline_on_the_elements_of_the_standard(tmp_path: Path) -> None:
    a = _analysis("seed_three_sprocket")
    spec = a.drive.chain.spec
    p, d1 = spec.pitch * MM, spec.roller_diameter * MM
    lam = p / d1
    K = next(k for bound, k in ((1.5, 0.48), (1.6, 0.532), (1.7, 0.555), (1.8, 0.575),
                                (2.0, 0.565)) if lam <= bound)
    for s in a.drive.sprockets:
        z = s.teeth
        d = p / math.sin(math.pi / z)
        De = p * (K + 1 / math.tan(math.pi / z))
        r = 0.5025 * d1 + 0.05
        r1 = 0.8 * d1 + r
        al, be, ph = (math.radians(x) for x in (55 - 60 / z, 18 - 56 / z, 17 - 64 / z))
        r2 = d1 * (1.24 * math.cos(ph) + 0.8 * math.cos(be) - 1.3025) - 0.05
        fc = d1 * (1.24 * math.sin(ph) - 0.8 * math.sin(be))
        o1 = 0.8 * d1 * np.array([math.sin(al), math.cos(al)])
        f = o1 + r1 * np.array([-math.sin(al + be), -math.cos(al + be)])
        c = f + fc * np.array([-math.cos(al + be), math.sin(al + be)])
        o2 = 1.24 * d1 * np.array([-math.cos(math.pi / z), -math.sin(math.pi / z)])
        pts = _outline(write_drawing(a, tmp_path / f"{s.name}.dxf", sprocket=s.name))
        theta = np.arctan2(pts[:, 1], pts[:, 0])
        th = np.round(theta / (2 * math.pi / z)) * 2 * math.pi / z
        ur = np.column_stack([np.cos(th), np.sin(th)])
        ut = np.column_stack([-np.sin(th), np.cos(th)])
        rel = pts - d / 2 * ur
        q = np.column_stack([-np.abs(np.sum(rel * ut, axis=1)), np.sum(rel * ur, axis=1)])
        t = np.clip((q - f) @ (c - f) / np.dot(c - f, c - f), 0, 1)
        off = np.stack([np.abs(np.hypot(*q.T) - r), np.abs(np.hypot(*(q - o1).T) - r1),
                        np.hypot(*(q - (f + t[:, None] * (c - f))).T),
                        np.abs(np.hypot(*(q - o2).T) - r2),
                        np.abs(np.hypot(*pts.T) - De / 2)])
        assert np.all(off.min(axis=0) < 5e-3), float(off.min(axis=0).max())  # mm
        assert np.hypot(*pts.T).max() == pytest.approx(De / 2, abs=1e-6)


def test_sprocket_drawing_labels_and_limits(tmp_path: Path) -> None:
    """Labels read as a drawing (names and symbols, not keys) and the tip and root
    diameters carry the limits of ISO 606, the root one inside its own limits."""
    a = _analysis("two_sprocket_jindal")
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "d.dxf", sprocket="driver"))
    texts = [t.plain_text() for t in doc.modelspace().query("TEXT")]
    joined = " ".join(texts)
    form = a.profiles[0].form
    assert "Root diameter df = " in joined and "_mm" not in joined
    assert f"{form.root_diameter_min * MM:.3f} … {form.root_diameter_max * MM:.3f}" in joined
    assert "driver" in joined and "chaindrive" in joined
    spec = a.drive.chain.spec
    dg = hub_limit_diameter(spec.pitch, form.teeth, spec.plate_depth)
    assert f"{dg * MM:.1f}" in joined
    with pytest.raises(DesignError, match="no sprocket named 'S9'"):
        write_drawing(a, tmp_path / "x.dxf", sprocket="S9")


def test_polymeric_body_and_svg(tmp_path: Path) -> None:
    d = chaindrive.load(ROOT / "examples" / "two_sprocket_jindal.toml")
    d = d.with_sprockets((d.sprockets[0], dataclasses.replace(d.sprockets[1], material="PA6")))
    a = chaindrive.analyze(d, response=False)
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "p.dxf"))
    body = doc.modelspace().query("*[layer=='BODY']")
    assert len(body.query("CIRCLE")) == 8  # face view: hub, rim and six lightening holes
    # its section: two closed hatched halves whose widths are the body's hub, web and rim
    p = a.profiles[1].body
    assert p is not None
    one = ezdxf.readfile(write_drawing(a, tmp_path / "d.dxf", sprocket="driven")).modelspace()
    halves = one.query("LWPOLYLINE[layer=='SECTION']")
    assert len(halves) == 2 and all(s.closed for s in halves)
    assert len(one.query("HATCH[layer=='HATCH']")) == 2
    xs = [x for x, *_ in halves[0].get_points()]
    mid = (max(xs) + min(xs)) / 2
    widths = [2 * abs(x - mid) for x in xs]
    for width in (p.hub_length, p.web_thickness, p.rim_width):
        assert min(abs(v - width * MM) for v in widths) < 1e-6, width
    texts = " ".join(t.plain_text() for t in doc.modelspace().query("TEXT"))
    assert "mass = " in texts and "inertia = " in texts
    svg = write_drawing(a, tmp_path / "p.svg").read_text()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg
    with pytest.raises(DesignError):
        write_drawing(a, tmp_path / "p.png")
