"""Threads of the linear algebra for a command: one unless the user asks for more.

The analyses of a drive are many small dense problems (eigenproblems of a few dozen to a few
hundred coordinates, products of matrices of that size). OpenBLAS runs each on all its threads;
on a machine whose cores are shared (a designer's laptop with a browser and a CAD package
open, the project's two-core machine with other work on it) the threads wait on one another.
Measured on the project machine (two cores, both kept busy by two other processes, five runs
in alternation): ``analyze --json`` of the 24-sprocket example 1.50 s wall, 0.52 s CPU median on
one BLAS thread against 4.41 s, 1.60 s on two (2.9× the wall time)
(docs/performance.md).

So every command runs its BLAS libraries on one thread, and the processes it starts (the
optimiser's and the robust study's Dask workers, the page's run workers) inherit the same
setting through the environment. A user who wants more threads says so with the environment
variable :data:`THREADS_VARIABLE` (``CHAINDRIVE_BLAS_THREADS=2 chaindrive analyze …``); one who
has already set ``OPENBLAS_NUM_THREADS`` (or MKL's, OpenMP's) keeps what they set.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping

from chaindrive.errors import DesignError

__all__ = ["LIBRARY_VARIABLES", "THREADS_VARIABLE", "blas_threads", "limit_blas_threads"]

#: The user's request for more threads of the linear algebra.
THREADS_VARIABLE = "CHAINDRIVE_BLAS_THREADS"
#: The variables the BLAS and OpenMP runtimes read when they load (in a new process).
LIBRARY_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS")
#: Threads a user may ask for: at least one; more than 256 is no machine a design tool runs on.
THREADS_RANGE = (1, 256)


def blas_threads(environ: MutableMapping[str, str]) -> int | None:
    """The BLAS threads a command runs on, from the environment.

    Parameters
    ----------
    environ : mapping
        The process's environment.

    Returns
    -------
    int or None
        :data:`THREADS_VARIABLE` when set, 1 when neither it nor any of
        :data:`LIBRARY_VARIABLES` is set, None when the user set a library's own variable
        (left as they set it).

    Raises
    ------
    DesignError
        :data:`THREADS_VARIABLE` is not a whole number in :data:`THREADS_RANGE`.
    """
    text = environ.get(THREADS_VARIABLE)
    if text is not None:
        lo, hi = THREADS_RANGE
        try:
            n = int(text.strip())
        except ValueError:
            n = 0
        if not lo <= n <= hi:
            raise DesignError(THREADS_VARIABLE, f"{text[:40]!r} is not a number of threads: "
                                                f"a whole number from {lo} to {hi}")
        return n
    if any(name in environ for name in LIBRARY_VARIABLES):
        return None
    return 1


def limit_blas_threads(environ: MutableMapping[str, str] | None = None) -> int | None:
    """Run this process's BLAS libraries on :func:`blas_threads` threads, and have the
    processes it starts do the same.

    The libraries already loaded (NumPy's and SciPy's OpenBLAS) are limited through
    :mod:`threadpoolctl`; the environment variables of :data:`LIBRARY_VARIABLES` are set so
    that a process started later reads the same number when its libraries load.

    Parameters
    ----------
    environ : mapping or None
        The environment to read and set (None: ``os.environ``).

    Returns
    -------
    int or None
        The number of threads set, or None where the user's own library setting was kept.
    """
    env = os.environ if environ is None else environ
    n = blas_threads(env)
    if n is None:
        return None
    for name in LIBRARY_VARIABLES:
        env[name] = str(n)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=n, user_api="blas")
    return n
