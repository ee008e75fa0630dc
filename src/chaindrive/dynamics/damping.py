"""Damping of a chain drive: hinge friction in a transversely vibrating span ([ChainHingeDissipation]).

The tight span of length a (z hinges, pitch t, a = t (z − 1)) vibrates as a string with
fixed ends in its first mode, y = y_0 sin(πx/a) cos(ωτ), relative amplitude ȳ_0 = y_0/a
(≤ 0.03). Friction in the hinges (pin diameter d_2, friction coefficient f) under the
initial tension F_0 dissipates W per cycle; E is the largest potential energy of the
cycle; the absorption coefficient (relative dissipation) is ψ = W/E. Equation numbers are
[ChainHingeDissipation]'s, restated in docs/dynamics.md §4::

    Σφ = 4π ȳ_0                                         (6)
    W = 4 f F_0 (d_2/2) Σφ = 8π f F_0 d_2 ȳ_0             (7, 8)
    Δl_max = 8 y_0² / (3a) = (8/3) a ȳ_0²                 (10)
    F_max = k1 + k2 ȳ_0 + k3 F_0 + k4 ȳ_0² + k5 ȳ_0 F_0 + k6 F_0²   (11, empirical)
    K_aF = (F_max − F_0) / F_0                           (13)
    E = 0.5 F_a Δl_max = (4/3) a ȳ_0² F_0 K_aF             (9, 12)
    ψ = 6π f d_2 / (ȳ_0 a K_aF) ≈ 18.9 f d_2 / (ȳ_0 t (z − 1) K_aF)   (14)

Equivalent viscous damping ratio ζ = ψ / (4π) (ψ = 2δ, δ = 2πζ the logarithmic decrement
for light damping). Alternative: the plain ratio D = 0.06 measured in [MultimassChainDrives, §3.2]
(Table 1: damped and undamped frequencies then differ by 0.18 %, √(1 − 0.06²) = 0.9982).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError, positive
from chaindrive.geometry.sag import slack_for_sag

__all__ = [
    "DEFAULT_DAMPING_RATIO",
    "PAIR_DAMPING_RATIOS",
    "PR_12_7_1820_1",
    "TABLE1_FREQUENCIES_RAD_S",
    "HingeFrictionCoefficients",
    "HingeFrictionResult",
    "absorption_coefficient",
    "damped_frequencies",
    "dissipated_energy_per_cycle",
    "dynamic_load_factor",
    "equivalent_damping_ratio",
    "hinge_friction_damping",
    "hinge_rotation_sum",
    "max_dynamic_force",
    "max_potential_energy",
    "pair_damping_ratio",
    "span_elongation_max",
    "span_hinge_damping_ratios",
    "table1_damping_ratio",
]

#: Dimensionless damping coefficient D = ζ measured for chain drives [MultimassChainDrives,
#: §3.2].
DEFAULT_DAMPING_RATIO = 0.06

#: [MultimassChainDrives], Table 1: undamped and damped natural frequency [rad/s] of one chain
#: drive by (chain, sprockets) material: "metal" or "polymer".
TABLE1_FREQUENCIES_RAD_S: dict[tuple[str, str], tuple[float, float]] = {
    ("metal", "metal"): (612.4, 611.3),
    ("polymer", "metal"): (155.0, 152.6),
    ("metal", "polymer"): (548.0, 546.9),
    ("polymer", "polymer"): (153.8, 151.4),
}


def table1_damping_ratio(undamped: float, damped: float) -> float:
    """Damping ratio ζ = √(1 − (ω_d/ω)²) [-] of a mode whose damped and undamped natural
    frequencies are ω_d and ω (any one unit): ω_d = ω√(1 − ζ²) of a viscously damped
    single-degree-of-freedom system [Rao2011, §2.6].

    Parameters
    ----------
    undamped : float
        ω, undamped natural frequency [rad/s].
    damped : float
        ω_d ≤ ω, damped natural frequency [rad/s].

    Returns
    -------
    float
        ζ [-].

    References
    ----------
    [Rao2011, §2.6]; applied to [MultimassChainDrives], Table 1.
    """
    r = damped / undamped
    if not 0.0 < r <= 1.0:
        raise DesignError("damped", f"need 0 < ω_d ≤ ω, got {damped!r} and {undamped!r}")
    return math.sqrt(1.0 - r * r)


#: Damping ratio of a chain on its sprockets by (chain, sprockets) material: a metal chain on
#: metal sprockets the measured D = 0.06 [MultimassChainDrives, §3.2] (Table 1 gives 0.0599);
#: the other pairs derived from the damped and undamped frequencies of its Table 1
#: (ζ = √(1 − (ω_d/ω)²)): 0.175 polymer chain on metal, 0.063 metal chain on polymer, 0.176
#: polymer on polymer. Table 1 prints four significant figures: ζ is known to about ±0.002
#: (metal chain) and ±0.001 (polymer chain).
PAIR_DAMPING_RATIOS: dict[tuple[str, str], float] = {
    **{pair: table1_damping_ratio(*w) for pair, w in TABLE1_FREQUENCIES_RAD_S.items()},
    ("metal", "metal"): DEFAULT_DAMPING_RATIO}


def pair_damping_ratio(chain_polymer: bool, sprocket_polymer: bool) -> float:
    """Damping ratio ζ [-] of a chain on a sprocket by their materials
    (:data:`PAIR_DAMPING_RATIOS`, [MultimassChainDrives], Table 1).

    Parameters
    ----------
    chain_polymer : bool
        The chain is of a polymer (else a metal).
    sprocket_polymer : bool
        The sprocket is of a polymer.

    Returns
    -------
    float
        ζ [-].
    """
    key = ("polymer" if chain_polymer else "metal", "polymer" if sprocket_polymer else "metal")
    return PAIR_DAMPING_RATIOS[key]


def span_hinge_damping_ratios(tensions: ArrayLike, lengths: ArrayLike, pin_diameter: float,
                              relative_amplitude: float,
                              coefficients: HingeFrictionCoefficients | None = None,
                              ) -> NDArray[np.float64]:
    """Damping ratio ζ = ψ/4π [-] of every span from the hinge friction at its own tension
    [ChainHingeDissipation, eq. 14]: ψ = 6π f d₂/(ȳ₀ a K_aF).

    Parameters
    ----------
    tensions : array_like
        Static tension F₀ of every span [N] (> 0; a slack span is given the least tension of
        the fit's range, 250 N, and its damping matters little).
    lengths : array_like
        Span length a [m].
    pin_diameter : float
        Pin diameter d₂ of the chain [m].
    relative_amplitude : float
        Relative transverse amplitude ȳ₀ = y₀/a [-] (the paper: 0.015–0.03).
    coefficients : HingeFrictionCoefficients | None
        The F_max fit and friction f (None: the paper's ПР-12,7-1820-1; for another chain an
        extrapolation).

    Returns
    -------
    ndarray
        ζ of every span [-].

    References
    ----------
    [ChainHingeDissipation], eqs. 11–14; ζ = ψ/4π [Panovko1960] (:func:`equivalent_damping_ratio`).
    """
    c = coefficients or PR_12_7_1820_1
    f0 = np.maximum(np.asarray(tensions, dtype=float), 250.0)
    psi = absorption_coefficient(c.friction, pin_diameter, lengths, relative_amplitude, f0, c)
    return equivalent_damping_ratio(psi)


@dataclass(frozen=True, slots=True)
class HingeFrictionCoefficients:
    """Empirical fit F_max = k1 + k2 ȳ_0 + k3 F_0 + k4 ȳ_0² + k5 ȳ_0 F_0 + k6 F_0² of one
    chain ([ChainHingeDissipation, eq. 11]) with the chain's hinge data. Replace with the
    coefficients of your chain.

    Parameters
    ----------
    chain : str
        The chain the fit belongs to.
    k1, k2, k4 : float
        Coefficients [N].
    k3, k5 : float
        Coefficients [-].
    k6 : float
        Coefficient [1/N].
    pin_diameter : float
        Pin diameter d_2 [m].
    pitch : float
        Chain pitch t [m].
    friction : float
        Coefficient of friction f in the hinges [-].
    source : str
        Where the fit comes from (a reference key).
    """

    chain: str
    k1: float
    k2: float
    k3: float
    k4: float
    k5: float
    k6: float
    pin_diameter: float
    pitch: float
    friction: float = 0.1
    source: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (SI units)."""
        return asdict(self)


#: [ChainHingeDissipation]'s set for chain ПР-12,7-1820-1 (GOST 13568-97): d_2 = 4.45 mm, t = 12.7 mm,
#: f = 0.1; the signs of the k's are unreadable in the source, all taken positive
#: (then F_max at ȳ_0 → 0 stays within 10 % of F_0).
PR_12_7_1820_1 = HingeFrictionCoefficients(
    chain="GOST 13568 ПР-12,7-1820-1", k1=32.55, k2=8276.0, k3=0.904, k4=1.374e6, k5=10.2,
    k6=15.7e-5, pin_diameter=4.45e-3, pitch=12.7e-3, friction=0.1,
    source="[ChainHingeDissipation] (coefficients of its ref. [16])",
)


def hinge_rotation_sum(relative_amplitude: ArrayLike) -> NDArray[np.float64]:
    """Total rotation of the pins in their bushes per quarter period, Σφ = 4π ȳ_0 [rad].

    Parameters
    ----------
    relative_amplitude : array_like
        ȳ_0 = y_0 / a [-].

    Returns
    -------
    ndarray
        Σφ [rad].

    References
    ----------
    [ChainHingeDissipation, eq. 6].
    """
    return 4.0 * math.pi * positive("relative_amplitude", relative_amplitude)


def dissipated_energy_per_cycle(friction: ArrayLike, tension: ArrayLike, pin_diameter: ArrayLike,
                                amplitude: ArrayLike, span_length: ArrayLike) -> NDArray[np.float64]:
    """Energy W [J] dissipated by hinge friction per cycle of transverse vibration:
    W = 4 f F_0 (d_2/2) Σφ = 8π f F_0 d_2 y_0 / a.

    Parameters
    ----------
    friction : array_like
        Coefficient of friction f in the hinges [-].
    tension : array_like
        Static span tension F_0 [N].
    pin_diameter : array_like
        Pin diameter d_2 [m].
    amplitude : array_like
        Amplitude y_0 at mid-span [m].
    span_length : array_like
        Span length a [m].

    Returns
    -------
    ndarray
        W [J].

    References
    ----------
    [ChainHingeDissipation, eqs. 7–8] (with ȳ_0 = y_0/a).
    """
    f = positive("friction", friction)
    y_rel = positive("amplitude", amplitude) / positive("span_length", span_length)
    return 8.0 * math.pi * f * positive("tension", tension) * positive(
        "pin_diameter", pin_diameter) * y_rel


def span_elongation_max(span_length: ArrayLike, relative_amplitude: ArrayLike) -> NDArray[np.float64]:
    """Elongation Δl_max = (8/3) a ȳ_0² [m] of a span at its largest deflection (sine-shaped
    span).

    Parameters
    ----------
    span_length : array_like
        Span length a [m].
    relative_amplitude : array_like
        ȳ_0 [-].

    Returns
    -------
    ndarray
        Δl_max [m].

    References
    ----------
    [ChainHingeDissipation, eq. 10]: the extra length of a parabolic span of sag ȳ_0·a,
    :func:`chaindrive.geometry.sag.slack_for_sag` ([Irvine1981, ch. 1]).
    """
    return slack_for_sag(positive("span_length", span_length),
                         positive("relative_amplitude", relative_amplitude))


@shared_parameters
def max_dynamic_force(tension: ArrayLike, relative_amplitude: ArrayLike,
                      coefficients: HingeFrictionCoefficients = PR_12_7_1820_1,
                      ) -> NDArray[np.float64]:
    """Largest span force F_max [N] during the vibration (empirical fit).

    %(hinge_force_returns)s
    ndarray
        F_max [N].

    References
    ----------
    [ChainHingeDissipation, eq. 11].
    """
    F0 = positive("tension", tension)
    y = positive("relative_amplitude", relative_amplitude)
    k = coefficients
    return k.k1 + k.k2 * y + k.k3 * F0 + k.k4 * y * y + k.k5 * y * F0 + k.k6 * F0 * F0


@shared_parameters
def dynamic_load_factor(tension: ArrayLike, relative_amplitude: ArrayLike,
                        coefficients: HingeFrictionCoefficients = PR_12_7_1820_1,
                        ) -> NDArray[np.float64]:
    """K_aF = F_a / F_0 = (F_max − F_0) / F_0 [-].

    %(hinge_force_returns)s
    ndarray
        K_aF [-].

    References
    ----------
    [ChainHingeDissipation, eq. 13].
    """
    F0 = positive("tension", tension)
    return (max_dynamic_force(F0, relative_amplitude, coefficients) - F0) / F0


@shared_parameters
def max_potential_energy(span_length: ArrayLike, relative_amplitude: ArrayLike,
                         tension: ArrayLike,
                         coefficients: HingeFrictionCoefficients = PR_12_7_1820_1,
                         ) -> NDArray[np.float64]:
    """Largest potential energy of the cycle E = 0.5 F_a Δl_max = (4/3) a ȳ_0² F_0 K_aF [J].

    Parameters
    ----------
    span_length : array_like
        Span length a [m].
    %(amplitude_tension_fit_returns)s
    ndarray
        E [J].

    References
    ----------
    [ChainHingeDissipation, eqs. 9, 12].
    """
    F0 = positive("tension", tension)
    k_af = dynamic_load_factor(F0, relative_amplitude, coefficients)
    return 0.5 * k_af * F0 * span_elongation_max(span_length, relative_amplitude)


@shared_parameters
def absorption_coefficient(friction: ArrayLike, pin_diameter: ArrayLike, span_length: ArrayLike,
                           relative_amplitude: ArrayLike, tension: ArrayLike,
                           coefficients: HingeFrictionCoefficients = PR_12_7_1820_1,
                           ) -> NDArray[np.float64]:
    """Absorption coefficient ψ = W / E = 6π f d_2 / (ȳ_0 a K_aF) [-].

    Parameters
    ----------
    friction : array_like
        Coefficient of friction f in the hinges [-].
    pin_diameter : array_like
        Pin diameter d_2 [m].
    span_length : array_like
        Span length a = t (z − 1) [m].
    %(amplitude_tension_fit_returns)s
    ndarray
        ψ [-].

    References
    ----------
    [ChainHingeDissipation, eq. 14].
    """
    y = positive("relative_amplitude", relative_amplitude)
    k_af = dynamic_load_factor(tension, y, coefficients)
    if np.any(k_af <= 0):
        raise DesignError("coefficients", "the F_max fit gives F_max ≤ F_0 (K_aF ≤ 0) here")
    return (6.0 * math.pi * positive("friction", friction) * positive("pin_diameter", pin_diameter)
            / (y * positive("span_length", span_length) * k_af))


def equivalent_damping_ratio(absorption: ArrayLike) -> NDArray[np.float64]:
    """Viscous damping ratio ζ = ψ / (4π) [-] equivalent to an absorption coefficient ψ
    (ψ = ΔW/W = 2δ for light damping and δ = 2πζ, the logarithmic decrement).

    Parameters
    ----------
    absorption : array_like
        Absorption coefficient ψ [-].

    Returns
    -------
    ndarray
        ζ [-].

    References
    ----------
    [Panovko1960].
    """
    return np.asarray(absorption, dtype=float) / (4.0 * math.pi)


def damped_frequencies(frequencies: ArrayLike, damping_ratio: ArrayLike) -> NDArray[np.float64]:
    """Damped natural frequencies ω_d = ω sqrt(1 − ζ²), mode by mode (modal damping).

    Parameters
    ----------
    frequencies : array_like
        Undamped natural frequencies [any frequency unit, kept].
    damping_ratio : array_like
        Damping ratio ζ [-], from 0 to below 1.

    Returns
    -------
    ndarray
        ω_d [unit of ``frequencies``].

    Raises
    ------
    DesignError
        ``damping_ratio`` out of range.

    References
    ----------
    [Rao2011, §2.6] (single-degree-of-freedom viscous damping); [MultimassChainDrives,
    Table 1] compares undamped and damped frequencies this way.
    """
    z = np.asarray(damping_ratio, dtype=float)
    if np.any((z < 0) | (z >= 1)):
        raise DesignError("damping_ratio", f"must be from 0 to below 1, got {damping_ratio!r}")
    return np.asarray(np.asarray(frequencies, dtype=float) * np.sqrt(1.0 - z * z), dtype=np.float64)


@dataclass(frozen=True, slots=True)
class HingeFrictionResult:
    """Hinge-friction damping of a span at one operating point (F_0, ȳ_0, a).

    Parameters
    ----------
    tension : float
        Static span tension F_0 [N].
    relative_amplitude : float
        ȳ_0 [-].
    span_length : float
        Span length a [m].
    dissipated_energy : float
        W per cycle [J].
    potential_energy : float
        Largest potential energy E of the cycle [J].
    dynamic_load_factor : float
        K_aF [-].
    absorption_coefficient : float
        ψ = W/E [-].
    damping_ratio : float
        ζ = ψ/4π [-].
    """

    tension: float
    relative_amplitude: float
    span_length: float
    dissipated_energy: float
    potential_energy: float
    dynamic_load_factor: float
    absorption_coefficient: float
    damping_ratio: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"tension_n": self.tension, "relative_amplitude": self.relative_amplitude,
                "span_length_m": self.span_length,
                "dissipated_energy_j": self.dissipated_energy,
                "potential_energy_j": self.potential_energy,
                "dynamic_load_factor": self.dynamic_load_factor,
                "absorption_coefficient": self.absorption_coefficient,
                "damping_ratio": self.damping_ratio}


