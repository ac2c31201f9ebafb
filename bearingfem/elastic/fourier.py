"""The solid bush per circumferential harmonic ("Fourier" finite elements of a body of
revolution): the 3-D hollow cylinder solved as one small 2-D problem per harmonic m on its
(r, z) section.

In harmonic m the displacement is u_r = U(r, z) cos m theta, u_theta = V(r, z) sin m theta,
u_z = W(r, z) cos m theta, and the strains are (cylindrical coordinates)

    eps_rr = U_r            eps_tt = (U + m V) / r      eps_zz = W_z      g_rz = U_z + W_r
    g_rt = -m U / r + V_r - V / r                       g_tz = V_z - m W / r

(the first four times cos m theta, the last two times sin m theta). The energy's theta
integral is pi for both parts (m > 0), so per unit pi the stiffness is
K_m = K_0 + m K_1 + m^2 K_2 (the strains are affine in m): three matrices assembled once.
At m = 0 the sine part is the torsion V, which the film's pressure does not load: held.
A pressure P(z) cos m theta on r = R (traction -p n = p e_r) does the work
R Int P dU dz per unit pi: the same load vector for every m. A rigid translation (m = 1:
U = 1, V = -1, W = 0) and a rigid tilt (m = 1: U = z, V = -z, W = -r) strain nothing
(tested).

Each harmonic is one banded Cholesky factorisation (band ~ 3 (n_radial + 1)) and one
triangular band solve for the surface block of K_m^-1: the block G_m (n_z x n_z) of
radial deflection at the film nodes under a unit pressure hat at each film node's z,
times cos m theta. Harmonic m's field decays into the wall within a few R / m, so it is
solved on the radial lines above the depth :data:`DECAY` R / m only. From m = 16 on, the
blocks are interpolated per octave of harmonics from a few solved at Chebyshev points
(:data:`OCTAVES`; m G_m is analytic in a real m): the band solves are ~16 + 13 log2(n_theta
/ 32), not n_theta / 2 + 1.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.linalg.blas import dsyrk
from scipy.linalg.lapack import dpbtrf, dtbtrs
from skfem import (Basis, BilinearForm, ElementQuad1, ElementVector, FacetBasis,
                   MeshQuad1, asm)

from ..validation import check_int
from .mesh import radial_lines
from .surface import FilmGrid

__all__ = ["Banded", "SectionSystem", "section_system", "harmonic_blocks",
           "fourier_spectrum", "fourier_columns", "DECAY"]


def _strains(u, r):
    """The m-free part A and the m-coefficient B of the six engineering strains
    (rr, tt, zz, rz, rt, tz) of a harmonic displacement (U, V, W)."""
    U, V, W, g = u[0], u[1], u[2], u.grad
    zero = 0.0 * U
    a = (g[0][0], U / r, g[2][1], g[0][1] + g[2][0], g[1][0] - V / r, g[1][1])
    b = (zero, V / r, zero, zero, -U / r, -W / r)
    return a, b


def _energy(lam, mu, e, f, r):
    """r-weighted isotropic energy product of two strain sextuples."""
    return r * (lam * (e[0] + e[1] + e[2]) * (f[0] + f[1] + f[2])
                + 2.0 * mu * (e[0] * f[0] + e[1] * f[1] + e[2] * f[2])
                + mu * (e[3] * f[3] + e[4] * f[4] + e[5] * f[5]))


def harmonic_forms(lam: float, mu: float):
    """The three bilinear forms K_0, K_1, K_2 of K_m = K_0 + m K_1 + m^2 K_2."""
    @BilinearForm
    def k0(u, v, w):
        r = w.x[0]
        return _energy(lam, mu, _strains(u, r)[0], _strains(v, r)[0], r)

    @BilinearForm
    def k1(u, v, w):
        r = w.x[0]
        (ua, ub), (va, vb) = _strains(u, r), _strains(v, r)
        return _energy(lam, mu, ua, vb, r) + _energy(lam, mu, ub, va, r)

    @BilinearForm
    def k2(u, v, w):
        r = w.x[0]
        return _energy(lam, mu, _strains(u, r)[1], _strains(v, r)[1], r)

    return k0, k1, k2


#: Groups of surface columns solved apart in :meth:`Banded.block`.
CHUNKS = 4


@dataclass(frozen=True, eq=False)
class Banded:
    """K_0, K_1, K_2 on the free dofs of one set of held dofs, in LAPACK's upper band
    storage (``bands``: (3, b + 1, n_free)); the unit columns of the inner surface's U
    dofs (``unit``: (n_free, n_s)), the load on them (``load``: (n_s, n_z), the film's
    hats, zero elsewhere) and the film nodes among them (``read``)."""

    bands: np.ndarray
    unit: np.ndarray
    load: np.ndarray
    read: np.ndarray

    @cached_property
    def starts(self) -> np.ndarray:
        """The row of each surface column's unit entry (increasing: z order)."""
        return np.argmax(self.unit, axis=0)

    def block(self, m: int) -> np.ndarray:
        """G_m (n_z, n_z) [m/Pa]: U at film node l under the unit hat load of node k.

        With K_m = C^T C (banded Cholesky), the surface block of K_m^-1 is Y^T Y,
        Y = C^-T E_s (E_s: the surface dofs' unit columns): triangular band solves,
        under half the work of a full solve with n_z right-hand sides."""
        band = self.bands[0] + m * self.bands[1] + (m * m) * self.bands[2]
        factor, info = dpbtrf(band, overwrite_ab=1)
        if info != 0:                        # held outer surface: K_m is positive definite
            raise ValueError(f"the section's stiffness of harmonic {m} is not positive "
                             f"definite (LAPACK dpbtrf info {info})")
        # column j of Y is zero above its dof (C^T is lower triangular): solve each group
        # of columns on the trailing rows from its first dof only (5/8 of the work)
        y = np.zeros_like(self.unit)
        starts = self.starts
        for group in np.array_split(np.arange(starts.size), CHUNKS):
            if group.size:
                first = starts[group[0]]
                y[first:, group], _ = dtbtrs(factor[:, first:], self.unit[first:, group],
                                             uplo="U", trans="T")
        # Y^T Y by BLAS syrk (its upper triangle: half the flops of the product)
        gram = dsyrk(1.0, y.T)
        gram = np.triu(gram) + np.triu(gram, 1).T
        return gram[self.read] @ self.load


