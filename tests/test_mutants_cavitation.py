"""The cavitation solvers (bearingfem.solvers.cavitation): a mutant of PSOR's refusal
survived the cavitation and block-solve tests (docs/mutation.md); the others there were
equivalent (iteration caps, the colouring's seed)."""
import numpy as np
import pytest
import scipy.sparse as sp

from bearingfem.solvers.cavitation import psor


@pytest.mark.parametrize("omega", [0.0, 2.0, 2.5, 3.9, -0.5])
def test_psor_relaxation_outside_the_open_interval_is_refused(omega):
    """SOR converges for a symmetric positive-definite K only for 0 < omega < 2 (Ostrowski-
    Reich): anything else is refused before any sweep, naming omega. Fails with the
    upper bound 2 doubled (cavitation.py:168)."""
    K = sp.csr_matrix(np.array([[2.0, -1.0], [-1.0, 2.0]]))
    with pytest.raises(ValueError, match="omega"):
        psor(K, np.array([1.0, -1.0]), omega=omega)


def test_psor_inside_the_interval_solves_a_two_dof_problem():
    """K = [[2, -1], [-1, 2]], b = (1, -1): the second dof cavitates (its unconstrained
    value is -1/3), so P = (1/2, 0) with multiplier r_2 = 1/2 >= 0, by hand."""
    K = sp.csr_matrix(np.array([[2.0, -1.0], [-1.0, 2.0]]))
    for omega in (0.5, 1.0, 1.9):
        res = psor(K, np.array([1.0, -1.0]), omega=omega, tol=1e-14)
        assert res.pressure == pytest.approx([0.5, 0.0], abs=1e-12)
