"""The seed pin at 250 rad/s with the bush's modes integrated (fem-ehd coupling 'states').

    python -m benchmarks.ehd_states [--turns 0.1] [--mesh 48 4] [--runs base rtol tau ...]
        [--modes 16 24 ... | 0] [--crown DEPTH_UM [LENGTH_MM]] [--progress] [--save DIR]
        [--differences]

A tenth of a turn from top dead centre (benchmarks/ehd_step.py's window), rough surfaces
(sigma 0.2 um, E* 80.8 GPa, K 1e-3), one run per row: steps, CPU time, peak eps, least film
(the gap itself: negative where the summits carry), peak film pressure, the steps the
integration loop cut where a film solve failed, the least film and peak pressure over the
last whole turn (the periodic state), and the rigid JFO run of the same mesh for the cost
ratio. With ``--differences`` each row runs again with the integrator's own difference
Jacobian (the film's tangent hidden, contract rule 17), in the same process: the
tangent's saving. ``--crown`` gives the bush a crowned bore (an
:class:`~bearingfem.fields.EdgeProfile`, depth [um] at the ends over the given length at
each end [mm], default the whole length); the last turn's summits' share (their load's
time integral over the total force's) and mean friction power (film shear and summits'
Coulomb friction) are printed after each row. docs/ehd-states.md has tables of it.
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses

import numpy as np

from bearingfem.contact import Roughness
from bearingfem.fields import EdgeProfile
from mechanism import load_scene, simulate
from mechanism.effects import FilmEffect
from mechanism.result import film_column

from .common import OILS, best_of, scene

ROUGH = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3, friction=0.1)
#: (name, rtol, relaxation [s], modes, oil)
RUNS = {"base": (1e-6, 1e-5, 16, "iso"), "rtol": (1e-7, 1e-5, 16, "iso"),
        "tau3": (1e-6, 3e-6, 16, "iso"), "tau1": (1e-6, 1e-6, 16, "iso"),
        "modes8": (1e-6, 1e-5, 8, "iso"), "modes24": (1e-6, 1e-5, 24, "iso"),
        "modes32": (1e-6, 1e-5, 32, "iso"), "modes48": (1e-6, 1e-5, 48, "iso"),
        "roelands": (1e-6, 1e-5, 16, "roelands")}


@contextlib.contextmanager
def without_tangent():
    """The film's tangent hidden: the integrator forms the Jacobian by differences."""
    kept = FilmEffect.has_tangent
    FilmEffect.has_tangent = property(lambda self: False)
    try:
        yield
    finally:
        FilmEffect.has_tangent = kept


def states_run(turns, nt, nz, rtol, tau, modes, oil, progress=False, profile=None):
    sc = scene("paper-short-ehd-sharp", 250.0, turns, n_theta=nt, n_z=nz, modes=modes,
               film_step=0.0, lubricant=OILS[oil], coupling="states", relaxation=tau,
               roughness=ROUGH, profile=profile)
    sc = dataclasses.replace(sc, run=dataclasses.replace(sc.run, rtol=rtol))
    t = best_of(lambda: simulate(sc, progress=progress))
    return t.out, t.cpu


def rigid_jfo(turns, nt, nz):
    sc = load_scene("paper-short-jfo")
    lub = dataclasses.replace(sc.lubrication, options=dict(sc.lubrication.options,
                                                           n_theta=nt, n_z=nz))
    sc = dataclasses.replace(sc, lubrication=lub, run=dataclasses.replace(
        sc.run, turns=turns, record_from_turn=0.0))
    return best_of(lambda: simulate(sc, progress=False)).cpu


def last_turn(r, turns):
    """(least film [um], peak film pressure [MPa]) over the run's last whole crank turn
    (the periodic state the seed records; NaN for a run under one turn)."""
    if turns < 1 or not len(r.eps):
        return float("nan"), float("nan")
    start = 2 * np.pi * (np.floor(turns) - 1)
    on = r.crank_angle >= start
    t0 = r.t[np.argmax(on)]
    p = film_column(r.film_record, "pressure_max")[film_column(r.film_record, "t") >= t0]
    return 1e6 * float(np.min(r.film_min[on])), float(np.max(p, initial=-np.inf)) / 1e6


