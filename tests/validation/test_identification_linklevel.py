"""Records of the link-level model identified by the whole-drive calibration.

The seed drive is built at half its link stiffness (k_link = 0.5 × 5.104e8 N/m) and run at
the level of its links (every roller a body, gravity on, from its static state at the
installed pre-tension; docs/linklevel.md) with no motor and no machine loads, the small
sprocket S3 given 1 rad/s at t = 0: a tap test of a stationary drive. Its speed record, with
white noise of a stated seed added, is read as a measured one: the most prominent peak of
its Welch spectrum ([Welch1967]) located to ± half a bin (u = Δf/(2√3), [JCGM100, §4.3.7]),
labelled the first elastic mode, and the whole-drive model's link stiffness fitted to it
(``calibrate_link_stiffness``: ``least_squares``, (JᵀJ)⁻¹ [Virtanen2020]). A damped run's
free decay gives the mode's damping ratio (logarithmic decrement [Inman2014, ch. 1]), to
which the chain's damping ratio is fitted (``calibrate_damping_ratio``).

Neither is recovered within its interval: the whole-drive fit of the stiffness lands 3.6 ×
the truth (a measured fact, tested as such), and the damping ratio's requirement stays an
``xfail(strict=True)`` test (should it pass, the strict mark fails it and the docs must be
revised). The link-level model's first mode along the chain rests on the pre-tension, not on
the links' elasticity: by Rayleigh's quotient the sensitivity of its frequency to the link
stiffness is d ln f/d ln k = e/2 [FoxKapoor1968], e the share of the mode's strain energy
stored in stretching the links, and the links' dampers c = β k_link, β = 2ζ_c/ω_ref, give it
ζ = βω e/2 = ζ_c (ω/ω_ref) e (proportional damping, ζ = βω/2 [Inman2014, ch. 4], on the
links' share of the stiffness). The tests below measure e (about 2 %), check the sensitivity against
it, and that the frequency moves with the pre-tension instead (docs/identification.md §4).

Fitted with the model that made the record — the link-level model linearised about its static
state (``calibrate_link_level``) — a small tap (0.2 rad/s, where the run rings within 0.3 %
of the linearisation) gives the link stiffness inside its 95 % interval, an interval that
spans a factor of thousands and is flagged as poorly identified, and the installed sag
(a record at 1.5 %, the design's 2 %) inside an interval ±9 % wide.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest
from scipy.linalg import eigh
from scipy.signal import detrend

import chaindrive
from chaindrive.geometry.contour import contour_geometry
from chaindrive.identification import MeasuredDamping, free_decay_damping_ratio, record_peak
from chaindrive.identification.calibration import (
    MeasuredMode,
    calibrate_link_stiffness,
    elastic_frequencies,
    with_link_stiffness,
)
from chaindrive.identification.damping import calibrate_damping_ratio
from chaindrive.identification.linklevel_fit import (
    POORLY_IDENTIFIED_RATIO,
    calibrate_link_level,
    with_sag,
)
from chaindrive.io.record import record_from_arrays
from chaindrive.linklevel import simulate
from chaindrive.linklevel.equilibrium import Balance, installed_geometry, kernel_tables
from chaindrive.linklevel.model import build_model
from chaindrive.linklevel.simulate import COURANT, equilibrium_state
from tests.conftest import EXAMPLES

#: The link stiffness the records are made with, as a fraction of the design's [-].
K_SCALE = 0.5
#: Seed of the white noise added to the records.
NOISE_SEED = 7
#: Speed given to S3 at t = 0 [rad/s] (the tap).
TAP = 1.0
#: Sample rate of the records [Hz] (the run records at the nearest whole number of steps).
RATE = 4000.0
#: The small tap of the records fitted with the link-level model [rad/s]: its run rings
#: within 0.3 % of the linearisation (the tap of 1 rad/s, 1.4 % above it).
SMALL_TAP = 0.2
#: The installed sag of the record fitted for the sag (the design's: 2 %) [-].
TRUE_SAG = 0.015


@pytest.fixture(scope="module")
def seed() -> dict[str, Any]:
    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    k0 = chaindrive.analyze(drive, response=False).ring_parameters.link_stiffness_n_per_m
    return {"drive": drive, "k0": k0, "true": with_link_stiffness(drive, K_SCALE * k0)}


def _s3_speed(drive: chaindrive.Drive, duration: float, *, damping: bool, tap: float = TAP
              ) -> tuple[float, np.ndarray[Any, np.dtype[np.float64]],
                         np.ndarray[Any, np.dtype[np.float64]]]:
    """(sample rate [Hz], time [s], S3's speed [rad/s]) of the link-level tap test."""
    run = simulate(drive, duration, motor=False, initial_speed="rest", damping=damping,
                   kick_rad_s=[0.0, 0.0, tap], sample_rate_hz=RATE)
    names, table = run.history()
    t = table[:, 0]
    return 1.0 / float(np.median(np.diff(t))), t, table[:, names.index("speed_S3_rad_s")]


@pytest.fixture(scope="module")
def tap_record(seed: dict[str, Any]) -> dict[str, Any]:
    """2 s of the undamped tap test (no dissipation: a sharp peak), S3's speed with white
    noise of a tenth of its RMS, its most prominent peak."""
    _fs, t, w = _s3_speed(seed["true"], 2.0, damping=False)
    x = w - w.mean()
    x = x + 0.1 * float(np.std(x)) * np.random.default_rng(NOISE_SEED).standard_normal(x.size)
    peak = record_peak(record_from_arrays("tap", t, {"speed_S3_rad_s": x}))
    return {"peak": peak, "std": peak.resolution / (2.0 * math.sqrt(3.0))}


def _linearised(drive: chaindrive.Drive, pretension_scale: float = 1.0) -> dict[str, float]:
    """The link-level model's first mode along the chain about its static state: frequency
    [Hz], e (share of its strain energy ω²·φᵀMφ in the links' stretch Σ k_link (u·Δφ)²),
    and the whole-drive model's reference frequency ω_ref/2π [Hz] the link dampers use."""
    geometry, take_up = installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry)
    model = dataclasses.replace(model, pretension=model.pretension * pretension_scale)
    _, eq = equilibrium_state(drive, geometry, model,
                              COURANT * 2.0 / (2.0 * math.pi * model.highest_frequency_hz),
                              take_up)
    n = model.centres.shape[0]
    x, th = eq.positions, eq.angles[:n].copy()
    N = x.shape[0]
    bal = Balance(model, kernel_tables(model), np.arange(n, dtype=np.int64), N, 0)
    K = -bal.jacobian(x, th, eq.rest_length, bal(x, th, eq.rest_length))[:-1, :-1]
    K = 0.5 * (K + K.T)
    mass = np.concatenate([np.full(2 * N, model.roller_mass),
                           model.inertias / model.pitch_radii ** 2])
    s = 1.0 / np.sqrt(mass)
    lam, vec = eigh(K * s[:, None] * s[None, :], subset_by_index=[0, 199])
    shapes = vec * s[:, None]
    link = np.roll(x, -1, axis=0) - x
    u = link / np.linalg.norm(link, axis=1)[:, None]
    for j in np.flatnonzero(lam > (2.0 * math.pi) ** 2):  # elastic modes (above 1 Hz)
        phi = shapes[:2 * N, j].reshape(N, 2)
        kinetic = float((mass * shapes[:, j] ** 2).sum())
        along = (model.roller_mass * float((np.sum(u * phi, axis=1) ** 2).sum())
                 + float((mass[2 * N:] * shapes[2 * N:, j] ** 2).sum()))
        if along > 0.5 * kinetic:  # more than half its kinetic energy along the chain
            stretch = np.sum(u * (np.roll(phi, -1, axis=0) - phi), axis=1)
            return {"f": math.sqrt(lam[j]) / (2.0 * math.pi),
                    "e": model.link_stiffness * float((stretch ** 2).sum()) / (lam[j] * kinetic),
                    "f_ref": model.reference_frequency_hz}
    raise AssertionError("no mode along the chain among the lowest 200")


