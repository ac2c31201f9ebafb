"""The EHD film with mass-conserving (JFO) cavitation: the JFO balance on the elastic gap.

The steady JFO balance of :mod:`bearingfem.fe.jfo` on the nodes' control volumes,

    R_j = (K(p, H) P)_j + (T(H) phi)_j + S_j phi_j = 0   on the free volumes,
    P >= 0,  phi <= 1,  P (1 - phi) = 0,

with the gap of the elastic bush H = H_rigid + w / c, w = C p (C its compliance,
:func:`~bearingfem.ehd.film_compliance.dof_compliance`), and a pressure-viscosity law of a
:class:`~bearingfem.lubricant.Lubricant` in the Poiseuille operator K (the EHD film's
own, :class:`~bearingfem.ehd.coupling.EHDFilm`, at zero wedge speed). T is the upwind
Couette transport across the volumes' downstream faces, whose flux 6 w int H dzeta
takes the deflection by the Gauss rule of :mod:`bearingfem.fe.jfo_fields` on each face
(w bilinear between the nodes there, as that module reads a nodal field; P1 at the
element quadrature points in K, as the Reynolds EHD film does). S is the squeeze storage
12 eps_dot int cos(theta) of the rigid cylinder: quasi-static, the deflection's rate is
left out, as in the Reynolds EHD film.

Solved by :func:`~bearingfem.ehd.jfo_newton.solve_ehd_jfo` (semismooth Newton on the
universal variable with load continuation).

References: M. Giacopini, M.T. Fowell, D. Dini, A. Strozzi, A mass-conserving
complementarity formulation to study lubricant films in the presence of cavitation,
J. Tribol. 132 (2010) 041702; C. Bertocchi, D. Dini, M. Giacopini, M.T. Fowell,
A. Baldini, Fluid film lubrication in the presence of cavitation: a mass-conserving
two-dimensional formulation for compressible, piezoviscous and non-Newtonian fluids,
Tribol. Int. 67 (2013) 61-71.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..caches import cached
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fe.jfo_balance import boundary_values, cos_integral, film_volumes
from ..fe.jfo_fields import BalanceFilm, halves, zeta_extent, rigid_balance_film
from ..fe.mixed import film_contact, with_contact
from ..fe.multilevel import prolongation
from ..fields import FilmFields
from ..lubricant import Lubricant
from ..fe.jfo_steady import jfo_film_solution, steady_jfo
from ..fe.volumes import transport_matrix
from .asperity import deflection_factors
from .coupling import EHDFilm, ehd_film
from .film_compliance import BushJacobian
from .jfo_newton import EHDJFOSolve, solve_ehd_jfo

__all__ = ["JFOCoupling", "FaceMaps", "jfo_coupling", "solve_ehd_jfo", "check_ehd_jfo",
           "EHDJFOSolve", "solve_elastic_jfo_film"]


def check_ehd_jfo(lubricant, fields, tilt, tilt_rate):
    """ValueError for what the EHD-JFO film does not model, before any work."""
    if lubricant is not None:
        if not isinstance(lubricant, Lubricant):
            raise ValueError(f"lubricant must be a bearingfem.Lubricant or None, "
                             f"got {type(lubricant).__name__}")
        if lubricant.density is not None or lubricant.bulk_modulus is not None:
            # the content rho phi H would need the density of the cavity's streamers
            raise ValueError("cavitation='jfo' with a bush takes a lubricant with a "
                             "pressure-viscosity law only: give density=None and "
                             "bulk_modulus=None")
    if fields is not None or any(tilt) or any(tilt_rate):
        raise ValueError("cavitation='jfo' with a bush or lubricant takes no fields, tilt "
                         "or tilt_rate yet")


@dataclass(frozen=True, eq=False)
class FaceMaps:
    """Linear maps from the nodal gap departure (H - H_rigid, dimensionless) to each
    control volume's downstream-face integral int dH dzeta (``face``) and content
    int dH dA (``content``), by the Gauss rule of :mod:`bearingfem.fe.jfo_fields`."""

    face: sp.csr_matrix
    content: sp.csr_matrix


@cached(maxsize=16)
def face_maps(op) -> FaceMaps:
    mesh = op.mesh
    cv = film_volumes(mesh)
    n = len(cv.down)
    ys, wy = halves(*zeta_extent(op, cv))
    th = np.broadcast_to(cv.face[:, None], ys.shape)
    rows = np.repeat(np.arange(n), ys.shape[1])
    face = sp.csr_matrix((wy.ravel(), (rows, np.arange(rows.size))), shape=(n, rows.size)) \
        @ prolongation(mesh, th.ravel(), ys.ravel())
    xs, wx = halves(cv.x_lo, mesh.axes[0][cv.column], cv.x_hi)
    TH = np.broadcast_to(xs[:, :, None], xs.shape + (ys.shape[1],))
    ZE = np.broadcast_to(ys[:, None, :], TH.shape)
    W = wx[:, :, None] * wy[:, None, :]
    rows = np.repeat(np.arange(n), W[0].size)
    content = sp.csr_matrix((W.ravel(), (rows, np.arange(rows.size))), shape=(n, rows.size)) \
        @ prolongation(mesh, TH.ravel(), ZE.ravel())
    return FaceMaps(face.tocsr(), content.tocsr())


@dataclass(frozen=True, eq=False)
class BalanceState:
    """The balance at one (P, phi): its film (K values, faces), residual on all nodes
    and the size of its terms."""

    ev: object
    K: sp.csr_matrix
    T: sp.csr_matrix
    face: np.ndarray
    residual: np.ndarray
    size: np.ndarray


@dataclass(frozen=True, eq=False)
class JFOCoupling:
    """One steady EHD-JFO problem on one P1 film operator (module docstring).

    poiseuille : the EHD film at zero wedge speed and no squeeze (its residual is K P);
    speed : the wedge speed w [rad/s] (6 x speed x face is the Couette flux);
    storage : the squeeze storage S per volume; P_fixed, phi_fixed : held values
    """

    poiseuille: EHDFilm
    speed: float
    storage: np.ndarray
    P_fixed: np.ndarray
    phi_fixed: np.ndarray
    maps: FaceMaps
    face0: np.ndarray
    content0: np.ndarray

    @property
    def op(self):
        return self.poiseuille.op

    def gap_departure(self, P: np.ndarray, s: float = 1.0) -> np.ndarray:
        """Nodal w / c (dimensionless) of the bush under s p."""
        f = self.poiseuille
        return f.deflection(P, s) / f.clearance

    def evaluate(self, P: np.ndarray, phi: np.ndarray, s: float = 1.0) -> BalanceState | None:
        """The balance at (P, phi) on all nodes, or None where the gap closes."""
        ev = self.poiseuille.evaluate(P, s)
        if ev is None:
            return None
        # with roughness the deflection was solved with the summits' pressure in ev
        dH = (self.gap_departure(P, s) if ev.contact is None
              else ev.contact.deflection / self.poiseuille.clearance)
        face = self.face0 + self.maps.face @ dH
        cv = film_volumes(self.op.mesh)
        T = transport_matrix(cv, 6.0 * self.speed * face)
        K = sp.csr_matrix((ev.values, self.op.indices, self.op.indptr), shape=self.op.shape)
        flow = T @ phi + self.storage * phi
        size = np.abs(K) @ np.abs(P) + np.abs(T) @ np.abs(phi) + np.abs(self.storage * phi)
        return BalanceState(ev, K, T, face, K @ P + flow, size)

    def content_slope(self, phi):
        """d(residual)/d(gap departure) beyond the faces' (None: the steady balance has
        no content term; the transient step's, :mod:`bearingfem.ehd.jfo_transient`)."""
        return None

    def jacobian(self, P, phi, s, state: BalanceState):
        """(dR/dP sparse, U, V, dR/dphi) with dR/dP = sparse + U V^T (U, V None without a
        bush; V None: U is the dense full product)."""
        J, U, V = self.poiseuille.jacobian(P, s, state.ev)
        A = state.T + sp.diags(self.storage, format="csr")
        f = self.poiseuille
        if f.compliance is None:
            return J, None, None, A
        cv = film_volumes(self.op.mesh)
        k = np.flatnonzero(cv.down >= 0)
        flux = 6.0 * self.speed * state.face[k]
        up = np.where(flux >= 0.0, k, cv.down[k])
        # d(T phi)/d(face_k) = 6 speed phi_up (e_k - e_down): the face flux leaves k
        g = 6.0 * self.speed * phi[up]
        n = len(cv.down)
        DT = sp.csr_matrix((np.concatenate([g, -g]),
                            (np.concatenate([k, cv.down[k]]), np.concatenate([k, k]))),
                           shape=(n, n))
        TH = DT @ self.maps.face
        slope = self.content_slope(phi)
        if slope is not None:
            TH = TH + slope
        scale = s * f.scale / f.clearance
        c = f.compliance
        if state.ev.contact is not None:     # dw/dp through the summits' stiffness
            Uc, Vc = deflection_factors(c, s, state.ev.contact.slope)   # s is in Uc
            return J, U + (f.scale / f.clearance) * (TH @ Uc), Vc, A
        if isinstance(U, BushJacobian):
            return J, U.plus(scale * TH), None, A
        if c.right is None:
            return J, U + scale * (TH @ c.left), None, A
        return J, U + scale * (TH @ (c.left * c.singular)), V, A


