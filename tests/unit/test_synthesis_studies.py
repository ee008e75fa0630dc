"""Studies on Dask with the study database (issue 8): a lost worker loses no finished
evaluation and every result is stored once; an interrupted study resumes from its SQLite file
without repeating finished work."""

from __future__ import annotations

import contextlib
import os
import signal
import time
import tomllib
from pathlib import Path

import pytest
from sqlalchemy import func, select

from chaindrive.synthesis.studies import (
    EVALUATIONS,
    StudyStore,
    evaluate_design,
    monte_carlo_inputs,
    run_study,
    sweep_inputs,
)
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.concurrency  # Dask clusters, threads and signals

distributed = pytest.importorskip("distributed")


def _base() -> dict:
    return tomllib.loads((EXAMPLES / "eight_sprocket.toml").read_text(encoding="utf-8"))


def _rows(url: str, study: str) -> tuple[int, int]:
    store = StudyStore(url)
    with store.engine.connect() as con:
        total = con.execute(select(func.count()).select_from(EVALUATIONS)
                            .where(EVALUATIONS.c.study == study)).scalar_one()
        distinct = con.execute(select(func.count(func.distinct(EVALUATIONS.c.key)))
                               .where(EVALUATIONS.c.study == study)).scalar_one()
    store.close()
    return total, distinct


def test_sweep_inputs_cartesian_and_paths() -> None:
    inputs = sweep_inputs(_base(), {"sprockets[1].x": ["790 mm", "810 mm"],
                                    "drive.power": ["3 kW", "4 kW", "5 kW"]})
    assert len(inputs) == 6
    assert {(i["design"]["sprockets"][1]["x"], i["design"]["drive"]["power"])
            for i in inputs} == {(x, p) for x in ("790 mm", "810 mm")
                                 for p in ("3 kW", "4 kW", "5 kW")}
    assert _base()["sprockets"][1]["x"] == "800 mm"  # the base is not modified


def test_monte_carlo_reproducible_and_spread() -> None:
    a = monte_carlo_inputs(_base(), {"sprockets[1].x": "0.5 mm"}, 200, seed=4)
    b = monte_carlo_inputs(_base(), {"sprockets[1].x": "0.0005 m"}, 200, seed=4)
    xa = [float(i["design"]["sprockets"][1]["x"].split()[0]) for i in a]
    xb = [float(i["design"]["sprockets"][1]["x"].split()[0]) for i in b]
    assert xa == pytest.approx(xb)  # the tolerance is converted to the value's unit
    mean = sum(xa) / len(xa)
    sd = (sum((x - mean) ** 2 for x in xa) / (len(xa) - 1)) ** 0.5
    assert abs(mean - 800) < 0.15 and 0.4 < sd < 0.6


def test_sweep_survives_a_killed_worker(tmp_path) -> None:
    """A worker killed (SIGKILL) once the first evaluations are stored, while the others are
    being computed: every result is there and stored once. The kill comes from the study's
    own ``on_stored`` (called as each batch is stored), not from a thread polling the
    database: at that moment the study is part-way whatever the load."""
    url = f"sqlite:///{tmp_path / 'study.db'}"
    inputs = sweep_inputs(_base(), {"sprockets[1].x": [f"{790 + 0.5 * k:g} mm"
                                                        for k in range(40)],
                                    "drive.power": ["3 kW", "4 kW", "5 kW"]})
    killed: dict[str, int] = {}
    stored = {"n": 0}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        pids = client.run(os.getpid)

        def kill_when_started(n: int) -> None:
            stored["n"] += n
            if "at" not in killed and stored["n"] >= 5:
                killed["at"] = stored["n"]
                os.kill(next(iter(pids.values())), signal.SIGKILL)

        result = run_study(evaluate_design, inputs, study="sweep", db=url, client=client,
                           progress=False, on_stored=kill_when_started)
    assert "at" in killed and killed["at"] < len(inputs)  # killed part-way
    assert result.computed == len(inputs) and result.reused == 0
    assert all(r is not None and "objectives" in r for r in result.results)
    assert _rows(url, "sweep") == (len(inputs), len(inputs))  # every result stored once