@pytest.fixture(scope="module")
def linearised(seed: dict[str, Any]) -> dict[str, dict[str, float]]:
    return {"true": _linearised(seed["true"]), "design": _linearised(seed["drive"]),
            "tight": _linearised(seed["true"], 2.0)}


def test_the_tap_record_rings_at_the_link_level_first_mode_along_the_chain(
        tap_record: dict[str, Any], linearised: dict[str, dict[str, float]]) -> None:
    # the record is read right: its peak is the linearised model's first mode along the
    # chain within a bin (3.8 Hz; the run is not the linearisation: the drive turns slowly
    # under the chain's weight and the tap is of finite size)
    peak = tap_record["peak"]
    assert abs(peak.frequency - linearised["true"]["f"]) < peak.resolution


def test_the_whole_drive_calibration_misses_the_link_level_stiffness(
        seed: dict[str, Any], tap_record: dict[str, Any]) -> None:
    # a measured fact, not the requirement: the whole-drive model's first elastic mode (at
    # the running tensions) is not the tap test's mode; its fit lands 3.65 × the truth and
    # its interval lies wholly above it (docs/identification.md §4)
    m = MeasuredMode(1, tap_record["peak"].frequency, tap_record["std"])
    cal = calibrate_link_stiffness(seed["drive"], [m], initial=seed["k0"])
    true = K_SCALE * seed["k0"]
    assert cal.interval[0] > 2.0 * true
    assert cal.stiffness / true > 3.0


