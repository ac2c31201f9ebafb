"""The mass-conserving (JFO) films of the mechanism: "fem-jfo" (incompressible) and
"fem-jfo-compressible" (Elrod-type), each steady at a state alone and transient along a
run (its film fraction carried by the flow: :class:`~bearingfem.transient.TransientJFO`)."""
from __future__ import annotations

from ..fe.jfo_balance import JFO_AMBIENT   # the JFO models' default supply [Pa]
from ..lubricant import Lubricant
from ..reynolds import solve_reynolds
from ..transient import TransientJFO
from ..transient_compressible import OIL_BULK_MODULUS, CompressibleTransientJFO
from .registry import FilmModel, register

__all__ = ["JFOModel", "CompressibleJFOModel", "JFO_AMBIENT"]

_MESH = dict(n_theta=48, n_z=8)


class JFOModel(FilmModel):
    """The steady film is steady in the frame of the line of centres; ``film_step`` [s]
    is for time integration only."""

    name = "fem-jfo"
    defaults = dict(_MESH, grooves=(), ambient_pressure=JFO_AMBIENT, film_step=0.0)
    numeric = True
    memory = True

    def _film_solution(self, bearing, state, n_theta, n_z, grooves, ambient_pressure,
                       film_step=0.0):
        return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", grooves=grooves,
                              ambient_pressure=ambient_pressure)

    def _film_force(self, bearing, state, **options):
        return self._film_solution(bearing, state, **options).force_local

    def _along_run(self, bearing, **options):
        return TransientJFO(bearing, **options)

    def _mass_conserving(self, options) -> bool:
        return True


class CompressibleJFOModel(JFOModel):
    """The oil's bulk modulus ``bulk_modulus`` [Pa] (above 1e5 Pa, a gas's: nothing
    below it is an oil)."""

    name = "fem-jfo-compressible"
    defaults = dict(JFOModel.defaults, bulk_modulus=OIL_BULK_MODULUS)
    rules = {"bulk_modulus": ("number", (1e5, None))}

    def _film_solution(self, bearing, state, n_theta, n_z, grooves, ambient_pressure,
                       film_step=0.0, bulk_modulus=OIL_BULK_MODULUS):
        oil = Lubricant(viscosity=bearing.viscosity, bulk_modulus=bulk_modulus)
        return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", grooves=grooves,
                              ambient_pressure=ambient_pressure, lubricant=oil)

    def _along_run(self, bearing, **options):
        return CompressibleTransientJFO(bearing, **options)


register(JFOModel())
register(CompressibleJFOModel())
