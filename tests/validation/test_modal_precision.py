"""Where double precision runs out (chaindrive.dynamics.precision): against 50-digit
references (mpmath), the ring and the torsional train either answer every mode within the
error bound of a backward-stable symmetric eigensolver, ε·n·λ_max [Golub2013, §8.1], or
refuse the model with its spread; no mode is lost and none is spurious; the modes with
shapes (``modal()``) and without (``frequencies_hz()``) agree wherever both answer.

The models are random (seeded): reduced masses and inertias over 14 decades and stiffnesses
over 10, so that about half of them spread beyond what double precision resolves."""

from __future__ import annotations

import math

import numpy as np
import pytest

from chaindrive.dynamics import RingModel
from chaindrive.dynamics.precision import SPREAD_LIMIT
from chaindrive.dynamics.torsional.model import TorsionalModel
from chaindrive.errors import DesignError

mpmath = pytest.importorskip("mpmath")
EPS = float(np.finfo(float).eps)
CASES = 150


def _reference(K: list[list[float]], m: list[float]) -> list[float]:
    """The eigenvalues ω² of K x = ω² M x (M = diag m), ascending, to 50 digits."""
    with mpmath.workdps(50):
        n = len(m)
        d = [1 / mpmath.sqrt(mpmath.mpf(x)) for x in m]
        A = mpmath.matrix(n, n)
        for i in range(n):
            for j in range(n):
                A[i, j] = mpmath.mpf(K[i][j]) * d[i] * d[j]
        lam = mpmath.eigsy(A, eigvals_only=True)
        return sorted(float(x) for x in lam)


def _ring_stiffness(c: np.ndarray) -> list[list[float]]:
    n = c.size
    K = np.zeros((n, n))
    for i in range(n):
        j = (i + 1) % n
        K[i, i] += c[i]
        K[j, j] += c[i]
        K[i, j] -= c[i]
        K[j, i] -= c[i]
    return K.tolist()


def _chain_stiffness(k: np.ndarray) -> list[list[float]]:
    n = k.size + 1
    K = np.zeros((n, n))
    for i, ki in enumerate(k):
        K[i, i] += ki
        K[i + 1, i + 1] += ki
        K[i, i + 1] -= ki
        K[i + 1, i] -= ki
    return K.tolist()


def _judge(computed: np.ndarray | None, reference: list[float]) -> str:
    """'answered' or 'refused', after checking the answer or the refusal."""
    elastic = np.array(reference[1:])  # one rigid-body mode: a free ring or train
    spread = elastic.max() / elastic.min()
    if computed is None:
        # refused only where the spread nears the limit (the computed lowest eigenvalue is
        # off by at most the bound below)
        assert spread > 0.5 * SPREAD_LIMIT, spread
        return "refused"
    assert spread < 2e14, spread  # answered: within what double precision resolves
    lam = computed[1:]
    assert lam.size == elastic.size and (lam > 0).all()  # none lost, none spurious
    bound = 4 * elastic.size * EPS * elastic.max()
    assert np.abs(lam - elastic).max() <= bound, (lam, elastic)
    return "answered"


def test_random_rings_answer_within_the_bound_or_refuse() -> None:
    rng = np.random.default_rng(20261128)
    seen = {"answered": 0, "refused": 0}
    for _ in range(CASES):
        n = int(rng.integers(3, 9))
        m = 10.0 ** rng.uniform(-8, 6, n)
        c = 10.0 ** rng.uniform(0, 10, n)
        try:
            f = RingModel(m, c).modal().frequencies_hz
            computed = (2 * math.pi * np.asarray(f)) ** 2
        except DesignError as exc:
            computed = None
            message = str(exc)
        if computed is None:
            assert "spread by" in message and "\n" not in message
        seen[_judge(computed, _reference(_ring_stiffness(c), m.tolist()))] += 1
    assert min(seen.values()) > CASES // 10, seen  # both sides of the limit were tried


def _train(J: np.ndarray, k: np.ndarray) -> TorsionalModel:
    model = TorsionalModel()
    for i, j in enumerate(J):
        model.add_inertia(f"n{i}", float(j))
    for i, ki in enumerate(k):
        model.add_shaft(f"n{i}", f"n{i + 1}", float(ki))
    return model


def test_random_trains_answer_within_the_bound_or_refuse_and_both_paths_agree() -> None:
    rng = np.random.default_rng(37)
    seen = {"answered": 0, "refused": 0}
    for _ in range(CASES):
        n = int(rng.integers(3, 9))
        J = 10.0 ** rng.uniform(-8, 6, n)
        k = 10.0 ** rng.uniform(0, 10, n - 1)
        model = _train(J, k)
        answers = []
        for path in ("modal", "frequencies"):
            try:
                f = (model.modal().frequencies_hz if path == "modal"
                     else model.frequencies_hz())
                answers.append((2 * math.pi * np.asarray(f)) ** 2)
            except DesignError as exc:
                answers.append(None)
                message = str(exc)
            if answers[-1] is None:
                assert "spread by" in message
        reference = _reference(_chain_stiffness(k), J.tolist())
        for computed in answers:
            seen[_judge(computed, reference)] += 1
        if answers[0] is not None and answers[1] is not None:
            bound = 4 * n * EPS * float(np.max(answers[0]))
            assert np.abs(answers[0] - answers[1]).max() <= bound
    assert min(seen.values()) > CASES // 10, seen
