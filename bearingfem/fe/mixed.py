"""Asperity contact on the film mesh: the mixed-lubrication part of a film solve.

In Greenwood & Tripp's model (Greenwood & Tripp, Proc. Instn Mech. Engrs 185 (1970) 625)
the summits carry a nominal pressure p_a(h) that depends on the local gap alone, and the
oil film's Reynolds equation is unchanged by it. So the contact is a quadrature of p_a
over the journal surface at the film mesh's quadrature points (the same rule the film's
force integral uses), added to the film's force: the load is carried by film and
asperities together. The roughness changes the film's flow only where it has flow
factors (``Roughness.flow``, Patir & Cheng's average flow model): :func:`film_flow` gives
their coefficient fields to the film's Reynolds form.

The rigid cylinder's gap h = c (1 + eps cos theta) makes the contact force a function of
eps alone (gamma only turns it), with the exact partial

    d(F_r, F_t)/d eps = int dp_a/dh c cos(theta) (cos theta, sin theta) dA,
    dp_a/dh = -(5/2) K E* F_3/2(h/sigma) / sigma,

and no partial in eps_dot or the wedge speed (the summits' pressure has no rate term).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..bearing import Bearing, JournalState
from ..contact.asperity import AsperityContact, Roughness, asperity_contact
from ..contact.flow_factors import FLOW_FLOOR, FlowFields, flow_fields
from ..film import film_thickness
from ..scales import half_film_factor
from .assembly import FilmOperator

__all__ = ["check_roughness", "film_contact", "contact_partial_eps", "with_contact",
           "film_flow", "refuse_rough_flow", "friction_fields"]


def check_roughness(roughness) -> Roughness | None:
    """``roughness`` if it is None or a :class:`~bearingfem.contact.Roughness`; else
    ValueError naming it."""
    if roughness is not None and not isinstance(roughness, Roughness):
        raise ValueError(f"roughness must be a bearingfem.Roughness or None, got "
                         f"{type(roughness).__name__}")
    return roughness


def friction_fields(fields, roughness: Roughness | None, clearance: float):
    """The fields whose gap the film's friction takes: with a rough gap's flow the
    nominal gap floored at FLOW_FLOOR sigma (it may be <= 0 where the surfaces are pressed
    through; Patir & Cheng's shear stress factors are not modelled), else ``fields``."""
    if roughness is None or roughness.flow is None:
        return fields
    return replace(fields, gap=np.maximum(fields.gap, FLOW_FLOOR * roughness.sigma / clearance))


def refuse_rough_flow(roughness, film: str) -> None:
    """ValueError naming ``roughness.flow`` when it is given to the film ``film``, which
    solves the smooth film's flow."""
    if roughness is not None and roughness.flow is not None:
        raise ValueError(f"roughness.flow (Patir & Cheng's flow factors) is not taken by "
                         f"the {film}: give roughness without flow (the smooth film's "
                         f"flow) or solve the rigid film (solve_reynolds, model 'fem')")


def _surface(bearing: Bearing, op: FilmOperator):
    """Journal-surface area [m^2] of each quadrature point: R^2 dtheta dzeta, doubled on a
    half mesh (the mirrored half presses the same)."""
    return bearing.radius ** 2 * half_film_factor(op.mesh.half) * op.qp_weight


def film_contact(bearing: Bearing, state: JournalState, op: FilmOperator,
                 roughness: Roughness, gap: np.ndarray | None = None) -> AsperityContact:
    """The asperity contact of the film on ``op``: ``gap`` is H = h/c at its quadrature
    points (elements x points), None for the rigid cylinder 1 + eps cos(theta)."""
    H = film_thickness(op.qp_theta, state.eps) if gap is None else gap
    return asperity_contact(roughness, bearing.clearance * H, _surface(bearing, op),
                            op.qp_theta, radius=bearing.radius, gamma=state.gamma,
                            omega=state.omega)


def contact_partial_eps(bearing: Bearing, state: JournalState, op: FilmOperator,
                        roughness: Roughness) -> tuple:
    """d(F_r, F_t)/d eps [N] of the rigid cylinder's asperity force on ``op`` (exact for
    the quadrature, see the module docstring)."""
    c, th = bearing.clearance, op.qp_theta
    dp = roughness.pressure_derivative(film_thickness(th, state.eps, c)) * c * np.cos(th)
    dA = _surface(bearing, op)
    return float(np.sum(dp * dA * np.cos(th))), float(np.sum(dp * dA * np.sin(th)))


def film_flow(bearing: Bearing, state: JournalState, roughness: Roughness | None,
              gap: np.ndarray) -> FlowFields | None:
    """The rough gap's coefficient fields on the nominal gap ``gap`` (H = h/c at the film's
    points) by ``roughness.flow`` (Patir & Cheng), or None for a smooth film's flow (no
    roughness, or roughness without flow factors)."""
    if roughness is None or roughness.flow is None:
        return None
    return flow_fields(roughness.flow, gap, roughness.sigma / bearing.clearance, state.omega)


def with_contact(solution, contact: AsperityContact):
    """The film solution with the asperity contact's force and friction torque added as
    their own fields (the film's force and friction stay the film's)."""
    return replace(solution, asperity_force=contact.force,
                   asperity_force_local=contact.force_local,
                   asperity_friction_torque=contact.friction_torque)
