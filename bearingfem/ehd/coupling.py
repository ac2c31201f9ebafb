"""The EHD film as a function of its pressure: fields, residual and Jacobian.

A pressure-dependent lubricant (:class:`~bearingfem.lubricant.Lubricant`) makes the
viscosity and density ratios functions of the local pressure; an elastic bush makes the
gap a function of the whole pressure field, H = H0 + w/c with w = C p the bush's radial
deflection (C its compliance, :mod:`bearingfem.elastic.compliance`). The residual of the
film on these fields, on the free dofs of the general assembly
(:mod:`bearingfem.fe.general`), is

    R_i(P) = sum_q dx [k grad P . grad phi_i - c d(phi_i)/dtheta - s phi_i],
    k = rho H^3 / mu,  c = 6 w rho H,  s = -12 (rho dH/dt + H drho/dt),

and its Jacobian is K + J_local + J_bush: J_local from d(k, c, s)/dp at the same point
(sparse, the element pattern) and J_bush = T_H I C (dense for the full compliance, of rank
n for a reduced one), T_H the quadrature-point derivatives in H and I the nodal-to-
quadrature interpolation.

A homotopy parameter ``s`` in [0, 1] scales the coupling: the fields are evaluated at
s p and the deflection is s C p, so s = 0 is the isoviscous rigid film and s = 1 the
EHD film (the load continuation of :mod:`bearingfem.ehd.newton`).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from ..elastic import BushCompliance, ElasticBush, ReducedCompliance, bush_compliance
from ..fields import FilmFields
from ..fe.general import film_system

__all__ = ["EHDFilm", "ehd_film", "dof_compliance"]


@dataclass(frozen=True, eq=False)
class DofCompliance:
    """The compliance on the film's dofs, C = left diag(s) right^T [m/Pa] (dense: left is
    the full matrix, right None)."""

    left: np.ndarray
    singular: np.ndarray | None = None
    right: np.ndarray | None = None

    def apply(self, p: np.ndarray) -> np.ndarray:
        if self.right is None:
            return self.left @ p
        return self.left @ (self.singular * (self.right.T @ p))


@lru_cache(maxsize=8)
def _cached_compliance(bush: ElasticBush, radius: float, length: float, n_theta: int,
                       n_z: int) -> BushCompliance:
    return bush_compliance(bush, radius, length, n_theta, n_z)


def dof_compliance(bush, bearing, op) -> DofCompliance:
    """The bush's compliance between the film mesh's P1 dofs (grid node (j, k) of the
    compliance at theta = theta_start + 2 pi j / n_theta, z = -L/2 + k L / n_z).

    ``bush`` is an :class:`ElasticBush` (its full compliance is built, cached) or a
    prebuilt :class:`BushCompliance` / :class:`ReducedCompliance` on the (n_theta,
    n_z + 1) grid. The compliance is circulant in theta, so a grid starting at any film
    angle (the journal's attitude) uses the same columns. Where a supply line closes the
    film, its two seam dofs are one grid node: the deflection is read at both, the pressure
    taken from one.
    """
    mesh = op.mesh
    shape = (mesh.n_theta, mesh.n_z + 1)
    if isinstance(bush, ElasticBush):
        bush = _cached_compliance(bush, bearing.radius, bearing.length, *shape)
    elif not isinstance(bush, (BushCompliance, ReducedCompliance)):
        raise ValueError(f"bush must be an ElasticBush, BushCompliance or ReducedCompliance, "
                         f"got {type(bush).__name__}")
    if tuple(bush.shape) != shape:
        raise ValueError(f"bush compliance must be on the film grid {shape} (n_theta, n_z + 1)"
                         f", got {tuple(bush.shape)}")
    if isinstance(bush, BushCompliance) and not (
            np.isclose(bush.radius, bearing.radius) and np.isclose(bush.length, bearing.length)):
        raise ValueError(f"bush compliance built for R={bush.radius}, L={bush.length} [m], "
                         f"the bearing has R={bearing.radius}, L={bearing.length}")
    start = 0.0 if mesh.theta0 is None else mesh.theta0
    h = 2.0 * np.pi / mesh.n_theta
    j = np.rint((mesh.theta - start) / h).astype(int) % mesh.n_theta
    k = np.rint((mesh.zeta + mesh.length_ratio) / (2 * mesh.length_ratio) * mesh.n_z)
    node = j * shape[1] + k.astype(int)
    grid_nodes, rep = np.unique(node, return_index=True)
    if grid_nodes.size != shape[0] * shape[1]:
        raise ValueError("the bush needs the whole-length P1 film mesh")
    if isinstance(bush, BushCompliance):
        full = bush.matrix()
        C = np.zeros((mesh.ndofs, mesh.ndofs))
        C[:, rep] = full[np.ix_(node, grid_nodes)]
        return DofCompliance(C)
    right = np.zeros((mesh.ndofs, bush.n_vectors))
    right[rep] = bush.right[grid_nodes]
    return DofCompliance(bush.left[node], bush.singular, right)


@dataclass(frozen=True, eq=False)
class ElementTables:
    """Shape functions of the film mesh at its quadrature points (built once per solve)."""

    rows: np.ndarray       # (nb, E, Q) dof of local function i
    cols: np.ndarray       # (nb, E, Q) flattened quadrature point e Q + q
    phi: np.ndarray        # (nb, E, Q) phi_i dx
    dphi: np.ndarray       # (nb, 2, E, Q) grad phi_i dx


def element_tables(op) -> ElementTables:
    basis = op.mesh.basis
    dx = basis.dx
    E, Q = dx.shape
    nb = basis.Nbfun
    rows = np.broadcast_to(basis.element_dofs[:, :, None], (nb, E, Q))
    cols = np.broadcast_to(np.arange(E * Q).reshape(E, Q), (nb, E, Q))
    phi = np.array([np.asarray(basis.basis[i][0]) * dx for i in range(nb)])
    dphi = np.array([np.asarray(basis.basis[i][0].grad) * dx for i in range(nb)])
    return ElementTables(rows, cols, phi, dphi)


@dataclass(frozen=True, eq=False)
class EHDFilm:
    """One EHD film problem on one film operator (see the module docstring).

    base : the film's own fields at the quadrature points (gap without deflection, its
        rate, and viscosity / density ratios the lubricant multiplies)
    gap0 : nodal gap without deflection (H)
    lubricant : Lubricant or None; compliance : DofCompliance or None
    scale : pressure scale mu0 (R/c)^2 [Pa s]; clearance c [m]; wedge : wedge speed [rad/s]
    viscosity : the bearing's viscosity mu0 [Pa s] (the ratios' reference)
    eps : the state's eccentricity ratio, the reference cylinder of the general load
        (:func:`~bearingfem.fe.general.film_system`)
    """

    op: object
    base: FilmFields
    gap0: np.ndarray
    lubricant: object
    compliance: DofCompliance | None
    scale: float
    clearance: float
    wedge: float
    viscosity: float
    tables: ElementTables
    eps: float = 0.0

    def deflection(self, P: np.ndarray, s: float = 1.0) -> np.ndarray:
        """Nodal radial deflection w [m] of the bush under s p (zero without a bush)."""
        if self.compliance is None:
            return np.zeros_like(P)
        return s * self.compliance.apply(self.scale * P)

    def fields(self, P: np.ndarray, s: float = 1.0):
        """(FilmFields at the quadrature points, d(rho, mu)/dp there [1/Pa] or None)."""
        Hq = self.base.gap
        if self.compliance is not None:
            Hq = Hq + self.op.at_quadrature(self.deflection(P, s)) / self.clearance
        if self.lubricant is None:
            rho = mu = 1.0
            slopes = None
        else:
            p = s * self.scale * self.op.at_quadrature(P)
            lub = self.lubricant
            # ratios to the bearing's viscosity mu0, the one in the pressure scale
            rho, mu = lub.density_at(p), lub.viscosity_at(p) / self.viscosity
            slopes = (lub.density_derivative(p), lub.viscosity_derivative(p) / self.viscosity)
        film = FilmFields(gap=Hq, gap_rate=self.base.gap_rate,
                          viscosity=self.base.viscosity * mu, density=self.base.density * rho,
                          density_rate=self.base.density_rate)
        return film, slopes

    def system(self, P: np.ndarray, s: float = 1.0):
        """(evaluated fields, stiffness values on the pattern, load) at pressure P; the
        fields are None where the gap closes or a viscosity or density is not finite
        and > 0."""
        film, _ = self.fields(P, s)
        # a trial pressure may close the gap or push a property law out of range
        for field in (film.gap, film.viscosity, film.density):
            if not np.all((field > 0.0) & np.isfinite(field)):
                return None, None, None
        values, load = film_system(self.op, film, self.wedge, self.eps)
        return film, values, load

    def residual(self, P: np.ndarray, s: float = 1.0):
        """(R = K P - load on all dofs, a scale of its terms, K values) or Nones when the
        gap closes."""
        film, values, load = self.system(P, s)
        if film is None:
            return None, None, None
        K = sp.csr_matrix((values, self.op.indices, self.op.indptr), shape=self.op.shape)
        size = np.abs(K) @ np.abs(P) + np.abs(load)
        return K @ P - load, size, values

    def jacobian(self, P: np.ndarray, s: float = 1.0):
        """(J_sparse, U, V) with dR/dP = J_sparse + U V^T (U, V None without a bush; for
        the full compliance V is the identity, given as None and U dense N x N)."""
        film, slopes = self.fields(P, s)
        values, _ = film_system(self.op, film, self.wedge)
        K = sp.csr_matrix((values, self.op.indices, self.op.indptr), shape=self.op.shape)
        t = self.tables
        rho, mu, H = film.density, film.viscosity, film.gap
        gP = np.asarray(self.op.mesh.basis.interpolate(P).grad)            # (2, E, Q)
        Bk = np.einsum("iceq,ceq->ieq", t.dphi, gP)                         # grad P.grad phi dx
        Bc = t.dphi[:, 0]                                                   # dphi/dtheta dx
        Bs = t.phi
        N, NQ = self.op.mesh.ndofs, H.size

        def assemble(dk, dc, dsq):     # sum_q B_iq (coefficient derivative)_q, (N, NQ)
            v = Bk * dk - Bc * dc - Bs * dsq
            return sp.csr_matrix((v.ravel(), (t.rows.ravel(), t.cols.ravel())),
                                 shape=(N, NQ))
        J = K
        if slopes is not None:
            drho, dmu = slopes
            ds = s * self.scale
            dk = ds * (drho * H**3 / mu - rho * H**3 * dmu / mu**2)
            dc = ds * 6.0 * self.wedge * drho * H
            dsq = ds * -12.0 * drho * film.gap_rate
            J = J + assemble(dk, dc, dsq) @ self.op.qp_interp
        if self.compliance is None:
            return J.tocsc(), None, None
        dsq_H = -12.0 * film.density_rate * np.ones_like(H)
        TH = assemble(3.0 * rho * H**2 / mu, 6.0 * self.wedge * rho, dsq_H) @ self.op.qp_interp
        k = s * self.scale / self.clearance
        c = self.compliance
        if c.right is None:
            return J.tocsc(), k * (TH @ c.left), None
        return J.tocsc(), k * (TH @ (c.left * c.singular)), c.right


def ehd_film(bearing, state, op, base: FilmFields, gap0, lubricant, bush) -> EHDFilm:
    """Build the EHD film of ``op`` on the evaluated base fields ``base``."""
    compliance = None if bush is None else dof_compliance(bush, bearing, op)
    return EHDFilm(op=op, base=base, gap0=gap0, lubricant=lubricant, compliance=compliance,
                   scale=bearing.pressure_scale, clearance=bearing.clearance,
                   wedge=state.wedge_speed, viscosity=bearing.viscosity,
                   tables=element_tables(op), eps=state.eps)