def banded(stiffness, load, held, surface, read, rank) -> Banded:
    """The free dofs (not ``held``) ordered by ``rank`` (radial layers fastest: a band of
    about 3 (n_radial + 1) on the structured section) in band storage."""
    free = np.setdiff1d(np.arange(load.shape[0]), held)
    free = free[np.argsort(rank[free], kind="stable")]
    position = np.empty(load.shape[0], int)
    position[free] = np.arange(free.size)
    kept = [k[free][:, free].tocoo() for k in stiffness]
    width = max(int(np.max(k.col - k.row, initial=0)) for k in kept)
    bands = np.zeros((3, width + 1, free.size))
    for band, k in zip(bands, kept):
        upper = k.col >= k.row
        band[width + k.row[upper] - k.col[upper], k.col[upper]] = k.data[upper]
    unit = np.zeros((free.size, surface.size))
    unit[position[surface], np.arange(surface.size)] = 1.0
    return Banded(bands, unit, load[surface], read)


@dataclass(frozen=True, eq=False)
class SectionSystem:
    """The (r, z) section of the bush: K_0, K_1, K_2 (sparse, all dofs), the film's load
    (dofs, n_z), the dofs held (``held``; at m = 0 ``torsion``, V held as well), the inner
    surface's U dofs (increasing z) and the film nodes among them (``read``), each dof's
    band rank and radial line, and the radial lines' depth below the film [m];
    ``decay`` the depth rule (:data:`DECAY`) and ``octave`` the Chebyshev points per octave
    of interpolated harmonics (:data:`OCTAVES`; None for both: every harmonic solved on
    the whole wall)."""

    stiffness: tuple
    load: np.ndarray
    held: np.ndarray
    torsion: np.ndarray
    surface: np.ndarray
    read: np.ndarray
    rank: np.ndarray
    radial: np.ndarray
    depth: np.ndarray
    radius: float
    decay: float | None
    octave: int | None = None

    def lines(self, m: int) -> int:
        """Radial lines harmonic m is solved on: those above the depth ``decay`` R / m
        and the first below it, held (all of them for m = 0 or ``decay=None``)."""
        if m == 0 or self.decay is None:
            return self.depth.size
        reach = self.decay * self.radius / m
        return int(min(self.depth.size, np.searchsorted(self.depth, reach) + 1))

    def banded(self, m: int) -> Banded:
        """The band system of harmonic m (its held dofs and depth)."""
        held = self.torsion if m == 0 else self.held
        deep = np.flatnonzero(self.radial >= self.lines(m) - 1)
        if self.lines(m) < self.depth.size:
            held = np.union1d(held, deep)
        return banded(self.stiffness, self.load, held, self.surface, self.read, self.rank)

    def block(self, m: int) -> np.ndarray:
        """G_m (n_z, n_z) [m/Pa]: U at film node l under the unit hat load of node k
        (the film pressure P_k(z) cos m theta): one banded Cholesky factorisation (K_m is
        symmetric positive definite once the outer surface is held)."""
        return self.banded(m).block(m)

    def blocks(self, harmonics) -> np.ndarray:
        """G_m (len(harmonics), n_z, n_z) [m/Pa]: those below :data:`OCTAVE_FROM` (all of
        them with ``octave=None``) solved, harmonics of one depth sharing their band
        system; the others interpolated per octave (:meth:`octave_blocks`)."""
        harmonics = np.array([int(m) for m in harmonics], dtype=int)
        out = np.empty((harmonics.size, self.read.size, self.load.shape[1]))
        solved = (harmonics < OCTAVE_FROM if self.octave is not None
                  else np.ones(harmonics.size, bool))
        done, a = solved.copy(), OCTAVE_FROM
        while not done.all():
            chosen = ~done & (harmonics < 2 * a)
            if np.unique(harmonics[chosen]).size > self.octave:
                out[chosen] = self.octave_blocks(harmonics[chosen], a)
            else:                                   # fewer harmonics than points: solved
                solved |= chosen
            done |= chosen
            a *= 2
        key = [(m == 0, self.lines(m)) for m in harmonics[solved]]
        index = np.flatnonzero(solved)
        for level in set(key):
            chosen = [i for i, k in zip(index, key) if k == level]
            system = self.banded(harmonics[chosen[0]])
            for i in chosen:
                out[i] = system.block(harmonics[i])
        return out

    def octave_blocks(self, harmonics: np.ndarray, low: int) -> np.ndarray:
        """G_m of the ``harmonics`` in the octave [low, 2 low) by interpolation: m G_m is
        an analytic function of a real m (K_m = K_0 + m K_1 + m^2 K_2 is positive definite
        for every real m >= 0), solved at ``octave`` Chebyshev points of [low, top] (top
        the largest harmonic asked for) on the depth of ``low`` (the deepest of the
        octave) and evaluated by the barycentric formula. Measured on the seed pin's bush
        (docs/elastic-bush.md), per octave, of the operator's 2-norm: 11 points 1e-16 ..
        3.1e-9, 15 points 4e-17 .. 3.4e-12 (spectral convergence in the points)."""
        top = int(harmonics.max())
        k = self.octave - 1
        points = 0.5 * (low + top) + 0.5 * (top - low) * np.cos(np.pi * np.arange(k + 1) / k)
        system = self.banded(low)
        values = np.array([x * system.block(x) for x in points])       # m G_m
        weight = (-1.0) ** np.arange(k + 1)
        weight[[0, -1]] *= 0.5
        gap = harmonics[:, None] - points[None, :]
        exact = gap == 0.0
        with np.errstate(divide="ignore"):
            c = np.where(exact.any(axis=1, keepdims=True), exact * 1.0, weight / gap)
        c /= c.sum(axis=1, keepdims=True) * harmonics[:, None]
        return np.tensordot(c, values, axes=1)


