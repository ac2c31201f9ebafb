"""Assembly of the film on any fields: -div(rho H^3/mu grad P) = -6 w d(rho H)/dtheta
- 12 d(rho H)/dt, for P1 and P2 (see :mod:`bearingfem.fields`).

The Couette term is taken in weak form, 6 w int rho H dv/dtheta (the boundary term vanishes:
the film is periodic in theta, or v = 0 on a supply line), so a gap needs no derivative and
may be any nodal or quadrature field.

Vectorised without a loop over elements: the film mesh is affine (straight triangles), so
on element e the gradients are J_e^-T times the reference gradients, and

    K_e[i, j] = sum_cd (J^-1 J^-T)_e[c, d] |det J_e| sum_q k_eq W_q dphi_ic(q) dphi_jd(q),

one contraction of the coefficient k = rho H^3/mu at the quadrature points with the
elements' tables (the metric summed into the reference tables once per mesh:
``GeneralAssembly.element_tables``); the local values are then
summed onto the fast path's sparsity pattern (``FilmOperator.indptr/indices``), so both
paths share the free-free selection and the solvers.

A rough film's flow (:mod:`bearingfem.contact.flow_factors`) makes the coefficient a
diagonal tensor, rho (phi_x H^3, phi_z H^3)/mu: each axis a then has its own metric
J^-1[c, a] J^-1[d, a] |det J|, and the Couette content rho H becomes rho E(h_T)/c plus
the shear flow's (omega / w) rho sigma phi_s / c.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..caches import cached
from ..contact.flow_factors import FlowFields
from ..fields import EdgeProfile, FilmFields, tilted_gap
from ..film import film_thickness_at
from ..scales import moment_factor
from .assembly import FilmOperator

__all__ = ["GeneralAssembly", "general_assembly", "ElementTables", "element_tables",
           "film_system", "reference_load_partial", "general_film", "film_moment"]


@dataclass(frozen=True, eq=False)
class GeneralAssembly:
    """Reference tables and element metrics of one film operator (built once per mesh)."""

    op: FilmOperator
    metric: np.ndarray       # (2, 2, elements): (J^-1 J^-T) |det J|
    axis_metric: np.ndarray  # (2, 2, 2, elements): [a, c, d] J^-1[c, a] J^-1[d, a] |det J|
    grad_theta: np.ndarray   # (2, elements): (J^-1)[c, 0] |det J|, d/dtheta of ref. grads
    det: np.ndarray          # (elements,) |det J|
    stiff_tables: np.ndarray  # (2, 2, points, nb*nb): W_q dphi_ic dphi_jd
    grad_tables: np.ndarray  # (2, points, nb): W_q dphi_ic
    value_table: np.ndarray  # (points, nb): W_q phi_i
    positions: np.ndarray    # (elements, nb*nb): place of each local entry in the pattern
    dofs: np.ndarray         # (elements, nb)

    def stiffness_values(self, k) -> np.ndarray:
        """Values on the pattern of the stiffness of -div(k grad P), k at the quadrature
        points (elements x points), or a pair (k_theta, k_zeta): the diagonal tensor's."""
        if not isinstance(k, tuple):
            return self.stiffness_scatter @ np.broadcast_to(k, self.op.qp_theta.shape).ravel()
        local = sum(self.axis_metric[a, c, d][:, None] * (k[a] @ self.stiff_tables[c, d])
                    for a in range(2) for c in range(2) for d in range(2))
        n = len(self.op.indices)
        return np.bincount(self.positions.ravel(), local.ravel(), minlength=n + 1)[:n]

    @cached_property
    def stiffness_scatter(self) -> sp.csr_matrix:
        """(pattern entries, elements * points): the stiffness values of a scalar k at the
        points are this matrix times k (raveled): each point's weight in each local entry
        (sum_cd metric[c, d] stiff_tables[c, d]) summed onto the pattern. Why: the
        contraction with the element tables and the sum onto the pattern in one sparse
        product, 0.19 against 0.36 ms a film at 192 x 16 (6 points an element)."""
        t = np.einsum("cde,cdqm->eqm", self.metric, self.stiff_tables)
        E, Q, m = t.shape
        n = len(self.op.indices)
        rows = np.broadcast_to(self.positions[:, None, :], (E, Q, m)).ravel()
        cols = np.broadcast_to(np.arange(E * Q).reshape(E, Q, 1), (E, Q, m)).ravel()
        # the spare slot n (couplings the pattern lacks, zero for every k) dropped
        return sp.csr_matrix((t.ravel(), (rows, cols)), shape=(n + 1, E * Q))[:n]

    @cached_property
    def load_scatter(self) -> tuple:
        """(couette, squeeze) (nodes, elements * points): :meth:`load` is the sum of their
        products with the raveled fields (the local loads' tables and their sum onto the
        nodes in one sparse product each)."""
        E, Q, nb = self.dofs.shape[0], self.value_table.shape[0], self.dofs.shape[1]
        rows = np.broadcast_to(self.dofs[:, None, :], (E, Q, nb)).ravel()
        cols = np.broadcast_to(np.arange(E * Q).reshape(E, Q, 1), (E, Q, nb)).ravel()
        couette = (self.grad_theta[0][:, None, None] * self.grad_tables[0][None]
                   + self.grad_theta[1][:, None, None] * self.grad_tables[1][None])
        squeeze = self.det[:, None, None] * self.value_table[None]
        shape = (self.op.mesh.ndofs, E * Q)
        return tuple(sp.csr_matrix((v.ravel(), (rows, cols)), shape=shape)
                     for v in (couette, squeeze))

    @cached_property
    def cos_theta(self) -> np.ndarray:
        """cos(theta) at the points (the reference cylinder 1 + eps cos(theta) of
        :func:`film_system`: a cosine of every point was a tenth of an EHD film's
        evaluation at 192 x 16)."""
        return np.cos(self.op.qp_theta)

    def load(self, couette: np.ndarray, squeeze: np.ndarray) -> np.ndarray:
        """Load of int couette dv/dtheta + squeeze v over the film (both at the
        quadrature points)."""
        c, s = self.load_scatter
        shape = self.op.qp_theta.shape
        return (c @ np.broadcast_to(couette, shape).ravel()
                + s @ np.broadcast_to(squeeze, shape).ravel())


