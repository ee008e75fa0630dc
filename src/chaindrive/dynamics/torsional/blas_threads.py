"""One BLAS thread while a small dense eigenproblem is solved (docs/torsional.md §8).

A modal analysis of a few dozen coordinates is a handful of LAPACK calls of tens of
microseconds each. OpenBLAS runs the products inside them on all its threads even at 72×72,
and waking and joining the threads costs about as much as the product; on a machine whose
cores are busy the threads also wait for one another. Measured on the project machine (two
cores, load average 3–5): ``numpy.linalg.eigh`` of a 72×72 symmetric matrix 1.9 ms best,
4.4 ms median on two BLAS threads against 1.0 / 1.3 ms on one; the modal analysis of
benchmarks/bench_torsional.py (72 coordinates, assembly included) 2.6× (best) to 7.5×
(median) slower on the default two threads than on one.

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

#: Largest eigenproblem [coordinates] solved on one BLAS thread. A judgement, not a fit:
#: ``numpy.linalg.eigh`` of a random symmetric matrix on one thread against two, best of 5 at
#: load average 4–5 on two cores: 1.0 / 1.9 ms at n = 72, 4.5 / 12.6 ms at 150, 22.6 / 26.2 ms
#: at 300. Whether a second thread pays above that on an idle machine was not measured (the
#: shared project machine was never idle).
SMALL_PROBLEM_SIZE = 256

_lock = threading.Lock()
_controller: list[ThreadpoolController] = []
_local = threading.local()  # per Python thread: .limited inside a block


def _blas_controller() -> ThreadpoolController:
    """The process's controller of the BLAS libraries loaded at its first call (numpy's
    OpenBLAS, which the eigensolvers here use, is loaded with numpy)."""
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
