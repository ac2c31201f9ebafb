"""Equations of motion of the slider-crank with a clearance joint (seed Eq. 1, re-derived).

Coordinates (q, A, X_PT). Lagrange's equations give

    M(q, A) [q'', A'']^T = Q(F) - s(q, A) [A'^2, q'^2]^T - g G(q, A)
    M_PT X_PT'' = -F_X - F_ext - g M_PT

with M = [[M_B R^2 + I_MO, m12], [m12, M_B (U^2 + V^2) + I_B]],
m12 = -M_B R (U cos(A + q) + V sin(A + q)), s = dm12/dA = dm12/dq
    = M_B R (U sin(A + q) - V cos(A + q)),
Q(F) = [F_Y R cos q - F_X R sin q + tau, -F_Y L cos A - F_X L sin A] for the joint force F
on the pin and a driving torque tau on the crank. The mass matrix, gravity and Q agree with
seed Eq. 1; its velocity term is printed with the opposite sign to s. The sympy
derivation in tests/test_dynamics.py and energy conservation settle it.
"""
from __future__ import annotations

import numpy as np

from .parameters import Mechanism

__all__ = ["pin_position", "pin_velocity", "accelerations", "energy"]


def pin_position(m: Mechanism, q, A):
    R, L = m.crank_length, m.rod_length
    return R * np.cos(q) + L * np.cos(A), R * np.sin(q) - L * np.sin(A)


def pin_velocity(m: Mechanism, q, A, qd, Ad):
    R, L = m.crank_length, m.rod_length
    return -R * np.sin(q) * qd - L * np.sin(A) * Ad, R * np.cos(q) * qd - L * np.cos(A) * Ad


def mass_terms(m: Mechanism, q, A):
    R = m.crank_length
    U, V = m.rod_cm
    MB = m.rod_mass
    m11 = MB * R * R + m.crank_inertia
    m22 = MB * (U * U + V * V) + m.rod_inertia
    m12 = -MB * R * (U * np.cos(A + q) + V * np.sin(A + q))
    s = MB * R * (U * np.sin(A + q) - V * np.cos(A + q))
    return m11, m12, m22, s


def gravity_terms(m: Mechanism, q, A, g):
    Um, Vm = m.crank_cm
    U, V = m.rod_cm
    gq = g * (m.crank_mass * (-Um * np.sin(q) - Vm * np.cos(q))
              - m.rod_mass * m.crank_length * np.sin(q))
    gA = g * m.rod_mass * (-U * np.sin(A) + V * np.cos(A))
    return gq, gA


def accelerations(m: Mechanism, q, A, qd, Ad, F_x, F_y, g=0.0, torque=0.0, slider_force=0.0):
    """(q'', A'', X_PT'') for joint force (F_x, F_y) on the pin [N].

    ``slider_force`` is F_ext of seed Eq. 1 (positive pushes the slider toward -X).
    """
    R, L = m.crank_length, m.rod_length
    m11, m12, m22, s = mass_terms(m, q, A)
    gq, gA = gravity_terms(m, q, A, g)
    Qq = F_y * R * np.cos(q) - F_x * R * np.sin(q) + torque - s * Ad * Ad - gq
    QA = -F_y * L * np.cos(A) - F_x * L * np.sin(A) - s * qd * qd - gA
    det = m11 * m22 - m12 * m12
    qdd = (m22 * Qq - m12 * QA) / det
    Add = (m11 * QA - m12 * Qq) / det
    Xdd = -(F_x + slider_force + g * m.slider_mass) / m.slider_mass
    return qdd, Add, Xdd


def energy(m: Mechanism, q, A, qd, Ad, Xd, X=0.0, g=0.0):
    """Kinetic plus gravitational energy [J] (X measured along the slider axis, up)."""
    m11, m12, m22, _ = mass_terms(m, q, A)
    T = 0.5 * (m11 * qd * qd + 2 * m12 * qd * Ad + m22 * Ad * Ad) + 0.5 * m.slider_mass * Xd * Xd
    Um, Vm = m.crank_cm
    U, V = m.rod_cm
    Xm = Um * np.cos(q) - Vm * np.sin(q)
    Xb = m.crank_length * np.cos(q) + U * np.cos(A) + V * np.sin(A)
    return T + g * (m.crank_mass * Xm + m.rod_mass * Xb + m.slider_mass * X)


def rod_from_eccentricity(m: Mechanism, q, qd, e_y, de_y):
    """Rod angle and speed from the crank and the eccentricity across the slider axis:
    e_y = R sin q - L sin A (the slider is guided on Y = 0)."""
    R, L = m.crank_length, m.rod_length
    A = np.arcsin((R * np.sin(q) - e_y) / L)
    Ad = (R * np.cos(q) * qd - de_y) / (L * np.cos(A))
    return A, Ad


def eccentricity_accelerations(m: Mechanism, q, A, qd, Ad, qdd, Add, Xdd):
    """(e_x'', e_y'') from the accelerations of (q, A, X_PT): e = pin - (X_PT, 0)."""
    R, L = m.crank_length, m.rod_length
    px_dd = -R * np.cos(q) * qd * qd - R * np.sin(q) * qdd - L * np.cos(A) * Ad * Ad \
        - L * np.sin(A) * Add
    py_dd = -R * np.sin(q) * qd * qd + R * np.cos(q) * qdd + L * np.sin(A) * Ad * Ad \
        - L * np.cos(A) * Add
    return px_dd - Xdd, py_dd
