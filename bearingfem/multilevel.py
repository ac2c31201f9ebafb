"""Nested iteration for the cavitated film: a good first active set from a coarser mesh.

From a cold start, the active-set method moves the cavitation front by about one node
layer per iteration, so its iteration count grows with the mesh. Solving first on a mesh
half as fine in each direction (recursively) and interpolating that pressure to the fine
dofs puts the front within a layer or two of its place: the fine solve then takes a few
iterations whatever the mesh.
"""
from __future__ import annotations

import numpy as np
from scipy.interpolate import RegularGridInterpolator

__all__ = ["grid_interpolator", "COARSEST_FREE_DOFS"]

#: Below this many free dofs a cold start is cheaper than another level.
COARSEST_FREE_DOFS = 400


def grid_interpolator(mesh, P):
    """Bilinear interpolant of the vertex values of ``P`` on the (theta, zeta) tensor grid."""
    theta, zeta = mesh.theta, mesh.zeta
    if mesh.periodic:
        # the seam's dofs may sit at theta = 2 pi: wrap them to 0
        tkey = np.mod(theta, 2 * np.pi)
        tkey[np.isclose(tkey, 2 * np.pi)] = 0.0
    else:
        tkey = theta
    th_u = np.unique(np.round(tkey, 12))
    ze_u = np.unique(np.round(zeta, 12))
    dth = th_u[1] - th_u[0]
    dze = ze_u[1] - ze_u[0]
    i = np.rint((tkey - th_u[0]) / dth).astype(int)
    j = np.rint((zeta - ze_u[0]) / dze).astype(int)
    on_grid = (np.abs(tkey - (th_u[0] + i * dth)) < 1e-9 * max(1.0, dth)) & \
              (np.abs(zeta - (ze_u[0] + j * dze)) < 1e-9 * max(1.0, dze))
    G = np.zeros((len(th_u), len(ze_u)))
    G[i[on_grid], j[on_grid]] = P[on_grid]
    if mesh.periodic:   # close the loop for interpolation across the seam
        th_u = np.append(th_u, th_u[0] + 2 * np.pi)
        G = np.vstack([G, G[:1]])
    f = RegularGridInterpolator((th_u, ze_u), G, bounds_error=False, fill_value=None)

    def at(theta_q, zeta_q):
        t = np.mod(theta_q - th_u[0], 2 * np.pi) + th_u[0] if mesh.periodic else theta_q
        return f(np.column_stack([t, zeta_q]))
    return at
