"""One BLAS thread while a small dense eigenproblem is solved (docs/torsional.md §8).

A modal analysis of a few dozen coordinates is a handful of LAPACK calls of tens of
microseconds each. OpenBLAS runs the products inside them on all its threads even at 72×72,
and waking and joining the threads costs about as much as the product; on a machine whose
cores are busy the threads also wait for one another. Measured
(benchmarks/bench_torsional.py, 72 coordinates, one process, load average 3–5 on two cores):
``numpy.linalg.eigh`` 1.9–4.4 ms with two BLAS threads against 1.0–1.3 ms with one, the whole
modal analysis 2–6× slower with the default two threads.

:func:`small_problem_threads` limits every BLAS library loaded in the process to one thread
for the duration of a block when the problem is small (:data:`SMALL_PROBLEM_SIZE`), through
:mod:`threadpoolctl`: the controller that finds the libraries is built once, at the first
call (≈ 8 ms); entering and leaving a block costs ≈ 13 µs. Is that a library's business? The
setting is process-wide (OpenBLAS has one pool of threads), so:

- another Python thread's BLAS calls made meanwhile also run on one thread (slower, never
  wrong), for the few hundred microseconds of the block;
- threadpoolctl lets one Python thread at a time set the limits of a pthreads OpenBLAS, so
  that threads never fight over the pool: the thread whose block opened first holds it until
  its block closes; a block another thread opens meanwhile changes nothing (that problem is
  solved with the threads as they are);
- a block nested in another of the same thread changes nothing; the outermost one restores
  what it found, also when the block raises.

The same trade is made by other numerical libraries that run many small BLAS calls; a caller
who wants the threads can set ``SMALL_PROBLEM_SIZE = 0``.

References
----------
[Anderson1999, ch. 3] (LAPACK's eigensolvers as blocked level-3 BLAS).
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager

from threadpoolctl import ThreadpoolController

__all__ = ["SMALL_PROBLEM_SIZE", "blas_thread_counts", "small_problem_threads"]

#: Largest eigenproblem [coordinates] solved on one BLAS thread. A judgement, not a fit: at
#: 72 coordinates one thread was 1.5–3× faster under load (module docstring); at 256 a dense
#: symmetric eigensolve is still a few ms, where a second thread gains little on an idle
#: machine and loses much on a busy one. Measured on the project machine only.
SMALL_PROBLEM_SIZE = 256



_lock = threading.Lock()
_controller: list[ThreadpoolController] = []
_local = threading.local()  # per Python thread: .limited inside a block


def _blas_controller() -> ThreadpoolController:
    """The process's controller of BLAS libraries (built once, at the first call)."""
    with _lock:
        if not _controller:
            _controller.append(ThreadpoolController())
        return _controller[0]


def blas_thread_counts() -> tuple[int, ...]:
    """The number of threads [-] of every BLAS library the controller found.

    Returns
    -------
    tuple of int
        One count per library (numpy's and scipy's OpenBLAS are separate libraries).
    """
    libraries = _blas_controller().select(user_api="blas").lib_controllers
    return tuple(int(lib.num_threads) for lib in libraries)


@contextmanager
def small_problem_threads(size: int) -> Iterator[None]:
    """Run the block on one BLAS thread when ``size`` ≤ :data:`SMALL_PROBLEM_SIZE`.

    Parameters
    ----------
    size : int
        Number of coordinates of the eigenproblem [-].

    Yields
    ------
    None
        Inside the block the BLAS libraries run on one thread (a larger problem, or a
        Python thread that does not control BLAS: unchanged; module docstring).
    """
    if size > SMALL_PROBLEM_SIZE or getattr(_local, "limited", False):
        yield  # a large problem, or a block nested in one of this thread's blocks
        return
    with _blas_controller().limit(limits=1, user_api="blas"):
        _local.limited = True
        try:
            yield
        finally:
            _local.limited = False
