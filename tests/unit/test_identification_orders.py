"""Order tracking of a run-up record ([Brandt2011]) and the half-power damping ratio of each
peak ([Ewins2000, ch. 4]), on records whose answers are known in closed form.

Run-up: the seed drive's driver (z₁ = 15) runs up linearly from 100 to 250 rpm in 12 s,
θ(t) = 2π(n₀t + (n₁ − n₀)t²/(2T)); the record holds the tooth order sin(15 θ), a line at the
fixed frequency 73.06 Hz (the model's mode 1) and white noise. The tooth order is one line at
order 15 in the order spectrum; the fixed line sits at f = 73.06 Hz in every slice of the
run-up map, at the order f·60/n for the slice's speed n [rpm], and spreads in the order
spectrum over 73.06·60/250 … 73.06·60/100 = 17.5 … 43.8.

Damping: a single mode of known ζ driven by white noise, made by the exact discrete-time
resonator whose poles are e^{s Δt}, s = −ζω ± iω sqrt(1 − ζ²) (impulse invariance).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import lfilter

import chaindrive
from chaindrive.analysis import Analysis
from chaindrive.errors import DesignError
from chaindrive.identification.orders import angle_from_tacho, identify_record, track_orders
from chaindrive.identification.spectrum import HALF_POWER_BINS, peak_damping_ratio
from chaindrive.io.record import Record, record_from_arrays, speed_unit, take_column
from tests.conftest import EXAMPLES

FS, T = 2000.0, 12.0
N0, N1 = 100.0 / 60.0, 250.0 / 60.0       # driver speed [rev/s]
FIXED = 73.06                              # a fixed-frequency line [Hz]


@pytest.fixture(scope="module")
def seed() -> Analysis:
    return chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                              response=False)


def _runup() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    t = np.arange(int(FS * T)) / FS
    n = N0 + (N1 - N0) * t / T
    theta = 2 * math.pi * (N0 * t + (N1 - N0) * t**2 / (2 * T))
    rng = np.random.default_rng(1)
    x = (np.sin(15 * theta) + 0.5 * np.sin(2 * math.pi * FIXED * t)
         + 0.05 * rng.standard_normal(t.size))
    return t, n, theta, x


def test_the_tooth_order_is_one_line_and_a_fixed_frequency_crosses_the_orders(
        seed: Analysis) -> None:
    t, n, _, x = _runup()
    result = track_orders(record_from_arrays("runup", t, {"a": x}), seed, "speed_rpm",
                          speed=2 * math.pi * n)
    assert result.speed_range_rpm == pytest.approx((100.0, 250.0), abs=0.1)
    sig = result.signals[0]
    tooth = [p for p in sig.peaks if p.line is not None]
    assert [p.line.label for p in tooth if p.line] == ["tooth x1"]
    assert abs(tooth[0].order - 15.0) < sig.resolution
    # the fixed line's energy lies at 73.06·60/n over the speeds, not at a shaft order
    others = [p for p in sig.peaks if p.line is None]
    assert others and all(FIXED / N1 <= p.order <= FIXED / N0 for p in others)
    assert all("mode 1" in p.swept for p in others)
    # the run-up map: in every slice the fixed line at 73.06 Hz (order 73.06·60/rpm) and
    # the tooth order at 15·rpm/60
    slices = sorted({p.speed_rpm for p in result.points})
    assert len(slices) >= 16
    df = result.slice_resolution
    for rpm in slices:
        here = [p for p in result.points if p.speed_rpm == rpm]
        fixed = [p for p in here if abs(p.frequency - FIXED) < df]
        assert len(fixed) == 1
        assert fixed[0].order == pytest.approx(FIXED * 60.0 / rpm, abs=df * 60.0 / rpm)
        assert fixed[0].line is not None and "mode 1" in (
            [fixed[0].line.label] + [a.label for a in fixed[0].also])
        # the slice is 0.512 s long: the speed moves by 6.4 rpm in it, the tooth line by 1.6 Hz
        teeth = [p for p in here if p.line is not None and p.line.label == "tooth x1"]
        assert len(teeth) == 1
        assert teeth[0].frequency == pytest.approx(15.0 * rpm / 60.0, abs=df)


def test_a_tacho_gives_the_angle_of_a_speed_signal(seed: Analysis) -> None:
    t, n, theta, x = _runup()
    pulses = (np.sin(theta) > 0).astype(float)           # one pulse per revolution
    angle, speed = angle_from_tacho(pulses, FS, 1)
    known = np.isfinite(angle)
    # the monotone cubic through one point per revolution follows ω within 0.3 % of n₀
    assert np.max(np.abs(speed[known] - 2 * math.pi * n[known])) < 0.003 * 2 * math.pi * N0
    result = track_orders(record_from_arrays("runup", t, {"a": x}), seed, "tacho",
                          speed=speed, angle=angle)
    sig = result.signals[0]
    tooth = [p for p in sig.peaks if p.line is not None and p.line.label == "tooth x1"]
    assert len(tooth) == 1 and abs(tooth[0].order - 15.0) < sig.resolution


def test_a_speed_column_names_its_unit() -> None:
    assert speed_unit("speed_rpm") == pytest.approx(2 * math.pi / 60)
    assert speed_unit("n [rpm]") == pytest.approx(2 * math.pi / 60)
    assert speed_unit("omega_rad_s") == 1.0
    assert speed_unit("n_hz") == pytest.approx(2 * math.pi)
    with pytest.raises(DesignError, match="names no unit"):
        speed_unit("speed")
    rec = Record("r", 100.0, {"speed_rpm": np.ones(64), "a": np.zeros(64)})
    rest, values = take_column(rec, "speed_rpm", "--speed")
    assert list(rest.signals) == ["a"] and values.size == 64
    with pytest.raises(DesignError, match="no column 'n'"):
        take_column(rec, "n", "--speed")


def test_a_record_that_does_not_turn_is_refused(seed: Analysis) -> None:
    t = np.arange(4000) / FS
    with pytest.raises(DesignError, match="does not turn"):
        track_orders(record_from_arrays("r", t, {"a": np.sin(t)}), seed, "speed_rpm",
                     speed=np.zeros(t.size))


def _single_mode(zeta: float, fn: float, fs: float, seconds: float, seed: int) -> np.ndarray:
    w, dt = 2 * math.pi * fn, 1.0 / fs
    a = math.exp(-zeta * w * dt)
    wd = w * math.sqrt(1 - zeta**2)
    drive = np.random.default_rng(seed).standard_normal(int(seconds * fs))
    return np.asarray(lfilter([1.0], [1.0, -2 * a * math.cos(wd * dt), a * a], drive))


@pytest.mark.parametrize("zeta", [0.05, 0.1])
def test_the_half_power_ratio_of_a_single_mode(zeta: float) -> None:
    # 80 s at 1 kHz: over seeds 0-7 the reading scattered by 5-8 % (one standard deviation)
    # about the true ζ, its mean within 3 %
    ratio, bins, why = peak_damping_ratio(_single_mode(zeta, 50.0, 1000.0, 80.0, 3), 1000.0,
                                          50.0)
    assert why is None and ratio is not None and bins is not None
    assert ratio == pytest.approx(zeta, rel=0.2)
    assert bins >= HALF_POWER_BINS * 0.5


def test_the_half_power_ratio_is_unbiased_over_noise_seeds() -> None:
    # ζ = 0.05 at 50 Hz, 80 s at 1 kHz, seeds 0-7: 7 are read (mean +0.5 %, scatter 4.7 %);
    # one is refused: its band fell below 8 bins at 2048 samples and narrower still at 4096,
    # and a finer segment would average fewer than 16
    readings = [peak_damping_ratio(_single_mode(0.05, 50.0, 1000.0, 80.0, s), 1000.0, 50.0)[0]
                for s in range(8)]
    read = [r for r in readings if r is not None]
    assert len(read) >= 6
    assert float(np.mean(read)) == pytest.approx(0.05, rel=0.05)


def test_a_forced_line_has_no_damping_ratio() -> None:
    fs = 1000.0
    t = np.arange(int(8 * fs)) / fs
    x = np.sin(2 * math.pi * 75.0 * t) + 0.01 * np.random.default_rng(0).standard_normal(t.size)
    ratio, bins, why = peak_damping_ratio(x, fs, 75.0)
    assert ratio is None and why is not None and "too few bins" not in why
    assert "needed" in why and bins is not None and bins < HALF_POWER_BINS


def test_a_tacho_column_and_a_swept_peak_through_the_entry_point(seed: Analysis) -> None:
    t, _, theta, x = _runup()
    record = record_from_arrays("runup", t, {"tacho": (np.sin(2 * theta) > 0).astype(float),
                                             "a": x})
    result = identify_record(record, seed, tacho="tacho", pulses_per_revolution=2)
    assert [s.name for s in result.spectrum.signals] == ["a"]   # the tacho is no signal
    assert result.orders is not None
    sig = result.orders.signals[0]
    assert any(p.line is not None and p.line.label == "tooth x1"
               and abs(p.order - 15.0) < sig.resolution for p in sig.peaks)
    # the frequency spectrum's peaks inside the tooth order's sweep 15·(100 … 250)/60 Hz
    # = 25 … 62.5 Hz carry no half-power ratio: their width is the sweep's
    swept = [p for p in result.spectrum.signals[0].peaks if 25.0 <= p.frequency <= 62.5]
    assert swept and all(p.damping_ratio is None for p in swept)
    with pytest.raises(DesignError, match="not both"):
        identify_record(record, seed, speed="tacho", tacho="tacho")
