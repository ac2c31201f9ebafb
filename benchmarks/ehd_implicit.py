"""The crowned seed pin with the bush's deflection advanced by the film's implicit step
(fem-ehd coupling 'implicit'): its convergence in the mesh, tau and the integrator's
tolerance, and its cost against the rigid JFO run of the same mesh.

    python -m benchmarks.ehd_implicit [--turns 2] [--meshes 48 4 96 8 192 16]
        [--tau 1e-5 ...] [--rtol 1e-6 ...] [--states] [--save DIR] [--figure PATH]
    python -m benchmarks.ehd_implicit --replay DIR --figure PATH [--turns 5] [--meshes 192 16]

The seed pin at 250 rad/s from top dead centre, the bush of ``paper-short-ehd-sharp`` (the
per-harmonic solid), a 2 um crown over the whole length, rough surfaces (sigma 0.2 um,
E* 80.8 GPa, K 1e-3, boundary friction 0.1), the isoviscous oil with Dowson-Higginson
density (benchmarks/ehd_states.py's); one run per row, each with the rigid JFO run of its
mesh and turns in the same process. Printed per row: steps, right-hand sides, CPU time,
the ratio to the rigid JFO run, and over the last whole turn the least film (the gap
itself, negative where the summits carry), the peak film pressure, the summits' share
(their load's time integral over the joint force's) and the mean friction power (film
shear and the summits' Coulomb friction), NaN for a run under a turn; and over the whole
run its peak eps, least film, peak film pressure, summits' share and friction power.
``--states`` adds the run with the whole deflection integrated as states (FullStateEHD) on
each mesh. A Ctrl-C stops the row's
run and prints what it computed (marked partial).

``--figure PATH`` draws the last row's film at its peak joint load (the film step with the
largest film + summits force, kept by the run: ``SimulationResult.peak_film``, no replay),
bush deflection and film pressure over the unwrapped film, and prints where it was
(crank angle, eps, force, peak pressure, largest deflection, least film). The rows then
record from the last whole turn (the periodic turn's peak, not the start's from the
bearing's centre, whose load is 2.7x larger): the "run:" columns' peak eps and least
film cover that turn (``--save`` keeps the samples of that turn alone).

``--replay DIR --figure PATH`` runs nothing: it draws the peak of the last whole turn of a
run saved in DIR (of ``--turns``, the first mesh, tau and rtol given), its film steps
replayed from the start (:func:`replayed_peak`; each checked against the run's record):
for a run saved without its kept peak, or recorded from its start.
"""
from __future__ import annotations

import argparse
import dataclasses

import numpy as np

from bearingfem.fields import EdgeProfile
from mechanism import load_result, load_scene, simulate
from bearingfem.contract import FilmStep
from mechanism.figures import render_deflection
from mechanism.film_history import film_history
from mechanism.result import film_column, film_states

from .common import OILS, best_of, scene
from .ehd_states import ROUGH, last_turn, last_turn_work, rigid_jfo

CROWN = EdgeProfile("crown", 2e-6)


def implicit_scene(turns, nt, nz, tau, rtol, coupling="implicit", record_from_turn=0.0):
    """The crowned seed pin's scene (module docstring), recorded from ``record_from_turn``."""
    sc = scene("paper-short-ehd-sharp", 250.0, turns, n_theta=nt, n_z=nz, modes=0, film_step=0.0,
               lubricant=OILS["iso"], coupling=coupling, relaxation=tau, roughness=ROUGH,
               profile=CROWN)
    return dataclasses.replace(sc, run=dataclasses.replace(
        sc.run, rtol=rtol, record_from_turn=record_from_turn))


def implicit_run(turns, nt, nz, tau, rtol, coupling="implicit", progress=False,
                 record_from_turn=0.0):
    """(result, CPU [s]) of one run."""
    sc = implicit_scene(turns, nt, nz, tau, rtol, coupling, record_from_turn)
    t = best_of(lambda: simulate(sc, progress=progress))
    return t.out, t.cpu


