"""Film operator: everything a state needs, assembled once per mesh.

With H = 1 + eps cos(theta), H^3 = sum_k a_k(eps) cos^k(theta) (:mod:`bearingfem.film`),
so the stiffness of -div(H^3 grad P) is K(eps) = sum_k a_k(eps) K_k with four matrices K_k
that do not depend on the state. They share one sparsity pattern; a state only forms a
linear combination of their value arrays (no re-assembly, no loop over elements). The load
is likewise b = a_sin b_sin + a_cos b_cos with the film's source coefficients.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad

from ..caches import cached
from ..film import cubed_thickness_coefficients, source_coefficients, theta_from_inertial
from ..solvers.pattern import Pattern
from .mesh import LEAST_FILM, FilmMesh, film_mesh

__all__ = ["FilmOperator", "film_operator", "fe_operator"]


def _stiffness_form(k: int) -> BilinearForm:
    @BilinearForm
    def form(u, v, w):
        return np.cos(w.x[0]) ** k * dot(grad(u), grad(v))
    return form


@LinearForm
def _load_sin(v, w):
    return np.sin(w.x[0]) * v


@LinearForm
def _load_cos(v, w):
    return np.cos(w.x[0]) * v


def _aligned_data(mats, pos: sp.csr_matrix) -> np.ndarray:
    """Value arrays of ``mats`` laid out on the pattern whose entries ``pos`` numbers 1..nnz
    (rows k of the result)."""
    out = np.zeros((len(mats), pos.nnz))
    for k, m in enumerate(mats):
        m = m.tocoo()
        idx = np.asarray(pos[m.row, m.col]).ravel().astype(np.int64) - 1
        np.add.at(out[k], idx, m.data)
    return out


@dataclass(frozen=True, eq=False)
class FilmOperator:
    """Assembled film: stiffness terms on a fixed pattern, loads, and selections.

    ``stiffness(eps)`` returns the full matrix; ``free_stiffness(eps)`` its free-free block.
    Both are new CSR wrappers around freshly combined value arrays on a shared pattern.
    """

    mesh: FilmMesh
    indptr: np.ndarray
    indices: np.ndarray
    terms: np.ndarray          # (4, nnz): values of K_0..K_3 on the pattern
    ff_indptr: np.ndarray
    ff_indices: np.ndarray
    ff_select: np.ndarray      # positions of the free-free block in the value arrays
    b_sin: np.ndarray
    b_cos: np.ndarray
    qp_theta: np.ndarray       # theta at the quadrature points (elements x points)
    qp_zeta: np.ndarray        # zeta = z/R at the same points
    qp_weight: np.ndarray      # quadrature weight times Jacobian at the same points
    qp_interp: sp.csr_matrix   # nodal values -> values at those points (flattened)

    @property
    def shape(self):
        n = self.mesh.ndofs
        return (n, n)

    def values(self, eps: float, derivative: bool = False) -> np.ndarray:
        """Values of K(eps) on the pattern (of dK/deps with ``derivative``)."""
        a = cubed_thickness_coefficients(eps, derivative)
        t = self.terms
        return a[0] * t[0] + a[1] * t[1] + a[2] * t[2] + a[3] * t[3]

    @cached_property
    def pattern(self) -> Pattern:
        """The stiffness pattern over all dofs (checked once, shared by every state)."""
        return Pattern(self.indptr, self.indices, self.shape)

    @cached_property
    def free_pattern(self) -> Pattern:
        """The pattern of the free-free block."""
        n = len(self.mesh.free)
        return Pattern(self.ff_indptr, self.ff_indices, (n, n))

    def matrix(self, values: np.ndarray) -> sp.csr_matrix:
        """The matrix of stiffness ``values`` on the pattern (e.g. a partial's)."""
        return self.pattern.matrix(values)

    def stiffness(self, eps: float) -> sp.csr_matrix:
        return self.matrix(self.values(eps))

    def free_stiffness(self, eps: float, values: np.ndarray | None = None) -> sp.csr_matrix:
        v = self.values(eps) if values is None else values
        return self.free_pattern.matrix(v[self.ff_select])

    def at_quadrature(self, P: np.ndarray) -> np.ndarray:
        """Values of nodal fields P (..., ndofs) at the quadrature points
        (..., elements, points)."""
        P = np.asarray(P)
        Q = self.qp_interp @ P.reshape(-1, P.shape[-1]).T
        return Q.T.reshape(P.shape[:-1] + self.qp_theta.shape)

    def force_integrals(self, P: np.ndarray, clip: bool = False, where=None) -> np.ndarray:
        """(integral of P cos theta, integral of P sin theta) over the meshed film, for
        nodal fields P (..., ndofs): shape (2, ...). ``clip`` integrates max(P, 0) at the
        quadrature points (Gumbel's film); ``where`` (a boolean array over the quadrature
        points) integrates there only. Unclipped, it is one mat-vec with the assembled
        cos/sin loads (the same quadrature)."""
        P = np.asarray(P)
        if not clip and where is None:
            return np.stack([P @ self.b_cos, P @ self.b_sin])
        Q = self.at_quadrature(P)
        if clip:
            Q = np.maximum(Q, 0.0)
        # (Q w) cos, in this order: time integrations stay bit-identical across versions
        Qw = Q * (self.qp_weight if where is None else np.where(where, self.qp_weight, 0.0))
        return np.stack([np.sum(Qw * np.cos(self.qp_theta), axis=(-2, -1)),
                         np.sum(Qw * np.sin(self.qp_theta), axis=(-2, -1))])

    def load(self, eps: float, eps_dot: float, wedge_speed: float) -> np.ndarray:
        """Load vector of the Reynolds source f = a_sin sin(theta) + a_cos cos(theta)."""
        a_sin, a_cos = source_coefficients(eps, eps_dot, wedge_speed)
        return a_sin * self.b_sin + a_cos * self.b_cos


def build_operator(mesh: FilmMesh) -> FilmOperator:
    basis = mesh.basis
    mats = [_stiffness_form(k).assemble(basis) for k in range(4)]
    pattern = sum(abs(m) for m in mats).tocsr()
    pattern.sort_indices()
    # Number the pattern's entries 1..nnz: slicing this matrix tells where entries go.
    pos = sp.csr_matrix((np.arange(1, pattern.nnz + 1, dtype=float), pattern.indices,
                         pattern.indptr), shape=pattern.shape)
    terms = _aligned_data(mats, pos)
    free = mesh.free
    ff = pos[free][:, free].tocsr()
    ff.sort_indices()
    return FilmOperator(
        mesh=mesh, indptr=pattern.indptr, indices=pattern.indices, terms=terms,
        ff_indptr=ff.indptr, ff_indices=ff.indices,
        ff_select=ff.data.astype(np.int64) - 1,
        b_sin=_load_sin.assemble(basis), b_cos=_load_cos.assemble(basis),
        qp_theta=np.array(basis.global_coordinates()[0]),
        qp_zeta=np.array(basis.global_coordinates()[1]), qp_weight=np.array(basis.dx),
        qp_interp=interpolation_matrix(basis))


def interpolation_matrix(basis) -> sp.csr_matrix:
    """Sparse map from nodal values to values at quadrature points: one mat-vec replaces
    the basis's interpolation inside time integration."""
    n_el, n_qp = basis.dx.shape
    rows = np.arange(n_el * n_qp).reshape(n_el, n_qp)
    r, c, v = [], [], []
    for i in range(basis.Nbfun):   # loop over the few local shape functions only
        r.append(rows.ravel())
        c.append(np.repeat(basis.element_dofs[i], n_qp))
        v.append(np.asarray(basis.basis[i][0]).ravel())
    return sp.csr_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))),
                         shape=(n_el * n_qp, basis.N))


