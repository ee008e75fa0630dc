"""Benchmark of the robust study (chaindrive.robust): many designs of the 24-sprocket drive,
each with the probability of its resonance check over the uncertainty model by the batched
modal path (frequencies and margins).

Designs: search vectors of an optimisation problem on examples/twenty_four_sprocket.toml
(a flywheel of 0 to 0.05 kg·m² on each of the twelve driven shafts, and the wear state new:
one geometric state per design), drawn at random (seeded). Per design, one batch of S modal
analyses of its whole-drive model (inertias ±10 %, chain stiffness ±10 %: S = 4 replicates ×
2^m ≥ the samples asked) through ``chaindrive.robust.study.robust_batch``.

What is reused and what is rebuilt per design: the designs differ only in their flywheels,
which enter the modal path only as inertia on their sprockets' shafts. So every worker
process builds once, for the design without flywheels
(``chaindrive.robust.study.shared_modal_basis``, kept under the value of that design and of
the ``[uncertainty]`` settings): the analysis up to the whole-drive model (geometry, static
tensions, ring reduction, the torsional system), the uncertainty model, the Sobol samples,
the stacked stiffness matrices of the S samples and their mass normalisation except for the
sprockets' coordinates, and the working and transverse frequencies. Per design it decodes
the vector, adds the flywheels ΔJ·f on the sprockets' nodes (f the sample's inertia factor),
scales the sprockets' rows and columns by their masses, and solves the S eigenvalue problems
(one ``numpy.linalg.eigvalsh`` of the stack), then the margins, the probability and its
interval. An optimiser with the same variables (flywheels) reuses exactly this; one whose
variables move the geometry (tooth counts, positions, chain, materials) gets a new key for
every design and rebuilds everything, as before.

1. The target: ``--designs`` (10 000) × ``--samples`` (100, i.e. 128 states) on a Dask
   LocalCluster of two worker processes, stored in a throw-away SQLite study (batches of 100
   designs per stored evaluation). Target: under 2 minutes on the 2-core project machine.
   Beside the wall time, the CPU time the run took (the workers', and this process's:
   scheduler, client, study store; the nannies' few left out): what two free cores would
   take is about half of it.
2. The speed-up from one to two Dask workers on the same workload (the first ``--speedup``
   designs), the contenders in alternation, two rounds each.
3. CPU time per design in one process (no Dask), side by side in alternation (several
   rounds of 100 designs each): every design built from its own analysis (its geometry,
   static tensions, model, uncertainty model, stacked matrices: the path before the shared
   basis) against the shared basis (built once per round, i.e. its cost spread over 100
   designs). The CPU time depends less on the load than the wall time does; two free cores
   would take designs × CPU / 2.
4. The peer of the batched frequencies: the same S states of a design one by one through the
   torsional engine (``TorsionalSystem.updated(...).frequencies_hz()``, the full per-state
   path's solver), CPU time per design side by side, and the ratio.

The machine is shared: the load average before and after each part is printed beside the
times; repeat the run to see the spread.

Run: .venv/bin/python benchmarks/bench_robust.py [--quick] [--designs N] [--samples S]
"""

from __future__ import annotations

import argparse
import os

# one BLAS thread per process: the parallelism is the Dask workers' (two BLAS threads in each
# of two workers on two cores oversubscribe them; set before NumPy is imported, inherited by
# the workers)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import tempfile  # noqa: E402
import time  # noqa: E402
import tomllib  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import tomli_w  # noqa: E402

from chaindrive.catalog import find_material  # noqa: E402
from chaindrive.robust.analysis import nominal_analysis  # noqa: E402
from chaindrive.robust.modal import batch_elastic_frequencies, batch_system_values  # noqa: E402
from chaindrive.robust.perturbation import modulus_factors  # noqa: E402
from chaindrive.robust.sampling import (  # noqa: E402
    _modal_factors,
    basis_reliability,
    reliability,
    sobol_points,
)
from chaindrive.robust.study import _SHARED_BASES, robust_batch, shared_modal_basis  # noqa: E402
from chaindrive.robust.uncertainty import uncertainty_model, uncertainty_settings  # noqa: E402
from chaindrive.synthesis.problem import problem_from_mapping  # noqa: E402
from chaindrive.synthesis.studies import run_study  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
BATCH = 100


