"""Iterations and factorisations per transient JFO step, against the mesh.

    python -m benchmarks.jfo_iterations                 # squeeze film 200..1600 cells, journal 240x40, 480x80
    python -m benchmarks.jfo_iterations --large         # adds the journal at 960x160 and 1920x320
    python -m benchmarks.jfo_iterations --quick         # a smoke run (CI)
    python -m benchmarks.jfo_iterations --before DIR    # the same runs with the toolkit in DIR
    python -m benchmarks.jfo_iterations --save A.npz    # keep each step's force (or load)
    python -m benchmarks.jfo_iterations --against A.npz # largest force change against A.npz

* planar: parallel plates 10 mm long, gap h = 10 um - 5 um cos(2 pi 50 t), mu = 0.01 Pa s,
  both ends at 1 bar, 2 periods of 3200 backward-Euler steps each (``--steps`` per
  period). The cavity opens in the first steps and its front runs ~1/5 of the plate in
  ~20 steps: ~100 cells a step at 800 cells.
* journal: a bearing R = 10 mm, L = 20 mm, c = 20 um, mu = 0.0117 Pa s, no
  rotation, 0.1 bar at the ends, pure squeeze at eps_dot = +-40 1/s between eps = 0.3 and
  0.7: eps_dot jumps at the turns (one period, 200 steps).

``--journal-steps N`` runs only the first N journal steps (large meshes),
``--journal-only`` skips the squeeze film (``--squeeze-only`` the journal), ``--mesh
960x160`` and ``--cells 1600`` run those meshes instead of the others (repeatable).

Per step: the iterations of its solves (all coarser meshes that placed a first set and
all substeps counted), the sparse LU factorisations (``scipy.sparse.linalg.splu`` calls,
counted), and how many steps were cut or ended unconverged. A step's flow balance is relative to its own throughput.
``--before DIR`` imports the toolkit from DIR (e.g. ``git worktree add DIR <commit>``):
its unconverged steps are counted instead of raising.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

PERIOD = 0.02
SQUEEZE_CELLS = (200, 400, 800, 1600)
JOURNAL_MESHES = ((240, 40), (480, 80))
LARGE_MESHES = ((960, 160), (1920, 320))


class _CountedLU:
    """Counts the sparse LU factorisations (every solver of the toolkit calls
    scipy.sparse.linalg.splu through the module, old and new code alike)."""

    def __enter__(self):
        import scipy.sparse.linalg as spla
        self.spla, self.splu, self.count = spla, spla.splu, 0
        spla.splu = self
        return self

    def __exit__(self, *exc):
        self.spla.splu = self.splu

    def __call__(self, *args, **kw):
        self.count += 1
        return self.splu(*args, **kw)


def _record(rows, lu, sol, substeps, balance, wall, force):
    rows.append((sol.iterations, lu.count, substeps, bool(sol.converged), balance, wall,
                 force))
    lu.count = 0


def _summary(name, mesh, rows):
    it, fac, sub, conv, bal, wall, force = (np.array(c) for c in zip(*rows))
    return dict(film=name, mesh=mesh, steps=len(rows), it_mean=it.mean(), it_max=int(it.max()),
                fac_mean=fac.mean(), fac_max=int(fac.max()), cut=int(np.sum(sub > 1)),
                unconverged=int(np.sum(~conv)), balance=float(bal.max()),
                ms_per_step=1e3 * float(wall.sum()) / len(rows), force=force)


def squeeze_run(lu, n_x: int, steps_per_period: int, periods: int = 2):
    from bearingfem.fe.planar import PlanarJFO
    from bearingfem.planar import PlanarFilm
    film = PlanarFilm(length=0.01, width=0.001, viscosity=0.01, inlet_pressure=1e5,
                      outlet_pressure=1e5,
                      gap=lambda x, y, t: 10e-6 - 5e-6 * np.cos(2 * np.pi * t / PERIOD) + 0 * x)
    f = PlanarJFO(film, n_x, 1)
    dt, rows = PERIOD / steps_per_period, []
    for _ in range(periods * steps_per_period):
        t0 = time.perf_counter()
        s = f.step(dt)
        thr = max(abs(s.flow_in), abs(s.flow_out), abs(s.storage))
        _record(rows, lu, s, getattr(s, "substeps", 1), abs(s.mass_balance) / thr,
                time.perf_counter() - t0, s.load)
    return _summary("squeeze", f"{n_x}", rows)


def journal_run(lu, n_theta: int, n_z: int, steps: int = 200, run: int | None = None):
    """The journal film, ``steps`` a period, the first ``run`` of them (all: None)."""
    from bearingfem import Bearing, JournalState
    from bearingfem.fe.jfo import JFOFilm
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    rate, lo, hi = 40.0, 0.3, 0.7
    period = 2.0 * (hi - lo) / rate
    dt = period / steps

    def state(t):
        u = np.mod(t, period) / period      # up from lo for half a period, then down
        up = u < 0.5
        eps = lo + (hi - lo) * (2 * u if up else 2 - 2 * u)
        return JournalState(eps=float(eps), eps_dot=rate if up else -rate)
    f = JFOFilm(b, state(0.0), n_theta, n_z, ambient_pressure=1e4)
    rows = []
    for k in range(1, (steps if run is None else run) + 1):
        t0 = time.perf_counter()
        s = f.step(state(k * dt), dt)
        thr = max(abs(s.flow_in or 0.0), abs(s.side_leakage),
                  abs(s.side_leakage - (s.flow_in or 0.0) + s.mass_balance))
        _record(rows, lu, s, getattr(f, "substeps", 1), abs(s.mass_balance) / max(thr, 1e-300),
                time.perf_counter() - t0, np.hypot(*s.force_local))
    return _summary("journal", f"{n_theta}x{n_z}", rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smoke run: small meshes, few steps")
    ap.add_argument("--large", action="store_true", help="add the journal at 960x160, 1920x320")
    ap.add_argument("--steps", type=int, default=3200, help="squeeze steps per period")
    ap.add_argument("--before", default=None, help="import the toolkit from this directory")
    ap.add_argument("--journal-steps", type=int, default=200,
                    help="journal steps run (of 200 a period)")
    ap.add_argument("--journal-only", action="store_true", help="skip the squeeze film")
    ap.add_argument("--squeeze-only", action="store_true", help="skip the journal film")
    ap.add_argument("--cells", action="append", type=int, default=None,
                    help="squeeze film cells instead of 200 ... 1600 (repeatable)")
    ap.add_argument("--mesh", action="append", default=None,
                    help="journal mesh NTHETAxNZ instead of the default ones (repeatable)")
    ap.add_argument("--save", default=None, help="keep each run's forces in this .npz")
    ap.add_argument("--against", default=None, help="compare the forces with this .npz")
    a = ap.parse_args(argv)
    if a.before:
        sys.path.insert(0, a.before)
        for m in [m for m in sys.modules if m == "bearingfem" or m.startswith("bearingfem.")]:
            del sys.modules[m]
    import bearingfem
    print(f"toolkit: {bearingfem.__file__}")
    with _CountedLU() as lu:
        rows = _table(lu, a)
    key = lambda r: f"{r['film']} {r['mesh']} {r['steps']}"    # noqa: E731
    if a.save:
        np.savez(a.save, **{key(r): r["force"] for r in rows})
    if a.against:
        kept = np.load(a.against)
        print("| film | mesh | steps | largest force change / largest force |\n|---|---|---|---|")
        for r in rows:
            if key(r) in kept:
                f0 = kept[key(r)]
                change = np.max(np.abs(r["force"] - f0)) / np.max(np.abs(f0))
                print(f"| {r['film']} | {r['mesh']} | {r['steps']} | {change:.1e} |")
    return rows


def _table(lu, a):
    if a.quick:
        runs = [lambda: squeeze_run(lu, 100, 400, 1), lambda: journal_run(lu, 48, 4, 20)]
    else:
        runs = ([] if a.journal_only else
                [lambda n=n: squeeze_run(lu, n, a.steps) for n in a.cells or SQUEEZE_CELLS])
        meshes = JOURNAL_MESHES + (LARGE_MESHES if a.large else ())
        if a.mesh:
            meshes = tuple(tuple(int(n) for n in m.split("x")) for m in a.mesh)
        runs += [lambda m=m: journal_run(lu, *m, run=a.journal_steps) for m in meshes
                 if not a.squeeze_only]
    print("| film | mesh | steps | iterations/step mean | max | factorisations/step mean | "
          "max | cut steps | unconverged | worst balance / throughput | ms/step |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for run in runs:
        lu.count = 0
        r = run()
        rows.append(r)
        print(f"| {r['film']} | {r['mesh']} | {r['steps']} | {r['it_mean']:.2f} | "
              f"{r['it_max']} | {r['fac_mean']:.2f} | {r['fac_max']} | {r['cut']} | "
              f"{r['unconverged']} | {r['balance']:.1e} | {r['ms_per_step']:.1f} |",
              flush=True)
    return rows


if __name__ == "__main__":
    main()
