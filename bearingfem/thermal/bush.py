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

Not coupled to the film's energy equation yet: the thermal film takes the bush as a
heat-transfer coefficient (:class:`~bearingfem.thermal.Thermal`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import (Basis, BilinearForm, ElementHex1, ElementQuad1, FacetBasis, LinearForm,
                   solve)
from skfem.models.poisson import laplace

from ..bearing import check_positive
from ..elastic import ElasticBush
from ..elastic.mesh import BushMesh, annulus_mesh, cylinder_mesh

__all__ = ["BushHeat", "bush_heat", "radial_conduction"]


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
    R = bush.check_inner_radius(radius)
    k = check_positive("conductivity", conductivity)
    h = check_positive("outer_coefficient", outer_coefficient)
    ta = check_positive("ambient_temperature", ambient_temperature)
    if bush.model == "solid":
        bm = cylinder_mesh(R, bush.outer_radius, check_positive("length", length), n_theta,
                           n_radial, n_axial, grading)
        elem = ElementHex1()
    else:
        bm = annulus_mesh(R, bush.outer_radius, n_theta, n_radial, grading)
        elem = ElementQuad1()
    basis = Basis(bm.mesh, elem)
    outer = FacetBasis(bm.mesh, elem, facets=_facets(bm, bm.radii.size - 1))
    inner = FacetBasis(bm.mesh, elem, facets=_facets(bm, 0))
    x = inner.global_coordinates()
    theta = np.arctan2(x[1], x[0])
    z = x[2] if x.shape[0] == 3 else np.zeros_like(theta)
    q = inner_flux(theta, z) if callable(inner_flux) else \
        np.full_like(theta, float(inner_flux))
    if not np.all(np.isfinite(q)):
        raise ValueError("inner_flux must be finite on the inner surface")
    A = k * laplace.assemble(basis) + _robin.assemble(outer, h=h)
    b = _flux.assemble(inner, q=q) + _flux.assemble(outer, q=h * ta)
    T = solve(A, b)
    heat_in = float(np.sum(q * inner.dx))
    heat_out = float(np.sum(h * (np.asarray(outer.interpolate(T)) - ta) * outer.dx))
    area = float(np.sum(inner.dx))
    inner_mean = float(np.sum(np.asarray(inner.interpolate(T)) * inner.dx)) / area
    return BushHeat(bm, T, heat_in, heat_out, inner_mean)


def radial_conduction(r, inner_radius: float, outer_radius: float, conductivity: float,
                      outer_coefficient: float, ambient_temperature: float,
                      inner_flux: float):
    """Closed form of a uniform flux q into a cylinder wall's inner surface with outer
    convection: the heat per length 2 pi R_i q crosses every radius, so
    T(r) = T_a + q R_i (1 / (h_o R_o) + ln(R_o / r) / k) [K]."""
    qr = inner_flux * inner_radius
    return ambient_temperature + qr * (1.0 / (outer_coefficient * outer_radius)
                                       + np.log(outer_radius / np.asarray(r)) / conductivity)

