"""Heat conduction in the bush: the steady heat equation on the elastic bush's mesh.

    -div(k grad T) = 0                      in the bush, R <= r <= R_o
    k dT/dn = q(theta, z)                   on the inner surface (the film's heat into it)
    -k dT/dn = h_o (T - T_a)                on the outer surface (convection to the ambient)
    dT/dn = 0                               on the end faces (solid model)

(n the bush's outward normal: on the inner surface it points into the film, so
k dT/dn = -k dT/dr = q, the heat flowing outward through the wall.)

k the bush's conductivity [W/(m K)], h_o the outer heat-transfer coefficient
[W/(m^2 K)], T_a the ambient temperature [K], q the heat flux into the bush [W/m^2].
Trilinear hexahedra on the solid's hollow cylinder (:func:`~bearingfem.elastic.mesh.
cylinder_mesh`) or bilinear quadrilaterals on the ring's annulus (per unit length,
:func:`~bearingfem.elastic.mesh.annulus_mesh`), scikit-fem's Laplace form and facet
integrals. Verified against radial conduction through a cylinder wall (closed form,
:func:`radial_conduction`) and by its heat balance (heat in = heat out to round-off: the
rows of the assembled system summed with v = 1).

Coupled to the film's energy equation (:func:`bush_wall`, used by
:func:`~bearingfem.thermal.energy.solve_energy`): the film loses q = H (T - T_w) [W/m^2]
to the inner surface, T_w the bush's inner temperature there. The bush is linear and
its mesh invariant under a turn by one cell, so its inner surface's response to nodal
heat loads is block-circulant in theta: ``n_axial + 1`` solves with its factorised
matrix (one for the ring) give every column, applied by an FFT in theta
(:class:`BushResponse`). The film's quadrature points and the bush's inner nodes are
joined by the angle-and-z-linear interpolation of the inner nodal temperatures
(``transfer``, :func:`bush_wall`); its transpose, weighted by the film's quadrature,
loads the bush with the film's heat, so the heat the film gives is the heat the bush
takes, to round-off, on any pair of meshes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu
from skfem import (Basis, BilinearForm, ElementHex1, ElementQuad1, FacetBasis, LinearForm,
                   solve)
from skfem.models.poisson import laplace

from ..bearing import check_positive
from ..caches import cached
from ..elastic import ElasticBush
from ..elastic.mesh import BushMesh, annulus_mesh, cylinder_mesh
from .spec import BushConduction

__all__ = ["BushHeat", "bush_heat", "radial_conduction", "BushResponse", "bush_response",
           "BushWall", "bush_wall"]


@BilinearForm
def _robin(u, v, w):
    return w["h"] * u * v


@LinearForm
def _flux(v, w):
    return w["q"] * v


@dataclass(frozen=True, eq=False)
class BushHeat:
    """The bush's temperature [K] at the nodes of ``mesh`` (a :class:`BushMesh`), the heat
    into it through the inner surface and out through the outer one [W] (per metre of
    length for the ring), and the inner surface's mean temperature [K]."""

    mesh: BushMesh
    temperature: np.ndarray
    heat_in: float
    heat_out: float
    inner_mean: float

    def at_radius(self, index: int) -> np.ndarray:
        """Nodal temperatures on the cell layer ``index`` (0: the inner surface)."""
        return self.temperature[self.mesh.radial == index]


def _facets(bm: BushMesh, layer: int) -> np.ndarray:
    facets = bm.mesh.boundary_facets()
    return facets[np.all(bm.radial[bm.mesh.facets[:, facets]] == layer, axis=0)]


