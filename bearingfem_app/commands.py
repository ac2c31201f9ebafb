"""What the film and run commands of ``bearingfem`` do (the parser is in
:mod:`bearingfem_app.parser`; the designer's commands in :mod:`bearingfem_app.design_commands`).

Every command checks what it can before any work - options that contradict each other,
output kinds and folders - and raises ValueError with one line naming the option.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

from bearingfem.outputs.tables import write_csv

from .bush import bush_from_args, bush_words
from .checks import check_writable, parse_angles
from .options import (ambient_pressure, check_film_options, check_output, check_rtol_mesh,
                      film_state, make_dir, note_coarse_film, supply_angle)

#: exit status of a run stopped by Ctrl-C (128 + SIGINT), as shells report it
INTERRUPTED = 130

__all__ = ["command_simulate", "command_solve", "command_render", "command_convergence",
           "command_sweep", "command_frames"]


def command_simulate(args):
    from dataclasses import replace

    from mechanism import load_scene, simulate
    from mechanism.figures import plot_run

    scene = load_scene(args.scene)
    if args.turns is not None:      # a quick look: these turns, every one recorded
        scene = replace(scene, run=replace(scene.run, turns=float(args.turns),
                                           record_from_turn=0.0))
    check_writable(args.output, "-o/--output")
    res = simulate(scene, progress=None if not args.quiet else False)
    out = make_dir(args.output, "-o/--output")
    res.save(out)
    plot_run(res, scene.bearing.clearance if scene.bearing else 1.0, out / "run.png")
    print(res.summary())
    print(f"wrote {out / 'result.npz'}, {out / 'result.csv'}, {out / 'result.json'}, "
          f"{out / 'run.png'}")
    if res.partial and res.message.startswith("interrupted"):
        return INTERRUPTED
    return 1 if res.partial else 0


#: What meshio writes from a film (checked before the solve, not after it).
FILM_FORMATS = (".vtu", ".xdmf", ".vtk")
#: What the off-screen renderer writes.
IMAGE_FORMATS = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff")


def _element(args, method="fem"):
    """--element belongs to the finite elements: refused when given with --model fvm."""
    if method == "fvm" and args.element_given:
        raise ValueError("--element applies to --model fem only (finite volumes have no "
                         f"element), got --element {args.element} with --model fvm")
    return args.element


def _film(args):
    """The film ``solve`` and ``render`` describe, solved: --model fem|fvm, the mesh or
    --rtol, the cavitation and its supply, a --bush; every option checked in its own name
    before any work. (bearing, journal state, the element used, the bush or None,
    FilmSolution)."""
    from bearingfem import fvm_reynolds, solve_reynolds
    element = _element(args, args.model)
    b, s = film_state(args)
    supply = supply_angle(args, s.gamma)
    bush = bush_from_args(args)
    if bush is not None and args.model == "fvm":
        raise ValueError("--bush applies to --model fem (the elastic film is a finite-"
                         "element film)")
    check_rtol_mesh(args)
    check_film_options(args)
    if args.rtol is not None and args.model == "fvm":    # the grid chosen, as for fem
        sol = fvm_reynolds(b, s, cavitation=args.cavitation,
                           ambient_pressure=ambient_pressure(args), supply_angle=supply,
                           rtol=args.rtol)
    elif args.rtol is not None:
        sol = solve_reynolds(b, s, element=element if args.element_given else None,
                             cavitation=args.cavitation, ambient_pressure=ambient_pressure(args),
                             supply_angle=supply, rtol=args.rtol, bush=bush)
    elif args.model == "fvm":
        sol = fvm_reynolds(b, s, args.n_theta, args.n_z, args.cavitation,
                           ambient_pressure=ambient_pressure(args), supply_angle=supply)
    else:
        sol = solve_reynolds(b, s, args.n_theta, args.n_z, element, args.cavitation,
                             ambient_pressure=ambient_pressure(args), supply_angle=supply,
                             bush=bush)
    return b, s, element, bush, sol


def _note_coarse(args, s, element, bush) -> None:
    """The coarse-film note of a rigid film on a given mesh (not with --rtol or --bush)."""
    if args.rtol is None and bush is None:
        note_coarse_film(s.eps, {"n_theta": args.n_theta,
                                 "element": "FV" if args.model == "fvm" else element})


def _deflection_words(sol) -> str:
    """The bush's largest deflection (by magnitude, signed) and where it is."""
    i = int(abs(sol.deformation).argmax())
    return (f"largest deflection {sol.deformation[i] * 1e6:.4g} um at theta "
            f"{math.degrees(float(sol.theta[i]) % (2 * math.pi)):.1f} deg from the maximum "
            "film (> 0 opens the gap)")


def command_solve(args):
    check_output(args.output, FILM_FORMATS)
    b, s, element, bush, sol = _film(args)
    print(sol.summary())
    if bush is not None:
        print(f"  bush: {bush_words(bush)}; {_deflection_words(sol)}")
    _note_coarse(args, s, element, bush)
    from bearingfem.design import sommerfeld_number
    load = math.hypot(*sol.force_local)
    print("  Sommerfeld number "
          + (f"{sommerfeld_number(b, load, s.omega):.6g}" if load > 0 and s.omega else "-"))
    if args.output:
        from bearingfem.outputs.export import write_solution
        make_dir(Path(args.output).parent, "-o/--output")
        write_solution(sol, args.output)
        print(f"wrote {args.output}")
    return 0


