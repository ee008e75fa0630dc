"""Coverage of the identification's 95 % intervals over noise seeds: how often each interval
holds the value the record was made with (docs/identification.md §3–4).

Six records, each repeated over noise seeds 0–19 (the signal itself is made once):

* ``sines``: the whole-drive model's first two elastic frequencies at 0.4 × the seed's link
  stiffness as sines with white noise (tests/unit/test_identification_calibration.py) →
  ``calibrate_link_stiffness``;
* ``sag``: a sideways pluck of S2-S3 at a sag of 1.5 % (tests/unit/test_identification_sag_record.py)
  → ``record_peak`` → ``span_tension_reading`` → ``calibrated_sag``;
* ``links-k``: the link-level tap test of the seed at 0.5 × its link stiffness, undamped, 2 s,
  noise a tenth of the RMS (tests/validation/test_identification_linklevel.py) →
  ``calibrate_link_stiffness``;
* ``links-zeta``: the same tap test damped, 0.5 s, noise 1 % of the peak → the logarithmic
  decrement → ``calibrate_damping_ratio``, against the links' ζ_c;
* ``linkmodel-k``: the small tap (0.2 rad/s) of the same drive, undamped, 2 s, noise a tenth
  of the RMS → ``record_peak`` → ``calibrate_link_level`` (the link-level model as the
  forward model) for the link stiffness, from the design's;
* ``linkmodel-sag``: the same small tap at a sag of 1.5 % → ``calibrate_link_level`` for the
  sag, from the design (its 2 % and its link stiffness, twice the record's).

``--only context`` prints what the link-level records are set against: the first elastic
frequency of the whole-drive model at the design's power and at 1 W (the spans at their
standstill tension), and the link-level model's first mode along the chain
(``linear_modes``), over 0.25–2 × the link stiffness.

With n = 20 the exact (Clopper–Pearson [ClopperPearson1934]) 95 % interval of a coverage of
19/20 is 75–99.9 %, of 20/20 83–100 %.

Run: .venv/bin/python benchmarks/bench_identification_coverage.py [--seeds 20] [--only sag]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import time
from collections.abc import Callable

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before NumPy loads BLAS
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np
from scipy.signal import detrend
from scipy.stats import beta
from tests.conftest import EXAMPLES
from tests.unit.test_identification_sag_record import TRUE_SAG as PLUCK_SAG
from tests.unit.test_identification_sag_record import pluck_record
from tests.validation.test_identification_linklevel import (
    K_SCALE,
    SMALL_TAP,
    TRUE_SAG,
    _s3_speed,
)

import chaindrive
from chaindrive.identification import (
    MeasuredDamping,
    calibrated_sag,
    free_decay_damping_ratio,
    record_peak,
    span_tension_reading,
)
from chaindrive.identification.calibration import (
    MeasuredMode,
    calibrate_link_stiffness,
    elastic_frequencies,
    with_chain,
)
from chaindrive.identification.damping import calibrate_damping_ratio
from chaindrive.identification.linklevel_fit import calibrate_link_level
from chaindrive.identification.spectrum import signal_spectrum, spectral_peaks
from chaindrive.io.record import record_from_arrays

Trial = tuple[float, float, float]  # (estimate, low, high)


def clopper_pearson(hits: int, n: int) -> tuple[float, float]:
    """Exact 95 % interval of a binomial proportion [ClopperPearson1934]."""
    lo = 0.0 if hits == 0 else float(beta.ppf(0.025, hits, n - hits + 1))
    hi = 1.0 if hits == n else float(beta.ppf(0.975, hits + 1, n - hits))
    return lo, hi


def sines(drive: chaindrive.Drive, k0: float) -> tuple[float, Callable[[int], Trial]]:
    true = 0.4 * k0
    f_true = elastic_frequencies(with_chain(drive, link_stiffness=true))[:2]
    fs = 1000.0
    t = np.arange(0.0, 20.0, 1.0 / fs)

    def trial(seed: int) -> Trial:
        x = (np.sin(2 * np.pi * f_true[0] * t) + 0.6 * np.sin(2 * np.pi * f_true[1] * t)
             + 0.3 * np.random.default_rng(seed).standard_normal(t.size))
        f, p, nper = signal_spectrum(x, fs)
        peaks = [fp for fp, _l, _p in spectral_peaks(f, p, 15.0)]
        u = fs / nper / (2 * math.sqrt(3))
        cal = calibrate_link_stiffness(drive, [MeasuredMode(k + 1, fp, u)
                                               for k, fp in enumerate(peaks[:2])], initial=k0)
        return cal.stiffness, *cal.interval

    return true, trial


def sag(drive: chaindrive.Drive) -> tuple[float, Callable[[int], Trial]]:
    analysis = chaindrive.analyze(drive, response=False)

    def trial(seed: int) -> Trial:
        peak = record_peak(pluck_record(analysis, TRUE_SAG, seed))
        reading = span_tension_reading(analysis, "S2-S3", peak.frequency,
                                       frequency_tolerance=0.5 * peak.resolution,
                                       length_tolerance=0.0, mass_tolerance=0.0)
        s = calibrated_sag(drive, reading)
        return s.sag, *s.interval

    return PLUCK_SAG, trial


def links_k(drive: chaindrive.Drive, k0: float) -> tuple[float, Callable[[int], Trial]]:
    true = with_chain(drive, link_stiffness=K_SCALE * k0)
    _fs, t, w = _s3_speed(true, 2.0, damping=False)
    x0 = w - w.mean()

    def trial(seed: int) -> Trial:
        x = x0 + 0.1 * float(np.std(x0)) * np.random.default_rng(seed).standard_normal(x0.size)
        peak = record_peak(record_from_arrays("tap", t, {"speed_S3_rad_s": x}))
        cal = calibrate_link_stiffness(
            drive, [MeasuredMode(1, peak.frequency, peak.resolution / (2 * math.sqrt(3)))],
            initial=k0)
        return cal.stiffness, *cal.interval

    return K_SCALE * k0, trial


def links_zeta(drive: chaindrive.Drive, k0: float) -> tuple[float, Callable[[int], Trial]]:
    true = with_chain(drive, link_stiffness=K_SCALE * k0)
    zeta_c = float(np.mean(chaindrive.analyze(true, response=False).dynamics.model
                           .span_damping_ratios))
    fs, _t, w = _s3_speed(true, 0.5, damping=True)
    x0 = detrend(w)
    start = int(0.02 * fs)

    def trial(seed: int) -> Trial:
        x = x0 + 0.01 * float(np.abs(x0).max()) * np.random.default_rng(seed).standard_normal(
            x0.size)
        ratio, std = free_decay_damping_ratio(x[start:], fs, 78.0,
                                              floor=0.05 * float(np.abs(x[start:]).max()))
        fit = calibrate_damping_ratio(true, [MeasuredDamping(1, ratio, std)])
        return fit.ratio, *fit.interval

    return zeta_c, trial


def linkmodel(drive: chaindrive.Drive, k0: float, parameter: str
              ) -> tuple[float, Callable[[int], Trial]]:
    """The small tap fitted with the link-level model (module docstring); prints each
    seed's fit, sensitivity and CPU."""
    known = with_chain(drive, link_stiffness=K_SCALE * k0)
    true_value = K_SCALE * k0 if parameter == "link_stiffness" else TRUE_SAG
    _fs, t, w = _s3_speed(known if parameter == "link_stiffness" else with_chain(known, sag=TRUE_SAG),
                          2.0, damping=False, tap=SMALL_TAP)
    x0 = w - w.mean()

    def trial(seed: int) -> Trial:
        x = x0 + 0.1 * float(np.std(x0)) * np.random.default_rng(seed).standard_normal(x0.size)
        peak = record_peak(record_from_arrays("tap", t, {"speed_S3_rad_s": x}))
        cpu = time.process_time()
        cal = calibrate_link_level(
            drive, [MeasuredMode(1, peak.frequency, peak.resolution / (2 * math.sqrt(3)))],
            parameter="sag" if parameter == "sag" else "link_stiffness")
        print(f"  seed {seed}: peak {peak.frequency:.3f} Hz; fitted {cal.value:.5g} "
              f"({cal.interval[0]:.4g} … {cal.interval[1]:.4g}, ratio {cal.interval_ratio:.3g}); "
              f"d ln f/d ln x {cal.sensitivities[0]:.4f}; {cal.evaluations} runs; "
              f"CPU {time.process_time() - cpu:.1f} s", flush=True)
        return cal.value, *cal.interval

    return true_value, trial