def _system(solid: bool, R: float, outer_radius: float, length: float, k: float,
            h: float, n_theta: int, n_radial: int, n_axial: int, grading: float):
    """(mesh, basis, inner and outer facet bases, the matrix k Laplace + h_o Robin) of
    the bush; the ring's per unit length."""
    if solid:
        bm = cylinder_mesh(R, outer_radius, length, n_theta, n_radial, n_axial, grading)
        elem = ElementHex1()
    else:
        bm = annulus_mesh(R, outer_radius, n_theta, n_radial, grading)
        elem = ElementQuad1()
    basis = Basis(bm.mesh, elem)
    outer = FacetBasis(bm.mesh, elem, facets=_facets(bm, bm.radii.size - 1))
    inner = FacetBasis(bm.mesh, elem, facets=_facets(bm, 0))
    A = k * laplace.assemble(basis) + _robin.assemble(outer, h=h)
    return bm, basis, inner, outer, A


def bush_heat(bush: ElasticBush, radius: float, length: float, *, conductivity: float,
              outer_coefficient: float, ambient_temperature: float, inner_flux,
              n_theta: int = 48, n_radial: int = 8, n_axial: int = 8,
              grading: float = 1.0) -> BushHeat:
    """The bush's steady temperature (module docstring).

    Parameters
    ----------
    bush : :class:`~bearingfem.elastic.ElasticBush` (its ``outer_radius``; ``model``
        "solid" meshes the hollow cylinder, "ring" or "liner" the annulus per unit length)
    radius, length : the film's radius R and length [m]
    conductivity : k [W/(m K)], > 0
    outer_coefficient : h_o [W/(m^2 K)], > 0 (some heat must leave)
    ambient_temperature : T_a [K], > 0
    inner_flux : q [W/m^2] into the bush: a number, or a function q(theta, z) of the
        inner surface's angle [rad] and axial place [m] (z = 0 for the ring)
    n_theta, n_radial, n_axial, grading : the mesh (:mod:`bearingfem.elastic.mesh`)
    """
    bush = bush.at_radius(radius)      # the default outer radius is R's
    R = bush.check_inner_radius(radius)
    k = check_positive("conductivity", conductivity)
    h = check_positive("outer_coefficient", outer_coefficient)
    ta = check_positive("ambient_temperature", ambient_temperature)
    bm, basis, inner, outer, A = _system(
        bush.model == "solid", R, bush.outer_radius, check_positive("length", length), k, h,
        n_theta, n_radial, n_axial, grading)
    x = inner.global_coordinates()
    theta = np.arctan2(x[1], x[0])
    z = x[2] if x.shape[0] == 3 else np.zeros_like(theta)
    q = inner_flux(theta, z) if callable(inner_flux) else \
        np.full_like(theta, float(inner_flux))
    if not np.all(np.isfinite(q)):
        raise ValueError("inner_flux must be finite on the inner surface")
    b = _flux.assemble(inner, q=q) + _flux.assemble(outer, q=h * ta)
    T = solve(A, b)
    heat_in = float(np.sum(q * inner.dx))
    heat_out = float(np.sum(h * (np.asarray(outer.interpolate(T)) - ta) * outer.dx))
    area = float(np.sum(inner.dx))
    inner_mean = float(np.sum(np.asarray(inner.interpolate(T)) * inner.dx)) / area
    return BushHeat(bm, T, heat_in, heat_out, inner_mean)


