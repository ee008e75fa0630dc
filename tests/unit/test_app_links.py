"""The page's tab "Link-level model" without a browser: the run it starts on request
(chaindrive.app.runs.bounded_link_level, a child process with the page's limits) brings back
the analysis' comparison with the whole-drive model and the two figures; a mistake comes
back as its one-line error.

Expected values: the rows are those of the same study run in this process (the analysis of
the seed example, [MultimassChainDrives] worked example): a bounded run computes nothing
differently; the figures are PNG files (their 8-byte signature, ISO/IEC 15948).
"""

from __future__ import annotations

import pytest

import chaindrive
from chaindrive.app.runs import bounded_link_level
from chaindrive.app.tabs import _comparison_records
from chaindrive.errors import DesignError
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # child processes

PNG = b"\x89PNG\r\n\x1a\n"
DURATION = 0.02


@pytest.fixture(scope="module")
def seed():
    return chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")


def test_the_bounded_run_brings_back_the_comparison_and_figures(seed) -> None:
    # this process's run first: it compiles the link-level kernel into numba's cache at full
    # priority when the cache is cold, so that the page's run (a child at niceness 10, with
    # the page's 60 s limit) loads it; compiling there on a loaded machine (8 s of CPU at a
    # tenth of a core) ran past the limit
    here = chaindrive.analyze(seed, studies=("links",), lazy=True, link_duration_s=DURATION)
    expected = here.link_level_comparison.to_dict()
    view = bounded_link_level(seed, DURATION)
    # the same numbers, to the round-off of the static state's linear solves and of the
    # link-level eigen solve of f1 (≈1e-9 relative between the worker's one BLAS thread and
    # this process's threads)
    assert len(view.comparison["rows"]) == len(expected["rows"])
    for got, want in zip(view.comparison["rows"], expected["rows"], strict=True):
        assert {k: v for k, v in got.items() if not isinstance(v, float)} == \
            {k: v for k, v in want.items() if not isinstance(v, float)}
        for k, v in want.items():
            if isinstance(v, float):
                assert got[k] == pytest.approx(v, rel=1e-7, abs=1e-12), (want["quantity"], k)
    assert view.comparison["duration_s"] == pytest.approx(DURATION, rel=0.2)
    assert view.time_step_s == here.link_level.dt
    assert view.frames_png.startswith(PNG) and view.tensions_png.startswith(PNG)
    # the table the tab shows: one record per row, forces in lbf for US units
    # (1 lbf = 4.4482216152605 N exactly [NIST-SP811])
    records = _comparison_records(view.comparison, "US")
    assert len(records) == len(expected["rows"])
    first_force = next(i for i, r in enumerate(expected["rows"]) if r["unit"] == "N")
    assert records[first_force]["unit"] == "lbf"
    assert float(records[first_force]["whole drive"]) == pytest.approx(
        expected["rows"][first_force]["whole_drive"] / 4.4482216152605, rel=1e-3)


def test_a_bad_duration_comes_back_as_its_error(seed) -> None:
    with pytest.raises(DesignError, match="outside 0.001 s to 10 s"):
        bounded_link_level(seed, 20.0)