#: Harmonics below this are solved one by one; from it on, per octave [a, 2 a) by
#: interpolation at :data:`OCTAVES` Chebyshev points (:meth:`SectionSystem.octave_blocks`).
OCTAVE_FROM = 16
#: Chebyshev points per octave of harmonics (None: every harmonic solved).
OCTAVES = 13


#: Depth, in R / m, below which harmonic m is held (its field decays like
#: (1 + m d / R) e^(-m d / R) with the depth d: 2e-6 at 16); None solves every harmonic
#: on the whole wall. Measured in docs/elastic-bush.md.
DECAY = 16.0


def section_system(bush, radius: float, film: FilmGrid, refine_z: int, n_radial: int,
                   grading: float, decay: float | None = DECAY,
                   octave: int | None = OCTAVES) -> SectionSystem:
    """Assemble the section of ``bush`` under the film grid: bilinear quadrilaterals,
    ``n_radial`` cells across the wall (graded as the 3-D solid's), ``refine_z`` cells
    per film cell along z; ``decay`` and ``octave`` as :class:`SectionSystem`'s."""
    if octave is not None:
        octave = check_int("octave", octave, 2)
    radii = radial_lines(radius, bush.outer_radius, n_radial, grading)
    heights = np.linspace(-0.5 * film.length, 0.5 * film.length,
                          (film.n_z - 1) * refine_z + 1)
    mesh = MeshQuad1.init_tensor(radii, heights)
    element = ElementVector(ElementQuad1(), dim=3)
    # the 1/r of the hoop strains is smooth on r >= R > 0: one order above the full
    # 2 x 2 rule keeps the weighted integrand's error below the element's
    basis = Basis(mesh, element, intorder=3)
    stiffness = tuple(asm(form, basis).tocsr() for form in harmonic_forms(*bush.lame))
    r, z = mesh.p
    tol = 1e-9 * (bush.outer_radius - radius)
    inner = mesh.facets_satisfying(lambda x: np.abs(x[0] - radius) < tol)
    facets = FacetBasis(mesh, element, facets=inner, intorder=4)

    @BilinearForm
    def traction(u, v, w):
        # the film pushes the bush outward: traction -p n = p e_r (n = -e_r on r = R)
        return u[0] * v[0] * w.x[0]

    inner_nodes = np.flatnonzero((np.abs(r - radius) < tol))
    inner_nodes = inner_nodes[np.argsort(z[inner_nodes])]
    surface = basis.nodal_dofs[0, inner_nodes]             # increasing z
    # the film's hats are linear between its nodes, so P1 on the section's surface
    # nodes (refine_z whole): their loads are one surface mass times their nodal values
    dz = film.length / (film.n_z - 1)
    hats = np.maximum(0.0, 1.0 - np.abs(z[inner_nodes][:, None] - film.heights) / dz)
    rhs = np.asarray(asm(traction, facets).tocsc()[:, surface] @ hats)
    outer = np.abs(r - bush.outer_radius) < tol
    held = [basis.nodal_dofs[:, outer].ravel()]
    if bush.ends == "plane-strain":
        ends = np.abs(np.abs(z) - 0.5 * film.length) < 1e-9 * film.length
        held.append(basis.nodal_dofs[2, ends])
    held = np.unique(np.concatenate(held))
    read = np.arange(0, surface.size, refine_z)             # film nodes among them
    # dof rank: axial layer, then radial layer, then component
    layer = np.searchsorted(heights, z - 1e-9 * film.length)
    line = np.searchsorted(radii, r - tol)
    node_rank = (layer * radii.size + line) * 3
    rank, radial = np.empty(basis.N, int), np.empty(basis.N, int)
    for c in range(3):
        rank[basis.nodal_dofs[c]] = node_rank + c
        radial[basis.nodal_dofs[c]] = line
    torsion = np.union1d(held, basis.nodal_dofs[1])
    return SectionSystem(stiffness, rhs, held, torsion, surface, read, rank, radial,
                         radii - radius, radius, decay, octave)


