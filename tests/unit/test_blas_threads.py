"""One BLAS thread for small eigenproblems (chaindrive.dynamics.torsional.blas_threads): the limit holds
inside the block, what was there before comes back after it (also when blocks nest or other
threads open theirs meanwhile), a large problem is left alone, and the modes do not depend on it.

The modal check compares against the closed form of a free two-disk shaft, ω² = k (J₁ + J₂) /
(J₁ J₂) [Rao2011, ch. 6].
"""

from __future__ import annotations

import math
import threading
from collections.abc import Iterator

import numpy as np
import pytest
from threadpoolctl import ThreadpoolController

from chaindrive.dynamics import TorsionalModel
from chaindrive.dynamics.torsional import blas_threads
from chaindrive.dynamics.torsional.blas_threads import blas_thread_counts, small_problem_threads

pytestmark = pytest.mark.concurrency  # threads


@pytest.fixture
def two_threads() -> Iterator[None]:
    """Every BLAS library of the process set to two threads for the test, then restored."""
    with ThreadpoolController().limit(limits=2, user_api="blas"):
        yield


def test_one_thread_inside_the_block_and_the_setting_back_after(two_threads: None) -> None:
    assert set(blas_thread_counts()) == {2}
    with small_problem_threads(72):
        assert set(blas_thread_counts()) == {1}
    assert set(blas_thread_counts()) == {2}


def test_a_large_problem_keeps_the_threads(two_threads: None) -> None:
    with small_problem_threads(blas_threads.SMALL_PROBLEM_SIZE + 1):
        assert set(blas_thread_counts()) == {2}


def test_a_nested_block_keeps_the_limit_and_the_outer_one_restores(two_threads: None) -> None:
    with small_problem_threads(72):
        with small_problem_threads(72):
            assert set(blas_thread_counts()) == {1}
        assert set(blas_thread_counts()) == {1}
    assert set(blas_thread_counts()) == {2}


def test_blocks_of_other_threads_leave_the_setting_alone(two_threads: None) -> None:
    inside: list[set[int]] = []
    barrier = threading.Barrier(4)

    def work() -> None:
        with small_problem_threads(10):
            barrier.wait(timeout=30)  # all four blocks open at once
            inside.append(set(blas_thread_counts()))
            barrier.wait(timeout=30)

    with small_problem_threads(72):  # the main thread's block, open throughout
        threads = [threading.Thread(target=work) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(timeout=60)
        assert set(blas_thread_counts()) == {1}
    assert inside == [{1}] * 4
    assert set(blas_thread_counts()) == {2}
    threads = [threading.Thread(target=work) for _ in range(4)]  # no block of the main thread
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=60)
    assert set(blas_thread_counts()) == {2}


def test_the_block_restores_the_setting_when_the_solver_raises(two_threads: None) -> None:
    with pytest.raises(RuntimeError), small_problem_threads(10):
        raise RuntimeError("solver failed")
    assert set(blas_thread_counts()) == {2}


def test_modes_under_the_limit_match_the_closed_form(two_threads: None) -> None:
    J1, J2, k = 0.3, 1.7, 2.0e5  # kg·m², N·m/rad
    t = TorsionalModel().add_inertia("a", J1).add_inertia("b", J2).add_shaft("a", "b", k)
    modes = t.modal()
    f = math.sqrt(k * (J1 + J2) / (J1 * J2)) / (2.0 * math.pi)
    np.testing.assert_allclose(modes.frequencies_hz, [0.0, f], rtol=1e-13)
    np.testing.assert_allclose(t.frequencies_hz(), [0.0, f], rtol=1e-13)
    assert set(blas_thread_counts()) == {2}


def test_a_block_in_another_thread_limits_when_no_thread_holds_the_pool() -> None:
    before = blas_thread_counts()
    inside: list[set[int]] = []

    def work() -> None:
        with small_problem_threads(10):
            inside.append(set(blas_thread_counts()))

    t = threading.Thread(target=work)
    t.start()
    t.join(timeout=60)
    assert inside == [{1}]
    assert blas_thread_counts() == before
