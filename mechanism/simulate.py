"""Time integration of a scene: variable-step, error-controlled, in segments.

The state is (q, e_x, e_y) and their rates: the eccentricity itself is integrated, so the
error control acts on it in units of the clearance (through X_PT and A it would be the
difference of two large numbers). A and X_PT follow from the kinematics.

Integrating segment by segment (a quarter crank turn each) keeps every finished segment:
a run stopped by Ctrl-C, a solver failure or the journal passing eps = 1 without a contact
effect returns what it computed, marked partial, with the time and the reason.
"""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from .dynamics import (_gravity_terms, _mass_terms, accelerations, eccentricity_accelerations,
                       pin_position, pin_velocity, rod_from_eccentricity)
from .effects import (CoulombFriction, FilmEffect, HertzContact, JointKinematics, LinearSpring,
                      hertz_stiffness)
from .parameters import GRAVITY
from .progress import Progress
from .result import FIELDS, FILM_RECORD, SimulationResult, provenance
from .rigid import integrate_rigid, rigid_kinematics, rigid_rhs
from .scene import Scene

__all__ = ["simulate", "build_effects"]

_METHODS = {"lsoda": "LSODA", "bdf": "BDF", "radau": "Radau", "rk45": "RK45", "dop853": "DOP853"}


class RunStopped(Exception):
    """The run cannot go on; the message says where and why."""


def build_effects(scene: Scene):
    """The joint effects the scene calls for, and nothing else."""
    effects, film, contact = [], None, None
    b = scene.bearing
    if scene.lubrication is not None:
        film = FilmEffect(b, scene.lubrication.model, dict(scene.lubrication.options),
                          scene.lubrication.eps_max)
        effects.append(film)
    if scene.contact is not None:
        c = scene.contact
        contact = HertzContact(b.clearance, hertz_stiffness(b.radius, b.clearance,
                                                            c.young_modulus, c.poisson),
                               c.restitution, c.exponent)
        effects.append(contact)
        if scene.friction is not None:
            effects.append(CoulombFriction(contact, scene.friction.coefficient, b.radius,
                                           scene.friction.v_reg))
    if scene.spring is not None:
        effects.append(LinearSpring(scene.spring.stiffness, scene.spring.damping))
    return effects, film, contact


def _coordinates(m, y):
    """(q, A, X_PT, q', A', X_PT') of the state y = (q, e_x, e_y, q', e_x', e_y')."""
    q, ex, ey, qd, exd, eyd = y
    A, Ad = rod_from_eccentricity(m, q, qd, ey, eyd)
    px, _ = pin_position(m, q, A)
    vx, _ = pin_velocity(m, q, A, qd, Ad)
    return q, A, px - ex, qd, Ad, vx - exd


def _joint(m, y):
    q, ex, ey, qd, exd, eyd = y
    _, Ad = rod_from_eccentricity(m, q, qd, ey, eyd)
    return JointKinematics(ex, ey, exd, eyd, -Ad)


def _joint_force(effects, k):
    fx = fy = 0.0
    for eff in effects:
        a, b = eff.force(k)
        fx += a
        fy += b
    return fx, fy


def _initial_state(scene: Scene):
    """Pin centred in the bush and moving with the slider: e = 0, e' = 0."""
    return np.array([scene.crank_angle, 0.0, 0.0, scene.crank_speed, 0.0, 0.0])


