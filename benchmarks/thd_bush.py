"""What the conducting bush costs, and why its inner response is precomputed.

    python -m benchmarks.thd_bush [--mesh 96x16 ...]

The 50 mm bearing of studies/thd_designer.py (ISO VG 32 at 40 C, two 20 deg grooves,
3000 rpm) at eps 0.7, carry-over 0.8, journal at zero net flux; the bush a steel hollow
cylinder R -> 2R (k 50 W/(m K), h_o 80 W/(m^2 K) to 40 C), its mesh the film's n_theta x 8
radial x the film's n_z axial cells. One process, OMP_NUM_THREADS=1, best of 5 CPU times
with the caches built (the build itself cold, once). Columns:

- build: the bush's inner response and transfer (mesh, assembly, one sparse LU, n_z + 1
  column solves, their FFT; ``bush_wall`` cold) [s], once per bush and film size;
- energy: one energy solve on the film of the first thermal step, with the bush as
  the coefficient of a radial wall (Thermal's bush_coefficient) [ms];
- bush: the same with the conducting bush (GMRES from zero; its iterations) [ms];
- one system: the film, the whole bush and the journal as one sparse matrix solved by a
  sparse LU (SuperLU, COLAMD), the alternative to the precomputed response [ms];
- film: the thermal film's solve (``solve_thd``) with the coefficient and with the bush
  [ms] and the number of film solves.
"""
from __future__ import annotations

import argparse
import math

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

import bearingfem.thermal.energy as energy_module
from bearingfem import JournalState
from bearingfem.caches import clear_caches
from bearingfem.elastic import ElasticBush
from bearingfem.routes.thd import (
    ThermalIteration,
    _dissipation_slope,
    groove_mixing,
    solve_thd,
)
from bearingfem.thermal import Thermal
from bearingfem.thermal.bush import bush_response, bush_wall
from bearingfem.thermal.energy import _film_coefficient, energy_system, solve_energy
from bearingfem.thermal.spec import BushConduction
from studies.thd_designer import BEARING, GROOVES, OIL, OMEGA, SUPPLY

from .common import best_of

STATE = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
SPEC = BushConduction(ElasticBush(outer_radius=2.0 * BEARING.radius), conductivity=50.0,
                      outer_coefficient=80.0)
R, RO = BEARING.radius, 2.0 * BEARING.radius
H_WALL = 1.0 / (R * (1.0 / (80.0 * RO) + math.log(RO / R) / 50.0))
BUSH = Thermal(SUPPLY, model="conducting", carry_over=0.8, bush=SPEC)
COEFFICIENT = Thermal(SUPPLY, model="conducting", carry_over=0.8, bush_coefficient=H_WALL)


def first_step(mesh):
    it = ThermalIteration(BEARING, STATE, *mesh, lubricant=OIL, thermal=BUSH,
                          grooves=GROOVES)
    it.film(STATE)
    eop, P = it.eop, it.p / BEARING.pressure_scale
    p_arc, T_arc = eop.at_points(it.p), eop.at_points(it.T)
    mu = OIL.viscosity_at(p_arc, temperature=T_arc)
    flow = eop.flow(BEARING, STATE, P, it.fraction, mu, OIL)
    mixing = groove_mixing(BEARING, STATE, it.op.mesh, eop.edges, P, it.fraction,
                           OIL.viscosity_at(it.p, temperature=it.T), BUSH)
    return it, flow, mixing, (_dissipation_slope(OIL, flow, mu, p_arc, T_arc), T_arc)


