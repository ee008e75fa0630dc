"""The sprocket's workshop drawing read back with ezdxf: on a standard sheet with its title
block, the front view (outline, bore, keyway), the axial section (face width, chamfer, hub,
hatched), and the notes with the values a workshop needs; the layout on a standard sheet.

Expected values are recomputed here from the standards, not read from the package:

* ISO 5457 sheets A4 210 × 297 mm, A3 420 × 297 mm; ISO 5455 scales 1:1, 1:2, 1:5, 1:10 …;
  ISO 7200 title block 180 mm wide [ISO5457], [ISO5455], [ISO7200].
* ISO 286-1 Table 1: IT7 = 25 µm over 30 up to 50 mm (32 H7: +0.025 / 0); IT9 = 36 µm over 6
  up to 10 mm (keyway 10 JS9: ±0.018); IT11 = 190 µm over 50 up to 80 mm [ISO286-1].
* DIN 6885-1: a 32 mm bore takes the key 10 × 8, hub depth t2 = 3.3 mm (+0.2), d + t2 = 35.3
  [DIN6885-1].
* ISO 606: d = p/sin(180°/z); measurement over pins of roller diameter: d·cos(90°/z) + d1 for
  odd z, d + d1 for even z; tip range d + p(1 − 1.6/z) − d1 … d + 1.25 p − d1; side relief
  ba = 0.10 … 0.15 p, side radius rx = p [ISO606]. GOST 591: side radius r3 = 1.7 d1 about
  centres h3 = 0.8 d1 below the tip, taking r3 − √(r3² − h3²) = 0.2 d1 off at the tip
  [GOST591].
"""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest

import chaindrive
from chaindrive.drawing import layout_document, write_drawing
from chaindrive.errors import DesignError

ROOT = Path(__file__).parents[2]
EXAMPLES = ROOT / "src" / "chaindrive" / "examples"
MM = 1e3
SHEETS = {(210.0, 297.0): "A4", (420.0, 297.0): "A3", (594.0, 420.0): "A2",
          (841.0, 594.0): "A1", (1189.0, 841.0): "A0"}
SCALES = (1, 2, 5, 10, 20, 50, 100, 200)


def _analysis(example: str, index: int = 0, **fields: object) -> chaindrive.analysis.Analysis:
    drive = chaindrive.load(EXAMPLES / f"{example}.toml")
    s = list(drive.sprockets)
    s[index] = dataclasses.replace(s[index], **fields)
    return chaindrive.analyze(drive.with_sprockets(tuple(s)), response=False)


def _box(entity: ezdxf.entities.DXFGraphic) -> tuple[float, float, float, float]:
    pts = np.array([p[:2] for p in entity.get_points("xy")])
    return pts[:, 0].min(), pts[:, 1].min(), pts[:, 0].max(), pts[:, 1].max()


def _sheet(msp: ezdxf.layouts.Modelspace) -> tuple[str, int, tuple[float, float, float, float]]:
    """The sheet (its name by its size on paper), 1:N and the box of its trimmed edge."""
    edges = sorted((_box(p) for p in msp.query("LWPOLYLINE[layer=='SHEET']")),
                   key=lambda b: -(b[2] - b[0]))
    assert len(edges) == 2  # the trimmed edge and the frame
    x0, y0, x1, y1 = edges[0]
    texts = [t.plain_text() for t in msp.query("TEXT")]
    n = next(int(t[2:]) for t in texts if t.startswith("1:"))
    assert n in SCALES
    size = (round((x1 - x0) / n, 6), round((y1 - y0) / n, 6))
    assert size in SHEETS, size
    fx0, fy0, fx1, fy1 = edges[1]  # ISO 5457: 20 mm filing margin, 10 mm elsewhere
    assert (fx0 - x0) / n == pytest.approx(20.0) and (x1 - fx1) / n == pytest.approx(10.0)
    assert (fy0 - y0) / n == pytest.approx(10.0) and (y1 - fy1) / n == pytest.approx(10.0)
    return SHEETS[size], n, edges[0]


