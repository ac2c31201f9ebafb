"""The thermal film of the mechanism ("fem-thd"): the Reynolds-condition film on the
viscosity of an oil whose temperature field is kept, and advanced at film steps along a
run, as the "fem-jfo" film's content is.

At a state alone (``film_force``, ``film_solution``) the temperatures are the steady
thermal film's at the journal's position and speed (:func:`~bearingfem.routes.thd.solve_thd`,
the velocities set apart: the temperature does not follow a vibration), and the film at
the whole state (squeeze included) is solved on that viscosity field.

Along a run (:class:`ThermalRun`) the temperature field starts as the steady one at the
first state (or at the supply temperature) and advances at the integrator's accepted
steps, once ``film_step`` has passed, by one backward-Euler step of the transient energy
equation, rho cp h dT/dt + (the steady operator) = Phi (:func:`~bearingfem.thermal.energy.
solve_energy` with ``storage``), on the film of the committed state; between film steps the
film is solved on the kept viscosity field, and the change of force a film step makes is
faded in over the next (:func:`~bearingfem.transient.faded_force`), as the JFO film's.
Each film step's energy balance (dissipation = convected + conducted + grooves + stored)
is kept with its film (``FilmStep.solution.thermal``). A conducting bush
(``Thermal(bush=BushConduction(...))``) enters each film step as a quasi-steady conductor:
its steady inner response (:mod:`bearingfem.thermal.bush`, no heat capacity) solved
together with the film's backward-Euler step, i.e. the bush follows the film at once
(its thermal time constant, seconds, taken as short against the film steps; docs/thd.md). The journal may turn either way:
with omega < 0 the oil enters each arc at the grooves' leading edges (the energy
equation's inlet and outlet edges swap, :func:`~bearingfem.thermal.energy.energy_operator`
with ``reverse``), so a pin whose rotation reverses, as the slider-crank's piston pin,
runs with temperature. At a film step with omega = 0 exactly no Couette flow carries heat
and the inlets are undefined: the temperatures are held and the step is taken at the next
accepted state (over the whole time since the last film step).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..bearing import Bearing, JournalState
from ..contract import FilmStep, StatelessRun
from ..film import film_thickness
from ..lubricant import Lubricant
from ..routes.thd import ReynoldsFieldFilm, check_thermal, solve_thd, thermal_operator
from ..thermal.bush import bush_wall
from ..thermal.mixing import groove_mixing
from ..thermal.energy import energy_operator, solve_energy
from ..thermal.operator import arc_degree
from ..thermal.spec import Thermal, ThermalRecord
from ..transient import faded_force, since_film_step
from .registry import FilmModel, register

__all__ = ["ThermalModel", "ThermalRun", "ThermalSnapshot"]

TOL = 1e-10     # the Reynolds film's complementarity tolerance


def _steady(state: JournalState) -> JournalState:
    return replace(state, eps_dot=0.0, gamma_dot=0.0)


def _check(lubricant, thermal, grooves):
    if lubricant is None or thermal is None:
        raise ValueError("film model 'fem-thd' needs lubricant= (a Lubricant with density, "
                         "specific heat and conductivity) and thermal= (a Thermal)")
    if not grooves:
        raise ValueError("film model 'fem-thd' needs grooves (the oil supply)")
    if any(g.fraction < 1.0 for g in grooves):
        raise ValueError("film model 'fem-thd' takes flooded grooves (fraction 1): its "
                         "film has Reynolds' condition")
    check_thermal(lubricant, thermal, JournalState(0.5, omega=1.0), "reynolds", "P1")


@dataclass(frozen=True)
class ThermalSnapshot:
    """What a :class:`ThermalRun` keeps: the time of its last film step [s], the nodal
    temperatures [K], the viscosity at the film's quadrature points [Pa s], the last film
    step's change of force (F_r, F_t) [N] and its fade time [s], the number of steps and
    the last film's solve (:class:`~bearingfem.solvers.cavitation.LCPResult`)."""

    t: float
    temperature: np.ndarray
    viscosity: np.ndarray
    jump: tuple
    fade: float
    steps: int
    warm: object = None     # the last film's solve, which starts the next (its cost only)
    bush_inner: object = None   # the conducting bush's inner temperatures [K] (GMRES start)