def jfo_coupling(bearing, state, op, lubricant, bush, grooves, ambient: float,
                 roughness=None) -> JFOCoupling:
    """The EHD-JFO problem of ``op`` (a whole-length P1 film operator); ``roughness``: the
    summits' pressure loads the bush too (:mod:`bearingfem.ehd.asperity`)."""
    rigid = FilmFields().on(op, state)
    base = replace(rigid, gap_rate=np.zeros_like(rigid.gap))
    gap0 = FilmFields().nodal_gap(op, state)
    poiseuille = replace(ehd_film(bearing, state, op, base, gap0, lubricant, bush, roughness),
                         wedge=0.0, eps=0.0)
    cv = film_volumes(op.mesh)
    P_fix, phi_fix = boundary_values(bearing, op.mesh, grooves, ambient)
    rb = rigid_balance_film(op, state)
    return JFOCoupling(poiseuille, state.wedge_speed,
                       12.0 * state.eps_dot * cos_integral(cv), P_fix, phi_fix,
                       face_maps(op), rb.face, rb.content)


def balance_film(film: JFOCoupling, P: np.ndarray) -> BalanceFilm:
    """The :class:`BalanceFilm` of the converged deformed film (its outputs' fields)."""
    fields, _ = film.poiseuille.fields(P)
    dH = film.gap_departure(P)
    values = film.poiseuille.evaluate(P).values
    return BalanceFilm(values=values, content=film.content0 + film.maps.content @ dH,
                       face=film.face0 + film.maps.face @ dH,
                       squeeze=film.storage / 12.0, fields=fields,
                       gap=film.poiseuille.gap0 + dH)


