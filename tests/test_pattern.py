"""Matrices on a fixed pattern: the values they are given, the pattern's structure."""
import numpy as np
import pytest
import scipy.sparse as sp

from bearingfem import JournalState
from bearingfem.fe.kernel import fe_operator
from bearingfem.solvers.linsolve import factorise
from bearingfem.solvers.pattern import Pattern
from conftest import table1_bearing


def _operator():
    s = JournalState(0.6, 0.0, 0.0, 0.0, 250.0)
    return fe_operator(table1_bearing(1.0), s, 24, 4, "P2")


def test_each_matrix_has_its_own_values_on_the_shared_structure():
    """Two matrices of one pattern equal scipy's own construction from the same arrays,
    in every use the films make of them (mat-vec, diagonal, dense, CSC factors), and
    keep their own values. Fails when the pattern reuses one matrix and swaps its data in
    place (the first matrix would carry the second's values: stale data) or when the
    structure is re-derived wrongly (e.g. the free block's pointers on the full pattern)."""
    op = _operator()
    rng = np.random.default_rng(0)
    P = rng.standard_normal(op.mesh.ndofs)
    values = [op.values(0.3), op.values(0.8)]
    made = [op.matrix(v) for v in values]
    free = [op.free_stiffness(e) for e in (0.3, 0.8)]
    for m, v, f, e in zip(made, values, free, (0.3, 0.8)):
        ref = sp.csr_matrix((v, op.indices, op.indptr), shape=op.shape)
        assert m.data is v and m.format == "csr" and m.shape == op.shape
        assert np.array_equal(m @ P, ref @ P)
        assert np.array_equal(m.diagonal(), ref.diagonal())
        assert np.array_equal(m.toarray(), ref.toarray())
        n = len(op.mesh.free)
        fref = sp.csr_matrix((v[op.ff_select], op.ff_indices, op.ff_indptr), shape=(n, n))
        assert np.array_equal(f.toarray(), fref.toarray())
        b = rng.standard_normal(n)
        assert np.array_equal(factorise(f).solve(b), factorise(fref).solve(b))
    assert not np.array_equal(made[0].toarray(), made[1].toarray())
    assert op.pattern is op.pattern            # checked once per operator


def test_bad_values_and_patterns_raise():
    """Values of the wrong length name ``data``; an unsorted pattern is refused (its
    shared structure would not be canonical)."""
    op = _operator()
    with pytest.raises(ValueError, match="data"):
        op.matrix(np.ones(len(op.indices) - 1))
    with pytest.raises(ValueError, match="sorted"):
        Pattern(np.array([0, 2, 3]), np.array([1, 0, 1]), (2, 2))
