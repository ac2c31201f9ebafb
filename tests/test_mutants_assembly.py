"""The film operator (bearingfem.fe.assembly) against scikit-fem's own interpolation: a
mutant of the batched quadrature values survived the manufactured, FE-vs-FV and cavitation
tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem.fe.assembly import film_operator


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_batched_fields_at_quadrature_points_are_the_basis_interpolation(element):
    """A stack of nodal fields (3, ndofs) at the quadrature points, row by row, against
    scikit-fem's ``basis.interpolate`` (a second implementation) to round-off; the force
    integrals of the stack, clipped, against the weighted sums of those values. Fails
    with the batch's leading shape dropped (assembly.py:99)."""
    op = film_operator(24, 4, element, 1.0)
    P = np.random.default_rng(3).normal(size=(3, op.mesh.ndofs))
    Q = op.at_quadrature(P)
    assert Q.shape == (3,) + op.qp_theta.shape
    for k in range(3):
        ref = np.asarray(op.mesh.basis.interpolate(P[k]))
        assert np.abs(Q[k] - ref).max() < 1e-12 * np.abs(ref).max()
        w = op.qp_weight * np.maximum(ref, 0.0)
        ic, is_ = op.force_integrals(P, clip=True)[:, k]
        assert ic == pytest.approx(np.sum(w * np.cos(op.qp_theta)), rel=1e-12, abs=1e-14)
        assert is_ == pytest.approx(np.sum(w * np.sin(op.qp_theta)), rel=1e-12, abs=1e-14)
