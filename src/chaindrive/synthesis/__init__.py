"""Optimal synthesis of chain drives (seed 000 §3.2, §3.6; issue 8).

:mod:`.problem` reads the ``[optimize]`` table; :mod:`.objectives` holds the registries of
objectives and constraints and evaluates a design; :mod:`.cost` the replaceable cost model;
:mod:`.solve` the multi-objective search (pymoo NSGA-II, or Optuna); :mod:`.detuning` the
seed's detuning task; :mod:`.inverse` the inverse eigenvalue problem; :mod:`.studies` sweeps,
Monte-Carlo studies and populations on Dask with a resumable study database.
See docs/synthesis.md.
"""

from __future__ import annotations

from chaindrive.synthesis.problem import Problem, load_problem, problem_from_mapping

__all__ = ["Problem", "load_problem", "problem_from_mapping"]
