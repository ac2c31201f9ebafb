"""The film on general fields (bearingfem.fe.general): a mutant of the density's rate in
the squeeze source survived the manufactured-field and misalignment tests
(docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds
from bearingfem.fields import FilmFields
from conftest import table1_bearing

B = table1_bearing(1.0)
S = JournalState(0.5, 3.0, 0.4, 0.0, 250.0)


def _force(fields):
    return np.array(solve_reynolds(B, S, 48, 8, "P1", "none", fields=fields).force)


@pytest.mark.parametrize("rate", [-40.0, 25.0])
def test_density_rate_is_the_product_rule_of_the_squeeze(rate):
    """d(rho H)/dt = rho dH/dt + H drho/dt: with rho = 1 and drho/dt = r [1/s] the film is
    that of the same density with the gap rate dH/dt + r H (the product rule, written
    into the gap rate here), to round-off of the element sums (measured 1e-15). Fails
    with the density-rate term's sign flipped (general.py:97)."""
    H = lambda th, ze: 1.0 + S.eps * np.cos(th)        # noqa: E731 (the rigid gap)
    by_density = _force(FilmFields(density_rate=rate))
    by_gap = _force(FilmFields(gap_rate=lambda th, ze: S.eps_dot * np.cos(th) + rate * H(th, ze)))
    assert np.linalg.norm(by_density - by_gap) < 1e-10 * np.linalg.norm(by_gap)
    assert np.linalg.norm(by_density - _force(FilmFields())) > 1e-2 * np.linalg.norm(by_gap)
