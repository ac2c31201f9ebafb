"""Command line: ``bearingfem COMMAND ...``; bad input prints one line and exits 2."""
from __future__ import annotations

import argparse
import functools
import math
import re
import sys
from pathlib import Path

from bearingfem.bearing import SEED_TABLE1

EXAMPLES = """examples:
  bearingfem simulate scenes/paper-short-fem.toml -o results/short-fem
  bearingfem solve --ld 1.0 --eps 0.6 --cavitation reynolds
  bearingfem render --ld 1.0 --eps 0.6 --cavitation reynolds -o film.png
  bearingfem convergence --ld 1.0 --eps 0.6 -o results/convergence
  bearingfem sweep sweeps/capacity.toml -o results/capacity --workers 2
  bearingfem frames scenes/paper-long-fem.toml results/long-fem -o results/long-frames --gif
  bearingfem equilibrium --ld 1 --load 1000 --model fem --element P2
  bearingfem coefficients --ld 0.5 --load 500 --frame load -o kc.csv
"""


def _simulate(args):
    from mechanism import load_scene, simulate
    from mechanism.figures import plot_run

    scene = load_scene(args.scene)
    out = _make_dir(args.output, "-o/--output")
    res = simulate(scene, progress=None if not args.quiet else False)
    res.save(out)
    plot_run(res, scene.bearing.clearance if scene.bearing else 1.0, out / "run.png")
    print(res.summary())
    print(f"wrote {out / 'result.npz'}, {out / 'result.json'}, {out / 'run.png'}")
    return 1 if res.partial else 0


def _bearing(args):
    from bearingfem import Bearing
    from bearingfem.bearing import check_positive
    check_positive("--length-ratio/--ld (L/D)", args.length_ratio)   # name what was typed
    return Bearing(radius=args.diameter / 2, length=args.length_ratio * args.diameter,
                   clearance=args.clearance, viscosity=args.viscosity)


def _table1(args):
    from bearingfem import JournalState
    s = JournalState(eps=args.eps, eps_dot=args.eps_dot, gamma=0.0, gamma_dot=0.0,
                     omega=args.omega)
    return _bearing(args), s


def _model_options(args):
    """The film model named on the command line and the options of it given there."""
    from bearingfem.models import film_model
    m = film_model(args.model, "--model")
    given = dict(n_theta=args.n_theta, n_z=args.n_z, element=args.element,
                 cavitation=args.cavitation)
    return args.model, {k: v for k, v in given.items() if k in m.defaults}


def _check_output(path, suffixes):
    """Refuse an output file of an unknown kind before any work; make its folder."""
    if path is None:
        return None
    out = Path(path)
    if out.suffix.lower() not in suffixes:
        raise ValueError(f"-o/--output must end in {' or '.join(suffixes)}, got {path!r}")
    _make_dir(out.parent, "-o/--output")
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
    if out.suffix.lower() == ".json":
        import json
        out.write_text(json.dumps({n: {"value": v, "unit": u} for n, v, u in rows}, indent=1))
    else:
        from bearingfem.outputs.tables import write_csv
        write_csv([dict(quantity=n, value=v, unit=u) for n, v, u in rows], out)
    print(f"wrote {out}")


def _print_rows(rows):
    for name, value, unit in rows:
        v = "-" if value is None else f"{value:.6g}"
        print(f"  {name:24s} {v:>14s} {unit}")


