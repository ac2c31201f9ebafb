"""The fitted mesh of studies/kc_fitted_mesh.py moving only a band of columns about each
boundary, its operator updated in the band's cells alone (studies/kc_fitted.py ``--band``
measures its errors and cost beside the full fit's).
"""
from __future__ import annotations

import numpy as np

from bearingfem.fe.assembly import FilmOperator
from bearingfem.fe.general import element_tables
from bearingfem.fe.grooved import GroovedOperator
from bearingfem.fe.grooved_build import _COS_POWERS, harmonic_weights

from .kc_fitted_mesh import Fit, _filled


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
