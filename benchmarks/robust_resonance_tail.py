"""Where the long tails of a robust study's metrics come from: the figures of docs/robust.md
("Why the seed's K_D, k₂ and f₁ indices converge slowly").

Reads the states that ``benchmarks/robust_sobol_convergence.py`` stored (``--store``), rebuilds
the example's uncertainty model and Saltelli design (same seed, same rows) and prints:

* the nominal drive: f₁, the tooth frequency f_z = z₁n₁ of the working speed, their
  detuning and K_D;
* every metric's distribution over the states (median, 99th percentile, largest, kurtosis)
  and the share of its sum of squared deviations Σ(y − ȳ)² held by the 1 % and 0.1 % of the
  states farthest from the mean (what Jansen's S_T estimator averages, SALib's and the
  package's before Janon et al.'s);
* the states with the largest K_D: f₁, f₂, life fraction, elongation, sag ratio;
* how many states lie within 5 % and 10 % of f_z, and how early in the life;
* the leading S_T of K_D, k₂ and f₁ at the full N with the base points whose block holds a
  state within 10 % of f_z left out (an illustration of where the width comes from, not a
  method: it changes the question);
* a sweep of the life fraction of the state with the largest K_D in steps of 0.001 (the
  resolution check of a sharp peak) and the largest step of K_D on it;
* K_D of the six largest states re-evaluated with 4096 samples per tooth period instead of
  the analysis's 128;
* with ``--delta``, Borgonovo's moment-independent δ of K_D for every variable (SALib's
  given-data estimator on the design's A and B rows, 30 bootstrap resamples): a variable that
  does not enter K_D (the eccentricities: their S_T is 0) shows the estimator's bias floor.

    python benchmarks/robust_resonance_tail.py seed_three_sprocket /tmp/seed.pkl --plot out.png
"""

from __future__ import annotations

import argparse
import math
import pickle
import tomllib
from pathlib import Path

import numpy as np
from SALib.sample import sobol as sobol_sample
from scipy.stats import kurtosis

from chaindrive import examples
from chaindrive.dynamics.frequency.response import drive_steady
from chaindrive.io.design import drive_from_mapping
from chaindrive.robust.analysis import PerturbedAnalysis
from chaindrive.robust.sampling import StateOutcome, state_outcome
from chaindrive.robust.sensitivity import SENSITIVITY_METRICS, _analyse, _saltelli_problem
from chaindrive.robust.study import nominal_analysis
from chaindrive.robust.uncertainty import UncertaintyModel, uncertainty_model, uncertainty_settings
from chaindrive.units import TWO_PI


