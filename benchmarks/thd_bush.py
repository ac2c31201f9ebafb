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
from scipy.sparse.linalg import splu

import bearingfem.thermal.energy as energy_module
from bearingfem import JournalState
from bearingfem.caches import clear_caches
from bearingfem.elastic import ElasticBush
from bearingfem.routes.thd import (
    ThermalIteration,
    solve_thd,
)
from bearingfem.thermal import Thermal
from bearingfem.thermal.bush import bush_response, bush_wall
from bearingfem.thermal.energy import solve_energy
from bearingfem.thermal.spec import BushConduction
from studies.thd_designer import BEARING, GROOVES, OIL, OMEGA, SUPPLY
from tests.test_bush_heat import one_sparse_system

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
    return (it, *it.energy_step(STATE))


def one_system(it, flow, mixing, lin):
    """The film rows, the whole bush (its assembled matrix, the one the response is built
    from) and the journal's row in one sparse matrix (tests/test_bush_heat's
    one_sparse_system, which checks the same system to 1e-8 K); its sparse LU and solve."""
    Kb = it.wall.response.matrix
    g_out = Kb @ np.full(Kb.shape[0], BUSH.walls[1])    # the Robin rows' ambient: K 1 = h_o int v
    M, rhs = one_sparse_system(it, flow, mixing, lin, it.wall, BUSH, Kb, g_out)
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