@dataclass(frozen=True, eq=False)
class ElementTables:
    """Element metrics and reference tables of an affine scikit-fem basis (the parts of
    :class:`GeneralAssembly` that need no sparsity pattern)."""

    metric: np.ndarray       # (2, 2, elements): (J^-1 J^-T) |det J|
    axis_metric: np.ndarray  # (2, 2, 2, elements): [a, c, d] J^-1[c, a] J^-1[d, a] |det J|
    grad_theta: np.ndarray   # (2, elements)
    det: np.ndarray          # (elements,)
    stiff_tables: np.ndarray  # (2, 2, points, nb*nb)
    grad_tables: np.ndarray  # (2, points, nb)
    value_table: np.ndarray  # (points, nb)
    dofs: np.ndarray         # (elements, nb)

    def local_stiffness(self, k: np.ndarray) -> np.ndarray:
        """(elements, nb*nb) element matrices of -div(k grad P), k at the quadrature
        points (elements x points)."""
        return sum(self.metric[c, d][:, None] * (k @ self.stiff_tables[c, d])
                   for c in range(2) for d in range(2))

    def local_load(self, couette: np.ndarray, squeeze: np.ndarray) -> np.ndarray:
        """(elements, nb) element loads of int couette dv/dtheta + squeeze v."""
        return (self.grad_theta[0][:, None] * (couette @ self.grad_tables[0])
                + self.grad_theta[1][:, None] * (couette @ self.grad_tables[1])
                + self.det[:, None] * (squeeze @ self.value_table))