def command_convergence(args):
    from bearingfem.outputs.convergence import QUANTITIES, convergence_study
    from bearingfem.validation import check_choice
    if args.element_given:
        raise ValueError("--element does not apply to convergence: --methods names the "
                         "discretisations (P1, P2, fvm)")
    check_choice("--quantity", args.quantity, QUANTITIES)
    methods = tuple(args.methods.split(","))
    for m in methods:
        check_choice("--methods entry", m, ("P1", "P2", "fvm"))
    if args.cavitation == "jfo" and "P2" in methods:
        # refused here, not after the P1 meshes have been solved
        raise ValueError("--cavitation jfo is solved by P1 and fvm only (the JFO content is "
                         "balanced on P1 control volumes): give --methods P1,fvm")
    check_film_options(args)     # a JFO film's supply, named as solve and render name it
    b, s = film_state(args)
    supply = supply_angle(args, s.gamma)
    check_writable(args.output, "-o/--output")
    done = []
    try:
        st = convergence_study(b, s, levels=args.levels, n_theta=args.n_theta, n_z=args.n_z,
                               cavitation=args.cavitation, methods=methods, progress=print,
                               supply_angle=supply, ambient_pressure=ambient_pressure(args),
                               on_row=done.append)
    except KeyboardInterrupt:
        # Ctrl-C keeps the meshes solved (a long study's fine levels took minutes each), in
        # a file of its own name: a complete study's convergence.csv in the folder is kept
        # beside its summary and figure, and the file says it is partial once stdout is gone
        if done:
            path = make_dir(args.output, "-o/--output") / "convergence_partial.csv"
            write_csv(done, path)
            print(f"interrupted: wrote the {len(done)} meshes solved to {path} (PARTIAL: no "
                  "summary or figure)")
        raise
    out = make_dir(args.output, "-o/--output")
    st.write_csv(out / "convergence.csv")
    st.plot(out / "convergence.png", args.quantity)
    (out / "convergence_partial.csv").unlink(missing_ok=True)   # an interrupted one's, done
    print(f"{'method':6s} {'quantity':18s} {'unit':6s} {'finest':>14s} {'order':>7s} "
          f"{'extrapolated':>14s} {'GCI [rel]':>9s}")
    for r in st.summary:
        print(f"{r['method']:6s} {r['quantity']:18s} {r['unit']:6s} {r['finest']:14.6g} "
              f"{r['order']:7.3f} {r['extrapolated']:14.6g} {r['gci']:9.2e}")
    if any(math.isnan(r["order"]) for r in st.summary):
        print("order nan: the three finest values do not change monotonically (oscillating "
              "or already at round-off) or their differences do not shrink, so no order, "
              "extrapolation or GCI")
    print(f"wrote {out / 'convergence.csv'}, {out / 'convergence_summary.csv'}, "
          f"{out / 'convergence.png'}")
    return 0


#: the fields of the films ``render`` solves: the bush's deflection with --bush (the
#: thermal film's temperature is drawn from Python, render_film: the command line builds no
#: thermal film)
RENDER_FIELDS = ("pressure", "film_thickness", "fraction", "deformation")


def command_render(args):
    from bearingfem.outputs.render import FIELDS, SURFACES, render_film
    from bearingfem.validation import check_choice
    if args.field == "temperature":
        raise ValueError("--field temperature is a thermal film's: the command line builds "
                         "no thermal film (render it from Python, docs/thd.md); choose one "
                         "of " + ", ".join(map(repr, RENDER_FIELDS)))
    check_choice("--field", args.field, tuple(f for f in FIELDS if f in RENDER_FIELDS))
    check_choice("--surface", args.surface, SURFACES)
    if args.field == "fraction" and args.cavitation != "jfo":
        raise ValueError("--field fraction is the JFO film's fraction: use it with "
                         f"--cavitation jfo, not {args.cavitation}")
    if args.field == "deformation" and args.bush is None:
        raise ValueError("--field deformation is the elastic bush's deflection: give --bush "
                         "ring|solid|liner")
    check_output(args.output, IMAGE_FORMATS)
    _, s, element, bush, sol = _film(args)
    make_dir(Path(args.output).parent, "-o/--output")
    render_film(sol, args.output, field=args.field, surface=args.surface)
    print(sol.summary())
    _note_coarse(args, s, element, bush)
    print(f"wrote {args.output}")
    return 0


#: local worker processes per core at most: more only share the cores (and --workers 200,
#: a typo, started 200 Python processes on a 2-core machine)
WORKERS_PER_CORE = 4


