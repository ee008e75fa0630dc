"""k1 of a design whose start-up is switched off ([dynamics] transient = false) is said to be
not computed beside its dash, never left as a bare "—"."""

from __future__ import annotations

import io
from contextlib import redirect_stderr, redirect_stdout

from chaindrive.cli import run
from tests.conftest import EXAMPLES


def test_analyze_says_why_k1_has_no_value() -> None:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        status = run(["analyze", str(EXAMPLES / "eight_sprocket_optimize.toml")])
    assert status == 0
    line = next(ln for ln in out.getvalue().splitlines() if ln.startswith("dynamic safety"))
    assert "k1 — (not computed: no start-up, [dynamics] transient = false)" in line
