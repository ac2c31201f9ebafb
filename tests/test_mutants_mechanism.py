"""The slider-crank's joint effects and command-free helpers (mechanism/): bugs planted one
at a time that the mechanism tests did not notice (docs/mutation.md)."""
import math

import numpy as np
import pytest

from mechanism.effects import CoulombFriction, HertzContact, JointKinematics

C = 20e-6
R = 0.01


def _contacts(n=200, seed=3):
    """Random kinematics in contact (e > c), every direction and sliding sense."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        e = C * (1.0 + rng.uniform(1e-4, 5e-3))
        a = rng.uniform(0, 2 * np.pi)
        yield JointKinematics(e * math.cos(a), e * math.sin(a), *rng.normal(0, 0.05, 2),
                              omega=rng.normal(0, 20.0))


def test_coulomb_friction_dissipates_and_is_bounded():
    """Energy: the friction force on the pin does no positive work against the sliding
    velocity of the pin surface over the bush at the contact point, v = e' + omega R t_hat
    (computed here from the kinematics), and its magnitude never exceeds mu_f F_n; it is
    tangential. Fails with the friction acting along the sliding velocity (effects.py,
    CoulombFriction.force: the sign of ft)."""
    contact = HertzContact(C, 1e10, v_impact=1.0)   # mild damping: F_n > 0
    friction = CoulombFriction(contact, 0.1, R, v_reg=1e-4)
    powers = []
    for k in _contacts():
        fx, fy = friction.force(k)
        rx, ry = k.e_x / k.e, k.e_y / k.e
        vx, vy = k.de_x - k.omega * R * ry, k.de_y + k.omega * R * rx
        powers.append(fx * vx + fy * vy)
        fn = contact.normal_force(k)
        assert math.hypot(fx, fy) <= 0.1 * fn * (1 + 1e-12)
        assert abs(fx * rx + fy * ry) <= 1e-12 * (1 + fn)
    powers = np.array(powers)
    assert np.all(powers <= 0.0) and np.mean(powers < 0) > 0.9
