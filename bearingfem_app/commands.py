"""What each ``bearingfem`` command does (the parser is in :mod:`bearingfem_app.cli`).

Every command checks what it can before any work - options that contradict each other,
output kinds and folders - and raises ValueError with one line naming the option.
"""
from __future__ import annotations

import math
from pathlib import Path

from .bush import bush_from_args
from .checks import check_writable, parse_angles

#: exit status of a run stopped by Ctrl-C (128 + SIGINT), as shells report it
INTERRUPTED = 130

__all__ = ["command_simulate", "command_solve", "command_render", "command_convergence",
           "command_sweep", "command_frames", "command_equilibrium", "command_coefficients",
           "command_design"]


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
    out = _make_dir(args.output, "-o/--output")
    res.save(out)
    plot_run(res, scene.bearing.clearance if scene.bearing else 1.0, out / "run.png")
    print(res.summary())
    print(f"wrote {out / 'result.npz'}, {out / 'result.json'}, {out / 'run.png'}")
    if res.partial and res.message.startswith("interrupted"):
        return INTERRUPTED
    return 1 if res.partial else 0


def _bearing(args):
    from bearingfem import Bearing
    from bearingfem.bearing import check_positive
    check_positive("--length-ratio/--ld (L/D)", args.length_ratio)   # name what was typed
    return Bearing(radius=args.diameter / 2, length=args.length_ratio * args.diameter,
                   clearance=args.clearance, viscosity=args.viscosity)


def _supply_angle(args, gamma=0.0):
    """--supply-angle: degrees from the maximum film (or max-film) -> inertial [rad], or
    None. The maximum film lies opposite the eccentricity, at gamma + pi."""
    text = args.supply_angle
    if text is None:
        return None
    if text == "max-film":
        return gamma + math.pi
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"--supply-angle must be degrees from the maximum film or max-film, "
                         f"got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"--supply-angle must be finite, got {text!r}")
    return gamma + math.pi + math.radians(value)


def _ambient(args):
    return 0.0 if args.ambient_pressure is None else args.ambient_pressure


def _film_state(args):
    """The bearing and the journal state the film options describe."""
    from bearingfem import JournalState
    s = JournalState(eps=args.eps, eps_dot=args.eps_dot, gamma=0.0, gamma_dot=0.0,
                     omega=args.omega)
    return _bearing(args), s


#: command-line options that are film-model options (dest -> option as typed)
MODEL_OPTIONS = {"n_theta": "--n-theta", "n_z": "--n-z", "element": "--element",
                 "cavitation": "--cavitation", "ambient_pressure": "--ambient-pressure"}


def _model_options(args):
    """The film model named on the command line and the options of it given there; an
    option typed that the model does not take is refused (it would be ignored)."""
    from bearingfem.models import film_model
    m = film_model(args.model, "--model")
    refused = [o for k, o in MODEL_OPTIONS.items() if k in args.given and k not in m.defaults]
    if refused:
        takes = ", ".join(MODEL_OPTIONS[k] for k in m.defaults if k in MODEL_OPTIONS)
        raise ValueError(f"{', '.join(refused)} {'does' if len(refused) == 1 else 'do'} not "
                         f"apply to --model {args.model} (its options: {takes or 'none'})")
    if m.disk_cache:      # tables are built once and kept: the cache must take them
        _check_cache()
    given = {k: getattr(args, k) for k in MODEL_OPTIONS}
    opts = {k: v for k, v in given.items()
            if k in m.defaults and (v is not None and (k != "ambient_pressure"
                                                       or k in args.given))}
    bush = bush_from_args(args)
    if bush is not None and "bush" not in m.defaults:
        raise ValueError(f"--bush applies to a film model that takes a bush (--model fem: "
                         f"the steady elastic film; fem-ehd: beyond the clearance and along "
                         f"a run), not --model {args.model}")
    return args.model, opts if bush is None else dict(opts, bush=bush)


def _accuracy(args, opts):
    """With --rtol the mesh options are the toolkit's to choose (the element too unless
    given): (options without them, {"rtol": ...}); without, (options, {})."""
    if args.rtol is None:
        return opts, {}
    drop = ("n_theta", "n_z") + (() if args.element_given else ("element",))
    return {k: v for k, v in opts.items() if k not in drop}, {"rtol": args.rtol}


