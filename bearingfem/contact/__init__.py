"""Contact between the rough surfaces where the film is thin (mixed lubrication)."""
from .asperity import AsperityContact, Roughness, asperity_contact, elastic_factor
from .flow_factors import FlowFactors
from .gaussian import tail_moment, tail_moment_derivative

__all__ = ["Roughness", "AsperityContact", "asperity_contact", "elastic_factor",
           "tail_moment", "tail_moment_derivative", "FlowFactors"]
