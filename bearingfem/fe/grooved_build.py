"""The grooved film's operator built from its element matrices alone (numpy, no
scikit-fem form assembly).

The bearing-fixed grooved film (:mod:`bearingfem.fe.grooved`) combines seven harmonic
tables int w(phi) grad u . grad v, w = 1, cos m phi, sin m phi (m = 1..3); the periodic
film's four cos^k matrices (:func:`~bearingfem.fe.assembly.build_operator`, scikit-fem's
assembly) only gave it their sparsity pattern. Here every table is one product of the
weights at the quadrature points with the reference tables of
:func:`~bearingfem.fe.general.element_tables`, summed onto the pattern of the element
dofs; entries that are exactly zero in every table (the couplings across the diagonal of
a right triangle, whose gradients are orthogonal) are dropped, so the pattern is the one
scikit-fem's assembly gives and the values agree with it to round-off
(tests/test_grooved_build.py). The four cos^k terms and the two loads come from the same
tables, so the result is a whole :class:`~bearingfem.fe.assembly.FilmOperator`.
"""
from __future__ import annotations

import numpy as np

from .assembly import FilmOperator, interpolation_matrix
from .general import element_tables
from .mesh import FilmMesh

__all__ = ["harmonic_weights", "build_grooved_tables"]


def harmonic_weights(phi: np.ndarray) -> np.ndarray:
    """(7, ...) weights 1, cos phi, sin phi, cos 2 phi, sin 2 phi, cos 3 phi, sin 3 phi."""
    return np.stack([np.ones_like(phi)] + [f(m * phi) for m in (1, 2, 3)
                                           for f in (np.cos, np.sin)])


#: cos^k phi (k = 0..3) in the harmonics: cos^2 = (1 + cos 2 phi) / 2,
#: cos^3 = (3 cos phi + cos 3 phi) / 4 (the periodic film's four terms from the seven tables)
_COS_POWERS = np.array([[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
                        [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
                        [0.5, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0],
                        [0.0, 0.75, 0.0, 0.0, 0.0, 0.25, 0.0]])


def build_grooved_tables(mesh: FilmMesh) -> tuple[FilmOperator, np.ndarray]:
    """(operator, (7, nnz) harmonic tables on its pattern) of ``mesh`` (module docstring)."""
    basis = mesh.basis
    t = element_tables(basis)
    N = basis.N
    dofs = t.dofs.astype(np.int64)
    local = (dofs[:, :, None] * N + dofs[:, None, :]).reshape(len(dofs), -1)
    keys, slot = np.unique(local, return_inverse=True)
    slot = slot.ravel()
    qp = basis.global_coordinates()
    qp_theta = np.array(qp[0])
    weights = harmonic_weights(qp_theta)                   # (7, elements, points)
    # element matrices of all seven weights at once, (7, elements, nb*nb): one matrix
    # product over (point, metric component), the element's metric folded into the
    # weights (four products of the full size and their sum cost ~3x more)
    n_w, n_e, n_q = weights.shape
    metric = t.metric.reshape(4, n_e)
    folded = (weights[:, :, :, None] * metric.T[None, :, None, :]).reshape(n_w * n_e, -1)
    stiff = t.stiff_tables.reshape(4, n_q, -1).transpose(1, 0, 2).reshape(4 * n_q, -1)
    local_k = (folded @ stiff).reshape(n_w, n_e, -1)
    n_keys = len(keys)
    tables = np.bincount((np.arange(n_w)[:, None] * n_keys + slot[None, :]).ravel(),
                         local_k.reshape(n_w, -1).ravel(),
                         minlength=n_w * n_keys).reshape(n_w, n_keys)
    # the orthogonal couplings sum to zero up to round-off in the one product: dropped
    # below 1e-12 of the largest entry (a coupling of the film is ~1e-3 of it or more)
    keep = np.any(np.abs(tables) > 1e-12 * np.abs(tables).max(), axis=0)
    keys, tables = keys[keep], tables[:, keep]
    rows, cols = keys // N, keys % N
    indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=N))])
    free = mesh.free
    renumber = np.full(N, -1, dtype=np.int64)
    renumber[free] = np.arange(len(free))
    ff = np.flatnonzero((renumber[rows] >= 0) & (renumber[cols] >= 0))
    ff_indptr = np.concatenate([[0], np.cumsum(np.bincount(renumber[rows[ff]],
                                                           minlength=len(free)))])

    def load(weight):       # int weight v over the film
        return np.bincount(dofs.ravel(), (t.det[:, None] * (weight @ t.value_table)).ravel(),
                           minlength=N)

    op = FilmOperator(
        mesh=mesh, indptr=indptr.astype(np.int32), indices=cols.astype(np.int32),
        terms=_COS_POWERS @ tables, ff_indptr=ff_indptr.astype(np.int32),
        ff_indices=renumber[cols[ff]].astype(np.int32), ff_select=ff,
        b_sin=load(weights[2]), b_cos=load(weights[1]), qp_theta=qp_theta,
        qp_zeta=np.array(qp[1]), qp_weight=np.array(basis.dx),
        qp_interp=interpolation_matrix(basis))
    return op, tables
