"""Thermal films (THD): the film-averaged energy equation coupled to the Reynolds film
through the oil's viscosity against temperature (:mod:`bearingfem.lubricant`)."""
from .spec import Thermal
from .energy import EnergyBalance, EnergySolution, solve_energy
from .coupled import ThermalRecord, solve_thd

__all__ = ["Thermal", "EnergyBalance", "EnergySolution", "solve_energy", "solve_thd",
           "ThermalRecord"]