def _equilibrium(args):
    from bearingfem.design import equilibrium
    out = _check_output(args.output, (".json", ".csv"))
    model, opts = _model_options(args)
    b = _bearing(args)
    eq = equilibrium(b, args.load, args.omega, model, direction=math.radians(args.direction),
                     **opts)
    rows = [("eccentricity ratio", eq.eps, "-"),
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
    print(f"equilibrium, {model} {opts or ''}: load {args.load:g} N at "
          f"{args.direction:g} deg, {args.omega:g} rad/s, L/D {args.length_ratio:g}")
    _print_rows(rows)
    _write_numbers(out, rows)
    return 0


def _coefficients(args):
    from bearingfem import JournalState
    from bearingfem.design import coefficients, equilibrium, lund_stability
    out = _check_output(args.output, (".json", ".csv"))
    model, opts = _model_options(args)
    b = _bearing(args)
    if (args.eps is None) == (args.load is None):
        raise ValueError("give exactly one of --eps (a steady state) or --load "
                         "(the equilibrium under that load)")
    if args.load is not None:
        state = equilibrium(b, args.load, args.omega, model,
                            direction=math.radians(args.direction), **opts).state
    else:
        state = JournalState(args.eps, omega=args.omega, gamma=math.radians(args.gamma))
    kc = coefficients(b, state, model, frame=args.frame, **opts)
    st = lund_stability(kc)
    names = ("xx", "xy", "yx", "yy") if args.frame == "inertial" else (
        ("rr", "rt", "tr", "tt") if args.frame == "local" else ("11", "12", "21", "22"))
    rows = ([(f"K_{n}", float(v), "N/m") for n, v in zip(names, kc.K.ravel())]
            + [(f"C_{n}", float(v), "N s/m") for n, v in zip(names, kc.C.ravel())]
            + [("eccentricity ratio", state.eps, "-"), ("load carried", kc.load, "N"),
               ("critical mass", st.critical_mass, "kg"),
               ("whirl frequency ratio", st.whirl_ratio, "-")])
    print(f"coefficients, {model} {opts or ''}, {args.frame} frame ({kc.method}):")
    _print_rows(rows)
    _write_numbers(out, rows)
    return 0


#: What meshio writes from a film (checked before the solve, not after it).
FILM_FORMATS = (".vtu", ".xdmf", ".vtk")
#: What the off-screen renderer writes.
IMAGE_FORMATS = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff")


def _element(args, method="fem"):
    """--element belongs to the finite elements: refused when given with --method fvm."""
    if method == "fvm" and args.element_given:
        raise ValueError("--element applies to --method fem only (finite volumes have no "
                         f"element), got --element {args.element} with --method fvm")
    return args.element


def _solve(args):
    from bearingfem import fvm_reynolds, solve_reynolds
    element = _element(args, args.method)
    _check_output(args.output, FILM_FORMATS)
    b, s = _table1(args)
    if args.method == "fvm":
        sol = fvm_reynolds(b, s, args.n_theta, args.n_z, args.cavitation)
    else:
        sol = solve_reynolds(b, s, args.n_theta, args.n_z, element, args.cavitation)
    print(sol.summary())
    from bearingfem.design import sommerfeld_number
    load = math.hypot(*sol.force_local)
    print("  Sommerfeld number "
          + (f"{sommerfeld_number(b, load, s.omega):.6g}" if load > 0 and s.omega else "-"))
    if args.output:
        from bearingfem.outputs.export import write_solution
        write_solution(sol, args.output)
        print(f"wrote {args.output}")
    return 0


def _convergence(args):
    from bearingfem.outputs.convergence import QUANTITIES, convergence_study
    from bearingfem.validation import check_choice
    if args.element_given:
        raise ValueError("--element does not apply to convergence: --methods names the "
                         "discretisations (P1, P2, fvm)")
    check_choice("--quantity", args.quantity, QUANTITIES)
    methods = tuple(args.methods.split(","))
    for m in methods:
        check_choice("--methods entry", m, ("P1", "P2", "fvm"))
    b, s = _table1(args)
    out = _make_dir(args.output, "-o/--output")
    st = convergence_study(b, s, levels=args.levels, n_theta=args.n_theta, n_z=args.n_z,
                           cavitation=args.cavitation, methods=methods, progress=print)
    st.write_csv(out / "convergence.csv")
    st.plot(out / "convergence.png", args.quantity)
    print(f"{'method':6s} {'quantity':18s} {'finest':>14s} {'order':>7s} {'extrapolated':>14s} {'GCI':>9s}")
    for r in st.summary:
        print(f"{r['method']:6s} {r['quantity']:18s} {r['finest']:14.6g} {r['order']:7.3f} "
              f"{r['extrapolated']:14.6g} {r['gci']:9.2e}")
    print(f"wrote {out / 'convergence.csv'}, {out / 'convergence_summary.csv'}, "
          f"{out / 'convergence.png'}")
    return 0


def _render(args):
    from bearingfem import solve_reynolds
    from bearingfem.outputs.render import FIELDS, SURFACES, render_film
    from bearingfem.validation import check_choice
    check_choice("--field", args.field, tuple(FIELDS))
    check_choice("--surface", args.surface, SURFACES)
    _check_output(args.output, IMAGE_FORMATS)
    b, s = _table1(args)
    sol = solve_reynolds(b, s, args.n_theta, args.n_z, _element(args), args.cavitation)
    render_film(sol, args.output, field=args.field, surface=args.surface)
    print(sol.summary())
    print(f"wrote {args.output}")
    return 0


def _sweep(args):
    from bearingfem_app.sweep import load_sweep, run_sweep
    sweep = load_sweep(args.sweep)
    _make_dir(args.output, "-o/--output")
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
    return 1 if res.failed or res.interrupted else 0


def _differences(a, b, where="scene"):
    """Dotted names of the entries where two nested dicts differ."""
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b))
                for d in _differences(a.get(k), b.get(k), f"{where}.{k}")]
    return [] if a == b else [where]


