"""The bibliography of the report: every entry of ``docs/references.md`` (the project's
one list of sources), keyed as the code and the report cite them (``[MultimassChainDrives,
§3.6]``). ``tests/unit/test_report_typst.py`` keeps the two in step; *text between
asterisks* is a title (set in italics).
"""

from __future__ import annotations

import re

__all__ = ["REFERENCES", "cited_keys"]

#: Key → (heading of docs/references.md, entry text).
REFERENCES: dict[str, tuple[str, str]] = {
    'MultimassChainDrives': ('The source papers of the design method',
        '*Dynamics and computer-aided optimal synthesis of multimass chain drives with '
        'metallic and polymeric chains and sprockets* (the "POSCD" design complex: '
        'geometric, force, kinematic, dynamic and optimisation modules for contours of 2 '
        'to 24 sprockets). Journal paper in English; the extracted text carries neither '
        'the authors nor the year. Cited for the n-mass ring model and its reduced masses '
        '(§3.1–3.3), the natural frequencies and normalised amplitudes (eq. 2), the '
        'damping D = 0.06 and Table 1, the start-up and amplitude–frequency '
        'characteristics (Fig. 2–3), the polymeric sprocket proportions (§3.4), the '
        'two-stage safety check k₁, k₂, k₂min with [k] = 2.5 (§3.6) and the '
        'three-sprocket worked example.'),
    'ChainHingeDissipation': ('The source papers of the design method',
        '*Energy dissipation in a drive chain under transverse vibration of its branches* '
        '(Russian, with English abstract; title as given by its abstract: "Рассеяние '
        'энергии при поперечных колебаниях ветвей цепной передачи"). Hinge friction model '
        'of a span vibrating as a string with fixed ends: energy dissipated per cycle W, '
        'energy E, absorption coefficient ψ = W/E, checked by free-decay experiments.'),
    'ChainNonUniformity': ('The source papers of the design method',
        '*Analysis of motion non-uniformity of chain drives* (textbook section, English). '
        'Mean chain speed v = z p n / 60 000, instantaneous speed v = R ω cos β, the '
        'non-constant instantaneous ratio (polygonal effect), eq. 4–6.'),
    'Lyashuk': ('The source papers of the design method',
        "O. L. Lyashuk (Ляшук О. Л.), *Вплив точності шпонкових з'єднань на несучу "
        'здатність багатоконтурних ланцюгових передач* (Influence of the accuracy of '
        'keyed joints on the load capacity of multi-contour chain drives), Ternopil Ivan '
        'Puluj National Technical University. Keyed-joint clearances, the 14 placements '
        '(Table 1), ΔL₃ and its half-normal distribution (eq. 13–14), K_m at a given risk '
        '(eq. 15–18).'),
    'ISO606': ('Standards',
        'ISO 606:2015 *Short-pitch transmission precision roller and bush chains, '
        'attachments and associated chain sprockets* (International Organization for '
        'Standardization). Chain dimensions and breaking loads (A and B series), sprocket '
        'tooth form (seating curve, flank, tip and root diameters).'),
    'ISO10823': ('Standards',
        'ISO 10823:2004 *Guidance on the selection of roller chain drives*.'),
    'GOST13568': ('Standards',
        'GOST 13568-97 (ISO 606-94) *Приводные роликовые и втулочные цепи. Общие '
        'технические условия* (Drive roller and bush chains. General specifications).'),
    'GOST591': ('Standards',
        'GOST 591-69 *Звездочки к приводным роликовым и втулочным цепям. Методы расчета и '
        'построения профиля зуба и инструмента. Допуски* (Sprockets for drive roller and '
        'bush chains: tooth profile and tolerances).'),
    'ANSI-B29.1': ('Standards',
        'ASME B29.1-2011 *Precision power transmission roller chains, attachments, and '
        'sprockets* (American Society of Mechanical Engineers).'),
    'ISO6336-1': ('Standards',
        'ISO 6336-1:2019 *Calculation of load capacity of spur and helical gears — Part '
        '1: Basic principles, introduction and general influence factors* (single '
        'tooth-pair stiffness c′).'),
    'NIST-SP811': ('Standards',
        'A. Thompson, B. N. Taylor, *Guide for the Use of the International System of '
        'Units (SI)*, NIST Special Publication 811, 2008 edition, National Institute of '
        'Standards and Technology (Appendix B: factors for converting US customary units '
        'to SI).'),
    'API684': ('Standards',
        'API Standard 684, *Rotordynamic tutorial: lateral critical speeds, unbalance '
        'response, stability, train torsionals and rotor balancing*, 2nd ed., American '
        'Petroleum Institute, 2005 (separation margins).'),
    'Rao2011': ('Books and papers',
        'S. S. Rao, *Mechanical Vibrations*, 5th ed., Prentice Hall, 2011.'),
    'Shigley2015': ('Books and papers',
        "R. G. Budynas, J. K. Nisbett, *Shigley's Mechanical Engineering Design*, 10th "
        'ed., McGraw-Hill, 2015 (chapter 17, roller chain; ACA rating equations).'),
    'Bhandari2010': ('Books and papers',
        'V. B. Bhandari, *Design of Machine Elements*, 3rd ed., Tata McGraw-Hill, 2010 '
        '(chapter 14, chain drives).'),
    'Bolotin1964': ('Books and papers',
        'V. V. Bolotin, *The Dynamic Stability of Elastic Systems*, Holden-Day, 1964 '
        '(principal parametric resonance).'),
    'Mote1965': ('Books and papers',
        'C. D. Mote, "A study of band saw vibrations", *Journal of the Franklin '
        'Institute* 279(6), 1965, 430–444 (transverse vibration of an axially moving '
        'string).'),
    'Ernst1965': ('Books and papers',
        'H.-J. Ernst, "Der E-Modul von Seilen unter Berücksichtigung des Durchhanges", '
        '*Der Bauingenieur* 40(2), 1965, 52–55 (equivalent modulus of a sagging cable).'),
    'Naji1983': ('Books and papers',
        'M. R. Naji, K. M. Marshek, "Analysis of sprocket load distribution", *Mechanism '
        'and Machine Theory* 18(5), 1983, 349–356.'),
    'VanLoan1978': ('Books and papers',
        'C. F. Van Loan, "Computing integrals involving the matrix exponential", *IEEE '
        'Transactions on Automatic Control* 23(3), 1978, 395–404.'),
    'Johnson1982': ('Books and papers',
        'C. D. Johnson, D. A. Kienholz, "Finite element prediction of damping in '
        'structures with constrained viscoelastic layers", *AIAA Journal* 20(9), 1982, '
        '1284–1290 (modal strain energy method).'),
    'Pedersen2004': ('Books and papers',
        'S. L. Pedersen, J. M. Hansen, J. A. C. Ambrósio, "A roller chain drive model '
        'including contact with guide-bars", *Multibody System Dynamics* 12, 2004, '
        '285–301 (rollers as mass particles, links as spring–dampers, sprockets as rigid '
        'bodies).'),
    'Pedersen2005': ('Books and papers',
        'S. L. Pedersen, "Model of contact between rollers and sprockets in chain-drive '
        'systems", *Archive of Applied Mechanics* 74, 2005, 489–508 (continuous '
        'roller–tooth contact force on the real tooth profile).'),
    'BinderCovert1948': ('Books and papers',
        'R. C. Binder, W. V. Covert, "Impact between chain roller and sprocket in a chain '
        'drive", *Journal of the Franklin Institute* 245(4), 1948, 319–329.'),
    'Lankarani1990': ('Books and papers',
        'H. M. Lankarani, P. E. Nikravesh, "A contact force model with hysteresis damping '
        'for impact analysis of multibody systems", *Journal of Mechanical Design* 112, '
        '1990, 369–376.'),
    'Gilardi2002': ('Books and papers',
        'G. Gilardi, I. Sharf, "Literature survey of contact dynamics modelling", '
        '*Mechanism and Machine Theory* 37(10), 2002, 1213–1239 (linear spring–dashpot '
        'contact and its coefficient of restitution).'),
    'Hairer2006': ('Books and papers',
        'E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., '
        'Springer, 2006 (symplectic Euler, Störmer–Verlet and their stability).'),
    'Press2007': ('Books and papers',
        'W. H. Press, S. A. Teukolsky, W. T. Vetterling, B. P. Flannery, *Numerical '
        'Recipes*, 3rd ed., Cambridge University Press, 2007 (§2.4 tridiagonal systems, '
        '§2.7 cyclic tridiagonal systems by Sherman–Morrison).'),
    'Roark2012': ('Books and papers',
        "W. C. Young, R. G. Budynas, A. M. Sadegh, *Roark's Formulas for Stress and "
        'Strain*, 8th ed., McGraw-Hill, 2012.'),
    'Bevan2005': ('Books and papers',
        'T. Bevan, *The Theory of Machines*, 3rd ed., reprint CBS Publishers, New Delhi, '
        '2005, ISBN 81-239-0874-1; ch. 15, torsional vibration, Examples 9 (p. 572) and '
        '11 (p. 587).'),
    'Sarkar2002': ('Books and papers',
        'B. K. Sarkar, *Theory of Machines*, Tata McGraw-Hill, 2002, ISBN 0-07-048288-8; '
        'ch. 11, Illustrations 3 (p. 291) and 12 (p. 298).'),
    'Khurmi2005': ('Books and papers',
        'R. S. Khurmi, J. K. Gupta, *Theory of Machines*, S. Chand & Co., New Delhi (2005 '
        'printing); ch. 24, torsional vibrations (three-rotor system).'),
    'Guyan1965': ('Books and papers',
        'R. J. Guyan, "Reduction of stiffness and mass matrices", *AIAA Journal* 3(2), '
        '1965, 380 (static condensation).'),
    'Friswell2010': ('Books and papers',
        'M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, *Dynamics of Rotating '
        'Machines*, Cambridge University Press, 2010 (torsional models with gear '
        'constraints; the method of openTorsion).'),
    'MotiveDelphi': ('Books and papers',
        'Motive s.r.l. (Italy), *Delphi series asynchronous three-phase electric motors — '
        'general catalogue*, technical data tables "2 poles 3000 rpm", "4 poles 1500 '
        'rpm", "6 poles 1000 rpm" (400 V 50 Hz, frames 56–355, rotor moment of inertia J '
        "[kg·m²]); manufacturer's catalogue of IEC cage-induction motors."),
    'Jindal2010': ('Books and papers',
        'U. C. Jindal, *Machine Design*, Pearson Education, 2010 (chapter 30, chain '
        'drives; Table 30-8 ratings, examples 30-2 and 30-3).'),
    'Mott2014': ('Books and papers',
        'R. L. Mott, *Machine Elements in Mechanical Design*, 5th ed., Pearson, 2014 '
        '(chapter 7, chain drives: service factors, design rules, wrap ≥ 120°).'),
    'Irvine1981': ('Books and papers',
        'H. M. Irvine, *Cable Structures*, MIT Press, 1981 (shallow parabolic cable: arc '
        'length ℓ + 8f²/(3ℓ)).'),
    'TrinhChat2006': ('Books and papers',
        'Trịnh Chất, Lê Văn Uyển, *Tính toán thiết kế hệ dẫn động cơ khí* (Design of '
        'mechanical drive systems), vol. 1, Nhà xuất bản Giáo dục (Education Publishing '
        'House), Hanoi, 2006 (Russian-derived tables 5.2–5.12: Kэ factors, n1 max, [i], '
        '[s], row factors), read through course programs that reproduce its tables.'),
    'ChainDesignRU': ('Catalogues, guides and compiled method notes',
        'The classical Russian roller-chain method (Иванов, Дунаев–Леликов, Решетов, '
        'Чернавский, Шейнблит) as reproduced by course programs and guides, compiled with '
        "each table's source in the project's method notes: Kэ factors, [p] (Table 2A), "
        'n1 max, [s] (Table 9A), link count, centre distance and sag reduction Δa = '
        '(0.002…0.004)·a, GOST 13568-97 §10 installation rules.'),
    'DiamondChain': ('Catalogues, guides and compiled method notes',
        'Diamond Chain Company, *Technical engineering guide* (working load at most 1/6 '
        'of the minimum ultimate tensile strength; never above 50 % even once).'),
    'McGuireLube': ('Catalogues, guides and compiled method notes',
        'McGuire Bearing Company, roller chain lubrication table (highest chain speed of '
        'ANSI lubrication types A and B per chain number).'),
    'KettenfabrikUnna': ('Catalogues, guides and compiled method notes',
        'Kettenfabrik Unna, lubrication notes (manual lubrication up to about 0.5 m/s, '
        'drip up to about 1.5 m/s).'),
    'Renold-DG': ('Catalogues, guides and compiled method notes',
        'Renold plc, *Transmission chain: installation, maintenance & designer guide* '
        '(idler sprockets: at least three teeth in engagement; chain adjustment).'),
    'Donghua2020': ('Catalogues, guides and compiled method notes',
        'Donghua Chain Group, *Drive Chains 2020* product catalogue (ANSI 41 and '
        "heavy-series dimensions, minimum tensile strength, mass), the catalogue's text "
        'read in a public repository copy.'),
}

_CITATION = re.compile(r"\[([A-Za-z][\w.-]*)(?:,[^\]]*)?\]")


def cited_keys(text: str) -> list[str]:
    """The keys of :data:`REFERENCES` cited in ``text`` (``[Key]`` or ``[Key, §3.6]``), in
    order of first citation."""
    seen: dict[str, None] = {}
    for m in _CITATION.finditer(text):
        if m.group(1) in REFERENCES:
            seen.setdefault(m.group(1))
    return list(seen)
