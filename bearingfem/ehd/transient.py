"""The EHD film along a time integration: the "fem-ehd" model's film with memory.

A full EHD solve (:mod:`bearingfem.ehd.newton`: Newton on the pressure with the bush's
compliance and the lubricant's fields) costs a few Newton steps even from a warm start,
and an integrator asks for the force at many trial states per step. :class:`TransientEHD`
therefore solves the full EHD film at accepted integrator steps only, spaced by
``film_step``, and keeps what that solve gave the film: the bush's radial deflection and
the lubricant's viscosity and density ratios, held in the bush's (inertial) frame. At a
trial state the force is the Reynolds film (Swift-Stieber cavitation) of the rigid gap of
that state plus the kept deflection, with the kept viscosity and density: one
general-field film solve (:func:`~bearingfem.solve_reynolds` with ``fields``),
a few milliseconds. The kept fields lag the journal by one film step (an explicit
coupling): the force's error is O(film_step). Beyond the rigid clearance circle the gap is
almost all deflection, so that lag moves the gap by about as much as the gap itself
(docs/ehd.md, "Beyond the rigid clearance"); :class:`~bearingfem.ehd.tangent.TangentEHD`
moves the kept fields along their tangent in the journal's state instead. The force changed
by a film step is faded in over the next one (smoothstep, as for the JFO film,
:mod:`bearingfem.transient`), so the integrator sees no jump.

Quasi-static bush: its deflection rate is left out of the squeeze term (as in the steady
EHD film), and the bush has no mass.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..bearing import Bearing, JournalState
from ..caches import cached
from ..contract import FilmStep, StatelessRun
from ..errors import ConvergenceError
from ..elastic import ElasticBush, bush_compliance
from ..fe.assembly import fe_operator
from ..fe.general import film_system
from ..fe.kernel import fe_pressure, solve_film
from ..fe.mixed import film_contact, refuse_rough_flow, with_contact
from ..fields import FilmFields
from ..scales import force_factor
from ..film import film_thickness, inertial_from_theta
from ..solution import FilmSolution
from ..transient import faded_force, since_film_step
from .film import solve_elastic_film

__all__ = ["TransientEHD", "EHDSnapshot", "KeptFilm", "kept_film", "ehd_solution",
           "ehd_compliance", "state_coordinates"]


@cached(maxsize=8)
def ehd_compliance(bush: ElasticBush, radius: float, length: float, n_theta: int, n_z: int,
                   modes: int):
    """The bush's compliance on the film grid: full (``modes`` 0) or its best rank-modes
    approximation (cached: one build per bush and mesh)."""
    full = bush_compliance(bush, radius, length, n_theta, n_z + 1)
    if modes == 0:
        return full
    if modes > n_theta * (n_z + 1):
        raise ValueError(f"modes must be <= n_theta (n_z + 1) = {n_theta * (n_z + 1)}, "
                         f"got {modes}")
    return full.reduced(modes)


def ehd_solution(bearing: Bearing, state: JournalState, lubricant, bush, roughness,
                 n_theta: int, n_z: int, modes: int, start: FilmSolution | None = None,
                 profile=None) -> FilmSolution:
    """The full EHD film at ``state`` (P1, Swift-Stieber cavitation; ``start`` a previous
    solution of the same mesh for a warm start; ``profile`` a bush edge profile or None)."""
    comp = None if bush is None else ehd_compliance(
        bush, bearing.radius, bearing.length, n_theta, n_z, modes)
    if comp is None and lubricant is None and profile is None:   # rigid isoviscous: no Newton
        op = fe_operator(bearing, state, n_theta, n_z, "P1", None, True)
        sol = solve_film(bearing, state, op, "P1", "reynolds")
        return sol if roughness is None else with_contact(
            sol, film_contact(bearing, state, op, roughness))
    return solve_elastic_film(bearing, state, n_theta, n_z, "reynolds", lubricant=lubricant,
                              bush=comp, roughness=roughness, start=start, profile=profile)


def total_force(sol: FilmSolution) -> tuple:
    """(F_r, F_t) [N]: the film's force plus the asperities' (zero without roughness)."""
    f, c = sol.force_local, sol.asperity_force_local
    return float(f[0] + c[0]), float(f[1] + c[1])


@dataclass(frozen=True, eq=False)
class KeptFilm:
    """What a full EHD solve leaves the film, on the film grid in the bush's frame: the
    deflection over the clearance w/c and the pressure p [Pa], each (n_theta, n_z + 1) at
    inertial angles ``alpha0`` + 2 pi j / n_theta and zeta = -h + 2 h k / n_z, ``half_width``
    h = L/(2R)."""

    alpha0: float
    deflection: np.ndarray
    pressure: np.ndarray
    half_width: float
    origin: np.ndarray | None = None          # s_n (5,): the state of the solve
    deflection_slope: np.ndarray | None = None    # d(w/c)/ds (5, n_theta, n_z + 1)
    pressure_slope: np.ndarray | None = None      # dp/ds [Pa] (5, n_theta, n_z + 1)
    profile: object = None          # the bush's EdgeProfile (fixed to the bush) or None
    profile_gap: np.ndarray | float = 0.0     # its h_p/c on the grid's zeta (n_z + 1,)

    def grids(self, state: JournalState) -> tuple:
        """(w/c, p) grids at ``state``: the kept ones moved along their tangent (the kept
        ones without a tangent); p clipped at 0."""
        if self.origin is None:
            return self.deflection, self.pressure
        s = state_coordinates(state)
        ds = s - self.origin
        n = self.deflection.shape[0]
        alpha = (self.alpha0 + 2 * np.pi * np.arange(n) / n)[:, None]
        # the held film's gap at s (the rigid gap 1 - x cos(alpha) - y sin(alpha) on the
        # grid plus w_n); the deflection's change dw closes it in log h (g exp(dw / g):
        # the same first derivative, and it stays > 0, where a linear step closes the thin
        # film at the bush's free ends) and opens it linearly (C1 across dw = 0)
        g = (1.0 - s[0] * np.cos(alpha) - s[1] * np.sin(alpha) + self.deflection
             + self.profile_gap)
        dw = np.tensordot(ds, self.deflection_slope, axes=1)
        safe = np.where(g > 0.0, g, 1.0)
        closing = g * np.expm1(np.minimum(dw, 0.0) / safe)
        w = self.deflection + np.where((dw < 0.0) & (g > 0.0), closing, dw)
        p = self.pressure + np.tensordot(ds, self.pressure_slope, axes=1)
        return w, np.maximum(p, 0.0)

    def at(self, grid: np.ndarray, alpha: np.ndarray, zeta: np.ndarray) -> np.ndarray:
        """Bilinear, periodic in alpha, values of a kept ``grid`` at (alpha, zeta) (exact
        at the grid's nodes)."""
        n, m = grid.shape
        u = np.mod(alpha - self.alpha0, 2 * np.pi) / (2 * np.pi) * n
        v = np.clip((zeta + self.half_width) / (2 * self.half_width) * (m - 1), 0, m - 1)
        j, k = np.floor(u).astype(int), np.minimum(np.floor(v).astype(int), m - 2)
        a, b = u - j, v - k
        j0, j1 = j % n, (j + 1) % n
        return ((1 - a) * ((1 - b) * grid[j0, k] + b * grid[j0, k + 1])
                + a * ((1 - b) * grid[j1, k] + b * grid[j1, k + 1]))

    def fields(self, bearing: Bearing, state: JournalState, op, lubricant) -> FilmFields:
        """The film's fields at ``state`` on the film operator ``op`` at its quadrature
        points: the rigid gap plus the kept deflection, and the lubricant's ratios at the
        kept pressure, both read at the mesh nodes (moved to the film angle of ``state``)
        and interpolated by the elements as the EHD film does: at the state of the solve
        they are that solve's fields (the edge profile at the points, as the solve's)."""
        alpha = inertial_from_theta(op.mesh.theta, state.gamma)
        w_grid, p_grid = self.grids(state)
        w = op.at_quadrature(self.at(w_grid, alpha, op.mesh.zeta))
        gap = film_thickness(op.qp_theta, state.eps) + w
        if self.profile is not None:
            gap = gap + self.profile.film_gap(bearing, op.qp_zeta)
        if lubricant is None:
            return FilmFields(gap=gap)
        p = op.at_quadrature(self.at(p_grid, alpha, op.mesh.zeta))
        return FilmFields(gap=gap, viscosity=lubricant.viscosity_at(p) / bearing.viscosity,
                          density=lubricant.density_at(p))


def state_coordinates(state: JournalState) -> np.ndarray:
    """s = (x, y, x', y', omega) of ``state``: x + i y = eps e^{i gamma} (the journal centre
    over the clearance in the bush's frame) and its rate [1/s], and omega [rad/s]."""
    c, s = np.cos(state.gamma), np.sin(state.gamma)
    e, ed, gd = state.eps, state.eps_dot, state.gamma_dot
    return np.array([e * c, e * s, ed * c - e * gd * s, ed * s + e * gd * c, state.omega])


def kept_film(bearing: Bearing, state: JournalState, sol: FilmSolution, n_theta: int,
              n_z: int, profile=None) -> KeptFilm:
    """The deflection and pressure of the EHD solution ``sol`` at ``state`` on the film
    grid (its mesh is the periodic whole-length one: nodes at theta = 2 pi j / n_theta), and
    the bush edge ``profile`` the solve had (None: none)."""
    theta, zeta = np.asarray(sol.theta), np.asarray(sol.z) / bearing.radius
    lam = bearing.length / (2 * bearing.radius)
    j = np.rint(theta / (2 * np.pi / n_theta)).astype(int) % n_theta
    k = np.rint((zeta + lam) / (2 * lam) * n_z).astype(int)
    p = np.asarray(sol.pressure)
    w = np.zeros_like(p) if sol.deformation is None else np.asarray(sol.deformation)
    grids = []
    for values in (w / bearing.clearance, p):
        g = np.full((n_theta, n_z + 1), np.nan)
        g[j, k] = values
        # a film solved on its half length (mid-plane symmetry: the rigid, untilted film)
        # covers z >= 0 only: its mirror image fills the other half
        g[j, n_z - k] = np.where(np.isnan(g[j, n_z - k]), values, g[j, n_z - k])
        if np.isnan(g).any():
            raise ValueError(f"the EHD solution's nodes do not cover the {n_theta} x {n_z} "
                             "film grid (n_theta, n_z must be the solve's mesh)")
        grids.append(g)
    edge = 0.0 if profile is None else profile.film_gap(bearing, np.linspace(-lam, lam, n_z + 1))
    return KeptFilm(float(inertial_from_theta(0.0, state.gamma)), *grids, half_width=lam,
                    profile=profile, profile_gap=edge)


@dataclass(frozen=True)
class EHDSnapshot:
    """What a :class:`TransientEHD` keeps (see :meth:`TransientEHD.snapshot`)."""

    t: float
    kept: KeptFilm
    solution: FilmSolution
    jump: tuple
    fade: float
    steps: int
    origin: np.ndarray | None = None


class TransientEHD(StatelessRun):
    """The "fem-ehd" model along one integration (see the module docstring).

    Parameters
    ----------
    bearing : the bearing
    lubricant, bush, roughness, n_theta, n_z, modes : the film (:func:`ehd_solution`)
    film_step : [s] time between full EHD solves (0: one at every accepted step)
    profile : a bush edge profile (:class:`~bearingfem.fields.EdgeProfile`) or None
    """

    memory = True

    def __init__(self, bearing: Bearing, lubricant=None, bush=None, roughness=None,
                 n_theta: int = 48, n_z: int = 8, modes: int = 0, film_step: float = 0.0,
                 profile=None):
        refuse_rough_flow(roughness, "transient EHD film")
        self.bearing = bearing
        self._film = dict(lubricant=lubricant, bush=bush, roughness=roughness,
                          n_theta=n_theta, n_z=n_z, modes=modes,
                          profile=None if profile is None else profile.check(bearing))
        self.film_step = float(film_step)
        self.steps = 0
        self._kept: KeptFilm | None = None
        self._solution: FilmSolution | None = None
        self.t, self._jump, self._fade = 0.0, (0.0, 0.0), 1.0
        self._active = None          # the last trial solve's cavitated set (a warm start)
        self._origin = None          # s at the last film step

    def _solve(self, state: JournalState) -> FilmSolution:
        return ehd_solution(self.bearing, state, start=self._solution, **self._film)

    def _keep(self, state: JournalState, sol: FilmSolution) -> KeptFilm:
        f = self._film
        return kept_film(self.bearing, state, sol, f["n_theta"], f["n_z"], f["profile"])

    def _keep_at(self, state: JournalState, sol: FilmSolution) -> KeptFilm:
        """The kept film of a film step (:class:`~bearingfem.ehd.tangent.TangentEHD` adds
        its tangent)."""
        return self._keep(state, sol)

    def _fits(self, state: JournalState) -> bool:
        """Whether the kept film still holds at the accepted ``state`` (always, here: the
        film steps come every ``film_step``)."""
        return True

    def start(self, state: JournalState, t: float) -> None:
        """Begin with the full EHD film at ``state``, time ``t`` [s] (a cold solve)."""
        self._solution = None
        self._solution = self._solve(state)
        self._kept = self._keep_at(state, self._solution)
        self._origin = state_coordinates(state)
        self.t, self._jump, self._fade, self.steps = float(t), (0.0, 0.0), 1.0, 0

    def kept_force(self, state: JournalState, kept: KeptFilm | None = None) -> tuple:
        """(F_r, F_t) [N]: the Reynolds film (Swift-Stieber) at ``state`` on the kept
        fields, plus the asperities' force with roughness. The light path of the
        integrator's trial states: the film's system, its pressure (active set started
        from the last call's cavitated set: the same answer to the solver's tolerance)
        and force, no other outputs."""
        f = self._film
        op = fe_operator(self.bearing, state, f["n_theta"], f["n_z"], "P1", None, False)
        fields = (kept or self._kept).fields(self.bearing, state, op, f["lubricant"])
        if not np.all(fields.gap > 0.0):
            # a trial state past what the kept bush opens (beyond the clearance circle): an
            # integrator cuts its step on this, as on a solve that does not converge
            raise ConvergenceError("EHD kept film", 0, None,
                                   f"eps {state.eps}: the kept deflection does not open the "
                                   "gap (the journal passed the deflected bush)")
        fields = FilmFields(gap=fields.gap, gap_rate=state.eps_dot * np.cos(op.qp_theta),
                            viscosity=np.broadcast_to(fields.viscosity, op.qp_theta.shape),
                            density=np.broadcast_to(fields.density, op.qp_theta.shape),
                            density_rate=np.zeros_like(op.qp_theta))
        active = self._active if (self._active is not None
                                  and self._active.shape == (op.mesh.ndofs,)
                                  and self._active.any()) else None
        res = fe_pressure(op, state, "reynolds", active0=active,
                          system=film_system(op, fields, state.wedge_speed, state.eps))
        self._active = res.active
        ic, is_ = op.force_integrals(res.pressure)
        k = force_factor(self.bearing, False)
        force = (k * float(ic), k * float(is_))
        if f["roughness"] is None:
            return force
        c = film_contact(self.bearing, state, op, f["roughness"], fields.gap).force_local
        return force[0] + c[0], force[1] + c[1]

    def force(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] at a trial ``state`` and time ``t``; keeps nothing (a film not
        started yet starts here)."""
        if self._kept is None:
            self.start(state, t)
        f = self.kept_force(state)
        return faded_force(f, self._jump, float(t) - self.t, self._fade)

    def commit(self, state: JournalState, t: float) -> FilmStep | None:
        """A full EHD solve at the accepted ``state`` once ``film_step`` has passed since the
        last one (None otherwise); a failed solve raises and keeps the film as it was."""
        if self._kept is None:
            self.start(state, t)
        t = float(t)
        dt = since_film_step(t, self.t)
        if dt <= 1e-12 * max(abs(self.t), 1e-3) or (dt <= self.film_step
                                                     and self._fits(state)):
            return None
        before = self.force(state, t)
        sol = self._solve(state)                # raises ConvergenceError before any change
        kept = self._keep_at(state, sol)
        after = self.kept_force(state, kept)
        self._kept, self._solution, self._origin = kept, sol, state_coordinates(state)
        self._jump = (before[0] - after[0], before[1] - after[1])
        self._fade = max(self.film_step, dt)
        self.t = t
        self.steps += 1
        return FilmStep(t, state, total_force(sol), sol)

    def snapshot(self) -> EHDSnapshot:
        return EHDSnapshot(self.t, self._kept, self._solution, self._jump, self._fade,
                           self.steps, self._origin)

    def restore(self, snapshot: EHDSnapshot) -> None:
        self.t, self._kept, self._solution = snapshot.t, snapshot.kept, snapshot.solution
        self._jump, self._fade, self.steps = snapshot.jump, snapshot.fade, snapshot.steps
        self._origin = snapshot.origin

    def replay(self, start: tuple, steps):
        """The film steps of a run taken again from ``start`` = (t, JournalState) and the
        (t, JournalState) of its committed steps; yields (t, FilmSolution) per step (the
        same solves, warm from the same previous solutions)."""
        t0, s0 = start
        self.start(s0, t0)
        for t, state in steps:
            self._solution = self._solve(state)
            self._kept = self._keep(state, self._solution)
            self._origin = state_coordinates(state)
            self.t = float(t)
            self.steps += 1
            yield self.t, self._solution

