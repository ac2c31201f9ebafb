"""The mesh fitted to the cavitation boundary (studies/kc_fitted.py, steps 2-4): the
boundary located on each row of nodes where sqrt(p) vanishes (:meth:`Fit.locate`), a
column of vertices per boundary chosen (:meth:`Fit.choose`) and moved onto it row by row
(:meth:`Fit.operator`), the held set beyond it (:meth:`Fit.held`) and the column's next
place at the vertex of the pressure's quadratic (:meth:`Fit.relocate`).
"""
from __future__ import annotations

import math

import numpy as np
from skfem import Basis, MeshTri1

from bearingfem.fe.grooved import GroovedOperator
from bearingfem.fe.grooved_build import build_grooved_tables
from bearingfem.fe.mesh import ELEMENTS, FilmMesh, quiet_skfem


def _pads(m) -> list:
    """The pads' (start, end) in the mesh angle (between consecutive grooves)."""
    t0 = m.theta.min()
    turn = 2.0 * math.pi
    arcs = sorted((t0 + np.mod(lo - t0, turn), t0 + np.mod(lo - t0, turn) + np.mod(hi - lo, turn))
                  for lo, hi in m.arcs)
    ends = [hi for _, hi in arcs]
    starts = [lo for lo, _ in arcs[1:]] + [t0 + turn]
    return list(zip(ends, starts))


def _rows(m):
    """(vertex rows' zeta, for each row the dofs on it; :class:`Fit` sorts them by the
    base mesh's theta)."""
    _, ze = m.axes
    out = []
    for z in ze:
        on = np.flatnonzero(np.abs(m.zeta - z) < 1e-9)
        out.append(on)
    return ze, out


