"""The ideal joint: the rigid slider-crank through the same interface as a clearance run."""
from __future__ import annotations

import time

import numpy as np

from .dynamics import gravity_terms, mass_terms
from .joint import METHODS
from .parameters import GRAVITY
from .result import SimulationResult, provenance
from .rigid import integrate_rigid, rigid_kinematics, rigid_rhs
from .sampling import output_times
from .scene import Scene

__all__ = ["simulate_ideal"]


def simulate_ideal(scene: Scene, progress=None) -> SimulationResult:
    """The rigid mechanism through the same interface (e = 0; force = joint reaction)."""
    m = scene.mechanism
    g = GRAVITY if scene.gravity else 0.0
    run = scene.run
    f = rigid_rhs(m, g, scene.crank_torque, scene.slider_force)
    start = time.perf_counter()
    sol = integrate_rigid(m, scene.crank_angle, scene.crank_speed, run.turns, g,
                          scene.crank_torque, scene.slider_force, METHODS[run.integrator],
                          rtol=min(run.rtol, 1e-8), atol=1e-10)
    wall = time.perf_counter() - start
    t = output_times(scene, lambda tt: sol.sol(tt)[0], 0.0, sol.t[-1])
    q, qd = sol.sol(t)
    qdd = np.array([f(0, [a, b])[1] for a, b in zip(q, qd)])
    A, A1, A2, X, X1, X2 = rigid_kinematics(m, q)
    Add = A1 * qdd + A2 * qd * qd
    Xdd = X1 * qdd + X2 * qd * qd
    # Joint reaction on the pin: F_x from the slider's equation, F_y from the rod's.
    Fx = -(m.slider_mass * Xdd + scene.slider_force + g * m.slider_mass)
    m11, m12, m22, s = mass_terms(m, q, A)
    _, gA = gravity_terms(m, q, A, g)
    L = m.rod_length
    Fy = -(m12 * qdd + m22 * Add + s * qd * qd + gA + Fx * L * np.sin(A)) / (L * np.cos(A))
    z = np.zeros_like(t)
    stats = {"wall_time": wall, "steps": len(sol.t) - 1, "rhs_evals": int(sol.nfev),
             "film_solves": 0, "contact_evals": 0, "integrator": run.integrator,
             "effects": []}
    return SimulationResult(t=t, crank_angle=q, crank_speed=qd, rod_angle=A, slider_position=X,
                            slider_acceleration=Xdd, eps=z, e_x=z, e_y=z, film_min=z + 0.0,
                            force_x=Fx, force_y=Fy, scene=scene.name, stats=stats,
                            provenance=provenance(scene))
