"""Elastohydrodynamic (EHL) contacts: the half-space, the line and the point contact."""
from .contact import LineContact, line_contact
from .pointcontact import PointContact, point_contact

__all__ = ["LineContact", "line_contact", "PointContact", "point_contact"]
