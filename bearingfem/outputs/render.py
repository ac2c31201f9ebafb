"""Off-screen pictures of a film solution that a researcher can read without asking.

* ``surface="unwrapped"``: the film as a map (matplotlib) over theta from the maximum film
  [deg] and z [mm], with the maximum film, the minimum film (where the eccentricity points)
  and the load line marked, the sliding direction of the journal surface, the cavitation
  boundary as the smooth p = 0 isoline and the cavitated region shaded.
* ``surface="journal"``: the 3-D journal (PyVista, no display needed), camera fitted to the
  body, the maximum-film line, the eccentricity and load directions and the rotation as
  arrows, the inertial axes (x: the slider axis), the cavitated region grey and its
  boundary red (the caption names only what is drawn).
* the JFO film fraction is shaded (interpolated), the full film in the top colour, with the
  rupture line (fraction < 1) red.

The title gives the force in the inertial frame, |F| and the attitude angle; the colour bar
starts at 0 (or below, at the least value, where the field is negative) with units.
``clim`` fixes the colour range (one scale for a series of frames).
"""
from __future__ import annotations

import numpy as np

from ..film import inertial_from_theta
from ..solution import FilmSolution
from .export import FIELD_NAMES, to_meshio

__all__ = ["render_film", "unwrapped_figure", "film_map", "color_range", "FIELDS", "SURFACES"]

SURFACES = ("journal", "unwrapped")
FIELDS = {"pressure": ("pressure", 1e-6, "pressure [MPa]"),
          "film_thickness": ("film_thickness", 1e6, "film thickness [um]"),
          "fraction": ("fraction", 1.0, "film fraction [1] (JFO)"),
          "temperature": ("temperature", 1.0, "film temperature [K] (thermal film)"),
          "deformation": ("deformation", 1e6, "bush deflection [um]")}
#: Share of the peak pressure below which a node counts as cavitated in pictures (the
#: complementarity solution is exactly 0 there; Gumbel's clip too).
CAVITY_LEVEL = 1e-6


def _title(sol: FilmSolution, title):
    fr, ft = sol.force_local
    load = float(np.hypot(fr, ft))
    att = float(np.degrees(np.arctan2(ft, -fr))) if load else 0.0
    text = (f"{sol.method}, {sol.cavitation}: F = ({sol.force[0]:.4g}, {sol.force[1]:.4g}) N "
            f"(inertial x, y), magnitude {load:.4g} N, attitude {att:.1f} deg")
    return text if title is None else f"{title}\n{text}"


def _load_theta(sol: FilmSolution) -> float:
    """Film angle [rad] the load points to. The film force makes the angle
    atan2(F_t, F_r) with the eccentricity, which points at theta = pi (the minimum film);
    the load is opposite it: pi + atan2 + pi, i.e. theta = atan2(F_t, F_r)."""
    fr, ft = sol.force_local
    return float(np.mod(np.arctan2(ft, fr), 2 * np.pi))


def _check(field, surface):
    if field not in FIELDS:
        raise ValueError(f"field must be one of {', '.join(FIELDS)}, got {field!r}")
    if surface not in SURFACES:
        raise ValueError(f"surface must be one of {', '.join(SURFACES)}, got {surface!r}")


def film_map(sol: FilmSolution, field: str):
    """Triangulation of the whole film over (theta [deg] in [0, 360], z [mm]) with one
    point per place, and the field's node values in display units."""
    import matplotlib.tri as mtri
    m = to_meshio(sol, "journal")         # mirrored to the whole length, node values
    th = np.mod(np.asarray(m.point_data[FIELD_NAMES["theta"]]), 2 * np.pi)
    z = np.asarray(m.point_data[FIELD_NAMES["z"]]) * 1e3
    key, scale, _ = FIELDS[field]
    v = np.asarray(m.point_data[FIELD_NAMES[key]]) * scale
    cells = m.cells[0].data[:, :3]        # corner nodes (P2 midside nodes add points only)
    # cells across the periodic seam would span the map: draw them shifted by 2 pi
    seam = np.ptp(th[cells], axis=1) > np.pi
    n = len(th)
    x = np.concatenate([np.degrees(th), np.degrees(th) + 360.0])
    zz = np.concatenate([z, z])
    vals = np.concatenate([v, v])
    shifted = np.where(th[cells] < np.pi, cells + n, cells)
    tris = np.vstack([cells[~seam], shifted[seam]])
    # one point per place: the mirrored half repeats the mid-plane nodes
    used = np.unique(tris)
    pts, inverse = np.unique(np.round(np.column_stack([x[used], zz[used]]), 9), axis=0,
                             return_inverse=True)
    index = np.empty(2 * n, int)
    index[used] = inverse.ravel()
    vals_u = np.empty(len(pts))
    vals_u[inverse.ravel()] = vals[used]
    return mtri.Triangulation(pts[:, 0], pts[:, 1], index[tris]), vals_u


