"""The saved samples of a run: its dense output at evenly spaced crank turns, with the joint
force re-evaluated there (a film with memory: taken from its committed steps)."""
from __future__ import annotations

import math

import numpy as np

from .dynamics import accelerations
from .joint import coordinates, joint_force, joint_kinematics
from .result import FIELDS, FILM_COLUMNS, SimulationResult, provenance

__all__ = ["sample_run", "output_times", "record_start"]


def _dense(pieces):
    bounds = np.array([p.t_min for p in pieces] + [pieces[-1].t_max])

    def at(t):
        i = np.clip(np.searchsorted(bounds, t, side="right") - 1, 0, len(pieces) - 1)
        out = np.empty((6, len(t)))
        for j in np.unique(i):
            sel = i == j
            out[:, sel] = pieces[j](t[sel])[:6]    # a film's own states follow the joint's
        return out
    return at, bounds[0], bounds[-1]


def record_start(scene) -> float:
    """The crank angle [rad] from which a run records: q0 + 2 pi record_from_turn."""
    return scene.crank_angle + 2 * math.pi * scene.run.record_from_turn


def output_times(scene, crank_angle_at, t0, t1):
    """Saved time points: every 1/samples_per_turn of a nominal turn, from where the crank
    passes q0 + 2 pi record_from_turn to t1. A run that stopped before that window keeps
    its whole computed trajectory, from t0."""
    tt = np.linspace(t0, t1, 20001)
    q = crank_angle_at(tt)
    q_rec = record_start(scene)
    t_rec = float(np.interp(q_rec, q, tt)) if q[-1] >= q_rec else t0
    dt = 2 * math.pi / scene.crank_speed / scene.run.samples_per_turn
    t = np.arange(t_rec, t1 + 0.5 * dt, dt)
    return t[t <= t1]


def sample_run(scene, pieces, effects, g, stats, partial, message):
    m = scene.mechanism
    if not pieces:
        return SimulationResult(**{k: np.empty(0) for k in FIELDS}, scene=scene.name,
                                partial=partial, message=message, stats=stats,
                                provenance=provenance(scene))
    at, t0, t1 = _dense(pieces)
    t = output_times(scene, lambda tt: at(tt)[0], t0, t1)
    Y = at(t)
    c = scene.bearing.clearance
    n = len(t)
    out = {k: np.empty(n) for k in ("slider_acceleration", "force_x", "force_y", "rod_angle",
                                    "slider_position")}
    solves_before = [e.solves for e in effects]
    # a film with memory cannot be re-solved at a sample: its committed steps give it
    live = [e for e in effects if not e.memory]
    recorded = [e.recorded_force(t) for e in effects if e.memory]
    for i in range(n):
        q, A, X, qd, Ad, _ = coordinates(m, Y[:, i])
        fx, fy = joint_force(live, joint_kinematics(m, Y[:, i]))
        for rx, ry in recorded:
            fx, fy = fx + float(rx[i]), fy + float(ry[i])
        out["force_x"][i], out["force_y"][i] = fx, fy
        out["rod_angle"][i], out["slider_position"][i] = A, X
        out["slider_acceleration"][i] = accelerations(
            m, q, A, qd, Ad, fx, fy, g, scene.crank_torque, scene.slider_force)[2]
    stats["output_film_solves"] = int(sum(e.solves for e in effects)
                                      - sum(solves_before))
    memory = next((e for e in effects if e.memory), None)
    record = np.empty((0, len(FILM_COLUMNS))) if memory is None else \
        np.array(memory.history).reshape(-1, len(FILM_COLUMNS))
    film_z = np.empty((0, 0)) if memory is None or not memory.state_size \
        else np.array(memory.z_history).reshape(-1, memory.state_size)
    eps = np.hypot(Y[1], Y[2]) / c
    film_min = np.maximum(c * (1.0 - eps), 0.0)
    if any(e.wall > 1.0 for e in effects) and len(record):
        # an elastic film's gap is the rigid one plus the bush's deflection (0 beyond the
        # clearance circle rigidly): its own minimum, committed per film step, between steps
        # linearly (the deflection is kept between film steps)
        film_min = np.interp(t, record[:, 0], record[:, list(FILM_COLUMNS).index("film_min")])
    td = np.linspace(t[0], t[-1], 10 * (len(t) - 1) + 1) if len(t) > 1 else t
    Yd = at(td)
    return SimulationResult(
        t=t, crank_angle=Y[0], crank_speed=Y[3], rod_angle=out["rod_angle"],
        slider_position=out["slider_position"],
        slider_acceleration=out["slider_acceleration"], eps=eps, e_x=Y[1],
        e_y=Y[2], film_min=film_min, force_x=out["force_x"],
        force_y=out["force_y"], scene=scene.name, partial=partial, message=message,
        stats=stats, provenance=provenance(scene), dense_t=td, dense_e_x=Yd[1],
        dense_e_y=Yd[2], film_record=record, film_z=film_z,
        step_t=np.concatenate([p.ts[1:] for p in pieces]),
        peak_film=None if memory is None else memory.peak)
