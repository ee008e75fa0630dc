"""The symbols of the report: what each one means, its formula, its unit and its source.

A section that uses a symbol asks :meth:`chaindrive.report.content.ReportInput.define` for
it; the first section to ask defines it (a "Symbols" table with the formula and the
reference), so that every number of the report can be traced to a formula and a source.

Each symbol is written twice: ``text`` / ``formula`` in Unicode for the HTML report and the
tables, ``math`` / ``formula_math`` in Typst math for the PDF.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["SYMBOLS", "Symbol", "symbol"]


@dataclass(frozen=True, slots=True)
class Symbol:
    """One symbol of the report.

    Parameters
    ----------
    key : str
        Identifier used by the sections (``"k1"``).
    text : str
        The symbol in Unicode (``"k₁"``).
    math : str
        The symbol in Typst math (``"k_1"``).
    meaning : str
        What it is.
    formula : str
        Its formula in Unicode ("" for an input).
    formula_math : str
        Its formula in Typst math ("" for an input).
    unit : str
        Kind of quantity of :data:`chaindrive.display.QUANTITIES` (its unit follows the
        report's unit system), or a fixed unit ("%", "teeth", "1"), or "" (dimensionless).
    source : str
        Citation of docs/references.md (``"[MultimassChainDrives, §3.6]"``), or where an
        input comes from.
    """

    key: str
    text: str
    math: str
    meaning: str
    formula: str = ""
    formula_math: str = ""
    unit: str = ""
    source: str = ""


_ALL: tuple[Symbol, ...] = (
    # --- inputs ---------------------------------------------------------------------------
    Symbol("P", "P", "P", "power transmitted from the driver", unit="power",
           source="design file"),
    Symbol("n1", "n₁", "n_1", "speed of the driver", unit="speed", source="design file"),
    Symbol("Ks", "K_s", "K_s", "service (application) factor of the drive; the Kэ method "
           "uses it as its operating factor Kэ", source="design file, [ChainDesignRU]"),
    Symbol("p", "p", "p", "chain pitch", unit="length", source="[ISO606], [GOST13568]"),
    Symbol("d1", "d₁", "d_1", "roller diameter of the chain (maximum)", unit="length",
           source="[ISO606], [GOST13568]"),
    Symbol("b1", "b₁", "b_1", "width between the inner plates (minimum)", unit="length",
           source="[ISO606], [GOST13568]"),
    Symbol("Q", "Q", "Q", "breaking load (minimum tensile strength) of the whole chain",
           unit="force_k", source="[ISO606], [GOST13568]"),
    Symbol("q", "q", "q", "mass of the chain per unit length", unit="linear_density",
           source="[ISO606], [GOST13568]"),
    Symbol("z", "z", "z", "number of teeth of a sprocket", source="design file"),
    Symbol("zeta", "ζ", "zeta", "damping ratio of the ring (hinge friction; material "
           "damping of polymer parts added by modal strain energy): [dynamics] damping_ratio "
           "when given, else by the material pair of chain and sprockets (0.06 for metal on "
           "metal)", "ζ = D", "zeta = D",
           source="[MultimassChainDrives, Table 1], [Johnson1982]"),
    # --- geometry -------------------------------------------------------------------------
    Symbol("d", "d", "d", "pitch diameter (circle through the roller centres)",
           "d = p / sin(180°/z)", "d = p / sin(180 degree \\/ z)", "length",
           "[ISO606], [GOST591]"),
    Symbol("da_iso", "d_a", "d_a", "tip diameter, ISO 606: mean of the two limits (any value "
           "between d_a,min and d_a,max is standard)",
           "d_a,max = d + 1.25 p − d₁; d_a,min = d + p (1 − 1.6/z) − d₁",
           "d_(a,max) = d + 1.25 p - d_1 ;quad d_(a,min) = d + p (1 - 1.6 \\/ z) - d_1",
           "length", "[ISO606]"),
    Symbol("da_gost", "D_e", "D_e", "tip diameter, GOST 591 (K from the table of λ = p/d₁)",
           "D_e = p (K + cot(180°/z))", "D_e = p (K + cot(180 degree \\/ z))", "length",
           "[GOST591]"),
    Symbol("df_iso", "d_f", "d_f", "root diameter, ISO 606", "d_f = d − d₁",
           "d_f = d - d_1", "length", "[ISO606]"),
    Symbol("df_gost", "D_i", "D_i", "root diameter, GOST 591 (r: seating radius)",
           "D_i = d − 2r, r = 0.5025 d₁ + 0.05 mm", "D_i = d - 2 r, quad r = 0.5025 d_1 + "
           "0.05 \"mm\"", "length", "[GOST591]"),
    Symbol("theta", "θ", "theta", "wrap angle: the arc of the pitch circle between the "
           "tangent points of the arriving and the leaving span",
           "from the common tangents of neighbouring pitch circles",
           "theta_k = \"angle between the tangent points\"", "angle",
           "[MultimassChainDrives, §3.1]"),
    Symbol("zm", "z_m", "z_m", "teeth in mesh (teeth within the wrap)", "z_m = z θ / 360°",
           "z_m = z theta \\/ 360 degree", "teeth", "[Renold-DG]"),
    Symbol("ell", "ℓ", "ell", "length of a span (tangent between two pitch circles)",
           unit="length", source="[MultimassChainDrives, §3.1]"),
    Symbol("Lp", "L_p", "L_p", "number of links: the tight contour length in pitches, "
           "rounded up to a whole (even) number; the take-up moves the adjustable sprocket "
           "to fit it", "L_p ≥ Σℓ/p + Σ z θ/360°",
           "L_p >= sum ell \\/ p + sum z theta \\/ 360 degree", "1",
           "[MultimassChainDrives, §3.1]"),
    # --- kinematics -----------------------------------------------------------------------
    Symbol("v", "v", "v", "mean chain speed", "v = z₁ p n₁ / 60", "v = z_1 p n_1 \\/ 60",
           "velocity", "[ChainNonUniformity, eq. 4]"),
    Symbol("fz", "f_z", "f_z", "tooth (mesh) frequency", "f_z = z₁ n₁ / 60",
           "f_z = z_1 n_1 \\/ 60", "frequency", "[MultimassChainDrives, §3.3]"),
    Symbol("dv", "δ_v", "delta_v", "speed variation of the chain over one tooth (polygonal "
           "effect)", "δ_v = 100 (1 − cos(180°/z)) %", "delta_v = 100 (1 - cos(180 degree "
           "\\/ z)) %", "%", "[ChainNonUniformity, eq. 5]"),
    # --- loads and strength ---------------------------------------------------------------
    Symbol("Ft", "F_t", "F_t", "peripheral (useful) force of the driver", "F_t = P / v",
           "F_t = P \\/ v", "force", "[Shigley2015, §17-5]"),
    Symbol("F0", "F₀", "F_0", "sag tension of the slack span (k_f from its inclination, "
           "a its length, g = 9.81 m/s²)", "F₀ = k_f q g a", "F_0 = k_f q g a", "force",
           "[ChainDesignRU]"),
    Symbol("Fv", "F_v", "F_v", "centrifugal tension", "F_v = q v²", "F_v = q v^2", "force",
           "[ChainDesignRU]"),
    Symbol("FR", "F_R", "F_R", "static tension of a span: F₀ + F_v on the slack span leaving "
           "the driver, raised by each driven sprocket's peripheral force against the "
           "direction of travel up to the tight span",
           "F_R,out = F_R,in + F_t,k at sprocket k", "F_(R,\"out\") = F_(R,\"in\") + F_(t,k)",
           "force", "[ChainDesignRU]"),
    Symbol("Fs", "F_s", "F_s", "shaft load: vector sum of the pulls of the arriving and the "
           "leaving span (less F_v)", "F_s = |(F_R,out − F_v) e_out − (F_R,in − F_v) e_in|",
           "F_s = |(F_(R,\"out\") - F_v) bold(e)_\"out\" - (F_(R,\"in\") - F_v) "
           "bold(e)_\"in\"|", "force", "[ChainDesignRU]"),
    Symbol("ph", "p_h", "p_h", "mean pressure in the chain joints (A: projected bearing area "
           "of the joints)", "p_h = Kэ F_t / A", "p_h = K_\"э\" F_t \\/ A", "pressure",
           "[ChainDesignRU]"),
    Symbol("ph_allow", "[p_h]", "[p_h]", "allowable joint pressure of the Kэ method (GOST "
           "chains: table by pitch and speed of the small sprocket; a rated chain has none, its "
           "rating is its wear and fatigue limit)", unit="pressure",
           source="[ChainDesignRU, Table 2A]"),
    Symbol("s", "s", "s", "static safety factor (k_д = 1: dynamic factor of the Kэ method)",
           "s = Q / (k_д F_t + F₀ + F_v)", "s = Q / (k_\"д\" F_t + F_0 + F_v)", "1",
           "[ChainDesignRU]"),
    Symbol("s_allow", "[s]", "[s]", "allowable static safety factor (GOST chains: table by "
           "pitch and speed; rated chains: working load ≤ 1/6 of the breaking load)", unit="1",
           source="[TrinhChat2006, Table 5.10]; [DiamondChain]"),
    Symbol("Prated", "P_r", "P_r", "rated power of the chain at the small sprocket's speed "
           "(ACA or ISO 606 B tables)", unit="power", source="[Shigley2015, §17-5]"),
    Symbol("Lh", "L_h", "L_h", "wear life to the permitted elongation",
           "L_h = 15 000 h (P_r / (K_s P))^2.5 L_p / 100",
           "L_h = 15000 \"h\" (P_r \\/ (K_s P))^2.5 L_p \\/ 100", "hours",
           "[Shigley2015, Eq. 17-40]"),
    # --- checks ---------------------------------------------------------------------------
    Symbol("margin", "m", "m", "margin of a check: ≥ 0 passes, < 0 fails (the same sign for "
           "every check)", "m = limit/value − 1 (upper limit); m = value/limit − 1 (lower "
           "limit)", "m = \"limit\" \\/ \"value\" - 1 \" (upper)\";quad m = \"value\" \\/ "
           "\"limit\" - 1 \" (lower)\"", "%", "chaindrive.checks"),
    # --- dynamics -------------------------------------------------------------------------
    Symbol("m_i", "m_i", "m_i", "reduced mass of sprocket i on its pitch circle (I_i: moment "
           "of inertia of all that turns with it, R_i = d_i/2)", "m_i = I_i / R_i²",
           "m_i = I_i \\/ R_i^2", "mass", "[MultimassChainDrives, §3.1]"),
    Symbol("c_i", "c_i", "c_i", "stiffness of the branch from mass i to mass i+1: chain span, "
           "teeth of the wrap and sag in series", "1/c_i = 1/c_chain + 1/c_wrap + 1/c_sag",
           "1 \\/ c_i = 1 \\/ c_\"chain\" + 1 \\/ c_\"wrap\" + 1 \\/ c_\"sag\"", "stiffness",
           "[MultimassChainDrives, §3.1], [Ernst1965]"),
    Symbol("fj", "f_j", "f_j", "natural frequency of mode j of the ring (M: masses, K: "
           "stiffness matrix of the closed ring)", "det(K − (2π f_j)² M) = 0",
           "det(K - (2 pi f_j)^2 M) = 0", "frequency", "[MultimassChainDrives, eq. 2]"),
    Symbol("X", "X^(j)", "X^((j))", "mode shape of mode j: the signed displacement of every "
           "mass along the chain (a node where it changes sign)",
           "(K − (2π f_j)² M) X^(j) = 0", "(K - (2 pi f_j)^2 M) X^((j)) = 0", "",
           "[MultimassChainDrives, eq. 2]"),
    Symbol("mu", "μ", "mu", "relative amplitude of mass k in mode j",
           "μ_k^(j) = |X_k^(j)| / Σ_i |X_i^(j)|",
           "mu_k^((j)) = |X_k^((j))| \\/ sum_i |X_i^((j))|", "", "[MultimassChainDrives, eq. 2]"),
    Symbol("fw", "f_w", "f_w", "working (disturbing) frequency: shaft rotations f_i = n_i/60 "
           "and the harmonics k f_z of the tooth frequency", "f_w ∈ {n_i/60, k f_z}",
           "f_w in {n_i \\/ 60, k f_z}", "frequency", "[MultimassChainDrives, §3.3]"),
    Symbol("detuning", "Δ", "Delta", "detuning of a working frequency from the nearest natural "
           "frequency (below or above it)", "Δ = |f_w − f_n| / f_n · 100 %",
           "Delta = |f_w - f_n| \\/ f_n dot 100 %", "%", "[MultimassChainDrives, §3.2], "
           "[API684]"),
    Symbol("fspan", "f_ℓ", "f_ell", "first transverse frequency of a span moving at v under "
           "the tension F_R; its principal parametric resonance is at f_z ≈ 2 f_ℓ",
           "f_ℓ = (1/2ℓ) √(F_R/q) (1 − q v²/F_R)",
           "f_ell = 1 / (2 ell) sqrt(F_R \\/ q) (1 - q v^2 \\/ F_R)", "frequency",
           "[Mote1965], [Bolotin1964]"),
    # --- dynamic response -----------------------------------------------------------------
    Symbol("F2", "F₂", "F_2", "peak of the steady dynamic load of a span at the working "
           "speed (polygonal excitation, all harmonics)", unit="force",
           source="[MultimassChainDrives, §3.3]"),
    Symbol("F2max", "F₂max", "F_(2 max)", "largest steady dynamic load of a span over the "
           "speed sweep (resonances in the run-up)", unit="force",
           source="[MultimassChainDrives, Fig. 3]"),
    Symbol("F1max", "F₁max", "F_(1 max)", "largest span force in the start-up from rest",
           unit="force", source="[MultimassChainDrives, Fig. 2]"),
    Symbol("FD", "F_D", "F_D", "dynamic load: root mean square over the spans of F₂",
           "F_D = √(Σ F₂,i² / n)", "F_D = sqrt(sum F_(2,i)^2 \\/ n)", "force",
           "[MultimassChainDrives, §3.3]"),
    Symbol("KD", "K_D", "K_D", "coefficient of dynamics", "K_D = 1 + F_D / F_t",
           "K_D = 1 + F_D \\/ F_t", "1", "[MultimassChainDrives, §3.3]"),
    Symbol("k1", "k₁", "k_1", "safety factor in the start-up", "k₁ = Q / F₁max",
           "k_1 = Q \\/ F_(1 max)", "1", "[MultimassChainDrives, §3.6]"),
    Symbol("k2", "k₂", "k_2", "safety factor in steady motion (least over the spans)",
           "k₂ = min_i Q / (F_R,i + F₂,i)", "k_2 = min_i Q \\/ (F_(R,i) + F_(2,i))", "1",
           "[MultimassChainDrives, §3.6]"),
    Symbol("k2min", "k₂min", "k_(2 min)", "safety factor at the resonances of the run-up",
           "k₂min = min_i Q / (F_R,i + F₂max,i)",
           "k_(2 min) = min_i Q \\/ (F_(R,i) + F_(2 max,i))", "1",
           "[MultimassChainDrives, §3.6]"),
    Symbol("k_allow", "[k]", "[k]", "allowable dynamic safety factor", "[k] = 2.5",
           "[k] = 2.5", "1", "[MultimassChainDrives, §3.6]"),
    Symbol("irr", "Δ_ω", "Delta_omega", "irregularity of rotation of a mass (x_A: amplitude "
           "of its displacement on the pitch circle)", "Δ_ω = 2 x_A / R · 100 %",
           "Delta_omega = 2 x_A \\/ R dot 100 %", "%", "[MultimassChainDrives, §3.3]"),
    # --- studies --------------------------------------------------------------------------
    Symbol("psi", "ψ", "psi", "absorption coefficient of a vibrating span (W: energy "
           "dissipated per cycle by hinge friction, E: energy of the vibration)",
           "ψ = W / E; ζ = ψ / 4π", "psi = W \\/ E ;quad zeta = psi \\/ (4 pi)", "",
           "[ChainHingeDissipation]"),
    Symbol("Km", "K_m", "K_m", "load share of the most loaded of m contours on common shafts "
           "(keyed-joint clearances)", unit="1", source="[Lyashuk, eq. 15–18]"),
)

#: Every symbol of the report by key.
SYMBOLS: dict[str, Symbol] = {s.key: s for s in _ALL}


def symbol(key: str) -> Symbol:
    """The symbol ``key`` (KeyError when the report has no such symbol).

    Parameters
    ----------
    key : str
        The symbol's identifier (``"k1"``).

    Returns
    -------
    Symbol
        Its text, Typst math, meaning, formula, unit and source.
    """
    return SYMBOLS[key]