@cached(maxsize=32)
def film_operator(n_theta: int, n_z: int, element: str, length_ratio: float,
                  theta0: float | None = None, half: bool = True,
                  arcs: tuple = (), grading: tuple | None = None) -> FilmOperator:
    """Cached operator for a mesh (see :func:`bearingfem.fe.mesh.film_mesh`)."""
    return build_operator(film_mesh(n_theta, n_z, element, length_ratio, theta0, half, arcs,
                                    grading))


def fe_operator(bearing, state, n_theta=120, n_z=20, element="P1",
                supply_angle=None, half=True, grooves=(), grading=None) -> FilmOperator:
    """The cached film operator for this bearing and mesh (supply line and grooves in the
    film frame; the mesh starts at the first groove's edge). ``grading``: a strength in
    [0, 0.99], the theta cells concentrated toward the least film, one operator for every
    journal state (the mesh is in the film frame); or (angle, strength), toward the
    inertial ``angle`` [rad] (its film angle at this state's gamma); None: uniform."""
    theta0, arcs = None, ()
    if supply_angle is not None:   # rounded: it is part of the operator cache key
        theta0 = float(np.round(theta_from_inertial(supply_angle, state.gamma), 12))
    if grooves:
        arcs = tuple((float(np.round(lo, 12)), float(np.round(hi, 12)))
                     for lo, hi in (g.arc(state.gamma) for g in grooves))
        theta0 = arcs[0][0]
    if grading is not None:     # the focus's film angle, rounded: part of the cache key
        focus = theta_from_inertial(grading[0], state.gamma) if isinstance(grading, tuple) \
            else LEAST_FILM
        grading = (float(np.round(focus, 12)),
                   float(grading[1] if isinstance(grading, tuple) else grading))
    return film_operator(int(n_theta), int(n_z), element, bearing.length_ratio, theta0,
                         bool(half), arcs, grading)