def _small_tap(drive: chaindrive.Drive, seeds: tuple[int, ...]) -> list[MeasuredMode]:
    """2 s of the undamped small tap test, S3's speed with white noise of a tenth of its RMS
    (each seed), its most prominent peak taken as mode 1 ± half a bin (rectangular)."""
    _fs, t, w = _s3_speed(drive, 2.0, damping=False, tap=SMALL_TAP)
    x0 = w - w.mean()
    out = []
    for noise in seeds:
        x = x0 + 0.1 * float(np.std(x0)) * np.random.default_rng(noise).standard_normal(x0.size)
        peak = record_peak(record_from_arrays("tap", t, {"speed_S3_rad_s": x}))
        out.append(MeasuredMode(1, peak.frequency, peak.resolution / (2.0 * math.sqrt(3.0))))
    return out


def test_the_link_level_calibration_holds_the_link_stiffness_in_a_wide_interval(
        seed: dict[str, Any]) -> None:
    # the design (its link stiffness twice the record's) fitted to the record
    (m,) = _small_tap(seed["true"], (NOISE_SEED,))
    cal = calibrate_link_level(seed["drive"], [m], parameter="link_stiffness")
    true = K_SCALE * seed["k0"]
    lo, hi = cal.interval
    assert lo < true < hi
    # the record says little: d ln f/d ln k is below 0.02 (Rayleigh: e/2, e ≈ 1–3 %), so
    # the interval spans far more than a factor 2 and the fit says so
    (slope,) = cal.sensitivities
    assert 0.0 < slope < 0.02
    assert cal.poorly_identified and cal.interval_ratio > 100 * POORLY_IDENTIFIED_RATIO
    # one measurement, not widened: σ(ln k) = u / (f · d ln f/d ln k) [JCGM100, §5.1]
    assert cal.std_log == pytest.approx(m.std / (cal.fitted_frequencies[0] * slope), rel=1e-6)


