"""Time integration of a scene: variable-step, error-controlled, in segments.

The state is (q, e_x, e_y) and their rates: the eccentricity itself is integrated, so the
error control acts on it in units of the clearance (through X_PT and A it would be the
difference of two large numbers). A and X_PT follow from the kinematics.

The loop is :func:`mechanism.stepping.integrate` (scipy's solvers stepped here: a film with
memory commits at each accepted step); the saved samples are :mod:`mechanism.sampling`'s,
the ideal joint :mod:`mechanism.ideal`'s.

Integrating segment by segment (a quarter crank turn each) keeps every finished segment:
a run stopped by Ctrl-C, a solver failure or the journal passing eps = 1 without a contact
effect returns what it computed, marked partial, with the time and the reason.
"""
from __future__ import annotations

import dataclasses
import math
import signal
import threading
import time

import numpy as np

from bearingfem.design.tolerance import mesh_for_run, run_force_error

from .dynamics import accelerations, eccentricity_accelerations
from .effects import (CoulombFriction, FilmEffect, HertzContact, JointKinematics, LinearSpring,
                      hertz_stiffness)
from .ideal import simulate_ideal
from .joint import METHODS, coordinates, joint_force
from .parameters import GRAVITY
from .progress import Progress
from .result import SimulationResult
from .sampling import record_start, sample_run
from .scene import Scene
from .stepping import INTERRUPTED, STEP_FAILURE, STOPPED, integrate

#: Relative step of the joint states' forward differences in the Jacobian (sqrt of the
#: double precision's unit roundoff, as LSODA's own).
DIFFERENCE = 1.5e-8

__all__ = ["simulate", "build_effects", "JointEquations"]


class JointEquations:
    """y' = f(t, y) of the clearance joint's slider-crank: the joint's six states (crank
    angle, pin eccentricity e_x, e_y, crank speed, de_x/dt, de_y/dt) and the film's own
    states z (contract rule 16), and df/dy for an implicit integrator.

    scene; effects and film as :func:`build_effects` gives them; ``scale`` (6 + n): per
    state, the size below which it counts as zero in the Jacobian's differences (atol /
    rtol; only the joint's six are differenced); ``bar`` a
    :class:`~mechanism.progress.Progress` or None.
    """

    def __init__(self, scene: Scene, effects, film, scale, bar=None):
        self.scene, self.effects, self.film, self.bar = scene, effects, film, bar
        self.n_film = film.state_size if film is not None else 0
        self.scale = np.asarray(scale, float)
        self.gravity = GRAVITY if scene.gravity else 0.0
        self.calls = 0              # rhs calls, the Jacobian's included
        self.jacobians = 0
        self.force = (0.0, 0.0)     # the joint force of the last rhs call [N]
        self.t = 0.0                # the time of the last rhs call [s]: where a run stopped

    @property
    def has_jacobian(self) -> bool:
        """The film's states come with their tangent (contract rule 17), so the Jacobian
        costs 7 film solves, not 6 + n."""
        return bool(self.n_film) and self.film.has_tangent

    def motion(self, y, coords, fx: float, fy: float) -> list:
        """The joint's six rates at joint force (fx, fy) [N] (affine in it)."""
        m, sc = self.scene.mechanism, self.scene
        q, A, _, qd, Ad, _ = coords
        qdd, Add, Xdd = accelerations(m, q, A, qd, Ad, fx, fy, self.gravity,
                                      sc.crank_torque, sc.slider_force)
        exdd, eydd = eccentricity_accelerations(m, q, A, qd, Ad, qdd, Add, Xdd)
        return [qd, y[4], y[5], qdd, exdd, eydd]

    def rhs(self, t: float, y) -> list:
        self.calls += 1
        self.t = t
        coords = coordinates(self.scene.mechanism, y[:6])
        if self.n_film:
            self.film.z = y[6:]
        self.force = joint_force(self.effects,
                                 JointKinematics(y[1], y[2], y[4], y[5], -coords[4], t))
        if self.bar is not None:
            self.bar.update((coords[0] - self.scene.crank_angle) / (2 * math.pi))
        rates = self.motion(y, coords, *self.force)
        return rates + list(self.film.z_rate) if self.n_film else rates

    def jacobian(self, t: float, y) -> np.ndarray:
        """df/dy: forward differences in the joint's six states (films solved), and in
        the film's own states its tangent (contract rule 17) through the motion's response
        to the joint force."""
        self.jacobians += 1
        y = np.asarray(y, float)
        f0 = np.asarray(self.rhs(t, y), float)
        dF, d_rates = self.film.tangent()
        fx, fy = self.force
        J = np.empty((y.size, y.size))
        for j in range(6):
            h = DIFFERENCE * max(abs(y[j]), self.scale[j])
            yj = y.copy()
            yj[j] += h
            J[:, j] = (np.asarray(self.rhs(t, yj), float) - f0) / h
        coords = coordinates(self.scene.mechanism, y[:6])
        base = np.asarray(self.motion(y, coords, fx, fy))
        unit = max(1.0, math.hypot(fx, fy))
        by_x = (np.asarray(self.motion(y, coords, fx + unit, fy)) - base) / unit
        by_y = (np.asarray(self.motion(y, coords, fx, fy + unit)) - base) / unit
        J[:6, 6:] = np.outer(by_x, dF[0]) + np.outer(by_y, dF[1])
        J[6:, 6:] = d_rates
        return J