def _inside(msp: ezdxf.layouts.Modelspace, box: tuple[float, float, float, float]) -> None:
    """Every entity but the sheet's own lies within the sheet."""
    from ezdxf import bbox

    ext = bbox.extents(e for e in msp if e.dxf.layer != "SHEET")
    assert ext.extmin.x >= box[0] and ext.extmax.x <= box[2]
    assert ext.extmin.y >= box[1] and ext.extmax.y <= box[3]


def test_iso606_sprocket_drawing_reads_back(tmp_path: Path) -> None:
    """Jindal's driver (06B, z = 21, odd) with a 32 mm H7 bore and a keyway."""
    a = _analysis("two_sprocket_jindal", bore=0.032, hardening="teeth induction hardened "
                  "45…50 HRC")
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "driver.dxf", sprocket="driver"))
    msp = doc.modelspace()
    sheet, n, edge = _sheet(msp)
    assert sheet in ("A4", "A3")
    _inside(msp, edge)
    texts = [t.plain_text() for t in msp.query("TEXT")]
    joined = "\n".join(texts)
    # ISO 7200 title block: one closed frame 180 mm wide on paper, its fields and values
    (block,) = [p for p in msp.query("LWPOLYLINE[layer=='FRAME']") if p.closed]
    b = _box(block)
    assert (b[2] - b[0]) / n == pytest.approx(180.0)
    for label in ("Title", "Drawing number", "Material", "Scale", "Sheet size",
                  "Date of issue", "Created by", "Checked by", "Approved by", "Legal owner"):
        assert label in texts, label
    assert sheet in texts and "Sprocket driver, z = 21" in texts
    assert "JINDAL-EXAMPLE-30-3-01" in texts
    assert "steel; teeth induction hardened 45…50 HRC" in texts
    # front view: the outline, the bore and the keyway (DIN 6885-1: 10 wide, d + t2 = 35.3)
    assert len(msp.query("LWPOLYLINE[layer=='OUTLINE']")) == 1
    (bore,) = msp.query("CIRCLE[layer=='BORE']")
    assert bore.dxf.radius == pytest.approx(16.0)
    (key,) = msp.query("LWPOLYLINE[layer=='KEYWAY']")
    kx0, _, kx1, ky1 = _box(key)
    assert kx1 - kx0 == pytest.approx(10.0) and ky1 + 16.0 == pytest.approx(35.3)
    assert "Bore Ø32.0 H7 (+0.025 / 0), given by the design" in joined
    assert "width 10 JS9 (±0.018), depth t2 = 3.3, d + t2 = 35.3 (+0.2 / 0)" in joined
    # axial section: two hatched halves, the tooth's tip narrowed by the chamfer
    p, z, d1 = 9.525, 21, 6.35
    sections = msp.query("LWPOLYLINE[layer=='SECTION']")
    assert len(sections) == 2 and all(s.closed for s in sections)
    assert len(msp.query("HATCH[layer=='HATCH']")) == 2
    upper = max(sections, key=lambda s: _box(s)[3])
    pts = np.array([q[:2] for q in upper.get_points("xy")])
    tip = pts[np.isclose(pts[:, 1], pts[:, 1].max(), atol=1e-9)]
    form = a.profiles[0].form
    bf1 = form.tooth_width * MM
    ba = 0.125 * p
    assert 0.10 * p <= ba <= 0.15 * p
    assert np.ptp(tip[:, 0]) == pytest.approx(bf1 - 2 * ba, abs=1e-6)
    assert f"face width bf1 = {bf1:.2f}, tooth chamfer ba = {ba:.2f}" in joined
    assert f"rx = {p:.2f} (= p)" in joined
    # measurement over pins (odd z) and the tip diameter chosen inside the ISO 606 range
    d = p / math.sin(math.pi / z)
    mr = d * math.cos(math.pi / (2 * z)) + d1
    assert f"Measurement over pins MR = {mr:.3f} (0 / −0.25, as the root diameter)" in joined
    lo, hi = d + p * (1 - 1.6 / z) - d1, d + 1.25 * p - d1
    da = math.floor((lo + hi) / 2 * 10) / 10
    assert lo <= da - 0.190 and da <= hi  # h11 over 50 up to 80 mm: IT11 = 190 µm
    assert f"Tip diameter da = {da:.1f} h11 (0 / −0.190)" in joined
    dims = [m.text for dim in msp.query("DIMENSION")
            for m in dim.get_geometry_block().query("MTEXT")]
    assert f"%%c{da:.1f} h11" in dims and "%%c32 H7" in dims
    assert "35.3 +0.2/0" in dims  # d + t2 in the section
    assert f"{bf1:.2f}" in dims  # the tooth width in the section
    assert "General tolerances ISO 2768-m" in texts
    # the SVG's and the PDF's page is the sheet, so the drawing prints at its scale
    svg = write_drawing(a, tmp_path / "driver.svg", sprocket="driver").read_text()
    w, h = {"A4": (210, 297), "A3": (420, 297)}[sheet]
    assert f'width="{w}mm"' in svg and f'height="{h}mm"' in svg
    pdf = write_drawing(a, tmp_path / "driver.pdf", sprocket="driver").read_bytes()
    box = re.search(rb"/MediaBox \[ *0 0 ([0-9.]+) ([0-9.]+) *\]", pdf)
    assert pdf.startswith(b"%PDF") and box is not None
    assert (float(box[1]), float(box[2])) == pytest.approx((w / 25.4 * 72, h / 25.4 * 72))


