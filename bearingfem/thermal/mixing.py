"""Groove mixing of the thermal film's energy equation: each groove's inlet temperature
from the supply and the oil carried over from the upstream arc, by the arcs' column flows
(Couette + Poiseuille, dp/dtheta one-sided on each arc: :func:`arc_theta_difference`)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..caches import cached
from ..film import film_thickness
from .energy import Mixing
from .spec import Thermal

__all__ = ["arc_theta_difference", "groove_mixing"]


@cached(maxsize=16)
def arc_theta_difference(mesh, edges) -> sp.csr_matrix:
    """(N, N) nodal P -> dP/dtheta at the arcs' nodes (0 inside the grooves), each node's
    from the parabola through it and its two neighbours along theta on its own arc, the
    two inward at the arc's edges (cached per mesh and edges): second order on the
    mesh's nodes, graded or not. Why the arc's own nodes: a groove holds its supply
    pressure, so a derivative reaching into it (a projection over the whole mesh)
    averages the arc's edge column with the groove's flat pressure, and an arc's inlet
    and exit flows then depend on the groove beside them (not falling with the mesh).
    The film mesh is a tensor grid: each arc column holds a node at every zeta."""
    N, ze = mesh.ndofs, mesh.zeta
    col, dofs = edges.column_index, edges.column_dofs
    n_col = len(edges.column_theta)
    rows_z, row = np.unique(np.round(ze[dofs], 10), return_inverse=True)
    grid = np.full((n_col, len(rows_z)), -1)
    grid[col, row] = dofs
    if np.any(grid < 0):
        raise ValueError("the thermal film needs a tensor film mesh (a node at every "
                         "zeta of each arc column)")
    # columns c and c + 1 on one arc: some arc element holds a dof of each
    where = np.full(N, -1)
    where[dofs] = col
    ec = where[mesh.basis.element_dofs[:, edges.elements]]
    linked = np.zeros(max(n_col - 1, 0), bool)
    lo, hi = ec.min(axis=0), ec.max(axis=0)
    for k in range(int(np.max(hi - lo, initial=0))):
        linked[(lo + k)[lo + k < hi]] = True
    t = mesh.theta[grid[:, 0]]           # each column's angle (not the rounded key)
    back, ahead = np.r_[False, linked], np.r_[linked, False]    # c -/+ 1 on c's arc
    rows, cols, vals = [], [], []
    for j in range(n_col):       # once per mesh, over the columns
        if back[j] and ahead[j]:
            stencil = [j - 1, j, j + 1]
        elif ahead[j]:           # an arc's first column: inward
            stencil = [j, j + 1, j + 2] if ahead[j + 1] else [j, j + 1]
        elif back[j]:            # its last
            stencil = [j - 2, j - 1, j] if back[j - 1] else [j - 1, j]
        else:
            raise ValueError("an arc of the thermal film has a single column of nodes")
        x = t[stencil] - t[j]
        if len(x) == 3:          # d/dx at 0 of the parabola through the three (x_i, P_i)
            w = [-(x[1] + x[2]) / ((x[0] - x[1]) * (x[0] - x[2])),
                 -(x[0] + x[2]) / ((x[1] - x[0]) * (x[1] - x[2])),
                 -(x[0] + x[1]) / ((x[2] - x[0]) * (x[2] - x[1]))]
        else:
            w = [-1.0 / (x[1] - x[0]), 1.0 / (x[1] - x[0])]
        for c, wc in zip(stencil, w):
            rows.append(grid[j])
            cols.append(grid[c])
            vals.append(np.full(grid.shape[1], wc))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(N, N))


def _column_flows(bearing, state, mesh, edges, P, fraction, mu_nodal):
    """Nodal q_theta [m^2/s] (Couette + Poiseuille, dp/dtheta on each arc's own nodes:
    :func:`arc_theta_difference`) and each arc column's flow int q_theta dz [m^3/s]."""
    R, c = bearing.radius, bearing.clearance
    dP = arc_theta_difference(mesh, edges) @ P
    h = c * film_thickness(mesh.theta - state.gamma, state.eps)
    q = (0.5 * state.omega * R * fraction * h
         - h ** 3 / (12.0 * mu_nodal) * bearing.pressure_scale / R * dP)
    flows = R * np.bincount(edges.column_index, edges.column_weight * q[edges.column_dofs],
                            minlength=len(edges.column_theta))
    return q, flows


def groove_mixing(bearing, state, mesh, edges, P, fraction, mu_nodal,
                  thermal: Thermal) -> Mixing:
    """Each groove's inlet temperature as a linear function of the film's (:class:`Thermal`'s
    ``carry_over``): the upstream arc's exit temperature, flow-weighted over its last line
    (trapezoidal in z), carried by lambda Q_out, Q_out the arc's least column flow (what
    passes its cavity), mixed with fresh oil up to the next arc's inlet flow Q_in:
    T_in = ((Q_in - C) T_supply + C T_out) / Q_in, C = min(lambda Q_out, Q_in). The flows'
    dp/dtheta is each arc's own (:func:`arc_theta_difference`): one-sided at every
    groove edge, so an arc's inlet and exit flows do not see the groove beside them. With
    omega < 0 (``edges`` reversed) the flows are counted along the oil's way."""
    q, flows = _column_flows(bearing, state, mesh, edges, P, fraction, mu_nodal)
    if state.omega < 0.0:
        q, flows = -q, -flows
    column = np.full(mesh.ndofs, -1)
    column[edges.column_dofs] = edges.column_index
    ts, lam = thermal.supply_temperature, thermal.carry_over
    fresh, dofs, weights = [], [], []
    for k, (d_in, d_out) in enumerate(zip(edges.inflow, edges.outflow)):
        o = d_out[np.argsort(mesh.zeta[d_out])]
        z, qo = mesh.zeta[o], q[o]
        w = np.zeros(len(o))                           # trapezoidal weights in z
        w[:-1] += 0.5 * np.diff(z)
        w[1:] += 0.5 * np.diff(z)
        q_sum = float(np.sum(w * qo))
        q_out = float(np.min(flows[edges.column_groove == k], initial=np.inf))
        q_in = float(flows[column[d_in[0]]])
        carried = min(lam * max(q_out, 0.0), q_in) if q_in > 0.0 and q_sum > 0.0 else 0.0
        share = carried / q_in if carried > 0.0 else 0.0
        fresh.append((1.0 - share) * ts)
        dofs.append(o)
        weights.append(share * w * qo / q_sum if share > 0.0 else np.zeros(len(o)))
    return Mixing(fresh=tuple(fresh), dofs=tuple(dofs), weights=tuple(weights))