def one_system(it, flow, mixing, lin):
    """The film rows, the whole bush and the journal's row in one sparse matrix; its
    sparse LU and solve (the answer is the bush-coupled solve's: tests/test_bush_heat.py
    checks the same system to 1e-8 K)."""
    op, wall = it.eop, it.wall
    hb, ta, hj, _ = BUSH.walls
    Hf = _film_coefficient(wall, flow)
    a, T0 = lin
    A, b, test = energy_system(op, flow, hb + hj + Hf - a, flow.dissipation - a * T0, R)
    N, held = op.N, op.held
    free = np.setdiff1d(np.arange(N), held)
    E, Q = op.dx.shape
    dofs = op.basis.element_dofs
    P = sp.csr_matrix((test.ravel(), (np.repeat(dofs, Q, axis=1).ravel(),
                                      np.tile(np.arange(E * Q), dofs.shape[0]))),
                      shape=(N, E * Q))
    Kb = wall.response.matrix
    Nb, n_inner = Kb.shape[0], wall.transfer.shape[1]
    I = sp.hstack([wall.transfer, sp.csr_matrix((E * Q, Nb - n_inner))]).tocsr()
    D = sp.diags((Hf * R ** 2 * op.dx).ravel())
    C = P @ sp.diags((R * Hf).ravel()) @ I
    cj = -op.vector(np.sum(test, axis=2) * R * hj)
    mj = op.vector(np.sum(op.phi * op.dx, axis=2) * R ** 2 * hj)
    rows, cols, vals, rhs_held = [], [], [], np.zeros(N)
    for k, (d_in, d_int) in enumerate(zip(op.edges.inflow, op.edges.interior)):
        d = np.concatenate([d_in, d_int]).astype(int)
        src = np.asarray(mixing.dofs[k], int)
        for i in d:
            rows += [i] * (1 + len(src))
            cols += [i, *src]
            vals += [1.0, *(-np.asarray(mixing.weights[k]))]
        rhs_held[d] = mixing.fresh[k]
    Hh = sp.csr_matrix((vals, (rows, cols)), shape=(N, N))[held]
    g_out = Kb @ np.full(Nb, ta)             # the Robin rows' ambient: K 1 = h_o int v
    M = sp.bmat([[A[free], -C[free], sp.csr_matrix(cj[free][:, None])], [Hh, None, None],
                 [-(I.T @ D @ op.value), Kb + I.T @ D @ I, None],
                 [sp.csr_matrix(mj[None, :]), None, sp.csr_matrix([[-float(mj.sum())]])]],
                format="csc")
    rhs = np.concatenate([b[free], rhs_held[held], g_out, [0.0]])
    return lambda: splu(M).solve(rhs)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", action="append", default=None,
                    help="n_thetaxn_z (repeatable; default 48x8 and 96x16)")
    args = ap.parse_args(argv)
    meshes = [tuple(int(v) for v in m.split("x")) for m in (args.mesh or ["48x8", "96x16"])]
    print(f"{'mesh':>7} {'bush nodes':>10} {'inner':>6} {'build s':>8} {'energy ms':>9} "
          f"{'bush ms':>8} {'GMRES':>5} {'one system ms':>13} {'film ms':>8} "
          f"{'films':>5} {'film+bush ms':>12} {'films':>5}")
    for mesh in meshes:
        clear_caches()
        it, flow, mixing, lin = first_step(mesh)
        bush_response.cache_clear()
        bush_wall.cache_clear()
        build = best_of(lambda: bush_wall(SPEC, R, BEARING.length, it.op.mesh, it.eop))
        walls = COEFFICIENT.walls
        energy = best_of(lambda: solve_energy(BEARING, it.eop, flow, mixing, walls,
                                              linearised=lin), 5)
        count = []

        def with_bush():
            return solve_energy(BEARING, it.eop, flow, mixing, BUSH.walls, linearised=lin,
                                bush=it.wall)
        bush = best_of(with_bush, 5)
        orig = energy_module.gmres

        def counted(*a, **k):
            n = [0]
            out = orig(*a, callback=lambda *_: n.__setitem__(0, n[0] + 1),
                       callback_type="pr_norm", **k)
            count.append(n[0])
            return out
        energy_module.gmres = counted
        with_bush()
        energy_module.gmres = orig
        mono = best_of(one_system(it, flow, mixing, lin), 5)
        assert np.max(np.abs(mono.out[:it.eop.N] - bush.out.temperature)) < 1e-8
        film = best_of(lambda: solve_thd(BEARING, STATE, *mesh, lubricant=OIL,
                                         thermal=COEFFICIENT, grooves=GROOVES), 5)
        film_bush = best_of(lambda: solve_thd(BEARING, STATE, *mesh, lubricant=OIL,
                                              thermal=BUSH, grooves=GROOVES), 5)
        print(f"{mesh[0]:>3}x{mesh[1]:<3} {it.wall.response.matrix.shape[0]:>10} "
              f"{it.wall.transfer.shape[1]:>6} {build.cpu:8.2f} {energy.cpu * 1e3:9.1f} "
              f"{bush.cpu * 1e3:8.1f} {count[0]:>5} {mono.cpu * 1e3:13.1f} "
              f"{film.cpu * 1e3:8.1f} {film.out.thermal.iterations:>5} "
              f"{film_bush.cpu * 1e3:12.1f} {film_bush.out.thermal.iterations:>5}",
              flush=True)


if __name__ == "__main__":
    main()