def harmonic_blocks(system: SectionSystem, harmonics) -> np.ndarray:
    """G_m (len(harmonics), n_z, n_z) [m/Pa] for each harmonic m >= 0."""
    return system.blocks(harmonics)


def fourier_spectrum(system: SectionSystem, n_theta: int,
                     aliases: int | None) -> np.ndarray:
    """The film grid's spectrum (n_theta // 2 + 1, n_z, n_z) [m/Pa] (numpy's rfft
    convention, that of :attr:`~.compliance.BushCompliance.spectrum`).

    The film's nodal pressure is P1 in theta (hat of width 2 pi / n_theta): its harmonic k
    is the nodal DFT's harmonic k mod n_theta times sinc^2(k / n_theta), so the deflection
    at the nodes has S[m] = Sum_q sinc^2(m / n + q) G_|m + q n| (the aliases q of the
    nodal harmonic m), summed here over |q| <= ``aliases``. ``aliases=None``: S[m] = G_m,
    the response to the nodal pressure's trigonometric interpolant (both tend to the
    continuum's response as the film grid is refined)."""
    m = np.arange(n_theta // 2 + 1)
    if aliases is None:
        return harmonic_blocks(system, m)
    q = np.arange(-aliases, aliases + 1)
    k = np.abs(m[:, None] + q[None, :] * n_theta)                # (M, 2Q + 1)
    weight = np.sinc(m[:, None] / n_theta + q[None, :]) ** 2
    needed, index = np.unique(k, return_inverse=True)
    blocks = harmonic_blocks(system, needed)
    return np.einsum("mq,mqlk->mlk", weight, blocks[index.reshape(k.shape)])


def fourier_columns(bush, radius: float, film: FilmGrid, refine_z: int, n_radial: int,
                    grading: float, aliases: int | None) -> np.ndarray:
    """Compliance columns (n_theta, n_z, n_z) [m/Pa] of the solid bush (see
    :mod:`.compliance`): the inverse real FFT of :func:`fourier_spectrum`."""
    system = section_system(bush, radius, film, refine_z, n_radial, grading,
                            octave=OCTAVES)
    spectrum = fourier_spectrum(system, film.n_theta, aliases)
    return np.fft.irfft(spectrum, n=film.n_theta, axis=0)