def problem_text(samples: int) -> str:
    """The 24-sprocket example with flywheel genes on its driven shafts and [uncertainty]."""
    data = tomllib.loads((ROOT / "examples" / "twenty_four_sprocket.toml")
                         .read_text(encoding="utf-8"))
    driven = [s["name"] for s in data["sprockets"] if s.get("role") == "driven"]
    data["optimize"] = {"objectives": ["cost"],
                        "inertia": {n: ["0 kg*m^2", "0.05 kg*m^2"] for n in driven}}
    data["uncertainty"] = {"samples": samples, "replicates": 4, "wear": "new"}
    return tomli_w.dumps(data)


def vectors(text: str, count: int, seed: int = 1) -> list[list[float]]:
    """``count`` random search vectors of the problem (seeded)."""
    problem = problem_from_mapping(tomllib.loads(text))
    lo, hi = (np.array(b) for b in problem.bounds)
    x = lo + np.random.default_rng(seed).random((count, lo.size)) * (hi - lo)
    return x.tolist()


def inputs_of(text: str, xs: list[list[float]]) -> list[dict]:
    return [{"problem": text, "vectors": xs[i:i + BATCH]} for i in range(0, len(xs), BATCH)]


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load {one:.1f} (5 min {five:.1f})"


def on_dask(inputs: list[dict], workers: int) -> tuple[float, float, float]:
    """Wall time [s] of the study on a LocalCluster of ``workers`` processes (warm), and the
    CPU time [s] it took: the workers', and this process's (scheduler, client, study
    store)."""
    from distributed import Client, LocalCluster

    with tempfile.TemporaryDirectory() as tmp, \
            LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                         dashboard_address=":0") as cluster, Client(cluster) as client:
        db = f"sqlite:///{tmp}/robust.db"
        warm = [{"problem": inputs[0]["problem"], "vectors": inputs[0]["vectors"][:2]}]
        client.run(lambda: __import__("chaindrive.robust.study"))
        run_study(robust_batch, warm * workers, study="warm", db=db, client=client,
                  progress=False, chunk=1)
        w0 = sum(client.run(time.process_time).values())
        c0, t0 = time.process_time(), time.perf_counter()
        result = run_study(robust_batch, inputs, study="bench", db=db, client=client,
                           progress=False, chunk=1)
        seconds = time.perf_counter() - t0
        main = time.process_time() - c0
        cpu = sum(client.run(time.process_time).values()) - w0
        designs = sum(len(r["designs"]) for r in result.results)
        assert designs == sum(len(i["vectors"]) for i in inputs)
    return seconds, cpu, main


def frequencies_side_by_side(text: str, xs: list[list[float]]) -> tuple[float, float]:
    """CPU time [s] per design of the S states' frequencies: stacked, and one by one."""
    problem = problem_from_mapping(tomllib.loads(text))
    settings = uncertainty_settings(tomllib.loads(text)["uncertainty"])
    stacked = single = 0.0
    for x in xs:
        state = nominal_analysis(problem.decode(x))
        modal = uncertainty_model(state, settings).modal_only()
        u = sobol_points(modal.dimension, settings.samples, settings.replicates, settings.seed)
        inertia, link, temperature = _modal_factors(
            modal, modal.values(u.reshape(-1, modal.dimension)), len(state.drive.sprockets))
        link = link * modulus_factors(find_material(state.drive.chain.spec.material),
                                      temperature)
        J, k = batch_system_values(state, inertia, link, temperature)
        system = state.drive_model.system
        c0 = time.process_time()
        batch = batch_elastic_frequencies(system, J, k)
        c1 = time.process_time()
        one = np.array([system.updated(node_inertia_kg_m2=J[i], element_stiffness=k[i])
                        .frequencies_hz()[1:] for i in range(J.shape[0])])
        c2 = time.process_time()
        assert np.allclose(batch, one, rtol=1e-9, atol=0.0)
        stacked, single = stacked + c1 - c0, single + c2 - c1
    return stacked / len(xs), single / len(xs)