def element_tables(basis) -> ElementTables:
    """The tables of an affine basis (raises ValueError on curved elements)."""
    X, W = basis.X, basis.W
    invJ = basis.mapping.invDF(X)[..., 0]             # (2, 2, elements), affine
    det = np.abs(basis.mapping.detDF(X)[:, 0])
    if not np.allclose(basis.dx, det[:, None] * W[None, :], rtol=1e-12, atol=0.0):
        raise ValueError("the general film assembly needs straight (affine) elements")
    nb = basis.Nbfun
    phi = np.array([basis.elem.lbasis(X, i)[0] for i in range(nb)])      # (nb, points)
    dphi = np.array([basis.elem.lbasis(X, i)[1] for i in range(nb)])     # (nb, 2, points)
    # physical gradient component a: sum_c invJ[c, a] dphi_c
    metric = np.einsum("cae,dae->cde", invJ, invJ) * det
    axis_metric = np.einsum("cae,dae->acde", invJ, invJ) * det
    stiff = np.einsum("q,icq,jdq->cdqij", W, dphi, dphi).reshape(2, 2, len(W), nb * nb)
    return ElementTables(metric=metric, axis_metric=axis_metric, grad_theta=invJ[:, 0] * det, det=det,
                         stiff_tables=stiff, grad_tables=np.einsum("q,icq->cqi", W, dphi),
                         value_table=(W * phi).T,
                         dofs=np.ascontiguousarray(basis.element_dofs.T))


@cached(maxsize=16)
def general_assembly(op: FilmOperator) -> GeneralAssembly:
    """The tables of ``op``'s mesh (cached per operator)."""
    t = element_tables(op.mesh.basis)
    dofs = t.dofs                                                        # (elements, nb)
    N = op.mesh.basis.N
    rows = np.repeat(np.arange(N, dtype=np.int64), np.diff(op.indptr))
    keys = rows * N + op.indices
    local = (dofs[:, :, None].astype(np.int64) * N + dofs[:, None, :]).reshape(len(dofs), -1)
    positions = np.minimum(np.searchsorted(keys, local), len(keys) - 1)
    # Couplings the pattern lacks are zero for every coefficient (gradients orthogonal on
    # right triangles): they go to a spare slot past the pattern's end, dropped.
    positions[keys[positions] != local] = len(keys)
    return GeneralAssembly(
        op=op, metric=t.metric, axis_metric=t.axis_metric, grad_theta=t.grad_theta, det=t.det,
        stiff_tables=t.stiff_tables, grad_tables=t.grad_tables, value_table=t.value_table,
        positions=positions, dofs=dofs)


def film_system(op: FilmOperator, fields, wedge_speed: float, eps: float = 0.0,
                flow: FlowFields | None = None):
    """(stiffness values on the pattern, load) of the film with evaluated
    :class:`~bearingfem.fields.FilmFields` ``fields`` at wedge speed w [rad/s]; ``flow``
    the rough gap's coefficient fields at the quadrature points
    (:func:`~bearingfem.contact.flow_factors.flow_fields` of ``fields.gap``; None: the
    smooth film's, H^3 and H).

    The Couette content rho H is split into a reference cylinder 1 + eps cos(theta), whose
    term is the fast path's exact load (strong form, :meth:`FilmOperator.load`), and the
    departure rho H - (1 + eps cos(theta)), taken in weak form: the rigid cylinder of
    ``eps`` given as fields then solves the fast path's discrete film to round-off, and
    any other film converges as before (the split changes the quadrature error only)."""
    ga = general_assembly(op)
    rho, H = fields.density, fields.gap
    if flow is None:
        k = rho * H ** 3 / fields.viscosity
        squeeze = -12.0 * (rho * fields.gap_rate + fields.density_rate * H)
        departure = rho * H - film_thickness_at(ga.cos_theta, eps)
        couette = 6.0 * wedge_speed * departure
    else:
        k = tuple(rho * c / fields.viscosity for c in flow.conductance)
        E = flow.mean_gap
        squeeze = -12.0 * (rho * flow.gap_slope * fields.gap_rate + fields.density_rate * E)
        # (U1 + U2)/2 carries the mean gap, (U1 - U2)/2 = omega R/2 the shear flow
        couette = (6.0 * wedge_speed * (rho * E - film_thickness_at(ga.cos_theta, eps))
                   + 6.0 * flow.shear_speed * rho * flow.shear)
    load = ga.load(couette, squeeze)
    if eps:
        load = load + op.load(eps, 0.0, wedge_speed)
    return ga.stiffness_values(k), load