#: Environment of the counting function's worker processes: where each call is logged, and
#: after how many calls it raises (an interruption).
_LOG, _FAIL_AFTER = "CHAINDRIVE_TEST_CALL_LOG", "CHAINDRIVE_TEST_FAIL_AFTER"
_CALLS = {"n": 0}  # calls made in this (worker) process


def _counting(inputs: dict) -> dict:
    """Squares ``x``, logging each call to a file named by the worker's process in the
    directory ``$CHAINDRIVE_TEST_CALL_LOG``; raises after ``$CHAINDRIVE_TEST_FAIL_AFTER`` calls
    of its process."""
    with (Path(os.environ[_LOG]) / f"{os.getpid()}.log").open("a", encoding="utf-8") as log:
        log.write(f"{inputs['x']}\n")
    _CALLS["n"] += 1
    fail_after = os.environ.get(_FAIL_AFTER)
    if fail_after is not None and _CALLS["n"] > int(fail_after):
        raise RuntimeError("interrupted")
    return {"square": inputs["x"] ** 2}


def _logged(directory: Path) -> list[int]:
    """The inputs every call logged in ``directory`` received."""
    return [int(line) for f in sorted(directory.glob("*.log"))
            for line in f.read_text(encoding="utf-8").split()]


def _cluster(log: Path, **env: str) -> distributed.LocalCluster:
    """One worker process with one thread, its calls logged to ``log``."""
    log.mkdir()
    return distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                    dashboard_address=":0", env={_LOG: str(log), **env})


def test_interrupted_study_resumes_from_sqlite(tmp_path) -> None:
    """A study interrupted by an exception keeps every evaluation finished before it; run
    again (a new process, as after a crash), it computes exactly the rest.

    Each run has its own cluster, closed before the next starts, so the calls the second
    run makes are the lines its worker logged: stragglers of the interrupted run (tasks
    cancelled but already started) cannot be counted in, whatever the timing."""
    url = f"sqlite:///{tmp_path / 'resume.db'}"
    inputs = [{"x": k} for k in range(30)]
    fail_after = 12
    with _cluster(tmp_path / "first", **{_FAIL_AFTER: str(fail_after)}) as cluster, \
            distributed.Client(cluster) as client, \
            pytest.raises(RuntimeError, match="interrupted"):
        run_study(_counting, inputs, study="resume", db=url, client=client, progress=False)
    store = StudyStore(url)
    stored = store.count("resume")
    done = {round(r["square"] ** 0.5) for r in store.get("resume", store.keys("resume")).values()}
    store.close()
    finished = _logged(tmp_path / "first")[:fail_after]  # the calls that returned
    assert stored == len(finished) == fail_after  # every finished evaluation was stored
    assert done == set(finished)
    with _cluster(tmp_path / "second") as cluster, distributed.Client(cluster) as client:
        result = run_study(_counting, inputs, study="resume", db=url, client=client,
                           progress=False)
    calls = _logged(tmp_path / "second")
    assert sorted(calls) == sorted(set(range(30)) - done)  # finished work is not repeated
    assert result.reused == stored and result.computed == len(inputs) - stored
    assert [r["square"] for r in result.results] == [k * k for k in range(30)]
    assert _rows(url, "resume") == (30, 30)


def test_optimiser_population_on_dask_matches_serial_and_resumes(tmp_path) -> None:
    from chaindrive.synthesis.problem import load_problem
    from chaindrive.synthesis.solve import solve
    from chaindrive.synthesis.studies import DaskEvaluator

    pytest.importorskip("optuna")
    problem = load_problem(EXAMPLES / "eight_sprocket_optimize.toml")
    serial = solve(problem, population=8, generations=2, seed=5)
    url = f"sqlite:///{tmp_path / 'opt.db'}"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        first = solve(problem, population=8, generations=2, seed=5,
                      evaluator=DaskEvaluator(db=url, study="opt", client=client))
        stored = StudyStore(url).count("opt")
        again = solve(problem, population=8, generations=2, seed=5,
                      evaluator=DaskEvaluator(db=url, study="opt", client=client))
    assert [p.objectives for p in first.pareto] == [p.objectives for p in serial.pareto]
    assert [p.objectives for p in again.pareto] == [p.objectives for p in serial.pareto]
    assert StudyStore(url).count("opt") == stored  # the rerun computed nothing new


