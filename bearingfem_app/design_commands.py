"""The designer's commands: ``equilibrium``, ``coefficients`` and ``design`` (the parser is
in :mod:`bearingfem_app.parser`; the options they read in :mod:`bearingfem_app.options`)."""
from __future__ import annotations

import math

from bearingfem.errors import LoadCapacityError

from .bush import bush_words
from .options import (accuracy_options, bearing_from_args, check_output, coarse_film_note,
                      estimate_options, model_options, note_coarse_film, print_rows,
                      write_numbers)

__all__ = ["command_equilibrium", "command_coefficients", "command_design"]


def _options_words(opts) -> str:
    """The film model's options as words for a header: ' (n_theta 120, element P1)'; a
    bush in its options' names (as ``solve`` prints it)."""
    words = [bush_words(v) if k == "bush" else f"{k} {v}" for k, v in opts.items()]
    return f" ({', '.join(words)})" if words else ""


def _equilibrium_rows(eq, b):
    """What the designer reads of an equilibrium: (name, value, unit) rows (with its
    estimated error and the mesh chosen when an accuracy was asked). One flow, what leaves
    through the ends: at a steady equilibrium a mass-conserving film's feed is its net side
    leakage, and a Reynolds-condition film has no feed of its own (its cavity makes up oil;
    ``Equilibrium.flow_in``); a film fed at its ends (JFO) draws in there what it loses."""
    return [("eccentricity ratio", eq.eps, "-")] + (
        [] if eq.eps_error is None else [("  its estimated error", eq.eps_error, "-"),
                                         (_mesh_words(eq.accuracy), _mesh_value(eq),
                                          "")]) + [
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
            ("side leakage (outflow)", _side_leakage(eq), "m^3/s")]


def _mesh_words(record) -> str:
    """The mesh row's name: chosen for an rtol, or the one given (--estimate)."""
    return "  mesh given" if record.rtol is None else "  mesh chosen"


def _mesh_value(eq) -> str:
    """'n_theta x n_z element' of the mesh estimated; the finite-volume film's grid as FV
    (its record carries the P1 order it is estimated at, not an element)."""
    n_theta, n_z = eq.accuracy.mesh
    return f"{n_theta} x {n_z} {'FV' if eq.model == 'fvm' else eq.accuracy.element}"


def _side_leakage(eq):
    """What leaves through the ends [m^3/s]: the film's outflow where it has it (a film fed
    at its ends, JFO, draws as much in elsewhere: its net is zero), else the net leakage."""
    out = None if eq.solution is None else eq.solution.side_outflow
    return eq.side_leakage if out is None else out


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


def _check_linearisable(model: str, command: str) -> None:
    """K and C need a film without memory: refused before the equilibrium is solved (it
    was solved, then refused by the coefficients)."""
    from bearingfem.models import film_model
    if film_model(model).memory:
        raise ValueError(f"{command} gives K and C, and --model {model} has memory (its film "
                         "at a state depends on the states before it): K and C at a state "
                         "alone are not defined; 'bearingfem equilibrium --model "
                         f"{model}' finds its equilibrium, 'bearingfem coefficients --model "
                         "fem' (with --bush for an elastic bush) K and C")


def _equilibrium(b, args, model, opts, acc=None):
    """The equilibrium under --load and --direction. A refusal of the load as beyond the
    film's capacity (:class:`~bearingfem.errors.LoadCapacityError`), on a rigid film's
    mesh given here and surely too coarse for the film at eps_max, says so: the capacity
    it names is the mesh's (8 x 2 cells gave 1991 N for a bearing that carries 2.5e5 N on
    120 x 20: D 50 mm, L/D 0.5, c 50 um, ISO VG 32, 3000 rpm), not the bearing's."""
    from bearingfem.design import equilibrium
    try:
        return equilibrium(b, args.load, args.omega, model,
                           direction=math.radians(args.direction), **opts, **(acc or {}))
    except LoadCapacityError as err:
        mesh = err.mesh if "n_theta" in opts and "bush" not in opts else None
        if mesh is not None and mesh.get("n_theta") != opts["n_theta"]:
            mesh = None      # --estimate's half mesh: its own words say so, not --n-theta's
        note = (None if mesh is None else
                coarse_film_note(err.eps_max, mesh["n_theta"], mesh.get("element", "P1"),
                                 estimate_options(args)))
        if note is None:
            raise
        raise ValueError(f"{err}; {note.removeprefix('note: ')}") from None


