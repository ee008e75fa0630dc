"""One BLAS thread for a command unless the user asks for more (chaindrive.cli.threads).

The counts are read back from the BLAS libraries themselves (threadpoolctl), in a fresh process
each time, since the setting is process-wide.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from chaindrive.cli.threads import LIBRARY_VARIABLES, THREADS_VARIABLE, blas_threads
from chaindrive.errors import DesignError

PROBE = """
import json, os, sys
from chaindrive.cli import run
status = run(['catalog', 'ISO 606 16B-1'])
from threadpoolctl import threadpool_info
counts = [i['num_threads'] for i in threadpool_info() if i['user_api'] == 'blas']
print(json.dumps({'status': status, 'counts': counts,
                  'env': os.environ.get('OPENBLAS_NUM_THREADS')}), file=sys.stderr)
"""


def _probe(**env: str) -> dict:
    base = {k: v for k, v in os.environ.items()
            if k not in (THREADS_VARIABLE, *LIBRARY_VARIABLES)}
    proc = subprocess.run([sys.executable, "-c", PROBE], env={**base, **env},
                          capture_output=True, text=True, timeout=120, check=False)
    return json.loads(proc.stderr.strip().splitlines()[-1])


def test_a_command_runs_blas_on_one_thread_and_its_children_inherit_it() -> None:
    out = _probe()
    assert out["status"] == 0
    assert out["counts"] and set(out["counts"]) == {1}
    assert out["env"] == "1"  # what a Dask worker or a page worker started later reads


def test_the_user_asks_for_more_threads() -> None:
    out = _probe(**{THREADS_VARIABLE: "2"})
    assert set(out["counts"]) == {2}
    assert out["env"] == "2"


def test_a_library_setting_of_the_user_is_kept() -> None:
    out = _probe(OPENBLAS_NUM_THREADS="2")
    assert out["env"] == "2"
    assert set(out["counts"]) == {2}


@pytest.mark.parametrize("text", ["0", "x", "-1", "1.5", "257", ""])
def test_a_bad_request_names_the_variable_and_the_range(text: str) -> None:
    with pytest.raises(DesignError, match=rf"{THREADS_VARIABLE}.*from 1 to 256"):
        blas_threads({THREADS_VARIABLE: text})


def test_a_bad_request_is_one_line_and_exit_2() -> None:
    env = {k: v for k, v in os.environ.items() if k != THREADS_VARIABLE}
    proc = subprocess.run([sys.executable, "-m", "chaindrive", "schema"],
                          env={**env, THREADS_VARIABLE: "many"}, capture_output=True,
                          text=True, timeout=120, check=False)
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.strip().count("\n") == 0
    assert THREADS_VARIABLE in proc.stderr
