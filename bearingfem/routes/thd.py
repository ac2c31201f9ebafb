"""The thermal film: pressure, film fraction and temperature coupled through the viscosity.

A fixed point on the temperature field with the dissipation's temperature dependence
taken implicitly: at the temperatures T_k the oil's viscosity mu(p_k, T_k) at the film's
quadrature points makes a viscosity field (:class:`~bearingfem.fields.FilmFields`) for the
isothermal film, whose pressure (and JFO fraction) gives the flow and dissipation of the
energy equation (:mod:`bearingfem.thermal.energy`, the grooves' mixing solved with it),
and the energy equation gives T_{k+1} with the dissipation linearised about T_k,

    Phi(T) = Phi_k + (d Phi/d T) (T - T_k),   d Phi/d T = Phi_k (d mu/d T) / mu,

the slope of a film whose viscosity changes uniformly (its shear term ~ mu at any
pressure, its pressure-flow term ~ mu because the pressure follows the viscosity). Why:
the dissipation falling as the oil heats is the loop's strongest feedback; lagged, it
makes a fixed point of factor ~0.3 (10 steps to 1e-6 K on the designer's bearing), taken
implicitly it leaves the pressure's lag only (factor ~1e-2, 6 steps; docs/thd.md). At the
fixed point T_{k+1} = T_k, so the linearisation changes the path, not the answer.

Each step reuses what the mesh fixes: the film's stiffness is assembled from its element
tables (:func:`~bearingfem.fe.general.general_assembly`), its cavitated set and factors
start from the last step's, and the energy equation is assembled on its operator's tables
(:func:`~bearingfem.thermal.energy.energy_operator`).

Converged when the temperatures' error is below ``temperature_tol`` [K] at every node
and the film's pressure is within ``pressure_rtol`` of its peak of the converged one, by
the contraction's estimate: a fixed point of contraction rho is within rho / (1 - rho)
of its last change of the answer (the last energy solve's largest nodal change; the
pressure's, whose error follows the temperatures' it was solved on), rho the largest
ratio of successive temperature changes measured in this solve (the first, the heating
from a cold start, included), once two are measured; for rho > 1/2 the factor exceeds
1 (a relaxed iteration's). Before, or for rho >= 1 (no contraction measured), the change
itself is the test. The film returned is the one on the returned temperatures;
otherwise :class:`~bearingfem.errors.ConvergenceError`. Why the estimate: the
pressure's lag contracts by ~1e-2 a step, so the change overstates the error by ~100
and the plain test took one more film and energy solve (docs/thd.md).
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from ..bearing import PLAUSIBLE, Bearing, JournalState
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fields import FilmFields
from ..lubricant import Lubricant
from ..oil_range import CELSIUS, OIL_TEMPERATURE_RANGE
from ..solution import FilmSolution
from ..solvers.cavitation import LCPResult
from ..thermal.bush import bush_wall
from ..thermal.energy import EnergyFlow, Mixing, energy_operator, solve_energy
from ..thermal.operator import arc_degree
from ..thermal.mixing import groove_mixing
from ..thermal.spec import Thermal, ThermalRecord, warn_out_of_range
from .base import Route
from .thd_film import ReynoldsFieldFilm
from .jfo import JFOFilm
from .problem import OPTION_DEFAULTS, FilmProblem

__all__ = ["ThermalFilm", "solve_thd", "ThermalRecord", "thermal_operator",
           "ReynoldsFieldFilm", "ThermalIteration", "error_factor"]

CAVITATION = ("reynolds", "jfo")

#: The largest relative change of the film's coefficient h^3/mu at any quadrature point
#: for which the last film's factors precondition CG on the next film instead of a new
#: factorisation: its preconditioned spectrum then lies in [1 - d, 1 + d] (each element's
#: stiffness scales by its points' ratios), so CG gains a factor of about d/2 a step
#: (about 9 steps to its 1e-12 at d = 0.05, against a factorisation's 25-35 solves).
FACTOR_REUSE = 0.05
#: Contraction rates measured before the stopping test trusts their largest: one is not
#: enough, a warm solve's first (7.6e-3 on the 50 mm bearing at 96 x 16) lies below the
#: next (1.2e-2), the error then 1.5x its estimate
MIN_RATES = 2


def check_thermal(lubricant, thermal, state, cavitation, element):
    """What a thermal film needs before any work (ValueError naming the parameter)."""
    if not isinstance(thermal, Thermal):
        raise ValueError(f"thermal must be a Thermal, got {type(thermal).__name__}")
    if not isinstance(lubricant, Lubricant):
        raise ValueError(f"a thermal film needs lubricant=Lubricant (with density, specific "
                         f"heat and conductivity), got {type(lubricant).__name__}")
    for name in ("mass_density", "specific_heat", "conductivity"):
        if getattr(lubricant, name) is None:
            raise ValueError(f"a thermal film needs the lubricant's {name} (e.g. "
                             f"Lubricant.two_point or Lubricant.iso_vg)")
    if lubricant.density is not None or lubricant.bulk_modulus is not None:
        raise ValueError("a thermal film takes an incompressible lubricant (no density "
                         "law or bulk_modulus)")
    check_supply_temperature(lubricant, thermal)
    if state.eps_dot != 0.0 or state.gamma_dot != 0.0:
        raise ValueError("a thermal film is steady: eps_dot and gamma_dot must be 0")
    if not (math.isfinite(state.omega) and state.omega != 0.0):
        raise ValueError(f"omega must be finite and nonzero for a thermal film (its sign "
                         f"says at which groove edges the oil enters; a journal at rest "
                         f"carries no oil through), got {state.omega!r}")
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION} for a thermal film, got "
                         f"{cavitation!r}")
    if cavitation == "jfo" and element != "P1":
        raise ValueError(f"element must be 'P1' with cavitation 'jfo', got {element!r}")


def check_supply_temperature(lubricant: Lubricant, thermal: Thermal) -> None:
    """ValueError naming ``supply_temperature`` when the oil's law gives no viscosity a
    film could have there: non-finite (Walther's below ~60 K), or below the oil range's low
    end, where the law is an extrapolation, above any lubricant's
    (:data:`~bearingfem.bearing.PLAUSIBLE`, 10 Pa s; within the range the law's value is
    taken, however viscous). Why: 40 typed for 40 C reached the solvers as 40 K and
    stopped in "Factor is exactly singular" or "non-finite temperature"; a cold start
    inside the range (ISO VG 32 at -50 C, 232 Pa s) and a cryogen's own law stay taken."""
    t = thermal.supply_temperature
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        mu = float(lubricant.viscosity_at(0.0, temperature=t))
    lo, hi = OIL_TEMPERATURE_RANGE
    if math.isfinite(mu) and mu > 0.0 and not (t < lo and mu > PLAUSIBLE["viscosity"][1]):
        return
    hint = (f": typed in degC? ({t:g} C = {t + CELSIUS:g} K)" if lo <= t + CELSIUS <= hi
            else "")
    # within the range any viscosity of the law is taken (ISO VG 32 at -50 C: 232 Pa s),
    # so the message says where the limit applies
    what = (f"a viscosity of {mu:g} Pa s below the oil range's {lo:g} K, where its law is "
            f"extrapolated (at most {PLAUSIBLE['viscosity'][1]:g} Pa s taken there)"
            if math.isfinite(mu) and mu > 0.0 else f"no finite viscosity ({mu:g} Pa s)")
    raise ValueError(f"thermal.supply_temperature {t:g} K gives the oil {what}{hint}; "
                     "temperatures are in K")


def thermal_operator(bearing, state, n_theta, n_z, element="P1", supply_angle=None,
                     grooves=()):
    """The whole-length film operator of a thermal film, fixed in the bearing: the film
    frame's mesh at gamma = 0, its first coordinate the bearing angle phi = theta + gamma.
    Why: the grooves (or the supply line) are fixed in the bearing, so one mesh, its
    tables and its energy operator serve every journal position (an equilibrium's steps,
    K and C), where the film frame's mesh turns with gamma and is rebuilt at each. The
    film frame's mesh at any gamma is this mesh turned (same nodes, elements and
    quadrature points in the same order), so a field on one is the field on the other."""
    return fe_operator(bearing, replace(state, gamma=0.0), n_theta, n_z, element,
                       supply_angle, False, grooves)


class _JFOFilm:
    """The JFO film on a viscosity field (its route, whole length)."""

    def __init__(self, problem):
        self.problem, self.route = problem, JFOFilm()

    def solve(self, ratio: np.ndarray):
        self.last = self.route.solve(replace(self.problem, fields=FilmFields(viscosity=ratio)))
        self.ratio = ratio
        frac = self.last.fraction
        return self.last.pressure, np.ones(len(frac)) if frac is None else frac

    def solution(self) -> FilmSolution:
        return self.last

    def force(self) -> np.ndarray:
        return np.array(self.last.force, float)


def error_factor(rates) -> float:
    """rho / (1 - rho): a fixed point's error over its last change, rho the largest of
    the measured contraction ``rates`` (ratios of successive changes) once MIN_RATES are
    measured, above 1 for rho > 1/2 (a slow contraction's error exceeds its change: a
    relaxed iteration's); 1 (the change as its own test) before, or for rho >= 1, where
    no contraction was measured."""
    rho = max(rates) if len(rates) >= MIN_RATES else 1.0
    return rho / (1.0 - rho) if rho < 1.0 else 1.0


class EnergyStep(NamedTuple):
    """One thermal step's energy-equation inputs: the film's flow, the grooves' mixing and
    the dissipation linearised about the step's temperatures, (slope [W/(m^2 K)], T [K])
    at the quadrature points."""
    flow: EnergyFlow
    mixing: Mixing
    linearised: tuple


def _dissipation_slope(flow, mu, dmu_dT):
    """d Phi / d T [W/(m^2 K)] of a film whose viscosity changes uniformly (module
    docstring): Phi (d mu/d T) / mu at the energy equation's points."""
    return flow.dissipation * dmu_dT / mu


def solve_thd(bearing: Bearing, state: JournalState, n_theta: int = 120, n_z: int = 20, *,
              lubricant: Lubricant, thermal: Thermal, grooves=(), cavitation="reynolds",
              element="P1", supply_angle=None, tol: float = 1e-10,
              temperature_tol: float = 1e-6, pressure_rtol: float = 1e-8,
              relaxation: float = 1.0, max_iterations: int = 200,
              start: FilmSolution | None = None) -> FilmSolution:
    """The steady thermal (THD) film at ``state`` (module docstring).

    Parameters
    ----------
    bearing, state : the bearing (its ``viscosity`` is only the film's reference scale)
        and a steady journal state (eps_dot = gamma_dot = 0; omega nonzero, its sign
        picks the groove edges the oil enters at)
    n_theta, n_z, element, cavitation ("reynolds" or "jfo"), grooves, supply_angle, tol :
        as :func:`~bearingfem.solve_reynolds`; a supply (grooves or
        supply_angle) is needed. The whole length is meshed.
    lubricant : :class:`~bearingfem.lubricant.Lubricant` with a temperature law (or none:
        the isothermal film), mass_density, specific_heat, conductivity; a pressure law is
        applied with the previous iterate's pressure
    thermal : :class:`~bearingfem.thermal.Thermal`
    temperature_tol : [K]; pressure_rtol : relative to the peak; the fixed point's tests
        on the estimated error (module docstring)
    relaxation : r in (0, 1] of T_{k+1} = T_k + r (T - T_k), T the energy equation's
    max_iterations : fixed-point steps before ConvergenceError
    start : a thermal :class:`FilmSolution` on the same mesh whose temperatures start the
        fixed point (default: the supply temperature everywhere)

    Returns
    -------
    FilmSolution with ``temperature`` (nodal [K]), ``temperature_max`` [K] and
    ``thermal`` (:class:`ThermalRecord`).
    """
    check_thermal(lubricant, thermal, state, cavitation, element)
    if not (isinstance(relaxation, (int, float)) and 0.0 < relaxation <= 1.0):
        raise ValueError(f"relaxation must lie in (0, 1], got {relaxation!r}")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
    for name, value in (("temperature_tol", temperature_tol),
                        ("pressure_rtol", pressure_rtol)):
        if not (isinstance(value, (int, float)) and np.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    if not grooves and supply_angle is None:
        raise ValueError("a thermal film needs an oil supply: give grooves or a "
                         "supply_angle")
    it = ThermalIteration(bearing, state, n_theta, n_z, lubricant=lubricant,
                          thermal=thermal, grooves=grooves, cavitation=cavitation,
                          element=element, supply_angle=supply_angle, tol=tol, start=start)
    rates = []
    for _ in range(max_iterations):
        it.film(state)
        bound = error_factor(rates)
        if bound * it.change < temperature_tol and bound * it.pressure_change < pressure_rtol:
            # the film on T, and T within the tolerance of the fixed point's: converged
            # without another energy solve
            return it.solution()
        before = it.change
        it.energy(state, relaxation)
        if np.isfinite(before) and before > 0.0:
            rates.append(it.change / before)
    raise ConvergenceError("thermal film (temperature fixed point)", max_iterations,
                           it.change, f"eps = {state.eps:.6g}; pressure change "
                           f"{it.pressure_change:.3g}")


class ThermalIteration:
    """The thermal film's steps (module docstring) on the bearing-fixed mesh, for a
    journal that may move between them (an equilibrium's search takes a position step
    between the film and the energy equation): :meth:`film` solves the film at a state on
    the viscosity of the kept temperatures, :meth:`energy` the energy equation on that
    film. ``start``: a thermal :class:`FilmSolution` on the same mesh whose temperatures
    (and cavitated set) start the iteration; default: the supply temperature."""

    def __init__(self, bearing, state, n_theta, n_z, *, lubricant, thermal, grooves=(),
                 cavitation="reynolds", element="P1", supply_angle=None, tol=1e-10,
                 start=None):
        self.bearing, self.lubricant, self.thermal = bearing, lubricant, thermal
        self.grooves, self.element, self.tol = tuple(grooves), element, tol
        self.op = op = thermal_operator(bearing, state, n_theta, n_z, element, supply_angle,
                                        grooves)
        self.degree = arc_degree(op.mesh, bush=thermal.bush is not None)
        self.eop = energy_operator(op.mesh, state.omega < 0.0, self.degree)
        self.wall = None if thermal.bush is None else \
            bush_wall(thermal.bush, bearing.radius, bearing.length, op.mesh, self.eop)
        n = op.mesh.ndofs
        fresh = start is None or getattr(start, "temperature", None) is None \
            or len(start.temperature) != n
        if cavitation == "jfo":
            self._jfo = FilmProblem(bearing, state, n_theta, n_z, element, cavitation,
                                    tol=tol, supply_angle=supply_angle,
                                    grooves=self.grooves, fields=FilmFields())
            self.last = None
        else:
            # a start's cavitated set starts the first film (no coarse levels needed)
            self._jfo = None
            self.last = None if fresh else LCPResult(start.pressure, 0, 0.0, True,
                                                     np.asarray(start.pressure) <= 0.0)
        self.T = np.full(n, thermal.supply_temperature) if fresh else \
            np.array(start.temperature, float)
        self.p = np.zeros(n) if fresh else np.array(start.pressure, float)
        self.change = self.pressure_change = np.inf
        self.iterations, self.energy_solution = 0, None
        self._factored = None      # the film coefficient h^3/mu the kept factors belong to

    def film(self, state):
        """Solve the film at ``state`` on mu(p, T) of the kept pressure and temperatures;
        keeps its pressure and the change from the last one (relative to its peak)."""
        b, oil, op = self.bearing, self.lubricant, self.op
        p_q, T_q = op.at_quadrature(np.stack([self.p, self.T]))      # one product
        self.mu = oil.viscosity_at(p_q, temperature=T_q)
        ratio = self.mu / b.viscosity
        if self._jfo is not None:
            f = _JFOFilm(replace(self._jfo, state=state))
        else:
            # the last film's cavitated set starts this one; its factors too while the
            # film's coefficient h^3/mu is within FACTOR_REUSE of theirs (module docstring)
            f = ReynoldsFieldFilm(b, state, op, self.element, self.grooves, self.tol,
                                  self.last)
            coefficient = f.cubed / ratio
            if self._factored is None or float(np.max(np.abs(
                    coefficient / self._factored - 1.0))) > FACTOR_REUSE:
                f.forget_factors()
        pressure, self.fraction = f.solve(ratio)
        if self._jfo is None and f.last.factorisations:
            self._factored = coefficient
        self.last, self.state = f, state
        peak = max(float(np.max(np.abs(pressure))), 1e-300)
        self.pressure_change = float(np.max(np.abs(pressure - self.p))) / peak
        self.p = pressure
        self.iterations += 1
        return f

    def energy_step(self, state) -> EnergyStep:
        """What the energy equation takes on the last film (its state ``state``): the
        film's flow, the grooves' mixing and the dissipation linearised about the current
        temperatures."""
        b, oil, T = self.bearing, self.lubricant, self.T
        self.eop = eop = energy_operator(self.op.mesh, state.omega < 0.0, self.degree)
        P = self.p / b.pressure_scale
        p_arc, T_arc = eop.at_points(np.column_stack([self.p, T]))   # one product
        # the viscosity and its temperature slope from one evaluation of the law
        mu_arc, _, dmu_dT = oil.viscosity_and_slopes(p_arc, T_arc)
        flow = eop.flow(b, state, P, self.fraction, mu_arc, oil)
        mixing = groove_mixing(b, state, self.op.mesh, eop.edges, P, self.fraction,
                               oil.viscosity_at(self.p, temperature=T), self.thermal)
        return EnergyStep(flow, mixing, (_dissipation_slope(flow, mu_arc, dmu_dT), T_arc))

    def energy(self, state, relaxation=1.0):
        """The energy equation on the last film (its state ``state``), the dissipation
        implicit to first order: T moves by ``relaxation`` of the change it asks."""
        step, T = self.energy_step(state), self.T
        energy = solve_energy(self.bearing, self.eop, step.flow, step.mixing,
                              self.thermal.walls, linearised=step.linearised, bush=self.wall,
                              bush_start=getattr(self.energy_solution, "bush_inner", None))
        self.change = float(np.max(np.abs(energy.temperature - T)))
        self.T = T + relaxation * (energy.temperature - T)
        self.energy_solution = energy
        return energy

    def solution(self) -> FilmSolution:
        """The last film's :class:`FilmSolution` with the temperatures and the record."""
        sol, energy, T, oil = self.last.solution(), self.energy_solution, self.T, self.lubricant
        record = ThermalRecord(
            balance=energy.balance, journal_temperature=energy.journal_temperature,
            inlet_temperatures=tuple(float(T[d[0]]) for d in self.eop.edges.inflow),
            viscosity=oil.viscosity_at(sol.pressure, temperature=T),
            viscosity_quadrature=self.mu, iterations=self.iterations,
            temperature_change=self.change, pressure_change=self.pressure_change,
            bush=energy.bush)
        warn_out_of_range(T)
        return replace(sol, temperature=T, temperature_max=float(np.max(T)), thermal=record,
                       method=sol.method + "/thd")


class ThermalFilm(Route):
    name = "thd"
    summary = "the thermal film: the energy equation coupled to the film through the " \
              "oil's viscosity against temperature (a lubricant with a temperature law), " \
              "whole length"
    uses = frozenset({"element", "tol", "supply_angle", "half", "grooves", "lubricant",
                      "thermal", "start"})

    def check_options(self, p: FilmProblem) -> None:
        check_thermal(p.lubricant, p.thermal, p.state, p.cavitation, p.element)
        if p.cavitation == "jfo" and p.tol != OPTION_DEFAULTS["tol"]:
            raise ValueError("tol is not used by the 'thd' film with cavitation 'jfo' (the "
                             "JFO film has no projected iteration)")

    def solve(self, p: FilmProblem):
        return solve_thd(p.bearing, p.state, p.n_theta, p.n_z, lubricant=p.lubricant,
                         thermal=p.thermal, grooves=p.grooves, cavitation=p.cavitation,
                         element=p.element, supply_angle=p.supply_angle, tol=p.tol,
                         start=p.start)
