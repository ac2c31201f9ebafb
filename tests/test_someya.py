"""Finite-bearing dynamic coefficients against Someya's Journal-Bearing Databook (1989):
table, bearing and our numbers in studies/someya.py.

Tolerances: on the meshes 72 / 144 / 288 cells around, our eps moves by 0.5 % / 0.15 %,
the attitude by 0.2 / 0.04 deg and the stiffness by <= 0.5 % (python -m studies.someya);
the book gives three figures. What is left is the difference from the book: eps within
0.6 %, attitude within 0.5 deg; K and B entry by entry within 3 % and 5 % of the largest
entry (observed 2.6 % and 4.4 %; entries near zero, such as Kyx by eps 0.7, make relative
errors per entry meaningless). The damping gap (Bxy, Byy 5-10 % low, at every mesh) is
not explained: see the study's docstring.
"""
import pytest

from studies.someya import TABLE, databook_case, largest_entry_error

ROWS = [row for row in TABLE[0.5] if row[1] in (0.3, 0.5, 0.8, 0.9)]


@pytest.mark.parametrize("row", ROWS, ids=lambda r: f"eps{r[1]}")
def test_two_axial_groove_bearing_against_someya(row):
    S, eps, phi, *book = row
    r = databook_case(0.5, S)
    assert r["eps"] == pytest.approx(eps, rel=0.006)
    assert r["phi"] == pytest.approx(phi, abs=0.5)
    assert largest_entry_error(r["K_turning"], book[:4]) < 0.03
    assert largest_entry_error(r["B"], book[4:]) < 0.05


def test_the_book_turns_its_grooves_with_the_line_of_centres():
    """With the grooves fixed in the bearing (our coefficients, the force's exact Jacobian)
    a displacement across the line of centres also moves the film against the grooves: at
    light load that changes Kxx, Kyx, Kyy by 10-40 %, and the book's values are the ones
    without it."""
    S, eps, phi, *book = TABLE[0.5][3]                 # eps = 0.3
    r = databook_case(0.5, S)
    for i in (0, 2, 3):
        assert abs(r["K_turning"][i] / book[i] - 1.0) < 0.03
        assert abs(r["K"][i] / book[i] - 1.0) > 0.10