def _check_cache():
    """The fem-table cache folder takes a file (tried, not guessed from permissions)."""
    import tempfile

    from bearingfem.fe.force_table import cache_dir
    folder = cache_dir()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:
        raise ValueError(f"--model fem-table: cannot write its table cache {str(folder)!r} "
                         f"({err.strerror}); set BEARINGFEM_CACHE to a writable folder") \
            from None


def _check_output(path, suffixes):
    """Refuse an output file of an unknown kind, or in a folder that cannot be made, before
    any work (the folder is made when the file is written)."""
    if path is None:
        return None
    out = Path(path)
    if out.suffix.lower() not in suffixes:
        raise ValueError(f"-o/--output must end in {' or '.join(suffixes)}, got {path!r}")
    check_writable(out.parent, "-o/--output")
    return out


def _make_dir(path, option):
    """Create an output folder before any work, or say in one line why it cannot be."""
    try:
        Path(path).mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ValueError(f"{option}: cannot create folder {str(path)!r} ({err.strerror})") \
            from None
    return Path(path)


def _write_numbers(out, rows):
    """rows: (name, value, unit) -> JSON object or a CSV table."""
    if out is None:
        return
    _make_dir(out.parent, "-o/--output")
    if out.suffix.lower() == ".json":
        import json
        out.write_text(json.dumps({n: {"value": v, "unit": u} for n, v, u in rows}, indent=1))
    else:
        from bearingfem.outputs.tables import write_csv
        write_csv([dict(quantity=n, value=v, unit=u) for n, v, u in rows], out)
    print(f"wrote {out}")


def _print_rows(rows):
    for name, value, unit in rows:
        v = "-" if value is None else (value if isinstance(value, str) else f"{value:.6g}")
        print(f"  {name:24s} {v:>14s} {unit}")


def _equilibrium_rows(eq, b):
    """What the designer reads of an equilibrium: (name, value, unit) rows (with its
    estimated error and the mesh chosen when an accuracy was asked)."""
    return [("eccentricity ratio", eq.eps, "-")] + (
        [] if eq.eps_error is None else [("  its estimated error", eq.eps_error, "-"),
                                         ("  mesh chosen", "{} x {} {}".format(
                                             *eq.accuracy.mesh, eq.accuracy.element), "")]) + [
            ("attitude angle", math.degrees(eq.attitude), "deg"),
            ("Sommerfeld number", eq.sommerfeld, "-"),
            ("minimum film", eq.film_min, "m"),
            ("minimum film angle", math.degrees(eq.film_min_angle), "deg (inertial)"),
            ("journal x", eq.eps * b.clearance * math.cos(eq.state.gamma), "m"),
            ("journal y", eq.eps * b.clearance * math.sin(eq.state.gamma), "m"),
            ("peak pressure", eq.pressure_max, "Pa"),
            ("friction force", eq.friction_force, "N"),
            ("friction coefficient", eq.friction_coefficient, "-"),
            ("power loss", eq.power_loss, "W"),
            ("side leakage", eq.side_leakage, "m^3/s"),
            ("inflow", eq.flow_in, "m^3/s")]


#: the axes of K and C in each frame, in words
FRAME_AXES = {
    "inertial": (("x", "y"), "x, y inertial (y up: --direction -90 is downward)"),
    "local": (("r", "t"), "r along the eccentricity (journal centre from bearing centre), "
                          "t = r turned +90 deg"),
    "load": (("1", "2"), "1 along the load, 2 = 1 turned +90 deg (counter-clockwise)")}


def _coefficient_rows(kc, frame):
    """K, C in ``frame`` as rows, and one line naming the frame's axes."""
    (a, b), words = FRAME_AXES[frame]
    names = (a + a, a + b, b + a, b + b)
    rows = ([(f"K_{n}", float(v), "N/m") for n, v in zip(names, kc.K.ravel())]
            + [(f"C_{n}", float(v), "N s/m") for n, v in zip(names, kc.C.ravel())])
    angles = [round(math.degrees(math.atan2(q[1], q[0])), 9) + 0.0 for q in kc.axes]
    return rows, (f"axes: {words}; axis {a} at {angles[0]:.4g} deg, axis {b} at "
                  f"{angles[1]:.4g} deg (inertial, counter-clockwise from x)")


