"""The basis of the B-series ratings: Bhandari's Table 14.2 read against the ANSI tables.

Bhandari, *Design of Machine Elements*, 3rd ed., Table 14.2 (p. 550) [Bhandari2010] prints A-
and B-series chains side by side on one basis (single strand, 17-tooth driving sprocket). Its
B values are the ones chaindrive rates B chains with (``strength/data/ratings_iso606_b.csv``);
its A values are quoted by the book's examples 14.1 (12A, 1000 rpm, 14.32 kW), 14.2 (16A,
300 rpm, 11.63 kW) and 14.3 (08A, 1400 rpm, 5.28 kW), as re-run by the FOSSEE Scilab textbook
companion 764/CH14 (data, solution and result files). Jindal's Table 30-8 [Jindal2010]
(06B, 1000 rpm, 2.03 kW, ex. 30-3) is on the same 17-tooth basis (its tooth factor 1.26 for
21 teeth = (21/17)^1.08).

The comparison is with the ACA formulas [Shigley2015, Eq. 17-32/17-33], which reproduce the
ANSI rating tables within 0.2 % (``tests/unit/test_strength_iso10823.py``) at the same 17
teeth (the tooth count enters the formulas). Two independent published sources for A chains
— the ANSI tables and Table 14.2 — agree within 4.7 % at two of the three printed points and
7.2 % at the third (measured, recorded below); the B rows of the same table lie 7.8 % to
25.8 % above ACA, always above. So the gap for B chains is not a difference of basis between
the table and the ANSI tables: the ACA formulas (made for ANSI chains, roller-bush constant
K_r = 17) rate B chains low, which is why B chains are rated by their printed table where it
has a value (docs/selection.md). No B-series table with several speeds per chain was found as
text (docs/selection.md lists the search), so a held-out check of the interpolation between
printed speeds is still missing.
"""

from __future__ import annotations

import math

import pytest

from chaindrive.catalog import find_chain
from chaindrive.strength import iso10823, ratings

RPM = math.pi / 30
TEETH = 17  # the table's reference sprocket [Bhandari2010, Table 14.2]

# (chain, small-sprocket speed [rpm], printed single-strand rating [kW], where it is printed,
#  measured ACA/table − 1 [%] recorded when this test was written)
A_ROWS = [
    ("12A", 1000.0, 14.32, "Bhandari ex. 14.1", -4.7),
    ("16A", 300.0, 11.63, "Bhandari ex. 14.2", -7.2),
    ("08A", 1400.0, 5.28, "Bhandari ex. 14.3", +4.7),
]
B_ROWS = [
    ("12B", 1400.0, 18.15, "Bhandari ex. 14.4", -25.8),
    ("10B", 1400.0, 11.67, "Bhandari ex. 14.7", -7.8),
    ("06B", 1000.0, 2.03, "Jindal ex. 30-3", -15.0),
]


def _aca(chain: str, rpm: float) -> float:
    single, _ = iso10823.aca_rating(find_chain(f"{chain}-1"), TEETH, rpm * RPM)
    return single


@pytest.mark.parametrize(("chain", "rpm", "printed_kw", "where", "measured_pct"), A_ROWS)
def test_a_rows_of_the_table_agree_with_the_ansi_tables(chain, rpm, printed_kw, where,
                                                        measured_pct):
    """The packaged value is the printed one, and ACA lies within 7.2 % of it (measured:
    −4.7 %, −7.2 %, +4.7 %; recorded to 0.1 percentage point)."""
    source = "Bhandari table 14.2"
    assert iso10823.textbook_rating(source, chain, rpm) == pytest.approx(printed_kw * 1e3)
    deviation = 100.0 * (_aca(chain, rpm) / (printed_kw * 1e3) - 1.0)
    assert deviation == pytest.approx(measured_pct, abs=0.1)


@pytest.mark.parametrize(("chain", "rpm", "printed_kw", "where", "measured_pct"), B_ROWS)
def test_b_rows_of_the_table_lie_above_aca(chain, rpm, printed_kw, where, measured_pct):
    """The packaged B value is the printed one; ACA rates the chain lower (measured −7.8 % to
    −25.8 %), below every A-row deviation of the same table (≥ −7.2 %)."""
    (point,) = [p for p in ratings.b_table() if p.chain == chain and p.speed_rpm == rpm]
    assert point.rating == pytest.approx(printed_kw * 1e3)
    assert point.reference_teeth == TEETH
    deviation = 100.0 * (_aca(chain, rpm) / (printed_kw * 1e3) - 1.0)
    assert deviation == pytest.approx(measured_pct, abs=0.1)
    assert deviation < min(row[4] for row in A_ROWS)
