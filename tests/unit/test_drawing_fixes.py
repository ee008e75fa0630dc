"""The workshop drawing read back with ezdxf: its root diameter is the analysis' d_f with the
ISO 606 tolerance, and nothing is written over anything else.

Root diameter. ISO 606 defines the root diameter of a sprocket d_f = d − d1 (d the pitch
diameter, d1 the roller diameter) with the upper deviation 0 and the lower deviation −0.25 mm
up to d_f = 127 mm, −0.30 mm up to 250 mm and h11 above [ISO606]; IT11 from ISO 286-1
[ISO286-1, Table 1]. The values are written out here, not read from the package. The drawing
states that d_f, the one ``chaindrive analyze --json`` gives (``root_diameter_mm``) and the
report's d_f = d − d1; the d − 2 ri of the two tooth-gap forms is the roller seating, not
d_f; and the outline the workshop cuts has its root within that tolerance.

Placement. Boxes as the drawing places them and ezdxf reads them back
(``ezdxf.bbox.extents``): every TEXT of the modelspace and every text of a dimension (the
MTEXT of its block); a title block is the box of a closed polyline on layer FRAME, and the
texts inside it are its cells; a sprocket of the layout is the disc of its tip circle (layer
TIP), a sprocket's drawing its closed outline (layer OUTLINE). No two texts overlap, no
title block overlaps another or a text outside it (a note), no text or title block covers a
sprocket of the layout or crosses an outline, and no title block covers an outline's disc;
the line of a centre-distance dimension passes beside the tip circles, not through them.
"""

from __future__ import annotations

import math
import re
from functools import cache
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from ezdxf import bbox
from ezdxf.document import Drawing

import chaindrive
from chaindrive.analysis import geometry_dict
from chaindrive.drawing import drawing_document, sprocket_document, write_drawing
from chaindrive.geometry.profile import iso606_drawn_seating_radius, iso606_root_diameter_tolerance
from chaindrive.geometry.sprocket import iso606_tooth_form

ROOT = Path(__file__).parents[2]
EXAMPLES = sorted(p.stem for p in (ROOT / "examples").glob("*.toml")
                  if not p.stem.endswith("_optimize"))
MM = 1e3
EPS = 1e-6  # mm: boxes that only touch do not overlap

#: ISO 286-1 IT11 [µm] over 250 mm: (up to [mm], IT11)
IT11 = ((315, 320), (400, 360), (500, 400), (630, 440), (800, 500), (1000, 560), (1250, 660),
        (1600, 780), (2000, 920), (2500, 1100), (3150, 1350))


def _iso606_lower_deviation(df_mm: float) -> tuple[float, str]:
    """ISO 606 lower deviation of the root diameter [mm] and its class ("" or "h11")."""
    if df_mm <= 127:
        return -0.25, ""
    if df_mm <= 250:
        return -0.30, ""
    return -next(t for up_to, t in IT11 if df_mm <= up_to) / 1000, "h11"


@cache
def _analysis(name: str) -> chaindrive.analysis.Analysis:
    return chaindrive.analyze(chaindrive.load(ROOT / "examples" / f"{name}.toml"), response=False)


@cache
def _layout(name: str) -> Drawing:
    """The full drawing (layout and every sprocket) as written and read back."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        return ezdxf.readfile(write_drawing(_analysis(name), Path(tmp) / "layout.dxf"))


# --- what a drawing holds ---------------------------------------------------------------------

def _box(entity: ezdxf.entities.DXFGraphic) -> tuple[float, float, float, float]:
    e = bbox.extents([entity])
    return e.extmin.x, e.extmin.y, e.extmax.x, e.extmax.y


def _texts(doc: Drawing) -> list[tuple[str, tuple[float, float, float, float]]]:
    """(text, box) of every TEXT of the modelspace and every text of a dimension."""
    msp = doc.modelspace()
    out = [(t.plain_text(), _box(t)) for t in msp.query("TEXT")]
    for dim in msp.query("DIMENSION"):
        out += [(m.text, _box(m)) for m in dim.get_geometry_block().query("MTEXT")]
    return out


def _overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(len(a), len(b)) matrix: do the boxes overlap (by more than EPS)?"""
    return ((a[:, None, 0] < b[None, :, 2] - EPS) & (b[None, :, 0] < a[:, None, 2] - EPS)
            & (a[:, None, 1] < b[None, :, 3] - EPS) & (b[None, :, 1] < a[:, None, 3] - EPS))