def command_equilibrium(args):
    from bearingfem.design import equilibrium
    out = _check_output(args.output, (".json", ".csv"))
    model, opts = _model_options(args)
    opts, acc = _accuracy(args, opts)
    b = _bearing(args)
    eq = equilibrium(b, args.load, args.omega, model, direction=math.radians(args.direction),
                     **opts, **acc)
    rows = _equilibrium_rows(eq, b)
    print(f"equilibrium, {model} {opts or ''}: load {args.load:g} N toward "
          f"{args.direction:g} deg (inertial), {args.omega:g} rad/s, L/D {args.length_ratio:g}")
    _print_rows(rows)
    _write_numbers(out, rows)
    return 0


def command_coefficients(args):
    from bearingfem import JournalState
    from bearingfem.design import coefficients, equilibrium, lund_stability
    out = _check_output(args.output, (".json", ".csv"))
    model, opts = _model_options(args)
    opts, acc = _accuracy(args, opts)
    b = _bearing(args)
    if (args.eps is None) == (args.load is None):
        raise ValueError("give exactly one of --eps (a steady state) or --load "
                         "(the equilibrium under that load)")
    eps_error = None
    if args.load is not None:
        eq = equilibrium(b, args.load, args.omega, model,
                         direction=math.radians(args.direction), **opts, **acc)
        state, eps_error = eq.state, eq.eps_error
    else:
        state = JournalState(args.eps, omega=args.omega, gamma=math.radians(args.gamma))
    kc = coefficients(b, state, model, frame=args.frame, eps_error=eps_error, **opts, **acc)
    st = lund_stability(kc)
    rows, axes = _coefficient_rows(kc, args.frame)
    rows += ([("eccentricity ratio", state.eps, "-"), ("load carried", kc.load, "N"),
              ("critical mass", st.critical_mass, "kg"),
              ("whirl frequency ratio", st.whirl_ratio, "-")]
             + ([] if kc.error is None else [("K, C estimated error", kc.error,
                                              "of the largest entry")]))
    print(f"coefficients, {model} {opts or ''}, {args.frame} frame ({kc.method}):")
    print(f"  {axes}")
    _print_rows(rows)
    print(f"  {st}")
    rows.append(("stability", st.verdict.value, "-"))
    _write_numbers(out, rows)
    return 0


def _oil_words(args) -> str:
    if getattr(args, "oil", None) is None:
        return ""
    t = 40.0 if args.oil_temperature is None else args.oil_temperature
    return f" ({args.oil} at {t:g} degC)"


def command_design(args):
    """The designer's question in one command: where the journal sits under the load
    (least film, attitude, friction power, flow) and the film's K, C there in the load
    frame, with Lund's stability of a rigid journal."""
    from bearingfem.design import coefficients, equilibrium, lund_stability
    out = _check_output(args.output, (".json", ".csv"))
    model, opts = _model_options(args)
    b = _bearing(args)
    eq = equilibrium(b, args.load, args.omega, model, direction=math.radians(args.direction),
                     **opts)
    kc = coefficients(b, eq.state, model, frame="load", **opts)
    st = lund_stability(kc)
    eq_rows = _equilibrium_rows(eq, b)
    k_rows, axes = _coefficient_rows(kc, "load")
    k_rows += [("critical mass", st.critical_mass, "kg"),
               ("whirl frequency ratio", st.whirl_ratio, "-")]
    print(f"design point, {model} {opts or ''}: D {b.diameter * 1e3:g} mm, L/D "
          f"{b.length_ratio:g}, radial clearance {b.clearance * 1e6:g} um, viscosity "
          f"{b.viscosity:.4g} Pa s{_oil_words(args)}, {args.omega:g} rad/s ({args.omega * 30 / math.pi:g} rpm), "
          f"load {args.load:g} N toward {args.direction:g} deg (inertial)")
    _print_rows(eq_rows)
    print(f"  K, C ({kc.method}); {axes}")
    _print_rows(k_rows)
    print(f"  {st}")
    rows = eq_rows + k_rows + [("stability", st.verdict.value, "-")]
    _write_numbers(out, rows)
    return 0


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