def _cavity(sol: FilmSolution, tri, vals):
    """The cavitated region as (refined triangulation, field, level), or None: a cubic
    interpolant on a refined mesh draws the free boundary as a smooth isoline instead of the
    element staircase (the pressure grows like distance^2 away from it). The ambient ends
    (p = 0 by the boundary condition, not cavitation) take the values of the row inside
    them, so that the boundary runs on to the ends and the cavity is shaded over the end
    rows too (left out, they showed as dark bands across the cavity)."""
    import matplotlib.tri as mtri
    # a film without pressure (a centred, still journal) has no boundary to draw
    if sol.cavitation == "none" or not np.max(vals) > 0.0 or \
            not np.any(vals <= CAVITY_LEVEL * np.max(vals)):
        return None
    vals = _ends_from_inside(tri, vals)
    fine, fine_vals = mtri.UniformTriRefiner(tri).refine_field(
        vals, subdiv=3, triinterpolator=mtri.CubicTriInterpolator(tri, vals, kind="geom"))
    return fine, fine_vals, 2e-3 * float(np.max(vals))


def _ends_from_inside(tri, vals):
    """``vals`` with each node on an end (|z| largest) given the value of the node at the
    same theta in the row inside it (the mesh's rows are straight in theta)."""
    y = np.abs(tri.y)
    rows = np.unique(np.round(y, 9))
    if len(rows) < 2:
        return vals
    end, inside = rows[-1], rows[-2]
    key = {(round(float(x), 6), round(float(z), 9)): i
           for i, (x, z) in enumerate(zip(tri.x, tri.y)) if abs(round(abs(z), 9) - inside) < 1e-12}
    out = np.array(vals, float)
    for i in np.flatnonzero(np.abs(np.round(y, 9) - end) < 1e-12):
        j = key.get((round(float(tri.x[i]), 6), round(float(np.sign(tri.y[i]) * inside), 9)))
        if j is not None:
            out[i] = vals[j]
    return out


