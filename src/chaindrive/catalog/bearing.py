"""The projected bearing area of a chain's hinges: row factor, bush length, area estimate.

``ChainSpec.bearing_area`` is the projected hinge bearing area of the whole chain as the
GOST/Russian method uses it (p = Kэ·Ft/A): for n rows A = m_r·A₁ with the row factor m_r
[TrinhChat2006, Table 5.12], [ChainDesignRU, §1]. GOST chains carry the tabulated value; for
ISO chains no source gives A, and it is DERIVED here: A₁ = d₂·B with the bush length
B ≈ (b₁ + p_t)/2, or B ≈ 1.42·b₁ when the transverse pitch is not known.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._numeric import FloatOrArray, float_or_array
from chaindrive.errors import CatalogError

__all__ = ["BUSH_TO_INNER_WIDTH", "ROW_FACTORS", "bearing_area_estimate", "bush_length_estimate",
           "row_factor"]

#: Row factor m_r of multi-row chains (effective bearing area / single-row area), 1–4 rows
#: [TrinhChat2006, Table 5.12] (ratios of its columns), [ChainDesignRU, §1]. Not the
#: multiple-strand factor of a power rating (:func:`chaindrive.strength.iso10823.strand_factor`).
ROW_FACTORS: dict[int, float] = {1: 1.0, 2: 1.7, 3: 2.5, 4: 3.0}
#: Median ratio of the bush length B to the inner width b₁ of the GOST 13568 ПР chains of
#: 19.05…50.8 mm pitch (17.75/12.70, 22.61/15.88, …) [GOST13568, Table 1].
BUSH_TO_INNER_WIDTH = 1.42


def row_factor(strands: int) -> float:
    """Row factor m_r of the bearing area of a multi-row chain.

    Parameters
    ----------
    strands : int
        Number of rows n [-].

    Returns
    -------
    float
        m_r [-]: 1, 1.7, 2.5, 3.0 for 1–4 rows (:data:`ROW_FACTORS`).

    Raises
    ------
    CatalogError
        On ``chain.strands`` beyond 4 rows (no source gives a factor).

    References
    ----------
    [TrinhChat2006, Table 5.12]; [ChainDesignRU, §1].
    """
    try:
        return ROW_FACTORS[strands]
    except KeyError:
        raise CatalogError(
            "chain.strands", f"no row factor for {strands!r} strands (known for 1 to 4)"
        ) from None


def bush_length_estimate(inner_width: ArrayLike, transverse_pitch: ArrayLike) -> FloatOrArray:
    """Bush length B [m] — an approximation derived for chaindrive.

    B ≈ (b₁ + p_t)/2: the transverse pitch spans the inner width, two inner and two outer
    plates, p_t ≈ b₁ + 2s_i + 2s_o; with s_i ≈ s_o the bush (inner-link) length is
    B = b₁ + 2s_i ≈ (b₁ + p_t)/2. Checked against the bush lengths of [TrinhChat2006,
    Table 5.5] (e.g. 16A/ПР-25,4: (15.88 + 29.29)/2 = 22.59 vs 22.61 mm). Where p_t is not
    known (0), B ≈ 1.42·b₁ (:data:`BUSH_TO_INNER_WIDTH`).

    Parameters
    ----------
    inner_width : float or array_like
        Inner width b₁ [m].
    transverse_pitch : float or array_like
        Transverse pitch p_t [m] (0: not known).

    Returns
    -------
    float or numpy.ndarray
        B [m].

    References
    ----------
    [TrinhChat2006, Table 5.5]; [GOST13568, Table 1].
    """
    b1 = np.asarray(inner_width, dtype=float)
    pt = np.asarray(transverse_pitch, dtype=float)
    return float_or_array(np.where(pt > 0, 0.5 * (b1 + pt), BUSH_TO_INNER_WIDTH * b1))


def bearing_area_estimate(pin_diameter: ArrayLike, inner_width: ArrayLike,
                          transverse_pitch: ArrayLike, strands: int = 1) -> FloatOrArray:
    """Projected bearing area of the whole chain A = m_r·d₂·B [m²] (DERIVED, module doc).

    Reproduces the GOST 13568 / table 5.12 areas within 4.5 % for every multi-row GOST chain
    (tested in ``tests/unit/test_catalog.py``).

    Parameters
    ----------
    pin_diameter : float or array_like
        Pin diameter d₂ [m].
    inner_width : float or array_like
        Inner width b₁ [m].
    transverse_pitch : float or array_like
        Transverse pitch p_t [m] (0: not known).
    strands : int
        Rows n [-] (m_r from :func:`row_factor`).

    Returns
    -------
    float or numpy.ndarray
        A [m²], B from :func:`bush_length_estimate`.

    References
    ----------
    [TrinhChat2006, Tables 5.5 and 5.12]; [ChainDesignRU, §1].
    """
    bush = np.asarray(bush_length_estimate(inner_width, transverse_pitch))
    return float_or_array(row_factor(strands) * np.asarray(pin_diameter, dtype=float) * bush)
