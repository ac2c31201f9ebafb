"""The ideal (no-clearance) slider-crank: one degree of freedom, the reference mechanism.

The pin stays on the slider axis, R sin q = L sin A, so A(q) and X_PT(q) follow from q.
Projecting the three-coordinate equations on the constraint (J = d(q, A, X)/dq):
(J^T M J) q'' = J^T (Q - M J' q'^2) with the terms of :mod:`mechanism.dynamics`.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from .dynamics import gravity_terms, mass_terms
from .parameters import Mechanism

__all__ = ["rigid_kinematics", "rigid_rhs", "integrate_rigid", "simulate_rigid"]


def rigid_kinematics(m: Mechanism, q):
    """A, dA/dq, d2A/dq2, X, dX/dq, d2X/dq2 of the ideal mechanism."""
    R, L = m.crank_length, m.rod_length
    lam = R / L
    sA = lam * np.sin(q)
    A = np.arcsin(sA)
    cA = np.cos(A)
    A1 = lam * np.cos(q) / cA
    A2 = (-lam * np.sin(q) * cA + lam * np.cos(q) * sA * A1) / (cA * cA)
    X = R * np.cos(q) + L * cA
    X1 = -R * np.sin(q) - L * sA * A1
    X2 = -R * np.cos(q) - L * cA * A1 * A1 - L * sA * A2
    return A, A1, A2, X, X1, X2


def rigid_rhs(m: Mechanism, g=0.0, torque=0.0, slider_force=0.0):
    def rhs(t, y):
        q, qd = y
        A, A1, A2, X, X1, X2 = rigid_kinematics(m, q)
        m11, m12, m22, s = mass_terms(m, q, A)
        gq, gA = gravity_terms(m, q, A, g)
        Ad = A1 * qd
        meff = m11 + 2 * m12 * A1 + m22 * A1 * A1 + m.slider_mass * X1 * X1
        # generalized forces minus velocity terms, for each coordinate
        fq = torque - s * Ad * Ad - gq - m12 * A2 * qd * qd
        fA = -s * qd * qd - gA - m22 * A2 * qd * qd
        fX = -slider_force - g * m.slider_mass - m.slider_mass * X2 * qd * qd
        return [qd, (fq + A1 * fA + X1 * fX) / meff]
    return rhs


def integrate_rigid(m: Mechanism, crank_angle: float, crank_speed: float, turns: float,
                    g=0.0, torque=0.0, slider_force=0.0, method="DOP853", rtol=1e-10,
                    atol=1e-10):
    """solve_ivp's dense solution of the ideal mechanism from (crank_angle, crank_speed)
    until the crank has turned ``turns`` times (a terminal event, whatever the speed)."""
    q_end = crank_angle + 2 * np.pi * turns
    ev = lambda t, y: y[0] - q_end
    ev.terminal, ev.direction = True, 1
    # the event ends the run; the span only bounds it (6x the time at the initial speed)
    t_max = 6.0 * 2 * np.pi * turns / crank_speed
    return solve_ivp(rigid_rhs(m, g, torque, slider_force), (0.0, t_max),
                     [crank_angle, crank_speed], method=method, rtol=rtol, atol=atol,
                     dense_output=True, events=ev)


def simulate_rigid(m: Mechanism, crank_speed=250.0, turns=5.0, g=0.0, rtol=1e-10,
                   atol=1e-10, samples_per_turn=720):
    """Integrate the ideal mechanism from top dead centre (q = 0) for ``turns`` turns."""
    sol = integrate_rigid(m, 0.0, crank_speed, turns, g, rtol=rtol, atol=atol)
    t = np.linspace(0.0, sol.t[-1], int(samples_per_turn * turns) + 1)
    q, qd = sol.sol(t)
    return t, q, qd