def test_no_keyway_and_even_teeth(tmp_path: Path) -> None:
    """Jindal's driven sprocket (z = 42, even) without a keyway: no KEYWAY entity, the note
    says so; M_R = d + d1."""
    a = _analysis("two_sprocket_jindal", index=1, bore=0.040, keyway=False, bore_fit="H8")
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "driven.dxf", sprocket="driven"))
    msp = doc.modelspace()
    joined = "\n".join(t.plain_text() for t in msp.query("TEXT"))
    assert not msp.query("*[layer=='KEYWAY']")
    assert "No keyway (keyway = false in the design)" in joined
    assert "Bore Ø40.0 H8 (+0.039 / 0)" in joined  # IT8 over 30 up to 50 mm: 39 µm
    p, z, d1 = 9.525, 42, 6.35
    mr = p / math.sin(math.pi / z) + d1
    assert f"MR = {mr:.3f}" in joined and "even z: d + dR" in joined
    assert "hardening: not given by the design" in joined


def test_gost591_chamfer(tmp_path: Path) -> None:
    """The seed's S1 (GOST 591, ПР-25,4-60, d1 = 15.88): f = 0.2·d1 taken off at the tip."""
    a = _analysis("seed_three_sprocket", material="steel")
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "s1.dxf", sprocket="S1"))
    msp = doc.modelspace()
    joined = "\n".join(t.plain_text() for t in msp.query("TEXT"))
    d1 = a.drive.chain.spec.roller_diameter * MM
    assert f"r3 = {1.7 * d1:.2f} (1.7 d1)" in joined and f"f = {0.2 * d1:.2f}" in joined
    upper = max(msp.query("LWPOLYLINE[layer=='SECTION']"), key=lambda s: _box(s)[3])
    pts = np.array([q[:2] for q in upper.get_points("xy")])
    tip = pts[np.isclose(pts[:, 1], pts[:, 1].max(), atol=1e-9)]
    b = a.profiles[0].form.rim_width * MM
    assert np.ptp(tip[:, 0]) == pytest.approx(b - 2 * 0.2 * d1, abs=1e-6)
    _inside(msp, _sheet(msp)[2])


@pytest.mark.parametrize("example", ["two_sprocket_jindal", "eight_sprocket",
                                     "twenty_four_sprocket"])
