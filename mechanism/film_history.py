"""The film along a mechanism run: solves at chosen crank angles, renders and exports.

A run saves the pin's eccentricity and the rod angle at every sample; the joint's state
at a sample (eccentricity rate, the journal's speed relative to the bearing = minus the
rod's angular velocity) follows by differentiating those records in time, so a film can
be re-solved at any saved instant without re-running the mechanism.

A film with memory (a model whose ``memory`` is True, e.g. "fem-jfo") depends on its whole
past, not on the instant: its run records the state of every film step (``film_record``),
and the film is replayed through them (the same solves as in the run, checked against the
recorded forces); each frame is the film step nearest its crank angle in the saved turns,
or the record's rows asked by ``film_steps``. A film whose own states the run
integrated (e.g. the bush's modes, "fem-ehd" coupling "states") needs no replay: each
frame is solved from its step's state and the states kept there (``film_z``), checked
the same way.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bearingfem import JournalState, solve_reynolds
from bearingfem.models import film_model

__all__ = ["FilmFrame", "film_history", "history_fields", "write_history", "render_history"]


@dataclass(frozen=True)
class FilmFrame:
    crank_angle_deg: float
    t: float
    solution: object          # bearingfem.FilmSolution


def _sample_indices(result, crank_angles_deg):
    """The saved sample nearest to each crank angle (degrees, taken modulo 360)."""
    q = np.mod(np.degrees(result.crank_angle), 360.0)
    out = []
    for a in np.mod(np.asarray(crank_angles_deg, float), 360.0):
        d = np.abs((q - a + 180.0) % 360.0 - 180.0)
        out.append(int(np.argmin(d)))
    return out


def history_fields(scene) -> tuple:
    """The nodal fields the frames of :func:`film_history` carry for ``scene``: a film with
    memory is replayed (its model's own fields, the fraction of a mass-conserving one);
    any other is solved again on the FE film (pressure and film thickness)."""
    lub = scene.lubrication
    model = None if lub is None else film_model(lub.model, "lubrication.model")
    if model is not None and model.memory:
        return model.film_fields(lub.options)
    return ("pressure", "film_thickness")


def film_history(result, scene, crank_angles_deg=None, n_frames=12, n_theta=None, n_z=None,
                 element=None, cavitation=None, progress=None, film_steps=None):
    """FE film solutions at the crank angles of a run (default: ``n_frames`` evenly spaced
    over a turn, or over the run's crank angles, ends included, when it covers less).
    A film with memory may be asked for rows of its run's ``film_record`` instead
    (``film_steps``, indices): a crank angle names a step of every turn the samples hold.

    The mesh and cavitation default to the scene's FE/FV/table lubrication options, else
    96 x 16 P1 with Gumbel cavitation. Returns a list of :class:`FilmFrame`.
    """
    if len(result.t) < 3:
        raise ValueError("the run has fewer than 3 saved samples: no film history")
    if scene.bearing is None:
        raise ValueError("the scene has no bearing (ideal joint): no film to show")
    if crank_angles_deg is None:
        if not (isinstance(n_frames, int) and n_frames >= 1):
            raise ValueError(f"n_frames must be an integer >= 1, got {n_frames!r}")
        crank_angles_deg = np.arange(n_frames) * 360.0 / n_frames
        span = float(np.degrees(result.crank_angle[-1] - result.crank_angle[0]))
        step = abs(span) / (len(result.t) - 1)
        # a recorded turn ends a sample short of 360 deg (359.5 for the paper's scenes):
        # that is a turn, whose frames stay 360 / n_frames apart
        if abs(span) + 2.0 * step < 360.0:
            # a run shorter than a turn (simulate --turns 0.25): a turn's angles would fall
            # beyond its ends onto the same few samples (4 frames asked, 2 given)
            crank_angles_deg = (float(np.degrees(result.crank_angle[0]))
                                + span * np.arange(n_frames) / max(n_frames - 1, 1))
    model = (film_model(scene.lubrication.model, "lubrication.model")
             if scene.lubrication is not None else None)
    if film_steps is not None and not (model is not None and model.memory):
        raise ValueError("film_steps names rows of a film record: a film with memory's "
                         "(the scene's film keeps none)")
    if model is not None and model.memory:
        given = dict(n_theta=n_theta, n_z=n_z, element=element, cavitation=cavitation)
        if any(v is not None for v in given.values()):
            raise ValueError(f"a {model.name} film is replayed on its run's own mesh: leave "
                             f"{', '.join(k for k, v in given.items() if v is not None)} "
                             "unset")
        return _replayed(result, scene, model, crank_angles_deg, progress, film_steps)
    opts = scene.lubrication.options if scene.lubrication is not None else {}
    n_theta = n_theta or opts.get("n_theta", 96)
    n_z = n_z or opts.get("n_z", 16)
    element = element or opts.get("element", "P1")
    cavitation = cavitation or opts.get("cavitation", "gumbel")
    c = scene.bearing.clearance
    t = result.t
    de_x, de_y = np.gradient(result.e_x, t), np.gradient(result.e_y, t)
    rod_rate = np.gradient(result.rod_angle, t)
    frames = []
    for k, i in enumerate(_sample_indices(result, crank_angles_deg)):
        s = JournalState.from_eccentricity(result.e_x[i], result.e_y[i], de_x[i], de_y[i], c,
                                           -rod_rate[i], eps_max=0.999)
        sol = solve_reynolds(scene.bearing, s, n_theta, n_z, element, cavitation)
        frames.append(FilmFrame(float(np.mod(np.degrees(result.crank_angle[i]), 360.0)),
                                float(t[i]), sol))
        if progress:
            progress(k + 1, len(crank_angles_deg))
    return frames


def _replayed(result, scene, model, crank_angles_deg, progress=None, film_steps=None):
    """Frames of a film with memory: its run's film steps replayed (see the module)."""
    from .result import FILM_COLUMNS, film_column, film_states
    rec, start = result.film_record, result.stats.get("film_start")
    if start is None or rec.ndim != 2 or rec.shape[1] != len(FILM_COLUMNS) or not len(rec):
        raise ValueError("the run has no film record with its journal states (runs of "
                         f"{model.name} record them from this version on): run the scene "
                         "again")
    t_rec = film_column(rec, "t")
    crank = lambda t: np.mod(np.degrees(np.interp(t, result.t, result.crank_angle)),  # noqa
                             360.0)
    if film_steps is not None:
        wanted = set()
        for i in np.atleast_1d(film_steps):
            if not (isinstance(i, (int, np.integer)) and 0 <= i < len(rec)):
                raise ValueError(f"film_steps must be rows of the film record, integers in "
                                 f"[0, {len(rec) - 1}], got {i!r}")
            wanted.add(int(i))
    else:
        inside = np.flatnonzero((t_rec >= result.t[0]) & (t_rec <= result.t[-1]))
        if not len(inside):
            raise ValueError("no film step of the run falls in its saved turns")
        q_rec = crank(t_rec[inside])
        wanted = set()
        for a in np.mod(np.asarray(crank_angles_deg, float), 360.0):
            wanted.add(int(inside[np.argmin(np.abs((q_rec - a + 180.0) % 360.0 - 180.0))]))
    last = max(wanted)
    force = np.column_stack([film_column(rec, "force_x"), film_column(rec, "force_y")])
    peak = float(np.max(np.hypot(force[:, 0], force[:, 1]))) or 1.0
    frames = {}
    film = model.along_run(scene.bearing, scene.lubrication.options)
    if film.state_size:
        steps = _from_states(result, film, film_states(rec[:last + 1]), wanted)
    else:
        steps = enumerate(film.replay((float(start[0]),
                                       JournalState(*(float(v) for v in start[1:]))),
                                      film_states(rec[:last + 1])))
    for i, (t, sol) in steps:
        # the record holds what carried the joint: the film and, where a film has
        # them, its summits (the force of a film without roughness)
        miss = float(np.hypot(*np.subtract(sol.total_force, force[i]))) / peak
        if miss > film.replay_tolerance:      # its own solves' (contract rule 13)
            raise ValueError(f"the replayed film departs from the run's record at film step "
                             f"{i} (t = {t:.6g} s) by {miss:.2g} of the peak force: the scene's "
                             "film options differ from the run's")
        if i in wanted:
            frames[i] = sol
            if progress:
                progress(len(frames), len(wanted))
    return [FilmFrame(float(crank(t_rec[i])), float(t_rec[i]), frames[i])
            for i in sorted(frames)]


def _from_states(result, film, states, wanted):
    """(film step, (t, FilmSolution)) of the ``wanted`` steps of a film whose own states
    the run integrated (contract rule 16): each solved at its row's state and the states
    the run kept there (``result.film_z``), no sequential replay needed."""
    z = np.asarray(result.film_z)
    if z.shape != (len(result.film_record), film.state_size):
        raise ValueError(f"the run keeps no film_z of {film.state_size} states per film step "
                         "(runs keep them from this version on): run the scene again")
    for i in sorted(wanted):
        t, state = states[i]
        yield i, (t, film.solution(state, z[i]))


def write_history(frames, directory, surface="journal") -> Path:
    """One VTU per frame and a ParaView collection ``film.pvd`` (time = run time [s])."""
    from bearingfem.outputs.export import write_solution
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    root = ET.Element("VTKFile", type="Collection", version="0.1")
    coll = ET.SubElement(root, "Collection")
    for k, f in enumerate(frames):
        name = f"film-{k:03d}.vtu"
        write_solution(f.solution, d / name, surface,
                       constants={"time [s]": f.t,
                                  "crank_angle [rad]": math.radians(f.crank_angle_deg)})
        ET.SubElement(coll, "DataSet", timestep=repr(f.t), part="0", file=name)
    ET.ElementTree(root).write(d / "film.pvd", xml_declaration=True)
    return d / "film.pvd"


def render_history(frames, directory, field="pressure", surface="journal", gif=True,
                   frame_seconds=0.4, fixed_camera: bool = False):
    """PNG per frame (off screen) and, with ``gif``, an animated GIF of them (Pillow).

    Every frame shares one colour scale (0, or the series' least where below 0, to its
    peak: :func:`bearingfem.outputs.render.color_range`), so frames compare. The
    journal view looks at each frame's loaded side, or from one place with ``fixed_camera``
    (that of the frame with the series' peak)."""
    from bearingfem.outputs.render import FIELDS, color_range, render_film
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    _, scale, _ = FIELDS[field]
    values = [np.asarray(getattr(f.solution, field)) * scale for f in frames]
    # one scale for the series, as render_film scales one film (below 0 where a film is)
    clim = color_range(field, np.concatenate([v.ravel() for v in values])) if frames else None
    peak = max(frames, key=lambda f: f.solution.pressure_max) if frames else None
    camera = peak.solution.pressure_max_angle if fixed_camera and peak else None
    paths = []
    for k, f in enumerate(frames):
        paths.append(render_film(f.solution, d / f"frame-{k:03d}.png", field=field,
                                 surface=surface, clim=clim, camera_angle=camera,
                                 title=f"crank {f.crank_angle_deg:.0f} deg, t = {f.t:.5f} s"))
    if gif and paths:
        from PIL import Image
        images = [Image.open(p).convert("P", palette=Image.ADAPTIVE) for p in paths]
        images[0].save(d / "film.gif", save_all=True, append_images=images[1:],
                       duration=int(1000 * frame_seconds), loop=0)
        paths.append(d / "film.gif")
    return paths
