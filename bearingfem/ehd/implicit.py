"""The EHD film with the bush's deflection advanced by the film's own implicit step.

:class:`~bearingfem.ehd.states.FullStateEHD` integrates the bush's whole deflection w with
the journal; the integrator's Jacobian then holds dw/dt's dense N x N derivative, which
grows past a few thousand grid nodes. Here w stays out of the integrator: the film keeps
the deflection w_n of the last accepted step (time t_n) and, at a trial state at time t,
steps it by backward Euler over dt = t - t_n (the Kelvin-Voigt bush of
:mod:`~bearingfem.ehd.states`, tau its relaxation time [s]):

    w = w_n + dt v,     (tau + dt) v + w_n = C (p + p_a),

v = dw/dt [m/s] the bush's rate, in the film's squeeze as in the states film
(dH/dt = dH_rigid/dt + v / c, plus the deflection passing under the whirling frame).
Given the journal's state the gap and its rate are known functions of the pressure, so
each trial state is one EHD solve: the film's semismooth Newton
(:mod:`bearingfem.ehd.newton`; its load continuation's s scales the lubricant's fields
and the deflection's step, w = w_n + s dt v, so s = 0 is the states film at q = w_n) with
the bush's part of the Jacobian, dR/dv dv/dP, applied
matrix-free (the compliance by FFT per theta harmonic, GMRES preconditioned by the film's
sparse LU and the compliance's leading modes by Woodbury); no dense matrix. With the
summits' pressure p_a (Greenwood & Tripp) v solves its own small equation inside each
evaluation, (tau + dt) v + w_n - C (p + p_a(w_n + dt v)) = 0 (Newton, GMRES on
S = (tau + dt) I + dt C T^T K T, K the summits' stiffness: compliance products only); in
the Newton matrix's products S^-1 is by Woodbury on the nodes where K counts,
:class:`~.bush_rate._RateInverse`: the compliance's columns at those nodes, built once a matrix.

Limits (tests/test_ehd_implicit.py): at dt = 0 the film is the states film at q = w_n
(the same residual); its force is continuous across a commit (the committed (P, v) solve
the next step's film at dt = 0); as dt grows with the journal held still, w tends to the
steady EHD film's deflection; with tau -> 0, w = C (p + p_a) is the quasi-static bush,
with its squeeze by the backward difference (w - w_n) / dt.

Each solve starts from the last two commits' pressures extrapolated linearly in t
(:meth:`ImplicitStepEHD.start_pressure`): where the integrator's step grows, the last
pressure is a whole step behind and Newton from it stalls where the gap closes. The first
solve at a new time factorises the Newton matrix at that start; every solve at that time
(the integrator's predictor, corrector and the commit) takes its chord steps on it
(:meth:`ImplicitStepEHD._refactor`).

The deflection's error is the backward Euler step's, O(dt) over the integrator's step,
which the integrator's error control (on the journal alone) does not see: its convergence
is measured in the integrator's tolerance (docs/ehd-states.md).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres

from ..bearing import Bearing, JournalState
from ..contact.flow_factors import FLOW_FLOOR
from ..contract import FilmStep, StatelessRun
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fe.kernel import film_outputs
from ..fe.mixed import friction_fields
from ..fields import FilmFields
from ..film import film_thickness, film_thickness_at, local_to_inertial
from ..scales import force_factor
from .bush_rate import _Frame, _RateCompliance, _RateInverse  # noqa: F401 (_RateInverse: tests)
from .coupling import ehd_film, jacobian_tables
from .film_compliance import BushJacobian
from .newton import EHDResult, _Factor, _merit, _newton, continuation, warm_solve
from .states import STEP_TOLERANCE, TOL, full_bush_setup

__all__ = ["ImplicitStepEHD", "ImplicitSnapshot"]

#: The bush rate's own Newton (with summits): its residual test, relative to the size of
#: its terms, and its most steps; the GMRES tolerance of each of its steps.
RATE_TOL = 1e-12
RATE_STEPS = 30
RATE_KRYLOV = 1e-10
#: The chord steps of a solve (on the Newton matrix at its time's first start): at most
#: CHORD_STEPS, each to cut max |Phi| by CHORD_RATE, before Newton takes over. Why not
#: newton's 6 and 0.3: on finer meshes more nodes leave or join the cavity in a step and
#: the first chord steps cut the residual only 0.4-0.9-fold while the held rows settle;
#: Newton then built a Jacobian per step (the seed pin's first 1 % of a turn at 192 x 16:
#: 311 Newton matrices with 0.3 and 6, 191 with 0.9 and 12, the same evaluations to 1 %,
#: CPU -16 %; at 48 x 4 the same to the timing's scatter)
CHORD_STEPS = 12
CHORD_RATE = 0.9
#: Chord steps of a solve allowed to miss CHORD_RATE before Newton takes over (a
#: nonmonotone chord, as the Newton's line search). Why: on 192 x 16 one solve in eleven
#: had its first chord step raise the residual while held rows settled, and Newton from
#: there took 4.6 fresh Jacobians (the seed pin's first 3 % of a turn: 81 Newton solves,
#: 375 Jacobians; with 2 allowed, 2 and 0, the CPU 55 -> 43 s, the same steps); at
#: 48 x 4 and 96 x 8 the same evaluations to 0.3 %
CHORD_SLACK = 2


@dataclass(frozen=True)
class ImplicitSnapshot:
    """What an :class:`ImplicitStepEHD` keeps: the time t_n [s] and deflection w_n [m]
    (bush grid) of the last committed step, the film steps, the warm start."""

    t: float
    deflection: np.ndarray
    steps: int
    pressure: np.ndarray | None
    committed: tuple = ()


class _Evaluated:
    """The film at one pressure: the EHD film built on its gap and rate, its evaluation,
    the bush's rate v [m/s] and deflection w [m] on the grid, the summits' nodal pressure
    [Pa] and their stiffness -dp_a/dh [Pa/m] (None without roughness; from the nodal gap
    ``summits_gap`` [m] when first asked: only a Newton matrix needs it)."""

    def __init__(self, film, ev, v, w, contact, summits_gap, gap, moving, roughness):
        self.film, self.ev, self.v, self.w = film, ev, v, w
        self.contact, self.gap, self.moving = contact, gap, moving
        self._h, self._roughness = summits_gap, roughness

    @cached_property
    def stiffness(self):
        if self.contact is None:
            return None
        return -self._roughness.pressure_derivative(self._h)



class _StepFilm:
    """The film of one trial state and step dt, as :func:`~.newton._newton` asks of a
    film: ``op``, ``evaluate(P, s)``, ``jacobian(P, s, ev)``."""

    def __init__(self, run: "ImplicitStepEHD", state: JournalState, dt: float, frame):
        b = run.bearing
        self.run, self.state, self.dt = run, state, float(dt)
        self.op = op = fe_operator(b, state, run.n_theta, run.n_z, "P1", None, False)
        self.frame, self.shift = frame, frame.shift
        self.c, self.scale = b.clearance, b.pressure_scale
        self.tau = run.tau + self.dt          # (tau + dt): the rate's factor
        self.w_n = run._w
        m = op.mesh
        self.th = op.qp_theta
        self.cos_th = np.cos(self.th)
        self.gap_q0 = film_thickness_at(self.cos_th, state.eps)   # rigid gap at the points
        self.gap_n0 = film_thickness(m.theta, state.eps)      # and at the nodes
        if run.profile is not None:          # the bore's crown or chamfer: fixed, no rate
            self.gap_q0 = self.gap_q0 + run.profile.film_gap(b, op.qp_zeta)
            self.gap_n0 = self.gap_n0 + run.profile.film_gap(b, m.zeta)
        self.tables = jacobian_tables(op)
        self._last = None

    # -- the bush ---------------------------------------------------------------------
    def comply(self, p_nodes: np.ndarray) -> np.ndarray:
        """C T^T p: the grid's quasi-static deflection [m] under nodal pressure [Pa]."""
        return self.run.compliance.on_grid(self.shift.to_grid(p_nodes))

    def node_compliance(self, nodes: np.ndarray) -> np.ndarray:
        """(T C T^T)[nodes, nodes] [m/Pa]: the film nodes' deflection under their
        pressure, gathered without a compliance product. C is circulant in theta and T a
        blend of two shifts ((1 - a) by whole cells, a by one more), so T C T^T is
        circulant: its entry between film nodes (j, k) and (j', k') is
        ((1 - a)^2 + a^2) c(d) + a (1 - a) (c(d - 1) + c(d + 1)), d = j - j', c(d) the
        grid's response at (d, k) to a unit load at (0, k') (:meth:`ImplicitStepEHD.
        grid_columns`)."""
        table = self.frame.blended(self.run.grid_columns, self.shift.frac)
        j, k = (x[nodes] for x in self.frame.indices)
        n, m = self.run.grid_columns.shape[:2]
        d = (j[:, None] - j[None, :]) % n
        return np.take(table, (d * m + k[:, None]) * m + k[None, :])

    def solve_rate(self, b: np.ndarray, stiffness, rtol: float, s: float = 1.0,
                   x0=None) -> np.ndarray:
        """y with S y = b, S = (tau + dt) I + s dt C T^T K T (K = diag(``stiffness``) at
        the nodes; None: S = (tau + dt) I), by GMRES from ``x0`` (None: b / (tau + dt))."""
        if stiffness is None or self.dt == 0.0 or s == 0.0 or not np.any(stiffness):
            return b / self.tau
        n = b.size
        dt, tau = s * self.dt, self.tau

        def S(y):
            return tau * y + dt * self.comply(stiffness * self.shift.to_nodes(y))
        y, _ = gmres(LinearOperator((n, n), matvec=S, dtype=float), b,
                     x0=b / tau if x0 is None else x0,
                     rtol=rtol, atol=0.0, restart=60, maxiter=20)
        return y

    def _nodal_gap(self, w: np.ndarray) -> np.ndarray:
        """The nodal gap over c (not floored) with the grid deflection w."""
        return self.gap_n0 + self.shift.to_nodes(w) / self.c

    def rate(self, P: np.ndarray, s: float = 1.0) -> tuple | None:
        """(v, w, p_a, h) at nodal P and coupling s (w = w_n + s dt v; h [m] the nodal
        gap the summits see, None without them): the bush's rate solved (with summits, by
        Newton), or None where that solve fails."""
        p = self.scale * P
        rough = self.run.roughness
        step = s * self.dt
        if rough is None:
            v = (self.comply(p) - self.w_n) / self.tau
            return v, self.w_n + step * v, None, None
        # the start: the rate with the summits' pressure held at the last evaluation's
        # (at w_n for the first), v = (C (p + p_held) - w_n) / (tau + dt)
        last = None if self._last is None else self._last.out
        held = (rough.pressure(self.c * self._nodal_gap(self.w_n)) if last is None
                else last.contact)
        load = self.comply(p + held)
        v = (load - self.w_n) / self.tau
        w = self.w_n + step * v
        h = self.c * self._nodal_gap(w)
        pa = rough.pressure(h)
        # its residual is C T^T (p_held - p_a(w)), at most |C| |p_a - p_held| (|T| <= 1):
        # where the summits' pressure has not moved that passes the test below without
        # a compliance product
        size = float(np.max(np.abs(self.tau * v) + np.abs(self.w_n) + np.abs(load)))
        moved = self.run.compliance_norm * float(np.linalg.norm(pa - held))
        if np.isfinite(size) and moved <= RATE_TOL * max(size, 1e-300):
            return v, w, pa, h
        for _ in range(RATE_STEPS):
            load = self.comply(p + pa)
            r = self.tau * v + self.w_n - load
            size = float(np.max(np.abs(self.tau * v) + np.abs(self.w_n) + np.abs(load)))
            if not np.all(np.isfinite(r)):
                return None
            if float(np.max(np.abs(r), initial=0.0)) <= RATE_TOL * max(size, 1e-300):
                return v, w, pa, h
            k = -rough.pressure_derivative(h)
            v = v - self.solve_rate(r, k, RATE_KRYLOV, s)
            w = self.w_n + step * v
            h = self.c * self._nodal_gap(w)
            pa = rough.pressure(h)
        return None

    # -- the film ---------------------------------------------------------------------
    def at(self, P: np.ndarray, s: float = 1.0) -> _Evaluated | None:
        """The film at nodal P built whole (kept for the Jacobian at the same P)."""
        if self._last is not None and self._last.s == s and np.array_equal(self._last.P, P):
            return self._last.out
        out = self._build(P, s)
        self._last = _Memo(P.copy(), s, out)
        return out

    def _build(self, P, s):
        run, op, c, state = self.run, self.op, self.c, self.state
        run.evaluations += 1
        solved = self.rate(P, s)
        if solved is None:
            return None
        v, w, pa, h = solved
        wn = self.shift.to_nodes(w)
        vn = self.shift.to_nodes(v)
        # dH/dt at the points: the journal's squeeze, the bush's rate, and the deflection
        # (fixed in the bush) passing under the whirling film frame, gamma_dot dw/dalpha
        dw = (run._whirl(op) @ wn).reshape(self.th.shape)
        rate = (state.eps_dot * self.cos_th + state.gamma_dot * dw / c
                + op.qp_interp.dot(vn).reshape(self.th.shape) / c)
        gap_q = self.gap_q0 + op.at_quadrature(wn) / c
        gap_n = self.gap_n0 + wn / c
        moving = None
        if run.roughness is not None and run.roughness.flow is None:
            floor = FLOW_FLOOR * run.roughness.sigma / c
            moving = (gap_q > floor).astype(float)
            gap_q = np.maximum(gap_q, floor)
        base = FilmFields(gap=gap_q, gap_rate=rate, viscosity=np.ones_like(gap_q),
                          density=np.ones_like(gap_q), density_rate=np.zeros_like(gap_q))
        film = ehd_film(run.bearing, state, op, base,
                        gap_n if moving is None else np.maximum(gap_n, floor),
                        run.lubricant, None, run.roughness)
        ev = film.evaluate(P, s)
        if ev is None:
            return None
        return _Evaluated(film, ev, v, w, pa, h, gap_n, moving, run.roughness)

    def evaluate(self, P: np.ndarray, s: float = 1.0):
        out = self.at(P, s)
        return None if out is None else out.ev

    def squeeze_load(self, ev) -> sp.csr_matrix:
        """d R / d(dH/dt) at the points, as nodes x points: 12 rho phi_i dx (a rough gap's
        flow: times dE(h_T)/dh)."""
        rho = np.broadcast_to(ev.fields.density, self.op.qp_weight.shape)
        if ev.flow is not None:
            rho = rho * ev.flow.gap_slope
        # the interpolation's transpose kept a run, its columns scaled in place (the
        # product with a diagonal matrix took a quarter of a Newton matrix's build)
        Wq = self.run._spread(self.op).copy()
        Wq.data *= (12.0 * rho * self.op.qp_weight).ravel()[Wq.indices]
        return Wq

    def jacobian(self, P, s, ev):
        """(J_sparse, BushJacobian, None): dR/dP with the gap and its rate held, and the
        bush's part (dR/dv) (dv/dP), dv/dP = scale S^-1 C T^T matrix-free."""
        out = self.at(P, s)
        op, c, dt = self.op, self.c, s * self.dt
        J, _, _ = out.film.jacobian(P, s, out.ev)
        T = self.frame.left                                      # (nodes, grid) sparse
        Wq = self.squeeze_load(out.ev)                           # (nodes, points)
        # dR/dv (nodes, grid) = [Wq (I + dt gamma_dot D) + dt T_H] T / c: the squeeze of
        # v, and through w = w_n + dt v the whirl's gamma_dot dw/dalpha and the gap; summed
        # on the nodes first, one product with T (six sparse products took half the
        # Jacobian's time at 96 x 16)
        points = op.qp_interp
        if dt and self.state.gamma_dot:
            points = points + (dt * self.state.gamma_dot) * self.run._whirl(op)
        nodes = Wq @ points
        if dt:
            nodes = nodes + dt * out.film.gap_slope(P, s, out.ev, out.moving)
        coupling = sp.csr_matrix(nodes @ T) / c
        low = self.run._low
        V = (self.scale / self.tau) * self.shift.to_nodes(low.right * low.singular)
        rate = _RateCompliance(self, out.stiffness, s)
        # the preconditioner's low-rank part with S^-1 (the summits' stiffness) on the
        # leading modes: (tau + dt) S_A^-1 L, not L alone
        left = self.tau * rate.inverse.woodbury(low.left)
        bush = BushJacobian(coupling, rate, (np.asarray(coupling @ left), V), STEP_TOLERANCE)
        return J, bush, None


