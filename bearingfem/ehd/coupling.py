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
(sparse, the element pattern) and J_bush = T_H I C, T_H the quadrature-point derivatives
in H and I the nodal-to-quadrature interpolation. The full compliance of a bush is
circulant in theta (:class:`~bearingfem.ehd.film_compliance.CirculantCompliance`): J_bush
is then never formed, only applied (:class:`~bearingfem.ehd.film_compliance.BushJacobian`:
C by FFT, T_H sparse; cost N log N, memory linear); a reduced compliance
(:class:`~bearingfem.ehd.film_compliance.DofCompliance`) gives it of rank n.

A homotopy parameter ``s`` in [0, 1] scales the coupling: the fields are evaluated at
s p and the deflection is s C p, so s = 0 is the isoviscous rigid film and s = 1 the
EHD film (the load continuation of :mod:`bearingfem.ehd.newton`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..caches import cached
from .asperity import contact_deflection, deflection_factors
from .film_compliance import (BushJacobian, CirculantCompliance, DofCompliance,
                              dof_compliance)
from ..contact.flow_factors import flow_fields
from ..fields import FilmFields
from ..fe.general import film_system
from ..solvers.pattern import Pattern

__all__ = ["EHDFilm", "ehd_film", "FilmState", "jacobian_tables"]


@dataclass(frozen=True, eq=False)
class JacobianTables:
    """The film mesh's element pattern and shape functions at its quadrature points
    (cached per film operator: one build per mesh, not per solve).

    The stiffness pattern of the operator drops couplings that vanish for every
    conductance (orthogonal gradients on right triangles); the Jacobian's local terms
    (phi_i phi_j, dphi_i/dtheta phi_j) do not vanish there, so it has the whole element
    pattern: ``indptr/indices``, ``positions`` (elements, nb*nb) of each local entry in
    it, ``from_stiffness`` the place of each stiffness entry.
    """

    indptr: np.ndarray
    indices: np.ndarray
    positions: np.ndarray
    from_stiffness: np.ndarray
    phi: np.ndarray        # (nb, E, Q) phi_i dx
    dphi: np.ndarray       # (nb, 2, E, Q) grad phi_i dx
    value: np.ndarray      # (nb, E, Q) phi_j (no weight)
    dx: np.ndarray         # (E, Q) quadrature weights
    shape: tuple
    pattern: Pattern       # the Jacobian's pattern (checked once)
    rows: np.ndarray       # the row of each of its entries
    keys: np.ndarray       # row * N + column of each entry (sorted): where (i, j) sits
    diagonal: np.ndarray   # the place of each diagonal entry in it
    stiffness_diagonal: np.ndarray   # the same in the operator's stiffness pattern


def _distinct(keys: np.ndarray) -> np.ndarray:
    """The sorted distinct values of the integer ``keys`` (np.unique's answer): by a sort,
    where numpy's hashed np.unique took 3.1 s against 0.04 s on the 2.8 million keys of
    a 960 x 160 film (numpy 2.4, one process)."""
    s = np.sort(keys, axis=None)
    return s[np.concatenate(([True], s[1:] != s[:-1]))] if s.size else s


def _holds(sorted_keys: np.ndarray, values: np.ndarray) -> bool:
    """Whether every value is among the sorted keys (np.isin(...).all() by bisection)."""
    at = np.minimum(np.searchsorted(sorted_keys, values), sorted_keys.size - 1)
    return bool(sorted_keys.size) and bool(np.all(sorted_keys[at] == values))


@cached(maxsize=16)
def jacobian_tables(op) -> JacobianTables:
    basis = op.mesh.basis
    dx = basis.dx
    nb, N = basis.Nbfun, basis.N
    dofs = np.ascontiguousarray(basis.element_dofs.T).astype(np.int64)     # (E, nb)
    local = (dofs[:, :, None] * N + dofs[:, None, :]).reshape(len(dofs), -1)
    keys = _distinct(local)
    rows, cols = np.divmod(keys, N)
    indptr = np.searchsorted(rows, np.arange(N + 1)).astype(np.int32)
    stiff_rows = np.repeat(np.arange(N, dtype=np.int64), np.diff(op.indptr))
    value = np.array([np.asarray(basis.basis[i][0]) for i in range(nb)])
    diagonal = np.arange(N, dtype=np.int64) * (N + 1)
    stiff_keys = stiff_rows * N + op.indices
    if not (_holds(keys, diagonal) and _holds(stiff_keys, diagonal)):
        raise ValueError("the film's patterns must hold every diagonal entry")
    return JacobianTables(
        indptr=indptr, indices=cols.astype(np.int32), positions=np.searchsorted(keys, local),
        from_stiffness=np.searchsorted(keys, stiff_rows * N + op.indices),
        phi=value * dx, dphi=np.array([np.asarray(basis.basis[i][0].grad) * dx
                                       for i in range(nb)]),
        value=value, dx=np.asarray(dx), shape=(N, N),
        pattern=Pattern(indptr, cols.astype(np.int32), (N, N)), rows=rows, keys=keys,
        diagonal=np.searchsorted(keys, diagonal),
        stiffness_diagonal=np.searchsorted(stiff_keys, diagonal))


class PressureSlopes:
    """(d rho/dp, d(mu/mu0)/dp) [1/Pa] at the points, taken when first unpacked
    (``drho, dmu = slopes``). Why: only a Newton matrix reads them, and evaluated with the
    fields at every film evaluation they were a fifth of the film's residual (the seed
    pin's implicit EHD film, 192 x 16: 0.35 of 1.8 ms)."""

    def __init__(self, lubricant, p: np.ndarray, viscosity: float):
        self._lubricant, self._p, self._viscosity = lubricant, p, viscosity
        self._values = None

    def __iter__(self):
        if self._values is None:
            lub, p = self._lubricant, self._p
            self._values = (lub.density_derivative(p),
                            lub.viscosity_derivative(p) / self._viscosity)
        return iter(self._values)


@dataclass(frozen=True, eq=False)
class FilmState:
    """The EHD film evaluated at one pressure: its fields at the quadrature points, their
    pressure slopes (None without a lubricant), stiffness values on the operator's
    pattern, load, residual R = K P - load and the size of its terms |K| |P| + |load|."""

    fields: FilmFields
    slopes: PressureSlopes | None
    values: np.ndarray
    load: np.ndarray
    residual: np.ndarray
    size: np.ndarray
    contact: object = None     # ContactDeflection with roughness (bearingfem.ehd.asperity)
    flow: object = None        # FlowFields of a rough gap's flow (Patir & Cheng), or None


@dataclass(frozen=True, eq=False)
class EHDFilm:
    """One EHD film problem on one film operator (see the module docstring).

    base : the film's own fields at the quadrature points (gap without deflection, its
        rate, and viscosity / density ratios the lubricant multiplies)
    gap0 : nodal gap without deflection (H)
    lubricant : Lubricant or None; compliance : CirculantCompliance, DofCompliance or None
    scale : pressure scale mu0 (R/c)^2 [Pa s]; clearance c [m]; wedge : wedge speed [rad/s]
    viscosity : the bearing's viscosity mu0 [Pa s] (the ratios' reference)
    eps : the state's eccentricity ratio, the reference cylinder of the general load
        (:func:`~bearingfem.fe.general.film_system`)
    """

    op: object
    base: FilmFields
    gap0: np.ndarray
    lubricant: object
    compliance: CirculantCompliance | DofCompliance | None
    scale: float
    clearance: float
    wedge: float
    viscosity: float
    tables: JacobianTables
    eps: float = 0.0   # the reference cylinder's eps (film_system's strong-form Couette)
    roughness: object = None   # Roughness: the summits' pressure loads the bush too
    flow: object = None        # FlowFactors: the rough gap's flow (Patir & Cheng), or None
    sigma: float = 0.0         # the roughness sigma [m] the flow factors take
    omega: float = 0.0         # the surfaces' relative speed [rad/s] (the shear flow's)

    def contact(self, P: np.ndarray, s: float = 1.0):
        """The bush's deflection under s (p + p_a) with the summits' pressure
        (:class:`~bearingfem.ehd.asperity.ContactDeflection`), None where its Newton
        solve fails (a bush and a roughness needed)."""
        return contact_deflection(self.compliance, self.roughness,
                                  self.clearance * self.gap0, self.scale * P, s)

    def deflection(self, P: np.ndarray, s: float = 1.0) -> np.ndarray | None:
        """Nodal radial deflection w [m] of the bush under s p, with roughness under
        s (p + p_a) (zero without a bush; None where the contact's solve fails)."""
        if self.compliance is None:
            return np.zeros_like(P)
        if self.roughness is not None:
            c = self.contact(P, s)
            return None if c is None else c.deflection
        return s * self.compliance.apply(self.scale * P)

    def fields(self, P: np.ndarray, s: float = 1.0, contact=None):
        """(FilmFields at the quadrature points, their :class:`PressureSlopes` or None);
        with roughness ``contact`` the deflection's solve at P (None: solved here);
        (None, None) where that solve fails."""
        Hq = self.base.gap
        if self.compliance is not None:
            w = self.deflection(P, s) if contact is None else contact.deflection
            if w is None:
                return None, None
            Hq = Hq + self.op.at_quadrature(w) / self.clearance
        if self.lubricant is None:
            rho = mu = 1.0
            slopes = None
        else:
            p = s * self.scale * self.op.at_quadrature(P)
            lub = self.lubricant
            # ratios to the bearing's viscosity mu0, the one in the pressure scale
            rho, mu = lub.density_at(p), lub.viscosity_at(p) / self.viscosity
            slopes = PressureSlopes(lub, p, self.viscosity)
        film = FilmFields(gap=Hq, gap_rate=self.base.gap_rate,
                          viscosity=self.base.viscosity * mu, density=self.base.density * rho,
                          density_rate=self.base.density_rate)
        return film, slopes

    def flow_fields(self, film: FilmFields):
        """The rough gap's coefficient fields on ``film``'s gap (None: the smooth flow)."""
        if self.flow is None:
            return None
        return flow_fields(self.flow, film.gap, self.sigma / self.clearance, self.omega)

    def evaluate(self, P: np.ndarray, s: float = 1.0) -> FilmState | None:
        """The film at pressure P, or None where the gap closes or a viscosity or density
        is not finite and > 0 (a trial pressure may push a property law out of range)."""
        contact = None
        if self.compliance is not None and self.roughness is not None:
            contact = self.contact(P, s)
            if contact is None:
                return None
        film, slopes = self.fields(P, s, contact)
        # a rough gap's flow takes any nominal gap (the surfaces pressed through: its
        # mean gap stays > 0), a smooth one a gap > 0
        checked = (film.viscosity, film.density) if self.flow is not None else (
            film.gap, film.viscosity, film.density)
        for field in checked:
            if not np.all((field > 0.0) & np.isfinite(field)):
                return None
        flow = self.flow_fields(film)
        values, load = film_system(self.op, film, self.wedge, self.eps, flow)
        pattern = self.op.pattern
        size = pattern.matrix(np.abs(values)) @ np.abs(P) + np.abs(load)
        return FilmState(film, slopes, values, load, pattern.matrix(values) @ P - load, size,
                         contact, flow)

    def system(self, P: np.ndarray, s: float = 1.0):
        """(evaluated fields, stiffness values on the pattern, load) at pressure P, or
        Nones where the gap closes."""
        ev = self.evaluate(P, s)
        return (None, None, None) if ev is None else (ev.fields, ev.values, ev.load)

    def residual(self, P: np.ndarray, s: float = 1.0):
        """(R = K P - load on all dofs, a scale of its terms, K values) or Nones when the
        gap closes."""
        ev = self.evaluate(P, s)
        return (None, None, None) if ev is None else (ev.residual, ev.size, ev.values)

    def _assembler(self, P: np.ndarray):
        """assemble(dk, dc, dsq): the values on the pattern of the residual's derivative
        sum_q B_iq (coefficient derivative)_q phi_j(q), given the derivatives of the
        stiffness coefficient (dk), the Couette content (dc) and the squeeze source (dsq)
        at the points in a nodal quantity interpolated there, at pressure P."""
        t = self.tables
        dofs = self.op.mesh.basis.element_dofs                              # (nb, E)
        gradP = np.einsum("jceq,je->ceq", t.dphi, P[dofs]) / t.dx          # grad P
        Bk = np.einsum("iceq,ceq->ieq", t.dphi, gradP)                      # grad P.grad phi dx
        Bc = t.dphi[:, 0]                                                   # dphi/dtheta dx
        Bs = t.phi

        def assemble(dk, dc, dsq):
            if isinstance(dk, tuple):       # a diagonal tensor's: one axis at a time
                flux = sum(t.dphi[:, a] * gradP[a] * dk[a] for a in range(2))
            else:
                flux = Bk * dk
            g = flux - Bc * dc - Bs * dsq                                   # (nb, E, Q)
            local = np.einsum("ieq,jeq->eij", g, t.value).reshape(g.shape[1], -1)
            return np.bincount(t.positions.ravel(), local.ravel(),
                               minlength=len(t.indices))
        return assemble

    def _gap_slope(self, assemble, ev: FilmState, where=None) -> sp.csr_matrix:
        film, f = ev.fields, ev.flow
        rho, mu, H = film.density, film.viscosity, film.gap
        if f is None:
            coef = (3.0 * rho * H**2 / mu, 6.0 * self.wedge * rho,
                    -12.0 * film.density_rate * np.ones_like(H))
        else:       # film_system's rough-gap coefficients differentiated in H
            coef = (tuple(rho * d / mu for d in f.conductance_slope),
                    6.0 * rho * (self.wedge * f.gap_slope + f.shear_speed * f.shear_slope),
                    -12.0 * (rho * f.gap_curvature * film.gap_rate
                             + film.density_rate * f.gap_slope))
        if where is not None:
            coef = tuple(tuple(x * where for x in c) if isinstance(c, tuple) else c * where
                         for c in coef)
        return self.tables.pattern.matrix(assemble(*coef))

    def gap_slope(self, P: np.ndarray, s: float = 1.0, state: FilmState | None = None,
                  where=None) -> sp.csr_matrix:
        """dR/dH (nodes x nodes): the residual's derivative in the nodal gap H
        (dimensionless; the gap at the points interpolated from it) at P, the fields held.
        ``where`` (elements x points): 0 at points whose gap does not follow the nodes'
        (a floor), 1 elsewhere."""
        ev = self.evaluate(P, s) if state is None else state
        return self._gap_slope(self._assembler(P), ev, where)

    def jacobian(self, P: np.ndarray, s: float = 1.0, state: FilmState | None = None):
        """(J_sparse, U, V) with dR/dP = J_sparse + U V^T (U, V None without a bush; for
        the circulant compliance U is a :class:`BushJacobian` (matrix-free) and V None;
        for a dense one V is the identity, given as None, and U dense N x N), at P
        (``state`` its evaluation, when the caller has it: the film is then not built
        again)."""
        ev = self.evaluate(P, s) if state is None else state
        film, slopes, t = ev.fields, ev.slopes, self.tables
        rho, mu, H = film.density, film.viscosity, film.gap
        assemble = self._assembler(P)
        data = np.bincount(t.from_stiffness, ev.values, minlength=len(t.indices))
        if slopes is not None and ev.flow is None:
            drho, dmu = slopes
            ds = s * self.scale
            # d(1/mu)/dp as (dmu/mu)/mu: a piezoviscous oil's mu at a Newton trial's high
            # pressure (Barus, 1e160 and up) overflows when squared
            data += assemble(ds * (drho * H**3 / mu - rho * H**3 * (dmu / mu) / mu),
                             ds * 6.0 * self.wedge * drho * H,
                             ds * -12.0 * drho * film.gap_rate)
        elif slopes is not None:    # the rough gap's coefficients through rho and mu
            drho, dmu = slopes
            ds, f = s * self.scale, ev.flow
            data += assemble(tuple(ds * (drho * C / mu - rho * C * (dmu / mu) / mu)
                                   for C in f.conductance),
                             ds * 6.0 * drho * (self.wedge * f.mean_gap
                                                + f.shear_speed * f.shear),
                             ds * -12.0 * drho * f.gap_slope * film.gap_rate)
        J = t.pattern.matrix(data)
        if self.compliance is None:
            return J, None, None
        TH = self._gap_slope(assemble, ev)
        k = s * self.scale / self.clearance
        c = self.compliance
        if ev.contact is not None:      # dw/dp through the summits' stiffness (asperity.py)
            U, V = deflection_factors(c, s, ev.contact.slope)
            k = self.scale / self.clearance          # s is in U
            return J, k * (TH @ U), V
        if isinstance(c, CirculantCompliance):
            return J, BushJacobian(k * TH, c), None
        if c.right is None:
            return J, k * (TH @ c.left), None
        return J, k * (TH @ (c.left * c.singular)), c.right


def ehd_film(bearing, state, op, base: FilmFields, gap0, lubricant, bush,
             roughness=None) -> EHDFilm:
    """Build the EHD film of ``op`` on the evaluated base fields ``base`` (``roughness``:
    the summits' pressure loads the bush too, :mod:`bearingfem.ehd.asperity`; its
    ``flow``, the rough gap's flow factors, enter the film's Reynolds form)."""
    compliance = None if bush is None else dof_compliance(bush, bearing, op)
    flow = None if roughness is None else roughness.flow
    return EHDFilm(op=op, base=base, gap0=gap0, lubricant=lubricant, compliance=compliance,
                   scale=bearing.pressure_scale, clearance=bearing.clearance,
                   wedge=state.wedge_speed, viscosity=bearing.viscosity,
                   tables=jacobian_tables(op), eps=state.eps,
                   roughness=None if bush is None else roughness, flow=flow,
                   sigma=0.0 if flow is None else roughness.sigma, omega=state.omega)