def solve_ehd_jfo_film(bearing, state, operator, n_theta: int, n_z: int, lubricant, bush,
                       grooves, ambient: float, tol: float, start=None, roughness=None):
    """The route of ``solve_reynolds(..., cavitation="jfo", bush=, lubricant=)``: the rigid
    JFO film on ``operator(n_theta, n_z)`` (whole length), then the EHD-JFO Newton; a
    :class:`FilmSolution` with ``fraction``, ``deformation`` [m] and the deformed ``gap``.
    ``start``: a previous EHD-JFO FilmSolution on the same mesh (warm start).
    ``roughness``: the summits' pressure deforms the bush with the film's, and their
    contact on the deformed gap is added to the solution (as the Reynolds EHD film's)."""
    op = operator(n_theta, n_z)
    film = jfo_coupling(bearing, state, op, lubricant, bush, grooves, ambient, roughness)

    def rigid():
        return steady_jfo(bearing, state, operator, n_theta, n_z, grooves, ambient)[:2]
    warm = None
    if start is not None:
        P, phi = getattr(start, "pressure", None), getattr(start, "fraction", None)
        if P is None or phi is None or np.shape(P) != (op.mesh.ndofs,):
            raise ValueError(f"start must be a JFO FilmSolution of the same film mesh "
                             f"({op.mesh.ndofs} nodes) or None")
        warm = (np.asarray(P, float) / bearing.pressure_scale, np.asarray(phi, float))
    try:
        out = solve_ehd_jfo(bearing, film, rigid, None, tol, warm)
    except ConvergenceError as e:
        raise e.at(f"steady EHD-JFO film {n_theta}x{n_z}, eps = {state.eps:.6g}") from None
    balance = balance_film(film, out.P)
    sol = jfo_film_solution(bearing, state, op, out.P, out.phi, out.result, out.flows,
                            "fem-P1/jfo-ehd-newton", balance)
    sol = replace(sol, deformation=film.poiseuille.deflection(out.P))
    if roughness is None:
        return sol
    # the summits on the deformed gap, at the quadrature points (the rigid mixed film's rule)
    return with_contact(sol, film_contact(bearing, state, op, roughness, balance.fields.gap))


def solve_elastic_jfo_film(bearing, state, n_theta: int, n_z: int, *, lubricant=None,
                           bush=None, grooves=(), ambient_pressure: float = 0.0,
                           tol: float = 1e-10, supply_angle=None, start=None,
                           roughness=None):
    """The EHD-JFO film on an (n_theta, n_z) mesh of the whole length (arguments as
    :func:`bearingfem.solve_reynolds`'s, checked there): :func:`solve_ehd_jfo_film`."""
    def whole(nt, nz):
        return fe_operator(bearing, state, nt, nz, "P1", supply_angle, False, grooves)
    return solve_ehd_jfo_film(bearing, state, whole, n_theta, n_z, lubricant, bush, grooves,
                              ambient_pressure, tol, start, roughness)
