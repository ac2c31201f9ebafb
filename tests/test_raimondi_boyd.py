"""Steady finite bearings against Raimondi & Boyd (1958): table and film numbers in
studies/raimondi_boyd.py (shared with the verification study)."""
import pytest

from studies.raimondi_boyd import CASES, LOOSE, bearing_numbers

@pytest.mark.parametrize("ld,eps,S0,phi0,f0,Q0,ratio0", CASES)
def test_raimondi_boyd(ld, eps, S0, phi0, f0, Q0, ratio0):
    S, phi, fvar, qs = bearing_numbers(ld, eps)
    tol = LOOSE.get((ld, eps), 0.02)
    assert S == pytest.approx(S0, rel=tol)
    assert phi == pytest.approx(phi0, abs=1.0)
    assert fvar == pytest.approx(f0, rel=tol)
    assert qs == pytest.approx(Q0 * ratio0, rel=0.02)


def test_periodic_film_departs_at_low_eccentricity():
    """seed-corrections §10: a fully periodic film has a larger attitude angle at eps = 0.1-0.2
    (L/D = 1), by up to ~4 deg, and agrees with the supplied film at high eps."""
    gaps = {}
    for eps in (0.1, 0.2, 0.9):
        phi_supply = bearing_numbers(1.0, eps)[1]
        phi_periodic = bearing_numbers(1.0, eps, periodic=True)[1]
        gaps[eps] = phi_periodic - phi_supply
    assert 1.0 < gaps[0.1] < 5.0 and 1.0 < gaps[0.2] < 5.0, gaps
    assert abs(gaps[0.9]) < 0.5, gaps
