"""Elastic half-space under a pressure on a plane (point contact), in Hertz units.

Two bodies of reduced modulus E' (2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2) pressed by p(x, y)
close their gap by v = (2 / (pi E')) int int p(s, t) / sqrt((x - s)^2 + (y - t)^2) ds dt
(Boussinesq; Johnson, Contact Mechanics, 1985, Sec. 3.2). With x = a X, p = p_h P and
h = (a^2 / R) H, where a = (3 w R / (2 E'))^(1/3) and p_h = 3 w / (2 pi a^2) are Hertz's
contact radius and peak pressure of a sphere of radius R (so p_h = E' a / (pi R)),

    V(X, Y) = (2 / pi^2) int int P(S, T) / |(X, Y) - (S, T)| dS dT,

the kernel of Venner & Lubrecht (Multilevel methods in lubrication, Elsevier 2000, Ch. 9).
P is piecewise constant on rectangular cells centred on the nodes; the deflection of a
uniform pressure on a rectangle is Love's (1929) closed form (Johnson Eq. 3.25), so
V_ij = sum_kl K_{i-k, j-l} P_kl exactly for that pressure, applied by a zero-padded 2-D FFT
convolution (DC-FFT: Liu, Wang & Liu, Wear 243 (2000) 101-111).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from ..errors import ConvergenceError

__all__ = ["PointCompliance", "hertz_point_deflection", "dry_point_contact", "DryPointContact",
           "HERTZ_POINT_LOAD"]

HERTZ_POINT_LOAD = 2.0 * math.pi / 3.0   # int int P dX dY of Hertz's P = sqrt(1 - r^2)


def _love(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """u ln(v + r) + v ln(u + r), r = sqrt(u^2 + v^2): its mixed derivative is 1/r, so its
    four-corner difference is int int 1/r over a rectangle (valid while no corner has
    u = 0 with v <= 0 or v = 0 with u <= 0, true at cell-centre offsets)."""
    r = np.hypot(u, v)
    return u * np.log(v + r) + v * np.log(u + r)


@dataclass(frozen=True)
class PointCompliance:
    """Influence coefficients of a uniform ``nx`` x ``ny`` grid spaced ``dx``, ``dy``
    (Hertz units; array index [i, j] is node (X_i, Y_j)).

    ``kernel[k, l]`` is the deflection at a node (k, l) cells away from a unit pressure on
    one cell: (2/pi^2) int int_cell 1/r.
    """

    nx: int
    ny: int
    dx: float
    dy: float

    @property
    def kernel(self) -> np.ndarray:
        x = np.arange(self.nx)[:, None] * self.dx
        y = np.arange(self.ny)[None, :] * self.dy
        a, b = self.dx / 2, self.dy / 2
        integral = (_love(x + a, y + b) - _love(x + a, y - b)
                    - _love(x - a, y + b) + _love(x - a, y - b))
        return 2.0 / math.pi**2 * integral

    def spectrum(self) -> np.ndarray:
        """rfft2 of the kernel mirrored into a (2 nx) x (2 ny) circulant (zero at index n:
        the padding that turns the cyclic product into the linear one)."""
        k = self.kernel
        kx = np.concatenate([k, np.zeros((1, self.ny)), k[:0:-1]], axis=0)
        circ = np.concatenate([kx, np.zeros((2 * self.nx, 1)), kx[:, :0:-1]], axis=1)
        return scipy.fft.rfft2(circ)

    def deflection(self, P: np.ndarray, spectrum: np.ndarray | None = None) -> np.ndarray:
        """V = K * P by DC-FFT (pass ``spectrum`` to reuse it)."""
        s = self.spectrum() if spectrum is None else spectrum
        shape = (2 * self.nx, 2 * self.ny)
        return scipy.fft.irfft2(s * scipy.fft.rfft2(P, shape), shape)[: self.nx, : self.ny]

    def matrix(self, rows: np.ndarray | None = None, cols: np.ndarray | None = None) -> np.ndarray:
        """Dense dV/dP between flat node indices (C order), all nodes by default."""
        k = self.kernel
        n = self.nx * self.ny
        rows = np.arange(n) if rows is None else np.asarray(rows)
        cols = np.arange(n) if cols is None else np.asarray(cols)
        ir, jr = np.divmod(rows, self.ny)
        ic, jc = np.divmod(cols, self.ny)
        return k[np.abs(ir[:, None] - ic[None, :]), np.abs(jr[:, None] - jc[None, :])]


def hertz_point_deflection(r: np.ndarray) -> np.ndarray:
    """Exact V of Hertz's P = sqrt(1 - r^2) inside the contact, r <= 1: 1 - r^2/2
    (Johnson Eq. 3.41 with p_h = E' a / (pi R)); so H0 = -1, the approach a^2/R."""
    r = np.asarray(r, float)
    if np.any(r > 1.0):
        raise ValueError("r must lie in the Hertz contact, r <= 1")
    return 1.0 - r**2 / 2.0


@dataclass(frozen=True)
class DryPointContact:
    """The elastic contact alone in Hertz units: nodes X, Y (1-D), pressure P[i, j], gap,
    rigid approach H0 (exact: -1), active-set iterations."""

    x: np.ndarray
    y: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int


def dry_point_contact(nodes: int, half_width: float = 1.5, max_iter: int = 100) -> DryPointContact:
    """Frictionless dry contact of a sphere on a half-space under Hertz's load 2 pi/3.

    Find P >= 0, H = H0 + r^2/2 + V(P) >= 0, P H = 0, dX dY sum P = 2 pi/3 on a square
    grid of ``nodes`` x ``nodes`` over [-half_width, half_width]^2, by a primal-dual active
    set with the dense influence matrix of the contact set; exactly P = sqrt(1 - r^2).
    """
    if isinstance(nodes, bool) or not isinstance(nodes, (int, np.integer)) or not 8 <= nodes <= 160:
        raise ValueError(f"nodes must be an integer in [8, 160], got {nodes!r}")
    if not (isinstance(half_width, (int, float)) and math.isfinite(half_width) and half_width > 1.0):
        raise ValueError(f"half_width must be a finite number > 1 [contact radii], got {half_width!r}")
    X = np.linspace(-half_width, half_width, nodes)
    d = X[1] - X[0]
    comp = PointCompliance(nodes, nodes, d, d)
    spec = comp.spectrum()
    r2 = (X[:, None] ** 2 + X[None, :] ** 2).ravel()
    contact = r2 < 1.0
    for iteration in range(1, max_iter + 1):
        c = np.flatnonzero(contact)
        A = np.empty((c.size + 1, c.size + 1))
        A[:-1, :-1] = comp.matrix(c, c)
        A[:-1, -1] = 1.0
        A[-1, :-1] = d * d
        A[-1, -1] = 0.0
        sol = np.linalg.solve(A, np.concatenate([-r2[c] / 2, [HERTZ_POINT_LOAD]]))
        P = np.zeros(nodes * nodes)
        P[c] = sol[:-1]
        gap = sol[-1] + r2 / 2 + comp.deflection(P.reshape(nodes, nodes), spec).ravel()
        new = (contact & (P > 0.0)) | (~contact & (gap < 0.0))
        if np.array_equal(new, contact):
            shape = (nodes, nodes)
            return DryPointContact(X, X.copy(), P.reshape(shape),
                                   np.where(contact, 0.0, gap).reshape(shape),
                                   float(sol[-1]), iteration)
        contact = new
    raise ConvergenceError("dry point contact (contact set)", max_iter)
