"""Exact sensitivity of the finite-element film force to the journal state.

The discrete film solves K(eps) P = b(eps, eps_dot, w) on the pressurised (inactive) dofs
I, with P = 0 on the cavitated ones. With that set held fixed (it is locally constant
wherever no dof sits exactly on the free boundary),

    K_II dP_I/dq = db_I/dq - (dK/dq P)_I,     q in (eps, eps_dot, w),
    dK/deps = 3 K_1 + 6 eps K_2 + 3 eps^2 K_3,   db/deps = 6 w b_sin,
    db/deps_dot = -12 b_cos,                     db/dw = 6 eps b_sin,

three right-hand sides on the factors the cavitation solve already holds: no extra
factorisation. The force is linear in P (b_cos . P, b_sin . P); for Gumbel's clipped film
it integrates dP over the quadrature points where P > 0 (the clip's boundary moves, but the
integrand is zero there, so it adds nothing to first order).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..fields import check_tilt
from ..scales import force_factor
from ..solution import ForceDerivatives
from ..solvers.blocksolve import inactive_solve
from ..validation import check_film_solve
from .general import film_system, general_assembly, reference_load_partial
from .grooved import groove_operator_for, grooved_derivatives
from .kernel import fe_operator, fe_pressure, general_film, groove_pressures

__all__ = ["fe_force_derivatives", "TiltCoefficients", "fe_tilt_coefficients",
           "gap_sensitivities", "generalised_forces"]

#: The four journal coordinates of a misaligned film and their generalised forces.
COORDINATES = ("e_x", "e_y", "tilt_x", "tilt_y")
FORCES = ("F_x", "F_y", "M_x", "M_y")


def fe_force_derivatives(bearing: Bearing, state: JournalState, n_theta: int = 120,
                         n_z: int = 20, element: str = "P1", cavitation: str = "reynolds",
                         grooves=(), grading=None) -> ForceDerivatives:
    """(F_r, F_t) [N] of the FE film and its exact partials in (eps, eps_dot, w).

    Same film as :func:`~bearingfem.solve_reynolds` (half domain). With
    ``grooves`` (held pressures enter through P, which carries them on the fixed dofs) the
    film is solved on the bearing-fixed mesh of :mod:`bearingfem.fe.grooved`, which also
    gives the partial in gamma (the grooves moving against the film) exactly. ``grading``:
    without grooves, the strength of the film-frame mesh's grading toward the least film
    (:func:`~bearingfem.fe.assembly.fe_operator`).
    """
    if grooves:     # the bearing-fixed mesh: d/dgamma exact (bearingfem.fe.grooved)
        if grading is not None:
            raise ValueError("grading (a strength toward the least film) is for the film "
                             "without grooves here: give one of them")
        return grooved_derivatives(bearing, state,
                                   groove_operator_for(bearing, n_theta, n_z, element, grooves),
                                   grooves, cavitation)
    op = fe_operator(bearing, state, n_theta, n_z, element, None, True, grooves, grading)
    res = fe_pressure(op, state, cavitation, dirichlet=groove_pressures(bearing, op, grooves))
    P = res.pressure
    free = op.mesh.free
    e, w = state.eps, state.wedge_speed
    dK = op.matrix(op.values(e, derivative=True))
    # the source is linear in eps (wedge part), eps_dot and w: unit values give its partials
    rhs = np.column_stack([op.load(1.0, 0.0, w) - dK @ P, op.load(e, 1.0, 0.0),
                           op.load(e, 0.0, 1.0)])[free]
    inactive = ~res.active[free] if cavitation == "reynolds" else np.ones(len(free), bool)
    dP = np.zeros((op.mesh.ndofs, 3))
    dP[free] = inactive_solve(op.free_stiffness(e), res.factor, inactive, rhs)

    k = force_factor(bearing, op.mesh.half)
    fields = np.concatenate([P[None], dP.T])
    # Gumbel: P and its partials where the clipped film is positive, as fe_force integrates
    where = op.at_quadrature(P) > 0.0 if cavitation == "gumbel" else None
    F = k * op.force_integrals(fields, where=where)
    col = [tuple(float(x) for x in F[:, j]) for j in range(4)]
    return ForceDerivatives(col[0], col[1], col[2], col[3], "exact-sensitivity")


@dataclass(frozen=True)
class TiltCoefficients:
    """Stiffness and damping of a misaligned film over q = (e_x, e_y, tilt_x, tilt_y)
    [m, m, rad, rad] with generalised forces Q = (F_x, F_y, M_x, M_y) [N, N, N m, N m],
    inertial: K_ij = -dQ_i/dq_j, C_ij = -dQ_i/dq_j' (units N/m, N, N m/m, N m/rad ... by
    entry; C likewise per unit rate). ``force`` is Q at the state."""

    K: np.ndarray
    C: np.ndarray
    force: np.ndarray
    method: str = "exact-sensitivity"


def gap_sensitivities(bearing: Bearing, state: JournalState, theta, zeta) -> np.ndarray:
    """dH/dq for q = (e_x, e_y, tilt_x, tilt_y) at film angles theta and zeta = z/R
    (shape (4,) + theta.shape) [1/m, 1/m, 1/rad, 1/rad].

    H = 1 + (e_x(z) cos(a) + e_y(z) sin(a)) / c with a = theta + gamma, e_x(z) = e_x +
    z tilt_y, e_y(z) = e_y - z tilt_x: the gap is linear in q. These are also the weights
    of the generalised forces, Q_j = c int p dH/dq_j dA (virtual work).
    """
    a = np.asarray(theta) + state.gamma
    c = bearing.clearance
    z = bearing.radius * np.asarray(zeta)
    return np.stack([np.cos(a) / c, np.sin(a) / c, -z * np.sin(a) / c, z * np.cos(a) / c])


def generalised_forces(bearing: Bearing, state: JournalState, op, P: np.ndarray,
                       clip: bool = False, where=None) -> np.ndarray:
    """(F_x, F_y, M_x, M_y) [N, N, N m, N m] of the whole-length nodal pressure P (or
    fields P of shape (n, ndofs): result (4, n)): c int p dH/dq at the quadrature points;
    ``clip`` integrates max(P, 0) (Gumbel's film), ``where`` only where it is True."""
    Q = op.at_quadrature(P)
    if clip:
        Q = np.maximum(Q, 0.0)
    if where is not None:
        Q = Q * where
    g = gap_sensitivities(bearing, state, op.qp_theta, op.qp_zeta) * op.qp_weight
    k = bearing.clearance * force_factor(bearing)
    return k * np.einsum("...eq,jeq->j...", Q, g)


def fe_tilt_coefficients(bearing: Bearing, state: JournalState, tilt=(0.0, 0.0),
                         n_theta: int = 120, n_z: int = 20, element: str = "P1",
                         cavitation: str = "reynolds") -> TiltCoefficients:
    """4x4 K and C of the (misaligned) FE film at a steady state, by exact sensitivity.

    With the cavitated set held, K_II dP_I = db/dq - dK/dq P for each coordinate, the
    partials of the general assembly (:mod:`bearingfem.fe.general`) with
    dk/dq = 3 H^2 dH/dq (rho = mu = 1) and db/dq the Couette load of 6 w dH/dq plus, along
    the eccentricity, the partial of the load's strong-form reference cylinder
    (:func:`~bearingfem.fe.general.reference_load_partial`; it moves with eps); a rate
    q' enters through the squeeze load -12 dH/dq only. Four right-hand sides of each kind
    on the factors the film solve holds. The state must be steady (eps_dot = gamma_dot = 0,
    no tilt rate): the linearisation is about it. Whole length meshed. The position
    columns are those of the film whose mesh turns with the journal, as ``solve_reynolds``
    solves it (:func:`_turning_position_columns`; eps >= ``EPS_TURN``): K is the exact
    derivative of its force and moment, and at zero tilt the aligned film's 2x2.
    """
    check_film_solve(bearing, state, n_theta, n_z, cavitation, "active-set", None,
                     element=(element, ("P1", "P2")))
    tilt = check_tilt("tilt", tilt)
    if cavitation == "jfo":
        raise ValueError("fe_tilt_coefficients: cavitation must be 'none', 'gumbel' or "
                         "'reynolds', got 'jfo'")
    if state.eps_dot != 0.0 or state.gamma_dot != 0.0:
        raise ValueError("fe_tilt_coefficients linearises about a steady state: eps_dot and "
                         f"gamma_dot must be 0, got {state.eps_dot!r}, {state.gamma_dot!r}")
    op = fe_operator(bearing, state, n_theta, n_z, element, None, False)
    film, _ = general_film(bearing, state, op, None, tilt)
    values, load = film_system(op, film, state.wedge_speed, state.eps)
    res = fe_pressure(op, state, cavitation, system=(values, load))
    P = res.pressure
    ga = general_assembly(op)
    g = gap_sensitivities(bearing, state, op.qp_theta, op.qp_zeta)
    H, w = film.gap, state.wedge_speed
    zero = np.zeros_like(H)
    shape = op.shape
    # the load's reference cylinder follows eps = |e| / c: it moves with e along r only,
    # deps/dq = (cos(gamma), sin(gamma), 0, 0) / c
    deps = np.array([math.cos(state.gamma), math.sin(state.gamma), 0.0, 0.0])
    deps /= bearing.clearance
    db_deps = reference_load_partial(op, w)
    rhs = []
    for gj, de in zip(g, deps):          # positions: db/dq - dK/dq P
        dK = sp.csr_matrix((ga.stiffness_values(3.0 * H ** 2 * gj), op.indices, op.indptr),
                           shape=shape)
        rhs.append(ga.load(6.0 * w * gj, zero) + de * db_deps - dK @ P)
    rhs += [ga.load(zero, -12.0 * gj) for gj in g]      # rates: squeeze loads
    free = op.mesh.free
    inactive = ~res.active[free] if cavitation == "reynolds" else np.ones(len(free), bool)
    dP = np.zeros((op.mesh.ndofs, 8))
    dP[free] = inactive_solve(op.free_stiffness(state.eps, values), res.factor, inactive,
                               np.column_stack(rhs)[free])
    where = op.at_quadrature(P) > 0.0 if cavitation == "gumbel" else None
    Q = generalised_forces(bearing, state, op, P, clip=cavitation == "gumbel")
    # Gumbel: the partials where the clipped film is positive (its edge adds nothing to
    # first order: the integrand vanishes there)
    dQ = generalised_forces(bearing, state, op, dP.T, where=where)
    K = -dQ[:, :4]
    if state.eps >= EPS_TURN:
        K[:, :2] = _turning_position_columns(bearing, state, tilt, K, Q)
    return TiltCoefficients(K=K, C=-dQ[:, 4:], force=Q)


#: Below this eccentricity ratio the position columns stay the fixed mesh's: the turning
#: form divides by eps (the polar frame is singular at the centre).
EPS_TURN = 1e-6


def _turning_position_columns(bearing, state, tilt, K, Q) -> np.ndarray:
    """K's (e_x, e_y) columns of the film as ``solve_reynolds`` solves it, its mesh turning
    with gamma.

    Along the eccentricity (r) the mesh stays put: the fixed-mesh column is exact. Across
    it (t) the mesh turns: turning eps, gamma and the tilt together turns the whole
    discrete problem, so Q turns with it exactly, dQ/dgamma|_all = J Q (J turns each of
    (F_x, F_y) and (M_x, M_y) by +90 deg); the tilt held inertial takes back its share,
    dQ/dtilt J tilt. Hence dQ/de_t = (J Q - dQ/dtilt J tilt) / (c eps), the partial that
    also makes the zero-tilt limit the aligned film's 2x2 (which turns its mesh too) to
    round-off, where the fixed mesh's differs by the cavitation front's discretisation.
    """
    g = state.gamma
    r_hat, t_hat = np.array([math.cos(g), math.sin(g)]), np.array([-math.sin(g), math.cos(g)])
    JQ = np.array([-Q[1], Q[0], -Q[3], Q[2]])
    J_tilt = np.array([-tilt[1], tilt[0]])
    K_r = K[:, :2] @ r_hat
    K_t = -(JQ + K[:, 2:] @ J_tilt) / (bearing.clearance * state.eps)
    return np.outer(K_r, r_hat) + np.outer(K_t, t_hat)