@dataclass(frozen=True, eq=False)
class BushResponse:
    """The conducting bush on its mesh, built once (:func:`bush_response`): the matrix
    k Laplace + h_o Robin (times the length for the ring, so that loads are in W),
    factorised, and the inner surface's response to nodal heat loads as the FFT in theta
    of its block-circulant columns (``spectrum[m, l, k]``: the temperature rise at axial
    node l of harmonic m under a unit load at axial node k)."""

    spec: BushConduction
    mesh: BushMesh
    basis: object
    outer: object              # the outer surface's FacetBasis
    inner: object              # the inner surface's FacetBasis
    matrix: sp.csr_matrix
    lu: object
    spectrum: np.ndarray
    scale: float               # the length for the ring (per-length matrix), 1 for the solid

    @property
    def shape(self) -> tuple:
        """(angles, axial nodes) of the inner surface's nodes."""
        return self.mesh.angles.size, max(self.mesh.heights.size, 1)

    def inner_response(self, loads: np.ndarray) -> np.ndarray:
        """The inner nodes' temperature rise above the ambient [K] under nodal heat
        ``loads`` [W] into them (both in the inner nodes' order: angle-major, then z)."""
        n, m = self.shape
        g = np.fft.rfft(np.asarray(loads).reshape(n, m), axis=0)
        return np.fft.irfft(np.einsum("mlk,mk->ml", self.spectrum, g), n=n,
                            axis=0).ravel()

    def field(self, loads: np.ndarray, ambient_temperature: float) -> BushHeat:
        """The whole bush's :class:`BushHeat` under inner nodal heat ``loads`` [W] (the
        inner mean taken over the nodes' shares of the loads' surface, i.e. by the
        inner facets)."""
        n_inner = loads.size
        b = np.zeros(self.matrix.shape[0])
        b[:n_inner] = loads
        T = ambient_temperature + self.lu.solve(b)
        h = self.spec.outer_coefficient
        heat_out = self.scale * float(np.sum(h * (np.asarray(self.outer.interpolate(T))
                                                   - ambient_temperature) * self.outer.dx))
        inner = self.inner
        area = float(np.sum(inner.dx))
        inner_mean = float(np.sum(np.asarray(inner.interpolate(T)) * inner.dx)) / area
        return BushHeat(self.mesh, T, float(np.sum(loads)), heat_out, inner_mean)


@cached(maxsize=8)
def bush_response(spec: BushConduction, radius: float, length: float, n_theta: int,
                  n_axial: int) -> BushResponse:
    """The :class:`BushResponse` of ``spec`` around a film of radius R and length L [m]
    on ``n_theta`` x ``n_axial`` cells of the inner surface (the spec's own sizes first);
    cached. Why columns: the response is dense on the inner surface (n_theta (n_axial +
    1) nodes), but circulant in theta, so n_axial + 1 solves build it and an FFT applies
    it (docs/thd.md, "The bush's conduction")."""
    bush = spec.bush.at_radius(radius)      # the default outer radius is R's
    R = bush.check_inner_radius(radius)
    n_theta = spec.n_theta or n_theta
    n_axial = spec.n_axial or n_axial
    bm, basis, inner, outer, A = _system(spec.solid, R, bush.outer_radius, length,
                                     spec.conductivity, spec.outer_coefficient, n_theta,
                                     spec.n_radial, n_axial, spec.grading)
    scale = 1.0 if spec.solid else float(length)
    A = (scale * A).tocsc()
    lu = splu(A)
    n, m = bm.angles.size, max(bm.heights.size, 1)
    # the inner nodes are the first n * m (radial-major numbering), angle-major then z
    assert np.all(bm.radial[:n * m] == 0) and np.all(bm.angular[:n * m] == np.repeat(
        np.arange(n), m))
    E = np.zeros((A.shape[0], m))
    E[np.arange(m), np.arange(m)] = 1.0              # unit loads at (angle 0, z node k)
    columns = lu.solve(E)[:n * m].reshape(n, m, m)    # [j, l, k]
    spectrum = np.fft.rfft(columns, axis=0)
    return BushResponse(spec=spec, mesh=bm, basis=basis, outer=outer, inner=inner,
                        matrix=A.tocsr(),
                        lu=lu, spectrum=spectrum, scale=scale)


@dataclass(frozen=True, eq=False)
class BushWall:
    """The conducting bush beside one film mesh (:func:`bush_wall`): its response and
    ``transfer`` (film quadrature points of the energy equation's arcs, flattened, x
    inner nodes): the inner nodal temperatures at the film's points, linear in the
    angle and in z between the bush's inner nodes. Its transpose with the film's
    quadrature weights turns a film heat flux into the inner nodal loads."""

    response: BushResponse
    transfer: sp.csr_matrix

    @property
    def spec(self) -> BushConduction:
        return self.response.spec

    def loads(self, flux_dA: np.ndarray) -> np.ndarray:
        """Inner nodal loads [W] of the heat ``flux_dA`` [W] at the film's points."""
        return self.transfer.T @ np.ravel(flux_dA)


