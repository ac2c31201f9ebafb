"""The integration loop: scipy's OdeSolver objects stepped here, so accepted steps are
explicit.

:func:`integrate` is ``scipy.integrate.solve_ivp``'s own loop (no ``t_eval``, dense output
on, events handled by scipy's ``find_active_events`` / ``handle_events``), so where nothing
is committed a run steps exactly as ``solve_ivp`` would, to the bit. Two things are added:

* ``accept(t, y)`` is called once per accepted step, at its end (at a terminal event's
  root when one ends the step), before the next step begins, and never on a rejected
  step or inside an event function: where a film with memory commits
  (:mod:`bearingfem.contract`, rule 11). When it returns True (what it committed may have
  changed ``fun`` at (t, y), e.g. a refill's force acting at once) a solver that keeps
  the derivative at its last state (Runge-Kutta's first-same-as-last, Radau's error
  estimate and Jacobian) has it evaluated again there: the next step then starts from
  the film as committed, not from the one before.
* A step that raises :data:`STEP_FAILURE` (a film solve that did not converge, in the
  right-hand side or in ``accept``) is cut: the loop goes back to the last accepted state,
  starts the solver again there with half the failed step as its largest and first step
  and records it (:class:`StepCut`); after ``max_cuts`` cuts in a row the error
  propagates. Each :data:`RELAX_AFTER` accepted steps after a cut the largest step is
  raised fourfold (the solver started again at the accepted state, from the step it had
  reached) until it is the caller's again, or dropped once the solver's own step has
  fallen below half of it: a solve that failed at one instant does not hold the rest of
  the call to its step.
* A step that fails past its cuts, or whose right-hand side raises a ValueError,
  ArithmeticError or LinAlgError, ends the call with status :data:`STOPPED` and the error
  as its message: the steps accepted before it are returned, not lost with the exception.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate._ivp.common import OdeSolution
from scipy.integrate._ivp.ivp import (BDF, LSODA, MESSAGES, METHODS, find_active_events,
                                      handle_events, prepare_events)

from bearingfem.errors import ConvergenceError

__all__ = ["integrate", "Segment", "StepCut", "STEP_FAILURE", "INTERRUPTED", "STOPPED"]

#: A segment's status when the caller's ``interrupted()`` stopped it between steps.
INTERRUPTED = 2
#: A segment's status when a step failed for good (module docstring): the steps before it.
STOPPED = 3
#: What else a step may raise that stops the call (a film asked outside its range, a
#: singular system) with the steps before it kept.
STEP_ERRORS = (ValueError, ArithmeticError, np.linalg.LinAlgError)

#: What cuts a step instead of stopping the run: a solve that did not converge.
STEP_FAILURE = ConvergenceError
#: Accepted steps after a cut before the largest step is raised fourfold. Why: held to the
#: end of the call, one cut at a failed film solve kept a seed-pin EHD run (24 modes) at
#: 1.5e-7 s steps for the last sixth of a turn: 27000 steps where 900 did the first half.
RELAX_AFTER = 20


@dataclass(frozen=True)
class StepCut:
    """A step the loop cut: where it started [s], the largest step allowed after it [s]
    and why."""

    t: float
    max_step: float
    reason: str


@dataclass(frozen=True)
class Segment:
    """One call of :func:`integrate`, as ``solve_ivp`` returns it: the accepted step ends
    ``t`` and states ``y`` (n x len(t)), the dense output ``sol``, the event roots per
    event, ``status`` (0 end reached, 1 terminal event, -1 solver failed, 2 interrupted by
    the caller's ``interrupted()`` between steps: the steps taken so far, 3 a step failed
    for good: the steps before it, the error in ``message``), the solver's message, and
    the steps cut."""

    t: np.ndarray
    y: np.ndarray
    sol: OdeSolution
    t_events: list
    status: int
    message: str
    cuts: tuple = ()


def integrate(fun, t_span, y0, method: str = "LSODA", events=(), accept=None,
              max_cuts: int = 20, interrupted=None, **options) -> Segment:
    """Integrate y' = fun(t, y) over ``t_span`` with the scipy method ``method`` (a name of
    ``solve_ivp``), ``events`` as ``solve_ivp`` takes them, ``accept(t, y)`` called at each
    accepted step (module docstring) and the solver's ``options`` (rtol, atol, max_step,
    first_step, ...)."""
    solver_class = METHODS[method]
    t0, tf = map(float, t_span)
    solver = solver_class(fun, t0, y0, tf, vectorized=False, **options)
    ts, ys, interpolants, cuts = [t0], [y0], [], []
    free = {k: v for k, v in options.items() if k != "first_step"}   # a restart's options
    top = options.get("max_step", np.inf)

    def restart(t, y, first_step, max_step=None):
        """The solver started again at (t, y): the caller's options, this first step and
        (None: the caller's) largest step."""
        extra = {} if max_step is None else {"max_step": max_step}
        return solver_class(fun, t, y, tf, vectorized=False,
                            **dict(free, first_step=first_step, **extra))
    limit, in_row, since = None, 0, 0      # the cut's largest step, cuts in a row, steps
    tried = options.get("first_step")      # the first step of the latest (re)start
    events, max_events, event_dir = prepare_events(events)
    event_count = np.zeros(len(events))
    g = [event(t0, y0) for event in events]
    t_events = [[] for _ in range(len(events))]
    status, message = None, ""
    while status is None:
        try:
            message = solver.step()
            if solver.status == "finished":
                status = 0
            elif solver.status == "failed":
                status = -1
                break
            t_old, t, y = solver.t_old, solver.t, solver.y
            sol = solver.dense_output()
            roots = []
            g_new = [event(t, y) for event in events]
            active_events = find_active_events(g, g_new, event_dir)
            if active_events.size > 0:
                count = event_count.copy()
                count[active_events] += 1
                root_indices, found, terminate = handle_events(
                    sol, events, active_events, count, max_events, t_old, t)
                roots = list(zip(root_indices, found))
                if terminate:
                    status = 1
                    t = found[-1]
                    y = sol(t)
            changed = accept is not None and bool(accept(t, y))
        except STEP_FAILURE as err:
            if in_row >= max_cuts:
                status, message = STOPPED, f"{type(err).__name__}: {err}"
                break
            t_last, y_last = ts[-1], ys[-1]
            # the step that failed, or (a solver that failed its first step has none) the
            # first step it was started with: each cut halves what was last tried
            h = solver.step_size or tried or abs(tf - t_last)
            limit, in_row, since = min(top, 0.5 * h), in_row + 1, 0
            tried = min(limit, abs(tf - t_last))
            cuts.append(StepCut(float(t_last), limit, f"{type(err).__name__}: {err}"))
            status = None
            # the limit as the first step too: a solver's own first-step choice (RK45,
            # BDF) evaluates fun ahead, where it failed
            solver = restart(t_last, y_last, tried, limit)
            continue
        except STEP_ERRORS as err:
            status, message = STOPPED, f"{type(err).__name__}: {err}"
            break
        # the step is accepted: keep it (solve_ivp's bookkeeping)
        if active_events.size > 0:
            event_count[active_events] += 1
            for e, te in roots:
                t_events[e].append(te)
        g = g_new
        interpolants.append(sol)
        if len(ts) > 1 and ts[-1] == t:
            interpolants.pop()
        else:
            ts.append(t)
            ys.append(y)
        if changed and status is None and hasattr(solver, "f"):
            solver.f = solver.fun(t, y)     # LSODA and BDF keep none (BDF: differences)
        if limit is not None and status is None:
            since += 1
            if since >= RELAX_AFTER:        # past the failed instant: raise the limit,
                # or drop it once the solver's own step no longer reaches it
                h = solver.step_size or limit
                raised = 4.0 * limit if h >= 0.5 * limit and 4.0 * limit < top else None
                since = 0
                first = min(h, abs(tf - t))             # the step it had reached
                try:
                    solver = restart(t, y, first, raised)
                    limit, in_row, tried = raised, 0, first
                except STEP_FAILURE:        # the solve fails here still: keep the solver
                    pass
        if interrupted is not None and interrupted() and status is None:
            # Ctrl-C seen by the caller's handler: stop here, between steps, in Python (an
            # interrupt raised inside a compiled solver's callback can be lost), and give
            # back the steps taken so far (the caller keeps them)
            status, message = INTERRUPTED, "interrupted"
    message = message if status == STOPPED else MESSAGES.get(status, message)
    ts = np.array(ts)
    dense = OdeSolution(ts, interpolants, alt_segment=solver_class in (BDF, LSODA)) \
        if interpolants else None
    return Segment(ts, np.vstack(ys).T, dense, [np.asarray(te) for te in t_events],
                   status, message, tuple(cuts))
