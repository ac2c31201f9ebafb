"""The transient EHD-JFO film along a time integration: the "fem-ehd" model with
``cavitation="jfo"``.

The stepping policy is the rigid JFO film's (:class:`~bearingfem.transient.TransientJFO`:
film steps at accepted steps spaced by ``film_step``, early on a refill or a turn of half
a cell, the force a routine step changes faded in). Its film is :class:`KeptEHDJFO`: the
backward-Euler step of :mod:`bearingfem.ehd.jfo_transient` at film steps; between them the
force at a trial state is the kept film's (as :class:`~bearingfem.ehd.transient.TransientEHD`
keeps its deflection): the Reynolds film of that state's rigid gap plus the kept deflection
(held in the bush's frame, :class:`~bearingfem.ehd.transient.KeptFilm`), with the kept
lubricant ratios, on the volumes full at the kept step; the kept cavities at zero pressure
(as :meth:`bearingfem.fe.jfo.JFOFilm.instant`, whose force it is with a rigid bush).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..fe.assembly import fe_operator
from ..fe.general import film_system
from ..fe.jfo_balance import JFOFlows, boundary_values, film_volumes, kept_set_pressure
from ..fe.jfo_steady import jfo_film_solution
from ..fields import FilmFields
from ..film import film_thickness, inertial_from_theta
from ..scales import flow_factor, force_factor
from ..transient import TransientJFO
from ..fe.jfo_fields import rigid_balance_film
from .jfo import check_ehd_jfo, face_maps
from .jfo_transient import EHDJFOFilm
from .transient import ehd_compliance, kept_film

__all__ = ["KeptEHDJFO", "TransientEHDJFO"]


@dataclass(frozen=True)
class EHDJFOSnapshot:
    """What a :class:`KeptEHDJFO` keeps: the step's film and its kept deflection."""

    film: tuple
    kept: object
    steps: int


class KeptEHDJFO:
    """The EHD-JFO film with the interface :class:`TransientJFO` drives (that of
    :class:`~bearingfem.fe.jfo.JFOFilm`: step, instant, refilled, turned, snapshot)."""

    def __init__(self, bearing: Bearing, state: JournalState, n_theta: int, n_z: int,
                 bush, lubricant, modes: int, ambient_pressure: float):
        comp = ehd_compliance(bush, bearing.radius, bearing.length, n_theta, n_z, modes)
        self.bearing, self.lubricant, self.n = bearing, lubricant, (n_theta, n_z)
        self._op(state)
        self.film = EHDJFOFilm(bearing, state, n_theta, n_z, comp, lubricant,
                               ambient_pressure)
        self.ambient = float(ambient_pressure)
        self.kept = None                 # the deflection's KeptFilm (None: undeformed)
        self.steps = 0

    def _op(self, state):
        if state.eps >= 1.0:
            # the rigid step that starts the load continuation needs a rigid gap > 0
            raise ValueError(f"eps must be < 1 for fem-ehd cavitation='jfo' (the elastic "
                             f"JFO film within the clearance circle), got {state.eps}")
        return fe_operator(self.bearing, state, *self.n, "P1", None, False)

    @property
    def cavitated(self) -> np.ndarray:
        op = self._op(self.film.state)
        cav = self.film.fraction < 1.0
        cav[op.mesh.fixed] = False
        return cav

    def snapshot(self) -> EHDJFOSnapshot:
        f = self.film
        return EHDJFOSnapshot((f.state, f.P, f.fraction, f.content, f.steps), self.kept,
                              self.steps)

    def restore(self, snap: EHDJFOSnapshot) -> None:
        f = self.film
        f.state, f.P, f.fraction, f.content, f.steps = snap.film
        self.kept, self.steps = snap.kept, snap.steps

    def refilled(self, state: JournalState, time=None) -> bool:
        """Whether the gap at ``state`` closed on the content of a kept cavity."""
        op = self._op(state)
        full = rigid_balance_film(op, state).content
        if self.kept is not None:
            full = full + face_maps(op).content @ self._departure(state, op)
        return bool(np.any(self.cavitated & (self.film.content >= full)))

    def turned(self, state: JournalState) -> bool:
        cv = film_volumes(self._op(state).mesh)
        return bool(abs(self.film._turn(state)) > np.pi / cv.n_columns)

    def _departure(self, state, op) -> np.ndarray:
        """Nodal kept w / c at ``state``'s mesh (read in the bush's frame)."""
        k = self.kept
        return k.at(k.deflection, inertial_from_theta(op.mesh.theta, state.gamma), op.mesh.zeta)

    def instant(self, state: JournalState, warm=None, time=None):
        """((F_r, F_t) [N], cavitated set) of the kept film at ``state`` (module docstring)."""
        op = self._op(state)
        mesh = op.mesh
        if self.kept is None:
            fields = FilmFields(gap=film_thickness(op.qp_theta, state.eps))
        else:
            fields = self.kept.fields(self.bearing, state, op, self.lubricant)
        if not np.all(fields.gap > 0.0):
            raise ValueError(f"the kept deflection does not open the gap at eps {state.eps} "
                             "(the journal passed the deflected bush): reduce film_step")
        shape = op.qp_theta.shape
        fields = FilmFields(gap=fields.gap, gap_rate=state.eps_dot * np.cos(op.qp_theta),
                            viscosity=np.broadcast_to(fields.viscosity, shape),
                            density=np.broadcast_to(fields.density, shape),
                            density_rate=np.zeros(shape))
        values, load = film_system(op, fields, state.wedge_speed, state.eps)
        K = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape)
        P, _ = boundary_values(self.bearing, mesh, (), self.ambient)
        P, cav = kept_set_pressure(K, load, P, mesh, self.cavitated, warm)
        ic, is_ = op.force_integrals(P)
        k = force_factor(self.bearing, mesh.half)
        return (k * float(ic), k * float(is_)), cav

    def step(self, state: JournalState, dt: float):
        """Advance by ``dt`` [s] and keep the film; its FilmSolution (raises
        ConvergenceError keeping the film as it was)."""
        op = self._op(state)
        a = self.film.advance(state, dt)
        k = flow_factor(self.bearing, False)
        flows = JFOFlows(flow_in=k * a.inflow, side_leakage=0.0, storage=k * a.content_rate)
        sol = jfo_film_solution(self.bearing, state, op, a.P, a.fraction, a.result, flows,
                             "fem-P1/jfo-ehd-transient")
        sol = replace(sol, deformation=a.deformation)
        self.kept = kept_film(self.bearing, state, sol, *self.n)
        self.steps += 1
        return sol


