"""Mass-conserving (JFO) journal films on the finite-element film mesh, steady and transient.

In the variables of :mod:`bearingfem.film` the Jakobsson-Floberg-Olsson film reads

    div(H^3 grad P) = 6 w d(phi H)/d theta + 12 d(phi H)/dt,
    P >= 0,  0 <= phi <= 1,  P (1 - phi) = 0,

with phi the film fraction (1 in the full film). The Poiseuille term is the P1 operator of
:mod:`bearingfem.fe.assembly`; transport and storage of the content phi H are balanced on
the nodes' control volumes (:mod:`bearingfem.fe.volumes`), which conserves mass exactly;
:func:`bearingfem.solvers.jfo.jfo_solve` finds (P, phi).

* Steady (:func:`~bearingfem.fe.jfo_steady.solve_jfo`): the film is steady in the frame of the line of centres,
  where the content moves at w/2 = (omega - 2 gamma_dot)/2 and a squeeze eps_dot changes
  the local film at the rate eps_dot cos(theta).
* Transient (:class:`JFOFilm`): backward Euler on the content. The mesh follows the line
  of centres, so between steps the previous content is carried to the new mesh position
  (an exact rotation of the periodic rows by whole cells, a limited second-order shift
  for the rest, :func:`~bearingfem.fe.volumes.shift_rows`: each row's total is kept
  exactly, and the error a step's pressure takes from it is second order in the cell);
  over the step the content then moves at omega/2 relative to the bearing. With grooves
  the mesh stays fixed in the bearing and nothing is carried.

On gap, viscosity and density fields and with a tilted journal the balance takes its
stiffness, contents, faces and squeeze from :mod:`bearingfem.fe.jfo_fields` (``film``
arguments, a function op -> BalanceFilm); without them the rigid cylinder's fast path.

Flows (per solve): what the grooves (or a supply line) feed, what leaves the axial ends
and the rate of change of the content of the free volumes; their balance is the residual
of the solve, so it holds to round-off.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState, check_finite, check_positive
from ..errors import ConvergenceError
from ..validation import check_film_solve, check_grooves, check_jfo_supply
from ..scales import force_factor
from ..solution import FilmSolution
from ..solvers.jfo import JFOResult
from .assembly import FilmOperator, fe_operator
from .general import film_system, general_film
from .jfo_fields import FilmSpec, balance_films
from .jfo_balance import (BalanceSolve, FilmAdvance, JFOFlows, state_between, boundary_values,
                          full_content, step_balance, film_volumes, kept_set_pressure)
from .volumes import ControlVolumes, shift_rows
from .jfo_steady import jfo_film_solution, jfo_force, solve_jfo   # (re-exported)

__all__ = ["JFOFilm", "JFOSnapshot", "BalanceSolve", "FilmAdvance", "solve_jfo", "jfo_force",
           "film_volumes", "JFOFlows"]


@dataclass(frozen=True)
class JFOSnapshot:
    """The kept state of a :class:`JFOFilm` (what :meth:`JFOFilm.restore` takes back)."""

    time: float
    state: JournalState
    fraction: np.ndarray
    content: np.ndarray
    cavitated: np.ndarray
    solution: FilmSolution | None
    steps: int
    trend: "SetTrend | None" = None


@dataclass(frozen=True)
class SetTrend:
    """The universal variable u = P - (1 - phi) of the kept step on its nodes (< 0 in a
    cavity) and its rate over that step [1/s] (None after the first step): what
    :meth:`JFOFilm.step` extrapolates to place the next step's first cavitated set."""

    universal: np.ndarray
    rate: np.ndarray | None


MAX_CUTS = 3


