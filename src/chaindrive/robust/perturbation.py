"""One state of a built drive: how it departs from the drawing (a sample of the uncertainty
model, or a point of the life curve), and the temperature law of polymer moduli.

A :class:`Perturbation` holds SI values only; :class:`chaindrive.robust.analysis.PerturbedAnalysis`
turns it into an analysis of the drive in that state.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive.errors import DesignError
from chaindrive.model import Material

__all__ = ["MODULUS_TEMPERATURES_C", "REFERENCE_TEMPERATURE_C", "Perturbation", "modulus_factor",
           "modulus_factors"]

#: Temperature at which the catalogue moduli are given [°C] (ISO 527 / ASTM D638 tests).
REFERENCE_TEMPERATURE_C = 23.0
#: Tensile modulus of an acetal homopolymer against temperature: (T [°C], E [MPa]),
#: [Delrin500P] (ASTM D638). The relative curve E(T)/E(23 °C) is applied to every polymer
#: part (an estimate for polyamides and other plastics, which give no temperature points
#: here).
MODULUS_TEMPERATURES_C: tuple[tuple[float, float], ...] = ((-40.0, 3450.0), (23.0, 3250.0),
                                                           (100.0, 700.0))


def modulus_factor(material: Material, temperature_c: float) -> float:
    """E(T)/E(23 °C) of a material [–]: 1 for metals, the acetal curve for polymers.

    Linear interpolation in :data:`MODULUS_TEMPERATURES_C`, held constant outside it.

    Parameters
    ----------
    material : Material
        The part's material (``is_polymer`` decides).
    temperature_c : float
        Operating temperature [°C].

    Returns
    -------
    float
        Factor on the catalogue Young's modulus [–].

    References
    ----------
    [Delrin500P]
    """
    if not np.isfinite(temperature_c):
        raise DesignError("uncertainty.temperature", f"must be finite, got {temperature_c!r}")
    if not material.is_polymer:
        return 1.0
    t, e = zip(*MODULUS_TEMPERATURES_C, strict=True)
    reference = float(np.interp(REFERENCE_TEMPERATURE_C, t, e))
    return float(np.interp(temperature_c, t, e)) / reference


def modulus_factors(material: Material, temperature_c: ArrayLike) -> NDArray[np.float64]:
    """:func:`modulus_factor` at many temperatures at once [–].

    Parameters
    ----------
    material : Material
        The part's material.
    temperature_c : array_like
        Operating temperatures [°C].

    Returns
    -------
    ndarray
        E(T)/E(23 °C) [–], the shape of ``temperature_c``.

    References
    ----------
    [Delrin500P]
    """
    t = np.asarray(temperature_c, dtype=float)
    if not material.is_polymer:
        return np.ones_like(t)
    temps, moduli = zip(*MODULUS_TEMPERATURES_C, strict=True)
    reference = float(np.interp(REFERENCE_TEMPERATURE_C, temps, moduli))
    out: NDArray[np.float64] = np.interp(t, temps, moduli) / reference
    return out


@dataclass(frozen=True, slots=True)
class Perturbation:
    """How a built drive departs from its drawing (SI units; empty tuples: nominal).

    Parameters
    ----------
    elongation : float
        Chain elongation ε over the nominal pitch: the length tolerance of a new chain plus
        the wear [–].
    offsets : tuple of (float, float)
        Displacement (Δx, Δy) of every sprocket centre [m] (empty: none).
    eccentricity : tuple of float
        Eccentricity of every sprocket [m] (empty: none).
    inertia_factors : tuple of float
        Factor on every reduced inertia [–] (empty: 1).
    chain_stiffness_factor : float
        Factor on the chain's link stiffness [–].
    temperature_c : float
        Operating temperature of polymer parts [°C].
    clearances : tuple of float
        Key clearance of the driving and driven sprocket of every contour, in the order
        (contour 1 driving, contour 1 driven, contour 2 driving, …) [m] (empty: the
        analysis's own K_m at its risk).
    """

    elongation: float = 0.0
    offsets: tuple[tuple[float, float], ...] = ()
    eccentricity: tuple[float, ...] = ()
    inertia_factors: tuple[float, ...] = ()
    chain_stiffness_factor: float = 1.0
    temperature_c: float = REFERENCE_TEMPERATURE_C
    clearances: tuple[float, ...] = field(default=())

    def __post_init__(self) -> None:
        if not (np.isfinite(self.elongation) and -0.5 < self.elongation < 0.5):
            raise DesignError("elongation", f"must be a fraction in (−0.5, 0.5), got "
                              f"{self.elongation!r}")
        if not (np.isfinite(self.chain_stiffness_factor) and self.chain_stiffness_factor > 0):
            raise DesignError("chain_stiffness_factor", "must be positive, got "
                              f"{self.chain_stiffness_factor!r}")
        if any(not (np.isfinite(f) and f > 0) for f in self.inertia_factors):
            raise DesignError("inertia_factors", f"must be positive, got {self.inertia_factors!r}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (lengths in mm)."""
        return {"elongation": self.elongation,
                "offsets_mm": [[x * 1e3, y * 1e3] for x, y in self.offsets],
                "eccentricity_mm": [e * 1e3 for e in self.eccentricity],
                "inertia_factors": list(self.inertia_factors),
                "chain_stiffness_factor": self.chain_stiffness_factor,
                "temperature_c": self.temperature_c,
                "clearances_mm": [z * 1e3 for z in self.clearances]}
