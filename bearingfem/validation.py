"""Argument checks shared by the solvers: fail before any work, naming the parameter."""
from __future__ import annotations

import math

from .bearing import Bearing, Groove, JournalState, check_finite

#: Cavitation models of the Reynolds family (pressure alone) and the mass-conserving one.
REYNOLDS_FAMILY = ("none", "gumbel", "reynolds")
CAVITATION = REYNOLDS_FAMILY + ("jfo",)
#: Coarsest meshes accepted (FE and FV): a periodic scikit-fem mesh needs >= 3 cells around,
#: and a film resolved by fewer than 8 cells around cannot place its pressure peak.
MIN_N_THETA = 8
MIN_N_Z = 2
METHODS = ("active-set", "psor")
#: Finest film accepted: unknowns (nodes; P2 has about four per cell). A cavitated solve
#: takes ~5 kB per unknown (benchmarks/film_solve.py --memory: 1.05 GB at 2e5), so 4e6 is
#: ~20 GB; the toolkit's finest meshes (1920 x 320 P1, P2 1536 x 256) stay well below.
MAX_UNKNOWNS = 4_000_000


def estimated_unknowns(n_theta: int, n_z: int, element: str = "P1") -> int:
    """Nodes of a whole-length film mesh (periodic in theta): what a solve's size follows."""
    k = 2 if element == "P2" else 1
    return k * n_theta * (k * n_z + 1)


def check_choice(name: str, value, allowed) -> str:
    if value not in allowed:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, allowed))}, got {value!r}")
    return value


def check_int(name: str, value, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int,)) and not (
            isinstance(value, float) and value.is_integer()):
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    v = int(value)
    if v < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return v


def check_inputs(bearing, state):
    if not isinstance(bearing, Bearing):
        raise ValueError(f"bearing must be a bearingfem.Bearing, got {type(bearing).__name__}")
    if not isinstance(state, JournalState):
        raise ValueError(f"state must be a bearingfem.JournalState, got {type(state).__name__}")


def check_supply_angle(value):
    """None (fully periodic film) or a finite angle [rad]."""
    return None if value is None else check_finite("supply_angle", value)


def check_grooves(grooves, supply_angle=None, mass_conserving: bool = False) -> tuple:
    """A tuple of :class:`Groove`; refuses what the Reynolds-condition films cannot do
    (a starved groove needs ``mass_conserving``, the JFO film)."""
    if isinstance(grooves, Groove):     # one groove, not a sequence of them
        raise ValueError("grooves must be a sequence of Groove objects, got one Groove: give "
                         "grooves=[Groove(...)]")
    try:
        grooves = tuple(grooves or ())
    except TypeError:
        raise ValueError(f"grooves must be a sequence of Groove objects, got "
                         f"{type(grooves).__name__}") from None
    for g in grooves:
        if not isinstance(g, Groove):
            raise ValueError(f"grooves must be bearingfem.Groove objects, got {type(g).__name__}")
        if g.fraction < 1.0 and not mass_conserving:
            raise ValueError(f"a starved groove (fraction {g.fraction:g} < 1) needs a "
                             "mass-conserving film (cavitation='jfo'); the Reynolds-family "
                             "films hold the groove flooded")
    if grooves and supply_angle is not None:
        raise ValueError("give grooves or supply_angle (a supply line), not both")
    return grooves


def check_film_solve(bearing, state, n_theta, n_z, cavitation, method, supply_angle,
                     tol=1e-10, **choices):
    """What every mesh film solver checks before any work, all at once (one message per
    bad parameter, joined): returns (n_theta, n_z, supply_angle). ``choices`` maps further
    parameter names to (value, allowed)."""
    errors, out = [], {}
    checks = [("inputs", lambda: check_inputs(bearing, state)),
              ("n_theta", lambda: check_int("n_theta", n_theta, MIN_N_THETA)),
              ("n_z", lambda: check_int("n_z", n_z, MIN_N_Z)),
              ("cavitation", lambda: check_choice("cavitation", cavitation, CAVITATION)),
              ("method", lambda: check_choice("method", method, METHODS)),
              ("supply_angle", lambda: check_supply_angle(supply_angle))]
    checks += [(k, lambda k=k, v=v: check_choice(k, *v)) for k, v in choices.items()]
    for name, check in checks:
        try:
            out[name] = check()
        except ValueError as err:
            errors.append(str(err))
    if not (isinstance(tol, (int, float)) and tol > 0.0 and math.isfinite(tol)):
        errors.append(f"tol must be a positive finite number, got {tol!r}")
    if "n_theta" in out and "n_z" in out:
        # refused before the mesh is built: a mistyped size ran the machine out of memory
        element = out.get("element", "P1")
        unknowns = estimated_unknowns(out["n_theta"], out["n_z"], element)
        if unknowns > MAX_UNKNOWNS:
            errors.append(f"n_theta x n_z = {out['n_theta']} x {out['n_z']} ({element}) is "
                          f"~{unknowns:.2g} unknowns, above the {MAX_UNKNOWNS:.0e} a film "
                          f"solve takes (~5 kB each): a coarser mesh, or rtol")
    if errors:
        raise ValueError("; ".join(errors))
    return out["n_theta"], out["n_z"], out["supply_angle"]


def check_jfo_supply(cavitation, grooves, supply_angle, ambient_pressure, element="P1"):
    """What a JFO film needs before any work: P1 elements, ambient_pressure >= 0 [Pa] (only
    with cavitation='jfo'), and a supply of oil. Without a groove, a supply line or
    ambient_pressure > 0 nothing refills a steady film and its content is undetermined."""
    p = check_finite("ambient_pressure", ambient_pressure)
    if p < 0.0:
        raise ValueError(f"ambient_pressure must be >= 0 [Pa], got {ambient_pressure!r}")
    if cavitation != "jfo":
        if p != 0.0:
            raise ValueError("ambient_pressure (end pressure above the cavitation pressure) "
                             "is a JFO-film option: use cavitation='jfo'")
        return p
    if element != "P1":
        raise ValueError(f"cavitation='jfo' needs element 'P1' (its content is balanced on "
                         f"the nodes' control volumes), got {element!r}")
    if not grooves and supply_angle is None and p == 0.0:
        raise ValueError("cavitation='jfo' needs a supply of oil: grooves, supply_angle or "
                         "ambient_pressure > 0 [Pa] (without one nothing refills the film "
                         "and a steady film's content is undetermined)")
    return p
