"""The cost of a film step of the transient EHD-JFO film (fem-ehd cavitation "jfo")
against the EHD-Reynolds film's (fem-ehd, TransientEHD), in one process.

    python -m benchmarks.ehd_jfo_run [--mesh 32 4] [--modes 8] [--steps 12]

Both films take the same sequence of film steps (a journal moving out and turning, the
bronze ring bush of the mechanism tests, L/D 0.5, 250 rad/s, film steps 2e-4 s apart) and
the same trial force between them; the table gives the mean wall time per film step
(commit) and per trial force, and their ratio over the EHD-Reynolds film's.
"""
from __future__ import annotations

import argparse

from bearingfem import ElasticBush, JournalState
from bearingfem.bearing import Bearing
from bearingfem.models import film_model

from .common import best_of

RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
DT = 2e-4


def state(i):
    return JournalState(eps=0.5 + 0.03 * i, gamma=0.3 + 0.05 * i, omega=250.0,
                        eps_dot=0.03 / DT, gamma_dot=0.05 / DT)


def timed(film, steps):
    film.start(state(0), 0.0)
    t_step = t_force = 0.0
    for i in range(1, steps + 1):
        t_force += best_of(lambda: film.force(state(i - 0.5), (i - 0.5) * DT)).wall
        t_step += best_of(lambda: film.commit(state(i), i * DT)).wall
    return t_step / steps, t_force / steps


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--mesh", type=int, nargs=2, default=(32, 4))
    ap.add_argument("--modes", type=int, default=8)
    ap.add_argument("--steps", type=int, default=12)
    a = ap.parse_args(argv)
    bearing = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
    m = film_model("fem-ehd")
    rows = {}
    for cav in ("reynolds", "jfo"):
        film = m.along_run(bearing, dict(n_theta=a.mesh[0], n_z=a.mesh[1], bush=RING,
                                         modes=a.modes, film_step=DT / 2, cavitation=cav))
        rows[cav] = timed(film, a.steps)
    ref = rows["reynolds"]
    print(f"mesh {a.mesh[0]}x{a.mesh[1]}, modes {a.modes}, {a.steps} film steps")
    print(f"{'cavitation':>10} {'step[ms]':>9} {'x':>6} {'force[ms]':>10} {'x':>6}")
    for cav, (s, f) in rows.items():
        print(f"{cav:>10} {1e3 * s:9.2f} {s / ref[0]:6.2f} {1e3 * f:10.2f} {f / ref[1]:6.2f}")


if __name__ == "__main__":
    main()