def window_work(r, radius, friction=ROUGH.friction):
    """(summits' share [1], mean friction power [W]) over the whole run (its film
    record): as ``last_turn_work``, for a window under a turn."""
    rec = np.asarray(r.film_record)
    t = film_column(rec, "t")
    a = film_column(rec, "asperity_load")
    f = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
    om = film_column(rec, "omega")
    power = (film_column(rec, "friction_force") * np.sign(om) + friction * a) \
        * radius * np.abs(om)
    return np.trapezoid(a, t) / np.trapezoid(f, t), np.trapezoid(power, t) / (t[-1] - t[0])


def last_turn_numbers(r, turns, radius):
    """(least film [um], peak pressure [MPa], summits' share, friction power [W]) over
    the run's last whole turn; NaN where a stopped run did not reach it."""
    # a completed run's samples stop short of its end by up to one sample's spacing
    reached = r.crank_angle[-1] >= 2 * np.pi * np.floor(turns) if len(r.t) else False
    if turns < 1 or (r.partial and not reached) or not len(r.t):
        return (float("nan"),) * 4
    h, p = last_turn(r, turns)
    share, _, power = last_turn_work(r, turns, radius)
    return h, p, share, power


def peak_figure(r, path, label=""):
    """Draw ``r``'s peak film (:func:`mechanism.figures.render_deflection`) to ``path``
    and return the line saying where it was; a run without one says so."""
    step = r.peak_film
    if step is None:
        return f"no film step kept at the peak load{label}: no figure"
    sol = step.solution
    q = r.crank_angle_at(step.t)
    turn, angle = divmod(np.degrees(q), 360.0)
    w, h = 1e6 * float(np.max(sol.deformation)), 1e6 * float(sol.film_min)
    render_deflection(sol, step.state, path,
                      f"crowned seed pin{label}\nfilm at the peak joint load: crank "
                      f"{angle:.1f} deg, eps {step.state.eps:.4f}")
    return (f"peak film{label}: crank {angle:.2f} deg of turn {int(turn) + 1}, t = "
            f"{step.t:.6g} s, eps {step.state.eps:.5f}, force "
            f"{np.hypot(*step.force_local):.1f} N, peak pressure {sol.pressure_max / 1e6:.1f} "
            f"MPa, largest deflection {w:.4f} um, least film {h:.4f} um -> {path}")


