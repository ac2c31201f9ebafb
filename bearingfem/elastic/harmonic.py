"""The bush's compliance per theta harmonic, stored where it is not negligible.

An axisymmetric bush's film compliance is one (n_z x n_z) block S_m per theta harmonic m
(:attr:`~.compliance.BushCompliance.spectrum`); the bush is also symmetric under
theta -> -theta, so each block is real (its imaginary part is round-off). Harmonic m's
field decays into the wall and along z over ~R / m, so the blocks of the high harmonics
are local in z: their entries fall exponentially with |z_l - z_k| m / R. Kept on the band
|l - k| <= w_m they cost n_z (2 w_m + 1) numbers instead of n_z^2, and the band is chosen
per harmonic so that the dropped part E_m obeys

    |E_m|_2 <= sqrt(|E_m|_1 |E_m|_inf) <= tol |S|_2        (every m)

with |S|_2 = max_m |S_m|_2 the compliance's norm (bounded from below by the largest
entry and |S_m 1| / sqrt(n_z), so the bound holds as stated). The FFT in theta is unitary,
so the whole operator's relative error in the 2-norm is at most ``tol``:
:attr:`HarmonicBlocks.error` is the bound reached.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["HarmonicBlocks", "banded_spectrum", "BAND_TOL"]

#: Relative 2-norm error allowed in the compliance by :func:`banded_spectrum`.
BAND_TOL = 1e-10


@dataclass(frozen=True, eq=False)
class HarmonicBlocks:
    """Real blocks of harmonics m = 0 .. M - 1 [m/Pa]: the first ``dense.shape[0]`` dense
    ((m, n_z, n_z)), the rest as one block-diagonal sparse matrix ``banded`` (harmonic
    m_dense + i on rows and columns i n_z .. (i + 1) n_z), each on its band ``width[m]``
    (n_z - 1: all of it); ``error`` bounds the relative 2-norm error of the operator."""

    dense: np.ndarray
    banded: sp.csr_matrix
    width: np.ndarray
    error: float

    @property
    def shape(self) -> tuple[int, int]:
        """(M, n_z): the harmonics and the axial nodes."""
        return self.width.size, self.dense.shape[1]

    def apply(self, harmonics: np.ndarray) -> np.ndarray:
        """S_m x_m for each harmonic m of ``harmonics`` ((M, n_z, ...), complex): the real
        blocks act on the real and imaginary parts at once (one BLAS product per dense
        block, one sparse product for the banded)."""
        M, nz = self.shape
        x = np.ascontiguousarray(harmonics, dtype=complex).reshape(M, nz, -1).view(float)
        out = np.empty_like(x)
        k = self.dense.shape[0]
        np.matmul(self.dense, x[:k], out=out[:k])
        out[k:] = (self.banded @ x[k:].reshape(-1, x.shape[2])).reshape(out[k:].shape)
        return out.view(complex).reshape(harmonics.shape)

    def toarray(self) -> np.ndarray:
        """The blocks (M, n_z, n_z) with the band's dropped entries zero."""
        M, nz = self.shape
        k = self.dense.shape[0]
        out = np.zeros((M, nz, nz))
        out[:k] = self.dense
        b = self.banded.tocoo()
        out[k + b.row // nz, b.row % nz, b.col % nz] = b.data
        return out

    @property
    def nbytes(self) -> int:
        """The stored numbers' memory [bytes]."""
        b = self.banded
        return self.dense.nbytes + b.data.nbytes + b.indices.nbytes + b.indptr.nbytes


def band_widths(blocks: np.ndarray, bound: float) -> tuple[np.ndarray, np.ndarray]:
    """The least half-band w_m of each real block (M, n, n) whose dropped part E_m has
    sqrt(|E_m|_1 |E_m|_inf) <= ``bound``, and that norm bound. The tails are summed
    from the outermost offset inward (vectorised over the harmonics)."""
    M, n, _ = blocks.shape
    a = np.abs(blocks)
    row, col = np.zeros((M, n)), np.zeros((M, n))
    width, reached = np.full(M, n - 1), np.zeros(M)
    for d in range(n - 1, -1, -1):
        # row and col hold the sums over offsets > d: is the band |l - k| <= d enough?
        tail = np.sqrt(row.max(axis=1) * col.max(axis=1))
        ok = tail <= bound
        width = np.where(ok, d, width)
        reached = np.where(ok, tail, reached)
        if d == 0 or not ok.any():
            break
        upper, lower = np.diagonal(a, d, 1, 2), np.diagonal(a, -d, 1, 2)
        row[:, :n - d] += upper
        row[:, d:] += lower
        col[:, d:] += upper
        col[:, :n - d] += lower
    return width, reached


def banded_spectrum(spectrum: np.ndarray, tol: float | None = None) -> HarmonicBlocks:
    """The real blocks of ``spectrum`` ((M, n_z, n_z); its imaginary part, round-off of
    the bush's theta -> -theta symmetry, dropped) on the bands that keep the operator
    within ``tol`` (relative, 2-norm; None: :data:`BAND_TOL`); a harmonic whose band holds
    more than half its block, and every one before it, is stored dense."""
    tol = BAND_TOL if tol is None else tol
    if not 0.0 <= tol < 1.0:
        raise ValueError(f"tol must be in [0, 1), got {tol}")
    blocks = np.ascontiguousarray(np.real(spectrum), dtype=float)
    M, nz, _ = blocks.shape
    norm = max(float(np.abs(blocks).max(initial=0.0)),
               float(np.linalg.norm(blocks.sum(axis=2), axis=1).max(initial=0.0))
               / np.sqrt(nz))
    width, reached = band_widths(blocks, tol * norm)
    wide = np.flatnonzero(2 * width + 1 > nz / 2)
    k = int(wide[-1]) + 1 if wide.size else 0
    width[:k] = nz - 1
    reached[:k] = 0.0
    l, j = np.arange(nz)[:, None], np.arange(nz)[None, :]
    m, row, column = np.nonzero(np.abs(l - j)[None] <= width[k:, None, None])
    banded = sp.csr_matrix((blocks[k + m, row, column], (m * nz + row, m * nz + column)),
                           shape=((M - k) * nz, (M - k) * nz))
    error = float(reached.max(initial=0.0) / norm) if norm > 0 else 0.0
    return HarmonicBlocks(blocks[:k].copy(), banded, width, error)
