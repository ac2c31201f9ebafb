"""The film's fields: gap, its rate, viscosity and density, one owner for every model.

The general dimensionless Reynolds equation (theta from the maximum film of the journal
centre at the mid-plane, zeta = z/R, p = mu0 (R/c)^2 P):

    -div(rho H^3 / mu grad P) = -6 w d(rho H)/dtheta - 12 d(rho H)/dt,

with H = h/c, mu and rho ratios to the reference mu0 (the bearing's viscosity) and rho0,
w = omega - 2 gamma_dot the wedge speed and d/dt at fixed theta (the frame turning with the
line of centres). The rigid cylinder, H = 1 + eps cos(theta), dH/dt = eps_dot cos(theta),
mu = rho = 1, gives back :mod:`bearingfem.film`'s source
6 w eps sin(theta) - 12 eps_dot cos(theta).

A field is given as a number (uniform), a function f(theta, zeta) of the film angle and the
axial coordinate z/R (evaluated at the quadrature points: exact wherever it is evaluated),
an array of nodal values (one per dof of the mesh, interpolated by the elements), or an
array already at the quadrature points. :meth:`FilmFields.on` turns the fields into arrays
at the quadrature points of one film operator, checked: that is what the assembly
(:mod:`bearingfem.fe.general`) takes.

Misalignment (:func:`tilted_gap`) is the first user: a journal whose axis is turned by
(tilt_x, tilt_y) about the inertial x and y axes through the bearing centre has its centre
at (e_x + z tilt_y, e_y - z tilt_x) at the axial position z, so its gap gains a part linear
in z.

A bush edge profile (:class:`EdgeProfile`, a crown or a chamfer of the bush bore) is the
second: a gap h_p(z) >= 0 fixed to the bush and even in z, which relieves the edge load
of a short, heavily loaded bush (whose sharp edge would carry the least film).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .bearing import check_finite
from .film import film_thickness

__all__ = ["FilmFields", "EdgeProfile", "PROFILE_KINDS", "tilted_gap", "check_tilt"]

#: The edge profiles of :class:`EdgeProfile`.
PROFILE_KINDS = ("crown", "chamfer")

FIELD_NAMES = ("gap", "gap_rate", "viscosity", "density", "density_rate")


@dataclass(frozen=True, eq=False)
class FilmFields:
    """The fields of one film (dimensionless; see the module docstring for the forms a
    field may take).

    Parameters
    ----------
    gap : H = h/c; None is the rigid cylinder 1 + eps cos(theta) of the solved state
    gap_rate : dH/dt at fixed theta [1/s]; None is the rigid eps_dot cos(theta)
    viscosity : mu/mu0 (> 0), default 1
    density : rho/rho0 (> 0), default 1
    density_rate : d(rho/rho0)/dt at fixed theta [1/s], default 0
    """

    gap: object = None
    gap_rate: object = None
    viscosity: object = 1.0
    density: object = 1.0
    density_rate: object = 0.0

    def on(self, op, state) -> "FilmFields":
        """These fields as arrays at the quadrature points of the film operator ``op``
        (elements x points), the rigid defaults taken from ``state``; raises ValueError
        naming a field that is not finite, or a gap, viscosity or density not > 0."""
        th = op.qp_theta
        gap = film_thickness(th, state.eps) if self.gap is None else self.gap
        rate = state.eps_dot * np.cos(th) if self.gap_rate is None else self.gap_rate
        values = {}
        for name, f in zip(FIELD_NAMES, (gap, rate, self.viscosity, self.density,
                                         self.density_rate)):
            values[name] = _checked(name, _at_quadrature(name, f, op))
        return FilmFields(**values)

    def beyond_clearance(self, op, state) -> "FilmFields":
        """As :meth:`on` for a state beyond the clearance circle (eps >= 1, only a film
        with a bush: its deflection opens the gap): the rigid gap 1 + eps cos(theta) is
        then negative on an arc and is not checked; the other fields are. Given gaps are
        refused (a bush film at eps >= 1 takes the state's own gap)."""
        if self.gap is not None:
            raise ValueError("a film beyond the clearance circle (eps >= 1) takes the "
                             "state's rigid gap: give no gap field")
        checked = replace(self, gap=np.ones_like(op.qp_theta)).on(op, state)
        return replace(checked, gap=film_thickness(op.qp_theta, state.eps))

    def nodal_gap(self, op, state) -> np.ndarray:
        """H at the dofs of ``op``'s mesh (a quadrature-point gap is projected, L2)."""
        th, ze = op.mesh.theta, op.mesh.zeta
        g = self.gap
        if g is None:
            return film_thickness(th, state.eps)
        if callable(g):
            return np.broadcast_to(np.asarray(g(th, ze), dtype=float), th.shape).copy()
        g = np.asarray(g, dtype=float)
        if g.ndim == 2:
            return np.asarray(op.mesh.basis.project(g))
        return np.broadcast_to(g, th.shape).copy()

    def is_rigid(self, op, state) -> bool:
        """True when these (evaluated) fields are the rigid cylinder's of ``state`` to
        round-off: then the film's fast path solves the same problem."""
        th = op.qp_theta
        return bool(np.allclose(self.gap, film_thickness(th, state.eps), rtol=0.0, atol=1e-14)
                    and np.allclose(self.gap_rate, state.eps_dot * np.cos(th), rtol=0.0,
                                    atol=1e-14 * max(1.0, abs(state.eps_dot)))
                    and np.all(self.viscosity == 1.0) and np.all(self.density == 1.0)
                    and not np.any(self.density_rate))

    def at_points(self, op, state, theta, zeta, interpolation) -> "FilmFields":
        """These fields as arrays at any points (theta, zeta) of ``op``'s film (the control
        volumes' quadrature of the JFO balance): a function is evaluated there, nodal
        values are interpolated by ``interpolation`` (sparse, points x dofs, the points
        flattened), values at the element quadrature points are first carried to the
        nodes (:func:`to_nodes`). Checked as :meth:`on`."""
        theta, zeta = np.asarray(theta, float), np.asarray(zeta, float)
        gap = ((lambda t, z: film_thickness(t, state.eps)) if self.gap is None
               else self.gap)
        rate = ((lambda t, z: state.eps_dot * np.cos(t)) if self.gap_rate is None
                else self.gap_rate)
        values = {}
        for name, f in zip(FIELD_NAMES, (gap, rate, self.viscosity, self.density,
                                         self.density_rate)):
            values[name] = _checked(name, _at_points(name, f, op, theta, zeta,
                                                     interpolation))
        return FilmFields(**values)

    def plus(self, **extra) -> "FilmFields":
        """Evaluated fields with arrays added to some of them (e.g. a tilt's gap)."""
        return replace(self, **{k: getattr(self, k) + v for k, v in extra.items()})


def _at_quadrature(name: str, f, op) -> np.ndarray:
    shape = op.qp_theta.shape
    if callable(f):
        v = np.asarray(f(op.qp_theta, op.qp_zeta), dtype=float)
        try:    # numpy's own "could not be broadcast ... remapped shapes" named nothing
            return np.broadcast_to(v, shape).astype(float)
        except ValueError:
            raise ValueError(f"film field {name}: its function of (theta, zeta) must "
                             f"return a number or an array that broadcasts to their shape "
                             f"{shape} (e.g. one value per element, ({shape[0]}, 1)), got "
                             f"shape {v.shape}") from None
    else:
        v = np.asarray(f, dtype=float)
        if v.ndim == 1 and v.shape[0] == op.mesh.ndofs:     # nodal values
            v = op.at_quadrature(v)
        elif v.ndim not in (0, 2) or (v.ndim == 2 and v.shape != shape):
            raise ValueError(f"film field {name} must be a number, a function of (theta, "
                             f"zeta), {op.mesh.ndofs} nodal values or an array of shape "
                             f"{shape}, got shape {v.shape}")
    return np.broadcast_to(v, shape).astype(float)


def _checked(name: str, v: np.ndarray) -> np.ndarray:
    if not np.all(np.isfinite(v)):
        raise ValueError(f"film field {name} must be finite everywhere")
    if name in ("gap", "viscosity", "density") and not np.all(v > 0.0):
        raise ValueError(f"film field {name} must be > 0 everywhere, "
                         f"min {float(np.min(v))!r}")
    return v


def _at_points(name: str, f, op, theta: np.ndarray, zeta: np.ndarray,
               interpolation) -> np.ndarray:
    if callable(f):
        v = np.asarray(f(theta, zeta), dtype=float)
    else:
        v = np.asarray(f, dtype=float)
        if v.ndim == 2 and v.shape == op.qp_theta.shape:   # at the element quadrature
            v = to_nodes(name, op.mesh.basis, v)
        elif not (v.ndim == 0 or (v.ndim == 1 and v.shape[0] == op.mesh.ndofs)):
            _at_quadrature(name, f, op)                     # raises, naming the field
        if v.ndim == 1:
            v = (interpolation @ v).reshape(theta.shape)
    return np.broadcast_to(v, np.broadcast(theta, zeta).shape).astype(float)


def nodal_average(basis, v: np.ndarray) -> np.ndarray:
    """Values ``v`` at ``basis``'s quadrature points (elements x points) carried to its
    nodes by the lumped-mass projection, v_i = int phi_i v / int phi_i: with P1's
    non-negative shape functions each nodal value is a weighted mean of the point values,
    so a positive field stays positive and within its bounds. Why not the L2 projection:
    it overshoots where the field changes steeply within a cell (a thermal film's
    viscosity at eps 0.97 projected to negative nodal values); the mean is exact for
    constants and first order elsewhere (second at the interior nodes of a uniform mesh)."""
    phi = np.array([np.asarray(basis.basis[i][0]) for i in range(basis.Nbfun)])
    dofs = basis.element_dofs
    w = phi * np.asarray(basis.dx)
    num = np.bincount(dofs.ravel(), np.sum(w * np.asarray(v), axis=2).ravel(),
                      minlength=basis.N)
    den = np.bincount(dofs.ravel(), np.sum(w, axis=2).ravel(), minlength=basis.N)
    return num / den


def to_nodes(name: str, basis, v: np.ndarray) -> np.ndarray:
    """The field ``name``'s values at ``basis``'s quadrature points carried to its nodes:
    the viscosity by :func:`nodal_average` (it must stay positive, and a thermal film's
    steep one overshoots under the L2 projection), the others (gap, density, rates: the
    JFO films' content) by the second-order L2 projection."""
    if name == "viscosity":
        return nodal_average(basis, v)
    return np.asarray(basis.project(v))


def check_tilt(name: str, tilt) -> tuple:
    """(x, y) as two finite floats, or ValueError naming ``name``."""
    try:
        tx, ty = tilt
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (about x, about y) [rad], got {tilt!r}") \
            from None
    return check_finite(f"{name}[0]", tx), check_finite(f"{name}[1]", ty)


def tilted_gap(bearing, state, theta, zeta, tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0)):
    """(dH, dH/dt) [-, 1/s]: what a tilted journal adds to the gap and its rate at the
    film angle theta and zeta = z/R.

    The journal centre at z sits at (e_x + z tilt_y, e_y - z tilt_x); the gap at inertial
    angle alpha is c - e(z) . (cos alpha, sin alpha). With alpha = theta + gamma + pi,
    dH = (R/c) zeta (tilt_y cos(theta + gamma) - tilt_x sin(theta + gamma)). The tilt is
    inertial while theta turns with gamma, so its rate at fixed theta gains
    gamma_dot d(dH)/dtheta.
    """
    tx, ty = tilt
    rx, ry = tilt_rate
    k = bearing.radius / bearing.clearance * np.asarray(zeta)
    a = np.asarray(theta) + state.gamma
    c, s = np.cos(a), np.sin(a)
    dH = k * (ty * c - tx * s)
    dH_dtheta = -k * (ty * s + tx * c)
    return dH, k * (ry * c - rx * s) + state.gamma_dot * dH_dtheta