def replayed_peak(r, sc, from_turn):
    """The film step of a saved run ``r`` of scene ``sc`` with the largest film + summits
    force from crank turn ``from_turn`` on, its film solved again by replaying the run's
    film steps from its start (:func:`mechanism.film_history`, checked against the
    record at every step): a :class:`~bearingfem.contract.FilmStep`, as ``r.peak_film``.
    For a run saved without its kept peak (or recorded from another turn)."""
    rec = np.asarray(r.film_record)
    t_rec = film_column(rec, "t")
    t0 = float(np.interp(sc.crank_angle + 2 * np.pi * from_turn, r.crank_angle, r.t))
    window = np.flatnonzero(t_rec >= t0)
    if not len(window):
        raise ValueError(f"the run has no film step from turn {from_turn:g} on")
    force = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
    j = int(window[np.argmax(force[window])])
    frame, = film_history(r, sc, film_steps=[j])
    sol = frame.solution
    f, a = sol.force_local, sol.asperity_force_local
    return FilmStep(float(t_rec[j]), film_states(rec[j:j + 1])[0][1],
                    (f[0] + a[0], f[1] + a[1]), sol)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--turns", type=float, default=2.0)
    ap.add_argument("--meshes", type=int, nargs="+", default=[48, 4, 96, 8, 192, 16])
    ap.add_argument("--tau", type=float, nargs="+", default=[1e-5])
    ap.add_argument("--rtol", type=float, nargs="+", default=[1e-6])
    ap.add_argument("--states", action="store_true",
                    help="each mesh also with the whole deflection integrated as states")
    ap.add_argument("--save", metavar="DIR", default=None)
    ap.add_argument("--progress", action="store_true", help="each run's progress on stderr")
    ap.add_argument("--replay", metavar="DIR", default=None,
                    help="no run: draw --figure from the run saved in DIR (of --turns, the "
                         "first mesh, tau and rtol), its film steps replayed to the peak "
                         "joint load of its last whole turn")
    ap.add_argument("--figure", metavar="PATH", default=None,
                    help="draw the last row's film at its peak joint load in the last whole "
                         "turn (the rows then record from that turn)")
    a = ap.parse_args(argv)
    if a.replay:
        if not a.figure:
            ap.error("--replay draws a figure: give --figure PATH")
        r = load_result(a.replay)
        sc = implicit_scene(a.turns, a.meshes[0], a.meshes[1], a.tau[0], a.rtol[0])
        step = replayed_peak(r, sc, max(np.floor(a.turns) - 1.0, 0.0))
        print(peak_figure(dataclasses.replace(r, peak_film=step), a.figure,
                          f" ({a.meshes[0]} x {a.meshes[1]}, replayed)"), flush=True)
        return
    # the periodic turn's peak: the rows record from the last whole turn (module docstring)
    record_from = max(np.floor(a.turns) - 1.0, 0.0) if a.figure else 0.0
    radius = load_scene("paper-short-ehd-sharp").bearing.radius
    print(f"crowned seed pin (2 um), 250 rad/s, {a.turns:g} turns; last turn's numbers",
          flush=True)
    print(f"{'mesh':>8} {'coupling':>8} {'tau[s]':>7} {'rtol':>6} {'steps':>6} {'rhs':>6} "
          f"{'CPU[s]':>7} {'JFO[s]':>7} {'x JFO':>6} {'h_min[um]':>9} {'p_max[MPa]':>10} "
          f"{'share':>7} {'power[W]':>8} {'run: peak eps':>13} {'h_min[um]':>9} "
          f"{'p_max[MPa]':>10} {'share':>7} {'power[W]':>8}", flush=True)
    for nt, nz in zip(a.meshes[::2], a.meshes[1::2]):
        rigid_jfo(0.002, nt, nz)                       # warm-up: the mesh's operators
        implicit_run(0.001, nt, nz, a.tau[0], a.rtol[0])
        base = rigid_jfo(a.turns, nt, nz)
        rows = [("implicit", tau, rtol) for tau in a.tau for rtol in a.rtol]
        if a.states:
            rows.append(("states", a.tau[0], a.rtol[0]))
        for coupling, tau, rtol in rows:
            r, cpu = implicit_run(a.turns, nt, nz, tau, rtol, coupling, a.progress,
                                  record_from)
            h, p, share, power = last_turn_numbers(r, a.turns, radius)
            window_share, window_power = window_work(r, radius)
            if a.save:
                r.save(f"{a.save}/{coupling}-{nt}x{nz}-tau{tau:g}-rtol{rtol:g}")
            note = "" if not r.partial else f"  (partial: {r.message[:50]})"
            print(f"{nt:>4}x{nz:<3} {coupling:>8} {tau:7.0e} {rtol:6.0e} "
                  f"{r.stats['steps']:6d} {r.stats['rhs_evals']:6d} {cpu:7.1f} {base:7.1f} "
                  f"{cpu / base:6.1f} {h:9.4f} {p:10.1f} {share:7.4f} {power:8.3f} "
                  f"{r.eps.max():13.5f} {1e6 * r.film_min.min():9.4f} "
                  f"{film_column(r.film_record, 'pressure_max').max() / 1e6:10.1f} "
                  f"{window_share:7.4f} {window_power:8.3f}" + note,
                  flush=True)
    if a.figure:
        print(f"(recorded from turn {record_from:g}: the run's peak eps and least film over "
              "it)")
        print(peak_figure(r, a.figure, f" ({nt} x {nz}, {coupling})"), flush=True)


if __name__ == "__main__":
    main()
