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

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..scales import force_factor
from ..solution import ForceDerivatives
from ..solvers.blocksolve import PinnedFactor, bordered_solve, pinned
from ..solvers.linsolve import factorise
from .reynolds import fe_force, fe_operator, fe_pressure, groove_pressures

__all__ = ["fe_force_derivatives"]


def fe_force_derivatives(bearing: Bearing, state: JournalState, n_theta: int = 120,
                         n_z: int = 20, element: str = "P1", cavitation: str = "reynolds",
                         grooves=()) -> ForceDerivatives:
    """(F_r, F_t) [N] of the FE film and its exact partials in (eps, eps_dot, w).

    Same film as :func:`~bearingfem.fe.reynolds.solve_reynolds` (half domain). With
    ``grooves`` (held pressures enter through P, which carries them on the fixed dofs) the
    partial in gamma, the grooves moving against the film, is a central difference: the
    mesh moves with the grooves, so the force is smooth in gamma.
    """
    op = fe_operator(bearing, state, n_theta, n_z, element, None, True, grooves)
    res = fe_pressure(op, state, cavitation, dirichlet=groove_pressures(bearing, op, grooves))
    P = res.pressure
    free = op.mesh.free
    e, w = state.eps, state.wedge_speed
    dK = sp.csr_matrix((op.values(e, derivative=True), op.indices, op.indptr), shape=op.shape)
    # the source is linear in eps (wedge part), eps_dot and w: unit values give its partials
    rhs = np.column_stack([op.load(1.0, 0.0, w) - dK @ P, op.load(e, 1.0, 0.0),
                           op.load(e, 0.0, 1.0)])[free]
    inactive = ~res.active[free] if cavitation == "reynolds" else np.ones(len(free), bool)
    dP = np.zeros((op.mesh.ndofs, 3))
    dP[free] = _inactive_solve(op.free_stiffness(e), res.factor, inactive, rhs)

    k = force_factor(bearing, op.mesh.half)
    fields = np.concatenate([P[None], dP.T])
    # Gumbel: P and its partials where the clipped film is positive, as fe_force integrates
    where = op.at_quadrature(P) > 0.0 if cavitation == "gumbel" else None
    F = k * op.force_integrals(fields, where=where)
    col = [tuple(float(x) for x in F[:, j]) for j in range(4)]
    d_gamma = (0.0, 0.0)
    if grooves:
        h = 1e-6
        plus, minus = (np.array(fe_force(bearing, replace(state, gamma=state.gamma + d), n_theta,
                                         n_z, element, cavitation, grooves=grooves)[0])
                       for d in (h, -h))
        d_gamma = tuple(float(v) for v in (plus - minus) / (2 * h))
    return ForceDerivatives(col[0], col[1], col[2], col[3], "exact-sensitivity", d_gamma)


def _inactive_solve(K: sp.csr_matrix, factor, inactive: np.ndarray, rhs: np.ndarray):
    """Solve K_II X_I = rhs_I (X = 0 elsewhere) with the factors of the film solve.

    ``factor`` is LU of K itself (full film), a :class:`PinnedFactor` of some cavitated set
    (the Reynolds solve's last factorisation: exact bordered solves correct the few dofs
    where its set differs from the final one), or None for films small enough to be solved
    densely, which are factorised here.
    """
    rhs = np.where(inactive[:, None], rhs, 0.0)
    if isinstance(factor, PinnedFactor):
        if np.array_equal(~factor.active, inactive):
            X = factor.solve(rhs)
        else:
            X = np.column_stack([bordered_solve(factor.lu, K, rhs[:, j], ~factor.active,
                                                inactive) for j in range(rhs.shape[1])])
    elif factor is not None and inactive.all():
        X = factor.solve(rhs)
    else:
        X = factorise(pinned(sp.csr_matrix(K), inactive)).solve(rhs)
    X[~inactive] = 0.0
    return X
