"""A mesh fitted to the cavitation boundary: do the force, K and C then converge regularly?

    python -m studies.kc_fitted             # ~1.5 min CPU (run it with no other heavy job on the machine)
    python -m studies.kc_fitted --quick     # two rows, three levels, P2
    python -m studies.kc_fitted --rows 0 9 --elements P2
    python -m studies.kc_fitted --band      # the band-fitted film's cost, five rows, ~1 min

With Reynolds' condition p = dp/dn = 0 on the rupture boundary theta_c(z), and the first
variation of the film solves the linearised Reynolds equation on the full-film region
with zero pressure on that boundary (the boundary's motion contributes nothing to first
order). The FE film's K and C (the held set's tangent) put that boundary on the first
cavitated node instead, a staircase whose steps move when a node joins or leaves the
film: their error jumps (studies/kc_phase.py). Here the boundary is made a mesh line:

1. solve the film on the mesh (the LCP);
2. on each axial row of nodes and each pad, the pressurised run about the pad's peak;
   where it ends inside the pad (not at a groove) its free end theta_c is where
   sqrt(p), linear through the run's last two nodes, vanishes (p ~ a (theta - theta_c)^2
   near the boundary);
3. one column of vertices per free boundary (the nearest to the boundary's median) is
   moved row by row onto theta_c(z_j), the other vertices of the row mapped piecewise
   linearly between it and the pad's ends (the grooves' edges stay);
4. on the fitted mesh the film is the linear film on the region inside the fitted
   columns, zero pressure on and beyond them (in pads without a fitted boundary the
   LCP's cavitated set); the column then moves to the vertex of the quadratic through its
   node and the two before it on each row (where dp/dtheta = 0), by secant steps per row,
   and steps 3-4 repeat (:data:`FIT_ITERATIONS` operators built);
5. force and partials of that film (the held set's tangent, the same right-hand sides as
   :func:`bearingfem.fe.grooved.grooved_derivatives`), K and C in the inertial frame.

Tables, on Lund & Thomsen's ten rows (studies/lund_thomsen.py) at the states of P2 144
equilibria, P1 and P2 on 36 .. 144 cells around, graded as a search grades them (toward
the least film from eps 0.3 on, uniform below), the film on the mesh ("plain", the LCP's
held set) and fitted: errors of the force (|dF| / |F|) and of K, C (the larger of the two
largest-entry errors, each relative to its matrix's largest entry) against (a) the
benchmark's reference (P2 288 graded, plain) and (b) the fitted P2 288 graded as the
meshes, with the observed orders between consecutive levels; the h/2h pairs' estimates
(order 1 for plain, as the search; 2 for fitted) against the true error; the first pair a
search at rtol 2e-3 would accept and what its two films cost (CPU). ``--band``: the same
fit moving only a band of columns about each boundary, its operator updated in the band's
cells alone (:class:`BandFit`), errors and CPU beside the full fit's. docs/accuracy.md, *A
mesh fitted to the cavitation boundary*, has the numbers.
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np
from scipy.sparse.linalg import splu
from skfem import Basis, MeshTri1

from bearingfem.design.records import DynamicCoefficients, frame_axes
from bearingfem.design.tolerance import GRADED_FROM_EPS, GRADING_STRENGTH
from bearingfem.fe.grooved import (GroovedOperator, _held, _system, groove_operator_for,
                                   partials_load,
                                   grooved_pressure, rotated)
from bearingfem.fe.assembly import FilmOperator
from bearingfem.fe.general import element_tables
from bearingfem.fe.grooved_build import _COS_POWERS, build_grooved_tables, harmonic_weights
from bearingfem.fe.mesh import ELEMENTS, FilmMesh, quiet_skfem
from bearingfem.film import local_to_inertial
from bearingfem.scales import force_factor

from bearingfem.design import equilibrium
from bearingfem.design.groups import load_from_sommerfeld

from .lund_thomsen import GROOVES, LOAD_DIRECTION, OMEGA, TABLE, bearing, mesh

#: fit (relocate the boundary, rebuild, resolve) this many times after the first solve
FIT_ITERATIONS = 4
#: cells around of the levels compared (multiples of 18: nodes on the grooves' edges)
LEVELS = (36, 54, 72, 108, 144)
REFERENCE = 288


# ----------------------------------------------------------------------------- the mesh

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


class BandFit(Fit):
    """A :class:`Fit` that moves only a band of vertex columns about each boundary (the
    columns two cells beyond the boundary's extent over the rows stay) and updates the
    base operator's tables in the band's cells alone: the element matrices from the cells'
    new Jacobians and the base's reference tables (geometry-free for straight P1/P2
    cells), the interpolation to the quadrature points the base's. On the full pattern of
    the cells' dofs (the base drops the couplings that vanish on right triangles)."""

    def __init__(self, gop, element):
        super().__init__(gop, element)
        basis = self.m.basis
        t = element_tables(basis)
        self.ref = t
        self.X = np.asarray(basis.X)
        self.W = np.asarray(basis.W)
        self.ref_dofs = np.asarray(basis.elem.doflocs).T        # (2, nb), reference
        N = basis.N
        dofs = t.dofs.astype(np.int64)
        local = (dofs[:, :, None] * N + dofs[:, None, :]).reshape(len(dofs), -1)
        self.keys, slot = np.unique(local, return_inverse=True)
        self.slot = slot.reshape(local.shape)
        geo = self._geometry(self.p[0], np.arange(self.t.shape[1]))
        self.base_local = geo
        self.base_tables = self._scatter(geo["stiff"], np.arange(self.t.shape[1]))
        self.base_loads = geo["loads"]
        self.base_doflocs = np.asarray(basis.doflocs)
        op = gop.op
        rows, cols = self.keys // N, self.keys % N
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=N))])
        free = self.m.free
        renumber = np.full(N, -1, dtype=np.int64)
        renumber[free] = np.arange(len(free))
        ff = np.flatnonzero((renumber[rows] >= 0) & (renumber[cols] >= 0))
        self.ff = ff
        self.ff_indptr = np.concatenate([[0], np.cumsum(np.bincount(renumber[rows[ff]],
                                                                    minlength=len(free)))])
        self.ff_indices = renumber[cols[ff]]
        self.indices = cols
        self.qp_interp = op.qp_interp

    def _geometry(self, x, cells):
        """Element matrices (7, cells, nb*nb), loads (2, cells, nb: sin, cos), quadrature
        points' (theta, zeta), weights, and the dofs' coordinates of ``cells`` at vertex
        angles ``x``."""
        v = np.stack([x, self.p[1]])[:, self.t[:, cells]]           # (2, 3, cells)
        J = np.stack([v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]], axis=1)  # (2, 2, cells) [a, c]
        det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
        invJ = np.stack([np.stack([J[1, 1], -J[0, 1]]), np.stack([-J[1, 0], J[0, 0]])]) / det
        det = np.abs(det)
        metric = np.einsum("cae,dae->cde", invJ, invJ) * det
        qp = v[:, 0, :, None] + np.einsum("ace,cq->aeq", J, self.X)   # (2, cells, q)
        weights = harmonic_weights(qp[0])                            # (7, cells, q)
        n_w, n_e, n_q = weights.shape
        folded = (weights[:, :, :, None] * metric.reshape(4, n_e).T[None, :, None, :]
                  ).reshape(n_w * n_e, -1)
        stiff = self.ref.stiff_tables.reshape(4, n_q, -1).transpose(1, 0, 2).reshape(4 * n_q, -1)
        loads = np.stack([det[:, None] * (weights[i] @ self.ref.value_table) for i in (2, 1)])
        dofloc = v[:, 0, :, None] + np.einsum("ace,cn->aen", J, self.ref_dofs)
        return {"stiff": (folded @ stiff).reshape(n_w, n_e, -1), "loads": loads, "qp": qp,
                "dx": det[:, None] * self.W[None, :], "doflocs": dofloc}

    def _scatter(self, local, cells):
        n_w = local.shape[0]
        n = len(self.keys)
        idx = (np.arange(n_w)[:, None] * n + self.slot[cells].ravel()[None, :]).ravel()
        return np.bincount(idx, local.reshape(n_w, -1).ravel(), minlength=n_w * n).reshape(n_w, n)

    def anchors(self, k, keys, cols, located, j):
        """As :meth:`Fit.anchors`, and each boundary's band held at the columns two cells
        beyond its extent over the rows."""
        a, b = self.pads[k]
        pairs = [(a, a), (b, b)]
        for s in keys:
            tc = _filled(located[(k, s)])
            c = cols[(k, s)]
            last = len(self.columns) - 1
            lo = max(0, np.searchsorted(self.columns, min(tc.min(), self.columns[c])) - 2)
            hi = min(last, np.searchsorted(self.columns, max(tc.max(), self.columns[c])) + 2)
            for e in (lo, hi):
                if a < self.columns[e] < b:
                    pairs.append((self.columns[e], self.columns[e]))
            pairs.append((self.columns[c], tc[j]))
        pairs = sorted(set(pairs))
        return [p[0] for p in pairs], [p[1] for p in pairs]

    def operator(self, cols, located) -> GroovedOperator:
        x = self.moved(cols, located)
        cells = np.flatnonzero(np.any(x[self.t] != self.p[0][self.t], axis=0))
        geo = self._geometry(x, cells)
        tables = self.base_tables + self._scatter(geo["stiff"] - self.base_local["stiff"][:, cells],
                                                  cells)
        dofs = self.ref.dofs
        N = self.m.basis.N
        loads = self.base_loads.copy()
        loads[:, cells] = geo["loads"]
        b_sin, b_cos = (np.bincount(dofs.ravel(), loads[i].ravel(), minlength=N) for i in (0, 1))
        qp = self.base_local["qp"].copy()
        qp[:, cells] = geo["qp"]
        dx = self.base_local["dx"].copy()
        dx[cells] = geo["dx"]
        doflocs = self.base_doflocs.copy()
        doflocs[:, dofs[cells]] = geo["doflocs"]
        # (the base basis rides along for its dof count; the geometry is the arrays')
        fm = self._film_mesh(self.m.basis, doflocs)
        op = FilmOperator(
            mesh=fm, indptr=self.indptr.astype(np.int32), indices=self.indices.astype(np.int32),
            terms=_COS_POWERS @ tables, ff_indptr=self.ff_indptr.astype(np.int32),
            ff_indices=self.ff_indices.astype(np.int32), ff_select=self.ff, b_sin=b_sin,
            b_cos=b_cos, qp_theta=qp[0], qp_zeta=qp[1], qp_weight=dx,
            qp_interp=self.qp_interp)
        return GroovedOperator(op, tables)


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


