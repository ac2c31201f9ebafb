"""bearingfem: verified hydrodynamic journal-bearing films.

film -> mesh -> assembly -> cavitation solve -> forces, with a finite-volume reference and
the closed-form short (Frene) and long (Pinkus-Sternlicht) bearing models; every model
registered by name in :mod:`bearingfem.models`; the designer's numbers (equilibrium,
stiffness and damping, stability) in :mod:`bearingfem.design`.
"""
from .bearing import Bearing, ElasticJournalState, Groove, JournalState
from .contact import Roughness  # Greenwood-Tripp asperity contact (mixed lubrication)
from .closed.long_bearing import long_bearing_exact_force, long_bearing_force
from .closed.short_bearing import short_bearing_exact_force, short_bearing_force
from .design import coefficients, equilibrium
from .elastic import ElasticBush
from .errors import ConvergenceError
from .fe.reynolds import solve_reynolds
from .fv.fvm import fvm_reynolds
from .lubricant import Lubricant
from .ehl import line_contact, point_contact
from .solution import FilmSolution
from .thermal import Thermal  # thermal (THD) films

__all__ = ["Bearing", "JournalState", "ElasticJournalState", "Groove", "solve_reynolds", "fvm_reynolds", "FilmSolution",
           "short_bearing_force", "long_bearing_force", "short_bearing_exact_force",
           "long_bearing_exact_force", "equilibrium", "coefficients", "ElasticBush",
           "Lubricant", "line_contact", "point_contact", "ConvergenceError", "Roughness",
           "Thermal"]
__version__ = "0.1.0"