def _boundary_lines(sol: FilmSolution):
    """The cavitation boundary as polylines in (theta [deg], z [mm])."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    tri, vals = film_map(sol, "pressure")
    cav = _cavity(sol, tri, vals)
    if cav is None:
        return []
    fig, ax = plt.subplots()
    lines = ax.tricontour(cav[0], cav[1], levels=[cav[2]]).allsegs[0]
    plt.close(fig)
    return lines


def color_range(field: str, values, clim=None) -> tuple[float, float]:
    """The colour scale (lo, hi) of ``field``'s displayed ``values`` (NaN: not drawn):
    ``clim`` when given; else from 0, or from the least value where it is below 0 (the
    full Sommerfeld film's suction half, a bush drawn into the film), to the largest; a
    temperature from its coolest node (0 K would flatten the map). A scale from 0 alone
    drew the negative pressures of cavitation "none" as 0."""
    if clim is not None:
        return float(clim[0]), float(clim[1])
    least, top = float(np.nanmin(values)), float(np.nanmax(values))
    return (least if field == "temperature" else min(0.0, least)), top


def unwrapped_figure(sol: FilmSolution, field: str = "pressure", clim=None, title=None,
                     size=(9.0, 5.0)):
    """The unwrapped film as a matplotlib figure (see the module docstring)."""
    _check(field, "unwrapped")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    tri, vals = film_map(sol, field)
    label = FIELDS[field][2]
    fig, ax = plt.subplots(figsize=size, constrained_layout=True)
    lo, top = color_range(field, vals, clim)
    levels = np.linspace(lo, top if top > lo else lo + 1.0, 41)
    if field == "fraction":
        # interpolated shading: the full film (fraction 1) takes the top colour (filled
        # contours leave a plateau at the top level blank) and the rupture is not a staircase
        cf = ax.tripcolor(tri, np.clip(vals, lo, levels[-1]), shading="gouraud",
                          cmap="viridis", vmin=levels[0], vmax=levels[-1])
        if np.any(vals < 1.0 - 1e-6) and np.any(vals >= 1.0 - 1e-6):
            ax.tricontour(tri, vals, levels=[1.0 - 1e-3], colors="red", linewidths=1.2)
            ax.plot([], [], color="red", label="film ruptures (fraction < 1)")
    else:
        cf = ax.tricontourf(tri, np.clip(vals, lo, levels[-1]), levels=levels, cmap="viridis")
    cbar = fig.colorbar(cf, ax=ax, label=label, ticks=np.linspace(levels[0], levels[-1], 6))
    cbar.ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%.3g"))
    cav = _cavity(sol, tri, vals) if field == "pressure" else None
    if cav is not None:
        fine, fine_vals, edge = cav
        ax.tricontourf(fine, fine_vals, levels=[-np.inf, edge], colors=["0.82"])
        ax.tricontour(fine, fine_vals, levels=[edge], colors="red", linewidths=1.5)
        ax.plot([], [], color="red", label="cavitation boundary (p = 0)")
        ax.fill([], [], color="0.82", label="cavitated")
    half = float(np.max(np.abs(tri.y)))
    marks = [(0.0, "maximum film", "cyan", "--"),
             (180.0, "minimum film (eccentricity)", "magenta", ":"),
             (np.degrees(_load_theta(sol)), "load line", "orange", "-")]
    for xm, name, colour, style in marks:
        ax.axvline(xm, color=colour, ls=style, lw=1.4, label=name)
    # the maximum film is the map's seam: drawn at both edges, wide, inside a margin
    ax.axvline(360.0, color="cyan", ls="--", lw=1.4)
    if sol.pressure_max > 0:
        ax.plot(np.degrees(sol.pressure_max_theta), sol.pressure_max_z * 1e3, "k+", ms=10,
                label="peak pressure")
    ax.set(xlim=(-6, 366), ylim=(-half, half),
           xlabel="theta from the maximum film [deg]  (the journal surface slides toward "
                  "+theta for omega > 0 ->)",
           ylabel="z [mm]", xticks=np.arange(0, 361, 45))
    if size[1] >= 4.0:    # below the map (inside, it hides the film), when there is room
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, fontsize=7,
                  frameon=False)
    else:
        ax.legend(loc="upper right", fontsize=6, framealpha=0.85)
    ax.set_title(_title(sol, title), fontsize=8)
    return fig


def render_film(sol: FilmSolution, path, *, field: str = "pressure", surface: str = "journal",
                window_size=(900, 650), title: str | None = None, clim=None,
                camera_angle: float | None = None):
    """Write a PNG (or other image) of ``field`` ("pressure", "film_thickness" (the
    deformed gap with a bush), for a JFO film "fraction", for a film with an elastic bush
    "deformation", its radial deflection) on
    ``surface`` ("journal" or "unwrapped"). ``clim`` (lo, hi) fixes the colour range in the
    field's display units (MPa, um); ``camera_angle`` [rad, inertial] fixes where the
    journal view looks from (default: the loaded side)."""
    _check(field, surface)
    if field == "fraction" and sol.fraction is None:
        raise ValueError("field 'fraction' needs a JFO film (cavitation='jfo')")
    if field == "temperature" and sol.temperature is None:
        raise ValueError("field 'temperature' needs a thermal film (thermal=Thermal(...))")
    if field == "deformation" and sol.deformation is None:
        raise ValueError("field 'deformation' needs a film with an elastic bush (bush=...)")
    if surface == "unwrapped":
        dpi = 100
        fig = unwrapped_figure(sol, field, clim, title,
                               size=(window_size[0] / dpi, window_size[1] / dpi))
        fig.savefig(path, dpi=dpi)
        import matplotlib.pyplot as plt
        plt.close(fig)
        return path
    return _render_journal(sol, path, field, window_size, title, clim, camera_angle)


def _quiet_vtk():
    try:
        import vtk
        vtk.vtkLogger.SetStderrVerbosity(vtk.vtkLogger.VERBOSITY_OFF)
        vtk.vtkObject.GlobalWarningDisplayOff()
    except Exception:   # older VTK: keep its messages
        pass


def _render_journal(sol, path, field, window_size, title, clim, camera_angle):
    import pyvista as pv
    _quiet_vtk()
    m = to_meshio(sol, "journal")
    # Render in millimetres so the thin film does not dwarf the camera's clipping range.
    m.points = m.points * 1e3
    grid = pv.from_meshio(m)
    key, scale, label = FIELDS[field]
    values = np.asarray(grid.point_data[FIELD_NAMES[key]]) * scale
    cavitated = np.zeros(len(values), bool)
    if field == "pressure" and sol.cavitation != "none" and values.max() > 0.0:
        zs = np.abs(grid.points[:, 2])
        cavitated = ((values <= CAVITY_LEVEL * max(values.max(), np.finfo(float).tiny))
                     & (zs < zs.max() * (1 - 1e-9)))     # the ambient ends are not a cavity
    shown = np.where(cavitated, np.nan, values)      # NaN: drawn grey, off the colour scale
    grid.point_data[label] = shown
    lo, hi = color_range(field, shown, clim)
    p = pv.Plotter(off_screen=True, window_size=list(window_size))
    p.set_background("white")
    bar = dict(title=label, color="black", vertical=True, fmt="%.3g", position_x=0.86,
               position_y=0.12, width=0.06, height=0.7, n_labels=6, title_font_size=12,
               label_font_size=12)
    # Flat colours: the mirrored half of the film has reversed cell orientation.
    p.add_mesh(grid, scalars=label, cmap="viridis", clim=(lo, hi if hi > lo else lo + 1.0),
               nan_color="lightgrey", show_edges=False, lighting=False, scalar_bar_args=bar)
    R = sol.radius * 1e3
    half = float(np.max(np.abs(grid.points[:, 2])))
    if field == "pressure":
        for seg in _boundary_lines(sol):   # smooth, drawn just off the surface
            alpha = inertial_from_theta(np.radians(seg[:, 0]), sol.gamma)
            pts = np.column_stack([1.003 * R * np.cos(alpha), 1.003 * R * np.sin(alpha),
                                   seg[:, 1]])
            p.add_mesh(pv.lines_from_points(pts), color="red", line_width=3)
    # the maximum film (theta = 0) along the journal, and arrows at the near end face
    a0 = inertial_from_theta(0.0, sol.gamma)
    p.add_mesh(pv.Line((R * np.cos(a0), R * np.sin(a0), -half),
                       (R * np.cos(a0), R * np.sin(a0), half)), color="white", line_width=4)
    g = sol.gamma
    ecc = np.array([np.cos(g), np.sin(g), 0.0])
    fr, ft = sol.force_local
    lt = inertial_from_theta(_load_theta(sol), g)
    load = np.array([np.cos(lt), np.sin(lt), 0.0])
    end = np.array([0.0, 0.0, 1.05 * half])
    p.add_mesh(pv.Arrow(start=end, direction=ecc, scale=0.9 * R), color="black")
    p.add_mesh(pv.Arrow(start=end, direction=load, scale=0.9 * R), color="orange")
    tang = np.array([-np.sin(g + np.pi / 2), np.cos(g + np.pi / 2), 0.0])
    rim = end + R * np.array([np.cos(g + np.pi / 2), np.sin(g + np.pi / 2), 0.0])
    p.add_mesh(pv.Arrow(start=rim, direction=tang, scale=0.5 * R), color="steelblue")
    # eccentricity and load are told apart by colour in the caption: their labels would
    # overlap whenever the attitude angle is small
    p.add_point_labels(np.array([rim + 0.5 * R * tang, [R * np.cos(a0), R * np.sin(a0), half]]),
                       ["rotation", "max film"], font_size=11,
                       text_color="black", shape_opacity=0.6, always_visible=True)
    # the inertial frame: x is the slider axis of the mechanism
    p.add_axes(xlabel="x (slider)", ylabel="y", zlabel="z (axis)", line_width=3,
               color="black", labels_off=False)
    a = sol.pressure_max_angle if camera_angle is None else camera_angle
    d = 6.0 * max(R, half)
    p.camera_position = [(d * np.cos(a), d * np.sin(a), 0.8 * d), (0.0, 0.0, 0.0), (0, 0, 1)]
    p.reset_camera()                  # fit the whole body (long bearings too)
    p.camera.zoom(0.9)
    key_text = "black arrow: eccentricity; orange arrow: load; blue: journal rotation"
    if cavitated.any():
        key_text += "\ngrey: cavitated; red: cavitation boundary"
    p.add_text(_title(sol, title) + "\n" + key_text, font_size=8, color="black",
               position="upper_left")
    p.screenshot(str(path))
    p.close()
    return path