def hinge_friction_damping(tension: float, relative_amplitude: float, span_length: float,
                           coefficients: HingeFrictionCoefficients = PR_12_7_1820_1,
                           ) -> HingeFrictionResult:
    """[ChainHingeDissipation]'s model for one span: W, E, K_aF, ψ and ζ = ψ/4π.

    Parameters
    ----------
    tension : float
        Static span tension F_0 [N].
    relative_amplitude : float
        ȳ_0 [-] (the paper: 0.015…0.03).
    span_length : float
        Span length a [m].
    coefficients : HingeFrictionCoefficients
        The chain's fit and hinge data (friction, pin diameter).

    Returns
    -------
    HingeFrictionResult
        The energies and coefficients.

    References
    ----------
    [ChainHingeDissipation, eqs. 6–14]; [Panovko1960] (ζ = ψ/4π).
    """
    c = coefficients
    y0 = relative_amplitude * span_length
    W = float(dissipated_energy_per_cycle(c.friction, tension, c.pin_diameter, y0, span_length))
    E = float(max_potential_energy(span_length, relative_amplitude, tension, c))
    psi = float(absorption_coefficient(c.friction, c.pin_diameter, span_length,
                                       relative_amplitude, tension, c))
    return HingeFrictionResult(
        tension=float(tension), relative_amplitude=float(relative_amplitude),
        span_length=float(span_length), dissipated_energy=W, potential_energy=E,
        dynamic_load_factor=float(dynamic_load_factor(tension, relative_amplitude, c)),
        absorption_coefficient=psi, damping_ratio=psi / (4.0 * math.pi),
    )