def test_layout_on_a_standard_sheet(example: str) -> None:
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / f"{example}.toml"), response=False)
    msp = layout_document(a).modelspace()
    sheet, n, edge = _sheet(msp)
    assert sheet in ("A4", "A3") and n > 1  # these drives are longer than an A3 sheet
    _inside(msp, edge)
    texts = [t.plain_text() for t in msp.query("TEXT")]
    assert "Layout" in texts and f"1:{n}" in texts and sheet in texts


def test_design_fields_are_checked(tmp_path: Path) -> None:
    text = (EXAMPLES / "two_sprocket_jindal.toml").read_text()
    head, tail = text.split('speed = "1000 rpm"\n', 1)

    def load(extra: str) -> chaindrive.model.Drive:
        path = tmp_path / "d.toml"
        path.write_text(head + 'speed = "1000 rpm"\n' + extra + tail)
        return chaindrive.load(path)

    drive = load('bore = "32 mm"\nbore_fit = "H6"\nkeyway = false\nhardening = "none"\n')
    s = drive.sprockets[0]
    assert (s.bore, s.bore_fit, s.keyway, s.hardening) == (pytest.approx(0.032), "H6", False,
                                                           "none")
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bore_fit.*H6, H7, H8|H6.*H7.*H8"):
        load('bore_fit = "H9"\n')
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bore"):
        load('bore = "300 mm"\n')  # beyond the key table with a keyway
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bore"):
        load('bore = "5 mm"\n')
    assert load('bore = "300 mm"\nkeyway = false\n').sprockets[0].bore == pytest.approx(0.3)


def test_a_bore_too_large_for_the_hub_is_refused(tmp_path: Path) -> None:
    a = _analysis("two_sprocket_jindal", bore=0.060)  # d_g of z = 21, 06B is about 54 mm
    with pytest.raises(DesignError, match=r"sprockets\[0\]\.bore.*no hub wall"):
        write_drawing(a, tmp_path / "x.dxf", sprocket="driver")
    assert not (tmp_path / "x.dxf").exists()


@pytest.mark.parametrize("example", sorted(p.stem for p in EXAMPLES.glob("*.toml")))
def test_every_example_sprocket_drawing_has_every_item(example: str, tmp_path: Path) -> None:
    """Each bundled example's first sprocket, read back from its DXF: a standard sheet with
    the ISO 7200 title block, the front view (outline, bore, keyway or the note that there is
    none), the axial section (two hatched halves), the bore fit, the measurement over pins,
    the tip diameter inside its range, the material note and ISO 2768's general tolerances."""
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / f"{example}.toml"), response=False)
    first = a.drive.sprockets[0]
    doc = ezdxf.readfile(write_drawing(a, tmp_path / "s.dxf", sprocket=first.name))
    msp = doc.modelspace()
    sheet, _, edge = _sheet(msp)
    assert sheet in SHEETS.values()
    _inside(msp, edge)
    texts = [t.plain_text() for t in msp.query("TEXT")]
    joined = "\n".join(texts)
    for label in ("Title", "Drawing number", "Material", "Scale", "Sheet size",
                  "Date of issue", "Created by", "Checked by", "Approved by", "Legal owner"):
        assert label in texts, label
    assert len(msp.query("LWPOLYLINE[layer=='OUTLINE']")) == 1
    assert len(msp.query("CIRCLE[layer=='BORE']")) == 1
    assert (len(msp.query("LWPOLYLINE[layer=='KEYWAY']")) == 1
            or "no keyway" in joined.lower())
    sections = msp.query("LWPOLYLINE[layer=='SECTION']")
    assert len(sections) == 2 and all(s.closed for s in sections)
    assert len(msp.query("HATCH[layer=='HATCH']")) == 2
    assert "Bore Ø" in joined and "face width bf1 = " in joined
    assert "Measurement over pins MR = " in joined and "Tip diameter da = " in joined
    assert "General tolerances ISO 2768-m" in texts
    assert any(t.startswith("Sprocket ") and f"z = {first.teeth}" in t for t in texts)
