"""bearingfem: verified hydrodynamic journal-bearing films.

film -> mesh -> assembly -> cavitation solve -> forces, with a finite-volume reference and
the closed-form short (Frene) and long (Pinkus-Sternlicht) bearing models; every model
registered by name in :mod:`bearingfem.models`, every film solved through the route
table of :mod:`bearingfem.routes`; the designer's numbers (equilibrium,
stiffness and damping, stability) in :mod:`bearingfem.design`.
"""
from .bearing import Bearing, ElasticJournalState, Groove, JournalState
from .caches import clear_caches  # empties every cache of the library (cold timings)
from .contact import Roughness  # Greenwood-Tripp asperity contact (mixed lubrication)
from .contact import FlowFactors  # Patir & Cheng's flow of a rough gap
from .closed.long_bearing import long_bearing_exact_force, long_bearing_force
from .closed.short_bearing import short_bearing_exact_force, short_bearing_force
from .design import coefficients, equilibrium
from .elastic import ElasticBush
from .errors import ConvergenceError, LoadCapacityError
from .reynolds import fvm_reynolds, solve_reynolds
from .lubricant import Lubricant
from .ehl import line_contact, point_contact
from .solution import FilmSolution
from .thermal import Thermal

__all__ = ["Bearing", "JournalState", "ElasticJournalState", "Groove", "solve_reynolds", "fvm_reynolds", "FilmSolution",
           "short_bearing_force", "long_bearing_force", "short_bearing_exact_force",
           "long_bearing_exact_force", "equilibrium", "coefficients", "ElasticBush",
           "Lubricant", "line_contact", "point_contact", "ConvergenceError", "Roughness",
           "FlowFactors", "clear_caches", "Thermal", "LoadCapacityError"]
from .version import __version__  # noqa: F401  (the package version)
