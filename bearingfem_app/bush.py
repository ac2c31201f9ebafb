"""The elastic bush on the command line: ``--bush ring|solid|liner`` with its outer radius,
Young's modulus and Poisson's ratio (the :class:`bearingfem.ElasticBush` of
``solve``, ``equilibrium`` and ``coefficients``)."""
from __future__ import annotations

from bearingfem.bearing import SEED_TABLE1
from bearingfem.elastic.bush import MODELS, OUTER_RATIO, ElasticBush

__all__ = ["add_bush_args", "bush_from_args", "bush_words", "BUSH_OPTIONS"]

#: Young's modulus [Pa] of any bush material, soft rubber (~1e6) to diamond (~1.1e12):
#: outside it the number was typed in another unit (110 for 110 GPa), and the EHD Newton
#: solve then fails without saying why
MODULUS_RANGE = (1e5, 1.2e12)

#: dest -> (option as typed, ElasticBush field)
BUSH_OPTIONS = {"bush_outer_radius": ("--bush-outer-radius", "outer_radius"),
                "bush_modulus": ("--bush-modulus", "modulus"),
                "bush_poisson": ("--bush-poisson", "poisson")}


def add_bush_args(p):
    d = ElasticBush()
    p.add_argument("--bush", default=None, choices=MODELS,
                   help="an elastic bush (EHD film): a 3-D solid, plane-strain rings per "
                        "slice, or a thin liner; outer surface held")
    p.add_argument("--bush-outer-radius", type=float, default=None,
                   help=f"the bush's held outer radius [m] (> R; default {OUTER_RATIO:g} R, "
                        f"{d.at_radius(SEED_TABLE1['diameter'] / 2).outer_radius:g} at the "
                        "default --diameter)")
    p.add_argument("--bush-modulus", type=float, default=None,
                   help=f"the bush's Young's modulus [Pa] in [{MODULUS_RANGE[0]:g}, "
                        f"{MODULUS_RANGE[1]:g}], rubber to diamond (default {d.modulus:g})")
    p.add_argument("--bush-poisson", type=float, default=None,
                   help=f"the bush's Poisson's ratio, in (-1, 0.5) (default {d.poisson:g})")


#: ElasticBush field -> its unit as printed
UNITS = {"outer_radius": " m", "modulus": " Pa", "poisson": ""}


def bush_words(bush: ElasticBush) -> str:
    """The bush in the options' own names: '--bush ring, --bush-outer-radius 0.016 m,
    --bush-modulus 1.1e+11 Pa, --bush-poisson 0.34' (its outer radius resolved)."""
    return ", ".join([f"--bush {bush.model}"] + [
        f"{option} {getattr(bush, field):g}{UNITS[field]}"
        for option, field in BUSH_OPTIONS.values()])


def bush_from_args(args) -> ElasticBush | None:
    """The bush the options describe, or None without ``--bush`` (or for a command that
    takes no bush); a bush option without ``--bush``, or a value out of range, raises
    ValueError naming the option."""
    given = [o for dest, (o, _) in BUSH_OPTIONS.items()
             if getattr(args, dest, None) is not None]
    if getattr(args, "bush", None) is None:
        if given:
            raise ValueError(f"{', '.join(given)} {'needs' if len(given) == 1 else 'need'} "
                             "--bush ring|solid|liner")
        return None
    radius = args.diameter / 2
    fields = {f: getattr(args, dest) for dest, (_, f) in BUSH_OPTIONS.items()
              if getattr(args, dest) is not None}
    try:
        bush = ElasticBush(model=args.bush, **fields)
    except ValueError as err:
        # ElasticBush names its field: name the option as typed
        text = str(err)
        for option, field in BUSH_OPTIONS.values():
            if text.startswith(field):
                text = option + text[len(field):]
        raise ValueError(text) from None
    lo, hi = MODULUS_RANGE
    if bush.modulus < lo:
        # the units that bring the number into the range: 110 is GPa (or MPa), 5e4 MPa alone
        units = [f"{u}? ({bush.modulus:g} {u} = {bush.modulus * f:g} Pa)"
                 for u, f in (("GPa", 1e9), ("MPa", 1e6)) if lo <= bush.modulus * f <= hi]
        raise ValueError(f"--bush-modulus {bush.modulus:g} Pa is below any bush material's "
                         f"(>= {lo:.0e} Pa; rubber ~1e6 Pa)"
                         + (f": typed in {' or '.join(units)}" if units else "")
                         + "; a softer solid: the library's ElasticBush takes any positive "
                         "modulus")
    if bush.modulus > hi:
        raise ValueError(f"--bush-modulus {bush.modulus:g} Pa is above any solid's "
                         f"(<= {hi:.1e} Pa, diamond's): give it in Pa")
    if bush.outer_radius is not None and not bush.outer_radius > radius:   # before any work
        raise ValueError(f"--bush-outer-radius must exceed the film radius R = --diameter / 2"
                         f" = {radius:g} m, got {bush.outer_radius:g}")
    # the library's default outer radius, OUTER_RATIO R, resolved here: the header and
    # the table print it
    return bush.at_radius(radius)