def _frames(args):
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
    angles = None
    if args.angles:
        try:
            angles = [float(a) for a in args.angles.split(",")]
        except ValueError:
            raise ValueError(f"--angles must be comma-separated degrees, got {args.angles!r}") \
                from None
    out = _make_dir(args.output, "-o/--output")
    frames = film_history(result, scene, angles, args.frames,
                          progress=lambda k, n: print(f"  film {k}/{n}", flush=True))
    pvd = write_history(frames, out, args.surface)
    print(f"wrote {pvd} ({len(frames)} VTU files, time = run time [s])")
    if not args.no_render:
        paths = render_history(frames, out, args.field, args.surface, gif=args.gif,
                               fixed_camera=args.fixed_camera)
        print(f"wrote {len(paths)} images to {out}" + (" incl. film.gif" if args.gif else ""))
    return 0


def _bearing_args(p):
    p.add_argument("--length-ratio", "--ld", dest="length_ratio", type=float, default=1.0,
                   help="L/D, the bearing's length over its diameter")
    p.add_argument("--omega", type=float, default=250.0, help="journal speed [rad/s]")
    p.add_argument("--diameter", type=float, default=SEED_TABLE1["diameter"],
                   help="[m] (seed Table 1)")
    p.add_argument("--clearance", type=float, default=SEED_TABLE1["clearance"],
                   help="[m] (seed Table 1)")
    p.add_argument("--viscosity", type=float, default=SEED_TABLE1["viscosity"],
                   help="[Pa s] (seed Table 1)")
    p.add_argument("--cavitation", default="reynolds", help="none | gumbel | reynolds")
    p.add_argument("--n-theta", type=int, default=120, help="cells around the film")
    p.add_argument("--n-z", type=int, default=20, help="cells along the length")
    p.add_argument("--element", default="P1", help="P1 | P2 (finite elements only)")


def _film_args(p):
    _bearing_args(p)
    p.add_argument("--eps", type=float, default=0.6, help="eccentricity ratio in [0, 1)")
    p.add_argument("--eps-dot", type=float, default=0.0, help="d(eps)/dt [1/s]")


def _load_args(p, required):
    p.add_argument("--load", type=float, required=required,
                   help="load magnitude [N]" + ("" if required else
                                                ": K, C at the equilibrium under it"))
    p.add_argument("--direction", type=float, default=-90.0,
                   help="load direction [deg], inertial (-90: downward)")


def _design_args(p):
    """Film model and mesh for the designer's commands (closed forms ignore the mesh)."""
    _bearing_args(p)
    p.add_argument("--model", default="fem", help="film model: short | long | short-exact "
                   "| long-exact | fem | fvm | fem-table")
    p.add_argument("-o", "--output", help="also write the numbers (.json or .csv)")


