"""The installed sag recovered within its interval from a noisy record of a sideways pluck.

Forward: a known sag s of the seed drive's slack span S1-S2 (the span the design's sag is
of) gives the chain its pretension F₀ = k_f q g a, k_f = cos ψ/(8s) + |sin ψ|, a and ψ of
S1-S2 ([ChainDesignRU, §8]), which every span carries at rest; the span S2-S3, of length L,
rings sideways at the string's f₁ = (1/2L) sqrt(F₀/q) ([WickertMote1990], v = 0). The
record: a decaying sine at f₁ with white noise of a stated seed. Back: its most prominent
Welch peak ([Welch1967]) ± half a bin (rectangular, [JCGM100, §4.3.7]) → the tension
(``span_tension_reading``, the span's length and mass per metre taken as exact, as the
record was made with them) → the sag
(``calibrated_sag``: the sag of S1-S2 that gives that pretension, its 95 % interval from
T ± 1.96 u(T)).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import DesignError
from chaindrive.identification import (
    calibrated_sag,
    expected_frequency,
    record_peak,
    span_tension_reading,
)
from chaindrive.io.record import Record, record_from_arrays
from chaindrive.strength.loads import sag_span, sag_tension
from tests.conftest import EXAMPLES

#: The sag the record is made with [-] (the design's is 0.02).
TRUE_SAG = 0.015
SPAN = "S2-S3"


@pytest.fixture(scope="module")
def seed() -> dict[str, Any]:
    drive = chaindrive.load(EXAMPLES / "seed_three_sprocket.toml")
    return {"drive": drive, "analysis": chaindrive.analyze(drive, response=False)}


def pluck_record(analysis: chaindrive.Analysis, sag: float, noise_seed: int) -> Record:
    """20 s at 200 Hz of a sideways pluck of S2-S3 at the pretension of the slack span's
    sag: 1 mm decaying at 0.05 /s, white noise of 0.3 mm (seed ``noise_seed``)."""
    sp = analysis.geometry.spans[1]
    slack = sag_span(analysis.drive, analysis.geometry)
    assert (slack.start_name, slack.end_name) == ("S1", "S2")
    q = analysis.drive.chain.spec.mass_per_length
    f0 = sag_tension(q, slack.length, slack.inclination, sag)
    f = expected_frequency(f0, sp.length, q, 1)
    t = np.arange(0.0, 20.0, 1.0 / 200.0)
    x = (1e-3 * np.exp(-0.05 * t) * np.sin(2 * np.pi * f * t)
         + 3e-4 * np.random.default_rng(noise_seed).standard_normal(t.size))
    return record_from_arrays("pluck", t, {"offset_m": x})


def test_a_known_sag_is_recovered_within_its_interval_from_a_noisy_pluck(
        seed: dict[str, Any]) -> None:
    analysis = seed["analysis"]
    peak = record_peak(pluck_record(analysis, TRUE_SAG, 1))
    assert peak.signal == "offset_m"
    reading = span_tension_reading(analysis, SPAN, peak.frequency,
                                   frequency_tolerance=0.5 * peak.resolution,
                                   length_tolerance=0.0, mass_tolerance=0.0)
    sag = calibrated_sag(seed["drive"], reading)
    lo, hi = sag.interval
    assert lo < TRUE_SAG < hi
    assert sag.sag == pytest.approx(TRUE_SAG, rel=0.03)
    assert sag.drive.chain.sag == pytest.approx(sag.sag)
    # the interval is the frequency's half bin (0.098 Hz of 5.48 Hz) carried to s ∝ 1/T ∝ 1/f²
    assert hi / lo == pytest.approx(
        (1 + 1.96 * 2 * 0.5 * peak.resolution / 3 ** 0.5 / peak.frequency)
        / (1 - 1.96 * 2 * 0.5 * peak.resolution / 3 ** 0.5 / peak.frequency), rel=0.02)


def test_a_record_without_a_peak_is_refused() -> None:
    t = np.arange(0.0, 2.0, 1e-3)
    flat = record_from_arrays("flat", t, {"offset_m": np.zeros(t.size)})
    with pytest.raises(DesignError, match="no peak 15 dB above its surroundings"):
        record_peak(flat)
