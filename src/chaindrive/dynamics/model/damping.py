"""The chain's damping in the whole-drive model of :mod:`chaindrive.dynamics.model.build`.

The damping ratio ζ of every span and of every sprocket's wrap is the ratio of its material
pair [MultimassChainDrives, Table 1], the design's ``[dynamics] damping_ratio``, or each
span's hinge friction at its own tension [ChainHingeDissipation]. Span and wrap dampers
d = 2ζ k/ω_ref are proportional to their stiffness, ω_ref the first elastic mode in which
the chain holds most of the strain energy, so that mode has the ratio ζ (times the chain's
share of its strain energy).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.damping import pair_damping_ratio, span_hinge_damping_ratios
from chaindrive.dynamics.model.assembly import DriveParts, LinearModel
from chaindrive.errors import DesignError

if TYPE_CHECKING:
    from chaindrive.dynamics.modes import Modes
    from chaindrive.dynamics.parameters import RingParameters
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, Material

__all__ = ["CHAIN_MODE_SHARE", "chain_damping",
           "reference_angular_frequency", "with_chain_dampers"]

FloatArray = NDArray[np.float64]
#: Least share of the strain energy the chain (spans and wraps) holds in the mode whose
#: frequency is the reference of the chain's damping.
CHAIN_MODE_SHARE = 0.5


@shared_parameters
def chain_damping(drive: Drive, geometry: GeometryResult, ring: RingParameters,
                  lookup: Callable[[str], Material]) -> tuple[FloatArray, FloatArray, str]:
    """ζ of every span and of every sprocket's wrap [-], and where they come from: the
    design's ``[dynamics] damping_ratio``, hinge friction at each span's tension
    [ChainHingeDissipation], or the chain/sprocket material pair [MultimassChainDrives,
    Table 1] (a span: the mean of its two ends' pairs).

    Parameters
    ----------
    %(drive)s
    geometry : GeometryResult
        Its geometry (span lengths).
    ring : RingParameters
        Its ring reduction (span tensions, for hinge friction).
    lookup : callable
        Material name → :class:`~chaindrive.model.Material`.

    Returns
    -------
    spans : ndarray
        (n,) ζ of the spans [-].
    wraps : ndarray
        (n,) ζ of the wraps [-].
    source : str
        Where they come from.

    Raises
    ------
    DesignError
        ``dynamics.hinge_friction`` without the span tensions (no power given).
    """
    spec = drive.chain.spec
    n = len(drive.sprockets)
    chain_polymer = lookup(spec.material).is_polymer
    sprocket_polymer = [lookup(s.material).is_polymer for s in drive.sprockets]
    wraps = np.array([pair_damping_ratio(chain_polymer, p) for p in sprocket_polymer])
    settings = drive.dynamics
    if settings.damping_ratio is not None:
        z = settings.damping_ratio
        return np.full(n, z), np.full(n, z), "given ([dynamics] damping_ratio)"
    spans = 0.5 * (wraps + np.roll(wraps, -1))
    if settings.hinge_friction:
        if ring.span_tensions_n is None:
            raise DesignError("dynamics.hinge_friction", "needs the span tensions: give the "
                              "drive's power")
        lengths = np.array([sp.length for sp in geometry.spans])
        spans = span_hinge_damping_ratios(ring.span_tensions_n, lengths, spec.pin_diameter,
                                          settings.hinge_amplitude)
        return spans, wraps, "hinge friction [ChainHingeDissipation]"
    return spans, wraps, "material pair [MultimassChainDrives, Table 1]"



def with_chain_dampers(model: DriveParts, span_zeta: FloatArray, wrap_zeta: FloatArray,
                       w_ref: float) -> DriveParts:
    """The model with the chain's dampers d = 2ζk/ω_ref on the spans and wraps (module
    docstring): in its linear model and in a copy of its torsional model (both built, frozen).

    Parameters
    ----------
    model : DriveParts
        The assembled model.
    span_zeta, wrap_zeta : ndarray
        ζ of the spans and of the wraps [-] (:func:`chain_damping`).
    w_ref : float
        ω_ref [rad/s] (:func:`reference_angular_frequency`); ≤ 0 adds no damper.

    Returns
    -------
    DriveParts
        The model with the dampers (``linear`` and ``torsional`` replaced).
    """
    lin, sys = model.linear, model.system
    if w_ref <= 0:
        return model
    d_span = 2.0 * span_zeta * lin.span_stiffness / w_ref
    kinds = np.array(sys.element_kinds)
    wraps = np.flatnonzero(kinds == "wrap")
    d_wrap = 2.0 * wrap_zeta * sys.element_stiffness[wraps] / w_ref
    Bw = sys.element_incidence[wraps] @ model.condensation
    dampers = dict(zip(sys.span_names, d_span.tolist(), strict=True))
    dampers.update((sys.element_names[k], d) for k, d in
                   zip(wraps.tolist(), d_wrap.tolist(), strict=True))
    linear = LinearModel(lin.mass, lin.stiffness_linear,
                         lin.damping_linear + (Bw.T * d_wrap) @ Bw, lin.span_incidence,
                         lin.span_stiffness, d_span, lin.span_tension_only)
    return replace(model, linear=linear, torsional=model.torsional.with_damping(dampers))


def reference_angular_frequency(modes: Modes) -> float:
    """ω_ref [rad/s] of the chain's dampers: the first elastic mode in which the chain's
    elements (spans and wraps) hold at least :data:`CHAIN_MODE_SHARE` of the strain energy
    (else the first elastic mode; 0 without one).

    Parameters
    ----------
    modes : Modes
        The undamped modes of the assembled model.

    Returns
    -------
    float
        ω_ref [rad/s].
    """
    kinds = np.array(modes.element_kinds)
    chain = (kinds == "span") | (kinds == "wrap")
    shares = modes.strain_energy_shares[chain].sum(axis=0)
    elastic = np.flatnonzero(~modes.rigid_body)
    if elastic.size == 0:
        return 0.0
    for j in elastic:
        if shares[j] >= CHAIN_MODE_SHARE:
            return float(modes.angular_frequencies_rad_s[j])
    return float(modes.angular_frequencies_rad_s[elastic[0]])