class ThermalRun(StatelessRun):
    """The "fem-thd" model along one integration (module docstring).

    Parameters
    ----------
    bearing : the bearing (its viscosity the film's reference scale only)
    n_theta, n_z, grooves : the film (whole length, P1, Reynolds' condition)
    lubricant, thermal : the oil and the heat exchanges (:class:`Thermal`)
    film_step : [s] time between film steps (0: a film step at every accepted step)
    initial : "steady" (the steady thermal film at the first state) or "supply" (the
        supply temperature everywhere)
    """

    memory = True

    def __init__(self, bearing: Bearing, n_theta: int, n_z: int, grooves, lubricant,
                 thermal, film_step: float = 0.0, initial: str = "steady"):
        self.bearing, self.n_theta, self.n_z = bearing, n_theta, n_z
        self.grooves, self.lubricant, self.thermal = tuple(grooves), lubricant, thermal
        self.film_step, self.initial = float(film_step), initial
        self.T = self.mu = self._bush = None
        self.t, self.steps, self._jump, self._fade, self._warm = 0.0, 0, (0.0, 0.0), 1.0, None

    def _operator(self, state):
        return thermal_operator(self.bearing, state, self.n_theta, self.n_z,
                                grooves=self.grooves)

    def start(self, state: JournalState, t: float) -> None:
        """Begin at ``state``, time ``t`` [s], with the initial temperatures (ValueError
        first when the options lack the oil, the heat exchanges or the grooves, or the
        steady start has a journal at rest)."""
        _check(self.lubricant, self.thermal, self.grooves)
        if self.initial == "steady" and state.omega == 0.0:
            raise ValueError("initial 'steady' needs omega != 0 at the first state (a "
                             "journal at rest has no steady thermal film); use initial "
                             "'supply'")
        if self.initial == "steady":
            sol = solve_thd(self.bearing, _steady(state), self.n_theta, self.n_z,
                            lubricant=self.lubricant, thermal=self.thermal,
                            grooves=self.grooves)
            self.T, self.mu = sol.temperature, sol.thermal.viscosity_quadrature
        else:
            op = self._operator(state)
            self.T = np.full(op.mesh.ndofs, self.thermal.supply_temperature)
            self.mu = self.lubricant.viscosity_at(
                0.0, temperature=op.at_quadrature(self.T))
        self.t, self.steps, self._jump, self._fade, self._warm = float(t), 0, (0.0, 0.0), \
            1.0, None
        self._bush = None

    def _film(self, state, viscosity) -> ReynoldsFieldFilm:
        f = ReynoldsFieldFilm(self.bearing, state, self._operator(state), "P1", self.grooves,
                              TOL, self._warm)
        f.solve(viscosity / self.bearing.viscosity)
        self._warm = f
        return f

    def force(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] at a trial ``state`` and time ``t`` on the kept viscosity."""
        if self.T is None:
            self.start(state, t)
        f = self._film(state, self.mu).force_local()
        return faded_force(f, self._jump, float(t) - self.t, self._fade)

    def commit(self, state: JournalState, t: float) -> FilmStep | None:
        """Advance the temperatures to the accepted ``state`` at ``t`` (one backward-Euler
        step over the time since the last film step, once ``film_step`` has passed)."""
        if self.T is None:
            self.start(state, t)
        t = float(t)
        dt = since_film_step(t, self.t)
        if dt <= 1e-12 * max(abs(self.t), 1e-3) or not dt > self.film_step:
            return None
        if state.omega == 0.0:
            # no Couette flow, no inlet edge: the temperatures are held, the step deferred
            return None
        before = self.force(state, t)
        old = self.T
        T, mu, energy = self._advance(state, dt)
        self.T, self.mu = T, mu
        film = self._film(state, mu)
        after = film.force_local()
        self._jump = (before[0] - after[0], before[1] - after[1])
        self._fade = max(self.film_step, dt)
        self.t, self.steps = t, self.steps + 1
        record = ThermalRecord(balance=energy.balance,
                               journal_temperature=energy.journal_temperature,
                               inlet_temperatures=(), viscosity=self.lubricant.viscosity_at(
                                   film.last.pressure * self.bearing.pressure_scale,
                                   temperature=T),
                               viscosity_quadrature=mu, iterations=1,
                               temperature_change=float(np.max(np.abs(T - old))),
                               pressure_change=0.0, bush=energy.bush)
        sol = replace(film.solution(), temperature=T, temperature_max=float(np.max(T)),
                      thermal=record)
        return FilmStep(t, state, after, sol)

    def _advance(self, state, dt):
        """(T, viscosity at the film's points, energy solution) one backward-Euler step
        of the energy equation on the film of ``state`` with the kept viscosity."""
        b, oil, op = self.bearing, self.lubricant, self._operator(state)
        eop = energy_operator(op.mesh, state.omega < 0.0,
                              arc_degree(op.mesh, bush=self.thermal.bush is not None))
        film = self._film(state, self.mu)
        pressure = film.last.pressure * b.pressure_scale
        P, ones = film.last.pressure, np.ones(op.mesh.ndofs)
        p_arc, T_arc = eop.at_points(np.column_stack([pressure, self.T]))
        mu_arc = oil.viscosity_at(p_arc, temperature=T_arc)
        flow = eop.flow(b, state, P, ones, mu_arc, oil)
        mixing = groove_mixing(b, state, op.mesh, eop.edges, P, ones,
                               oil.viscosity_at(pressure, temperature=self.T), self.thermal)
        h = b.clearance * film_thickness(eop.theta - state.gamma, state.eps)
        capacity = oil.mass_density * oil.specific_heat * h / dt
        # the dissipation implicit to first order, as the steady film's steps take it
        slope = flow.dissipation * oil.viscosity_temperature_derivative(T_arc, p_arc) / mu_arc
        # the conducting bush as a quasi-steady conductor: its steady inner response
        # (no heat capacity) joined to the film's backward-Euler step (module docstring)
        wall = None if self.thermal.bush is None else \
            bush_wall(self.thermal.bush, b.radius, b.length, op.mesh, eop)
        energy = solve_energy(b, eop, flow, mixing, self.thermal.walls,
                              linearised=(slope, T_arc), storage=(capacity, T_arc),
                              bush=wall, bush_start=self._bush)
        self._bush = energy.bush_inner
        T = energy.temperature
        p_q, T_q = op.at_quadrature(np.stack([pressure, T]))
        mu = oil.viscosity_at(p_q, temperature=T_q)
        return T, mu, energy

    def snapshot(self) -> ThermalSnapshot:
        return ThermalSnapshot(self.t, self.T, self.mu, self._jump, self._fade, self.steps,
                               self._warm.last if isinstance(self._warm, ReynoldsFieldFilm)
                               else self._warm, self._bush)

    def restore(self, snapshot: ThermalSnapshot) -> None:
        self.t, self.T, self.mu = snapshot.t, snapshot.temperature, snapshot.viscosity
        self._jump, self._fade, self.steps = snapshot.jump, snapshot.fade, snapshot.steps
        self._warm, self._bush = snapshot.warm, snapshot.bush_inner

    def replay(self, start: tuple, steps):
        """The film steps of a run taken again from ``start`` = (t, JournalState) and the
        committed (t, JournalState): yields (t, FilmSolution) per step, the same solves on
        the same data as the run (a state at rest defers its step: it yields none)."""
        t0, s0 = start
        self.start(s0, t0)
        for t, state in steps:
            self.film_step, keep = 0.0, self.film_step
            step = self.commit(state, t)
            self.film_step = keep
            if step is not None:
                yield self.t, step.solution


class ThermalModel(FilmModel):
    """Options: the mesh (``n_theta``, ``n_z``), ``grooves`` (the oil supply, required),
    ``lubricant`` (a :class:`~bearingfem.lubricant.Lubricant` with density, specific heat
    and conductivity), ``thermal`` (a :class:`~bearingfem.thermal.Thermal`), ``film_step``
    [s] and ``initial`` ("steady" or "supply") for a run."""

    name = "fem-thd"
    defaults = dict(n_theta=48, n_z=8, grooves=(), lubricant=None, thermal=None,
                    film_step=0.0, initial="steady")
    rules = {"lubricant": ("instance", (Lubricant,)), "thermal": ("instance", (Thermal,)),
             "initial": ("choice", ("steady", "supply"))}
    numeric = True
    memory = True

    def _film_solution(self, bearing, state, n_theta, n_z, grooves, lubricant, thermal,
                       film_step=0.0, initial="steady"):
        _check(lubricant, thermal, grooves)
        thd = solve_thd(bearing, _steady(state), n_theta, n_z, lubricant=lubricant,
                        thermal=thermal, grooves=grooves)
        if state.eps_dot == 0.0 and state.gamma_dot == 0.0:
            return thd
        op = thermal_operator(bearing, state, n_theta, n_z, grooves=grooves)
        f = ReynoldsFieldFilm(bearing, state, op, "P1", tuple(grooves), TOL)
        f.solve(thd.thermal.viscosity_quadrature / bearing.viscosity)
        return replace(f.solution(), temperature=thd.temperature,
                       temperature_max=thd.temperature_max, thermal=thd.thermal)

    def _film_force(self, bearing, state, **options):
        return self._film_solution(bearing, state, **options).force_local

    def _along_run(self, bearing, n_theta, n_z, grooves, lubricant, thermal, film_step,
                   initial):
        # checked when the run starts: the contract asks a run film of the defaults too
        return ThermalRun(bearing, n_theta, n_z, grooves, lubricant, thermal, film_step,
                          initial)


register(ThermalModel())
