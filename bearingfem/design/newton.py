"""Newton's method for the journal position where the film force balances a load.

The unknown is the journal centre q = e / c = eps (cos gamma, sin gamma) (inertial), the
residual r(q) = (F(q) + W) / |W|. With F = R(gamma) F_loc(eps, gamma) and the partials
A = dF_loc/deps, G = dF_loc/dgamma (grooves fixed in the bearing), the Jacobian is

    dF/dq = R(gamma) [A, (J F_loc + G) / eps] R(gamma)^T,   J F_loc = (-F_t, F_r),

i.e. -c times the stiffness of :mod:`bearingfem.design.coefficients` at a steady state. A
backtracking line search on |r| (Armijo, halving) makes it global enough from a
closed-form start; steps are cut to stay inside eps_max.

A misaligned journal (its axis tilted) has its centre at q + z d(tilt) along the length:
``ends`` = d at z = L/2 keeps both ends, q + d and q - d, inside eps_max (the least film is
at an end), and the Jacobian comes straight from the tilted film's exact 4x4 stiffness.

The start (:func:`closed_form_start`) is the equilibrium of the finite bearing
approximated by combining the short- and long-bearing forces, 1/|F| = 1/|F_short| +
1/|F_long| (each closed form overestimates the finite film's load capacity in its own
limit; the harmonic combination follows the smaller one: Hirani, Athre & Biswas 1999,
J. Tribol. 121, 204-210), with the short bearing's attitude.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..bearing import Bearing, JournalState
from ..closed.long_bearing import long_bearing_force
from ..closed.short_bearing import short_bearing_force
from ..errors import ConvergenceError, LoadCapacityError
from ..film import local_to_inertial

__all__ = ["closed_form_start", "film_mesh", "newton_position", "polar_linearisation",
           "shrink_inside", "NEWTON_MAX_STEPS"]

#: Newton steps before giving up: converged films need 3-6 from the closed-form start
#: (benchmarks/design.py --grooved); more means a start outside the basin.
NEWTON_MAX_STEPS = 30
#: Largest closed-form eccentricity searched for the start (the closed forms reach the wall).
_START_EPS_MAX = 1.0 - 1e-6


def closed_form_start(bearing: Bearing, omega: float, load) -> np.ndarray:
    """q = e/c where the combined short/long-bearing film (module docstring) carries
    ``load`` (W_x, W_y) [N] at ``omega`` [rad/s]: a start, not an answer."""
    W = math.hypot(*load)

    def forces(eps):
        s = JournalState(eps, omega=omega)
        return np.array(short_bearing_force(bearing, s)), np.array(long_bearing_force(bearing, s))

    def carried(eps):
        fs, fl = forces(eps)
        return 1.0 / (1.0 / np.hypot(*fs) + 1.0 / np.hypot(*fl))

    eps = brentq(lambda e: carried(e) - W, 1e-12, _START_EPS_MAX, rtol=1e-6) \
        if carried(_START_EPS_MAX) > W else _START_EPS_MAX
    f_r, f_t = forces(eps)[0]
    gamma = math.atan2(-load[1], -load[0]) - math.atan2(f_t, f_r)
    return eps * np.array([math.cos(gamma), math.sin(gamma)])


def _jacobian(d, eps, gamma):
    """dF/dq [N] (inertial) from the local partials ``d`` (:class:`ForceDerivatives`)."""
    F, A, G = (np.asarray(v, float) for v in (d.force, d.d_eps, d.d_gamma))
    M = np.column_stack([A, (np.array([-F[1], F[0]]) + G) / eps])
    c, s = math.cos(gamma), math.sin(gamma)
    R = np.array([[c, -s], [s, c]])
    return R @ M @ R.T


def polar_linearisation(partials):
    """``film(q)`` -> (F, dF/dq) [N] (inertial) from ``partials(eps, gamma)`` ->
    :class:`ForceDerivatives` (local frame, d_gamma included)."""
    def film(q):
        eps, gamma = math.hypot(*q), math.atan2(q[1], q[0])
        d = partials(eps, gamma)
        return np.array(local_to_inertial(*d.force, gamma)), _jacobian(d, eps, gamma)
    return film


def newton_position(film, load, q0, eps_max, rtol, capacity, model, ends=(0.0, 0.0),
                    mesh=None):
    """(eps, gamma) where the film force balances ``load`` (W_x, W_y) [N].

    ``film(q)`` -> (F, dF/dq) [N], inertial, at the journal position q = e/c (e.g.
    :func:`polar_linearisation`); ``q0`` the start; the iteration stops once a Newton step
    is below sqrt(rtol) |q| (the step after it would be below rtol |q|: quadratic
    convergence) and takes that step. ``ends`` = d: the journal centres q + d and q - d (a
    tilted journal's ends) stay inside eps_max; (0, 0) for an aligned journal.
    ``capacity()`` -> what the film carries at eps_max [N], asked only on failure or when a
    step heads past eps_max: a load beyond it raises :class:`LoadCapacityError` (a
    ValueError naming ``mesh``, the film's mesh options, see :func:`film_mesh`), any other
    failure ConvergenceError.
    """
    W = math.hypot(*load)
    d_end = np.asarray(ends, float)
    q = np.asarray(q0, float)
    if _reach(q, d_end) >= eps_max:      # a closed-form start at the wall: come back inside
        q = shrink_inside(q, d_end, _reach(np.zeros(2), d_end) + 0.9 * (
            eps_max - _reach(np.zeros(2), d_end)))
    checked = []

    def evaluate(q):
        F, J = film(q)
        return (np.asarray(F, float) + load) / W, np.asarray(J, float) / W

    def check_capacity():
        if not checked:
            checked.append(capacity())
        if not checked[0] >= W:
            raise LoadCapacityError(W, checked[0], eps_max, model, mesh)

    def fail(why):
        check_capacity()
        raise ConvergenceError(f"Newton's equilibrium ({model} model)", steps[0],
                               float(np.linalg.norm(r)),
                               f"eps = {math.hypot(*q):.6g} ({why}; start it nearer: "
                               f"start=a nearby Equilibrium)")

    r, J = evaluate(q)
    step_tol = math.sqrt(rtol)
    steps = [0]
    for steps[0] in range(1, NEWTON_MAX_STEPS + 1):
        try:
            dq = -np.linalg.solve(J, r)
        except np.linalg.LinAlgError:
            fail("singular Jacobian")
        if not np.all(np.isfinite(dq)):
            fail("non-finite Newton step")
        t = min(_inside(q, dq, eps_max, s * d_end) for s in (1.0, -1.0))
        if t < 1.0:     # heading for the wall: does the film carry the load at all?
            check_capacity()
        if t == 1.0 and math.hypot(*dq) <= step_tol * math.hypot(*q):
            q = q + dq
            return math.hypot(*q), math.atan2(q[1], q[0])
        norm = np.linalg.norm(r)
        while True:     # backtrack: accept a step that decreases |r| (Armijo)
            r_new, J_new = evaluate(q + t * dq)
            if np.linalg.norm(r_new) <= (1.0 - 1e-4 * t) * norm:
                break
            t *= 0.5
            if t < 1.0 / 64:
                fail("the line search found no decrease of the force residual")
        q, r, J = q + t * dq, r_new, J_new
    fail(f"{NEWTON_MAX_STEPS} Newton steps")


def _reach(q, d_end) -> float:
    """The larger eccentricity ratio of the journal's ends q + d and q - d."""
    return max(math.hypot(*(q + d_end)), math.hypot(*(q - d_end)))


def film_mesh(opts) -> dict | None:
    """The mesh options of a film model's ``opts`` (n_theta, n_z, element: those it has),
    or None for a model without a mesh: what a :class:`LoadCapacityError` names."""
    mesh = {k: opts[k] for k in ("n_theta", "n_z", "element") if k in opts}
    return mesh or None


def shrink_inside(q, d_end, target) -> np.ndarray:
    """s q with s in (0, 1] largest such that both ends s q +- d reach at most ``target``
    (> |d|): |s q + d|^2 = target^2 solved for s, the nearer end's root."""
    q, d_end = np.asarray(q, float), np.asarray(d_end, float)
    a = q @ q
    roots = [1.0]
    for d in (d_end, -d_end):
        b, c = q @ d, d @ d - target ** 2
        roots.append((-b + math.sqrt(b * b - a * c)) / a)
    return min(roots) * q


def _inside(q, dq, eps_max, d=np.zeros(2)):
    """Step fraction in (0, 1] that keeps |q + d + t dq| at most half way to eps_max."""
    p = q + d
    if math.hypot(*(p + dq)) < eps_max:
        return 1.0
    target = 0.5 * (math.hypot(*p) + eps_max)
    a, b, c = dq @ dq, 2.0 * p @ dq, p @ p - target ** 2     # |p + t dq|^2 = target^2
    return float((-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a))