class Fit:
    """A base grooved operator and what a fitted mesh of it needs: its logical dof angles
    (the base mesh's), rows, pads and vertex columns."""

    def __init__(self, gop: GroovedOperator, element: str):
        self.base = gop
        self.element = element
        m = gop.op.mesh
        self.m = m
        self.theta = m.theta.copy()              # logical angles of the dofs
        self.ze, rows = _rows(m)
        self.rows = [r[np.argsort(self.theta[r])] for r in rows]
        self.pads = _pads(m)
        self.columns, _ = m.axes                 # vertex columns (logical)
        self.p = m.basis.mesh.p.copy()
        self.t = m.basis.mesh.t.copy()
        self.vrow = np.argmin(np.abs(self.p[1][:, None] - self.ze[None, :]), axis=1)

    def locate(self, P, theta, pos, reach=1.0):
        """{(pad, side): theta_c per vertex row (nan where none)}; ``theta`` the dofs'
        physical angles, ``pos`` where the film is pressurised."""
        out = {}
        for k, (a, b) in enumerate(self.pads):
            for side in ("left", "right"):
                out[(k, side)] = np.full(len(self.ze), np.nan)
            for j, r in enumerate(self.rows):
                lt = self.theta[r]
                r = r[(lt > a + 1e-9) & (lt < b - 1e-9)]
                if len(r) < 3 or not pos[r].any():
                    continue
                p, th, ok = P[r], theta[r], pos[r]
                i = int(np.argmax(np.where(ok, p, -np.inf)))
                hi = i
                while hi + 1 < len(r) and ok[hi + 1]:
                    hi += 1
                lo = i
                while lo - 1 >= 0 and ok[lo - 1]:
                    lo -= 1
                if hi < len(r) - 1 and hi >= 1 and hi - 1 >= lo:
                    out[(k, "right")][j] = _vanish(th[hi - 1], th[hi], p[hi - 1], p[hi],
                                                   th[hi + 1], reach)
                if lo > 0 and lo + 1 <= hi:
                    out[(k, "left")][j] = _vanish(th[lo + 1], th[lo], p[lo + 1], p[lo],
                                                  th[lo - 1], reach)
        return out

    def relocate(self, P, theta, cols, located):
        """The fitted boundaries moved to the vertex of the quadratic through the fitted
        column's node (p = 0) and the two nodes before it on each row: where a film
        pressurised up to the column would have dp/dtheta = 0 (the pressure's change from
        holding zero at a wrong place is, over a cell, about a constant: the vertex moves
        onto the boundary at once); the end row (held) keeps its neighbour's."""
        out = {}
        for key, c in cols.items():
            k, side = key
            a, b = self.pads[k]
            x = self.columns[c]
            h = np.min(np.diff(self.columns))
            tc = located[key].copy()
            for j, r in enumerate(self.rows[:-1]):
                lt = self.theta[r]
                r = r[(lt > a + 1e-9) & (lt < b - 1e-9)]
                i = int(np.argmin(np.abs(self.theta[r] - x)))
                nb = (i - 1, i - 2) if side == "right" else (i + 1, i + 2)
                if min(nb) < 0 or max(nb) >= len(r):
                    continue
                t = theta[r[[i, nb[0], nb[1]]]]
                p = np.array([0.0, P[r[nb[0]]], P[r[nb[1]]]])
                c2, c1, _ = np.polyfit(t - t[0], p, 2)
                if c2 > 0.0:
                    tc[j] = t[0] + float(np.clip(-c1 / (2.0 * c2), -h, h))
            tc[-1] = tc[-2]
            out[key] = tc
        return out

    def choose(self, located, share=0.5):
        """{(pad, side): vertex column index} for the boundaries found on at least
        ``share`` of the rows (the column nearest their median)."""
        cols = {}
        for (k, side), tc in located.items():
            found = np.isfinite(tc)
            if found.sum() < share * len(tc):
                continue
            a, b = self.pads[k]
            inner = np.flatnonzero((self.columns > a + 1e-9) & (self.columns < b - 1e-9))
            c = inner[np.argmin(np.abs(self.columns[inner] - np.median(tc[found])))]
            cols[(k, side)] = int(c)
        for k in range(len(self.pads)):      # a left and a right boundary a cell apart at least
            if (k, "left") in cols and (k, "right") in cols and \
                    cols[(k, "right")] - cols[(k, "left")] < 2:
                del cols[(k, "left")]
        return cols

    def held(self, cols, lcp_active) -> np.ndarray:
        """The dofs held at zero: on and beyond each fitted column, inside its pad; in the
        pads without a fitted column the LCP's cavitated set."""
        active = lcp_active.copy()
        for k, (a, b) in enumerate(self.pads):
            if (k, "left") in cols or (k, "right") in cols:
                active[(self.theta > a + 1e-9) & (self.theta < b - 1e-9)] = False
        for (k, side), c in cols.items():
            a, b = self.pads[k]
            x = self.columns[c]
            lt = self.theta
            if side == "right":
                active |= (lt >= x - 1e-9) & (lt < b - 1e-9)
            else:
                active |= (lt <= x + 1e-9) & (lt > a + 1e-9)
        active[self.m.fixed] = False
        return active

    def operator(self, cols, located) -> GroovedOperator:
        """The grooved operator with each fitted column moved, row by row, onto its
        boundary (the rows without one: the nearest row's), the other vertices mapped
        piecewise linearly between the pad's ends and the columns."""
        x = self.moved(cols, located)
        with quiet_skfem():
            mesh = MeshTri1(np.vstack([x, self.p[1]]), self.t)
            basis = Basis(mesh, ELEMENTS[self.element](),
                          intorder=4 if self.element == "P1" else 6)
        d = basis.doflocs
        return GroovedOperator(*build_grooved_tables(self._film_mesh(basis, d)))

    def _film_mesh(self, basis, doflocs) -> FilmMesh:
        m = self.m
        return FilmMesh(basis=basis, fixed=m.fixed, free=m.free, end=m.end,
                        theta=np.array(doflocs[0]), zeta=np.array(doflocs[1]), half=m.half,
                        periodic=m.periodic, n_theta=m.n_theta, n_z=m.n_z,
                        length_ratio=m.length_ratio, theta0=m.theta0, grooves=m.grooves,
                        arcs=m.arcs, grading=m.grading)

    def anchors(self, k, keys, cols, located, j):
        """(source, destination) angles of row ``j``'s piecewise-linear map in pad ``k``:
        the pad's ends fixed, each fitted column onto its boundary."""
        a, b = self.pads[k]
        src, dst = [a], [a]
        for s in keys:
            src.append(self.columns[cols[(k, s)]])
            dst.append(_filled(located[(k, s)])[j])
        return src + [b], dst + [b]

    def moved(self, cols, located) -> np.ndarray:
        """The vertices' angles with the fitted columns moved (:meth:`operator`)."""
        x = self.p[0].copy()
        nrow = len(self.ze)
        for k, (a, b) in enumerate(self.pads):
            keys = [s for s in ("left", "right") if (k, s) in cols]
            if not keys:
                continue
            ins = (x > a + 1e-9) & (x < b - 1e-9)
            for j in range(nrow):
                src, dst = self.anchors(k, keys, cols, located, j)
                dst = np.array(dst)
                # keep the map monotone: each moved column inside its neighbours
                gap = 0.2 * np.min(np.diff(self.columns))
                for i in range(1, len(dst) - 1):
                    dst[i] = min(max(dst[i], dst[i - 1] + gap), b - gap * (len(dst) - 1 - i))
                sel = ins & (self.vrow == j)
                x[sel] = np.interp(self.p[0][sel], src, dst)
        return x


def _vanish(t1, t2, p1, p2, t_next, reach=1.0):
    """Where sqrt(p), linear through (t1, p1), (t2, p2), vanishes, kept between t2 and
    ``reach`` times the step to the next node ``t_next`` beyond it (on the LCP's mesh the
    boundary lies before the first cavitated node: reach 1; on a fitted mesh, whose
    held boundary may be too early, further)."""
    s1, s2 = math.sqrt(max(p1, 0.0)), math.sqrt(max(p2, 0.0))
    if s1 <= s2:
        return 0.5 * (t2 + t_next)
    tc = t2 + s2 * (t2 - t1) / (s1 - s2)
    lo, hi = sorted((t2, t2 + reach * (t_next - t2)))
    return min(max(tc, lo), hi)


def _filled(tc):
    """The rows without a boundary take the nearest row's (the end row is held)."""
    tc = tc.copy()
    found = np.flatnonzero(np.isfinite(tc))
    missing = np.flatnonzero(~np.isfinite(tc))
    for j in missing:
        tc[j] = tc[found[np.argmin(np.abs(found - j))]]
    return tc
