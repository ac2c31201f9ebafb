"""The solid bush's whole displacement field under one film pressure, for inspection and
files: the deformed bush with the pressure on its inner surface, as VTU (meshio)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compliance import check_pressure, discretise
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
        self._meshio().write(str(path))

    def _meshio(self):
        # scikit-fem's converter: its hexahedra number their nodes unlike VTK's
        from skfem.io.meshio import to_meshio
        return to_meshio(self.mesh, point_data={"displacement": self.displacement.T,
                                                "pressure": self.pressure})

    def render(self, path, magnify: float | None = None, window_size=(1000, 800)) -> str:
        """Off-screen picture (PyVista) of the bush deformed ``magnify`` times (default:
        the largest displacement drawn as 15 % of the wall), coloured by the displacement
        magnitude [um], the loaded part of the inner surface coloured by the pressure
        [MPa]."""
        import pyvista as pv
        grid = pv.from_meshio(self._meshio())
        grid.points = grid.points * 1e3                               # millimetres
        r = np.hypot(self.mesh.p[0], self.mesh.p[1])
        largest = float(np.linalg.norm(self.displacement, axis=0).max())
        if magnify is None:
            magnify = 0.15 * (r.max() - r.min()) / largest if largest > 0 else 1.0
        grid.point_data["displacement [um]"] = np.linalg.norm(self.displacement, axis=0) * 1e6
        grid.point_data["pressure [MPa]"] = self.pressure * 1e-6
        grid.point_data["u"] = self.displacement.T * 1e3 * magnify
        warped = grid.warp_by_vector("u")
        plot = pv.Plotter(off_screen=True, window_size=list(window_size))
        plot.set_background("white")
        plot.add_mesh(warped, scalars="displacement [um]", cmap="viridis",
                      scalar_bar_args=dict(color="black", vertical=True, position_x=0.86))
        inner = warped.extract_surface(algorithm="dataset_surface").threshold(
            1e-3, scalars="pressure [MPa]")
        if inner.n_points:
            plot.add_mesh(inner, scalars="pressure [MPa]", cmap="inferno",
                          scalar_bar_args=dict(color="black", vertical=True, position_x=0.04))
        plot.add_text(f"elastic bush, deformation x {magnify:.0f}; largest displacement "
                      f"{largest * 1e6:.2f} um", font_size=9, color="black")
        plot.camera_position = "xy"
        plot.camera.elevation = -35.0
        plot.reset_camera()
        plot.screenshot(str(path))
        plot.close()
        return str(path)


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
    p = check_pressure(pressure, shape)
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