def _inside(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(len(a), len(b)) matrix: does box a lie within box b?"""
    return ((a[:, None, 0] >= b[None, :, 0] - EPS) & (a[:, None, 2] <= b[None, :, 2] + EPS)
            & (a[:, None, 1] >= b[None, :, 1] - EPS) & (a[:, None, 3] <= b[None, :, 3] + EPS))


def _box_in_disc(box: np.ndarray, c: tuple[float, float], r: float) -> np.ndarray:
    """Do the boxes (N, 4) reach into the disc (c, r)?"""
    dx = np.maximum(np.maximum(box[:, 0] - c[0], 0), c[0] - box[:, 2])
    dy = np.maximum(np.maximum(box[:, 1] - c[1], 0), c[1] - box[:, 3])
    return np.hypot(dx, dy) < r - EPS


def _crossed_by(box: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Do the edges of the closed polygon ``pts`` (K, 2) pass through the boxes (N, 4)?
    (Sampled: every edge at 8 points; the outline's edges are a fraction of a tooth.)"""
    a, b = pts, np.roll(pts, -1, axis=0)
    s = np.linspace(0, 1, 8)
    p = (a[:, None, :] + s[None, :, None] * (b - a)[:, None, :]).reshape(-1, 2)
    hit = ((p[None, :, 0] > box[:, None, 0] + EPS) & (p[None, :, 0] < box[:, None, 2] - EPS)
           & (p[None, :, 1] > box[:, None, 1] + EPS) & (p[None, :, 1] < box[:, None, 3] - EPS))
    return hit.any(axis=1)


def _placement_faults(doc: Drawing) -> list[str]:
    """Everything written over something else (the rules of the module docstring)."""
    msp = doc.modelspace()
    texts = _texts(doc)
    labels = [t for t, _ in texts]
    tb = np.array([b for _, b in texts])
    frames = np.array([_box(p) for p in msp.query("LWPOLYLINE[layer=='FRAME']") if p.closed])
    faults = []
    over = np.triu(_overlap(tb, tb), k=1)
    faults += [f"text {labels[i]!r} over text {labels[j]!r}" for i, j in zip(*np.nonzero(over), strict=True)]
    cell = _inside(tb, frames)
    hit = _overlap(tb, frames) & ~cell
    faults += [f"title block {j} over note {labels[i]!r}" for i, j in zip(*np.nonzero(hit), strict=True)]
    faults += [f"title blocks {i} and {j} overlap"
               for i, j in zip(*np.nonzero(np.triu(_overlap(frames, frames), k=1)), strict=True)]
    for c in msp.query("CIRCLE[layer=='TIP']"):
        centre, r = (c.dxf.center.x, c.dxf.center.y), c.dxf.radius
        faults += [f"text {labels[i]!r} on the sprocket at {centre}"
                   for i in np.nonzero(_box_in_disc(tb, centre, r))[0]]
        faults += [f"title block {i} on the sprocket at {centre}"
                   for i in np.nonzero(_box_in_disc(frames, centre, r))[0]]
    for poly in msp.query("LWPOLYLINE[layer=='OUTLINE']"):
        pts = np.array([p[:2] for p in poly.get_points("xy")])
        faults += [f"text {labels[i]!r} across an outline"
                   for i in np.nonzero(_crossed_by(tb, pts))[0]]
        centre = tuple(pts.mean(axis=0))
        r = float(np.hypot(*(pts - centre).T).max())
        faults += [f"title block {i} on an outline"
                   for i in np.nonzero(_box_in_disc(frames, centre, r))[0]]
    return faults


# --- 1. the root diameter ---------------------------------------------------------------------

def test_iso606_root_diameter_tolerance_table() -> None:
    for df, lower, grade in ((57.558, -0.25, ""), (127.0, -0.25, ""), (127.1, -0.30, ""),
                             (250.0, -0.30, ""), (250.1, -0.32, "h11"), (400.0, -0.36, "h11"),
                             (1000.0, -0.56, "h11")):
        upper, low, cls = iso606_root_diameter_tolerance(df / MM)
        assert upper == 0.0 and low * MM == pytest.approx(lower) and cls == grade, df


@pytest.mark.parametrize(("pitch", "d1", "z"), [(9.525, 6.35, 21), (19.05, 12.07, 17),
                                                (25.4, 15.88, 25), (31.75, 19.05, 45),
                                                (38.1, 25.4, 9)])
def test_drawn_seating_radius_puts_the_root_in_its_tolerance(pitch: float, d1: float,
                                                             z: int) -> None:
    form = iso606_tooth_form(pitch / MM, z, d1 / MM, 10 / MM)
    ri = iso606_drawn_seating_radius(form) * MM
    ri_min, ri_max = 0.505 * d1, 0.505 * d1 + 0.069 * d1 ** (1 / 3)
    assert ri_min - 1e-9 <= ri <= ri_max + 1e-9
    d = pitch / math.sin(math.pi / z)
    df = d - d1
    lower, _ = _iso606_lower_deviation(df)
    if 0.01 * d1 <= -lower:  # both limits can hold: the root lies within the tolerance
        assert df + lower - 1e-9 <= d - 2 * ri <= df + 1e-9
    else:  # they cannot: the root as close as ri,min puts it
        assert ri == pytest.approx(ri_min)


@pytest.mark.parametrize("example", EXAMPLES)
def test_root_diameter_text_is_the_analysis_value(example: str) -> None:
    """Each sprocket's drawing states the d_f of ``analyze --json`` (the report's d − d1),
    with the ISO 606 deviations, on the notes and on the diameter dimension; the roller
    seating d − 2 ri is labelled as such; the outline's root lies within the tolerance."""
    a = _analysis(example)
    expected = [s["root_diameter_mm"] for s in geometry_dict(a.geometry)["sprockets"]]
    doc = _layout(example)
    notes = [t.plain_text() for t in doc.modelspace().query("TEXT")]
    pattern = re.compile(r"^Root diameter (df|Di) = ([0-9.]+) \((d − d1|d − 2 r)\)")
    stated = [m for m in map(pattern.match, notes) if m]
    assert [float(m[2]) for m in stated] == pytest.approx(expected, abs=6e-4)
    dims = [t for t, _ in _texts(doc)]
    for m, df, profile in zip(stated, expected, a.profiles, strict=True):
        if profile.standard == "GOST 591":
            assert m[1] == "Di" and f"%%c{df:.3f}" in dims
            continue
        assert m[1] == "df" and m[3] == "d − d1"
        lower, grade = _iso606_lower_deviation(df)
        tol = f"{grade} (0 / −{-lower:.3f})" if grade else f"0 / −{-lower:.2f}"
        line = next(n for n in notes if n.startswith(m[0]))
        assert f"deviations {tol}: {df + lower:.3f} … {df:.3f}" in line
        assert f"%%c{df:.2f} {tol}" in dims  # the root diameter dimension on the face view
        form = profile.form
        seat = f"Roller seating d − 2 ri = {form.root_diameter_min * MM:.3f} … " \
               f"{form.root_diameter_max * MM:.3f}"
        assert any(n.startswith(seat) for n in notes)
        root = 2 * np.hypot(*np.asarray(profile.outline).T).min() * MM
        assert df + lower - 1e-6 <= root <= df + 1e-6
        assert f"(drawn {root:.3f})" in line


def test_sprocket_alone_states_the_same_root_diameter(tmp_path: Path) -> None:
    """``draw --sprocket M`` of the eight-sprocket example: d_f = 91.604 (analyze: 91.60),
    not the 91.166 … 91.483 of d − 2 ri."""
    a = _analysis("eight_sprocket")
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "m.dxf", sprocket="M"))
    notes = [t.plain_text() for t in doc.modelspace().query("TEXT")]
    line = next(n for n in notes if n.startswith("Root diameter"))
    assert line.startswith("Root diameter df = 91.604 (d − d1), deviations 0 / −0.25: "
                           "91.354 … 91.604")
    assert geometry_dict(a.geometry)["sprockets"][0]["root_diameter_mm"] == pytest.approx(
        91.604, abs=5e-4)
    assert not any("(d − 2 ri)" in n for n in notes)
    assert any(n.startswith("Roller seating d − 2 ri = 91.166 … 91.483") for n in notes)


