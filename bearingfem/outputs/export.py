"""Export a film solution to meshio (VTU, XDMF, ...) for ParaView.

Points lie on the 3-D journal surface (x = R cos alpha, y = R sin alpha, z) or, with
``surface="unwrapped"``, on the plane (R theta, z, 0). Point data, each named with its SI
unit (:data:`FIELD_NAMES`, what ParaView shows; in a legacy .vtk file, which takes no
spaces, "pressure_[Pa]" and so on): "pressure [Pa]", "film_thickness [m]",
"theta [rad]" (from the maximum film) and "z [m]"; a JFO film's "fraction [1]", a thermal
film's "temperature [K]", an elastic bush's "deformation [m]" (its radial deflection, > 0
opens the gap; film_thickness is then the deformed gap). A half-domain solve is mirrored
to the whole length.
"""
from __future__ import annotations

import meshio
import numpy as np

from ..fe.mesh import FilmMesh
from ..fv.fvm import FVMGrid
from ..film import inertial_from_theta
from ..solution import FilmSolution

__all__ = ["to_meshio", "write_solution", "FIELD_NAMES"]

#: The film's quantities -> their point-data names in the exported files (quantity [unit]).
FIELD_NAMES = {"pressure": "pressure [Pa]", "film_thickness": "film_thickness [m]",
               "theta": "theta [rad]", "z": "z [m]", "fraction": "fraction [1]",
               "temperature": "temperature [K]", "deformation": "deformation [m]"}


def _named(data: dict) -> dict:
    return {FIELD_NAMES[k]: v for k, v in data.items()}


def _cells_fe(mesh: FilmMesh):
    dofs = mesh.basis.element_dofs
    if mesh.basis.elem.__class__.__name__.endswith("P2"):
        return "triangle6", dofs[:6].T.copy()
    return "triangle", dofs[:3].T.copy()


def _cells_fv(g: FVMGrid):
    nt, nz = g.n_theta, g.n_z
    i, j = np.meshgrid(np.arange(nt), np.arange(nz - 1), indexing="ij")
    i1 = (i + 1) % nt if g.theta0 is None else i + 1
    keep = np.ones_like(i, bool) if g.theta0 is None else (i < nt - 1)
    quads = np.stack([i * nz + j, i1 * nz + j, i1 * nz + j + 1, i * nz + j + 1], -1)[keep]
    return "quad", quads.reshape(-1, 4)


def to_meshio(sol: FilmSolution, surface: str = "journal") -> meshio.Mesh:
    """The film as a meshio mesh (3-D journal surface or the unwrapped plane)."""
    if surface not in ("journal", "unwrapped"):
        raise ValueError(f"surface must be 'journal' or 'unwrapped', got {surface!r}")
    if isinstance(sol.mesh, FilmMesh):
        ctype, cells = _cells_fe(sol.mesh)
    elif isinstance(sol.mesh, FVMGrid):
        ctype, cells = _cells_fv(sol.mesh)
    else:
        raise ValueError("sol.mesh must be the FilmMesh or FVMGrid of the solve")
    theta, z = np.asarray(sol.theta), np.asarray(sol.z)
    p, h = np.asarray(sol.pressure), np.asarray(sol.film_thickness)
    # the JFO film fraction (1 in the full film), a thermal film's temperature [K] and the
    # bush's deflection [m] where the film has them
    extra = {k: np.asarray(v) for k, v in (("fraction", sol.fraction),
                                           ("temperature", sol.temperature),
                                           ("deformation", sol.deformation)) if v is not None}
    if sol.half:
        n = len(theta)
        theta, z = np.concatenate([theta, theta]), np.concatenate([z, -z])
        p, h = np.concatenate([p, p]), np.concatenate([h, h])
        extra = {k: np.concatenate([v, v]) for k, v in extra.items()}
        mirrored = cells + n
        if ctype == "triangle":
            mirrored = mirrored[:, [0, 2, 1]]
        cells = np.vstack([cells, mirrored])
    R = sol.radius
    if surface == "journal":
        alpha = inertial_from_theta(theta, sol.gamma)
        pts = np.column_stack([R * np.cos(alpha), R * np.sin(alpha), z])
        data = {"pressure": p, "film_thickness": h, "theta": theta, "z": z, **extra}
        return meshio.Mesh(pts, [(ctype, cells)], point_data=_named(data))
    # Unwrapped: cells across the periodic seam would span the whole plane, so every cell
    # gets its own vertices and seam cells are unwrapped by 2 pi.
    th = theta[cells]
    th = np.where((th.max(axis=1, keepdims=True) - th.min(axis=1, keepdims=True) > np.pi)
                  & (th < np.pi), th + 2 * np.pi, th)
    flat = cells.ravel()
    pts = np.column_stack([R * th.ravel(), z[flat], np.zeros(flat.size)])
    own = np.arange(flat.size).reshape(cells.shape)
    data = {"pressure": p[flat], "film_thickness": h[flat], "theta": theta[flat],
            "z": z[flat], **{k: v[flat] for k, v in extra.items()}}
    return meshio.Mesh(pts, [(ctype, own)], point_data=_named(data))


def write_solution(sol: FilmSolution, path, surface: str = "journal", constants=None):
    """Write the film to ``path``; the format follows the suffix (.vtu, .xdmf, ...).
    ``constants``: name -> number written as a uniform point field (e.g. ``"time [s]"``,
    the run's time, named with its unit as the film's fields are; meshio's VTU writer
    drops field data, ParaView reads point fields)."""
    m = to_meshio(sol, surface)
    for k, v in (constants or {}).items():
        m.point_data[k] = np.full(len(m.points), float(v))
    if str(path).lower().endswith(".vtk"):
        # the legacy VTK format takes no spaces in names: "pressure_[Pa]"
        m.point_data = {k.replace(" ", "_"): v for k, v in m.point_data.items()}
    m.write(str(path))