def build_parser():
    p = argparse.ArgumentParser(prog="bearingfem", description="Verified journal-bearing films "
                                "and the slider-crank that carries them.", epilog=EXAMPLES,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    add = functools.partial(sub.add_parser,   # every option shows its default in --help
                            formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    s = add("simulate", help="integrate a scene; write result and figure",
                       epilog="example: bearingfem simulate scenes/paper-long-fem.toml -o out")
    s.add_argument("scene", help="scene TOML file")
    s.add_argument("-o", "--output", required=True, help="output directory")
    s.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    s.set_defaults(func=_simulate)
    f = add("solve", help="one film solve; print forces, optionally export VTU",
                       epilog="example: bearingfem solve --ld 0.5 --eps 0.8 -o film.vtu")
    _film_args(f)
    f.add_argument("--method", default="fem", choices=["fem", "fvm"],
                   help="finite elements or finite volumes")
    f.add_argument("-o", "--output", help="write the film (.vtu, .xdmf)")
    f.set_defaults(func=_solve)
    c = add("convergence", help="mesh-convergence study: CSV table + log-log PNG",
                       epilog="example: bearingfem convergence --ld 1.0 --eps 0.6 -o conv")
    _film_args(c)
    c.set_defaults(n_theta=24, n_z=4)
    c.add_argument("--levels", type=int, default=4, help="meshes, each twice as fine (>= 3)")
    c.add_argument("--methods", default="P1,P2,fvm", help="comma list of P1, P2, fvm")
    c.add_argument("--quantity", default="force", help="quantity for the figure")
    c.add_argument("-o", "--output", required=True, help="output directory")
    c.set_defaults(func=_convergence)
    r = add("render", help="off-screen PNG of the film pressure or thickness",
                       epilog="example: bearingfem render --ld 1.0 --eps 0.6 -o film.png")
    _film_args(r)
    r.add_argument("--field", default="pressure", help="pressure | film_thickness")
    r.add_argument("--surface", default="journal", help="journal | unwrapped")
    r.add_argument("-o", "--output", required=True, help="PNG file")
    r.set_defaults(func=_render)
    w = add("sweep", help="parameter sweep on Dask: one file per case, resumable",
                       epilog="example: bearingfem sweep sweeps/capacity.toml -o out "
                              "--scheduler tcp://10.0.0.5:8786")
    w.add_argument("sweep", help="sweep TOML file (see sweeps/)")
    w.add_argument("-o", "--output", required=True, help="output directory (rerun to resume)")
    w.add_argument("--scheduler", help="address of a running Dask scheduler; default: a "
                   "local cluster")
    w.add_argument("--workers", type=int, default=2, help="local cluster processes")
    w.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    w.set_defaults(func=_sweep)
    fr = add("frames", help="the film along a saved run: VTU series (.pvd), PNG "
                        "frames, GIF", epilog="example: bearingfem frames "
                        "scenes/paper-long-fem.toml results/long-fem -o frames --angles 0,90")
    fr.add_argument("scene", help="the scene TOML the run was made from")
    fr.add_argument("result", help="directory written by 'bearingfem simulate'")
    fr.add_argument("-o", "--output", required=True, help="output directory")
    fr.add_argument("--angles", help="crank angles [deg], comma-separated (default: evenly "
                    "spaced --frames)")
    fr.add_argument("--frames", type=int, default=12, help="number of evenly spaced frames")
    fr.add_argument("--field", default="pressure", help="pressure | film_thickness")
    fr.add_argument("--surface", default="journal", help="journal | unwrapped")
    fr.add_argument("--gif", action="store_true", help="also write an animated film.gif")
    fr.add_argument("--fixed-camera", action="store_true",
                    help="journal view from one place for every frame (default: each "
                         "frame's loaded side)")
    fr.add_argument("--no-render", action="store_true", help="VTU series only, no PNG")
    fr.set_defaults(func=_frames)
    e = add("equilibrium", help="where the journal sits under a load: eps, "
                       "attitude, Sommerfeld number, film, friction, flow",
                       epilog="example: bearingfem equilibrium --ld 1 --load 1000 "
                              "--model fem --element P2")
    _design_args(e)
    _load_args(e, required=True)
    e.set_defaults(func=_equilibrium)
    k = add("coefficients", help="stiffness and damping (K, C) and Lund's "
                       "critical mass, at an eccentricity or under a load",
                       epilog="example: bearingfem coefficients --ld 0.5 --load 500 "
                              "--frame load")
    _design_args(k)
    k.add_argument("--eps", type=float, help="steady state at this eccentricity ratio")
    k.add_argument("--gamma", type=float, default=0.0, help="its attitude [deg] (with --eps)")
    _load_args(k, required=False)
    k.add_argument("--frame", default="inertial", choices=["inertial", "local", "load"],
                   help="axes of K and C")
    k.set_defaults(func=_coefficients)
    return p


_NEGATIVE = re.compile(r"^-(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$", re.IGNORECASE)


def _negative_values(argv):
    """``--opt -20e-6`` -> ``--opt=-20e-6``: argparse would read the value as an option,
    so that the range check could not speak."""
    out, i = [], 0
    while i < len(argv):
        a = argv[i]
        if a.startswith("--") and "=" not in a and i + 1 < len(argv) and _NEGATIVE.match(argv[i + 1]):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
        else:
            out.append(a)
            i += 1
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    args = build_parser().parse_args(_negative_values(argv))
    # options whose meaning depends on others: was it typed, or is it the default?
    args.element_given = any(a == "--element" or a.startswith("--element=") for a in argv)
    try:
        return args.func(args)
    except ValueError as err:
        print(f"bearingfem: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