def simulate(scene: Scene, progress: bool | None = None) -> SimulationResult:
    """Integrate the scene; see :class:`mechanism.result.SimulationResult`."""
    if scene.joint == "ideal":
        return _simulate_ideal(scene, progress)
    m = scene.mechanism
    g = GRAVITY if scene.gravity else 0.0
    effects, film, contact = build_effects(scene)
    c = scene.bearing.clearance
    run = scene.run
    turn_time = 2 * math.pi / scene.crank_speed
    q_end = scene.crank_angle + 2 * math.pi * run.turns
    t_limit = 4.0 * run.turns * turn_time
    bar = Progress(run.turns, f"{scene.name}", progress)
    n_rhs = [0]

    def rhs(t, y):
        n_rhs[0] += 1
        q, A, _, qd, Ad, _ = _coordinates(m, y)
        fx, fy = _joint_force(effects, JointKinematics(y[1], y[2], y[4], y[5], -Ad, t))
        qdd, Add, Xdd = accelerations(m, q, A, qd, Ad, fx, fy, g,
                                      scene.crank_torque, scene.slider_force)
        exdd, eydd = eccentricity_accelerations(m, q, A, qd, Ad, qdd, Add, Xdd)
        bar.update((q - scene.crank_angle) / (2 * math.pi))
        return [qd, y[4], y[5], qdd, exdd, eydd]

    def ev_end(t, y):
        return y[0] - q_end
    ev_end.terminal, ev_end.direction = True, 1

    def gap(t, y):   # eps - 1: positive in contact
        return math.hypot(y[1], y[2]) / c - 1.0

    def ev_in(t, y):
        return gap(t, y)
    ev_in.terminal, ev_in.direction = True, 1

    def ev_out(t, y):
        return gap(t, y)
    ev_out.terminal, ev_out.direction = True, -1

    events = [ev_end, None]
    if film is not None and film.memory:
        # A film with memory advances at each accepted step: solve_ivp evaluates every
        # event function once at the end of each accepted step (this one never fires).
        def ev_commit(t, y):
            _, _, _, _, Ad, _ = _coordinates(m, y)
            film.commit(JointKinematics(y[1], y[2], y[4], y[5], -Ad, t))
            return 1.0
        events.append(ev_commit)

    a_len = run.atol if run.atol is not None else 1e-4 * c
    w = scene.crank_speed
    atol = np.array([a_len / m.crank_length, a_len, a_len,
                     a_len * w / m.crank_length, a_len * w, a_len * w])
    opts = dict(method=_METHODS[run.integrator], rtol=run.rtol, atol=atol, dense_output=True)
    if run.max_step is not None:
        opts["max_step"] = run.max_step

    t, y = 0.0, _initial_state(scene)
    in_contact = gap(t, y) > 0.0
    pieces, steps, message, partial = [], 0, "completed", False
    first_step = None
    start = time.perf_counter()
    try:
        while True:
            t_stop = min(t + 0.25 * turn_time, t_limit)
            if first_step is not None and opts["method"] != "LSODA":
                opts["first_step"] = min(first_step, t_stop - t)
            events[1] = ev_out if in_contact else ev_in
            sol = solve_ivp(rhs, (t, t_stop), y, events=events, **opts)
            if sol.status == -1:
                raise RunStopped(f"integrator failed at t = {sol.t[-1]:.6g} s: {sol.message}")
            if len(sol.t) > 1:
                pieces.append(sol.sol)
                steps += len(sol.t) - 1
                first_step = sol.t[-1] - sol.t[-2]
            t, y = float(sol.t[-1]), sol.y[:, -1]
            if sol.t_events[0].size:
                break
            if sol.t_events[1].size:
                if in_contact:
                    in_contact = False
                elif contact is None and scene.spring is None:
                    raise RunStopped(
                        f"the journal reached the bearing wall (eps = 1) at t = {t:.6g} s, "
                        f"crank angle {math.degrees(y[0]):.1f} deg, and the scene has no "
                        "contact effect: add scene.effects.contact or a stiffer film")
                else:
                    in_contact = True
                    if contact is not None:   # Lankarani-Nikravesh needs the impact speed
                        contact.v_impact = (y[1] * y[4] + y[2] * y[5]) / math.hypot(y[1], y[2])
            if t >= t_limit:
                raise RunStopped(f"crank did not finish {run.turns} turns by t = {t:.6g} s")
    except RunStopped as err:
        partial, message = True, str(err)
    except KeyboardInterrupt:
        partial, message = True, f"interrupted at t = {t:.6g} s"
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as err:
        partial, message = True, f"stopped at t = {t:.6g} s: {type(err).__name__}: {err}"
    wall = time.perf_counter() - start
    bar.close(message if partial else "done", complete=not partial)
    stats = {"wall_time": wall, "steps": steps, "rhs_evals": n_rhs[0],
             "film_solves": film.solves if film else 0,
             "film_steps": film.steps if film is not None else 0,
             "contact_evals": contact.evaluations if contact else 0,
             "integrator": run.integrator, "rtol": run.rtol, "atol_length": a_len,
             "effects": [type(e).__name__ for e in effects]}
    if film is not None and film.start is not None:   # where a film with memory began
        stats["film_start"] = [float(v) for v in film.start]
    if film is not None and film.model == "fem-table":
        from bearingfem.fe.force_table import force_table   # the one the run used (cached)
        stats["fem_table_mesh_error"] = force_table(scene.bearing.length_ratio,
                                                    **film.options).mesh_error
    return _sample(scene, pieces, effects, g, stats, partial, message)


def _dense(pieces):
    bounds = np.array([p.t_min for p in pieces] + [pieces[-1].t_max])

    def at(t):
        i = np.clip(np.searchsorted(bounds, t, side="right") - 1, 0, len(pieces) - 1)
        out = np.empty((6, len(t)))
        for j in np.unique(i):
            sel = i == j
            out[:, sel] = pieces[j](t[sel])
        return out
    return at, bounds[0], bounds[-1]


def _output_times(scene, crank_angle_at, t0, t1):
    """Saved time points: every 1/samples_per_turn of a nominal turn, from where the crank
    passes q0 + 2 pi record_from_turn to t1. A run that stopped before that window keeps
    its whole computed trajectory, from t0."""
    tt = np.linspace(t0, t1, 20001)
    q = crank_angle_at(tt)
    q_rec = scene.crank_angle + 2 * math.pi * scene.run.record_from_turn
    t_rec = float(np.interp(q_rec, q, tt)) if q[-1] >= q_rec else t0
    dt = 2 * math.pi / scene.crank_speed / scene.run.samples_per_turn
    t = np.arange(t_rec, t1 + 0.5 * dt, dt)
    return t[t <= t1]