# ----------------------------------------------------------------------------- the film

def held_film(gop, bearing, state, active):
    """(force (F_r, F_t) [N], K, C inertial, pressure) of the linear film with ``active``
    held at zero and the grooves at their pressure: the held set's tangent."""
    op = gop.op
    m = op.mesh
    G = _held(bearing, gop, GROOVES)
    values, load = _system(gop, state)
    A = op.matrix(values).tocsr()
    inner = m.free[~active[m.free]]
    lu = splu(A[inner][:, inner].tocsc())
    P = G.copy()
    P[inner] = lu.solve((load - A @ G)[inner])
    g = state.gamma
    rhs = partials_load(gop, state, P)
    dP = np.zeros((m.ndofs, 4))
    dP[inner] = lu.solve(rhs[inner])
    k = force_factor(bearing, True)
    I = op.force_integrals(np.concatenate([P[None], dP.T]))
    F = k * rotated(I, g)
    d_gamma = F[:, 4] + np.array([F[1, 0], -F[0, 0]])
    return _coefficients(bearing, state, F[:, 0], F[:, 1], F[:, 2], F[:, 3], d_gamma), P


def _coefficients(bearing, state, F, A, B, W, G):
    """(force inertial, K, C inertial) from the local partials (steady state, as
    :func:`bearingfem.design.coefficients`)."""
    e, c = state.eps, bearing.clearance
    JF = np.array([-F[1], F[0]]) + G
    K = -np.column_stack([A, JF / e]) / c
    C = -np.column_stack([B, -2.0 * W / e]) / c
    force = tuple(float(f) for f in local_to_inertial(F[0], F[1], state.gamma))
    kc = DynamicCoefficients(K, C, "local", frame_axes("local", state.gamma, force), state,
                             force, "fem", "held", c, np.zeros((2, 2))).in_frame("inertial")
    return np.array(force), np.asarray(kc.K), np.asarray(kc.C)