def usable_cores() -> int:
    """The cores this process may run on: its CPU affinity where the system reports it
    (Linux), else the machine's count. Why: a container pinned to 2 of a host's 64 cores
    reports 64 to os.cpu_count(), and --workers would be allowed 256."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:        # no affinity call (macOS, Windows)
        return os.cpu_count() or 1


def check_workers(args) -> None:
    """--workers: local processes, at most WORKERS_PER_CORE per core; not with --scheduler,
    whose cluster's own workers run the cases (it was ignored there)."""
    if args.scheduler is not None:
        if "workers" in getattr(args, "given", ()):
            raise ValueError("--workers starts a local cluster; with --scheduler the "
                             "cluster's own workers run the cases: give one of them")
        return
    cores = usable_cores()
    if args.workers > WORKERS_PER_CORE * cores:
        raise ValueError(f"--workers {args.workers} local processes on {cores} cores: at "
                         f"most {WORKERS_PER_CORE * cores} (more only share the cores; "
                         "--scheduler runs on a larger cluster)")


def command_sweep(args):
    from bearingfem_app.sweep import load_sweep, run_sweep
    sweep = load_sweep(args.sweep)
    check_workers(args)
    check_writable(args.output, "-o/--output")      # the runner makes it once all is checked
    res = run_sweep(sweep, args.output, scheduler=args.scheduler, workers=args.workers,
                    progress=None if not args.quiet else False)
    out = Path(args.output)
    print(f"sweep {sweep.name}: {res.computed} computed, {res.skipped} already done, "
          f"{len(res.failed)} failed in {res.wall_time:.1f} s"
          + (" - interrupted, rerun to continue" if res.interrupted else ""))
    for cid, msg in res.failed.items():
        print(f"  {cid}: {msg}")
    if res.rows:
        print(f"wrote {out / 'results.csv'}, {out / 'summary.png'} ({len(res.rows)} cases)")
    return INTERRUPTED if res.interrupted else (1 if res.failed else 0)


def _differences(a, b, where="scene"):
    """Dotted names of the entries where two nested dicts differ."""
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b))
                for d in _differences(a.get(k), b.get(k), f"{where}.{k}")]
    return [] if a == b else [where]


#: why a film field is not among a run's frames, named for the field asked (a thermal run's
#: '--field temperature' was told that 'the film fraction needs a mass-conserving film')
FRAME_FIELD_HINTS = {
    "fraction": "the film fraction needs a mass-conserving film (model fem-jfo)",
    "temperature": "the frames keep no film temperature: draw one thermal film's from Python "
                   "(render_film(sol, path, field='temperature'), docs/thd.md)",
    "deformation": "the frames keep no bush deflection: draw one elastic film's with "
                   "'bearingfem render --bush ... --field deformation'",
}


def command_frames(args):
    from mechanism import load_scene
    from mechanism.film_history import film_history, render_history, write_history
    from mechanism.result import load_result
    scene = load_scene(args.scene)
    if not (Path(args.result) / "result.npz").is_file():
        raise ValueError(f"no run result in {args.result!r} (expected result.npz from "
                         "'bearingfem simulate')")
    result = load_result(args.result)
    if result.scene != scene.name:
        raise ValueError(f"the run in {args.result!r} was made from scene {result.scene!r}, "
                         f"not from {scene.name!r} ({args.scene}): give the scene of the run")
    stored = result.provenance.get("scene")
    if stored is not None:   # the physics must match; run settings (turns, output) need not
        import dataclasses
        import json
        now = json.loads(json.dumps(dataclasses.asdict(scene), default=float))
        stored = json.loads(json.dumps(stored, default=float))
        differ = _differences({k: v for k, v in stored.items() if k != "run"},
                              {k: v for k, v in now.items() if k != "run"})
        if differ:
            raise ValueError(f"scene {args.scene} differs from the one the run in "
                             f"{args.result!r} was made from ({', '.join(differ[:4])})")
    angles = parse_angles(args.angles) if args.angles else None
    from bearingfem.outputs.render import FIELDS, SURFACES
    from bearingfem.validation import check_choice
    from mechanism.film_history import history_fields
    check_choice("--field", args.field, tuple(FIELDS))
    check_choice("--surface", args.surface, SURFACES)
    fields = history_fields(scene)
    if args.field not in fields:
        model = scene.lubrication.model if scene.lubrication is not None else "none"
        hint = FRAME_FIELD_HINTS.get(args.field)
        raise ValueError(f"--field {args.field}: the frames of this run (film {model}) "
                         f"carry {', '.join(fields)}" + (f"; {hint}" if hint else ""))
    check_writable(args.output, "-o/--output")
    frames = film_history(result, scene, angles, args.frames,
                          progress=lambda k, n: print(f"  film {k}/{n}", flush=True))
    out = make_dir(args.output, "-o/--output")
    pvd = write_history(frames, out, args.surface)
    print(f"wrote {pvd} ({len(frames)} VTU files, time = run time [s])")
    if not args.no_render:
        paths = render_history(frames, out, args.field, args.surface, gif=args.gif,
                               fixed_camera=args.fixed_camera)
        print(f"wrote {len(paths)} images to {out}" + (" incl. film.gif" if args.gif else ""))
    return 0
