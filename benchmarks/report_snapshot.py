"""Snapshot of every bundled example's report, to show that a change leaves the report the
same: for each example (``src/chaindrive/examples/*.toml``), the full report and the
``--summary`` sheet as ``chaindrive report FILE -o x.pdf`` builds them (dpi 110, SI), the
Typst source and each figure's PNG, written to ``OUT/<example>[-summary]/``. The one
run-specific text of the source, the build date (``YYYY-MM-DD HH:MM UTC``), is replaced by
``DATE``; the PNGs carry no date or other run-specific bytes (Pillow writes none).

Run: .venv/bin/python benchmarks/report_snapshot.py OUT
     .venv/bin/python benchmarks/report_snapshot.py --compare BEFORE AFTER

``--compare`` lists every file that differs between two snapshots (a figure that differs
with its largest pixel difference and how many pixels differ) and exits 1 if any
does, 0 if every file is byte-identical.
"""

from __future__ import annotations

import argparse
import io
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "src" / "chaindrive" / "examples"
#: The build date in the Typst source (page footer and metadata).
DATE = re.compile(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC")


def snapshot(out: Path) -> None:
    """Write the Typst source and figures of every example's full report and sheet."""
    import chaindrive
    from chaindrive.report import build_report
    from chaindrive.report.pdf import typst_source

    for design in sorted(EXAMPLES.glob("*.toml")):
        analysis = chaindrive.analyze(chaindrive.load(design))
        for summary in (False, True):
            report = build_report(analysis, source=design, summary=summary)
            source, figures = typst_source(report)
            where = out / (design.stem + ("-summary" if summary else ""))
            where.mkdir(parents=True, exist_ok=True)
            (where / "report.typ").write_text(DATE.sub("DATE", source), encoding="utf-8")
            for name, png in figures.items():
                (where / name).write_bytes(png)
            print(f"{where.name}: {len(figures)} figures", flush=True)


def pixel_difference(a: bytes, b: bytes) -> str:
    """The largest difference of a channel [0–255] and how many pixels differ, or the two
    sizes when they differ."""
    import numpy as np
    from PIL import Image

    x = np.asarray(Image.open(io.BytesIO(a)).convert("RGBA"), dtype=np.int16)
    y = np.asarray(Image.open(io.BytesIO(b)).convert("RGBA"), dtype=np.int16)
    if x.shape != y.shape:
        return f"sizes {x.shape[1]}×{x.shape[0]} and {y.shape[1]}×{y.shape[0]}"
    diff = np.abs(x - y)
    changed = int((diff.max(axis=-1) > 0).sum())
    return (f"max pixel difference {int(diff.max())}, {changed} of "
            f"{x.shape[0] * x.shape[1]} pixels differ")


def compare(before: Path, after: Path) -> int:
    """Print the files that differ between two snapshots; 0 when none does, else 1."""
    names = sorted({p.relative_to(before) for p in before.rglob("*") if p.is_file()}
                   | {p.relative_to(after) for p in after.rglob("*") if p.is_file()})
    differ = 0
    for name in names:
        a, b = before / name, after / name
        if not a.exists() or not b.exists():
            print(f"{name}: only in {'after' if not a.exists() else 'before'}")
            differ += 1
        elif a.read_bytes() != b.read_bytes():
            what = (pixel_difference(a.read_bytes(), b.read_bytes())
                    if name.suffix == ".png" else "text differs")
            print(f"{name}: {what}")
            differ += 1
    print(f"{len(names) - differ} of {len(names)} files byte-identical")
    return 1 if differ else 0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", type=Path, help="directory to write the snapshot to")
    parser.add_argument("--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    args = parser.parse_args()
    if args.compare:
        sys.exit(compare(*args.compare))
    if args.out is None:
        parser.error("give OUT or --compare BEFORE AFTER")
    snapshot(args.out)


if __name__ == "__main__":
    main()