def films(bearing, state, n_theta, n_z, element, grading=None, iterations=FIT_ITERATIONS,
          band=False):
    """({"plain": (F, K, C), "fitted": (F, K, C)}, the fit's last step [rad], the number of
    fitted boundaries, (CPU of the LCP and the plain tangent, of all) [s]): the film on the
    mesh (the LCP's held set) and on the mesh fitted to its boundary (``iterations``
    operators; with none, or no boundary found, the plain film)."""
    gop = groove_operator_for(bearing, n_theta, n_z, element, GROOVES, grading)
    gop.last.clear()
    t0 = time.process_time()
    res = grooved_pressure(gop, bearing, state, GROOVES, "reynolds")
    plain, _ = held_film(gop, bearing, state, res.active)
    t1 = time.process_time()
    fit = (BandFit if band else Fit)(gop, element)
    m = gop.op.mesh
    located = fit.locate(res.pressure, m.theta, ~res.active & (res.pressure > 0.0))
    cols = fit.choose(located)
    active = fit.held(cols, res.active)
    x = {key: _filled(located[key]) for key in cols}
    last = {}
    move = 0.0
    out = plain
    h = np.min(np.diff(fit.columns))
    for _ in range(iterations if cols else 0):
        fop = fit.operator(cols, {**located, **x})
        out, P = held_film(fop, bearing, state, active)
        vertex = fit.relocate(P, fop.op.mesh.theta, cols, x)
        step = {}
        for key in cols:
            r = vertex[key] - x[key]
            dx = r
            if key in last:     # a secant step per row where the last step gives a slope
                x0, r0 = last[key]
                run = x[key] - x0
                slope = np.divide(r - r0, run, out=np.zeros_like(r), where=np.abs(run) > 1e-12)
                use = slope < -0.05
                dx = np.where(use, -r / np.where(use, slope, 1.0), r)
            last[key] = (x[key], r)
            step[key] = np.clip(dx, -h, h)
        move = max(float(np.max(np.abs(r))) for r in step.values())
        x = {key: x[key] + step[key] for key in cols}
    seconds = (t1 - t0, time.process_time() - t0)
    return {"plain": plain, "fitted": out}, move, len(cols), seconds