class TransientEHDJFO(TransientJFO):
    """The "fem-ehd" model with ``cavitation="jfo"`` along one integration (module
    docstring). Parameters: bearing, lubricant, bush, roughness (None only), n_theta, n_z,
    modes, film_step [s], ambient_pressure [Pa].

    Film steps taken early (a refill, a turn) are at least a quarter film step apart
    (the rigid film's: 1e-3): a step much shorter than the film step is stiff for the
    bush's squeeze (12 C / dt dense against the Poiseuille operator), where the Newton of
    :mod:`bearingfem.ehd.jfo` stalls (measured: a 2e-7 s step of a bronze ring bush,
    32 x 4, does not converge; 1e-5 s does with the full compliance)."""

    early_fraction = 0.25

    def __init__(self, bearing: Bearing, lubricant=None, bush=None, roughness=None,
                 n_theta: int = 48, n_z: int = 8, modes: int = 0, film_step: float = 0.0,
                 ambient_pressure: float = 1e5):
        if roughness is not None:
            raise ValueError("cavitation='jfo' takes roughness=None (the mixed film is "
                             "Reynolds-cavitated only)")
        if bush is None:
            raise ValueError("cavitation='jfo' in fem-ehd needs a bush (without one: "
                             "model 'fem-jfo')")
        check_ehd_jfo(lubricant, None, (0.0, 0.0), (0.0, 0.0))
        super().__init__(bearing, n_theta, n_z, (), ambient_pressure, film_step)
        self._ehd = dict(n_theta=n_theta, n_z=n_z, bush=bush, lubricant=lubricant,
                         modes=modes, ambient_pressure=ambient_pressure)

    def start(self, state: JournalState, t: float) -> None:
        self.film = KeptEHDJFO(self.bearing, state, **self._ehd)
        self.t = float(t)
        self._warm, self._jump, self._fade, self.steps = None, (0.0, 0.0), 1.0, 0