def command_equilibrium(args):
    out = check_output(args.output, (".json", ".csv"))
    model, opts = model_options(args)
    opts, acc = accuracy_options(args, opts)
    b = bearing_from_args(args)
    eq = _equilibrium(b, args, model, opts, acc)
    rows = _equilibrium_rows(eq, b)
    print(f"equilibrium, {model}{_options_words(opts)}: load {args.load:g} N toward "
          f"{args.direction:g} deg (inertial), {args.omega:g} rad/s, L/D {args.length_ratio:g}, "
          f"viscosity {b.viscosity:.4g} Pa s{_oil_words(args)}")
    print_rows(rows)
    note_coarse_film(eq.eps, opts, estimate_options(args))
    write_numbers(out, rows)
    return 0


def command_coefficients(args):
    from bearingfem import JournalState
    from bearingfem.design import coefficients, lund_stability
    out = check_output(args.output, (".json", ".csv"))
    model, opts = model_options(args)
    _check_linearisable(model, "coefficients")
    opts, acc = accuracy_options(args, opts)
    b = bearing_from_args(args)
    if (args.eps is None) == (args.load is None):
        raise ValueError("give exactly one of --eps (a steady state) or --load "
                         "(the equilibrium under that load)")
    eps_error = None
    if args.load is not None:
        eq = _equilibrium(b, args, model, opts, acc)
        state, eps_error = eq.state, eq.eps_error
    else:
        state = JournalState(args.eps, omega=args.omega, gamma=math.radians(args.gamma))
    kc = coefficients(b, state, model, frame=args.frame, eps_error=eps_error, **opts, **acc)
    # a film without rotation (--omega 0: a squeeze-film damper) has C but no K, and no
    # stability verdict: K and C are still the answer
    st = lund_stability(kc) if kc.K.any() else None
    rows, axes = _coefficient_rows(kc, args.frame)
    rows += ([("eccentricity ratio", state.eps, "-"), ("load carried", kc.load, "N")]
             + ([] if st is None else [("critical mass", st.critical_mass, "kg"),
                                       ("whirl frequency ratio", st.whirl_ratio, "-")])
             + ([] if kc.error is None else [("K, C estimated error", kc.error,
                                              "of the largest entry")]))
    print(f"coefficients, {model}{_options_words(opts)}, {args.frame} frame ({kc.method}); "
          f"{args.omega:g} rad/s, L/D {args.length_ratio:g}, viscosity {b.viscosity:.4g} "
          f"Pa s{_oil_words(args)}:")
    print(f"  {axes}")
    print_rows(rows)
    print(f"  {st}" if st is not None else "  no stability verdict: the film has no "
          "stiffness (K = 0; without rotation it only damps)")
    note_coarse_film(state.eps, opts, estimate_options(args))
    rows.append(("stability", "none (K = 0)" if st is None else st.verdict.value, "-"))
    write_numbers(out, rows)
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
    from bearingfem.design import coefficients, lund_stability
    out = check_output(args.output, (".json", ".csv"))
    model, opts = model_options(args)
    _check_linearisable(model, "design")
    b = bearing_from_args(args)
    eq = _equilibrium(b, args, model, opts)
    kc = coefficients(b, eq.state, model, frame="load", **opts)
    st = lund_stability(kc)
    eq_rows = _equilibrium_rows(eq, b)
    k_rows, axes = _coefficient_rows(kc, "load")
    k_rows += [("critical mass", st.critical_mass, "kg"),
               ("whirl frequency ratio", st.whirl_ratio, "-")]
    print(f"design point, {model}{_options_words(opts)}: D {b.diameter * 1e3:g} mm, L/D "
          f"{b.length_ratio:g}, radial clearance {b.clearance * 1e6:g} um, viscosity "
          f"{b.viscosity:.4g} Pa s{_oil_words(args)}, {args.omega:g} rad/s "
          f"({args.omega * 30 / math.pi:g} rpm), "
          f"load {args.load:g} N toward {args.direction:g} deg (inertial)")
    print_rows(eq_rows)
    print(f"  K, C ({kc.method}); {axes}")
    print_rows(k_rows)
    print(f"  {st}")
    note_coarse_film(eq.eps, opts, estimate_options(args))
    rows = eq_rows + k_rows + [("stability", st.verdict.value, "-")]
    write_numbers(out, rows)
    return 0
