"""Elastohydrodynamic (EHL) contacts: the half-space and the line contact."""
from .contact import LineContact, line_contact

__all__ = ["LineContact", "line_contact"]
