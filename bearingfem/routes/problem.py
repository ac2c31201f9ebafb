"""What a film solve is asked: one frozen record, checked once, before any work.

:func:`film_problem` checks what every route shares (bearing and state, mesh sizes,
cavitation, grooves and supply, tilt, fields, roughness); the route that the record's
:attr:`FilmProblem.kind` names checks the rest (:mod:`bearingfem.routes`).
"""
from __future__ import annotations

from dataclasses import dataclass, fields as dataclass_fields

from ..bearing import Bearing, JournalState, check_inside_clearance, check_surface_speed
from ..contact import Roughness
from ..fe.mesh import ELEMENTS, check_grading
from ..fe.mixed import check_roughness
from ..fields import EdgeProfile, FilmFields, check_tilt
from ..lubricant import Lubricant
from ..validation import check_film_solve, check_grooves, check_jfo_supply

__all__ = ["FilmProblem", "film_problem", "OPTION_DEFAULTS", "SHEAR"]

#: Couette shear in a cavity: over the whole gap ("full") or none ("none").
SHEAR = ("full", "none")


@dataclass(frozen=True)
class FilmProblem:
    """A film to solve: the bearing and journal state, the mesh, the cavitation model and
    the physics options (SI units; the names and meanings of
    :func:`bearingfem.solve_reynolds`'s keywords).

    ``discretisation`` is "fe" (finite elements, :mod:`bearingfem.fe`) or "fv" (finite
    volumes, :mod:`bearingfem.fv`).
    """

    bearing: Bearing
    state: JournalState
    n_theta: int = 120
    n_z: int = 20
    element: str = "P1"
    cavitation: str = "reynolds"
    method: str = "active-set"
    supply_angle: float | None = None
    half: bool = True
    tol: float = 1e-10
    cavitated_shear: str = "full"
    grooves: tuple = ()
    ambient_pressure: float = 0.0
    fields: FilmFields | None = None
    tilt: tuple = (0.0, 0.0)
    tilt_rate: tuple = (0.0, 0.0)
    profile: EdgeProfile | None = None
    lubricant: Lubricant | None = None
    bush: object = None
    roughness: Roughness | None = None
    start: object = None
    grading: tuple | None = None
    thermal: object = None
    discretisation: str = "fe"

    # -- what the problem is (each decided here, once) ------------------------------------
    @property
    def mass_conserving(self) -> bool:
        """The JFO film (its fraction is a field of the solve)."""
        return self.cavitation == "jfo"

    @property
    def compressible(self) -> bool:
        """The compressible (Elrod-type) JFO film: cavitation "jfo", a lubricant with a
        ``bulk_modulus`` and no bush."""
        return (self.mass_conserving and self.bush is None and self.lubricant is not None
                and self.lubricant.bulk_modulus is not None)

    @property
    def elastic(self) -> bool:
        """The EHD film: a pressure-dependent oil or an elastic bush (solved by Newton)."""
        return not self.compressible and (self.lubricant is not None or self.bush is not None)

    @property
    def tilted(self) -> bool:
        return any(self.tilt) or any(self.tilt_rate)

    @property
    def general(self) -> bool:
        """The film on general fields (gap, viscosity, density): fields, a tilt, a bush edge
        profile, a rough gap's flow or the EHD film. Its whole length is meshed (no mid-plane symmetry)."""
        return (self.fields is not None or self.tilted or self.profile is not None
                or self.elastic or self.rough_flow)

    @property
    def rough_flow(self) -> bool:
        """The film's flow through a rough gap (``roughness.flow``, Patir & Cheng)."""
        return self.roughness is not None and self.roughness.flow is not None

    @property
    def kind(self) -> str:
        """The route's name in :data:`bearingfem.routes.ROUTES`."""
        if self.discretisation == "fv":
            return "fv"
        if self.thermal is not None:
            return "thd"
        if self.mass_conserving:
            if self.compressible:
                return "jfo-compressible"
            if self.elastic:
                return "ehd-jfo"
            if self.grooves and self.half and not self.general and self.roughness is None:
                return "jfo-grooved"
            return "jfo"
        if self.elastic:
            return "ehd"
        if self.general:
            return "general"
        if self.grooves and self.half and self.supply_angle is None:
            return "grooved"
        return "rigid"

    def given(self) -> tuple:
        """The names of the options set away from their defaults (what a route must use)."""
        return tuple(f.name for f in dataclass_fields(self)
                     if f.name in OPTION_DEFAULTS and _differs(getattr(self, f.name),
                                                               OPTION_DEFAULTS[f.name]))


def _differs(value, default) -> bool:
    if value is default:
        return False
    try:
        return bool(value != default)
    except (TypeError, ValueError):     # arrays and objects: anything given counts
        return True


#: The options of a film solve with their defaults (the route-independent arguments,
#: bearing, state, n_theta, n_z and cavitation, are not options).
OPTION_DEFAULTS = {f.name: f.default for f in dataclass_fields(FilmProblem)
                   if f.name not in ("bearing", "state", "n_theta", "n_z", "cavitation",
                                     "discretisation")}


def film_problem(bearing: Bearing, state: JournalState, n_theta: int = 120, n_z: int = 20,
                 cavitation: str = "reynolds", *, discretisation: str = "fe",
                 **options) -> FilmProblem:
    """The checked :class:`FilmProblem` (ValueError naming the parameter, before any
    work): what every route shares is checked here, the rest by the route."""
    if discretisation not in ("fe", "fv"):
        raise ValueError(f"discretisation must be 'fe' or 'fv', got {discretisation!r}")
    unknown = sorted(set(options) - set(OPTION_DEFAULTS))
    if unknown:
        raise ValueError(f"{', '.join(unknown)}: not an option of a film solve (options: "
                         f"{', '.join(sorted(OPTION_DEFAULTS))})")
    o = {**OPTION_DEFAULTS, **options}
    n_theta, n_z, supply_angle = check_film_solve(
        bearing, state, n_theta, n_z, cavitation, o["method"], o["supply_angle"], o["tol"],
        element=(o["element"], tuple(ELEMENTS)), cavitated_shear=(o["cavitated_shear"], SHEAR))
    grooves = check_grooves(o["grooves"], supply_angle, mass_conserving=cavitation == "jfo")
    ambient = check_jfo_supply(cavitation, grooves, supply_angle, o["ambient_pressure"],
                               o["element"])
    tilt, tilt_rate = check_tilt("tilt", o["tilt"]), check_tilt("tilt_rate", o["tilt_rate"])
    check_surface_speed(bearing.radius, state.omega, "state.omega")
    if o["bush"] is None:
        check_inside_clearance(state, "a film without a bush")
    if o["fields"] is not None and not isinstance(o["fields"], FilmFields):
        raise ValueError(f"fields must be a FilmFields, got {type(o['fields']).__name__}")
    if o["profile"] is not None:
        if not isinstance(o["profile"], EdgeProfile):
            raise ValueError(f"profile must be an EdgeProfile or None, "
                             f"got {type(o['profile']).__name__}")
        o["profile"].check(bearing)
    if o["lubricant"] is not None and not isinstance(o["lubricant"], Lubricant):
        raise ValueError(f"lubricant must be a bearingfem.Lubricant or None, "
                         f"got {type(o['lubricant']).__name__}")
    o.update(supply_angle=supply_angle, grooves=grooves, ambient_pressure=ambient, tilt=tilt,
             tilt_rate=tilt_rate, roughness=check_roughness(o["roughness"]),
             grading=check_grading(o["grading"]))
    return FilmProblem(bearing, state, n_theta, n_z, cavitation=cavitation,
                       discretisation=discretisation, **o)