def test_a_bad_database_url_is_one_line(tmp_path) -> None:
    from chaindrive.errors import DesignError

    for url in ("sqlite:////missing/dir/x.db", "nosuchdialect://x", "sqlite:///"
                + str(tmp_path / "no" / "such" / "dir" / "x.db")):
        with pytest.raises(DesignError) as info:
            StudyStore(url)
        line = str(info.value)
        assert line.startswith("db: cannot open the study database") and "\n" not in line


def test_optimize_with_a_bad_db_is_one_line_and_exit_2(capsys) -> None:
    from chaindrive.cli import run

    status = run(["optimize", str(EXAMPLES / "eight_sprocket_optimize.toml"), "--db",
                  "sqlite:////missing/dir/x.db"])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1 and err[0].startswith("error: db: cannot open")


def _small_problem():  # type: ignore[no-untyped-def]
    from chaindrive.synthesis.problem import load_problem

    return load_problem(EXAMPLES / "eight_sprocket_optimize.toml")


def test_one_cluster_serves_every_generation(tmp_path, monkeypatch) -> None:
    """The evaluator starts one cluster for the study, not one per generation (a new
    LocalCluster per generation made a worker lost while one started abort the study)."""
    from chaindrive.synthesis import studies
    from chaindrive.synthesis.solve import solve

    pytest.importorskip("optuna")
    started: list[object] = []

    def client(scheduler, n_workers):  # type: ignore[no-untyped-def]
        cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1,
                                           processes=False, dashboard_address=":0")
        started.append(cluster)
        return distributed.Client(cluster), cluster

    monkeypatch.setattr(studies, "_client", client)
    url = f"sqlite:///{tmp_path / 'one.db'}"
    with studies.DaskEvaluator(db=url, study="one") as evaluator:
        result = solve(_small_problem(), population=4, generations=3, seed=2,
                       evaluator=evaluator)
        assert len(started) == 1 and evaluator.client.status == "running"
    assert evaluator._client is None  # closed with the evaluator
    assert result.evaluations >= 12
    # the same search again: every population is stored, so no cluster is started
    with studies.DaskEvaluator(db=url, study="one") as evaluator:
        again = solve(_small_problem(), population=4, generations=3, seed=2,
                      evaluator=evaluator)
    assert len(started) == 1 and evaluator._client is None
    assert [p.objectives for p in again.pareto] == [p.objectives for p in result.pareto]