class JFOFilm:
    """A transient JFO film on the FE film mesh: its state is the film fraction field.

    Parameters
    ----------
    bearing, state : the bearing and the journal state at the start
    n_theta, n_z, half : the P1 film mesh, as in :func:`bearingfem.solve_reynolds`
    grooves, supply_angle : the supply (grooves fixed in the bearing, flooded or starved)
    fraction : the film fraction at the start, a number or one value per node (1: full)
    ambient_pressure : pressure of the oil at the axial ends (and a supply line) above
        the cavitation pressure [Pa]; > 0 lets a cavity draw oil in from the ends
    fields : the film's :class:`~bearingfem.fields.FilmFields` (gap, viscosity, density),
        or a function (state, t) -> FilmFields of the journal state and the time t [s];
        None: the rigid cylinder (:mod:`bearingfem.fe.jfo_fields`)
    tilt, tilt_rate : the journal's tilt (tilt_x, tilt_y) [rad] and its rate [rad/s]
        (:func:`~bearingfem.fields.tilted_gap`), each a pair or a function t -> pair
    time : the time of the start [s] (the clock of ``fields`` and ``tilt``)

    With fields or a tilt the whole length is meshed and the film's ``moment`` reported;
    without them the film is the rigid cylinder's, on the fast path.

    ``step(state, dt)`` advances by dt [s] to the new journal state and keeps the result;
    ``trial(state, dt)`` computes the same step from the kept state without keeping it
    (what a time integrator's stages need). Both return a :class:`FilmSolution` with
    ``fraction`` and the step's ``mass_balance`` (feed - leakage - change of content).
    """

    def __init__(self, bearing: Bearing, state: JournalState, n_theta: int = 96,
                 n_z: int = 16, *, grooves=(), supply_angle=None, half: bool = True,
                 fraction=1.0, ambient_pressure: float = 0.0, fields=None,
                 tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0), time: float = 0.0):
        n_theta, n_z, supply_angle = check_film_solve(bearing, state, n_theta, n_z, "jfo",
                                                      "active-set", supply_angle)
        self.grooves = check_grooves(grooves, supply_angle, mass_conserving=True)
        self.ambient_pressure = check_jfo_supply("jfo", self.grooves, supply_angle,
                                                 ambient_pressure)
        self._film_spec = FilmSpec.checked(fields, tilt, tilt_rate)
        self.bearing = bearing
        half = half and self._film_spec is None
        self._operator = lambda s: fe_operator(bearing, s, n_theta, n_z, "P1", supply_angle,
                                               half, self.grooves)
        op = self._operator(state)
        self.time = check_finite("time", time)
        phi = np.broadcast_to(np.asarray(fraction, float), (op.mesh.ndofs,)).copy()
        if not np.all((phi >= 0.0) & (phi <= 1.0)):
            raise ValueError("fraction must lie in [0, 1] (one number or one per node)")
        self.state = state
        self.fraction = phi
        self.content = phi * self._full_content(op, state, self.time)   # per volume
        self.cavitated = phi < 1.0
        self.solution: FilmSolution | None = None
        self.steps = 0
        self.substeps = 1       # backward-Euler steps the last kept step was cut into
        self.trend: SetTrend | None = None

    def snapshot(self) -> JFOSnapshot:
        """The kept state (to go back to with :meth:`restore`, e.g. when an integrator
        steps back to an event inside its last step)."""
        return JFOSnapshot(self.time, self.state, self.fraction, self.content,
                           self.cavitated, self.solution, self.steps, self.trend)

    def restore(self, snapshot: JFOSnapshot) -> None:
        self.time, self.state = snapshot.time, snapshot.state
        self.fraction, self.content = snapshot.fraction, snapshot.content
        self.cavitated, self.solution = snapshot.cavitated, snapshot.solution
        self.steps = snapshot.steps
        self.trend = snapshot.trend

    def _carried(self, cv: ControlVolumes, state: JournalState, *values: np.ndarray):
        """Per-node arrays of the kept step on the mesh of ``state`` (a tuple): a periodic
        mesh starts at the line of centres, so it has turned by the change of the attitude
        angle since the kept state; a grooved or supply-line mesh stays in the bearing."""
        if not cv.periodic:
            return values
        cells = self._turn(state) / (2.0 * np.pi / cv.n_columns)
        return tuple(shift_rows(cv, np.stack(values), cells))

    def _turn(self, state: JournalState) -> float:
        """How far the line of centres has turned since the kept step [rad], in [-pi, pi)."""
        return float(np.mod(state.gamma - self.state.gamma + np.pi, 2.0 * np.pi) - np.pi)

    def _films(self, state: JournalState, time: float):
        """The function op -> BalanceFilm of the fields at ``state`` and ``time``, or None
        for the rigid cylinder."""
        if self._film_spec is None:
            return None
        spec, tilt, rate = self._film_spec.at(state, time)
        return balance_films(self.bearing, state, self._operator(state), spec, tilt, rate)

    def _full_content(self, op: FilmOperator, state: JournalState, time: float):
        """The content of the full film per volume at ``state`` and ``time``."""
        films = self._films(state, time)
        return full_content(film_volumes(op.mesh), state.eps) if films is None else \
            films(op).content

    def refilled(self, state: JournalState, time: float | None = None) -> bool:
        """Whether the gap at ``state`` (at ``time`` [s], default the kept time) has closed
        on the content of a kept cavity (the kept film would hold it at zero pressure
        where the oil now fills the gap)."""
        full = self._full_content(self._operator(state), state,
                                  self.time if time is None else time)
        return bool(np.any(self.cavitated & (self.content >= full)))

    def turned(self, state: JournalState) -> bool:
        """Whether a periodic mesh (it starts at the line of centres) has turned by more
        than half a cell since the kept step, which :meth:`instant` does not follow."""
        cv = film_volumes(self._operator(state).mesh)
        return bool(cv.periodic and abs(self._turn(state)) > np.pi / cv.n_columns)

    def instant(self, state: JournalState, warm: np.ndarray | None = None,
                time: float | None = None):
        """The film at ``state`` with the kept film, before any content moves: the volumes
        full at the kept step carry the Reynolds film of this instant's motion (Reynolds'
        condition is exact at rupture), the others stay cavities at zero pressure, the set
        attached to the mesh (the line of centres, or the bearing when grooved) until
        :meth:`step` moves it. What a time integrator sees between accepted steps: a
        function of the state with no jumps (a set that followed the carried content
        between steps would switch volumes one by one as the journal moves, each a jump of
        the force). ``time`` [s]: of the fields and tilt (default the kept time). Returns
        ((F_r, F_t) [N], cavitated set on all nodes, for ``warm`` of the next call)."""
        op = self._operator(state)
        mesh = op.mesh
        # held values on the fixed nodes, zero on the free ones
        P, _ = boundary_values(self.bearing, mesh, self.grooves, self.ambient_pressure)
        if self._film_spec is None:
            K = op.stiffness(state.eps)
            load = op.load(state.eps, state.eps_dot, state.wedge_speed)
        else:           # the Reynolds film of the fields at this instant
            spec, tilt, rate = self._film_spec.at(state, self.time if time is None else time)
            values, load = film_system(op, general_film(self.bearing, state, op, spec, tilt,
                                                        rate)[0], state.wedge_speed, state.eps)
            K = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape)
        P, cav = kept_set_pressure(K, load, P, mesh, self.cavitated, warm)
        ic, is_ = op.force_integrals(P)
        k = force_factor(self.bearing, mesh.half)
        return (k * float(ic), k * float(is_)), cav

    def _advance(self, state: JournalState, dt: float) -> FilmAdvance:
        op = self._operator(state)
        cv = film_volumes(op.mesh)
        # the extrapolated set first, then the kept one (better just after the squeeze
        # rate jumps, where the extrapolation continues the old trend)
        sets = [u for u in (self._predicted(dt), np.where(self.cavitated, -1.0, 1.0))
                if u is not None]
        old, *sets = self._carried(cv, state, self.content, *sets)
        first = tuple(u < 0.0 for u in sets)
        return step_balance(self.bearing, op, state, dt, old, first, self.grooves,
                             self.ambient_pressure, self._films(state, self.time + dt))

    def _predicted(self, dt: float) -> np.ndarray | None:
        """The universal variable u = P - (1 - phi) extrapolated over ``dt`` [s] from the
        last two kept steps, on the kept mesh (its cavity u < 0 is the first set tried;
        None before two steps). Fronts move several cells a step on a fine mesh but at a
        speed that changes slowly; the active set moves a reformation front about one
        cell per iteration, so the kept set costs as many iterations as the front has
        cells to travel, where the extrapolated one leaves a cell or less (measured on
        the journal film of benchmarks/jfo_iterations.py, see docs/convergence.md)."""
        if self.trend is None or self.trend.rate is None:
            return None
        return self.trend.universal + dt * self.trend.rate

    def _solution(self, state: JournalState, a: FilmAdvance, dt: float) -> FilmSolution:
        b = a.solve
        films = self._films(state, self.time + dt)
        return jfo_film_solution(self.bearing, state, a.op, b.P, b.phi, b.result, b.flows,
                              "fem-P1/jfo", None if films is None else films(a.op))

    def _where(self, state: JournalState, dt: float) -> str:
        return (f"JFO film step {self.steps + 1} to t = {self.time + dt:.6g} s "
                f"(eps = {state.eps:.6g}, eps_dot = {state.eps_dot:.6g} 1/s)")

    def trial(self, state: JournalState, dt: float) -> FilmSolution:
        """The step to ``state`` after ``dt`` [s], not kept (one step, never cut: raises
        :class:`~bearingfem.errors.ConvergenceError` when it does not converge)."""
        dt = check_positive("dt", dt)
        try:
            a = self._advance(state, dt)
        except ConvergenceError as e:
            raise e.at(self._where(state, dt)) from None
        return self._solution(state, a, dt)

    def step(self, state: JournalState, dt: float) -> FilmSolution:
        """Advance to ``state`` after ``dt`` [s] and keep the new film. A step whose
        solve does not converge is cut in two, the journal state between taken linearly
        (up to ``MAX_CUTS`` times; ``substeps`` then says into how many, and the returned
        film, flows included, is that of the last); if it still does not converge,
        :class:`~bearingfem.errors.ConvergenceError` is raised and the film stays at its
        last converged step."""
        dt = check_positive("dt", dt)
        try:
            sol, self.substeps = self._cut_step(state, dt, MAX_CUTS)
        except ConvergenceError as e:
            raise e.at(self._where(state, dt) + f", cut {MAX_CUTS} times") from None
        self.steps += 1
        return sol

    def _cut_step(self, state: JournalState, dt: float, cuts: int):
        try:
            return self._keep(state, dt), 1
        except ConvergenceError:
            if cuts == 0:
                raise
        kept = self.snapshot()
        try:
            _, first = self._cut_step(state_between(self.state, state), 0.5 * dt, cuts - 1)
            sol, last = self._cut_step(state, 0.5 * dt, cuts - 1)
        except ConvergenceError:
            self.restore(kept)
            raise
        return sol, first + last

    def _keep(self, state: JournalState, dt: float) -> FilmSolution:
        a = self._advance(state, dt)
        sol = self._solution(state, a, dt)
        self.trend = self._next_trend(a, state, dt)     # before the state moves on
        self.time += dt
        self.state, self.fraction, self.content = state, a.solve.phi, a.content
        self.cavitated = _cavitated_nodes(a.op, a.solve.result)
        self.solution = sol
        return sol

    def _next_trend(self, a: FilmAdvance, state: JournalState, dt: float) -> SetTrend:
        u = a.solve.P - (1.0 - a.solve.phi)
        if self.trend is None:
            return SetTrend(u, None)
        # the kept step's u carried to this step's mesh
        before, = self._carried(film_volumes(a.op.mesh), state, self.trend.universal)
        return SetTrend(u, (u - before) / dt)


def _cavitated_nodes(op: FilmOperator, res: JFOResult) -> np.ndarray:
    """The cavitated set of a solve on all nodes (fixed nodes: not cavitated)."""
    cav = np.zeros(op.mesh.ndofs, bool)
    cav[op.mesh.free] = res.cavitated
    return cav