def built_and_shared(text: str, xs: list[list[float]], rounds: int = 4
                     ) -> tuple[list[float], list[float]]:
    """CPU time [s] per design of the modal probabilities, each design built from its own
    analysis and through the shared basis, in alternation: ``rounds`` blocks of
    ``len(xs) // rounds`` designs each, the shared bases cleared before every block."""
    problem = problem_from_mapping(tomllib.loads(text))
    settings = uncertainty_settings(tomllib.loads(text)["uncertainty"])
    size = len(xs) // rounds
    built: list[float] = []
    shared: list[float] = []
    for k in range(rounds):
        block = xs[k * size:(k + 1) * size]
        c0 = time.process_time()
        own = []
        for x in block:
            nominal = nominal_analysis(problem.decode(x))
            own.append(reliability(nominal, uncertainty_model(nominal, settings), path="modal"))
        c1 = time.process_time()
        _SHARED_BASES.clear()
        reused = []
        for x in block:
            basis, added = shared_modal_basis(problem.decode(x), settings)
            reused.append(basis_reliability(basis, added))
        c2 = time.process_time()
        for a, b in zip(own, reused, strict=True):
            assert np.allclose(a.values["f1_hz"], b.values["f1_hz"], rtol=1e-9, atol=0.0)
            assert a.checks[0].failures == b.checks[0].failures
        built.append((c1 - c0) / size)
        shared.append((c2 - c1) / size)
    return built, shared


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true", help="1000 designs, 200 for the speed-up")
    parser.add_argument("--designs", type=int, default=10_000)
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--speedup", type=int, default=2_000)
    parser.add_argument("--rounds", type=int, default=4,
                        help="rounds of 100 designs, built and shared in alternation")
    args = parser.parse_args()
    designs = 1_000 if args.quick else args.designs
    speedup = 200 if args.quick else args.speedup
    text = problem_text(args.samples)
    xs = vectors(text, designs)
    states = robust_batch({"problem": text, "vectors": xs[:1]})["designs"][0]["samples"]

    t0, c0 = time.perf_counter(), time.process_time()
    serial = robust_batch({"problem": text, "vectors": xs[:100]})
    rate = 100 / (time.perf_counter() - t0)
    cpu = (time.process_time() - c0) / 100
    p = [d["resonance_probability"] for d in serial["designs"]]
    print(f"in one process: {rate:.0f} designs/s ({states} states each: "
          f"{rate * states:,.0f} modal analyses/s), {load()}")
    print(f"   CPU time per design {cpu * 1e3:.1f} ms: {designs} designs on two free cores "
          f"≈ {designs * cpu / 2:.0f} s of evaluation")
    print(f"   P(resonance margin < 10 %) over the first 100 designs: {min(p):.3f} … "
          f"{max(p):.3f}")

    before = load()
    built, shared = built_and_shared(text, xs[:100 * args.rounds], args.rounds)
    print(f"   CPU per design, in alternation ({args.rounds} rounds of 100): each design built "
          f"{min(built) * 1e3:.1f} ms (median {np.median(built) * 1e3:.1f}), shared basis "
          f"{min(shared) * 1e3:.1f} ms (median {np.median(shared) * 1e3:.1f}) = "
          f"{np.median(built) / np.median(shared):.2f}× (medians); {before} → {load()}")

    stacked, single = frequencies_side_by_side(text, xs[:10])
    print(f"   frequencies of the {states} states, CPU per design: stacked {stacked * 1e3:.1f} ms, "
          f"one by one through the torsional engine {single * 1e3:.1f} ms = "
          f"{single / stacked:.1f}×; {load()}")

    before = load()
    seconds, cpu, main = on_dask(inputs_of(text, xs), 2)
    print(f"{designs} designs × {states} states on 2 Dask workers: {seconds:.1f} s "
          f"({designs * states / seconds:,.0f} modal analyses/s; target < 120 s); "
          f"{before} → {load()}")
    print(f"   CPU time of the workers {cpu:.1f} s ({cpu / designs * 1e3:.1f} ms per design), "
          f"of the scheduler, client and store {main:.1f} s: on two free cores ≈ "
          f"{(cpu + main) / 2:.0f} s")

    sub = inputs_of(text, xs[:speedup])
    times: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(2):
        for workers in (1, 2):
            times[workers].append(on_dask(sub, workers)[0])
    t1, t2 = min(times[1]), min(times[2])
    print(f"speed-up 1 → 2 workers ({speedup} designs): {t1:.1f} s → {t2:.1f} s = "
          f"{t1 / t2:.2f}× (best of 2 rounds in alternation; all {times}); {load()}")


if __name__ == "__main__":
    main()