def hinge_friction_grid(coefficients: HingeFrictionCoefficients, tensions: Sequence[float],
                        relative_amplitudes: Sequence[float], span_length: float
                        ) -> tuple[HingeFrictionResult, ...]:
    """The hinge-friction model over a grid of tensions and relative amplitudes (a study of
    how ψ moves with the operating point [ChainHingeDissipation]).

    Parameters
    ----------
    coefficients : HingeFrictionCoefficients
        The chain's fit and hinge data.
    tensions : sequence of float
        Static tensions F₀ [N].
    relative_amplitudes : sequence of float
        Relative amplitudes ȳ₀ [-].
    span_length : float
        Span length a [m].

    Returns
    -------
    tuple of HingeFrictionResult
        One per (F₀, ȳ₀), tensions varying slowest.
    """
    return tuple(hinge_friction_damping(f0, y, span_length, coefficients)
                 for f0 in tensions for y in relative_amplitudes)


# ---------------------------------------------------------------------------------------
# Material (hysteretic) damping of the ring, added to the hinge-friction damping
# ---------------------------------------------------------------------------------------

#: Typical loss factors η (= 2ζ at resonance) by material family, room temperature, low
#: frequency. Steels: 10⁻⁴…10⁻³ (Cremer & Heckl, Structure-borne sound, table via
#: T. Irvine, "Damping properties of materials", 2004; NPTEL 112104040 table 9.1 gives the
#: order 10⁻³); grey cast iron: order 10⁻² (same NPTEL table); polyamides: tan δ ≈ 0.02…0.04
#: dry at 23 °C, glass-filled lower, acetal ≈ 0.01…0.02 (M.P. Sepe, Dynamic Mechanical
#: Analysis for Plastics Engineering, 1998 — typical DMA curves; values are typical, not
#: guaranteed: replace them with measured ones for a real design).
LOSS_FACTORS: dict[str, float] = {
    "steel": 5e-4, "carbon steel": 5e-4, "alloy steel": 5e-4, "case-hardening steel": 5e-4,
    "cast steel": 5e-4, "grey cast iron": 1e-2, "cast iron": 1e-2,
    "polyamide": 0.03, "glass-filled polyamide": 0.02, "acetal": 0.015,
    "polyethylene": 0.05, "laminate": 0.03,
}
POLYMER_LOSS_FACTOR = 0.03


