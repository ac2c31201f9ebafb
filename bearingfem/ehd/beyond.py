"""The EHD film beyond the rigid clearance circle (eps >= 1): where its Newton starts.

At eps >= 1 the rigid gap 1 + eps cos(theta) is negative on an arc around theta = pi and
only the bush's deflection opens it (H = 1 + eps cos(theta) + w/c > 0), as in an EHL
contact. The load continuation of :mod:`bearingfem.ehd.newton` starts from the rigid film
(coupling s = 0), which does not exist there. This module starts instead from the EHD
film at ``START_EPS`` < 1 (reached by that load continuation) and continues in eps at full
coupling: each step moves the rigid gap by d eps cos(theta) and solves Newton from the
previous pressure, whose deflection keeps the moved gap open for a small enough step. A
step that stalls or closes the gap is retried with a quarter of the increment, a
converged one doubles it (up to ``MAX_INCREMENT``); below ``MIN_INCREMENT`` the solve
raises :class:`~bearingfem.errors.ConvergenceError`.

The elastic gap can open only where the bush deflects under the film's pressure. A bush
whose deflection vanishes where the rigid gap is closed, whatever the pressure (the
plane-strain ring, :mod:`bearingfem.elastic.ring`, at the film's ends: its slices are
independent and the end slices carry the ambient pressure), cannot carry the journal
beyond the circle: :func:`check_opens` refuses it by name before any work.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .newton import EHDResult, _newton, continuation, solve_ehd

__all__ = ["solve_beyond", "check_opens", "START_EPS"]

#: Where the continuation in eps starts: an EHD film with a rigid gap still open.
START_EPS = 0.95
MAX_INCREMENT = 0.02
MIN_INCREMENT = 1e-5


def at_eps(film, eps: float):
    """The EHD film ``film`` with its rigid gap moved to eccentricity ratio ``eps`` (the
    same mesh, rates, lubricant and bush)."""
    d = eps - film.eps
    base = replace(film.base, gap=film.base.gap + d * np.cos(film.op.qp_theta))
    return replace(film, base=base, gap0=film.gap0 + d * np.cos(film.op.mesh.theta), eps=eps)


def check_opens(film) -> None:
    """ValueError when the bush cannot open the rigid gap where it is closed: its
    deflection under a unit pressure on every free dof is zero at a closed node."""
    if film.compliance is None:
        raise ValueError(f"eps must lie in [0, 1) for a film without a bush, got {film.eps!r}")
    closed = film.gap0 <= 0.0
    unit = np.zeros(film.gap0.size)
    unit[film.op.mesh.free] = 1.0
    w = film.compliance.apply(unit)
    stuck = closed & (np.abs(w) <= 1e-12 * np.max(np.abs(w)))
    if stuck.any():
        raise ValueError(
            f"eps {film.eps!r} >= 1 closes the rigid gap where the bush cannot deflect "
            f"({int(stuck.sum())} film nodes, e.g. the ends of a 'ring' bush, whose slices "
            "are independent): use ElasticBush(model='solid') beyond the clearance circle")


def solve_beyond(film, rigid, cavitation: str, tol: float,
                 start: np.ndarray | None = None) -> EHDResult:
    """The EHD pressure of ``film`` at eps >= 1 (see the module docstring). ``rigid(film)``
    gives the rigid film's pressure of a film with an open gap (the load continuation's
    s = 0); ``start``: a warm start (nodal P), tried first at full coupling."""
    check_opens(film)
    free = film.op.mesh.free
    if start is not None:
        out, its = _newton(film, np.array(start, float), 1.0, free, cavitation, tol)
        if out is not None:
            return EHDResult(out[0], its, out[1], True, out[2], 1, 0)
    first = at_eps(film, START_EPS)
    res = solve_ehd(first, lambda: rigid(first), cavitation, tol)
    walk = continuation(lambda eps, P: _newton(at_eps(film, eps), P, 1.0, free, cavitation, tol),
                        res.pressure, START_EPS, film.eps, MAX_INCREMENT, MIN_INCREMENT,
                        "EHD Newton (continuation in eps)", "eps",
                        "the bush does not open the gap further (refine the mesh or stiffen "
                        "the bush)")
    return replace(walk, iterations=res.iterations + walk.iterations,
                   steps=res.steps + walk.steps, rejected=res.rejected + walk.rejected)