class RunStopped(Exception):
    """The run cannot go on; the message says where and why."""


def build_effects(scene: Scene):
    """The joint effects the scene calls for, and nothing else."""
    effects, film, contact = [], None, None
    b = scene.bearing
    if scene.lubrication is not None:
        lub = scene.lubrication
        options, every = dict(lub.options), 0
        if lub.rtol is not None:     # an accuracy asked instead of a mesh
            options, _ = mesh_for_run(b, lub.model, options, lub.rtol, scene.crank_speed,
                                      lub.eps_max)
            every = 200
        film = FilmEffect(b, lub.model, options, lub.eps_max, sample_every=every)
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


def _catch_sigint(hits: list):
    """Count Ctrl-C in ``hits`` instead of raising at once (the run stops at its next step,
    :func:`mechanism.stepping.integrate`); a second Ctrl-C raises at once. Returns the
    function that puts the previous handler back (nothing to do off the main thread)."""
    if threading.current_thread() is not threading.main_thread():
        return lambda: None

    def handler(signum, frame):
        hits.append(signum)
        if len(hits) > 1:
            raise KeyboardInterrupt
    previous = signal.signal(signal.SIGINT, handler)
    return lambda: signal.signal(signal.SIGINT, previous)


def _before_window(scene: Scene, last) -> str:
    """What a run stopped before its recorded turns keeps, said after its message ("" when
    it stopped inside them): its samples are then the whole run from t = 0
    (:func:`mechanism.sampling.output_times`), whose extremes include the start from the
    bearing centre, not a settled turn. ``last``: the run's last dense-output piece."""
    done = (float(last(last.t_max)[0]) - scene.crank_angle) / (2 * math.pi)
    first = scene.run.record_from_turn
    if done >= first:
        return ""
    return (f" (after {done:.3g} of {scene.run.turns:g} turns, before the recorded turns "
            f"from turn {first:g}: kept the whole run from t = 0)")


def _initial_state(scene: Scene):
    """Pin centred in the bush and moving with the slider: e = 0, e' = 0."""
    return np.array([scene.crank_angle, 0.0, 0.0, scene.crank_speed, 0.0, 0.0])


