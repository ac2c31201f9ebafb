"""The elastic bush of an EHD journal bearing: linear isotropic finite elements (a
plane-strain ring per slice or the 3-D solid) and the circulant compliance of the film
surface they give."""
from .bush import ElasticBush
from .compliance import BushCompliance, ReducedCompliance, bush_compliance
from .field import BushField, bush_field

__all__ = ["ElasticBush", "BushCompliance", "ReducedCompliance", "bush_compliance",
           "BushField", "bush_field"]
