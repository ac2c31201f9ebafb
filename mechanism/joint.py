"""The joint's coordinates from the integrated state, and the force its effects make."""
from __future__ import annotations

from .dynamics import pin_position, pin_velocity, rod_from_eccentricity
from .effects import JointKinematics

__all__ = ["METHODS", "coordinates", "joint_kinematics", "joint_force"]

#: Integrators by their scene names (scipy's method names).
METHODS = {"lsoda": "LSODA", "bdf": "BDF", "radau": "Radau", "rk45": "RK45", "dop853": "DOP853"}


def coordinates(m, y):
    """(q, A, X_PT, q', A', X_PT') of the state y = (q, e_x, e_y, q', e_x', e_y')."""
    q, ex, ey, qd, exd, eyd = y
    A, Ad = rod_from_eccentricity(m, q, qd, ey, eyd)
    px, _ = pin_position(m, q, A)
    vx, _ = pin_velocity(m, q, A, qd, Ad)
    return q, A, px - ex, qd, Ad, vx - exd


def joint_kinematics(m, y) -> JointKinematics:
    """The joint's kinematics at the state y (time left at 0: sampling needs none)."""
    q, ex, ey, qd, exd, eyd = y
    _, Ad = rod_from_eccentricity(m, q, qd, ey, eyd)
    return JointKinematics(ex, ey, exd, eyd, -Ad)


def joint_force(effects, k):
    """The sum of the effects' forces on the pin (F_x, F_y) [N] at kinematics ``k``."""
    fx = fy = 0.0
    for eff in effects:
        a, b = eff.force(k)
        fx += a
        fy += b
    return fx, fy