def command_solve(args):
    from bearingfem import fvm_reynolds, solve_reynolds
    element = _element(args, args.model)
    _check_output(args.output, FILM_FORMATS)
    b, s = _film_state(args)
    supply = _supply_angle(args, s.gamma)
    bush = bush_from_args(args)
    if bush is not None and args.model == "fvm":
        raise ValueError("--bush applies to --model fem (the elastic film is a finite-"
                         "element film)")
    if args.model == "fvm" and args.rtol is not None:
        raise ValueError("--rtol applies to --model fem only")
    if args.rtol is not None:
        sol = solve_reynolds(b, s, element=element if args.element_given else None,
                             cavitation=args.cavitation, ambient_pressure=_ambient(args),
                             supply_angle=supply, rtol=args.rtol, bush=bush)
    elif args.model == "fvm":
        sol = fvm_reynolds(b, s, args.n_theta, args.n_z, args.cavitation,
                           ambient_pressure=_ambient(args), supply_angle=supply)
    else:
        sol = solve_reynolds(b, s, args.n_theta, args.n_z, element, args.cavitation,
                             ambient_pressure=_ambient(args), supply_angle=supply, bush=bush)
    print(sol.summary())
    from bearingfem.design import sommerfeld_number
    load = math.hypot(*sol.force_local)
    print("  Sommerfeld number "
          + (f"{sommerfeld_number(b, load, s.omega):.6g}" if load > 0 and s.omega else "-"))
    if args.output:
        from bearingfem.outputs.export import write_solution
        _make_dir(Path(args.output).parent, "-o/--output")
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
    if args.ambient_pressure is not None:
        raise ValueError("--ambient-pressure does not apply to convergence (Reynolds-family "
                         "films: none, gumbel, reynolds)")
    b, s = _film_state(args)
    supply = _supply_angle(args, s.gamma)
    check_writable(args.output, "-o/--output")
    st = convergence_study(b, s, levels=args.levels, n_theta=args.n_theta, n_z=args.n_z,
                           cavitation=args.cavitation, methods=methods, progress=print,
                           supply_angle=supply)
    out = _make_dir(args.output, "-o/--output")
    st.write_csv(out / "convergence.csv")
    st.plot(out / "convergence.png", args.quantity)
    print(f"{'method':6s} {'quantity':18s} {'finest':>14s} {'order':>7s} {'extrapolated':>14s} {'GCI':>9s}")
    for r in st.summary:
        print(f"{r['method']:6s} {r['quantity']:18s} {r['finest']:14.6g} {r['order']:7.3f} "
              f"{r['extrapolated']:14.6g} {r['gci']:9.2e}")
    print(f"wrote {out / 'convergence.csv'}, {out / 'convergence_summary.csv'}, "
          f"{out / 'convergence.png'}")
    return 0


def command_render(args):
    from bearingfem import solve_reynolds
    from bearingfem.outputs.render import FIELDS, SURFACES, render_film
    from bearingfem.validation import check_choice
    check_choice("--field", args.field, tuple(FIELDS))
    check_choice("--surface", args.surface, SURFACES)
    if args.field == "fraction" and args.cavitation != "jfo":
        raise ValueError("--field fraction is the JFO film's fraction: use it with "
                         f"--cavitation jfo, not {args.cavitation}")
    _check_output(args.output, IMAGE_FORMATS)
    b, s = _film_state(args)
    sol = solve_reynolds(b, s, args.n_theta, args.n_z, _element(args), args.cavitation,
                         ambient_pressure=_ambient(args),
                         supply_angle=_supply_angle(args, s.gamma))
    _make_dir(Path(args.output).parent, "-o/--output")
    render_film(sol, args.output, field=args.field, surface=args.surface)
    print(sol.summary())
    print(f"wrote {args.output}")
    return 0


def command_sweep(args):
    from bearingfem_app.sweep import load_sweep, run_sweep
    sweep = load_sweep(args.sweep)
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
        raise ValueError(f"--field {args.field}: the frames of this run (film {model}) "
                         f"carry {', '.join(fields)}; the film fraction needs a "
                         f"mass-conserving film (model fem-jfo)")
    check_writable(args.output, "-o/--output")
    frames = film_history(result, scene, angles, args.frames,
                          progress=lambda k, n: print(f"  film {k}/{n}", flush=True))
    out = _make_dir(args.output, "-o/--output")
    pvd = write_history(frames, out, args.surface)
    print(f"wrote {pvd} ({len(frames)} VTU files, time = run time [s])")
    if not args.no_render:
        paths = render_history(frames, out, args.field, args.surface, gif=args.gif,
                               fixed_camera=args.fixed_camera)
        print(f"wrote {len(paths)} images to {out}" + (" incl. film.gif" if args.gif else ""))
    return 0
