"""The elastohydrodynamic film of the mechanism ("fem-ehd"): a pressure-dependent oil, an
elastic bush and the summits' contact, with Reynolds' condition or the JFO film; along a
run its bush held between film steps ("kept"), moved along its tangent ("tangent") or its
modes integrated with the journal ("states")."""
from __future__ import annotations

from ..bearing import ELASTIC_EPS_CAP
from ..ehd.implicit import ImplicitStepEHD
from ..ehd.jfo_run import TransientEHDJFO
from ..ehd.states import FullStateEHD, ModalStateEHD
from ..ehd.tangent import TangentEHD
from ..ehd.transient import TransientEHD, ehd_compliance, ehd_solution
from ..elastic import ElasticBush
from ..fields import EdgeProfile
from ..lubricant import Lubricant
from ..reynolds import solve_reynolds
from .jfo import JFO_AMBIENT
from .registry import FilmModel, register

__all__ = ["EHDModel", "ehd_model_solution", "ehd_jfo_solution", "ehd_run_film"]

#: Bush relaxation time's range [s] (Kelvin-Voigt, for coupling "states" and "implicit").
RELAXATION = (1e-12, 1.0)


def ehd_jfo_solution(bearing, state, lubricant, bush, roughness, n_theta: int, n_z: int,
                     modes: int, profile=None):
    """The steady EHD-JFO film of "fem-ehd" with ``cavitation="jfo"`` (whole length, oil
    around it at :data:`~bearingfem.models.jfo.JFO_AMBIENT`; ``profile`` a bush edge
    profile or None)."""
    comp = None if bush is None else ehd_compliance(bush, bearing.radius, bearing.length,
                                                     n_theta, n_z, modes)
    return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", half=False,
                          lubricant=lubricant, bush=comp, roughness=roughness,
                          ambient_pressure=JFO_AMBIENT, profile=profile)


def ehd_model_solution(bearing, state, lubricant, bush, roughness, n_theta: int, n_z: int,
                       modes: int, film_step: float = 0.0, cavitation: str = "reynolds",
                       coupling: str = "kept", relaxation: float = 1e-5, profile=None):
    """The "fem-ehd" model's steady film for its ``cavitation`` (a cold full solve;
    ``film_step``, ``coupling`` and ``relaxation`` are for time integration only;
    ``profile`` a bush edge profile, :class:`~bearingfem.fields.EdgeProfile`, or None)."""
    if profile is not None:
        profile.check(bearing)
    if cavitation == "jfo":
        return ehd_jfo_solution(bearing, state, lubricant, bush, roughness, n_theta, n_z, modes,
                                profile)
    return ehd_solution(bearing, state, lubricant, bush, roughness, n_theta, n_z, modes,
                        profile=profile)


def ehd_run_film(bearing, lubricant=None, bush=None, roughness=None, n_theta: int = 48,
                 n_z: int = 8, modes: int = 0, film_step: float = 0.0,
                 cavitation: str = "reynolds", coupling: str = "kept",
                 relaxation: float = 1e-5, profile=None):
    """The "fem-ehd" model's RunFilm for its ``cavitation``: "reynolds" (Swift-Stieber,
    :class:`~bearingfem.ehd.transient.TransientEHD`, or with ``coupling`` "tangent"
    :class:`~bearingfem.ehd.tangent.TangentEHD`) or "jfo" (:class:`TransientEHDJFO`, oil
    around the film at 1e5 Pa); ``coupling`` "states": the bush's modes integrated with
    the journal (:class:`~bearingfem.ehd.states.ModalStateEHD`, Reynolds' condition, a
    bush, ``relaxation`` [s] its Kelvin-Voigt time; ``modes`` 0: the whole deflection on
    the bush's grid, no truncation, :class:`~bearingfem.ehd.states.FullStateEHD`);
    ``coupling`` "implicit": the whole deflection advanced by the film's own backward-Euler
    step between accepted steps (:class:`~bearingfem.ehd.implicit.ImplicitStepEHD`, modes
    0, no dense matrix). ``profile``: a bush edge profile
    (:class:`~bearingfem.fields.EdgeProfile`) in the gap of the Reynolds-condition films;
    the transient EHD-JFO film takes none."""
    if profile is not None:
        profile.check(bearing)
    if coupling == "implicit":
        if cavitation != "reynolds":
            raise ValueError(f"coupling 'implicit' takes cavitation 'reynolds', got "
                             f"{cavitation!r}")
        if modes:
            raise ValueError(f"coupling 'implicit' takes the full compliance (modes 0), got "
                             f"modes {modes!r}")
        return ImplicitStepEHD(bearing, lubricant, bush, n_theta, n_z, relaxation, roughness,
                               profile)
    if coupling == "states":
        if cavitation != "reynolds":
            raise ValueError(f"coupling 'states' takes cavitation 'reynolds', got {cavitation!r}")
        if not modes:       # the full compliance: the whole deflection integrated
            return FullStateEHD(bearing, lubricant, bush, n_theta, n_z, relaxation, roughness,
                                profile)
        return ModalStateEHD(bearing, lubricant, bush, n_theta, n_z, modes, relaxation,
                             roughness, profile)
    o = dict(lubricant=lubricant, bush=bush, roughness=roughness, n_theta=n_theta, n_z=n_z,
             modes=modes, film_step=film_step)
    if cavitation == "jfo":
        if coupling == "tangent":
            raise ValueError("coupling 'tangent' takes cavitation 'reynolds', got 'jfo'")
        if profile is not None:
            # its kept film's volumes and content are those of the bore without one
            raise ValueError("profile takes cavitation 'reynolds' along a run (the "
                             "transient EHD-JFO film has no edge profile), got 'jfo'")
        return TransientEHDJFO(bearing, **o, ambient_pressure=JFO_AMBIENT)
    return (TangentEHD if coupling == "tangent" else TransientEHD)(bearing, **o,
                                                                   profile=profile)


class EHDModel(FilmModel):
    """Options: ``lubricant`` and ``bush`` objects (or None), ``modes`` the number of
    compliance vectors (0: the full compliance), ``roughness``, the mesh, ``film_step``
    [s], ``cavitation``, ``coupling``, ``relaxation`` [s] and ``profile`` (a bush edge
    profile, :class:`~bearingfem.fields.EdgeProfile`, or None) (:func:`ehd_run_film`)."""

    name = "fem-ehd"
    defaults = dict(n_theta=48, n_z=8, lubricant=None, bush=None, roughness=None, modes=64,
                    film_step=0.0, cavitation="reynolds", coupling="kept", relaxation=1e-5,
                    profile=None)
    rules = {"lubricant": ("instance", (Lubricant,)), "bush": ("instance", (ElasticBush,)),
             "profile": ("instance", (EdgeProfile,)),
             "modes": ("int", (0, None)), "cavitation": ("choice", ("reynolds", "jfo")),
             "coupling": ("choice", ("kept", "tangent", "states", "implicit")),
             "relaxation": ("number", RELAXATION)}
    numeric = True
    memory = True
    beyond_clearance = ELASTIC_EPS_CAP

    def _film_solution(self, bearing, state, **options):
        return ehd_model_solution(bearing, state, **options)

    def _film_force(self, bearing, state, **options):
        """The steady film's force, film plus asperity contact."""
        sol = ehd_model_solution(bearing, state, **options)
        f, c = sol.force_local, sol.asperity_force_local
        return float(f[0] + c[0]), float(f[1] + c[1])

    def _along_run(self, bearing, **options):
        return ehd_run_film(bearing, **options)

    def _mass_conserving(self, options) -> bool:
        return options["cavitation"] == "jfo"


register(EHDModel())