def test_the_link_level_calibration_recovers_the_sag(seed: dict[str, Any]) -> None:
    # the record at a sag of 1.5 %, fitted from the design (its 2 %, and its link stiffness,
    # twice the record's: the frequency moves by 0.7 % with it, the sag by about 2 %)
    for m in _small_tap(with_sag(seed["true"], TRUE_SAG), (0, NOISE_SEED)):
        cal = calibrate_link_level(seed["drive"], [m], parameter="sag")
        lo, hi = cal.interval
        assert lo < TRUE_SAG < hi
        assert not cal.poorly_identified and cal.interval_ratio < 1.3
        # the mode rests on T₀ ∝ 1/s: d ln f/d ln s ≈ −0.3 (+23 % at 2 T₀ measured)
        assert -0.4 < cal.sensitivities[0] < -0.2


def test_the_link_level_first_mode_stores_little_strain_energy_in_the_links(
        seed: dict[str, Any], linearised: dict[str, dict[str, float]]) -> None:
    half, design = linearised["true"], linearised["design"]
    # e: 2.6 % at half the stiffness, 1.3 % at the design's
    assert half["e"] < 0.05 and design["e"] < 0.05
    # Rayleigh: d ln f / d ln k = e/2 [FoxKapoor1968]; over k → 2k the mean of the two ends
    measured = math.log(design["f"] / half["f"]) / math.log(2.0)
    assert measured == pytest.approx(0.25 * (half["e"] + design["e"]), rel=0.25)
    # while the whole-drive model's first elastic mode moves with k^0.16
    wd = elastic_frequencies(seed["drive"])[0] / elastic_frequencies(seed["true"])[0]
    assert math.log(wd) / math.log(2.0) > 10 * measured
    # and the link-level's moves with the pre-tension: twice T₀ raises it by a fifth
    assert linearised["tight"]["f"] / half["f"] > 1.15


@pytest.fixture(scope="module")
def decay(seed: dict[str, Any]) -> dict[str, float]:
    """The damped tap test (the design's dampers: links, contacts, hinge friction), 0.5 s:
    S3's speed less its linear trend (the drive turning under the chain's weight), white
    noise of 1 % of its largest value; ζ from the maxima above 5 % of it."""
    fs, _t, w = _s3_speed(seed["true"], 0.5, damping=True)
    x = detrend(w)
    x = x + 0.01 * float(np.abs(x).max()) * np.random.default_rng(NOISE_SEED).standard_normal(
        x.size)
    start = int(0.02 * fs)
    ratio, std = free_decay_damping_ratio(x[start:], fs, 78.0,
                                          floor=0.05 * float(np.abs(x[start:]).max()))
    return {"ratio": ratio, "std": std}


@pytest.mark.xfail(strict=True, reason="the links' dampers act on their stretch, which holds "
                   "2.6 % of the first mode's strain energy (docs/identification.md §4)")
def test_the_whole_drive_calibration_recovers_the_link_level_damping_ratio(
        seed: dict[str, Any], decay: dict[str, float]) -> None:
    zeta_links = chaindrive.analyze(seed["true"], response=False).dynamics.model \
        .span_damping_ratios
    fit = calibrate_damping_ratio(seed["true"], [MeasuredDamping(1, decay["ratio"],
                                                                 decay["std"])])
    assert fit.interval[0] < float(np.mean(zeta_links)) < fit.interval[1]


def test_the_link_dampers_give_the_first_mode_a_small_share_of_their_ratio(
        seed: dict[str, Any], linearised: dict[str, dict[str, float]],
        decay: dict[str, float]) -> None:
    # ζ from the links' dampers alone, ζ_c (ω/ω_ref) e: 0.0019 for ζ_c = 0.0633; the decay
    # measured with every damper is larger (hinge friction) but still well below ζ_c
    zeta_c = float(np.mean(chaindrive.analyze(seed["true"], response=False).dynamics.model
                           .span_damping_ratios))
    half = linearised["true"]
    from_links = zeta_c * half["f"] / half["f_ref"] * half["e"]
    assert from_links < 0.1 * zeta_c
    assert from_links < decay["ratio"] < 0.75 * zeta_c
