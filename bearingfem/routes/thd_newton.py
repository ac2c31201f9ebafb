"""The Reynolds-condition thermal film by a coupled Newton on pressure and temperature.

Unknowns: the dimensionless pressure P on the film's free, uncavitated dofs, the nodal
temperature T on every dof of the energy equation, each groove's inlet temperature T_in
(the mixing of :func:`~bearingfem.routes.thd.groove_mixing`) and, for a zero-flux journal,
its temperature T_j. Equations: the film K(mu) P = b on those dofs (mu = mu(p, T) at the
film's quadrature points), the energy equation on its free rows
(:func:`~bearingfem.thermal.jacobian.energy_linearisation`), T = T_in on each groove's
held rows, T_in = the mixing of the upstream exit, and the journal's zero net flux.

The block Jacobian is exact (tested against finite differences):

    | K + dK/dp P     dK/dT P      0     0     |   film rows
    | dE/dP           dE/dT        0     dE/dTj |   energy rows (free)
    | 0               I            -1    0     |   held rows
    | -dM/dP          -dM/dT       1     0     |   mixing rows (one per groove)
    | 0               m_j          0     -sum m_j |   journal row

with dK/dT P the film's change through mu(p, T) at its quadrature points, dE/dP the
energy equation's through the Poiseuille flow, its dissipation and the SUPG weight,
dE/dT its operator plus the same through mu, and dM the mixing's through the exit
flows (the projected dP/dtheta) and the viscosity at the nodes. One sparse LU per step.

The cavitated set is held during the Newton steps and updated as the isothermal active
set does (an uncavitated dof with P < 0 joins, a cavitated one whose multiplier
K P - b is negative leaves) once the steps have converged; it rarely moves after the
first film's. Converged when a step moved no temperature by more than
``temperature_tol`` [K] and no pressure by more than ``pressure_rtol`` of its peak, at
a settled set (the residual after such a step is of its square: round-off).

Why Newton over the fixed point (:class:`~bearingfem.routes.thd.ThermalIteration`): the
fixed point contracts by about 1e-2 per step, each step a film and an energy solve (6
film and 5 energy solves to 1e-6 K); Newton's steps each cost one assembly and one LU of
the coupled system and converge quadratically from the fixed point's first step (docs/thd.md).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres, splu
from skfem import BilinearForm
from skfem.models.poisson import mass

from ..caches import cached
from ..errors import ConvergenceError
from ..fe.general import general_assembly
from ..film import film_thickness
from ..solvers.cavitation import LCPResult
from ..thermal.energy import EnergySolution
from ..thermal.jacobian import energy_linearisation
from ..thermal.spec import ThermalRecord
from .thd import ThermalIteration, check_thermal
from .thd_film import ReynoldsFieldFilm

__all__ = ["ThermalNewton", "mixing_linearisation", "solve_thd_newton"]


@BilinearForm
def _theta_gradient_form(u, v, w):
    return u.grad[0] * v


@cached(maxsize=16)
def _theta_projection(mesh):
    """(LU of the mass matrix, the form int dP/dtheta v): dP/dtheta projected on the
    nodes is M^-1 B P (the mixing's flows, :func:`~bearingfem.routes.thd.groove_mixing`)."""
    basis = mesh.basis
    return splu(mass.assemble(basis).tocsc()), _theta_gradient_form.assemble(basis).tocsr()


def mixing_linearisation(bearing, state, mesh, edges, P, fraction, T, lubricant, thermal):
    """Each groove's inlet temperature T_in = M_k(P, T) of
    :func:`~bearingfem.routes.thd.groove_mixing` (the same formula) and its gradients:
    a list of (value [K], d/dP (N,), d/dT (N,)) over the grooves, P dimensionless.
    The least column flow and the carried flow's cap are taken on their current branch."""
    R, c, ps = bearing.radius, bearing.clearance, bearing.pressure_scale
    sc = ps / R
    lu, B = _theta_projection(mesh)
    dP = lu.solve(B @ P)
    h = c * film_thickness(mesh.theta - state.gamma, state.eps)
    p = P * ps
    mu = lubricant.viscosity_at(p, temperature=T)
    k3 = h ** 3 / (12.0 * mu)
    q = 0.5 * state.omega * R * fraction * h - k3 * sc * dP
    dq_dmu = k3 / mu * sc * dP                             # q's change with mu at its node
    dq_dP_local = dq_dmu * lubricant.viscosity_derivative(p, temperature=T) * ps
    dq_dT = dq_dmu * lubricant.viscosity_temperature_derivative(T, p)
    col_w = np.zeros(mesh.ndofs)
    col_w[edges.column_dofs] = edges.column_weight
    column = np.full(mesh.ndofs, -1)
    column[edges.column_dofs] = edges.column_index
    flows = R * np.bincount(edges.column_index, edges.column_weight * q[edges.column_dofs],
                            minlength=len(edges.column_theta))
    ts, lam = thermal.supply_temperature, thermal.carry_over
    out = []
    for k, (d_in, d_out) in enumerate(zip(edges.inflow, edges.outflow)):
        o = d_out[np.argsort(mesh.zeta[d_out])]
        z, qo = mesh.zeta[o], q[o]
        w = np.zeros(len(o))
        w[:-1] += 0.5 * np.diff(z)
        w[1:] += 0.5 * np.diff(z)
        q_sum = float(np.sum(w * qo))
        cols = np.flatnonzero(edges.column_groove == k)
        c_out = cols[np.argmin(flows[cols])] if len(cols) else -1
        q_out = float(flows[c_out]) if len(cols) else np.inf
        c_in = column[d_in[0]]
        q_in = float(flows[c_in])
        carried = min(lam * max(q_out, 0.0), q_in) if q_in > 0.0 and q_sum > 0.0 else 0.0
        share = carried / q_in if carried > 0.0 else 0.0
        zero = np.zeros(mesh.ndofs)
        if share == 0.0:
            out.append((ts, zero, zero.copy()))
            continue
        t_mean = float(np.sum(w * qo * T[o])) / q_sum
        value = (1.0 - share) * ts + share * t_mean
        a = np.zeros(mesh.ndofs)                           # d value / d q at each node
        a[o] += share * w * (T[o] - t_mean) / q_sum
        if lam * q_out < q_in:                             # share = lam q_out / q_in
            on = column == c_out
            a[on] += (t_mean - ts) * lam / q_in * R * col_w[on]
            on = column == c_in
            a[on] -= (t_mean - ts) * share / q_in * R * col_w[on]
        d_T = a * dq_dT
        d_T[o] += share * w * qo / q_sum
        d_P = B.T @ lu.solve(-a * k3 * sc) + a * dq_dP_local
        out.append((value, d_P, d_T))
    return out


class ThermalNewton:
    """The coupled Newton (module docstring) on the bearing-fixed mesh of a
    :class:`~bearingfem.routes.thd.ThermalIteration` ``it`` whose last film (solved)
    gives the start's pressure and cavitated set and whose ``T`` the start's
    temperatures; a journal may move between solves (:meth:`solve` at another state
    continues from the last fields)."""

    def __init__(self, it: ThermalIteration):
        if it._jfo is not None:
            raise ValueError("the coupled Newton takes the Reynolds-condition film")
        self.it = it
        self.bearing, self.oil, self.thermal = it.bearing, it.lubricant, it.thermal
        self.op, self.eop = it.op, it.eop
        self.ga = general_assembly(self.op)
        film = it.last
        self.P = film.last.pressure.copy()
        self.active = np.asarray(film.last.active, bool).copy()
        self.T = it.T.copy()
        edges = self.eop.edges
        self.T_in = np.array([self.T[d[0]] for d in edges.inflow])
        _, ta, hj, tj = self.thermal.walls
        self.zero_flux = hj > 0.0 and tj is None
        self.mj = self.eop.vector(np.sum(self.eop.phi * self.eop.dx, axis=2)
                                  * self.bearing.radius ** 2 * hj) if hj > 0.0 else None
        self.t_journal = float(self.mj @ self.T / self.mj.sum()) if self.zero_flux else \
            (ta if tj is None else float(tj))
        self.fraction = np.ones(self.op.mesh.ndofs)
        self.held = self.eop.held
        self.free_rows = np.setdiff1d(np.arange(self.eop.N), self.held)
        self.steps, self.history, self.krylov = 0, [], 0

    # -- the system --------------------------------------------------------------------
    def _film_blocks(self, state, unknown):
        """(film residual on ``unknown``, d/dP (unknown x unknown), d/dT (unknown x N),
        stiffness values, load, viscosity ratio at the film's points)."""
        b, op, oil, ga = self.bearing, self.op, self.oil, self.ga
        ps = b.pressure_scale
        film = ReynoldsFieldFilm(b, state, op, self.it.element, self.it.grooves, self.it.tol)
        p_q, T_q = op.at_quadrature(self.P * ps), op.at_quadrature(self.T)
        mu = oil.viscosity_at(p_q, temperature=T_q)
        ratio = mu / b.viscosity
        k = film.cubed / ratio
        values = ga.stiffness_values(k)
        K = op.matrix(values)
        load = film.load
        r = (K @ self.P - load)[unknown]
        # d(K P)_i / d k at each point: sum_cd metric sum_i' table[i, i'] P_i'
        E, nb = ga.dofs.shape
        Q = ga.stiff_tables.shape[2]
        tables = ga.stiff_tables.reshape(2, 2, Q, nb, nb)
        G = np.einsum("cde,cdqij,ej->eqi", ga.metric, tables, self.P[ga.dofs])
        rows = np.broadcast_to(ga.dofs[:, None, :], G.shape).ravel()
        cols = np.broadcast_to(np.arange(E * Q).reshape(E, Q, 1), G.shape).ravel()
        dk_dmu = -k / mu
        mu_T = oil.viscosity_temperature_derivative(T_q, p_q)
        Gm = sp.csr_matrix(((G * (dk_dmu * mu_T)[:, :, None]).ravel(), (rows, cols)),
                           shape=(op.mesh.ndofs, E * Q))
        d_T = (Gm @ op.qp_interp).tocsr()[unknown]
        d_P = K[unknown][:, unknown]
        if oil.pressure_viscosity != 0.0:
            mu_p = oil.viscosity_derivative(p_q, temperature=T_q)
            Gp = sp.csr_matrix(((G * (dk_dmu * mu_p * ps)[:, :, None]).ravel(),
                                (rows, cols)), shape=(op.mesh.ndofs, E * Q))
            d_P = d_P + (Gp @ op.qp_interp).tocsr()[unknown][:, unknown]
        return r, d_P, d_T, values, load, ratio, K

    def system(self, state):
        """(residual, Jacobian (csc), unknown film dofs, parts) at the kept fields."""
        b, eop, edges = self.bearing, self.eop, self.eop.edges
        unknown = np.setdiff1d(self.op.mesh.free, np.flatnonzero(self.active))
        r_f, Pp, Pt, values, load, ratio, K = self._film_blocks(state, unknown)
        lin = energy_linearisation(b, state, eop, self.P, self.fraction, self.T,
                                   self.t_journal, self.oil, self.thermal.walls)
        mix = mixing_linearisation(b, state, self.op.mesh, edges, self.P, self.fraction,
                                   self.T, self.oil, self.thermal)
        N, G, fr = eop.N, len(edges.inflow), self.free_rows
        nu = len(unknown)
        # the energy rows
        Ep = lin.d_pressure[fr][:, unknown]
        Et = lin.d_temperature[fr]
        # held rows: T_i - T_in[k]
        h_rows, h_groove = [], []
        for k, (d_in, d_int) in enumerate(zip(edges.inflow, edges.interior)):
            d = np.concatenate([d_in, d_int]).astype(int)
            h_rows.append(d)
            h_groove.append(np.full(len(d), k))
        h_rows, h_groove = np.concatenate(h_rows), np.concatenate(h_groove)
        nh = len(h_rows)
        Ht = sp.csr_matrix((np.ones(nh), (np.arange(nh), h_rows)), shape=(nh, N))
        Hg = sp.csr_matrix((-np.ones(nh), (np.arange(nh), h_groove)), shape=(nh, G))
        Mp = sp.csr_matrix(np.array([-m[1][unknown] for m in mix]))
        Mt = sp.csr_matrix(np.array([-m[2] for m in mix]))
        blocks = [[Pp, Pt, None], [Ep, Et, None], [None, Ht, Hg],
                  [Mp, Mt, sp.identity(G, format="csr")]]
        res = [r_f, lin.residual[fr], self.T[h_rows] - self.T_in[h_groove],
               self.T_in - np.array([m[0] for m in mix])]
        if self.zero_flux:
            for row in blocks:
                row.append(None)
            blocks[1][3] = sp.csr_matrix(lin.d_journal[fr][:, None])
            blocks.append([None, sp.csr_matrix(self.mj[None, :]), None,
                           sp.csr_matrix([[-self.mj.sum()]])])
            res.append(np.array([self.mj @ self.T - self.t_journal * self.mj.sum()]))
        J = sp.bmat(blocks, format="csc")
        parts = dict(values=values, load=load, ratio=ratio, K=K, lin=lin, unknown=unknown)
        return np.concatenate(res), J, nu, parts

    def _step(self, J, r, nu):
        """The Newton step J dx = -r by GMRES, preconditioned by the block lower triangle:
        the film's block, then the energy block (operator, held, mixing and journal rows)
        on what the film's step leaves. Why: one LU of the coupled system fills in ~10
        times a block's (the coupling blocks join the two meshes' graphs); the blocks'
        LUs cost about one film and one energy solve, and the coupling is weak enough
        for a few Krylov steps (``krylov``) to take the step to round-off."""
        J = J.tocsr()
        film = splu(J[:nu][:, :nu].tocsc())
        energy = splu(J[nu:][:, nu:].tocsc())
        coupling = J[nu:][:, :nu]

        def precondition(v):
            y = np.empty_like(v)
            y[:nu] = film.solve(v[:nu])
            y[nu:] = energy.solve(v[nu:] - coupling @ y[:nu])
            return y
        n = J.shape[0]
        M = LinearOperator((n, n), precondition)
        count = [0]

        def counter(_):
            count[0] += 1
        dx, info = gmres(J, -r, M=M, rtol=1e-12, atol=0.0, restart=40, maxiter=2,
                         callback=counter, callback_type="pr_norm")
        self.krylov += count[0]
        if info != 0:
            raise ConvergenceError("thermal Newton step (GMRES)", count[0], float(
                np.linalg.norm(J @ dx + r) / max(np.linalg.norm(r), 1e-300)))
        return dx

    def _settle_set(self, parts) -> bool:
        """Update the cavitated set (module docstring); True if it did not move."""
        free = self.op.mesh.free
        r = parts["K"] @ self.P - parts["load"]
        scale = max(float(np.max(np.abs(parts["load"][free]))), np.finfo(float).tiny)
        on = np.zeros(self.op.mesh.ndofs, bool)
        on[free] = True
        new = np.where(self.active, r > -self.it.tol * scale, self.P < 0.0) & on
        moved = not np.array_equal(new, self.active)
        self.active = new
        self.P = np.where(new, 0.0, self.P)
        return not moved

    def solve(self, state, temperature_tol=1e-6, pressure_rtol=1e-8, max_iterations=30):
        """Newton steps at ``state`` from the kept fields to the tolerances (module
        docstring); the last assembled parts are kept for :meth:`solution`."""
        small = False
        for _ in range(max_iterations + 1):
            r, J, nu, parts = self.system(state)
            if self.steps and not self._settle_set(parts):
                # the set moved: the system on the new set
                small = False
                r, J, nu, parts = self.system(state)
            self.history.append(float(np.max(np.abs(r[nu:nu + len(self.free_rows)]),
                                             initial=0.0)))
            if small:
                self.parts, self.state = parts, state
                return self
            dx = self._step(J, r, nu)
            N, G = self.eop.N, len(self.T_in)
            dP = dx[:nu]
            dT = dx[nu:nu + N]
            self.P[parts["unknown"]] += dP
            self.T += dT
            self.T_in += dx[nu + N:nu + N + G]
            if self.zero_flux:
                self.t_journal += float(dx[-1])
            self.steps += 1
            peak = max(float(np.max(np.abs(self.P))), 1e-300)
            self.change = float(np.max(np.abs(dT)))
            self.pressure_change = float(np.max(np.abs(dP), initial=0.0)) / peak
            if not np.all(np.isfinite(dx)):
                break
            small = self.change < temperature_tol and self.pressure_change < pressure_rtol
        raise ConvergenceError("thermal film (coupled Newton)", max_iterations,
                               getattr(self, "change", np.inf), f"eps = {state.eps:.6g}")

    def film(self) -> ReynoldsFieldFilm:
        """The film of the kept fields (its outputs, force) at the last state."""
        p = self.parts
        f = ReynoldsFieldFilm(self.bearing, self.state, self.op, self.it.element,
                              self.it.grooves, self.it.tol)
        f.values, f.ratio = p["values"], p["ratio"]
        f.last = LCPResult(self.P.copy(), self.steps, 0.0, True,
                           self.active.copy(), None)
        return f

    def solution(self):
        """The :class:`~bearingfem.solution.FilmSolution` with temperatures and record."""
        b, eop, lin = self.bearing, self.eop, self.parts["lin"]
        sol = self.film().solution()
        energy = EnergySolution(
            temperature=self.T, journal_temperature=self.t_journal,
            parts=(b.radius, eop, lin.flow, lin.flow.dissipation, self.thermal.walls, lin.A,
                   lin.b, lin.c_all, False, None))
        T = self.T
        record = ThermalRecord(
            balance=energy.balance, journal_temperature=self.t_journal,
            inlet_temperatures=tuple(float(T[d[0]]) for d in eop.edges.inflow),
            viscosity=self.oil.viscosity_at(sol.pressure, temperature=T),
            viscosity_quadrature=self.parts["ratio"] * b.viscosity,
            iterations=self.it.iterations + self.steps, temperature_change=self.change,
            pressure_change=self.pressure_change)
        return replace(sol, temperature=T.copy(), temperature_max=float(np.max(T)),
                       thermal=record, method=sol.method + "/thd")


def solve_thd_newton(bearing, state, n_theta=120, n_z=20, *, lubricant, thermal, grooves=(),
                     element="P1", supply_angle=None, tol=1e-10, temperature_tol=1e-6,
                     pressure_rtol=1e-8, max_iterations=30, start=None):
    """The steady Reynolds-condition thermal film by the coupled Newton (module
    docstring), from the film on the supply temperature's viscosity (or on ``start``'s
    fields): the same answer as :func:`~bearingfem.routes.thd.solve_thd` (its arguments,
    ``max_iterations`` counting Newton steps). ``sol.thermal.iterations``: the film solve
    plus the Newton steps."""
    check_thermal(lubricant, thermal, state, "reynolds", element)
    if not grooves and supply_angle is None:
        raise ValueError("a thermal film needs an oil supply: give grooves or a "
                         "supply_angle")
    it = ThermalIteration(bearing, state, n_theta, n_z, lubricant=lubricant,
                          thermal=thermal, grooves=grooves, element=element,
                          supply_angle=supply_angle, tol=tol, start=start)
    it.film(state)
    return ThermalNewton(it).solve(state, temperature_tol, pressure_rtol,
                                   max_iterations).solution()
