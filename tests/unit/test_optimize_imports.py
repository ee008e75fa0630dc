"""What the optimiser imports: the synthesis package without the robust study's statistics
(scipy.stats, SALib, pandas) or the detuning search (scipy.optimize), which a deterministic
problem does not use; the robust package's names still reachable (imported on first use)."""

from __future__ import annotations

import subprocess
import sys

HEAVY = ("scipy.stats", "SALib", "pandas", "scipy.optimize")


def _loaded_after(statement: str) -> set[str]:
    probe = (f"import sys; {statement}; "
             f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True, timeout=120).stdout.strip()
    return set(filter(None, out.split(",")))


def test_the_optimiser_does_not_import_the_robust_statistics() -> None:
    assert _loaded_after("import chaindrive.synthesis.problem, chaindrive.synthesis.solve, "
                         "chaindrive.synthesis.evaluation, chaindrive.synthesis.objectives, "
                         "chaindrive.robust.synthesis") == set()


def test_the_robust_package_names_import_on_first_use() -> None:
    import chaindrive.robust as robust
    from chaindrive.robust.sampling import reliability

    assert robust.reliability is reliability
    assert set(robust.__all__) <= set(dir(robust)) | set(robust._HOME)
    assert _loaded_after("from chaindrive.robust import reliability") >= {"scipy.stats"}
