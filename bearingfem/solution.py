"""The result of a film solve: forces, fields and diagnostics, cheap to keep."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .film import film_thickness, inertial_from_theta, local_to_inertial

__all__ = ["FilmSolution", "ForceDerivatives", "film_solution", "undriven"]


@dataclass(frozen=True, eq=False)
class FilmSolution:
    """A solved film (finite element or finite volume).

    Forces act on the journal. Fields are given at the solver's nodes (FE dofs or FV cell
    centres): ``theta`` from the maximum film, ``z`` axial [m]. A half-domain solve stores
    the half z >= 0 only; integrals already cover the whole bearing.

    Attributes
    ----------
    force_local : (F_r, F_t) [N] along r_hat (eccentricity) and t_hat
    force : (F_x, F_y) [N] inertial frame
    pressure : gauge pressure [Pa] at the nodes
    film_thickness : h [m] at the nodes
    pressure_max : [Pa]; pressure_max_theta, pressure_max_z its location
    pressure_max_angle : its inertial angle [rad]
    film_min : minimum film thickness [m]: c (1 - eps) on the rigid cylinder, the least
        nodal gap on a general gap field
    cavitated_fraction : share of the film area at ambient (zero gauge) pressure; 0 for
        a film that nothing drives (:func:`undriven`: no pressure anywhere, no cavity)
    friction_force : shear force on the journal surface opposing positive omega [N]
    friction_torque : friction_force * R [N m]
    side_leakage : volume flow out of both axial ends [m^3/s], net (less what enters there)
    side_outflow : what leaves through the ends alone [m^3/s] (FE films, and FV films
        other than the JFO film; None where not given): a Reynolds-condition film's side leakage (no oil enters at its
        ends), a film fed at its ends (JFO with ``ambient_pressure``) loses this much where
        it is pressurised and draws as much in where it is cavitated (net: zero, steady)
    flow_in : flow fed by grooves or a supply line [m^3/s] (None where not defined)
    fraction : film fraction theta at the nodes (JFO films; 1 in the full film)
    mass_balance : JFO films: flow_in - side_leakage - rate of change of the film content
        [m^3/s], zero to the solver's round-off
    iterations, residual, converged : record of the (cavitation) solve
    moment : (M_x, M_y) [N m], the film's moment on the journal about the bearing centre
        (mid-plane), inertial; zero for an aligned film (mid-plane symmetry)
    radius, gamma : journal radius [m] and attitude angle [rad] of the solved state
    asperity_force : (F_x, F_y) [N], inertial: the Greenwood-Tripp asperity contact force
        on the journal when the solve was given a roughness (:mod:`bearingfem.fe.mixed`),
        (0, 0) otherwise; ``force`` stays the film's, ``total_force`` is their sum
    asperity_force_local : the same in the local frame (F_r, F_t) [N]
    asperity_friction_torque : the summits' Coulomb friction torque [N m], the film's
        convention (opposing positive omega); ``friction_torque`` stays the film's shear
    temperature, temperature_max : a thermal film's nodal temperature and its largest [K]
        (:mod:`bearingfem.thermal`); None for an isothermal film
    thermal : a thermal film's :class:`~bearingfem.thermal.ThermalRecord` (energy
        balance, journal and inlet temperatures, viscosity, iterations)
    force_error : a solve asked for an accuracy (``rtol``): the estimated relative
        discretisation error of the force vector, |F_h - F| / |F| (:mod:`bearingfem.accuracy`);
        None for a solve on a given mesh
    accuracy : the :class:`~bearingfem.accuracy.AccuracyRecord` of how that mesh was chosen
    """

    force_local: tuple
    force: tuple
    # the nodal fields stay out of the repr (thousands of numbers): print(sol) reads as a
    # record, sol.summary() as lines with units
    pressure: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    z: np.ndarray = field(repr=False)
    film_thickness: np.ndarray = field(repr=False)
    pressure_max: float
    pressure_max_theta: float
    pressure_max_z: float
    pressure_max_angle: float
    film_min: float
    cavitated_fraction: float
    friction_force: float
    friction_torque: float
    side_leakage: float
    iterations: int
    residual: float
    converged: bool
    method: str
    cavitation: str
    n_dofs: int
    half: bool
    radius: float             # journal radius R [m]
    gamma: float              # attitude angle of the solved state [rad]
    mesh: object = field(default=None, repr=False)   # FilmMesh (FE) or grid shape (FV)
    flow_in: float | None = None   # flow the supply grooves feed [m^3/s] (None: no groove)
    fraction: np.ndarray | None = field(default=None, repr=False)  # JFO film fraction, [0, 1]
    mass_balance: float | None = None  # JFO: flow_in - side_leakage - d(content)/dt [m^3/s]
    moment: tuple = (0.0, 0.0)    # (M_x, M_y) [N m] on the journal about the bearing centre
    deformation: np.ndarray | None = field(default=None, repr=False)  # bush deflection [m]
    asperity_force: tuple = (0.0, 0.0)         # (F_x, F_y) [N], inertial
    asperity_force_local: tuple = (0.0, 0.0)   # (F_r, F_t) [N]
    asperity_friction_torque: float = 0.0      # [N m]
    density: np.ndarray | None = field(default=None, repr=False)  # compressible JFO: rho/rho0
    temperature: np.ndarray | None = field(default=None, repr=False)  # thermal film: nodal [K]
    temperature_max: float | None = None       # thermal film: the film's hottest node [K]
    thermal: object = field(default=None, repr=False)  # thermal film: its ThermalRecord
    force_error: float | None = None   # estimated relative error of |F| (solves with rtol)
    accuracy: object = field(default=None, repr=False)   # AccuracyRecord (solves with rtol)
    side_outflow: float | None = None  # out of the ends alone [m^3/s] (None: FV JFO)

    @property
    def asperity_load(self) -> float:
        """|asperity force| [N]: what the summits carry (0 without roughness)."""
        return float(np.hypot(*self.asperity_force_local))

    @property
    def total_force(self) -> tuple:
        """(F_x, F_y) [N]: film plus asperity contact, what carries the load."""
        return tuple(float(f + a) for f, a in zip(self.force, self.asperity_force))

    def _outflow_words(self) -> str:
        """', X m^3/s leave alone' where the ends also draw oil in (the outflow differs
        from the net leakage), else nothing."""
        out, net = self.side_outflow, self.side_leakage
        if out is None or abs(out - net) <= 1e-9 * max(abs(out), abs(net)):
            return ""
        return f", {out:.6g} m^3/s leave where the film is above ambient"

    def summary(self) -> str:
        """The solve in a few named lines with units (what ``bearingfem solve`` prints)."""
        fr, ft = self.force_local
        load = float(np.hypot(fr, ft))
        attitude = float(np.degrees(np.arctan2(ft, -fr))) if load else 0.0
        err = "" if self.force_error is None else f" (+- {100 * self.force_error:.2g} %)"
        # a film without pressure (a centred, still journal) has no peak to place
        peak = (f"peak pressure {self.pressure_max:.6g} Pa at theta "
                f"{np.degrees(self.pressure_max_theta):.1f} deg from the maximum film"
                if self.pressure_max > 0.0 else "no pressure in the film (peak 0 Pa)")
        return "\n".join([
            f"film {self.method}, cavitation {self.cavitation}, {self.n_dofs} unknowns"
            + ("" if self.accuracy is None else "; mesh {} x {} chosen for rtol {:g}".format(
                *self.accuracy.mesh, self.accuracy.rtol)),
            f"  force on the journal |F| {load:.6g} N{err}, attitude angle {attitude:.4g} deg; "
            f"local (F_r, F_t) ({fr:.6g}, {ft:.6g}) N; inertial (F_x, F_y) "
            f"({self.force[0]:.6g}, {self.force[1]:.6g}) N",
            f"  {peak}; minimum film {self.film_min * 1e6:.4g} um",
            f"  cavitated area {100 * self.cavitated_fraction:.1f} % of the film; friction "
            f"{self.friction_force:.6g} N; side leakage {self.side_leakage + 0.0:.6g} m^3/s "
            "(net, out of both ends)" + self._outflow_words(),
            f"  solver: {self.iterations} iterations, complementarity residual "
            f"{self.residual:.1e}" + ("" if self.converged else " (NOT converged)")]
            + ([] if self.fraction is None else [
                f"  JFO film fraction {float(np.min(self.fraction)):.4g} .. 1; fed "
                f"{self.flow_in or 0.0:.6g} m^3/s; mass balance {self.mass_balance:.1e} m^3/s"]))


def undriven(state, gap=None) -> bool:
    """True when nothing drives a pressure in the rigid film (``gap`` None): no squeeze
    (eps_dot 0) and no wedge (a centred journal, eps 0, or no wedge speed
    omega - 2 gamma_dot). Such a film is at ambient because nothing raises it, not because
    it ruptured: it has no cavity (a separating film, eps_dot < 0, at ambient everywhere
    is cavitated)."""
    return gap is None and state.eps_dot == 0.0 and (state.eps == 0.0
                                                      or state.wedge_speed == 0.0)


def film_solution(bearing, state, P, theta, zeta, force_local, *, friction, leakage,
                  cavitated_fraction, record, method, cavitation, half, mesh,
                  flow_in=None, fraction=None, mass_balance=None, moment=(0.0, 0.0),
                  gap=None, side_outflow=None) -> FilmSolution:
    """The one builder of :class:`FilmSolution` for every mesh solver: derives the
    inertial force, pressures [Pa], film, peak and its place from the dimensionless nodal
    pressure ``P`` (p = mu (R/c)^2 P, clipped as the cavitation model says) at (theta,
    zeta = z/R), given the solver's own force, friction [N] and leakage [m^3/s]; ``record``
    carries iterations, residual, converged; ``gap``: nodal H of a general gap field
    (None: the rigid cylinder's); ``moment`` (M_x, M_y) [N m]."""
    R, c = bearing.radius, bearing.clearance
    f_r, f_t = force_local
    i = int(np.argmax(P))
    theta_i = float(theta[i])
    return FilmSolution(
        force_local=(f_r, f_t),
        force=tuple(float(f) for f in local_to_inertial(f_r, f_t, state.gamma)),
        pressure=bearing.pressure_scale * P, theta=theta, z=R * zeta,
        film_thickness=film_thickness(theta, state.eps, c) if gap is None else c * gap,
        pressure_max=bearing.pressure_scale * float(P[i]),
        pressure_max_theta=float(np.mod(theta_i, 2 * np.pi)),
        pressure_max_z=float(R * zeta[i]),
        pressure_max_angle=float(np.mod(inertial_from_theta(theta_i, state.gamma), 2 * np.pi)),
        film_min=c * (1.0 - state.eps) if gap is None else c * float(np.min(gap)),
        cavitated_fraction=cavitated_fraction,
        friction_force=friction, friction_torque=friction * R, side_leakage=leakage,
        iterations=record.iterations, residual=record.residual, converged=record.converged,
        method=method, cavitation=cavitation, n_dofs=len(P), half=half, radius=R,
        gamma=state.gamma, mesh=mesh, flow_in=flow_in, fraction=fraction,
        mass_balance=mass_balance, moment=tuple(float(m) for m in moment),
        side_outflow=None if side_outflow is None else float(side_outflow) + 0.0)


@dataclass(frozen=True)
class ForceDerivatives:
    """A film force in the local frame and its first derivatives at one journal state.

    The film force depends on the state through eps, eps_dot and the wedge speed
    w = omega - 2 gamma_dot only (gamma just turns the frame), so these three partials
    are all a linearisation needs (see :mod:`bearingfem.design.coefficients`).

    Attributes
    ----------
    force : (F_r, F_t) [N]
    d_eps : d(F_r, F_t)/d eps [N]
    d_eps_dot : d(F_r, F_t)/d eps_dot [N s]
    d_wedge : d(F_r, F_t)/d w [N s]
    method : how the partials were found ("analytic", "exact-sensitivity",
        "central-differences")
    d_gamma : d(F_r, F_t)/d gamma at fixed (eps, eps_dot, w) [N/rad]: zero for a film that
        turns with the line of centres, not when grooves stay fixed in the inertial frame
    """

    force: tuple
    d_eps: tuple
    d_eps_dot: tuple
    d_wedge: tuple
    method: str
    d_gamma: tuple = (0.0, 0.0)