# ----------------------------------------------------------------------------- the tables

def _errors(out, ref):
    F, K, C = out
    F0, K0, C0 = ref
    return (float(np.linalg.norm(F - F0) / np.linalg.norm(F0)),
            float(max(np.abs(K - K0).max() / np.abs(K0).max(),
                      np.abs(C - C0).max() / np.abs(C0).max())))


def _nz(ld, n):
    return max(4, round(n * ld / 3))


def reference_grading(state):
    """The grading of the meshes (and the reference) at ``state``: toward the least film
    (the search's, its angle on the 15 deg grid) from GRADED_FROM_EPS on, else None."""
    if state.eps < GRADED_FROM_EPS:
        return None
    step = math.pi / 12.0
    return (step * round(state.gamma / step), GRADING_STRENGTH)


def study(levels=LEVELS, elements=("P2", "P1"), select=None):
    """[(L/D, S, eps, element, n_theta, {"plain"|"fitted": (F, K, C)}, the fit's last
    move [rad], fitted columns, (LCP + plain tangent, plus the fit) seconds)] on the
    meshes graded as a search grades them (:func:`reference_grading`), and per row the
    references {"benchmark": (F, K, C) of P2 288 graded unfitted (the benchmark's),
    "fitted": the fitted P2 288 graded as the meshes}."""
    out, refs = [], {}
    cases = [(ld, S) for ld, table in TABLE.items() for S, *_ in table]
    for i, (ld, S) in enumerate(cases):
        if select is not None and i not in select:
            continue
        b = bearing(ld)
        s = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                        direction=LOAD_DIRECTION, **mesh(ld, 144, "P2")).state
        grading = reference_grading(s)
        bench, _, _, _ = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2",
                               (s.gamma, GRADING_STRENGTH), iterations=0)
        fitted, _, _, _ = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2", grading)
        refs[(ld, S)] = {"benchmark": bench["plain"], "fitted": fitted["fitted"]}
        for el in elements:
            for n in levels:
                f, move, ncols, dt = films(b, s, n, _nz(ld, n), el, grading)
                out.append((ld, S, s.eps, el, n, f, move, ncols, dt))
    return out, refs


