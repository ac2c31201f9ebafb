"""Off-screen renders of a film solution (pyvista/VTK; no display needed).

The pressure is drawn on the 3-D journal surface or on the unwrapped film; the cavitated
region (zero gauge pressure) is drawn grey, and the scalar bar carries the units.
"""
from __future__ import annotations

import numpy as np

from ..solution import FilmSolution
from .export import to_meshio

__all__ = ["render_film", "FIELDS", "SURFACES"]

SURFACES = ("journal", "unwrapped")
FIELDS = {"pressure": ("pressure", 1e-6, "pressure [MPa]"),
          "film_thickness": ("film_thickness", 1e6, "film thickness [um]")}


def _quiet_vtk():
    try:
        import vtk
        vtk.vtkLogger.SetStderrVerbosity(vtk.vtkLogger.VERBOSITY_OFF)
        vtk.vtkObject.GlobalWarningDisplayOff()
    except Exception:   # older VTK: keep its messages
        pass


def render_film(sol: FilmSolution, path, *, field: str = "pressure", surface: str = "journal",
                window_size=(900, 650), title: str | None = None):
    """Write a PNG of ``field`` ("pressure" or "film_thickness") on ``surface``
    ("journal": 3-D cylinder, or "unwrapped"); ``title`` is added above the summary line."""
    if field not in FIELDS:
        raise ValueError(f"field must be one of {', '.join(FIELDS)}, got {field!r}")
    import pyvista as pv
    _quiet_vtk()
    m = to_meshio(sol, surface)
    # Render in millimetres so the thin film does not dwarf the camera's clipping range.
    m.points = m.points * 1e3
    grid = pv.from_meshio(m)
    key, scale, label = FIELDS[field]
    values = grid.point_data[key] * scale
    grid.point_data[label] = values
    p = pv.Plotter(off_screen=True, window_size=list(window_size))
    p.set_background("white")
    bar = dict(title=label, color="black", vertical=False, fmt="%.3g", position_x=0.2,
               position_y=0.04, width=0.6, height=0.08)
    # Flat colours: the mirrored half of the film has reversed cell orientation.
    style = dict(scalars=label, cmap="viridis", show_edges=False, lighting=False,
                 scalar_bar_args=bar)
    if field == "pressure" and sol.cavitation != "none" and np.any(values <= 0.0):
        lo = max(values.max() * 1e-6, np.finfo(float).tiny)
        bar["below_label"] = "cavitated"
        p.add_mesh(grid, clim=(lo, max(values.max(), 2 * lo)), below_color="lightgrey", **style)
    else:
        p.add_mesh(grid, **style)
    if surface == "journal":
        a = sol.pressure_max_angle   # look at the loaded side
        d = 6.0 * sol.radius * 1e3
        p.camera_position = [(d * np.cos(a), d * np.sin(a), 0.6 * d), (0.0, 0.0, 0.0), (0, 0, 1)]
    else:
        p.view_xy()
        p.camera.zoom(1.3)
    text = f"{sol.method}, {sol.cavitation}: F = ({sol.force[0]:.4g}, {sol.force[1]:.4g}) N"
    p.add_text(text if title is None else f"{title}\n{text}", font_size=9, color="black")
    p.screenshot(str(path))
    p.close()
    return path