@dataclass
class _Memo:
    P: np.ndarray
    s: float
    out: _Evaluated | None


class ImplicitStepEHD(StatelessRun):
    """The "fem-ehd" film (Reynolds' condition) with the bush's whole deflection advanced
    by the film's backward-Euler step between accepted integrator steps (module
    docstring): a film with memory and no states of its own (contract rules 10-14); each
    trial state is one EHD solve, no dense matrix.

    Parameters: bearing; lubricant, bush (an :class:`~bearingfem.ElasticBush`), n_theta,
    n_z as "fem-ehd"; relaxation tau [s] > 0 the bush's Kelvin-Voigt time; roughness (the
    summits' pressure loads the bush and the journal); profile a bush edge profile or None.
    """

    memory = True
    #: A replay's departure from its run (contract rule 13), relative to the run's largest
    #: force: a replayed commit starts from the last two commits' pressures, the run's
    #: from its trial solves at that time, and both stop at the Newton tolerance TOL of
    #: the residual's terms, so they agree to TOL times the film's conditioning, which
    #: grows with the mesh. Measured on the seed pin's first 0.05 turn (its largest where
    #: the run-up closes the gap): 5e-11 (24 x 4, 48 x 4), 1.0e-9 (96 x 16), 1.7e-9
    #: (192 x 16); another crown or relaxation time by 0.1 % departs by 1e-4
    replay_tolerance = 1e3 * TOL

    def __init__(self, bearing: Bearing, lubricant=None, bush=None, n_theta: int = 48,
                 n_z: int = 8, relaxation: float = 1e-5, roughness=None, profile=None):
        full_bush_setup(self, "implicit-step", bearing, lubricant, bush, n_theta, n_z,
                        relaxation, roughness, profile)
        n = self.compliance.shape[0] * self.compliance.shape[1]
        self.size = n
        self.steps = 0
        self.evaluations = 0             # film evaluations so far (a benchmark's record)
        self.rate_fallbacks = 0          # S^-1 solves that fell back to GMRES (a record)
        # |C|_2 (the largest singular value of the harmonic blocks), a bound with margin
        # for the banded blocks' relative error
        self.compliance_norm = float(np.max(self._low.singular)) * (1.0 + 1e-6)
        self.t = 0.0
        self._w = np.zeros(n)            # w_n [m] on the bush grid
        self._P, self._factor, self._frame = None, [], None
        self._P_t = None                 # the time [s] of the last solve's pressure
        self._factor_t = None            # the time [s] of the kept Newton matrix's film
        self._committed = ()             # (t, P) of the last two commits, older first
        self._whirls, self._spreads = {}, {}

    @cached_property
    def grid_columns(self) -> np.ndarray:
        """c (n_theta, n_z + 1, n_z + 1) [m/Pa]: c[d, k, k'] the deflection at grid node
        (d, k) under a unit pressure at grid node (0, k'); the compliance is circulant in
        theta, so these n_z + 1 columns (one batched product, once a run) give every
        entry, C[(j, k), (j', k')] = c[j - j', k, k']."""
        n, m = self.compliance.shape
        unit = np.zeros((n * m, m))
        unit[np.arange(m), np.arange(m)] = 1.0
        return self.compliance.on_grid(unit).reshape(n, m, m)

    def _spread(self, op) -> sp.csr_matrix:
        """The interpolation's transpose (nodes x points, CSR), per film operator."""
        kept = self._spreads.get(id(op))
        if kept is None or kept[0] is not op:
            kept = self._spreads = {id(op): (op, op.qp_interp.T.tocsr())}
            kept = kept[id(op)]
        return kept[1]

    def _whirl(self, op) -> sp.csr_matrix:
        """d/dalpha at the points of nodal values (points x nodes), per film operator."""
        D = self._whirls.get(id(op))
        if D is None:
            t = jacobian_tables(op)
            dofs = op.mesh.basis.element_dofs
            E, Q = t.dx.shape
            rows = np.broadcast_to((np.arange(E)[:, None] * Q + np.arange(Q))[None],
                                   t.dphi[:, 0].shape)
            cols = np.broadcast_to(dofs[:, :, None], t.dphi[:, 0].shape)
            D = sp.csr_matrix(((t.dphi[:, 0] / t.dx[None]).ravel(),
                               (rows.ravel(), cols.ravel())), shape=(E * Q, op.mesh.ndofs))
            self._whirls = {id(op): D}
        return D

    def step_film(self, state: JournalState, t: float) -> _StepFilm:
        """The film at the trial ``state`` at time ``t`` [s] (t >= the last commit's)."""
        dt = float(t) - self.t
        if dt < 0.0:
            raise ValueError(f"t must be >= the last committed step's time {self.t!r} [s] "
                             f"(the implicit-step film steps forward), got {t!r}")
        op = fe_operator(self.bearing, state, self.n_theta, self.n_z, "P1", None, False)
        frame = self._frame
        if frame is None or frame.op is not op or frame.gamma != state.gamma:
            frame = self._frame = _Frame(op, state.gamma)
        return _StepFilm(self, state, dt, frame)

    def _solve(self, film: _StepFilm) -> EHDResult:
        """Chord steps on the Newton matrix at this time's first start (:meth:`_refactor`),
        then Newton, from the start of :meth:`start_pressure`; where those fail, the continuation in s (the deflection's step) from the
        s = 0 film (the states film at q = w_n) solved from that pressure, else from none."""
        free = film.op.mesh.free
        n = film.op.mesh.ndofs
        starts = [np.zeros(n)]
        if self._P is not None and self._P.shape == (n,):
            t = film.dt + self.t
            start = self.start_pressure(t, n)
            if self._factor_t != t:
                self._refactor(film, start, free, t)
            result, its = warm_solve(film, start, free, TOL, self._factor, CHORD_STEPS,
                                     CHORD_RATE, CHORD_SLACK)
            if result is not None:
                return result
            starts.insert(0, self._P.copy())
        for P in starts:
            out, its = _newton(film, P, 0.0, free, "reynolds", TOL, self._factor)
            if out is not None:
                break
        else:
            raise ConvergenceError("implicit-step EHD film", its, None, "its isoviscous start")
        return continuation(lambda s, P: _newton(film, P, s, free, "reynolds", TOL,
                                                 self._factor),
                            out[0], 0.0, 1.0, 1.0, 1e-3, "implicit-step EHD film",
                            "coupling s", "reduce the load or refine the mesh")

    def _refactor(self, film: _StepFilm, P: np.ndarray, free, t: float) -> None:
        """The Newton matrix at the start ``P`` of the first solve at a new time ``t``,
        kept for the chord steps of every solve at ``t`` (the integrator's predictor,
        corrector and the commit share t, hence dt and tau + dt). Why: a matrix kept from
        an earlier time, at another tau + dt (the bush's rate, the Newton matrix's largest
        part, scales as 1 / (tau + dt)), cut the residual ~30-fold a chord step where a
        fresh one cuts it by GMRES's 1e-3: 3.8 against 2.6 chord steps a trial solve and
        1 in 6 chords stalled to Newton (the seed pin's first 2 % of a turn, 48 x 4).
        Where the start's film fails or its matrix is singular the old one is kept."""
        phi, _, held, ev = _merit(film, P, 1.0, free, "reynolds")
        if phi is None:
            return
        try:
            factor = _Factor.at(film, P, 1.0, free, held, ev)
        except (RuntimeError, la.LinAlgError):
            return
        self._factor[:] = [factor]
        self._factor_t = t

    def start_pressure(self, t: float, n: int) -> np.ndarray:
        """The warm start at time ``t`` [s] (n nodes): the last solve's pressure where it
        was at ``t`` (the integrator's corrector iterating at one time); else the pressure
        of the last two commits extrapolated linearly in t to ``t``, floored at 0 (where a
        step's dt jumps, the last pressure is a step behind: from it the chord and Newton
        stalled past the gap's closure and the continuation in s took over); else the
        last solve's."""
        if self._P_t == t or len(self._committed) < 2:
            return self._P
        (t0, P0), (t1, P1) = self._committed
        if P0.shape != (n,) or P1.shape != (n,) or not t1 > t0:
            return self._P
        return np.maximum(P1 + (t - t1) / (t1 - t0) * (P1 - P0), 0.0)

    def _force(self, film: _StepFilm, P: np.ndarray) -> tuple:
        """(F_r, F_t) [N]: the film's and the summits' pressure on the journal."""
        out = film.at(P)
        if out.contact is not None:
            P = P + out.contact / film.scale
        ic, is_ = film.op.force_integrals(P)
        k = force_factor(self.bearing, False)
        return k * float(ic), k * float(is_)

    def solve(self, state: JournalState, t: float) -> tuple:
        """(film, converged pressure result) at the trial ``state`` and time ``t``; keeps
        only the warm start."""
        film = self.step_film(state, t)
        res = self._solve(film)
        self._P, self._P_t = res.pressure, film.dt + self.t
        return film, res

    # -- the RunFilm contract (rules 10-14) ----------------------------------------------
    def start(self, state: JournalState, t: float) -> None:
        """Begin with the bush undeformed at time ``t`` [s] (as the states films)."""
        self.t, self._w, self.steps = float(t), np.zeros(self.size), 0
        self._P, self._factor, self._P_t, self._committed = None, [], None, ()
        self._factor_t = None

    def force(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] at a trial ``state`` and time ``t``: w stepped from the last
        commit over t - t_n; keeps nothing but a warm start."""
        film, res = self.solve(state, t)
        return self._force(film, res.pressure)

    def deflection_rate(self, state: JournalState, t: float) -> tuple:
        """(w, v) [m, m/s] on the bush grid at a trial ``state`` and time ``t``."""
        film, res = self.solve(state, t)
        out = film.at(res.pressure)
        return out.w, out.v

    def solution(self, state: JournalState, t: float):
        """The whole film at a trial (``state``, ``t``): pressures, the elastic gap,
        friction; and the step's deflection w [m] on the grid."""
        film, res = self.solve(state, t)
        out = film.at(res.pressure)
        ev = out.ev
        fields = friction_fields(ev.fields, self.roughness, self.bearing.clearance)
        sol = film_outputs(self.bearing, state, film.op, res, ev.values, ev.load, fields,
                           "reynolds", "full", (), "fem-P1/ehd-implicit", gap=out.gap)
        sol = replace(sol, deformation=film.shift.to_nodes(out.w))
        if out.contact is None:
            return sol, out.w
        total = self._force(film, res.pressure)
        local = (total[0] - sol.force_local[0], total[1] - sol.force_local[1])
        r = self.bearing.radius
        load = r * r * float(np.sum(film.op.at_quadrature(out.contact) * film.op.qp_weight))
        friction = self.roughness.friction * load * float(np.sign(state.omega))
        return replace(sol, asperity_force_local=local,
                       asperity_force=tuple(map(float, local_to_inertial(*local, state.gamma))),
                       asperity_friction_torque=friction * r), out.w

    def commit(self, state: JournalState, t: float) -> FilmStep | None:
        """The film at the accepted step: w_n advanced to it (its record: force, least film,
        peak); a failed solve raises and keeps the film as it was."""
        t = float(t)
        if t <= self.t:
            return None
        sol, w = self.solution(state, t)
        self._w, self.t = w, t
        self._committed = self._committed[-1:] + ((t, self._P),)
        self.steps += 1
        f, a = sol.force_local, sol.asperity_force_local
        return FilmStep(t, state, (f[0] + a[0], f[1] + a[1]), sol)

    def snapshot(self) -> ImplicitSnapshot:
        return ImplicitSnapshot(self.t, self._w, self.steps, self._P, self._committed)

    def restore(self, snapshot: ImplicitSnapshot) -> None:
        self.t, self._w, self.steps, self._P = (snapshot.t, snapshot.deflection,
                                                snapshot.steps, snapshot.pressure)
        self._committed, self._factor, self._P_t = snapshot.committed, [], None
        self._factor_t = None

    def replay(self, start, steps):
        """The committed steps taken again from ``start`` = (t, JournalState) and the
        (t, JournalState) of each step: the same solves from the same deflections."""
        t0, s0 = start
        self.start(s0, t0)
        for t, state in steps:
            step = self.commit(state, t)
            if step is not None:
                yield step.t, step.solution