def simulate(scene: Scene, progress: bool | None = None) -> SimulationResult:
    """Integrate the scene; see :class:`mechanism.result.SimulationResult`."""
    if scene.joint == "ideal":
        return simulate_ideal(scene, progress)
    m = scene.mechanism
    g = GRAVITY if scene.gravity else 0.0
    effects, film, contact = build_effects(scene)
    c = scene.bearing.clearance
    run = scene.run
    turn_time = 2 * math.pi / scene.crank_speed
    q_end = scene.crank_angle + 2 * math.pi * run.turns
    t_limit = 4.0 * run.turns * turn_time
    bar = Progress(run.turns, f"{scene.name}", progress)
    n_film = film.state_size if film is not None else 0    # the film's own states
    a_len = run.atol if run.atol is not None else 1e-4 * c
    w = scene.crank_speed
    # the film's states (a bush's modal deflection [m]) at the joint's length tolerance
    atol = np.array([a_len / m.crank_length, a_len, a_len,
                     a_len * w / m.crank_length, a_len * w, a_len * w] + [a_len] * n_film)
    eq = JointEquations(scene, effects, film, atol / run.rtol, bar)
    rhs = eq.rhs

    def ev_end(t, y):
        return y[0] - q_end
    ev_end.terminal, ev_end.direction = True, 1

    # the wall: eps = 1, or beyond it for a film whose bush carries the journal there
    # (contract rule 15) when no contact effect takes over at eps = 1
    wall = film.wall if film is not None and contact is None else 1.0

    def gap(t, y):   # eps - wall: positive in contact
        return math.hypot(y[1], y[2]) / c - wall

    def ev_in(t, y):
        return gap(t, y)
    ev_in.terminal, ev_in.direction = True, 1

    def ev_out(t, y):
        return gap(t, y)
    ev_out.terminal, ev_out.direction = True, -1

    events = [ev_end, None]

    q_rec = record_start(scene)

    def accept(t, y):        # each accepted step: a film with memory commits there
        _, _, _, _, Ad, _ = coordinates(m, y[:6])
        if n_film:
            film.z = y[6:]
        # recording where the saved samples are (mechanism.sampling.output_times)
        return film.commit(JointKinematics(y[1], y[2], y[4], y[5], -Ad, t),
                           recording=y[0] >= q_rec)

    opts = dict(method=METHODS[run.integrator], rtol=run.rtol, atol=atol)
    if eq.has_jacobian and opts["method"] in ("LSODA", "BDF", "Radau"):
        opts["jac"] = eq.jacobian
    if run.max_step is not None:
        opts["max_step"] = run.max_step

    t, y = 0.0, np.concatenate([_initial_state(scene), np.zeros(n_film)])
    in_contact = gap(t, y) > 0.0
    pieces, steps, message, partial, cuts = [], 0, "completed", False, []
    first_step = None
    start = time.perf_counter()
    sigints = []
    restore = _catch_sigint(sigints)
    try:
        while True:
            t_stop = min(t + 0.25 * turn_time, t_limit)
            if first_step is not None and opts["method"] != "LSODA":
                opts["first_step"] = min(first_step, t_stop - t)
            events[1] = ev_out if in_contact else ev_in
            sol = integrate(rhs, (t, t_stop), y, events=events,
                            accept=accept if film is not None else None,
                            interrupted=lambda: bool(sigints), **opts)
            cuts.extend(sol.cuts)
            if sol.status == -1:
                raise RunStopped(f"integrator failed at t = {sol.t[-1]:.6g} s: {sol.message}")
            if len(sol.t) > 1:
                pieces.append(sol.sol)
                steps += len(sol.t) - 1
                first_step = sol.t[-1] - sol.t[-2]
            t, y = float(sol.t[-1]), sol.y[:, -1]
            if sol.status == INTERRUPTED:     # Ctrl-C: the steps taken are kept above
                raise KeyboardInterrupt
            if sol.status == STOPPED:         # a step failed: the steps before it kept above
                # where the failing right-hand side was asked, not the segment's start
                raise RunStopped(f"stopped at t = {max(t, eq.t):.6g} s: {sol.message}")
            if sol.t_events[0].size:
                break
            if sol.t_events[1].size:
                if in_contact:
                    in_contact = False
                elif contact is None and scene.spring is None:
                    raise RunStopped(
                        f"the journal reached the bearing wall (eps = {wall:g}) at t = {t:.6g} s, "
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
    except (ValueError, ArithmeticError, np.linalg.LinAlgError, STEP_FAILURE) as err:
        # where the failing right-hand side was asked, not the segment's start (the
        # integrator raises from inside a segment of a quarter turn)
        partial, message = True, (f"stopped at t = {max(t, eq.t):.6g} s: "
                                  f"{type(err).__name__}: {err}")
    finally:
        restore()
    if partial and pieces:
        message += _before_window(scene, pieces[-1])
    wall = time.perf_counter() - start
    bar.close(message if partial else "done", complete=not partial)
    stats = {"wall_time": wall, "steps": steps, "rhs_evals": eq.calls,
             "jacobians": eq.jacobians, "film_solves": film.solves if film else 0,
             "film_steps": film.steps if film is not None else 0,
             "contact_evals": contact.evaluations if contact else 0,
             "integrator": run.integrator, "rtol": run.rtol, "atol_length": a_len,
             "effects": [type(e).__name__ for e in effects],
             "step_cuts": [dataclasses.asdict(c) for c in cuts]}
    if film is not None and film.start is not None:   # where a film with memory began
        stats["film_start"] = [float(v) for v in film.start]
    if film is not None:     # what the model records about itself (e.g. a table's error)
        stats.update(film.film_model.run_notes(scene.bearing, film.options))
    if film is not None and film.sample_every and film.deepest is not None:
        # the film's estimated error over the run: at the state nearest the wall and at
        # up to 7 of the states met, spread over the run
        met = film.samples[::max(1, len(film.samples) // 7)][:7] + [film.deepest]
        stats.update(film_rtol=scene.lubrication.rtol,
                     film_mesh=[film.options["n_theta"], film.options["n_z"],
                                film.options.get("element", "P1")],
                     film_force_error=run_force_error(scene.bearing, film.model,
                                                      film.options, met))
    return sample_run(scene, pieces, effects, g, stats, partial, message)
