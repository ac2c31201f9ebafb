"""Finite-bearing coefficients against Lund & Thomsen (1978), two axial 20 deg grooves across
the load: table, bearing and our numbers in studies/lund_thomsen.py.

Tolerances (``python -m studies.lund_thomsen``): on the meshes 72 / 144 / 288 cells around
(L/D 0.5, S 1.656 and 0.244) our eps moves by 0.0016-0.0021 / 0.0004-0.0006, the attitude
by 0.17-0.23 / 0.04-0.06 deg, K by <= 0.4 % / 0.16 % and B by <= 0.5 % / 0.33 % of the
largest entry; the table gives three figures. Measured against the table at 144 cells over
the 10 rows: eps within 0.0011, attitude within 0.09 deg, K within 1.01 % and B within
1.19 % of the largest entry. Held: 0.002, 0.2 deg, 2 % and 2 % (ROSS holds 0.01, 0.5 deg
and 6 % per entry for the same rows).
"""
from functools import lru_cache

import pytest

from studies.lund_thomsen import TABLE, largest_entry_error, table_case

ROWS = [(0.5, TABLE[0.5][0]), (0.5, TABLE[0.5][4]), (1.0, TABLE[1.0][0]),
        (1.0, TABLE[1.0][4])]


@lru_cache(maxsize=None)
def _ours(ld, sommerfeld):
    return table_case(ld, sommerfeld, n_theta=144)


@pytest.mark.parametrize("ld, row", ROWS, ids=lambda r: f"{r}" if isinstance(r, float)
                         else f"S{r[0]}")
def test_two_axial_groove_bearing_against_lund_thomsen(ld, row):
    """Fails (run) with 10 deg grooves for 20 deg, and with K - K_groove_shift for K
    (the grooves' part is up to 53 % of the largest entry at S = 0.991, L/D = 1)."""
    S, eps, phi, *table = row
    r = _ours(ld, S)
    assert r["eps"] == pytest.approx(eps, abs=0.002)
    assert r["phi"] == pytest.approx(phi, abs=0.2)
    assert largest_entry_error(r["K"], table[:4]) < 0.02
    assert largest_entry_error(r["B"], table[4:]) < 0.02


@pytest.mark.parametrize("ld, row", [ROWS[0], ROWS[2]], ids=["LD0.5", "LD1"])
def test_lund_and_thomsen_keep_the_grooves_fixed_in_the_bearing(ld, row):
    """The convention: Lund & Thomsen's K is ours with the grooves fixed in the bearing
    (kc.K); the turning-grooves form kc.K - kc.K_groove_shift, which Someya's data book
    matches (tests/test_someya.py), misses their table at light load by 23 % (L/D 0.5,
    S 1.656) and 53 % (L/D 1, S 0.991) of the largest entry, Kyx by up to 179 %. Fails
    (run) with the two forms swapped in studies/lund_thomsen.table_case."""
    S, eps, phi, *table = row
    r = _ours(ld, S)
    assert largest_entry_error(r["K"], table[:4]) < 0.02
    assert largest_entry_error(r["K_turning"], table[:4]) > 0.15
