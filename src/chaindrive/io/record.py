"""Read a measured time record: a CSV with a time column and one or more signals, or a WAV
file with its sample rate. Returns plain arrays (SI: seconds); refuses a bad record in one
line naming the field, the value and what is allowed.

CSV: a header row, then numbers. The time column names its unit: ``time_s``, ``time [s]``,
``time (s)`` or ``time_ms`` (a unit is never guessed); every other column is a signal
(speed, torque, acceleration, span force — its unit as its name gives it; the spectrum's
peaks do not depend on the signal's unit). Time must increase strictly and evenly (every
step within :data:`SPACING_TOLERANCE` of the median step). WAV: one signal per channel at
the file's sample rate (:func:`scipy.io.wavfile.read`).
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError

__all__ = ["MIN_SAMPLES", "SPACING_TOLERANCE", "Record", "read_record", "record_from_arrays",
           "record_from_csv_bytes", "speed_unit", "take_column"]

#: Fewest samples of a record [-]: a spectrum of fewer than 64 points resolves nothing.
MIN_SAMPLES = 64
#: Largest relative departure of a time step from the median step [-].
SPACING_TOLERANCE = 0.01
#: Time column names → factor to seconds.
_TIME = re.compile(r"^\s*(time|t)\s*(?:_|\[|\()\s*(s|ms)\s*[\])]?\s*$", re.IGNORECASE)
_FIELD = "--record"
#: Speed column units → factor to rad/s (the unit ends the column's name: ``speed_rpm``,
#: ``n [rpm]``, ``omega_rad_s``, ``n (rev/s)``, ``f_hz``).
_SPEED = re.compile(r"(?:_|\[|\(|\s)\s*(rpm|rad/s|rad_s|rev/s|rev_s|hz)\s*[\])]?\s*$",
                    re.IGNORECASE)
_SPEED_FACTOR = {"rpm": 2.0 * math.pi / 60.0, "rad/s": 1.0, "rad_s": 1.0,
                 "rev/s": 2.0 * math.pi, "rev_s": 2.0 * math.pi, "hz": 2.0 * math.pi}


@dataclass(frozen=True, slots=True)
class Record:
    """A measured record sampled evenly.

    Parameters
    ----------
    name : str
        The file's name.
    sample_rate : float
        f_s [Hz].
    signals : dict of str to ndarray
        Each signal's samples [its own unit, as its name gives it].
    """

    name: str
    sample_rate: float
    signals: dict[str, NDArray[np.float64]]


@shared_parameters
def record_from_arrays(name: str, time: NDArray[np.float64],
                       signals: dict[str, NDArray[np.float64]],
                       time_field: str = "time_s") -> Record:
    """A :class:`Record` from a time vector [s] and its signals, checked.

    Parameters
    ----------
    name : str
        What the record is called.
    time : ndarray
        t [s], strictly and evenly increasing, at least :data:`MIN_SAMPLES` long.
    signals : dict of str to ndarray
        Signals of the length of ``time``, finite [each its own unit].
    time_field : str
        The time column's name, for messages.

    %(returns_record)s

    Raises
    ------
    DesignError
        Too short, not increasing, unevenly spaced, no signal, or a non-finite sample.
    """
    t = np.asarray(time, dtype=float)
    if t.size < MIN_SAMPLES:
        raise DesignError(f"{_FIELD}.{time_field}", f"{t.size} samples; allowed: at least "
                          f"{MIN_SAMPLES}")
    if not signals:
        raise DesignError(_FIELD, "no signal column; allowed: one or more beside the time")
    if not np.all(np.isfinite(t)):
        raise DesignError(f"{_FIELD}.{time_field}", "a time that is not a number")
    dt = np.diff(t)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        k = int(bad[0])
        raise DesignError(f"{_FIELD}.{time_field}", f"not increasing at sample {k + 2} "
                          f"({t[k + 1]:.9g} s after {t[k]:.9g} s); allowed: strictly "
                          "increasing")
    step = float(np.median(dt))
    uneven = np.flatnonzero(np.abs(dt - step) > SPACING_TOLERANCE * step)
    if uneven.size:
        k = int(uneven[0])
        raise DesignError(f"{_FIELD}.{time_field}", f"uneven step {dt[k]:.9g} s at sample "
                          f"{k + 2} (median {step:.9g} s); allowed: within "
                          f"{SPACING_TOLERANCE:.0%} of the median")
    for key, values in signals.items():
        if values.shape != t.shape or not np.all(np.isfinite(values)):
            raise DesignError(f"{_FIELD}.{key}", "a sample missing or not a finite number")
    return Record(name, 1.0 / step, {k: np.asarray(v, dtype=float) for k, v in signals.items()})


def take_column(record: Record, column: str, option: str) -> tuple[Record, NDArray[np.float64]]:
    """The record without one of its signals, and that signal.

    Parameters
    ----------
    record : Record
        The record.
    column : str
        The signal's name.
    option : str
        The option that named it, for messages.

    Returns
    -------
    rest : Record
        The other signals.
    values : ndarray
        The column's samples [its unit].

    Raises
    ------
    DesignError
        No such column, or no other signal left.
    """
    if column not in record.signals:
        raise DesignError(option, f"no column {column!r} in {record.name}; allowed: "
                          f"{', '.join(record.signals)}")
    rest = {k: v for k, v in record.signals.items() if k != column}
    if not rest:
        raise DesignError(option, f"{column!r} is the only signal of {record.name}; allowed: "
                          "a record with a signal beside it")
    return Record(record.name, record.sample_rate, rest), record.signals[column]


def speed_unit(column: str) -> float:
    """Factor from a speed column's unit, read from the end of its name, to rad/s (a unit is
    never guessed).

    Parameters
    ----------
    column : str
        ``speed_rpm``, ``n [rpm]``, ``omega_rad_s``, ``n_rev_s``, ``n_hz`` (revolutions per
        second) …

    Returns
    -------
    float
        [rad/s per the column's unit].

    Raises
    ------
    DesignError
        No unit recognised at the end of the name.
    """
    match = _SPEED.search(column)
    if match is None:
        raise DesignError("--speed", f"{column!r} names no unit; allowed: a name ending in "
                          "_rpm, _rad_s, _rev_s or _hz (revolutions per second), or [rpm]")
    return _SPEED_FACTOR[match.group(1).lower()]


def _number(text: str, row: int, column: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise DesignError(f"{_FIELD}.{column}", f"{text.strip()[:40]!r} at row {row} is not a "
                          "number") from None
    if not math.isfinite(value):
        raise DesignError(f"{_FIELD}.{column}", f"{text.strip()!r} at row {row}; allowed: a "
                          "finite number")
    return value


def _read_csv(path: Path) -> Record:
    with path.open(newline="", encoding="utf-8-sig") as handle:
        rows = list(csv.reader(handle))
    return _csv_record(path.name, rows)


@shared_parameters
def record_from_csv_bytes(name: str, data: bytes) -> Record:
    """A CSV record from its bytes (an upload), read as :func:`read_record` reads a file.

    Parameters
    ----------
    name : str
        The file's name.
    data : bytes
        Its content (UTF-8).

    %(returns_record)s

    Raises
    ------
    DesignError
        Not UTF-8, or not a record as described in the module docstring.
    """
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise DesignError(_FIELD, f"{name} is not UTF-8 text; allowed: a CSV file") from None
    return _csv_record(name, list(csv.reader(io.StringIO(text, newline=""))))


def _csv_record(name: str, rows: list[list[str]]) -> Record:
    if not rows:
        raise DesignError(_FIELD, f"{name} is empty; allowed: a header row and samples")
    header = [h.strip() for h in rows[0]]
    times = [(i, m) for i, h in enumerate(header) if (m := _TIME.match(h))]
    if len(times) != 1:
        raise DesignError(_FIELD, f"{'no' if not times else 'more than one'} time column in "
                          f"{header!r}; allowed: one column named time_s, time [s] or time_ms")
    col, match = times[0]
    factor = 1e-3 if match.group(2).lower() == "ms" else 1.0
    data = [r for r in rows[1:] if any(c.strip() for c in r)]
    for n, r in enumerate(data, start=2):
        if len(r) != len(header):
            raise DesignError(_FIELD, f"row {n} has {len(r)} cells; allowed: {len(header)} "
                              "(one per header column)")
    values = np.array([[_number(c, n, header[j]) for j, c in enumerate(r)]
                       for n, r in enumerate(data, start=2)], dtype=float).reshape(
                           len(data), len(header))
    signals = {h: values[:, j] for j, h in enumerate(header) if j != col}
    return record_from_arrays(name, values[:, col] * factor, signals, header[col])


def _read_wav(path: Path) -> Record:
    from scipy.io import wavfile  # lazy: only a WAV record needs it

    try:
        rate, data = wavfile.read(path)
    except ValueError as exc:
        raise DesignError(_FIELD, f"{path.name} is not a readable WAV file ({exc})") from None
    samples = np.asarray(data, dtype=float)
    if samples.ndim == 1:
        samples = samples[:, None]
    t = np.arange(samples.shape[0]) / float(rate)
    signals = {f"channel_{k + 1}": samples[:, k] for k in range(samples.shape[1])}
    return record_from_arrays(path.name, t, signals)


@shared_parameters
def read_record(path: str | Path) -> Record:
    """Read a CSV or WAV record (module docstring).

    Parameters
    ----------
    path : str | Path
        ``*.csv`` or ``*.wav``.

    %(returns_record)s

    Raises
    ------
    DesignError
        The file missing, of another kind, or not a record as described.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix not in (".csv", ".wav"):
        raise DesignError(_FIELD, f"{p.name!r}: allowed: a .csv or .wav file")
    if not p.is_file():
        raise DesignError(_FIELD, f"no such file {str(p)!r}")
    return _read_csv(p) if suffix == ".csv" else _read_wav(p)
