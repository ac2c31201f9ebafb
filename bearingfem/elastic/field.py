"""The solid bush's whole displacement field under one film pressure, for inspection and
files: the deformed bush with the pressure on its inner surface, as VTU (meshio)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compliance import _check_pressure, discretise
from .solid import solid_system

__all__ = ["BushField", "bush_field"]


@dataclass(frozen=True, eq=False)
class BushField:
    """Displacement of the solid bush under a film pressure.

    Attributes
    ----------
    mesh : scikit-fem ``MeshHex1`` of the bush [m]
    displacement : (3, n_nodes) [m], Cartesian
    pressure : (n_nodes,) [Pa], the film pressure on inner-surface nodes, 0 elsewhere
    deflection : (n_theta, n_z) [m], u . e_r at the film nodes
    """

    mesh: object
    displacement: np.ndarray
    pressure: np.ndarray
    deflection: np.ndarray

    def write_vtu(self, path) -> None:
        """The undeformed mesh with point data ``displacement`` [m] and ``pressure``
        [Pa] (ParaView: Warp By Vector to see it deformed)."""
        import meshio
        meshio.Mesh(self.mesh.p.T, [("hexahedron", self.mesh.t.T)],
                    point_data={"displacement": self.displacement.T,
                                "pressure": self.pressure}).write(str(path))


def bush_field(bush, radius: float, length: float, pressure, refine_theta: int = 1,
               refine_z: int | None = None, n_radial: int | None = None,
               grading: float = 4.0) -> BushField:
    """Solve the solid bush (``bush.model`` is ignored) under the nodal film pressure
    [Pa] (n_theta, n_z) directly, without the compliance; arguments as for
    :func:`~.compliance.bush_compliance`."""
    shape = np.shape(pressure)
    if len(shape) != 2:
        raise ValueError(f"pressure must be an (n_theta, n_z) array, got shape {shape}")
    d = discretise(bush, radius, length, shape[0], shape[1], refine_theta, refine_z,
                   n_radial, grading)
    p = _check_pressure(pressure, shape)
    system = solid_system(bush, d.radius, d.film, d.refine_theta, d.refine_z, d.n_radial,
                          d.grading)
    solution = system.solve([lambda x: d.film.interpolate(p, x)])[:, 0]
    mesh = system.bush_mesh
    nodes = mesh.node(0, np.arange(shape[0])[:, None] * d.refine_theta,
                      np.arange(shape[1])[None, :] * d.refine_z)
    deflection = system.radial(solution[:, None], nodes, d.film.angles[:, None])[..., 0]
    displacement = solution[system.basis.nodal_dofs]
    inner = mesh.radial == 0
    nodal_p = np.zeros(mesh.mesh.p.shape[1])
    nodal_p[inner] = d.film.interpolate(p, mesh.mesh.p[:, inner])
    return BushField(mesh.mesh, displacement, nodal_p, deflection)
