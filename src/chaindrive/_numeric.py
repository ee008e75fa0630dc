"""Array shaping shared by the vectorised formula modules (internal): a formula computes on
arrays and hands back a Python float when its inputs were scalars; a frozen model holds
read-only arrays."""

from __future__ import annotations

from dataclasses import fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, DTypeLike, NDArray

#: What a vectorised formula returns: a float for scalar inputs, else a float64 array.
FloatOrArray = float | NDArray[np.float64]


def float_or_array(value: ArrayLike) -> FloatOrArray:
    """A Python float for a 0-d result, else a float64 array.

    Parameters
    ----------
    value : array_like
        The result of a formula [any unit, kept].

    Returns
    -------
    float or numpy.ndarray
        ``float(value)`` when it is 0-d, else ``value`` as a float64 array [same unit].
    """
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def read_only(value: ArrayLike, dtype: DTypeLike = np.float64) -> NDArray[Any]:
    """``value`` as an array of ``dtype`` that cannot be written: what a frozen model holds.

    An array that is already read-only, of that dtype and owns its data is returned as it is
    (models built from one another share it); anything else is copied first, so that the
    caller's array stays writeable and the model's cannot change behind it.

    Parameters
    ----------
    value : array_like
        The data [any unit, kept].
    dtype : dtype
        The dtype of the result.

    Returns
    -------
    numpy.ndarray
        A read-only array [same unit].
    """
    if (isinstance(value, np.ndarray) and not value.flags.writeable and value.base is None
            and value.dtype == dtype):
        return value
    arr = np.array(value, dtype=dtype)
    arr.flags.writeable = False
    return arr


def freeze_arrays(obj: Any, copy: bool = True) -> None:
    """Make every ndarray field of the (frozen) dataclass instance ``obj`` read-only.

    Parameters
    ----------
    obj : dataclass instance
        The instance whose array fields are frozen (called from its ``__post_init__``).
    copy : bool
        True: a writeable array is replaced by a read-only copy (:func:`read_only`), the
        caller's array stays writeable; False: frozen in place (arrays its builder made for
        it alone).
    """
    for f in fields(obj):
        value = getattr(obj, f.name)
        if not isinstance(value, np.ndarray):
            continue
        if copy:
            object.__setattr__(obj, f.name, read_only(value, value.dtype))
        else:
            value.flags.writeable = False


def rebuilt(obj: Any) -> tuple[Any, tuple[Any, ...]]:
    """What ``pickle`` needs to rebuild the dataclass instance ``obj`` through its
    constructor (``__reduce__``), so that a model sent to another process is frozen there
    too (NumPy does not pickle the read-only flag).

    Parameters
    ----------
    obj : dataclass instance
        The instance.

    Returns
    -------
    tuple
        (its class, its field values in order).
    """
    return type(obj), tuple(getattr(obj, f.name) for f in fields(obj))
