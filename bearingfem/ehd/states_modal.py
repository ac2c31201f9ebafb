"""The EHD film with the bush's modal deflection as states of the time integration.

:class:`~bearingfem.ehd.transient.TransientEHD` holds the bush's deflection between film
steps; beyond the rigid clearance circle the gap is nearly all deflection, and that lag
does not converge as the film step shrinks (docs/ehd.md). Here the deflection is w = L q
on the bush's film grid (L the reduced compliance's left vectors, fixed in the bush's
frame) and the modal coordinates q [m] are integrated with the journal: the integrator's
own error control replaces the film step, and nothing lags.

A purely quasi-static bush (q = S R^T p, S R^T the reduced compliance's other factor)
leaves dq/dt undetermined wherever a mode sits in a cavity. The bush is therefore given a
Kelvin-Voigt relaxation time ``relaxation`` tau [s] (material damping):

    q + tau dq/dt = S R^T (p + p_a),

and the film's squeeze carries the bush's motion, dH/dt = dH_rigid/dt + (L dq/dt) / c.
Given the journal's state and q the gap is known; the unknowns are the pressure and dq/dt,
and eliminating dq/dt = (S R^T p - q) / tau leaves the Reynolds residual with a rank-n
term, R(P) = K P - load(P), solved by the EHD film's semismooth Newton
(:mod:`bearingfem.ehd.newton`, Reynolds' condition, the lubricant's fields, exact
Jacobian: sparse plus U V^T, U = G / tau, G the squeeze load of unit modal rates). As tau
-> 0 the film tends to the quasi-static EHD film; a journal held still relaxes to the
steady EHD solve (tests/test_ehd_states.py).

With ``roughness`` the summits' pressure (Greenwood & Tripp) loads the journal and the
bush. The film's flow through the rough gap is Patir & Cheng's average flow model when
the roughness has ``flow`` factors (:mod:`bearingfem.contact.flow_factors`: any nominal
gap, the surfaces pressed through included; tests/test_flow_factors.py); without them the
smooth film's flow sees the gap floored at FLOW_FLOOR sigma.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..contact.flow_factors import FLOW_FLOOR
from ..contract import REPLAY_TOLERANCE, FilmStep, StateTangent
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fe.kernel import film_outputs
from ..fe.mixed import friction_fields
from ..fields import FilmFields
from ..film import film_thickness, local_to_inertial
from ..scales import force_factor
from ..solution import FilmSolution
from .coupling import FilmState, ehd_film, jacobian_tables
from .grid import FrameShift, node_grid
from .newton import EHDResult, _Factor, _newton, continuation, warm_solve
from .transient import ehd_compliance

__all__ = ["ModalStateEHD"]

#: Newton's tolerance on the film's residual (as the steady EHD solve's).
TOL = 1e-10
#: With roughness and no flow factors, the film's flow sees the gap floored at FLOW_FLOOR
#: sigma (bearingfem.contact.flow_factors, which floors the pressure term's h^3 there).


class _CoupledFilm:
    """The EHD film of one journal state and one q, with dq/dt eliminated (module
    docstring): what :func:`~bearingfem.ehd.newton._newton` asks of a film."""

    def __init__(self, film, q, relaxation, frame, modal, rigid_rate,
                 contact=None, gap=None, deflection=None, moving=None, gamma_dot=0.0):
        self.film, self.op = film, film.op
        self.gamma_dot = gamma_dot      # the journal's whirl speed [rad/s]
        self.moving = moving            # (E, Q): 1 where the flow's gap follows w, 0 floored
        self.gap = gap                  # the nodal gap H as it is (not floored), reported
        self.deflection = deflection    # the bush's nodal deflection w = L q [m]
        self.contact = contact          # the summits' pressure at the film nodes [Pa] or None
        self.q, self.tau = q, relaxation
        self.frame = frame              # what depends on gamma only (a _Frame)
        self.modal = modal              # (n, grid): S R^T [m/Pa]
        self.rigid_rate = rigid_rate    # (E, Q) dH/dt at q's rate 0, film frame [1/s]
        self._G = None                  # the Jacobian's squeeze factor, kept per density
        self._J = self._affine = None   # without a lubricant: the sparse Jacobian, load_0
        self._last = None               # with one: (P, s, the film at P), the last evaluated

    def rates(self, P):
        """dq/dt [m/s] at nodal P (dimensionless, p = scale P)."""
        p = self.film.scale * P if self.contact is None else self.film.scale * P + self.contact
        return (self.frame.comply(self.frame.shift.to_grid(p)) - self.q) / self.tau

    def _at(self, P):
        qdot = self.rates(P)
        rate = self.rigid_rate + self.frame.squeeze(qdot).reshape(self.rigid_rate.shape)
        return replace(self.film, base=replace(self.film.base, gap_rate=rate)), qdot

    def film_state(self, P, s=1.0):
        """The film at P built whole (fields, stiffness, load): what :meth:`evaluate`
        gives, on any lubricant."""
        film, _ = self._at(P)
        return film.evaluate(P, s)

    def evaluate(self, P, s=1.0):
        """The film at P. Isoviscous and incompressible (no lubricant), the gap does not
        depend on P and dq/dt is affine in it, so the residual is affine,
        R(P) = K P - load_0 + G dq/dt(P) (load_0 the load at dq/dt = 0, G the squeeze load
        of unit modal rates, as in :meth:`jacobian`): K and load_0 are built once per film
        (tested against :meth:`film_state`)."""
        if self.film.lubricant is not None:
            # the last evaluation again when asked at the same P (Newton after a failed
            # chord starts from the chord's iterate of least residual, often its last)
            if self._last is not None and self._last[1] == s and np.array_equal(self._last[0], P):
                return self._last[2]
            ev = self.film_state(P, s)
            self._last = (P.copy(), s, ev)
            return ev
        if self._affine is None:
            film = replace(self.film, base=replace(self.film.base, gap_rate=self.rigid_rate))
            ev0 = film.evaluate(np.zeros_like(P), s)
            self._affine = (ev0, None if ev0 is None else self.op.pattern.matrix(ev0.values))
        ev0, K = self._affine
        if ev0 is None:
            return None
        load = ev0.load - self.squeeze_load(ev0) @ self.rates(P)
        size = self.op.pattern.matrix(np.abs(ev0.values)) @ np.abs(P) + np.abs(load)
        return FilmState(ev0.fields, None, ev0.values, load, K @ P - load, size,
                         flow=ev0.flow)

    def squeeze_load(self, ev):
        """G (nodes, n): d R / d(dq/dt), the squeeze load of unit modal rates,
        d R_i / d(dH/dt)_q = 12 rho phi_i dx (times dE(h_T)/dh with a rough gap's flow;
        kept per density: the gap is this film's)."""
        rho = np.broadcast_to(ev.fields.density, self.op.qp_weight.shape)
        if ev.flow is not None:     # the squeeze moves the mean gap: dE(h_T)/dh dH/dt
            rho = rho * ev.flow.gap_slope
        if self._G is None or not np.array_equal(rho, self._G[0]):
            # G = I^T W I L / c (I the points' interpolation, W the weights): through the
            # sparse nodal product, not the dense (points, n) squeeze
            w = sp.diags((12.0 * rho * self.op.qp_weight).ravel())
            I = self.op.qp_interp
            G = (I.T @ (w @ I)) @ self.frame.left / self.frame.clearance
            self._G = (rho, G if sp.issparse(G) else np.asarray(G))
        return self._G[1]

    def rate_load(self, ev, M: np.ndarray) -> np.ndarray:
        """d R / da (nodes, k) for dH/dt at the points moving by M (E*Q, k) [1/s] per unit
        of a: d R_i / d(dH/dt)_q = 12 rho phi_i dx."""
        rho = np.broadcast_to(ev.fields.density, self.op.qp_weight.shape)
        if ev.flow is not None:     # the squeeze moves the mean gap: dE(h_T)/dh dH/dt
            rho = rho * ev.flow.gap_slope
        w = (12.0 * rho * self.op.qp_weight).ravel()
        return np.asarray(self.op.qp_interp.T @ (w[:, None] * M))

    def jacobian(self, P, s, ev):
        if self.film.lubricant is None and self._J is not None:
            J = self._J         # the affine film's: the same at every P
        else:
            film, _ = self._at(P)
            J, _, _ = film.jacobian(P, s, ev)
            if self.film.lubricant is None:
                self._J = J
        return (J,) + self.frame.newton_part(self.squeeze_load(ev), self.film.scale, self.tau)


class _Frame:
    """What depends on the journal angle gamma alone, on one film mesh: the frame shift,
    the modes' nodal shapes L (nodes, n) [1], their squeeze at the points
    (:meth:`squeeze`), and the rates' factor V (:meth:`rates_factor`). Kept while gamma
    holds: the integrator's difference Jacobian moves the modal coordinates and the
    speeds at the same gamma."""

    def __init__(self, op, gamma: float, left_grid, modal, clearance: float):
        self.op, self.gamma, self.modal, self.clearance = op, gamma, modal, clearance
        self.shift = FrameShift(node_grid(op.mesh), gamma)
        self.left = self.shift.to_nodes(left_grid)
        self._V = None

    def deflection(self, q: np.ndarray) -> np.ndarray:
        """The nodal deflection w = L q [m] of the states q."""
        return self.left @ q

    def comply(self, p_grid: np.ndarray) -> np.ndarray:
        """S R^T p [m] of the grid's pressure ``p_grid`` [Pa]: the states' quasi-static
        value."""
        return self.modal @ p_grid

    def squeeze(self, qdot: np.ndarray) -> np.ndarray:
        """dH/dt at the points (E*Q,) [1/s] of the modal rates ``qdot`` [m/s]: the nodal
        deflection rate L qdot / c interpolated (nodes first: the dense (points, n) factor
        costs some 20x more to apply)."""
        return self.op.qp_interp @ self.deflection(qdot) / self.clearance

    def newton_part(self, G, scale: float, relaxation: float) -> tuple:
        """(U, V): the Newton matrix's bush part U V^T = G d(dq/dt)/dP, U = G the squeeze
        load of unit rates, V the rates' factor (a low rank: Woodbury)."""
        return G, self.rates_factor(scale, relaxation)

    def rates_factor(self, scale: float, relaxation: float) -> np.ndarray:
        """V (nodes, n) with d(dq/dt)/dP = V^T: the same at every pressure and q."""
        if self._V is None:
            # to_grid's transpose is to_nodes (both blend the same two shifts)
            self._V = (scale / relaxation) * self.shift.to_nodes(self.modal.T)
        return self._V


class ModalStateEHD:
    """The "fem-ehd" film with the bush's modal coordinates as integration states (module
    docstring): ``state_size`` = modes; :meth:`rates` gives the force and dq/dt.

    Parameters: bearing; lubricant, bush (an :class:`~bearingfem.ElasticBush`), n_theta,
    n_z, modes (>= 1) as "fem-ehd"; relaxation tau [s] > 0; profile a bush edge profile
    (:class:`~bearingfem.fields.EdgeProfile`, fixed to the bush: it adds to the gap, not to
    its rate) or None.
    """

    memory = True
    has_tangent = True       # contract rule 17: tangent() after a rates call
    replay_tolerance = REPLAY_TOLERANCE     # rule 13: a step solved from its kept states

    def __init__(self, bearing: Bearing, lubricant=None, bush=None, n_theta: int = 48,
                 n_z: int = 8, modes: int = 16, relaxation: float = 1e-5, roughness=None,
                 profile=None):
        if bush is not None and not int(modes) >= 1:
            raise ValueError(f"modes must be >= 1 for the modal-state EHD film, got {modes!r}")
        hold_bush_inputs(self, "modal-state", bearing, lubricant, bush, n_theta, n_z,
                         relaxation, roughness, profile)
        comp = ehd_compliance(bush, bearing.radius, bearing.length, self.n_theta, self.n_z,
                              int(modes))
        self.left = comp.left                                   # (grid, n) [1]
        self.modal = comp.singular[:, None] * comp.right.T      # (n, grid) [m/Pa]
        self.state_size = comp.singular.size
        self.steps = 0
        self._P = None          # the last solve's pressure: a warm start only
        self._factor = []       # its last Newton factorisation: chord steps from it
        self._frame = None      # the last journal angle's _Frame
        self._rated = None      # the last rates call's (film, solve): what tangent() takes

    # -- the film at (state, q) ---------------------------------------------------------
    def _new_frame(self, op, gamma: float) -> _Frame:
        return _Frame(op, gamma, self.left, self.modal, self.bearing.clearance)

    def _coupled(self, state: JournalState, q: np.ndarray) -> _CoupledFilm:
        b = self.bearing
        op = fe_operator(b, state, self.n_theta, self.n_z, "P1", None, False)
        m = op.mesh
        c = b.clearance
        frame = self._frame
        if frame is None or frame.op is not op or frame.gamma != state.gamma:
            frame = self._frame = self._new_frame(op, state.gamma)
        w = frame.deflection(q)                                     # nodal deflection [m]
        # the rigid gap, negative beyond the clearance circle where the bush opens it
        # (an evaluation whose whole gap closes fails, and the integrator cuts its step)
        th = op.qp_theta
        gap_q = film_thickness(th, state.eps) + op.at_quadrature(w) / c
        # dH/dt at a film point with q held: the journal's squeeze, and the deflection
        # (fixed in the bush) passing under the film's frame as the journal whirls:
        # gamma_dot dw/dalpha (the wedge term's omega - 2 gamma_dot covers the rest)
        t = jacobian_tables(op)
        dw = np.einsum("jeq,je->eq", t.dphi[:, 0], w[m.basis.element_dofs]) / t.dx
        rigid_rate = state.eps_dot * np.cos(th) + state.gamma_dot * dw / c
        gap0 = film_thickness(m.theta, state.eps) + w / c
        if self.profile is not None:        # the bore's crown or chamfer: fixed, no rate
            gap_q = gap_q + self.profile.film_gap(b, op.qp_zeta)
            gap0 = gap0 + self.profile.film_gap(b, m.zeta)
        contact, gap_nodes, moving = None, gap0, None   # the gap as it is (not floored)
        if self.roughness is not None and self.roughness.flow is not None:
            # the summits carry what the film cannot; the film's flow through the rough
            # gap by Patir & Cheng's factors, which take any nominal gap (no floor)
            contact = self.roughness.pressure(c * gap0)
        elif self.roughness is not None:
            # the summits carry what the film cannot where the gap nearly closes: their
            # pressure loads the bush and the journal; the film's flow sees a gap floored at
            # FLOW_FLOOR sigma (a stand-in for the flow factors of a rough gap)
            contact = self.roughness.pressure(c * gap0)
            floor = FLOW_FLOOR * self.roughness.sigma / c
            moving = (gap_q > floor).astype(float)
            gap_q, gap0 = np.maximum(gap_q, floor), np.maximum(gap0, floor)
        base = FilmFields(gap=gap_q, gap_rate=np.zeros_like(gap_q),
                          viscosity=np.ones_like(gap_q), density=np.ones_like(gap_q),
                          density_rate=np.zeros_like(gap_q))
        film = ehd_film(b, state, op, base, gap0, self.lubricant, None, self.roughness)
        return _CoupledFilm(film, q, self.tau, frame, self.modal, rigid_rate, contact,
                            gap_nodes, w, moving, state.gamma_dot)

    def _solve(self, coupled: _CoupledFilm) -> EHDResult:
        free = coupled.op.mesh.free
        n = coupled.op.mesh.ndofs
        if self._P is not None and self._P.shape == (n,):
            # warm: chord steps on the last solve's factorisation, then Newton at s = 1
            result, _ = warm_solve(coupled, self._P, free, TOL, self._factor)
            if result is not None:
                return result
        # cold: the isoviscous film (s = 0) from no pressure, then the lubricant's fields
        out, its = _newton(coupled, np.zeros(n), 0.0, free, "reynolds", TOL, self._factor)
        if out is None:
            closed = float(np.min(coupled.gap)) <= 0.0
            raise ConvergenceError("modal-state EHD film", its, None,
                                   "its isoviscous start" + (
                                       " (the gap is closed at some nodes: without roughness "
                                       "nothing carries that contact)" if closed else ""))
        return continuation(lambda s, P: _newton(coupled, P, s, free, "reynolds", TOL,
                                                 self._factor),
                            out[0], 0.0, 1.0, 1.0, 1e-3, "modal-state EHD film",
                            "coupling s", "reduce the load or refine the mesh")

    def rates(self, state: JournalState, q: np.ndarray, t: float = 0.0):
        """((F_r, F_t) [N], dq/dt [m/s]) at the journal ``state`` and modal coordinates
        ``q`` [m]; keeps nothing but a warm start (and this film, for :meth:`tangent`)."""
        coupled = self._coupled(state, np.asarray(q, float))
        res = self._solve(coupled)
        P = self._P = res.pressure
        self._rated = (coupled, res)
        return self._force(coupled, P), coupled.rates(P)

    def tangent(self) -> StateTangent:
        """The force and dq/dt of the last :meth:`rates` call differentiated in q, with the
        journal's state held (contract rule 17): what an implicit integrator's Jacobian
        needs, at the cost of one factorisation and one n-column solve.

        q moves the flow's gap (H = H_rigid + L q / c, where not floored), the whirl's
        squeeze gamma_dot d(L q)/dalpha / c, dq/dt's -q / tau, and the summits' pressure
        (p_a at the gap c H): dR/dq at the converged pressure, the fields held. The pressure
        follows by the implicit function theorem, dP/dq = -M^-1 dR/dq with M the Newton
        matrix on the rows not held cavitated (those keep P = 0): exact while no node
        leaves or joins the cavity."""
        if self._rated is None:
            raise ValueError("tangent() differentiates the last rates() call: call rates first")
        coupled, res = self._rated
        op, frame, film = coupled.op, coupled.frame, coupled.film
        c, P, n = self.bearing.clearance, res.pressure, self.state_size
        ev = coupled.evaluate(P)
        L = frame.left                                               # (nodes, n) [1]
        # a rough gap's squeeze term moves with the gap at the film's own rate: the film
        # built whole (the affine path's fields hold the rate at dq/dt = 0)
        whole = ev if ev.flow is None or film.lubricant is not None else coupled.film_state(P)
        dR = film.gap_slope(P, 1.0, whole, coupled.moving) @ (L / c)
        if coupled.gamma_dot:
            t = jacobian_tables(op)
            dL = np.einsum("jeq,jen->eqn", t.dphi[:, 0], L[op.mesh.basis.element_dofs])
            dR += coupled.rate_load(ev, (coupled.gamma_dot / c) * (dL / t.dx[..., None])
                                    .reshape(-1, n))
        dpa = (np.zeros_like(L) if coupled.contact is None else
               self.roughness.pressure_derivative(c * coupled.gap)[:, None] * L)   # [Pa/m]
        rates_q = (self.modal @ frame.shift.to_grid(dpa) - np.eye(n)) / self.tau
        G = coupled.squeeze_load(ev)
        dR += G @ rates_q
        free = op.mesh.free
        factor = _Factor.at(coupled, P, 1.0, free, res.active[free], ev)
        dP = np.zeros_like(L)
        dP[factor.I] = factor.lu.solve(-dR[factor.I])
        V = frame.rates_factor(film.scale, self.tau)
        k = force_factor(self.bearing, False)
        ic, is_ = op.force_integrals((dP + dpa / film.scale).T)
        return StateTangent(force_local=k * np.vstack([ic, is_]), rates=rates_q + V.T @ dP)

    def _force(self, coupled, P) -> tuple:
        """(F_r, F_t) [N]: the film's and the summits' pressure on the journal."""
        if coupled.contact is not None:
            P = P + coupled.contact / coupled.film.scale
        ic, is_ = coupled.op.force_integrals(P)
        k = force_factor(self.bearing, False)
        return k * float(ic), k * float(is_)

    def solution(self, state: JournalState, q: np.ndarray) -> FilmSolution:
        """The whole film at (``state``, ``q``): pressures, the elastic gap, friction."""
        coupled = self._coupled(state, np.asarray(q, float))
        res = self._solve(coupled)
        self._P = res.pressure
        ev = coupled.film_state(res.pressure)
        fields = friction_fields(ev.fields, self.roughness, self.bearing.clearance)
        sol = film_outputs(self.bearing, state, coupled.op, res, ev.values, ev.load,
                           fields, "reynolds", "full", (), "fem-P1/ehd-states",
                           gap=coupled.gap)
        sol = replace(sol, deformation=coupled.deflection)     # [m], opening the gap
        if coupled.contact is None:
            return sol
        total = self._force(coupled, res.pressure)
        local = (total[0] - sol.force_local[0], total[1] - sol.force_local[1])
        # the summits' Coulomb friction on their load, int p_a dA (as asperity_contact)
        r = self.bearing.radius
        load = r * r * float(np.sum(coupled.op.at_quadrature(coupled.contact)
                                    * coupled.op.qp_weight))
        friction = self.roughness.friction * load * float(np.sign(state.omega))
        return replace(sol, asperity_force_local=local,
                       asperity_force=tuple(map(float, local_to_inertial(*local, state.gamma))),
                       asperity_friction_torque=friction * r)

    # -- the RunFilm contract (rules 10-14, 16) -------------------------------------------
    def start(self, state: JournalState, t: float) -> None:
        self.steps, self._P, self._factor, self._rated = 0, None, [], None

    def force(self, state: JournalState, t: float) -> tuple:
        raise ValueError("the modal-state EHD film needs its states: call rates(state, q, t)")

    def commit(self, state: JournalState, t: float, q=None) -> FilmStep | None:
        """The whole film at an accepted step (its record: force, least film, peak)."""
        if q is None:
            return None
        sol = self.solution(state, q)
        self.steps += 1
        f, a = sol.force_local, sol.asperity_force_local
        return FilmStep(float(t), state, (f[0] + a[0], f[1] + a[1]), sol)

    def snapshot(self):
        return (self.steps, self._P)

    def restore(self, snapshot) -> None:
        self.steps, self._P = snapshot

    def replay(self, start, steps):
        """Nothing: a step's film needs its states, which a replay is not given; the run
        keeps them (its ``film_z``) and :meth:`solution` solves a step's film from them."""
        return iter(())


def hold_bush_inputs(film, name: str, bearing: Bearing, lubricant, bush, n_theta: int,
                     n_z: int, relaxation: float, roughness, profile) -> None:
    """The inputs every film with the bush's deflection as states holds (the modal, the
    full and the implicit-step films), checked: a bush, tau = ``relaxation`` > 0 [s]
    (``film.tau``), the edge profile checked against the bearing."""
    if bush is None:
        raise ValueError(f"bush is required for the {name} EHD film")
    if not (np.isfinite(relaxation) and relaxation > 0.0):
        raise ValueError(f"relaxation must be > 0 [s], got {relaxation!r}")
    film.bearing, film.lubricant, film.roughness = bearing, lubricant, roughness
    film.profile = None if profile is None else profile.check(bearing)
    film.n_theta, film.n_z = int(n_theta), int(n_z)
    film.tau = float(relaxation)
