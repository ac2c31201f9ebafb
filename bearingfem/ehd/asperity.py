"""Asperity contact in the elastic film: the bush carries film and summit pressure.

With rough surfaces (Greenwood & Tripp, Proc. Instn Mech. Engrs 185 (1970) 625; the
pressure law of :mod:`bearingfem.contact.asperity`) the bush deflects under the film's
pressure p and the summits' nominal pressure p_a together,

    w = s C (p + p_a(h)),   h = h_rigid + w,   p_a(h) = K E* F_5/2(h / sigma),

at the film mesh's nodes: the compliance C acts on nodal pressures (the P1 interpolant of
the film pressure), so the summits' pressure enters it the same way, as the interpolant of
its nodal values (quadrature-point values would need a projection onto the nodes, a second
discretisation of the same load). ``s`` is the load continuation's coupling
(:mod:`bearingfem.ehd.newton`). The reported asperity force is the quadrature of p_a over
the deformed gap at the film's quadrature points (:func:`bearingfem.fe.mixed.film_contact`,
the rigid mixed film's rule), so an infinitely stiff bush gives today's mixed film exactly;
the two quadratures of the summit load differ by the mesh's O(h^2).

For a given film pressure the deflection solves the monotone equation
r(w) = w - s C (p + p_a(h0 + w)) = 0 (C positive, p_a decreasing in h: one solution),
here by Newton's method on w. Its Jacobian I - s C D, D = diag(dp_a/dh), is a low-rank
update of the identity: D is negligible where h exceeds several sigma (below round-off of C p there: those
nodes are left out of the update, ``NEGLIGIBLE``) and C = U W^T
with U = C[:, A], W the selection of the contact nodes A (full compliance) or
U = left diag(s), W = right (reduced), so each step solves a |A| x |A| or k x k system.
The film's Newton (:mod:`bearingfem.ehd.coupling`) then sees the deflection as a function
of the film pressure with the exact derivative

    dw/dp = (I - s C D)^-1 s C = s U (I - W^T D U)^-1 W^T    (Woodbury, push-through),

the summits' stiffness dp_a/dh = -(5/2) K E* F_3/2(h/sigma) / sigma acting through it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as la

__all__ = ["ContactDeflection", "contact_deflection", "deflection_factors"]

#: Newton iterations of the deflection before a trial film pressure is rejected
MAX_ITERATIONS = 60
#: the deflection's convergence: max |r| <= TOL max(|w|, FLOOR sigma) (round-off of C p
#: is ~1e-16 relative; the floor keeps a deflection of a few subnormal numbers, summits
#: 30 sigma away, from asking for digits it does not have)
TOL = 1e-13
FLOOR = 1e-6


@dataclass(frozen=True, eq=False)
class ContactDeflection:
    """The bush's deflection with the summits' pressure at one film pressure.

    deflection : nodal w [m]; asperity_pressure : nodal p_a [Pa] (on the deformed gap);
    slope : nodal dp_a/dh [Pa/m]; iterations : Newton steps on w
    """

    deflection: np.ndarray
    asperity_pressure: np.ndarray
    slope: np.ndarray
    iterations: int


#: summits whose stiffness moves the deflection by less than this share of the pressure's
#: own (|dp_a/dh| max C_ii) are left out of the low-rank update: below round-off of C p
NEGLIGIBLE = 1e-17


def _contact_nodes(compliance, s: float, slope: np.ndarray) -> np.ndarray:
    """The nodes whose summits' stiffness enters I - s C D above round-off."""
    if compliance.right is None:
        self_compliance = np.max(np.abs(np.diag(compliance.left)))
    else:
        self_compliance = np.max(np.abs(compliance.left * compliance.singular)
                                 @ np.abs(compliance.right).T.max(axis=1, keepdims=True))
    return np.flatnonzero(s * self_compliance * np.abs(slope) > NEGLIGIBLE)


def _factors(compliance, s: float, nodes: np.ndarray):
    """(U, W^T) with the compliance's columns that multiply the nodes ``nodes``:
    s C[:, nodes] = U W^T[:, nodes] (W^T as a matrix acting on the nodes' values)."""
    if compliance.right is None:
        U = s * compliance.left[:, nodes]
        return U, np.eye(nodes.size)
    return s * compliance.left * compliance.singular, compliance.right[nodes].T


def deflection_factors(compliance, s: float, slope: np.ndarray):
    """(U, V) with dw/dp [m/Pa] = U V^T (V None: the dense matrix U) for the summits'
    stiffness ``slope`` = dp_a/dh at the nodes (see the module docstring)."""
    nodes = _contact_nodes(compliance, s, slope)
    if compliance.right is None:
        C = s * compliance.left
        if nodes.size == 0:
            return C, None
        U, Wt = _factors(compliance, s, nodes)
        small = np.eye(nodes.size) - (Wt * slope[nodes]) @ U[nodes]
        return C + U @ la.solve(small, slope[nodes, None] * C[nodes], check_finite=False), None
    U, Wt = _factors(compliance, s, nodes)
    small = np.eye(U.shape[1]) - (Wt * slope[nodes]) @ U[nodes]
    return U @ la.inv(small, check_finite=False), compliance.right


def contact_deflection(compliance, roughness, gap0: np.ndarray, pressure: np.ndarray,
                       s: float = 1.0) -> ContactDeflection | None:
    """The deflection w [m] solving w = s C (p + p_a(gap0 + w)) at the film's nodes, from
    ``gap0`` the gap without deflection [m] and the film pressure ``pressure`` [Pa]
    (nodal); None when Newton's method does not converge (the caller rejects the trial)."""
    film = s * compliance.apply(pressure)

    def residual(w):
        pa = roughness.pressure(gap0 + w)
        return w - film - s * compliance.apply(pa), pa

    w = film.copy()
    r, pa = residual(w)
    for it in range(MAX_ITERATIONS + 1):
        size = max(float(np.max(np.abs(w), initial=0.0)), FLOOR * roughness.sigma)
        norm = float(np.max(np.abs(r), initial=0.0))
        if norm <= TOL * size:
            slope = roughness.pressure_derivative(gap0 + w)
            return ContactDeflection(w, pa, slope, it)
        if it == MAX_ITERATIONS or not np.isfinite(norm):
            return None
        slope = roughness.pressure_derivative(gap0 + w)
        nodes = _contact_nodes(compliance, s, slope)
        # (I - U W^T D) dw = -r: dw = -r + U y, (I - W^T D U) y = -W^T D r
        U, Wt = _factors(compliance, s, nodes)
        WtD = Wt * slope[nodes]
        try:
            y = la.solve(np.eye(WtD.shape[0]) - WtD @ U[nodes], -WtD @ r[nodes],
                         check_finite=False)
        except la.LinAlgError:
            return None
        step = -r + U @ y
        alpha, l2 = 1.0, np.linalg.norm(r)
        while alpha >= 1.0 / 1024:
            trial = w + alpha * step
            with np.errstate(over="ignore", invalid="ignore"):
                t_r, t_pa = residual(trial)
            if np.all(np.isfinite(t_r)) and np.linalg.norm(t_r) < (1 - 1e-4 * alpha) * l2:
                w, r, pa = trial, t_r, t_pa
                break
            alpha *= 0.5
        else:
            if norm <= 1e3 * TOL * size:      # at round-off: no descent left to find
                slope = roughness.pressure_derivative(gap0 + w)
                return ContactDeflection(w, pa, slope, it)
            return None
    return None