@cached(maxsize=8)
def bush_wall(spec: BushConduction, radius: float, length: float, mesh, op) -> BushWall:
    """The :class:`BushWall` of ``spec`` beside the film ``mesh`` (a whole-length film
    mesh fixed in the bearing: its angle is the bearing angle, the bush's) and its energy
    operator ``op`` (:func:`~bearingfem.thermal.energy.energy_operator`); the bush mesh
    has the film's ``n_theta`` and ``n_z`` unless the spec gives its own. Cached."""
    if mesh.half:
        raise ValueError("a conducting bush needs the whole-length film (half=False)")
    n_theta = spec.n_theta or mesh.n_theta
    n_axial = spec.n_axial or mesh.n_z
    heights = np.linspace(-0.5 * length, 0.5 * length, n_axial + 1) if spec.solid \
        else np.zeros(1)
    zeta = np.asarray(op.basis.global_coordinates()[1])
    # a bush much finer than the film aliases the film's heat: its inner nodes between
    # the film's quadrature points take none (measured on a thin wall, R/80: the film
    # 1.0 K off the local coefficient's answer with 8 bush cells per film cell, 0.3 K
    # with 1 or 2)
    if n_theta > 2 * mesh.n_theta or (spec.solid and n_axial > 2 * mesh.n_z):
        raise ValueError(f"the bush mesh (n_theta {n_theta}, n_axial {n_axial}) is finer "
                         f"than twice the film's (n_theta {mesh.n_theta}, n_z {mesh.n_z}): "
                         f"give the BushConduction n_theta, n_axial <= 2x the film's")
    response = bush_response(spec, radius, length, n_theta, n_axial)
    assert response.shape == (n_theta, heights.size)
    transfer = wall_transfer(n_theta, heights, op.theta, radius * zeta)
    return BushWall(response=response, transfer=transfer)


def wall_transfer(n: int, heights: np.ndarray, theta, z) -> sp.csr_matrix:
    """(points, inner nodes) interpolation matrix: the inner nodal values at the angles
    ``theta`` [rad] and axial places ``z`` [m] (flattened), linear in the angle between
    the bush's ``n`` angular lines (2 pi j / n) and in z between its axial lines
    ``heights`` (one: the ring, angle only)."""
    theta, z = np.ravel(theta), np.ravel(z)
    m = heights.size
    s = np.mod(theta, 2.0 * np.pi) * n / (2.0 * np.pi)
    j0 = np.minimum(np.floor(s).astype(int), n - 1)
    a = s - j0
    js = (j0, (j0 + 1) % n)
    wa = (1.0 - a, a)
    rows = np.arange(theta.size)
    if m == 1:
        r, c, w = [rows, rows], [js[0], js[1]], [wa[0], wa[1]]
    else:
        hz = heights
        t = np.clip((z - hz[0]) / (hz[1] - hz[0]), 0.0, m - 1)
        k0 = np.minimum(np.floor(t).astype(int), m - 2)
        b = t - k0
        ks, wb = (k0, k0 + 1), (1.0 - b, b)
        r, c, w = [], [], []
        for jj, aa in zip(js, wa):
            for kk, bb in zip(ks, wb):
                r.append(rows)
                c.append(jj * m + kk)
                w.append(aa * bb)
    return sp.csr_matrix((np.concatenate(w), (np.concatenate(r), np.concatenate(c))),
                         shape=(theta.size, n * m))


def radial_conduction(r, inner_radius: float, outer_radius: float, conductivity: float,
                      outer_coefficient: float, ambient_temperature: float,
                      inner_flux: float):
    """Closed form of a uniform flux q into a cylinder wall's inner surface with outer
    convection: the heat per length 2 pi R_i q crosses every radius, so
    T(r) = T_a + q R_i (1 / (h_o R_o) + ln(R_o / r) / k) [K]."""
    qr = inner_flux * inner_radius
    return ambient_temperature + qr * (1.0 / (outer_coefficient * outer_radius)
                                       + np.log(outer_radius / np.asarray(r)) / conductivity)

