"""Array shaping shared by the vectorised formula modules (internal): a formula computes on
arrays and hands back a Python float when its inputs were scalars."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

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
