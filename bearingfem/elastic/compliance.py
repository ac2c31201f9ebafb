"""Compliance of the film surface: nodal film pressure [Pa] -> nodal radial deflection [m].

The bush and its mesh are invariant under a turn by one film cell, so the compliance is
block-circulant in theta: the deflection at film node (j, l) under a unit pressure at
(j', k) depends on j - j' (mod n_theta) only. The ``n_z`` columns of one theta position
(``columns[j, l, k]``: response at (j, l) to a unit pressure at (0, k)) therefore carry
the whole operator; it is applied with an FFT in theta (cost n_theta log n_theta n_z^2),
and a film grid turned by the journal's attitude angle needs no rebuild: only the spacing
2 pi / n_theta matters. Deflection > 0 opens the gap (the surface moves radially outward).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..bearing import check_positive
from ..validation import check_int
from .bush import ElasticBush
from .fourier import fourier_columns
from .harmonic import HarmonicBlocks, banded_spectrum
from .liner import liner_columns
from .ring import ring_columns
from .solid import solid_columns, solid_system
from .surface import FilmGrid

__all__ = ["BushCompliance", "ReducedCompliance", "bush_compliance", "discretise"]

#: Aliases |q| <= ALIASES of each film harmonic summed by the Fourier solid
#: (:func:`.fourier.fourier_spectrum`); 0 is the trigonometric interpolation of the nodal
#: pressure (docs/elastic-bush.md has the measurement that chose it).
ALIASES = 0


def check_pressure(pressure, shape) -> np.ndarray:
    p = np.asarray(pressure, dtype=float)
    if p.shape != shape:
        raise ValueError(f"pressure must have the film grid's shape {shape}, got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError("pressure must be finite at every film node")
    return p


@dataclass(frozen=True, eq=False)
class BushCompliance:
    """The film surface's compliance of an :class:`ElasticBush` on an
    (n_theta x n_z)-node film grid.

    Attributes
    ----------
    stored : (n_theta, n_z, n_z) [m/Pa], the columns (see the module docstring); or
        (n_theta, n_z), their diagonals, where the axial slices do not couple (the ring,
        the liner): memory n_theta n_z, not n_theta n_z^2
    bush, radius, length : what it was built for ([m])
    """

    stored: np.ndarray
    bush: ElasticBush
    radius: float
    length: float

    @property
    def uncoupled(self) -> bool:
        """Whether the axial slices do not couple (only the columns' diagonals stored)."""
        return self.stored.ndim == 2

    @property
    def columns(self) -> np.ndarray:
        """(n_theta, n_z, n_z) [m/Pa], see the module docstring (made on each call where
        only the diagonals are stored)."""
        if self.uncoupled:
            return self.stored[:, :, None] * np.eye(self.stored.shape[1])
        return self.stored

    @property
    def shape(self) -> tuple[int, int]:
        """The film grid (n_theta, n_z) the operator acts on."""
        return self.stored.shape[:2]

    @property
    def spectrum(self) -> np.ndarray:
        """Block-diagonal form: ``spectrum[m]`` (n_z x n_z) acts on the m-th theta harmonic
        of the pressure (m = 0 .. n_theta // 2, numpy's rfft convention)."""
        if self.uncoupled:
            return np.fft.rfft(self.stored, axis=0)[:, :, None] * np.eye(self.shape[1])
        return np.fft.rfft(self.stored, axis=0)

    @cached_property
    def blocks(self) -> HarmonicBlocks:
        """The spectrum's real blocks (the bush is symmetric under theta -> -theta), banded
        in z where the kernel is local: the operator kept to :data:`~.harmonic.BAND_TOL`
        (relative, 2-norm; :mod:`.harmonic`). Built once, on demand."""
        return banded_spectrum(self.spectrum)

    def deflection(self, pressure) -> np.ndarray:
        """Nodal radial deflection [m] (n_theta, n_z) under nodal pressure [Pa]."""
        p = check_pressure(pressure, self.shape)
        if self.uncoupled:
            harmonics = np.fft.rfft(self.stored, axis=0) * np.fft.rfft(p, axis=0)
        else:
            harmonics = np.einsum("mlk,mk->ml", self.spectrum, np.fft.rfft(p, axis=0))
        return np.fft.irfft(harmonics, n=self.shape[0], axis=0)

    def matrix(self) -> np.ndarray:
        """The dense (N, N) compliance [m/Pa], N = n_theta n_z, node (j, l) at j n_z + l
        (the C order of the film arrays)."""
        n, nz = self.shape
        shift = (np.arange(n)[:, None] - np.arange(n)[None, :]) % n
        return self.columns[shift].transpose(0, 2, 1, 3).reshape(n * nz, n * nz)

    def reduced(self, n_vectors: int) -> "ReducedCompliance":
        """The best rank-``n_vectors`` approximation of the operator (Eckart-Young) as real
        orthonormal vectors: the largest singular triples (s, u, v) of the harmonic blocks,
        a harmonic 0 < m < n_theta / 2 giving two (its cosine and sine).

        In theta harmonic m the operator is Sum_i s_i phi_i psi_i^H with
        phi = u e^(i m theta_j) / sqrt(n_theta), psi likewise from v; with its conjugate
        (harmonic -m) that is s [a c^T + b d^T], a, b = sqrt(2) (Re, Im) phi and c, d from
        psi: two real orthonormal pairs of equal singular value."""
        n, nz = self.shape
        n_vectors = check_int("n_vectors", n_vectors, 1)
        if n_vectors > n * nz:
            raise ValueError(f"n_vectors must be <= n_theta n_z = {n * nz}, got {n_vectors}")
        u, s, vh = np.linalg.svd(self.spectrum)                  # (M, nz, nz), (M, nz)
        m = np.arange(s.shape[0])
        single = (m == 0) | (2 * m == n)                         # real harmonics
        weight = np.where(single, 1, 2)[:, None] * np.ones_like(s, dtype=int)
        order = np.argsort(-s, axis=None, kind="stable")
        order = order[np.cumsum(weight.ravel()[order]) <= n_vectors]
        harmonic, index = np.unravel_index(order, s.shape)
        wave = np.exp(2j * np.pi * np.outer(np.arange(n), harmonic) / n) / np.sqrt(n)
        # a real block's singular pair is real up to a common phase (LAPACK returns it real
        # here, so no test sees this line; it guards the real vectors against other builds)
        lead = u[harmonic, np.abs(u[harmonic, :, index]).argmax(axis=1), index]
        wave = wave * np.where(single[harmonic], np.conj(lead) / np.abs(lead), 1.0)
        phi = wave[:, None, :] * u[harmonic, :, index].T[None]          # (n, nz, kept)
        psi = wave[:, None, :] * vh[harmonic, index, :].conj().T[None]
        scale = np.where(single[harmonic], 1.0, np.sqrt(2.0))
        pairs = ~single[harmonic]
        left, right = (np.concatenate([a.real * scale, np.sqrt(2.0) * a.imag[..., pairs]],
                                      axis=2).reshape(n * nz, -1) for a in (phi, psi))
        singular = np.concatenate([s[harmonic, index], s[harmonic, index][pairs]])
        dropped = np.ones(s.shape, bool)
        dropped[harmonic, index] = False
        error = float(s[dropped].max() / s.max()) if dropped.any() else 0.0
        return ReducedCompliance(left, singular, right, (n, nz), error)


@dataclass(frozen=True, eq=False)
class ReducedCompliance:
    """A truncated compliance C_k = left diag(singular) right^T [m/Pa] on the film grid
    flattened in C order: ``n_vectors`` real orthonormal left (deflection) and right
    (pressure) vectors. ``operator_error`` = |C_k - C|_2 / |C|_2 = sigma_(k+1) / sigma_1.
    The left vectors are a Ritz basis for the deflection: w = left q.
    """

    left: np.ndarray
    singular: np.ndarray
    right: np.ndarray
    shape: tuple
    operator_error: float

    @property
    def n_vectors(self) -> int:
        return self.singular.size

    def deflection(self, pressure) -> np.ndarray:
        """Nodal radial deflection [m] from the retained vectors only (cost N k)."""
        p = check_pressure(pressure, self.shape).ravel()
        return (self.left @ (self.singular * (self.right.T @ p))).reshape(self.shape)


@dataclass(frozen=True)
class Discretisation:
    """The checked film grid, the bush under it (its outer radius resolved) and the bush
    mesh options (see :func:`bush_compliance`)."""

    bush: ElasticBush
    radius: float
    film: FilmGrid
    refine_theta: int
    refine_z: int
    n_radial: int
    grading: float


def discretise(bush, radius, length, n_theta, n_z, refine_theta=1, refine_z=None,
               n_radial=None, grading=4.0) -> Discretisation:
    """Check the arguments of :func:`bush_compliance` and fill in its defaults."""
    if not isinstance(bush, ElasticBush):
        raise ValueError(f"bush must be a bearingfem.ElasticBush, got {type(bush).__name__}")
    bush = bush.at_radius(radius)      # the default outer radius is R's
    radius = bush.check_inner_radius(radius)
    length = check_positive("length", length)
    n_theta = check_int("n_theta", n_theta, 8)
    n_z = check_int("n_z", n_z, 2)
    refine_theta = check_int("refine_theta", refine_theta, 1)
    arc = 2.0 * math.pi * radius / (n_theta * refine_theta)
    refine_z = check_int("refine_z", 1 if refine_z is None else refine_z, 1)
    grading = check_positive("grading", grading)
    if n_radial is None:
        # first cell of the graded map ~ (outer - R) ln g / (n (g - 1)): make it ~ arc
        g = math.log(grading)
        factor = g / math.expm1(g) if g else 1.0
        n_radial = max(2, math.ceil((bush.outer_radius - radius) * factor / arc - 1e-9))
    n_radial = check_int("n_radial", n_radial, 1)
    return Discretisation(bush, radius, FilmGrid(n_theta, n_z, length), refine_theta,
                          refine_z, n_radial, grading)


def bush_compliance(bush: ElasticBush, radius: float, length: float, n_theta: int,
                    n_z: int, refine_theta: int = 1, refine_z: int | None = None,
                    n_radial: int | None = None, grading: float = 4.0) -> BushCompliance:
    """Build the compliance of ``bush`` under a film of radius ``radius`` and ``length``
    [m] on a film grid of ``n_theta`` nodes around and ``n_z`` along (ends included).

    The bush mesh refines the film grid ``refine_theta`` times in theta (ring and 3-D
    solid) and ``refine_z`` times in z (the solids); ``n_radial`` cells cross the wall, growing outward to
    ``grading`` times the inner one. Defaults: inner cells about as deep radially as they
    are wide, axially one cell per film cell. The solid (``model="solid"``) is solved per
    theta harmonic on its (r, z) section (:mod:`.fourier`), exact in theta, so
    ``refine_theta`` does not enter it; ``"solid-3d"`` meshes the whole body (its cost is
    one 3-D sparse LU). The liner (``model="liner"``) has no mesh: its compliance is local
    (:mod:`.liner`).
    """
    d = discretise(bush, radius, length, n_theta, n_z, refine_theta, refine_z, n_radial,
                   grading)
    bush = d.bush
    if bush.model == "liner":
        columns = liner_columns(bush, d.radius, d.film)
    elif bush.model == "ring":
        columns = ring_columns(bush, d.radius, d.film, d.refine_theta, d.n_radial,
                               d.grading)
    elif bush.model == "solid":
        columns = fourier_columns(bush, d.radius, d.film, d.refine_z, d.n_radial,
                                  d.grading, ALIASES)
    else:
        system = solid_system(bush, d.radius, d.film, d.refine_theta, d.refine_z,
                              d.n_radial, d.grading)
        columns = solid_columns(system, d.film, d.refine_theta, d.refine_z)
    return BushCompliance(columns, bush, d.radius, length)