def loss_factor(family: str, polymer: bool = False) -> float:
    """Loss factor η [–] of a material family (:data:`LOSS_FACTORS`); unknown families take
    the steel value, or :data:`POLYMER_LOSS_FACTOR` for a polymer."""
    return LOSS_FACTORS.get(family, POLYMER_LOSS_FACTOR if polymer else LOSS_FACTORS["steel"])


def series_loss_factor(loss_factors: ArrayLike, compliances: ArrayLike) -> NDArray[np.float64]:
    """Loss factor of springs in series [–]: η = Σ η_k/c_k / Σ 1/c_k, the strain-energy
    weighted mean (at one force the energy of spring k is F²/(2c_k)); ``compliances`` 1/c_k
    stacked on the first axis, like ``loss_factors``."""
    eta = np.asarray(loss_factors, dtype=float)
    comp = np.asarray(compliances, dtype=float)
    return np.asarray(np.sum(eta * comp, axis=0) / np.sum(comp, axis=0), dtype=np.float64)


def modal_loss_factor(loss_factors: ArrayLike, stiffness: ArrayLike, shape: ArrayLike) -> float:
    """Loss factor of one mode by the modal strain energy method (Johnson & Kienholz, AIAA J.
    20 (1982) 1284): η_j = Σ_b η_b U_b / Σ_b U_b, U_b = c_b (x_{b+1} − x_b)² / 2 the strain
    energy of branch b in the mode (ring: branch b joins mass b and b+1)."""
    x = np.asarray(shape, dtype=float)
    c = np.asarray(stiffness, dtype=float)
    energy = c * (np.roll(x, -1) - x) ** 2
    total = float(energy.sum())
    return float(np.dot(np.asarray(loss_factors, dtype=float), energy) / total) if total else 0.0