# --- 2. placement ---------------------------------------------------------------------------------

@pytest.mark.parametrize("example", EXAMPLES)
def test_full_drawing_writes_nothing_over_anything(example: str) -> None:
    doc = _layout(example)
    faults = _placement_faults(doc)
    assert not faults, "\n".join(faults[:20])
    tips = [(c.dxf.center.x, c.dxf.center.y, c.dxf.radius)
            for c in doc.modelspace().query("CIRCLE[layer=='TIP']")]
    for dim in doc.modelspace().query("DIMENSION"):
        if dim.dimtype not in (0, 1) or dim.dxf.layer != "DIM" or not any(
                math.dist((dim.dxf.defpoint2.x, dim.dxf.defpoint2.y), c[:2]) < 1e-6
                for c in tips):  # the centre distances, not the sections' dimensions
            continue
        p1, p2 = np.array(dim.dxf.defpoint2)[:2], np.array(dim.dxf.defpoint3)[:2]
        u = (p2 - p1) / np.linalg.norm(p2 - p1)
        n = np.array([-u[1], u[0]])
        off = float((np.array(dim.dxf.defpoint)[:2] - p1) @ n)
        a, b = p1 + off * n, p2 + off * n  # the dimension line
        for cx, cy, r in tips:
            c = np.array([cx, cy])
            t = np.clip((c - a) @ (b - a) / ((b - a) @ (b - a)), 0, 1)
            assert np.linalg.norm(a + t * (b - a) - c) >= r, (dim.get_measurement(), cx, cy)


