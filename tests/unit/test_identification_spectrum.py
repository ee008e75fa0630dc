"""A measured record matched to the model: records synthesised from the model's own
frequencies (sines at known frequencies plus white noise) are labelled by the lines they were
made from; a sine at no line is "unexplained"; bad records are refused by name.

The spectrum is Welch's ([Welch1967]); a sine at f shows its peak within one bin of f."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import chaindrive
from chaindrive.errors import DesignError
from chaindrive.identification import identify, model_lines
from chaindrive.identification.spectrum import ModelLine, label_peak, segment_length
from chaindrive.io.record import MIN_SAMPLES, read_record, record_from_arrays
from tests.conftest import EXAMPLES


@pytest.fixture(scope="module")
def lines() -> tuple[ModelLine, ...]:
    return model_lines(chaindrive.analyze(chaindrive.load(EXAMPLES / "seed_three_sprocket.toml"),
                                          response=False))


def _line(lines: tuple[ModelLine, ...], label: str) -> ModelLine:
    return next(ln for ln in lines if ln.label == label)


def test_a_record_made_of_model_lines_is_labelled_by_them(lines: tuple[ModelLine, ...]) -> None:
    fs = 1000.0
    t = np.arange(0.0, 20.0, 1.0 / fs)
    rng = np.random.default_rng(7)
    made = {"mode 2": 1.0, "tooth x2": 0.5, "span S1-S2 n=3": 0.4}
    x = sum(a * np.sin(2 * np.pi * _line(lines, k).frequency * t) for k, a in made.items())
    x = x + 0.4 * np.sin(2 * np.pi * 41.3 * t) + 0.2 * rng.standard_normal(t.size)
    result = identify(record_from_arrays("synthetic", t, {"a": np.asarray(x)}), lines)
    sig = result.signals[0]
    assert sig.resolution == pytest.approx(fs / segment_length(t.size))
    got = {p.line.label if p.line else "unexplained": p for p in sig.peaks}
    assert set(got) == {*made, "unexplained"}
    for label in made:
        assert abs(got[label].frequency - _line(lines, label).frequency) < sig.resolution
    assert abs(got["unexplained"].frequency - 41.3) < sig.resolution
    # mode 3 and above lie beyond 500 Hz: named as not seen
    assert "mode 3" in result.notes[0]


def test_the_labelling_rule() -> None:
    lines = (ModelLine("natural", "mode 1", 100.0), ModelLine("tooth", "tooth x1", 103.0))
    line, dev, also = label_peak(102.0, lines, 0.05, 0.1)
    assert line is not None and line.label == "tooth x1"   # the nearer
    assert dev == pytest.approx(-1.0 / 103.0)
    assert [a.label for a in also] == ["mode 1"]            # also within 5 %
    assert label_peak(110.0, lines, 0.05, 0.1)[0] is None    # 6.8 % from the nearest
    # one bin is the floor of the tolerance
    assert label_peak(106.0, lines, 0.01, 3.5)[0] is not None


def _csv(path: Path, header: str, rows: list[str]) -> Path:
    path.write_text(header + "\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


def _good_rows(n: int = MIN_SAMPLES, dt: float = 0.001) -> list[str]:
    return [f"{k * dt!r},{float(np.sin(k))!r}" for k in range(n)]


def test_a_csv_record_reads_its_time_unit(tmp_path: Path) -> None:
    rec = read_record(_csv(tmp_path / "r.csv", "time_ms,force_n",
                           [f"{k * 2},{k}" for k in range(MIN_SAMPLES)]))
    assert rec.sample_rate == pytest.approx(500.0)
    assert list(rec.signals) == ["force_n"]


@pytest.mark.parametrize(("header", "rows", "field", "words"), [
    ("time,a", _good_rows(), "--record", "no time column"),
    ("t_s,a", _good_rows(MIN_SAMPLES - 1), "--record.t_s", f"allowed: at least {MIN_SAMPLES}"),
    ("time_s,a", [*_good_rows()[:10], "0.005,1.0", *_good_rows()[11:]], "--record.time_s",
     "not increasing at sample 11 (0.005 s after 0.009 s)"),
    ("time_s,a", [*_good_rows()[:10], "0.0105,1.0", *_good_rows()[11:]], "--record.time_s",
     "uneven step"),
    ("time_s,a", [*_good_rows()[:10], "0.010,abc", *_good_rows()[11:]], "--record.a",
     "'abc' at row 12 is not a number"),
    ("time_s", _good_rows(), "--record", "no signal column"),
])
def test_a_bad_record_is_refused_by_name(tmp_path: Path, header: str, rows: list[str],
                                         field: str, words: str) -> None:
    if header == "time_s":
        rows = [r.split(",")[0] for r in rows]
    with pytest.raises(DesignError) as err:
        read_record(_csv(tmp_path / "r.csv", header, rows))
    assert err.value.field == field and words in str(err.value)


def test_a_wav_record_keeps_its_sample_rate(tmp_path: Path) -> None:
    from scipy.io import wavfile

    data = (1000 * np.sin(np.arange(4096) * 0.3)).astype(np.int16)
    wavfile.write(tmp_path / "r.wav", 8000, np.c_[data, data])
    rec = read_record(tmp_path / "r.wav")
    assert rec.sample_rate == pytest.approx(8000.0)
    assert list(rec.signals) == ["channel_1", "channel_2"]


def test_tolerance_and_prominence_are_checked(lines: tuple[ModelLine, ...]) -> None:
    t = np.arange(256) / 100.0
    rec = record_from_arrays("r", t, {"a": np.sin(t)})
    with pytest.raises(DesignError, match="--tolerance"):
        identify(rec, lines, tolerance=0.0)
    with pytest.raises(DesignError, match="--prominence"):
        identify(rec, lines, prominence_db=-1.0)
