"""What the designer's numbers cost: equilibrium + 8 coefficients, accuracy against time.

    python -m benchmarks.design            # our table (FE P1 / P2 ladders, short bearing)
    python -m benchmarks.design --quick    # smoke run (CI)
    python -m benchmarks.design --ross     # also ROSS's FluidFlow on the same bearing, side by
                                           # side (installs ross-rotordynamics into .venv-ross
                                           # on first use; it is not a dependency)
    python -m benchmarks.design --grooved  # Newton's equilibrium against the root search it
                                           # replaced, grooved and periodic (below)

Bearing: Friswell et al. (2010) Example 5.5.1 (D 0.1 m, L 0.03 m, c 0.1 mm, mu 0.1 Pa s,
157.1 rad/s, 525 N downward), with Gumbel's condition (ROSS's FluidFlow clips negative
pressure the same way). Reference: FE P2 on 384x48. Error = the largest of |d eps| / eps,
max|dK| / max|K| and max|dC| / max|C| (entries pass through zero, so entry-wise relative
errors would be meaningless). Times: one run, best of ``--repeat``; "cold" includes
building the mesh and assembling its matrices (once per mesh in a session), "warm" reuses
them, as every later call on that mesh does.

``--grooved``: equilibrium + K/C of a grooved bearing, Newton on the exact partials against
the root search it replaced (Brent on the periodic film's |F(eps)|, then Powell's hybrid
method in the journal position), film solves and wall time at the same accuracy.
Bearing: Lund & Thomsen's (1978) two-axial-groove bearing, 20 deg grooves across the load
(at 0 and 180 deg, load downward), L/D 1, D 0.1 m, c 100 um, mu 0.02 Pa s, 3000 rpm,
S 0.635, Reynolds' condition. Reference: Newton on FE P2 192x32 (eps and attitude against
the root search there agree to 1e-10). Error = the largest of |d eps| / eps, |d attitude|
[rad], max|dK| / max|K|, max|dC| / max|C|. "periodic" is the same bearing without grooves
(a load it carries at the same Sommerfeld number). Film solves are counted at the FE
pressure solve (a grooved partial costs one: its d/dgamma is exact on the bearing-fixed
mesh, :mod:`bearingfem.fe.grooved`). Times: best of ``repeat``, cold (the library's
caches cleared before each).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, root

import bearingfem.fe.grooved as fe_grooved
import bearingfem.fe.kernel as fe_kernel
import bearingfem.fe.sensitivity as fe_sensitivity
from bearingfem import JournalState
from bearingfem.design import coefficients, equilibrium
from bearingfem.film import local_to_inertial
from bearingfem.models import film_model

from .common import (PLAIN_BEARING as BEARING, PLAIN_LOAD as LOAD, PLAIN_OMEGA as OMEGA,
                     TWO_GROOVE_BEARING, TWO_GROOVE_LOAD, TWO_GROOVE_OMEGA, TWO_GROOVES,
                     best_of, design_error)

CAVITATION = "gumbel"
REFERENCE = dict(n_theta=384, n_z=48, element="P2")
LADDER = [("fem", dict(n_theta=n, n_z=z, element=el))
          for el, meshes in (("P1", ((48, 8), (96, 12), (192, 24))),
                             ("P2", ((24, 4), (36, 6), (48, 8), (72, 12))))
          for n, z in meshes] + [("short", {})]
ROOT = Path(__file__).resolve().parent.parent


def design_numbers(model, opts):
    """eps and the inertial K, C at equilibrium."""
    if model == "fem":
        opts = dict(opts, cavitation=CAVITATION)
    eq = equilibrium(BEARING, LOAD, OMEGA, model, **opts)
    kc = coefficients(BEARING, eq.state, model, **opts)
    return eq.eps, kc.K, kc.C


def error(numbers, ref):
    eps, K, C = numbers
    e0, K0, C0 = ref
    return max(abs(eps - e0) / e0, np.abs(K - K0).max() / np.abs(K0).max(),
               np.abs(C - C0).max() / np.abs(C0).max())


GROOVED_MESHES = [(48, 8), (72, 12), (96, 16)]
GROOVED_REFERENCE = (192, 32)


class SolveCounter:
    """Counts FE pressure solves (every force, solution and partial goes through one)."""

    def __init__(self):
        self.n = 0
        self._orig = fe_kernel.fe_pressure

    def __enter__(self):
        def counted(*a, **k):
            self.n += 1
            return self._orig(*a, **k)
        # every module that calls the kernel's pressure solve by name
        fe_kernel.fe_pressure = fe_grooved.fe_pressure = fe_sensitivity.fe_pressure = counted
        return self

    def __exit__(self, *exc):
        fe_kernel.fe_pressure = fe_grooved.fe_pressure = fe_sensitivity.fe_pressure = \
            self._orig


def root_search(opts):
    """The route before Newton: Brent on the periodic |F(eps)|, then the 2-D hybrid root."""
    m = film_model("fem")
    o = m.options(opts)
    periodic = {**o, "grooves": ()}
    W = math.hypot(*TWO_GROOVE_LOAD)

    def force(eps, gamma, oo):
        state = JournalState(eps, omega=TWO_GROOVE_OMEGA, gamma=gamma)
        return m.film_force(TWO_GROOVE_BEARING, state, **oo)

    math.hypot(*force(0.99, 0.0, periodic))         # the capacity check it made
    eps = brentq(lambda e: math.hypot(*force(e, 0.0, periodic)) - W, 0.0, 0.99,
                 xtol=1e-300, rtol=1e-13)
    f_r, f_t = force(eps, 0.0, periodic)
    gamma = math.atan2(-TWO_GROOVE_LOAD[1], -TWO_GROOVE_LOAD[0]) - math.atan2(f_t, f_r)
    if o["grooves"]:
        def residual(q):
            e, g = math.hypot(*q), math.atan2(q[1], q[0])
            return np.add(local_to_inertial(*force(e, g, o), g), TWO_GROOVE_LOAD) / W
        sol = root(residual, [eps * math.cos(gamma), eps * math.sin(gamma)], method="hybr",
                   options=dict(xtol=1e-12))
        eps, gamma = math.hypot(*sol.x), math.atan2(sol.x[1], sol.x[0])
    state = JournalState(eps, omega=TWO_GROOVE_OMEGA, gamma=gamma)
    f_r, f_t = force(eps, gamma, o)
    film_model("fem").film_solution(TWO_GROOVE_BEARING, state, **opts)  # the solution it returned
    return state, math.atan2(f_t, -f_r)


def newton(opts):
    eq = equilibrium(TWO_GROOVE_BEARING, TWO_GROOVE_LOAD, TWO_GROOVE_OMEGA, "fem", **opts)
    return eq.state, eq.attitude


def grooved_numbers(route, opts):
    state, attitude = route(opts)
    kc = coefficients(TWO_GROOVE_BEARING, state, "fem", **opts)
    return state.eps, attitude, kc.K, kc.C


def run(route, opts, repeat):
    """(the design numbers, the film solves of the last call, the best cold wall time)."""
    solves = []

    def counted():
        with SolveCounter() as count:
            out = grooved_numbers(route, opts)
        solves.append(count.n)
        return out

    t = best_of(counted, repeat, cold=True)
    return t.out, solves[-1], t.wall


def grooved_table(repeat=2, quick=False):
    meshes = GROOVED_MESHES[:2] if quick else GROOVED_MESHES
    ref_mesh = (96, 16) if quick else GROOVED_REFERENCE
    rows = []
    print(f"Lund & Thomsen two-groove bearing, L/D 1, S 0.635, W = {-TWO_GROOVE_LOAD[1]:.1f} N; "
          f"reference P2 {ref_mesh[0]}x{ref_mesh[1]}")
    print(f"{'film':9s} {'mesh':10s} {'route':12s} {'eps':>9s} {'att [deg]':>9s} "
          f"{'error':>9s} {'solves':>6s} {'time [ms]':>10s} {'ratio':>6s}")
    for film, grooves in (("grooved", TWO_GROOVES), ("periodic", ())):
        base = dict(element="P2", cavitation="reynolds", grooves=grooves)
        ref = grooved_numbers(newton, dict(base, n_theta=ref_mesh[0], n_z=ref_mesh[1]))
        for n, z in meshes:
            opts = dict(base, n_theta=n, n_z=z)
            timing = {}
            for name, route in (("root search", root_search), ("Newton", newton)):
                out, solves, t = run(route, opts, repeat)
                timing[name] = t
                row = dict(film=film, mesh=f"P2 {n}x{z}", route=name, eps=out[0],
                           attitude=math.degrees(out[1]), error=design_error(out, ref),
                           solves=solves, time_s=t)
                rows.append(row)
                ratio = timing["root search"] / t
                print(f"{film:9s} {row['mesh']:10s} {name:12s} {out[0]:9.6f} "
                      f"{row['attitude']:9.4f} {row['error']:9.2e} {solves:6d} "
                      f"{1e3 * t:10.1f} {ratio:6.2f}")
    return rows


def ross_numbers(repeat, quick):
    """Run ROSS's FluidFlow equilibrium + coefficients in its own venv; rows as dicts."""
    venv = ROOT / ".venv-ross"
    py = venv / "bin" / "python"
    if not py.exists():
        print("installing ross-rotordynamics into .venv-ross (once) ...", flush=True)
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        # ROSS 2.3 themes plotly with "scattermapbox", which plotly 6 removed
        subprocess.run([str(py), "-m", "pip", "install", "--quiet", "ross-rotordynamics",
                        "plotly<6"],
                       check=True)
    script = Path(__file__).with_name("_ross_fluidflow.py")
    meshes = "8x32" if quick else "8x32,16x64,32x128"
    r = subprocess.run([str(py), str(script), "--meshes", meshes, "--repeat", str(repeat)],
                       capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    if r.returncode != 0:
        raise RuntimeError(f"ROSS run failed:\n{r.stderr[-2000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="two meshes, coarse reference")
    ap.add_argument("--ross", action="store_true", help="measure ROSS side by side")
    ap.add_argument("--grooved", action="store_true",
                    help="Newton vs root search on Lund & Thomsen's two-groove bearing")
    args = ap.parse_args(argv)
    if args.grooved:
        return grooved_table(max(1, args.repeat // 2), args.quick)
    ref_opts = dict(n_theta=96, n_z=12, element="P2") if args.quick else REFERENCE
    ref = design_numbers("fem", ref_opts)
    ladder = LADDER[:1] + LADDER[3:4] if args.quick else LADDER
    rows = []
    print(f"reference: FE P2 {ref_opts['n_theta']}x{ref_opts['n_z']}, {CAVITATION}: "
          f"eps = {ref[0]:.6f}")
    print(f"{'model':6s} {'mesh':12s} {'error':>9s} {'cold [ms]':>10s} {'warm [ms]':>10s}")
    for model, opts in ladder:
        t_cold = best_of(lambda: design_numbers(model, opts), 1 if args.quick else 3,
                         cold=True).wall
        warm = best_of(lambda: design_numbers(model, opts), args.repeat)
        t_warm, out = warm.wall, warm.out
        mesh = f"{opts['element']} {opts['n_theta']}x{opts['n_z']}" if opts else "-"
        row = dict(model=model, mesh=mesh, error=error(out, ref), cold_s=t_cold, warm_s=t_warm)
        rows.append(row)
        print(f"{model:6s} {mesh:12s} {row['error']:9.2e} {1e3 * t_cold:10.2f} "
              f"{1e3 * t_warm:10.2f}")
    if args.ross:
        for r in ross_numbers(max(1, args.repeat // 2), args.quick):
            row = dict(model="ROSS", mesh=r["mesh"],
                       error=error((r["eps"], np.array(r["K"]), np.array(r["C"])), ref),
                       cold_s=r["time_s"], warm_s=r["time_s"])
            rows.append(row)
            print(f"{'ROSS':6s} {row['mesh']:12s} {row['error']:9.2e} "
                  f"{1e3 * r['time_s']:10.1f} {'':>10s}")
        ok = [r for r in rows if r["model"] == "fem" and r["error"] <= 0.005]
        ross = [r for r in rows if r["model"] == "ROSS"]
        if ok and ross:
            ours = min(ok, key=lambda r: r["cold_s"])
            best_ross = min(ross, key=lambda r: r["error"])
            print(f"ours at <= 0.5 % ({ours['mesh']}, cold): {1e3 * ours['cold_s']:.1f} ms; "
                  f"ROSS's most accurate ({best_ross['mesh']}, error "
                  f"{100 * best_ross['error']:.2g} %): {best_ross['cold_s']:.2f} s = "
                  f"{best_ross['cold_s'] / ours['cold_s']:.0f}x")
    return rows


if __name__ == "__main__":
    main()
