"""The multi-contour check of a drive: m identical chain contours side by side on sprockets
keyed to common shafts [Lyashuk], applied to a :class:`~chaindrive.model.Drive`.

Model ([Lyashuk] with the generalisation of :mod:`.capacity`):

* the keyed joint of the driving sprocket: shaft diameter from the driver torque,
  d = ∛(16T/(π[τ])) with [τ] = 20 MPa (preliminary sizing in torsion,
  :func:`.effect.shaft_diameter_for_torque`), the [DIN6885-1] / [GOST23360] key
  for it and the fit's largest clearance (:meth:`.joints.KeyedJoint.from_standard`);
  C₄ of eq. 6 for that joint; every joint of the drive (driving and driven, every contour)
  is taken alike and independent (the eq. 13 model);
* Δ_y, the elastic stretch of the working (tight) span of one contour at its nominal share
  of the peripheral force F_t/m: Δ_y = F_t/(m·c), c the chain stiffness of that span
  (:mod:`chaindrive.dynamics.stiffness`);
* the load sharing at the design load, by compatibility of deformations: every contour j,
  longer by its slack s_j = C₄·(z_1j + z_2j) (random clearances of its two joints), carries
  c·max(0, δ − s_j), and δ is such that they add up to F_t (:func:`most_loaded_share`);
* K_m = F_t / F_max, the effective number of contours, at the risk level (default 5 %: K_m
  is lower with probability 5 %); for m = 2 the paper's own eq. 16–17 value is given beside
  it (it is optimistic, see docs/multicontour.md finding 5);
* the most loaded contour carries F_t/K_m: the strength check of the drive is made for that
  share of the power.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError
from chaindrive.multicontour.capacity import contour_factor_at_risk
from chaindrive.multicontour.clearance import sample_clearances
from chaindrive.multicontour.effect import shaft_diameter_for_torque
from chaindrive.multicontour.joints import KeyedJoint, clearance_coefficient_c4

#: Allowable shear stress for preliminary shaft sizing [Pa] ([Reshetov1974]: 15–25 MPa).
PRELIMINARY_SHEAR = 20e6
#: Monte-Carlo samples of the load sharing (a 95 % quantile to about ±0.3 %).
SAMPLES = 20_000


@shared_parameters
@dataclass(frozen=True, slots=True)
class ContourCheck:
    """The multi-contour check.

    Parameters
    ----------
    contours : int
        m [-].
    %(risk)s
    joint : KeyedJoint
        The driving joint.
    %(c4)s
    span_deformation : float
        Δ_y [m].
    km : float
        K_m by compatibility of deformations, at the risk level [-].
    km_mean : float
        Its mean [-].
    km_printed : float or None
        The value of [Lyashuk, eq. 16–17] (m = 2, else None) [-].
    max_share : float
        Largest share of the load one contour carries at that risk [-].
    """

    contours: int
    risk: float
    joint: KeyedJoint
    c4: float
    span_deformation: float
    km: float
    km_mean: float
    km_printed: float | None
    max_share: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (lengths in mm)."""
        return {
            "contours": self.contours,
            "risk": self.risk,
            "contour_factor_km": self.km,
            "contour_factor_km_mean": self.km_mean,
            "contour_factor_km_eq16": self.km_printed,
            "max_contour_share": self.max_share,
            "shaft_diameter_mm": 2e3 * self.joint.shaft_radius,
            "key_width_mm": self.joint.key_width * 1e3,
            "max_clearance_mm": self.joint.max_clearance * 1e3,
            "c4": self.c4,
            "span_deformation_mm": self.span_deformation * 1e3,
        }


def most_loaded_share(slacks: NDArray[np.float64], stretch: float) -> NDArray[np.float64]:
    """Share F_max/F of the most loaded of m equally stiff contours under a total force F.

    Compatibility of deformations: with the k least slack contours engaged,
    δ_k = (F/c + Σ_{j≤k} s_j)/k, valid for the largest k with δ_k > s_k; then
    F_max = c(δ_k − s_min) (piecewise-linear solution, vectorised over the leading axes;
    :func:`chaindrive.multicontour.capacity.load_sharing` solves one case with unequal
    stiffnesses).

    Parameters
    ----------
    slacks : numpy.ndarray
        (..., m) how much longer each contour is [m].
    stretch : float
        F/c, the elongation one contour of stiffness c would take carrying F alone [m].

    Returns
    -------
    numpy.ndarray
        (...) F_max/F [-].

    References
    ----------
    [Reshetov1974].
    """
    s = np.sort(np.asarray(slacks, dtype=float), axis=-1)
    s = s - s[..., :1]
    k = np.arange(1, s.shape[-1] + 1)
    delta = (stretch + np.cumsum(s, axis=-1)) / k
    engaged = delta > s  # true for k = 1 … k*, false beyond (δ_k falls below s_k once past)
    kstar = engaged.sum(axis=-1)
    d = np.take_along_axis(delta, (kstar - 1)[..., None], axis=-1)[..., 0]
    share: NDArray[np.float64] = d / stretch
    return share


@shared_parameters
def contour_check(contours: int, torque: float, pitch_radius: float, peripheral_force: float,
                  span_stiffness: float, *, risk: float = 0.05, fit: str = "normal",
                  samples: int = SAMPLES, seed: int = 0) -> ContourCheck:
    """K_m of m contours (module docstring).

    Parameters
    ----------
    contours : int
        m ≥ 2 [-].
    torque : float
        T on the driving shaft [N·m].
    pitch_radius : float
        R_δ of the driving sprocket [m].
    peripheral_force : float
        F_t of the whole drive [N].
    span_stiffness : float
        c of one contour's tight span [N/m].
    %(risk)s
    fit : str
        The keyway fit (:func:`chaindrive.multicontour.joints.keyway_max_clearance`).
    samples : int
        Monte-Carlo samples [-].
    seed : int
        Seed of the Monte-Carlo.

    Returns
    -------
    ContourCheck
        K_m and the largest share.

    References
    ----------
    [Lyashuk, eq. 6, 7, 16–18]; [Reshetov1974].
    """
    if not isinstance(contours, int) or contours < 2:
        raise DesignError("chain.contours", f"the check needs 2 or more contours, got {contours!r}")
    if not (torque > 0 and peripheral_force > 0 and span_stiffness > 0):
        raise DesignError("drive.power", "the multi-contour check needs a power and a speed")
    joint = KeyedJoint.from_standard(pitch_radius, shaft_diameter_for_torque(torque,
                                                                             PRELIMINARY_SHEAR), fit)
    c4 = clearance_coefficient_c4(joint)
    dy = peripheral_force / (contours * span_stiffness)
    rng = np.random.default_rng(seed)
    z = sample_clearances((samples, contours, 2), rng, joint.max_clearance)
    km = 1.0 / most_loaded_share(c4 * z.sum(axis=-1), peripheral_force / span_stiffness)
    km_printed = (contour_factor_at_risk(c4, joint.max_clearance, dy, risk) if contours == 2
               else None)
    km_risk = float(np.quantile(km, risk))
    return ContourCheck(contours, risk, joint, c4, dy, km_risk, float(km.mean()), km_printed,
                        1.0 / km_risk)
