"""The package installed from a wheel into a fresh virtualenv finds its own data: the web
page lists the bundled examples (package data, not a folder found by walking up from the
installed file), and the catalogue and the examples load.

The wheel is built from this checkout and installed without dependencies into a new
virtualenv; the dependencies (NumPy, SciPy …) come from the test environment's
site-packages, put on the path after the new environment's own (so the ``chaindrive`` that
is imported is the wheel's, which the test checks).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from chaindrive import examples

pytestmark = pytest.mark.concurrency  # builds and installs in subprocesses

ROOT = Path(__file__).resolve().parents[2]
PROBE = """
import json, chaindrive
from chaindrive import examples
from chaindrive.app.state import list_examples
drive = examples.load("seed_three_sprocket")
print(json.dumps({"file": chaindrive.__file__, "page": list(list_examples()),
                  "links": chaindrive.analyze(drive, response=False).geometry.links}))
"""


def _run(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(args, capture_output=True, text=True, timeout=600, env=env,
                          check=False)


def test_web_page_lists_the_examples_from_an_installed_wheel(tmp_path: Path) -> None:
    built = _run(sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w",
                 str(tmp_path / "dist"), str(ROOT))
    assert built.returncode == 0, built.stderr[-2000:]
    wheel = next((tmp_path / "dist").glob("chaindrive-*.whl"))
    venv = tmp_path / "venv"
    # a virtualenv without a pip of its own (installing one took 3 of the test's 5 s CPU):
    # the test environment's pip installs the wheel into it (``--python``), outside any
    # PYTHONPATH (a checkout's src/ on it made pip take the package as installed already)
    made = _run(sys.executable, "-m", "venv", "--without-pip", str(venv))
    assert made.returncode == 0, made.stderr[-2000:]
    python = str(venv / "bin" / "python")
    clean = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    installed = _run(sys.executable, "-m", "pip", "--python", python, "install", "--quiet",
                     "--no-deps", str(wheel), env=clean)
    assert installed.returncode == 0, installed.stderr[-2000:]
    deps = sysconfig.get_paths()["purelib"]  # the test environment's site-packages
    own = _run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([own.stdout.strip(), deps])}
    probe = _run(python, "-c", PROBE, env={**env, "PWD": str(tmp_path)})
    assert probe.returncode == 0, probe.stderr[-2000:]
    found = json.loads(probe.stdout.strip().splitlines()[-1])
    assert Path(found["file"]).is_relative_to(venv)  # the wheel's package, not the source
    assert found["page"] == list(examples.names())
    assert found["links"] == 128  # the seed example, from the installed package data
