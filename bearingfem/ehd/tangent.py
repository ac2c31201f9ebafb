"""The kept EHD film moved along its tangent in the journal's state.

:class:`~bearingfem.ehd.transient.TransientEHD` holds the bush's deflection w_n of its last
film step fixed between film steps: an explicit coupling whose lag moves the gap, beyond
the rigid clearance circle, by about as much as the gap itself. Here the kept film also
carries its tangent in the state s = (x, y, x', y', omega), x + i y = eps e^{i gamma} the
journal centre over the clearance in the bush's frame:

* the deflection moves by dw = (dw/ds)(s - s_n). Where dw closes the held film's gap
  g = h_rigid(s) + w_n (h_rigid = 1 - x cos(alpha) - y sin(alpha) on the bush's grid) the
  step is taken in log h, h = g exp(dw / g): the same first derivative, and the gap stays
  open where a linear step closes the thin film at the bush's free ends; where dw opens it
  linearly (C1 across dw = 0; the rigid gap's own change stays exact);
* the pressure that sets the viscosity and density moves to p_n + (dp/ds)(s - s_n),
  clipped at 0 (the Swift-Stieber film's own bound).

The tangent is taken by forward differences: five full EHD solves at states one
``TANGENT_STEP`` from s_n, each warm from the film step's solution (a few Newton steps
each), read back on the film step's grid. The force at a trial state stays continuous in
the state and changes nothing kept (contract rules 10-14). A film step also comes early,
at an accepted state where the tangent moves the gap by more than ``GAP_FIT`` of the kept
gap somewhere (beyond the tangent's reach).

Measured (tests/test_ehd_step.py, seed pin at eps 1.03, 48 x 4, 16 modes): the kept
force's error from the full EHD film along a path falls from 68e3 N to 0.9e3 N per unit
change of s (a 75x smaller constant); it stays first order, as the forward-difference
tangent and the film's active set (Swift-Stieber) leave a ~1 % error in the slope.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..bearing import ElasticJournalState, JournalState
from ..solution import FilmSolution
from .transient import KeptFilm, TransientEHD, ehd_solution, state_coordinates

__all__ = ["TangentEHD", "with_tangent", "state_from_coordinates", "GAP_FIT",
           "TANGENT_STEP"]

#: A film step comes early (before ``film_step``) at an accepted state where the kept
#: tangent moves the gap by more than this fraction of the kept gap somewhere.
GAP_FIT = 0.2

#: Forward-difference steps of the tangent in s = (x, y, x', y', omega), as fractions of
#: (1, 1, v, v, v), v = max(|omega|, |x'|, |y'|, 1): the film's Newton converges to 1e-10
#: relative, so 1e-6 leaves truncation and round-off both near 1e-5 relative.
TANGENT_STEP = 1e-6


def state_from_coordinates(s: np.ndarray) -> JournalState:
    """The inverse of :func:`~bearingfem.ehd.transient.state_coordinates` (an elastic
    state: eps may pass 1; eps > 0)."""
    x, y, xd, yd, omega = (float(v) for v in s)
    eps = float(np.hypot(x, y))
    return ElasticJournalState(eps=eps, eps_dot=(x * xd + y * yd) / eps,
                               gamma=float(np.arctan2(y, x)),
                               gamma_dot=(x * yd - y * xd) / eps ** 2, omega=omega)


def with_tangent(kept: KeptFilm, state: JournalState, solve, keep) -> KeptFilm:
    """``kept`` (the film of ``state``) with its tangent in s by forward differences:
    ``solve(state)`` the full EHD film (warm), ``keep(state, sol)`` its :class:`KeptFilm`.
    A state at the centre (eps < 1e-6, no frame for the rates) keeps no tangent."""
    if state.eps < 1e-6:
        return kept
    s0 = state_coordinates(state)
    step = np.full(5, TANGENT_STEP)
    step[2:] *= max(abs(state.omega), abs(s0[2]), abs(s0[3]), 1.0)
    n, m = kept.deflection.shape
    alpha = kept.alpha0 + 2 * np.pi * np.arange(n)[:, None] / n + np.zeros((1, m))
    zeta = (-kept.half_width + 2 * kept.half_width * np.arange(m)[None, :] / (m - 1)
            + np.zeros((n, 1)))
    dw, dp = np.empty((5, n, m)), np.empty((5, n, m))
    for k in range(5):
        s1 = s0.copy()
        s1[k] += step[k]
        moved = state_from_coordinates(s1)
        other = keep(moved, solve(moved))
        # read on the film step's grid (the moved state's grid is turned by d gamma)
        dw[k] = (other.at(other.deflection, alpha, zeta) - kept.deflection) / step[k]
        dp[k] = (other.at(other.pressure, alpha, zeta) - kept.pressure) / step[k]
    return replace(kept, origin=s0, deflection_slope=dw, pressure_slope=dp)


class TangentEHD(TransientEHD):
    """:class:`~bearingfem.ehd.transient.TransientEHD` with the kept film moved along its
    tangent at a trial state and film steps that come early where it no longer fits (the
    module docstring); the same parameters."""

    def _keep_at(self, state: JournalState, sol: FilmSolution) -> KeptFilm:
        kept = self._keep(state, sol)
        if self._film["bush"] is None and self._film["lubricant"] is None:
            return kept                            # the rigid film: nothing is kept
        solve = lambda s: ehd_solution(self.bearing, s, start=sol, **self._film)  # noqa: E731
        return with_tangent(kept, state, solve, self._keep)

    def _fits(self, state: JournalState) -> bool:
        return self.gap_change(state) <= GAP_FIT

    def gap_change(self, state: JournalState) -> float:
        """The largest change of the gap over the kept gap, |dh| / h_n, on the film grid
        from the last film step to ``state``, along the kept tangent (the rigid gap's
        change only without one): how far ``state`` is from where the kept film holds."""
        k = self._kept
        n = k.deflection.shape[0]
        alpha = (k.alpha0 + 2 * np.pi * np.arange(n) / n)[:, None]
        ds = state_coordinates(state) - self._origin
        dh = -np.cos(alpha) * ds[0] - np.sin(alpha) * ds[1]
        if k.origin is not None:
            dh = dh + np.tensordot(ds, k.deflection_slope, axes=1)
        h0 = (1.0 - np.cos(alpha) * self._origin[0] - np.sin(alpha) * self._origin[1]
              + k.deflection + k.profile_gap)
        return float(np.max(np.abs(dh) / h0))


