"""Thermal films (THD): the film-averaged energy equation (:mod:`.energy`) and what a
thermal film is asked (:class:`Thermal`). The film and the energy equation are coupled
through the oil's viscosity against temperature (:mod:`bearingfem.lubricant`) by the
thermal route, :mod:`bearingfem.routes.thd` (``solve_reynolds(..., thermal=)``). The
bush's heat conduction on its finite-element mesh, coupled to the film when a
:class:`Thermal` has a ``bush`` (:class:`BushConduction`): :mod:`.bush`."""
from .spec import BushConduction, Thermal, ThermalRecord
from .energy import EnergyBalance, EnergySolution, solve_energy

__all__ = ["Thermal", "BushConduction", "EnergyBalance", "EnergySolution", "solve_energy",
           "ThermalRecord"]
