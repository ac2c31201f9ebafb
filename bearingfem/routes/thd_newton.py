"""The Reynolds-condition thermal film by a coupled Newton on pressure and temperature.

Unknowns: the dimensionless pressure P on the film's free, uncavitated dofs, the nodal
temperature T on every dof of the energy equation and, for a zero-flux journal, its
temperature T_j. Equations: the film K(mu) P = b on those dofs (mu = mu(p, T) at the
film's quadrature points), the energy equation on its free rows
(:func:`~bearingfem.thermal.jacobian.energy_linearisation`), T_i = M_k(P, T) on groove
k's held rows (its inlet temperature, the mixing of the upstream exit:
:func:`mixing_linearisation`, :func:`~bearingfem.thermal.mixing.groove_mixing`'s formula),
and the journal's zero net flux.

The block Jacobian is exact (tested against central differences, :meth:`ThermalNewton.apply`):

    | K (+ dK/dp P)     dK/dT P              0        |   film rows
    | dE/dP             dE/dT                dE/dT_j  |   energy rows (free)
    | -dM_k/dP          I - dM_k/dT          0        |   held rows
    | 0                 m_j                  -sum m_j |   journal row

with dK/dT P the film's change through mu(p, T) at its quadrature points, dE/dP the
energy equation's through the Poiseuille flow, its dissipation and the SUPG weight,
dE/dT its operator plus the same through mu, and dM_k the mixing's through the exit and
column flows (dP/dtheta by differences on the arcs) and the viscosity at the nodes (rank
one per groove). A step eliminates the film (its LU) and solves the Schur complement on the
temperatures by GMRES with the temperature block's inverse on the right (:meth:`_step`).

The cavitated set is held during a step and updated after it as the isothermal active
set does (an uncavitated dof with P < 0 joins, a cavitated one whose multiplier
K P - b is negative leaves); it rarely moves after the first film's. Converged when a
step moved no temperature by more than ``temperature_tol`` [K] and no pressure by more
than ``pressure_rtol`` of its peak and the set did not move (the residual after such a
step is of its square: round-off), else :class:`~bearingfem.errors.ConvergenceError`.

Beside the fixed point (:class:`~bearingfem.routes.thd.ThermalIteration`, the default):
the same answer; quadratic convergence (five steps from the supply temperature's film
to round-off) against the fixed point's factor of about 1e-2 per step, but each step
assembles the coupling blocks and costs about two fixed-point steps, so at the meshes
measured it is the slower of the two (docs/thd.md, Cost).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp
from scipy.linalg import lapack
from scipy.sparse.linalg import LinearOperator, gmres, splu

from ..errors import ConvergenceError, TemperatureRangeError
from ..fe.general import general_assembly
from ..film import film_thickness
from ..solvers.cavitation import LCPResult
from ..solvers.linsolve import principal_block
from ..thermal.energy import EnergyParts, EnergySolution
from ..thermal.jacobian import energy_linearisation
from ..thermal.spec import ThermalRecord, warn_out_of_range
from ..thermal.mixing import arc_theta_difference
from .thd import ThermalIteration, check_thermal
from .thd_film import ReynoldsFieldFilm

__all__ = ["ThermalNewton", "mixing_linearisation", "solve_thd_newton"]


def mixing_linearisation(bearing, state, mesh, edges, P, fraction, T, lubricant, thermal):
    """Each groove's inlet temperature T_in = M_k(P, T) of
    :func:`~bearingfem.thermal.mixing.groove_mixing` (the same formula) and its gradients:
    a list of (value [K], d/dP (N,), d/dT (N,)) over the grooves, P dimensionless.
    The least column flow and the carried flow's cap are taken on their current branch."""
    R, c, ps = bearing.radius, bearing.clearance, bearing.pressure_scale
    sc = ps / R
    D = arc_theta_difference(mesh, edges)
    dP = D @ P
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
        d_P = D.T @ (-a * k3 * sc) + a * dq_dP_local
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
        _, ta, hj, tj = self.thermal.walls
        self.zero_flux = hj > 0.0 and tj is None
        self.mj = self.eop.vector(np.sum(self.eop.phi * self.eop.dx, axis=2)
                                  * self.bearing.radius ** 2 * hj) if hj > 0.0 else None
        self.t_journal = float(self.mj @ self.T / self.mj.sum()) if self.zero_flux else \
            (ta if tj is None else float(tj))
        self.fraction = np.ones(self.op.mesh.ndofs)
        self.held = self.eop.held
        self.free_rows = np.setdiff1d(np.arange(self.eop.N), self.held)
        # each groove's held rows (T_i = its inlet temperature)
        self.groove_rows = [np.concatenate([d_in, d_int]).astype(int)
                            for d_in, d_int in zip(edges.inflow, edges.interior)]
        self.steps, self.history, self.krylov = 0, [], 0
        self.change = self.pressure_change = np.inf
        self._film_state = None

    # -- the system --------------------------------------------------------------------
    def _film(self, state) -> ReynoldsFieldFilm:
        if self._film_state is None or self._film_state[0] != state:
            self._film_state = (state, ReynoldsFieldFilm(
                self.bearing, state, self.op, self.it.element, self.it.grooves, self.it.tol))
        return self._film_state[1]

    def system(self, state) -> dict:
        """The residual and the Jacobian's blocks at the kept fields (``unknown``: the
        film's unknown dofs)."""
        b, op, oil, ga, eop = self.bearing, self.op, self.oil, self.ga, self.eop
        ps = b.pressure_scale
        film = self._film(state)
        unknown = np.setdiff1d(op.mesh.free, np.flatnonzero(self.active))
        # the film: K(mu) P - b and its change with mu at its points
        p_q, T_q = op.at_quadrature(self.P * ps), op.at_quadrature(self.T)
        mu, mu_p, mu_T = oil.viscosity_and_slopes(p_q, T_q)
        ratio = mu / b.viscosity
        k = film.cubed / ratio
        values = ga.stiffness_values(k)
        K = op.matrix(values)
        r_film = K @ self.P - film.load
        E, nb = ga.dofs.shape
        Q = ga.stiff_tables.shape[2]
        # d(K P)_i / d k at each point: sum_cd metric sum_i' table[i, i'] P_i'
        tables = ga.stiff_tables.reshape(2, 2, Q, nb, nb)
        G = np.einsum("cde,cdqij,ej->eqi", ga.metric, tables, self.P[ga.dofs],
                      optimize=True)
        dk_dmu = -k / mu
        Kuu = principal_block(K, unknown)
        if np.any(mu_p):
            Gp = G * (dk_dmu * mu_p * ps)[:, :, None]
            rows = np.broadcast_to(ga.dofs[:, None, :], G.shape).ravel()
            cols = np.broadcast_to(np.arange(E * Q).reshape(E, Q, 1), G.shape).ravel()
            Kp = (sp.csr_matrix((Gp.ravel(), (rows, cols)), shape=(op.mesh.ndofs, E * Q))
                  @ op.qp_interp).tocsr()
            Kuu = Kuu + principal_block(Kp, unknown)
        lin = energy_linearisation(b, state, eop, self.P, self.fraction, self.T,
                                   self.t_journal, oil, self.thermal.walls)
        mix = mixing_linearisation(b, state, op.mesh, eop.edges, self.P, self.fraction,
                                   self.T, oil, self.thermal)
        # the temperature rows: the energy equation's free rows, T_i - M_k on the held
        r_T = lin.residual.copy()
        for rows, m in zip(self.groove_rows, mix):
            r_T[rows] = self.T[rows] - m[0]
        r_j = float(self.mj @ self.T - self.t_journal * self.mj.sum()) if self.zero_flux \
            else 0.0
        return dict(unknown=unknown, r_film=r_film[unknown], r_T=r_T, r_j=r_j, K=K,
                    load=film.load, values=values, ratio=ratio, Kuu=Kuu,
                    film_slope=G * (dk_dmu * mu_T)[:, :, None], lin=lin, mix=mix)

    def _step(self, s, eta):
        """The Newton step (dP on the unknown dofs, dT, dT_j): the film eliminated, its
        Schur complement on the temperatures by GMRES (relative tolerance ``eta``) with
        the temperature block's inverse on the right (a banded LU of the energy rows, the
        held rows' mixing by Woodbury's identity, the journal's row bordered). Why: one
        LU of the coupled system fills in ~10 times the blocks' (the coupling joins the
        two graphs); the blocks' LUs cost about one film and one energy solve, and the
        film's coupling leaves a few Krylov steps."""
        eop, lin, N = self.eop, s["lin"], self.eop.N
        film = splu(s["Kuu"].tocsc())
        # the temperature block: band (energy rows, held rows' identity) - U W^T
        w = eop.band
        ab = np.zeros((3 * w + 1, N))
        ab[w:] = np.bincount(eop.band_index, lin.d_temperature * eop.free_rows,
                             minlength=(2 * w + 1) * N).reshape(2 * w + 1, N)
        ab[2 * w, eop.band_rank[self.held]] = 1.0
        lu, piv, info = lapack.dgbtrf(ab, w, w, overwrite_ab=1)
        if info != 0:
            raise ConvergenceError("thermal Newton step (singular temperature block)", 0,
                                   float(info))
        order, rank = eop.band_order, eop.band_rank

        def band(v):
            x, _ = lapack.dgbtrs(lu, w, w, v[order], piv)
            return x[rank]
        nG = len(self.groove_rows)
        U = self._groove_indicator()
        W = np.column_stack([m[2] for m in s["mix"]]) if nG else np.zeros((N, 0))
        ZU = np.column_stack([band(U[:, k]) for k in range(nG)]) if nG else U
        small = np.linalg.inv(np.eye(nG) - W.T @ ZU) if nG else np.zeros((0, 0))

        def block(v):                  # (band - U W^T)^-1 v
            x = band(v)
            return x + ZU @ (small @ (W.T @ x))
        cj = lin.d_journal.copy()
        cj[self.held] = 0.0
        if self.zero_flux:
            Zc = block(cj)
            denom = float(self.mj @ Zc + self.mj.sum())

        def t_solve(z):               # the temperature block with the journal's border
            if not self.zero_flux:
                return block(z[:N]), 0.0
            y = block(z[:N])
            t = (float(self.mj @ y) - z[N]) / denom
            return y - t * Zc, t
        film_from_T, T_from_P = self._film_from_T, self._T_from_P
        n = N + int(self.zero_flux)

        def extend(v):
            return np.concatenate([v, [0.0]]) if self.zero_flux else v

        def schur(z):                   # z -> (T-block - E K^-1 C) T-block^-1 z
            dT, _ = t_solve(z)
            return z - extend(T_from_P(s, film.solve(film_from_T(s, dT))))
        rhs = -extend(s["r_T"]) + extend(T_from_P(s, film.solve(s["r_film"])))
        if self.zero_flux:
            rhs[N] = -s["r_j"]
        count = [0]

        def counter(_):
            count[0] += 1
        z, info = gmres(LinearOperator((n, n), schur), rhs, rtol=eta, atol=0.0,
                        restart=30, maxiter=3, callback=counter, callback_type="pr_norm")
        self.krylov += count[0]
        if info != 0:
            raise ConvergenceError("thermal Newton step (GMRES)", count[0], float(
                np.linalg.norm(schur(z) - rhs) / max(np.linalg.norm(rhs), 1e-300)))
        dT, dt = t_solve(z)
        dP = -film.solve(s["r_film"] + film_from_T(s, dT))
        return dP, dT, dt

    def _groove_indicator(self) -> np.ndarray:
        """(N, grooves): 1 on each groove's held rows."""
        U = np.zeros((self.eop.N, len(self.groove_rows)))
        for k, rows in enumerate(self.groove_rows):
            U[rows, k] = 1.0
        return U

    def _film_from_T(self, s, dT):
        """The film rows' change for a nodal temperature change ``dT`` (through mu at its
        points): sum_q d(K P)_i/d k dk/dmu dmu/dT dT(q)."""
        slope, dofs, op = s["film_slope"], self.ga.dofs, self.op
        E, Q = slope.shape[:2]
        v = (op.qp_interp @ dT).reshape(E, Q)
        return np.bincount(dofs.ravel(), np.einsum("eqi,eq->ei", slope, v).ravel(),
                           minlength=op.mesh.ndofs)[s["unknown"]]

    def _T_from_P(self, s, dP_u):
        """The temperature rows' change for a pressure change on the unknown dofs: the
        energy equation's free rows and the held rows' mixing (-dM_k/dP)."""
        lin, eop = s["lin"], self.eop
        dP = np.zeros(self.op.mesh.ndofs)
        dP[s["unknown"]] = dP_u
        if "EP" not in s:
            s["EP"] = lin.matrix(lin.d_pressure * eop.free_rows)
        out = s["EP"] @ dP
        for rows, m in zip(self.groove_rows, s["mix"]):
            out[rows] -= m[1] @ dP
        return out

    def apply(self, s, dP_u, dT, dt=0.0):
        """The block Jacobian of the system ``s`` times (dP on the unknown dofs, dT, dT_j):
        (film rows, temperature rows, journal row) [as the residuals]."""
        lin, eop = s["lin"], self.eop
        film = s["Kuu"] @ dP_u + self._film_from_T(s, dT)
        temp = lin.matrix(lin.d_temperature * eop.free_rows) @ dT + self._T_from_P(s, dP_u)
        cj = lin.d_journal.copy()
        cj[self.held] = 0.0
        temp += cj * dt
        for rows, m in zip(self.groove_rows, s["mix"]):
            temp[rows] += dT[rows] - m[2] @ dT
        journal = float(self.mj @ dT - dt * self.mj.sum()) if self.zero_flux else 0.0
        return film, temp, journal

    def _settle_set(self, s) -> bool:
        """Update the cavitated set (module docstring); True if it did not move."""
        free = self.op.mesh.free
        r = s["K"] @ self.P - s["load"]
        scale = max(float(np.max(np.abs(s["load"][free]))), np.finfo(float).tiny)
        on = np.zeros(self.op.mesh.ndofs, bool)
        on[free] = True
        new = np.where(self.active, r > -self.it.tol * scale, self.P < 0.0) & on
        moved = not np.array_equal(new, self.active)
        self.active = new
        self.P = np.where(new, 0.0, self.P)
        return not moved

    def solve(self, state, temperature_tol=1e-6, pressure_rtol=1e-8, max_iterations=30):
        """Newton steps at ``state`` from the kept fields to the tolerances (module
        docstring); the last assembled system is kept for :meth:`solution`."""
        small = False
        for _ in range(max_iterations + 1):
            try:
                s = self.system(state)
                if self.steps and not self._settle_set(s):
                    small = False          # the set moved: the system on the new set
                    s = self.system(state)
            except TemperatureRangeError as err:
                if not self.steps:         # the start's: an input, refused as given
                    raise
                # a step's temperatures where the oil's law has no viscosity (the lubricant
                # refuses them): diverged, as a step with NaN (before, the law's inf gave one)
                raise ConvergenceError("thermal film (coupled Newton)", self.steps,
                                       self.change, f"eps = {state.eps:.6g}: {err}") from err
            r = float(np.max(np.abs(s["r_T"][self.free_rows]), initial=0.0))
            self.history.append(r)
            if small:
                self.parts, self.state = s, state
                return self
            # inexact steps: the Krylov tolerance follows the residual (quadratic
            # convergence kept), 1e-12 at the least
            eta = min(1e-4, max(1e-12, 1e-2 * r / max(self.history[0], 1e-300)))
            dP, dT, dt = self._step(s, eta)
            if not (np.all(np.isfinite(dP)) and np.all(np.isfinite(dT))):
                break
            self.P[s["unknown"]] += dP
            self.T += dT
            self.t_journal += dt
            self.steps += 1
            peak = max(float(np.max(np.abs(self.P))), 1e-300)
            self.change = float(np.max(np.abs(dT)))
            self.pressure_change = float(np.max(np.abs(dP), initial=0.0)) / peak
            small = self.change < temperature_tol and self.pressure_change < pressure_rtol
        raise ConvergenceError("thermal film (coupled Newton)", max_iterations,
                               self.change, f"eps = {state.eps:.6g}")

    def film(self) -> ReynoldsFieldFilm:
        """The film of the kept fields (its outputs, force) at the last state."""
        p = self.parts
        f = ReynoldsFieldFilm(self.bearing, self.state, self.op, self.it.element,
                              self.it.grooves, self.it.tol)
        f.values, f.ratio = p["values"], p["ratio"]
        f.last = LCPResult(self.P.copy(), self.steps, 0.0, True, self.active.copy(), None)
        return f

    def solution(self):
        """The :class:`~bearingfem.solution.FilmSolution` with temperatures and record."""
        b, eop, lin = self.bearing, self.eop, self.parts["lin"]
        sol = self.film().solution()
        energy = EnergySolution(
            temperature=self.T, journal_temperature=self.t_journal,
            parts=EnergyParts(b.radius, eop, lin.flow, lin.flow.dissipation,
                              self.thermal.walls, lin.A, lin.b, lin.c_all, half=False,
                              storage=None, bush=None))
        T = self.T
        record = ThermalRecord(
            balance=energy.balance, journal_temperature=self.t_journal,
            inlet_temperatures=tuple(float(T[d[0]]) for d in eop.edges.inflow),
            viscosity=self.oil.viscosity_at(sol.pressure, temperature=T),
            viscosity_quadrature=self.parts["ratio"] * b.viscosity,
            iterations=self.it.iterations + self.steps, temperature_change=self.change,
            pressure_change=self.pressure_change)
        warn_out_of_range(T)
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
    if thermal is not None and thermal.bush is not None:
        raise ValueError("thermal.bush (a conducting bush) is solve_thd's: the coupled "
                         "Newton takes the walls as heat-transfer coefficients")
    if state.omega < 0.0:
        # Why: its mixing and SUPG derivatives are written for oil entering at the
        # grooves' trailing edges; the reversed film is solve_thd's (routes/thd.py)
        raise ValueError(f"state.omega must be > 0 for the coupled Newton (got "
                         f"{state.omega}); solve_thd solves a journal turning either way")
    if not grooves and supply_angle is None:
        raise ValueError("a thermal film needs an oil supply: give grooves or a "
                         "supply_angle")
    it = ThermalIteration(bearing, state, n_theta, n_z, lubricant=lubricant,
                          thermal=thermal, grooves=grooves, element=element,
                          supply_angle=supply_angle, tol=tol, start=start)
    it.film(state)
    return ThermalNewton(it).solve(state, temperature_tol, pressure_rtol,
                                   max_iterations).solution()
