"""Elastic half-space under a line (plane-strain) pressure, in Hertz units.

Two bodies of reduced modulus E' (2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2) pressed by a
pressure p(x) close their gap by v(x) = -(4 / (pi E')) int p(s) ln|x - s| ds + const
(Johnson, Contact Mechanics, 1985, Sec. 2.2). With x = b X, p = p_h P and the gap
h = (b^2 / R) H, where b = sqrt(8 w R / (pi E')) and p_h = 2 w / (pi b) are Hertz's
half-width and peak pressure (so p_h = E' b / (4 R)), this becomes

    V(X) = -(1/pi) int P(S) ln|X - S| dS,

the kernel of Venner & Lubrecht (Multilevel methods in lubrication, Elsevier 2000).
The pressure is taken piecewise constant on cells of width dX centred on the nodes; the
integral over each cell is exact, so V_i = sum_j K_{i-j} P_j with a Toeplitz kernel K,
applied as a zero-padded FFT convolution (N log N).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft
import scipy.linalg

from ._errors import ConvergenceError

__all__ = ["LineCompliance", "hertz_deflection", "dry_line_contact", "DryContact"]


def _t_log_t(t: np.ndarray) -> np.ndarray:
    """t ln|t| - t, the antiderivative of ln|t| (0 at t = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = t * np.log(np.abs(t)) - t
    return np.where(t == 0.0, 0.0, out)


@dataclass(frozen=True)
class LineCompliance:
    """Influence coefficients of a uniform grid of ``n`` nodes spaced ``dx`` (Hertz units).

    ``kernel[k]`` is the deflection at a node k cells away from a unit pressure on one
    cell: -(1/pi) int_{k dx - dx/2}^{k dx + dx/2} ln|t| dt.
    """

    n: int
    dx: float

    @property
    def kernel(self) -> np.ndarray:
        t = np.arange(self.n) * self.dx
        return -(_t_log_t(t + self.dx / 2) - _t_log_t(t - self.dx / 2)) / np.pi

    def deflection(self, P: np.ndarray) -> np.ndarray:
        """V = K P by FFT: the symmetric Toeplitz kernel embedded in a circulant of 2n."""
        k = self.kernel
        circ = np.concatenate([k, [0.0], k[:0:-1]])          # length 2n
        m = circ.size
        spectrum = scipy.fft.rfft(circ)
        return scipy.fft.irfft(spectrum * scipy.fft.rfft(P, m), m)[: self.n]

    def matrix(self) -> np.ndarray:
        """The dense n x n influence matrix dV/dP (for the Newton Jacobian)."""
        return scipy.linalg.toeplitz(self.kernel)


def hertz_deflection(X: np.ndarray) -> np.ndarray:
    """Exact V(X) of Hertz's pressure P = sqrt(1 - X^2) inside the contact, |X| <= 1:
    (1 + 2 ln 2)/4 - X^2/2 (from int_0^1 sqrt(1 - s^2) ln s ds = -(pi/8)(1 + 2 ln 2))."""
    X = np.asarray(X, float)
    if np.any(np.abs(X) > 1.0):
        raise ValueError("X must lie in the Hertz contact [-1, 1]")
    return (1.0 + 2.0 * np.log(2.0)) / 4.0 - X**2 / 2.0


@dataclass(frozen=True)
class DryContact:
    """The elastic contact alone in Hertz units: pressure P, gap H, rigid approach H0."""

    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int


def dry_line_contact(nodes: int, half_width: float = 1.5, max_iter: int = 100) -> DryContact:
    """Frictionless dry contact of a cylinder on a half-space under the Hertz load pi/2.

    Find P >= 0, H = H0 + X^2/2 + V(P) >= 0, P H = 0, dX sum P = pi/2 by a primal-dual
    active set on the dense influence matrix; the exact answer is P = sqrt(1 - X^2).
    """
    if not (isinstance(nodes, (int, np.integer)) and 8 <= nodes <= 6000):
        raise ValueError(f"nodes must be an integer in [8, 6000], got {nodes!r}")
    X = np.linspace(-half_width, half_width, nodes)
    dx = X[1] - X[0]
    K = LineCompliance(nodes, dx).matrix()
    contact = np.abs(X) < 1.0
    for iteration in range(1, max_iter + 1):
        c = np.flatnonzero(contact)
        # unknowns: P on the contact set and H0 (with the sign it enters H)
        A = np.zeros((c.size + 1, c.size + 1))
        A[:-1, :-1] = K[np.ix_(c, c)]
        A[:-1, -1] = 1.0
        A[-1, :-1] = dx
        rhs = np.concatenate([-X[c] ** 2 / 2, [np.pi / 2]])
        sol = np.linalg.solve(A, rhs)
        P = np.zeros(nodes)
        P[c] = sol[:-1]
        gap = sol[-1] + X**2 / 2 + K @ P
        new = (contact & (P > 0.0)) | (~contact & (gap < 0.0))
        if np.array_equal(new, contact):
            return DryContact(X, P, np.where(contact, 0.0, gap), float(sol[-1]), iteration)
        contact = new
    raise ConvergenceError(f"dry line contact: contact set not settled in {max_iter} iterations")
