"""Partial derivatives of a film force with respect to the state: (eps, eps_dot, w).

* :func:`complex_step` - for closed forms written with complex-safe arithmetic:
  f'(x) = Im f(x + i h) / h has no subtractive cancellation, so it is exact to round-off
  for any tiny h (Squire & Trapp, SIAM Review 40, 1998; Martins et al., ACM TOMS 29, 2003).
* :func:`central_differences` - for any model (second order in the step), the reference
  that every exact derivative is tested against.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .bearing import JournalState
from .solution import ForceDerivatives

__all__ = ["complex_step", "central_differences", "state_steps"]

_H = 1e-30   # complex step: any h far below sqrt(machine eps) times the scale is exact


def complex_step(kernel, eps: float, eps_dot: float, wedge: float) -> ForceDerivatives:
    """Force and partials of ``kernel(eps, eps_dot, wedge) -> (F_r, F_t)`` (complex-safe)."""
    args = np.array([eps, eps_dot, wedge], dtype=complex)
    force = tuple(float(np.real(f)) for f in kernel(*args))
    parts = []
    for k in range(3):
        a = args.copy()
        a[k] += 1j * _H
        parts.append(tuple(float(np.imag(f)) / _H for f in kernel(*a)))
    return ForceDerivatives(force, parts[0], parts[1], parts[2], "analytic")


def state_steps(state: JournalState, eps_max: float = 0.999, rel: float = 1e-6):
    """Central-difference steps (h_eps, h_eps_dot, h_wedge) scaled to the state.

    A relative step of 1e-6 leaves a truncation error ~1e-12 and a round-off error
    ~1e-10 relative; it is also small enough that a cavitated set or a Gumbel clip rarely
    changes inside the step (a change there makes differences wrong by up to 1e-3 at
    1e-4). h_eps keeps eps +- h_eps inside (0, eps_max).
    """
    if not 0.0 < state.eps < eps_max:
        raise ValueError(f"eps must lie in (0, {eps_max}) to be differenced, got {state.eps!r}")
    speed = max(abs(state.wedge_speed), abs(state.eps_dot), abs(state.omega), 1.0)
    h_eps = rel * min(state.eps, eps_max - state.eps)
    return h_eps, rel * speed, rel * speed


def central_differences(force, state: JournalState) -> ForceDerivatives:
    """Partials of ``force(state) -> (F_r, F_t)`` by central differences in eps, eps_dot
    and the wedge speed (changed through gamma_dot, omega fixed)."""
    h_eps, h_ed, h_w = state_steps(state)
    f0 = tuple(float(f) for f in force(state))

    def diff(**delta):
        plus = {k: getattr(state, k) + v for k, v in delta.items()}
        minus = {k: getattr(state, k) - v for k, v in delta.items()}
        fp = np.asarray(force(replace(state, **plus)), float)
        fm = np.asarray(force(replace(state, **minus)), float)
        h = 2.0 * next(iter(delta.values()))
        return tuple((fp - fm) / h)

    d_eps = diff(eps=h_eps)
    d_ed = diff(eps_dot=h_ed)
    # w = omega - 2 gamma_dot, so dF/dw = -dF/d(gamma_dot) / 2
    d_w = tuple(-0.5 * np.asarray(diff(gamma_dot=0.5 * h_w)))
    d_g = diff(gamma=1e-6)    # nonzero only for films with something fixed in space
    return ForceDerivatives(f0, d_eps, d_ed, d_w, "central-differences", d_g)