@dataclass(frozen=True)
class EdgeProfile:
    """A bush edge profile: the gap h_p(z) [m] the bore adds at the axial position z
    (from the mid-plane, |z| <= L/2), fixed to the bush, the same at both ends.

    With a = L/2 - length, where the profile starts, and u = max(0, |z| - a) / length:

    * ``kind="crown"``: h_p = depth u^2, a parabola tangent to the bore at |z| = a; the
      default ``length`` (None: L/2) is the crown of the whole length, depth (2 z / L)^2.
    * ``kind="chamfer"``: h_p = depth u, a straight taper (a conical edge) of axial
      ``length`` and radial ``depth``.

    Parameters
    ----------
    kind : "crown" or "chamfer"
    depth : the extra gap at the bush's ends [m] (>= 0; 0 is the sharp-edged bore)
    length : the axial length of the profile at each end [m], in (0, L/2]; None: L/2
    """

    kind: str = "crown"
    depth: float = 0.0
    length: float | None = None

    def __post_init__(self):
        if self.kind not in PROFILE_KINDS:
            raise ValueError(f"kind must be one of {PROFILE_KINDS}, got {self.kind!r}")
        depth = check_finite("depth", self.depth)
        if depth < 0.0:
            raise ValueError(f"depth must be >= 0 [m], got {self.depth!r}")
        object.__setattr__(self, "depth", depth)
        if self.length is not None:
            length = check_finite("length", self.length)
            if not length > 0.0:
                raise ValueError(f"length must be > 0 [m] (or None: half the bush "
                                 f"length), got {self.length!r}")
            object.__setattr__(self, "length", length)

    def check(self, bearing) -> "EdgeProfile":
        """This profile, or a ValueError naming ``length`` when it exceeds L/2 of
        ``bearing``."""
        if self.length is not None and self.length > 0.5 * bearing.length * (1 + 1e-12):
            raise ValueError(f"length must lie in (0, L/2] = (0, {0.5 * bearing.length!r}] "
                             f"[m], got {self.length!r}")
        return self

    def gap(self, z, bearing_length: float) -> np.ndarray:
        """h_p [m] at the axial positions z [m] of a bush of length ``bearing_length``."""
        half = 0.5 * bearing_length
        length = half if self.length is None else self.length
        u = np.maximum(0.0, np.abs(np.asarray(z, dtype=float)) - (half - length)) / length
        return self.depth * (u * u if self.kind == "crown" else u)

    def film_gap(self, bearing, zeta) -> np.ndarray:
        """dH = h_p / c at zeta = z/R of ``bearing``'s film (dimensionless)."""
        z = bearing.radius * np.asarray(zeta, dtype=float)
        return self.gap(z, bearing.length) / bearing.clearance