@pytest.mark.parametrize(("example", "name"), [("two_sprocket_jindal", "driver"),
                                               ("eight_sprocket", "M"),
                                               ("seed_three_sprocket", "S2")])
def test_sprocket_alone_writes_nothing_over_anything(example: str, name: str) -> None:
    faults = _placement_faults(sprocket_document(_analysis(example), name))
    assert not faults, "\n".join(faults[:20])


def test_the_faults_are_found() -> None:
    """The checks see a text over a text, a title block over a note and a text on a
    sprocket, drawn over the Jindal example's drawing on purpose)."""
    doc = drawing_document(_analysis("two_sprocket_jindal"))
    msp = doc.modelspace()
    note = next(t for t in msp.query("TEXT") if t.plain_text().startswith("Pitch diameter"))
    msp.add_text("Pitch diameter", height=note.dxf.height).set_placement(
        note.dxf.insert, align=note.get_align_enum())
    frame = next(p for p in msp.query("LWPOLYLINE[layer=='FRAME']"))
    frame.translate(note.dxf.insert.x - _box(frame)[0], note.dxf.insert.y - _box(frame)[1], 0)
    tip = next(iter(msp.query("CIRCLE[layer=='TIP']")))
    msp.add_text("on the sprocket", height=1.0).set_placement(tip.dxf.center)
    faults = "\n".join(_placement_faults(doc))
    assert "over text 'Pitch diameter'" in faults or "text 'Pitch diameter' over" in faults
    assert "over note" in faults and "'on the sprocket' on the sprocket" in faults