def context(drive: chaindrive.Drive, k0: float) -> None:
    """The whole-drive and link-level first frequencies over the link stiffness (docstring)."""
    from chaindrive.linklevel.modes import linear_modes

    for scale in (0.25, 0.5, 1.0, 2.0):
        d = with_chain(drive, link_stiffness=scale * k0)
        running = elastic_frequencies(d)[0]
        still = elastic_frequencies(dataclasses.replace(d, power=1.0))[0]
        links = linear_modes(d, count=200).first_longitudinal_hz
        print(f"k = {scale:g} x design: whole drive f1 {running:.2f} Hz at {drive.power:g} W, "
              f"{still:.2f} Hz at 1 W; link level (linearised, at rest) {links:.2f} Hz",
              flush=True)
    # the tap test's decay (read as the test reads it, no noise) with the dampers one by one
    from chaindrive.geometry.contour import contour_geometry
    from chaindrive.linklevel import simulate
    from chaindrive.linklevel.equilibrium import installed_geometry
    from chaindrive.linklevel.model import build_model

    true = with_chain(drive, link_stiffness=K_SCALE * k0)
    geometry = installed_geometry(true, contour_geometry(true))[0]
    for label, hinge, contact, damped in (
            ("every damper (links, contacts, hinge friction 0.1)", 0.1, 0.06, True),
            ("links and contacts, no hinge friction", 0.0, 0.06, True),
            ("links only", 0.0, 0.0, True), ("none (undamped)", 0.0, 0.0, False)):
        model = build_model(true, geometry, hinge_friction=hinge, contact_damping_ratio=contact)
        run = simulate(true, 0.5, model=model, motor=False, initial_speed="rest",
                       damping=damped, kick_rad_s=[0.0, 0.0, 1.0], sample_rate_hz=4000.0)
        names, table = run.history()
        fs = 1.0 / float(np.median(np.diff(table[:, 0])))
        x = detrend(table[:, names.index("speed_S3_rad_s")])[int(0.02 * fs):]
        ratio, std = free_decay_damping_ratio(x, fs, 78.0, floor=0.05 * float(np.abs(x).max()))
        print(f"tap-test decay, {label}: zeta = {ratio:.4f} +- {std:.4f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--only", choices=["sines", "sag", "links-k", "links-zeta",
                                           "linkmodel-k", "linkmodel-sag", "context"])
    args = parser.parse_args()
    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    k0 = chaindrive.analyze(drive, response=False).ring_parameters.link_stiffness_n_per_m
    if args.only == "context":
        context(drive, k0)
        return
    cases: dict[str, Callable[[], tuple[float, Callable[[int], Trial]]]] = {
        "sines": lambda: sines(drive, k0), "sag": lambda: sag(drive),
        "links-k": lambda: links_k(drive, k0), "links-zeta": lambda: links_zeta(drive, k0),
        "linkmodel-k": lambda: linkmodel(drive, k0, "link_stiffness"),
        "linkmodel-sag": lambda: linkmodel(drive, k0, "sag")}
    for name, make in cases.items():
        if args.only and name != args.only:
            continue
        cpu = time.process_time()
        true, trial = make()
        runs = [trial(s) for s in range(args.seeds)]
        hits = sum(lo < true < hi for _e, lo, hi in runs)
        est = np.array([e for e, _lo, _hi in runs]) / true
        width = np.array([(hi - lo) / true for _e, lo, hi in runs])
        lo_c, hi_c = clopper_pearson(hits, args.seeds)
        print(f"{name}: true {true:.6g}; held {hits}/{args.seeds} ({100 * hits / args.seeds:.0f} "
              f"%, 95 % CI {100 * lo_c:.0f}–{100 * hi_c:.0f} %); estimate/true "
              f"{est.min():.4f}–{est.max():.4f} (median {np.median(est):.4f}); interval "
              f"width/true median {np.median(width):.4f}; CPU {time.process_time() - cpu:.1f} s",
              flush=True)


if __name__ == "__main__":
    main()
