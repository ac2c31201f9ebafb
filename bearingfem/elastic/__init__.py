"""The elastic bush of an EHD journal bearing: linear isotropic finite elements (a
plane-strain ring per slice, the 3-D solid per circumferential harmonic, or by 3-D
hexahedra) and the circulant compliance of the film surface they give."""
from .bush import ElasticBush
from .compliance import BushCompliance, ReducedCompliance, bush_compliance
from .field import BushField, bush_field

__all__ = ["ElasticBush", "BushCompliance", "ReducedCompliance", "bush_compliance",
           "BushField", "bush_field"]
