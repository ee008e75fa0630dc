"""Optimal synthesis of chain drives [MultimassChainDrives, §3.2, §3.6].

:mod:`.problem` reads the ``[optimize]`` table; :mod:`.objectives` holds the registry of
objectives; :mod:`.evaluation` evaluates a design from its analysis (the cost model is
:mod:`chaindrive.cost`); :mod:`.solve` the multi-objective search (pymoo NSGA-II, or Optuna);
:mod:`.detuning` the detuning task of the paper; :mod:`.inverse` the inverse eigenvalue
problem; :mod:`.studies` sweeps, Monte-Carlo studies and populations on Dask with a
resumable study database; :mod:`.workflow` what follows a search. See docs/synthesis.md.
"""

from __future__ import annotations

from chaindrive.synthesis.problem import Problem, load_problem, problem_from_mapping

__all__ = ["Problem", "load_problem", "problem_from_mapping"]
