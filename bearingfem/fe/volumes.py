"""Node-centred control volumes of a tensor P1 mesh: where the film content is balanced.

The JFO film transports its content phi h with the Couette flow. On a P1 mesh of a
tensor grid, each node owns the rectangle half way to its neighbours (the dual cell,
whose area is also the node's lumped mass), and the content crosses the faces between
neighbours along the sliding direction x, taken from the upwind node. Every face flux
leaves one volume and enters the next, so the discrete film conserves mass exactly; with
phi = 1 the transport term is the exact integral of the Reynolds wedge source over the
volume, so the full film keeps the accuracy of the Poiseuille operator.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..solvers.jfo import upwind_transport

__all__ = ["ControlVolumes", "control_volumes", "transport_matrix", "shift_rows"]


@dataclass(frozen=True, eq=False)
class ControlVolumes:
    """Dual cells of the nodes of a tensor grid (x along the sliding direction).

    Attributes
    ----------
    x_lo, x_hi : the cell's extent along x (clipped at non-periodic ends)
    width : its extent across x
    down : index of the next node along +x in the same row, -1 where none
    row, column : the node's grid indices
    """

    x_lo: np.ndarray
    x_hi: np.ndarray
    width: np.ndarray
    down: np.ndarray
    row: np.ndarray
    column: np.ndarray
    n_columns: int
    periodic: bool

    @property
    def face(self) -> np.ndarray:
        """x of each node's downstream face (= x_hi)."""
        return self.x_hi

    @property
    def area(self) -> np.ndarray:
        return (self.x_hi - self.x_lo) * self.width


def control_volumes(x: np.ndarray, y: np.ndarray, x_axis: np.ndarray, y_axis: np.ndarray,
                    periodic: bool, periodic_y: bool = False) -> ControlVolumes:
    """Volumes of nodes at (x, y) on the grid lines ``x_axis`` x ``y_axis`` (a periodic
    axis lists its first line again at the end, as the mesh generators do)."""
    dx = np.diff(x_axis)
    dy = np.diff(y_axis)
    nx = len(x_axis) - 1 if periodic else len(x_axis)
    i = np.rint(np.interp(x, x_axis, np.arange(len(x_axis)))).astype(int)
    j = np.rint(np.interp(y, y_axis, np.arange(len(y_axis)))).astype(int)
    if periodic:
        i = np.mod(i, nx)
    lo_dx = np.where(i > 0, dx[np.maximum(i - 1, 0)], dx[-1] if periodic else 0.0)
    hi_dx = np.where(i < len(dx), dx[np.minimum(i, len(dx) - 1)], 0.0)
    xi = x_axis[i]
    if periodic_y:
        j = np.mod(j, len(dy))
    lo_dy = np.where(j > 0, dy[np.maximum(j - 1, 0)], dy[-1] if periodic_y else 0.0)
    hi_dy = np.where(j < len(dy), dy[np.minimum(j, len(dy) - 1)], 0.0)
    index = np.full((nx, len(y_axis)), -1)
    index[i, j] = np.arange(len(x))
    if periodic:
        nxt = index[np.mod(i + 1, nx), j]
    else:
        nxt = np.where(i + 1 < nx, index[np.minimum(i + 1, nx - 1), j], -1)
    return ControlVolumes(x_lo=xi - 0.5 * lo_dx, x_hi=xi + 0.5 * hi_dx,
                          width=0.5 * (lo_dy + hi_dy), down=nxt, row=j, column=i,
                          n_columns=nx, periodic=periodic)


def transport_matrix(cv: ControlVolumes, face_flux: np.ndarray) -> sp.csr_matrix:
    """Upwind transport of the fraction phi: (T phi)_k = net outflow of volume k, for
    ``face_flux`` = (sliding transport speed) x (film at the face) x (face width) on each
    node's downstream face (positive along +x). The flux takes phi from the upwind node."""
    k = np.flatnonzero(cv.down >= 0)
    return upwind_transport(k, cv.down[k], face_flux[k], len(cv.down))


def shift_rows(cv: ControlVolumes, values: np.ndarray, cells: float) -> np.ndarray:
    """Values per node (last axis) moved ``cells`` columns towards -x along each periodic
    row (the new node k takes what sat at k + cells): the content a rotating mesh carries
    from one time step to the next. Whole columns move exactly; the fraction s of a column
    moves as one step of limited Lax-Wendroff advection at Courant number s (flux form,
    monotonized-central slopes): each row's sum is kept exactly, no new extremum appears,
    and where the values are smooth a shift errs by the cube of the cell (a donor-cell
    shift by its square; a time step divides the error by its dt, so what reaches the
    pressure is second order in the cell, against first)."""
    if cells == 0.0 or not cv.periodic:
        return values
    m = int(np.floor(cells))
    s = cells - m
    n = cv.n_columns
    node_at = np.empty((n, cv.row.max() + 1), dtype=np.intp)
    node_at[cv.column, cv.row] = np.arange(len(cv.column))
    at = lambda k: node_at[(cv.column + k) % n, cv.row]   # noqa: E731 (k columns on)
    u = values[..., at(m)]                                   # whole columns moved
    if s == 0.0:
        return u
    right, left = values[..., at(m + 1)], values[..., at(m - 1)]
    slope = _mc_slope(right - u, u - left)
    # what crosses each node's +x face during the shift: the upwind (right-hand) node's
    # value at that face, averaged over the part that crosses
    flux = s * (right - 0.5 * (1.0 - s) * slope[..., at(1)])
    return u + flux - flux[..., at(-1)]


def _mc_slope(forward: np.ndarray, backward: np.ndarray) -> np.ndarray:
    """Monotonized-central limited slope (per column): zero at an extremum."""
    same = forward * backward > 0.0
    mag = np.minimum(np.minimum(2.0 * np.abs(forward), 2.0 * np.abs(backward)),
                     0.5 * np.abs(forward + backward))
    return np.where(same, np.sign(forward) * mag, 0.0)
