"""The page's verdict says what it leaves out: its screen runs without the dynamic response
(as ``analyze --quick``), so k1, k2, k2min and the fatigue check are not among its checks."""

from __future__ import annotations

from streamlit.testing.v1 import AppTest

import chaindrive.app as app_pkg
from chaindrive.app.main import SCREEN_LEAVES_OUT


def test_the_verdict_names_the_checks_the_screen_leaves_out() -> None:
    at = AppTest.from_file(str(app_pkg.PAGE), default_timeout=60).run()
    assert not at.exception
    assert SCREEN_LEAVES_OUT in [c.value for c in at.caption]
    for name in ("k1", "k2min", "fatigue"):
        assert name in SCREEN_LEAVES_OUT