def _sample(scene, pieces, effects, g, stats, partial, message):
    m = scene.mechanism
    if not pieces:
        return SimulationResult(**{k: np.empty(0) for k in FIELDS}, scene=scene.name,
                                partial=partial, message=message, stats=stats,
                                provenance=provenance(scene))
    at, t0, t1 = _dense(pieces)
    t = _output_times(scene, lambda tt: at(tt)[0], t0, t1)
    Y = at(t)
    c = scene.bearing.clearance
    n = len(t)
    out = {k: np.empty(n) for k in ("slider_acceleration", "force_x", "force_y", "rod_angle",
                                    "slider_position")}
    solves_before = [getattr(e, "solves", 0) for e in effects]
    # a film with memory cannot be re-solved at a sample: its committed steps give it
    live = [e for e in effects if not getattr(e, "memory", False)]
    recorded = [e.recorded_force(t) for e in effects if getattr(e, "memory", False)]
    for i in range(n):
        q, A, X, qd, Ad, _ = _coordinates(m, Y[:, i])
        fx, fy = _joint_force(live, _joint(m, Y[:, i]))
        for rx, ry in recorded:
            fx, fy = fx + float(rx[i]), fy + float(ry[i])
        out["force_x"][i], out["force_y"][i] = fx, fy
        out["rod_angle"][i], out["slider_position"][i] = A, X
        out["slider_acceleration"][i] = accelerations(
            m, q, A, qd, Ad, fx, fy, g, scene.crank_torque, scene.slider_force)[2]
    stats["output_film_solves"] = int(sum(getattr(e, "solves", 0) for e in effects)
                                      - sum(solves_before))
    record = next((np.array(e.history).reshape(-1, len(FILM_RECORD)) for e in effects
                   if getattr(e, "memory", False)), np.empty((0, len(FILM_RECORD))))
    eps = np.hypot(Y[1], Y[2]) / c
    td = np.linspace(t[0], t[-1], 10 * (len(t) - 1) + 1) if len(t) > 1 else t
    Yd = at(td)
    return SimulationResult(
        t=t, crank_angle=Y[0], crank_speed=Y[3], rod_angle=out["rod_angle"],
        slider_position=out["slider_position"],
        slider_acceleration=out["slider_acceleration"], eps=eps, e_x=Y[1],
        e_y=Y[2], film_min=np.maximum(c * (1.0 - eps), 0.0), force_x=out["force_x"],
        force_y=out["force_y"], scene=scene.name, partial=partial, message=message,
        stats=stats, provenance=provenance(scene), dense_t=td, dense_e_x=Yd[1],
        dense_e_y=Yd[2], film_record=record,
        step_t=np.concatenate([p.ts[1:] for p in pieces]))


def _simulate_ideal(scene: Scene, progress=None) -> SimulationResult:
    """The rigid mechanism through the same interface (e = 0; force = joint reaction)."""
    m = scene.mechanism
    g = GRAVITY if scene.gravity else 0.0
    run = scene.run
    f = rigid_rhs(m, g, scene.crank_torque, scene.slider_force)
    start = time.perf_counter()
    sol = integrate_rigid(m, scene.crank_angle, scene.crank_speed, run.turns, g,
                          scene.crank_torque, scene.slider_force, _METHODS[run.integrator],
                          rtol=min(run.rtol, 1e-8), atol=1e-10)
    wall = time.perf_counter() - start
    t = _output_times(scene, lambda tt: sol.sol(tt)[0], 0.0, sol.t[-1])
    q, qd = sol.sol(t)
    qdd = np.array([f(0, [a, b])[1] for a, b in zip(q, qd)])
    A, A1, A2, X, X1, X2 = rigid_kinematics(m, q)
    Add = A1 * qdd + A2 * qd * qd
    Xdd = X1 * qdd + X2 * qd * qd
    # Joint reaction on the pin: F_x from the slider's equation, F_y from the rod's.
    Fx = -(m.slider_mass * Xdd + scene.slider_force + g * m.slider_mass)
    m11, m12, m22, s = _mass_terms(m, q, A)
    _, gA = _gravity_terms(m, q, A, g)
    L = m.rod_length
    Fy = -(m12 * qdd + m22 * Add + s * qd * qd + gA + Fx * L * np.sin(A)) / (L * np.cos(A))
    z = np.zeros_like(t)
    stats = {"wall_time": wall, "steps": len(sol.t) - 1, "rhs_evals": int(sol.nfev),
             "film_solves": 0, "contact_evals": 0, "integrator": run.integrator,
             "effects": []}
    return SimulationResult(t=t, crank_angle=q, crank_speed=qd, rod_angle=A, slider_position=X,
                            slider_acceleration=Xdd, eps=z, e_x=z, e_y=z, film_min=z + 0.0,
                            force_x=Fx, force_y=Fy, scene=scene.name, stats=stats,
                            provenance=provenance(scene))