def _orders(errs, levels):
    return [math.log(a / b) / math.log(n2 / n1) if a > 0 and b > 0 else float("nan")
            for a, b, n1, n2 in zip(errs[:-1], errs[1:], levels[:-1], levels[1:])]


#: the order and safety factor an h/2h pair's estimate would use: the search's (order 1
#: for the held set's K and C, accuracy.py's SAFETY 1.5) and order 2 for the fitted film
PAIR_ORDER = {"plain": 1.0, "fitted": 2.0}
SAFETY = 1.5
#: the first pair (n / 2n) whose estimate is within this is what a search would accept
SEARCH_RTOL = 2e-3


#: the rows of the band table (:func:`band_table`): a light one and the graded ones
BAND_ROWS = ((0.5, 1.656), (0.5, 0.58), (0.5, 0.244), (1.0, 0.235), (1.0, 0.108))


def band_table(levels=LEVELS):
    """[(L/D, S, n_theta, (plain error, seconds), (fitted error, seconds), (band-fitted
    error, seconds))]: K, C errors against the fitted P2 288 (graded as the meshes) and
    CPU of one film (the second of two calls: the base operator built): the LCP and
    its tangent; with the fit; with the fit moving only a band (:class:`BandFit`)."""
    out = []
    for ld, S in BAND_ROWS:
        b = bearing(ld)
        s = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                        direction=LOAD_DIRECTION, **mesh(ld, 144, "P2")).state
        g = reference_grading(s)
        ref = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2", g)[0]["fitted"]
        for n in levels:
            row = []
            for band in (False, True):
                films(b, s, n, _nz(ld, n), "P2", g, band=band)
                f, _, _, dt = films(b, s, n, _nz(ld, n), "P2", g, band=band)
                row.append((_errors(f["fitted"], ref)[1], dt[1]))
            out.append((ld, S, n, (_errors(f["plain"], ref)[1], dt[0]), *row))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    p.add_argument("--band", action="store_true",
                   help="the band-fitted film's errors and cost beside the fitted one's")
    p.add_argument("--rows", type=int, nargs="*", help="the rows (0-9) shown; all by default")
    p.add_argument("--elements", nargs="*", default=["P2", "P1"])
    a = p.parse_args(argv)
    n_rows = sum(len(table) for table in TABLE.values())
    if a.rows and not all(0 <= r < n_rows for r in a.rows):
        p.error(f"--rows must lie in 0..{n_rows - 1}, got {a.rows}")
    if a.band:
        print("K, C error against the fitted P2 288 and CPU of one film: plain (LCP and "
              "tangent), fitted, band-fitted")
        for ld, S, n, plain, fitted, band in band_table():
            print(f"L/D {ld:g} S {S:<6g} {n:4d}  plain {plain[0]:.1e} {plain[1]:.3f} s  "
                  f"fitted {fitted[0]:.1e} {fitted[1]:.3f} s  band {band[0]:.1e} "
                  f"{band[1]:.3f} s")
        return
    levels = LEVELS[:3] if a.quick else LEVELS
    select = (4, 9) if a.quick else a.rows
    rows, refs = study(levels, ("P2",) if a.quick else tuple(a.elements), select)
    print("K, C error: the larger of K's and C's largest-entry error over the largest entry; "
          "(a) against P2 288 graded unfitted (the benchmark's reference), (b) against the "
          "fitted P2 288 (graded as the meshes); orders per doubling between levels")
    groups = {}
    for ld, S, eps, el, n, f, move, ncols, dt in rows:
        groups.setdefault((ld, S, eps, el), []).append((n, f, move, ncols, dt))
    worst = {}
    pairs = {"plain": [], "fitted": []}
    searches = {"plain": [], "fitted": []}
    for (ld, S, eps, el), g in groups.items():
        ref = refs[(ld, S)]
        ns = [x[0] for x in g]
        kind = "graded" if eps >= GRADED_FROM_EPS else "uniform"
        bf, bk = _errors(ref["benchmark"], ref["fitted"])
        print(f"\nL/D {ld:g}, S {S:g} (eps {eps:.3f}), {el} {kind}: cells around {ns}, "
              f"fitted columns {[x[3] for x in g]}, last fit move [deg] "
              f"{' '.join(f'{math.degrees(x[2]):.0e}' for x in g)}; (a) from (b): force "
              f"{bf:.1e}, K, C {bk:.1e}")
        for film in ("plain", "fitted"):
            for q, name in ((0, "force"), (1, "K, C")):
                for against in ("benchmark", "fitted"):
                    e = [_errors(x[1][film], ref[against])[q] for x in g]
                    o = _orders(e, ns)
                    tag = "(a)" if against == "benchmark" else "(b)"
                    print(f"  {film:6s} {name:5s} {tag} " + " ".join(f"{v:8.1e}" for v in e)
                          + "   orders " + " ".join(f"{v:5.2f}" for v in o))
                    if against == "fitted":
                        for n, v in zip(ns, e):
                            key = (el, film, name, n)
                            worst[key] = max(worst.get(key, 0.0), v)
            # h/2h pairs within the levels: estimate against the true error (b)
            by_n = {x[0]: x[1][film] for x in g}
            cost = {x[0]: x[4][0 if film == "plain" else 1] for x in g}
            accepted = None
            for n in ns:
                if 2 * n in by_n:
                    fine, coarse = by_n[2 * n], by_n[n]
                    est = SAFETY * _errors(fine, coarse)[1] / (2.0 ** PAIR_ORDER[film] - 1.0)
                    true = _errors(fine, ref["fitted"])[1]
                    pairs[film].append((el, ld, S, 2 * n, est, true))
                    if accepted is None and est <= SEARCH_RTOL:
                        accepted = (2 * n, est, true, cost[n] + cost[2 * n])
            searches[film].append((el, ld, S, accepted))
        print("  seconds, LCP + tangent " + " ".join(f"{x[4][0]:.3f}" for x in g)
              + "; with the fit " + " ".join(f"{x[4][1]:.3f}" for x in g))
    print("\nlargest error over the rows against (b), per level")
    for el in sorted({k[0] for k in worst}):
        for film in ("plain", "fitted"):
            for name in ("force", "K, C"):
                e = [worst[(el, film, name, n)] for n in levels if (el, film, name, n) in worst]
                print(f"  {el} {film:6s} {name:5s} " + " ".join(f"{v:8.1e}" for v in e))
    print("\nh/2h pairs (n / 2n cells around) of K, C: estimate SAFETY |d| / (2^p - 1), "
          "p = 1 (plain, the search's) and 2 (fitted), against the true error (b)")
    for film, ps in pairs.items():
        if not ps:
            continue
        eff = np.array([est / true for *_, est, true in ps if true > 2e-5])
        low = [(el, ld, S, n, est, true) for el, ld, S, n, est, true in ps
               if true > 2e-5 and est < true]
        print(f"  {film:6s}: {len(eff)} pairs (true error > 2e-5), effectivity least "
              f"{eff.min():.2f}, median {np.median(eff):.2f}, largest {eff.max():.2f}; "
              f"below 1: {len(low)}")
        for el, ld, S, n, est, true in low:
            print(f"     {el} L/D {ld:g} S {S:g} {n} cells: estimate {est:.1e}, true {true:.1e}")
    print(f"\nthe first pair whose estimate is within {SEARCH_RTOL:g} (a search from 36 / 72 "
          "on these levels): fine mesh, estimate, true error (b), CPU of the pair's two films "
          "(plain: LCP + tangent; fitted: with the fit)")
    for film, ss in searches.items():
        total = {}
        for el, ld, S, acc in sorted(ss, key=lambda r: r[0], reverse=True):
            if acc is None:
                print(f"  {film:6s} {el} L/D {ld:g} S {S:<6g} none within the levels")
                continue
            n, est, true, dt = acc
            total[el] = total.get(el, 0.0) + dt
            print(f"  {film:6s} {el} L/D {ld:g} S {S:<6g} {n:4d} cells  estimate {est:.1e}  "
                  f"true {true:.1e}  {dt:.3f} s")
        for el, t in total.items():
            print(f"  {film:6s} {el}: the accepted pairs {t:.3f} s CPU")


if __name__ == "__main__":
    main()