def test_a_study_survives_workers_lost_at_any_time(tmp_path, monkeypatch) -> None:
    """Workers killed (SIGKILL) as the cluster starts, within a generation (once its first
    batch is stored; the rest of it, if any, computing) and between generations (the second
    stored, the third not submitted): the optimisation ends with the same Pareto set as the
    serial run.

    Each kill comes at its moment from the study itself (the evaluator's ``on_stored``, a
    wrapper of the evaluator called once a generation), whatever the load; a thread polling
    the database every 10 ms killed 4-5 times a run at moments of chance (each kill a worker
    restart, most of the test's CPU)."""
    from chaindrive.synthesis import studies
    from chaindrive.synthesis.solve import solve

    pytest.importorskip("optuna")
    problem = _small_problem()
    serial = solve(problem, population=6, generations=3, seed=3)
    url = f"sqlite:///{tmp_path / 'lost.db'}"
    kills: list[str] = []
    clusters: list[distributed.LocalCluster] = []
    real_client = studies._client

    def client_losing_a_worker(scheduler, n_workers):  # type: ignore[no-untyped-def]
        client, cluster = real_client(scheduler, n_workers)
        clusters.append(cluster)
        os.kill(next(iter(client.run(os.getpid).values())), signal.SIGKILL)
        kills.append("start")  # lost while the cluster starts, before any task
        return client, cluster

    monkeypatch.setattr(studies, "_client", client_losing_a_worker)
    evaluator = studies.DaskEvaluator(db=url, study="lost", n_workers=2)
    generation = {"n": 0}

    def kill_a_worker(when: str) -> None:
        """Kill a worker the scheduler has now, by its nanny's process id (``client.run``
        on a worker just killed and not yet removed waits up to its connect timeout)."""
        deadline = time.monotonic() + 60  # a bound on a stuck test
        while time.monotonic() < deadline:
            live = set(evaluator.client.scheduler_info(n_workers=-1)["workers"])
            for nanny in list(clusters[0].workers.values()):
                if nanny.worker_address in live and nanny.pid:
                    with contextlib.suppress(ProcessLookupError):  # gone, not yet removed
                        os.kill(nanny.pid, signal.SIGKILL)
                        kills.append(when)
                        return
            time.sleep(0.05)

    def within_a_generation(n: int) -> None:
        if generation["n"] == 2 and "within" not in kills:
            kill_a_worker("within")

    def between_generations(problem_, xs):  # type: ignore[no-untyped-def]
        generation["n"] += 1
        if generation["n"] == 3:
            kill_a_worker("between")
        return evaluator(problem_, xs)

    evaluator.on_stored = within_a_generation
    with evaluator:
        result = solve(problem, population=6, generations=3, seed=3,
                       evaluator=between_generations)
    assert kills == ["start", "within", "between"], kills
    assert [p.objectives for p in result.pareto] == [p.objectives for p in serial.pareto]


def _square_and_worker(inputs: dict) -> dict:
    """Squares ``x`` and names the worker that did it."""
    return {"square": inputs["x"] ** 2, "worker": distributed.get_worker().name}


def test_the_watchdog_brings_back_workers_the_nanny_gave_up_on(tmp_path, monkeypatch) -> None:
    """Every worker's nanny gives up before the study's first task: it closes, as Dask's
    nanny does when the worker it restarts is lost again while it starts
    (``nanny-instantiate-failed``), and the cluster keeps it in its spec, closed, with no
    worker at all (a study waited for ever; now it stops after LOST_WORKERS_SECONDS). The
    watchdog re-creates the workers, and the study ends with every result.

    The workers that computed are new ones, under names of their own: a nanny's restart
    keeps its worker's name, so no result can come from the nannies given up on. (Killing
    workers as they restart left it to chance: Dask's nanny gave up once in 12 kills in one
    run, never in 10 in another, and the test passed without the watchdog acting.)"""
    from chaindrive.synthesis import studies

    real_client = studies._client
    gave_up: list[object] = []

    def client_whose_nannies_gave_up(scheduler, n_workers):  # type: ignore[no-untyped-def]
        client, cluster = real_client(scheduler, n_workers)
        for name, nanny in list(cluster.workers.items()):
            cluster.sync(nanny.close, reason="nanny-instantiate-failed")
            gave_up.append(name)
        assert {w.status.name for w in cluster.workers.values()} == {"closed"}
        assert set(cluster.worker_spec) == set(gave_up)  # closed, not removed
        return client, cluster

    monkeypatch.setattr(studies, "_client", client_whose_nannies_gave_up)
    url = f"sqlite:///{tmp_path / 'revived.db'}"
    inputs = [{"x": k} for k in range(20)]
    result = run_study(_square_and_worker, inputs, study="revived", db=url, n_workers=2,
                       progress=False)
    assert len(gave_up) == 2
    assert result.computed == len(inputs) and result.reused == 0
    assert [r["square"] for r in result.results] == [k * k for k in range(20)]
    ran_on = {r["worker"] for r in result.results}
    assert ran_on and not ran_on & set(gave_up), (ran_on, gave_up)  # re-created workers
    assert _rows(url, "revived") == (len(inputs), len(inputs))
