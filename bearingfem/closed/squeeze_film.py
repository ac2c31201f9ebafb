"""Exact JFO solution of the oscillating squeeze film between parallel plates.

Two plates of length l (x in [0, l]) at a uniform gap h(t), oil at pressure p_a above the
cavitation pressure at both ends, no sliding. With k = 12 mu h'/h^3 the JFO film is, by
symmetry about x = l/2 (x_c: the end of the full film on the left half, the cavity
(x_c, l - x_c) in between):

* full film, k <= 8 p_a / l^2:  p = p_a + (k/2)(x^2 - l x);
* rupture (cavity growing): p = p' = 0 at x_c, so p = (k/2)(x - x_c)^2 and
  x_c = sqrt(2 p_a / k); the content phi h of each point freezes at h when it cavitates;
* reformation (cavity shrinking): p(x_c) = 0 with the JFO jump condition
  dx_c/dt (h - c(x_c)) = q(x_c), q = h^3 / (12 mu) (p_a / x_c - k x_c / 2),
  c the frozen content; the cavity collapses when x_c = l/2 and the pressure jumps back
  to the full film.

The rupture branch is algebraic, the reformation branch one ODE, integrated here to a
tolerance far below any mesh error (Ausas, Jai and Buscaglia 2009 used this problem; the
derivation above is ours and the tests check it against the full-film and rupture
formulas).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = ["SqueezeFilmExact", "oscillating_squeeze"]


@dataclass(frozen=True)
class SqueezeFilmExact:
    """Front x_c(t) [m] of the full film on the left half (l/2: no cavity) and the load per
    unit width W(t) [N/m] on a time grid, with the collapse times."""

    t: np.ndarray
    front: np.ndarray
    load: np.ndarray
    rupture_times: tuple
    collapse_times: tuple


def oscillating_squeeze(gap: Callable, gap_rate: Callable, t_end: float, *, length=1.0,
                        viscosity=1.0 / 12.0, ambient_pressure=0.025, n_t=4001,
                        rtol=1e-11) -> SqueezeFilmExact:
    """The exact film for gap h(t) (and h'(t)) on [0, t_end], starting full at t = 0."""
    l, mu, pa = float(length), float(viscosity), float(ambient_pressure)
    k = lambda t: 12.0 * mu * gap_rate(t) / gap(t) ** 3     # noqa: E731
    half = 0.5 * l
    tt = np.linspace(0.0, t_end, 200 * n_t)
    kk = k(tt)

    def rupture_front(t):
        return np.sqrt(2.0 * pa / np.maximum(k(t), 1e-300))

    ts, fronts = [], []
    ruptures, collapses = [], []
    t = 0.0
    state = "full"
    while t < t_end:
        if state == "full":
            # the cavity opens where the mid-plane pressure reaches zero: k = 8 p_a / l^2
            i = np.flatnonzero((tt > t) & (kk > 8.0 * pa / l ** 2))
            t_open = t_end if not len(i) else brentq(
                lambda s: k(s) - 8.0 * pa / l ** 2, tt[i[0] - 1], tt[i[0]], xtol=1e-14)
            ts.append(np.linspace(t, t_open, 50)), fronts.append(np.full(50, half))
            if t_open >= t_end:
                break
            ruptures.append(t_open)
            t, state = t_open, "rupture"
        else:
            # rupture while k grows; its front sets the frozen content c(x) = h(t_x)
            i = np.flatnonzero((tt > t) & (np.gradient(kk, tt) <= 0.0))
            t_turn = t_end if not len(i) else brentq(
                lambda s: (k(s + 1e-9) - k(s - 1e-9)), tt[i[0] - 1], tt[i[0]], xtol=1e-14)
            tr = np.linspace(t, t_turn, 20001)
            xr = rupture_front(tr)
            xr[0] = half
            ts.append(tr[::50]), fronts.append(xr[::50])
            if t_turn >= t_end:
                break
            # frozen content c(x) = h(t_x) on [x_c(t_turn), l/2]: the rupture branch is
            # monotone, so it is tabulated against x (dense where it turns)
            xs, cs = xr[::-1], gap(tr)[::-1]

            def rate(s, y, xs=xs, cs=cs):
                x = min(max(y[0], xs[0]), half)
                c = np.interp(x, xs, cs)
                q = gap(s) ** 3 / (12.0 * mu) * (pa / x - 0.5 * k(s) * x)
                return [max(q, 0.0) / max(gap(s) - c, 1e-300)]

            def closed(s, y):
                return y[0] - half
            closed.terminal, closed.direction = True, 1
            t0 = t_turn + 1e-9 * max(t_end, 1.0)
            sol = solve_ivp(rate, (t0, t_end), [xr[-1]], events=closed, rtol=rtol,
                            atol=1e-14 * l, dense_output=True, method="LSODA")
            t_c = float(sol.t[-1])
            tc = np.linspace(t0, t_c, 2000)
            ts.append(tc), fronts.append(np.minimum(sol.sol(tc)[0], half))
            if sol.status != 1:
                break
            collapses.append(t_c)
            t, state = t_c, "full"
    t_all = np.concatenate(ts)
    x_all = np.concatenate(fronts)
    o = np.argsort(t_all, kind="stable")
    t_all, x_all = t_all[o], x_all[o]
    kt = k(t_all)
    # full film: p_a l - k l^3 / 12; with a cavity p(x_c) = 0 on both branches, so
    # W = 2 (p_a x_c / 2 - k x_c^3 / 12)
    load = np.where(x_all >= half, pa * l - kt * l ** 3 / 12.0,
                    pa * x_all - kt * x_all ** 3 / 6.0)
    return SqueezeFilmExact(t_all, x_all, load, tuple(ruptures), tuple(collapses))
