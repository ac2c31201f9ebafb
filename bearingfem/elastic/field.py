"""The solid bush's whole displacement field under one film pressure, for inspection and
files: the deformed bush with the pressure on its inner surface, as VTU (meshio)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compliance import check_pressure, discretise
from .solid import solid_system

__all__ = ["BushField", "bush_field", "film_grid_pressure"]


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
        """The undeformed mesh with point data "displacement [m]" and "pressure [Pa]" (each
        named with its unit; ParaView: Warp By Vector to see it deformed)."""
        self._meshio().write(str(path))

    def _meshio(self):
        # scikit-fem's converter: its hexahedra number their nodes unlike VTK's
        from skfem.io.meshio import to_meshio
        return to_meshio(self.mesh, point_data={"displacement [m]": self.displacement.T,
                                                "pressure [Pa]": self.pressure})

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


def film_grid_pressure(sol) -> tuple[float, float, np.ndarray]:
    """(R [m], L [m], nodal pressure (n_theta, n_z + 1) [Pa]) of a whole-length P1 film
    solution (a :class:`~bearingfem.solution.FilmSolution` of ``solve_reynolds``) on its
    tensor grid: angle index j at theta = 2 pi j / n_theta from the maximum film, axial
    index k at z = -L/2 + k L / n_z."""
    mesh = getattr(sol, "mesh", None)
    if not all(hasattr(mesh, a) for a in ("n_theta", "n_z", "length_ratio")) or sol.half:
        raise ValueError("the film solution must be a whole-length finite-element film "
                         "(half=False; the EHD films are)")
    n, nz = mesh.n_theta, mesh.n_z
    theta, z = np.mod(np.asarray(sol.theta), 2 * np.pi), np.asarray(sol.z)
    length = 2.0 * float(np.max(np.abs(z)))
    j = np.rint(theta / (2 * np.pi / n)).astype(int) % n
    k = np.rint((z / length + 0.5) * nz).astype(int)
    grid = np.full((n, nz + 1), np.nan)
    grid[j, k] = np.asarray(sol.pressure)
    if np.isnan(grid).any():
        raise ValueError("the film solution's nodes must fill its (n_theta, n_z + 1) grid "
                         "(a P1 film)")
    return float(sol.radius), length, grid


def bush_field(bush, radius, length: float | None = None, pressure=None,
               refine_theta: int = 1, refine_z: int | None = None,
               n_radial: int | None = None, grading: float = 4.0) -> BushField:
    """Solve the solid bush (``bush.model`` is ignored) under the nodal film pressure
    [Pa] (n_theta, n_z) directly, without the compliance; arguments as for
    :func:`~.compliance.bush_compliance`. ``bush_field(bush, sol)``: the pressure, radius
    and length of a film solution ``sol`` (:func:`film_grid_pressure`; angle 0 of the
    bush mesh at the film's maximum film)."""
    if hasattr(radius, "pressure"):
        if length is not None or pressure is not None:
            raise ValueError("give a film solution alone or radius, length and pressure")
        radius, length, pressure = film_grid_pressure(radius)
    elif length is None or pressure is None:
        raise ValueError("bush_field needs a film solution or radius, length and pressure")
    shape = np.shape(pressure)
    if len(shape) != 2:
        raise ValueError(f"pressure must be an (n_theta, n_z) array, got shape {shape}")
    d = discretise(bush, radius, length, shape[0], shape[1], refine_theta, refine_z,
                   n_radial, grading)
    p = check_pressure(pressure, shape)
    system = solid_system(d.bush, d.radius, d.film, d.refine_theta, d.refine_z, d.n_radial,
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