def last_turn_work(r, turns, bearing_radius, friction=ROUGH.friction):
    """(summits' share [1], their peak load [N], mean friction power [W]) over the run's
    last whole turn: the time integral of the summits' load over that of the joint film's
    total force, and the mean of (film shear + summits' Coulomb force) R |omega|."""
    if turns < 1 or not len(r.eps):
        return (float("nan"),) * 3
    t0 = r.t[np.argmax(r.crank_angle >= 2 * np.pi * (np.floor(turns) - 1))]
    rec = np.asarray(r.film_record)
    rec = rec[film_column(rec, "t") >= t0]
    t = film_column(rec, "t")
    a = film_column(rec, "asperity_load")
    f = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
    om = film_column(rec, "omega")
    power = (film_column(rec, "friction_force") * np.sign(om) + friction * a) \
        * bearing_radius * np.abs(om)
    span = t[-1] - t[0]
    return (np.trapezoid(a, t) / np.trapezoid(f, t), float(a.max()),
            np.trapezoid(power, t) / span)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--turns", type=float, default=0.1)
    ap.add_argument("--mesh", type=int, nargs=2, default=(48, 4))
    ap.add_argument("--runs", nargs="+", default=list(RUNS), choices=list(RUNS))
    ap.add_argument("--modes", type=int, nargs="+", default=None,
                    help="run each selected row at each of these numbers of modes (0: the "
                         "whole deflection integrated, no modes)")
    ap.add_argument("--progress", action="store_true",
                    help="each run's progress on stderr (five turns take minutes to hours)")
    ap.add_argument("--differences", action="store_true",
                    help="each row again with the integrator's difference Jacobian")
    ap.add_argument("--crown", type=float, nargs="+", default=None,
                    metavar=("DEPTH_UM", "LENGTH_MM"),
                    help="a crowned bush bore: depth [um] at the ends, over LENGTH_MM at each "
                         "end (default: the whole length)")
    ap.add_argument("--save", metavar="DIR", default=None,
                    help="write each run's result to DIR/<run>-<modes>modes (its film record "
                         "and modal states, for a look at where the least film falls)")
    a = ap.parse_args(argv)
    nt, nz = a.mesh
    radius = load_scene("paper-short-ehd-sharp").bearing.radius
    profile = None
    if a.crown:
        profile = EdgeProfile("crown", a.crown[0] * 1e-6,
                              None if len(a.crown) < 2 else a.crown[1] * 1e-3)
    # warm-up: the first run of a process builds the meshes' operators and tables
    rigid_jfo(0.002, nt, nz)
    rtol0, tau0, modes0, oil0 = RUNS[a.runs[0]]
    states_run(0.002, nt, nz, rtol0, tau0, (a.modes or [modes0])[0], oil0, profile=profile)
    base = rigid_jfo(a.turns, nt, nz)
    print(f"seed pin, 250 rad/s, {a.turns:g} turn, {nt} x {nz}; rigid JFO run {base:.2f} s CPU"
          + ("" if profile is None else f"; bush bore {profile}"))
    print(f"{'run':>9} {'rtol':>6} {'tau[s]':>7} {'modes':>5} {'oil':>8} {'steps':>6} "
          f"{'rhs':>6} {'CPU[s]':>7} {'x JFO':>6} {'peak eps':>9} {'h_min[um]':>9} "
          f"{'p_max[MPa]':>10} {'cuts':>4} {'last turn: h_min[um]':>20} {'p_max[MPa]':>10}")
    rows = [(name, m, diff) for name in a.runs for m in (a.modes or [RUNS[name][2]])
            for diff in ((False, True) if a.differences else (False,))]
    for name, modes, diff in rows:
        rtol, tau, _, oil = RUNS[name]
        with without_tangent() if diff else contextlib.nullcontext():
            r, cpu = states_run(a.turns, nt, nz, rtol, tau, modes, oil, a.progress, profile)
        p = film_column(r.film_record, "pressure_max")
        p_max = p.max() / 1e6 if p.size else float("nan")
        note = "" if not r.partial else f"  (stopped: {r.message[:60]})"
        h_last, p_last = last_turn(r, a.turns)
        label = name + ("/diff" if diff else "")
        if a.save:
            r.save(f"{a.save}/{name}-{modes}modes" + ("-differences" if diff else ""))
        print(f"{label:>9} {rtol:6.0e} {tau:7.0e} {modes:5d} {oil:>8} {r.stats['steps']:6d} "
              f"{r.stats['rhs_evals']:6d} {cpu:7.1f} {cpu / base:6.1f} "
              f"{r.eps.max() if len(r.eps) else float('nan'):9.4f} "
              f"{1e6 * r.film_min.min() if len(r.eps) else float('nan'):9.3f} {p_max:10.1f} "
              f"{len(r.stats.get('step_cuts', ())):4d} {h_last:20.3f} {p_last:10.1f}" + note,
              flush=True)
        share, a_max, power = last_turn_work(r, a.turns, radius)
        print(f"{'':>9} last turn: summits' share {share:.4f}, their peak load {a_max:.1f} N, "
              f"friction power {power:.2f} W; integrator Jacobians {r.stats['jacobians']}",
              flush=True)


if __name__ == "__main__":
    main()
