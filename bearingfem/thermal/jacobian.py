"""The energy equation's residual and its exact derivatives with respect to the film's
nodal pressure and temperature: the energy block of a coupled (pressure, temperature)
Newton (:mod:`bearingfem.routes.thd_newton`).

The residual is the one :func:`~bearingfem.thermal.energy.solve_energy` solves for (its
matrix and load from :func:`~bearingfem.thermal.operator.energy_system`, so a term added
there flows through), on every row; held rows are the caller's. Per quadrature point,
with the test function's weight w_i = (R v_i + tau beta . grad v_i) dx,

    r_i = sum_q w_i e + k h grad T . grad v_i dx,   e = beta . grad T + R s T - R f - R H_j T_j,

where beta = rho cp q depends on grad p and mu, f = Phi + H_b T_a on grad p and mu, tau
on beta (SUPG), and mu = mu(p, T). Its change for a change of grad P (theta and zeta
components) or of mu at a point is

    delta r_i = sum_q [(delta tau beta . grad v_i + tau delta beta . grad v_i) e
                       + (R v_i + tau beta . grad v_i)(delta beta . grad T - R delta Phi)] dx,

each assembled on the operator's tables (:class:`~bearingfem.thermal.operator.EnergyOperator`)
against the trial basis (gradients for grad P, values times d mu/dp or d mu/dT for mu).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..film import film_thickness
from .operator import EnergyFlow, EnergyOperator, energy_system

__all__ = ["EnergyLinearisation", "energy_linearisation", "supg_tau_derivatives"]


@dataclass(frozen=True, eq=False)
class EnergyLinearisation:
    """The energy equation at nodal (P, T, T_j): ``residual`` (N,) [as assembled, per
    d(theta) d(zeta)], its derivatives with respect to nodal T (``d_temperature``) and to
    the dimensionless nodal P (``d_pressure``) as values on the operator's pattern
    (:meth:`~bearingfem.thermal.operator.EnergyOperator.matrix`'s), ``d_journal`` (N,)
    with respect to the journal's temperature; ``flow``, ``A``, ``b``, ``c_all``: the
    assembled system (for the energy balance)."""

    op: EnergyOperator
    residual: np.ndarray
    d_temperature: np.ndarray
    d_pressure: np.ndarray
    d_journal: np.ndarray
    flow: EnergyFlow
    A: sp.csr_matrix
    b: np.ndarray
    c_all: np.ndarray

    def matrix(self, data: np.ndarray) -> sp.csr_matrix:
        """The (N, N) matrix of pattern values ``data`` (e.g. ``d_pressure``)."""
        op = self.op
        return sp.csr_matrix((data, op.indices, op.indptr), shape=(op.N, op.N))


def supg_tau_derivatives(op: EnergyOperator, flow: EnergyFlow, R: float):
    """(tau, d tau/d beta_theta, d tau/d beta_zeta) at the quadrature points: tau of
    :func:`~bearingfem.thermal.operator._supg_tau`, written as tau = a xi(Pe) / (2 |beta|^2)
    with a = R (|beta_theta| dtheta_e + |beta_zeta| dzeta_e) = h_e |beta| and
    Pe = a / (2 k h)."""
    bt, bz, D = flow.beta_theta, flow.beta_zeta, flow.diffusivity
    s2 = bt ** 2 + bz ** 2
    moving = s2 > 0.0
    s2 = np.where(moving, s2, 1.0)
    a = R * (np.abs(bt) * op.cell[0] + np.abs(bz) * op.cell[1])
    pe = a / (2.0 * D)
    big = np.maximum(pe, 1e-3)
    xi = np.where(pe > 1e-3, 1.0 / np.tanh(big) - 1.0 / big, pe / 3.0)
    # xi' = 1/Pe^2 - 1/sinh^2 Pe; its series below 0.05 (no cancellation)
    e2 = np.exp(-2.0 * np.maximum(pe, 0.05))
    dxi = np.where(pe > 0.05, 1.0 / np.maximum(pe, 0.05) ** 2 - 4.0 * e2 / (1.0 - e2) ** 2,
                   1.0 / 3.0 - pe ** 2 / 15.0 + 2.0 * pe ** 4 / 189.0)
    dxi = np.where(pe > 1e-3, dxi, 1.0 / 3.0)
    tau = np.where(moving, a * xi / (2.0 * s2), 0.0)
    da_coeff = (xi + a * dxi / (2.0 * D)) / (2.0 * s2)
    tau_t = np.where(moving, da_coeff * R * op.cell[0] * np.sign(bt) - a * xi * bt / s2 ** 2,
                     0.0)
    tau_z = np.where(moving, da_coeff * R * op.cell[1] * np.sign(bz) - a * xi * bz / s2 ** 2,
                     0.0)
    return tau, tau_t, tau_z


def energy_linearisation(bearing, state, op: EnergyOperator, P, fraction, T,
                         t_journal: float, lubricant, walls) -> EnergyLinearisation:
    """The energy equation's residual and derivatives (module docstring) at the
    dimensionless nodal pressure ``P`` (p = P x ``bearing.pressure_scale``), nodal
    ``fraction`` (held, 1 in a Reynolds-condition film), nodal temperature ``T`` [K] and
    the journal's temperature ``t_journal`` [K]; ``walls`` as
    :func:`~bearingfem.thermal.energy.solve_energy`'s; ``op`` on the bearing-fixed mesh."""
    R, ps = bearing.radius, bearing.pressure_scale
    sc = ps / R
    hb, ta, hj, _ = walls
    p_q, T_q = op.at_points(P) * ps, op.at_points(T)
    mu, mu_p, mu_T = lubricant.viscosity_and_slopes(p_q, T_q)
    flow = op.flow(bearing, state, P, fraction, mu, lubricant)
    s, f = hb + hj, flow.dissipation + hb * ta
    A, b, test = energy_system(op, flow, s, f, R)
    c_all = -op.vector(np.sum(test, axis=2) * R * hj) if hj > 0.0 else np.zeros(op.N)
    residual = A @ T + c_all * t_journal - b

    h = bearing.clearance * film_thickness(op.theta - state.gamma, state.eps)
    U = state.omega * R
    k3 = h ** 3 / (12.0 * mu)
    rho_cp = lubricant.mass_density * lubricant.specific_heat
    gT, gP = op.gradient(T), op.gradient(P)
    dpx, dpz = sc * gP[0], sc * gP[1]
    bt, bz = flow.beta_theta, flow.beta_zeta
    e = bt * gT[0] + bz * gT[1] + R * s * T_q - R * f - R * hj * t_journal
    tau, tau_t, tau_z = supg_tau_derivatives(op, flow, R)
    g = op.grad
    bu = bt * g[:, 0] + bz * g[:, 1]                       # (nb, E, Q)
    weight = R * op.phi + tau * bu
    if op.affine_p1:        # the gradients are the element's at every point
        g0, g1 = g[:, 0, :, :1], g[:, 1, :, :1]
    else:
        g0, g1 = g[:, 0], g[:, 1]

    def row_weights(dbt, dbz, dphi):
        """(nb, E, Q) d r_i per unit change of a point variable moving beta, Phi."""
        dtau = tau_t * dbt + tau_z * dbz
        return op.dx * ((dtau * bu + tau * (dbt * g0 + dbz * g1)) * e
                        + weight * (dbt * gT[0] + dbz * gT[1] - R * dphi))

    x_t = row_weights(-rho_cp * k3 * sc, 0.0, 2.0 * k3 * sc * dpx)
    x_z = row_weights(0.0, -rho_cp * k3 * sc, 2.0 * k3 * sc * dpz)
    F = op.at_points(fraction)
    x_mu = row_weights(rho_cp * k3 / mu * dpx, rho_cp * k3 / mu * dpz,
                       F * U ** 2 / h - k3 / mu * (dpx ** 2 + dpz ** 2))
    if op.affine_p1:        # sum the points first
        local_p = (np.einsum("ie,je->ije", x_t.sum(axis=2), g0[..., 0])
                   + np.einsum("ie,je->ije", x_z.sum(axis=2), g1[..., 0]))
    else:
        local_p = np.einsum("ieq,jeq->ije", x_t, g0) + np.einsum("ieq,jeq->ije", x_z, g1)
    if np.any(mu_p):
        local_p = local_p + np.einsum("ieq,jeq->ije", x_mu * (mu_p * ps), op.phi)
    local_t = np.einsum("ieq,jeq->ije", x_mu * mu_T, op.phi)
    n = len(op.indices)
    return EnergyLinearisation(
        op=op, residual=residual,
        d_temperature=A.data + np.bincount(op.positions, local_t.ravel(), minlength=n),
        d_pressure=np.bincount(op.positions, local_p.ravel(), minlength=n),
        d_journal=c_all, flow=flow, A=A, b=b, c_all=c_all)
