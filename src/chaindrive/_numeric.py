"""Small array helpers shared by the vectorised formula modules (internal)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError

FloatOrArray = float | NDArray[np.float64]


def float_or_array(value: ArrayLike) -> FloatOrArray:
    """A Python float for a 0-d result, else a float64 array."""
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def teeth_array(teeth: ArrayLike) -> NDArray[np.float64]:
    """Tooth counts as floats, refusing anything below 3 or not finite."""
    z = np.asarray(teeth, dtype=float)
    if np.any(~np.isfinite(z)) or np.any(z < 3):
        raise DesignError("teeth", f"must be a whole number of at least 3, got {teeth!r}")
    return z