def state(nominal: object, model: UncertaintyModel, row: np.ndarray) -> PerturbedAnalysis:
    """The analysis of one variable row."""
    return PerturbedAnalysis(nominal, model.perturbation(row),  # type: ignore[arg-type]
                             allowable_elongation=model.allowable_elongation,
                             take_up_capacity=model.take_up_capacity, response=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("example", help="a bundled example's name")
    parser.add_argument("store", type=Path, help="pickle of robust_sobol_convergence.py")
    parser.add_argument("--plot", type=Path, default=None, help="PNG of K_D and f₁")
    parser.add_argument("--delta", action="store_true", help="Borgonovo's δ of K_D")
    a = parser.parse_args()

    d = pickle.loads(a.store.read_bytes())
    out = [StateOutcome.from_dict(o) for o in d["outcomes"]]
    data = tomllib.loads(examples.text(a.example))
    nominal = nominal_analysis(drive_from_mapping(data))
    model = uncertainty_model(nominal, uncertainty_settings(data.get("uncertainty")))
    n_max = len(out) // (len(model.groups) + 2)
    u = sobol_sample.sample(_saltelli_problem(model), n_max, calc_second_order=False,
                            seed=model.settings.seed)[:len(out)]
    x = model.values(u)
    wear = [v.group for v in model.variables].index("wear")
    life = u[:, wear]
    metrics = {k: np.array([o.metrics.get(k, math.nan) for o in out])
               for k in (*SENSITIVITY_METRICS, "sag_ratio", "elongation")}

    steady = nominal.steady
    assert steady is not None
    f_z = steady.tooth_angular_frequency / TWO_PI
    f1_nom = float(nominal.dynamics.modal.elastic_frequencies_hz[0])
    print(f"nominal: f1 {f1_nom:.2f} Hz, tooth frequency {f_z:.2f} Hz, detuning "
          f"{100 * abs(f_z / f1_nom - 1):.2f} %, K_D {steady.coefficient_of_dynamics:.3f}")

    print(f"\n{len(out)} states: metric, median, p99, largest, smallest, excess kurtosis, "
          "share of the sum of squares in the farthest 1 % / 0.1 %")
    for k in SENSITIVITY_METRICS:
        y = metrics[k]
        dev = (y - y.mean()) ** 2
        share = [dev[dev >= np.percentile(dev, q)].sum() / dev.sum() for q in (99, 99.9)]
        print(f"  {k:26s} {np.median(y):8.3f} {np.percentile(y, 99):8.3f} {y.max():8.3f} "
              f"{y.min():8.3f} {kurtosis(y):7.1f}   {100 * share[0]:.0f} % / "
              f"{100 * share[1]:.0f} %")

    kd, f1 = metrics["coefficient_of_dynamics"], metrics["f1_hz"]
    for band in (0.05, 0.10):
        near = np.abs(f1 / f_z - 1) < band
        print(f"\nstates with f1 within {100 * band:.0f} % of f_z: {near.sum()} "
              f"({100 * near.mean():.2f} %); life fraction ≤ {life[near].max():.4f}, "
              f"elongation ≤ {metrics['elongation'][near].max():.5f}")

    per = len(model.groups) + 2
    near = (np.abs(f1 / f_z - 1) < 0.10)[:n_max * per].reshape(n_max, per).any(axis=1)
    rows = (np.flatnonzero(~near)[:, None] * per + np.arange(per)).ravel()
    keep = _analyse(_saltelli_problem(model), {k: [metrics[k][rows]] for k in
                    ("coefficient_of_dynamics", "k2", "f1_hz")}, 0.95, 0)
    print(f"\nwithout the {near.sum()} of {n_max} base points whose block has a state within "
          "10 % of f_z (illustration only), leading S_T:")
    for k, r in keep.items():
        j = int(np.argmax(r[1]))
        print(f"  {k:26s} {model.groups[j]} {r[1][j]:.3f} ± {r[3][j]:.3f}")

    top = np.argsort(kd)[::-1][:8]
    print("\nlargest K_D: row, K_D, k2, f1, f2, life fraction, elongation, sag ratio")
    for i in top:
        f = state(nominal, model, x[i]).dynamics.modal.elastic_frequencies_hz
        print(f"  {i:5d} {kd[i]:6.3f} {metrics['k2'][i]:6.1f} {f1[i]:6.2f} {f[1]:6.1f} "
              f"{life[i]:.4f} {metrics['elongation'][i]:.5f} {metrics['sag_ratio'][i]:.4f}")

    i0 = int(top[0])
    print(f"\nsweep of the life fraction of row {i0} (other variables kept):")
    sweep = []
    for lam in np.concatenate([np.linspace(0.0, 0.03, 31), [0.05, 0.1, 0.3, 0.6, 1.0]]):
        q = u[i0].copy()
        q[wear] = max(lam, 1e-9)
        m = state_outcome(state(nominal, model, model.values(q[None])[0])).metrics
        sweep.append((lam, m))
        print(f"  life {lam:.3f} ε {m['elongation']:.5f} sag {m['sag_ratio']:.4f} "
              f"f1 {m['f1_hz']:6.2f} K_D {m['coefficient_of_dynamics']:.3f} "
              f"k2 {m['k2']:6.1f} margin {m['resonance_margin_percent']:5.2f} %")
    fine = [m["coefficient_of_dynamics"] for lam, m in sweep[:31]]
    print(f"  largest step of K_D over the 0.001 steps: {np.abs(np.diff(fine)).max():.3f}")

    print("\nK_D at 128 and 4096 samples per tooth period:")
    for i in top[:6]:
        s = state(nominal, model, x[i])
        st = s._static
        assert s.steady is not None and st is not None and s.afc is not None
        fine_kd = drive_steady(s.drive_model, s._excitation, samples=4096,
                               nominal_force=s._nominal_force,
                               breaking_load=s.drive.chain.spec.breaking_load,
                               operating_forces=st.loads.span_tensions,
                               resonance_loads=s.afc.max_span_load).coefficient_of_dynamics
        print(f"  {i:5d} {s.steady.coefficient_of_dynamics:.4f} {fine_kd:.4f}")

    if a.delta:
        import warnings

        from SALib.analyze import delta
        rows = np.concatenate([np.arange(0, len(out), per), np.arange(per - 1, len(out), per)])
        plain = {"num_vars": model.dimension, "names": [v.name for v in model.variables],
                 "bounds": [[0.0, 1.0]] * model.dimension}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = delta.analyze(plain, u[rows], kd[rows], num_resamples=30, seed=1)
        print(f"\nBorgonovo's δ of K_D on {len(rows)} points (balanced estimate ± 95 %):")
        for k, v in enumerate(model.variables):
            print(f"  {v.name:18s} {r['delta_balanced'][k]:.3f} ± "
                  f"{r['delta_balanced_conf'][k]:.3f}")

    if a.plot is not None:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
        ax[0].scatter(metrics["elongation"] * 100, kd, s=2)
        ax[0].set(xscale="log", xlabel="chain elongation ε [%]", ylabel="K_D [–]",
                  title=f"K_D of the {len(out)} states over the wear")
        ax[1].scatter(f1, kd, s=2, label="states")
        ax[1].axvline(f_z, color="C3", lw=1, label=f"tooth frequency {f_z:.0f} Hz")
        ax[1].axvline(f1_nom, color="C2", lw=1, ls="--", label=f"f₁ as drawn {f1_nom:.1f} Hz")
        ax[1].set(xlabel="f₁ [Hz]", ylabel="K_D [–]", title="K_D against f₁")
        ax[1].legend(loc="upper left", fontsize=8)
        fig.savefig(a.plot, dpi=90)
        print(f"\nwrote {a.plot}")


if __name__ == "__main__":
    main()
