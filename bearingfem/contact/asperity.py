"""Greenwood-Tripp asperity contact between rough journal and bush (mixed lubrication).

Where the film h falls to a few combined roughnesses sigma, the summits of the two surfaces
touch and carry a nominal pressure (Greenwood & Tripp, Proc. Instn Mech. Engrs 185 (1970)
625, their Eq. 16 with the Gaussian summit heights):

    p_a(h) = K E* F_5/2(h / sigma),   K = (16 sqrt(2) pi / 15) (sigma eta beta)^2 sqrt(sigma / beta)

with E* the contact modulus (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2), eta the summit density
[1/m^2], beta the summit radius [m] and F_5/2 from :mod:`bearingfem.contact.gaussian`.
Coulomb friction with coefficient ``friction`` acts on the asperity pressure.

Forces follow the film's convention (:mod:`bearingfem.film`, bearingfem.fe.kernel): theta
from the maximum film, the surface point at theta has outward journal normal
n = -(cos theta r_hat + sin theta t_hat), and the force on the journal is
F = integral of -p n dA, so (F_r, F_t) = integral of p (cos theta, sin theta) dA. A film
force and an asperity force computed at the same state therefore add.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..bearing import check_finite, check_positive
from ..film import local_to_inertial
from .flow_factors import FlowFactors
from .gaussian import tail_moment, tail_moment_derivative

__all__ = ["Roughness", "AsperityContact", "asperity_contact", "surface_force_local",
           "elastic_factor"]


def elastic_factor(sigma: float, asperity_density: float, asperity_radius: float) -> float:
    """K = (16 sqrt(2) pi / 15) (sigma eta beta)^2 sqrt(sigma / beta) (Greenwood & Tripp
    1970), sigma [m], eta [1/m^2], beta [m]; dimensionless."""
    return (16.0 * math.sqrt(2.0) * math.pi / 15.0
            * (sigma * asperity_density * asperity_radius) ** 2
            * math.sqrt(sigma / asperity_radius))


@dataclass(frozen=True)
class Roughness:
    """Rough surfaces in Greenwood-Tripp contact.

    Parameters
    ----------
    sigma : combined roughness sqrt(sigma1^2 + sigma2^2) [m], > 0
    contact_modulus : E* [Pa], 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, > 0
    elastic_factor : K [-], > 0; or give instead
    asperity_density : eta [1/m^2], > 0, and
    asperity_radius : beta [m], > 0 (then K follows from Greenwood & Tripp's formula)
    friction : asperity (boundary) friction coefficient [-], >= 0
    flow : :class:`~bearingfem.contact.FlowFactors` or None: the film's flow through the
        rough gap by Patir & Cheng's average flow model (None: the smooth film's flow)
    """

    sigma: float
    contact_modulus: float
    elastic_factor: float | None = None
    asperity_density: float | None = None
    asperity_radius: float | None = None
    friction: float = 0.0
    flow: FlowFactors | None = None

    def __post_init__(self):
        check_positive("sigma", self.sigma)
        check_positive("contact_modulus", self.contact_modulus)
        summits = (self.asperity_density is not None, self.asperity_radius is not None)
        if self.elastic_factor is not None:
            if any(summits):
                raise ValueError("give elastic_factor or (asperity_density, asperity_radius), "
                                 "not both")
            check_positive("elastic_factor", self.elastic_factor)
        elif not all(summits):
            raise ValueError("give elastic_factor (K > 0) or both asperity_density "
                             "(eta > 0, 1/m^2) and asperity_radius (beta > 0, m)")
        else:
            check_positive("asperity_density", self.asperity_density)
            check_positive("asperity_radius", self.asperity_radius)
        v = check_finite("friction", self.friction)
        if v < 0.0:
            raise ValueError(f"friction must be >= 0, got {self.friction!r}")
        if self.flow is not None and not isinstance(self.flow, FlowFactors):
            raise ValueError(f"flow must be a bearingfem.FlowFactors or None, got "
                             f"{type(self.flow).__name__}")

    @property
    def factor(self) -> float:
        """K [-], given or from (sigma, eta, beta)."""
        if self.elastic_factor is not None:
            return float(self.elastic_factor)
        return elastic_factor(self.sigma, self.asperity_density, self.asperity_radius)

    def pressure(self, gap) -> np.ndarray:
        """Nominal asperity pressure p_a = K E* F_5/2(h/sigma) [Pa] at gaps h [m].
        h < 0 (mean planes overlapping) is allowed: p_a grows like K E* (-h/sigma)^5/2."""
        gap = np.asarray(gap, dtype=float)
        return self.factor * self.contact_modulus * tail_moment(gap / self.sigma, 2.5)

    def pressure_derivative(self, gap) -> np.ndarray:
        """dp_a/dh = -(5/2) K E* F_3/2(h/sigma) / sigma [Pa/m], for Newton on the gap."""
        gap = np.asarray(gap, dtype=float)
        return (self.factor * self.contact_modulus / self.sigma
                * tail_moment_derivative(gap / self.sigma, 2.5))


@dataclass(frozen=True)
class AsperityContact:
    """Asperity contact integrated over the journal surface.

    Attributes
    ----------
    pressure : p_a at the given points [Pa]
    load : integral of p_a dA, the total normal load the summits carry [N] (a scalar: it
        is the load, not the net force, so a uniform gap has a load and no force)
    force_local : (F_r, F_t) [N], the asperity force on the journal, the film's convention
    force : (F_x, F_y) [N], inertial
    friction_force : friction * load * sign(omega) [N], on the journal surface, opposing
        positive omega like the film's ``friction_force``; 0 when omega = 0 (no sliding)
    friction_torque : friction_force * R [N m]
    """

    pressure: np.ndarray
    load: float
    force_local: tuple
    force: tuple
    friction_force: float
    friction_torque: float


def surface_force_local(pressure, area, theta) -> tuple:
    """(F_r, F_t) = sum of p (cos theta, sin theta) dA [N]: a normal pressure [Pa] at film
    angles theta [rad] over area weights dA [m^2] on the journal, the force on the journal
    in the line-of-centres frame (the same integral bearingfem.fe.kernel takes)."""
    pa = np.asarray(pressure, dtype=float) * np.asarray(area, dtype=float)
    return float(np.sum(pa * np.cos(theta))), float(np.sum(pa * np.sin(theta)))


def asperity_contact(roughness: Roughness, gap, area, theta, *, radius: float,
                     gamma: float = 0.0, omega: float = 0.0) -> AsperityContact:
    """Asperity pressure, force and friction from a gap field.

    Parameters
    ----------
    roughness : :class:`Roughness`
    gap : film thickness h [m] at the integration points (nodes or quadrature points),
        e.g. c (1 + eps cos theta) plus any elastic deflection
    area : journal-surface area [m^2] each point stands for (quadrature weight times
        Jacobian, R^2 dtheta dzeta for the film mesh; double it on a half mesh)
    theta : film angle of each point [rad], from the maximum film (bearingfem.film)
    radius : journal radius R [m], the lever arm of the friction torque
    gamma : attitude angle [rad] that turns the local force into the inertial frame
    omega : journal speed relative to the bush [rad/s]; only its sign enters (Coulomb)
    """
    if not isinstance(roughness, Roughness):
        raise ValueError(f"roughness must be a bearingfem.Roughness, got "
                         f"{type(roughness).__name__}")
    radius = check_positive("radius", radius)
    gamma = check_finite("gamma", gamma)
    omega = check_finite("omega", omega)
    gap, area, theta = (np.asarray(a, dtype=float) for a in (gap, area, theta))
    if not (gap.shape == area.shape == theta.shape):
        raise ValueError(f"gap, area and theta must have one shape, got {gap.shape}, "
                         f"{area.shape}, {theta.shape}")
    if not (np.all(np.isfinite(gap)) and np.all(np.isfinite(area))
            and np.all(np.isfinite(theta))):
        raise ValueError("gap, area and theta must be finite")
    if np.any(area < 0.0):
        raise ValueError("area weights must be >= 0")
    p = roughness.pressure(gap)
    load = float(np.sum(p * area))
    f_r, f_t = surface_force_local(p, area, theta)
    friction = roughness.friction * load * float(np.sign(omega))
    return AsperityContact(pressure=p, load=load, force_local=(f_r, f_t),
                           force=tuple(map(float, local_to_inertial(f_r, f_t, gamma))),
                           friction_force=friction, friction_torque=friction * radius)
