"""Sag of the slack span: the extra chain length a given sag takes, and the sag a given
extra length makes (shallow parabola).

A span of chord ℓ hanging with mid-span sag f is, for f ≪ ℓ, a parabola of arc length
ℓ + 8f²/(3ℓ) [Irvine1981, ch. 1]; so a sag f = s·ℓ takes the extra length
ΔL = (8/3)·s²·ℓ, and an extra length ΔL makes f = √(3ℓ·ΔL/8).

The installed sag is a design choice: s = 0.02 is the sag the static model of
:func:`chaindrive.strength.loads.sag_factor` assumes (k_f = 1/(8s) = 6.25, the textbook
k_f = 6 of a horizontal drive [ChainDesignRU, §8]); textbooks reduce the centre distance by
Δa = (0.002 … 0.004)·a for it [ChainDesignRU, §7], [Bhandari2010, ex. 14.4].
"""

from __future__ import annotations

import math
from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

_F = TypeVar("_F", float, NDArray[np.float64])

DEFAULT_SAG_RATIO = 0.02
"""Installed sag of the slack span as a fraction of its length, assumed when a design gives
none [-] (chains are installed with about 1–3 %, [DiamondChainTension])."""


def slack_for_sag(span: _F, sag_fraction: _F) -> _F:
    """Extra chain length ΔL = (8/3)·s²·ℓ that makes a span of chord ℓ sag by s·ℓ.

    Parameters
    ----------
    span : float or ndarray
        Chord ℓ of the span [m].
    sag_fraction : float or ndarray
        Mid-span sag as a fraction s of the chord [-].

    Returns
    -------
    float or ndarray
        ΔL [m].

    References
    ----------
    [Irvine1981, ch. 1].
    """
    return 8.0 / 3.0 * sag_fraction**2 * span


def sag_of_slack(span: float, slack: float) -> float:
    """Mid-span sag f = √(3ℓ·ΔL/8) of a span carrying an extra length.

    Parameters
    ----------
    span : float
        Chord ℓ of the span [m].
    slack : float
        Extra chain length ΔL [m] (≤ 0: no sag).

    Returns
    -------
    float
        f [m].

    References
    ----------
    [Irvine1981, ch. 1].
    """
    return math.sqrt(3.0 * span * max(slack, 0.0) / 8.0)