def reference_load_partial(op: FilmOperator, wedge_speed: float) -> np.ndarray:
    """d(load)/d(eps) of :func:`film_system` with the fields held: the reference cylinder's
    strong-form load d/deps 6 w (1 + eps cos(theta)) minus its weak-form share taken back
    from the departure, at wedge speed w [rad/s].

    Zero for the exact integrals, but not for the discrete ones: the two forms differ by
    the weak Couette term's quadrature error, so a sensitivity that moves eps (and with it
    the fields' gap) needs it to differentiate the load the solve assembles. The load is
    linear in eps, so this holds at any eps."""
    weak = general_assembly(op).load(6.0 * wedge_speed * np.cos(op.qp_theta),
                                     np.zeros_like(op.qp_theta))
    return op.load(1.0, 0.0, wedge_speed) - weak


def general_film(bearing: Bearing, state: JournalState, op: FilmOperator,
                 fields: FilmFields | None = None, tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0),
                 profile: EdgeProfile | None = None):
    """The film's fields at ``op``'s quadrature points with the tilt's gap and the bush
    edge ``profile``'s added, and the nodal gap; raises ValueError when the tilted journal
    touches the bush."""
    spec = fields or FilmFields()
    film = spec.on(op, state) if state.eps < 1.0 else spec.beyond_clearance(op, state)
    gap = spec.nodal_gap(op, state)
    if profile is not None:     # fixed to the bush: no rate
        film = film.plus(gap=profile.film_gap(bearing, op.qp_zeta))
        gap = gap + profile.film_gap(bearing, op.mesh.zeta)
    if any(tilt) or any(tilt_rate):
        dH, dH_dt = tilted_gap(bearing, state, op.qp_theta, op.qp_zeta, tilt, tilt_rate)
        film = film.plus(gap=dH, gap_rate=dH_dt)
        gap = gap + tilted_gap(bearing, state, op.mesh.theta, op.mesh.zeta, tilt)[0]
        if not np.all(film.gap > 0.0):
            raise ValueError(f"tilt {tilt} [rad] brings the journal into the bush (minimum "
                             f"gap {float(np.min(film.gap)) * bearing.clearance:.3g} m at eps "
                             f"{state.eps}): reduce eps or the tilt")
    return film, gap


def film_moment(bearing: Bearing, op: FilmOperator, P: np.ndarray, gamma: float,
                clip: bool = False) -> tuple:
    """(M_x, M_y) [N m]: the film's moment on the journal about the bearing centre
    (mid-plane), inertial, of the whole-length film P.

    The pressure force on the journal per area is p (cos, sin)(theta + gamma), inertial, at
    the lever arm z = R zeta: M_x = -int z dF_y, M_y = int z dF_x. ``clip`` integrates
    max(P, 0) at the quadrature points (Gumbel's film), as the force does.
    """
    Q = op.at_quadrature(P)
    if clip:
        Q = np.maximum(Q, 0.0)
    Qz = Q * op.qp_weight * op.qp_zeta
    a = op.qp_theta + gamma
    k = moment_factor(bearing)
    return (-k * float(np.sum(Qz * np.sin(a))), k * float(np.sum(Qz * np.cos(a))))
